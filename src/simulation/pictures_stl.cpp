// The simulated part as a binary STL: a mill's height field as cell columns, a lathe's profile
// revolved. The triangles are made twice, once counted and once written, so that nothing but
// the (merged) part is held.
#include "camgen/simulation/pictures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>

#include <fmt/format.h>

namespace camgen {

namespace {

struct StlVertex {
    double x = 0, y = 0, z = 0;
};

// Hands each triangle, oriented so that its normal points along `outward`, to a writer.
class StlEmitter {
public:
    explicit StlEmitter(std::ostream* out) : out_(out) {}
    void triangle(StlVertex a, StlVertex b, StlVertex c, StlVertex outward) {
        StlVertex n = normal(a, b, c);
        if (n.x * outward.x + n.y * outward.y + n.z * outward.z < 0) {
            std::swap(b, c);
            n = {-n.x, -n.y, -n.z};
        }
        ++count_;
        if (!out_) return;
        std::array<char, 50> rec{};
        const std::array<float, 12> v{static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z),
                                      static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z),
                                      static_cast<float>(b.x), static_cast<float>(b.y), static_cast<float>(b.z),
                                      static_cast<float>(c.x), static_cast<float>(c.y), static_cast<float>(c.z)};
        for (std::size_t k = 0; k < v.size(); ++k) put32(&rec[4 * k], v[k] == 0.0f ? 0.0f : v[k]);  // no -0
        out_->write(rec.data(), rec.size());
    }
    // Two triangles of the quad a b c d (in order around it).
    void quad(StlVertex a, StlVertex b, StlVertex c, StlVertex d, StlVertex outward) {
        triangle(a, b, c, outward);
        triangle(a, c, d, outward);
    }
    std::size_t count() const { return count_; }

    static void put32(char* at, float value) {
        std::uint32_t bits;
        std::memcpy(&bits, &value, 4);
        for (int k = 0; k < 4; ++k) at[k] = static_cast<char>((bits >> (8 * k)) & 0xff);  // little-endian
    }

private:
    static StlVertex normal(StlVertex a, StlVertex b, StlVertex c) {
        const StlVertex u{b.x - a.x, b.y - a.y, b.z - a.z}, v{c.x - a.x, c.y - a.y, c.z - a.z};
        StlVertex n{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
        const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
        if (len > 0) n = {n.x / len, n.y / len, n.z / len};
        return n;
    }
    std::ostream* out_;
    std::size_t count_ = 0;
};

// A mill's part as blocks of k x k cells: the grid's edges and each block's height (the
// stock's bottom where it holds no material).
struct StlBlocks {
    std::vector<double> xs, ys;  // bx + 1, by + 1 edges, mm
    std::vector<double> height;  // bx * by
    std::vector<char> material;
    int bx = 0, by = 0;
    double bottom = 0;
    // A block's height, or the bottom outside the grid or without material.
    double at(int i, int j) const {
        if (i < 0 || j < 0 || i >= bx || j >= by) return bottom;
        const std::size_t k = static_cast<std::size_t>(j) * bx + i;
        return material[k] ? height[k] : bottom;
    }
};

StlBlocks stl_blocks(const HeightField& f, int k) {
    StlBlocks b;
    b.bx = (f.nx + k - 1) / k, b.by = (f.ny + k - 1) / k;
    b.bottom = f.bottom;
    for (int i = 0; i <= b.bx; ++i) b.xs.push_back(f.x0 + std::min(i * k, f.nx) * f.cell);
    for (int j = 0; j <= b.by; ++j) b.ys.push_back(f.y0 + std::min(j * k, f.ny) * f.cell);
    b.height.assign(static_cast<std::size_t>(b.bx) * b.by, 0.0);
    b.material.assign(b.height.size(), 0);
    std::vector<double> sum(static_cast<std::size_t>(b.bx)), count(static_cast<std::size_t>(b.bx));
    for (int bj = 0; bj < b.by; ++bj) {
        std::fill(sum.begin(), sum.end(), 0.0);
        std::fill(count.begin(), count.end(), 0.0);
        for (int j = bj * k; j < std::min((bj + 1) * k, f.ny); ++j)
            for (int i = 0; i < f.nx; ++i) {
                sum[static_cast<std::size_t>(i / k)] += static_cast<double>(f.heights[static_cast<std::size_t>(j) * f.nx + i]) - f.bottom;
                count[static_cast<std::size_t>(i / k)] += 1;
            }
        for (int bi = 0; bi < b.bx; ++bi) {
            const std::size_t at = static_cast<std::size_t>(bj) * b.bx + bi;
            // k = 1: the cell's own height; else the mean, which keeps the block's volume.
            const double mean = sum[static_cast<std::size_t>(bi)] / count[static_cast<std::size_t>(bi)];
            b.height[at] = k == 1 ? static_cast<double>(f.heights[static_cast<std::size_t>(bj) * f.nx + bi]) : f.bottom + mean;
            b.material[at] = b.height[at] > f.bottom;
        }
    }
    return b;
}

// The heights where columns meet the vertical line at grid vertex (i, j) (the four blocks
// around it), within (lo, hi), ascending, with lo and hi at the ends.
std::vector<double> stl_breaks(const StlBlocks& b, int i, int j, double lo, double hi) {
    std::vector<double> z{lo, hi};
    for (auto [di, dj] : {std::pair{-1, -1}, {0, -1}, {-1, 0}, {0, 0}}) {
        const double h = b.at(i + di, j + dj);
        if (h > lo && h < hi) z.push_back(h);
    }
    std::sort(z.begin(), z.end());
    z.erase(std::unique(z.begin(), z.end()), z.end());
    return z;
}

// A wall on the grid edge from vertex p to vertex q (grid indices), between heights lo and hi,
// facing `outward`: a ladder of triangles between its two vertical sides, each split where the
// columns around that vertex meet it.
void stl_wall(const StlBlocks& b, int pi, int pj, int qi, int qj, double lo, double hi, StlVertex outward, StlEmitter& e) {
    const std::vector<double> zp = stl_breaks(b, pi, pj, lo, hi), zq = stl_breaks(b, qi, qj, lo, hi);
    const double px = b.xs[static_cast<std::size_t>(pi)], py = b.ys[static_cast<std::size_t>(pj)];
    const double qx = b.xs[static_cast<std::size_t>(qi)], qy = b.ys[static_cast<std::size_t>(qj)];
    std::size_t i = 0, j = 0;
    while (i + 1 < zp.size() || j + 1 < zq.size()) {
        if (i + 1 < zp.size() && (j + 1 == zq.size() || zp[i + 1] <= zq[j + 1])) {
            e.triangle({px, py, zp[i]}, {px, py, zp[i + 1]}, {qx, qy, zq[j]}, outward);
            ++i;
        } else {
            e.triangle({px, py, zp[i]}, {qx, qy, zq[j + 1]}, {qx, qy, zq[j]}, outward);
            ++j;
        }
    }
}

void stl_mill(const StlBlocks& b, StlEmitter& e) {
    for (int j = 0; j < b.by; ++j)
        for (int i = 0; i < b.bx; ++i) {
            if (!b.material[static_cast<std::size_t>(j) * b.bx + i]) continue;
            const double x0 = b.xs[static_cast<std::size_t>(i)], x1 = b.xs[static_cast<std::size_t>(i) + 1];
            const double y0 = b.ys[static_cast<std::size_t>(j)], y1 = b.ys[static_cast<std::size_t>(j) + 1];
            const double h = b.at(i, j);
            e.quad({x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}, {0, 0, 1});
            e.quad({x0, y0, b.bottom}, {x1, y0, b.bottom}, {x1, y1, b.bottom}, {x0, y1, b.bottom}, {0, 0, -1});
        }
    // Walls on the edges x = xs[i] (between blocks i - 1 and i) and y = ys[j].
    for (int j = 0; j < b.by; ++j)
        for (int i = 0; i <= b.bx; ++i) {
            const double l = b.at(i - 1, j), r = b.at(i, j);
            if (l == r) continue;
            stl_wall(b, i, j, i, j + 1, std::min(l, r), std::max(l, r), {l > r ? 1.0 : -1.0, 0, 0}, e);
        }
    for (int j = 0; j <= b.by; ++j)
        for (int i = 0; i < b.bx; ++i) {
            const double d = b.at(i, j - 1), u = b.at(i, j);
            if (d == u) continue;
            stl_wall(b, i, j, i + 1, j, std::min(d, u), std::max(d, u), {0, d > u ? 1.0 : -1.0, 0}, e);
        }
}

// A lathe's part as bands along Z: from z, each an outside radius and a bore (no material
// where the outside is not above the bore), less rings of air (a face groove's: sorted, inside).
struct StlBand {
    double z0 = 0, z1 = 0, outside = 0, bore = 0;
    std::vector<std::pair<double, double>> gaps;
    bool material() const { return outside > bore; }
};

std::vector<StlBand> stl_bands(const LatheProfile& p, std::size_t budget) {
    const int m = static_cast<int>(std::max<std::size_t>(1, (static_cast<std::size_t>(p.nz) + budget - 1) / std::max<std::size_t>(budget, 1)));
    std::vector<StlBand> bands;
    for (int k0 = 0; k0 < p.nz; k0 += m) {
        const int k1 = std::min(p.nz, k0 + m);
        StlBand band{p.z0 + k0 * p.dz, p.z0 + k1 * p.dz, 0, 0, {}};
        if (m == 1) {
            if (p.outside[static_cast<std::size_t>(k0)] > p.bore[static_cast<std::size_t>(k0)]) {
                band.outside = p.outside[static_cast<std::size_t>(k0)], band.bore = p.bore[static_cast<std::size_t>(k0)];
                if (const std::vector<LatheGap>* gaps = p.gaps_at(k0))
                    for (const LatheGap& g : *gaps) band.gaps.emplace_back(g.lo, g.hi);
            }
        } else {
            // The mean ring area over the band, and the mean square bore of its samples with
            // material: the band's volume kept. Where every such sample has as many rings of
            // air, the rings' mean square radii too (and the outside wider by their area), if
            // they stay in order inside; else their area comes off the outside.
            double area = 0, bore2 = 0;
            int solid = 0;
            std::vector<std::pair<double, double>> gap2;  // sums of lo^2 and hi^2
            bool same = true;
            for (int k = k0; k < k1; ++k) {
                const double r = p.outside[static_cast<std::size_t>(k)], b = p.bore[static_cast<std::size_t>(k)];
                if (!(r > b)) continue;
                area += r * r - b * b, bore2 += b * b;
                const std::vector<LatheGap>* gaps = p.gaps_at(k);
                const std::size_t n = gaps ? gaps->size() : 0;
                if (solid == 0) gap2.assign(n, {0.0, 0.0});
                else if (n != gap2.size()) same = false;
                for (std::size_t j = 0; j < n; ++j) {
                    const LatheGap& g = (*gaps)[j];
                    area -= g.hi * g.hi - g.lo * g.lo;
                    if (same && j < gap2.size()) gap2[j].first += g.lo * g.lo, gap2[j].second += g.hi * g.hi;
                }
                ++solid;
            }
            if (solid > 0 && area > 0) {
                band.bore = std::sqrt(bore2 / solid);
                double within = 0;  // the rings' mean area, (k1 - k0) samples
                if (same)
                    for (const auto& [lo2, hi2] : gap2) {
                        band.gaps.emplace_back(std::sqrt(lo2 / solid), std::sqrt(hi2 / solid));
                        within += (hi2 - lo2) / (k1 - k0);
                    }
                band.outside = std::sqrt(band.bore * band.bore + area / (k1 - k0) + within);
                double at = band.bore;
                for (const auto& [lo, hi] : band.gaps) {
                    if (!(lo > at && hi > lo)) same = false;
                    at = hi;
                }
                if (!same || !(band.outside > at)) {
                    band.gaps.clear();
                    band.outside = std::sqrt(band.bore * band.bore + area / (k1 - k0));
                }
            }
        }
        if (!bands.empty() && bands.back().outside == band.outside && bands.back().bore == band.bore && bands.back().gaps == band.gaps)
            bands.back().z1 = band.z1;
        else bands.push_back(band);
    }
    return bands;
}

void stl_lathe(const std::vector<StlBand>& bands, int n, StlEmitter& e) {
    std::vector<double> c(static_cast<std::size_t>(n) + 1), s(static_cast<std::size_t>(n) + 1);
    for (int k = 0; k <= n; ++k) {
        const double a = two_pi * (k % n) / n;
        c[static_cast<std::size_t>(k)] = std::cos(a), s[static_cast<std::size_t>(k)] = std::sin(a);
    }
    auto at = [&](double r, int k, double z) { return StlVertex{r * c[static_cast<std::size_t>(k)], r * s[static_cast<std::size_t>(k)], z}; };
    // A cylinder of radius r from z0 to z1, facing out (+1) or in (-1).
    auto cylinder = [&](double r, double z0, double z1, double side) {
        for (int k = 0; k < n; ++k) {
            const double mid = two_pi * (k + 0.5) / n;
            e.quad(at(r, k, z0), at(r, k + 1, z0), at(r, k + 1, z1), at(r, k, z1), {side * std::cos(mid), side * std::sin(mid), 0});
        }
    };
    // The flat ring from r0 to r1 at z, facing up (+1) or down (-1); a disc where r0 is 0.
    auto ring = [&](double r0, double r1, double z, double side) {
        for (int k = 0; k < n; ++k) {
            if (r0 > 0) e.quad(at(r0, k, z), at(r1, k, z), at(r1, k + 1, z), at(r0, k + 1, z), {0, 0, side});
            else e.triangle({0, 0, z}, at(r1, k, z), at(r1, k + 1, z), {0, 0, side});
        }
    };
    for (std::size_t k = 0; k <= bands.size(); ++k) {
        // The face at the foot of band k: what the band below holds and this one does not faces
        // up, the reverse down.
        const StlBand* below = k > 0 && bands[k - 1].material() ? &bands[k - 1] : nullptr;
        const StlBand* above = k < bands.size() && bands[k].material() ? &bands[k] : nullptr;
        const double z = k < bands.size() ? bands[k].z0 : bands[k - 1].z1;
        std::vector<double> cuts;
        for (const StlBand* b : {below, above})
            if (b) {
                cuts.push_back(b->bore), cuts.push_back(b->outside);
                for (const auto& [lo, hi] : b->gaps) cuts.push_back(lo), cuts.push_back(hi);
            }
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
        auto in = [](const StlBand* b, double r) {
            if (!b || !(r > b->bore && r < b->outside)) return false;
            for (const auto& [lo, hi] : b->gaps)
                if (r > lo && r < hi) return false;
            return true;
        };
        for (std::size_t a = 0; a + 1 < cuts.size();) {
            const double mid = (cuts[a] + cuts[a + 1]) / 2;
            const int side = in(below, mid) == in(above, mid) ? 0 : in(below, mid) ? 1 : -1;
            std::size_t b = a + 1;
            while (side != 0 && b + 1 < cuts.size()) {
                const double next = (cuts[b] + cuts[b + 1]) / 2;
                const int next_side = in(below, next) == in(above, next) ? 0 : in(below, next) ? 1 : -1;
                if (next_side != side) break;
                ++b;
            }
            if (side != 0) ring(cuts[a], cuts[b], z, side);
            a = b;
        }
        if (above) {
            cylinder(above->outside, above->z0, above->z1, 1);
            if (above->bore > 0) cylinder(above->bore, above->z0, above->z1, -1);
            for (const auto& [lo, hi] : above->gaps) cylinder(lo, above->z0, above->z1, 1), cylinder(hi, above->z0, above->z1, -1);
        }
    }
}

}  // namespace

StlSummary write_simulation_stl(const SimResult& r, const StlOptions& options, std::ostream& out) {
    StlSummary summary;
    std::optional<StlBlocks> blocks;
    if (r.kind == MachineKind::lathe) {
        if (options.lathe_segments < 3) throw SimInputError("a revolved part needs at least 3 segments");
        const std::size_t m = (static_cast<std::size_t>(r.lathe.nz) + options.lathe_bands - 1) / std::max<std::size_t>(options.lathe_bands, 1);
        summary.block = static_cast<int>(std::max<std::size_t>(m, 1));
    } else {
        const HeightField& f = r.field;
        const double cells = static_cast<double>(f.nx) * f.ny;
        int k = 1;
        while (cells / (static_cast<double>(k) * k) > static_cast<double>(std::max<std::size_t>(options.mill_cells, 1))) ++k;
        summary.block = k;
        blocks = stl_blocks(f, k);
    }
    auto run = [&](StlEmitter& e) {
        if (blocks) stl_mill(*blocks, e);
        else stl_lathe(stl_bands(r.lathe, options.lathe_bands), options.lathe_segments, e);
    };
    StlEmitter counter(nullptr);
    run(counter);
    summary.triangles = counter.count();
    std::array<char, 84> head{};
    const std::string title = r.kind == MachineKind::lathe
                                  ? fmt::format("camgen simulated part (lathe, mm, Z the spindle's axis, {} segments)", options.lathe_segments)
                                  : std::string("camgen simulated part (mill, mm)");
    std::fill(head.begin(), head.begin() + 80, ' ');
    std::copy_n(title.begin(), std::min<std::size_t>(title.size(), 80), head.begin());
    const auto n = static_cast<std::uint32_t>(summary.triangles);
    for (int k = 0; k < 4; ++k) head[static_cast<std::size_t>(80 + k)] = static_cast<char>((n >> (8 * k)) & 0xff);
    out.write(head.data(), head.size());
    StlEmitter writer(&out);
    run(writer);
    return summary;
}

}  // namespace camgen
