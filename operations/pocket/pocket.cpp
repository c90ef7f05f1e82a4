#include "camgen/operations/pocket/pocket.hpp"
#include "camgen/operations/dxf_source.hpp"
#include "camgen/operations/shapes.hpp"
#include "camgen/geometry/clearance.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/operations/part_guard.hpp"

// Planning a pocket. The rings of strategy offset are the boundaries of the region shrunk by
// d0 = radius + stockToLeave (+ radialStock while roughing), d0 + s, d0 + 2s, ... until nothing
// is left (offset_region). A point of the pocket at distance t >= d0 from its walls lies
// between the rings at d_k <= t < d_k + s, at t - d_k < s from ring k (the shrunk regions'
// boundaries are exactly that far apart): with s at most the tool radius every such point is
// cut, and a point nearer the wall than d0 is within the tool radius of ring 0 or is the stock
// left. So a stepOver above the radius is refused for rings. Rows (zigzag) s apart, s at most the
// diameter, cover every point of the shrunk region within s/2 of a row or of its boundary, which
// the cleanup ring follows. The rings nest as a tree (each shrunk region lies in one of the
// level before); inside-out cuts a tree's leaves first, outside-in its root.

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

constexpr KeySpec pocket_keys[] = {
    {.key = "islands", .type = JsonType::array, .ref = "pocketIsland", .description = "closed profiles inside the outline that stay standing"},
    {.key = "strategy", .type = JsonType::string, .default_json = "\"offset\"", .choices = &choices_of<pocket_strategies>, .description = "offset (rings) or zigzag (rows and a cleanup ring)"},
    {.key = "order", .type = JsonType::string, .default_json = "\"inside-out\"", .choices = &choices_of<pocket_orders>, .description = "offset: inside-out or outside-in"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"climb\"", .choices = &choices_of<cut_directions>, .description = "climb or conventional, against the walls and islands"},
    {.key = "stepOver", .quantity = Quantity::length, .min = Bound{0, false}, .description = "mm between rings or rows (default: 40 % of the tool diameter); at most the tool radius for offset, the diameter for zigzag"},
    {.key = "stepOverPercent", .min = Bound{0, false}, .max = Bound{100, true}, .description = "or stepOver as a percentage of the tool diameter"},
    {.key = "angle", .quantity = Quantity::angle, .default_json = "0", .description = "zigzag: the rows' direction, degrees from +X"},
    {.key = "rows", .type = JsonType::string, .default_json = "\"both-ways\"", .choices = &choices_of<row_directions>, .description = "zigzag: both-ways or one-way"},
    {.key = "stockToLeave", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0", .description = "radial stock left on every wall and island"},
};

constexpr KeySpec pocket_entry_keys[] = {
    {.key = "finishing", .type = JsonType::object, .ref = "contourFinishing", .description = "a floor pass (axialStock) and a finishing pass along the walls and islands (radialStock) at full depth"},
    {.key = "leadIn", .type = JsonType::object, .ref = "contourLead", .description = "how the finishing pass joins each wall"},
    {.key = "leadOut", .type = JsonType::object, .ref = "contourLead", .description = "how the finishing pass leaves each wall"},
    {.key = "ramp", .type = JsonType::object, .ref = "contourRamp", .description = "how the tool enters the material (default: a helix of the tool's radius at 5 degrees; see the fallbacks)"},
};

// The smallest helix camgen makes before it falls back to a ramp: a quarter of the tool radius.
constexpr double min_helix_share = 0.25;
// Rings or rows beyond this many per level are refused: the pocket is far larger than the tool.
constexpr std::size_t max_pocket_paths = 200000;
// A link at depth is at most this many tool diameters long.
constexpr double max_link_diameters = 2.0;
// The directions tried for a straight ramp line from a step's start.
constexpr int line_directions = 24;

// The pocket's loops (outline and islands) as clearances, to measure how far a tool-centre
// move stays from the walls.
class Walls {
public:
    Walls(const PlaneRegion& region, double reach) {
        clearances_.emplace_back(region.outer, reach);
        for (const Profile& island : region.islands) clearances_.emplace_back(island, reach);
    }
    double distance(const PathPiece& move) const {
        double d = 1e300;
        for (const ProfileClearance& c : clearances_) d = std::min(d, c.nearest(move).distance);
        return d;
    }
    double distance(Vec2 p) const { return distance(PathPiece{p, {p, std::nullopt, ArcDirection::ccw}}); }

private:
    std::vector<ProfileClearance> clearances_;
};

// A closed profile started at its vertex `k` (same path, same direction).
Profile started_at(const Profile& p, std::size_t k) {
    if (k == 0) return p;
    Profile out;
    out.plane = p.plane;
    out.start = segment_start(p, k);
    for (std::size_t i = 0; i < p.segments.size(); ++i) out.segments.push_back(p.segments[(k + i) % p.segments.size()]);
    out.segments.back().end = out.start;
    return out;
}

// A closed profile started in the middle of its longest line (a lead there joins a straight
// wall), or as it is when it has no line.
Profile started_mid_line(const Profile& p) {
    std::optional<std::size_t> longest;
    double best = 0.0;
    for (std::size_t k = 0; k < p.segments.size(); ++k)
        if (!p.segments[k].centre && distance(segment_start(p, k), p.segments[k].end) > best) {
            best = distance(segment_start(p, k), p.segments[k].end);
            longest = k;
        }
    if (!longest) return p;
    const Vec2 a = segment_start(p, *longest), b = p.segments[*longest].end;
    const Vec2 mid = (a + b) * 0.5;
    Profile out;
    out.plane = p.plane;
    out.start = mid;
    out.segments.push_back({b, std::nullopt, ArcDirection::ccw});
    for (std::size_t i = 1; i < p.segments.size(); ++i) out.segments.push_back(p.segments[(*longest + i) % p.segments.size()]);
    out.segments.push_back({mid, std::nullopt, ArcDirection::ccw});
    return out;
}

// The left normal of travel at the start of a path.
Vec2 start_left(const Profile& p) { return left_of(point_at(p, 0.0).tangent); }

// The ends of the segments of a region's loops.
std::vector<Vec2> region_vertices(const PlaneRegion& r) {
    std::vector<Vec2> out;
    for (const Profile* l : {&r.outer})
        for (const ProfileSegment& s : l->segments) out.push_back(s.end);
    for (const Profile& l : r.islands)
        for (const ProfileSegment& s : l.segments) out.push_back(s.end);
    return out;
}

// Where `p` lies along `loop` (mm from its start) and how far from it.
std::pair<double, double> position_on(const Profile& loop, Vec2 p) {
    double walked = 0.0, best = 1e300, at = 0.0;
    for (std::size_t k = 0; k < loop.segments.size(); ++k) {
        const Vec2 a = segment_start(loop, k);
        const ProfileSegment& s = loop.segments[k];
        Profile one;
        one.start = a;
        one.segments = {s};
        const double l = profile_length(one);
        double t = 0.0;  // mm along the segment
        if (!s.centre) {
            const Vec2 d = s.end - a;
            t = l > 0 ? std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0) * l : 0.0;
        } else {
            const Vec2 c = *s.centre;
            const double rho = distance(a, c);
            double turn = std::atan2(cross(a - c, p - c), dot(a - c, p - c));  // from a to p, counter-clockwise
            if (s.direction == ArcDirection::cw) turn = -turn;
            if (turn < 0) turn += two_pi;
            t = std::min(turn * rho, l);
        }
        const double d = distance(point_at(one, t).point, p);
        if (d < best) {
            best = d;
            at = walked + t;
        }
        walked += l;
    }
    return {at, best};
}

// A piece of the area's edge from `p` (on it), some tool radii long, for a ramp back and forth:
// nullopt when `p` is on no loop of it or the loop is shorter than 1.5 tool radii.
std::optional<Profile> edge_track(const PlaneRegion& area, Vec2 p, double tool_radius) {
    std::vector<const Profile*> loops{&area.outer};
    for (const Profile& i : area.islands) loops.push_back(&i);
    for (const Profile* l : loops) {
        const auto [at, off] = position_on(*l, p);
        if (off > 1e-6) continue;
        const double total = profile_length(*l);
        if (total < 1.5 * tool_radius) return std::nullopt;
        const double length = std::min(4 * tool_radius, 0.9 * total);
        Profile t = sub_profile(*l, at, std::fmod(at + length, total));
        t.start = p;
        return t;
    }
    return std::nullopt;
}

// Everything the planning needs.
struct PocketPlanner {
    const PocketOp& op;
    const JobInput& in;
    double wall = 0.0;           // how far the tool centre keeps from the walls while roughing
    double reach = 0.0;
    Walls walls;
    std::vector<std::string> notes;
    std::vector<PocketStep> steps;
    const PlaneRegion* area = nullptr;  // the area being cleared (its edge at the walls' distance)
    Vec2 at{};                   // where the tool is after the last step
    bool have_at = false;

    PocketPlanner(const PocketOp& o, const JobInput& i, double w, double r) : op(o), in(i), wall(w), reach(r), walls(o.region, r) {}

    // True when the straight move stays inside the tool-centre area.
    bool inside(Vec2 a, Vec2 b) const { return walls.distance(PathPiece{a, {b, std::nullopt, ArcDirection::ccw}}) >= wall - 1e-6; }

    // The entry at the start of `p` (`into`: a unit vector from its start into the area
    // where a helix may turn), `z_key` only names the ramp in messages.
    PocketEntry entry_at(const Profile& p, bool closed, Vec2 into, std::string& error) const {
        const Vec2 s = p.start;
        PocketEntry e;
        if (op.ramp.kind == Ramp::Kind::helix) {
            for (double rho = op.ramp.radius; rho >= op.tool_radius * min_helix_share - 1e-12; rho /= 2) {
                const Vec2 c = s + into * rho;
                if (inside(s, c) && walls.distance(c) >= wall + rho - 1e-6) {
                    e.kind = PocketEntry::Kind::helix;
                    e.radius = rho;
                    e.centre = c;
                    return e;
                }
            }
        }
        if (op.ramp.kind != Ramp::Kind::plunge) {
            // Along the path when the tool centre moves far enough on it to leave the floor under
            // its middle cut by its edge: a row the tool radius long, a ring as long as the
            // smallest helix (not a speck of a ring, which would take hundreds of laps on a spot).
            const double length = profile_length(p);
            if (length >= (closed ? two_pi * op.tool_radius * min_helix_share : op.tool_radius)) {
                e.kind = PocketEntry::Kind::along;
                return e;
            }
            // A path too short to ramp on: back and forth on a straight line from its start into
            // the pocket, at least the tool radius long (so that the tool's centre, which may not
            // cut, passes over floor its edge cut), the longer the fewer legs; in evenly spread
            // directions and towards the area's vertices (along a sliver). Else along the edge
            // of the area (a curved sliver's), which the start lies on.
            std::vector<Vec2> directions;
            for (int k = 0; k < line_directions; ++k) directions.push_back(rotated(into, two_pi * k / line_directions));
            if (area)
                for (Vec2 v : region_vertices(*area))
                    if (distance(v, s) >= op.tool_radius) directions.push_back((v - s) * (1.0 / distance(v, s)));
            for (double length_share : {4.0, 2.0, 1.0})
                for (Vec2 d : directions) {
                    const Vec2 end = s + d * (op.tool_radius * length_share);
                    if (inside(s, end)) {
                        e.kind = PocketEntry::Kind::track;
                        e.track.start = s;
                        e.track.segments = {{end, std::nullopt, ArcDirection::ccw}};
                        return e;
                    }
                }
            if (area)
                if (std::optional<Profile> t = edge_track(*area, s, op.tool_radius)) {
                    e.kind = PocketEntry::Kind::track;
                    e.track = std::move(*t);
                    return e;
                }
        }
        if (op.centre_cutting) {
            e.kind = PocketEntry::Kind::plunge;
            return e;
        }
        error = fmt::format("the tool cannot enter the pocket at ({}, {}): {}, and tool {} does not cut at its centre (give it "
                            "\"centreCutting\": true if it does)",
                            in.show(s.x), in.show(s.y),
                            op.ramp.kind == Ramp::Kind::plunge ? "the ramp is a plunge"
                                                               : fmt::format("there is no room for a helix of radius {} or more, nor "
                                                                             "a path, line or edge as long as the tool radius to ramp along",
                                                                             in.show(op.tool_radius * min_helix_share)),
                            op.tool);
        return e;
    }

    // Adds `p` as the next step, reached at depth from the tool's position when the link is
    // short and inside, else entered (a closed `p` is first started at the vertex nearest the
    // tool, or where a helix fits). `interior` is the side of travel the area lies on (+1 left,
    // -1 right) for a helix beside a ring; rows pass their own direction.
    void add(Profile p, bool closed, std::optional<Vec2> helix_into = std::nullopt, double interior = 1.0) {
        if (closed && have_at && p.segments.size() > 1) {
            std::size_t best = 0;
            double best_d = 1e300;
            for (std::size_t k = 0; k < p.segments.size(); ++k) {
                const double d = distance(segment_start(p, k), at);
                if (d < best_d) {
                    best_d = d;
                    best = k;
                }
            }
            p = started_at(p, best);
        }
        PocketStep step;
        step.closed = closed;
        const double link = have_at ? distance(at, p.start) : 1e300;
        step.stay_down = have_at && link <= max_link_diameters * 2 * op.tool_radius && inside(at, p.start);
        if (!step.stay_down) {
            std::string error;
            const Vec2 into = helix_into ? *helix_into : start_left(p) * interior;
            step.entry = entry_at(p, closed, into, error);
            if (!error.empty() && closed && p.segments.size() > 1) {
                // Another vertex of the ring may have room for the helix.
                for (std::size_t k = 1; k < p.segments.size() && !error.empty(); k += std::max<std::size_t>(1, p.segments.size() / 16)) {
                    Profile q = started_at(p, k);
                    std::string again;
                    const PocketEntry e = entry_at(q, closed, start_left(q) * interior, again);
                    if (again.empty()) {
                        p = std::move(q);
                        step.entry = e;
                        error.clear();
                    }
                }
            }
            if (!error.empty()) throw PlanError(op.ramp.kind == Ramp::Kind::plunge ? "ramp" : "tool", error);
            if (step.entry.kind == PocketEntry::Kind::helix && closed && p.segments.size() > 1) {
                // A smaller helix than asked for, or none: try the other vertices for the full one.
                if (step.entry.radius < op.ramp.radius - 1e-12)
                    for (std::size_t k = 1; k < p.segments.size(); k += std::max<std::size_t>(1, p.segments.size() / 16)) {
                        Profile q = started_at(p, k);
                        std::string again;
                        const PocketEntry e = entry_at(q, closed, start_left(q) * interior, again);
                        if (again.empty() && e.kind == PocketEntry::Kind::helix && e.radius > step.entry.radius) {
                            p = std::move(q);
                            step.entry = e;
                        }
                    }
            }
        }
        at = point_at(p, profile_length(p)).point;
        have_at = true;
        step.path = std::move(p);
        steps.push_back(std::move(step));
        if (steps.size() > max_pocket_paths)
            throw PlanError("stepOver", fmt::format("the pocket needs more than {} paths a level: the stepOver is far too small for it",
                                                    max_pocket_paths));
    }
};

// The regions of `r` shrunk by `d`, with the notes of the shrinking.
RegionOffset shrunk(const PlaneRegion& r, double d) { return offset_region(r, d); }

// A node of the ring tree: a shrunk region and the nodes of the next level inside it.
struct RingNode {
    PlaneRegion region;
    std::vector<std::size_t> children;
};

// The rings of strategy offset, as a forest: nodes of all levels, the roots' indices.
struct RingForest {
    std::vector<RingNode> nodes;
    std::vector<std::size_t> roots;
};

RingForest ring_forest(const PlaneRegion& region, double d0, double s, std::vector<std::string>& notes) {
    RingForest forest;
    std::vector<std::size_t> level;  // the previous level's nodes
    std::size_t paths = 0;
    for (int k = 0;; ++k) {
        RegionOffset o = shrunk(region, d0 + k * s);
        if (k == 0)
            for (const RegionNote& n : o.notes) notes.push_back(n.message);
        if (o.regions.empty()) break;
        std::vector<std::size_t> next;
        for (PlaneRegion& r : o.regions) {
            paths += 1 + r.islands.size();
            if (paths > max_pocket_paths)
                throw PlanError("stepOver", fmt::format("the pocket needs more than {} rings: the stepOver is far too small for it",
                                                        max_pocket_paths));
            const std::size_t id = forest.nodes.size();
            const Vec2 probe = r.outer.start;
            forest.nodes.push_back({std::move(r), {}});
            std::optional<std::size_t> parent;
            for (std::size_t p : level)
                if (region_contains(forest.nodes[p].region, probe)) {
                    parent = p;
                    break;
                }
            if (parent) forest.nodes[*parent].children.push_back(id);
            else forest.roots.push_back(id);
            next.push_back(id);
        }
        level = std::move(next);
    }
    return forest;
}

// The loops of a region in the direction the tool walks them: outer counter-clockwise and
// islands clockwise (the area on the left) when `area_left`, else reversed.
std::vector<Profile> walked_loops(const PlaneRegion& r, bool area_left) {
    std::vector<Profile> loops{r.outer};
    loops.insert(loops.end(), r.islands.begin(), r.islands.end());
    if (!area_left)
        for (Profile& l : loops) l = reversed(l);
    return loops;
}

void plan_offset(PocketPlanner& planner, const PocketOp& op, double d0) {
    RingForest forest = ring_forest(op.region, d0, op.step_over, planner.notes);
    if (forest.roots.empty())
        throw PlanError("path", fmt::format("the tool (radius {}) with the stock left does not fit in the pocket", planner.in.show(op.tool_radius)));
    // The material a ring cuts lies towards the walls (inside-out) or towards the middle
    // (outside-in); the tool is left of its travel for climb with M3. A ring walked with the
    // area on its left has the walls on its right.
    const bool walls_right = op.order == PocketOrder::inside_out;
    const bool area_left = walls_right == op.tool_left;
    const double interior = area_left ? 1.0 : -1.0;
    auto cut_node = [&](std::size_t id) {
        planner.area = &forest.nodes[id].region;
        for (Profile& l : walked_loops(forest.nodes[id].region, area_left)) planner.add(std::move(l), true, std::nullopt, interior);
    };
    // Depth first: inside-out leaves first (post-order), outside-in the root first (pre-order).
    auto visit = [&](auto&& self, std::size_t id) -> void {
        if (op.order == PocketOrder::outside_in) cut_node(id);
        for (std::size_t c : forest.nodes[id].children) self(self, c);
        if (op.order == PocketOrder::inside_out) cut_node(id);
    };
    for (std::size_t root : forest.roots) visit(visit, root);
}

void plan_zigzag(PocketPlanner& planner, const PocketOp& op, double d0) {
    RegionOffset area = shrunk(op.region, d0);
    for (const RegionNote& n : area.notes) planner.notes.push_back(n.message);
    if (area.regions.empty())
        throw PlanError("path", fmt::format("the tool (radius {}) with the stock left does not fit in the pocket", planner.in.show(op.tool_radius)));
    const Vec2 along = unit_at(op.angle * rad_per_deg);
    for (const PlaneRegion& r : area.regions) {
        planner.area = &r;
        std::vector<HatchRow> rows = hatch_region(r, op.angle, op.step_over);
        // Each row's pieces not cut yet, walked from `a` to `b` along the row direction.
        std::vector<std::vector<std::pair<Vec2, Vec2>>> left;
        std::size_t remaining = 0;
        for (HatchRow& row : rows) {
            remaining += row.pieces.size();
            left.push_back(std::move(row.pieces));
        }
        auto piece_profile = [](Vec2 a, Vec2 b) {
            Profile p;
            p.start = a;
            p.segments.push_back({b, std::nullopt, ArcDirection::ccw});
            return p;
        };
        while (remaining > 0) {
            // A chunk: the first row with a piece left, its first piece, then a piece of each
            // next row that a link at depth (both-ways) or a drop onto the cleared floor
            // (one-way) reaches.
            std::size_t i = 0;
            while (left[i].empty()) ++i;
            std::pair<Vec2, Vec2> piece = left[i].front();
            left[i].erase(left[i].begin());
            --remaining;
            bool forward = true;
            planner.add(piece_profile(piece.first, piece.second), false, along);
            for (;;) {
                const std::size_t next_row = i + 1;
                if (next_row >= left.size() || left[next_row].empty()) break;
                const Vec2 end = planner.at;
                std::optional<std::size_t> pick;
                double best = 1e300;
                for (std::size_t k = 0; k < left[next_row].size(); ++k) {
                    const auto& [a, b] = left[next_row][k];
                    const Vec2 start = op.rows == RowDirection::one_way ? a : (forward ? b : a);
                    const double d = distance(end, start);
                    if (d < best) {
                        best = d;
                        pick = k;
                    }
                }
                const auto [a, b] = left[next_row][*pick];
                if (op.rows == RowDirection::both_ways) {
                    const Vec2 start = forward ? b : a;
                    if (!(best <= max_link_diameters * 2 * op.tool_radius && planner.inside(end, start))) break;
                    forward = !forward;
                    planner.add(forward ? piece_profile(a, b) : piece_profile(b, a), false, forward ? along : along * -1.0);
                } else {
                    // One way: the tool lifts and comes down at the next row's start, which
                    // must lie on floor the row before cleared.
                    const Vec2 prev_a = piece.first, prev_b = piece.second;
                    const ClosestApproach c = point_piece_distance(a, PathPiece{prev_a, {prev_b, std::nullopt, ArcDirection::ccw}});
                    if (c.distance > 0.9 * op.tool_radius) break;
                    PocketStep step;
                    step.path = piece_profile(a, b);
                    step.entry.kind = PocketEntry::Kind::drop;
                    planner.steps.push_back(step);
                    planner.at = b;
                }
                piece = {a, b};
                left[next_row].erase(left[next_row].begin() + static_cast<std::ptrdiff_t>(*pick));
                --remaining;
                i = next_row;
            }
        }
        // The cleanup ring along the walls and islands, walked against them.
        for (Profile& l : walked_loops(r, op.tool_left)) planner.add(std::move(l), true, std::nullopt, op.tool_left ? 1.0 : -1.0);
    }
}

// The corners of the outline and the islands the tool cannot reach: a sharp corner with the
// air on its inside leaves a fillet of the tool radius (plus the stock).
void note_corners(const PocketOp& op, const JobInput& in, double d, std::vector<std::string>& notes) {
    struct Corner {
        std::string where;
        Vec2 at;
        double angle;
        double deep;
    };
    std::vector<Corner> corners;
    auto scan = [&](const Profile& p, bool air_left, const std::string& base) {
        const std::size_t n = p.segments.size();
        for (std::size_t k = 0; k < n; ++k) {
            // The corner at the end of segment k.
            Profile one;
            one.start = segment_start(p, k);
            one.segments = {p.segments[k]};
            const Vec2 t_in = point_at(one, profile_length(one)).tangent;
            Profile two;
            two.start = p.segments[k].end;
            two.segments = {p.segments[(k + 1) % n]};
            const Vec2 t_out = point_at(two, 0.0).tangent;
            const double turn = std::atan2(cross(t_in, t_out), dot(t_in, t_out));
            // The air turns away from the corner: a convex corner of the air.
            const bool convex = air_left ? turn > 1e-6 : turn < -1e-6;
            if (!convex) continue;
            if (d / std::sin((pi - std::abs(turn)) / 2) - d < 0.001) continue;  // a joint a thousandth off tangent
            const double inner = pi - std::abs(turn);  // the corner's angle, radians
            const double deep = d / std::sin(inner / 2) - d;
            corners.push_back({fmt::format("{}/{}", base, (k + 1) % n), p.segments[k].end, inner * deg_per_rad, deep});
        }
    };
    const bool outer_ccw = orientation(op.region.outer) == Orientation::ccw;
    scan(op.region.outer, outer_ccw, op.path + "/path");
    for (std::size_t i = 0; i < op.region.islands.size(); ++i) {
        const bool ccw = orientation(op.region.islands[i]) == Orientation::ccw;
        scan(op.region.islands[i], !ccw, fmt::format("{}/islands/{}/path", op.path, i));
    }
    if (corners.empty()) return;
    std::sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) { return a.deep > b.deep; });
    std::string list;
    for (std::size_t k = 0; k < corners.size() && k < 4; ++k)
        list += fmt::format("{}{} ({}, {}): {} degrees, {} deep", k ? "; " : "", corners[k].where, number_text(corners[k].at.x, 3),
                            number_text(corners[k].at.y, 3), fmt::format("{:.0f}", corners[k].angle), in.show(corners[k].deep));
    notes.push_back(fmt::format("{} corner{} the tool cannot reach: it leaves a fillet of radius {} in each, with material up to the "
                                "depth given from the corner ({}{})",
                                corners.size(), corners.size() == 1 ? "" : "s", in.show(d), list,
                                corners.size() > 4 ? fmt::format("; and {} more", corners.size() - 4) : ""));
}

// The pocket's settings for the cutter.
CutSettings pocket_settings(const PocketOp& op, const JobHeader& job) {
    CutSettings s;
    s.tool = op.tool;
    s.tool_radius = op.tool_radius;
    s.tool_left = op.tool_left;
    s.compensation = CompensationMode::computer;
    s.lead_in = op.lead_in;
    s.lead_out = op.lead_out;
    s.ramp = op.ramp;
    s.feeds = op.feeds;
    s.z = resolve_planes(op.heights);
    s.clearance = job.clearance;
    return s;
}

// A closed profile started in the middle of its segment `k` (same path, same direction).
Profile started_mid(const Profile& p, std::size_t k) {
    Profile one;
    one.start = segment_start(p, k);
    one.segments = {p.segments[k]};
    const Vec2 mid = point_at(one, profile_length(one) / 2).point;
    const ProfileSegment& s = p.segments[k];
    Profile out;
    out.plane = p.plane;
    out.start = mid;
    out.segments.push_back(s);
    for (std::size_t i = 1; i < p.segments.size(); ++i) out.segments.push_back(p.segments[(k + i) % p.segments.size()]);
    out.segments.push_back({mid, s.centre, s.direction});
    return out;
}

// The finishing pass along `loop` (a tool-centre loop of the walls' offset, from its given
// start) with leads that have room: the tool goes down where the lead-in starts, in the pocket
// the roughing cleared (at least the radius, the stock and the radial stock from every wall
// and island), and no point of either lead comes nearer the walls than the loop itself (the
// radius and the stock). Tried in order: the job's leads at the loop's start, in the middle of
// each segment (the longest first) and at each vertex; then the leads at half and a quarter
// of their size; then all of it again with the tool going down anywhere the loop keeps (a line
// lead along the loop's own tangent starts there, beside the radial stock); then no leads (the
// tool goes down on the loop). The first that fits is taken.
PocketFinish fit_leads(const PocketOp& op, const JobInput& in, const PocketPlanner& planner, Profile loop) {
    const double radial = op.finishing ? op.finishing->radial_stock : 0.0;
    const double keep = op.tool_radius + op.stock_to_leave - 1e-6;
    CutSettings probe = pocket_settings(op, in.header());
    EventRecorder nowhere;
    const Cutter cutter(probe, nowhere);
    auto clear = [&](const Profile& lead, double need) {
        Vec2 at = lead.start;
        if (planner.walls.distance(at) < need) return false;
        for (const ProfileSegment& s : lead.segments) {
            if (planner.walls.distance(PathPiece{at, s}) < need) return false;
            at = s.end;
        }
        return true;
    };
    std::vector<Profile> starts{loop};
    std::vector<std::size_t> order(loop.segments.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::vector<double> lengths;
    for (std::size_t k = 0; k < loop.segments.size(); ++k) {
        Profile one;
        one.start = segment_start(loop, k);
        one.segments = {loop.segments[k]};
        lengths.push_back(profile_length(one));
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lengths[a] > lengths[b]; });
    for (std::size_t k : order)
        if (lengths[k] > 0.01) starts.push_back(started_mid(loop, k));
    for (std::size_t k = 1; k < loop.segments.size(); ++k) starts.push_back(started_at(loop, k));
    auto scaled = [](Lead l, double f) {
        l.radius *= f;
        l.length *= f;
        return l;
    };
    // First where the tool goes down in cleared pocket, else (a lead along the loop's own line,
    // say) beside the radial stock.
    for (double down : {keep + radial, keep})
        for (double f : {1.0, 0.5, 0.25}) {
            probe.lead_in = scaled(op.lead_in, f);
            probe.lead_out = scaled(op.lead_out, f);
            for (const Profile& p : starts) {
                const Profile lead_in = cutter.lead_in(p), lead_out = cutter.lead_out(p);
                if (planner.walls.distance(lead_in.start) >= down && clear(lead_in, keep) && clear(lead_out, keep))
                    return {p, probe.lead_in, probe.lead_out};
            }
        }
    return {std::move(loop), Lead{}, Lead{}};
}

// A note for the finishing loops that got shorter leads than the job's, or none.
void note_leads(const PocketOp& op, std::vector<std::string>& notes) {
    const bool asked = op.lead_in.kind != Lead::Kind::none || op.lead_out.kind != Lead::Kind::none;
    std::size_t shorter = 0, none = 0;
    for (const PocketFinish& f : op.finish_loops) {
        const bool without = f.lead_in.kind == Lead::Kind::none && f.lead_out.kind == Lead::Kind::none;
        if (asked && without) ++none;
        else if (f.lead_in.radius < op.lead_in.radius - 1e-12 || f.lead_in.length < op.lead_in.length - 1e-12 ||
                 f.lead_out.radius < op.lead_out.radius - 1e-12 || f.lead_out.length < op.lead_out.length - 1e-12)
            ++shorter;
    }
    if (shorter > 0)
        notes.push_back(fmt::format("{} finishing pass{} along the walls and islands enter{} or leave{} with leads shorter than the job's: "
                                    "no room for them",
                                    shorter, shorter == 1 ? "" : "es", shorter == 1 ? "s" : "", shorter == 1 ? "s" : ""));
    if (none > 0)
        notes.push_back(fmt::format("{} finishing pass{} along the walls and islands {} without leads: no room for them", none,
                                    none == 1 ? "" : "es", none == 1 ? "goes" : "go"));
}

// One depth level: every step at `z`, the floor at `z_prev` cleared above it.
void cut_level(Cutter& cutter, const CutSettings& s, const PocketOp& op, double z_prev, double z, Movement m, double feed) {
    for (const PocketStep& step : op.steps) {
        const Vec2 a = step.path.start;
        if (step.stay_down && cutter.known()) {
            cutter.feed_to({a.x, a.y, z}, feed, m);
        } else {
            if (cutter.known()) cutter.retract(false);
            else cutter.rapid({a.x, a.y, s.clearance});
            cutter.rapid({a.x, a.y, s.z.retract_z});
            cutter.rapid({a.x, a.y, s.z.safe_z});
            // Down through what the level before cleared (the same place), then into the material.
            if (cutter.at().z > z_prev) cutter.feed_to({a.x, a.y, z_prev}, op.feeds.plunge, Movement::plunge);
            switch (step.entry.kind) {
                case PocketEntry::Kind::helix: {
                    const Vec2 away = (step.entry.centre - a) * (1.0 / step.entry.radius);
                    cutter.go_down(z, away, step.entry.radius);
                    break;
                }
                case PocketEntry::Kind::along: {
                    const double drop = cutter.at().z - z;
                    if (drop <= 0) break;
                    const double need = drop / std::tan(op.ramp.angle * rad_per_deg);
                    const double length = profile_length(step.path);
                    if (step.closed) {
                        const int laps = std::max(1, static_cast<int>(std::ceil(need / length - 1e-9)));
                        const double top = cutter.at().z;
                        for (int k = 0; k < laps; ++k)
                            cutter.follow(step.path, top - drop * k / laps, top - drop * (k + 1) / laps, op.feeds.ramp, Movement::ramp);
                    } else {
                        // Back and forth along the row, an even number of legs.
                        int legs = std::max(2, static_cast<int>(std::ceil(need / length - 1e-9)));
                        if (legs % 2) ++legs;
                        const double top = cutter.at().z;
                        const Profile back = reversed(step.path);
                        for (int k = 0; k < legs; ++k)
                            cutter.follow(k % 2 ? back : step.path, top - drop * k / legs, top - drop * (k + 1) / legs, op.feeds.ramp,
                                          Movement::ramp);
                    }
                    break;
                }
                case PocketEntry::Kind::track: {
                    // Back and forth on the track from the start, an even number of legs.
                    const double drop = cutter.at().z - z;
                    if (drop <= 0) break;
                    const double need = drop / std::tan(op.ramp.angle * rad_per_deg);
                    int legs = std::max(2, static_cast<int>(std::ceil(need / profile_length(step.entry.track) - 1e-9)));
                    if (legs % 2) ++legs;
                    const Profile back = reversed(step.entry.track);
                    const double top = cutter.at().z;
                    for (int k = 0; k < legs; ++k)
                        cutter.follow(k % 2 ? back : step.entry.track, top - drop * k / legs, top - drop * (k + 1) / legs, op.feeds.ramp,
                                      Movement::ramp);
                    break;
                }
                case PocketEntry::Kind::plunge:
                case PocketEntry::Kind::drop: cutter.feed_to({a.x, a.y, z}, op.feeds.plunge, Movement::plunge); break;
            }
        }
        cutter.follow(step.path, z, z, feed, m);
    }
}

// The whole pocket: the roughing levels, the floor, the walls. `guard`: the part check the
// events go to (it is also `sink`), told what each part keeps.
void cut_pocket(const PocketOp& op, const JobHeader& job, EventSink& sink, PartGuard* guard = nullptr) {
    const CutSettings settings = pocket_settings(op, job);
    Cutter cutter(settings, sink);
    const Planes& z = settings.z;
    const double radial = op.finishing ? op.finishing->radial_stock : 0.0;
    const double axial = op.finishing ? op.finishing->axial_stock : 0.0;
    const double rough_bottom = z.bottom_z + axial;
    if (guard) guard->keep(op.stock_to_leave + radial, rough_bottom);
    double z_prev = z.reference_z;
    for (double level : pass_depths(z.reference_z, rough_bottom, op.step_down, op.equal_steps)) {
        cut_level(cutter, settings, op, z_prev, level, Movement::cutting, op.feeds.cutting);
        z_prev = level;
    }
    if (axial > 0) {
        if (guard) guard->keep(op.stock_to_leave + radial, z.bottom_z);
        cut_level(cutter, settings, op, z_prev, z.bottom_z, Movement::finishing, op.feeds.finishing);
    }
    if (op.finish_loops.empty()) {
        cutter.retract(true);
        return;
    }
    // The walls: the tool goes down in the cleared pocket beside each.
    if (guard) guard->keep(op.stock_to_leave, z.bottom_z);
    CutSettings walls = settings;
    walls.ramp = Ramp{};
    Cutter finisher(walls, sink);
    cutter.retract(false);
    const std::vector<double> depths = pass_depths(z.reference_z, z.bottom_z, op.finishing->step_down, op.equal_steps);
    for (std::size_t k = 0; k < op.finish_loops.size(); ++k) {
        if (k == 0) finisher.continue_from(cutter.at());
        // The finisher reads its settings by reference: each loop's own leads.
        walls.lead_in = op.finish_loops[k].lead_in;
        walls.lead_out = op.finish_loops[k].lead_out;
        finisher.cut_run(op.finish_loops[k].path, true, depths, Movement::finishing, op.feeds.finishing, k + 1 == op.finish_loops.size());
    }
}

void guard_pocket(const PocketOp& op, Fields& f, const JobInput& in) {
    GuardedPart part;
    part.profile = &op.region.outer;
    part.material_inside = false;
    for (const Profile& island : op.region.islands) part.islands.push_back(&island);
    part.tool_radius = op.tool_radius;
    part.top_z = resolve_planes(op.heights).reference_z;
    PartGuard guard(part);
    cut_pocket(op, in.header(), guard, &guard);
    const std::optional<Violation>& v = guard.violation();
    if (!v) return;
    std::string key = "path";
    std::string hint = "please report it: camgen planned a move into the part";
    switch (v->rapid ? Movement::cutting : v->movement) {
        case Movement::lead_in: key = "leadIn"; hint = "give a shorter or different leadIn"; break;
        case Movement::lead_out: key = "leadOut"; hint = "give a shorter or different leadOut"; break;
        case Movement::ramp: key = "ramp"; hint = "give a smaller ramp radius or another ramp"; break;
        case Movement::plunge:
        case Movement::cutting:
        case Movement::finishing: break;
    }
    if (!f.has(key)) key = "";
    f.fail(key, fmt::format("the {} {}: {}", movement_words(v->movement, v->rapid), v->what, hint));
}

// A closed profile of the outline or an island, read and checked.
Profile read_loop(Fields& f, const JobInput& in, std::string_view what) {
    Profile p = read_profile(f, in, what);
    if (!is_closed(p))
        f.fail("path", fmt::format("{} must be closed, but it ends at ({}, {}), not at its start ({}, {})", what,
                                   in.show(p.segments.back().end.x), in.show(p.segments.back().end.y), in.show(p.start.x),
                                   in.show(p.start.y)));
    return p;
}

// The outline and islands of a pocket from a drawing: the one outermost closed profile, and
// the closed profiles directly inside it (those inside an island are left standing with it).
void read_drawn_region(Fields& f, const JobInput& in, PocketOp& op) {
    const DxfProfiles d = read_dxf_profiles(f, in, "profile", read_tolerance(f, in).value_or(0.01), op.notes);
    std::vector<std::size_t> outer;
    for (std::size_t i = 0; i < d.profiles.size(); ++i) {
        if (!d.closed[i])
            f.fail("profile", fmt::format("a pocket needs closed profiles, but the one from {} is open (its ends are {} apart, more "
                                          "than gapTolerance): close it in the drawing or raise gapTolerance",
                                          d.describe[i], in.show(distance(d.profiles[i].start, d.profiles[i].segments.back().end))));
        if (d.parent[i] < 0) outer.push_back(i);
    }
    if (outer.size() != 1)
        f.fail("profile", fmt::format("a pocket takes one outline, but the selection holds {} closed profiles side by side (the first "
                                      "from {}): select one by layer, colour, linetype or block",
                                      outer.size(), d.describe[outer[0]]));
    for (std::size_t i = 0; i < d.profiles.size(); ++i) {
        if (!is_simple(d.profiles[i])) f.fail("profile", fmt::format("the profile from {} crosses or touches itself", d.describe[i]));
        if (i == outer[0]) op.region.outer = d.profiles[i];
        else if (d.parent[i] == static_cast<int>(outer[0])) op.region.islands.push_back(d.profiles[i]);
        else
            op.notes.push_back(fmt::format("{}/profile: the profile from {} lies inside an island: left standing with it", op.path,
                                           d.describe[i]));
    }
}

constexpr KeySpec island_keys[] = {
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length, .description = "where the island's profile starts [x, y]"},
    {.key = "path", .type = JsonType::array, .ref = "contourElement", .min_items = 1, .description = "the island's lines and arcs, ending at its start"},
    {.key = "profile", .type = JsonType::object, .ref = "profileSource", .description = "or the island as a shape (rectangle, circle, slot, polygon) or from a DXF drawing (one closed profile)"},
};

}  // namespace

std::vector<ObjectSpec> PocketOp::objects() {
    std::vector<KeySpec> keys = operation_head_keys();
    auto add = [&](const std::vector<KeySpec>& more) { keys.insert(keys.end(), more.begin(), more.end()); };
    add(height_keys(true));
    add(profile_keys("pocket"));
    add({std::begin(pocket_keys), std::end(pocket_keys)});
    add(depth_pass_keys());
    add({std::begin(pocket_entry_keys), std::end(pocket_entry_keys)});
    add(cut_feed_keys());
    add(tolerance_keys());
    std::vector<ObjectSpec> out{
        {.name = "pocket", .description = "clear the material inside a closed outline and around islands, in depth passes", .keys = keys,
         .groups = {{.keys = {"start", "profile"}, .min = 1, .max = 1, .description = "start and path, or profile"}}},
        {.name = "pocketIsland", .description = "an island: a closed profile of lines and arcs, a shape or from a drawing", .keys = {std::begin(island_keys), std::end(island_keys)},
         .groups = {{.keys = {"start", "profile"}, .min = 1, .max = 1, .description = "start and path, or profile"}}},
    };
    for (ObjectSpec& o : cutting_objects()) out.push_back(std::move(o));
    return out;
}

PocketOp PocketOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, objects().front().keys);
    const Tool& tool = in.tool(f);
    check_cutting_tool(f, tool, "a pocket");
    PocketOp op;
    op.path = f.path();
    op.tool = tool.number;
    if (std::optional<std::string> note = untyped_milling_note(tool)) op.notes.push_back(std::move(*note));
    op.comment = f.optional_string("comment").value_or("");
    if (!(tool.diameter > 0)) f.fail("tool", fmt::format("tool {} has no diameter: a pocket offsets by its radius", tool.number));
    op.tool_radius = tool.diameter / 2;
    op.spindle = tool.direction;
    op.centre_cutting = tool.centre_cutting;
    op.heights = read_heights(f, in, "pass");
    const Planes z = resolve_planes(op.heights);
    const double total_depth = z.reference_z - z.bottom_z;
    if (tool.flute_length && total_depth > *tool.flute_length)
        f.fail("endDepth", fmt::format("the pocket is {} deep below the reference plane, but tool {} has a fluteLength of {}",
                                       in.show(total_depth), tool.number, in.show(*tool.flute_length)));
    if (f.has("profile") && !names_a_shape(*f.member("profile"))) {
        if (f.has("start") || f.has("path")) f.fail("profile", "give start and path, or profile, not both");
        if (f.has("islands")) f.fail("islands", "the islands of a pocket from a drawing are the closed profiles inside its outline");
        read_drawn_region(f, in, op);
    } else {
        op.region.outer = read_loop(f, in, "a pocket's outline");
    }
    if (const Json* islands = f.member("islands")) {
        const Json& list = in.array(f, "islands");
        (void)islands;
        for (std::size_t k = 0; k < list.size(); ++k) {
            Fields i(list[k], f.path_of("islands") + "/" + std::to_string(k), in.source());
            JobInput::known_keys(i, island_keys);
            op.region.islands.push_back(read_loop(i, in, "an island"));
        }
    }
    if (const std::optional<RegionProblem> problem = region_problem(op.region)) {
        if (problem->island) json::fail(in.source(), f.path_of("islands") + "/" + std::to_string(*problem->island), problem->message);
        f.fail("path", problem->message);
    }
    op.strategy = f.choice("strategy", pocket_strategies, PocketStrategy::offset);
    op.order = f.choice("order", pocket_orders, PocketOrder::inside_out);
    op.rows = f.choice("rows", row_directions, RowDirection::both_ways);
    op.angle = f.optional_number("angle").value_or(0.0);
    if (!std::isfinite(op.angle) || std::abs(op.angle) > 360) f.fail("angle", "angle must be from -360 to 360 degrees");
    if (op.strategy == PocketStrategy::offset) {
        for (const char* key : {"angle", "rows"})
            if (f.has(key)) f.fail(key, fmt::format("{} is for strategy zigzag; this pocket is cut by offset rings", key));
    } else if (f.has("order")) {
        f.fail("order", "order is for strategy offset; zigzag cuts rows, then the cleanup ring");
    }
    op.direction = f.choice("direction", cut_directions, CutDirection::climb);
    op.tool_left = tool_left_of_travel(op.direction, op.spindle);
    std::string over_key;
    op.step_over = read_step_over(f, in, tool.diameter, 40.0, over_key);
    if (op.strategy == PocketStrategy::offset && op.step_over > op.tool_radius * (1 + 1e-9))
        f.fail(over_key, fmt::format("offset rings {} apart leave material between them at the corners: the step must be at most "
                                     "the tool radius ({}, 50 %); use a smaller step, or strategy zigzag (rows up to the diameter apart)",
                                     in.show(op.step_over), in.show(op.tool_radius)));
    op.stock_to_leave = in.optional_length(f, "stockToLeave").value_or(0.0);
    if (!(op.stock_to_leave >= 0)) f.fail("stockToLeave", "stockToLeave must be >= 0");
    op.step_down = read_step_down(f, in, total_depth);
    op.equal_steps = f.boolean("equalSteps", true);
    op.finishing = read_finishing(f, in, total_depth);
    op.lead_in = read_lead(f, in, "leadIn", tool.diameter);
    op.lead_out = read_lead(f, in, "leadOut", tool.diameter);
    for (const char* key : {"leadIn", "leadOut"})
        if (f.has(key) && !op.finishing)
            f.fail(key, fmt::format("{} is for the finishing pass along the walls: give finishing too (the clearing paths are linked, "
                                    "not led in)",
                                    key));
    if (f.has("ramp")) {
        op.ramp = read_ramp(f, in, "ramp", op.tool_radius);
    } else {
        op.ramp = Ramp{Ramp::Kind::helix, 5.0, op.tool_radius};
    }
    if (op.ramp.kind == Ramp::Kind::plunge && !op.centre_cutting)
        json::fail(in.source(), f.path_of("ramp") + "/type",
                   fmt::format("tool {} does not cut at its centre: it cannot plunge into the material (give the tool \"centreCutting\": "
                               "true if it does, or a helix or along ramp)",
                               tool.number));
    // No chip-thinning correction for the stepover: each level begins with a cut of the
    // tool's full width (the first ring or row), which the thinned feed would overload.
    op.feeds = read_cut_feeds(f, in, tool, 0.0, op.notes);
    op.tolerance = read_tolerance(f, in);

    const double radial = op.finishing ? op.finishing->radial_stock : 0.0;
    const double d0 = op.tool_radius + op.stock_to_leave + radial;
    PocketPlanner planner(op, in, d0, d0 + std::max(op.ramp.radius, op.tool_radius) * 2 + 1.0);
    try {
        if (op.strategy == PocketStrategy::offset) plan_offset(planner, op, d0);
        else plan_zigzag(planner, op, d0);
        if (op.finishing) {
            RegionOffset walls = shrunk(op.region, op.tool_radius + op.stock_to_leave);
            for (const PlaneRegion& r : walls.regions)
                for (Profile& l : walked_loops(r, op.tool_left))
                    op.finish_loops.push_back(fit_leads(op, in, planner, started_mid_line(l)));
            note_leads(op, planner.notes);
        }
    } catch (const PlanError& e) {
        f.fail(f.has(e.key) ? e.key : "", e.what());
    }
    op.steps = std::move(planner.steps);
    op.notes.insert(op.notes.end(), planner.notes.begin(), planner.notes.end());  // after the drawing's
    note_corners(op, in, op.tool_radius + op.stock_to_leave, op.notes);
    std::size_t smaller = 0, along = 0, line = 0;
    for (const PocketStep& s : op.steps) {
        if (s.stay_down) continue;
        if (s.entry.kind == PocketEntry::Kind::helix && s.entry.radius < op.ramp.radius - 1e-9 && op.ramp.kind == Ramp::Kind::helix) ++smaller;
        if (s.entry.kind == PocketEntry::Kind::along && op.ramp.kind == Ramp::Kind::helix) ++along;
        if (s.entry.kind == PocketEntry::Kind::track) ++line;
    }
    if (smaller > 0)
        op.notes.push_back(fmt::format("{} entr{} with a smaller helix than the ramp's: no room for it there", smaller, smaller == 1 ? "y" : "ies"));
    if (along > 0) op.notes.push_back(fmt::format("{} entr{} ramp along the path: no room for a helix there", along, along == 1 ? "y" : "ies"));
    if (line > 0)
        op.notes.push_back(fmt::format("{} entr{} ramp back and forth on a straight line or along the edge of the area: no room for "
                                       "a helix there, and the path is too short to ramp along",
                                       line, line == 1 ? "y" : "ies"));
    guard_pocket(op, f, in);
    return op;
}

std::string default_name(const PocketOp& op) { return op.comment.empty() ? "pocket" : op.comment; }

void expand(const PocketOp& op, const Context& ctx, EventSink& sink) { cut_pocket(op, ctx.job, sink); }

}  // namespace camgen
