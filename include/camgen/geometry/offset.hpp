#pragma once
// Offsetting a 2D profile by a distance (a tool radius) to one side, and the small questions a
// contour operation asks of a profile: the point and tangent at a length, the piece between two
// lengths, the distance of a point from it, which side is inside. Lines stay lines and arcs stay
// arcs; the offset never comes closer than the distance to the profile (it is the boundary of
// the region within the distance, on the chosen side). Machine-free. Lengths mm.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/profile.hpp"

namespace camgen {

// Left or right of the direction of travel (seen looking down the plane's normal).
enum class OffsetSide { left, right };

// Inside or outside a closed profile, whatever the drawing direction.
enum class Region { inside, outside };

// The side of travel that is `region` of a closed profile turning `orientation`: a
// counter-clockwise profile has its inside on the left, its outside on the right.
OffsetSide side_for(Orientation orientation, Region region);

// What the offset could not follow, naming the input segment. A consumed profile has only
// the `consumed` note.
enum class OffsetNoteKind {
    arc_too_tight,    // a concave arc of radius below the distance: the tool cannot reach into it
    element_removed,  // a segment whose offset vanished entirely after trimming (a notch or a
                      // step narrower than the tool, a short segment between concave corners)
    split,            // the offset fell apart into several paths (a neck narrower than the tool)
    consumed,         // nothing remains: the profile is smaller than the tool
};

struct OffsetNote {
    OffsetNoteKind kind = OffsetNoteKind::element_removed;
    std::optional<std::size_t> segment;  // the input segment's index, when one is to blame
    std::string message;                 // a sentence for the user, e.g. "segment 3: ..."
};

// The result of offset_profile. `profile` is the main path (the longest one; no segments when
// the profile is consumed), `others` any further paths it split into, in the order of the
// profile. `source[i]` is the input segment that `profile.segments[i]` offsets, or nullopt for
// an arc added around a convex corner (one input segment may give several output segments
// when the offset of something else cuts through it).
struct OffsetResult {
    Profile profile;
    std::vector<std::optional<std::size_t>> source;
    std::vector<Profile> others;
    std::vector<OffsetNote> notes;
    bool empty() const { return profile.segments.empty(); }
};

// The profile offset by `distance` mm to `side` of its direction of travel, walked the same
// way: lines parallel, arcs about the same centre with the radius +- distance, an arc of
// radius `distance` around each convex corner, concave corners trimmed where the two offsets
// meet, loops cut away where the offset would cross itself, so that every point is at exactly
// `distance` from the profile (within 1e-6 mm) and none closer. A closed profile gives closed
// simple paths; an open one its one-sided offset, from the start's offset to the end's where
// those are not cut away. An arc whose given end is off its circle (its radius is the start's,
// as resolve_arc) counts as the arc to its circle's end and a line on to the given end (a
// drawing's slightly non-tangent joints; a job's arcs within arc_radius_tolerance arrive made
// exact by make_arcs_exact, profile.hpp, as that line can turn against a sharp corner and lose
// the corner's arc). Zero-length segments are passed over; a distance <= 0 gives the
// profile itself. Cost: about the number of segments times those within 2 distance of each.
OffsetResult offset_profile(const Profile& profile, double distance, OffsetSide side);

// A position along a profile: the point, the unit tangent of travel there, and the segment.
struct ProfilePoint {
    Vec2 point;
    Vec2 tangent;
    std::size_t segment = 0;
};

// The position `length` mm along the profile from its start (clamped to [0, profile_length]).
// At a segment's end the position belongs to that segment (its tangent is the arriving one).
ProfilePoint point_at(const Profile& profile, double length);

// The part of the profile between `from` and `to` mm along it, lines and arcs split exactly (an
// arc keeps its centre and direction). from <= to; on a closed profile from > to wraps past the
// start. Clamped to the profile's length.
Profile sub_profile(const Profile& profile, double from, double to);

// The shortest distance from `p` to the profile's path, mm.
double distance_to(const Profile& profile, Vec2 p);

}  // namespace camgen
