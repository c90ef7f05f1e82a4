// LinuxCNC oracle for turn-rough's canned cycle (issue 30 item 2): many generated turn-rough jobs
// (monotone shafts with steps, tapers, chamfers, rounds and fillets; allowances; the nose made
// up for by camgen or not) posted for linuxcnc-lathe, where most become G71 with the boundary as
// a subroutine, run in rs274 (lathe mode) to PROGRAM_END. Every move rs274 makes is camgen's
// reading of the program within 0.001 mm, and that reading is the job's moves (verify --job).
// On the read-back path: no feed goes below the boundary (the profile and its allowances, as the
// tip follows it), and every rapid runs in air above what the moves before it left. The same
// along X, where most become G72.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/turn_rough/turn_rough.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_rough_cycle_oracle {

using namespace camgen;

namespace {

std::string trc_rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A move's end in (X radius, Z), a rapid or an arc (rs274's: oracle::xz_moves; camgen's: oracle::camgen_xz_moves).
using TrcEnd = oracle::XzMove;

// A generated monotone profile as job path elements (diameters), from (Z0, r0).
std::string trc_path(std::mt19937& rng, double& r0) {
    auto pick = [&](int lo, int hi) { return lo + static_cast<int>(rng() % static_cast<unsigned>(hi - lo + 1)); };
    double z = 0, r = pick(6, 14) * 0.5;
    r0 = r;
    std::string out;
    auto add = [&](const std::string& e) { out += (out.empty() ? "" : ", ") + e; };
    auto line = [&](double nz, double nr) {
        add(fmt::format(R"({{"line": [{}, {}]}})", 2 * nr, nz));
        z = nz, r = nr;
    };
    auto arc = [&](double nz, double nr, double cz, double cr, const char* dir) {
        add(fmt::format(R"({{"arc": {{"end": [{}, {}], "centre": [{}, {}], "direction": "{}"}}}})", 2 * nr, nz, 2 * cr, cz, dir));
        z = nz, r = nr;
    };
    const int n = pick(2, 6);
    for (int i = 0; i < n && r < 15; ++i) {
        switch (pick(0, 5)) {
            case 0: line(z - pick(2, 16) * 0.5, r); break;                             // along -Z
            case 1: line(z - pick(2, 10) * 0.5, r + pick(1, 5) * 0.5); break;          // a taper
            case 2: line(z, r + pick(1, 6) * 0.5), line(z - pick(2, 8) * 0.5, r); break;  // a shoulder and a cylinder
            case 3: {                                                                  // a chamfer
                const double k = pick(1, 6) * 0.25;
                line(z - k, r + k);
            } break;
            case 4: {  // a convex quarter round, face to cylinder
                const double k = pick(2, 8) * 0.25;
                arc(z - k, r + k, z - k, r, "ccw");
                line(z - pick(2, 6) * 0.5, r);
            } break;
            default: {  // a concave quarter fillet, cylinder to face
                const double k = pick(2, 8) * 0.25;
                line(z - pick(2, 6) * 0.5, r);
                arc(z - k, r + k, z, r + k, "cw");
            } break;
        }
    }
    if (out.empty()) line(z - 5, r);
    line(z - 2, r);
    return out;
}

// On the program camgen's reader makes of it: the deepest a feed goes below the boundary, and
// the deepest a rapid runs into what the moves before it left (the bar as a radius every
// 0.01 mm of Z; a feed takes everything above the tip at its Z, as the insert stands there).
struct TrcCheck {
    double gouge = 0, rapid_in_material = 0;
    Vec2 gouge_at;  // where the deepest feed below the boundary is (Z, radius)
    int feeds = 0, rapids = 0;
};

TrcCheck trc_check(const std::vector<ReadEvent>& events, const TurnRoughOp& op, double bar, double face, double clearance) {
    TrcCheck c;
    const double g0 = -80.0, dz = 0.01;
    const int cells = static_cast<int>((clearance + 5 - g0) / dz);
    std::vector<double> top(cells);
    for (int i = 0; i < cells; ++i) top[i] = g0 + i * dz <= face + 1e-9 ? bar : 0.0;
    const double z_hi = op.tip_boundary.start.x, z_lo = op.tip_boundary.segments.back().end.x;
    auto cell = [&](double z) { return std::clamp(static_cast<int>(std::lround((z - g0) / dz)), 0, cells - 1); };
    auto visit = [&](Vec2 p, bool rapid) {  // p: (Z, radius)
        const int i = cell(p.x);
        if (rapid) {
            c.rapid_in_material = std::max(c.rapid_in_material, top[i] - p.y);
            return;
        }
        if (p.x >= z_lo - 1e-9 && p.x <= z_hi + 1e-9) {
            const double b = turn_rough_boundary_at(op, std::clamp(p.x, z_lo, z_hi));
            if (std::isfinite(b)) c.gouge = std::max(c.gouge, b - p.y);
        }
        top[i] = std::min(top[i], p.y);
    };
    bool started = false;
    Vec2 at;
    for (const ReadEvent& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e.event)) {
            const Vec2 to{r->to.z, r->to.x};
            if (!started) {
                started = r->to.x >= bar && r->to.z >= clearance - 1e-6;
                at = to;
                continue;
            }
            const int n = std::max(1, static_cast<int>(distance(at, to) / 0.002));
            for (int k = 1; k <= n; ++k) visit(at + (to - at) * (static_cast<double>(k) / n), true);
            at = to;
            ++c.rapids;
        } else if (const auto* l = std::get_if<Linear>(&e.event); l && started) {
            const Vec2 to{l->to.z, l->to.x};
            const int n = std::max(1, static_cast<int>(distance(at, to) / 0.002));
            for (int k = 0; k <= n; ++k) visit(at + (to - at) * (static_cast<double>(k) / n), false);
            at = to;
            ++c.feeds;
        } else if (const auto* a = std::get_if<Arc>(&e.event); a && started) {
            const Vec2 cc{a->centre.z, a->centre.x}, to{a->to.z, a->to.x};
            const double rad = distance(at, cc);
            const double a0 = std::atan2(at.y - cc.y, at.x - cc.x), a1 = std::atan2(to.y - cc.y, to.x - cc.x);
            double sweep = a->direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
            while (sweep < 0) sweep += 2 * M_PI;
            const int n = std::max(1, static_cast<int>(sweep * rad / 0.002));
            for (int k = 0; k <= n; ++k) {
                const double ang = a0 + (a->direction == ArcDirection::ccw ? 1 : -1) * sweep * k / n;
                visit(k == n ? to : Vec2{cc.x + rad * std::cos(ang), cc.y + rad * std::sin(ang)}, false);
            }
            at = to;
            ++c.feeds;
        }
    }
    return c;
}

// The same along X: the bar as a face Z for each radius every 0.01 mm (material below the
// bar's radius up to its face); a feed takes everything +Z of the tip at its radius (the insert
// stands there); a rapid below a radius's face Z runs into material.
TrcCheck trc_check_x(const std::vector<ReadEvent>& events, const TurnRoughOp& op, double bar, double face, double clearance) {
    TrcCheck c;
    const double dr = 0.01;
    const int cells = static_cast<int>((bar + 10) / dr);
    std::vector<double> top(cells);
    for (int i = 0; i < cells; ++i) top[i] = i * dr < bar - 1e-9 ? face : -1e9;
    const double z_hi = op.tip_boundary.start.x, z_lo = op.tip_boundary.segments.back().end.x;
    auto cell = [&](double r) { return std::clamp(static_cast<int>(std::lround(r / dr)), 0, cells - 1); };
    auto visit = [&](Vec2 p, bool rapid) {  // p: (Z, radius)
        const int i = cell(p.y);
        if (rapid) {
            c.rapid_in_material = std::max(c.rapid_in_material, top[i] - p.x);
            return;
        }
        if (p.x >= z_lo - 1e-9 && p.x <= z_hi + 1e-9) {
            // The boundary's least radius within 0.0001 mm of the point's Z (the program's Z
            // carries 4 decimals, and where the tip path stands steep, a nose's round at a
            // corner, its radius changes fast with Z).
            double b = INFINITY;
            for (double dz : {-1e-4, 0.0, 1e-4}) b = std::min(b, turn_rough_boundary_at(op, std::clamp(p.x + dz, z_lo, z_hi)));
            if (std::isfinite(b) && b - p.y > c.gouge) c.gouge = b - p.y, c.gouge_at = p;
        }
        top[i] = std::min(top[i], p.x);
    };
    bool started = false;
    Vec2 at;
    for (const ReadEvent& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e.event)) {
            const Vec2 to{r->to.z, r->to.x};
            if (!started) {
                started = r->to.x >= bar && r->to.z >= clearance - 1e-6;
                at = to;
                continue;
            }
            const int n = std::max(1, static_cast<int>(distance(at, to) / 0.002));
            for (int k = 1; k <= n; ++k) visit(at + (to - at) * (static_cast<double>(k) / n), true);
            at = to;
            ++c.rapids;
        } else if (const auto* l = std::get_if<Linear>(&e.event); l && started) {
            const Vec2 to{l->to.z, l->to.x};
            const int n = std::max(1, static_cast<int>(distance(at, to) / 0.002));
            for (int k = 0; k <= n; ++k) visit(at + (to - at) * (static_cast<double>(k) / n), false);
            at = to;
            ++c.feeds;
        } else if (const auto* a = std::get_if<Arc>(&e.event); a && started) {
            const Vec2 cc{a->centre.z, a->centre.x}, to{a->to.z, a->to.x};
            const double rad = distance(at, cc);
            const double a0 = std::atan2(at.y - cc.y, at.x - cc.x), a1 = std::atan2(to.y - cc.y, to.x - cc.x);
            double sweep = a->direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
            while (sweep < 0) sweep += 2 * M_PI;
            const int n = std::max(1, static_cast<int>(sweep * rad / 0.002));
            for (int k = 0; k <= n; ++k) {
                const double ang = a0 + (a->direction == ArcDirection::ccw ? 1 : -1) * sweep * k / n;
                visit(k == n ? to : Vec2{cc.x + rad * std::cos(ang), cc.y + rad * std::sin(ang)}, false);
            }
            at = to;
            ++c.feeds;
        }
    }
    return c;
}

}  // namespace

TEST_CASE("linuxcnc-lathe: generated turn-rough jobs as G71 run in rs274 as camgen reads them, leave the allowances, "
          "return in air") {
    const std::string rs274 = trc_rs274();
    const Machine m = load_machine("linuxcnc-lathe");
    std::mt19937 rng(2026120330);
    int canned = 0, total = 0;
    double worst = 0, worst_gouge = 0, worst_rapid = 0;
    for (int n = 0; n < 80; ++n) {
        double r0 = 0;
        const std::string path = trc_path(rng, r0);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const double doc = std::round((0.5 + 2.0 * u(rng)) * 100) / 100;
        const double ax = std::round(0.6 * u(rng) * 100) / 100, az = std::round(0.3 * u(rng) * 100) / 100;
        const bool nose = n % 2 == 0;
        const std::string text = fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 34, "length": 80, "faceZ": 0}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-rough", "tool": 1, "feedMode": "per-revolution", "feed": 0.2, "depthOfCut": {},
                   "allowanceX": {}, "allowanceZ": {}, "lift": {}, "compensation": "{}", "start": [{}, 0], "path": [{}]}}]}})",
            doc, ax, az, n % 3 == 0 ? 1.0 : 0.5, nose ? "computer" : "none", 2 * r0, path);
        if (!oracle::oracle_case(n)) continue;
        CAPTURE(n);
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "rough.json"));
        const auto& op = std::get<TurnRoughOp>(job.operations.front());
        const std::string program = oracle::posted_program(job, m);
        INFO(program);
        const bool g71 = program.find("G71 Q") != std::string::npos;
        canned += g71 ? 1 : 0;
        ++total;
        // rs274 runs it to its end, moving as camgen reads it.
        std::string canon;
        REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(rs274, program));
        auto from_first_feed = [](std::vector<TrcEnd> v) {
            const auto it = std::find_if(v.begin(), v.end(), [](const TrcEnd& e) { return !e.rapid; });
            return std::vector<TrcEnd>(it, v.end());
        };
        const std::vector<TrcEnd> theirs = from_first_feed(oracle::xz_moves(canon)),
                                  ours = from_first_feed(oracle::camgen_xz_moves(program, m));
        REQUIRE(theirs.size() == ours.size());
        double here = 0;
        for (std::size_t i = 0; i < ours.size(); ++i) {
            CAPTURE(i);
            CHECK(theirs[i].rapid == ours[i].rapid);
            CHECK(theirs[i].arc == ours[i].arc);
            here = std::max({here, std::abs(theirs[i].x - ours[i].x), std::abs(theirs[i].z - ours[i].z)});
        }
        CHECK(here <= 0.001);
        worst = std::max(worst, here);
        // verify --job: the reading is the job's moves (within its 0.001 mm: the control's moves
        // are those of the rounded subroutine).
        const std::vector<ReadEvent> read = read_program(program, m, "rough.ngc");
        const auto mismatch = compare_traces(trace_expected(expand_job(job), m), trace_program(read, m), compare_tolerance(m));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        // The allowances stay, the rapids run in air.
        const TrcCheck c = trc_check(read, op, 17.0, 0.0, 10.0);
        CHECK(c.feeds > 3);
        CHECK(c.gouge <= 0.001);
        CHECK(c.rapid_in_material <= 0.001);
        worst_gouge = std::max(worst_gouge, c.gouge);
        worst_rapid = std::max(worst_rapid, c.rapid_in_material);
    }
    CHECK(canned * 2 >= total);
    MESSAGE(total << " generated turn-rough jobs on linuxcnc-lathe, " << canned << " as G71: rs274 and camgen's reading "
                  << "differ by at most " << worst << " mm; deepest feed below the boundary " << worst_gouge
                  << " mm, deepest rapid into material " << worst_rapid << " mm");
}

TEST_CASE("the rapids-in-air check of the cycle oracle finds a rapid through the bar and a feed into the allowance") {
    const std::string text =
        R"({"clearance": 10, "stock": {"bar": {"diameter": 34, "length": 80, "faceZ": 0}},
  "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}],
  "operations": [{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": 1.5, "allowanceX": 0.4, "allowanceZ": 0.1,
                  "compensation": "none", "start": [20, 0], "path": [{"line": [20, -20]}, {"line": [30, -25]}, {"line": [30, -30]}]}]})";
    const Job job = read_job(text, "rough.json");
    const auto& op = std::get<TurnRoughOp>(job.operations.front());
    const Machine m = load_machine("linuxcnc-lathe");
    const std::string program = oracle::posted_program(job, m);
    REQUIRE(program.find("G71 Q") != std::string::npos);
    std::vector<ReadEvent> read = read_program(program, m, "rough.ngc");
    const TrcCheck good = trc_check(read, op, 17.0, 0.0, 10.0);
    CHECK(good.gouge <= 0.001);
    CHECK(good.rapid_in_material <= 0.001);
    // The last pass's feed along the cylinder (boundary radius 10.2) ending 0.1 deeper: found.
    std::vector<ReadEvent> deeper = read;
    bool moved = false;
    for (auto it = deeper.rbegin(); it != deeper.rend() && !moved; ++it)
        if (auto* l = std::get_if<Linear>(&it->event); l && std::abs(l->to.x - 10.2) < 1e-3 && l->to.z < -19) l->to.x = 10.1, moved = true;
    REQUIRE(moved);
    CHECK(trc_check(deeper, op, 17.0, 0.0, 10.0).gouge >= 0.099);
    // A rapid straight along -Z at the bar's radius less 1 from the start: through material.
    std::vector<ReadEvent> through = read;
    for (std::size_t i = 0; i < through.size(); ++i)
        if (std::holds_alternative<Linear>(through[i].event)) {
            through.insert(through.begin() + static_cast<std::ptrdiff_t>(i), ReadEvent{.event = Rapid{{16.0, 0.0, -10.0}}});
            break;
        }
    CHECK(trc_check(through, op, 17.0, 0.0, 10.0).rapid_in_material > 0.5);
}


TEST_CASE("linuxcnc-lathe: generated turn-rough jobs along X as G72 run in rs274 as camgen reads them, leave the "
          "allowances, return in air") {
    const std::string rs274 = trc_rs274();
    const Machine m = load_machine("linuxcnc-lathe");
    std::mt19937 rng(2026120372);
    int canned = 0, total = 0;
    double worst = 0, worst_gouge = 0, worst_rapid = 0;
    for (int n = 0; n < 80; ++n) {
        double r0 = 0;
        const std::string path = trc_path(rng, r0);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const double doc = std::round((0.5 + 2.0 * u(rng)) * 100) / 100;
        const double ax = std::round(0.6 * u(rng) * 100) / 100, az = std::round(0.3 * u(rng) * 100) / 100;
        const bool nose = n % 2 == 0;
        const std::string text = fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 34, "length": 80, "faceZ": 0}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-rough", "direction": "x", "tool": 1, "feedMode": "per-revolution", "feed": 0.2, "depthOfCut": {},
                   "allowanceX": {}, "allowanceZ": {}, "lift": {}, "compensation": "{}", "start": [{}, 0], "path": [{}]}}]}})",
            doc, ax, az, n % 3 == 0 ? 1.0 : 0.5, nose ? "computer" : "none", 2 * r0, path);
        if (!oracle::oracle_case(n)) continue;
        CAPTURE(n);
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "rough.json"));
        const auto& op = std::get<TurnRoughOp>(job.operations.front());
        const std::string program = oracle::posted_program(job, m);
        INFO(program);
        const bool g72 = program.find("G72 Q") != std::string::npos;
        canned += g72 ? 1 : 0;
        ++total;
        std::string canon;
        REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(rs274, program));
        auto from_first_feed = [](std::vector<TrcEnd> v) {
            const auto it = std::find_if(v.begin(), v.end(), [](const TrcEnd& e) { return !e.rapid; });
            return std::vector<TrcEnd>(it, v.end());
        };
        const std::vector<TrcEnd> theirs = from_first_feed(oracle::xz_moves(canon)),
                                  ours = from_first_feed(oracle::camgen_xz_moves(program, m));
        REQUIRE(theirs.size() == ours.size());
        double here = 0;
        for (std::size_t i = 0; i < ours.size(); ++i) {
            CAPTURE(i);
            CHECK(theirs[i].rapid == ours[i].rapid);
            CHECK(theirs[i].arc == ours[i].arc);
            here = std::max({here, std::abs(theirs[i].x - ours[i].x), std::abs(theirs[i].z - ours[i].z)});
        }
        CHECK(here <= 0.001);
        worst = std::max(worst, here);
        const std::vector<ReadEvent> read = read_program(program, m, "rough.ngc");
        const auto mismatch = compare_traces(trace_expected(expand_job(job), m), trace_program(read, m), compare_tolerance(m));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        const TrcCheck c = trc_check_x(read, op, 17.0, 0.0, 10.0);
        CHECK(c.feeds > 3);
        CHECK_MESSAGE(c.gouge <= 0.001, "at Z " << c.gouge_at.x << " X " << c.gouge_at.y);
        CHECK(c.rapid_in_material <= 0.001);
        worst_gouge = std::max(worst_gouge, c.gouge);
        worst_rapid = std::max(worst_rapid, c.rapid_in_material);
    }
    CHECK(canned * 2 >= total);
    MESSAGE(total << " generated turn-rough jobs along X on linuxcnc-lathe, " << canned << " as G72: rs274 and camgen's reading "
                  << "differ by at most " << worst << " mm; deepest feed below the boundary " << worst_gouge
                  << " mm, deepest rapid into material " << worst_rapid << " mm");
}

TEST_CASE("the along-X check of the cycle oracle finds a rapid through the bar and a feed into the allowance") {
    const std::string text =
        R"({"clearance": 10, "stock": {"bar": {"diameter": 34, "length": 80, "faceZ": 0}},
  "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}],
  "operations": [{"type": "turn-rough", "direction": "x", "tool": 1, "feed": 200, "depthOfCut": 1.5, "allowanceX": 0.4, "allowanceZ": 0.1,
                  "compensation": "none", "start": [20, 0], "path": [{"line": [20, -20]}, {"line": [30, -25]}, {"line": [30, -30]}]}]})";
    const Job job = read_job(text, "rough.json");
    const auto& op = std::get<TurnRoughOp>(job.operations.front());
    const Machine m = load_machine("linuxcnc-lathe");
    const std::string program = oracle::posted_program(job, m);
    REQUIRE(program.find("G72 Q") != std::string::npos);
    std::vector<ReadEvent> read = read_program(program, m, "rough.ngc");
    const TrcCheck good = trc_check_x(read, op, 17.0, 0.0, 10.0);
    CHECK(good.gouge <= 0.001);
    CHECK(good.rapid_in_material <= 0.001);
    // The last pass's feed back along the cylinder (boundary radius 10.2) ending 0.1 deeper: found.
    std::vector<ReadEvent> deeper = read;
    bool moved = false;
    for (auto it = deeper.rbegin(); it != deeper.rend() && !moved; ++it)
        if (auto* l = std::get_if<Linear>(&it->event); l && std::abs(l->to.x - 10.2) < 1e-3 && l->to.z > -19) l->to.x = 10.1, moved = true;
    REQUIRE(moved);
    CHECK(trc_check_x(deeper, op, 17.0, 0.0, 10.0).gouge >= 0.099);
    // A rapid along -X at Z-10 to radius 12 before the first feed: through the bar.
    std::vector<ReadEvent> through = read;
    for (std::size_t i = 0; i < through.size(); ++i)
        if (std::holds_alternative<Linear>(through[i].event)) {
            through.insert(through.begin() + static_cast<std::ptrdiff_t>(i), ReadEvent{.event = Rapid{{12.0, 0.0, -10.0}}});
            break;
        }
    CHECK(trc_check_x(through, op, 17.0, 0.0, 10.0).rapid_in_material > 0.5);
}

}  // namespace test_turn_rough_cycle_oracle
