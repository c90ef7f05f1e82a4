#pragma once
// The turn-rough operation: roughing the outside of a bar on a lathe down to a profile (the
// same start and path as a turn-profile) plus allowances, in passes along Z. The boundary it
// roughs to is the profile moved by allowanceX outwards and allowanceZ towards +Z (as Fanuc's
// G71 U W move the finishing shape), closed at the profile's end by a face up to the bar. Passes
// at levels depthOfCut apart (radial) each feed along -Z wherever the boundary lies below their
// level, lift off at 45 degrees and return in air; a last pass follows the boundary, so that
// the allowances are all that is left. With direction "x" the passes run along -X instead (the
// facing direction, as Fanuc's G72), at Z levels depthOfCut apart, each from outside the bar in
// to the boundary, lifted off away from it; the last pass follows the boundary from the end face
// back to the start. Output "auto" or "canned" hands the passes to the machine's roughing cycle
// (TurnCycle: LinuxCNC's G71 along Z, G72 along X, on linuxcnc-lathe, the profile as the tip
// follows it in a subroutine, D0). With a nose radius and computer compensation the passes and
// the last pass keep the nose circle on the boundary in both directions (tip_boundary).
// (Z, radius), mm.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/design_lathe.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"

namespace camgen {

// Which way a turn-rough's passes run: along -Z (turning, as G71) or along -X (facing, as G72).
enum class RoughDirection { z, x };
inline constexpr Named<RoughDirection> rough_directions[] = {
    {RoughDirection::z, "z", "passes along -Z towards the chuck, at radial levels depthOfCut apart (turning, as G71)"},
    {RoughDirection::x, "x", "passes along -X towards the axis, at Z levels depthOfCut apart (facing, as G72)"},
};

// What a turn-rough roughs from (key "stock"): what the operations before it left of the job's
// bar, or the whole bar (of startX).
enum class RoughStock { from_earlier, bar };
inline constexpr Named<RoughStock> rough_stocks[] = {
    {RoughStock::from_earlier, "auto",
     "with a stock bar, what the outside operations before it left of it (faces, roughs, profiles, grooves, "
     "part-offs); without one the bar of startX"},
    {RoughStock::bar, "bar", "the whole bar of startX (or the stock bar's diameter) over the profile, as if nothing had cut it"},
};

struct TurnRoughOp {
    static constexpr std::string_view type = "turn-rough";
    static constexpr MachineKind machine_kind = MachineKind::lathe;
    // Reads one operation of this type (its "type" is already read).
    static TurnRoughOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    XValues given_x = XValues::diameter;
    FeedMode feed_mode = FeedMode::per_minute;
    double feed = 0.0;              // mm/min
    Profile profile;                // the finished profile, (Z, radius), Z never rising along it
    Profile boundary;               // the profile moved by the allowances: what the roughing leaves
    // What the tool tip follows to leave the boundary: with a nose radius and computer
    // compensation the tip path of nose_path along the boundary closed by its end face up to
    // the bar (so its end is that face's), else the boundary itself. Along X it begins with
    // the nose's roll round the boundary's start corner from +Z (unless the boundary starts up
    // a face), so that every Z level from the start down has its stop on it. The levels' spans
    // (along X: each pass's stop) and the last pass are this path's.
    Profile tip_boundary;
    NoseCompensation compensation = NoseCompensation::computer;
    double nose_radius = 0.0;       // mm
    double allowance_x = 0.0;       // radial, mm
    double allowance_z = 0.0;       // mm
    double stock_radius = 0.0;      // the bar's radius it roughs from, mm
    double bottom = 0.0;            // the boundary's least radius, mm
    RoughDirection direction = RoughDirection::z;
    double depth_of_cut = 0.0;      // the most per pass, mm: radial along Z, axial along X
    double steepest_fall = 0.0;     // degrees: the boundary's steepest fall towards the chuck (0: none)
    double approach = 1.0;          // mm beyond the boundary's start where passes start, and outside the bar
    double lift = 0.5;              // mm of the 45-degree lift off each pass's end
    CycleOutput output = CycleOutput::automatic;  // along Z: a roughing cycle (TurnCycle) or longhand passes
    // The Z of the bar's face when this operation runs (the stock's faceZ, or where an earlier
    // turn-face left it; set after the operations are read), nullopt without a bar.
    std::optional<double> bar_face;
    RoughStock stock = RoughStock::from_earlier;
    // What it roughs from where that is the earlier operations' result ("stock": "auto" with a
    // bar): set by read_job once every operation is read (lathe_material_cut of each outside
    // operation before it), empty otherwise (the whole bar of stock_radius). The levels start
    // from its most over the profile, a pass begins approachDistance before it at its level, a
    // level wholly in air is left out.
    LatheMaterial material;
    std::vector<std::string> notes;
    // The turn-profile right after it that finishes its cycle's shape with Fanuc's G70 (set by
    // read_job where that is exact, link_fanuc_finishing): its cycle (TurnCycle::finish) then
    // carries the finishing shape and the allowances.
    std::optional<CycleFinish> finish;

    // Whether the operations before it left the whole bar over the boundary's length up to the
    // bar's face (material empty, or only the face moved): a roughing cycle, which roughs from
    // the bar, then cuts no more air than passes from that material.
    bool whole_bar_over_boundary() const;
};

// A stretch of a roughing pass along Z at one level: from Z `hi` down to Z `lo`.
struct TurnRoughSpan {
    double lo = 0.0, hi = 0.0;
};

// Where the tip at level `radius` runs above the tip boundary of `op` (the nose above the
// boundary) between its start's Z and its end's: the spans from +Z to -Z.
std::vector<TurnRoughSpan> turn_rough_spans(const TurnRoughOp& op, double radius);

// The tip boundary's radius at Z z (the least where a face stands at z), for z within it.
double turn_rough_boundary_at(const TurnRoughOp& op, double z);

// The Z levels of the passes along X: equal steps from the boundary's start down to its end,
// the last step left to the pass along the boundary.
std::vector<double> turn_rough_x_levels(const TurnRoughOp& op);

// Rapid outside the bar to approachDistance beyond the boundary's start; for each level, for each
// span: rapid down in air (beyond the start, or down the column the levels above have cleared),
// feed along -Z to the span's end, lift at 45 degrees, rapid back in air; then feed along the
// boundary, up the face at its end to the bar, lift off, rapid back to the clearance. Along X:
// for each Z level, rapid down outside the bar, feed in along -X to the tip boundary, lift off
// (+Z, and +X steeper than the boundary's steepest fall) and rapid back out; then feed down the
// end face, along the tip boundary to its start, lift off it and rapid to the clearance. Under
// "auto"/"canned" the cycle (turn_cycle) instead, in either direction, where it is not refused.
void expand(const TurnRoughOp& op, const Context& context, EventSink& sink);

// The roughing cycle of a turn-rough along Z: from its start beyond the part, levels depthOfCut
// apart at most, the control's moves (linuxcnc_g71), or a refusal saying why the cycle would not
// rough this boundary (a pocket, a profile starting inside the bar, a level through a corner
// whatever the start). Along X (along_x): G72 (linuxcnc_g72) on the tip boundary walked
// backwards from the top of its end face at the bar, from a start approachDistance outside the
// bar whose Z, the first level, is at most depthOfCut below the boundary's start (or the bar's
// face beyond it).
TurnCycle turn_cycle(const TurnRoughOp& op);

// The operation's name for comments: its comment, else "turn rough".
std::string default_name(const TurnRoughOp& op);

}  // namespace camgen
