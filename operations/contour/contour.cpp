#include "camgen/operations/contour/contour.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/events/visit.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;
// Arc end points may be this far off the circle through the start point, mm.
constexpr double arc_radius_tolerance = 0.001;
// A segment shorter than this is refused: no control writes it as a move of its own, mm.
constexpr double min_segment = 0.001;
// Sanity bound on depth passes, so that a tiny step cannot make a program without end.
constexpr double max_passes = 10000;

// The keys of a contour operation (the heights follow "comment").
constexpr KeySpec contour_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true}, .description = "a tool number from tools (its diameter is the cutter's)"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"", .description = "written as a comment before the operation"},
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "where the profile starts [x, y]"},
    {.key = "path", .type = JsonType::array, .required = true, .ref = "contourElement", .min_items = 1, .description = "the profile's lines and arcs in XY, each starting where the previous one ends"},
    {.key = "side", .type = JsonType::string, .default_json = "\"outside\"", .choices = &choices_of<contour_sides>, .description = "where the tool cuts: left, right, on, inside or outside (the last two: closed profiles)"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"climb\"", .choices = &choices_of<cut_directions>, .description = "climb or conventional: the profile is walked the way round that gives it"},
    {.key = "compensation", .type = JsonType::string, .default_json = "\"computer\"", .choices = &choices_of<compensation_modes>, .description = "who offsets the tool radius: computer, control, wear or inverse-wear"},
    {.key = "stockToLeave", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0", .description = "radial stock left on the wall by every pass"},
    {.key = "stepDown", .quantity = Quantity::length, .min = Bound{0, false}, .description = "the most each depth pass takes (default: one pass at endDepth)"},
    {.key = "equalSteps", .type = JsonType::boolean, .default_json = "true", .description = "passes of equal depth (else: full steps and a smaller last one)"},
    {.key = "finishing", .type = JsonType::object, .ref = "contourFinishing", .description = "a finishing pass at full depth after the roughing passes"},
    {.key = "leadIn", .type = JsonType::object, .ref = "contourLead", .description = "how the tool joins the profile"},
    {.key = "leadOut", .type = JsonType::object, .ref = "contourLead", .description = "how the tool leaves the profile"},
    {.key = "ramp", .type = JsonType::object, .ref = "contourRamp", .description = "how the tool goes down to a pass (default: plunge)"},
    {.key = "tabs", .type = JsonType::object, .ref = "contourTabs", .description = "tabs that hold the part of a closed through-cut"},
    {.key = "feed", .quantity = Quantity::feed, .required = true, .min = Bound{0, false}, .description = "cutting feed"},
    {.key = "plungeFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed straight down (default: feed)"},
    {.key = "rampFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of a ramp (default: feed)"},
    {.key = "leadInFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of the lead-in (default: feed)"},
    {.key = "leadOutFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of the lead-out (default: feed)"},
    {.key = "finishingFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of the finishing pass (default: feed)"},
    {.key = "tolerance", .quantity = Quantity::length, .min = Bound{0.0001, true}, .description = "how far the lines of an arc the machine cannot write may stray from it (default: the machine's "
                    "chordTolerance, which also caps it)"},
};

// The keys of a profile element: exactly one of them.
constexpr KeySpec element_keys[] = {
    {.key = "line", .type = JsonType::point, .quantity = Quantity::length, .description = "a straight line to [x, y]"},
    {.key = "arc", .type = JsonType::object, .ref = "contourArc", .description = "an arc about an absolute centre"},
};

constexpr KeySpec arc_keys[] = {
    {.key = "end", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "end point [x, y]"},
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "absolute centre [x, y]"},
    {.key = "direction", .type = JsonType::string, .required = true, .choices = &choices_of<arc_directions>, .description = "seen from +Z: cw (G2) or ccw (G3)"},
};

constexpr KeySpec finishing_keys[] = {
    {.key = "radialStock", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0", .description = "what the roughing passes leave on the wall for the finishing pass"},
    {.key = "axialStock", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0", .description = "what the roughing passes leave on the floor for the finishing pass"},
    {.key = "stepDown", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the finishing step: the most each finishing pass takes in depth (default: one pass at endDepth)"},
};

constexpr Named<Lead::Kind> lead_kinds[] = {
    {Lead::Kind::none, "none", "straight onto the profile (control compensation gets a line anyway)"},
    {Lead::Kind::arc, "arc", "a tangent arc"},
    {Lead::Kind::line, "line", "a straight line"},
};
constexpr KeySpec lead_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .choices = &choices_of<lead_kinds>, .description = "none, arc or line"},
    {.key = "radius", .quantity = Quantity::length, .min = Bound{0, false}, .description = "arc: its radius (default: the tool's diameter)"},
    {.key = "sweep", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{180, true}, .default_json = "90", .description = "arc: degrees turned"},
    {.key = "length", .quantity = Quantity::length, .min = Bound{0, false}, .description = "line: its length (default: the tool's diameter)"},
    {.key = "angle", .quantity = Quantity::angle, .min = Bound{0, true}, .max = Bound{90, true}, .default_json = "0", .description = "line: degrees from the profile's tangent towards the tool's side"},
};

constexpr Named<Ramp::Kind> ramp_kinds[] = {
    {Ramp::Kind::plunge, "plunge", "straight down at plungeFeed"},
    {Ramp::Kind::along, "along", "down along the profile at an angle, then back to its start at depth"},
    {Ramp::Kind::helix, "helix", "a helix down before the lead-in"},
};
constexpr KeySpec ramp_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .choices = &choices_of<ramp_kinds>, .description = "plunge, along or helix"},
    {.key = "angle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{45, true}, .default_json = "5", .description = "degrees above horizontal"},
    {.key = "radius", .quantity = Quantity::length, .min = Bound{0, false}, .description = "helix: its radius (default: the tool's radius)"},
};

constexpr KeySpec tab_keys[] = {
    {.key = "count", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true}, .max = Bound{1000, true}, .description = "tabs evenly spaced along the profile"},
    {.key = "spacing", .quantity = Quantity::length, .min = Bound{0, false}, .description = "or one tab every so many mm"},
    {.key = "width", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "width of a tab on the part"},
    {.key = "height", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "height of a tab above the bottom of the cut"},
};

Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 add(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 scale(Vec2 a, double k) { return {a.x * k, a.y * k}; }
double len(Vec2 a) { return std::hypot(a.x, a.y); }
Vec2 left_normal(Vec2 t) { return {-t.y, t.x}; }
Vec2 rotate(Vec2 v, double a) { return {v.x * std::cos(a) - v.y * std::sin(a), v.x * std::sin(a) + v.y * std::cos(a)}; }

// The elements of a profile as JSON (lines and arcs).
void read_elements(Fields& f, const JobInput& in, const std::string& base, Profile& p) {
    const Json& elements = in.array(f, "path");
    if (elements.empty()) f.fail("path", "a contour needs at least one line or arc");
    in.claim_path_elements(static_cast<double>(elements.size()), f, "path");
    Vec2 at = p.start;
    for (std::size_t k = 0; k < elements.size(); ++k) {
        const std::string path = base + "/" + std::to_string(k);
        Fields e(elements[k], path, in.source());
        JobInput::known_keys(e, element_keys);
        if (int(e.has("line")) + int(e.has("arc")) != 1) e.fail("", "a contour element needs exactly one of \"line\" or \"arc\"");
        ProfileSegment s;
        if (e.has("line")) {
            s.end = in.point(e, "line");
        } else {
            Fields a(e.required("arc"), e.path_of("arc"), in.source());
            JobInput::known_keys(a, arc_keys);
            s.end = in.point(a, "end");
            s.centre = in.point(a, "centre");
            s.direction = a.choice("direction", arc_directions);
            const double r0 = len(sub(at, *s.centre)), r1 = len(sub(s.end, *s.centre));
            if (std::abs(r0 - r1) > arc_radius_tolerance)
                a.fail("", fmt::format("start is {:.3f} mm from the centre but end is {:.3f} mm", r0, r1));
            if (r0 < min_segment) a.fail("centre", "the centre is the arc's start: an arc needs a radius");
        }
        p.segments.push_back(s);
        at = s.end;
    }
}

// The lines of a profile read straight into numbers ({"line": [x, y]} each, see PackedArray).
void read_packed_lines(const json::PackedArray& packed, const std::string& base, const JobInput& in, Profile& p) {
    p.segments.reserve(packed.size());
    for (std::size_t k = 0; k < packed.size(); ++k) {
        auto line_path = [&] { return fmt::format("{}/{}/line", base, k); };
        if (packed.has_z(k)) json::fail(in.source(), line_path(), "expected a point [x, y], got an array");
        ProfileSegment s;
        s.end = {in.packed_coordinate(packed.x(k), [&] { return line_path() + "/0"; }),
                 in.packed_coordinate(packed.y(k), [&] { return line_path() + "/1"; })};
        p.segments.push_back(s);
    }
}

Profile read_profile(Fields& f, const JobInput& in) {
    Profile p;
    p.start = in.point(f, "start");
    const std::string base = f.path_of("path");
    if (const json::PackedArray* packed = in.packed(f.required("path"))) {
        in.claim_path_elements(static_cast<double>(packed->size()), f, "path");
        read_packed_lines(*packed, base, in, p);
    } else {
        read_elements(f, in, base, p);
    }
    if (auto k = first_short_segment(p, min_segment))
        json::fail(in.source(), base + "/" + std::to_string(*k), fmt::format("this element is shorter than {} mm: remove it", min_segment));
    if (!is_simple(p))
        f.fail("path", is_closed(p) ? "the profile crosses or touches itself" : "the open profile crosses or touches itself");
    return p;
}

Lead read_lead(Fields& f, const JobInput& in, std::string_view key, double tool_diameter) {
    Lead lead;
    const Json* value = f.member(key);
    if (!value) return lead;
    Fields l(*value, f.path_of(key), in.source());
    JobInput::known_keys(l, lead_keys);
    lead.kind = l.choice("type", lead_kinds);
    lead.radius = in.optional_length(l, "radius").value_or(tool_diameter);
    lead.sweep = l.optional_number("sweep").value_or(90.0);
    lead.length = in.optional_length(l, "length").value_or(tool_diameter);
    lead.angle = l.optional_number("angle").value_or(0.0);
    if (!(lead.radius > 0)) l.fail("radius", "radius must be > 0");
    if (!(lead.sweep > 0 && lead.sweep <= 180)) l.fail("sweep", "sweep must be more than 0 and at most 180 degrees");
    if (!(lead.length > 0)) l.fail("length", "length must be > 0");
    if (!(lead.angle >= 0 && lead.angle <= 90)) l.fail("angle", "angle must be from 0 to 90 degrees");
    return lead;
}

// The feed of `key`, or `fallback`.
double feed_of(Fields& f, const JobInput& in, std::string_view key, double fallback) {
    const std::optional<double> v = in.optional_length(f, key);
    if (v && !(*v > 0)) f.fail(key, fmt::format("{} must be > 0", key));
    return v.value_or(fallback);
}


// What camgen cuts must be what the offset promises: every arc on its circle, and (for
// profiles of ordinary size) every segment's ends and middle at `distance` from the profile
// or farther. A path that is not is refused rather than cut (a fuzz finding: an offset "arc"
// whose end lay 49 mm from its centre on a radius-5 arc, the pocket's side missing).
void check_offset(const Profile& path, const Profile& walk, double distance, const char* which, Fields& f) {
    constexpr double slack = 1e-5;
    const bool sample = path.segments.size() * walk.segments.size() <= 25'000'000;
    Vec2 from = path.start;
    for (std::size_t k = 0; k < path.segments.size(); ++k) {
        const ProfileSegment& s = path.segments[k];
        bool bad = false;
        if (s.centre) bad = std::abs(len(sub(from, *s.centre)) - len(sub(s.end, *s.centre))) > slack;
        if (!bad && sample) {
            Profile one;
            one.start = from;
            one.segments.push_back(s);
            for (double t : {0.0, 0.5, 1.0})
                if (distance_to(walk, point_at(one, t * profile_length(one)).point) < distance - slack) bad = true;
        }
        if (bad)
            f.fail("path", fmt::format("camgen could not offset this profile for the {} path (segment {} of its offset is wrong): "
                                       "please report it; use compensation control or side on meanwhile",
                                       which, k));
        from = s.end;
    }
}

// The walk direction, the offsets and the notes of an operation just read.
void plan(ContourOp& op, Fields& f, const JobInput& in) {
    // Climb: the tool left of its travel with a clockwise spindle, right with a counter-clockwise one.
    op.tool_left = tool_left_of_travel(op.direction, op.spindle);
    // The profile in the direction the tool walks it: reversed into a copy of its own only when
    // it must be (a contour of a million segments holds its profile and its paths, no more).
    Profile reversed_profile;
    const Profile* walk = &op.profile;
    bool reversed_walk = false;
    if (op.side != ContourSide::on) {
        OffsetSide drawn = OffsetSide::left;
        switch (op.side) {
            case ContourSide::left: drawn = OffsetSide::left; break;
            case ContourSide::right: drawn = OffsetSide::right; break;
            case ContourSide::inside: drawn = side_for(orientation(op.profile), Region::inside); break;
            case ContourSide::outside: drawn = side_for(orientation(op.profile), Region::outside); break;
            case ContourSide::on: break;
        }
        if ((drawn == OffsetSide::left) != op.tool_left) {
            reversed_profile = reversed(op.profile);
            walk = &reversed_profile;
            reversed_walk = true;
        }
    }
    const OffsetSide side = op.tool_left ? OffsetSide::left : OffsetSide::right;
    const bool computer = op.compensation != CompensationMode::control;
    const double radius = computer && op.side != ContourSide::on ? op.tool_radius : 0.0;
    const double finishing_stock = op.finishing ? op.finishing->radial_stock : 0.0;
    const std::size_t n = op.profile.segments.size();
    // `last`: the walk is not needed after this path (a reversed one may then be moved into it).
    auto offset = [&](double distance, const char* which, bool last) -> Profile {
        if (distance <= 0 && last && reversed_walk) return std::move(reversed_profile);
        if (distance <= 0) return *walk;
        OffsetResult r = offset_profile(*walk, distance, side);
        if (r.empty())
            f.fail("path", fmt::format("the {} path is empty: the tool (radius {}) with the stock left does not fit {} the profile", which,
                                       in.show(op.tool_radius), op.side == ContourSide::inside ? "inside" : "beside"));
        for (const OffsetNote& note : r.notes) {
            std::string where = op.path + "/path";
            if (note.segment && *note.segment < n) where = op.element_path(reversed_walk ? n - 1 - *note.segment : *note.segment);
            op.notes.push_back(fmt::format("{}: the {} path: {}", where, which, note.message));
        }
        check_offset(r.profile, *walk, distance, which, f);
        if (!r.others.empty())
            op.notes.push_back(fmt::format("the {} path falls apart into {} pieces where the tool does not fit; only the longest "
                                           "is cut",
                                           which, r.others.size() + 1));
        return r.profile;
    };
    op.rough = offset(radius + op.stock_to_leave + finishing_stock, "roughing", !op.finishing);
    if (op.finishing) op.finish = offset(radius + op.stock_to_leave, "finishing", true);
}

}  // namespace

std::vector<double> pass_depths(double top, double bottom, std::optional<double> step_down, bool equal_steps) {
    const double total = top - bottom;
    if (!step_down || *step_down >= total) return {bottom};
    const int n = static_cast<int>(std::ceil(total / *step_down - 1e-9));
    std::vector<double> z;
    for (int k = 1; k < n; ++k) z.push_back(equal_steps ? top - total * k / n : top - *step_down * k);
    z.push_back(bottom);
    return z;
}

std::vector<ObjectSpec> ContourOp::objects() {
    std::vector<KeySpec> keys(std::begin(contour_keys), std::begin(contour_keys) + 3);
    const std::vector<KeySpec> heights = height_keys(true);
    keys.insert(keys.end(), heights.begin(), heights.end());
    keys.insert(keys.end(), std::begin(contour_keys) + 3, std::end(contour_keys));
    return {
        {.name = "contour", .description = "cut beside (or on) a profile of lines and arcs, in depth passes", .keys = keys},
        {.name = "contourElement", .description = "one element of a profile: exactly one of line or arc",
         .keys = {std::begin(element_keys), std::end(element_keys)},
         .groups = {{.keys = {"line", "arc"}, .min = 1, .max = 1, .description = "exactly one of line or arc"}}},
        {.name = "contourArc", .description = "an arc in XY about an absolute centre", .keys = {std::begin(arc_keys), std::end(arc_keys)}},
        {.name = "contourFinishing", .description = "stock the roughing passes leave for the finishing pass",
         .keys = {std::begin(finishing_keys), std::end(finishing_keys)}},
        {.name = "contourLead", .description = "a lead-in or lead-out: a tangent arc or a straight line",
         .keys = {std::begin(lead_keys), std::end(lead_keys)}},
        {.name = "contourRamp", .description = "how the tool goes down to a pass", .keys = {std::begin(ramp_keys), std::end(ramp_keys)}},
        {.name = "contourTabs", .description = "tabs: count or spacing, width and height",
         .keys = {std::begin(tab_keys), std::end(tab_keys)},
         .groups = {{.keys = {"count", "spacing"}, .min = 1, .max = 1, .description = "exactly one of count or spacing"}}},
    };
}

ContourOp ContourOp::read(Fields& f, const JobInput& in) {
    if (f.has("depth"))
        f.fail("depth", "depth was replaced by endDepth: the depth below referencePlane, the stock top (> 0), or an absolute "
                        "Z with endDepthIsAbsolute; a tool-centre path at absolute Z is the \"path\" operation");
    std::vector<KeySpec> keys = objects().front().keys;
    JobInput::known_keys(f, keys);
    const Tool& tool = in.tool(f);
    ContourOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    if (!(tool.diameter > 0)) f.fail("tool", fmt::format("tool {} has no diameter: a contour offsets by its radius", tool.number));
    op.tool_radius = tool.diameter / 2;
    op.spindle = tool.direction;
    op.heights = read_heights(f, in, "pass");
    if (const Planes z = resolve_planes(op.heights); tool.flute_length && z.reference_z - z.bottom_z > *tool.flute_length)
        f.fail("endDepth", fmt::format("the contour is {} deep below the reference plane, but tool {} has a fluteLength of {}",
                                       in.show(z.reference_z - z.bottom_z), tool.number, in.show(*tool.flute_length)));
    op.profile = read_profile(f, in);
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
    op.step_down = in.optional_length(f, "stepDown");
    if (op.step_down && !(*op.step_down > 0)) f.fail("stepDown", "stepDown must be > 0");
    if (op.step_down && total_depth / *op.step_down > max_passes)
        f.fail("stepDown", fmt::format("stepDown {} makes more than {} passes", in.show(*op.step_down), max_passes));
    op.equal_steps = f.boolean("equalSteps", true);
    if (const Json* value = f.member("finishing")) {
        Fields fin(*value, f.path_of("finishing"), in.source());
        JobInput::known_keys(fin, finishing_keys);
        Finishing finishing;
        finishing.radial_stock = in.optional_length(fin, "radialStock").value_or(0.0);
        finishing.axial_stock = in.optional_length(fin, "axialStock").value_or(0.0);
        if (!(finishing.radial_stock >= 0)) fin.fail("radialStock", "radialStock must be >= 0");
        if (!(finishing.axial_stock >= 0)) fin.fail("axialStock", "axialStock must be >= 0");
        if (finishing.axial_stock >= total_depth)
            fin.fail("axialStock", fmt::format("axialStock {} is not less than the depth of the cut ({})", in.show(finishing.axial_stock),
                                               in.show(total_depth)));
        if (op.side == ContourSide::on && finishing.radial_stock > 0) fin.fail("radialStock", "side on leaves no stock on a wall");
        finishing.step_down = in.optional_length(fin, "stepDown");
        if (finishing.step_down && !(*finishing.step_down > 0)) fin.fail("stepDown", "stepDown must be > 0");
        if (finishing.step_down && total_depth / *finishing.step_down > max_passes)
            fin.fail("stepDown", fmt::format("stepDown {} makes more than {} passes", in.show(*finishing.step_down), max_passes));
        op.finishing = finishing;
    }
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
    if (const Json* value = f.member("ramp")) {
        Fields r(*value, f.path_of("ramp"), in.source());
        JobInput::known_keys(r, ramp_keys);
        op.ramp.kind = r.choice("type", ramp_kinds);
        op.ramp.angle = r.optional_number("angle").value_or(5.0);
        if (!(op.ramp.angle > 0 && op.ramp.angle <= 45)) r.fail("angle", "angle must be more than 0 and at most 45 degrees");
        op.ramp.radius = in.optional_length(r, "radius").value_or(op.tool_radius);
        if (!(op.ramp.radius > 0)) r.fail("radius", "radius must be > 0");
    }
    if (const Json* value = f.member("tabs")) {
        Fields t(*value, f.path_of("tabs"), in.source());
        JobInput::known_keys(t, tab_keys);
        if (!closed) t.fail("", "tabs hold the part of a closed profile; this profile is open");
        if (int(t.has("count")) + int(t.has("spacing")) != 1) t.fail("", "tabs need exactly one of count or spacing");
        Tabs tabs;
        tabs.width = in.length(t, "width");
        tabs.height = in.length(t, "height");
        if (!(tabs.width > 0)) t.fail("width", "width must be > 0");
        if (!(tabs.height > 0)) t.fail("height", "height must be > 0");
        if (tabs.height >= total_depth)
            t.fail("height", fmt::format("a tab {} high does not fit in a cut {} deep", in.show(tabs.height), in.show(total_depth)));
        double shortest = profile_length(op.profile);
        Vec2 from = op.profile.start;
        for (const ProfileSegment& seg : op.profile.segments) {
            if (!seg.centre) shortest = std::min(shortest, len(sub(seg.end, from)));
            from = seg.end;
        }
        if (tabs.width >= shortest)
            t.fail("width", fmt::format("a tab {} wide does not fit on the profile's shortest side ({} long)", in.show(tabs.width),
                                        in.show(shortest)));
        if (t.has("count")) {
            tabs.count = t.integer("count");
            if (tabs.count < 1 || tabs.count > 1000) t.fail("count", "count must be from 1 to 1000");
        } else {
            const double spacing = in.length(t, "spacing");
            if (!(spacing > 0)) t.fail("spacing", "spacing must be > 0");
            const double n = std::floor(profile_length(op.profile) / spacing);
            if (n > 1000) t.fail("spacing", "spacing makes more than 1000 tabs");
            tabs.count = std::max(1, static_cast<int>(n));
        }
        if (tabs.count * (tabs.width + tool.diameter) >= profile_length(op.profile))
            t.fail("", fmt::format("{} tabs {} wide (the tool lifts over {} each) do not fit on a profile {} long", tabs.count,
                                   in.show(tabs.width), in.show(tabs.width + tool.diameter), in.show(profile_length(op.profile))));
        op.tabs = tabs;
    }
    op.feeds.cutting = in.length(f, "feed");
    if (!(op.feeds.cutting > 0)) f.fail("feed", "feed must be > 0");
    op.feeds.plunge = feed_of(f, in, "plungeFeed", op.feeds.cutting);
    op.feeds.ramp = feed_of(f, in, "rampFeed", op.feeds.cutting);
    op.feeds.lead_in = feed_of(f, in, "leadInFeed", op.feeds.cutting);
    op.feeds.lead_out = feed_of(f, in, "leadOutFeed", op.feeds.cutting);
    op.feeds.finishing = feed_of(f, in, "finishingFeed", op.feeds.cutting);
    op.tolerance = in.optional_length(f, "tolerance");
    if (op.tolerance && !(*op.tolerance >= 0.0001)) f.fail("tolerance", "tolerance must be at least 0.0001 mm");
    plan(op, f, in);
    return op;
}

std::string default_name(const ContourOp& c) { return c.comment.empty() ? "contour" : c.comment; }

}  // namespace camgen

namespace camgen {

namespace {

// Emits the moves of a contour, keeping track of where the tool is.
class Cutter {
public:
    Cutter(const ContourOp& op, const Context& ctx, EventSink& sink)
        : op_(op), ctx_(ctx), sink_(sink), z_(resolve_planes(op.heights)) {}

    void run() {
        const bool closed = is_closed(op_.rough);
        const double rough_bottom = z_.bottom_z + (op_.finishing ? op_.finishing->axial_stock : 0.0);
        const std::vector<double> depths = pass_depths(z_.reference_z, rough_bottom, op_.step_down, op_.equal_steps);
        const bool has_finish = !op_.finish.segments.empty();
        first_ = true;
        cut_run(op_.rough, closed, depths, Movement::cutting, op_.feeds.cutting, !has_finish);
        if (has_finish)
            cut_run(op_.finish, closed, pass_depths(z_.reference_z, z_.bottom_z, op_.finishing->step_down, op_.equal_steps),
                    Movement::finishing, op_.feeds.finishing, true);
    }

private:
    // A lead: the path from where the tool joins (or to where it leaves), with the straight
    // entry or exit line that carries the compensation change when the control compensates.
    struct LeadPath {
        Profile path;  // lead-in: ends on the profile; lead-out: starts on it
    };

    bool control_compensates() const { return op_.compensation != CompensationMode::computer; }

    // The length of the straight move that switches compensation on or off: LinuxCNC wants an
    // entry move at least the tool radius long; a tenth more keeps it so after rounding.
    double switch_length() const { return std::max(op_.tool_radius * 1.1, op_.tool_radius + 0.1); }

    Vec2 side_normal(Vec2 t) const { return op_.tool_left ? left_normal(t) : scale(left_normal(t), -1); }

    // The lead-in onto `p`'s start; its path's start is where the tool goes down.
    Profile lead_in(const Profile& p) const {
        const ProfilePoint s = point_at(p, 0.0);
        Lead lead = op_.lead_in;
        if (lead.kind == Lead::Kind::none && control_compensates()) lead = Lead{Lead::Kind::line, 0, 90, switch_length(), 0};
        Profile out;
        out.start = s.point;
        Vec2 tangent_at_start = s.tangent;  // of travel where the lead begins
        if (lead.kind == Lead::Kind::arc) {
            const double rho = std::max(lead.radius, control_compensates() ? op_.tool_radius * 1.5 : 0.0);
            const Vec2 c = add(s.point, scale(side_normal(s.tangent), rho));
            const double turn = (op_.tool_left ? -1 : 1) * lead.sweep * deg;
            out.start = add(c, rotate(sub(s.point, c), turn));
            out.segments.push_back({s.point, c, op_.tool_left ? ArcDirection::ccw : ArcDirection::cw});
            const Vec2 radial = scale(sub(out.start, c), 1.0 / rho);
            tangent_at_start = op_.tool_left ? left_normal(radial) : scale(left_normal(radial), -1);
        } else if (lead.kind == Lead::Kind::line) {
            const double a = lead.angle * deg;
            out.start = add(sub(s.point, scale(s.tangent, lead.length * std::cos(a))), scale(side_normal(s.tangent), lead.length * std::sin(a)));
            out.segments.push_back({s.point, std::nullopt, ArcDirection::ccw});
            tangent_at_start = scale(sub(s.point, out.start), 1.0 / lead.length);
        }
        if (control_compensates() && lead.kind == Lead::Kind::arc) {
            // The compensation comes on along a straight line before the arc.
            Profile entry;
            entry.start = sub(out.start, scale(tangent_at_start, switch_length()));
            entry.segments.push_back({out.start, std::nullopt, ArcDirection::ccw});
            entry.segments.insert(entry.segments.end(), out.segments.begin(), out.segments.end());
            return entry;
        }
        return out;
    }

    // The lead-out from `p`'s end.
    Profile lead_out(const Profile& p) const {
        const ProfilePoint e = point_at(p, profile_length(p));
        Lead lead = op_.lead_out;
        if (lead.kind == Lead::Kind::none && control_compensates()) lead = Lead{Lead::Kind::line, 0, 90, switch_length(), 0};
        Profile out;
        out.start = e.point;
        Vec2 tangent_at_end = e.tangent;
        if (lead.kind == Lead::Kind::arc) {
            const double rho = std::max(lead.radius, control_compensates() ? op_.tool_radius * 1.5 : 0.0);
            const Vec2 c = add(e.point, scale(side_normal(e.tangent), rho));
            const double turn = (op_.tool_left ? 1 : -1) * lead.sweep * deg;
            const Vec2 end = add(c, rotate(sub(e.point, c), turn));
            out.segments.push_back({end, c, op_.tool_left ? ArcDirection::ccw : ArcDirection::cw});
            const Vec2 radial = scale(sub(end, c), 1.0 / rho);
            tangent_at_end = op_.tool_left ? left_normal(radial) : scale(left_normal(radial), -1);
        } else if (lead.kind == Lead::Kind::line) {
            const double a = lead.angle * deg;
            const Vec2 end = add(add(e.point, scale(e.tangent, lead.length * std::cos(a))), scale(side_normal(e.tangent), lead.length * std::sin(a)));
            out.segments.push_back({end, std::nullopt, ArcDirection::ccw});
            tangent_at_end = scale(sub(end, e.point), 1.0 / lead.length);
        }
        if (control_compensates() && lead.kind == Lead::Kind::arc) {
            const Vec2 from = out.segments.back().end;
            out.segments.push_back({add(from, scale(tangent_at_end, switch_length())), std::nullopt, ArcDirection::ccw});
        }
        return out;
    }

    CompensationSide compensation_side() const {
        const bool left = op_.compensation == CompensationMode::inverse_wear ? !op_.tool_left : op_.tool_left;
        return left ? CompensationSide::left : CompensationSide::right;
    }

    // The radius the control offsets by: the tool's when it compensates alone; with wear only
    // the wear, which camgen does not know (0).
    double compensation_radius() const { return op_.compensation == CompensationMode::control ? op_.tool_radius : 0.0; }

    void rapid(Vec3 to) {
        if (known_ && to == at_) return;
        sink_.emit(Rapid{to});
        at_ = to;
        known_ = true;
    }

    void feed_to(Vec3 to, double feed, Movement m) {
        if (to == at_) return;
        sink_.emit(Linear{to, feed, m});
        at_ = to;
    }

    // The segments of `p` from the tool's position, Z going linearly from `z0` to `z1` along it.
    void follow(const Profile& p, double z0, double z1, double feed, Movement m) {
        const double total = profile_length(p);
        double done = 0.0;
        Vec2 from = p.start;
        for (const ProfileSegment& s : p.segments) {
            Profile one;
            one.start = from;
            one.segments.push_back(s);
            done += profile_length(one);
            const double z = total > 0 ? z0 + (z1 - z0) * done / total : z1;
            const Vec3 to{s.end.x, s.end.y, z};
            if (s.centre)
                sink_.emit(Arc{to, {s.centre->x, s.centre->y, at_.z}, s.direction, Plane::xy, feed, 0, m});
            else
                sink_.emit(Linear{to, feed, m});
            at_ = to;
            from = s.end;
        }
    }

    // One pass along `p` at `z`, rising over the tabs where `z` is below their top.
    void cut_pass(const Profile& p, double z, double feed, Movement m) {
        const double tab_top = op_.tabs ? z_.bottom_z + op_.tabs->height : -1e300;
        if (!op_.tabs || z >= tab_top - 1e-9) {
            follow(p, z, z, feed, m);
            return;
        }
        const double total = profile_length(p);
        double from = 0.0;
        for (const auto& [a, b] : tab_intervals(p)) {
            follow(sub_profile(p, from, a), z, z, feed, m);
            feed_to({at_.x, at_.y, tab_top}, feed, m);
            follow(sub_profile(p, a, b), tab_top, tab_top, feed, m);
            feed_to({at_.x, at_.y, z}, op_.feeds.plunge, Movement::plunge);
            from = b;
        }
        follow(sub_profile(p, from, total), z, z, feed, m);
    }

    // Where along `p` the tool rises over a tab: evenly spaced, each the tab's width plus the
    // tool's diameter long (so that the tab is `width` wide on the part), moved off arcs too
    // short to hold it onto the next straight side.
    std::vector<std::pair<double, double>> tab_intervals(const Profile& p) const {
        std::vector<std::pair<double, double>> out;
        const double total = profile_length(p);
        const double half = (op_.tabs->width + 2 * op_.tool_radius) / 2;
        // The lines long enough for a tab, as [start, end] lengths along p.
        std::vector<std::pair<double, double>> arcs_too_short, lines;
        double done = 0.0;
        Vec2 from = p.start;
        for (const ProfileSegment& s : p.segments) {
            Profile one;
            one.start = from;
            one.segments.push_back(s);
            const double l = profile_length(one);
            if (s.centre && l < 2 * half) arcs_too_short.push_back({done, done + l});
            if (!s.centre && l >= 2 * half) lines.push_back({done, done + l});
            done += l;
            from = s.end;
        }
        for (int k = 0; k < op_.tabs->count; ++k) {
            double c = total * (k + 0.5) / op_.tabs->count;
            const bool on_short_arc = std::any_of(arcs_too_short.begin(), arcs_too_short.end(),
                                                  [&](const auto& a) { return c + half > a.first && c - half < a.second; });
            if (on_short_arc) {
                auto next = std::find_if(lines.begin(), lines.end(), [&](const auto& l) { return l.second - half >= c; });
                if (next == lines.end()) next = lines.begin();
                if (next != lines.end()) c = std::clamp(c, next->first + half, next->second - half);
            }
            const double a = std::max(c - half, out.empty() ? 0.0 : out.back().second), b = std::min(c + half, total);
            if (b > a) out.push_back({a, b});
        }
        return out;
    }

    // Down from the tool's Z to `z` at its XY: straight at plunge feed, or a helix turning
    // about a centre `away` (a unit vector) from the tool, on the side away from the profile.
    void go_down(double z, Vec2 away) {
        if (op_.ramp.kind == Ramp::Kind::helix) {
            const double rho = op_.ramp.radius;
            const double per_turn = 2 * pi * rho * std::tan(op_.ramp.angle * deg);
            const int turns = std::max(1, static_cast<int>(std::ceil((at_.z - z) / per_turn - 1e-9)));
            const Vec3 centre{at_.x + away.x * rho, at_.y + away.y * rho, at_.z};
            sink_.emit(Arc{{at_.x, at_.y, z}, centre, op_.tool_left ? ArcDirection::ccw : ArcDirection::cw, Plane::xy,
                           op_.feeds.ramp, turns - 1, Movement::ramp});
            at_.z = z;
            return;
        }
        feed_to({at_.x, at_.y, z}, op_.feeds.plunge, Movement::plunge);
    }

    // One pass at `z` from the profile's start, the tool at its start at `z_prev`: down (plunge
    // there, or a ramp along the profile and back at depth), then the whole profile.
    void pass_from_start(const Profile& p, double z_prev, double z, double feed, Movement m) {
        if (op_.ramp.kind == Ramp::Kind::along && z_prev > z) {
            const double total = profile_length(p);
            double l = (z_prev - z) / std::tan(op_.ramp.angle * deg);
            l = std::min(l, total);
            const Profile down = sub_profile(p, 0.0, l);
            follow(down, z_prev, z, op_.feeds.ramp, Movement::ramp);
            follow(reversed(down), z, z, op_.feeds.ramp, Movement::ramp);
        } else {
            feed_to({at_.x, at_.y, z}, op_.feeds.plunge, Movement::plunge);
        }
        cut_pass(p, z, feed, m);
    }

    // Every pass of one path: lead in once (each pass for an open path), down pass by pass,
    // lead out, and up.
    void cut_run(const Profile& p, bool closed, const std::vector<double>& depths, Movement m, double feed, bool last_run) {
        const Profile in = lead_in(p), out = lead_out(p);
        double z_prev = z_.reference_z;
        for (std::size_t k = 0; k < depths.size(); ++k) {
            const double z = depths[k];
            const bool enter = k == 0 || !closed;
            if (enter) {
                const Vec2 a = in.start;
                if (first_) {
                    rapid({a.x, a.y, ctx_.job.clearance});
                    first_ = false;
                }
                rapid({a.x, a.y, z_.retract_z});
                rapid({a.x, a.y, z_.safe_z});
                // Along a ramp the tool enters at the previous level and ramps on the profile.
                const double entry_z = op_.ramp.kind == Ramp::Kind::along ? std::max(z_prev, z) : z;
                if (at_.z > entry_z) go_down(entry_z, side_normal(point_at(p, 0.0).tangent));
                if (control_compensates()) sink_.emit(Compensation{compensation_side(), op_.tool, compensation_radius()});
                follow(in, at_.z, at_.z, op_.feeds.lead_in, Movement::lead_in);
                pass_from_start(p, at_.z, z, feed, m);
            } else {
                pass_from_start(p, at_.z, z, feed, m);
            }
            z_prev = z;
            const bool leave = k + 1 == depths.size() || !closed;
            if (leave) {
                if (control_compensates() && !out.segments.empty()) {
                    // Off on the last straight move of the lead-out.
                    Profile before = out, last = out;
                    before.segments.pop_back();
                    last.start = before.segments.empty() ? out.start : before.segments.back().end;
                    last.segments = {out.segments.back()};
                    follow(before, at_.z, at_.z, op_.feeds.lead_out, Movement::lead_out);
                    sink_.emit(Compensation{CompensationSide::off, 0, 0.0});
                    follow(last, at_.z, at_.z, op_.feeds.lead_out, Movement::lead_out);
                } else {
                    follow(out, at_.z, at_.z, op_.feeds.lead_out, Movement::lead_out);
                }
                const bool done = last_run && k + 1 == depths.size();
                // Across to the next entry at the retract plane: rapids across stay above it.
                rapid({at_.x, at_.y, done ? ctx_.job.clearance : z_.retract_z});
            }
        }
    }

    const ContourOp& op_;
    const Context& ctx_;
    EventSink& sink_;
    const Planes z_;
    Vec3 at_;
    bool known_ = false;
    bool first_ = true;
};

}  // namespace

void expand(const ContourOp& op, const Context& ctx, EventSink& sink) { Cutter(op, ctx, sink).run(); }

}  // namespace camgen
