#pragma once
// Small value types for positions. Units: mm unless a comment says otherwise.

namespace camgen {

// Millimetres in an inch (exact).
inline constexpr double mm_per_inch = 25.4;

// A point or vector in the XY plane, mm.
struct Vec2 {
    double x = 0.0;
    double y = 0.0;
    friend bool operator==(const Vec2&, const Vec2&) = default;
};

// A point or vector in machine space, mm.
struct Vec3 {
    double x = 0.0;
    double y = 0.0;
    double z = 0.0;
    friend bool operator==(const Vec3&, const Vec3&) = default;
};

// The plane of an arc: XY (G17), XZ (G18), YZ (G19).
enum class Plane { xy, xz, yz };

// The turning direction of an arc, seen looking down the plane's normal axis (Z for XY, Y for
// XZ, X for YZ: the G17/G18/G19 convention).
enum class ArcDirection { cw, ccw };

}  // namespace camgen
