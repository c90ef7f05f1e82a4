#include "camgen/operations/path/path.hpp"
#include "camgen/geometry/arc.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/dxf_source.hpp"
#include "camgen/operations/shapes.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

constexpr double min_arc_radius = 0.0005;

// The shortest partial last turn of a helix (mm along its circle): shorter, the end rounds
// onto the start (or the start's neighbour) and a control reads a full circle or nothing.
constexpr double path_helix_least_arc = 0.002;

// The keys of a path operation.
constexpr KeySpec path_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "z", .quantity = Quantity::length, .required = true,
     .description = "absolute Z where the path starts, below clearance"},
    {.key = "feed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "cutting feed; required unless the tool comes from the library with a feedPerTooth for the job's "
                    "material (default: then fz x flutes x rpm)"},
    {.key = "plungeFeed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "feed down to z (default: feed)"},
    {.key = "tolerance", .quantity = Quantity::length, .min = Bound{0.0001, true},
     .description = "how far the lines of an arc the machine cannot write may stray from it (default: the machine's "
                    "chordTolerance, which also caps it)"},
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length,
     .description = "where the path starts [x, y], at z"},
    {.key = "path", .type = JsonType::array, .ref = "pathElement", .min_items = 1,
     .description = "the path elements, each starting where the previous one ends"},
    {.key = "profile", .type = JsonType::object, .ref = "profileSource",
     .description = "or the path in XY at z: one profile of a DXF drawing (open or closed) or a shape (rectangle, circle, slot, polygon)"},
};

// The keys of a path element: exactly one of them.
constexpr KeySpec path_element_keys[] = {
    {.key = "line", .type = JsonType::point3, .quantity = Quantity::length,
     .description = "a straight move to [x, y] (at the current Z: where the element before ended) or [x, y, z]"},
    {.key = "arc", .type = JsonType::object, .ref = "pathArc", .description = "an arc about an absolute centre"},
    {.key = "helix", .type = JsonType::object, .ref = "pathHelix",
     .description = "a helix about a vertical axis to another Z: whole turns, or at an exact pitch a partial last turn"},
};

// The keys of an arc.
constexpr KeySpec path_arc_keys[] = {
    {.key = "end", .type = JsonType::point3, .quantity = Quantity::length, .required = true,
     .description = "end point [x, y] (at the current Z) or [x, y, z]"},
    {.key = "centre", .type = JsonType::point3, .quantity = Quantity::length, .required = true,
     .description = "absolute centre [x, y] (xy only) or [x, y, z]; along the plane's normal axis it is the start's"},
    {.key = "direction", .type = JsonType::string, .required = true, .choices = &choices_of<arc_directions>,
     .description = "seen looking down the plane's normal axis: cw (G2) or ccw (G3)"},
    {.key = "plane", .type = JsonType::string, .default_json = "\"xy\"", .choices = &choices_of<plane_names>,
     .description = "the arc's plane: xy (G17), xz (G18) or yz (G19)"},
};

// The keys of a helix: centre, direction and exactly two of z, turns and pitch.
constexpr KeySpec helix_keys[] = {
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "the axis [x, y]"},
    {.key = "direction", .type = JsonType::string, .required = true, .choices = &choices_of<arc_directions>,
     .description = "seen from +Z: cw or ccw"},
    {.key = "z", .quantity = Quantity::length, .description = "absolute Z at the end"},
    {.key = "turns", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{100000, true}, .description = "number of whole turns"},
    {.key = "pitch", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "Z travel per turn (down with turns; with z kept exactly: a partial last turn ends elsewhere on the "
                    "circle, unless wholeTurns)"},
    {.key = "wholeTurns", .type = JsonType::boolean, .default_json = "false",
     .description = "with z and pitch: whole turns back to the start's X and Y, the fewest that go no further than pitch "
                    "per turn (the pitch becomes a little less)"},
};

// Reads an arc from `current` (an end [x, y] is at its Z); `lowest` becomes the lowest Z it
// reaches if that is below it.
PathArc read_arc(Fields& a, const JobInput& in, const Vec3& current, double& lowest) {
    JobInput::known_keys(a, path_arc_keys);
    PathArc arc;
    arc.plane = a.choice("plane", plane_names, Plane::xy);
    const char* plane_name = arc.plane == Plane::xy ? "xy" : arc.plane == Plane::xz ? "xz" : "yz";
    const char* normal_axis = arc.plane == Plane::xy ? "z" : arc.plane == Plane::xz ? "y" : "x";
    arc.end = in.point3(a, "end", current.z);
    const Json& centre = a.required("centre");
    if (arc.plane != Plane::xy && !(centre.is_array() && centre.size() == 3))
        a.fail("centre", fmt::format("an {} arc needs its centre as [x, y, z], got {}", plane_name, JobInput::describe(centre)));
    arc.centre = in.point3(centre, a.path_of("centre"), current.z);
    // The centre's coordinate along the normal axis is the start's: a centre elsewhere on the
    // axis would be a different arc.
    const double c_normal = to_plane(arc.centre, arc.plane).w, s_normal = to_plane(current, arc.plane).w;
    if (std::abs(c_normal - s_normal) > arc_radius_tolerance)
        a.fail("centre", fmt::format("the centre's {} ({}) must be the start's {} ({}) in an {} arc", normal_axis,
                                     in.show(c_normal), normal_axis, in.show(s_normal), plane_name));
    arc.centre = from_plane({to_plane(arc.centre, arc.plane).u, to_plane(arc.centre, arc.plane).v, s_normal}, arc.plane);
    arc.direction = a.choice("direction", arc_directions);
    const PlanePoint s = to_plane(current, arc.plane), e = to_plane(arc.end, arc.plane), c = to_plane(arc.centre, arc.plane);
    const double r_start = std::hypot(s.u - c.u, s.v - c.v);
    const double r_end = std::hypot(e.u - c.u, e.v - c.v);
    if (std::abs(r_start - r_end) > arc_radius_tolerance)
        a.fail("", fmt::format("start is {:.3f} mm from the centre but end is {:.3f} mm{}", r_start, r_end,
                               arc.plane == Plane::xy ? "" : fmt::format(" (in the {} plane)", plane_name)));
    if (r_start <= min_arc_radius)
        a.fail("", fmt::format("the arc radius is {:.4f} mm; it must be more than {} mm", r_start, min_arc_radius));
    // The highest point of the arc: an arc in XZ or YZ may rise above its ends.
    const ArcGeometry g = resolve_arc(current, ArcSpec{arc.end, arc.centre, arc.direction, arc.plane, 0});
    double top = std::max(current.z, arc.end.z);
    lowest = std::min(lowest, arc.end.z);
    if (arc.plane != Plane::xy) {
        // Whether the sweep passes the direction `angle` (radians in (u, v)) from the centre.
        auto passes = [&](double angle) {
            double delta = arc.direction == ArcDirection::ccw ? angle - g.start_angle : g.start_angle - angle;
            delta = std::fmod(delta, 2 * std::numbers::pi);
            if (delta < 0) delta += 2 * std::numbers::pi;
            return delta <= g.sweep;
        };
        const double up = arc.plane == Plane::xz ? 0.0 : std::numbers::pi / 2;  // angle of +Z in (u, v)
        const double centre_z = arc.plane == Plane::xz ? c.u : c.v;
        if (passes(up)) top = std::max(top, centre_z + r_start);
        if (passes(up + std::numbers::pi)) lowest = std::min(lowest, centre_z - r_start);
    }
    if (top >= in.header().clearance)
        a.fail("", fmt::format("the arc reaches Z {}, at or above the clearance (Z {})", in.show(top), in.show(in.header().clearance)));
    return arc;
}

PathHelix read_helix(Fields& h, const JobInput& in, const Vec3& current) {
    JobInput::known_keys(h, helix_keys);
    PathHelix helix;
    helix.centre = in.point(h, "centre");
    helix.direction = h.choice("direction", arc_directions);
    const double radius = std::hypot(current.x - helix.centre.x, current.y - helix.centre.y);
    if (radius <= min_arc_radius)
        h.fail("centre", fmt::format("the helix radius is {:.4f} mm; it must be more than {} mm", radius, min_arc_radius));
    const bool has_depth = h.has("z"), has_turns = h.has("turns"), has_pitch = h.has("pitch");
    if (int(has_depth) + int(has_turns) + int(has_pitch) != 2)
        h.fail("", "a helix needs exactly two of \"z\" (end Z), \"turns\" and \"pitch\" (Z travel per turn, down)");
    std::optional<double> pitch = in.optional_length(h, "pitch");
    if (pitch && *pitch <= 0) h.fail("pitch", "pitch must be > 0 (the helix goes down by it each turn)");
    const bool whole_turns = h.boolean("wholeTurns", false);
    if (h.has("wholeTurns") && !(has_depth && has_pitch))
        h.fail("wholeTurns", "wholeTurns is for a helix given by z and pitch (with turns it makes whole turns anyway)");
    if (has_turns) {
        const int turns = h.integer("turns");
        if (turns < 1 || turns > 100000) h.fail("turns", "turns must be a whole number from 1 to 100000");
        helix.turns = turns;
    }
    if (has_depth) {
        helix.end_z = in.length(h, "z");
        if (std::abs(helix.end_z - current.z) < 1e-9)
            h.fail("z", fmt::format("the helix starts and ends at Z {}; a helix must change Z (use an arc for a circle)",
                                        in.show(current.z)));
        if (helix.end_z >= in.header().clearance)
            h.fail("z", fmt::format("z is at or above the clearance (Z {}, clearance at Z {})", in.show(helix.end_z),
                                        in.show(in.header().clearance)));
        if (pitch) {
            const double exact = std::abs(helix.end_z - current.z) / *pitch;
            if (exact > 100000) h.fail("pitch", "pitch is too small: more than 100000 turns");
            if (whole_turns) {
                helix.turns = static_cast<int>(std::ceil(exact - 1e-9));
            } else {
                // The pitch kept: whole turns, then what is left of a turn. A remainder shorter
                // than path_helix_least_arc along the circle (either way) is no arc a control can
                // tell from a full circle or from none: the turns are rounded to it instead.
                int turns = static_cast<int>(std::floor(exact));
                double partial = (exact - turns) * 2.0 * std::numbers::pi;
                if (partial * radius < path_helix_least_arc) partial = 0.0;
                if ((2.0 * std::numbers::pi - partial) * radius < path_helix_least_arc) {
                    ++turns;
                    partial = 0.0;
                }
                helix.turns = turns;
                helix.partial = partial;
            }
        }
    } else {
        helix.end_z = current.z - helix.turns * *pitch;
    }
    const double sense = helix.direction == ArcDirection::ccw ? 1.0 : -1.0;
    const Vec2 from{current.x - helix.centre.x, current.y - helix.centre.y};
    const double c = std::cos(sense * helix.partial), s = std::sin(sense * helix.partial);
    helix.end = helix.partial == 0.0 ? Vec2{current.x, current.y}
                                     : Vec2{helix.centre.x + c * from.x - s * from.y, helix.centre.y + s * from.x + c * from.y};
    return helix;
}

// The path from "profile": a shape, or the one profile (open or closed) of a drawing's
// selection, in XY at the path's z. A path is the tool centre's: it may cross itself.
void read_path_profile(Fields& f, const JobInput& in, PathOp& op) {
    Profile p;
    std::string what = "the profile";
    if (std::optional<Profile> shape = read_shape_profile(f, in, "profile")) {
        p = std::move(*shape);
    } else {
        DxfProfiles d = read_dxf_profiles(f, in, "profile", op.tolerance.value_or(0.01), op.notes);
        if (d.profiles.size() != 1) {
            std::string list;
            for (std::size_t i = 0; i < d.profiles.size() && i < 8; ++i)
                list += fmt::format("{}{} {}", i ? "; " : "", d.closed[i] ? "a closed profile from" : "an open profile from", d.describe[i]);
            if (d.profiles.size() > 8) list += fmt::format("; and {} more", d.profiles.size() - 8);
            f.fail("profile", fmt::format("a path takes one profile, but the selection holds {}: {}; select one by layer, colour, "
                                          "linetype or block (or raise gapTolerance to join pieces), or give one path operation "
                                          "for each",
                                          d.profiles.size(), list));
        }
        p = std::move(d.profiles.front());
        what = "the profile from " + d.describe.front();
    }
    if (auto k = first_short_segment(p, min_profile_segment))
        f.fail("profile", fmt::format("segment {} of {} is shorter than {} mm", *k, what, min_profile_segment));
    op.start = p.start;
    op.elements.reserve(p.segments.size());
    for (const ProfileSegment& s : p.segments) {
        const Vec3 end{s.end.x, s.end.y, op.z};
        if (s.centre) op.elements.emplace_back(PathArc{end, {s.centre->x, s.centre->y, op.z}, s.direction, Plane::xy});
        else op.elements.emplace_back(PathLine{end});
    }
}

}  // namespace

std::vector<ObjectSpec> PathOp::objects() {
    std::vector<ObjectSpec> out{
        {.name = "path", .description = "feed the tool centre along a path of lines, arcs in any plane and helices, at absolute Z",
         .keys = {std::begin(path_keys), std::end(path_keys)},
         .groups = {{.keys = {"start", "profile"}, .min = 1, .max = 1, .description = "start and path, or profile"}}},
        {.name = "pathElement", .description = "one element of a path: exactly one of line, arc or helix",
         .keys = {std::begin(path_element_keys), std::end(path_element_keys)},
         .groups = {{.keys = {"line", "arc", "helix"}, .min = 1, .max = 1,
                     .description = "exactly one of line, arc or helix"}}},
        {.name = "pathArc", .description = "an arc in a plane about an absolute centre",
         .keys = {std::begin(path_arc_keys), std::end(path_arc_keys)}},
        {.name = "pathHelix", .description = "a helix about a vertical axis: exactly two of z, turns and pitch",
         .keys = {std::begin(helix_keys), std::end(helix_keys)},
         .groups = {{.keys = {"z", "turns", "pitch"}, .min = 2, .max = 2,
                     .description = "exactly two of z, turns and pitch"}}},
    };
    for (ObjectSpec& o : profile_source_objects()) out.push_back(std::move(o));
    return out;
}

PathOp PathOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, path_keys);
    const Tool& tool = in.tool(f);
    PathOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    op.z = in.length(f, "z");
    if (op.z >= in.header().clearance)
        f.fail("z", fmt::format("z is above the clearance (cut at Z {}, clearance at Z {}); "
                                "it must be below",
                                    in.show(op.z), in.show(in.header().clearance)));
    op.feed = read_cutting_feed(f, in, tool, 0.0, op.notes);
    op.plunge_feed = in.optional_length(f, "plungeFeed");
    if (op.plunge_feed && *op.plunge_feed <= 0) f.fail("plungeFeed", "plungeFeed must be > 0");
    op.tolerance = in.optional_length(f, "tolerance");
    // Finer than any control resolves; a smaller value only multiplies the segments of broken arcs.
    if (op.tolerance && !(*op.tolerance >= 0.0001)) f.fail("tolerance", "tolerance must be at least 0.0001 mm");
    if (f.has("profile")) {
        if (f.has("start") || f.has("path")) f.fail("profile", "give start and path, or profile, not both");
        read_path_profile(f, in, op);
        return op;
    }
    if (!f.has("start") && !f.has("path")) f.fail("", "a path needs start and path, or profile");
    op.start = in.point(f, "start");

    const std::string base = f.path_of("path");
    auto above_clearance = [&](double z, const char* what) {
        return fmt::format("{} is at or above the clearance (Z {}, clearance at Z {})", what, in.show(z),
                           in.show(in.header().clearance));
    };
    // The lowest Z the path reaches. camgen does not know a path's stock top: the depth the
    // flutes must reach is taken from the path's start (at z) down.
    double lowest = op.z;
    // Whether the path has gone deeper than the tool's flutes; the refusal at element `where`.
    auto too_deep = [&] { return tool.flute_length && op.z - lowest > *tool.flute_length; };
    auto refuse_depth = [&](const std::string& where) {
        json::fail(in.source(), where,
                   fmt::format("the path goes {} deep below its start (z, Z {}), but tool {} has a fluteLength of {}",
                               in.show(op.z - lowest), in.show(op.z), tool.number, in.show(*tool.flute_length)));
    };
    if (const json::PackedArray* packed = in.packed(f.required("path"))) {
        // Lines read straight into numbers ({"line": [x, y(, z)]} each, see PackedArray).
        in.claim_path_elements(static_cast<double>(packed->size()), f, "path");
        op.elements.reserve(packed->size());
        // A line [x, y] stays at the Z where it starts (the end of the line before it).
        double current_z = op.z;
        for (std::size_t k = 0; k < packed->size(); ++k) {
            auto line_path = [&] { return fmt::format("{}/{}/line", base, k); };
            Vec3 end{in.packed_coordinate(packed->x(k), [&] { return line_path() + "/0"; }),
                     in.packed_coordinate(packed->y(k), [&] { return line_path() + "/1"; }), current_z};
            if (packed->has_z(k)) end.z = in.packed_coordinate(packed->z(k), [&] { return line_path() + "/2"; });
            if (end.z >= in.header().clearance) json::fail(in.source(), line_path(), above_clearance(end.z, "the line's end"));
            op.elements.emplace_back(PathLine{end});
            current_z = end.z;
            lowest = std::min(lowest, end.z);
            if (too_deep()) refuse_depth(line_path());
        }
        return op;
    }
    const Json& elements = in.array(f, "path");
    if (elements.empty()) f.fail("path", "a path needs at least one element");
    in.claim_path_elements(static_cast<double>(elements.size()), f, "path");
    Vec3 current{op.start.x, op.start.y, op.z};
    auto below_clearance = [&](Fields& at, std::string_view key, double z, const char* what) {
        if (z >= in.header().clearance) at.fail(key, above_clearance(z, what));
    };
    for (std::size_t k = 0; k < elements.size(); ++k) {
        const std::string path = base + "/" + std::to_string(k);
        Fields e(elements[k], path, in.source());
        JobInput::known_keys(e, path_element_keys);
        const int given = int(e.has("line")) + int(e.has("arc")) + int(e.has("helix"));
        if (given != 1) e.fail("", "a path element needs exactly one of \"line\", \"arc\" or \"helix\"");
        if (e.has("line")) {
            // [x, y] keeps the current Z, as a G1 X Y block does: after an element that
            // changed Z, going back to the operation's z would feed diagonally through what
            // was just cut.
            const Vec3 end = in.point3(e, "line", current.z);
            below_clearance(e, "line", end.z, "the line's end");
            op.elements.emplace_back(PathLine{end});
            current = end;
            lowest = std::min(lowest, end.z);
        } else if (e.has("arc")) {
            Fields a(e.required("arc"), e.path_of("arc"), in.source());
            PathArc arc = read_arc(a, in, current, lowest);
            op.elements.emplace_back(arc);
            current = arc.end;
        } else {
            Fields h(e.required("helix"), e.path_of("helix"), in.source());
            PathHelix helix = read_helix(h, in, current);
            op.elements.emplace_back(helix);
            current = {helix.end.x, helix.end.y, helix.end_z};
            lowest = std::min(lowest, helix.end_z);
        }
        if (too_deep()) refuse_depth(path);
    }
    return op;
}

void expand(const PathOp& op, const Context& ctx, EventSink& sink) {
    sink.emit(Rapid{{op.start.x, op.start.y, ctx.job.clearance}});
    Vec3 at{op.start.x, op.start.y, op.z};
    sink.emit(Linear{at, op.plunge_feed.value_or(op.feed)});
    for (const PathElement& e : op.elements) {
        visit_exhaustive(overloaded{
                             [&](const PathLine& line) {
                                 sink.emit(Linear{line.end, op.feed});
                                 at = line.end;
                             },
                             [&](const PathArc& arc) {
                                 sink.emit(Arc{arc.end, arc.centre, arc.direction, arc.plane, op.feed, 0});
                                 at = arc.end;
                             },
                             [&](const PathHelix& helix) {
                                 // Whole turns: the end is above or below the start; the first turn
                                 // is the arc's own sweep, the others are extra turns. With a partial
                                 // last turn the arc's own sweep is that, all turns are extra.
                                 Vec3 end{helix.end.x, helix.end.y, helix.end_z};
                                 sink.emit(Arc{end, {helix.centre.x, helix.centre.y, at.z}, helix.direction, Plane::xy,
                                               op.feed, helix.partial > 0.0 ? helix.turns : helix.turns - 1});
                                 at = end;
                             },
                         },
                         e);
    }
    sink.emit(Rapid{{at.x, at.y, ctx.job.clearance}});
}

std::string default_name(const PathOp& c) { return c.comment.empty() ? "path" : c.comment; }

}  // namespace camgen
