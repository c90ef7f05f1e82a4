// LinuxCNC oracle for turn-thread's longhand passes (issue 30; output "longhand": G76 is
// test_thread_cycle_oracle.cpp's): linuxcnc-lathe programs of external and internal
// threads (metric and unified sizes, both infeed rules, radial and flank infeed, spring passes,
// several starts) run through rs274 in lathe mode to their end; every move rs274 makes ends
// where camgen's own reading of the program says within 0.001 mm; each thread pass is a
// spindle-synchronised move (START_SPEED_FEED_SYNC with the lead) along Z only; the passes'
// depths, measured on rs274's trace, follow the infeed rule (computed here on its own) and the
// last is the thread's depth (external metric: 0.613435 P, REFERENCE.md section 10).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include <fmt/format.h>

#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/vocabulary/threads.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_thread_oracle {

using namespace camgen;

namespace {

std::string rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A move in (X radius, Z); a synchronised feed carries its K (rs274's moves: oracle::xz_moves).
using Move = oracle::XzMove;

// The cumulative depths of the infeed rule, computed here on its own: constant depth, the
// fewest equal steps of at most `first`; constant area, first x sqrt(n) below the total, each
// step at least `least`, then the total.
std::vector<double> expected_depths(bool constant_area, double total, double first, double least) {
    std::vector<double> d;
    if (!constant_area) {
        int n = 1;
        while (total / n > first + 1e-9) ++n;
        for (int k = 1; k <= n; ++k) d.push_back(total * k / n);
        return d;
    }
    double at = 0;
    for (int k = 1;; ++k) {
        const double next = std::max(first * std::sqrt(double(k)), at + least);
        if (next >= total - 1e-9) break;
        d.push_back(next);
        at = next;
    }
    d.push_back(total);
    return d;
}

struct Case {
    std::string thread;      // a designation, or "" for the diameters
    double major = 0, minor = 0, pitch = 0;
    bool internal = false;
    bool constant_area = true;
    double first = 0.2, least = 0;
    int spring = 1, starts = 1;
    double angle = 29.5;
    bool left = false;
};

std::string job_text(const Case& c) {
    const std::string thread = c.thread.empty()
                                   ? fmt::format(R"("majorDiameter": {:.4f}, "minorDiameter": {:.4f}, "pitch": {:.4f})",
                                                 c.major, c.minor, c.pitch)
                                   : fmt::format(R"("thread": "{}")", c.thread);
    return fmt::format(
        R"({{"clearance": 40,
  "tools": [{{"number": 7, "type": "threading-tool", "noseRadius": 0.05, "profileAngle": 60, "rpm": 300,
              "direction": "{}"}}],
  "operations": [{{"type": "turn-thread", "tool": 7, {}, "side": "{}", "hand": "{}", "starts": {},
                   "startZ": 0, "endZ": -12.5, "infeed": "{}", "firstDepth": {:.3f}, "minDepth": {:.3f},
                   "springPasses": {}, "infeedAngle": {:.2f}, "output": "longhand"}}]}})",
        c.left ? "ccw" : "cw", thread, c.internal ? "internal" : "external", c.left ? "left" : "right", c.starts,
        c.constant_area ? "constant-area" : "constant-depth", c.first, c.least, c.spring, c.angle);
}

// Posts the case for linuxcnc-lathe, runs it through rs274 and checks the moves, the
// synchronisation and the depths. The worst difference between rs274 and camgen's reading, mm.
double check_case(const Case& c) {
    const std::string text = job_text(c);
    INFO(text);
    Job job;
    REQUIRE_NOTHROW(job = read_job(text, "thread.json"));
    const auto& op = std::get<TurnThreadOp>(job.operations.front());
    const Machine m = load_machine("linuxcnc-lathe");
    const std::string program = oracle::posted_program(job, m);
    INFO(program);
    std::string canon;
    REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(rs274(), program));
    const std::vector<Move> theirs = oracle::xz_moves(canon);
    for (const Move& mv : theirs) CHECK_MESSAGE(!mv.arc, "an arc in a threading program");
    std::vector<Move> ours = oracle::camgen_xz_moves(program, m);
    // rs274 starts at its origin, camgen's reading at the first rapid that sets every axis.
    REQUIRE(theirs.size() >= ours.size());
    const std::vector<Move> tail(theirs.end() - static_cast<std::ptrdiff_t>(ours.size()), theirs.end());
    double worst = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        INFO("move " << i);
        CHECK(tail[i].rapid == ours[i].rapid);
        worst = std::max({worst, std::abs(tail[i].x - ours[i].x), std::abs(tail[i].z - ours[i].z)});
    }
    CHECK(worst <= 0.001);

    // The synchronised moves: along Z towards the chuck, K the lead, to endZ.
    std::vector<double> xs;
    for (const Move& mv : theirs) {
        if (mv.rapid) continue;
        REQUIRE_MESSAGE(mv.sync > 0, "a feed move without spindle synchronisation");
        CHECK(std::abs(mv.sync - c.pitch * c.starts) <= 1e-4);
        CHECK(std::abs(mv.x - mv.from_x) <= 1e-9);
        CHECK(mv.z < mv.from_z);
        CHECK(std::abs(mv.z - (-12.5)) <= 1e-4);
        xs.push_back(mv.x);
    }
    // The depths of each start's passes, from rs274's X (a radius).
    const double surface = (c.internal ? c.minor : c.major) / 2, root = (c.internal ? c.major : c.minor) / 2;
    const double total = std::abs(root - surface);
    std::vector<double> want = expected_depths(c.constant_area, total, c.first, c.least);
    for (int k = 0; k < c.spring; ++k) want.push_back(total);
    REQUIRE(xs.size() == want.size() * static_cast<std::size_t>(c.starts));
    for (std::size_t i = 0; i < xs.size(); ++i) {
        const double depth = c.internal ? xs[i] - surface : surface - xs[i];
        INFO("pass " << i);
        CHECK(std::abs(depth - want[i % want.size()]) <= 0.0001);
    }
    // The last depth is the table's: external 17/24 H = 0.613435 P, internal 5/8 H.
    if (!c.thread.empty()) {
        const double depth = c.internal ? xs.back() - surface : surface - xs.back();
        CHECK(std::abs(depth - (c.internal ? 0.541266 : 0.613435) * c.pitch) <= 0.0001);
    }
    // Each pass starts (its rapid in) beyond the thread and its returns stay outside (inside) it.
    for (std::size_t i = 1; i < theirs.size(); ++i) {
        const Move& mv = theirs[i];
        if (!mv.rapid || mv.z >= 40 - 1e-9) continue;
        if (std::abs(mv.x - mv.from_x) > 1e-9 && std::abs(mv.z - mv.from_z) < 1e-9 && mv.z > -12.5 + 1e-9) {
            // A rapid in X at a pass's start: beyond startZ.
            CHECK(mv.z > 0.0);
        }
        if (std::abs(mv.z - mv.from_z) > 1e-9) {
            // A rapid along Z: outside the thread's surface (inside the bore).
            CHECK((c.internal ? mv.x < surface : mv.x > surface));
        }
    }
    (void)op;
    return worst;
}

}  // namespace

TEST_CASE("linuxcnc-lathe: an M20x2.5 thread's G33 passes run in rs274 as camgen reads them, at the infeed rule's depths") {
    Case c;
    c.thread = "M20x2.5";
    c.major = 20;
    c.pitch = 2.5;
    c.minor = external_minor_diameter(20, 2.5);
    c.first = 0.35;
    c.least = 0.05;
    c.spring = 2;
    const double worst = check_case(c);
    MESSAGE("M20x2.5 external: rs274 and camgen's reading differ by at most " << worst << " mm");
}

TEST_CASE("linuxcnc-lathe: random threads (metric and unified, internal and external, both rules, starts) run in rs274") {
    std::mt19937 rng(3076);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const char* metric[] = {"M6", "M8", "M10x1.25", "M12", "M16", "M20", "M24", "M30x2", "M36", "M42x3"};
    const char* unified[] = {"1/4-20 UNC", "3/8-16 UNC", "1/2-13 UNC", "5/8-18 UNF", "3/4-10 UNC", "1-8 UNC"};
    double worst = 0;
    for (int n = 0; n < 30; ++n) {
        Case c;
        const bool inch = n % 3 == 2;
        const bool diameters = n % 7 == 5;
        c.thread = inch ? unified[rng() % std::size(unified)] : metric[rng() % std::size(metric)];
        c.internal = n % 2 == 1;
        std::string why;
        const auto t = find_thread(c.thread, why);
        REQUIRE(t);
        c.major = t->major;
        c.pitch = t->pitch;
        c.minor = c.internal ? internal_minor_diameter(c.major, c.pitch) : external_minor_diameter(c.major, c.pitch);
        if (diameters) {
            // The same thread by its diameters, its depth a little less than the table's.
            c.thread.clear();
            c.minor += 0.1 * u(rng);
        }
        c.constant_area = u(rng) < 0.6;
        const double total = (c.major - c.minor) / 2;
        // (rounded as the job writes them)
        c.first = std::round(std::max(0.05, total * (0.1 + 0.4 * u(rng))) * 1000) / 1000;
        c.least = u(rng) < 0.5 ? 0.0 : std::round((0.02 + 0.05 * u(rng)) * 1000) / 1000;
        c.spring = static_cast<int>(rng() % 3);
        c.starts = n % 5 == 4 ? 2 : 1;
        c.angle = u(rng) < 0.3 ? 0.0 : 25 + 4.5 * u(rng);
        c.left = n % 6 == 3;
        worst = std::max(worst, check_case(c));
    }
    MESSAGE("30 random threads on linuxcnc-lathe: rs274 and camgen's reading differ by at most " << worst << " mm");
}

}  // namespace test_turn_thread_oracle
