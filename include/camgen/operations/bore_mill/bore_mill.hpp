#pragma once
// The bore-mill operation: a circular hole or counterbore of a given diameter milled with a
// smaller tool at every hole of the hole sources (holes.hpp): a helical ramp down from the stock
// top at a pitch, a full circle at the bottom, an optional finishing circle, and back to the
// centre before the tool rises, so that it leaves no dwell mark on the wall. A bore wider than
// twice the tool is cleared ring by ring from the inside out, each ring its own helix.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/heights.hpp"
#include "camgen/operations/holes.hpp"

namespace camgen {

// Mill circular holes with a smaller tool (the holes: HoleSet).
struct BoreMillOp : HoleSet {
    static constexpr std::string_view type = "bore-mill";
    // Reads one operation of this type (its "type" is already read).
    static BoreMillOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("bore-mill") first.
    static std::vector<ObjectSpec> objects();
    std::string path;          // JSON path of the operation, for messages
    std::string comment;
    int tool = 0;
    Heights heights;
    double diameter = 0.0;                 // mm, of the hole milled
    double pitch = 0.0;                    // mm, the most the helix goes down per turn
    double step_over = 0.5;                // fraction of the tool diameter between rings
    double finishing_allowance = 0.0;      // mm, radial stock the roughing leaves for the finishing circle
    CutDirection direction = CutDirection::climb;
    double feed = 0.0;                     // mm/min, the bottom circle and the way back to the centre
    double ramp_feed = 0.0;                // mm/min, the helix
    double plunge_feed = 0.0;              // mm/min, from above the centre to the start of the helix
    double finishing_feed = 0.0;           // mm/min, the finishing circle and the step out to it
    std::optional<double> tolerance;       // mm, for helices that become lines (capped by the machine's)
};

// The radii of the tool centre's circles for a bore of `bore` mm with a tool of `tool` mm, from
// the inside out: one circle when the tool covers the centre from it, else evenly spaced rings,
// at most `step_over` x tool apart, the first close enough to the centre to clear it, the last
// (bore - tool) / 2 - `allowance`.
std::vector<double> ring_radii(double bore, double tool, double step_over, double allowance);

// How many rings ring_radii makes (a double, so that a huge count can be refused before it is made).
double ring_count(double bore, double tool, double step_over, double allowance);

// Whole helix turns from the stock top to the bottom (`drop` mm) at most `pitch` mm per turn:
// the helix ends exactly at the depth and at the angle it started.
int helix_turns(double drop, double pitch);

// Per hole, from the retract plane: rapid down to the safe distance above the centre; per ring,
// feed out and down to the ring at the stock top, helix down to the bottom, one circle at the
// bottom, back to the centre and rapid up; after the last ring the finishing circle if any.
void expand(const BoreMillOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "bore-mill N holes Ø D".
std::string default_name(const BoreMillOp& op);

}  // namespace camgen
