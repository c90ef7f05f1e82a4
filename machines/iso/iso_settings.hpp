#pragma once
// The machine-file "settings" of the ISO dialect and of its lathe variant: their key tables and
// the structs they are read into once (with the machine file), which the ISO post and reader
// share. iso-lathe's settings are the ISO ones and its own.
#include <memory>
#include <span>
#include <string>

#include "camgen/common/json_util.hpp"
#include "camgen/common/key_spec.hpp"
#include "camgen/post/machine.hpp"
#include "machines/iso/iso_words.hpp"

namespace camgen::iso {

// The settings of the ISO dialect (fanuc, linuxcnc, grbl).
struct Settings : DialectSettings {
    int program_number = 1000;  // the O number; 0: none, the program name becomes a comment
    bool percent = true;        // % lines around the program
    bool length_offset = true;  // G43 H on the first Z move after a tool change
    ToolChangeStyle tool_change = ToolChangeStyle::m6;
    StopStyle stop;
    std::string end_code = "M30";
    // What the control accepts that camgen's posts need not write (the reader refuses the rest).
    bool length_offset_h = true;          // G43 H.. (GRBL: only G43.1)
    bool return_levels = true;            // G98/G99, a canned cycle's return level
    bool arc_turns = true;                // P on G2/G3: the number of turns
    bool compensation_without_d = false;  // G41/G42 without D: the radius of the tool in the spindle (LinuxCNC)
};

// The settings of the ISO lathe variant (linuxcnc-lathe, fanuc-lathe): the ISO ones and these.
struct LatheSettings : Settings {
    bool drilling_plane = true;  // a canned cycle drills under G17 (LinuxCNC); false: no plane word (Fanuc T)
    LatheToolCall tool_call = LatheToolCall::m6;
    bool spindle_limit = false;  // G50 S<maxRpm> before the first spindle start, then G97 S.. M3
    LatheThreadMove thread_move = LatheThreadMove::g33_k;  // the thread-cutting move's words
};

// The keys of each dialect's settings (iso-lathe's: the ISO keys, then its own).
std::span<const KeySpec> setting_keys();
std::span<const KeySpec> lathe_setting_keys();

// The readers of Dialect::read_settings.
std::shared_ptr<const DialectSettings> read_settings(json::Fields& f, const Machine& machine, const json::Source& source);
std::shared_ptr<const DialectSettings> read_lathe_settings(json::Fields& f, const Machine& machine,
                                                           const json::Source& source);

}  // namespace camgen::iso
