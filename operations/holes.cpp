#include "camgen/operations/holes.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/large_buffer.hpp"
#include "camgen/geometry/transform.hpp"
#include "camgen/operations/dxf_source.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

// Sanity bound for generated hole patterns, so a typo cannot exhaust memory.
constexpr double max_pattern_holes = 10'000'000;

// The keys of the hole sources, which operations list among their own.
constexpr KeySpec source_keys[] = {
    {.key = "order", .type = JsonType::string, .default_json = "\"as-given\"", .choices = &choices_of<hole_orders>,
     .description = "visit the holes in file order, or reorder them for a short rapid path"},
    {.key = "holes", .type = JsonType::array, .ref = "drillHole", .min_items = 1,
     .description = "holes, each [x, y] or {\"x\": x, \"y\": y}"},
    {.key = "grid", .type = JsonType::object, .ref = "drillGrid", .description = "a grid of holes"},
    {.key = "boltCircle", .type = JsonType::object, .ref = "drillBoltCircle", .description = "holes on a circle"},
    {.key = "line", .type = JsonType::object, .ref = "drillLine", .description = "holes evenly spaced along a line"},
    {.key = "drawing", .type = JsonType::object, .ref = "dxfSource",
     .description = "holes from a DXF drawing: the centres of its circles and its points, selected"},
};

// The keys of a hole given as an object.
constexpr KeySpec point_keys[] = {
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

void read_patterns(Fields& f, const JobInput& in, std::vector<HolePattern>& patterns);

// The holes of a list read straight into numbers: each [x, y] is already two numbers, so only
// the range of a length is checked, and a hole's path is made only for its message.
void read_packed_holes(const json::PackedArray& packed, Fields& f, const JobInput& in, std::vector<Vec2>& holes) {
    in.claim_holes(static_cast<double>(packed.size()), f, "holes");
    reserve_large(holes, holes.size() + packed.size());
    const std::string base = f.path_of("holes");
    for (std::size_t i = 0; i < packed.size(); ++i) {
        auto path = [&](int k) { return [&, k] { return fmt::format("{}/{}/{}", base, i, k); }; };
        holes.push_back({in.packed_coordinate(packed.x(i), path(0)), in.packed_coordinate(packed.y(i), path(1))});
    }
}

// The holes of the list are read at once (the document holds them already); the patterns are
// counted now and made later (make_pending_holes), once the whole job's count is known.
void read_holes(Fields& f, const JobInput& in, std::string_view op_type, std::vector<Vec2>& holes,
                std::vector<HolePattern>& patterns) {
    const bool any = f.has("holes") || f.has("grid") || f.has("boltCircle") || f.has("line") || f.has("drawing");
    if (!any)
        f.fail("", fmt::format("a {} operation needs holes: give at least one of holes, grid, boltCircle, "
                               "line or drawing (a DXF drawing's circles and points)",
                               op_type));

    if (f.has("holes")) {
        if (const json::PackedArray* packed = in.packed(f.required("holes"))) {
            read_packed_holes(*packed, f, in, holes);
            return read_patterns(f, in, patterns);
        }
        const Json& list = in.array(f, "holes");
        const std::string base = f.path_of("holes");
        in.claim_holes(static_cast<double>(list.size()), f, "holes");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string path = base + "/" + std::to_string(i);
            const Json& hole = list[i];
            if (hole.is_object()) {
                Fields h(hole, path, in.source());
                JobInput::known_keys(h, point_keys);
                holes.push_back({in.length(h, "x"), in.length(h, "y")});
            } else if (hole.is_array()) {
                holes.push_back(in.point(hole, path));
            } else {
                json::fail(in.source(), path,
                                   "expected a hole [x, y] or {\"x\": ..., \"y\": ...}, got " +
                                       JobInput::describe(hole));
            }
        }
        if (holes.empty()) f.fail("holes", fmt::format("holes is empty: a {} operation needs at least one hole", op_type));
    }
    read_patterns(f, in, patterns);
}

// The hole patterns (grid, boltCircle, line) of a hole source.
void read_patterns(Fields& f, const JobInput& in, std::vector<HolePattern>& patterns) {
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
            reserve_large(out, out.size() + static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
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
            reserve_large(out, out.size() + static_cast<std::size_t>(count));
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
            reserve_large(out, out.size() + static_cast<std::size_t>(count));
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
    std::vector<Vec2> order;
    reserve_large(order, n);
    order.push_back(holes[0]);
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

std::vector<KeySpec> hole_keys() { return {std::begin(source_keys), std::end(source_keys)}; }

KeyGroup hole_group(std::string_view description) {
    return {.keys = {"holes", "grid", "boltCircle", "line", "drawing"}, .min = 1, .max = 5, .description = description};
}

std::vector<ObjectSpec> hole_objects() {
    std::vector<ObjectSpec> out = dxf_source_objects();
    std::vector<ObjectSpec> own = {
        {.name = "drillHole", .description = "a hole {\"x\": x, \"y\": y} (or a point [x, y])",
         .keys = {std::begin(point_keys), std::end(point_keys)}, .also_point = true},
        {.name = "drillGrid", .description = "holes row by row, X fastest", .keys = {std::begin(grid_keys), std::end(grid_keys)}},
        {.name = "drillBoltCircle", .description = "holes counter-clockwise on a circle",
         .keys = {std::begin(bolt_circle_keys), std::end(bolt_circle_keys)}},
        {.name = "drillLine", .description = "holes evenly spaced from start to end",
         .keys = {std::begin(line_keys), std::end(line_keys)}},
    };
    for (ObjectSpec& o : own) out.push_back(std::move(o));
    return out;
}

HoleSet read_hole_set(Fields& f, const JobInput& in, std::string_view op_type) {
    HoleSet set;
    set.order = f.choice("order", hole_orders, HoleOrder::as_given);
    read_holes(f, in, op_type, set.holes, set.pending_patterns);
    // The drawing's holes after the list's (the patterns' follow in make_pending_holes).
    if (f.has("drawing")) {
        std::vector<Vec2> drawn = read_dxf_holes(f, in, "drawing", set.notes);
        set.holes.insert(set.holes.end(), drawn.begin(), drawn.end());
    }
    return set;
}

void make_pending_holes(HoleSet& set) {
    for (const HolePattern& make : set.pending_patterns) make(set.holes);
    set.pending_patterns.clear();
}

std::vector<Vec2> shortest_order(const std::vector<Vec2>& holes) {
    if (holes.size() < 3) return holes;
    std::vector<Vec2> order = nearest_neighbour(holes);
    if (order.size() <= max_two_opt_holes) two_opt(order);
    return order;
}

std::vector<Vec2> visit_order(const HoleSet& set) {
    std::vector<Vec2> storage;
    return visit_order(set, storage);
}

const std::vector<Vec2>& visit_order(const HoleSet& set, std::vector<Vec2>& storage) {
    if (set.order != HoleOrder::shortest) return set.holes;
    storage = shortest_order(set.holes);
    return storage;
}

}  // namespace camgen
