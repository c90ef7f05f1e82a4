#pragma once
// The ISO (Fanuc-style) words that the post writes and the reader reads back: the canned
// cycle codes and the values of the dialect settings both follow (iso_settings.hpp reads them).
#include <string_view>

#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen::iso {

// A canned drilling cycle kind and the G code that calls it.
struct CycleCode {
    CycleKind kind;
    double code;
};

// The canned cycle G code of every cycle kind (G98/G99 pick the return level, G80 cancels).
inline constexpr CycleCode cycle_codes[] = {
    {CycleKind::drill, 81},   {CycleKind::dwell, 82}, {CycleKind::deep, 83},      {CycleKind::chip_break, 73},
    {CycleKind::tap, 84},     {CycleKind::tap_left, 74}, {CycleKind::ream, 85},   {CycleKind::bore_stop, 86},
    {CycleKind::bore_dwell, 89},
};

// The G code of the canned cycle of this kind.
constexpr double cycle_code(CycleKind kind) {
    for (const CycleCode& c : cycle_codes)
        if (c.kind == kind) return c.code;
    return 81;
}

// Lathes: how a tool is called (the iso-lathe setting "toolCall"): the ISO tool change
// (T.. M6), or a turret's T0101 (tool 01 with offset 01, Fanuc T).
enum class LatheToolCall { m6, turret };

// Lathes: the move synchronised with the spindle that cuts a thread (the iso-lathe setting
// "threadMove"): LinuxCNC's G33 Z K (K the lead, mm per revolution; LinuxCNC G-code docs, G33)
// or Fanuc T's G32 Z F (F the lead; Fanuc 0i-TF operator's manual, "Thread cutting (G32)").
enum class LatheThreadMove { g33_k, g32_f };
inline constexpr double thread_g33_code = 33;
inline constexpr double thread_g32_code = 32;

// The maximum spindle speed code of Fanuc T (system A): G50 S<rpm>.
inline constexpr double spindle_limit_code = 50;
// Constant spindle speed (rpm), Fanuc T and LinuxCNC: G97.
inline constexpr double constant_rpm_code = 97;
// Constant surface speed (S in m/min, ft/min under G20), Fanuc T and LinuxCNC: G96 (LinuxCNC's
// D: the spindle's limit; Fanuc T's limit is G50 S).
inline constexpr double surface_speed_code = 96;
// Fanuc T's end-face peck drilling cycle: G74 R(e) / G74 Z Q F.
inline constexpr double face_peck_code = 74;

// LinuxCNC's rigid tapping code: G33.1 Z K, one synchronised move in and out.
inline constexpr double rigid_tap_code = 33.1;

// How an ISO control changes tools: T.. M6, a pause (M0) with a message for the operator
// (GRBL), or not at all.
enum class ToolChangeStyle { m6, pause, none };

// How an ISO control shows a stop's message, and whether it stops at M1: the settings
// "stopMessage" ("comment": the message as a comment in the M0/M1 block, as Fanuc shows the
// block; "msg": LinuxCNC's "(MSG, text)", which it shows in a window) and "optionalStop"
// (false: the control ignores M1, as GRBL does, so an optional stop is written as M0).
struct StopStyle {
    bool msg = false;
    bool optional_stop = true;
};

// The prefix of LinuxCNC's message comment "(MSG, text)".
inline constexpr std::string_view msg_prefix = "MSG,";

}  // namespace camgen::iso
