#pragma once
// The turn-face operation: facing the end of the bar on a lathe, from its outside (the stock
// bar's diameter, or outerX) in to the spindle axis (or innerX), down to a Z in passes. Each
// pass rapids to approachDistance outside the bar at its Z, feeds across the face towards the
// axis, lifts off the face by `lift` in Z and X together, and rapids back across above the face
// it has just cut. (Z, radius), mm.
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"

namespace camgen {

struct TurnFaceOp {
    static constexpr std::string_view type = "turn-face";
    static constexpr MachineKind machine_kind = MachineKind::lathe;
    // Reads one operation of this type (its "type" is already read).
    static TurnFaceOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    XValues given_x = XValues::diameter;
    FeedMode feed_mode = FeedMode::per_minute;
    double feed = 0.0;            // mm/min (a job's mm/rev times the tool's speed)
    double outer = 0.0;           // radius the face starts at (the bar's), mm
    double inner = 0.0;           // radius it ends at (0: the axis), mm
    // The radius the tip feeds to: inner, or at the axis minus the nose radius (the nose's
    // centre on the axis, past the centre by the radius, so that no nub of the nose's round is
    // left at the centre), mm.
    double tip_end = 0.0;
    double start_z = 0.0;         // Z of the face before (the bar's), mm
    double z = 0.0;               // Z of the face after, mm
    std::vector<double> passes;   // the Z of each pass, from start_z down, the last z
    double approach = 1.0;        // mm outside the bar where the feed across begins
    double lift = 0.5;            // mm the tool lifts in Z and in X before each return
    std::vector<std::string> notes;
};

// Rapid to approachDistance outside the bar at the clearance; for each pass: rapid along Z to
// its Z, feed across to tip_end, feed off by lift in +Z and +X, rapid back out above the
// face; rapid back to the clearance.
void expand(const TurnFaceOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "turn face".
std::string default_name(const TurnFaceOp& op);

}  // namespace camgen
