#include "camgen/geometry/transform.hpp"

#include <cmath>
#include <numbers>

namespace camgen {

Vec2 unit_direction(double degrees) {
    double d = std::fmod(degrees, 360.0);
    if (d < 0) d += 360.0;
    if (d == 0.0) return {1.0, 0.0};
    if (d == 90.0) return {0.0, 1.0};
    if (d == 180.0) return {-1.0, 0.0};
    if (d == 270.0) return {0.0, -1.0};
    const double r = degrees * std::numbers::pi / 180.0;
    return {std::cos(r), std::sin(r)};
}

Eigen::Isometry2d placement(Vec2 origin, double degrees) {
    const Vec2 u = unit_direction(degrees);
    Eigen::Isometry2d t = Eigen::Isometry2d::Identity();
    t.linear() << u.x, -u.y, u.y, u.x;
    t.translation() << origin.x, origin.y;
    return t;
}

Vec2 apply(const Eigen::Isometry2d& t, Vec2 p) {
    const Eigen::Vector2d r = t * Eigen::Vector2d(p.x, p.y);
    return {r.x(), r.y()};
}

}  // namespace camgen
