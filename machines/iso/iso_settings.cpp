// The ISO dialect's settings and its lathe variant's: key tables and readers.
#include "machines/iso/iso_settings.hpp"

#include <array>

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen::iso {

namespace {

// The highest program number: eight digits, as Fanuc's O allows.
constexpr int max_program_number = 99999999;

constexpr Named<ToolChangeStyle> tool_change_styles[] = {
    {ToolChangeStyle::m6, "m6", "T.. M6 (true means the same)"},
    {ToolChangeStyle::pause, "pause", "no tool changer (GRBL): a comment naming the tool and M0"},
    {ToolChangeStyle::none, "none", "no tool change written, only the tool's comment (false means the same)"},
};
constexpr Named<bool> stop_messages[] = {
    {false, "comment", "a stop's message as a comment in its M0/M1 block"},
    {true, "msg", "LinuxCNC's (MSG, message), shown in a window"},
};
constexpr Named<LatheToolCall> lathe_tool_calls[] = {
    {LatheToolCall::m6, "m6", "the ISO tool change (toolChange)"},
    {LatheToolCall::turret, "turret", "T0101: the tool and its offset number (Fanuc T)"},
};

constexpr Named<LatheThreadMove> lathe_thread_moves[] = {
    {LatheThreadMove::g33_k, "g33-k", "G33 Z K: K the lead (LinuxCNC)"},
    {LatheThreadMove::g32_f, "g32-f", "G32 Z F: F the lead (Fanuc T)"},
};

constexpr KeySpec iso_keys[] = {
    {.key = "programNumber", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{0, true},
     .max = Bound{max_program_number, true}, .default_json = "1000",
     .description = "the O number written at the start, with the program's name as a comment (0: none, the name "
                    "as a comment; LinuxCNC and GRBL)"},
    {.key = "percentLines", .type = JsonType::boolean, .default_json = "true",
     .description = "a % line before and after the program (Fanuc's tape start and end)"},
    {.key = "toolLengthOffset", .type = JsonType::boolean, .default_json = "true",
     .description = "G43 H (the tool's number) on the first Z move after a tool change"},
    {.key = "toolChange", .type = JsonType::string, .default_json = "\"m6\"", .choices = &choices_of<tool_change_styles>,
     .description = "how tools are changed: m6 (T.. M6), pause (no tool changer, GRBL: a comment naming the tool "
                    "and M0), none (only the tool's comment); true is m6, false none",
     .or_boolean = true},
    {.key = "endCode", .type = JsonType::string, .default_json = "\"M30\"",
     .description = "the end of program (M30, M2)"},
    {.key = "stopMessage", .type = JsonType::string, .default_json = "\"comment\"", .choices = &choices_of<stop_messages>,
     .description = "how a stop's message is shown: comment (in its M0/M1 block) or msg (LinuxCNC's (MSG, message))"},
    {.key = "optionalStop", .type = JsonType::boolean, .default_json = "true",
     .description = "false: the control ignores M1 (GRBL), so an optional stop is written as M0"},
    {.key = "lengthOffsetH", .type = JsonType::boolean, .default_json = "true",
     .description = "the control takes G43 H (a length offset from its table); false: verify refuses G43 (GRBL has only "
                    "G43.1); needs toolLengthOffset false"},
    {.key = "returnLevels", .type = JsonType::boolean, .default_json = "true",
     .description = "the control takes G98/G99 (a canned cycle's return level); false: verify refuses them (GRBL)"},
    {.key = "arcTurns", .type = JsonType::boolean, .default_json = "true",
     .description = "the control reads P on G2/G3 as the number of turns (LinuxCNC); false: verify refuses it (GRBL "
                    "refuses the unused word)"},
    {.key = "compensationWithoutD", .type = JsonType::boolean, .default_json = "false",
     .description = "a mill's G41/G42 without D offsets by the radius of the tool in the spindle (LinuxCNC); false: "
                    "verify refuses it"},
};

constexpr KeySpec lathe_only_keys[] = {
    {.key = "drillingPlane", .type = JsonType::boolean, .default_json = "true",
     .description = "a canned drilling cycle runs under G17, so that it drills along Z, and G18 follows "
                    "it (LinuxCNC); false: no plane word (Fanuc T)"},
    {.key = "toolCall", .type = JsonType::string, .default_json = "\"m6\"", .choices = &choices_of<lathe_tool_calls>,
     .description = "m6 (the ISO tool change, toolChange) or turret (T0101: tool and offset number, Fanuc T)"},
    {.key = "spindleLimit", .type = JsonType::boolean, .default_json = "false",
     .description = "G50 S (limits.maxRpm) before the first spindle start, and the speed as G97 S.. M3 "
                    "(Fanuc T); needs limits.maxRpm"},
    {.key = "threadMove", .type = JsonType::string, .default_json = "\"g33-k\"", .choices = &choices_of<lathe_thread_moves>,
     .description = "the move synchronised with the spindle that cuts a thread: g33-k (G33 Z K, K the lead: LinuxCNC) "
                    "or g32-f (G32 Z F, F the lead: Fanuc T)"},
};

// The ISO keys, then the lathe's.
constexpr auto lathe_keys = [] {
    std::array<KeySpec, std::size(iso_keys) + std::size(lathe_only_keys)> all{};
    std::size_t i = 0;
    for (const KeySpec& k : iso_keys) all[i++] = k;
    for (const KeySpec& k : lathe_only_keys) all[i++] = k;
    return all;
}();

// Reads the ISO settings into `s` (a variant's struct is one).
void read_iso(json::Fields& f, Settings& s) {
    s.program_number = f.optional_integer("programNumber").value_or(s.program_number);
    if (s.program_number < 0 || s.program_number > max_program_number)
        f.fail("programNumber", fmt::format("programNumber must be between 0 (none) and {}", max_program_number));
    s.percent = f.boolean("percentLines", s.percent);
    s.length_offset = f.boolean("toolLengthOffset", s.length_offset);
    if (const auto* tc = f.member("toolChange"); tc && tc->is_boolean())
        s.tool_change = tc->get<bool>() ? ToolChangeStyle::m6 : ToolChangeStyle::none;
    else
        s.tool_change = f.choice("toolChange", tool_change_styles, s.tool_change);
    s.end_code = f.optional_string("endCode").value_or(s.end_code);
    if (s.end_code.empty()) f.fail("endCode", "the end of program must not be empty (M30, M2)");
    s.stop.msg = f.choice("stopMessage", stop_messages, s.stop.msg);
    s.stop.optional_stop = f.boolean("optionalStop", s.stop.optional_stop);
    s.length_offset_h = f.boolean("lengthOffsetH", s.length_offset_h);
    s.return_levels = f.boolean("returnLevels", s.return_levels);
    s.arc_turns = f.boolean("arcTurns", s.arc_turns);
    s.compensation_without_d = f.boolean("compensationWithoutD", s.compensation_without_d);
    if (s.length_offset && !s.length_offset_h)
        f.fail("toolLengthOffset", "toolLengthOffset writes G43 H, which the control does not take (lengthOffsetH is false)");
}

}  // namespace

std::span<const KeySpec> setting_keys() { return iso_keys; }
std::span<const KeySpec> lathe_setting_keys() { return lathe_keys; }

std::shared_ptr<const DialectSettings> read_settings(json::Fields& f, const Machine&, const json::Source&) {
    auto s = std::make_shared<Settings>();
    read_iso(f, *s);
    return s;
}

std::shared_ptr<const DialectSettings> read_lathe_settings(json::Fields& f, const Machine& machine,
                                                           const json::Source& source) {
    auto s = std::make_shared<LatheSettings>();
    read_iso(f, *s);
    s->drilling_plane = f.boolean("drillingPlane", s->drilling_plane);
    s->tool_call = f.choice("toolCall", lathe_tool_calls, s->tool_call);
    s->spindle_limit = f.boolean("spindleLimit", s->spindle_limit);
    s->thread_move = f.choice("threadMove", lathe_thread_moves, s->thread_move);
    if (s->spindle_limit && !(machine.limits.max_rpm > 0))
        f.fail("spindleLimit", "spindleLimit writes G50 S<maxRpm>: the machine needs limits.maxRpm");
    if (machine.kind != MachineKind::lathe)
        json::fail(source, "/dialect", "the iso-lathe dialect writes for lathes: set \"kind\": \"lathe\"");
    return s;
}

}  // namespace camgen::iso
