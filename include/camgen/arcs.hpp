#pragma once
// Arc geometry shared by posts and the reader: sweeps, splitting, linearizing.
#include <vector>

#include "camgen/events.hpp"
#include "camgen/geometry.hpp"

namespace camgen {

// The coordinates of a point in an arc plane: (u, v) the in-plane axes, w the normal axis.
// XY: (x, y, z); XZ: (z, x, y) so that cw/ccw follow G18's convention seen from +Y;
// YZ: (y, z, x).
struct PlanePoint {
    double u = 0.0, v = 0.0, w = 0.0;
};
PlanePoint to_plane(const Vec3& p, Plane plane);
Vec3 from_plane(const PlanePoint& p, Plane plane);

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

// Resolves an Arc event that starts at `start`. Ends that coincide in the plane (within
// `same_point` mm) make a full circle.
ArcGeometry resolve_arc(const Vec3& start, const Arc& arc, double same_point = 1e-9);

// The point at angle fraction t (0..1) along the arc, the normal axis moving linearly.
Vec3 point_on_arc(const ArcGeometry& arc, double t);

// Splits an arc into `pieces` arcs of equal sweep; the last ends exactly at arc.end.
std::vector<ArcGeometry> split_arc(const ArcGeometry& arc, int pieces);

// Number of equal straight segments whose chords stay within `tolerance` of the arc.
int segments_for_tolerance(double radius, double sweep, double tolerance);

// The end points of `segments` equal chords along the arc (the last is exactly arc.end).
std::vector<Vec3> linearize_arc(const ArcGeometry& arc, int segments);

}  // namespace camgen
