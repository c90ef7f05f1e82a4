#pragma once
// The geometry of a cutter that operations cut with (issue 29, item 1): the diameter a pointed
// tool's cone (chamfer mill, V-bit: a cone of included angle `tipAngle` with a flat of
// `tipDiameter` at its point, up to the tool's `diameter`) cuts at a height above its point, the
// height at which it cuts a diameter, and the width any milling tool cuts at a depth. One place
// for it, so that every operation that needs it (chamfer, engrave) measures the same tool the
// same way. Header-only. Lengths mm.
#include <algorithm>
#include <cmath>
#include <optional>

#include "camgen/geometry/vec.hpp"
#include "camgen/job/job.hpp"

namespace camgen {

// Whether the tool cuts with a cone (a chamfer mill or a V-bit with its tip angle).
inline bool is_cone_tool(const Tool& tool) {
    return is_pointed_cutter(tool.type) && tool.tip_angle && *tool.tip_angle > 0 &&
           *tool.tip_angle < 180;
}

// tan of half the tip angle: the cone's radius gained per mm of height.
inline double cone_flank_tan(const Tool& tool) { return std::tan(tool.tip_angle.value_or(90.0) / 2.0 * rad_per_deg); }

// The effective diameter of a V at a depth: the diameter the cone of a chamfer mill or V-bit
// cuts `height` mm above its point (its tip diameter at 0), at most the tool's diameter (above
// its cone the tool cuts with its full diameter).
inline double cone_diameter_at(const Tool& tool, double height) {
    return std::min(tool.diameter, tool.tip_diameter + 2.0 * std::max(0.0, height) * cone_flank_tan(tool));
}

// The height above the point at which the cone cuts `diameter` (0 at or below its tip
// diameter); beyond the tool's diameter the cone's full length.
inline double cone_height_for(const Tool& tool, double diameter) {
    const double d = std::clamp(diameter, tool.tip_diameter, tool.diameter);
    return (d - tool.tip_diameter) / 2.0 / cone_flank_tan(tool);
}

// The width a milling tool cuts `depth` mm deep into a flat top: a V-bit's or chamfer mill's
// cone diameter at that height, a ball's chord (2 sqrt(r^2 - (r - depth)^2) within its radius),
// else (end mill, bull-nose) its diameter. None for a V without its tipAngle.
inline std::optional<double> cut_width_at_depth(const Tool& tool, double depth) {
    switch (tool.type) {
    case ToolType::v_bit:
    case ToolType::engraver:
    case ToolType::chamfer_mill:
        if (!is_cone_tool(tool)) return std::nullopt;
        return cone_diameter_at(tool, depth);
    case ToolType::ball_mill: {
        const double r = tool.diameter / 2.0;
        if (depth >= r) return tool.diameter;
        return 2.0 * std::sqrt(std::max(0.0, r * r - (r - depth) * (r - depth)));
    }
    default:
        return tool.diameter;
    }
}

}  // namespace camgen
