// A simulated part against the job's design (design_check.hpp).
#include "camgen/simulation/design_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "camgen/common/number_text.hpp"
#include "camgen/geometry/clearance.hpp"
#include "camgen/geometry/region.hpp"
#include "camgen/operations/drill/drill.hpp"
#include "camgen/post/stops.hpp"

namespace camgen {

namespace {

// A loop that is a circle (arcs about one centre, one radius): its centre and radius. Holes'
// discs and rings are, and are answered without the region functions (a hundred thousand holes).
struct DesignCircle {
    Vec2 centre;
    double radius = 0.0;
};
std::optional<DesignCircle> design_circle(const Profile& loop) {
    if (loop.segments.empty() || !is_closed(loop)) return std::nullopt;
    const auto& first = loop.segments.front().centre;
    if (!first) return std::nullopt;
    const double r = distance(loop.start, *first);
    for (const ProfileSegment& seg : loop.segments)
        if (!seg.centre || distance(*seg.centre, *first) > 1e-9 || std::abs(distance(seg.end, *first) - r) > 1e-9)
            return std::nullopt;
    return DesignCircle{*first, r};
}
// A region of circles: its outline and islands.
struct DesignCircles {
    DesignCircle outer;
    std::vector<DesignCircle> islands;
};
std::optional<DesignCircles> design_circles(const PlaneRegion& region) {
    const auto outer = design_circle(region.outer);
    if (!outer) return std::nullopt;
    DesignCircles c{*outer, {}};
    for (const Profile& i : region.islands) {
        const auto island = design_circle(i);
        if (!island) return std::nullopt;
        c.islands.push_back(*island);
    }
    return c;
}

// Calls f(i, j, centre) for every cell whose centre lies in the disc `outer` less the discs
// `islands`, grown (d > 0) or shrunk (d < 0) by |d|.
template <class F>
void design_circle_cells(const DesignCircle& outer, const std::vector<DesignCircle>& islands, double d, const HeightGridView& g,
                         F f) {
    const double r = outer.radius + d;
    if (!(r > 0)) return;
    const Vec2 o = outer.centre;
    const double j0 = std::max(0.0, std::ceil((o.y - r - g.y0) / g.cell - 0.5));
    const double j1 = std::min(static_cast<double>(g.ny) - 1.0, std::floor((o.y + r - g.y0) / g.cell - 0.5));
    std::vector<std::pair<double, double>> spans, next;
    for (double jd = j0; jd <= j1; ++jd) {
        const double y = g.y0 + (jd + 0.5) * g.cell, dy = y - o.y;
        if (dy * dy > r * r) continue;
        const double hw = std::sqrt(r * r - dy * dy);
        spans.assign(1, {o.x - hw, o.x + hw});
        for (const DesignCircle& island : islands) {
            const double ri = island.radius - d, di = y - island.centre.y;
            if (!(ri > 0) || di * di >= ri * ri) continue;
            const double iw = std::sqrt(ri * ri - di * di), a = island.centre.x - iw, b = island.centre.x + iw;
            next.clear();
            for (const auto& [xa, xb] : spans) {
                if (b <= xa || a >= xb) {
                    next.emplace_back(xa, xb);
                    continue;
                }
                if (a > xa) next.emplace_back(xa, a);
                if (b < xb) next.emplace_back(b, xb);
            }
            spans.swap(next);
        }
        const std::size_t j = static_cast<std::size_t>(jd);
        for (const auto& [xa, xb] : spans) {
            // Strictly inside: a centre on an island's edge is not the region's.
            const double i0 = std::max(0.0, std::ceil((xa - g.x0) / g.cell - 0.5));
            const double i1 = std::min(static_cast<double>(g.nx) - 1.0, std::floor((xb - g.x0) / g.cell - 0.5));
            for (double id = i0; id <= i1; ++id) f(static_cast<std::size_t>(id), j, Vec2{g.x0 + (id + 0.5) * g.cell, y});
        }
    }
}

// Calls f(i, j, centre) for every cell whose centre lies in the region grown (d > 0) or shrunk
// (d < 0) by |d|.
template <class F>
void design_cells(const PlaneRegion& region, double d, const HeightGridView& g, F f) {
    if (const auto c = design_circles(region)) return design_circle_cells(c->outer, c->islands, d, g, f);
    std::vector<PlaneRegion> parts;
    if (d > 0.0) parts = grow_region(region, d).regions;
    else if (d < 0.0) parts = offset_region(region, -d).regions;
    else parts = {region};
    for (const PlaneRegion& part : parts) {
        const RegionRows rows(part);
        const auto b = rows.bounds();
        const double j0 = std::max(0.0, std::ceil((b[1] - g.y0) / g.cell - 0.5));
        const double j1 = std::min(static_cast<double>(g.ny) - 1.0, std::floor((b[3] - g.y0) / g.cell - 0.5));
        for (double jd = j0; jd <= j1; ++jd) {
            const std::size_t j = static_cast<std::size_t>(jd);
            const double y = g.y0 + (jd + 0.5) * g.cell;
            for (const auto& [xa, xb] : rows.spans(y)) {
                const double i0 = std::max(0.0, std::ceil((xa - g.x0) / g.cell - 0.5));
                const double i1 = std::min(static_cast<double>(g.nx) - 1.0, std::floor((xb - g.x0) / g.cell - 0.5));
                for (double id = i0; id <= i1; ++id) f(static_cast<std::size_t>(id), j, Vec2{g.x0 + (id + 0.5) * g.cell, y});
            }
        }
    }
}

// One piece of a cut's or keep's region: the region itself, or one of its discs (a ring where
// `islands` has the hole).
struct DesignPiece {
    const PlaneRegion* region = nullptr;
    DesignCircle outer;
    std::vector<DesignCircle> islands;
};

// Calls f(piece) for each piece of a cut or keep (one piece object, refilled).
template <class T, class F>
void design_pieces(const T& feature, F f) {
    if (!feature.discs) {
        DesignPiece piece;
        piece.region = &feature.region;
        f(piece);
        return;
    }
    const DesignDiscs& d = *feature.discs;
    DesignPiece piece;
    if (d.hole > 0) piece.islands.resize(1);
    for (const Vec2 c : d.centres) {
        piece.outer = {c, d.radius};
        if (d.hole > 0) piece.islands[0] = {c, d.hole};
        f(piece);
    }
}

template <class F>
void design_cells(const DesignPiece& piece, double d, const HeightGridView& g, F f) {
    if (piece.region) design_cells(*piece.region, d, g, f);
    else design_circle_cells(piece.outer, piece.islands, d, g, f);
}

// A cut's floor over one of its pieces (`centre`: a disc's): a drill's point at each disc's centre.
DesignFloor design_floor(const DesignCut& cut, Vec2 centre) {
    DesignFloor f = cut.floor;
    if (cut.discs && f.apex) f.apex = centre;
    return f;
}

// Calls f(point, inward normal) every `spacing` mm along a loop (a point in the middle of each
// of a segment's equal pieces); `inward`: +1 where the material is to the loop's left.
template <class F>
void design_loop_points(const Profile& loop, double spacing, F f) {
    const double left = orientation(loop) == Orientation::ccw ? 1.0 : -1.0;
    for (std::size_t k = 0; k < loop.segments.size(); ++k) {
        const Vec2 a = segment_start(loop, k);
        const ProfileSegment& seg = loop.segments[k];
        if (!seg.centre) {
            const double len = distance(a, seg.end);
            if (len < 1e-9) continue;
            const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
            const Vec2 u = (seg.end - a) * (1.0 / len);
            for (int q = 0; q < n; ++q) f(a + u * (len * (q + 0.5) / n), left_of(u) * left);
            continue;
        }
        const Vec2 c = *seg.centre;
        const double r = distance(a, c), sweep = segment_sweep(loop, k);
        if (r < 1e-9) continue;
        const double sign = seg.direction == ArcDirection::ccw ? 1.0 : -1.0;
        const double a0 = std::atan2(a.y - c.y, a.x - c.x);
        const int n = std::max(1, static_cast<int>(std::ceil(r * sweep / spacing)));
        for (int q = 0; q < n; ++q) {
            // Travel along the arc is left_of(radial) x sign; its left, left_of of that, is
            // -radial x sign.
            const Vec2 radial = unit_at(a0 + sign * sweep * (q + 0.5) / n);
            f(c + radial * r, radial * (-sign * left));
        }
    }
}

// A cut's region as the probes ask of it: inside, and how far from its edge (exact, by a
// grid of its pieces where it has many).
class DesignCutShape {
public:
    DesignCutShape(const PlaneRegion& region, double reach) : region_(region), circles_(design_circles(region)) {
        if (circles_) return;
        std::size_t n = region.outer.segments.size();
        for (const Profile& p : region.islands) n += p.segments.size();
        if (n <= 64) return;
        loops_.emplace_back(region.outer, reach);
        for (const Profile& p : region.islands) loops_.emplace_back(p, reach);
    }
    // The distance from the edge, negative inside.
    double signed_distance(Vec2 p) const {
        if (circles_) {
            // Outside the outline, or inside an island: the distance to it; inside the region
            // the nearest of them.
            auto dist = [&](Vec2 c) { return std::sqrt((p.x - c.x) * (p.x - c.x) + (p.y - c.y) * (p.y - c.y)); };
            double d = dist(circles_->outer.centre) - circles_->outer.radius;
            for (const DesignCircle& i : circles_->islands) d = std::max(d, i.radius - dist(i.centre));
            return d;
        }
        if (loops_.empty()) {
            const double d = region_boundary_distance(region_, p);
            return region_contains(region_, p) ? -d : d;
        }
        double d = std::numeric_limits<double>::infinity();
        for (const ProfileClearance& l : loops_) d = std::min(d, l.nearest(p).distance);
        bool in = loops_[0].inside(p);
        for (std::size_t k = 1; in && k < loops_.size(); ++k) in = !loops_[k].inside(p);
        return in ? -d : d;
    }

private:
    const PlaneRegion& region_;
    std::optional<DesignCircles> circles_;
    std::vector<ProfileClearance> loops_;
};

// The extent of a region's outline: {x0, y0, x1, y1}.
std::array<double, 4> design_extent(const PlaneRegion& region) {
    if (const auto c = design_circle(region.outer))
        return {c->centre.x - c->radius, c->centre.y - c->radius, c->centre.x + c->radius, c->centre.y + c->radius};
    std::array<double, 4> b{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (Vec2 p : sample_profile(region.outer, 0.01)) {
        b[0] = std::min(b[0], p.x - 0.01), b[1] = std::min(b[1], p.y - 0.01);
        b[2] = std::max(b[2], p.x + 0.01), b[3] = std::max(b[3], p.y + 0.01);
    }
    return b;
}

}  // namespace

namespace {

// Calls f(point, inward normal) every `spacing` mm around a circle; `inside`: the material is
// inside it (else outside).
template <class F>
void design_circle_points(const DesignCircle& c, double spacing, bool inside, F f) {
    const int n = std::max(1, static_cast<int>(std::ceil(two_pi * c.radius / spacing)));
    for (int q = 0; q < n; ++q) {
        const Vec2 radial = unit_at(two_pi * (q + 0.5) / n);
        f(c.centre + radial * c.radius, inside ? radial * -1.0 : radial);
    }
}

}  // namespace

DesignProbes design_probes(const PartDesign& design, const HeightGridView& g, double tolerance, double margin,
                           std::size_t budget) {
    DesignProbes out;
    if (design.keeps.empty() || design.cuts.empty() || g.nx == 0 || g.ny == 0) return out;
    double length = 0.0;
    for (const DesignKeep& k : design.keeps)
        design_pieces(k, [&](const DesignPiece& p) {
            if (p.region) {
                length += profile_length(p.region->outer);
                for (const Profile& i : p.region->islands) length += profile_length(i);
                return;
            }
            length += two_pi * p.outer.radius;
            for (const DesignCircle& i : p.islands) length += two_pi * i.radius;
        });
    out.spacing = std::max(g.cell, length / static_cast<double>(std::max<std::size_t>(budget, 1)));
    // The cuts' pieces (a region, or one disc of a cut's discs) by buckets of the field: each in
    // those its extent grown by the margin meets.
    struct CutPiece {
        std::uint32_t cut;
        const PlaneRegion* region;  // or the disc
        DesignCircle disc;
        double hole;                // less a disc of this radius (0: none)
    };
    std::vector<CutPiece> pieces;
    for (std::size_t c = 0; c < design.cuts.size(); ++c)
        design_pieces(design.cuts[c], [&](const DesignPiece& p) {
            pieces.push_back({static_cast<std::uint32_t>(c), p.region, p.outer, p.islands.empty() ? 0.0 : p.islands[0].radius});
        });
    const double reach = margin + tolerance;
    const double fx1 = g.x0 + static_cast<double>(g.nx) * g.cell, fy1 = g.y0 + static_cast<double>(g.ny) * g.cell;
    // Small enough that a probe asks few cuts, at most a million buckets.
    const double bucket = std::max({g.cell * 8, 4 * reach, std::sqrt((fx1 - g.x0) * (fy1 - g.y0) / 1e6)});
    const std::size_t bx = static_cast<std::size_t>(std::ceil((fx1 - g.x0) / bucket)) + 1;
    const std::size_t by = static_cast<std::size_t>(std::ceil((fy1 - g.y0) / bucket)) + 1;
    auto bucket_of = [&](double v, double v0, std::size_t n) {
        return static_cast<std::size_t>(std::clamp(std::floor((v - v0) / bucket), 0.0, static_cast<double>(n - 1)));
    };
    std::vector<std::vector<std::uint32_t>> buckets(bx * by);
    for (std::size_t q = 0; q < pieces.size(); ++q) {
        const CutPiece& p = pieces[q];
        const auto e = p.region ? design_extent(*p.region)
                                : std::array<double, 4>{p.disc.centre.x - p.disc.radius, p.disc.centre.y - p.disc.radius,
                                                        p.disc.centre.x + p.disc.radius, p.disc.centre.y + p.disc.radius};
        if (e[2] + reach < g.x0 || e[0] - reach > fx1 || e[3] + reach < g.y0 || e[1] - reach > fy1) continue;
        for (std::size_t j = bucket_of(e[1] - reach, g.y0, by); j <= bucket_of(e[3] + reach, g.y0, by); ++j)
            for (std::size_t i = bucket_of(e[0] - reach, g.x0, bx); i <= bucket_of(e[2] + reach, g.x0, bx); ++i)
                buckets[j * bx + i].push_back(static_cast<std::uint32_t>(q));
    }
    std::vector<std::unique_ptr<DesignCutShape>> shapes(pieces.size());
    auto signed_distance = [&](std::size_t q, Vec2 p) {
        const CutPiece& piece = pieces[q];
        if (!piece.region) {
            const double from_centre = distance(p, piece.disc.centre);
            return std::max(from_centre - piece.disc.radius, piece.hole - from_centre);
        }
        if (!shapes[q]) shapes[q] = std::make_unique<DesignCutShape>(*piece.region, reach);
        return shapes[q]->signed_distance(p);
    };
    const std::uint32_t cuts = static_cast<std::uint32_t>(design.cuts.size());
    // A profile stock's outline, asked of every point: its segments by a grid, once.
    std::vector<ProfileClearance> stock_loops;
    if (g.stock) {
        stock_loops.emplace_back(g.stock->outer, reach);
        for (const Profile& p : g.stock->islands) stock_loops.emplace_back(p, reach);
    }
    auto in_stock = [&](Vec2 q) {
        if (stock_loops.empty()) return true;
        if (!stock_loops[0].inside(q)) return false;
        for (std::size_t s = 1; s < stock_loops.size(); ++s)
            if (stock_loops[s].inside(q)) return false;
        return true;
    };
    for (std::size_t k = 0; k < design.keeps.size(); ++k) {
        const DesignKeep& keep = design.keeps[k];
        auto place = [&](Vec2 p, Vec2 inward) {
            const Vec2 q = p + inward * tolerance;
            if (q.x < g.x0 || q.x > fx1 || q.y < g.y0 || q.y > fy1) return;
            if (!in_stock(q)) return;
            bool near = false;
            double designed = keep.top_z, override_floor = std::numeric_limits<double>::quiet_NaN();
            std::uint32_t owner = cuts + static_cast<std::uint32_t>(k);
            for (std::uint32_t piece : buckets[bucket_of(q.y, g.y0, by) * bx + bucket_of(q.x, g.x0, bx)]) {
                const double d = signed_distance(piece, q);
                if (std::abs(d) < tolerance / 2) return;  // on a cut's edge: either way
                if (d > reach) continue;
                near = true;
                if (d > 0) continue;
                const std::uint32_t c = pieces[piece].cut;
                const DesignCut& cut = design.cuts[c];
                const double f = design_floor(cut, pieces[piece].disc.centre).at(q);
                if (cut.overrides) override_floor = f, owner = c;
                else if (std::isnan(override_floor) && f < designed) designed = f, owner = c;
            }
            if (!near) return;
            if (!std::isnan(override_floor)) designed = override_floor;
            out.points.push_back(q);
            out.designed.push_back(std::clamp(designed, g.bottom, g.top));
            out.owner.push_back(owner);
        };
        design_pieces(keep, [&](const DesignPiece& p) {
            if (!p.region) {
                design_circle_points(p.outer, out.spacing, true, place);
                for (const DesignCircle& i : p.islands) design_circle_points(i, out.spacing, false, place);
                return;
            }
            design_loop_points(p.region->outer, out.spacing, place);
            for (const Profile& island : p.region->islands)
                design_loop_points(island, out.spacing, [&](Vec2 pt, Vec2 inward) { place(pt, inward * -1.0); });
        });
    }
    return out;
}

std::string DesignFinding::message() const {
    const std::string where = fmt::format("({}, {})", number_text(at.x, 3), number_text(at.y, 3));
    if (kind == Kind::gouge)
        return fmt::format("{} ({}): material removed {} mm below the designed {} at {}{} ({} of the part cut)", path, what,
                           number_text(amount, 3), number_text(designed, 3), where,
                           line > 0 ? fmt::format(", by line {}", line) : std::string(),
                           points == 0  ? fmt::format("{} cells", cells)
                           : cells == 0 ? fmt::format("{} points on its walls", points)
                                        : fmt::format("{} cells and {} points on its walls", cells, points));
    return fmt::format("{} ({}): material left {} mm above its floor and allowance {} at {} ({} cells)", path, what,
                       number_text(amount, 3), number_text(designed, 3), where, cells);
}

namespace {

// A finding as the check gathers it (its names are added at the end, for the few found).
struct DesignTally {
    double amount = 0.0;
    Vec2 at;
    double height = 0.0, designed = 0.0;
    std::size_t cells = 0, points = 0;
    int line = 0;
};

}  // namespace

std::vector<DesignFinding> check_design(const PartDesign& design, const HeightGridView& g, double tolerance, double margin,
                                        const ProbeHeights& probes) {
    // Per cell: its designed height (a float, as the field's heights are), the feature that
    // designs it and flags: 9 bytes beside the field's own 8.
    const std::size_t n = g.nx * g.ny;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> designed(n, nan);
    std::vector<std::int32_t> owner(n, -1);  // cuts 0..C-1, keeps C..
    enum : std::uint8_t { near_cut = 1, may_leave = 2, edge = 4, strict_now = 8 };
    std::vector<std::uint8_t> flags(n, 0);
    const auto at = [&](std::size_t i, std::size_t j) { return j * g.nx + i; };
    const std::int32_t cuts = static_cast<std::int32_t>(design.cuts.size());

    // A cell within the margin of a cut's edge, inside or out, could be that cut's or not: it
    // is judged by nothing (edge). The cut's own strict cells are marked while its margin is
    // walked (strict_now), then unmarked.
    for (std::int32_t c = 0; c < cuts; ++c) {
        const DesignCut& cut = design.cuts[static_cast<std::size_t>(c)];
        design_pieces(cut, [&](const DesignPiece& piece) {
            const DesignFloor floor = design_floor(cut, piece.outer.centre);
            design_cells(piece, -margin, g, [&](std::size_t i, std::size_t j, Vec2 p) {
                flags[at(i, j)] |= strict_now;
                if (cut.overrides) return;
                const float f = static_cast<float>(floor.at(p));
                float& d = designed[at(i, j)];
                if (std::isnan(d) || f < d) d = f, owner[at(i, j)] = c;
            });
            design_cells(piece, margin, g, [&](std::size_t i, std::size_t j, Vec2) {
                std::uint8_t& fl = flags[at(i, j)];
                fl |= near_cut | (cut.may_leave ? may_leave : 0);
                if (!cut.overrides && !(fl & strict_now)) fl |= edge;
            });
            design_cells(piece, -margin, g, [&](std::size_t i, std::size_t j, Vec2) { flags[at(i, j)] &= ~strict_now; });
        });
    }
    for (std::int32_t c = 0; c < cuts; ++c) {
        const DesignCut& cut = design.cuts[static_cast<std::size_t>(c)];
        if (!cut.overrides) continue;
        design_pieces(cut, [&](const DesignPiece& piece) {
            const DesignFloor floor = design_floor(cut, piece.outer.centre);
            design_cells(piece, -margin, g, [&](std::size_t i, std::size_t j, Vec2 p) {
                designed[at(i, j)] = static_cast<float>(floor.at(p));
                owner[at(i, j)] = c;
            });
        });
    }
    for (std::size_t k = 0; k < design.keeps.size(); ++k) {
        const DesignKeep& keep = design.keeps[k];
        const float top = static_cast<float>(keep.top_z);
        design_pieces(keep, [&](const DesignPiece& piece) {
            design_cells(piece, -margin, g, [&](std::size_t i, std::size_t j, Vec2) {
                const std::size_t a = at(i, j);
                if (flags[a] & near_cut) return;
                if (std::isnan(designed[a]) || top < designed[a]) designed[a] = top, owner[a] = cuts + static_cast<std::int32_t>(k);
            });
        });
    }

    // Outside a profile stock there is nothing to judge (strict_now marks the inside here).
    if (g.stock) {
        design_cells(*g.stock, 0.0, g, [&](std::size_t i, std::size_t j, Vec2) { flags[at(i, j)] |= strict_now; });
        for (std::size_t a = 0; a < n; ++a) {
            if (!(flags[a] & strict_now)) owner[a] = -1, flags[a] |= edge;
            flags[a] &= ~strict_now;
        }
    }
    const float top = static_cast<float>(g.top);
    std::unordered_map<std::uint32_t, DesignTally> gouges, left;  // by feature, by cut: the few found
    for (std::size_t j = 0; j < g.ny; ++j)
        for (std::size_t i = 0; i < g.nx; ++i) {
            const std::size_t a = at(i, j);
            if (owner[a] < 0 || (flags[a] & edge)) continue;
            const double h = g.height(i, j);
            if (std::isnan(h)) continue;
            const double want = std::min(designed[a], top), below = want - h;
            if (below > tolerance) {
                DesignTally& f = gouges[static_cast<std::uint32_t>(owner[a])];
                ++f.cells;
                if (below > f.amount) {
                    f.amount = below;
                    f.at = {g.x0 + (static_cast<double>(i) + 0.5) * g.cell, g.y0 + (static_cast<double>(j) + 0.5) * g.cell};
                    f.height = h;
                    f.designed = want;
                    f.line = g.line ? g.line(i, j) : 0;
                }
            }
        }
    // The walls' probes, swept exactly.
    if (probes.probes && probes.heights && probes.lines) {
        const DesignProbes& pr = *probes.probes;
        for (std::size_t k = 0; k < pr.points.size() && k < probes.heights->size(); ++k) {
            const double below = pr.designed[k] - (*probes.heights)[k];
            if (std::isnan(below) || below <= tolerance) continue;
            DesignTally& f = gouges[pr.owner[k]];
            ++f.points;
            if (below > f.amount) {
                f.amount = below;
                f.at = pr.points[k];
                f.height = (*probes.heights)[k];
                f.designed = pr.designed[k];
                f.line = (*probes.lines)[k];
            }
        }
    }
    // Material left: each cut over its own cells (another cut's deeper floor does not excuse it,
    // nor hide it: the height is below both then).
    for (std::size_t c = 0; c < design.cuts.size(); ++c) {
        const DesignCut& cut = design.cuts[c];
        if (cut.overrides || cut.may_leave) continue;
        design_pieces(cut, [&](const DesignPiece& piece) {
            const DesignFloor floor = design_floor(cut, piece.outer.centre);
            design_cells(piece, -margin, g, [&](std::size_t i, std::size_t j, Vec2 p) {
                if (flags[at(i, j)] & (may_leave | edge)) return;
                const double h = g.height(i, j);
                const double limit = std::max(floor.at(p) + cut.axial_allowance, g.bottom);
                if (std::isnan(h) || h - limit <= tolerance) return;
                DesignTally& f = left[static_cast<std::uint32_t>(c)];
                ++f.cells;
                if (h - limit > f.amount) f.amount = h - limit, f.at = p, f.height = h, f.designed = limit;
            });
        });
    }
    // In the design's order: gouges by feature, then what is left by cut.
    auto finding = [&](std::uint32_t k, const DesignTally& t, DesignFinding::Kind kind) {
        DesignFinding f;
        f.kind = kind;
        f.amount = t.amount, f.at = t.at, f.height = t.height, f.designed = t.designed;
        f.cells = t.cells, f.points = t.points, f.line = t.line;
        const bool is_cut = k < design.cuts.size();
        f.path = is_cut ? design.cuts[k].path : design.keeps[k - design.cuts.size()].path;
        f.what = is_cut ? design.cuts[k].what : design.keeps[k - design.cuts.size()].what;
        // A feature of discs: the hole nearest the worst point ("hole 3 at (20, 10)").
        if (const auto& discs = is_cut ? design.cuts[k].discs : design.keeps[k - design.cuts.size()].discs) {
            std::size_t best = 0;
            for (std::size_t q = 1; q < discs->centres.size(); ++q)
                if (distance(discs->centres[q], t.at) < distance(discs->centres[best], t.at)) best = q;
            const Vec2 c = discs->centres[best];
            f.what = fmt::format("{} {} at ({}, {})", f.what, best, number_text(c.x), number_text(c.y));
        }
        return f;
    };
    std::vector<DesignFinding> out;
    for (auto* group : {&gouges, &left}) {
        std::vector<std::uint32_t> keys;
        for (const auto& [k, t] : *group) keys.push_back(k);
        std::sort(keys.begin(), keys.end());
        for (std::uint32_t k : keys)
            out.push_back(finding(k, group->at(k), group == &gouges ? DesignFinding::Kind::gouge : DesignFinding::Kind::left));
    }
    return out;
}

void leave_out_operator_cycles(PartDesign& design, const Job& job, const Machine& machine) {
    auto left_out = [&](const std::string& path, const std::string& why) {
        design.unchecked.push_back(fmt::format("{}: the program leaves its cycle to the operator at a stop ({})", path, why));
    };
    for (const Operation& op : job.operations) {
        if (const auto* drill = std::get_if<DrillOp>(&op)) {
            const auto tool = job.tools.find(drill->tool);
            if (tool == job.tools.end()) continue;
            const std::optional<std::string> why = impossible_cycle(machine, resolve_cycle(*drill, tool->second));
            if (!why) continue;
            std::erase_if(design.cuts, [&](const DesignCut& c) { return c.path == drill->path; });
            left_out(drill->path, *why);
        } else if (const auto* turn = std::get_if<TurnDrillOp>(&op)) {
            const std::optional<std::string> why = impossible_cycle(machine, turn->cycle);
            if (!why) continue;
            std::erase_if(design.lathe.holes, [&](const LatheHoleDesign& h) { return h.path == turn->path; });
            left_out(turn->path, *why);
        }
    }
}

}  // namespace camgen
