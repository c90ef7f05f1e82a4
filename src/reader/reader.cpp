// The dialects camgen can read, by the name a machine file gives in "dialect" (as
// machines/registry.cpp for the posts). A new dialect adds a line to the table.
#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/reader/reader.hpp"
#include "src/reader/nc_reader.hpp"

namespace camgen {

namespace reader {

namespace {

struct DialectReader {
    const char* dialect;
    std::unique_ptr<NcReader> (*make)(const Machine&, std::string);
};

constexpr DialectReader dialect_readers[] = {
    {"iso", make_iso_reader},
    {"nccad", make_nccad_reader},
    {"sinumerik", make_sinumerik_reader},
    {"heidenhain", make_heidenhain_reader},
};

}  // namespace

std::unique_ptr<NcReader> make_reader(const Machine& machine, std::string source) {
    for (const auto& d : dialect_readers)
        if (machine.dialect == d.dialect) return d.make(machine, std::move(source));
    std::vector<std::string> names;
    for (const auto& d : dialect_readers) names.emplace_back(d.dialect);
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
    for (const auto& d : reader::dialect_readers)
        if (dialect == d.dialect) return true;
    return false;
}

}  // namespace camgen
