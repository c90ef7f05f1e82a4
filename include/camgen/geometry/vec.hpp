#pragma once
// Arithmetic on Vec2 and the angle constants, one meaning each for every file of camgen.
#include <cmath>
#include <numbers>

#include "camgen/geometry/geometry.hpp"

namespace camgen {

inline constexpr double pi = std::numbers::pi;
inline constexpr double two_pi = 2.0 * std::numbers::pi;
// Multiply an angle in radians by this to get degrees, and one in degrees by rad_per_deg.
inline constexpr double deg_per_rad = 180.0 / std::numbers::pi;
inline constexpr double rad_per_deg = std::numbers::pi / 180.0;

constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator*(Vec2 a, double k) { return {a.x * k, a.y * k}; }
constexpr Vec2 operator*(double k, Vec2 a) { return {a.x * k, a.y * k}; }
constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// The z of the 3D cross product: > 0 when b turns left (counter-clockwise) from a.
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }
inline double distance(Vec2 a, Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }
// `a` turned 90 degrees counter-clockwise.
constexpr Vec2 left_of(Vec2 a) { return {-a.y, a.x}; }
// The unit vector at `angle` (radians, counter-clockwise from +X).
inline Vec2 unit_at(double angle) { return {std::cos(angle), std::sin(angle)}; }
// `v` turned by `angle` (radians, counter-clockwise).
inline Vec2 rotated(Vec2 v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {v.x * c - v.y * s, v.x * s + v.y * c};
}

}  // namespace camgen
