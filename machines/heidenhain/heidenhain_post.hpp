#pragma once
#include <optional>

#include "camgen/post/post.hpp"

namespace camgen {

// Heidenhain TNC conversational (Klartext) post: numbered blocks from
// `0 BEGIN PGM name MM` to `END PGM name MM`, `; ` comments, `TOOL CALL n Z S..`, `M3`/`M5`,
// `L X.. Y.. Z.. R0 FMAX` / `L X.. F..`, arcs `CC X.. Y..` + `C X.. Y.. DR+/-`, dwell cycle 9,
// drilling as `CYCL DEF 200 DRILLING`, `203 UNIVERSAL DRILLING` or `207 RIGID TAPPING NEW`
// with one `L X.. Y.. R0 FMAX M99` per hole. No dialect settings.
class HeidenhainPost : public Post {
public:
    HeidenhainPost(const Machine& machine, std::ostream& out, PostOptions options);

protected:
    void on_open() override;
    void on_close() override;
    void on_comment(const std::string& text) override;
    void on_tool_change(const ToolChange& tool) override;
    void on_spindle(const Spindle& spindle) override;
    void on_dwell(double seconds) override;
    // STOP (or M1 for an optional stop) with the message as the block's comment.
    void on_stop(const Stop& stop) override;
    void on_rapid(const Vec3& to) override;
    void rapid_z_from_unknown(double z) override;
    std::string compensation_words(const Compensation& compensation) const override;
    LinearLayout linear_layout() override;
    void on_circular(const ArcGeometry& arc, double feed) override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec, Vec2 at, bool first) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    std::optional<std::string> canned_limit(const DrillCycle& cycle, const DrillingCycleSpec& spec) const override;

private:
    void flush_tool_call(std::optional<double> rpm);
    std::string program_name() const;
    std::optional<ToolChange> pending_tool_;
    double speed_ = 0.0;
};

// One Q parameter of a TNC cycle definition: number, value as written, and its comment.
struct TncParameter {
    int q = 0;
    std::string value;
    std::string comment;
};

// The cycle definition camgen writes for `cycle` on a Heidenhain `machine`: its title
// ("CYCL DEF 203 UNIVERSAL DRILLING") and Q parameters in order.
std::pair<std::string, std::vector<TncParameter>> heidenhain_cycle(const DrillCycle& cycle, const Machine& machine);

// The machine-file settings the Heidenhain dialect would write as wrong motion (Dialect::check_machine).
std::optional<MachineProblem> check_heidenhain_machine(const Machine& machine);

// The tool length offset the Heidenhain post selects for `tool` (Dialect::length_offset): the
// TOOL CALL applies the called tool's own length from the control's tool table; there is no
// register of its own to select (as G43 H has), so it is always the tool's ("TOOL CALL 1").
std::string heidenhain_length_offset(const Machine& machine, int tool);

}  // namespace camgen
