#pragma once
// The contour operation: a machinist's profile cut. A closed or open 2D profile of lines and
// arcs in XY (the geometry layer's Profile), cut beside it (left, right, inside, outside) or on
// it, climb or conventional, with the tool radius offset by camgen (computer), by the control
// (G41/G42) or both (wear, inverse wear); in depth passes from the stock top down to the end
// depth (the heights every operation takes), with an optional finishing pass, lead-in and
// lead-out, plunge or ramp entry, and tabs that hold a through-cut part.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/heights.hpp"

namespace camgen {

// Where the tool cuts, seen along the profile as drawn (left, right), on it, or for a closed
// profile inside or outside whatever the drawing direction.
enum class ContourSide { left, right, on, inside, outside };
inline constexpr Named<ContourSide> contour_sides[] = {
    {ContourSide::left, "left", "left of the profile as drawn"},
    {ContourSide::right, "right", "right of the profile as drawn"},
    {ContourSide::on, "on", "the tool centre on the profile (no offset)"},
    {ContourSide::inside, "inside", "inside a closed profile (a pocket wall)"},
    {ContourSide::outside, "outside", "outside a closed profile (a part's outline)"},
};

// Who offsets the tool radius (Fusion's compensation types).
enum class CompensationMode { computer, control, wear, inverse_wear };
inline constexpr Named<CompensationMode> compensation_modes[] = {
    {CompensationMode::computer, "computer", "camgen offsets the path by the tool radius; no G41/G42"},
    {CompensationMode::control, "control",
     "the program is the profile itself with G41/G42 (RL/RR): the control offsets by the radius in its tool table"},
    {CompensationMode::wear, "wear",
     "camgen offsets by the radius and writes G41/G42 too: the control's table holds only the wear (negative shrinks the cut)"},
    {CompensationMode::inverse_wear, "inverse-wear", "as wear with G41 and G42 swapped: a positive wear shrinks the cut"},
};

// A lead-in or lead-out: none, a tangent arc (radius, sweep in degrees) or a straight line
// (length, angle in degrees from the tangent towards the tool's side).
struct Lead {
    enum class Kind { none, arc, line } kind = Kind::none;
    double radius = 0.0;
    double sweep = 90.0;
    double length = 0.0;
    double angle = 0.0;
};

// How the tool gets down to each pass: plunge straight down, ramp along the profile at an
// angle (degrees above horizontal), or a helix of a radius at that angle before the lead-in.
struct Ramp {
    enum class Kind { plunge, along, helix } kind = Kind::plunge;
    double angle = 5.0;
    double radius = 0.0;
};

// Tabs on a closed through-cut, each `width` mm wide on the part (the tool stays up over its
// width plus the tool's diameter along the path) and `height` mm above the bottom of the cut,
// with flanks at `ramp_angle` degrees (90: straight up and down; less: a trapezoid, `width` at
// its top, the tool climbing and descending along the path at that angle).
// Where: `count` tabs spread by length over the profile's straight runs (consecutive collinear
// lines, across a closed profile's start too) and arcs long enough, none within the tool radius
// plus half a tab (and its flank) of a corner or of the profile's start; or the explicit
// positions `at`, mm along the profile as drawn from its start (a job's points near the profile
// are read as the distance of their nearest point). Reading plans `centres` from either.
struct Tabs {
    int count = 0;
    std::vector<double> at;
    double width = 0.0;
    double height = 0.0;
    double ramp_angle = 90.0;
    std::vector<double> centres;  // planned on reading: mm along the profile as drawn, ascending
};

// The finishing pass: after roughing that leaves `radial_stock` on the wall and
// `axial_stock` on the floor, the final offset at the full depth: in one pass, or in steps of
// at most `step_down` (a tall wall finished in several depths).
struct Finishing {
    double radial_stock = 0.0;
    double axial_stock = 0.0;
    std::optional<double> step_down;
};

// The feeds of each movement kind, mm/min (CNC-Calc's getFeedrate(movement)).
struct ContourFeeds {
    double cutting = 0.0;
    double plunge = 0.0;
    double ramp = 0.0;
    double lead_in = 0.0;
    double lead_out = 0.0;
    double finishing = 0.0;
};

struct ContourOp {
    static constexpr std::string_view type = "contour";
    // Reads one operation of this type (its "type" is already read).
    static ContourOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("contour") first.
    static std::vector<ObjectSpec> objects();
    std::string path;
    // The JSON path of segment k, for messages.
    std::string element_path(std::size_t k) const { return path + "/path/" + std::to_string(k); }
    std::string comment;
    int tool = 0;
    double tool_radius = 0.0;
    Heights heights;
    Profile profile;                         // as drawn, XY
    ContourSide side = ContourSide::outside;
    CutDirection direction = CutDirection::climb;
    SpindleDirection spindle = SpindleDirection::cw;
    CompensationMode compensation = CompensationMode::computer;
    double stock_to_leave = 0.0;             // radial, left on the wall after every pass
    std::optional<double> step_down;         // absent: one pass
    bool equal_steps = true;
    std::optional<Finishing> finishing;
    Lead lead_in, lead_out;
    Ramp ramp;
    std::optional<Tabs> tabs;
    ContourFeeds feeds;
    std::optional<double> tolerance;  // mm, for arcs that become lines (capped by the machine's)

    // Planned on reading (so that what cannot be cut is an error naming the operation):
    bool tool_left = true;            // the tool is left of its travel
    Profile rough;                    // the path of the roughing passes (programmed path)
    Profile finish;                   // the path of the finishing pass (empty: none)
    std::vector<std::string> notes;   // what camgen decided that the job did not ask for
};

// The pass depths from the top down (absolute Z): steps of at most `step_down` from `top` to
// `bottom`, equal (each (top - bottom) / n) or full steps with a smaller last one.
std::vector<double> pass_depths(double top, double bottom, std::optional<double> step_down, bool equal_steps);

// Lead in, cut each pass, lead out, retract: see contour.cpp.
void expand(const ContourOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "contour".
std::string default_name(const ContourOp& op);

}  // namespace camgen
