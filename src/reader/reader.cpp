// Reading programs through the dialect registry (machines/registry.cpp), which names each
// dialect's reader beside its post.
#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/reader/reader.hpp"
#include "src/post/dialect_registry.hpp"
#include "src/reader/nc_reader.hpp"

namespace camgen {

namespace reader {

std::unique_ptr<NcReader> make_reader(const Machine& machine, std::string source) {
    if (const Dialect* d = find_dialect(machine.dialect); d && d->make_reader) return d->make_reader(machine, std::move(source));
    std::vector<std::string> names;
    for (const Dialect& d : dialects())
        if (d.make_reader) names.emplace_back(d.name);
    throw InputError("/dialect",
                     fmt::format("camgen cannot read programs of dialect \"{}\" (machine {}) yet; it reads: {}",
                                 machine.dialect, machine.name, fmt::join(names, ", ")),
                     0, machine.source);
}

}  // namespace reader

std::vector<ReadEvent> read_program(std::string_view text, const Machine& machine, const std::string& source,
                                    ReadResolution* resolution) {
    auto reader = reader::make_reader(machine, source);
    std::vector<ReadEvent> events = reader->read(text);
    if (resolution) *resolution = reader->coarsest_resolution();
    return events;
}

ReadResolution read_resolution(const Machine& machine) { return reader::make_reader(machine, {})->resolution(); }

bool has_reader(const std::string& dialect) {
    const Dialect* d = find_dialect(dialect);
    return d && d->make_reader;
}

}  // namespace camgen
