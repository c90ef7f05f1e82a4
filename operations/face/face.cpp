#include "camgen/operations/face/face.hpp"
#include "camgen/geometry/clearance.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

constexpr KeySpec face_area_keys[] = {
    {.key = "rectangle", .type = JsonType::object, .ref = "faceRectangle", .description = "the area: a rectangle by two opposite corners (default: the outline of the job's stock)"},
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length, .description = "or a closed profile: where it starts [x, y]"},
    {.key = "path", .type = JsonType::array, .ref = "contourElement", .min_items = 1, .description = "and its lines and arcs, ending at its start"},
    {.key = "profile", .type = JsonType::object, .ref = "profileSource", .description = "or a closed profile from a DXF drawing or a shape (rectangle, circle, slot, polygon)"},
};

constexpr KeySpec face_keys[] = {
    {.key = "overhang", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "2", .description = "how far the tool clears the area's edge at the rows' ends and beside the first and last rows"},
    {.key = "rows", .type = JsonType::string, .default_json = "\"both-ways\"", .choices = &choices_of<row_directions>, .description = "both-ways (linked beyond the edge) or one-way (the tool lifts before each return)"},
    {.key = "angle", .quantity = Quantity::angle, .default_json = "0", .description = "the rows' direction, degrees from +X"},
    {.key = "stepOver", .quantity = Quantity::length, .min = Bound{0, false}, .description = "mm between rows, at most the tool diameter (default: 70 % of it)"},
    {.key = "stepOverPercent", .min = Bound{0, false}, .max = Bound{100, true}, .description = "or stepOver as a percentage of the tool diameter"},
};

constexpr KeySpec face_finishing_keys[] = {
    {.key = "finishingStock", .quantity = Quantity::length, .min = Bound{0, false}, .description = "a finishing pass: the roughing passes stop this much above endDepth, then one pass at endDepth at finishingFeed"},
};

constexpr KeySpec face_rectangle_keys[] = {
    {.key = "corner", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "one corner [x, y]"},
    {.key = "oppositeCorner", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "the opposite corner [x, y]"},
};

// Rows beyond this many are refused: the area is far larger than the tool.
constexpr std::size_t max_face_rows = 200000;

// Is every point of the move from a to b within `reach` of the area (inside it, or that close to
// its edge)? Checked at points at most a tenth of the reach apart.
bool face_link_near(const Profile& area, const ProfileClearance& edge, Vec2 a, Vec2 b, double reach) {
    const double length = distance(a, b);
    const int n = std::max(1, static_cast<int>(std::ceil(length / (reach / 10))));
    for (int k = 0; k <= n; ++k) {
        const Vec2 p = a + (b - a) * (static_cast<double>(k) / n);
        if (edge.nearest(p).distance > reach + 1e-6 && !contains(area, p)) return false;
    }
    return true;
}

// Plans the rows: the hatch of the area grown by the tool radius and the overhang, in order.
void plan_face_rows(FaceOp& op, const JobInput& in, Fields& f) {
    const double reach = op.tool_radius + op.overhang;
    PlaneRegion area{op.area, {}};
    RegionOffset grown = grow_region(area, reach);
    if (grown.regions.empty()) f.fail("", "the area grown by the tool radius and the overhang is empty");
    std::vector<HatchRow> rows;
    for (const PlaneRegion& r : grown.regions) {
        std::vector<HatchRow> more = hatch_region(r, op.angle, op.step_over);
        rows.insert(rows.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
    }
    std::size_t count = 0;
    for (const HatchRow& r : rows) count += r.pieces.size();
    if (count > max_face_rows)
        f.fail(f.has("stepOver") ? "stepOver" : "stepOverPercent",
               fmt::format("the area needs more than {} rows: the step is far too small for it", max_face_rows));
    bool forward = true;
    for (const HatchRow& r : rows) {
        std::vector<std::pair<Vec2, Vec2>> pieces = r.pieces;
        if (op.rows == RowDirection::both_ways && !forward) {
            std::reverse(pieces.begin(), pieces.end());
            for (auto& [a, b] : pieces) std::swap(a, b);
        }
        for (const auto& piece : pieces) op.row_paths.push_back(piece);
        forward = !forward;
    }
    (void)in;
}

}  // namespace

std::vector<ObjectSpec> FaceOp::objects() {
    std::vector<KeySpec> keys = operation_head_keys();
    auto add = [&](const std::vector<KeySpec>& more) { keys.insert(keys.end(), more.begin(), more.end()); };
    add(height_keys(true));
    add({std::begin(face_area_keys), std::end(face_area_keys)});
    add({std::begin(face_keys), std::end(face_keys)});
    add(depth_pass_keys());
    add({std::begin(face_finishing_keys), std::end(face_finishing_keys)});
    add(cut_feed_keys());
    std::vector<ObjectSpec> out{
        {.name = "face", .description = "mill the stock top flat over a rectangle or a closed profile, in rows past its edges",
         .keys = keys,
         .groups = {{.keys = {"rectangle", "start", "profile"}, .min = 0, .max = 1, .description = "at most one of rectangle, start and path, or profile (none: the job's stock outline)"}}},
        {.name = "faceRectangle", .description = "a rectangle by two opposite corners", .keys = {std::begin(face_rectangle_keys), std::end(face_rectangle_keys)}},
    };
    for (ObjectSpec& o : cutting_objects()) out.push_back(std::move(o));
    return out;
}

FaceOp FaceOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, objects().front().keys);
    const Tool& tool = in.tool(f);
    check_cutting_tool(f, tool, "a face");
    FaceOp op;
    op.path = f.path();
    op.tool = tool.number;
    if (std::optional<std::string> note = untyped_milling_note(tool)) op.notes.push_back(std::move(*note));
    op.comment = f.optional_string("comment").value_or("");
    if (!(tool.diameter > 0)) f.fail("tool", fmt::format("tool {} has no diameter", tool.number));
    op.tool_radius = tool.diameter / 2;
    op.heights = read_heights(f, in, "pass");
    // A face's top is the stock's: it faces from there.
    const std::optional<Stock>& stock = in.header().stock;
    if (stock && stock->for_mill() && f.has("referencePlane") && std::abs(op.heights.reference_plane - stock->top()) > 1e-9)
        f.fail("referencePlane", fmt::format("referencePlane (Z {}) is not the stock top (Z {}, {}): a face starts at the "
                                             "stock top (leave referencePlane out to take it)",
                                             in.show(op.heights.reference_plane), in.show(stock->top()), stock->path));
    const Planes z = resolve_planes(op.heights);
    const double total_depth = z.reference_z - z.bottom_z;
    if (tool.flute_length && total_depth > *tool.flute_length)
        f.fail("endDepth", fmt::format("the face is {} deep below the reference plane, but tool {} has a fluteLength of {}",
                                       in.show(total_depth), tool.number, in.show(*tool.flute_length)));
    if (int{f.has("rectangle")} + int{f.has("start")} + int{f.has("profile")} > 1)
        f.fail("", "a face needs at most one of rectangle, start and path, or profile");
    if (!f.has("rectangle") && !f.has("start") && !f.has("profile")) {
        // The stock's outline, where the job gives a mill's stock.
        // A stock that failed to read is reported as such.
        if (!stock && in.root().is_object() && in.root().contains("stock"))
            throw FollowOnError(f.path(), "a face without an area faces the job's stock, which failed to read",
                                in.source().lines.line_of(f.path()), in.source().name);
        if (!stock || !stock->for_mill())
            f.fail("", stock ? "a face needs a rectangle, start and path, or a profile: the job's stock is a lathe's bar"
                             : "a face needs a rectangle, start and path, a profile, or a stock (box or profile) in the job to face");
        if (f.has("path")) f.fail("path", "path goes with start");
        op.area = stock->outline;
    } else if (f.has("rectangle")) {
        if (f.has("path")) f.fail("path", "path goes with start, not with rectangle");
        Fields r(f.required("rectangle"), f.path_of("rectangle"), in.source());
        JobInput::known_keys(r, face_rectangle_keys);
        const Vec2 a = in.point(r, "corner"), b = in.point(r, "oppositeCorner");
        if (!(std::abs(a.x - b.x) >= min_profile_segment && std::abs(a.y - b.y) >= min_profile_segment))
            r.fail("oppositeCorner", "the corners must differ in x and in y: the rectangle has no area");
        const Vec2 lo{std::min(a.x, b.x), std::min(a.y, b.y)}, hi{std::max(a.x, b.x), std::max(a.y, b.y)};
        op.area.start = lo;
        for (Vec2 p : {Vec2{hi.x, lo.y}, hi, Vec2{lo.x, hi.y}, lo}) op.area.segments.push_back({p, std::nullopt, ArcDirection::ccw});
    } else {
        op.area = read_profile(f, in, "a face's area", "start", "path", &op.notes);
        const std::string_view area_key = f.has("profile") ? "profile" : "path";
        if (!is_closed(op.area))
            f.fail(area_key, fmt::format("the area must be closed, but it ends at ({}, {}), not at its start ({}, {})",
                                       in.show(op.area.segments.back().end.x), in.show(op.area.segments.back().end.y),
                                       in.show(op.area.start.x), in.show(op.area.start.y)));
        // What the region geometry cannot grow (an arc's end a hair off its circle at a sharp
        // corner, crossing back): said as it is, not as an empty area later.
        if (const std::optional<RegionProblem> problem = region_problem(PlaneRegion{op.area, {}})) f.fail(area_key, problem->message);
    }
    op.overhang = in.optional_length(f, "overhang").value_or(2.0);
    if (!(op.overhang >= 0)) f.fail("overhang", "overhang must be >= 0");
    op.rows = f.choice("rows", row_directions, RowDirection::both_ways);
    op.angle = f.optional_number("angle").value_or(0.0);
    if (!std::isfinite(op.angle) || std::abs(op.angle) > 360) f.fail("angle", "angle must be from -360 to 360 degrees");
    std::string over_key;
    op.step_over = read_step_over(f, in, tool.diameter, 70.0, over_key);
    op.step_down = read_step_down(f, in, total_depth);
    op.equal_steps = f.boolean("equalSteps", true);
    op.finishing_stock = in.optional_length(f, "finishingStock").value_or(0.0);
    if (f.has("finishingStock") && !(op.finishing_stock > 0)) f.fail("finishingStock", "finishingStock must be > 0");
    if (op.finishing_stock >= total_depth)
        f.fail("finishingStock", fmt::format("finishingStock {} is not less than the depth faced ({})", in.show(op.finishing_stock),
                                             in.show(total_depth)));
    // The rows take the stepover each, the first beside the edge less: thinning by the stepover.
    op.feeds = read_cut_feeds(f, in, tool, op.step_over, op.notes);
    plan_face_rows(op, in, f);
    return op;
}

std::string default_name(const FaceOp& op) { return op.comment.empty() ? "face" : op.comment; }

void expand(const FaceOp& op, const Context& ctx, EventSink& sink) {
    CutSettings s;
    s.tool = op.tool;
    s.tool_radius = op.tool_radius;
    s.feeds = op.feeds;
    s.z = resolve_planes(op.heights);
    s.clearance = ctx.job.clearance;
    Cutter cutter(s, sink);
    const double reach = op.tool_radius + op.overhang;
    const ProfileClearance edge(op.area, reach + 1.0);
    const double rough_bottom = s.z.bottom_z + op.finishing_stock;
    std::vector<std::pair<double, Movement>> levels;
    for (double z : pass_depths(s.z.reference_z, rough_bottom, op.step_down, op.equal_steps)) levels.push_back({z, Movement::cutting});
    if (op.finishing_stock > 0) levels.push_back({s.z.bottom_z, Movement::finishing});
    for (const auto& [z, m] : levels) {
        const double feed = m == Movement::finishing ? op.feeds.finishing : op.feeds.cutting;
        bool down = false;
        for (const auto& [a, b] : op.row_paths) {
            const bool link = down && op.rows == RowDirection::both_ways && face_link_near(op.area, edge, {cutter.at().x, cutter.at().y}, a, reach);
            if (link) {
                cutter.feed_to({a.x, a.y, z}, feed, m);
            } else {
                // Up before the return (one-way), or over a gap; down beside the area, in the air.
                if (cutter.known()) cutter.retract(false);
                else cutter.rapid({a.x, a.y, s.clearance});
                cutter.rapid({a.x, a.y, s.z.retract_z});
                cutter.rapid({a.x, a.y, s.z.safe_z});
                cutter.feed_to({a.x, a.y, z}, op.feeds.plunge, Movement::plunge);
            }
            cutter.feed_to({b.x, b.y, z}, feed, m);
            down = true;
        }
    }
    cutter.retract(true);
}

}  // namespace camgen
