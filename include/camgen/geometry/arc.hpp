#pragma once
// Arc geometry, machine-free: planes, sweeps, splitting, sampling, linearizing. Used by job
// reading, operations, posts and readers alike.
#include <cmath>
#include <vector>

#include "camgen/geometry/geometry.hpp"

namespace camgen {

// How far an arc's end may lie off the circle through its start (the radii differ by at most
// this), mm: the tolerance of every arc a job gives.
inline constexpr double arc_radius_tolerance = 0.001;

// The coordinates of a point in an arc plane: (u, v) the in-plane axes, w the normal axis.
// XY: (x, y, z); XZ: (z, x, y) so that cw/ccw follow G18's convention seen from +Y;
// YZ: (y, z, x).
struct PlanePoint {
    double u = 0.0, v = 0.0, w = 0.0;
};
PlanePoint to_plane(const Vec3& p, Plane plane);
Vec3 from_plane(const PlanePoint& p, Plane plane);

// A point or vector in a plane's (u, v) axes.
struct PlaneVec {
    double u = 0.0, v = 0.0;
};
inline PlaneVec operator+(PlaneVec a, PlaneVec b) { return {a.u + b.u, a.v + b.v}; }
inline PlaneVec operator-(PlaneVec a, PlaneVec b) { return {a.u - b.u, a.v - b.v}; }
inline PlaneVec operator*(PlaneVec a, double k) { return {a.u * k, a.v * k}; }
inline double dot(PlaneVec a, PlaneVec b) { return a.u * b.u + a.v * b.v; }
inline double norm(PlaneVec a) { return std::hypot(a.u, a.v); }
// `a` turned by `angle` radians (counter-clockwise in the plane's (u, v)).
PlaneVec rotate(PlaneVec a, double angle);
// The (u, v) of a point in `plane`.
PlaneVec in_plane(const Vec3& p, Plane plane);

// An arc as programmed: from a start (given separately) to `to` around the absolute `centre`,
// clockwise or counter-clockwise seen looking down the plane's normal axis, with `turns`
// extra full turns of a helix.
struct ArcSpec {
    Vec3 to;
    Vec3 centre;
    ArcDirection direction = ArcDirection::cw;
    Plane plane = Plane::xy;
    int turns = 0;
};

// One arc with its start, resolved: sweep is positive, in radians, the direction says which
// way; a full circle has sweep 2*pi (plus 2*pi per extra helix turn).
struct ArcGeometry {
    Vec3 start;
    Vec3 end;
    Vec3 centre;
    ArcDirection direction = ArcDirection::cw;
    Plane plane = Plane::xy;
    double radius = 0.0;        // from the start point
    double sweep = 0.0;         // radians, > 0
    double start_angle = 0.0;   // radians, in the plane's (u, v)
};

// Resolves an arc that starts at `start`. Ends that coincide in the plane (within
// `same_point` mm) make a full circle.
ArcGeometry resolve_arc(const Vec3& start, const ArcSpec& arc, double same_point = 1e-9);

// The point at angle fraction t (0..1) along the arc, the normal axis moving linearly.
Vec3 point_on_arc(const ArcGeometry& arc, double t);

// Splits an arc into `pieces` arcs of equal sweep; the last ends exactly at arc.end.
std::vector<ArcGeometry> split_arc(const ArcGeometry& arc, int pieces);

// Number of equal straight segments whose chords stay within `tolerance` of the arc.
int segments_for_tolerance(double radius, double sweep, double tolerance);

// The end points of `segments` equal chords along the arc (the last is exactly arc.end).
std::vector<Vec3> linearize_arc(const ArcGeometry& arc, int segments);

// Length of the arc along its path, mm (a helix counts its travel along the normal axis).
double arc_length(const ArcGeometry& arc);

// Length of one of `segments` equal chords of the arc, mm.
double chord_length(const ArcGeometry& arc, int segments);

}  // namespace camgen
