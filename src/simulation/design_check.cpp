// A simulated part against the job's design (design_check.hpp).
#include "camgen/simulation/design_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <fmt/format.h>

#include "camgen/common/number_text.hpp"
#include "camgen/geometry/region.hpp"

namespace camgen {

namespace {

// Calls f(i, j, centre) for every cell whose centre lies in the region grown (d > 0) or shrunk
// (d < 0) by |d|.
template <class F>
void design_cells(const PlaneRegion& region, double d, const HeightGridView& g, F f) {
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

}  // namespace

std::string DesignFinding::message() const {
    const std::string where = fmt::format("({}, {})", number_text(at.x, 3), number_text(at.y, 3));
    if (kind == Kind::gouge)
        return fmt::format("{} ({}): material removed {} mm below the designed {} at {}{} ({} cells of the part cut)", path, what,
                           number_text(amount, 3), number_text(designed, 3), where,
                           line > 0 ? fmt::format(", by line {}", line) : std::string(), cells);
    return fmt::format("{} ({}): material left {} mm above its floor and allowance {} at {} ({} cells)", path, what,
                       number_text(amount, 3), number_text(designed, 3), where, cells);
}

std::vector<DesignFinding> check_design(const PartDesign& design, const HeightGridView& g, double tolerance, double margin) {
    const std::size_t n = g.nx * g.ny;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> designed(n, nan);
    std::vector<std::int32_t> owner(n, -1);  // cuts 0..C-1, keeps C..
    enum : std::uint8_t { near_cut = 1, may_leave = 2, edge = 4 };
    std::vector<std::uint8_t> flags(n, 0);
    const auto at = [&](std::size_t i, std::size_t j) { return j * g.nx + i; };
    const std::int32_t cuts = static_cast<std::int32_t>(design.cuts.size());

    // A cell within the margin of a cut's edge, inside or out, could be that cut's or not: it
    // is judged by nothing (edge).
    std::vector<std::int32_t> strict(n, -1);
    for (std::int32_t c = 0; c < cuts; ++c) {
        const DesignCut& cut = design.cuts[static_cast<std::size_t>(c)];
        design_cells(cut.region, -margin, g, [&](std::size_t i, std::size_t j, Vec2 p) {
            strict[at(i, j)] = c;
            if (cut.overrides) return;
            const double f = cut.floor.at(p);
            double& d = designed[at(i, j)];
            if (std::isnan(d) || f < d) d = f, owner[at(i, j)] = c;
        });
        design_cells(cut.region, margin, g, [&](std::size_t i, std::size_t j, Vec2) {
            std::uint8_t& fl = flags[at(i, j)];
            fl |= near_cut | (cut.may_leave ? may_leave : 0);
            if (!cut.overrides && strict[at(i, j)] != c) fl |= edge;
        });
    }
    for (std::int32_t c = 0; c < cuts; ++c) {
        const DesignCut& cut = design.cuts[static_cast<std::size_t>(c)];
        if (!cut.overrides) continue;
        design_cells(cut.region, -margin, g, [&](std::size_t i, std::size_t j, Vec2 p) {
            designed[at(i, j)] = cut.floor.at(p);
            owner[at(i, j)] = c;
        });
    }
    for (std::size_t k = 0; k < design.keeps.size(); ++k) {
        const DesignKeep& keep = design.keeps[k];
        design_cells(keep.region, -margin, g, [&](std::size_t i, std::size_t j, Vec2) {
            const std::size_t a = at(i, j);
            if (flags[a] & near_cut) return;
            if (std::isnan(designed[a]) || keep.top_z < designed[a]) designed[a] = keep.top_z, owner[a] = cuts + static_cast<std::int32_t>(k);
        });
    }

    // Outside a profile stock there is nothing to judge.
    if (g.stock) {
        std::vector<std::uint8_t> inside(n, 0);
        design_cells(*g.stock, 0.0, g, [&](std::size_t i, std::size_t j, Vec2) { inside[at(i, j)] = 1; });
        for (std::size_t a = 0; a < n; ++a)
            if (!inside[a]) owner[a] = -1, flags[a] |= edge;
    }
    const std::size_t features = design.cuts.size() + design.keeps.size();
    std::vector<DesignFinding> gouges(features), left(design.cuts.size());
    for (std::size_t j = 0; j < g.ny; ++j)
        for (std::size_t i = 0; i < g.nx; ++i) {
            const std::size_t a = at(i, j);
            if (owner[a] < 0 || (flags[a] & edge)) continue;
            const double h = g.height(i, j);
            if (std::isnan(h)) continue;
            const double below = std::min(designed[a], g.top) - h;
            if (below > tolerance) {
                DesignFinding& f = gouges[static_cast<std::size_t>(owner[a])];
                ++f.cells;
                if (below > f.amount) {
                    f.amount = below;
                    f.at = {g.x0 + (static_cast<double>(i) + 0.5) * g.cell, g.y0 + (static_cast<double>(j) + 0.5) * g.cell};
                    f.height = h;
                    f.designed = std::min(designed[a], g.top);
                    f.line = g.line ? g.line(i, j) : 0;
                }
            }
        }
    // Material left: each cut over its own cells (another cut's deeper floor does not excuse it,
    // nor hide it: the height is below both then).
    for (std::size_t c = 0; c < design.cuts.size(); ++c) {
        const DesignCut& cut = design.cuts[c];
        if (cut.overrides || cut.may_leave) continue;
        design_cells(cut.region, -margin, g, [&](std::size_t i, std::size_t j, Vec2 p) {
            if (flags[at(i, j)] & (may_leave | edge)) return;
            const double h = g.height(i, j);
            const double limit = std::max(cut.floor.at(p) + cut.axial_allowance, g.bottom);
            if (std::isnan(h) || h - limit <= tolerance) return;
            DesignFinding& f = left[c];
            ++f.cells;
            if (h - limit > f.amount) f.amount = h - limit, f.at = p, f.height = h, f.designed = limit;
        });
    }
    std::vector<DesignFinding> out;
    for (std::size_t k = 0; k < features; ++k) {
        if (gouges[k].cells == 0) continue;
        DesignFinding f = gouges[k];
        f.kind = DesignFinding::Kind::gouge;
        f.path = k < design.cuts.size() ? design.cuts[k].path : design.keeps[k - design.cuts.size()].path;
        f.what = k < design.cuts.size() ? design.cuts[k].what : design.keeps[k - design.cuts.size()].what;
        out.push_back(std::move(f));
    }
    for (std::size_t c = 0; c < design.cuts.size(); ++c) {
        if (left[c].cells == 0) continue;
        DesignFinding f = left[c];
        f.kind = DesignFinding::Kind::left;
        f.path = design.cuts[c].path;
        f.what = design.cuts[c].what;
        out.push_back(std::move(f));
    }
    return out;
}

}  // namespace camgen
