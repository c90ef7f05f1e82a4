// A simulated turned part against the job's lathe design (design_check_lathe.hpp).
#include "camgen/simulation/design_check_lathe.hpp"

#include "camgen/simulation/design_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/stops.hpp"

namespace camgen {

namespace {

// Either side of a corner, the design is read this far from it (a face's two radii), mm.
constexpr double lathe_check_beside = 1e-9;

// One position of the simulated bar.
struct LatheCheckAt {
    double z, outside, bore;
    int outside_line, bore_line;
    bool section;
    const std::vector<LatheGap>* gaps;  // the rings of air inside the material (null: none)
};

class LatheChecker {
public:
    LatheChecker(const LatheDesign& design, const SimStock& bar, double tolerance, const std::vector<OperationSpan>& operations)
        : d_(design), tol_(tolerance), ops_(operations), radius_(bar.bar_diameter / 2),
          bore_(bar.bore_diameter.value_or(0.0) / 2), end_(bar.face_z - bar.bar_length), face_(bar.face_z),
          nose_excess_(design.profiles.size(), 0.0), nose_at_(design.profiles.size(), 0.0) {}

    void judge(const LatheCheckAt& at) {
        if (at.z < end_ || at.z > face_) return;  // no bar there
        ++(at.section ? out_.sections : out_.samples);
        const double a = at.z - tol_, b = at.z + tol_;
        const std::size_t np = d_.profiles.size(), nh = d_.holes.size();
        // The outside the design keeps: the least of the profiles over the window, else the bar.
        double kept = radius_;
        std::optional<std::size_t> profile;
        ranges_.assign(np, std::nullopt);
        for (std::size_t i = 0; i < np; ++i) {
            ranges_[i] = d_.profiles[i].radius_range(a, b);
            if (ranges_[i] && ranges_[i]->first < kept) kept = ranges_[i]->first, profile = i;
        }
        // The bore it allows: the most of the holes' over the window, else the bar's.
        double bored = bore_;
        std::optional<std::size_t> hole;
        for (std::size_t j = 0; j < nh; ++j)
            if (const double r = d_.holes[j].radius_most(a, b); r > bored) bored = r, hole = j;
        // A face groove's ring that reaches the outside (or the bore) lets it fall (rise) to the ring.
        const std::size_t nr = d_.rings.size();
        std::optional<std::size_t> ring_out, ring_in;
        for (std::size_t r = 0; r < nr; ++r) {
            double lo = 0, hi = 0;
            if (!d_.rings[r].allowed(a, b, lo, hi)) continue;
            if (hi + tol_ >= kept && lo < kept) kept = lo, profile.reset(), ring_out = r;
            if (lo - tol_ <= bored && hi > bored) bored = hi, hole.reset(), ring_in = r;
        }
        if (kept > bored + tol_) {
            if (at.outside < kept - tol_) {
                LatheFinding& f = profile ? finding(LatheFinding::Kind::gouge, LatheFinding::Surface::outside, *profile,
                                                    d_.profiles[*profile].path, "the part inside the profile")
                                  : ring_out ? finding(LatheFinding::Kind::gouge, LatheFinding::Surface::outside, ring_rank(*ring_out),
                                                       d_.rings[*ring_out].path, "the part around the face groove")
                                             : bar_finding(LatheFinding::Surface::outside, at.outside_line);
                record(f, at, kept - at.outside, at.outside, kept, at.outside_line);
            }
            if (at.bore > bored + tol_) {
                LatheFinding* f = nullptr;
                if (ring_in) {
                    f = &finding(LatheFinding::Kind::gouge, LatheFinding::Surface::bore, ring_rank(*ring_in),
                                 d_.rings[*ring_in].path, "the part around the face groove");
                } else if (hole) {
                    f = &finding(LatheFinding::Kind::gouge, LatheFinding::Surface::bore, np + *hole, d_.holes[*hole].path,
                                 "the part around the hole");
                } else {
                    // Below every point: the hole whose point is nearest above.
                    std::optional<std::size_t> above;
                    for (std::size_t j = 0; j < nh; ++j)
                        if (!d_.holes[j].groove() && d_.holes[j].bottom_z >= at.z &&
                            (!above || d_.holes[j].bottom_z < d_.holes[*above].bottom_z))
                            above = j;
                    if (above)
                        f = &finding(LatheFinding::Kind::gouge, LatheFinding::Surface::bore, np + nh + *above,
                                     d_.holes[*above].path, "the part below the hole's point");
                    else f = &bar_finding(LatheFinding::Surface::bore, at.bore_line);
                }
                record(*f, at, std::min(at.bore, kept) - bored, at.bore, bored, at.bore_line);
            }
        }
        // The rings of air inside the material: each within a designed ring's walls over the window.
        if (at.gaps)
            for (const LatheGap& g : *at.gaps) judge_gap(at, g, a, b);
        // Material left inside each face groove's ring where it must be clear over the window.
        for (std::size_t r = 0; r < nr; ++r) {
            double lo = 0, hi = 0;
            if (!d_.rings[r].required(a, b, lo, hi)) continue;
            const double left = lathe_material_within(at.outside, at.bore, at.gaps, lo, hi, true);
            if (left > tol_) {
                LatheFinding& f =
                    finding(LatheFinding::Kind::left, LatheFinding::Surface::ring, ring_rank(r), d_.rings[r].path, "the face groove");
                if (record(f, at, left, left, lo, 0)) f.designed_hi = hi;
            }
        }
        // Material left beyond what each profile's tool leaves.
        for (std::size_t i = 0; i < np; ++i) {
            const LatheTurnDesign& p = d_.profiles[i];
            if (at.z < p.z_lo || at.z > p.z_hi) continue;
            const double most = ranges_[i] ? ranges_[i]->second : -std::numeric_limits<double>::infinity();
            if (!at.section && p.nose > 0) {
                // What the nose leaves beyond the profile, for the note.
                const auto here = p.radius_range(at.z, at.z);
                const double left = p.left_radius(at.z);
                if (here && std::isfinite(left) && left - here->second > nose_excess_[i])
                    nose_excess_[i] = left - here->second, nose_at_[i] = at.z;
            }
            if (!(at.outside > most + tol_) || !(at.outside > at.bore)) continue;
            double limit = std::max({most, p.left_radius(a), p.left_radius(at.z), p.left_radius(b)});
            for (double c : p.corners())
                if (c >= a && c <= b)
                    limit = std::max({limit, p.left_radius(c - lathe_check_beside), p.left_radius(c),
                                      p.left_radius(c + lathe_check_beside)});
            if (at.outside - limit > tol_)
                record(finding(LatheFinding::Kind::left, LatheFinding::Surface::outside, i, p.path, "the turned profile"), at,
                       at.outside - limit, at.outside, limit, 0);
        }
        // Material left inside each hole's drill.
        for (std::size_t j = 0; j < nh; ++j) {
            const LatheHoleDesign& h = d_.holes[j];
            if (at.z < h.bottom_z && !h.groove()) continue;
            const double need = h.radius_least(a, b), top = std::min(at.outside, need);
            if (top - at.bore > tol_)
                record(finding(LatheFinding::Kind::left, LatheFinding::Surface::bore, np + j, h.path, "the hole"), at,
                       top - at.bore, at.bore, need, 0);
        }
    }

    // A ring of air: a gouge where no designed ring holds it within the tolerance.
    void judge_gap(const LatheCheckAt& at, const LatheGap& g, double a, double b) {
        double excess = std::numeric_limits<double>::infinity(), dlo = 0, dhi = 0;
        std::optional<std::size_t> owner;
        for (std::size_t r = 0; r < d_.rings.size(); ++r) {
            double lo = 0, hi = 0;
            if (!d_.rings[r].allowed(a, b, lo, hi)) continue;
            const double e = std::max({0.0, lo - g.lo, g.hi - hi});
            if (e < excess) excess = e, owner = r, dlo = lo, dhi = hi;
        }
        if (!(excess > tol_)) return;
        if (owner) {
            LatheFinding& f = finding(LatheFinding::Kind::gouge, LatheFinding::Surface::ring, ring_rank(*owner),
                                      d_.rings[*owner].path, "the part around the face groove");
            if (record(f, at, excess, dlo - g.lo > g.hi - dhi ? g.lo : g.hi, dlo, g.line)) f.designed_hi = dhi;
            return;
        }
        // Below every ring at this Z: the ring above whose radii it meets, nearest.
        std::optional<std::size_t> above;
        for (std::size_t r = 0; r < d_.rings.size(); ++r) {
            const LatheRingDesign& d = d_.rings[r];
            if (d.bottom_z >= at.z && d.lo_at(d.bottom_z) < g.hi && d.hi_at(d.bottom_z) > g.lo &&
                (!above || d.bottom_z < d_.rings[*above].bottom_z))
                above = r;
        }
        if (above) {
            const LatheRingDesign& d = d_.rings[*above];
            record(finding(LatheFinding::Kind::gouge, LatheFinding::Surface::ring_bottom, ring_rank(*above), d.path,
                           "the part below the face groove"),
                   at, d.bottom_z - at.z, g.lo, d.bottom_z, g.line);
            return;
        }
        LatheFinding& f = bar_finding(LatheFinding::Surface::ring, g.line);
        if (record(f, at, g.hi - g.lo, g.lo, g.lo, g.line)) f.designed_hi = g.hi;
    }

    LatheCheck take() {
        std::vector<std::size_t> order(found_.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
            return std::tie(found_[x].kind, rank_[x]) < std::tie(found_[y].kind, rank_[y]);
        });
        for (std::size_t k : order) out_.findings.push_back(found_[k]);
        for (std::size_t i = 0; i < d_.profiles.size(); ++i) {
            const LatheTurnDesign& p = d_.profiles[i];
            if (nose_excess_[i] > tol_)
                out_.notes.push_back(fmt::format(
                    "{}: the nose of tool {} (radius {} mm) leaves up to {} mm beyond the profile (in radius, at Z{}): {}; "
                    "material left is judged beyond what the nose leaves",
                    p.path, p.tool, number_text(p.nose), number_text(nose_excess_[i], 3), number_text(nose_at_[i], 3),
                    p.nose_compensated ? "the nose runs along the profile but cannot reach into a sharp concave corner or "
                                         "past the profile's ends"
                                       : "the profile is the tip's path, without nose compensation"));
        }
        return std::move(out_);
    }

private:
    LatheFinding& finding(LatheFinding::Kind kind, LatheFinding::Surface surface, std::size_t rank, const std::string& path,
                          const char* what) {
        const auto key = std::make_tuple(static_cast<int>(kind), static_cast<int>(surface), rank, std::string(what));
        auto [it, made] = index_.try_emplace(key, found_.size());
        if (made) {
            LatheFinding f;
            f.kind = kind, f.surface = surface, f.path = path, f.what = what;
            found_.push_back(std::move(f));
            rank_.push_back(rank);
        }
        return found_[it->second];
    }

    // The bar where no operation designs it: named after the operation of the line that cut it.
    LatheFinding& bar_finding(LatheFinding::Surface surface, int line) {
        std::string path;
        if (line > 0 && !ops_.empty()) {
            auto it = std::upper_bound(ops_.begin(), ops_.end(), line, [](int l, const OperationSpan& o) { return l < o.first_line; });
            if (it != ops_.begin()) path = std::prev(it)->path;
        }
        // After every operation's own features, in the order the operations first cut the bar.
        const std::size_t base = 2 * (d_.profiles.size() + d_.holes.size()) + d_.rings.size();
        const std::size_t rank = base + bar_rank_.try_emplace(path, bar_rank_.size()).first->second;
        return finding(LatheFinding::Kind::gouge, surface, rank, path,
                       surface == LatheFinding::Surface::outside ? "the bar, which no operation turns there"
                       : surface == LatheFinding::Surface::bore  ? "the bar, which no operation bores there"
                                                                 : "the bar, which no face groove cuts there");
    }

    // A face groove's rank: after the profiles' and the holes' features, before the bar's.
    std::size_t ring_rank(std::size_t r) const { return 2 * (d_.profiles.size() + d_.holes.size()) + r; }

    // Counts the position; true where it is the finding's worst yet (then taken).
    bool record(LatheFinding& f, const LatheCheckAt& at, double amount, double radius, double designed, int line) {
        ++(at.section ? f.sections : f.samples);
        if (amount <= f.amount) return false;
        f.amount = amount, f.z = at.z, f.radius = radius, f.designed = designed, f.line = line;
        return true;
    }

    const LatheDesign& d_;
    double tol_;
    const std::vector<OperationSpan>& ops_;
    double radius_, bore_, end_, face_;
    std::vector<std::optional<std::pair<double, double>>> ranges_;
    std::vector<LatheFinding> found_;
    std::vector<std::size_t> rank_;
    std::map<std::tuple<int, int, std::size_t, std::string>, std::size_t> index_;
    std::map<std::string, std::size_t> bar_rank_;  // the operations that cut the bar where none designs it
    std::vector<double> nose_excess_, nose_at_;
    LatheCheck out_;
};

}  // namespace

std::string LatheFinding::message() const {
    const std::string who = path.empty() ? what : fmt::format("{} ({})", path, what);
    const std::string z_text = number_text(z, 3);
    const bool outside = surface == Surface::outside;
    const std::string by = line > 0 ? fmt::format(", by line {}", line) : std::string();
    std::string where = fmt::format("{} sample{}", samples, samples == 1 ? "" : "s");
    if (sections > 0) where += fmt::format(" and {} section{} beside corners", sections, sections == 1 ? "" : "s");
    if (surface == Surface::ring_bottom)
        return fmt::format("{}: material removed {} mm below the designed bottom Z{} at Z{} (a ring of air from radius {}){} "
                           "(cut at {})",
                           who, number_text(amount, 3), number_text(designed, 3), z_text, number_text(radius, 3), by, where);
    if (surface == Surface::ring && kind == Kind::gouge && what.rfind("the bar", 0) == 0)
        return fmt::format("{}: material removed {} mm thick inside the part at Z{} (a ring of air from radius {} to {}){} "
                           "(cut at {})",
                           who, number_text(amount, 3), z_text, number_text(designed, 3), number_text(designed_hi, 3), by, where);
    if (surface == Surface::ring && kind == Kind::gouge)
        return fmt::format("{}: material removed {} mm beyond the designed ring (radius {} to {}) at Z{} (a ring of air to "
                           "radius {}){} (cut at {})",
                           who, number_text(amount, 3), number_text(designed, 3), number_text(designed_hi, 3), z_text,
                           number_text(radius, 3), by, where);
    if (surface == Surface::ring)
        return fmt::format("{}: material left {} mm thick inside the ring its blade cuts (radius {} to {}) at Z{} (at {})", who,
                           number_text(amount, 3), number_text(designed, 3), number_text(designed_hi, 3), z_text, where);
    if (kind == Kind::gouge)
        return fmt::format("{}: material removed {} mm {} {} at Z{} ({} {}){} (cut at {})", who, number_text(amount, 3),
                           outside ? "inside the designed radius" : "beyond the designed bore radius", number_text(designed, 3),
                           z_text, outside ? "radius" : "bore radius", number_text(radius, 3),
                           line > 0 ? fmt::format(", by line {}", line) : std::string(), where);
    return fmt::format("{}: material left {} mm {} ({}) at Z{}: {} {} (at {})", who, number_text(amount, 3),
                       outside ? "above the radius its tool leaves" : "inside the radius its tool cuts", number_text(designed, 3),
                       z_text, outside ? "radius" : "bore radius", number_text(radius, 3), where);
}

std::vector<double> lathe_check_sections(const LatheDesign& design, const SimStock& bar, double offset) {
    std::vector<double> corners;
    for (const LatheTurnDesign& p : design.profiles)
        for (double c : p.corners()) corners.push_back(c);
    for (const LatheHoleDesign& h : design.holes) {
        corners.push_back(h.bottom_z);
        if (h.slope > 0) corners.push_back(h.bottom_z + (h.radius - h.flat) * h.slope);
        if (h.groove()) {
            corners.push_back(h.top_z);
            if (h.groove_chamfer > 0)
                for (double z : {h.bottom_z - h.groove_chamfer, h.top_z + h.groove_chamfer}) corners.push_back(z);
        }
    }
    for (const LatheRingDesign& r : design.rings)
        for (double z : {r.bottom_z, r.face_z - r.chamfer, r.face_z}) corners.push_back(z);
    const double end = bar.face_z - bar.bar_length;
    std::vector<double> out;
    for (double c : corners)
        for (double z : {c - offset, c + offset})
            if (z >= end && z <= bar.face_z) out.push_back(z);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

LatheCheck check_lathe_design(const LatheDesign& design, const SimStock& bar, const LatheProfile& part,
                              const LatheSections& sections, double tolerance, const std::vector<OperationSpan>& operations) {
    LatheChecker checker(design, bar, tolerance, operations);
    auto line = [](const std::vector<std::int32_t>& lines, std::size_t k) { return k < lines.size() ? static_cast<int>(lines[k]) : 0; };
    for (int k = 0; k < part.nz; ++k) {
        const std::size_t s = static_cast<std::size_t>(k);
        checker.judge({part.z(k), part.outside[s], part.bore[s], line(part.outside_lines, s), line(part.bore_lines, s), false,
                       part.gaps_at(k)});
    }
    for (std::size_t i = 0; i < sections.z.size(); ++i)
        checker.judge({sections.z[i], sections.outside[i], sections.bore[i], line(sections.outside_lines, i),
                       line(sections.bore_lines, i), true, sections.gaps_at(i)});
    return checker.take();
}

std::map<int, ToolShape> job_tool_shapes(const Job& job) {
    std::map<int, ToolShape> shapes = tool_shapes(job.tools);
    for (const Operation& op : job.operations)
        if (const TurnThreadOp* t = std::get_if<TurnThreadOp>(&op); t && t->side == ThreadSide::internal)
            if (const auto it = job.tools.find(t->tool); it != job.tools.end() && it->second.orientation == 0)
                shapes[t->tool].orientation = 3;
    return shapes;
}

LatheDesignCheck prepare_lathe_design_check(const Job& job, const Machine& machine, const SimStock& bar, Simulator& sim) {
    LatheDesignCheck c;
    c.design = part_design(job);
    leave_out_operator_cycles(c.design, job, machine);
    c.bar = bar;
    // As verify compares, and as the mill's check judges: the machine's tolerance and its chords.
    c.tolerance = compare_tolerance(machine).path;
    c.offset = 1.1 * c.tolerance;
    sim.set_lathe_sections(lathe_check_sections(c.design.lathe, bar, c.offset));
    return c;
}

std::size_t report_lathe_design_check(const LatheDesignCheck& c, const SimResult& r, const std::vector<OperationSpan>& operations,
                                      std::ostream& out) {
    const LatheCheck found = check_lathe_design(c.design.lathe, c.bar, r.lathe, r.lathe_sections, c.tolerance, operations);
    const std::size_t profiles = c.design.lathe.profiles.size(), holes = c.design.lathe.holes.size();
    const std::size_t rings = c.design.lathe.rings.size();
    out << fmt::format("design check   lathe: {} profile{}, {} hole{}{}, within {} mm in radius and in Z, {} samples and {} "
                       "sections {} mm beside the designed corners\n",
                       profiles, profiles == 1 ? "" : "s", holes, holes == 1 ? "" : "s",
                       rings == 0 ? std::string() : fmt::format(", {} face groove{}", rings, rings == 1 ? "" : "s"),
                       number_text(c.tolerance), found.samples, found.sections, number_text(c.offset));
    for (const std::string& u : c.design.unchecked) out << "  not checked: " << u << '\n';
    for (const std::string& n : found.notes) out << "  note: " << n << '\n';
    std::size_t gouges = 0;
    for (const LatheFinding& f : found.findings) {
        const bool gouge = f.kind == LatheFinding::Kind::gouge;
        gouges += gouge;
        out << (gouge ? "error: gouge: " : "warning: ") << f.message() << '\n';
    }
    if (found.findings.empty()) out << "  the part is as designed\n";
    return gouges;
}

}  // namespace camgen
