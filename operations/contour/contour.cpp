#include "camgen/operations/contour/contour.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/part_guard.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

constexpr KeySpec contour_side_keys[] = {
    {.key = "side", .type = JsonType::string, .default_json = "\"outside\"", .choices = &choices_of<contour_sides>, .description = "where the tool cuts: left, right, on, inside or outside (the last two: closed profiles)"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"climb\"", .choices = &choices_of<cut_directions>, .description = "climb or conventional: the profile is walked the way round that gives it"},
    {.key = "compensation", .type = JsonType::string, .default_json = "\"computer\"", .choices = &choices_of<compensation_modes>, .description = "who offsets the tool radius: computer, control, wear or inverse-wear"},
    {.key = "stockToLeave", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0", .description = "radial stock left on the wall by every pass"},
};

constexpr KeySpec contour_entry_keys[] = {
    {.key = "finishing", .type = JsonType::object, .ref = "contourFinishing", .description = "a finishing pass at full depth after the roughing passes"},
    {.key = "leadIn", .type = JsonType::object, .ref = "contourLead", .description = "how the tool joins the profile"},
    {.key = "leadOut", .type = JsonType::object, .ref = "contourLead", .description = "how the tool leaves the profile"},
    {.key = "ramp", .type = JsonType::object, .ref = "contourRamp", .description = "how the tool goes down to a pass (default: plunge)"},
    {.key = "tabs", .type = JsonType::object, .ref = "contourTabs", .description = "tabs that hold the part of a closed through-cut"},
};

// The contour's settings for the cutter.
CutSettings contour_settings(const ContourOp& op, const JobHeader& job) {
    CutSettings s;
    s.tool = op.tool;
    s.tool_radius = op.tool_radius;
    s.tool_left = op.tool_left;
    s.compensation = op.compensation;
    s.lead_in = op.lead_in;
    s.lead_out = op.lead_out;
    s.ramp = op.ramp;
    s.tabs = op.tabs ? &*op.tabs : nullptr;
    s.drawn = &op.profile;
    s.feeds = op.feeds;
    s.z = resolve_planes(op.heights);
    s.clearance = job.clearance;
    return s;
}

// The contour's passes: the roughing path at each depth, then the finishing path. `guard`:
// the part check the events go to (it is also `sink`), told what each run keeps.
void cut_contour(const ContourOp& op, const JobHeader& job, EventSink& sink, PartGuard* guard = nullptr) {
    const CutSettings settings = contour_settings(op, job);
    Cutter cutter(settings, sink);
    const Planes& z = settings.z;
    const bool closed = is_closed(op.rough);
    const double rough_bottom = z.bottom_z + (op.finishing ? op.finishing->axial_stock : 0.0);
    const std::vector<double> depths = pass_depths(z.reference_z, rough_bottom, op.step_down, op.equal_steps);
    const bool has_finish = !op.finish.segments.empty();
    if (guard) guard->keep(op.stock_to_leave + (op.finishing ? op.finishing->radial_stock : 0.0), rough_bottom);
    cutter.cut_run(op.rough, closed, depths, Movement::cutting, op.feeds.cutting, !has_finish);
    if (has_finish) {
        if (guard) guard->keep(op.stock_to_leave, z.bottom_z);
        cutter.cut_run(op.finish, closed, pass_depths(z.reference_z, z.bottom_z, op.finishing->step_down, op.equal_steps),
                       Movement::finishing, op.feeds.finishing, true);
    }
}

void guard_against_part(const ContourOp& op, Fields& f, const JobInput& in, const Tool& tool) {
    if (op.side == ContourSide::on) return;  // the tool centre on the line: no side to keep
    GuardedPart part;
    part.profile = &op.profile;
    part.tool_radius = op.tool_radius;
    part.top_z = resolve_planes(op.heights).reference_z;
    if (is_closed(op.profile)) {
        // The tool's side is air: inside for a pocket wall, outside for an outline; left or right
        // of a closed profile is one of the two by its turning.
        const bool tool_inside = op.side == ContourSide::inside ||
                                 (op.side == ContourSide::left && orientation(op.profile) == Orientation::ccw) ||
                                 (op.side == ContourSide::right && orientation(op.profile) == Orientation::cw);
        part.material_inside = !tool_inside;
    }
    PartGuard guard(part);
    (void)tool;
    cut_contour(op, in.header(), guard, &guard);
    const std::optional<Violation>& v = guard.violation();
    if (!v) return;
    std::string key;
    std::string hint;
    if (!v->control_refuses.empty()) {
        key = "compensation";
        f.fail(key, fmt::format("the control would refuse this program at the {} (its cutter compensation says: \"{}\"): the tool "
                                "(radius {}) does not fit the profile there as the control offsets it; use a smaller tool, or "
                                "compensation computer to see where it does not fit",
                                movement_words(v->movement, v->rapid), v->control_refuses, in.show(op.tool_radius)));
    }
    const GuardBlame blame = guard_blame(v->movement, v->rapid, op.compensation == CompensationMode::control);
    key = blame.key;
    hint = blame.hint;
    // A lead, ramp or plunge the job does not give: where the profile starts decides where the
    // tool goes down (the start, else the profile).
    if (!f.has(key)) key = key == "path" ? "" : f.has("start") ? "start" : f.has("profile") ? "profile" : "";
    f.fail(key, fmt::format("the {}{} {}: {}", movement_words(v->movement, v->rapid),
                            v->movement == Movement::plunge && !v->rapid ? " at the lead-in's start" : "", v->what, hint));
}

}  // namespace

std::vector<ObjectSpec> ContourOp::objects() {
    std::vector<KeySpec> keys = operation_head_keys();
    auto add = [&](const std::vector<KeySpec>& more) { keys.insert(keys.end(), more.begin(), more.end()); };
    add(height_keys(true));
    add(profile_keys("contour"));
    add({std::begin(contour_side_keys), std::end(contour_side_keys)});
    add(depth_pass_keys());
    add({std::begin(contour_entry_keys), std::end(contour_entry_keys)});
    add(cut_feed_keys());
    add(tolerance_keys());
    std::vector<ObjectSpec> out{{.name = "contour", .description = "cut beside (or on) a profile of lines and arcs, in depth passes", .keys = keys,
                                 .groups = {{.keys = {"start", "profile"}, .min = 1, .max = 1, .description = "start and path, or profile"}}}};
    for (ObjectSpec& o : cutting_objects()) out.push_back(std::move(o));
    return out;
}

ContourOp ContourOp::read(Fields& f, const JobInput& in) {
    if (f.has("depth"))
        f.fail("depth", "depth was replaced by endDepth: the depth below referencePlane, the stock top (> 0), or an absolute "
                        "Z with endDepthIsAbsolute; a tool-centre path at absolute Z is the \"path\" operation");
    std::vector<KeySpec> keys = objects().front().keys;
    JobInput::known_keys(f, keys);
    const Tool& tool = in.tool(f);
    check_cutting_tool(f, tool, "a contour");
    ContourOp op;
    op.path = f.path();
    op.tool = tool.number;
    if (std::optional<std::string> note = untyped_milling_note(tool)) op.notes.push_back(std::move(*note));
    op.comment = f.optional_string("comment").value_or("");
    if (!(tool.diameter > 0)) f.fail("tool", fmt::format("tool {} has no diameter: a contour offsets by its radius", tool.number));
    op.tool_radius = tool.diameter / 2;
    op.spindle = tool.direction;
    op.heights = read_heights(f, in, "pass");
    if (const Planes z = resolve_planes(op.heights); tool.flute_length && z.reference_z - z.bottom_z > *tool.flute_length)
        f.fail("endDepth", fmt::format("the contour is {} deep below the reference plane, but tool {} has a fluteLength of {}",
                                       in.show(z.reference_z - z.bottom_z), tool.number, in.show(*tool.flute_length)));
    op.profile = read_profile(f, in, "a contour", "start", "path", &op.notes);
    const bool closed = is_closed(op.profile);

    op.side = f.choice("side", contour_sides, ContourSide::outside);
    if ((op.side == ContourSide::inside || op.side == ContourSide::outside) && !closed)
        f.fail("side", fmt::format("side {} needs a closed profile, but it ends at ({}, {}), not at its start ({}, {})",
                                   name_of(contour_sides, op.side), in.show(op.profile.segments.back().end.x),
                                   in.show(op.profile.segments.back().end.y), in.show(op.profile.start.x),
                                   in.show(op.profile.start.y)));
    op.direction = f.choice("direction", cut_directions, CutDirection::climb);
    op.compensation = f.choice("compensation", compensation_modes, CompensationMode::computer);
    if (op.side == ContourSide::on && op.compensation != CompensationMode::computer)
        f.fail("compensation", "side on cuts with the tool centre on the profile: there is no radius to compensate");
    op.stock_to_leave = in.optional_length(f, "stockToLeave").value_or(0.0);
    if (!(op.stock_to_leave >= 0)) f.fail("stockToLeave", "stockToLeave must be >= 0");
    if (op.side == ContourSide::on && op.stock_to_leave > 0) f.fail("stockToLeave", "side on leaves no stock: there is no side");

    const Planes z = resolve_planes(op.heights);
    const double total_depth = z.reference_z - z.bottom_z;
    op.step_down = read_step_down(f, in, total_depth);
    op.equal_steps = f.boolean("equalSteps", true);
    op.finishing = read_finishing(f, in, total_depth);
    if (op.finishing && op.side == ContourSide::on && op.finishing->radial_stock > 0)
        json::fail(in.source(), f.path_of("finishing") + "/radialStock", "side on leaves no stock on a wall");
    op.lead_in = read_lead(f, in, "leadIn", tool.diameter);
    op.lead_out = read_lead(f, in, "leadOut", tool.diameter);
    if (op.compensation != CompensationMode::computer) {
        // The control switches compensation on along a straight lead: LinuxCNC refuses an
        // entry move shorter than the tool radius ("Length of cutter compensation entry move is
        // not greater than the tool radius"). A straight lead gets the length the arcs' entry
        // line has (see Cutter::switch_length).
        const double needed = std::max(op.tool_radius * 1.1, op.tool_radius + 0.1);
        for (auto [lead, key] : {std::pair{&op.lead_in, "leadIn"}, std::pair{&op.lead_out, "leadOut"}})
            if (lead->kind == Lead::Kind::line && lead->length < needed) {
                op.notes.push_back(fmt::format("{}/{}: the line is {} long; with the control compensating it must be longer than "
                                               "the tool radius: camgen makes it {}",
                                               op.path, key, in.show(lead->length), in.show(needed)));
                lead->length = needed;
            }
    }
    op.ramp = read_ramp(f, in, "ramp", op.tool_radius);
    if (op.ramp.kind == Ramp::Kind::along && op.compensation == CompensationMode::control)
        json::fail(in.source(), f.path_of("ramp") + "/type",
                   "an along ramp goes down along the profile and back at depth; with the control compensating, the way "
                   "back reverses the path and the control offsets it to the other side of the line (into the part): "
                   "use a helix or plunge ramp, or compensation computer");
    {
        // The tabs sit on the profile as drawn, the tool on its side.
        TabGeometry g;
        g.profile = &op.profile;
        switch (op.side) {
            case ContourSide::left: g.tool_left = true; break;
            case ContourSide::right: g.tool_left = false; break;
            case ContourSide::inside: g.tool_left = side_for(orientation(op.profile), Region::inside) == OffsetSide::left; break;
            case ContourSide::outside: g.tool_left = side_for(orientation(op.profile), Region::outside) == OffsetSide::left; break;
            case ContourSide::on: break;
        }
        g.distance = op.side == ContourSide::on ? 0.0 : op.tool_radius + op.stock_to_leave + (op.finishing ? op.finishing->radial_stock : 0.0);
        g.tool_radius = op.tool_radius;
        g.tool_diameter = tool.diameter;
        op.tabs = read_tabs(f, in, g, total_depth, closed);
    }
    // The radial engagement of a contour is not known (its first pass may be a slot).
    op.feeds = read_cut_feeds(f, in, tool, 0.0, op.notes);
    op.tolerance = read_tolerance(f, in);
    OffsetRequest request;
    request.profile = &op.profile;
    request.side = op.side;
    request.direction = op.direction;
    request.spindle = op.spindle;
    request.compensation = op.compensation;
    request.tool_radius = op.tool_radius;
    request.stock_to_leave = op.stock_to_leave;
    request.finishing = op.finishing.has_value();
    request.finishing_stock = op.finishing ? op.finishing->radial_stock : 0.0;
    request.json_path = op.path;
    try {
        OffsetPlan plan = plan_offsets(request, [&](double v) { return in.show(v); });
        op.tool_left = plan.tool_left;
        op.rough = std::move(plan.rough);
        op.finish = std::move(plan.finish);
        op.notes.insert(op.notes.end(), plan.notes.begin(), plan.notes.end());
    } catch (const PlanError& e) {
        f.fail(e.key, e.what());
    }
    guard_against_part(op, f, in, tool);
    return op;
}

std::string default_name(const ContourOp& c) { return c.comment.empty() ? "contour" : c.comment; }

void expand(const ContourOp& op, const Context& ctx, EventSink& sink) { cut_contour(op, ctx.job, sink); }

}  // namespace camgen
