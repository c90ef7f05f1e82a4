// The nccad dialect's settings: key table and reader.
#include "machines/nccad/nccad_settings.hpp"

#include <fmt/format.h>

namespace camgen::nccad {

namespace {

// The most "_" lines at the start: nccad needs one or two; more are a mistake.
constexpr int max_underscore_lines = 100;

constexpr KeySpec nccad_keys[] = {
    {.key = "underscoreLines", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{0, true},
     .max = Bound{max_underscore_lines, true}, .default_json = "2",
     .description = "the \"_\" lines that start the program (nccad's header)"},
    {.key = "referenceRun", .type = JsonType::boolean, .default_json = "false",
     .description = "a reference run G76 after the start block"},
    {.key = "homeAtEnd", .type = JsonType::boolean, .default_json = "true", .description = "G77 (home) at the end"},
    {.key = "endOfProgram", .type = JsonType::boolean, .default_json = "true", .description = "G99 (end of program) at the end"},
};

}  // namespace

std::span<const KeySpec> setting_keys() { return nccad_keys; }

std::shared_ptr<const DialectSettings> read_settings(json::Fields& f, const Machine&, const json::Source&) {
    auto s = std::make_shared<Settings>();
    s->underscore_lines = f.optional_integer("underscoreLines").value_or(s->underscore_lines);
    if (s->underscore_lines < 0 || s->underscore_lines > max_underscore_lines)
        f.fail("underscoreLines", fmt::format("underscoreLines must be between 0 and {}", max_underscore_lines));
    s->reference_run = f.boolean("referenceRun", s->reference_run);
    s->home_at_end = f.boolean("homeAtEnd", s->home_at_end);
    s->end_of_program = f.boolean("endOfProgram", s->end_of_program);
    return s;
}

}  // namespace camgen::nccad
