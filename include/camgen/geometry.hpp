#pragma once
// Small value types for positions. Units: mm unless a comment says otherwise.

namespace camgen {

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

}  // namespace camgen
