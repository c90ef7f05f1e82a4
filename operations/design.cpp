// What a job designs (design.hpp): each operation's cuts and keeps as regions with heights.
#include "camgen/operations/design.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "camgen/common/number_text.hpp"
#include "camgen/events/events.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/registry.hpp"

namespace camgen {

namespace {

// A flat floor at z.
DesignFloor design_flat(double z) {
    DesignFloor f;
    f.z = z;
    return f;
}

// The largest region of an offset (the one a band is made of), or none.
std::optional<PlaneRegion> design_largest(const RegionOffset& o) {
    std::optional<PlaneRegion> best;
    double area = -1.0;
    for (const PlaneRegion& r : o.regions)
        if (const double a = region_area(r); a > area) area = a, best = r;
    return best;
}

// The region grown by d (d = 0: as it is).
std::optional<PlaneRegion> design_grown(const PlaneRegion& r, double d) {
    if (d <= 0.0) return normalised(r);
    return design_largest(grow_region(r, d));
}

// The points outside `inner` within `width` of it: its growth less itself.
std::optional<PlaneRegion> design_band_outside(const PlaneRegion& inner, double width) {
    std::optional<PlaneRegion> grown = design_grown(inner, width);
    if (!grown) return std::nullopt;
    PlaneRegion band = *grown;
    band.islands = {reversed(normalised(inner).outer)};
    return normalised(band);
}

// What a tool of radius r reaches of a region from inside it: the region shrunk by r and grown
// back (a sharp concave corner keeps a fillet of r). Empty where the tool does not fit.
std::vector<PlaneRegion> design_opening(const PlaneRegion& region, double r) {
    std::vector<PlaneRegion> out;
    for (const PlaneRegion& centre : offset_region(region, r).regions)
        for (PlaneRegion& g : grow_region(centre, r).regions) out.push_back(std::move(g));
    return out;
}

// The region with what a tool of radius r cannot reach from outside it filled: grown by r and
// shrunk back (a sharp concave corner of a part's outline is rounded by r).
std::optional<PlaneRegion> design_closing(const PlaneRegion& region, double r) {
    const std::optional<PlaneRegion> grown = design_grown(region, r);
    if (!grown) return std::nullopt;
    return design_largest(offset_region(*grown, r));
}

// ---- A tab as the cutter leaves it (Cutter::tab_intervals, follow_over_tabs): the tool stays at
// the tab's top over `half` mm each side of the point of ITS path nearest the tab's centre, and
// is below the top everywhere else on that path (on the flanks too). What stands at the top is
// the band within the radius of that stretch of the centre path less the discs of every other
// centre position. The region is traced from that exact test on a fine grid (marching squares):
// a sharp corner of the centre path, where normals jump, or an arc tighter than the radius, or
// another pass or the path's far side coming near, need no case of their own, and the loops it
// gives never cross themselves.

// A line or an arc of a tool centre path.
struct DtabPiece {
    Vec2 a, b;
    std::optional<Vec2> centre;
    double radius = 0.0, a0 = 0.0, sweep = 0.0, sign = 1.0;  // an arc's: start angle, sweep (>= 0), +1 ccw
    double from = 0.0, length = 0.0;                           // along its path
    Vec2 lo, hi;                                               // its extent (an arc's: its circle's)
};

std::vector<DtabPiece> dtab_pieces(const Profile& p, double offset_along = 0.0) {
    std::vector<DtabPiece> out;
    double done = offset_along;
    for (std::size_t k = 0; k < p.segments.size(); ++k) {
        const ProfileSegment& s = p.segments[k];
        DtabPiece q;
        q.a = segment_start(p, k);
        q.b = s.end;
        q.from = done;
        if (s.centre) {
            q.centre = *s.centre;
            q.radius = distance(q.a, *s.centre);
            q.a0 = std::atan2(q.a.y - s.centre->y, q.a.x - s.centre->x);
            q.sweep = segment_sweep(p, k);
            q.sign = s.direction == ArcDirection::ccw ? 1.0 : -1.0;
            q.length = q.sweep * q.radius;
            q.lo = *s.centre - Vec2{q.radius, q.radius};
            q.hi = *s.centre + Vec2{q.radius, q.radius};
        } else {
            q.length = distance(q.a, q.b);
            q.lo = {std::min(q.a.x, q.b.x), std::min(q.a.y, q.b.y)};
            q.hi = {std::max(q.a.x, q.b.x), std::max(q.a.y, q.b.y)};
        }
        done += q.length;
        out.push_back(q);
    }
    return out;
}

// The point of a piece nearest to x: how far along the piece, and how far from x.
std::pair<double, double> dtab_nearest(const DtabPiece& q, Vec2 x) {
    if (!q.centre) {
        if (q.length <= 0.0) return {0.0, distance(x, q.a)};
        const Vec2 d = q.b - q.a;
        const double t = std::clamp(((x - q.a).x * d.x + (x - q.a).y * d.y) / (q.length * q.length), 0.0, 1.0);
        return {t * q.length, distance(x, q.a + d * t)};
    }
    const Vec2 c = *q.centre;
    double delta = q.sign * (std::atan2(x.y - c.y, x.x - c.x) - q.a0);
    delta = std::fmod(std::fmod(delta, 2 * pi) + 2 * pi, 2 * pi);
    if (delta <= q.sweep) return {delta * q.radius, std::abs(distance(x, c) - q.radius)};
    const double da = distance(x, q.a), db = distance(x, q.b);
    return da <= db ? std::pair{0.0, da} : std::pair{q.length, db};
}

double dtab_distance(const std::vector<DtabPiece>& pieces, Vec2 x) {
    double d = std::numeric_limits<double>::infinity();
    for (const DtabPiece& q : pieces) d = std::min(d, dtab_nearest(q, x).second);
    return d;
}

// How far along the path (its pieces) its point nearest to x is (the first of equals).
double dtab_along(const std::vector<DtabPiece>& pieces, Vec2 x) {
    double best = std::numeric_limits<double>::infinity(), along = 0.0;
    for (const DtabPiece& q : pieces)
        if (const auto [t, d] = dtab_nearest(q, x); d < best) best = d, along = q.from + t;
    return along;
}

// The pieces of closed path p from `from` to `to` mm along it (to > from, either beyond the
// path's ends: on round it), those reaching the box [lo, hi] grown by `reach` only.
std::vector<DtabPiece> dtab_stretch(const Profile& p, double from, double to, Vec2 lo, Vec2 hi, double reach) {
    std::vector<DtabPiece> out;
    const double total = profile_length(p);
    if (total <= 0.0 || to <= from) return out;
    if (to - from >= total) from = 0.0, to = total;
    const double shift = std::floor(from / total) * total;
    from -= shift, to -= shift;
    auto add = [&](double x0, double x1) {
        if (x1 - x0 <= 1e-9) return;
        for (const DtabPiece& q : dtab_pieces(sub_profile(p, x0, x1), x0))
            if (q.hi.x + reach >= lo.x && q.lo.x - reach <= hi.x && q.hi.y + reach >= lo.y && q.lo.y - reach <= hi.y) out.push_back(q);
    };
    add(from, std::min(to, total));
    if (to > total) add(0.0, to - total);
    return out;
}

// The regions of the points where `in` holds, inside the box [lo, hi] (nothing on its edge
// holds), traced on a grid of `cell`: the loops between the grid's nodes in and out, each
// crossing found on its grid edge by halving. A loop's chord may cut a corner of the set, and
// lies within a few microns of it elsewhere.
std::vector<PlaneRegion> dtab_trace(const std::function<bool(Vec2)>& in, Vec2 lo, Vec2 hi, double cell) {
    const Vec2 o = lo - Vec2{cell, cell};
    const std::size_t nx = static_cast<std::size_t>(std::ceil((hi.x - lo.x) / cell)) + 2;
    const std::size_t ny = static_cast<std::size_t>(std::ceil((hi.y - lo.y) / cell)) + 2;
    const std::size_t w = nx + 1;
    auto node = [&](std::size_t i, std::size_t j) { return o + Vec2{static_cast<double>(i) * cell, static_cast<double>(j) * cell}; };
    std::vector<char> v(w * (ny + 1), 0);
    for (std::size_t j = 1; j < ny; ++j)
        for (std::size_t i = 1; i < nx; ++i) v[j * w + i] = in(node(i, j)) ? 1 : 0;
    // Edge ids: 2 (j w + i) the one from node (i, j) along x, + 1 along y.
    std::unordered_map<std::size_t, Vec2> crossing;
    auto point_on = [&](std::size_t id) {
        if (const auto it = crossing.find(id); it != crossing.end()) return it->second;
        const std::size_t n = id / 2, i = n % w, j = n / w;
        Vec2 a = node(i, j), b = id % 2 ? node(i, j + 1) : node(i + 1, j);
        if (!v[n]) std::swap(a, b);  // a in, b out
        for (int k = 0; k < 20; ++k) {
            const Vec2 m = (a + b) * 0.5;
            (in(m) ? a : b) = m;
        }
        const Vec2 at = (a + b) * 0.5;
        crossing.emplace(id, at);
        return at;
    };
    std::unordered_map<std::size_t, std::size_t> next;
    for (std::size_t j = 0; j < ny; ++j)
        for (std::size_t i = 0; i < nx; ++i) {
            // Corners counter-clockwise from the lower left, and the edge after each.
            const std::size_t c[4] = {j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i};
            const std::size_t e[4] = {2 * c[0], 2 * c[1] + 1, 2 * c[3], 2 * c[0] + 1};
            int outs = 0;
            bool leaves[4], enters[4];
            for (int k = 0; k < 4; ++k) {
                leaves[k] = v[c[k]] && !v[c[(k + 1) % 4]];
                enters[k] = !v[c[k]] && v[c[(k + 1) % 4]];
                outs += leaves[k];
            }
            if (outs == 0) continue;
            // Two ins across: joined through the cell when its centre is in.
            const bool joined = outs == 2 && in(node(i, j) + Vec2{cell / 2, cell / 2});
            for (int k = 0; k < 4; ++k) {
                if (!leaves[k]) continue;
                for (int s = 1; s < 4; ++s) {
                    const int m = joined ? (k + s) % 4 : (k + 4 - s) % 4;
                    if (!enters[m]) continue;
                    next[e[k]] = e[m];
                    break;
                }
            }
        }
    // The loops: counter-clockwise around what is in, clockwise around a hole in it.
    std::vector<std::vector<Vec2>> outers, holes;
    while (!next.empty()) {
        const std::size_t first = next.begin()->first;
        std::vector<Vec2> loop;
        std::size_t at = first;
        for (std::size_t guard = 0; guard <= crossing.size() + next.size() + 4; ++guard) {
            loop.push_back(point_on(at));
            const auto it = next.find(at);
            if (it == next.end()) break;
            at = it->second;
            next.erase(it);
            if (at == first) break;
        }
        // Points on a straight run between their neighbours dropped.
        std::vector<Vec2> kept;
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const Vec2 a = kept.empty() ? loop.back() : kept.back(), b = loop[k], c = loop[(k + 1) % loop.size()];
            const double len = distance(a, c);
            if (len > 0 && std::abs(cross(b - a, c - a)) / len < 1e-6) continue;
            kept.push_back(b);
        }
        if (kept.size() < 3) continue;
        double area = 0.0;
        for (std::size_t k = 0; k < kept.size(); ++k) area += cross(kept[k], kept[(k + 1) % kept.size()]);
        // A sliver of a few cells (the tip of a cusp the grid cuts off) is left out: the region
        // is then smaller, never larger; a hole is always kept.
        if (area > 0 && area / 2 < 4 * cell * cell) continue;
        (area > 0 ? outers : holes).push_back(std::move(kept));
    }
    auto profile_of = [](const std::vector<Vec2>& pts) {
        Profile p;
        p.start = pts.front();
        for (std::size_t k = 1; k < pts.size(); ++k) p.segments.push_back({pts[k], std::nullopt, ArcDirection::ccw});
        p.segments.push_back({pts.front(), std::nullopt, ArcDirection::ccw});
        return p;
    };
    std::vector<PlaneRegion> out;
    for (const std::vector<Vec2>& loop : outers) out.push_back(PlaneRegion{profile_of(loop), {}});
    for (const std::vector<Vec2>& hole : holes)
        for (PlaneRegion& r : out)
            if (contains(r.outer, hole.front())) {
                r.islands.push_back(profile_of(hole));
                break;
            }
    for (PlaneRegion& r : out) r = normalised(r);
    return out;
}

class Designer {
public:
    Designer(const Job& job, double keep_band) : job_(job), keep_band_(keep_band) {}

    PartDesign run() {
        for (const Operation& op : job_.operations)
            visit_exhaustive(overloaded{
                                 [&](const DrillOp& o) { drill(o); },
                                 [&](const BoreMillOp& o) { bore(o); },
                                 [&](const ContourOp& o) { contour(o); },
                                 [&](const PocketOp& o) { pocket(o); },
                                 [&](const FaceOp& o) { face(o); },
                                 [&](const PathOp& o) { skip(o.path, "a path has no designed part"); },
                                 [&](const ThreadMillOp& o) { thread(o); },
                                 [&](const EngraveOp& o) { engrave(o); },
                                 [&](const ChamferOp& o) { chamfer(o); },
                                 [&](const CustomOp& o) { skip(o.path, "custom blocks have no designed part"); },
                                 [&](const StopOp&) {},
                                 // A lathe's part: design_lathe.cpp.
                                 [&](const TurnDrillOp& o) { design_turn_drill(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnProfileOp& o) { design_turn_profile(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnFaceOp& o) { design_turn_face(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnRoughOp& o) { design_turn_rough(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnGrooveOp& o) { design_turn_groove(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnPartOp& o) { design_turn_part(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnThreadOp& o) { design_turn_thread(o, job_, design_.lathe, design_.unchecked); },
                             },
                             op);
        return std::move(design_);
    }

private:
    double band_for(double diameter) const { return keep_band_ > 0.0 ? keep_band_ : std::max(diameter, 3.0); }

    void skip(const std::string& path, const std::string& why) { design_.unchecked.push_back(path + ": " + why); }

    const Tool* tool_of(int number) const {
        const auto it = job_.tools.find(number);
        return it == job_.tools.end() ? nullptr : &it->second;
    }

    void holes(const std::string& path, const std::vector<Vec2>& centres, double radius, double top, DesignFloor floor) {
        if (centres.empty()) return;
        DesignCut cut;
        cut.path = path;
        cut.what = "hole";
        cut.discs = DesignDiscs{centres, radius, 0.0};
        cut.floor = floor;
        cut.top_z = top;
        design_.cuts.push_back(std::move(cut));
        DesignKeep keep;
        keep.path = path;
        keep.what = "the part around hole";
        keep.discs = DesignDiscs{centres, radius + band_for(2.0 * radius), radius};
        keep.top_z = top;
        design_.keeps.push_back(std::move(keep));
    }

    void drill(const DrillOp& op) {
        const Tool* tool = tool_of(op.tool);
        if (!tool) return skip(op.path, "its tool is not in the job");
        const DrillCycle c = resolve_cycle(op, *tool);
        DesignFloor floor = design_flat(c.bottom_z);
        if (tool->tip_angle && *tool->tip_angle > 0.0 && *tool->tip_angle < 180.0) {
            floor.apex = Vec2{0.0, 0.0};  // placed at each hole
            floor.slope = 1.0 / std::tan(*tool->tip_angle / 2.0 * rad_per_deg);
        }
        holes(op.path, op.holes, tool->diameter / 2.0, c.reference_z, floor);
    }

    // A thread as the height field holds it (its flanks are undercuts it cannot): the tool's
    // sweep, down to the lowest its lead takes it, may reach any depth there (may_leave: the last
    // turn's floor is a helix); the part beyond the thread's outer edge (internal: the major
    // diameter) and inside its core (external: the minor diameter) is kept.
    void thread(const ThreadMillOp& op) {
        const Tool* tool = tool_of(op.tool);
        if (!tool) return skip(op.path, "its tool is not in the job");
        if (op.holes.empty()) return;
        const Planes z = resolve_planes(op.heights);
        const double radius = tool->diameter / 2.0;
        double rise = 0.0, widest = 0.0;
        for (const double r : thread_pass_radii(op, tool->diameter)) {
            rise = std::max(rise, thread_lead_rise(op, r, tool->diameter));
            widest = std::max(widest, r);
        }
        DesignCut cut;
        cut.path = op.path;
        cut.what = "thread";
        cut.floor = design_flat(z.bottom_z - rise);
        cut.top_z = z.reference_z;
        cut.may_leave = true;
        DesignKeep keep;
        keep.path = op.path;
        keep.top_z = z.reference_z;
        if (op.side == ThreadSide::internal) {
            // The half-circle leads stay inside the thread's circle.
            cut.discs = DesignDiscs{op.holes, op.major / 2.0, 0.0};
            keep.what = "the part around thread";
            keep.discs = DesignDiscs{op.holes, op.major / 2.0 + band_for(op.major), op.major / 2.0};
        } else {
            // The quarter-circle leads of the tool's radius reach at most a tool radius beyond the
            // widest pass (and the tool its radius beyond that).
            cut.discs = DesignDiscs{op.holes, widest + 2.0 * radius, op.minor / 2.0};
            keep.what = "the core of thread";
            keep.discs = DesignDiscs{op.holes, op.minor / 2.0, 0.0};
        }
        design_.cuts.push_back(std::move(cut));
        design_.keeps.push_back(std::move(keep));
    }

    // Engraving: each stroke's piece a band of the line's width about it (a stadium: a
    // rectangle with half discs at its ends; a stroke without length a disc), down to the depth.
    // A V's, a ball's or a bull-nose's flanks rise from that floor towards the band's edges: the
    // band may keep material there (may_leave), but nothing in it may be cut below the depth.
    void engrave(const EngraveOp& op) {
        const Tool* tool = tool_of(op.tool);
        if (!tool) return skip(op.path, "its tool is not in the job");
        const Planes z = resolve_planes(op.heights);
        const double h = op.width / 2.0;
        const bool flat = tool->type == ToolType::end_mill;
        auto add = [&](PlaneRegion region, std::size_t stroke) {
            DesignCut cut;
            cut.path = op.path;
            cut.what = fmt::format("stroke {}", stroke);
            cut.region = std::move(region);
            cut.floor.z = z.bottom_z;
            cut.top_z = z.reference_z;
            cut.may_leave = !flat;
            design_.cuts.push_back(std::move(cut));
        };
        std::vector<Vec2> dots;
        for (std::size_t k = 0; k < op.strokes.size(); ++k) {
            const std::vector<Vec2> pts = sample_profile(op.strokes[k], 0.005);
            if (op.strokes[k].segments.empty() || pts.size() < 2) {
                dots.push_back(op.strokes[k].start);
                continue;
            }
            for (std::size_t i = 1; i < pts.size(); ++i) {
                const Vec2 a = pts[i - 1], b = pts[i];
                const double len = distance(a, b);
                if (len < 1e-9) continue;
                const Vec2 n = Vec2{-(b.y - a.y), b.x - a.x} * (h / len);
                PlaneRegion r;
                r.outer.start = a + n;
                r.outer.segments = {{b + n, std::nullopt, ArcDirection::ccw},
                                    {b - n, b, ArcDirection::cw},
                                    {a - n, std::nullopt, ArcDirection::ccw},
                                    {a + n, a, ArcDirection::cw}};
                add(normalised(r), k);
            }
        }
        if (!dots.empty()) {
            DesignCut cut;
            cut.path = op.path;
            cut.what = "dot";
            cut.discs = DesignDiscs{dots, h, 0.0};
            cut.floor.z = z.bottom_z;
            cut.top_z = z.reference_z;
            cut.may_leave = !flat;
            design_.cuts.push_back(std::move(cut));
        }
    }

    // A chamfer: its sloped face as a cut whose floor rises with the distance from the edge (a
    // hole's: from its centre), `width` into the part; on the air side the cone's continuation
    // down to the tip's depth (may_leave: beyond the tool's axis its cone rises again); the part
    // beyond the chamfer kept up to the top face. Open profiles have none.
    void chamfer(const ChamferOp& op) {
        const Planes z = resolve_planes(op.heights);
        const ChamferGeometry& g = op.geometry;
        const double slope = 1.0 / std::tan(op.angle * rad_per_deg);
        const double lower = z.reference_z - g.height;  // the chamfer's lower edge
        const double band = band_for(2.0 * g.reach);
        auto add_cut = [&](std::string what, DesignFloor floor, bool may_leave) -> DesignCut& {
            DesignCut cut;
            cut.path = op.path;
            cut.what = std::move(what);
            cut.floor = std::move(floor);
            cut.top_z = z.reference_z;
            cut.may_leave = may_leave;
            design_.cuts.push_back(std::move(cut));
            return design_.cuts.back();
        };
        auto add_keep = [&](std::string what) -> DesignKeep& {
            DesignKeep keep;
            keep.path = op.path;
            keep.what = std::move(what);
            keep.top_z = z.reference_z;
            design_.keeps.push_back(std::move(keep));
            return design_.keeps.back();
        };
        if (op.on_holes()) {
            if (op.holes.empty()) return;
            const double r = op.diameter / 2.0;
            // About each hole's centre: lower + slope x (distance - r).
            DesignFloor floor = design_flat(lower - slope * r);
            floor.apex = Vec2{0.0, 0.0};
            floor.slope = slope;
            add_cut("the chamfer of hole", floor, false).discs = DesignDiscs{op.holes, r + op.width, r};
            floor.lowest = z.bottom_z;
            add_cut("the tool's cone inside hole", floor, true).discs = DesignDiscs{op.holes, r, 0.0};
            add_keep("the part beyond the chamfer of hole").discs = DesignDiscs{op.holes, r + op.width + band, r + op.width};
            return;
        }
        if (!is_closed(op.profile)) return skip(op.path, "only a chamfer of a closed profile has a designed part");
        PlaneRegion shape;
        shape.outer = op.profile;
        shape = normalised(shape);
        const bool tool_inside = op.side == ContourSide::inside ||
                                 (op.side == ContourSide::left && orientation(op.profile) == Orientation::ccw) ||
                                 (op.side == ContourSide::right && orientation(op.profile) == Orientation::cw);
        const auto edge = std::make_shared<const Profile>(op.profile);
        // The points inside the shape within d of its edge.
        auto inner_band = [&](double d) -> std::optional<PlaneRegion> {
            PlaneRegion b = shape;
            for (const PlaneRegion& i : offset_region(shape, d).regions) b.islands.push_back(reversed(i.outer));
            return normalised(b);
        };
        const std::optional<PlaneRegion> face = tool_inside ? design_band_outside(shape, op.width) : inner_band(op.width);
        const std::optional<PlaneRegion> air = tool_inside ? inner_band(g.reach) : design_band_outside(shape, g.reach);
        if (!face || !air) return skip(op.path, "its chamfer's band is empty");
        DesignFloor up = design_flat(lower);
        up.slope = slope;
        up.edge = edge;
        add_cut("the chamfer", up, false).region = *face;
        DesignFloor down = design_flat(lower);
        down.slope = -slope;
        down.edge = edge;
        down.lowest = z.bottom_z;
        add_cut("the tool's cone beside the chamfer", down, true).region = *air;
        if (tool_inside) {
            const std::optional<PlaneRegion> out = design_grown(shape, op.width);
            if (!out) return;
            if (std::optional<PlaneRegion> around = design_band_outside(*out, band)) add_keep("the part beyond the chamfer").region = *around;
        } else {
            for (const PlaneRegion& i : offset_region(shape, op.width).regions) add_keep("the part inside the chamfer").region = i;
        }
    }

    void bore(const BoreMillOp& op) {
        const Planes z = resolve_planes(op.heights);
        holes(op.path, op.holes, op.diameter / 2.0, z.reference_z, design_flat(z.bottom_z));
    }

    void contour(const ContourOp& op) {
        const bool outside = op.side == ContourSide::outside, inside = op.side == ContourSide::inside;
        if (!(outside || inside) || !is_closed(op.profile))
            return skip(op.path, "only a contour inside or outside a closed profile has a designed part");
        const Planes z = resolve_planes(op.heights);
        const double d = 2.0 * op.tool_radius, s = op.stock_to_leave;
        PlaneRegion shape;
        shape.outer = op.profile;
        shape = normalised(shape);
        // The part's wall: the profile with the stock the contour leaves on it.
        std::optional<PlaneRegion> wall;
        if (outside) wall = design_grown(shape, s);
        else wall = s > 0.0 ? design_largest(offset_region(shape, s)) : std::optional<PlaneRegion>(shape);
        if (!wall) return skip(op.path, "its wall with the stock to leave is empty");
        // The band the tool sweeps: one diameter beside the wall, less what it cannot reach (an
        // outline's sharp concave corner keeps a fillet of the radius, as does a sharp corner of a
        // pocket wall).
        std::vector<PlaneRegion> bands;
        if (outside) {
            const std::optional<PlaneRegion> grown = design_grown(*wall, d), closed = design_closing(*wall, op.tool_radius);
            if (grown && closed) {
                PlaneRegion band = *grown;
                band.islands = {reversed(closed->outer)};
                bands.push_back(normalised(band));
            }
        } else {
            const std::vector<PlaneRegion> inner = offset_region(*wall, d).regions;
            for (PlaneRegion open : design_opening(*wall, op.tool_radius)) {
                for (const PlaneRegion& i : inner)
                    if (region_contains(open, i.outer.start)) open.islands.push_back(reversed(i.outer));
                bands.push_back(normalised(open));
            }
        }
        if (bands.empty()) return skip(op.path, "its band is empty");
        for (const PlaneRegion& band : bands) {
            DesignCut cut;
            cut.path = op.path;
            cut.what = "the band beside the contour's wall";
            cut.region = band;
            cut.floor.z = z.bottom_z;
            cut.top_z = z.reference_z;
            design_.cuts.push_back(std::move(cut));
        }
        DesignKeep keep;
        keep.path = op.path;
        keep.top_z = z.reference_z;
        if (outside) {
            keep.what = "the part inside the contour";
            keep.region = *wall;
        } else {
            std::optional<PlaneRegion> around = design_band_outside(*wall, band_for(d));
            if (!around) return;
            keep.what = "the part around the contour";
            keep.region = *around;
        }
        design_.keeps.push_back(std::move(keep));
        if (!op.tabs) return;
        // The tool centre's paths: the programmed ones (computer, wear and inverse-wear: camgen
        // offsets them, the control's table holding only the wear, taken as none), or under
        // control compensation their offset by the radius as the control makes it (an arc about
        // each convex corner, concave corners trimmed). The cutter measures a tab's stretch on
        // the programmed path; its ends are carried across to the centre path along the normal.
        const double r = op.tool_radius, half = op.tabs->width / 2.0 + r;
        const double run = op.tabs->ramp_angle < 90.0 ? op.tabs->height / std::tan(op.tabs->ramp_angle * rad_per_deg) : 0.0;
        struct CentrePath {
            const Profile* programmed;
            std::vector<DtabPiece> programmed_pieces;
            Profile centre;
            std::vector<DtabPiece> centre_pieces;
        };
        const bool control = op.compensation == CompensationMode::control;
        std::vector<CentrePath> paths;
        for (const Profile* prog : {&op.rough, &op.finish}) {
            if (prog->segments.empty() || !is_closed(*prog)) continue;
            CentrePath c{prog, dtab_pieces(*prog), *prog, {}};
            if (op.compensation == CompensationMode::control) {
                OffsetResult o = offset_profile(*prog, r, op.tool_left ? OffsetSide::left : OffsetSide::right);
                if (o.empty()) continue;
                c.centre = std::move(o.profile);
            }
            c.centre_pieces = dtab_pieces(c.centre);
            paths.push_back(std::move(c));
        }
        if (paths.empty()) return skip(op.path, "its tool centre path for the tabs is empty");
        // Where else the tool goes at depth: each path's lead-in and lead-out, and the helix it
        // may go down on before the lead-in (about a centre beside its start). Under control
        // compensation the leads as programmed and offset by the radius both, and the moves
        // between (the control switches on and off along them): more than it reaches, so the tab
        // is smaller, never larger, than what stands.
        std::vector<DtabPiece> elsewhere;
        {
            CutSettings cs;
            cs.tool = op.tool;
            cs.tool_radius = r;
            cs.tool_left = op.tool_left;
            cs.compensation = op.compensation;
            cs.lead_in = op.lead_in;
            cs.lead_out = op.lead_out;
            cs.ramp = op.ramp;
            cs.z = z;
            EventRecorder nowhere;
            const Cutter cutter(cs, nowhere);
            for (const CentrePath& c : paths) {
                for (const Profile& lead : {cutter.lead_in(*c.programmed), cutter.lead_out(*c.programmed)}) {
                    if (lead.segments.empty()) continue;
                    for (const DtabPiece& q : dtab_pieces(lead)) elsewhere.push_back(q);
                    if (!control) continue;
                    OffsetResult o = offset_profile(lead, r, op.tool_left ? OffsetSide::left : OffsetSide::right);
                    if (o.empty()) continue;
                    Profile joins;
                    joins.start = lead.start;
                    joins.segments = {{o.profile.start, std::nullopt, ArcDirection::ccw}};
                    for (const DtabPiece& q : dtab_pieces(joins)) elsewhere.push_back(q);
                    joins.start = lead.segments.back().end;
                    joins.segments = {{o.profile.segments.back().end, std::nullopt, ArcDirection::ccw}};
                    for (const DtabPiece& q : dtab_pieces(joins)) elsewhere.push_back(q);
                    for (const DtabPiece& q : dtab_pieces(o.profile)) elsewhere.push_back(q);
                }
                if (op.ramp.kind == Ramp::Kind::helix) {
                    const Vec2 at = cutter.lead_in(*c.programmed).start, t = point_at(*c.programmed, 0.0).tangent;
                    const Vec2 away = op.tool_left ? left_of(t) : left_of(t) * -1.0;
                    DtabPiece helix;
                    helix.a = helix.b = at;
                    helix.centre = at + away * op.ramp.radius;
                    helix.radius = op.ramp.radius;
                    helix.a0 = std::atan2(at.y - helix.centre->y, at.x - helix.centre->x);
                    helix.sweep = 2 * pi;
                    helix.length = 2 * pi * helix.radius;
                    helix.lo = *helix.centre - Vec2{helix.radius, helix.radius};
                    helix.hi = *helix.centre + Vec2{helix.radius, helix.radius};
                    elsewhere.push_back(helix);
                }
            }
        }
        for (std::size_t i = 0; i < op.tabs->centres.size(); ++i) {
            const Vec2 tab_centre = point_at(op.profile, op.tabs->centres[i]).point;
            // Each pass's stretches on its centre path: [a, b] over the tab, [ea, eb] with the
            // flanks and a radius more.
            struct Span {
                const CentrePath* path;
                double a, b, ea, eb;
            };
            std::vector<Span> spans;
            for (const CentrePath& c : paths) {
                const double along = dtab_along(c.programmed_pieces, tab_centre);
                double x[5] = {along, along - half, along + half, along - half - run - r, along + half + run + r};
                if (control) {
                    const double lp = profile_length(*c.programmed), lc = profile_length(c.centre);
                    double m[5];
                    for (int k = 0; k < 5; ++k) {
                        const ProfilePoint q = point_at(*c.programmed, x[k] - std::floor(x[k] / lp) * lp);
                        const Vec2 n = op.tool_left ? left_of(q.tangent) : left_of(q.tangent) * -1.0;
                        m[k] = dtab_along(c.centre_pieces, q.point + n * r);
                    }
                    for (int k = 1; k < 5; ++k) {
                        if (k % 2 == 1 && m[k] > m[0]) m[k] -= lc;
                        if (k % 2 == 0 && m[k] < m[0]) m[k] += lc;
                    }
                    std::copy(std::begin(m), std::end(m), std::begin(x));
                }
                spans.push_back({&c, x[1], x[2], x[3], x[4]});
            }
            // The extent of a stretch (sampled), grown by `by`.
            auto extent = [&](bool ends, double by) {
                Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}, hi = lo * -1.0;
                for (const Span& sp : spans) {
                    const std::vector<DtabPiece> pieces =
                        dtab_stretch(sp.path->centre, ends ? sp.ea : sp.a, ends ? sp.eb : sp.b, {-1e300, -1e300}, {1e300, 1e300}, 0.0);
                    for (const DtabPiece& q : pieces)
                        for (int k = 0; k <= 64; ++k) {
                            const Vec2 p = q.centre ? *q.centre + unit_at(q.a0 + q.sign * q.sweep * k / 64.0) * q.radius
                                                    : q.a + (q.b - q.a) * (k / 64.0);
                            lo = {std::min(lo.x, p.x - by), std::min(lo.y, p.y - by)};
                            hi = {std::max(hi.x, p.x + by), std::max(hi.y, p.y + by)};
                        }
                }
                return std::pair{lo, hi};
            };
            // About 300 cells across, 0.01 to 0.1 mm, at most about a million nodes.
            auto cell_for = [](Vec2 lo, Vec2 hi) {
                return std::max(std::clamp(std::max(hi.x - lo.x, hi.y - lo.y) / 300.0, 0.01, 0.1), std::sqrt((hi.x - lo.x) * (hi.y - lo.y) / 1e6));
            };
            // What stands at the tab's top: within the radius of a pass's stretch over the tab
            // and beyond the radius (and a little more: the loops' chords) of every other
            // position of every pass.
            const auto [lo, hi] = extent(false, r);
            if (!(lo.x < hi.x && lo.y < hi.y)) continue;
            const double cell = cell_for(lo, hi), eps = 1e-3 + cell * cell / r;
            std::vector<std::vector<DtabPiece>> up, down, ends;
            for (const Span& sp : spans) {
                up.push_back(dtab_stretch(sp.path->centre, sp.a, sp.b, lo, hi, r + 2 * cell));
                down.push_back(dtab_stretch(sp.path->centre, sp.b, sp.a + profile_length(sp.path->centre), lo, hi, r + 2 * cell));
            }
            auto standing = [&](Vec2 q) {
                bool near = false;
                for (const auto& u : up) near = near || dtab_distance(u, q) <= r;
                if (!near) return false;
                for (const auto& dn : down)
                    if (dtab_distance(dn, q) <= r + eps) return false;
                return dtab_distance(elsewhere, q) > r + eps;
            };
            for (PlaneRegion& region : dtab_trace(standing, lo, hi, cell)) {
                DesignCut tab;
                tab.path = op.path;
                tab.what = fmt::format("tab {}", i);
                tab.region = std::move(region);
                tab.floor.z = std::min(z.reference_z, z.bottom_z + op.tabs->height);
                tab.top_z = z.reference_z;
                tab.overrides = true;
                design_.cuts.push_back(std::move(tab));
            }
            // Where the tool climbs onto it and comes down again: within the radius of the
            // centre paths over the tab, its flanks and a radius more, down to the bottom.
            const auto [elo, ehi] = extent(true, r + 0.01);
            if (!(elo.x < ehi.x && elo.y < ehi.y)) continue;
            for (const Span& sp : spans) ends.push_back(dtab_stretch(sp.path->centre, sp.ea, sp.eb, elo, ehi, r + 1.0));
            auto beside = [&](Vec2 q) {
                for (const auto& e : ends)
                    if (dtab_distance(e, q) <= r + 1e-3) return true;
                return false;
            };
            for (PlaneRegion& region : dtab_trace(beside, elo, ehi, cell_for(elo, ehi))) {
                DesignCut shoulder;
                shoulder.path = op.path;
                shoulder.what = fmt::format("the ends of tab {}", i);
                shoulder.region = std::move(region);
                shoulder.floor.z = z.bottom_z;
                shoulder.top_z = z.reference_z;
                shoulder.may_leave = true;
                design_.cuts.push_back(std::move(shoulder));
            }
        }
    }

    void pocket(const PocketOp& op) {
        const Planes z = resolve_planes(op.heights);
        const double s = op.stock_to_leave, d = 2.0 * op.tool_radius;
        std::vector<PlaneRegion> walls = s > 0.0 ? offset_region(op.region, s).regions : std::vector<PlaneRegion>{normalised(op.region)};
        // What the tool reaches of it (a sharp corner keeps a fillet of the tool's radius).
        std::size_t made = 0;
        for (const PlaneRegion& w : walls)
            for (PlaneRegion& open : design_opening(w, op.tool_radius)) {
                DesignCut cut;
                cut.path = op.path;
                cut.what = "the pocket";
                cut.region = std::move(open);
                cut.floor.z = z.bottom_z;
                cut.top_z = z.reference_z;
                design_.cuts.push_back(std::move(cut));
                ++made;
            }
        if (made == 0) return skip(op.path, "its tool fits nowhere in its region");
        PlaneRegion outline;
        outline.outer = op.region.outer;
        if (std::optional<PlaneRegion> around = design_band_outside(outline, band_for(d))) {
            DesignKeep keep;
            keep.path = op.path;
            keep.what = "the part around the pocket";
            keep.region = *around;
            keep.top_z = z.reference_z;
            design_.keeps.push_back(std::move(keep));
        }
        for (std::size_t i = 0; i < op.region.islands.size(); ++i) {
            PlaneRegion island;
            island.outer = op.region.islands[i];
            DesignKeep keep;
            keep.path = op.path;
            keep.what = fmt::format("island {}", i);
            keep.region = normalised(island);
            keep.top_z = z.reference_z;
            design_.keeps.push_back(std::move(keep));
        }
    }

    void face(const FaceOp& op) {
        const Planes z = resolve_planes(op.heights);
        DesignCut cut;
        cut.path = op.path;
        cut.what = "the faced area";
        cut.region.outer = op.area;
        cut.region = normalised(cut.region);
        cut.floor.z = z.bottom_z;
        cut.top_z = z.reference_z;
        // Beyond its edge the tool overhangs: it may cut there, down to the same floor, as far as
        // the overhang and its diameter reach.
        if (std::optional<PlaneRegion> beyond = design_grown(cut.region, op.overhang + 2.0 * op.tool_radius)) {
            DesignCut over = cut;
            over.what = "the overhang beyond the faced area";
            over.region = *beyond;
            over.may_leave = true;
            design_.cuts.push_back(std::move(cut));
            design_.cuts.push_back(std::move(over));
            return;
        }
        design_.cuts.push_back(std::move(cut));
    }

    const Job& job_;
    double keep_band_;
    PartDesign design_;
};

}  // namespace

std::size_t design_cut_count(const PartDesign& design) {
    std::size_t n = 0;
    for (const DesignCut& c : design.cuts) n += c.discs ? c.discs->centres.size() : 1;
    return n;
}

std::size_t design_keep_count(const PartDesign& design) {
    std::size_t n = 0;
    for (const DesignKeep& k : design.keeps) n += k.discs ? k.discs->centres.size() : 1;
    return n;
}

PartDesign part_design(const Job& job, double keep_band) { return Designer(job, keep_band).run(); }

}  // namespace camgen
