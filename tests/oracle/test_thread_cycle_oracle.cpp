// LinuxCNC oracle for turn-thread's canned cycle (issue 30 item 2): linuxcnc-lathe programs of
// external and internal threads (metric and unified sizes, both infeed rules, radial and flank
// infeed, spring passes, several starts, inch output) written as G76 run through rs274 to their
// end. Every move rs274 makes ends where camgen's reader, expanding G76 by its model of the
// cycle (machines/iso/linuxcnc_g76.hpp), says within 0.001 mm; every synchronised pass starts
// and ends where the job's ThreadCycle events (what verify, stats and the simulation see) put it
// within 0.001 mm (inch programs: plus rs274's own print, 4 decimals of an inch, 0.00127 mm);
// the passes' depths follow the infeed rule, computed here on its own; the last
// is the thread table's depth; G76 shortens each pass's end by (K - d) tan Q.
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
namespace test_thread_cycle_oracle {

using namespace camgen;

namespace {

std::string rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A straight move in (X radius, Z) from where the last one ended; a synchronised feed carries its lead
// (rs274's moves: oracle::xz_moves).
using Move = oracle::XzMove;

// The job's synchronised passes (from, to), from its ThreadCycle events.
std::vector<Move> design_passes(const Job& job) {
    std::vector<Move> out;
    Vec3 at{};
    for (const Event& e : expand_job(job)) {
        const auto* c = std::get_if<ThreadCycle>(&e);
        if (!c) continue;
        at = c->start;
        for (const Event& m : thread_cycle_moves(*c)) {
            if (const auto* r = std::get_if<Rapid>(&m)) {
                at = r->to;
            } else if (const auto* t = std::get_if<ThreadFeed>(&m)) {
                out.push_back(Move{.x = t->to.x, .z = t->to.z, .sync = t->lead, .from_x = at.x, .from_z = at.z});
                at = t->to;
            }
        }
    }
    return out;
}

// The infeed rule, computed here on its own: constant depth, the fewest equal steps of at most
// `first`; constant area, first x sqrt(n) below the total, then the total.
std::vector<double> rule_depths(bool constant_area, double total, double first) {
    std::vector<double> d;
    if (!constant_area) {
        int n = 1;
        while (total / n > first + 1e-9) ++n;
        for (int k = 1; k <= n; ++k) d.push_back(total * k / n);
        return d;
    }
    for (int k = 1;; ++k) {
        const double next = first * std::sqrt(double(k));
        if (next >= total - 1e-9) break;
        d.push_back(next);
    }
    d.push_back(total);
    return d;
}

struct Case {
    std::string thread;
    double major = 0, minor = 0, pitch = 0;
    bool internal = false;
    bool constant_area = true;
    double first = 0.2;
    int spring = 1, starts = 1;
    double angle = 29.5;
    double start_z = 0, end_z = -12.5;
    bool inch = false;
};

std::string job_text(const Case& c) {
    const std::string thread = c.thread.empty()
                                   ? fmt::format(R"("majorDiameter": {:.4f}, "minorDiameter": {:.4f}, "pitch": {:.4f})",
                                                 c.major, c.minor, c.pitch)
                                   : fmt::format(R"("thread": "{}")", c.thread);
    return fmt::format(
        R"({{"clearance": 40,
  "tools": [{{"number": 7, "type": "threading-tool", "noseRadius": 0.05, "profileAngle": 60, "rpm": 300}}],
  "operations": [{{"type": "turn-thread", "tool": 7, {}, "side": "{}", "starts": {},
                   "startZ": {:.3f}, "endZ": {:.3f}, "infeed": "{}", "firstDepth": {:.3f},
                   "springPasses": {}, "infeedAngle": {:.2f}, "output": "canned"}}]}})",
        thread, c.internal ? "internal" : "external", c.starts, c.start_z, c.end_z,
        c.constant_area ? "constant-area" : "constant-depth", c.first, c.spring, c.angle);
}

// Posts the case as G76, runs it in rs274 and checks it; the worst difference, mm.
double check_case(const Case& c) {
    const std::string text = job_text(c);
    INFO(text);
    Job job;
    REQUIRE_NOTHROW(job = read_job(text, "thread.json"));
    Machine m = load_machine("linuxcnc-lathe");
    if (c.inch) m.units = Units::inch;
    std::string program;
    REQUIRE_NOTHROW(program = oracle::posted_program(job, m));
    INFO(program);
    CHECK(program.find("G76 P") != std::string::npos);
    CHECK(program.find("G33") == std::string::npos);
    std::string canon;
    REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(rs274(), program));
    // rs274 prints 4 decimals in the program's units: a move shorter than that print's step is
    // its rounding (G76's last return to the drive line), left out.
    const double unit = c.inch ? 25.4 : 1.0;
    const std::vector<Move> theirs = oracle::xz_moves(canon, unit, 0.0002 * unit);
    const std::vector<Move> ours = oracle::camgen_xz_moves(program, m);
    // rs274 prints 4 decimals: in inch its own rounding is up to 0.00127 mm.
    const double print = c.inch ? 0.00005 * 25.4 : 0.00005;
    REQUIRE(theirs.size() >= ours.size());
    const std::vector<Move> tail(theirs.end() - static_cast<std::ptrdiff_t>(ours.size()), theirs.end());
    double worst = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        INFO("move " << i << ": rs274 " << tail[i].x << " " << tail[i].z << ", camgen " << ours[i].x << " " << ours[i].z);
        CHECK(tail[i].rapid == ours[i].rapid);
        worst = std::max({worst, std::abs(tail[i].x - ours[i].x), std::abs(tail[i].z - ours[i].z)});
    }
    CHECK(worst <= 0.001 + print);

    // rs274's synchronised passes against the job's ThreadCycle passes.
    std::vector<Move> passes;
    for (const Move& mv : theirs)
        if (!mv.rapid) passes.push_back(mv);
    const std::vector<Move> design = design_passes(job);
    REQUIRE(passes.size() == design.size());
    const double tan_q = std::tan(c.angle * 3.14159265358979323846 / 180.0);
    const double surface = (c.internal ? c.minor : c.major) / 2, root = (c.internal ? c.major : c.minor) / 2;
    const double total = std::abs(root - surface);
    std::vector<double> want = rule_depths(c.constant_area, total, c.first);
    for (int k = 0; k < c.spring; ++k) want.push_back(total);
    REQUIRE(passes.size() == want.size() * static_cast<std::size_t>(c.starts));
    for (std::size_t i = 0; i < passes.size(); ++i) {
        const Move& p = passes[i];
        const Move& d = design[i];
        INFO("pass " << i);
        REQUIRE(p.sync > 0);
        CHECK(std::abs(p.sync - c.pitch * c.starts) <= 1e-4 * (c.inch ? 25.4 : 1.0));
        CHECK(std::abs(p.x - p.from_x) <= 1e-9);
        worst = std::max({worst, std::abs(p.from_x - d.from_x), std::abs(p.from_z - d.from_z), std::abs(p.x - d.x),
                          std::abs(p.z - d.z)});
        CHECK(std::abs(p.from_z - d.from_z) <= 0.001 + print);
        CHECK(std::abs(p.z - d.z) <= 0.001 + print);
        CHECK(std::abs(p.x - d.x) <= 0.001 + print);
        const double depth = c.internal ? p.x - surface : surface - p.x;
        const double w = want[i % want.size()];
        CHECK(std::abs(depth - w) <= 0.001 + print);
        // Each pass ends short of endZ by (depth - d) tan Q, the last at endZ.
        CHECK(std::abs(p.z - (c.end_z + (total - w) * tan_q)) <= 0.001 + print);
    }
    if (!c.thread.empty()) {
        const double depth = c.internal ? passes.back().x - surface : surface - passes.back().x;
        CHECK(std::abs(depth - (c.internal ? 0.541266 : 0.613435) * c.pitch) <= 0.001 + print);
    }
    return worst;
}

}  // namespace

TEST_CASE("linuxcnc-lathe G76: an M20x2.5 thread's canned passes in rs274 are camgen's reading and the job's") {
    Case c;
    c.thread = "M20x2.5";
    c.major = 20;
    c.pitch = 2.5;
    c.minor = external_minor_diameter(20, 2.5);
    c.first = 0.35;
    c.spring = 2;
    const double worst = check_case(c);
    MESSAGE("M20x2.5 G76: rs274, camgen's reading and the job differ by at most " << worst << " mm");
}

TEST_CASE("linuxcnc-lathe G76: random threads (pitches, lengths, internal and external, both rules, spring passes, "
          "starts, inch) run in rs274 as camgen reads them and as the job cuts them") {
    std::mt19937 rng(7676);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const char* metric[] = {"M6", "M8", "M10x1.25", "M12", "M16", "M20", "M24", "M30x2", "M36", "M42x3", "M20x1.5"};
    const char* unified[] = {"1/4-20 UNC", "3/8-16 UNC", "1/2-13 UNC", "5/8-18 UNF", "3/4-10 UNC", "1-8 UNC"};
    double worst = 0, worst_inch = 0;
    int canned = 0;
    for (int n = 0; n < 60; ++n) {
        Case c;
        const bool unc = n % 3 == 2;
        c.thread = unc ? unified[rng() % std::size(unified)] : metric[rng() % std::size(metric)];
        c.internal = n % 2 == 1;
        std::string why;
        const auto t = find_thread(c.thread, why);
        REQUIRE(t);
        c.major = t->major;
        c.pitch = t->pitch;
        c.minor = c.internal ? internal_minor_diameter(c.major, c.pitch) : external_minor_diameter(c.major, c.pitch);
        if (n % 7 == 5) {
            c.thread.clear();
            c.minor = std::round((c.minor + (c.internal ? -0.1 : 0.1) * u(rng)) * 1e4) / 1e4;
        }
        c.constant_area = u(rng) < 0.6;
        const double total = std::abs(c.major - c.minor) / 2;
        c.first = std::round(std::max(0.05, total * (0.1 + 0.4 * u(rng))) * 1000) / 1000;
        c.spring = static_cast<int>(rng() % 3);
        c.starts = n % 5 == 4 ? 2 : 1;
        c.angle = u(rng) < 0.3 ? 0.0 : std::round((20 + 9.5 * u(rng)) * 100) / 100;
        c.end_z = c.start_z - std::round((4 + 30 * u(rng)) * 1000) / 1000;
        c.inch = n % 8 == 7;
        (c.inch ? worst_inch : worst) = std::max(c.inch ? worst_inch : worst, check_case(c));
        ++canned;
    }
    MESSAGE(canned << " random G76 threads on linuxcnc-lathe: rs274, camgen's reading and the job differ by at most "
                   << worst << " mm (mm programs), " << worst_inch << " mm (inch programs)");
}

}  // namespace test_thread_cycle_oracle
