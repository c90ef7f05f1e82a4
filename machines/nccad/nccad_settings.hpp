#pragma once
// The machine-file "settings" of the nccad dialect: their key table and the struct they are
// read into once (with the machine file), which the nccad post writes by.
#include <memory>
#include <span>

#include "camgen/common/json_util.hpp"
#include "camgen/common/key_spec.hpp"
#include "camgen/post/machine.hpp"

namespace camgen::nccad {

struct Settings : DialectSettings {
    int underscore_lines = 2;  // "_" lines at the start of the program
    bool reference_run = false;  // G76 after the start block
    bool home_at_end = true;     // G77 at the end
    bool end_of_program = true;  // G99 at the end
};

std::span<const KeySpec> setting_keys();

// The reader of Dialect::read_settings.
std::shared_ptr<const DialectSettings> read_settings(json::Fields& f, const Machine& machine, const json::Source& source);

}  // namespace camgen::nccad
