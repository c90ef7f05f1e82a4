#include "operations/drill/drill.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "camgen/common/error.hpp"
#include "camgen/geometry/transform.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

// Sanity bound for generated hole patterns, so a typo cannot exhaust memory.
constexpr double max_pattern_holes = 10'000'000;

// The keys of a drill operation besides the drilling fields (drill_fields), which follow them.
constexpr KeySpec drill_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "cycle", .type = JsonType::string, .default_json = "\"drill\"", .choices = &choices_of<cycle_kinds>,
     .description = "the drilling cycle"},
    {.key = "drillTip", .type = JsonType::boolean, .default_json = "false",
     .description = "add the tool's tip length (from diameter and tipAngle) to the depth"},
    {.key = "output", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<cycle_outputs>,
     .description = "canned cycle or plain moves: auto, canned or longhand"},
    {.key = "order", .type = JsonType::string, .default_json = "\"as-given\"", .choices = &choices_of<hole_orders>,
     .description = "drill the holes in file order, or reorder them for a short rapid path"},
    {.key = "holes", .type = JsonType::array, .ref = "drillHole", .min_items = 1,
     .description = "holes, each [x, y] or {\"x\": x, \"y\": y}"},
    {.key = "grid", .type = JsonType::object, .ref = "drillGrid", .description = "a grid of holes"},
    {.key = "boltCircle", .type = JsonType::object, .ref = "drillBoltCircle", .description = "holes on a circle"},
    {.key = "line", .type = JsonType::object, .ref = "drillLine", .description = "holes evenly spaced along a line"},
};

// The keys of a hole given as an object.
constexpr KeySpec hole_keys[] = {
    {.key = "x", .quantity = Quantity::length, .required = true, .description = "X of the hole"},
    {.key = "y", .quantity = Quantity::length, .required = true, .description = "Y of the hole"},
};

// The keys of a grid of holes.
constexpr KeySpec grid_keys[] = {
    {.key = "origin", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "the first hole [x, y]"},
    {.key = "countX", .type = JsonType::integer, .quantity = Quantity::count, .required = true,
     .min = Bound{1, true}, .description = "holes along X"},
    {.key = "countY", .type = JsonType::integer, .quantity = Quantity::count, .required = true,
     .min = Bound{1, true}, .description = "holes along Y"},
    {.key = "spacingX", .quantity = Quantity::length, .required = true, .description = "distance between columns"},
    {.key = "spacingY", .quantity = Quantity::length, .required = true, .description = "distance between rows"},
    {.key = "rotation", .quantity = Quantity::angle, .default_json = "0",
     .description = "counter-clockwise turn of the grid about origin"},
};

// The keys of a bolt circle.
constexpr KeySpec bolt_circle_keys[] = {
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "centre of the circle [x, y]"},
    {.key = "radius", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "radius of the circle"},
    {.key = "count", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "holes, 360/count degrees apart"},
    {.key = "startAngle", .quantity = Quantity::angle, .default_json = "0",
     .description = "angle of the first hole from +X, counter-clockwise"},
};

// The keys of a line of holes.
constexpr KeySpec line_keys[] = {
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "the first hole [x, y]"},
    {.key = "end", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "the last hole [x, y]"},
    {.key = "count", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "holes, evenly spaced including both ends"},
};

// A drilling field of the vocabulary's table as a key of the drill operation.
KeySpec key_of_field(const DrillFieldInfo& d) {
    KeySpec k{.key = d.key, .quantity = d.quantity, .min = d.min, .description = d.description};
    if (d.quantity == Quantity::choice) {
        k.type = JsonType::string;
        k.default_json = "\"none\"";
        k.choices = &choices_of<degression_types>;
    }
    return k;
}

// The keys of a drill operation: drill_keys with the heights after "cycle", then the drilling
// fields (safeDistance is one of them).
std::vector<KeySpec> all_drill_keys() {
    std::vector<KeySpec> keys(std::begin(drill_keys), std::end(drill_keys));
    const std::vector<KeySpec> heights = height_keys(false);
    keys.insert(keys.begin() + 4, heights.begin(), heights.end());
    for (const auto& d : drill_fields) keys.push_back(key_of_field(d));
    return keys;
}

// Per cycle kind: the drilling fields it needs and those it refuses; and the degression's
// partners (see read_degression).
std::vector<KeyRule> drill_rules() {
    std::vector<KeyRule> rules;
    for (const auto& kind : cycle_kinds) {
        KeyRule r{.when_key = "cycle", .values = {std::string(kind.name)}, .require = {}, .forbid = {}};
        for (const auto& d : drill_fields) {
            if (d.required_by.contains(kind.value)) r.require.push_back(d.key);
            if (!d.in_planes && !d.used_by.contains(kind.value)) r.forbid.push_back(d.key);
        }
        rules.push_back(std::move(r));
    }
    const std::string_view degression = key_of(DrillField::degression), minimum = key_of(DrillField::minimum_depth);
    rules.push_back({.when_key = key_of(DrillField::degression_type),
                     .values = {std::string(name_of(degression_types, DegressionType::none))},
                     .require = {},
                     .forbid = {degression, minimum}});
    rules.push_back({.when_key = key_of(DrillField::degression_type),
                     .values = {std::string(name_of(degression_types, DegressionType::value)),
                                std::string(name_of(degression_types, DegressionType::factor))},
                     .require = {degression, minimum},
                     .forbid = {key_of(DrillField::subsequent_depth)}});
    return rules;
}

// The fields a cycle kind uses, in table order ("plungingFeedrate, retractFeedrate, topDwell").
std::vector<std::string_view> fields_used_by(CycleKind kind) {
    std::vector<std::string_view> out;
    for (const auto& f : drill_fields)
        if (!f.in_planes && f.used_by.contains(kind)) out.push_back(f.key);
    return out;
}

// The holes of the list are read at once (the document holds them already); the patterns are
// counted now and made later (make_pending_holes), once the whole job's count is known.
void read_holes(Fields& f, const JobInput& in, std::vector<Vec2>& holes, std::vector<HolePattern>& patterns) {
    const bool any = f.has("holes") || f.has("grid") || f.has("boltCircle") || f.has("line");
    if (!any)
        f.fail("", "a drill operation needs holes: give at least one of holes, grid, boltCircle "
                   "or line");

    if (f.has("holes")) {
        const Json& list = in.array(f, "holes");
        const std::string base = f.path_of("holes");
        in.claim_holes(static_cast<double>(list.size()), f, "holes");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string path = base + "/" + std::to_string(i);
            const Json& hole = list[i];
            if (hole.is_object()) {
                Fields h(hole, path, in.source());
                JobInput::known_keys(h, hole_keys);
                holes.push_back({in.length(h, "x"), in.length(h, "y")});
            } else if (hole.is_array()) {
                holes.push_back(in.point(hole, path));
            } else {
                json::fail(in.source(), path,
                                   "expected a hole [x, y] or {\"x\": ..., \"y\": ...}, got " +
                                       JobInput::describe(hole));
            }
        }
        if (holes.empty()) f.fail("holes", "holes is empty: a drill operation needs at least one hole");
    }

    if (const Json* value = f.member("grid")) {
        Fields g(*value, f.path_of("grid"), in.source());
        JobInput::known_keys(g, grid_keys);
        const Vec2 origin = in.point(g, "origin");
        const int nx = g.integer("countX");
        if (nx < 1) g.fail("countX", "countX must be 1 or more");
        const int ny = g.integer("countY");
        if (ny < 1) g.fail("countY", "countY must be 1 or more");
        if (static_cast<double>(nx) * ny > max_pattern_holes)
            g.fail("", fmt::format("a grid of {} x {} holes is too many", nx, ny));
        in.claim_holes(static_cast<double>(nx) * ny, g, "");
        const double sx = in.length(g, "spacingX");
        const double sy = in.length(g, "spacingY");
        const Eigen::Isometry2d to_job = placement(origin, g.optional_number("rotation").value_or(0.0));
        patterns.push_back([=](std::vector<Vec2>& out) {
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) out.push_back(apply(to_job, {i * sx, j * sy}));
        });
    }

    if (const Json* value = f.member("boltCircle")) {
        Fields b(*value, f.path_of("boltCircle"), in.source());
        JobInput::known_keys(b, bolt_circle_keys);
        const Vec2 centre = in.point(b, "centre");
        const double radius = in.length(b, "radius");
        if (radius <= 0) b.fail("radius", "radius must be > 0");
        const int count = b.integer("count");
        if (count < 1) b.fail("count", "count must be 1 or more");
        if (count > max_pattern_holes) b.fail("count", "count is too large");
        in.claim_holes(count, b, "count");
        const double start = b.optional_number("startAngle").value_or(0.0);
        patterns.push_back([=](std::vector<Vec2>& out) {
            for (int i = 0; i < count; ++i) {
                const Vec2 u = unit_direction(start + 360.0 * i / count);
                out.push_back({centre.x + radius * u.x, centre.y + radius * u.y});
            }
        });
    }

    if (const Json* value = f.member("line")) {
        Fields l(*value, f.path_of("line"), in.source());
        JobInput::known_keys(l, line_keys);
        const Vec2 a = in.point(l, "start");
        const Vec2 b = in.point(l, "end");
        const int count = l.integer("count");
        if (count < 1) l.fail("count", "count must be 1 or more");
        if (count > max_pattern_holes) l.fail("count", "count is too large");
        in.claim_holes(count, l, "count");
        patterns.push_back([=](std::vector<Vec2>& out) {
            if (count == 1) {
                out.push_back(a);
                return;
            }
            for (int i = 0; i < count - 1; ++i) {
                const double t = static_cast<double>(i) / (count - 1);
                out.push_back({a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t});
            }
            out.push_back(b);  // exactly the end point, no rounding
        });
    }
}


// Reads one optional drilling field: presence, bounds and the cycle's need of it.
void read_field(Fields& f, const JobInput& in, const DrillFieldInfo& info, CycleKind kind, DrillValues& values) {
    if (info.quantity == Quantity::choice) return;  // degressionType: read with its partner
    const std::string_view key = info.key;
    std::optional<double> v = in.optional_quantity(f, key, info.quantity);
    if (!v && info.required_by.contains(kind))
        f.fail(key, fmt::format("cycle {} needs {}{}{}", name_of(cycle_kinds, kind), key,
                                info.required_hint.empty() ? "" : " ", info.required_hint));
    if (v && info.min && (info.min->inclusive ? *v < info.min->value : *v <= info.min->value)) {
        if (!info.bound_message.empty()) f.fail(key, std::string(info.bound_message));
        f.fail(key, fmt::format("{} must be {} {}", key, info.min->inclusive ? ">=" : ">", info.min->value));
    }
    values.set(info.field, v);
}

// degressionType and degression: a value in mm or a factor, bounded below by minimumDepth.
void read_degression(Fields& f, const JobInput& in, DrillValues& values) {
    const DegressionType type = f.choice("degressionType", degression_types, DegressionType::none);
    values.set_degression_type(type);
    const std::optional<double> degression = type == DegressionType::factor ? f.optional_number("degression")
                                                                            : in.optional_length(f, "degression");
    values.set(DrillField::degression, degression);
    const std::optional<double> minimum = values.get(DrillField::minimum_depth);
    switch (type) {
        case DegressionType::none:
            if (degression) f.fail("degression", "degression has no effect without degressionType");
            if (minimum) f.fail("minimumDepth", "minimumDepth has no effect without degressionType");
            break;
        case DegressionType::value:
            if (!degression || *degression <= 0)
                f.fail("degression", "degressionType value needs a degression > 0 (mm taken off each peck)");
            break;
        case DegressionType::factor:
            if (!degression || *degression <= 0 || *degression > 1)
                f.fail("degression",
                       "degressionType factor needs a degression with 0 < degression <= 1 (each "
                       "peck is the previous one times the factor)");
            break;
    }
    if (type != DegressionType::none && values.has(DrillField::subsequent_depth))
        f.fail("subsequentDepth", "subsequentDepth and a degression both set the later pecks: give one of them");
    if (type != DegressionType::none && !minimum)
        f.fail("degressionType",
               "a degression needs a positive minimumDepth, or the pecks shrink towards zero "
               "forever");
}

}  // namespace

std::vector<ObjectSpec> DrillOp::objects() {
    return {
        {.name = "drill", .description = "drill a list of holes with one cycle", .keys = all_drill_keys(),
         .groups = {{.keys = {"holes", "grid", "boltCircle", "line"}, .min = 1, .max = 4,
                     .description = "a drill operation needs holes"}},
         .rules = drill_rules()},
        {.name = "drillHole", .description = "a hole {\"x\": x, \"y\": y} (or a point [x, y])",
         .keys = {std::begin(hole_keys), std::end(hole_keys)}, .also_point = true},
        {.name = "drillGrid", .description = "holes row by row, X fastest", .keys = {std::begin(grid_keys), std::end(grid_keys)}},
        {.name = "drillBoltCircle", .description = "holes counter-clockwise on a circle",
         .keys = {std::begin(bolt_circle_keys), std::end(bolt_circle_keys)}},
        {.name = "drillLine", .description = "holes evenly spaced from start to end",
         .keys = {std::begin(line_keys), std::end(line_keys)}},
    };
}

DrillOp DrillOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, all_drill_keys());
    const Tool& tool = in.tool(f);

    DrillOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    DrillParams& p = op.params;

    p.kind = f.choice("cycle", cycle_kinds, CycleKind::drill);
    const std::string_view cycle_name = name_of(cycle_kinds, p.kind);
    // Of the parameters this cycle does not use, report the one that comes first in the file.
    std::optional<std::string_view> unused;
    int unused_line = 0;
    for (const auto& d : drill_fields) {
        if (d.in_planes || !f.has(d.key) || d.used_by.contains(p.kind)) continue;
        const int line = in.source().lines.line_of(f.path_of(d.key));
        if (!unused || line < unused_line) {
            unused = d.key;
            unused_line = line;
        }
    }
    if (unused) {
        const std::string_view key = *unused;
        std::string detail = fmt::format("{} is not used by cycle {} (it uses: {})", key, cycle_name,
                                         fmt::join(fields_used_by(p.kind), ", "));
        if (is_tapping(p.kind) && key == key_of(DrillField::plunging_feedrate)) detail += "; a tapping feed is pitch x rpm";
        f.fail(key, detail);
    }

    // Planes and depths.
    static_cast<Heights&>(p) = read_heights(f, in, "hole");

    // The optional fields, by the vocabulary's table; then the degression, which reads two.
    for (const auto& d : drill_fields)
        if (!d.in_planes) read_field(f, in, d, p.kind, p.values);
    read_degression(f, in, p.values);

    p.drill_tip = f.boolean("drillTip", false);
    if (p.drill_tip && !tool.tip_angle)
        f.fail("drillTip", fmt::format("drillTip needs the tool's tipAngle, but tool {} ({}) "
                                       "has none",
                                       tool.number, tool.path));
    p.output = f.choice("output", cycle_outputs, CycleOutput::automatic);
    op.order = f.choice("order", hole_orders, HoleOrder::as_given);

    read_holes(f, in, op.holes, op.pending_patterns);
    return op;
}

void make_pending_holes(DrillOp& op) {
    for (const HolePattern& make : op.pending_patterns) make(op.holes);
    op.pending_patterns.clear();
}

std::string default_name(const DrillOp& d) {
    return d.comment.empty() ? fmt::format("drill {} hole{}", d.holes.size(), d.holes.size() == 1 ? "" : "s")
                             : d.comment;
}


namespace {

double dist(Vec2 a, Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Nearest-neighbour order from holes[0], with a uniform grid so that large jobs stay fast
// (each step searches outwards ring by ring until no closer hole can exist).
std::vector<Vec2> nearest_neighbour(const std::vector<Vec2>& holes) {
    const size_t n = holes.size();
    double minx = holes[0].x, maxx = minx, miny = holes[0].y, maxy = miny;
    for (Vec2 h : holes) {
        minx = std::min(minx, h.x), maxx = std::max(maxx, h.x);
        miny = std::min(miny, h.y), maxy = std::max(maxy, h.y);
    }
    const double w = std::max(maxx - minx, 1e-9), hgt = std::max(maxy - miny, 1e-9);
    // About two holes per cell.
    const double cell = std::max(std::sqrt(w * hgt * 2.0 / static_cast<double>(n)), std::max(w, hgt) / 4096.0);
    const int nx = static_cast<int>(w / cell) + 1, ny = static_cast<int>(hgt / cell) + 1;
    auto cx = [&](Vec2 p) { return std::min(nx - 1, static_cast<int>((p.x - minx) / cell)); };
    auto cy = [&](Vec2 p) { return std::min(ny - 1, static_cast<int>((p.y - miny) / cell)); };
    std::vector<std::vector<size_t>> grid(static_cast<size_t>(nx) * ny);
    for (size_t i = 1; i < n; ++i) grid[static_cast<size_t>(cy(holes[i])) * nx + cx(holes[i])].push_back(i);
    std::vector<Vec2> order{holes[0]};
    order.reserve(n);
    Vec2 at = holes[0];
    for (size_t left = n - 1; left > 0; --left) {
        const int px = cx(at), py = cy(at);
        size_t best_cell = 0, best_slot = 0;
        double best = std::numeric_limits<double>::infinity();
        for (int r = 0; r <= std::max(nx, ny); ++r) {
            // Every hole outside ring r is at least r * cell away.
            if (best <= (r - 1) * cell) break;
            for (int y = py - r; y <= py + r; ++y) {
                if (y < 0 || y >= ny) continue;
                const bool edge = y == py - r || y == py + r;
                for (int x = px - r; x <= px + r; x += edge ? 1 : 2 * r) {
                    if (x >= 0 && x < nx) {
                        const size_t c = static_cast<size_t>(y) * nx + x;
                        for (size_t s = 0; s < grid[c].size(); ++s) {
                            const double d = dist(at, holes[grid[c][s]]);
                            if (d < best) best = d, best_cell = c, best_slot = s;
                        }
                    }
                    if (r == 0) break;
                }
            }
        }
        auto& bucket = grid[best_cell];
        at = holes[bucket[best_slot]];
        order.push_back(at);
        bucket[best_slot] = bucket.back();
        bucket.pop_back();
    }
    return order;
}

// 2-opt on an open path whose first point stays first: reverse p[i..j] while that shortens
// the path. O(n^2) per pass, so it runs only up to max_two_opt holes and a few passes.
void two_opt(std::vector<Vec2>& p) {
    const size_t n = p.size();
    for (int pass = 0; pass < 50; ++pass) {
        bool improved = false;
        for (size_t i = 1; i + 1 < n; ++i) {
            for (size_t j = i + 1; j < n; ++j) {
                double before = dist(p[i - 1], p[i]), after = dist(p[i - 1], p[j]);
                if (j + 1 < n) before += dist(p[j], p[j + 1]), after += dist(p[i], p[j + 1]);
                if (after < before - 1e-9) {
                    std::reverse(p.begin() + static_cast<long>(i), p.begin() + static_cast<long>(j) + 1);
                    improved = true;
                }
            }
        }
        if (!improved) break;
    }
}

}  // namespace

std::vector<Vec2> shortest_order(const std::vector<Vec2>& holes) {
    if (holes.size() < 3) return holes;
    std::vector<Vec2> order = nearest_neighbour(holes);
    if (order.size() <= max_two_opt_holes) two_opt(order);
    return order;
}

DrillCycle resolve_cycle(const DrillOp& op, const Tool& tool) {
    const DrillParams& p = op.params;
    const Planes z = resolve_planes(p);
    DrillCycle c;
    c.kind = p.kind;
    c.output = p.output;
    c.path = op.path;
    c.values = p.values;
    c.retract_z = z.retract_z;
    c.reference_z = z.reference_z;
    c.safe_z = z.safe_z;
    c.bottom_z = z.bottom_z;
    if (p.drill_tip && tool.tip_angle) c.bottom_z -= drill_tip_length(tool.diameter, *tool.tip_angle);
    c.spindle_rpm = tool.rpm;
    c.spindle_direction = tool.direction;
    c.feed = is_tapping(p.kind) ? p.values.value_or(DrillField::pitch, 0.0) *
                                      p.values.value_or(DrillField::tapping_speed, tool.rpm)
                                : p.values.value_or(DrillField::plunging_feedrate, 0.0);
    return c;
}

double drill_tip_length(double diameter, double tip_angle) {
    const double half = tip_angle * std::numbers::pi / 360.0;
    return diameter / 2.0 / std::tan(half);
}

void expand(const DrillOp& op, const Context& ctx, EventSink& sink) {
    if (op.holes.empty()) return;
    expand_cycle(resolve_cycle(op, ctx.tool), op.order == HoleOrder::shortest ? shortest_order(op.holes) : op.holes, ctx,
                 sink);
}

void expand_cycle(const DrillCycle& c, const std::vector<Vec2>& holes, const Context& ctx, EventSink& sink) {
    const Vec2 first = holes.front();
    sink.emit(Rapid{{first.x, first.y, ctx.job.clearance}});
    if (c.retract_z != ctx.job.clearance) sink.emit(Rapid{{first.x, first.y, c.retract_z}});
    sink.emit(c);
    for (const Vec2& h : holes) sink.emit(DrillPoint{h});
    sink.emit(DrillEnd{});
    const Vec2 last = holes.back();
    if (c.retract_z != ctx.job.clearance) sink.emit(Rapid{{last.x, last.y, ctx.job.clearance}});
}

}  // namespace camgen
