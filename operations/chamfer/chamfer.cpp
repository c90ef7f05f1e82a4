#include "camgen/operations/chamfer/chamfer.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/job/tool_geometry.hpp"
#include "camgen/operations/part_guard.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

constexpr int chamfer_max_passes = 100;
// The least radius of the tool centre's circle in a hole, mm: its half-circle leads need room.
constexpr double chamfer_least_circle = 0.1;
// How closely the chamfer's angle must match the half tip angle, degrees.
constexpr double chamfer_angle_match = 1e-6;

constexpr KeySpec chamfer_head_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a chamfer-mill, v-bit or engraver whose half tip angle is the chamfer's angle"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
};

constexpr KeySpec chamfer_own_keys[] = {
    {.key = "width", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "the chamfer's leg on the top face, from the edge into the part"},
    {.key = "angle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{90, false}, .default_json = "45",
     .description = "the chamfer's angle from the vertical wall, degrees: the tool's half tip angle must be this"},
    {.key = "tipClearance", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0.2",
     .description = "how far the tool's tip goes below the chamfer's lower edge, so that its cone (not its point) "
                    "forms the chamfer"},
    {.key = "passes", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{100, true}, .default_json = "1", .description = "depth passes down to the tip's depth, equal steps"},
    {.key = "side", .type = JsonType::string, .default_json = "\"outside\"", .choices = &choices_of<contour_sides>,
     .description = "a profile's air side, where the tool runs: left, right, inside or outside (the last two: closed "
                    "profiles; on is refused)"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"climb\"", .choices = &choices_of<cut_directions>,
     .description = "climb or conventional"},
    {.key = "diameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "or the edges of holes: each hole's diameter (with the hole sources)"},
    {.key = "leadIn", .type = JsonType::object, .ref = "contourLead", .description = "a profile's lead-in (default: none)"},
    {.key = "leadOut", .type = JsonType::object, .ref = "contourLead", .description = "a profile's lead-out (default: none)"},
    {.key = "ramp", .type = JsonType::object, .ref = "contourRamp",
     .description = "how the tool goes down onto a profile (default: plunge)"},
};

std::vector<KeySpec> all_chamfer_keys() {
    std::vector<KeySpec> keys(std::begin(chamfer_head_keys), std::end(chamfer_head_keys));
    for (const KeySpec& k : height_keys(true))
        if (k.key != "endDepth" && k.key != "endDepthIsAbsolute") keys.push_back(k);
    keys.insert(keys.end(), std::begin(chamfer_own_keys), std::end(chamfer_own_keys));
    const std::vector<KeySpec> profile = profile_keys("chamfer");
    keys.insert(keys.end(), profile.begin(), profile.end());
    for (const KeySpec& k : cut_feed_keys())
        if (k.key != "finishingFeed") keys.push_back(k);
    const std::vector<KeySpec> tol = tolerance_keys();
    keys.insert(keys.end(), tol.begin(), tol.end());
    const std::vector<KeySpec> holes = hole_keys();
    keys.insert(keys.end(), holes.begin(), holes.end());
    return keys;
}

// The cutter's settings for a profile or a hole's circle.
CutSettings chamfer_settings(const ChamferOp& op, const JobHeader& job) {
    CutSettings s;
    s.tool = op.tool;
    s.tool_radius = op.geometry.offset;
    s.tool_left = op.tool_left;
    s.compensation = CompensationMode::computer;
    s.lead_in = op.lead_in;
    s.lead_out = op.lead_out;
    s.ramp = op.ramp;
    s.drawn = &op.profile;
    s.feeds = op.feeds;
    s.z = resolve_planes(op.heights);
    s.clearance = job.clearance;
    return s;
}

std::vector<double> chamfer_depths(const ChamferOp& op) {
    const Planes z = resolve_planes(op.heights);
    const std::optional<double> step =
        op.passes > 1 ? std::optional<double>((z.reference_z - z.bottom_z) / op.passes) : std::nullopt;
    std::vector<double> d = pass_depths(z.reference_z, z.bottom_z, step, true);
    d.back() = z.bottom_z;  // exactly
    return d;
}

// The tool centre's circle in a hole at `centre`: two half circles, counter-clockwise when the
// tool is left of its travel (the edge outside it, on its right).
Profile chamfer_hole_circle(const ChamferOp& op, Vec2 centre) {
    const double r = op.diameter / 2.0 - op.geometry.offset;
    const ArcDirection dir = op.tool_left ? ArcDirection::ccw : ArcDirection::cw;
    Profile p;
    p.start = centre + Vec2{r, 0.0};
    p.segments.push_back({centre + Vec2{-r, 0.0}, centre, dir});
    p.segments.push_back({centre + Vec2{r, 0.0}, centre, dir});
    return p;
}

// The cuts of the whole operation into `sink` (the holes: those given, or `only` when set).
void cut_chamfer(const ChamferOp& op, const JobHeader& job, EventSink& sink, const std::vector<Vec2>* only = nullptr) {
    const CutSettings settings = chamfer_settings(op, job);
    Cutter cutter(settings, sink);
    const std::vector<double> depths = chamfer_depths(op);
    if (!op.on_holes()) {
        cutter.cut_run(op.cut, is_closed(op.cut), depths, Movement::cutting, op.feeds.cutting, true);
        return;
    }
    std::vector<Vec2> reordered;
    const std::vector<Vec2>& holes = only ? *only : visit_order(op, reordered);
    for (std::size_t k = 0; k < holes.size(); ++k)
        cutter.cut_run(chamfer_hole_circle(op, holes[k]), true, depths, Movement::cutting, op.feeds.cutting,
                       k + 1 == holes.size());
}

// The part-aware check: the cut, its leads and links keep the tool's cone out of the part
// below the chamfer (the tool centre at least the offset from the edge on its air side, the tip
// no lower than its depth). A hole is checked at one hole (they are all alike).
void chamfer_guard(const ChamferOp& op, Fields& f, const JobInput& in) {
    Profile circle;
    GuardedPart part;
    if (op.on_holes()) {
        const double r = op.diameter / 2.0;
        circle.start = {r, 0.0};
        circle.segments.push_back({{-r, 0.0}, Vec2{0.0, 0.0}, ArcDirection::ccw});
        circle.segments.push_back({{r, 0.0}, Vec2{0.0, 0.0}, ArcDirection::ccw});
        part.profile = &circle;
        part.material_inside = false;
    } else {
        part.profile = &op.profile;
        if (is_closed(op.profile)) {
            const bool tool_inside = op.side == ContourSide::inside ||
                                     (op.side == ContourSide::left && orientation(op.profile) == Orientation::ccw) ||
                                     (op.side == ContourSide::right && orientation(op.profile) == Orientation::cw);
            part.material_inside = !tool_inside;
        }
    }
    part.tool_radius = op.geometry.offset;
    part.top_z = resolve_planes(op.heights).reference_z;
    PartGuard guard(part);
    guard.keep(0.0, resolve_planes(op.heights).bottom_z);
    const std::vector<Vec2> one{Vec2{0.0, 0.0}};
    cut_chamfer(op, in.header(), guard, op.on_holes() ? &one : nullptr);
    const std::optional<Violation>& v = guard.violation();
    if (!v) return;
    const GuardBlame blame = guard_blame(v->movement, v->rapid, false);
    std::string key = op.on_holes() ? "diameter" : blame.key;
    if (!f.has(key)) key = "";
    f.fail(key, fmt::format("the {} {}: {}", movement_words(v->movement, v->rapid), v->what,
                            op.on_holes() ? "the tool does not fit the hole" : blame.hint));
}

}  // namespace

ChamferGeometry chamfer_geometry(double width, double angle, double tip_diameter, double tip_clearance) {
    const double t = std::tan(angle * rad_per_deg);
    ChamferGeometry g;
    g.height = width / t;
    g.depth = g.height + tip_clearance;
    g.offset = tip_diameter / 2.0 + tip_clearance * t;
    g.reach = g.offset + width;
    return g;
}

std::vector<ObjectSpec> ChamferOp::objects() {
    std::vector<ObjectSpec> out{
        {.name = "chamfer",
         .description = "a chamfer of a width and angle with the cone of a chamfer mill or V-bit, along a profile's top "
                        "edge or around the top edges of holes; its depth and offset from the tool's geometry",
         .keys = all_chamfer_keys(),
         .groups = {{.keys = {"start", "profile", "diameter"}, .min = 1, .max = 1,
                     .description = "a profile (start and path, or profile), or holes (diameter and hole sources)"}}}};
    return out;
}

ChamferOp ChamferOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, all_chamfer_keys());
    const Tool& tool = in.tool(f);
    if (!is_pointed_cutter(tool.type))
        f.fail("tool", fmt::format("tool {} ({}) is a {}: a chamfer is cut with the cone of a tool of type \"chamfer-mill\", "
                                   "\"v-bit\" or \"engraver\" (its tipAngle and tipDiameter give the chamfer's depth and offset)",
                                   tool.number, tool.path, tool_types[static_cast<int>(tool.type)].description));
    ChamferOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.spindle = tool.direction;
    op.comment = f.optional_string("comment").value_or("");
    op.width = in.length(f, "width");
    if (!(op.width > 0)) f.fail("width", "width must be > 0");
    op.angle = f.optional_number("angle").value_or(45.0);
    if (!(op.angle > 0 && op.angle < 90)) f.fail("angle", "angle must be more than 0 and less than 90 degrees (from the wall)");
    const double half = tool.tip_angle.value_or(0.0) / 2.0;
    if (!is_cone_tool(tool) || std::abs(half - op.angle) > chamfer_angle_match)
        f.fail(f.has("angle") ? "angle" : "tool",
               fmt::format("tool {} ({}, a {}) has a tip angle of {:g} degrees: its cone cuts at {:g} degrees from the wall, "
                           "but the chamfer's angle is {:g} degrees; use a tool of tipAngle {:g}",
                           tool.number, tool.path, tool_types[static_cast<int>(tool.type)].description,
                           tool.tip_angle.value_or(0.0), half, op.angle, 2.0 * op.angle));
    op.tip_clearance = in.optional_length(f, "tipClearance").value_or(0.2);
    if (!(op.tip_clearance >= 0)) f.fail("tipClearance", "tipClearance must be >= 0");
    op.geometry = chamfer_geometry(op.width, op.angle, tool.tip_diameter, op.tip_clearance);
    const ChamferGeometry& g = op.geometry;
    if (g.reach > tool.diameter / 2.0 + 1e-9)
        f.fail("width", fmt::format("the chamfer needs the cone of tool {} ({}) to reach {} from its axis at the top face (the "
                                    "offset {} from its tip diameter {} and tipClearance {}, plus the width {}), but the "
                                    "tool's diameter {} reaches {}: use a larger tool, a narrower chamfer or less tipClearance",
                                    tool.number, tool.path, in.show(g.reach), in.show(g.offset), in.show(tool.tip_diameter),
                                    in.show(op.tip_clearance), in.show(op.width), in.show(tool.diameter),
                                    in.show(tool.diameter / 2.0)));
    if (tool.flute_length && g.depth > *tool.flute_length + 1e-9)
        f.fail("width", fmt::format("the tip goes {} below the top face (the chamfer's {} and tipClearance {}), but tool {} "
                                    "({}) has a fluteLength of {}",
                                    in.show(g.depth), in.show(g.height), in.show(op.tip_clearance), tool.number, tool.path,
                                    in.show(*tool.flute_length)));
    op.heights = read_heights(f, in, "pass", "width", g.depth);
    if (f.has("passes")) {
        const int passes = f.integer("passes");
        if (passes < 1 || passes > chamfer_max_passes)
            f.fail("passes", fmt::format("passes must be a whole number from 1 to {}", chamfer_max_passes));
        op.passes = passes;
    }
    op.direction = f.choice("direction", cut_directions, CutDirection::climb);
    op.feeds = read_cut_feeds(f, in, tool, 0.0, op.notes);
    op.tolerance = read_tolerance(f, in);
    const Planes z = resolve_planes(op.heights);

    if (f.has("diameter")) {
        for (std::string_view key : {"start", "path", "profile"})
            if (f.has(key)) f.fail(key, "give a profile (start and path, or profile) or holes (diameter), not both");
        for (std::string_view key : {"side", "leadIn", "leadOut", "ramp"})
            if (f.has(key))
                f.fail(key, fmt::format("{} is a profile's: a hole's chamfer is a circle inside the hole, entered and left "
                                        "on a half circle from its centre",
                                        key));
        op.diameter = in.length(f, "diameter");
        if (!(op.diameter > 0)) f.fail("diameter", "diameter must be > 0");
        const double circle = op.diameter / 2.0 - g.offset;
        if (circle < chamfer_least_circle)
            f.fail("diameter", fmt::format("tool {} ({}) does not fit the hole (diameter {}): its centre runs {} inside the "
                                           "edge, which leaves a circle of radius {} (at least {} needed for its leads)",
                                           tool.number, tool.path, in.show(op.diameter), in.show(g.offset), in.show(circle),
                                           in.show(chamfer_least_circle)));
        op.side = ContourSide::inside;
        op.tool_left = tool_left_of_travel(op.direction, op.spindle);
        op.lead_in = op.lead_out = Lead{Lead::Kind::arc, circle / 2.0, 180.0, 0.0, 0.0};
        std::vector<std::string> notes = std::move(op.notes);
        static_cast<HoleSet&>(op) = read_hole_set(f, in, type);
        op.notes.insert(op.notes.begin(), notes.begin(), notes.end());
        op.notes.insert(op.notes.begin(), fmt::format("each hole's tool centre circle of radius {}", in.show(circle)));
    } else {
        op.profile = read_profile(f, in, "a chamfer", "start", "path", &op.notes);
        const bool closed = is_closed(op.profile);
        op.side = f.choice("side", contour_sides, ContourSide::outside);
        if (op.side == ContourSide::on)
            f.fail("side", "a chamfer is cut beside its edge, on the air side: left, right, inside or outside");
        if ((op.side == ContourSide::inside || op.side == ContourSide::outside) && !closed)
            f.fail("side", fmt::format("side {} needs a closed profile, but it ends at ({}, {}), not at its start ({}, {})",
                                       name_of(contour_sides, op.side), in.show(op.profile.segments.back().end.x),
                                       in.show(op.profile.segments.back().end.y), in.show(op.profile.start.x),
                                       in.show(op.profile.start.y)));
        op.lead_in = read_lead(f, in, "leadIn", tool.diameter);
        op.lead_out = read_lead(f, in, "leadOut", tool.diameter);
        op.ramp = read_ramp(f, in, "ramp", tool.diameter / 2.0);
        OffsetRequest request;
        request.profile = &op.profile;
        request.side = op.side;
        request.direction = op.direction;
        request.spindle = op.spindle;
        request.compensation = CompensationMode::computer;
        request.tool_radius = g.offset;
        request.json_path = op.path;
        try {
            OffsetPlan plan = plan_offsets(request, [&](double v) { return in.show(v); });
            op.tool_left = plan.tool_left;
            op.cut = std::move(plan.rough);
            op.notes.insert(op.notes.end(), plan.notes.begin(), plan.notes.end());
        } catch (const PlanError& e) {
            f.fail(e.key, e.what());
        }
    }
    op.notes.insert(op.notes.begin(),
                    fmt::format("chamfer {} x {:g} degrees with tool {} ({}, tip angle {:g}, tip diameter {}): tip at Z {} ({} "
                                "below the top face: the chamfer's {} and tipClearance {}), tool centre {} from the edge",
                                in.show(op.width), op.angle, tool.number,
                                tool_types[static_cast<int>(tool.type)].description, *tool.tip_angle,
                                in.show(tool.tip_diameter), in.show(z.bottom_z), in.show(g.depth), in.show(g.height),
                                in.show(op.tip_clearance), in.show(g.offset)));
    chamfer_guard(op, f, in);
    return op;
}

void expand(const ChamferOp& op, const Context& ctx, EventSink& sink) {
    if (op.on_holes() && op.holes.empty()) return;
    cut_chamfer(op, ctx.job, sink);
}

std::string default_name(const ChamferOp& op) {
    if (!op.comment.empty()) return op.comment;
    std::string s = fmt::format("chamfer {:g} x {:g}", op.width, op.angle);
    if (op.on_holes()) s += fmt::format(", {} hole{}", op.holes.size(), op.holes.size() == 1 ? "" : "s");
    return s;
}

}  // namespace camgen
