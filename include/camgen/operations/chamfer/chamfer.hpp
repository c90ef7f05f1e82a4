#pragma once
// The chamfer operation: a chamfer of a width (its leg on the top face) and an angle (from the
// vertical wall) cut with the cone of a chamfer mill or a V-bit whose half tip angle is the
// chamfer's angle, along the top edge of a profile (an outline, a pocket wall, an open edge:
// the profile sources and sides of a contour) or around the top edges of holes (the hole sources
// of bore-mill, each hole's diameter given). The depth and the offset come from the tool's
// geometry: the tip goes `tip_clearance` below the chamfer's lower edge, so that the cone and
// not the point forms the chamfer, and the tool centre runs that far from the edge that its cone
// passes through the lower edge (tool_geometry.hpp). Profiles go through the cutting engine a
// contour uses (leads, ramps, depth passes, feeds, the part-aware check); each hole is one
// circle with a half-circle lead in and out from its centre.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/heights.hpp"
#include "camgen/operations/holes.hpp"

namespace camgen {

// The geometry of a chamfer cut with a cone, mm (see chamfer_geometry).
struct ChamferGeometry {
    double height = 0.0;   // the chamfer's vertical leg: width / tan(angle)
    double depth = 0.0;    // the tip below the top edge: height + tip clearance
    double offset = 0.0;   // the tool centre from the edge, on the air side
    double reach = 0.0;    // the cone's radius at the top face: offset + width
};
// The chamfer `width` wide at `angle` degrees from the vertical, cut by a cone of that half tip
// angle with a flat of `tip_diameter` at its point, the point `tip_clearance` below the lower
// edge.
ChamferGeometry chamfer_geometry(double width, double angle, double tip_diameter, double tip_clearance);

struct ChamferOp : HoleSet {
    static constexpr std::string_view type = "chamfer";
    // Reads one operation of this type (its "type" is already read).
    static ChamferOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("chamfer") first.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    Heights heights;               // the reference plane is the top face; the end depth the tip's
    double width = 0.0;            // mm, the chamfer's leg on the top face
    double angle = 45.0;           // degrees from the vertical wall
    double tip_clearance = 0.2;    // mm, the tip below the chamfer's lower edge
    ChamferGeometry geometry;
    int passes = 1;                // depth passes, equal steps down to the tip's depth
    // Along a profile (holes empty):
    Profile profile;               // the top edge as drawn, XY
    ContourSide side = ContourSide::outside;
    CutDirection direction = CutDirection::climb;
    SpindleDirection spindle = SpindleDirection::cw;
    Lead lead_in, lead_out;
    Ramp ramp;
    bool tool_left = true;         // planned: the tool left of its travel
    Profile cut;                   // planned: the tool centre's path
    // Around holes (the HoleSet's holes):
    double diameter = 0.0;         // mm, each hole's; 0: a profile chamfer
    CutFeeds feeds;
    std::optional<double> tolerance;  // mm, for arcs that become lines (capped by the machine's)
    bool on_holes() const { return diameter > 0.0; }
};

// Per profile: its passes through the cutting engine; per hole: down at its centre, a
// half-circle lead onto the circle, the circle, a half-circle lead back to the centre.
void expand(const ChamferOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "chamfer 0.5 x 45".
std::string default_name(const ChamferOp& op);

}  // namespace camgen
