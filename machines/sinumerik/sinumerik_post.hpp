#pragma once
#include <optional>

#include "camgen/post/post.hpp"

namespace camgen {

// Siemens Sinumerik 840D post: `;` comments, G71 metric, `T.. D1` / `M6`,
// `S.. M3`, dwell `G4 F<s>`, arcs `G2/G3 X Y I J` or `CR=`, drilling as
// `MCALL CYCLE81..89(...)`, one X/Y block per hole, `MCALL` to end, `M30`.
// No dialect settings.
class SinumerikPost : public Post {
public:
    SinumerikPost(const Machine& machine, std::ostream& out, PostOptions options);

protected:
    void on_open() override;
    void on_close() override;
    void on_tool_change(const ToolChange& tool) override;
    void on_dwell(double seconds) override;
    // MSG("message"), M0 or M1, MSG(): the control shows the message while it stands.
    void on_stop(const Stop& stop) override;
    std::string compensation_words(const Compensation& compensation) const override;
    std::string radius_word(double radius) const override;
    bool force_arc_end() const override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec, Vec2 at, bool first) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    std::optional<std::string> canned_limit(const DrillCycle& cycle, const DrillingCycleSpec& spec) const override;

};

// The cycle call camgen writes for `cycle` on a Sinumerik `machine`, such as
// "CYCLE83(10.000, 0.000, 2.000, -20.000, , -3.000, , 0.500, , 1.000, 1, 1, , 1.000, , , 1.000)".
std::string sinumerik_cycle_call(const DrillCycle& cycle, const Machine& machine);

// The machine-file settings the Sinumerik dialect would write as wrong motion (Dialect::check_machine).
std::optional<MachineProblem> check_sinumerik_machine(const Machine& machine);

// The tool length offset the Sinumerik posts select for `tool` (Dialect::length_offset): its
// first cutting edge D1, written with the tool (T1 D1), which holds its length and radius.
std::string sinumerik_length_offset(const Machine& machine, int tool);

}  // namespace camgen
