#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "operations/registry.hpp"

namespace camgen {

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
    DrillCycle c;
    c.kind = p.kind;
    c.output = p.output;
    c.path = op.path;
    c.params = p;
    c.retract_z = p.retract_plane;
    c.reference_z = p.reference_plane;
    c.safe_z = !p.safe_distance ? p.retract_plane
               : p.safe_distance_is_absolute ? *p.safe_distance
                                             : p.reference_plane + *p.safe_distance;
    c.bottom_z = p.end_depth_is_absolute ? p.end_depth : p.reference_plane - p.end_depth;
    if (p.drill_tip && tool.tip_angle) {
        // Tip length of a point of included angle a on diameter d: (d/2) / tan(a/2).
        double half = *tool.tip_angle * std::numbers::pi / 360.0;
        c.bottom_z -= tool.diameter / 2.0 / std::tan(half);
    }
    c.spindle_rpm = tool.rpm;
    c.spindle_direction = tool.direction;
    bool tapping = p.kind == CycleKind::tap || p.kind == CycleKind::tap_left;
    c.feed = tapping ? p.pitch.value_or(0.0) * p.tapping_speed.value_or(tool.rpm) : p.plunging_feedrate.value_or(0.0);
    return c;
}

void expand(const DrillOp& op, const Context& ctx, EventSink& sink) {
    if (op.holes.empty()) return;
    DrillCycle c = resolve_cycle(op, ctx.tool);
    const std::vector<Vec2> holes = op.order == HoleOrder::shortest ? shortest_order(op.holes) : op.holes;
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
