#pragma once
#include <optional>

#include "camgen/post/post.hpp"
#include "machines/iso/iso_settings.hpp"
#include "machines/iso/iso_words.hpp"

namespace camgen {

// Fanuc-style ISO post (fanuc, linuxcnc, grbl). Its settings (machine file "settings",
// iso::Settings, read with the machine) are programNumber (0: none, the program name becomes
// a comment), percentLines, toolLengthOffset (G43 H), toolChange (true/"m6", "pause",
// false/"none"), endCode, stopMessage and optionalStop. Canned cycles are
// G81-G89/G73/G74 with G98/G99, R, Q, P, F and G80; a cycle of style "rigid-g33.1" in the
// machine's drilling table is LinuxCNC rigid tapping G33.1 (M4 before it for tap-left).
class IsoPost : public Post {
public:
    IsoPost(const Machine& machine, std::ostream& out, PostOptions options);

    // The settings this post writes by (a variant's post reads its own struct, which extends these).
    const iso::Settings& settings() const { return settings_; }

protected:
    void on_open() override;
    void on_close() override;
    void on_tool_change(const ToolChange& tool) override;
    void on_dwell(double seconds) override;
    // M0, or M1 where the control has an optional stop, with the message as a comment (or
    // LinuxCNC's MSG comment) in the block.
    void on_stop(const Stop& stop) override;
    // A job's program number replaces the O-number where the machine writes one.
    bool takes_program_number() const override { return settings_.program_number > 0; }
    void rapid_z_from_unknown(double z) override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec, Vec2 at, bool first) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;

    // Whether a canned cycle block starts with its return level G98/G99 (not where those codes
    // mean something else: Fanuc T system A's feed modes).
    virtual bool writes_return_level() const { return true; }

    bool length_offset_pending_ = false;

private:
    const iso::Settings& settings_;
    // The spindle direction a tapping cycle needs before it starts, if it differs from the
    // operation's (G74 and left-hand rigid tapping need M4).
    static std::optional<SpindleState> tapping_direction(const DrillCycle& cycle);
};

// The machine-file settings the ISO dialect would write as wrong motion (Dialect::check_machine).
std::optional<MachineProblem> check_iso_machine(const Machine& machine);

// The tool length offset the ISO posts select for `tool` (Dialect::length_offset): "G43 H<tool>"
// where toolLengthOffset writes it (rapid_z_from_unknown), else none (""; GRBL as camgen
// writes it: the operator touches each tool off); the lathe's turret call "T0101" (its offset
// is the tool's number).
std::string iso_length_offset(const Machine& machine, int tool);
std::string iso_lathe_length_offset(const Machine& machine, int tool);

}  // namespace camgen
