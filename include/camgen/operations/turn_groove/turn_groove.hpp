#pragma once
// The turn-groove operation: an external groove on a lathe, cut by a grooving (or parting) tool
// of a width: its walls at Z `z` (the +Z wall, towards the bar's face) and `width` towards the
// chuck, its bottom at a radius, 45-degree chamfers on its edges. Plunges straight in X (pecked
// or not) overlapping by the stepover, a finishing pass along the bottom where the groove is
// wider than the tool, the chamfers by the blade's corners; every Z move in air above the
// surface, every plunge fed from approachDistance above it. (Z, radius), mm.
//
// The blade: a flat cutting edge `width` wide, no nose radius, its body straight out in +X
// (it clears the Z it covers from its edge out). Its programmed point is a corner of the
// edge: the left one (-Z, towards the chuck; the tool's orientation 2 or none) or the right
// one (+Z; orientation 1). Positions here are the left corner's; `GrooveBlade::at` makes the
// programmed point of them.
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"

namespace camgen {

// A grooving or parting tool's blade as the operations use it.
struct GrooveBlade {
    double width = 0.0;         // mm
    bool right_point = false;   // its programmed point is the right (+Z) corner
    // The programmed point of the blade whose left corner is at radius r, Z left_z.
    Vec3 at(double r, double left_z) const { return {r, 0.0, left_z + (right_point ? width : 0.0)}; }
};

// Pecking in X: none (peck = 0), or pecks of `peck` (radial mm) with a chip-breaking retract of
// `retract` mm between them, or (full) a rapid out to the air above the surface and back down
// to `retract` above the depth reached.
struct GroovePecks {
    double peck = 0.0;
    double retract = 0.3;
    bool full = false;
};

// One straight plunge of the blade (left corner at Z left_z): fed from `start` (radius, where
// the tool stands) down to `end`, the pecks counted from the surface `top`, a full retract out
// to `air`; the feed `slow_feed` below the
// radius `slow_below` (0: none); a dwell of `dwell` s at the end. Ends at `end`.
struct GroovePlunge {
    double left_z = 0.0, start = 0.0, air = 0.0, top = 0.0, end = 0.0;
    double feed = 0.0, slow_feed = 0.0, slow_below = 0.0;  // mm/min, mm/min, radius mm
    double dwell = 0.0;
};
void emit_groove_plunge(const GrooveBlade& blade, const GroovePlunge& p, const GroovePecks& pecks, EventSink& sink);

// Reads the blade of an operation's "tool": a grooving-tool or parting-tool (else refused at
// "tool", naming `what`). External: orientation none, 2 (left corner) or 1 (right corner);
// internal (the blade cuts towards +X): 3 (left corner) or 4 (right corner); face (its edge
// faces -Z, its width along X): 7, programmed at the edge's inner (-X) corner.
GrooveBlade read_groove_blade(json::Fields& f, const JobInput& input, std::string_view what, const Tool*& tool,
                              GrooveSide side = GrooveSide::external);
// Reads "peckDepth", "peckRetract" and "fullRetract"; `depth` (mm) is the deepest plunge's, of
// which peckDepth may make at most groove_max_pecks pecks.
// and which is at least groove_min_peck (mm).
inline constexpr double groove_max_pecks = 10000;
inline constexpr double groove_min_peck = 0.01;
GroovePecks read_groove_pecks(json::Fields& f, const JobInput& input, double depth);

struct TurnGrooveOp {
    static constexpr std::string_view type = "turn-groove";
    static constexpr MachineKind machine_kind = MachineKind::lathe;
    // Reads one operation of this type (its "type" is already read).
    static TurnGrooveOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    XValues given_x = XValues::diameter;
    FeedMode feed_mode = FeedMode::per_minute;
    double feed = 0.0;            // mm/min
    GrooveBlade blade;
    GrooveSide side = GrooveSide::external;  // a face groove: the Zs below are radii and the radii Zs
    double z_right = 0.0;         // Z of the groove's +Z wall (face: the radius of its outer wall), mm
    double z_left = 0.0;          // Z of its -Z wall (z_right - width; face: its inner wall's radius), mm
    double surface = 0.0;         // radius of the surface it is cut into (face: the face's Z), mm
    double bottom = 0.0;          // radius of its bottom (internal: above surface; face: its Z), mm
    double outside = 0.0;         // external: the bar's radius (the tool moves along Z approachDistance beyond it), mm
    double chamfer = 0.0;         // each edge's 45-degree chamfer, along Z and along X, mm
    std::vector<double> plunges;  // the left corner's Z of each plunge, from the +Z wall to the -Z wall
    double finish = 0.0;          // radial allowance the plunges leave for the pass along the bottom (0: one plunge)
    GroovePecks pecks;
    double dwell = 0.0;           // s at the bottom
    double approach = 1.0;        // mm above the surface where the feeds start
    CycleOutput output = CycleOutput::automatic;  // a grooving cycle (GrooveCycle) or longhand moves
    std::vector<std::string> notes;
};

// The operation's groove as a GrooveCycle, from the approach level over its first plunge: its
// fields the keys that go beyond plain plunges; a plain groove's plunges G75's (pecks counted
// from the approach level, a Z step whole in µm, back to the start at the end), another's the
// operation's own.
GrooveCycle groove_cycle(const TurnGrooveOp& op);

// Rapid outside the bar along Z, down to approachDistance above the surface; then the groove
// (groove_cycle: a GrooveCycle, or its moves with output "longhand"): each plunge (the first at
// the +Z wall, the last at the -Z wall) fed from there, out at rapid; with more than one plunge
// and not plain, the last goes on to the bottom and along it to the +Z wall; the chamfers (the
// right corner down the +Z edge's, the left corner down the -Z edge's), each straight out; back
// outside the bar and to the clearance.
void expand(const TurnGrooveOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "turn groove".
std::string default_name(const TurnGrooveOp& op);

}  // namespace camgen
