#include "camgen/operations/turn_profile/turn_profile.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/geometry/offset.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

// Arcs are sampled within this for the material checks, mm.
constexpr double sampling_tolerance = 0.001;
// A move counts as in the material when it runs inside it (by more than profile_same_point
// across) for more than this along Z, mm: a move along a kept surface, or past the corner where
// a profile leaves its start, is not.
constexpr double material_margin = 0.002;
// An arc may dip this far below the spindle axis (rounding), mm.
constexpr double axis_tolerance = 1e-6;

constexpr KeySpec turn_profile_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "xValues", .type = JsonType::string, .default_json = "\"diameter\"", .choices = &choices_of<x_values>,
     .description = "the points' X as diameters or as radii (the program writes X as the machine's xDiameterProg says)"},
    {.key = "feed", .quantity = Quantity::feed, .required = true, .min = Bound{0, false},
     .description = "cutting feed, per minute or per revolution (feedMode)"},
    {.key = "feedMode", .type = JsonType::string, .default_json = "\"per-minute\"", .choices = &choices_of<feed_modes>,
     .description = "feed in mm/min or mm/rev; the program feeds the same way (G94/G95, Fanuc T G98/G99)"},
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "where the profile starts [x, z]; the tool feeds to it along Z from the clearance"},
    {.key = "path", .type = JsonType::array, .required = true, .ref = "turnProfileElement", .min_items = 1,
     .description = "the profile's elements [x, z], each starting where the previous one ends"},
    {.key = "retractX", .quantity = Quantity::length, .required = true,
     .description = "X (as xValues) the tool rapids out to after it has lifted off the profile's end, before it rapids "
                    "back to the clearance"},
    {.key = "approachDistance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "1",
     .description = "how far before the start the approach along Z turns from rapid to feed, mm"},
    {.key = "compensation", .type = JsonType::string, .default_json = "\"computer\"", .choices = &choices_of<nose_compensation_modes>,
     .description = "who makes up for the tool's nose radius: computer (the program runs the nose circle along the "
                    "profile, for the tool's orientation), control (the program runs the profile with G42 and the "
                    "control offsets the nose by its tool table's radius and orientation) or none (the profile is the "
                    "imaginary tip's path)"},
    {.key = "lift", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "0.5",
     .description = "how far the tool feeds off the profile's end, away from the finished surface along its tip "
                    "orientation (orientation 2: +Z and +X at 45 degrees, steeper after a falling slope), before it "
                    "rapids, mm"},
    {.key = "output", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<cycle_outputs>,
     .description = "after a turn-rough of the same profile right before it written as Fanuc's G71: auto finishes "
                    "with G70 P Q on that cycle's shape where it cuts this pass (else longhand with a note), canned "
                    "G70 or an error, longhand its own moves; on other machines and without such a turn-rough its "
                    "own moves (canned: an error)"},
};

constexpr KeySpec turn_element_keys[] = {
    {.key = "line", .type = JsonType::point, .quantity = Quantity::length, .description = "a straight cut to [x, z]"},
    {.key = "arc", .type = JsonType::object, .ref = "turnProfileArc", .description = "an arc about an absolute centre"},
};

constexpr KeySpec turn_arc_keys[] = {
    {.key = "end", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "end point [x, z]"},
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "absolute centre [x, z], as far from the end as from the start"},
    {.key = "direction", .type = JsonType::string, .required = true, .choices = &choices_of<arc_directions>,
     .description = "cw (G2) or ccw (G3), seen from +Y as G18 arcs are (Z to the right, X up)"},
};

// A point [x, z] of the job as the profile's (u, v) = (z, radius); a negative X is refused.
Vec2 profile_point(const JobInput& in, const Json& value, const std::string& path, XValues given) {
    const Vec2 p = in.point(value, path);
    if (p.x < 0)
        json::fail(in.source(), path + "/0",
                   fmt::format("X {} is negative: a {} is measured from the spindle axis and is never below 0",
                               in.show(p.x), name_of(x_values, given)));
    return {p.y, given == XValues::diameter ? p.x / 2.0 : p.x};
}

// A radius as the job gives X (a diameter or a radius), for messages.
double x_as_given(double radius, XValues given) { return given == XValues::diameter ? 2.0 * radius : radius; }

// The box a segment from `from` covers in (u, v) = (Z, radius): an arc's, with the points of
// its sweep that lie beyond its ends.
struct Extent {
    double u_min, u_max, v_min, v_max;
};
Extent extent_of(Vec2 from, const ProfileSegment& s) {
    Extent e{std::min(from.x, s.end.x), std::max(from.x, s.end.x), std::min(from.y, s.end.y), std::max(from.y, s.end.y)};
    if (!s.centre) return e;
    const Vec2 c = *s.centre;
    const ArcGeometry g =
        resolve_arc({from.x, from.y, 0.0}, ArcSpec{{s.end.x, s.end.y, 0.0}, {c.x, c.y, 0.0}, s.direction, Plane::xy, 0});
    // Whether the sweep passes the direction `angle` (radians in (u, v)) from the centre.
    auto passes = [&](double angle) {
        double d = s.direction == ArcDirection::ccw ? angle - g.start_angle : g.start_angle - angle;
        d = std::fmod(d, 2 * std::numbers::pi);
        if (d < 0) d += 2 * std::numbers::pi;
        return d <= g.sweep;
    };
    if (passes(0.0)) e.u_max = c.x + g.radius;
    if (passes(std::numbers::pi)) e.u_min = c.x - g.radius;
    if (passes(std::numbers::pi / 2)) e.v_max = c.y + g.radius;
    if (passes(-std::numbers::pi / 2)) e.v_min = c.y - g.radius;
    return e;
}

// The first element of a profile that is not simple: the one that crosses or touches the
// elements before it (found by halving: a chain that crosses itself goes on crossing).
std::size_t first_crossing(const Profile& profile) {
    std::size_t simple = 1, crossing = profile.segments.size();
    while (crossing - simple > 1) {
        const std::size_t mid = simple + (crossing - simple) / 2;
        Profile prefix{profile.plane, profile.start, {profile.segments.begin(), profile.segments.begin() + static_cast<std::ptrdiff_t>(mid)}};
        (is_simple(prefix) ? simple : crossing) = mid;
    }
    return crossing - 1;
}

}  // namespace

OutsideTurningHead read_outside_turning_head(Fields& f, const JobInput& in, std::string_view what) {
    OutsideTurningHead head;
    const Tool& tool = in.tool(f);
    head.tool = &tool;
    if (tool.type != ToolType::turning_tool || tool.orientation != 2)
        f.fail("tool", fmt::format("a {} needs a turning-tool of orientation 2 (the outside tool, its tip to -Z and -X of its "
                                   "nose); tool {} is a {} of orientation {}",
                                   what, tool.number, name_of(tool_types, tool.type), tool.orientation));
    head.given_x = f.choice("xValues", x_values, XValues::diameter);
    head.feed_mode = f.choice("feedMode", feed_modes, FeedMode::per_minute);
    head.feed = in.length(f, "feed");
    if (!(head.feed > 0)) f.fail("feed", "feed must be > 0");
    if (head.feed_mode == FeedMode::per_revolution) head.feed *= tool.rpm;
    return head;
}

Profile read_turned_profile(json::Fields& f, const JobInput& in, XValues xv) {
    Profile profile;
    profile.plane = ProfilePlane::xz;
    profile.start = profile_point(in, f.required("start"), f.path_of("start"), xv);
    const double clearance = in.header().clearance;
    if (profile.start.x >= clearance)
        json::fail(in.source(), f.path_of("start") + "/1",
                   fmt::format("the start is at Z {}, at or above the clearance (Z {}): the tool feeds down to it along "
                               "Z from the clearance",
                               in.show(profile.start.x), in.show(clearance)));
    const Json& list = in.array(f, "path");
    if (list.empty()) f.fail("path", "a profile needs at least one element");
    in.claim_path_elements(static_cast<double>(list.size()), f, "path");
    Vec2 at = profile.start;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string path = f.path_of("path") + "/" + std::to_string(i);
        Fields e(list[i], path, in.source());
        JobInput::known_keys(e, turn_element_keys);
        ProfileSegment s;
        if (e.has("line") == e.has("arc")) e.fail("", "a profile element is exactly one of line, arc");
        if (e.has("line")) {
            s.end = profile_point(in, e.required("line"), e.path_of("line"), xv);
        } else {
            Fields a(e.required("arc"), e.path_of("arc"), in.source());
            JobInput::known_keys(a, turn_arc_keys);
            s.end = profile_point(in, a.required("end"), a.path_of("end"), xv);
            s.centre = profile_point(in, a.required("centre"), a.path_of("centre"), xv);
            s.direction = a.choice("direction", arc_directions);
            const double r0 = std::hypot(at.x - s.centre->x, at.y - s.centre->y);
            const double r1 = std::hypot(s.end.x - s.centre->x, s.end.y - s.centre->y);
            if (std::abs(r0 - r1) > arc_radius_tolerance)
                a.fail("centre", fmt::format("the centre is {} from the arc's start but {} from its end: it is not the "
                                             "centre of an arc through both (radii, mm)",
                                             in.show(r0), in.show(r1)));
            if (r0 < arc_radius_tolerance) a.fail("centre", "the centre is on the arc's start: an arc needs a radius");
        }
        const Extent box = extent_of(at, s);
        const std::string key = e.has("line") ? "line" : "arc";
        if (box.v_min < -axis_tolerance)
            e.fail(key, fmt::format("the arc sweeps through the spindle axis: it reaches X {} ({}) at Z {}, and X is never "
                                    "below 0 (its ends and centre are above the axis, the arc between them is not)",
                                    in.show(x_as_given(box.v_min, xv)), name_of(x_values, xv), in.show(s.centre->x)));
        if (box.u_max >= clearance)
            e.fail(key, fmt::format("the {} reaches Z {}, at or above the clearance (Z {}): the tool comes to the profile "
                                    "at the clearance, which must be above all of it",
                                    key, in.show(box.u_max), in.show(clearance)));
        profile.segments.push_back(s);
        at = s.end;
    }
    // An arc's end within arc_radius_tolerance of its circle: the exact arc through both ends,
    // once, for every stage (make_arcs_exact, profile.hpp).
    make_arcs_exact(profile, arc_radius_tolerance);
    if (auto short_one = first_short_segment(profile))
        json::fail(in.source(), f.path_of("path") + "/" + std::to_string(*short_one),
                   "this element ends where it starts: it has no length");
    if (!is_simple(profile))
        json::fail(in.source(), f.path_of("path") + "/" + std::to_string(first_crossing(profile)),
                   "this element crosses or touches the profile before it: the tool tip would cut into the surface it "
                   "has just finished");
    return profile;
}

bool turned_material_right(const Profile& profile) {
    // The shoelace sum of the profile closed through the axis (from its end down to the axis,
    // along it, up to its start): clockwise in (Z, radius) puts its inside on the right of travel.
    std::vector<Vec2> ring = sample_profile(profile, 0.01);
    ring.push_back({profile.segments.back().end.x, 0.0});
    ring.push_back({profile.start.x, 0.0});
    double twice_area = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
        twice_area += a.x * b.y - b.x * a.y;
    }
    return twice_area < 0;
}

Vec2 turned_lift_direction(int orientation, const Profile& profile, bool material_right) {
    // From the imaginary tip towards the nose centre (LinuxCNC's codes, interp_queue.cc), in
    // (Z, radius): the way the tool's body lies, away from what the tip has just cut.
    Vec2 d{1.0, 1.0};
    switch (orientation) {
    case 1: d = {-1.0, 1.0}; break;
    case 3: d = {1.0, -1.0}; break;
    case 4: d = {-1.0, -1.0}; break;
    case 5: d = {-1.0, 0.0}; break;
    case 6: d = {0.0, 1.0}; break;
    case 7: d = {1.0, 0.0}; break;
    case 8: d = {0.0, -1.0}; break;
    default: break;
    }
    // A profile that runs towards +Z (its material on the right of travel) is the mirror image
    // in Z of one that runs towards -Z: a nose centre's lift (0, 9) mirrors with it, and
    // orientation 1 (the left-hand tool) takes orientation 2's rule mirrored.
    const double mirror = material_right ? -1.0 : 1.0;
    if (material_right && (orientation == 0 || orientation == 9)) d.x = -d.x;
    d = d * (1.0 / norm(d));
    if (material_right ? orientation != 1 && orientation != 0 && orientation != 9
                       : orientation != 2 && orientation != 0 && orientation != 9)
        return d;
    // After a falling slope (the surface behind the tip rises towards +Z steeper than 45
    // degrees), halfway between it and straight up.
    const std::size_t k = profile.segments.size() - 1;
    const ProfileSegment& s = profile.segments[k];
    Vec2 back = segment_start(profile, k) - s.end;  // the surface behind the end, towards its start
    if (s.centre) {
        const Vec2 r = s.end - *s.centre;
        back = s.direction == ArcDirection::ccw ? Vec2{r.y, -r.x} : Vec2{-r.y, r.x};
    }
    back.x *= mirror;
    if (!(back.x > 0 && back.y > 0)) return d;
    const double phi = std::atan2(back.y, back.x);
    if (phi <= pi / 4) return d;
    Vec2 u = unit_at((phi + pi / 2) / 2);
    u.x *= mirror;
    return u;
}

std::optional<UnfollowableSegment> first_unfollowable(const Profile& profile, const Tool& tool) {
    if (!tool.insert_angle || !tool.approach_angle) return std::nullopt;
    // The directions of travel (degrees from +Z towards +X) the insert can follow: rising up to
    // the main edge's angle (180 - approachAngle .. 180) and falling down to the end edge's
    // clearance (-180 .. -180 + 180 - approachAngle - insertAngle), one interval through 180.
    const double lo = 180.0 - *tool.approach_angle;
    const double width = *tool.approach_angle + (180.0 - *tool.approach_angle - *tool.insert_angle);
    const double end_clearance = 180.0 - *tool.approach_angle - *tool.insert_angle;
    constexpr double slack = 1e-6;  // degrees
    auto offset_of = [&](double angle_deg) {
        double d = std::fmod(angle_deg - lo, 360.0);
        if (d < 0) d += 360.0;
        if (d > 360.0 - slack) d -= 360.0;
        return d;
    };
    for (std::size_t k = 0; k < profile.segments.size(); ++k) {
        const ProfileSegment& s = profile.segments[k];
        const Vec2 a = segment_start(profile, k);
        double from = 0.0, sweep = 0.0;
        if (!s.centre) {
            from = std::atan2(s.end.y - a.y, s.end.x - a.x) * deg_per_rad;
        } else {
            const Vec2 r = a - *s.centre;
            const double sign = s.direction == ArcDirection::ccw ? 1.0 : -1.0;
            from = std::atan2(sign * r.x, -sign * r.y) * deg_per_rad;
            sweep = sign * segment_sweep(profile, k) * deg_per_rad;
        }
        const double d0 = offset_of(from), d1 = d0 + sweep;
        if (d0 >= -slack && d0 <= width + slack && d1 >= -slack && d1 <= width + slack) continue;
        const double worst = d0 < -slack || d0 > width + slack ? from : from + sweep;
        const double dir = std::fmod(worst + 540.0, 360.0) - 180.0;
        UnfollowableSegment out{k, ""};
        if (dir < 0)
            out.why = fmt::format("this element falls towards the chuck at {:.1f} degrees, and tool {}'s insert ({:.0f} degrees "
                                  "in a {:.0f} degree holder) clears only {:.1f}: its end edge would rub the finished surface",
                                  dir + 180.0, tool.number, *tool.insert_angle,
                                  *tool.approach_angle, end_clearance);
        else
            out.why = fmt::format("this element rises at {:.1f} degrees from the direction of feed, and tool {}'s main edge "
                                  "stands at {:.0f} degrees (approachAngle): it would rub the wall it leaves",
                                  180.0 - dir, tool.number, *tool.approach_angle);
        return out;
    }
    return std::nullopt;
}


namespace {
// The direction (degrees from +Z towards +X, in [0, 360)) of a vector in (Z, radius).
double degrees_of(Vec2 v) {
    double a = std::atan2(v.y, v.x) * deg_per_rad;
    if (a < 0) a += 360.0;
    return a;
}
// Where a nose of `orientation` touches the material, as a direction from its centre: a
// material direction `c` (degrees) within `half` degrees of the tip's.
bool nose_reaches(int orientation, double c, double half) {
    const Vec2 t = lathe_tip_offset(orientation, 1.0);
    double d = std::fmod(c - degrees_of(t) + 540.0, 360.0) - 180.0;
    return std::abs(d) <= half + 1e-6;
}
// A direction in words, for messages.
std::string direction_words(double deg) {
    static constexpr const char* names[] = {"+Z", "+Z and +X", "+X", "-Z and +X", "-Z", "-Z and -X", "-X", "+Z and -X"};
    const int k = static_cast<int>(std::lround(deg / 45.0)) % 8;
    return names[k];
}
}  // namespace

std::optional<UnfollowableSegment> first_unreachable(const Profile& profile, int orientation, int tool_number,
                                                    bool material_right) {
    if (orientation < 1 || orientation > 8) return std::nullopt;
    constexpr double half = 90.0;
    const Vec2 t = lathe_tip_offset(orientation, 1.0);
    const double lo = degrees_of(t) - half, hi = degrees_of(t) + half;
    auto refuse = [&](std::size_t k, double c) {
        return UnfollowableSegment{
            k, fmt::format("the nose touches this element's surface from {} (its material lies {:.1f} degrees from +Z "
                           "towards +X of the nose centre), and tool {} of orientation {} (its tip towards {}) cuts only "
                           "between {:.0f} and {:.0f} degrees: the insert cannot reach it; use a tool of another "
                           "orientation",
                           direction_words(std::fmod(c + 180.0, 360.0)), c, tool_number, orientation,
                           direction_words(degrees_of(t)), std::fmod(lo + 360.0, 360.0), std::fmod(hi + 360.0, 360.0))};
    };
    // The material directions are the left normals of travel (the right ones where the material
    // lies on the right), turning with an arc's sweep and about a convex corner; each sweep is checked at its ends and every 1 degree between
    // (reach is an interval of less than 180 degrees, so the ends decide: the steps are a
    // guard against a sweep that wraps past it).
    auto check = [&](std::size_t k, double from, double sweep) -> std::optional<UnfollowableSegment> {
        const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep))));
        for (int i = 0; i <= n; ++i) {
            const double c = std::fmod(from + sweep * i / n + 720.0, 360.0);
            if (!nose_reaches(orientation, c, half)) return refuse(k, c);
        }
        return std::nullopt;
    };
    std::optional<double> before;  // the material direction at the end of the element before
    for (std::size_t k = 0; k < profile.segments.size(); ++k) {
        const ProfileSegment& s = profile.segments[k];
        const Vec2 a = segment_start(profile, k);
        double from = 0.0, sweep = 0.0;
        if (!s.centre) {
            if (distance(a, s.end) <= profile_same_point) continue;
            from = degrees_of(left_of(s.end - a) * (material_right ? -1.0 : 1.0));
        } else {
            const double sign = s.direction == ArcDirection::ccw ? 1.0 : -1.0;
            const Vec2 r = a - *s.centre;
            // The left normal of travel: towards the centre of a ccw arc, away from a cw one's.
            from = degrees_of(r * (material_right ? sign : -sign));
            sweep = sign * segment_sweep(profile, k) * deg_per_rad;
        }
        if (before) {
            // A convex corner (a turn towards the material: left, or right where the material lies
            // on the right): the nose rolls about it from one normal to the next.
            const double turn = std::fmod(from - *before + 540.0, 360.0) - 180.0;
            if (material_right ? turn < -1e-9 : turn > 1e-9)
                if (auto bad = check(k, *before, turn)) return bad;
        }
        if (auto bad = check(k, from, sweep)) return bad;
        before = std::fmod(from + sweep + 720.0, 360.0);
    }
    return std::nullopt;
}

NosePath nose_path(const Profile& profile, double r, int orientation, bool material_right) {
    NosePath out;
    const OffsetResult off = offset_profile(profile, r, material_right ? OffsetSide::left : OffsetSide::right);
    for (const OffsetNote& n : off.notes) {
        std::string why;
        switch (n.kind) {
        case OffsetNoteKind::arc_too_tight: why = "a concave arc tighter than the nose radius {}: the nose cannot follow it"; break;
        case OffsetNoteKind::element_removed: why = "the nose (radius {}) cannot reach this element: its neighbours are closer together than the nose is wide"; break;
        case OffsetNoteKind::split: why = "the nose (radius {}) cannot pass a neck of the profile narrower than itself"; break;
        case OffsetNoteKind::consumed: why = "the profile is smaller than the nose (radius {})"; break;
        }
        out.refusal = UnfollowableSegment{n.segment.value_or(0), fmt::format(fmt::runtime(why), fmt::format("{:.3f} mm", r))};
        return out;
    }
    out.centre = off.profile;
    // The nose must start and end square to the profile's ends: an offset trimmed there means
    // the nose cannot reach the profile's first or last element whole.
    const ProfilePoint first = point_at(profile, 0.0), last = point_at(profile, profile_length(profile));
    const double air = material_right ? -1.0 : 1.0;  // the air side: the right of travel, or the left
    const Vec2 want_start = first.point - left_of(first.tangent) * (r * air),
               want_end = last.point - left_of(last.tangent) * (r * air);
    if (distance(out.centre.start, want_start) > 1e-6) {
        out.refusal = UnfollowableSegment{0, fmt::format("the nose (radius {:.3f} mm) cannot start on this element: the "
                                                         "elements after it come closer to its start than the nose is wide",
                                                         r)};
        return out;
    }
    if (distance(out.centre.segments.back().end, want_end) > 1e-6) {
        out.refusal = UnfollowableSegment{profile.segments.size() - 1,
                                          fmt::format("the nose (radius {:.3f} mm) cannot end on this element: the elements "
                                                      "before it come closer to its end than the nose is wide",
                                                      r)};
        return out;
    }
    const Vec2 tip = lathe_tip_offset(orientation, r);
    out.tip = out.centre;
    out.tip.start = out.tip.start + tip;
    for (ProfileSegment& s : out.tip.segments) {
        s.end = s.end + tip;
        if (s.centre) s.centre = *s.centre + tip;
    }
    // Sharp concave corners (a right turn between two elements' tangents).
    for (std::size_t k = 1; k < profile.segments.size(); ++k) {
        auto tangent_at = [&](std::size_t i, bool at_end) {
            const ProfileSegment& s = profile.segments[i];
            const Vec2 a = segment_start(profile, i);
            if (!s.centre) return (s.end - a) * (1.0 / norm(s.end - a));
            const Vec2 p = at_end ? s.end : a;
            const Vec2 rr = (p - *s.centre) * (1.0 / norm(p - *s.centre));
            return s.direction == ArcDirection::ccw ? left_of(rr) : Vec2{rr.y, -rr.x};
        };
        if (distance(segment_start(profile, k - 1), profile.segments[k - 1].end) <= profile_same_point ||
            distance(segment_start(profile, k), profile.segments[k].end) <= profile_same_point)
            continue;
        const Vec2 din = tangent_at(k - 1, true), dout = tangent_at(k, false);
        if (cross(din, dout) * air < -1e-9) out.concave_corners.push_back(k);
    }
    return out;
}

std::vector<ObjectSpec> TurnProfileOp::objects() {
    return {
        {.name = "turn-profile",
         .description = "a lathe finishing pass of the tool tip along a profile of lines and arcs in XZ",
         .keys = {std::begin(turn_profile_keys), std::end(turn_profile_keys)}},
        {.name = "turnProfileElement", .description = "one element of a lathe profile: exactly one of line, arc",
         .keys = {std::begin(turn_element_keys), std::end(turn_element_keys)},
         .groups = {{.keys = {"line", "arc"}, .min = 1, .max = 1, .description = "exactly one of line, arc"}}},
        {.name = "turnProfileArc", .description = "an arc in XZ about an absolute centre",
         .keys = {std::begin(turn_arc_keys), std::end(turn_arc_keys)}},
    };
}

namespace {

// The program of control compensation, checked as the control runs it (CutterCompensation in
// (Z, radius), LinuxCNC's rules): the entry along Z under G42, the designed profile up to a nose
// radius before its end, G40 on the lift. A move the control refuses is refused at its element
// ("path/N"; the entry at "approachDistance"); the lift goes from where the control leaves the
// tip, along the lift direction.
void plan_control_compensation(TurnProfileOp& op, Fields& f, const JobInput& in) {
    const double r = op.nose_radius;
    const double length = profile_length(op.profile);
    if (!(length > r + profile_same_point))
        f.fail("path", fmt::format("the profile ({} long) is not longer than the nose radius {}: under control compensation "
                                   "the nose stops a radius before the profile's end, so nothing would be cut",
                                   in.show(length), in.show(r)));
    op.control_path = sub_profile(op.profile, 0.0, length - r);
    CutterCompensation comp([](const CompMove&) {});
    auto at = [](Vec2 p) { return Vec3{p.x, p.y, 0.0}; };
    auto check = [&](std::optional<CompError> e) {
        if (!e) return;
        if (e->source == 0)
            f.fail("approachDistance", "the entry move under G42 to the profile's start: the control refuses it: " + e->message);
        json::fail(in.source(), f.path_of("path") + "/" + std::to_string(e->source - 1),
                   "under control compensation the control refuses this element: " + e->message);
    };
    const Vec2 start = op.profile.start;
    comp.set_position(at({start.x + op.approach, start.y}));
    check(comp.on(op.material_right ? CompSide::left : CompSide::right, r, 0));
    check(comp.move(CompMove{CompMove::Kind::feed, at(start), {}, ArcDirection::ccw, 0, 0}));
    for (std::size_t k = 0; k < op.control_path.segments.size(); ++k) {
        const ProfileSegment& s = op.control_path.segments[k];
        CompMove m{s.centre ? CompMove::Kind::arc : CompMove::Kind::feed, at(s.end), s.centre.value_or(Vec2{}), s.direction,
                   0, std::min(k, op.profile.segments.size() - 1) + 1};
        check(comp.move(m));
    }
    check(comp.off(op.control_path.segments.size()));
    const Vec3 centre = comp.position().value_or(Vec3{});
    op.control_exit = Vec2{centre.x, centre.y} + lathe_tip_offset(op.orientation, r) + op.lift_direction * op.lift;
}

}  // namespace

TurnProfileOp TurnProfileOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, turn_profile_keys);
    const Tool& tool = in.tool(f);
    TurnProfileOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    const XValues xv = f.choice("xValues", x_values, XValues::diameter);
    op.given_x = xv;
    op.feed_mode = f.choice("feedMode", feed_modes, FeedMode::per_minute);
    op.feed = in.length(f, "feed");
    if (!(op.feed > 0)) f.fail("feed", "feed must be > 0");
    if (op.feed_mode == FeedMode::per_revolution) op.feed *= tool.rpm;
    op.profile = read_turned_profile(f, in, xv);
    const double retract = in.length(f, "retractX");
    if (retract < 0) f.fail("retractX", "retractX is negative: X is measured from the spindle axis");
    op.retract_x = xv == XValues::diameter ? retract / 2.0 : retract;
    op.approach = in.optional_length(f, "approachDistance").value_or(1.0);
    if (!(op.approach > 0)) f.fail("approachDistance", "approachDistance must be > 0");
    op.lift = in.optional_length(f, "lift").value_or(0.5);
    if (!(op.lift > 0)) f.fail("lift", "lift must be > 0");
    op.material_right = turned_material_right(op.profile);
    op.lift_direction = turned_lift_direction(tool.orientation, op.profile, op.material_right);
    if (auto bad = first_unfollowable(op.profile, tool))
        json::fail(in.source(), f.path_of("path") + "/" + std::to_string(bad->index), bad->why);
    op.nose_radius = tool.nose_radius;
    op.rpm = tool.rpm;
    op.output = f.choice("output", cycle_outputs, CycleOutput::automatic);
    op.compensation = f.choice("compensation", nose_compensation_modes, NoseCompensation::computer);
    op.tip_path = op.profile;
    op.orientation = tool.orientation;
    if (op.compensation == NoseCompensation::control) {
        if (!(op.nose_radius > 0))
            f.fail("compensation", fmt::format("control compensation needs the tool's nose radius: tool {} gives no noseRadius",
                                               tool.number));
        if (tool.orientation < 1 || tool.orientation > 8)
            f.fail("compensation", fmt::format("control compensation needs the tool's tip orientation 1 to 8 (the control "
                                               "moves that imaginary tip); tool {} has orientation {}{}",
                                               tool.number, tool.orientation,
                                               tool.orientation == 9 || tool.orientation == 0
                                                   ? " (the nose centre: use compensation computer or none)"
                                                   : ""));
        if (!(op.approach > op.nose_radius))
            f.fail("approachDistance",
                   fmt::format("the entry move under G42 (the feed along Z to the start, approachDistance {}) must be longer "
                               "than the nose radius {}: the control refuses a shorter one",
                               in.show(op.approach), in.show(op.nose_radius)));
    }
    if (op.compensation != NoseCompensation::none && op.nose_radius > 0) {
        // An insert with angles is checked by first_unfollowable (orientation 2); any other
        // nose by the directions its orientation reaches.
        if (!(tool.insert_angle && tool.orientation == 2))
            if (auto bad = first_unreachable(op.profile, tool.orientation, tool.number, op.material_right))
                json::fail(in.source(), f.path_of("path") + "/" + std::to_string(bad->index), bad->why);
        const NosePath nose = nose_path(op.profile, op.nose_radius, tool.orientation, op.material_right);
        if (nose.refusal)
            json::fail(in.source(), f.path_of("path") + "/" + std::to_string(nose.refusal->index), nose.refusal->why);
        // The nose stops a radius short of the profile's end along it: its leading point at the
        // end, never beyond it into what lies past the profile (the bar a later cut parts or a
        // shoulder the profile does not give).
        const double length = profile_length(nose.tip);
        op.tip_path = length > op.nose_radius + profile_same_point ? sub_profile(nose.tip, 0.0, length - op.nose_radius) : nose.tip;
        op.nose_low = -lathe_tip_offset(tool.orientation, op.nose_radius).y - op.nose_radius;
        for (std::size_t k : nose.concave_corners)
            op.notes.push_back(fmt::format("{}/{}: the sharp concave corner before this element keeps the nose's radius "
                                           "({}): give the profile a fillet of at least that radius to cut it as drawn",
                                           f.path_of("path"), k, in.show(op.nose_radius)));
        if (op.tip_path.start.x >= in.header().clearance)
            f.fail("start", fmt::format("the compensated start (the tip of the nose on the profile's start) is at Z {}, at or "
                                        "above the clearance (Z {})",
                                        in.show(op.tip_path.start.x), in.show(in.header().clearance)));
    }
    if (op.compensation == NoseCompensation::control) plan_control_compensation(op, f, in);
    if (!tool.insert_angle && tool.type == ToolType::turning_tool)
        op.notes.push_back(fmt::format("tool {} gives no insertAngle and approachAngle: camgen does not check that its "
                                       "insert can follow the profile's slopes",
                                       tool.number));

    if (tool.flute_length)
        op.notes.push_back(fmt::format("tool {} has a fluteLength of {}: a turn-profile does not check it (camgen does not "
                                       "know the stock, so not the depth of cut)",
                                       tool.number, in.show(*tool.flute_length)));
    return op;
}

namespace {
// A profile point (u = Z, v = radius) as a position.
Vec3 position_of(Vec2 p) { return {p.y, 0.0, p.x}; }
}  // namespace

namespace {
// Control compensation: the designed profile under G42, the control's table giving the nose.
void expand_control(const TurnProfileOp& op, const Context& ctx, EventSink& sink) {
    const Vec3 start = position_of(op.profile.start);
    sink.emit(Rapid{{start.x, 0.0, ctx.job.clearance}});
    if (start.z + op.approach < ctx.job.clearance) sink.emit(Rapid{{start.x, 0.0, start.z + op.approach}});
    // The outside profile's material lies left of travel in (Z, X): the nose on its right, G42;
    // a profile that runs towards +Z has it on its right: G41.
    sink.emit(Compensation{op.material_right ? CompensationSide::left : CompensationSide::right, 0, op.nose_radius,
                           op.orientation});
    sink.emit(Linear{start, op.feed, Movement::lead_in});
    for (const ProfileSegment& s : op.control_path.segments) {
        if (s.centre)
            sink.emit(Arc{position_of(s.end), position_of(*s.centre), s.direction, Plane::xz, op.feed, 0, Movement::finishing});
        else
            sink.emit(Linear{position_of(s.end), op.feed, Movement::finishing});
    }
    // G40 on the lift: from where the control leaves the tip, away from the finished surface.
    sink.emit(Compensation{CompensationSide::off, 0, 0.0, 0});
    sink.emit(Linear{position_of(op.control_exit), op.feed, Movement::lead_out});
    sink.emit(Rapid{{op.retract_x, 0.0, op.control_exit.x}});
    sink.emit(Rapid{{op.retract_x, 0.0, ctx.job.clearance}});
}
}  // namespace

namespace {
void expand_own(const TurnProfileOp& op, const Context& ctx, EventSink& sink);

// Collects a turn-profile's own moves for a FinishCycle.
class PlainMoveSink : public EventSink {
public:
    explicit PlainMoveSink(std::vector<PlainMove>& out) : out_(out) {}
    void emit(const Event& e) override {
        if (const auto* r = std::get_if<Rapid>(&e)) out_.emplace_back(*r);
        else if (const auto* l = std::get_if<Linear>(&e)) out_.emplace_back(*l);
        else if (const auto* a = std::get_if<Arc>(&e)) out_.emplace_back(*a);
        else if (const auto* c = std::get_if<Compensation>(&e)) out_.emplace_back(*c);
        else throw std::logic_error("turn-profile: a finishing pass of moves only");
    }

private:
    std::vector<PlainMove>& out_;
};
}  // namespace

void expand(const TurnProfileOp& op, const Context& ctx, EventSink& sink) {
    if (!op.g70 || op.output == CycleOutput::longhand) return expand_own(op, ctx, sink);
    FinishCycle c;
    c.path = op.path;
    c.output = op.output;
    c.rough_path = op.g70->rough_path;
    c.along_x = op.g70->along_x;
    c.start = op.g70->start;
    c.shape = op.tip_path.segments.empty() ? op.profile : op.tip_path;
    c.feed = op.feed;
    c.clearance = ctx.job.clearance;
    c.out_x = op.retract_x;
    c.refusal = op.g70->refusal;
    PlainMoveSink plain(c.plain);
    expand_own(op, ctx, plain);
    sink.emit(c);
}

namespace {
void expand_own(const TurnProfileOp& op, const Context& ctx, EventSink& sink) {
    // An op built by hand (a library user, a test) may leave tip_path empty: the profile is then the tip's path.
    if (op.compensation == NoseCompensation::control && !op.control_path.segments.empty()) return expand_control(op, ctx, sink);
    const Profile& tip_path = op.tip_path.segments.empty() ? op.profile : op.tip_path;
    const Vec3 start = position_of(tip_path.start);
    sink.emit(Rapid{{start.x, 0.0, ctx.job.clearance}});
    // Rapid to the approach distance before the start, feed the rest.
    if (start.z + op.approach < ctx.job.clearance) sink.emit(Rapid{{start.x, 0.0, start.z + op.approach}});
    sink.emit(Linear{start, op.feed, Movement::lead_in});
    // The profile is a finishing pass.
    for (const ProfileSegment& s : tip_path.segments) {
        if (s.centre)
            sink.emit(Arc{position_of(s.end), position_of(*s.centre), s.direction, Plane::xz, op.feed, 0, Movement::finishing});
        else
            sink.emit(Linear{position_of(s.end), op.feed, Movement::finishing});
    }
    // Off the finished surface first, then out and back at rapid.
    const Vec2 lifted = tip_path.segments.back().end + op.lift_direction * op.lift;
    sink.emit(Linear{position_of(lifted), op.feed, Movement::lead_out});
    sink.emit(Rapid{{op.retract_x, 0.0, lifted.x}});
    sink.emit(Rapid{{op.retract_x, 0.0, ctx.job.clearance}});
}
}  // namespace

std::string default_name(const TurnProfileOp& op) { return op.comment.empty() ? "turn profile" : op.comment; }

KeptMaterial kept_by(const TurnProfileOp& op) {
    KeptMaterial k = kept_under(op.profile);
    k.op = &op;
    return k;
}

KeptMaterial kept_under(const Profile& profile) {
    KeptMaterial k;
    k.ring = sample_profile(profile, sampling_tolerance);
    const Vec2 start = profile.start, end = profile.segments.back().end;
    k.ring.push_back({end.x, 0.0});
    k.ring.push_back({start.x, 0.0});
    k.u_min = k.u_max = start.x;
    for (const Vec2& p : k.ring) {
        k.u_min = std::min(k.u_min, p.x);
        k.u_max = std::max(k.u_max, p.x);
        k.v_max = std::max(k.v_max, p.y);
    }
    return k;
}

std::vector<ZSpan> kept_inside_at(const KeptMaterial& k, double level) {
    if (level >= k.v_max) return {};
    std::vector<double> crossings;
    for (std::size_t i = 0; i < k.ring.size(); ++i) {
        const Vec2 a = k.ring[i], b = k.ring[(i + 1) % k.ring.size()];
        if ((a.y > level) != (b.y > level)) crossings.push_back(a.x + (level - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    std::sort(crossings.begin(), crossings.end());
    std::vector<ZSpan> out;
    for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) out.push_back({crossings[i], crossings[i + 1]});
    return out;
}

double kept_largest_radius(const KeptMaterial& k, double lo, double hi) {
    double top = 0.0;
    for (std::size_t i = 0; i < k.ring.size(); ++i) {
        const Vec2 a = k.ring[i], b = k.ring[(i + 1) % k.ring.size()];
        if (a.x >= lo && a.x <= hi) top = std::max(top, a.y);
        // Where the edge crosses either end of the span.
        for (double u : {lo, hi})
            if ((a.x - u) * (b.x - u) < 0) top = std::max(top, a.y + (u - a.x) * (b.y - a.y) / (b.x - a.x));
    }
    return top;
}

std::optional<KeptMaterialHit> first_kept_hit(const std::vector<KeptMaterial>& kept, std::size_t cut, double radius,
                                              double lo, double hi, bool downwards) {
    const double level = radius + profile_same_point;
    // +1/-1 at each end of an interval, for the material and for the air.
    struct Edge {
        double u;
        int material, air;
    };
    std::vector<Edge> edges;
    for (std::size_t i = 0; i < kept.size(); ++i) {
        const KeptMaterial& k = kept[i];
        if (k.u_max <= lo || k.u_min >= hi) continue;
        const std::vector<ZSpan> inside = kept_inside_at(k, level);
        for (const ZSpan& s : inside) {
            edges.push_back({s.lo, 1, 0});
            edges.push_back({s.hi, -1, 0});
        }
        if (i >= cut) continue;
        // Air: the profile's stretch of Z where the line is not inside.
        double from = k.u_min;
        for (const ZSpan& s : inside) {
            edges.push_back({from, 0, 1});
            edges.push_back({s.lo, 0, -1});
            from = s.hi;
        }
        edges.push_back({from, 0, 1});
        edges.push_back({k.u_max, 0, -1});
    }
    std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.u < b.u; });
    std::vector<ZSpan> bad;
    int material = 0, air = 0;
    for (std::size_t i = 0; i < edges.size(); ++i) {
        material += edges[i].material;
        air += edges[i].air;
        if (i + 1 == edges.size() || edges[i + 1].u == edges[i].u) continue;
        const double a = std::max(edges[i].u, lo), b = std::min(edges[i + 1].u, hi);
        if (material <= 0 || air > 0 || b - a <= 0) continue;
        if (!bad.empty() && bad.back().hi >= a) bad.back().hi = b;
        else bad.push_back({a, b});
    }
    std::erase_if(bad, [](const ZSpan& s) { return s.hi - s.lo <= material_margin; });
    if (bad.empty()) return std::nullopt;
    const ZSpan s = downwards ? bad.back() : bad.front();
    const double mid = (s.lo + s.hi) / 2;
    for (const KeptMaterial& k : kept)
        for (const ZSpan& in : kept_inside_at(k, level))
            if (in.lo <= mid && mid <= in.hi) return KeptMaterialHit{s, &k};
    return std::nullopt;  // not reached: every stretch lies inside one of them
}

namespace {

// How deep a nose circle of radius `r` about `c` reaches into the ring's inside (< 0: clear of
// it by that much).
double nose_depth(const std::vector<Vec2>& ring, Vec2 c, double r) {
    double d = std::numeric_limits<double>::infinity();
    bool inside = false;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
        const Vec2 ab = b - a;
        const double len2 = dot(ab, ab);
        const double t = len2 > 0 ? std::clamp(dot(c - a, ab) / len2, 0.0, 1.0) : 0.0;
        d = std::min(d, distance(c, a + ab * t));
        if ((a.y > c.y) != (b.y > c.y) && c.x < a.x + (c.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
    }
    return inside ? r + d : r - d;
}

// The deepest a nose reaches into the ring while its centre moves straight from `a` to `b`
// (sampled every 0.005 mm), and where its centre is then.
struct NoseDepth {
    double depth;
    Vec2 centre;
};
NoseDepth deepest_along(const std::vector<Vec2>& ring, Vec2 a, Vec2 b, double r) {
    const int n = std::clamp(static_cast<int>(std::ceil(distance(a, b) / 0.005)), 1, 20000);
    NoseDepth worst{nose_depth(ring, a, r), a};
    for (int i = 1; i <= n; ++i) {
        const Vec2 c = a + (b - a) * (static_cast<double>(i) / n);
        const double d = nose_depth(ring, c, r);
        if (d > worst.depth) worst = {d, c};
    }
    return worst;
}

// "this profile" or "the profile of /operations/N".
std::string whose(const KeptMaterial& k, const TurnProfileOp& op) {
    return k.op == &op ? "this profile" : "the profile of " + k.op->path;
}

}  // namespace

void check_turned_material(const std::vector<const TurnProfileOp*>& ops, const JobInput& in) {
    const double clearance = in.header().clearance;
    std::vector<KeptMaterial> kept;
    kept.reserve(ops.size());
    for (const TurnProfileOp* op : ops) {
        kept.push_back(kept_by(*op));
        const XValues xv = op->given_x;
        auto x = [&](double radius) { return in.show(x_as_given(radius, xv)); };
        // The tool's path (the tip's: the nose lies nose_low and more above it), from the
        // profile's designed end's Z.
        // (Under control compensation the tip approaches the designed start itself.)
        const bool control = op->compensation == NoseCompensation::control && !op->control_path.segments.empty();
        const Vec2 start = op->tip_path.segments.empty() || control ? op->profile.start : op->tip_path.start;
        const Vec2 end = op->profile.segments.back().end;
        // The approach: before this profile cuts, the material above it is still there.
        if (auto hit = first_kept_hit(kept, kept.size() - 1, start.y + op->nose_low, start.x, clearance, true))
            json::fail(in.source(), op->path + "/start",
                             fmt::format("the approach runs along Z at X {} from the clearance (Z {}) down to the start "
                                         "(Z {}) through the material that {} keeps: X up to {} between Z {} and Z {}",
                                         x(start.y), in.show(clearance), in.show(start.x), whose(*hit->kept, *op),
                                         x(kept_largest_radius(*hit->kept, hit->span.lo, hit->span.hi)), in.show(hit->span.lo),
                                         in.show(hit->span.hi)));
        if (auto hit = first_kept_hit(kept, kept.size(), op->retract_x + op->nose_low, end.x, clearance, false))
            json::fail(in.source(), op->path + "/retractX",
                             fmt::format("retractX {} is inside the part: the return along Z from the profile's end (Z {}) "
                                         "to the clearance (Z {}) runs through the material that {} keeps, up to X {} "
                                         "between Z {} and Z {}; retractX must be beyond it",
                                         x(op->retract_x), in.show(end.x), in.show(clearance), whose(*hit->kept, *op),
                                         x(kept_largest_radius(*hit->kept, hit->span.lo, hit->span.hi)), in.show(hit->span.lo),
                                         in.show(hit->span.hi)));
        // (After the return along Z, whose message names a retractX inside the part.)
        // The way off the profile's end: the feed of the lift (from the tip path's end, or from
        // where the control leaves the tip), then the rapid out along X to retractX. The nose
        // must go no deeper into what this profile keeps than it is at the end of the cut (on
        // it, under compensation; without compensation the nose may already lie across a slope).
        {
            const double r = op->nose_radius;
            const Vec2 tip_offset = r > 0 ? lathe_tip_offset(op->orientation, r) : Vec2{0.0, 0.0};
            const Profile& tip_path = op->tip_path.segments.empty() ? op->profile : op->tip_path;
            Vec2 from = tip_path.segments.back().end - tip_offset;  // the nose centre
            Vec2 lifted = from + op->lift_direction * op->lift;
            if (control) {
                // The nose centre where the control leaves it (plan_control_compensation).
                lifted = op->control_exit - tip_offset;
                from = lifted - op->lift_direction * op->lift;
            }
            const Vec2 out{lifted.x, op->retract_x - tip_offset.y};
            const std::vector<Vec2>& ring = kept.back().ring;
            const double allowed = std::max(0.0, nose_depth(ring, from, r)) + material_margin;
            auto where = [&](Vec2 centre) {
                const Vec2 tip = centre + tip_offset;
                return fmt::format("the tip at X {} Z {}", x(tip.y), in.show(tip.x));
            };
            if (const NoseDepth lift = deepest_along(ring, from, lifted, r); lift.depth > allowed)
                json::fail(in.source(), op->path + "/lift",
                           fmt::format("the lift off the profile's end ({} towards {}: from tool {}'s imaginary tip "
                                       "towards its nose centre, orientation {}) runs the tool into the material this "
                                       "profile keeps, {} deep with {}: end the profile where the tool can leave it that "
                                       "way, or use a tool of another orientation",
                                       in.show(op->lift), direction_words(degrees_of(op->lift_direction)), op->tool,
                                       op->orientation, in.show(lift.depth - std::max(0.0, allowed - material_margin)),
                                       where(lift.centre)));
            if (const NoseDepth way = deepest_along(ring, lifted, out, r); way.depth > allowed)
                json::fail(in.source(), op->path + "/retractX",
                           fmt::format("the rapid out along X from the lifted end (Z {}) to retractX {} runs the tool "
                                       "through the material this profile keeps, {} deep with {}: the lift leaves the "
                                       "tool over the part, not beside it",
                                       in.show(lifted.x + tip_offset.x), x(op->retract_x),
                                       in.show(way.depth - std::max(0.0, allowed - material_margin)), where(way.centre)));
        }
    }
}

}  // namespace camgen
