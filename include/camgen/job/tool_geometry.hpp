#pragma once
// The geometry of a pointed tool (chamfer mill, V-bit) that operations cut with: the diameter
// its cone cuts at a height above its point, and the height at which it cuts a diameter. One
// place for it, so that every operation that cuts with the cone (chamfer, engrave) measures the
// same tool the same way. A cone of included angle `tipAngle` with a flat of `tipDiameter` at its
// point, up to the tool's `diameter`. Lengths mm.
#include <algorithm>
#include <cmath>

#include "camgen/geometry/vec.hpp"
#include "camgen/job/job.hpp"

namespace camgen {

// Whether the tool cuts with a cone (a chamfer mill or a V-bit with its tip angle).
inline bool is_cone_tool(const Tool& tool) {
    return (tool.type == ToolType::chamfer_mill || tool.type == ToolType::v_bit) && tool.tip_angle && *tool.tip_angle > 0 &&
           *tool.tip_angle < 180;
}

// tan of half the tip angle: the cone's radius gained per mm of height.
inline double cone_flank_tan(const Tool& tool) { return std::tan(tool.tip_angle.value_or(90.0) / 2.0 * rad_per_deg); }

// The effective diameter of a V at a depth: the diameter the cone of a chamfer mill or V-bit
// cuts `height` mm above its point (its tip diameter at 0), at most the tool's diameter.
inline double cone_diameter_at(const Tool& tool, double height) {
    return std::min(tool.diameter, tool.tip_diameter + 2.0 * std::max(0.0, height) * cone_flank_tan(tool));
}

// The height above the point at which the cone cuts `diameter` (0 at or below its tip
// diameter); beyond the tool's diameter the cone's full length.
inline double cone_height_for(const Tool& tool, double diameter) {
    const double d = std::clamp(diameter, tool.tip_diameter, tool.diameter);
    return (d - tool.tip_diameter) / 2.0 / cone_flank_tan(tool);
}

}  // namespace camgen
