#include "camgen/operations/turn_profile/turn_profile.hpp"

#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

// Arc ends may be this much farther from the centre than the start, mm.
constexpr double arc_radius_tolerance = 0.001;

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
     .description = "X (as xValues) the tool feeds out to from the profile's end, before it rapids back to the clearance"},
};

constexpr KeySpec element_keys[] = {
    {.key = "line", .type = JsonType::point, .quantity = Quantity::length, .description = "a straight cut to [x, z]"},
    {.key = "arc", .type = JsonType::object, .ref = "turnProfileArc", .description = "an arc about an absolute centre"},
};

constexpr KeySpec arc_keys[] = {
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
                               p.x, name_of(x_values, given)));
    return {p.y, given == XValues::diameter ? p.x / 2.0 : p.x};
}

}  // namespace

std::vector<ObjectSpec> TurnProfileOp::objects() {
    return {
        {.name = "turn-profile",
         .description = "a lathe finishing pass of the tool tip along a profile of lines and arcs in XZ",
         .keys = {std::begin(turn_profile_keys), std::end(turn_profile_keys)}},
        {.name = "turnProfileElement", .description = "one element of a lathe profile: exactly one of line, arc",
         .keys = {std::begin(element_keys), std::end(element_keys)},
         .groups = {{.keys = {"line", "arc"}, .min = 1, .max = 1, .description = "exactly one of line, arc"}}},
        {.name = "turnProfileArc", .description = "an arc in XZ about an absolute centre",
         .keys = {std::begin(arc_keys), std::end(arc_keys)}},
    };
}

TurnProfileOp TurnProfileOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, turn_profile_keys);
    const Tool& tool = in.tool(f);
    TurnProfileOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    const XValues xv = f.choice("xValues", x_values, XValues::diameter);
    op.feed_mode = f.choice("feedMode", feed_modes, FeedMode::per_minute);
    op.feed = in.length(f, "feed");
    if (!(op.feed > 0)) f.fail("feed", "feed must be > 0");
    if (op.feed_mode == FeedMode::per_revolution) op.feed *= tool.rpm;
    op.profile.plane = ProfilePlane::xz;
    op.profile.start = profile_point(in, f.required("start"), f.path_of("start"), xv);
    const double retract = in.length(f, "retractX");
    if (retract < 0) f.fail("retractX", "retractX is negative: X is measured from the spindle axis");
    op.retract_x = xv == XValues::diameter ? retract / 2.0 : retract;

    const Json& list = in.array(f, "path");
    if (list.empty()) f.fail("path", "a profile needs at least one element");
    in.claim_path_elements(static_cast<double>(list.size()), f, "path");
    Vec2 at = op.profile.start;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string path = f.path_of("path") + "/" + std::to_string(i);
        Fields e(list[i], path, in.source());
        JobInput::known_keys(e, element_keys);
        ProfileSegment s;
        if (e.has("line") == e.has("arc")) e.fail("", "a profile element is exactly one of line, arc");
        if (e.has("line")) {
            s.end = profile_point(in, e.required("line"), e.path_of("line"), xv);
        } else {
            Fields a(e.required("arc"), e.path_of("arc"), in.source());
            JobInput::known_keys(a, arc_keys);
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
        op.profile.segments.push_back(s);
        at = s.end;
    }
    if (auto short_one = first_short_segment(op.profile))
        json::fail(in.source(), f.path_of("path") + "/" + std::to_string(*short_one),
                   "this element ends where it starts: it has no length");
    return op;
}

namespace {
// A profile point (u = Z, v = radius) as a position.
Vec3 position_of(Vec2 p) { return {p.y, 0.0, p.x}; }
}  // namespace

void expand(const TurnProfileOp& op, const Context& ctx, EventSink& sink) {
    const Vec3 start = position_of(op.profile.start);
    sink.emit(Rapid{{start.x, 0.0, ctx.job.clearance}});
    sink.emit(Linear{start, op.feed, Movement::lead_in});
    // The profile is a finishing pass.
    for (const ProfileSegment& s : op.profile.segments) {
        if (s.centre)
            sink.emit(Arc{position_of(s.end), position_of(*s.centre), s.direction, Plane::xz, op.feed, 0, Movement::finishing});
        else
            sink.emit(Linear{position_of(s.end), op.feed, Movement::finishing});
    }
    const Vec3 end = position_of(op.profile.segments.back().end);
    sink.emit(Linear{{op.retract_x, 0.0, end.z}, op.feed, Movement::lead_out});
    sink.emit(Rapid{{op.retract_x, 0.0, ctx.job.clearance}});
}

std::string default_name(const TurnProfileOp& op) { return op.comment.empty() ? "turn profile" : op.comment; }

}  // namespace camgen
