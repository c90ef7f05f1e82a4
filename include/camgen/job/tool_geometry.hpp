#pragma once
// What a cutter's geometry makes of a cut (issue 29, item 1): the width a pointed or round tool
// cuts at a depth. Header-only, so that every operation that needs it (engrave, chamfer) shares
// one definition.
#include <algorithm>
#include <cmath>
#include <optional>

#include "camgen/geometry/vec.hpp"
#include "camgen/job/job.hpp"

namespace camgen {

// The effective diameter of a V (a V-bit's or chamfer mill's cone of included angle
// `tip_angle` degrees with a flat of `tip_diameter` at its point) `depth` mm above its point:
// tip_diameter + 2 x depth x tan(tip_angle / 2), at most the tool's `diameter` (above its cone
// the tool cuts with its full diameter). mm.
inline double v_diameter_at_depth(double tip_angle, double tip_diameter, double diameter, double depth) {
    const double d = tip_diameter + 2.0 * std::max(depth, 0.0) * std::tan(tip_angle / 2.0 * rad_per_deg);
    return std::min(d, diameter);
}

// The width a milling tool cuts `depth` mm deep into a flat top: a V-bit's or chamfer mill's
// effective V diameter, a ball's chord (2 sqrt(r^2 - (r - depth)^2) within its radius), else
// (end mill, bull-nose) its diameter. None for a tool without that geometry (a V without its
// tipAngle). mm.
inline std::optional<double> cut_width_at_depth(const Tool& tool, double depth) {
    switch (tool.type) {
    case ToolType::v_bit:
    case ToolType::chamfer_mill:
        if (!tool.tip_angle) return std::nullopt;
        return v_diameter_at_depth(*tool.tip_angle, tool.tip_diameter, tool.diameter, depth);
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
