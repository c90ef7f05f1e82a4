#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace camgen {

namespace {

}  // namespace

PlanePoint to_plane(const Vec3& p, Plane plane) {
    switch (plane) {
        case Plane::xy: return {p.x, p.y, p.z};
        case Plane::xz: return {p.z, p.x, p.y};
        case Plane::yz: return {p.y, p.z, p.x};
    }
    return {};
}

Vec3 from_plane(const PlanePoint& p, Plane plane) {
    switch (plane) {
        case Plane::xy: return {p.u, p.v, p.w};
        case Plane::xz: return {p.v, p.w, p.u};
        case Plane::yz: return {p.w, p.u, p.v};
    }
    return {};
}

PlaneVec rotate(PlaneVec a, double angle) {
    double c = std::cos(angle), s = std::sin(angle);
    return {a.u * c - a.v * s, a.u * s + a.v * c};
}

PlaneVec in_plane(const Vec3& p, Plane plane) {
    PlanePoint q = to_plane(p, plane);
    return {q.u, q.v};
}

ArcGeometry resolve_arc(const Vec3& start, const ArcSpec& arc, double same_point) {
    ArcGeometry g;
    g.start = start;
    g.end = arc.to;
    g.centre = arc.centre;
    g.direction = arc.direction;
    g.plane = arc.plane;
    PlanePoint s = to_plane(start, arc.plane);
    PlanePoint e = to_plane(arc.to, arc.plane);
    PlanePoint c = to_plane(arc.centre, arc.plane);
    g.radius = std::hypot(s.u - c.u, s.v - c.v);
    double a0 = std::atan2(s.v - c.v, s.u - c.u);
    double a1 = std::atan2(e.v - c.v, e.u - c.u);
    g.start_angle = a0;
    double sweep;
    if (std::hypot(e.u - s.u, e.v - s.v) <= same_point) {
        sweep = two_pi;
    } else {
        sweep = arc.direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
        while (sweep <= 0.0) sweep += two_pi;
        while (sweep > two_pi) sweep -= two_pi;
    }
    g.sweep = sweep + two_pi * arc.turns;
    return g;
}

Vec3 point_on_arc(const ArcGeometry& arc, double t) {
    if (t >= 1.0) return arc.end;
    if (t <= 0.0) return arc.start;
    PlanePoint s = to_plane(arc.start, arc.plane);
    PlanePoint e = to_plane(arc.end, arc.plane);
    PlanePoint c = to_plane(arc.centre, arc.plane);
    double sign = arc.direction == ArcDirection::ccw ? 1.0 : -1.0;
    double a = arc.start_angle + sign * t * arc.sweep;
    PlanePoint p{c.u + arc.radius * std::cos(a), c.v + arc.radius * std::sin(a), s.w + t * (e.w - s.w)};
    return from_plane(p, arc.plane);
}

std::vector<ArcGeometry> split_arc(const ArcGeometry& arc, int pieces) {
    std::vector<ArcGeometry> out;
    pieces = std::max(pieces, 1);
    out.reserve(static_cast<size_t>(pieces));
    double sign = arc.direction == ArcDirection::ccw ? 1.0 : -1.0;
    Vec3 from = arc.start;
    for (int k = 0; k < pieces; ++k) {
        ArcGeometry piece = arc;
        piece.start = from;
        piece.end = k + 1 == pieces ? arc.end : point_on_arc(arc, double(k + 1) / pieces);
        piece.sweep = arc.sweep / pieces;
        piece.start_angle = arc.start_angle + sign * arc.sweep * k / pieces;
        out.push_back(piece);
        from = piece.end;
    }
    return out;
}

int segments_for_tolerance(double radius, double sweep, double tolerance) {
    if (radius <= 0.0 || sweep <= 0.0) return 1;
    double max_step = tolerance >= radius ? std::numbers::pi : 2.0 * std::acos(1.0 - tolerance / radius);
    if (!(max_step > 0.0)) max_step = 1e-6;
    double n = std::ceil(sweep / max_step - 1e-9);
    return static_cast<int>(std::clamp(n, 1.0, 1e7));
}

std::vector<Vec3> linearize_arc(const ArcGeometry& arc, int segments) {
    std::vector<Vec3> points;
    segments = std::max(segments, 1);
    points.reserve(static_cast<size_t>(segments));
    for (int k = 1; k < segments; ++k) points.push_back(point_on_arc(arc, double(k) / segments));
    points.push_back(arc.end);
    return points;
}

double arc_length(const ArcGeometry& arc) {
    PlanePoint a = to_plane(arc.start, arc.plane), b = to_plane(arc.end, arc.plane);
    return std::hypot(arc.radius * arc.sweep, b.w - a.w);
}

double chord_length(const ArcGeometry& arc, int segments) {
    segments = std::max(segments, 1);
    PlanePoint a = to_plane(arc.start, arc.plane), b = to_plane(arc.end, arc.plane);
    double step = arc.sweep / segments;
    double in_plane_chord = step >= two_pi ? 0.0 : 2.0 * arc.radius * std::abs(std::sin(step / 2.0));
    return std::hypot(in_plane_chord, (b.w - a.w) / segments);
}

}  // namespace camgen
