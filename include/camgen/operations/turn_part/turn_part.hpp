#pragma once
// The turn-part operation: parting off on a lathe with a parting (or grooving) tool. The part
// lies on the +Z side (the bar's free end); `z` is its end face, where the blade's right (+Z)
// edge runs; the blade plunges in X to a remainder radius (0: through), pecked or not, at a
// reduced feed near the centre; an optional 45-degree chamfer on the part's edge is cut by the
// blade's right corner after a first plunge to the chamfer's depth. (Z, radius), mm.
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/turn_groove/turn_groove.hpp"

namespace camgen {

struct TurnPartOp {
    static constexpr std::string_view type = "turn-part";
    static constexpr MachineKind machine_kind = MachineKind::lathe;
    // Reads one operation of this type (its "type" is already read).
    static TurnPartOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    XValues given_x = XValues::diameter;
    FeedMode feed_mode = FeedMode::per_minute;
    double feed = 0.0;            // mm/min
    double slow_feed = 0.0;       // mm/min below slow_below
    double slow_below = 0.0;      // radius, mm
    GrooveBlade blade;
    double z = 0.0;               // the part's end face: the blade's right edge, mm
    double surface = 0.0;         // radius parted from, mm
    double end = 0.0;             // remainder radius (0: through), mm
    double outside = 0.0;         // the bar's radius, mm
    double chamfer = 0.0;         // on the part's edge, 45 degrees, mm
    GroovePecks pecks;
    double approach = 1.0;        // mm above the surface where the feeds start
    std::vector<std::string> notes;
};

// Rapid outside the bar along Z, down to approachDistance above the surface; with a chamfer, a
// plunge to its depth, out, the chamfer down the part's edge by the right corner; the plunge
// to the remainder (reduced feed near the centre); straight out, back to the clearance. A
// comment says that the part falls off there.
void expand(const TurnPartOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "turn part".
std::string default_name(const TurnPartOp& op);

}  // namespace camgen
