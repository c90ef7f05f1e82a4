#include "camgen/geometry/profile.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

// Boost 1.74's rescale policy trips GCC 12's -Wmaybe-uninitialized inside its own headers.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "camgen/geometry/arc.hpp"

namespace camgen {

namespace {

namespace bg = boost::geometry;
using BgPoint = bg::model::d2::point_xy<double>;
using BgRing = bg::model::polygon<BgPoint, false, true>;  // counter-clockwise, closed
using BgLine = bg::model::linestring<BgPoint>;


// The segment as an arc of the arc geometry (in its own (u, v) taken as XY).
ArcGeometry arc_of(Vec2 from, const ProfileSegment& s) {
    return resolve_arc({from.x, from.y, 0.0}, ArcSpec{{s.end.x, s.end.y, 0.0}, {s.centre->x, s.centre->y, 0.0}, s.direction,
                                                      Plane::xy, 0});
}

// Where segment `index` starts.

// Calls `add` with each point of sample_profile in order, without a vector of them: a profile
// of a million segments is sampled into the shape that checks it, not twice.
template <class Add>
void for_each_sample(const Profile& profile, double tolerance, Add&& add) {
    add(profile.start);
    for (std::size_t i = 0; i < profile.segments.size(); ++i) {
        const ProfileSegment& s = profile.segments[i];
        if (s.centre) {
            const ArcGeometry arc = arc_of(segment_start(profile, i), s);
            for (const Vec3& p : linearize_arc(arc, segments_for_tolerance(arc.radius, arc.sweep, tolerance)))
                add(Vec2{p.x, p.y});
        } else {
            add(s.end);
        }
    }
}

BgRing ring_of(const Profile& profile, double tolerance) {
    BgRing ring;
    ring.outer().reserve(profile.segments.size() + 1);
    for_each_sample(profile, tolerance, [&](Vec2 v) { bg::append(ring.outer(), BgPoint(v.x, v.y)); });
    return ring;
}

}  // namespace

bool is_closed(const Profile& profile) {
    const Vec2 end = profile.segments.empty() ? profile.start : profile.segments.back().end;
    return !profile.segments.empty() && distance(end, profile.start) <= profile_same_point;
}

double segment_sweep(const Profile& profile, std::size_t index) {
    const ProfileSegment& s = profile.segments.at(index);
    return s.centre ? arc_of(segment_start(profile, index), s).sweep : 0.0;
}

std::optional<std::size_t> first_short_segment(const Profile& profile, double min_length) {
    for (std::size_t i = 0; i < profile.segments.size(); ++i) {
        const ProfileSegment& s = profile.segments[i];
        const Vec2 from = segment_start(profile, i);
        const double length = s.centre ? arc_length(arc_of(from, s)) : distance(from, s.end);
        if (length < min_length) return i;
    }
    return std::nullopt;
}

double profile_length(const Profile& profile) {
    double total = 0.0;
    for (std::size_t i = 0; i < profile.segments.size(); ++i) {
        const ProfileSegment& s = profile.segments[i];
        const Vec2 from = segment_start(profile, i);
        total += s.centre ? arc_length(arc_of(from, s)) : distance(from, s.end);
    }
    return total;
}

std::vector<Vec2> sample_profile(const Profile& profile, double tolerance) {
    std::vector<Vec2> out;
    out.reserve(profile.segments.size() + 1);
    for_each_sample(profile, tolerance, [&](Vec2 v) { out.push_back(v); });
    return out;
}

bool is_simple(const Profile& profile, double tolerance) {
    if (is_closed(profile)) {
        BgRing ring = ring_of(profile, tolerance);
        bg::correct(ring);
        return bg::is_valid(ring);
    }
    BgLine line;
    line.reserve(profile.segments.size() + 1);
    for_each_sample(profile, tolerance, [&](Vec2 v) { bg::append(line, BgPoint(v.x, v.y)); });
    // Boost 1.74's is_simple calls a fine sampling of an S (two tangent arcs turning opposite
    // ways) not simple; its self-intersection test answers the question asked.
    return !bg::intersects(line);
}

namespace {

// The signed area (counter-clockwise positive), exact: the chords' polygon (the shoelace sum)
// and, for each arc, the circular segment between its chord and itself, r^2 (sweep - sin sweep) / 2,
// added where the arc turns counter-clockwise and taken where it turns clockwise.
double exact_signed_area(const Profile& profile) {
    double twice = 0.0;
    for (std::size_t i = 0; i < profile.segments.size(); ++i) {
        const ProfileSegment& s = profile.segments[i];
        const Vec2 a = segment_start(profile, i);
        twice += a.x * s.end.y - s.end.x * a.y;
        if (s.centre) {
            const ArcGeometry arc = arc_of(a, s);
            const double piece = arc.radius * arc.radius * (arc.sweep - std::sin(arc.sweep));
            twice += s.direction == ArcDirection::ccw ? piece : -piece;
        }
    }
    // An open profile is closed by the chord from its end back to its start.
    if (!profile.segments.empty()) {
        const Vec2 e = profile.segments.back().end;
        twice += e.x * profile.start.y - profile.start.x * e.y;
    }
    return twice / 2.0;
}

}  // namespace

Orientation orientation(const Profile& profile, double) {
    return exact_signed_area(profile) >= 0.0 ? Orientation::ccw : Orientation::cw;
}

double enclosed_area(const Profile& profile, double tolerance) {
    return std::abs(bg::area(ring_of(profile, tolerance)));
}

bool contains(const Profile& profile, Vec2 p, double tolerance) {
    BgRing ring = ring_of(profile, tolerance);
    bg::correct(ring);
    return bg::within(BgPoint(p.x, p.y), ring);
}

Profile transformed(const Profile& profile, const Eigen::Isometry2d& t) {
    auto map = [&](Vec2 v) {
        const Eigen::Vector2d r = t * Eigen::Vector2d(v.x, v.y);
        return Vec2{r.x(), r.y()};
    };
    const bool mirrored = t.linear().determinant() < 0.0;
    Profile out{profile.plane, map(profile.start), {}};
    for (const ProfileSegment& s : profile.segments) {
        ProfileSegment m{map(s.end), std::nullopt, s.direction};
        if (s.centre) m.centre = map(*s.centre);
        if (mirrored) m.direction = s.direction == ArcDirection::cw ? ArcDirection::ccw : ArcDirection::cw;
        out.segments.push_back(m);
    }
    return out;
}

std::size_t make_arcs_exact(Profile& profile, double within) {
    std::size_t moved = 0;
    for (std::size_t i = 0; i < profile.segments.size(); ++i) {
        ProfileSegment& s = profile.segments[i];
        if (!s.centre) continue;
        const Vec2 a = segment_start(profile, i), b = s.end, c = *s.centre;
        const double r0 = distance(a, c), r1 = distance(b, c), chord = distance(a, b);
        const double off = std::abs(r1 - r0);
        if (off <= 1e-9 || off > within || chord <= profile_same_point) continue;
        const Vec2 u = (b - a) * (1.0 / chord), mid = (a + b) * 0.5;
        const Vec2 exact = c - u * dot(c - mid, u);
        // The given arc as resolve_arc takes it (the start's radius, to the end's angle) and the
        // exact one: the exact one's points against the given radius turning evenly about c.
        const ArcGeometry given = arc_of(a, s);
        ProfileSegment candidate = s;
        candidate.centre = exact;
        const ArcGeometry made = arc_of(a, candidate);
        if (std::abs(made.sweep - given.sweep) > pi / 2) continue;
        const double sign = s.direction == ArcDirection::ccw ? 1.0 : -1.0;
        double worst = 0.0;
        constexpr int samples = 64;
        for (int k = 1; k < samples; ++k) {
            const double t = static_cast<double>(k) / samples;
            const Vec2 p = exact + unit_at(made.start_angle + sign * t * made.sweep) * made.radius;
            // The angle turned about c from the start, near the given arc's t * sweep.
            const double turned = sign * (std::atan2(p.y - c.y, p.x - c.x) - given.start_angle);
            const double along = t * given.sweep + std::remainder(turned - t * given.sweep, two_pi);
            worst = std::max(worst, std::abs(distance(p, c) - (r0 + (r1 - r0) * along / given.sweep)));
        }
        if (worst > within) continue;
        s.centre = exact;
        ++moved;
    }
    return moved;
}

Profile reversed(const Profile& profile) {
    Profile out{profile.plane, profile.segments.empty() ? profile.start : profile.segments.back().end, {}};
    for (std::size_t i = profile.segments.size(); i-- > 0;) {
        const ProfileSegment& s = profile.segments[i];
        ProfileSegment r{segment_start(profile, i), s.centre, s.direction == ArcDirection::cw ? ArcDirection::ccw : ArcDirection::cw};
        out.segments.push_back(r);
    }
    return out;
}

}  // namespace camgen
