#pragma once
// A 2D profile: a chain of line and arc segments in one plane (XY for milling contours, XZ for
// a lathe's profile), open or closed, with the polygon questions a CAM program asks of it
// (closed, simple, orientation, point inside) answered by Boost.Geometry on a sampling within
// a chord tolerance, and rigid transforms through Eigen. Machine-free: depends on nothing of
// camgen but the geometry's own types. Lengths mm.
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "camgen/geometry/geometry.hpp"

namespace camgen {

// The plane of a profile: its (u, v) are (x, y) in XY and (z, x) in XZ (Z along the spindle
// of a lathe as u, the radius as v).
enum class ProfilePlane { xy, xz };

// One segment, from the end of the previous one (or the profile's start) to `end`: a straight
// line, or an arc around `centre` turning `direction` (seen looking down the plane's normal).
struct ProfileSegment {
    Vec2 end;
    std::optional<Vec2> centre;   // set: an arc
    ArcDirection direction = ArcDirection::ccw;
    friend bool operator==(const ProfileSegment&, const ProfileSegment&) = default;
};

struct Profile {
    ProfilePlane plane = ProfilePlane::xy;
    Vec2 start;
    std::vector<ProfileSegment> segments;
};

// Turning direction of a closed profile.
enum class Orientation { ccw, cw };

// Two points closer than this are the same point, mm.
inline constexpr double profile_same_point = 1e-6;

// True when the last segment ends at the start (within profile_same_point).
bool is_closed(const Profile& profile);

// The index of the first segment shorter than `min_length` mm along its path, if any.
std::optional<std::size_t> first_short_segment(const Profile& profile, double min_length = profile_same_point);

// The sweep of segment `index` in radians (0 for a line; a full circle is 2 pi).
double segment_sweep(const Profile& profile, std::size_t index);
// Where segment `index` starts: the profile's start, or the end of the segment before it.
inline Vec2 segment_start(const Profile& profile, std::size_t index) {
    return index == 0 ? profile.start : profile.segments[index - 1].end;
}

// Length along the profile, mm.
double profile_length(const Profile& profile);

// Points along the profile whose chords stay within `tolerance` mm of its arcs: the start, then
// every segment's intermediate points and end.
std::vector<Vec2> sample_profile(const Profile& profile, double tolerance);

// The polygon questions, on the sampling (within `tolerance` mm):
// a closed profile that does not touch or cross itself (an open one: a chain that does not);
bool is_simple(const Profile& profile, double tolerance = 0.001);
// the turning direction of a closed profile (by its signed area, computed exactly with its arcs:
// the tolerance is not used);
Orientation orientation(const Profile& profile, double tolerance = 0.001);
// the area enclosed by a closed profile, mm^2, positive;
double enclosed_area(const Profile& profile, double tolerance = 0.001);
// `p` strictly inside a closed profile.
bool contains(const Profile& profile, Vec2 p, double tolerance = 0.001);

// The profile moved by a rigid transform (rotation and translation; a reflection also turns
// every arc's direction), arcs staying arcs.
Profile transformed(const Profile& profile, const Eigen::Isometry2d& transform);

// The same path walked the other way round.
Profile reversed(const Profile& profile);

// An arc whose end lies off the circle through its start (a job's coordinates rounded; a job
// may give an arc's end up to arc_radius_tolerance off) made exact, once, where the profile
// enters: its centre moved along the perpendicular bisector of its ends to the point nearest
// the given centre, so that both ends lie on its circle and every later stage (offsets, the
// part guard, the posts, verify's comparison, simulate's design) takes the one arc. Only arcs
// off by more than 1e-9 mm and at most `within` mm are moved, and only where the exact arc
// lies within `within` of the arc as given (its radius turning evenly from the start's to the
// end's); that leaves out only arcs turning past about 300 degrees, whose exact arc through
// both ends lies further from the given one (nearly a full circle: the centre would move by
// about the end's distance off over the chord's length times the radius), which stay as
// given (src/geometry/curve.hpp's curves_of takes them). Returns how many arcs it moved.
std::size_t make_arcs_exact(Profile& profile, double within);

}  // namespace camgen
