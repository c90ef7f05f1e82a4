// The rapids of turn-groove and turn-part, and the diameter a turn-thread is cut on, against the
// material earlier operations keep and, with a bar, the bar's solid they left (registry.hpp:
// check_blade_material).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/design_lathe.hpp"
#include "camgen/operations/registry.hpp"

namespace camgen {

namespace {

// A stretch of solid shorter than this along Z is not counted (a move along a kept surface), mm.
constexpr double blade_material_margin = 0.002;
// How far a blade's programmed radius may lie past the approach level and still be the level, mm.
constexpr double blade_level_tolerance = 1e-6;

// A rapid of a blade, from one programmed point to another.
struct BladeRapid {
    Vec3 from, to;
};

// The rapids of an operation as expand writes them (a grooving cycle as its moves).
template <typename Op>
std::vector<BladeRapid> blade_rapids(const Op& op, const JobInput& in) {
    std::vector<BladeRapid> out;
    const auto tool = in.header().tools.find(op.tool);
    if (tool == in.header().tools.end()) return out;
    EventRecorder recorder;
    expand(op, Context{in.header(), tool->second}, recorder);
    std::optional<Vec3> at;
    auto take = [&](const Event& e) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            if (at) out.push_back({*at, r->to});
            at = r->to;
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            at = l->to;
        }
    };
    for (const Event& e : recorder.events) {
        if (const auto* c = std::get_if<GrooveCycle>(&e))
            for (const Event& m : groove_cycle_moves(*c)) take(m);
        else take(e);
    }
    return out;
}

// What the operations before one removed of the bar, each as the region it takes away (read by
// bar_solid_at): made once as the operations are walked, in job order (material once removed
// stays removed, so the order within it does not matter).
struct BarRemoved {
    // A turn-face: beyond Z `z` between `inner` and `outer` (radii).
    struct Face {
        double z, inner, outer;
    };
    // An internal groove: Z lo to hi, from the axis out to `bottom`.
    struct Slot {
        double lo, hi, bottom;
    };
    // Above an outline over its stretch of Z (a turn-profile's, a turn-rough's boundary, an
    // external groove's or part-off's outline), up to `top` (a turn-rough's startX; else
    // infinity).
    struct Above {
        KeptMaterial under;
        double top;
    };
    std::vector<Face> faces;
    std::vector<LatheHoleDesign> holes;  // turn-drills' bores
    std::vector<Slot> slots;
    std::vector<Above> above;

    // What `op` takes away (nothing for the operations that cut no round: threads, mills' ...).
    void add(const Operation& op, const Job& tools) {
        constexpr double far = std::numeric_limits<double>::infinity();
        if (const auto* f = std::get_if<TurnFaceOp>(&op)) faces.push_back({f->z, f->inner, f->outer});
        if (const auto* d = std::get_if<TurnDrillOp>(&op)) {
            LatheDesign design;
            std::vector<std::string> unchecked;
            design_turn_drill(*d, tools, design, unchecked);
            for (LatheHoleDesign& h : design.holes) holes.push_back(std::move(h));
        }
        if (const auto* t = std::get_if<TurnProfileOp>(&op)) above.push_back({kept_by(*t), far});
        if (const auto* r = std::get_if<TurnRoughOp>(&op); r && !r->boundary.segments.empty())
            above.push_back({kept_under(r->boundary), r->stock_radius});
        // An external groove's and a part-off's outline (design_turn_groove, design_turn_part):
        // the blade's body stands out in +X, so all above it over its Z is gone.
        if (const auto* g = std::get_if<TurnGrooveOp>(&op); g && g->side == GrooveSide::internal)
            slots.push_back({g->z_left, g->z_right, g->bottom});
        LatheDesign design;
        std::vector<std::string> unchecked;
        if (const auto* g = std::get_if<TurnGrooveOp>(&op); g && g->side == GrooveSide::external)
            design_turn_groove(*g, tools, design, unchecked);
        if (const auto* p = std::get_if<TurnPartOp>(&op)) design_turn_part(*p, tools, design, unchecked);
        for (const LatheTurnDesign& d : design.profiles)
            if (!d.profile.segments.empty()) above.push_back({kept_under(d.profile), far});
    }
};

// Where the bar's solid that `removed` left lies along Z between `lo` and `hi`: inside
// (`outward` false), on the line at radius `level` (an internal blade's edge, its body towards
// the axis); outside (`outward`), anywhere on the ray from `level` out (an external blade's edge
// and its body straight out in +X, or a thread's major): the bar less its bore, less what
// earlier turn-faces, turn-drills, internal grooves, turn-roughs, turn-profiles, external
// grooves and part-offs took away. Outside, a bore or drill counts for nothing (the ray meets
// the wall around it) and a turn-face or turn-rough only where it took all out to the bar's
// radius.
std::vector<ZSpan> bar_solid_at(const Stock& bar, const BarRemoved& removed, double level, double lo, double hi, bool outward) {
    const double radius = bar.diameter / 2;
    if (level >= radius || (!outward && level <= bar.bore_diameter.value_or(0.0) / 2)) return {};
    lo = std::max(lo, bar.face_z - bar.length);
    hi = std::min(hi, bar.face_z);
    if (!(hi > lo)) return {};
    std::vector<ZSpan> air;
    constexpr double far = std::numeric_limits<double>::infinity();
    auto reaches_out = [&](double top) { return !outward || top >= radius - 1e-9; };
    for (const BarRemoved::Face& f : removed.faces)
        if (f.inner <= level && level <= f.outer && reaches_out(f.outer)) air.push_back({f.z, far});
    if (!outward) {
        for (const LatheHoleDesign& h : removed.holes)
            if (h.radius >= level) air.push_back({h.bottom_z + std::max(0.0, level - h.flat) * h.slope, far});
        for (const BarRemoved::Slot& g : removed.slots)
            if (level <= g.bottom) air.push_back({g.lo, g.hi});
    }
    // Above what an outline keeps, over its stretch of Z, the operation took the material away.
    for (const BarRemoved::Above& a : removed.above) {
        if (!(level < a.top) || !reaches_out(a.top)) continue;
        const KeptMaterial& k = a.under;
        double from = k.u_min;
        for (const ZSpan& s : kept_inside_at(k, level)) {
            air.push_back({from, s.lo});
            from = s.hi;
        }
        air.push_back({from, k.u_max});
    }
    std::sort(air.begin(), air.end(), [](const ZSpan& a, const ZSpan& b) { return a.lo < b.lo; });
    std::vector<ZSpan> solid;
    double from = lo;
    for (const ZSpan& a : air) {
        if (a.hi <= from) continue;
        if (a.lo >= hi) break;
        if (a.lo > from) solid.push_back({from, a.lo});
        from = std::max(from, a.hi);
    }
    if (from < hi) solid.push_back({from, hi});
    std::erase_if(solid, [](const ZSpan& s) { return s.hi - s.lo <= blade_material_margin; });
    return solid;
}

// The largest radius of the bar's solid that `removed` left outside, between Z `lo` and `hi` (for
// the messages): at the span's ends, the corners of the outlines within it and 256 steps
// between (exact where the material is straight along Z, as a turned diameter is).
double bar_outer_most(const Stock& bar, const BarRemoved& removed, double lo, double hi) {
    const double radius = bar.diameter / 2;
    auto outer = [&](double z) {
        double r = radius;
        for (const BarRemoved::Face& f : removed.faces)
            if (z > f.z && f.outer >= radius - 1e-9) r = std::min(r, std::max(0.0, f.inner));
        for (const BarRemoved::Above& a : removed.above)
            if (a.top >= radius - 1e-9 && z >= a.under.u_min && z <= a.under.u_max)
                r = std::min(r, kept_largest_radius(a.under, z, z));
        return r;
    };
    std::vector<double> at{lo, hi};
    for (int i = 1; i < 256; ++i) at.push_back(lo + (hi - lo) * i / 256);
    for (const BarRemoved::Above& a : removed.above)
        for (const Vec2& p : a.under.ring)
            if (p.x > lo && p.x < hi) at.push_back(p.x);
    double most = 0.0;
    for (double z : at) most = std::max(most, outer(z));
    return most;
}

// A thread is cut into the diameter the operations before it leave: more than its major
// (external; inside, a bore less than its minor) by more than this, radial, and its first pass
// would take the excess with the threading insert, mm.
constexpr double thread_material_tolerance = 0.05;

// Refuses a turn-thread whose diameter is not there: outside, material beyond its major over its
// length (what an earlier turn-profile keeps, or with a bar the bar's solid the operations
// before it left); inside, with a bar, solid within its minor.
void check_thread_material(const TurnThreadOp& t, const std::vector<KeptMaterial>& kept, const Stock* bar,
                           const BarRemoved& removed, const JobInput& in) {
    const bool outside = t.side == ThreadSide::external;
    const std::string key = t.path + "/" + (!t.thread.empty() ? "thread" : outside ? "majorDiameter" : "minorDiameter");
    const std::string what = t.thread.empty() ? std::string("the thread") : "the thread " + t.thread;
    const double lo = t.end_z, hi = t.start_z;
    if (outside) {
        const double level = t.surface_radius() + thread_material_tolerance;
        if (auto hit = first_kept_hit(kept, kept.size(), level, lo, hi, false))
            json::fail(in.source(), key,
                       fmt::format("{} (major diameter {}) is cut on the material that the profile of {} keeps: diameter "
                                   "up to {} between Z {} and Z {}; its first pass would cut the excess with the threading "
                                   "insert: turn the diameter to the thread's major first",
                                   what, in.show(t.major), hit->kept->op->path,
                                   in.show(2 * kept_largest_radius(*hit->kept, hit->span.lo, hit->span.hi)),
                                   in.show(hit->span.lo), in.show(hit->span.hi)));
        if (!bar) return;
        const std::vector<ZSpan> solid = bar_solid_at(*bar, removed, level, lo, hi, true);
        if (solid.empty()) return;
        json::fail(in.source(), key,
                   fmt::format("{} (major diameter {}) is cut on the bar's solid between Z {} and Z {}: the operations "
                               "before it left the bar (diameter {}) up to diameter {} there, none (a turn-face, turn-rough, "
                               "turn-profile, groove or part-off) turned it down to the major; its first pass would cut the "
                               "excess with the threading insert: turn the diameter to the thread's major first",
                               what, in.show(t.major), in.show(solid.front().lo), in.show(solid.front().hi),
                               in.show(bar->diameter),
                               in.show(2 * bar_outer_most(*bar, removed, solid.front().lo, solid.front().hi))));
    }
    // Inside: only a bar says where solid is.
    if (!bar) return;
    const double level = t.surface_radius() - thread_material_tolerance;
    const std::vector<ZSpan> solid = bar_solid_at(*bar, removed, level, lo, hi, false);
    if (solid.empty()) return;
    json::fail(in.source(), key,
               fmt::format("{} (minor diameter {}) is cut into the bar's solid between Z {} and Z {}: nothing before it (the "
                           "bar's bore, a turn-drill, a turn-face, an internal groove, a turn-profile) bored it out to the "
                           "minor there; its first pass would cut the excess with the threading insert: bore the thread's "
                           "minor diameter first",
                           what, in.show(t.minor), in.show(solid.front().lo), in.show(solid.front().hi)));
}

}  // namespace

void check_blade_material(const std::vector<Operation>& operations, const JobInput& in) {
    const double clearance = in.header().clearance;
    const std::optional<Stock>& stock = in.header().stock;
    const Stock* bar = stock && stock->shape == StockShape::bar ? &*stock : nullptr;
    std::vector<KeptMaterial> kept;
    BarRemoved removed;
    Job tools;  // the designs of turn-drills, grooves and part-offs read the job's header and tools
    static_cast<JobHeader&>(tools) = in.header();
    for (const Operation& operation : operations) {
        const auto* groove = std::get_if<TurnGrooveOp>(&operation);
        const auto* part = std::get_if<TurnPartOp>(&operation);
        if (groove || part) {
            const GrooveSide side = groove ? groove->side : GrooveSide::external;
            const GrooveBlade& blade = groove ? groove->blade : part->blade;
            const double w = blade.width;
            const XValues xv = groove ? groove->given_x : part->given_x;
            const std::string& path = groove ? groove->path : part->path;
            auto x = [&](double radius) { return in.show(xv == XValues::diameter ? 2.0 * radius : radius); };
            // The cut's own column (the left corner's Z span plus the width; a face groove's
            // radii) and its approach level: the rapids below that level inside the column run
            // where its own feeds just cut.
            const double own_lo = groove ? groove->z_left : part->z - w;
            const double own_hi = groove ? groove->z_right : part->z;
            const double air_level = groove ? groove->surface + (side == GrooveSide::internal ? -1.0 : 1.0) * groove->approach
                                            : part->surface + part->approach;
            const std::vector<BladeRapid> rapids = groove ? blade_rapids(*groove, in) : blade_rapids(*part, in);
            for (const BladeRapid& r : rapids) {
                if (side == GrooveSide::face) {
                    // The blade's edge faces -Z, its width along X from the programmed (inner)
                    // corner, its body straight up in +Z.
                    const double x_lo = std::min(r.from.x, r.to.x), z_lo = std::min(r.from.z, r.to.z);
                    if (z_lo < air_level - blade_level_tolerance && x_lo >= own_lo - 1e-9 &&
                        std::max(r.from.x, r.to.x) + w <= own_hi + 1e-9)
                        continue;
                    if (auto hit = first_kept_hit(kept, kept.size(), x_lo, z_lo, clearance, true))
                        json::fail(in.source(), path + "/z",
                                   fmt::format("the blade's rapid from X {} Z {} to X {} Z {} (its body above it, up to "
                                               "the clearance) runs through the material that the profile of {} keeps: X up "
                                               "to {} between Z {} and Z {}; the face groove must lie in a face open above it",
                                               x(r.from.x), in.show(r.from.z), x(r.to.x), in.show(r.to.z), hit->kept->op->path,
                                               x(kept_largest_radius(*hit->kept, hit->span.lo, hit->span.hi)),
                                               in.show(hit->span.lo), in.show(hit->span.hi)));
                    if (!bar) continue;
                    const std::vector<ZSpan> solid = bar_solid_at(*bar, removed, x_lo + blade_level_tolerance, z_lo, clearance, true);
                    if (solid.empty()) continue;
                    json::fail(in.source(), path + "/z",
                               fmt::format("the blade's rapid from X {} Z {} to X {} Z {} (its body above it, up to the "
                                           "clearance) runs through the bar's solid between Z {} and Z {}: the operations "
                                           "before it left the bar (X {}) up to X {} there, none (a turn-face, turn-rough, "
                                           "turn-profile, groove or part-off) took it away down to X {}; the face groove must "
                                           "lie in a face open above it",
                                           x(r.from.x), in.show(r.from.z), x(r.to.x), in.show(r.to.z), in.show(solid.back().lo),
                                           in.show(solid.back().hi), x(bar->diameter / 2),
                                           x(bar_outer_most(*bar, removed, solid.back().lo, solid.back().hi)), x(x_lo)));
                }
                // External and internal: the blade's edge spans Z [left, left + w] at the
                // programmed radius.
                const double shift = blade.right_point ? w : 0.0;
                const double z_lo = std::min(r.from.z, r.to.z) - shift, z_hi = std::max(r.from.z, r.to.z) - shift + w;
                const bool downwards = r.to.z < r.from.z;
                const bool in_column = z_lo >= own_lo - 1e-9 && z_hi <= own_hi + 1e-9;
                auto along = [&]() {
                    return r.from.z == r.to.z ? fmt::format("along X from X {} to X {} at Z {}", x(r.from.x), x(r.to.x), in.show(r.from.z))
                                              : r.from.x == r.to.x
                                                  ? fmt::format("along Z at X {} from Z {} to Z {}", x(r.from.x), in.show(r.from.z), in.show(r.to.z))
                                                  : fmt::format("from X {} Z {} to X {} Z {}", x(r.from.x), in.show(r.from.z), x(r.to.x),
                                                                in.show(r.to.z));
                };
                if (side == GrooveSide::external) {
                    // Its body stands straight out in +X from the edge.
                    const double radius = std::min(r.from.x, r.to.x);
                    if (in_column && radius < air_level - blade_level_tolerance) continue;
                    if (auto hit = first_kept_hit(kept, kept.size(), radius, z_lo, z_hi, downwards))
                        json::fail(in.source(), path + "/startX",
                                   fmt::format("the blade's rapid {} runs through the material that the profile of {} keeps: "
                                               "X up to {} between Z {} and Z {}; startX ({}) must be the largest X over the {}, "
                                               "its chamfers and approachDistance either side",
                                               along(), hit->kept->op->path,
                                               x(kept_largest_radius(*hit->kept, hit->span.lo, hit->span.hi)),
                                               in.show(hit->span.lo), in.show(hit->span.hi),
                                               x(groove ? groove->surface : part->surface), groove ? "groove" : "blade's width"));
                    // With a bar: the bar's solid that the operations before it did not turn away.
                    if (!bar) continue;
                    const std::vector<ZSpan> solid = bar_solid_at(*bar, removed, radius + blade_level_tolerance, z_lo, z_hi, true);
                    if (solid.empty()) continue;
                    const ZSpan s = downwards ? solid.back() : solid.front();
                    json::fail(in.source(), path + "/startX",
                               fmt::format("the blade's rapid {} runs through the bar's solid between Z {} and Z {}: the "
                                           "operations before it left the bar (X {}) up to X {} there, none (a turn-face, "
                                           "turn-rough, turn-profile, groove or part-off) turned it down to X {}; startX ({}) "
                                           "must be the largest X over the {}, its chamfers and approachDistance either side, "
                                           "of what the operations before it leave",
                                           along(), in.show(s.lo), in.show(s.hi), x(bar->diameter / 2),
                                           x(bar_outer_most(*bar, removed, s.lo, s.hi)), x(radius),
                                           x(groove ? groove->surface : part->surface), groove ? "groove" : "blade's width"));
                    continue;
                }
                // Internal: the edge faces +X, the blade and its bar lie inside it. Only a bar
                // says where solid is.
                if (!bar) continue;
                const double radius = std::max(r.from.x, r.to.x);
                if (in_column && radius > air_level + blade_level_tolerance) continue;
                const std::vector<ZSpan> solid = bar_solid_at(*bar, removed, radius - blade_level_tolerance, z_lo, z_hi, false);
                if (solid.empty()) continue;
                const ZSpan s = downwards ? solid.back() : solid.front();
                json::fail(in.source(), path + "/startX",
                           fmt::format("the blade's rapid {} runs through the bar's solid between Z {} and Z {}: nothing "
                                       "before it (the bar's bore, a turn-drill, a turn-face, an internal groove, a "
                                       "turn-profile) bored it out to X {} there; the bore (startX {}, approachDistance {}) "
                                       "must be there from the face down to the groove",
                                       along(), in.show(s.lo), in.show(s.hi), x(radius), x(groove->surface),
                                       in.show(groove->approach)));
            }
        }
        if (const auto* t = std::get_if<TurnThreadOp>(&operation)) check_thread_material(*t, kept, bar, removed, in);
        if (const auto* t = std::get_if<TurnProfileOp>(&operation)) {
            kept.push_back(kept_by(*t));
        }
        if (bar) removed.add(operation, tools);  // read only with a bar
    }
}

}  // namespace camgen
