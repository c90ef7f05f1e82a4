#pragma once
// The turn-drill operation: one hole on a lathe's spindle axis (X0), drilled by a tool standing
// in the turret while the work turns. It is CNC-Calc's onDrilling: one call carrying every
// parameter (section 6), the optional ones named as its TurnDrillingFields. Expanded into the
// same DrillCycle / DrillPoint / DrillEnd events as milling, so that the posts' canned-or-
// longhand choice and the longhand peck model are the milling side's.
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"

namespace camgen {

// Centre drilling on a lathe. Depths are absolute Z (CNC-Calc onDrilling): startDepth the
// face of the material, endDepth the bottom of the hole, safeDistance where rapid turns to
// feed, retractDistance where the drill goes after the hole.
struct TurnDrillOp {
    static constexpr std::string_view type = "turn-drill";
    static constexpr MachineKind machine_kind = MachineKind::lathe;
    // Reads one operation of this type (its "type" is already read).
    static TurnDrillOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    FeedMode feed_mode = FeedMode::per_minute;  // how the program states feeds (job: per revolution in mm/rev)
    // The resolved cycle (kind from the parameters, planes, drill tip, feed), without the
    // tool's spindle, which expand() takes from the context.
    DrillCycle cycle;
};

// Rapid to X0 at the clearance, down to retractDistance, the cycle at X0, back to the clearance.
void expand(const TurnDrillOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "centre drill to Z<endDepth>".
std::string default_name(const TurnDrillOp& op);

}  // namespace camgen
