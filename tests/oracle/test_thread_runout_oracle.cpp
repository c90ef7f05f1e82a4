// LinuxCNC oracle for turn-thread's chamfered runout (issue 30): linuxcnc-lathe programs of
// external and internal threads (metric and unified sizes, both infeed rules, radial and flank
// infeed, spring passes, several starts, inch output, runout lengths from the thread's depth to
// two leads) written canned (G76 ... E L2) and longhand (G33 Z K, then G33 X Z K) run through
// rs274 to PROGRAM_END. Every move rs274 makes ends where camgen's reader says within 0.001 mm;
// every synchronised move starts and ends where the job's events put it within 0.001 mm (inch
// programs: plus rs274's own print, 4 decimals of an inch); each pass's taper runs from its depth
// out by the thread's depth over the runout length to the pass's end; and every synchronised
// move advances the thread's lead along Z per revolution, rs274's lead being along the path (its
// START_SPEED_FEED_SYNC times the move's Z over its length).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/vocabulary/threads.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_thread_runout_oracle {

using namespace camgen;

namespace {

std::string runout_rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

using Move = oracle::XzMove;

// The job's synchronised moves (from, to) as linuxcnc-lathe cuts them: its ThreadFeed events,
// a ThreadCycle's expanded.
std::vector<Move> runout_design_moves(const Job& job) {
    std::vector<Move> out;
    Vec3 at{};
    auto take = [&](const Event& m) {
        if (const auto* r = std::get_if<Rapid>(&m)) {
            at = r->to;
        } else if (const auto* t = std::get_if<ThreadFeed>(&m)) {
            out.push_back(Move{.x = t->to.x, .z = t->to.z, .sync = t->lead, .from_x = at.x, .from_z = at.z});
            at = t->to;
        }
    };
    for (const Event& e : expand_job(job)) {
        if (const auto* c = std::get_if<ThreadCycle>(&e)) {
            at = c->start;
            for (const Event& m : thread_cycle_moves(*c)) take(m);
            at = thread_cycle_end(*c);
        } else {
            take(e);
        }
    }
    return out;
}

struct RunoutCase {
    std::string thread;
    double pitch = 0;
    bool internal = false, constant_area = true, canned = true, inch = false;
    double first = 0.2, angle = 29.5, runout = 0;
    int spring = 1, starts = 1;
    double start_z = 0, end_z = -12.5;
};

std::string runout_job_text(const RunoutCase& c) {
    return fmt::format(
        R"({{"clearance": 40,
  "tools": [{{"number": 7, "type": "threading-tool", "noseRadius": 0.05, "profileAngle": 60, "rpm": 300}}],
  "operations": [{{"type": "turn-thread", "tool": 7, "thread": "{}", "side": "{}", "starts": {},
                   "startZ": {:.3f}, "endZ": {:.3f}, "infeed": "{}", "firstDepth": {:.3f},
                   "springPasses": {}, "infeedAngle": {:.2f}, "runout": "chamfered", "runoutLength": {:.3f},
                   "output": "{}"}}]}})",
        c.thread, c.internal ? "internal" : "external", c.starts, c.start_z, c.end_z,
        c.constant_area ? "constant-area" : "constant-depth", c.first, c.spring, c.angle, c.runout,
        c.canned ? "canned" : "longhand");
}

// Posts the case, runs it in rs274 and checks it; the worst difference, mm.
double runout_check(const RunoutCase& c) {
    const std::string text = runout_job_text(c);
    INFO(text);
    Job job;
    REQUIRE_NOTHROW(job = read_job(text, "thread.json"));
    const auto& op = std::get<TurnThreadOp>(job.operations.front());
    Machine m = load_machine("linuxcnc-lathe");
    if (c.inch) m.units = Units::inch;
    std::string program;
    REQUIRE_NOTHROW(program = oracle::posted_program(job, m));
    INFO(program);
    if (c.canned) {
        CHECK(program.find(" L2\n") != std::string::npos);
        CHECK(program.find("G33") == std::string::npos);
    } else {
        CHECK(program.find("G76") == std::string::npos);
        CHECK(program.find("G33 X") != std::string::npos);
    }
    std::string canon;
    REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(runout_rs274(), program));
    const double unit = c.inch ? 25.4 : 1.0;
    const double print = c.inch ? 0.00005 * 25.4 : 0.00005;
    const std::vector<Move> theirs = oracle::xz_moves(canon, unit, 0.0002 * unit);
    const std::vector<Move> ours = oracle::camgen_xz_moves(program, m);
    REQUIRE(theirs.size() >= ours.size());
    const std::vector<Move> tail(theirs.end() - static_cast<std::ptrdiff_t>(ours.size()), theirs.end());
    double worst = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        INFO("move " << i << ": rs274 " << tail[i].x << " " << tail[i].z << ", camgen " << ours[i].x << " " << ours[i].z);
        CHECK(tail[i].rapid == ours[i].rapid);
        worst = std::max({worst, std::abs(tail[i].x - ours[i].x), std::abs(tail[i].z - ours[i].z)});
    }
    CHECK(worst <= 0.001 + print);

    // rs274's synchronised moves against the job's.
    std::vector<Move> sync;
    for (const Move& mv : theirs)
        if (!mv.rapid) sync.push_back(mv);
    const std::vector<Move> design = runout_design_moves(job);
    REQUIRE(sync.size() == design.size());
    REQUIRE(sync.size() == 2 * op.depths.size() * static_cast<std::size_t>(c.starts));
    const double lead = c.pitch * c.starts;
    const double surface = op.surface_radius(), total = std::abs(op.root_radius() - surface);
    const double out = c.internal ? -1.0 : 1.0;
    for (std::size_t i = 0; i < sync.size(); ++i) {
        const Move& p = sync[i];
        const Move& d = design[i];
        INFO("synchronised move " << i << ": rs274 " << p.from_x << " " << p.from_z << " -> " << p.x << " " << p.z);
        worst = std::max({worst, std::abs(p.from_x - d.from_x), std::abs(p.from_z - d.from_z), std::abs(p.x - d.x),
                          std::abs(p.z - d.z)});
        CHECK(std::abs(p.from_x - d.from_x) <= 0.001 + print);
        CHECK(std::abs(p.from_z - d.from_z) <= 0.001 + print);
        CHECK(std::abs(p.x - d.x) <= 0.001 + print);
        CHECK(std::abs(p.z - d.z) <= 0.001 + print);
        // The lead along Z: rs274 synchronises the path's length, K (or G76's P x hypot(E, K) / E)
        // per revolution; its Z advance per revolution is that times Z over the length.
        REQUIRE(p.sync > 0);
        const double dz = std::abs(p.z - p.from_z), dx = std::abs(p.x - p.from_x);
        const double along_z = p.sync * dz / std::hypot(dx, dz);
        CHECK_MESSAGE(std::abs(along_z - lead) <= 0.0005 * unit, along_z << " mm per revolution along Z, not " << lead);
        // Over the move: the Z it drifts off the thread's helix.
        CHECK(std::abs(dz / along_z - dz / lead) * lead <= 0.001 + print);
        const double depth = out * (surface - (i % 2 == 0 ? p.x : p.from_x));
        if (i % 2 == 0) {
            // The straight part at its depth, to runoutLength above the pass's end.
            CHECK(dx <= 1e-9 + 2 * print);
        } else {
            // The taper: out by the thread's depth over runoutLength, to the pass's end.
            CHECK(std::abs(out * (p.x - p.from_x) - total) <= 0.001 + 2 * print);
            CHECK(std::abs(dz - c.runout) <= 0.001 + 2 * print);
            CHECK(std::abs(p.from_z - sync[i - 1].z) <= 1e-9 + print);
        }
        const double w = op.depths[(i / 2) % op.depths.size()];
        CHECK(std::abs(depth - w) <= 0.001 + print);
    }
    // The last taper ends at the crest (the major diameter outside, the minor inside) at endZ.
    CHECK(std::abs(sync.back().x - surface) <= 0.001 + print);
    CHECK(std::abs(sync.back().z - c.end_z) <= 0.001 + print);
    return worst;
}

}  // namespace

TEST_CASE("linuxcnc-lathe chamfered runout: an M20x2.5 thread's G76 E L2 and its G33 X Z K passes in rs274 are camgen's") {
    for (const bool canned : {true, false}) {
        RunoutCase c;
        c.thread = "M20x2.5";
        c.pitch = 2.5;
        c.first = 0.35;
        c.spring = 2;
        c.runout = 2.5;
        c.canned = canned;
        const double worst = runout_check(c);
        MESSAGE("M20x2.5 " << std::string(canned ? "G76 E2.5 L2" : "G33 X Z K") << ": rs274, camgen's reading and the job differ by at most "
                           << worst << " mm");
    }
}

TEST_CASE("linuxcnc-lathe chamfered runout: random threads (canned and longhand, internal and external, both rules, flank "
          "and radial, spring passes, starts, runout lengths, inch) run in rs274 as camgen reads them and as the job cuts them") {
    std::mt19937 rng(3030);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const char* metric[] = {"M6", "M8", "M10x1.25", "M12", "M16", "M20", "M24", "M30x2", "M36", "M20x1.5"};
    const char* unified[] = {"1/4-20 UNC", "3/8-16 UNC", "1/2-13 UNC", "5/8-18 UNF", "3/4-10 UNC"};
    double worst = 0;
    int runs = 0;
    for (int n = 0; n < 48; ++n) {
        RunoutCase c;
        const bool unc = n % 3 == 2;
        c.thread = unc ? unified[rng() % std::size(unified)] : metric[rng() % std::size(metric)];
        c.internal = n % 2 == 1;
        c.canned = n % 4 < 2;
        std::string why;
        const auto t = find_thread(c.thread, why);
        REQUIRE(t);
        c.pitch = t->pitch;
        const double minor = c.internal ? internal_minor_diameter(t->major, t->pitch) : external_minor_diameter(t->major, t->pitch);
        const double total = std::abs(t->major - minor) / 2;
        c.constant_area = u(rng) < 0.6;
        c.first = std::round(std::max(0.05, total * (0.1 + 0.4 * u(rng))) * 1000) / 1000;
        c.spring = static_cast<int>(rng() % 3);
        c.starts = n % 5 == 4 ? 2 : 1;
        c.angle = u(rng) < 0.3 ? 0.0 : std::round((20 + 9.5 * u(rng)) * 100) / 100;
        c.end_z = c.start_z - std::round((8 + 26 * u(rng)) * 1000) / 1000;
        // From the depth (45 degrees) to two leads, rounded up to the micrometre.
        c.runout = std::ceil((total + (2 * c.pitch * c.starts - total) * u(rng)) * 1000) / 1000;
        c.inch = n % 8 == 7;
        worst = std::max(worst, runout_check(c));
        ++runs;
    }
    MESSAGE(runs << " random chamfered runouts on linuxcnc-lathe (half G76 E L2, half G33 X Z K): rs274, camgen's reading "
                 "and the job differ by at most " << worst << " mm");
}

}  // namespace test_thread_runout_oracle
