#pragma once
// Stops for the operator, as every post writes them and every comparison expects them. A job
// says where it stops (a Stop event) and which drilling cycles the operator makes by hand where
// the machine cannot make them (DrillCycle::unsupported = stop); OperatorStops turns that into
// the events of the program, between the job's events and a post (Post::emit) or the expected
// trace of a comparison (TraceBuilder::add_job_event), so that both see the same:
//   - before a stop the coolant and the spindle stop (whatever the control does at M0: some
//     stop the spindle, some keep it running, and the operator reaches into the machine);
//   - after it, before the next move, the spindle restarts as it ran, the program waits
//     `spin_up` seconds for it, and the coolant comes back on; a tool change or a spindle or
//     coolant event of the job's own before that move takes the place of the restart;
//   - a cycle the machine cannot make (impossible_cycle) is left out: in its place comment
//     lines name the cycle and every hole, the tool goes straight up to the height it came from
//     (the clearance), and at the end of the operation, at the clearance, the program stops
//     with a message that lists the holes (a few of them and the count where they are many).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// Why `machine` cannot make `cycle` in any form, or nullopt: a tap where the machine cannot
// tap (drilling.tapping none), or a tap of a kind the machine has no canned cycle for where it
// taps only rigidly (a longhand tap would break a rigid tap).
std::optional<std::string> impossible_cycle(const Machine& machine, const DrillCycle& cycle);

// How long the program waits after the stop that replaces a cycle restarts the spindle (s).
inline constexpr double unsupported_spin_up = 2.0;

// The stops of a job's events as a program makes them (see above); every other event passes
// unchanged.
class OperatorStops : public EventSink {
public:
    OperatorStops(const Machine& machine, EventSink& next);
    void emit(const Event& event) override;

private:
    // A drilling cycle left to the operator: what the stop's message says of it.
    struct LeftOut {
        DrillCycle cycle;
        int tool = 0;
        std::vector<Vec2> shown;  // the first holes, as many as the message has room for
        std::size_t count = 0;    // every hole
    };
    // What a stop stopped, to restart before the next move.
    struct Resume {
        std::optional<Spindle> spindle;
        double spin_up = 0.0;
        std::optional<Coolant> coolant;
    };
    void stop(const Stop& stop);
    void resume();
    void left_out(const DrillCycle& cycle, const std::string& why);
    Stop stop_for(const LeftOut& cycle) const;
    // A position as the machine's program writes it ("X10 Y20"), for the operator.
    std::string position(Vec2 at) const;

    const Machine& machine_;
    EventSink& next_;
    SpindleState spindle_ = SpindleState::off;
    double rpm_ = 0.0;
    double surface_speed_ = 0.0;  // m/min under G96 (rpm_ its limit), else 0
    Coolant coolant_{CoolantMode::off, ""};
    int tool_ = 0;
    std::string tool_description_;
    std::string op_path_, op_name_;
    std::optional<Vec3> pos_;        // where the tool is, if known
    std::optional<double> op_top_;   // the highest Z a rapid of the operation went to
    std::optional<LeftOut> leaving_;    // the cycle being left out (between its DrillCycle and DrillEnd)
    std::vector<LeftOut> left_;         // cycles left out in this operation, stopped for at its end
    std::optional<Resume> resume_;
};

}  // namespace camgen
