// Material simulation: steps swept through a height field (mill) or a turned profile (lathe).
// See simulation.hpp for what is exact and the bounds of what is not.
#include "camgen/simulation/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "camgen/common/number_text.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen {

namespace {

constexpr double sim_tiny = 1e-12;
// Material thinner than this above a tool's surface does not count as engaged, mm.
constexpr double sim_engaged_above = 1e-3;
// Golden-section iterations: the bracket shrinks to 0.618^50 < 1e-10 of the move.
constexpr int sim_golden_iterations = 50;
constexpr double sim_golden = 0.6180339887498949;
// The most engagement samples along one move.
constexpr int sim_engagement_samples = 256;
// Probe columns are found by blocks of this many cells a side.
constexpr int sim_probe_block = 16;
// mm: the largest sagitta of a helix's chords (an arc in XY at one height is swept exactly).
constexpr double sim_helix_sagitta = 0.0005;

// The height of a tool's lowest surface above its tip at `r` mm from its axis (r <= radius).
struct SimProfile {
    ToolForm form = ToolForm::flat;
    double radius = 0.0;
    double corner = 0.0;    // bull_nose
    double flat = 0.0;      // bull_nose: radius - corner; cone: tip radius
    double slope = 0.0;     // cone: rise per mm of radius
    double operator()(double r) const {
        switch (form) {
        case ToolForm::flat:
        case ToolForm::cylinder:
        case ToolForm::turning:
        case ToolForm::blade: return 0.0;
        case ToolForm::ball: return radius - std::sqrt(std::max(0.0, radius * radius - r * r));
        case ToolForm::bull_nose: {
            if (r <= flat) return 0.0;
            const double s = r - flat;
            return corner - std::sqrt(std::max(0.0, corner * corner - s * s));
        }
        case ToolForm::cone: return r <= flat ? 0.0 : (r - flat) * slope;
        }
        return 0.0;
    }
};

SimProfile sim_profile_of(const ToolShape& t) {
    SimProfile p;
    p.form = t.form;
    p.radius = t.diameter / 2;
    if (t.form == ToolForm::bull_nose) {
        p.corner = std::min(t.corner_radius, p.radius);
        p.flat = p.radius - p.corner;
    } else if (t.form == ToolForm::cone) {
        p.flat = std::min(t.tip_diameter / 2, p.radius);
        p.slope = 1.0 / std::tan(t.tip_angle / 2 * rad_per_deg);
    }
    return p;
}

// lo <= k * x + c <= hi narrows [xlo, xhi]; false when empty.
bool sim_clip(double k, double c, double lo, double hi, double& xlo, double& xhi) {
    if (std::abs(k) < sim_tiny) return c >= lo && c <= hi;
    double a = (lo - c) / k, b = (hi - c) / k;
    if (a > b) std::swap(a, b);
    xlo = std::max(xlo, a);
    xhi = std::min(xhi, b);
    return xlo <= xhi;
}

// What one move did: its deepest cut below the surface as it was, its volume.
struct SimMoveAcc {
    double volume = 0.0;     // mm^3
    double max_depth = 0.0;  // mm: the deepest material removed in one column (a crash's measure)
    double flute_depth = 0.0;  // mm: how far below the material's surface before the move the tool cut
    double engagement = 0.0; // fraction of the diameter
};

// The lowest surface of a tool whose tip moves straight from a to b, over the column at (x, y):
// +inf where the tool does not pass over it. Exact for every form on horizontal and vertical
// moves, for flat, cylinder and ball on any move; bull-nose and cone on a sloping move by
// golden-section search (see simulation.hpp).
struct SimLineColumns {
    Vec3 a, b;
    SimProfile prof;
    double R, vx, vy, dz, len2, len, ux, uy, dlen, Dx, Dy, Dz, zlow;
    bool level;
    SimLineColumns(const Vec3& a_, const Vec3& b_, const SimProfile& p)
        : a(a_), b(b_), prof(p), R(p.radius), vx(b_.x - a_.x), vy(b_.y - a_.y), dz(b_.z - a_.z) {
        len2 = vx * vx + vy * vy, len = std::sqrt(len2);
        ux = len > 0 ? vx / len : 0.0, uy = len > 0 ? vy / len : 0.0;
        level = std::abs(dz) < sim_tiny;
        dlen = std::sqrt(len2 + dz * dz);
        Dx = dlen > 0 ? vx / dlen : 0, Dy = dlen > 0 ? vy / dlen : 0, Dz = dlen > 0 ? dz / dlen : 0;
        zlow = std::min(a.z, b.z);
    }
    [[gnu::always_inline]] double low(double x, double y) const {
        constexpr double none = std::numeric_limits<double>::infinity();
        const double wx = x - a.x, wy = y - a.y;
        const double w2 = wx * wx + wy * wy;
        if (len2 < sim_tiny) return w2 > R * R ? none : zlow + prof(std::sqrt(w2));
        if (level) {
            const double t = std::clamp((wx * vx + wy * vy) / len2, 0.0, 1.0);
            const double ex = wx - t * vx, ey = wy - t * vy;
            const double d2 = ex * ex + ey * ey;
            return d2 > R * R ? none : a.z + prof(std::sqrt(d2));
        }
        // The covered interval: |w - t v|^2 <= R^2.
        const double B = -2 * (wx * vx + wy * vy), C = w2 - R * R;
        const double disc = B * B - 4 * len2 * C;
        if (disc < 0) return none;
        const double sq = std::sqrt(disc);
        const double t1 = std::max(0.0, (-B - sq) / (2 * len2)), t2 = std::min(1.0, (-B + sq) / (2 * len2));
        if (t1 > t2) return none;
        if (prof.form == ToolForm::flat || prof.form == ToolForm::cylinder) return a.z + dz * (dz < 0 ? t2 : t1);
        if (prof.form == ToolForm::ball) {
            double z = none;
            for (const Vec3* e : {&a, &b}) {
                const double ex = x - e->x, ey = y - e->y, d2 = ex * ex + ey * ey;
                if (d2 <= R * R) z = std::min(z, e->z + R - std::sqrt(R * R - d2));
            }
            // The cylinder around the centre line: |q - A|^2 - ((q - A).D)^2 = R^2 on the column.
            const double k = wx * Dx + wy * Dy;
            const double qa = 1 - Dz * Dz, qb = -2 * k * Dz, qc = w2 - k * k - R * R;
            const double qd = qb * qb - 4 * qa * qc;
            if (qa > sim_tiny && qd >= 0) {
                const double zr = (-qb - std::sqrt(qd)) / (2 * qa);
                const double foot = k + zr * Dz;
                if (foot >= 0 && foot <= dlen) z = std::min(z, a.z + R + zr);
            }
            return z;
        }
        auto g = [&](double t) __attribute__((always_inline)) {
            const double ex = wx - t * vx, ey = wy - t * vy;
            return a.z + dz * t + prof(std::min(R, std::sqrt(ex * ex + ey * ey)));
        };
        double lo_t = t1, hi_t = t2;
        double m1 = hi_t - sim_golden * (hi_t - lo_t), m2 = lo_t + sim_golden * (hi_t - lo_t);
        double g1 = g(m1), g2 = g(m2);
        for (int it = 0; it < sim_golden_iterations; ++it) {
            if (g1 <= g2) {
                hi_t = m2, m2 = m1, g2 = g1;
                m1 = hi_t - sim_golden * (hi_t - lo_t), g1 = g(m1);
            } else {
                lo_t = m1, m1 = m2, g1 = g2;
                m2 = lo_t + sim_golden * (hi_t - lo_t), g2 = g(m2);
            }
        }
        return std::min({g(t1), g(t2), g1, g2});
    }
};

// The same for an arc in XY at one height: the column's nearest point on the arc.
struct SimArcColumns {
    const ArcGeometry& arc;
    SimProfile prof;
    double R, r, cx, cy, sign, z0;
    bool full;
    SimArcColumns(const ArcGeometry& a, const SimProfile& p)
        : arc(a), prof(p), R(p.radius), r(a.radius), cx(a.centre.x), cy(a.centre.y),
          sign(a.direction == ArcDirection::ccw ? 1.0 : -1.0), z0(a.start.z), full(a.sweep >= two_pi - 1e-12) {}
    bool within(double angle) const {
        const double d = std::fmod(sign * (angle - arc.start_angle) + 8 * two_pi, two_pi);
        return full || d <= arc.sweep;
    }
    double low(double x, double y) const {
        constexpr double none = std::numeric_limits<double>::infinity();
        const double dx = x - cx, dy = y - cy;
        const double rho = std::hypot(dx, dy);
        double d;
        if (std::abs(rho - r) > R) return none;
        if (full || within(std::atan2(dy, dx))) {
            d = std::abs(rho - r);
        } else {
            d = std::min(std::hypot(x - arc.start.x, y - arc.start.y), std::hypot(x - arc.end.x, y - arc.end.y));
            if (d > R) return none;
        }
        return z0 + prof(d);
    }
};

// A direction `deg` degrees from +Z towards +X, as (Z, radius); exact along the axes.
Vec2 sim_unit_deg(double deg) {
    if (deg == 0.0) return {1.0, 0.0};
    if (deg == 90.0) return {0.0, 1.0};
    if (deg == 180.0) return {-1.0, 0.0};
    return {std::cos(deg * rad_per_deg), std::sin(deg * rad_per_deg)};
}

// A turning tool whose nose centre moves straight from a to b, in (Z, radius) of the frame in
// which it is an outside tool (its body towards +X): the nose disc of radius n and its flanks,
// rays tangent to the disc in the directions lo and hi (degrees from +Z towards +X, 0 <= lo <= hi
// <= 180: the insert fills the angle between them). The swept shape, the sum of the segment, the
// disc and the angle, is convex; the lower edge of the segment plus the angle lies on five
// pieces (the segment and the two rays from each end), so the swept shape's lower edge at Z z is
// the least of the discs at a and b and those pieces each moved n down along its normal.
// Closed form, a few operations a sample.
struct SimTurnSweep {
    struct Piece {
        Vec2 o, d;     // o + t d, 0 <= t <= t_max
        double t_max;
    };
    Vec2 a, b;
    double n;
    Piece rays[4];
    int nrays = 0;
    Piece seg{};
    bool has_seg = false;

    SimTurnSweep(Vec2 a_, Vec2 b_, double nose, double lo, double hi) : a(a_), b(b_), n(nose) {
        // The piece moved n along its normal that points down (-X); none along X (the discs at
        // its ends lie lower).
        auto moved = [&](Vec2 o, Vec2 d, double t_max, Piece& out) {
            const double len = std::hypot(d.x, d.y);
            if (!(len > 0) || std::abs(d.x) < sim_tiny * len) return false;
            Vec2 down{d.y / len, -d.x / len};
            if (down.y > 0) down = down * -1.0;
            out = {o + down * n, d, t_max};
            return true;
        };
        constexpr double none = std::numeric_limits<double>::infinity();
        for (Vec2 v : {a, b})
            for (double deg : {lo, hi})
                if (moved(v, sim_unit_deg(deg), none, rays[nrays])) ++nrays;
        has_seg = moved(a, b - a, 1.0, seg);
    }

    // The least radius the swept shape reaches at Z z (+infinity: it does not reach z).
    double low(double z) const {
        double r = std::numeric_limits<double>::infinity();
        for (Vec2 v : {a, b}) {
            const double e = z - v.x;
            if (std::abs(e) <= n) r = std::min(r, v.y - std::sqrt(std::max(0.0, n * n - e * e)));
        }
        auto piece = [&](const Piece& p) {
            const double t = (z - p.o.x) / p.d.x;
            if (t >= 0 && t <= p.t_max) r = std::min(r, p.o.y + t * p.d.y);
        };
        for (int i = 0; i < nrays; ++i) piece(rays[i]);
        if (has_seg) piece(seg);
        return r;
    }

    // The Z range [lo, hi] outside which the swept shape stays at or above radius `bound`
    // (the flanks rise away from the nose; one along Z never does: the range is unbounded).
    void extent(double bound, double& lo, double& hi) const {
        lo = std::min(a.x, b.x) - n, hi = std::max(a.x, b.x) + n;
        for (int i = 0; i < nrays; ++i) {
            const Piece& p = rays[i];
            const double t = p.o.y >= bound ? 0.0
                             : p.d.y > sim_tiny ? (bound - p.o.y) / p.d.y
                                                : std::numeric_limits<double>::infinity();
            const double z = p.o.x + t * p.d.x;
            lo = std::min(lo, z), hi = std::max(hi, z);
        }
    }
};

// Removes the radii [lo, hi] from the material at one Z (outside, bore, gaps): where it reaches
// the outside, the outside falls to lo (or to the edge of a gap it opens into); where it reaches
// the bore, the bore rises to hi (likewise); else it is a gap, merged with those it meets. Sets
// `out_changed` and `bore_changed`; gaps the move made or widened take `line`.
void sim_remove_radii(double& outside, double& bore, std::vector<LatheGap>& gaps, double lo, double hi, int line,
                      bool& out_changed, bool& bore_changed) {
    out_changed = bore_changed = false;
    if (!(outside > bore) || !(hi > lo) || hi <= bore || lo >= outside) return;
    if (hi >= outside) {
        double r = std::max(lo, 0.0);
        while (!gaps.empty() && gaps.back().lo >= r) gaps.pop_back();
        if (!gaps.empty() && gaps.back().hi >= r) r = gaps.back().lo, gaps.pop_back();
        outside = r, out_changed = true;
    } else if (lo <= bore) {
        double b = hi;
        std::size_t n = 0;
        while (n < gaps.size() && gaps[n].hi <= b) ++n;
        if (n < gaps.size() && gaps[n].lo <= b) b = gaps[n].hi, ++n;
        gaps.erase(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(n));
        bore = b, bore_changed = true;
    } else {
        auto first = std::lower_bound(gaps.begin(), gaps.end(), lo, [](const LatheGap& g, double v) { return g.hi < v; });
        auto last = first;
        double nlo = lo, nhi = hi;
        while (last != gaps.end() && last->lo <= hi) nlo = std::min(nlo, last->lo), nhi = std::max(nhi, last->hi), ++last;
        if (last - first == 1 && first->lo == nlo && first->hi == nhi) return;  // within a gap: air
        first = gaps.erase(first, last);
        gaps.insert(first, LatheGap{nlo, nhi, line});
    }
    if (!(outside > bore)) gaps.clear();
}

}  // namespace

double lathe_material_area(double outside, double bore, const std::vector<LatheGap>* gaps) {
    if (!(outside > bore)) return 0.0;
    double a = pi * (outside * outside - bore * bore);
    if (gaps)
        for (const LatheGap& g : *gaps) a -= pi * (g.hi * g.hi - g.lo * g.lo);
    return a;
}

double lathe_material_within(double outside, double bore, const std::vector<LatheGap>* gaps, double lo, double hi,
                             bool largest_piece) {
    if (!(outside > bore)) return 0.0;
    double total = 0.0, best = 0.0, from = bore;
    auto piece = [&](double a, double b) {
        const double len = std::min(b, hi) - std::max(a, lo);
        if (len > 0) total += len, best = std::max(best, len);
    };
    if (gaps)
        for (const LatheGap& g : *gaps) piece(from, g.lo), from = g.hi;
    piece(from, outside);
    return largest_piece ? best : total;
}

class Simulator::Impl {
public:
    Impl(const Machine& machine, SimStock stock, std::map<int, ToolShape> tools, SimOptions options)
        : stats_(machine), stock_(std::move(stock)), tools_(std::move(tools)), options_(std::move(options)) {
        result_.kind = machine.kind;
        for (const auto& [number, t] : tools_) check_tool(number, t);
        if (machine.kind == MachineKind::lathe) init_lathe();
        else init_mill();
    }

    void step(const Step& s) {
        stats_.step(s);
        line_ = s.line;
        if (s.kind != StepKind::rapid && s.kind != StepKind::feed) return;
        const ToolShape* tool = shape_of(s.tool, s.line);
        if (!tool) return;
        SimMoveAcc acc;
        if (result_.kind == MachineKind::lathe) lathe_move(s, *tool, acc);
        else mill_move(s, *tool, acc);
        account(s, *tool, acc);
    }
    void hole(const Hole& h) { stats_.hole(h); }
    void finish(const TraceSummary& summary) {
        stats_.finish(summary);
        result_.stats = stats_.stats();
        if (skipped_tool0_ > 0)
            result_.notes.push_back(fmt::format("{} moves before the first tool change were not swept (no tool)",
                                                skipped_tool0_));
        for (const SimFigure& f : result_.tools) {
            const auto it = tools_.find(f.tool);
            if (it != tools_.end() && it->second.thread_mill && f.max_engagement > thread_mill_engagement)
                result_.notes.push_back(fmt::format(
                    "line {}: tool {}, a thread mill, cuts {} % of its diameter into the stock: a thread mill cuts a "
                    "thread's depth into a bore or onto a boss made before it (an operation that makes them first)",
                    f.engagement_line, f.tool, number_text(f.max_engagement * 100, 1)));
        }
    }
    void begin_operation(std::string path) { current_op_ = std::move(path); }
    void observe(SimObserver* observer) { options_.observer = observer; }
    void report_error(int line, int tool, std::string message) {
        result_.errors.push_back({line, operation_of(line), tool, std::move(message)});
    }
    SimResult result_;

private:
    void check_tool(int number, const ToolShape& t) {
        auto bad = [&](const std::string& why) {
            throw SimInputError(fmt::format("tool {}: {}", number, why));
        };
        if (t.form != ToolForm::turning && !(t.diameter > 0)) bad("needs a diameter above 0");
        if (t.form == ToolForm::bull_nose && !(t.corner_radius >= 0 && t.corner_radius <= t.diameter / 2))
            bad("a corner radius from 0 to the tool's radius");
        if (t.form == ToolForm::cone && !(t.tip_angle > 0 && t.tip_angle < 180)) bad("a tip angle between 0 and 180 degrees");
        if (t.form == ToolForm::cone && !(t.tip_diameter >= 0 && t.tip_diameter <= t.diameter))
            bad("a tip diameter from 0 to the tool's diameter");
        if (t.form == ToolForm::turning && !(t.nose_radius >= 0)) bad("a nose radius of 0 or more");
        if (t.form == ToolForm::turning &&
            !(t.flank_lo >= 0 && t.flank_lo <= t.flank_hi && t.flank_hi <= 180 && t.flank_hi - t.flank_lo < 180))
            bad("flanks between 0 and 180 degrees from +Z, less than 180 apart");
        if (t.flute_length && !(*t.flute_length > 0)) bad("a flute length above 0");
    }

    const ToolShape* shape_of(int number, int line) {
        auto it = tools_.find(number);
        if (it != tools_.end()) return &it->second;
        if (number == 0) {
            ++skipped_tool0_;
            return nullptr;
        }
        throw SimInputError(fmt::format("line {}: tool {} has no shape to simulate", line, number));
    }

    // ---- mill ----------------------------------------------------------------------------

    void init_mill() {
        double x0, y0, x1, y1, top, bottom;
        std::vector<Vec2> polygon;
        if (stock_.kind == SimStock::Kind::box) {
            x0 = std::min(stock_.min.x, stock_.max.x), x1 = std::max(stock_.min.x, stock_.max.x);
            y0 = std::min(stock_.min.y, stock_.max.y), y1 = std::max(stock_.min.y, stock_.max.y);
            bottom = std::min(stock_.min.z, stock_.max.z), top = std::max(stock_.min.z, stock_.max.z);
        } else if (stock_.kind == SimStock::Kind::profile) {
            if (!is_closed(stock_.profile) || stock_.profile.segments.empty())
                throw SimInputError("the stock's profile is not closed");
            top = stock_.top, bottom = stock_.bottom;
            if (bottom > top) std::swap(top, bottom);
            polygon = sample_profile(stock_.profile, 0.001);
            x0 = y0 = std::numeric_limits<double>::infinity();
            x1 = y1 = -x0;
            for (Vec2 p : polygon) {
                x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
                y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
            }
        } else {
            throw SimInputError("a bar is a lathe's stock; a mill needs a box or a profile");
        }
        const double w = x1 - x0, h = y1 - y0;
        if (!(w > 0 && h > 0 && top > bottom) || !std::isfinite(w + h + top + bottom))
            throw SimInputError("the stock has no volume");
        double cell = options_.resolution;
        if (!(cell > 0)) {
            const double budget = static_cast<double>(std::max<std::size_t>(options_.cell_budget, 1));
            cell = std::ceil(std::sqrt(w * h / budget) * 1000.0 - 1e-9) / 1000.0;  // whole microns
            cell = std::max(cell, 0.001);
        }
        // Whole cells over the box may exceed the budget by a row and a column: a micron more.
        if (!(options_.resolution > 0))
            while (std::ceil(w / cell - 1e-9) * std::ceil(h / cell - 1e-9) > static_cast<double>(options_.cell_budget))
                cell += 0.001;
        const double nxd = std::ceil(w / cell - 1e-9), nyd = std::ceil(h / cell - 1e-9);
        if (nxd * nyd > 400e6) throw SimInputError(fmt::format("a resolution of {} mm makes {} cells, more than 400 million",
                                                               number_text(cell), number_text(nxd * nyd, 0)));
        HeightField& f = result_.field;
        f.x0 = x0, f.y0 = y0, f.cell = cell, f.nx = static_cast<int>(nxd), f.ny = static_cast<int>(nyd);
        f.bottom = bottom, f.top = top;
        f.heights.assign(static_cast<std::size_t>(f.nx) * f.ny, static_cast<float>(bottom));
        f.lines.assign(f.heights.size(), 0);
        for (int j = 0; j < f.ny; ++j) {
            const double y = f.y(j);
            if (y > y1) continue;
            float* row = &f.heights[static_cast<std::size_t>(j) * f.nx];
            if (polygon.empty()) {
                for (int i = 0; i < f.nx; ++i)
                    if (f.x(i) <= x1) row[i] = static_cast<float>(top);
                continue;
            }
            // Even-odd crossings of the row's centre line.
            std::vector<double> xs;
            for (std::size_t k = 0; k < polygon.size(); ++k) {
                Vec2 a = polygon[k], b = polygon[(k + 1) % polygon.size()];
                if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
            }
            std::sort(xs.begin(), xs.end());
            for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
                const int i0 = std::max(0, static_cast<int>(std::ceil((xs[k] - x0) / cell - 0.5)));
                const int i1 = std::min(f.nx - 1, static_cast<int>(std::floor((xs[k + 1] - x0) / cell - 0.5)));
                for (int i = i0; i <= i1; ++i) row[i] = static_cast<float>(top);
            }
        }
        result_.resolution = cell;
        result_.cells = f.heights.size();
        double sum = 0.0;
        for (float v : f.heights) sum += v - bottom;
        result_.initial_volume = sum * cell * cell;
        field_x1_ = x1, field_y1_ = y1;
        stock_polygon_ = std::move(polygon);
        if (!options_.probes.empty()) {
            std::vector<Vec2> probes = std::move(options_.probes);
            set_probes(std::move(probes));
        }
    }

public:
    // The probe columns: the stock's top where they lie in the stock, else NaN (no material,
    // nothing swept); indexed by blocks of cells.
    void set_probes(std::vector<Vec2> points) {
        if (result_.kind != MachineKind::mill) throw SimInputError("probes are a mill's");
        options_.probes = std::move(points);
        const std::vector<Vec2>& probes = options_.probes;
        const double x1 = field_x1_, y1 = field_y1_;
        const std::vector<Vec2>& polygon = stock_polygon_;
        if (probes.size() > std::numeric_limits<std::uint32_t>::max()) throw SimInputError("more than 2^32 probes");
        const HeightField& f = result_.field;
        result_.probe_heights.assign(probes.size(), std::numeric_limits<double>::quiet_NaN());
        result_.probe_lines.assign(probes.size(), 0);
        const double span = f.cell * sim_probe_block;
        probe_nx_ = (f.nx + sim_probe_block - 1) / sim_probe_block;
        probe_ny_ = (f.ny + sim_probe_block - 1) / sim_probe_block;
        const std::size_t blocks = static_cast<std::size_t>(probe_nx_) * static_cast<std::size_t>(probe_ny_);
        std::vector<std::size_t> block_of(probes.size(), blocks);
        probe_start_.assign(blocks + 1, 0);
        for (std::size_t k = 0; k < probes.size(); ++k) {
            const Vec2 q = probes[k];
            if (!(q.x >= f.x0 && q.x <= x1 && q.y >= f.y0 && q.y <= y1)) continue;
            bool inside = polygon.empty();
            for (std::size_t e = 0; e < polygon.size(); ++e) {
                const Vec2 a = polygon[e], b = polygon[(e + 1) % polygon.size()];
                if ((a.y <= q.y) != (b.y <= q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x)) inside = !inside;
            }
            if (!inside) continue;
            result_.probe_heights[k] = f.top;
            const int bx = std::min(probe_nx_ - 1, static_cast<int>((q.x - f.x0) / span));
            const int by = std::min(probe_ny_ - 1, static_cast<int>((q.y - f.y0) / span));
            block_of[k] = static_cast<std::size_t>(by) * static_cast<std::size_t>(probe_nx_) + static_cast<std::size_t>(bx);
            ++probe_start_[block_of[k] + 1];
        }
        for (std::size_t b = 0; b < blocks; ++b) probe_start_[b + 1] += probe_start_[b];
        probe_order_.assign(probe_start_[blocks], 0);
        std::vector<std::uint32_t> next(probe_start_.begin(), probe_start_.end() - 1);
        for (std::size_t k = 0; k < probes.size(); ++k)
            if (block_of[k] < blocks) probe_order_[next[block_of[k]]++] = static_cast<std::uint32_t>(k);
    }

private:

    // The rows [j0, j1] whose centres lie in [ylo, yhi] (empty: j0 > j1).
    void rows(double ylo, double yhi, int& j0, int& j1) const {
        const HeightField& f = result_.field;
        j0 = std::max(0, static_cast<int>(std::ceil((ylo - f.y0) / f.cell - 0.5)));
        j1 = std::min(f.ny - 1, static_cast<int>(std::floor((yhi - f.y0) / f.cell - 0.5)));
    }
    void columns(double xlo, double xhi, int& i0, int& i1) const {
        const HeightField& f = result_.field;
        i0 = std::max(0, static_cast<int>(std::ceil((xlo - f.x0) / f.cell - 0.5)));
        i1 = std::min(f.nx - 1, static_cast<int>(std::floor((xhi - f.x0) / f.cell - 0.5)));
    }

    // Lowers a column to `z` (not below the bottom).
    void lower(int i, int j, double z, SimMoveAcc& acc) {
        HeightField& f = result_.field;
        float& h = f.heights[static_cast<std::size_t>(j) * f.nx + i];
        const double nz = std::max(z, f.bottom);
        if (nz < h) {
            const double depth = h - nz;
            acc.volume += depth;
            acc.max_depth = std::max(acc.max_depth, depth);
            acc.flute_depth = acc.max_depth;
            h = static_cast<float>(nz);
            f.lines[static_cast<std::size_t>(j) * f.nx + i] = line_;
            if (options_.observer) options_.observer->lowered(static_cast<std::size_t>(j) * f.nx + i, h, line_);
        }
    }

    void mill_move(const Step& s, const ToolShape& tool, SimMoveAcc& acc) {
        if (s.tool != profile_tool_) profile_ = sim_profile_of(tool), profile_tool_ = s.tool;
        const SimProfile& prof = profile_;
        if (s.kind == StepKind::feed) acc.engagement = engagement(s, prof);
        const bool up_from_last = s.from_known && !s.arc && s.from == last_end_ && s.tool == last_tool_ &&
                                  s.to.z >= s.from.z && s.to.x == s.from.x && s.to.y == s.from.y;
        last_end_ = s.to;
        last_tool_ = s.tool;
        if (up_from_last) {
            // Straight up from where the last move left the tool: its lowest surface over the
            // move is where it already was.
        } else if (!s.from_known) {
            mill_line(s.to, s.to, prof, acc);
        } else if (s.arc && s.arc->plane == Plane::xy && std::abs(s.arc->end.z - s.arc->start.z) < sim_tiny) {
            mill_flat_arc(*s.arc, prof, acc);
        } else if (s.arc) {
            // Chords cut inside the arc by their sagitta: at most half a micrometre, below the
            // design check's least tolerance (0.001 mm), so that the wall points it puts that far
            // into a wall are not lowered by a chord the control does not cut.
            const double tol = std::min(arc_chord_fraction * result_.field.cell, sim_helix_sagitta);
            const int n = std::max(1, segments_for_tolerance(s.arc->radius, s.arc->sweep, tol));
            Vec3 prev = s.arc->start;
            for (int k = 1; k <= n; ++k) {
                const Vec3 p = k == n ? s.arc->end : point_on_arc(*s.arc, static_cast<double>(k) / n);
                mill_line(prev, p, prof, acc);
                prev = p;
            }
        } else {
            mill_line(s.from, s.to, prof, acc);
        }
        acc.volume *= result_.field.cell * result_.field.cell;
    }

    // A straight move of the tool tip from a to b.
    void mill_line(const Vec3& a, const Vec3& b, const SimProfile& prof, SimMoveAcc& acc) {
        const HeightField& f = result_.field;
        const SimLineColumns m(a, b, prof);
        const double R = m.R;
        // Nothing to cut above the stock.
        const double zlow = m.zlow;
        if (zlow >= f.top) return;
        probe(std::min(a.x, b.x) - R, std::min(a.y, b.y) - R, std::max(a.x, b.x) + R, std::max(a.y, b.y) + R, zlow, m);
        int j0, j1;
        rows(std::min(a.y, b.y) - R, std::max(a.y, b.y) + R, j0, j1);
        if (m.len2 < sim_tiny) {
            // No XY motion (a plunge, a retract, a drill): the tool's disc at its lowest.
            for (int j = j0; j <= j1; ++j) {
                const double dy = f.y(j) - a.y;
                if (std::abs(dy) > R) continue;
                const double hw = std::sqrt(R * R - dy * dy);
                int i0, i1;
                columns(a.x - hw, a.x + hw, i0, i1);
                const float* row = &f.heights[static_cast<std::size_t>(j) * f.nx];
                result_.cell_updates += static_cast<std::size_t>(std::max(0, i1 - i0 + 1));
                for (int i = i0; i <= i1; ++i) {
                    if (row[i] <= zlow) continue;
                    const double z = m.low(f.x(i), f.y(j));
                    if (z < row[i]) lower(i, j, z, acc);
                }
            }
            return;
        }
        for (int j = j0; j <= j1; ++j) {
            const double y = f.y(j);
            // The row's x-interval in the stadium: end discs and the band between them.
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (const Vec3* e : {&a, &b}) {
                const double dy = y - e->y;
                if (std::abs(dy) <= R) {
                    const double hw = std::sqrt(R * R - dy * dy);
                    lo = std::min(lo, e->x - hw), hi = std::max(hi, e->x + hw);
                }
            }
            if (m.len > 0) {
                double blo = -std::numeric_limits<double>::infinity(), bhi = -blo;
                // n = (-uy, ux): |n.(p - a)| <= R; u.(p - a) in [0, len]
                if (sim_clip(-m.uy, m.uy * a.x + m.ux * (y - a.y), -R, R, blo, bhi) &&
                    sim_clip(m.ux, -m.ux * a.x + m.uy * (y - a.y), 0.0, m.len, blo, bhi) && blo <= bhi)
                    lo = std::min(lo, blo), hi = std::max(hi, bhi);
            }
            if (!(lo <= hi)) continue;
            int i0, i1;
            columns(lo, hi, i0, i1);
            const float* row = &f.heights[static_cast<std::size_t>(j) * f.nx];
            for (int i = i0; i <= i1; ++i) {
                ++result_.cell_updates;
                // The tool is nowhere lower than its tip's lowest point.
                if (row[i] <= zlow) continue;
                const double z = m.low(f.x(i), y);
                if (z < row[i]) lower(i, j, z, acc);
            }
        }
    }

    // An arc in XY at one height: each column's nearest point on the arc.
    void mill_flat_arc(const ArcGeometry& arc, const SimProfile& prof, SimMoveAcc& acc) {
        const HeightField& f = result_.field;
        const SimArcColumns m(arc, prof);
        const double z0 = m.z0;
        if (z0 >= f.top) return;
        const double R = m.R, r = m.r, cx = m.cx;
        // The arc's box: its ends and the axis extremes it passes.
        double bx0 = std::min(arc.start.x, arc.end.x), bx1 = std::max(arc.start.x, arc.end.x);
        double by0 = std::min(arc.start.y, arc.end.y), by1 = std::max(arc.start.y, arc.end.y);
        for (int q = 0; q < 4; ++q) {
            const double ang = q * pi / 2;
            if (m.within(ang)) {
                const double px = cx + r * std::cos(ang), py = m.cy + r * std::sin(ang);
                bx0 = std::min(bx0, px), bx1 = std::max(bx1, px), by0 = std::min(by0, py), by1 = std::max(by1, py);
            }
        }
        probe(bx0 - R, by0 - R, bx1 + R, by1 + R, z0, m);
        int j0, j1;
        rows(by0 - R, by1 + R, j0, j1);
        const double outer = r + R;
        for (int j = j0; j <= j1; ++j) {
            const double y = f.y(j), dy = y - m.cy;
            if (std::abs(dy) > outer) continue;
            const double hw = std::sqrt(outer * outer - dy * dy);
            int i0, i1;
            columns(std::max(bx0 - R, cx - hw), std::min(bx1 + R, cx + hw), i0, i1);
            const float* row = &f.heights[static_cast<std::size_t>(j) * f.nx];
            for (int i = i0; i <= i1; ++i) {
                ++result_.cell_updates;
                if (row[i] <= z0) continue;
                const double z = m.low(f.x(i), y);
                if (z < row[i]) lower(i, j, z, acc);
            }
        }
    }

    // The probe columns (SimOptions::probes) under a move's box: each lowered to the move's
    // lowest surface over it, exactly as a cell's centre is.
    template <class Columns>
    void probe(double x0, double y0, double x1, double y1, double zlow, const Columns& m) {
        if (probe_start_.empty()) return;
        const HeightField& f = result_.field;
        const double span = f.cell * sim_probe_block;
        const int bx0 = std::max(0, static_cast<int>(std::floor((x0 - f.x0) / span)));
        const int by0 = std::max(0, static_cast<int>(std::floor((y0 - f.y0) / span)));
        const int bx1 = std::min(probe_nx_ - 1, static_cast<int>(std::floor((x1 - f.x0) / span)));
        const int by1 = std::min(probe_ny_ - 1, static_cast<int>(std::floor((y1 - f.y0) / span)));
        for (int by = by0; by <= by1; ++by)
            for (int bx = bx0; bx <= bx1; ++bx) {
                const std::size_t b = static_cast<std::size_t>(by) * static_cast<std::size_t>(probe_nx_) + static_cast<std::size_t>(bx);
                for (std::uint32_t k = probe_start_[b]; k < probe_start_[b + 1]; ++k) {
                    const std::size_t p = probe_order_[k];
                    double& h = result_.probe_heights[p];
                    if (h <= zlow) continue;
                    const Vec2 q = options_.probes[p];
                    const double z = std::max(m.low(q.x, q.y), f.bottom);
                    if (z < h) h = z, result_.probe_lines[p] = line_;
                }
            }
    }

    // The move's radial engagement on the field before it (see SimFigure).
    double engagement(const Step& s, const SimProfile& prof) const {
        if (!s.from_known) return 0.0;
        const HeightField& f = result_.field;
        const double R = prof.radius;
        const int across = std::max(1, static_cast<int>(std::ceil(2 * R / f.cell)));
        double length;
        if (s.arc && s.arc->plane == Plane::xy) length = s.arc->radius * s.arc->sweep;
        else if (s.arc) return 0.0;
        else length = std::hypot(s.to.x - s.from.x, s.to.y - s.from.y);
        if (length < 1e-9) return 0.0;
        const int n = std::clamp(static_cast<int>(std::ceil(length / f.cell)), 1, sim_engagement_samples);
        double best = 0.0;
        for (int k = 0; k < n; ++k) {
            const double t = (k + 0.5) / n;
            Vec3 p;
            double tx, ty;
            if (s.arc) {
                p = point_on_arc(*s.arc, t);
                const double rx = p.x - s.arc->centre.x, ry = p.y - s.arc->centre.y, rn = std::hypot(rx, ry);
                const double sg = s.arc->direction == ArcDirection::ccw ? 1.0 : -1.0;
                tx = -sg * ry / rn, ty = sg * rx / rn;
            } else {
                p = {s.from.x + t * (s.to.x - s.from.x), s.from.y + t * (s.to.y - s.from.y),
                     s.from.z + t * (s.to.z - s.from.z)};
                tx = (s.to.x - s.from.x) / length, ty = (s.to.y - s.from.y) / length;
            }
            if (p.z >= f.top) continue;
            int in = 0;
            for (int q = 0; q < across; ++q) {
                const double u = -R + (q + 0.5) * (2 * R / across);
                const double x = p.x - ty * u, y = p.y + tx * u;
                const int i = static_cast<int>(std::floor((x - f.x0) / f.cell));
                const int j = static_cast<int>(std::floor((y - f.y0) / f.cell));
                if (i < 0 || j < 0 || i >= f.nx || j >= f.ny) continue;
                if (f.at(i, j) > p.z + prof(std::abs(u)) + sim_engaged_above) ++in;
            }
            best = std::max(best, static_cast<double>(in) / across);
        }
        return best;
    }

    // ---- lathe ---------------------------------------------------------------------------

    void init_lathe() {
        if (stock_.kind != SimStock::Kind::bar) throw SimInputError("a lathe's stock is a bar");
        if (!(stock_.bar_diameter > 0 && stock_.bar_length > 0) || !std::isfinite(stock_.face_z))
            throw SimInputError("the bar needs a diameter and a length above 0");
        const double bore = stock_.bore_diameter.value_or(0.0);
        if (!(bore >= 0 && bore < stock_.bar_diameter)) throw SimInputError("the bore must be smaller than the bar");
        double dz = options_.resolution;
        if (!(dz > 0)) {
            const double budget = static_cast<double>(std::max<std::size_t>(options_.lathe_budget, 1));
            dz = std::max(0.001, std::ceil(stock_.bar_length / budget * 1000.0 - 1e-9) / 1000.0);
        }
        const double n = std::ceil(stock_.bar_length / dz - 1e-9);
        if (n > 100e6) throw SimInputError(fmt::format("a resolution of {} mm makes more than 100 million samples", number_text(dz)));
        LatheProfile& p = result_.lathe;
        p.dz = dz;
        p.nz = static_cast<int>(n);
        p.z0 = stock_.face_z - stock_.bar_length;
        p.outside.assign(p.nz, stock_.bar_diameter / 2);
        p.bore.assign(p.nz, bore / 2);
        // A last sample whose centre is above the face holds no material.
        for (int k = 0; k < p.nz; ++k)
            if (p.z(k) > stock_.face_z) p.outside[k] = p.bore[k];
        result_.resolution = dz;
        result_.cells = static_cast<std::size_t>(p.nz);
        double v = 0.0;
        for (int k = 0; k < p.nz; ++k) v += ring(p.outside[k], p.bore[k]);
        result_.initial_volume = v * dz;
        p.outside_lines.assign(p.nz, 0);
        p.bore_lines.assign(p.nz, 0);
        p.gaps.clear();
        if (!options_.lathe_sections.empty()) {
            std::vector<double> z = std::move(options_.lathe_sections);
            set_lathe_sections(std::move(z));
        }
    }

public:
    // The sections: the bar as it is at each Z (no material beyond its ends), swept in order
    // of Z (section_order_).
    void set_lathe_sections(std::vector<double> z) {
        if (result_.kind != MachineKind::lathe) throw SimInputError("sections are a lathe's");
        if (z.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
            throw SimInputError("more than 2^31 sections");
        LatheSections& s = result_.lathe_sections;
        const double bore = stock_.bore_diameter.value_or(0.0) / 2, end = stock_.face_z - stock_.bar_length;
        s.z = std::move(z);
        s.bore.assign(s.z.size(), bore);
        s.outside.assign(s.z.size(), bore);
        s.outside_lines.assign(s.z.size(), 0);
        s.bore_lines.assign(s.z.size(), 0);
        s.gaps.clear();
        for (std::size_t i = 0; i < s.z.size(); ++i)
            if (s.z[i] >= end && s.z[i] <= stock_.face_z) s.outside[i] = stock_.bar_diameter / 2;
        section_order_.resize(s.z.size());
        for (std::size_t i = 0; i < s.z.size(); ++i) section_order_[i] = static_cast<std::int32_t>(i);
        std::sort(section_order_.begin(), section_order_.end(), [&](std::int32_t a, std::int32_t b) { return s.z[a] < s.z[b]; });
    }

private:
    static double ring(double outside, double bore) { return outside > bore ? pi * (outside * outside - bore * bore) : 0.0; }

    // Sets a sample's outside radius to at most `r` and its bore to at least `b`; returns the
    // radial depth of material removed, mm.
    double lathe_cut(int k, double r, double b, SimMoveAcc& acc) {
        LatheProfile& p = result_.lathe;
        if (!p.gaps.empty() && !p.gaps[static_cast<std::size_t>(k)].empty())
            return std::isfinite(r) ? lathe_ring_cut(k, r, std::numeric_limits<double>::infinity(), acc)
                                    : lathe_ring_cut(k, -std::numeric_limits<double>::infinity(), b, acc);
        ++result_.cell_updates;
        const double before = ring(p.outside[k], p.bore[k]);
        const double old_r = p.outside[k], old_b = p.bore[k];
        if (r < p.outside[k]) p.outside[k] = std::max(r, 0.0), p.outside_lines[k] = line_;
        if (b > p.bore[k]) p.bore[k] = b, p.bore_lines[k] = line_;
        const double removed = before - ring(p.outside[k], p.bore[k]);
        if (options_.observer && (p.outside[k] != old_r || p.bore[k] != old_b))
            options_.observer->turned(k, p.outside[k], p.bore[k], line_);
        if (!(removed > 0) || !(old_r > old_b)) return 0.0;
        acc.volume += removed;
        return std::max(old_r - std::max(p.outside[k], old_b), std::min(p.bore[k], old_r) - old_b);
    }

    // Removes the radii [lo, hi] from sample k, its gaps kept (sim_remove_radii); returns the
    // radial length of material removed, mm.
    double lathe_ring_cut(int k, double lo, double hi, SimMoveAcc& acc) {
        LatheProfile& p = result_.lathe;
        ++result_.cell_updates;
        const std::size_t i = static_cast<std::size_t>(k);
        if (p.gaps.empty()) p.gaps.resize(static_cast<std::size_t>(p.nz));
        std::vector<LatheGap>& gaps = p.gaps[i];
        const double before = lathe_material_area(p.outside[i], p.bore[i], &gaps);
        const double depth = lathe_material_within(p.outside[i], p.bore[i], &gaps, lo, hi);
        bool out_changed = false, bore_changed = false;
        sim_remove_radii(p.outside[i], p.bore[i], gaps, lo, hi, line_, out_changed, bore_changed);
        if (out_changed) p.outside_lines[i] = line_;
        if (bore_changed) p.bore_lines[i] = line_;
        if (options_.observer && (out_changed || bore_changed)) options_.observer->turned(k, p.outside[i], p.bore[i], line_);
        const double removed = before - lathe_material_area(p.outside[i], p.bore[i], &gaps);
        if (!(removed > 0)) return 0.0;
        acc.volume += removed;
        return depth;
    }

    void lathe_move(const Step& s, const ToolShape& tool, SimMoveAcc& acc) {
        const Vec3 b = s.to;
        const Vec3 a = s.from_known ? s.from : s.to;
        std::vector<std::pair<Vec3, Vec3>> pieces;
        if (s.arc) {
            const int n = std::max(1, segments_for_tolerance(s.arc->radius, s.arc->sweep, arc_chord_fraction * result_.lathe.dz));
            Vec3 prev = s.arc->start;
            for (int k = 1; k <= n; ++k) {
                const Vec3 q = k == n ? s.arc->end : point_on_arc(*s.arc, static_cast<double>(k) / n);
                pieces.emplace_back(prev, q);
                prev = q;
            }
        } else {
            pieces.emplace_back(a, b);
        }
        for (const auto& [p, q] : pieces) {
            if (tool.form == ToolForm::turning)
                lathe_turn(p, q, tool, acc);
            else if (tool.form == ToolForm::blade && tool.orientation == 7)
                lathe_face_blade(p, q, tool.diameter, acc);
            else if (tool.form == ToolForm::blade)
                lathe_blade(p, q, tool.blade_lo, tool.blade_lo + tool.diameter,
                            tool.orientation == 3 || tool.orientation == 4 ? -1.0 : 1.0, acc);
            else lathe_axial(s, p, q, tool, acc);
        }
        acc.volume *= result_.lathe.dz;
    }

    // A section's outside radius to at most `r` (where it holds material) and its bore to at
    // least `b`, as lathe_cut does a sample's.
    void section_cut(std::size_t i, double r, double b) {
        LatheSections& s = result_.lathe_sections;
        if (!s.gaps.empty() && !s.gaps[i].empty())
            return std::isfinite(r) ? section_ring_cut(i, r, std::numeric_limits<double>::infinity())
                                    : section_ring_cut(i, -std::numeric_limits<double>::infinity(), b);
        if (r < s.outside[i] && s.outside[i] > s.bore[i]) s.outside[i] = std::max(r, 0.0), s.outside_lines[i] = line_;
        if (b > s.bore[i]) s.bore[i] = b, s.bore_lines[i] = line_;
    }

    // A section's radii [lo, hi] removed, as lathe_ring_cut does a sample's.
    void section_ring_cut(std::size_t i, double lo, double hi) {
        LatheSections& s = result_.lathe_sections;
        if (s.gaps.empty()) s.gaps.resize(s.z.size());
        bool out_changed = false, bore_changed = false;
        sim_remove_radii(s.outside[i], s.bore[i], s.gaps[i], lo, hi, line_, out_changed, bore_changed);
        if (out_changed) s.outside_lines[i] = line_;
        if (bore_changed) s.bore_lines[i] = line_;
    }

    // The sections from Z `zlo` to `zhi`, in order of Z: f(index).
    template <class F>
    void sections_within(double zlo, double zhi, F f) {
        const std::vector<double>& zs = result_.lathe_sections.z;
        auto it = std::lower_bound(section_order_.begin(), section_order_.end(), zlo,
                                   [&](std::int32_t i, double z) { return zs[static_cast<std::size_t>(i)] < z; });
        for (; it != section_order_.end() && zs[static_cast<std::size_t>(*it)] <= zhi; ++it) f(static_cast<std::size_t>(*it));
    }

    // The sections at or above Z `zlo`, in order of Z: f(index).
    template <class F>
    void sections_above(double zlo, F f) {
        const std::vector<double>& zs = result_.lathe_sections.z;
        auto it = std::lower_bound(section_order_.begin(), section_order_.end(), zlo,
                                   [&](std::int32_t i, double z) { return zs[static_cast<std::size_t>(i)] < z; });
        for (; it != section_order_.end(); ++it) f(static_cast<std::size_t>(*it));
    }

    // A turning tool whose programmed point (the imaginary tip) moves from p to q: its nose
    // circle's centre lies from the point as the orientation says (lathe_tip_offset; 2: a nose
    // radius above it in X and Z), its insert's flanks as ToolShape::flank_lo/hi say, mirrored
    // in Z for an outside tool whose tip lies on the nose's +Z side (1, 5: the body towards -Z,
    // its shank out along +X) and in X for one on its +X side (3, 4, 8: a boring tool, its body
    // towards the axis; never in Z: its bar leaves the bore towards +Z). The swept shape is
    // SimTurnSweep's in the mirrored frame. An outside tool clears every radius from the
    // shape's lowest at each Z outward (the profile holds no overhang: what lies above the
    // insert is its holder's, or was cut on the way in); its centre's X is taken signed (a nose
    // that crosses the axis clears the axis), or as its mirror image where the move lies wholly
    // past the axis (X <= 0). A boring tool opens the bore to the shape's highest, its
    // centre's radius |X|.
    void lathe_turn(const Vec3& p, const Vec3& q, const ToolShape& tool, SimMoveAcc& acc) {
        const LatheProfile& pr = result_.lathe;
        constexpr double none = std::numeric_limits<double>::infinity();
        const double n = tool.nose_radius;
        const Vec2 tip = lathe_tip_offset(tool.orientation, n);  // (Z, radius) from the centre
        const Vec2 unit = lathe_tip_offset(tool.orientation, 1.0);
        const bool boring = unit.y > 0;                          // X mirrored
        const double zs = unit.x > 0 && !boring ? -1.0 : 1.0;   // left-hand outside: Z mirrored
        double xa = p.x - tip.y, xb = q.x - tip.y;
        if (boring) xa = -std::abs(xa), xb = -std::abs(xb);
        else if (xa <= 0 && xb <= 0) xa = -xa, xb = -xb;
        const SimTurnSweep sweep({zs * (p.z - tip.x), xa}, {zs * (q.z - tip.x), xb}, n, tool.flank_lo, tool.flank_hi);
        // The shape cuts only below the most material can reach: the bar's radius outside, the
        // bar's bore (less) in a boring tool's frame.
        const double bound = boring ? -stock_.bore_diameter.value_or(0.0) / 2 : stock_.bar_diameter / 2;
        double lo = 0, hi = 0;
        sweep.extent(bound, lo, hi);
        if (zs < 0) std::swap(lo, hi), lo = -lo, hi = -hi;
        // The radius at Z z: outside, cut to at most it; boring, bored to at least it; none.
        auto reach = [&](double z) {
            const double r = sweep.low(zs * z);
            if (!std::isfinite(r)) return none;
            return boring ? -r : std::max(r, 0.0);
        };
        // The samples whose Z lie in [lo, hi] (as doubles first: either may be infinite).
        const double f0 = std::ceil((lo - pr.z0) / pr.dz - 0.5), f1 = std::floor((hi - pr.z0) / pr.dz - 0.5);
        const int k0 = f0 > 0 ? (f0 < pr.nz ? static_cast<int>(f0) : pr.nz) : 0;
        const int k1 = f1 < pr.nz - 1 ? (f1 >= 0 ? static_cast<int>(f1) : -1) : pr.nz - 1;
        for (int k = k0; k <= k1; ++k) {
            if (pr.outside[k] <= pr.bore[k]) continue;
            const double r = reach(pr.z(k));
            if (!std::isfinite(r)) continue;
            if (!boring && r < pr.outside[k]) acc.max_depth = std::max(acc.max_depth, lathe_cut(k, r, 0.0, acc));
            else if (boring && r > pr.bore[k]) acc.max_depth = std::max(acc.max_depth, lathe_cut(k, none, r, acc));
        }
        sections_within(lo, hi, [&](std::size_t i) {
            const double r = reach(result_.lathe_sections.z[i]);
            if (std::isfinite(r)) boring ? section_cut(i, none, r) : section_cut(i, r, 0.0);
        });
    }

    // A blade: its edge from the point's Z + lo to + hi, its body straight out in +X (side +1),
    // or (side -1, an internal grooving tool) its edge facing +X, its body towards the axis: it
    // opens the bore to the edge's radius.
    void lathe_blade(const Vec3& a, const Vec3& b, double lo, double hi, double side, SimMoveAcc& acc) {
        const LatheProfile& p = result_.lathe;
        constexpr double none = std::numeric_limits<double>::infinity();
        const double zlo = std::min(a.z, b.z) + lo, zhi = std::max(a.z, b.z) + hi;
        int k0 = std::max(0, static_cast<int>(std::ceil((zlo - p.z0) / p.dz - 0.5)));
        for (int k = k0; k < p.nz && p.z(k) <= zhi + p.dz; ++k) {
            const double r = side * blade_reach(a, b, lo, hi, p.z(k), side);
            if (!std::isfinite(r) || !(p.outside[k] > p.bore[k])) continue;
            if (side > 0 && r < p.outside[k]) acc.max_depth = std::max(acc.max_depth, lathe_cut(k, r, 0.0, acc));
            else if (side < 0 && r > p.bore[k]) acc.max_depth = std::max(acc.max_depth, lathe_cut(k, none, r, acc));
        }
        sections_above(zlo, [&](std::size_t i) {
            const double r = side * blade_reach(a, b, lo, hi, result_.lathe_sections.z[i], side);
            if (std::isfinite(r)) side > 0 ? section_cut(i, r, 0.0) : section_cut(i, none, r);
        });
    }

    // The least radius a blade moving from a to b clears at Z z: where its point's Z lies in
    // [z - hi, z - lo] its edge covers z; the radius is linear along the move, least at an end
    // of that stretch (infinity: it never covers z). With `side` -1 the radii are taken
    // negative: minus the greatest radius an internal blade's edge reaches.
    static double blade_reach(const Vec3& a, const Vec3& b, double lo, double hi, double z, double side = 1.0) {
        const double xa = side * std::abs(a.x), xb = side * std::abs(b.x), dz = b.z - a.z;
        double t0 = 0, t1 = 1;
        if (std::abs(dz) < sim_tiny) {
            if (a.z < z - hi || a.z > z - lo) return std::numeric_limits<double>::infinity();
        } else {
            double s0 = (z - hi - a.z) / dz, s1 = (z - lo - a.z) / dz;
            if (s0 > s1) std::swap(s0, s1);
            t0 = std::max(0.0, s0), t1 = std::min(1.0, s1);
            if (t0 > t1) return std::numeric_limits<double>::infinity();
        }
        return std::min(xa + t0 * (xb - xa), xa + t1 * (xb - xa));
    }

    // A face grooving blade (orientation 7): its edge faces -Z, `width` along X from the
    // programmed point out, its body along +Z. At Z z it clears the ring from the least X to
    // the greatest X + width of the stretch of the move at or below z: a ring that reaches the
    // outside or the bore turns it; one strictly inside the material is a gap (LatheGap).
    void lathe_face_blade(const Vec3& a, const Vec3& b, double width, SimMoveAcc& acc) {
        LatheProfile& p = result_.lathe;
        constexpr double none = std::numeric_limits<double>::infinity();
        // The ring at Z z, or none where the blade's edge stays above z.
        auto ring_at = [&](double z, double& lo, double& hi) {
            const double xa = std::abs(a.x), xb = std::abs(b.x), dz = b.z - a.z;
            double t0 = 0, t1 = 1;
            if (std::abs(dz) < sim_tiny) {
                if (a.z > z) return false;
            } else {
                const double t = (z - a.z) / dz;
                if (dz > 0) t1 = std::min(1.0, t);
                else t0 = std::max(0.0, t);
                if (t0 > t1) return false;
            }
            const double x0 = xa + t0 * (xb - xa), x1 = xa + t1 * (xb - xa);
            lo = std::min(x0, x1), hi = std::max(x0, x1) + width;
            return true;
        };
        const double zlo = std::min(a.z, b.z);
        const int k0 = std::max(0, static_cast<int>(std::ceil((zlo - p.z0) / p.dz - 0.5)));
        for (int k = k0; k < p.nz; ++k) {
            double lo = 0, hi = 0;
            if (!ring_at(p.z(k), lo, hi) || !(p.outside[k] > p.bore[k])) continue;
            if (hi <= p.bore[k] || lo >= p.outside[k]) continue;  // in the bore or beyond the outside: air
            if (hi >= p.outside[k]) acc.max_depth = std::max(acc.max_depth, lathe_cut(k, lo, 0.0, acc));
            else if (lo <= p.bore[k]) acc.max_depth = std::max(acc.max_depth, lathe_cut(k, none, hi, acc));
            else acc.max_depth = std::max(acc.max_depth, lathe_ring_cut(k, lo, hi, acc));
        }
        sections_above(zlo, [&](std::size_t i) {
            LatheSections& sec = result_.lathe_sections;
            double lo = 0, hi = 0;
            if (!ring_at(sec.z[i], lo, hi) || !(sec.outside[i] > sec.bore[i])) return;
            if (hi <= sec.bore[i] || lo >= sec.outside[i]) return;
            if (hi >= sec.outside[i]) section_cut(i, lo, 0.0);
            else if (lo <= sec.bore[i]) section_cut(i, none, hi);
            else section_ring_cut(i, lo, hi);
        });
    }

    // A drill (or any round tool) on the spindle's axis: it clears its radius above its point.
    void lathe_axial(const Step& s, const Vec3& a, const Vec3& b, const ToolShape& tool, SimMoveAcc& acc) {
        const LatheProfile& p = result_.lathe;
        if (std::abs(a.x) > 1e-3 || std::abs(b.x) > 1e-3) {
            ++off_axis_;
            if (off_axis_ == 1)
                result_.notes.push_back(fmt::format("line {}: tool {} moves off the spindle's axis; a lathe simulates a "
                                                    "round tool on the axis only (not swept)", s.line, s.tool));
            return;
        }
        const SimProfile prof = sim_profile_of(tool);
        const double zt = std::min(a.z, b.z);
        const int k0 = std::max(0, static_cast<int>(std::ceil((zt - p.z0) / p.dz - 0.5)));
        // The drill's depth below the material it meets at the axis before the move.
        double below = 0.0;
        for (int k = p.nz - 1; k >= k0; --k) {
            if (p.outside[k] > p.bore[k] && p.bore[k] < prof.radius) {
                below = p.z(k) + p.dz / 2 - zt;
                break;
            }
        }
        // The radius the point reaches h above its tip: the inverse of the tool's profile.
        auto radius_at = [&](double h) {
            if (prof.form == ToolForm::cone && prof.slope > 0) return std::min(prof.radius, prof.flat + h / prof.slope);
            return prof.radius;
        };
        // A crash's depth: the length along Z over which the bore grew.
        double bored = 0.0;
        for (int k = k0; k < p.nz; ++k) {
            const double rad = radius_at(p.z(k) - zt);
            if (rad > p.bore[k] && lathe_cut(k, std::numeric_limits<double>::infinity(), rad, acc) > 1e-6) bored += p.dz;
        }
        sections_above(zt, [&](std::size_t i) {
            section_cut(i, std::numeric_limits<double>::infinity(), radius_at(result_.lathe_sections.z[i] - zt));
        });
        if (bored > 0) {
            acc.max_depth = std::max(acc.max_depth, bored);
            acc.flute_depth = std::max(acc.flute_depth, below);
        }
    }

    // ---- per move ------------------------------------------------------------------------

    const std::string& operation_of(int line) {
        if (options_.operations.empty() || line <= 0) return current_op_;
        auto it = std::upper_bound(options_.operations.begin(), options_.operations.end(), line,
                                   [](int l, const OperationSpan& o) { return l < o.first_line; });
        if (it == options_.operations.begin()) return empty_;
        return std::prev(it)->path;
    }

    static SimFigure& figure(std::vector<SimFigure>& list, const std::string& name, int tool) {
        for (SimFigure& f : list)
            if (f.name == name) return f;
        list.push_back({name, tool});
        return list.back();
    }

    SimFigure& tool_figure(int tool) {
        if (last_figure_tool_ != tool || last_figure_ >= result_.tools.size()) {
            figure(result_.tools, fmt::format("T{}", tool), tool);
            last_figure_ = static_cast<std::size_t>(
                std::find_if(result_.tools.begin(), result_.tools.end(), [&](const SimFigure& f) { return f.tool == tool; }) -
                result_.tools.begin());
            last_figure_tool_ = tool;
        }
        return result_.tools[last_figure_];
    }

    void account(const Step& s, const ToolShape& tool, const SimMoveAcc& acc) {
        if (!(acc.volume > 0) && !(acc.engagement > 0) && !(acc.max_depth > 0)) return;
        const std::string& op = operation_of(s.line);
        if (acc.volume > 0) {
            result_.removed_volume += acc.volume;
            tool_figure(s.tool).volume += acc.volume;
            if (!op.empty()) figure(result_.operations, op, s.tool).volume += acc.volume;
        }
        if (acc.engagement > 0) {
            for (SimFigure* f : {&tool_figure(s.tool), op.empty() ? nullptr : &figure(result_.operations, op, s.tool)}) {
                if (f && acc.engagement > f->max_engagement) f->max_engagement = acc.engagement, f->engagement_line = s.line;
            }
        }
        if (s.kind == StepKind::rapid && acc.max_depth > options_.crash_depth) {
            result_.errors.push_back({s.line, op, s.tool,
                                      fmt::format("a rapid removes material (a crash): {} mm deep, {} mm^3",
                                                  number_text(acc.max_depth, 3), number_text(acc.volume, 3))});
        } else if (s.kind == StepKind::feed && tool.threading && s.pitch > 0 && acc.max_depth > thread_pass_depth * s.pitch + 1e-6) {
            result_.errors.push_back({s.line, op, s.tool,
                                      fmt::format("a thread pass cuts {} mm deep (radial) in one pass, more than a thread of "
                                                  "lead {} mm is deep ({} mm, a sharp 60-degree V): the threading insert is "
                                                  "overloaded (a crash); turn the diameter to the thread's major (bore it to "
                                                  "its minor) first",
                                                  number_text(acc.max_depth, 3), number_text(s.pitch, 4),
                                                  number_text(thread_pass_depth * s.pitch, 3))});
        } else if (s.kind == StepKind::feed && tool.flute_length && acc.flute_depth > *tool.flute_length + 1e-6) {
            result_.errors.push_back({s.line, op, s.tool,
                                      fmt::format("a feed cuts {} mm below the stock's surface, deeper than tool {}'s "
                                                  "fluteLength {} mm",
                                                  number_text(acc.flute_depth, 3), s.tool, number_text(*tool.flute_length))});
        }
    }

    StatsAccumulator stats_;
    SimStock stock_;
    std::map<int, ToolShape> tools_;
    SimOptions options_;
    std::string current_op_;
    const std::string empty_;
    int skipped_tool0_ = 0;
    SimProfile profile_;     // of profile_tool_ (a tangent per move costs as much as the move)
    int profile_tool_ = -1;
    int line_ = 0;  // the program line of the step being swept
    int last_figure_tool_ = -1;       // the tool of result_.tools[last_figure_]
    std::size_t last_figure_ = 0;
    Vec3 last_end_{0, 0, std::numeric_limits<double>::infinity()};  // where the last move left the tool
    int last_tool_ = -1;
    int off_axis_ = 0;
    // Probe columns by block: block b's probes are probe_order_[probe_start_[b] .. probe_start_[b + 1]).
    std::vector<std::uint32_t> probe_start_, probe_order_;
    int probe_nx_ = 0, probe_ny_ = 0;
    double field_x1_ = 0.0, field_y1_ = 0.0;  // the stock's extent (the field may reach beyond)
    std::vector<Vec2> stock_polygon_;          // a profile stock's outline as sampled (empty: a box)
    std::vector<std::int32_t> section_order_;  // the lathe's sections in order of Z
};

Simulator::Simulator(const Machine& machine, SimStock stock, std::map<int, ToolShape> tools, SimOptions options)
    : impl_(std::make_unique<Impl>(machine, std::move(stock), std::move(tools), std::move(options))) {}
Simulator::~Simulator() = default;
void Simulator::step(const Step& step) { impl_->step(step); }
void Simulator::hole(const Hole& hole) { impl_->hole(hole); }
void Simulator::finish(const TraceSummary& summary) { impl_->finish(summary); }
void Simulator::begin_operation(std::string path) { impl_->begin_operation(std::move(path)); }
void Simulator::set_probes(std::vector<Vec2> points) { impl_->set_probes(std::move(points)); }
void Simulator::set_lathe_sections(std::vector<double> z) { impl_->set_lathe_sections(std::move(z)); }
void Simulator::observe(SimObserver* observer) { impl_->observe(observer); }
void Simulator::report_error(int line, int tool, std::string message) { impl_->report_error(line, tool, std::move(message)); }
const SimResult& Simulator::result() const { return impl_->result_; }
SimResult Simulator::take() { return std::move(impl_->result_); }

ToolShape tool_shape(const Tool& tool) {
    ToolShape s;
    s.diameter = tool.diameter;
    s.flute_length = tool.flute_length;
    switch (tool.type) {
    case ToolType::end_mill: s.form = ToolForm::flat; break;
    case ToolType::ball_mill: s.form = ToolForm::ball; break;
    case ToolType::bull_nose:
        s.form = ToolForm::bull_nose;
        s.corner_radius = tool.corner_radius.value_or(0.0);
        break;
    case ToolType::chamfer_mill:
    case ToolType::v_bit:
    case ToolType::engraver:
        s.form = ToolForm::cone;
        s.tip_angle = tool.tip_angle.value_or(90.0);
        s.tip_diameter = tool.tip_diameter;
        break;
    case ToolType::drill:
    case ToolType::centre_drill:
    case ToolType::spot_drill:
        s.form = ToolForm::cone;
        s.tip_angle = tool.tip_angle.value_or(tool.type == ToolType::drill ? 118.0 : 90.0);
        break;
    case ToolType::thread_mill:  // its teeth's tips: the height field cannot hold a thread's undercut flanks
        s.thread_mill = true;
        s.form = ToolForm::cylinder;
        break;
    case ToolType::tap:
    case ToolType::reamer:
    case ToolType::boring_bar: s.form = ToolForm::cylinder; break;
    case ToolType::turning_tool:
        s.form = ToolForm::turning;
        s.nose_radius = tool.diameter / 2;
        s.orientation = tool.orientation;
        if (tool.insert_angle && tool.approach_angle) {
            // The main edge at approachAngle from the direction of feed (-Z), the end edge
            // insertAngle further round: 180 - approachAngle - insertAngle above +Z.
            s.flank_lo = 180.0 - *tool.approach_angle - *tool.insert_angle;
            s.flank_hi = 180.0 - *tool.approach_angle;
        }
        break;
    case ToolType::grooving_tool:  // a blade of its width, programmed at its left corner (orientation 1: right)
    case ToolType::parting_tool:
        s.form = ToolForm::blade;
        s.diameter = tool.width > 0 ? tool.width : tool.diameter;
        s.blade_lo = tool.orientation == 1 || tool.orientation == 4 ? -s.diameter : 0.0;
        s.orientation = tool.orientation;
        break;
    case ToolType::threading_tool:
        s.form = ToolForm::turning;
        s.threading = true;
        s.nose_radius = tool.nose_radius;
        // A threading tool given no orientation: programmed at its nose's lowest point in X and
        // its -Z side (the root of an external thread), as orientation 2 is.
        s.orientation = tool.orientation > 0 ? tool.orientation : 2;
        break;
    }
    return s;
}

std::map<int, ToolShape> tool_shapes(const std::map<int, Tool>& tools) {
    std::map<int, ToolShape> out;
    for (const auto& [number, tool] : tools) out[number] = tool_shape(tool);
    return out;
}

SimResult simulate(const std::vector<Step>& steps, const Machine& machine, const SimStock& stock,
                   const std::map<int, ToolShape>& tools, const SimOptions& options) {
    Simulator sim(machine, stock, tools, options);
    for (const Step& s : steps) sim.step(s);
    sim.finish({});
    return sim.take();
}

std::string format_simulation(const SimResult& r) {
    std::string out;
    auto vol = [](double v) { return number_text(v, 3); };
    if (r.kind == MachineKind::lathe)
        out += fmt::format("simulation: lathe, turned profile of {} samples of {} mm along Z\n", r.cells,
                           number_text(r.resolution));
    else
        out += fmt::format("simulation: mill, height field of {} x {} cells of {} mm ({} cells)\n", r.field.nx, r.field.ny,
                           number_text(r.resolution), r.cells);
    out += fmt::format("stock: {} mm^3, removed {} mm^3, left {} mm^3\n", vol(r.initial_volume), vol(r.removed_volume),
                       vol(r.initial_volume - r.removed_volume));
    auto figures = [&](const std::vector<SimFigure>& list, const char* what) {
        for (const SimFigure& f : list) {
            out += fmt::format("{} {}: removed {} mm^3", what, f.name, vol(f.volume));
            if (f.max_engagement > 0)
                out += fmt::format(", largest radial engagement {} % of the diameter (line {})",
                                   number_text(f.max_engagement * 100, 1), f.engagement_line);
            out += '\n';
        }
    };
    figures(r.tools, "tool");
    figures(r.operations, "operation");
    out += fmt::format("machining time: {}\n", format_duration(r.stats.total_time()));
    out += fmt::format("cell visits by moves: {}\n", r.cell_updates);
    for (const std::string& n : r.notes) out += fmt::format("note: {}\n", n);
    for (const SimReport& e : r.errors) {
        out += fmt::format("error: line {}", e.line);
        if (!e.operation.empty()) out += fmt::format(" ({})", e.operation);
        out += fmt::format(", tool {}: {}\n", e.tool, e.message);
    }
    out += r.errors.empty()        ? std::string("simulation: no errors\n")
           : r.errors.size() == 1 ? std::string("simulation: 1 error\n")
                                   : fmt::format("simulation: {} errors\n", r.errors.size());
    return out;
}

}  // namespace camgen
