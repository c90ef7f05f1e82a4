// The dialects camgen writes and reads, by the name a machine file gives in "dialect". A new
// dialect is one folder beside these and one line in the table.
#include "src/post/dialect_registry.hpp"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "machines/heidenhain/heidenhain_post.hpp"
#include "machines/heidenhain/heidenhain_reader.hpp"
#include "machines/iso/iso_lathe_post.hpp"
#include "machines/iso/iso_post.hpp"
#include "machines/iso/iso_reader.hpp"
#include "machines/iso/iso_settings.hpp"
#include "machines/nccad/nccad_post.hpp"
#include "machines/nccad/nccad_reader.hpp"
#include "machines/nccad/nccad_settings.hpp"
#include "machines/sinumerik/sinumerik_lathe_post.hpp"
#include "machines/sinumerik/sinumerik_post.hpp"
#include "machines/sinumerik/sinumerik_reader.hpp"

namespace camgen {

namespace {

// The post factory of dialect post class P.
template <class P>
std::unique_ptr<Post> post_of(const Machine& machine, std::ostream& out, PostOptions options) {
    return std::make_unique<P>(machine, out, std::move(options));
}

}  // namespace

std::span<const Dialect> dialects() {
    // Name, post, reader, machine check, settings: one entry per dialect. A variant (iso-lathe)
    // names its own post, reader and settings, each extending its base dialect's.
    static const Dialect registry[] = {
        {"iso", post_of<IsoPost>, reader::make_iso_reader, check_iso_machine, iso::setting_keys(), iso::read_settings,
         iso_length_offset},
        {"iso-lathe", post_of<IsoLathePost>, reader::make_iso_lathe_reader, check_iso_machine, iso::lathe_setting_keys(),
         iso::read_lathe_settings, iso_lathe_length_offset},
        // nccad (wabeco, kosy) has no tool length offsets: the operator touches each tool off.
        {"nccad", post_of<NccadPost>, reader::make_nccad_reader, check_nccad_machine, nccad::setting_keys(),
         nccad::read_settings, nullptr},
        {"sinumerik", post_of<SinumerikPost>, reader::make_sinumerik_reader, check_sinumerik_machine, {}, nullptr,
         sinumerik_length_offset},
        {"sinumerik-lathe", post_of<SinumerikLathePost>, reader::make_sinumerik_reader, check_sinumerik_machine, {}, nullptr,
         sinumerik_length_offset},
        {"heidenhain", post_of<HeidenhainPost>, reader::make_heidenhain_reader, check_heidenhain_machine, {}, nullptr,
         heidenhain_length_offset},
    };
    return registry;
}

const Dialect* find_dialect(std::string_view name) {
    for (const Dialect& d : dialects())
        if (d.name == name) return &d;
    return nullptr;
}

std::string post_length_offset(const Machine& machine, int tool) {
    const Dialect* d = find_dialect(machine.dialect);
    return d && d->length_offset ? d->length_offset(machine, tool) : std::string();
}

std::unique_ptr<Post> make_post(const Machine& machine, std::ostream& out, PostOptions options) {
    if (const Dialect* d = find_dialect(machine.dialect)) return d->make_post(machine, out, std::move(options));
    std::vector<std::string_view> names;
    for (const Dialect& d : dialects()) names.push_back(d.name);
    std::sort(names.begin(), names.end());
    throw InputError("/dialect", fmt::format("unknown dialect \"{}\"; dialects: {}", machine.dialect, fmt::join(names, ", ")),
                     0, machine.source);
}

}  // namespace camgen
