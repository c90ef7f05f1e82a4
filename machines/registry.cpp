// The dialects camgen can write, by the name a machine file gives in "dialect".
#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/post/post.hpp"
#include "machines/heidenhain/heidenhain_post.hpp"
#include "machines/iso/iso_post.hpp"
#include "machines/nccad/nccad_post.hpp"
#include "machines/sinumerik/sinumerik_post.hpp"

namespace camgen {

std::unique_ptr<Post> make_post(const Machine& machine, std::ostream& out, PostOptions options) {
    if (machine.dialect == "iso") return std::make_unique<IsoPost>(machine, out, std::move(options));
    if (machine.dialect == "nccad") return std::make_unique<NccadPost>(machine, out, std::move(options));
    if (machine.dialect == "sinumerik") return std::make_unique<SinumerikPost>(machine, out, std::move(options));
    if (machine.dialect == "heidenhain") return std::make_unique<HeidenhainPost>(machine, out, std::move(options));
    throw InputError("/dialect", fmt::format("unknown dialect \"{}\"; dialects: heidenhain, iso, nccad, sinumerik", machine.dialect), 0,
                     machine.source);
}

}  // namespace camgen
