#pragma once
#include <optional>

#include "camgen/post/post.hpp"
#include "machines/nccad/nccad_settings.hpp"

namespace camgen {

// nccad post (Wabeco, KOSY). Settings: underscoreLines (the "_" lines at the start),
// referenceRun (G76 after G90), homeAtEnd (G77), endOfProgram (G99).
class NccadPost : public Post {
public:
    NccadPost(const Machine& machine, std::ostream& out, PostOptions options);
    // nccad has no G41/G42, whatever the machine file's cutterCompensation says.
    std::optional<std::string> control_compensation_refusal() const override;
    // nccad's spindle runs clockwise only (M10 O6.1).
    std::optional<std::string> ccw_spindle_refusal() const override;

protected:
    void on_open() override;
    void on_close() override;
    void on_tool_change(const ToolChange& tool) override;
    void on_spindle(const Spindle& spindle) override;
    void on_dwell(double seconds) override;
    // M01 <message>: nccad shows the message and waits (it has no optional stop: an optional
    // stop waits as well, with a note).
    void on_stop(const Stop& stop) override;
    void on_compensation(const Compensation& compensation) override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec, Vec2 at, bool first) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    // nccad's spindle runs clockwise only: a right-hand tap cannot come out, a left-hand one cannot cut.
    std::optional<std::string> tapping_impossible(CycleKind kind) const override;

private:
    void flush_tool_message(std::optional<double> rpm);
    const nccad::Settings& settings_;
    bool spindle_on_ = false;
    double speed_ = 0.0;
    std::optional<ToolChange> pending_tool_;
};

// The machine-file settings the nccad dialect would write as wrong motion (Dialect::check_machine).
std::optional<MachineProblem> check_nccad_machine(const Machine& machine);

}  // namespace camgen
