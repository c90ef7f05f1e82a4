#pragma once
// Placing things in the plane: directions by angle and rigid placements (Eigen), exact for
// multiples of 90 degrees so that a grid or a pattern at 90 degrees lands on round numbers.
#include <Eigen/Geometry>

#include "camgen/geometry/geometry.hpp"

namespace camgen {

// The unit vector at `degrees` counter-clockwise from +X (exactly (0, 1) at 90 degrees).
Vec2 unit_direction(double degrees);

// The rigid placement that turns by `degrees` counter-clockwise about the origin, then moves
// the origin to `origin`.
Eigen::Isometry2d placement(Vec2 origin, double degrees);

// `p` placed by `t`.
Vec2 apply(const Eigen::Isometry2d& t, Vec2 p);

}  // namespace camgen
