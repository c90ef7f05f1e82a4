// The rapids of turn-groove and turn-part against the material earlier operations keep
// (registry.hpp: check_blade_material).
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

// Where a line at radius `level` along Z between `lo` and `hi` runs through the bar's solid
// that none of `earlier` removed: the bar less its bore, less what earlier turn-faces,
// turn-drills, internal turn-grooves and turn-profiles (above what they keep) took away.
std::vector<ZSpan> bar_solid_at(const Stock& bar, const std::vector<const Operation*>& earlier,
                                const std::vector<KeptMaterial>& kept, const JobInput& in, double level, double lo, double hi) {
    if (level >= bar.diameter / 2 || level <= bar.bore_diameter.value_or(0.0) / 2) return {};
    lo = std::max(lo, bar.face_z - bar.length);
    hi = std::min(hi, bar.face_z);
    if (!(hi > lo)) return {};
    std::vector<ZSpan> air;
    constexpr double far = std::numeric_limits<double>::infinity();
    Job tools;  // design_turn_drill reads the tool of the job
    tools.tools = in.header().tools;
    for (const Operation* op : earlier) {
        if (const auto* f = std::get_if<TurnFaceOp>(op); f && f->inner <= level) air.push_back({f->z, far});
        if (const auto* d = std::get_if<TurnDrillOp>(op)) {
            LatheDesign design;
            std::vector<std::string> unchecked;
            design_turn_drill(*d, tools, design, unchecked);
            for (const LatheHoleDesign& h : design.holes)
                if (h.radius >= level) air.push_back({h.bottom_z + std::max(0.0, level - h.flat) * h.slope, far});
        }
        if (const auto* g = std::get_if<TurnGrooveOp>(op); g && g->side == GrooveSide::internal && level <= g->bottom)
            air.push_back({g->z_left, g->z_right});
    }
    // Above what a turn-profile keeps, over its stretch of Z, it took the material away.
    for (const KeptMaterial& k : kept) {
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

}  // namespace

void check_blade_material(const std::vector<Operation>& operations, const JobInput& in) {
    const double clearance = in.header().clearance;
    const std::optional<Stock>& stock = in.header().stock;
    const Stock* bar = stock && stock->shape == StockShape::bar ? &*stock : nullptr;
    std::vector<KeptMaterial> kept;
    std::vector<const Operation*> earlier;
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
                    continue;
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
                    continue;
                }
                // Internal: the edge faces +X, the blade and its bar lie inside it. Only a bar
                // says where solid is.
                if (!bar) continue;
                const double radius = std::max(r.from.x, r.to.x);
                if (in_column && radius > air_level + blade_level_tolerance) continue;
                const std::vector<ZSpan> solid = bar_solid_at(*bar, earlier, kept, in, radius - blade_level_tolerance, z_lo, z_hi);
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
        if (const auto* t = std::get_if<TurnProfileOp>(&operation)) {
            kept.push_back(kept_by(*t));
        }
        earlier.push_back(&operation);
    }
}

}  // namespace camgen
