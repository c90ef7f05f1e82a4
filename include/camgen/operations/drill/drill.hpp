#pragma once
// The drill operation: a list of holes drilled with one cycle (the CNC-Calc drill header and
// its MillDrillingFields), read from the job and expanded into a DrillCycle event, one
// DrillPoint per hole and a DrillEnd.
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/heights.hpp"
#include "camgen/operations/holes.hpp"

namespace camgen {

// The drilling parameters as the job gives them. Z values are absolute mm unless named
// relative; the optional fields of the vocabulary's drill_fields table are in `values`.
struct DrillParams : Heights {
    CycleKind kind = CycleKind::drill;
    DrillValues values;                          // the optional fields the job set
    bool drill_tip = false;                      // add the tool's tip length to the depth
    CycleOutput output = CycleOutput::automatic;
    UnsupportedCycle unsupported = UnsupportedCycle::refuse;  // where the machine cannot make the cycle
    friend bool operator==(const DrillParams&, const DrillParams&) = default;
};

// Drill a list of holes with one cycle (the holes: HoleSet).
struct DrillOp : HoleSet {
    static constexpr std::string_view type = "drill";
    // Reads one operation of this type (its "type" is already read).
    static DrillOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("drill") first.
    static std::vector<ObjectSpec> objects();
    std::string path;          // JSON path of the operation, for messages
    std::string comment;
    int tool = 0;
    DrillParams params;
};

// Position above the first hole at the clearance, then down to the retract plane, the cycle
// over every hole, and back up to the clearance.
void expand(const DrillOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "drill N holes".
std::string default_name(const DrillOp& op);

// The resolved drilling cycle of an operation (absolute planes, drill tip, tapping feed).
DrillCycle resolve_cycle(const DrillOp& op, const Tool& tool);

// The length of a drill's point of included angle `tip_angle` degrees on `diameter` mm:
// (d/2) / tan(a/2), added to a hole's depth for drillTip.
double drill_tip_length(double diameter, double tip_angle);

// The events of one drilling cycle over `holes` (at least one, in order): rapid above the
// first hole at the job's clearance, down to the retract plane, the cycle, one DrillPoint per
// hole, its end, and back up to the clearance.
void expand_cycle(const DrillCycle& cycle, const std::vector<Vec2>& holes, const Context& context, EventSink& sink);

}  // namespace camgen
