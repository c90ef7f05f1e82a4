// Fanuc T's two-block G76 on fanuc-lathe (issue 30): camgen's model of the cycle
// (machines/iso/fanuc_g76.hpp: there is no Fanuc interpreter here, so these are properties of
// the model and of the post and reader held to it): the depths follow the rule, the last is the
// height; the words written are the thread cycle's, rounded; a program posted and read back
// makes the job's moves (traced for fanuc-lathe: the passes in Fanuc's pattern, canned or
// longhand) within the machine's resolution, on many generated threads.
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
#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "machines/iso/fanuc_g76.hpp"
#include "support.hpp"

namespace test_fanuc_g76 {

using namespace camgen;

namespace {

std::string fanuc_g76_job(const std::string& op, const std::string& units = "mm", int direction_ccw = 0) {
    const double s = units == "inch" ? 1 / 25.4 : 1.0;
    // No stock: a thread is cut on a diameter turned to its major, which a bar nothing turned is
    // not (check_blade_material).
    return fmt::format(R"({{"units": "{}", "clearance": {},
        "tools": [{{"number": 5, "type": "threading-tool", "noseRadius": {}, "profileAngle": 60, "rpm": 300{}}}],
        "operations": [{{"type": "turn-thread", "tool": 5, {}}}]}})",
                       units, 20 * s, 0.1 * s, direction_ccw ? R"(, "direction": "ccw")" : "", op);
}

struct FanucPosted {
    Job job;
    std::string text, notes;
};

FanucPosted fanuc_g76_post(const std::string& job_text, const Machine& m) {
    FanucPosted p{read_job(job_text, "t.json"), {}, {}};
    std::ostringstream out, notes;
    PostOptions o;
    o.notes = &notes;
    auto post = make_post(m, out, o);
    post->open();
    expand_job(p.job, *post);
    post->close();
    p.text = out.str();
    p.notes = notes.str();
    return p;
}

std::vector<std::string> g76_lines(const std::string& text) {
    std::vector<std::string> out;
    for (const std::string& l : test::lines_of(text))
        if (l.find(" G76 ") != std::string::npos || l.rfind("G76 ", 0) == 0) out.push_back(l.substr(l.find("G76 ")));
    return out;
}

}  // namespace

TEST_CASE("fanuc G76 model: first x sqrt(n), the least step, roughing to k - d, then m passes at k") {
    iso::FanucG76 g;
    g.k = 1.534, g.first = 0.4, g.m = 1;
    std::vector<double> d = iso::fanuc_g76_depths(g);
    // ceil((1.534 / 0.4)^2) = 15: 14 below the height, the 15th clamped to it, 1 finishing pass.
    REQUIRE(d.size() == 16);
    for (int n = 1; n <= 14; ++n) CHECK(d[n - 1] == doctest::Approx(0.4 * std::sqrt(double(n))).epsilon(1e-12));
    CHECK(d[14] == 1.534);
    CHECK(d[15] == 1.534);
    // A least step: no step below it (the last may be less: what is left).
    g.least = 0.15, g.m = 2;
    d = iso::fanuc_g76_depths(g);
    // (the last roughing pass is clamped at the height: what is left, which may be less)
    for (std::size_t n = 1; n + 3 < d.size(); ++n) CHECK(d[n] - d[n - 1] >= 0.15 - 1e-12);
    CHECK(d[d.size() - 1] == 1.534);
    CHECK(d[d.size() - 2] == 1.534);
    CHECK(d[d.size() - 3] == 1.534);
    // A finishing allowance: the roughing ends at k - d, the finishing pass takes d.
    g.least = 0, g.m = 1, g.finish = 0.1;
    d = iso::fanuc_g76_depths(g);
    CHECK(d[d.size() - 2] == doctest::Approx(1.434));
    CHECK(d.back() == 1.534);
    for (std::size_t n = 0; n + 2 < d.size(); ++n) CHECK(d[n] < 1.434);
    // The least step equal to the first: equal steps.
    g.first = g.least = 0.3, g.finish = 0, g.k = 1.2;
    d = iso::fanuc_g76_depths(g);
    REQUIRE(d.size() == 5);
    for (int n = 1; n <= 4; ++n) CHECK(d[n - 1] == doctest::Approx(0.3 * n));
}

TEST_CASE("fanuc G76 model: the passes from the start point along the flank at a/2, the last at X and Z") {
    iso::FanucG76 g;
    g.start_x = 12, g.start_z = 6, g.x = 8.5, g.z = -20, g.k = 1.5, g.first = 0.5, g.m = 1, g.angle = 60, g.lead = 2.5;
    const std::vector<Event> moves = iso::fanuc_g76_moves(g);
    const std::vector<double> depths = iso::fanuc_g76_depths(g);
    REQUIRE(moves.size() == 5 * depths.size());
    const double t = std::tan(std::numbers::pi / 6);
    for (std::size_t n = 0; n < depths.size(); ++n) {
        const double d = depths[n];
        CHECK(std::get<Rapid>(moves[5 * n]).to.x == 12);
        CHECK(std::get<Rapid>(moves[5 * n]).to.z == doctest::Approx(6 - d * t));
        CHECK(std::get<Rapid>(moves[5 * n + 1]).to.x == doctest::Approx(10 - d));
        const auto& f = std::get<ThreadFeed>(moves[5 * n + 2]);
        CHECK(f.to.z == doctest::Approx(-20 + (1.5 - d) * t));
        CHECK(f.lead == 2.5);
        CHECK(std::get<Rapid>(moves[5 * n + 3]).to.x == 12);
        CHECK(std::get<Rapid>(moves[5 * n + 4]).to == Vec3{12, 0, 6});
    }
    const auto& last = std::get<ThreadFeed>(moves[moves.size() - 3]);
    CHECK(last.to.x == doctest::Approx(8.5));
    CHECK(last.to.z == doctest::Approx(-20));
    // Radial (a = 0): no move along Z before a pass; internal: X beyond the start.
    g.angle = 0, g.start_x = 8, g.x = 10.5;
    const std::vector<Event> radial = iso::fanuc_g76_moves(g);
    REQUIRE(radial.size() == 4 * depths.size());
    CHECK(std::get<Rapid>(radial[0]).to.x == doctest::Approx(9 + 0.5));
    CHECK(std::get<ThreadFeed>(radial[radial.size() - 3]).to.x == doctest::Approx(10.5));
}

TEST_CASE("fanuc G76 on fanuc-lathe: the two blocks carry the thread cycle's values, rounded") {
    const Machine m = load_machine("fanuc-lathe");
    // M20x2.5 outside, a flank infeed of 30 (a = 60), 2 spring passes, a least step.
    const auto p = fanuc_g76_post(fanuc_g76_job(R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4,
        "minDepth": 0.12, "springPasses": 2, "infeedAngle": 30, "approachDistance": 6)"),
                                  m);
    const auto& op = std::get<TurnThreadOp>(p.job.operations.front());
    const ThreadCycle c = thread_cycle(op, 0);
    REQUIRE(c.min_depth == 0.12);
    const std::vector<std::string> g76 = g76_lines(p.text);
    REQUIRE_MESSAGE(g76.size() == 2, p.text);
    CHECK(p.text.find("G32") == std::string::npos);
    // m 02 r 00 a 60; Q the least step and P the height in um; R0 (the spring passes finish).
    CHECK(g76[0] == "G76 P020060 Q120 R0.000");
    const double k = 0.613435 * 2.5;  // 1.5335875
    CHECK(g76[1] == fmt::format("G76 X{:.3f} Z-20.000 P{} Q400 F2.5000", 2 * (10 - k), std::lround(k * 1000)));
    // The start point before it: X the crest plus the retract (a diameter), Z the approach.
    CHECK(p.text.find(" X22.000\nN40 Z6.000\nN45 G76 ") != std::string::npos);
    // Read back: each pass as the model cuts it, the job's moves as traced for fanuc-lathe.
    const auto read = read_program(p.text, m, "t.nc");
    CHECK_FALSE(compare_traces(trace_expected(expand_job(p.job), m), trace_program(read, m), compare_tolerance(m, 0.0)));
    int feeds = 0;
    double last_x = 0;
    for (const ReadEvent& e : read)
        if (const auto* f = std::get_if<ThreadFeed>(&e.event)) ++feeds, last_x = f->to.x;
    CHECK(feeds == static_cast<int>(op.depths.size()));
    CHECK(last_x == doctest::Approx(10 - k).epsilon(1e-4));
    // A height off by one increment is another thread: the comparison finds it.
    std::string wrong = p.text;
    wrong.replace(wrong.find(fmt::format(" P{} ", std::lround(k * 1000))), 6, " P1500 ");
    CHECK(compare_traces(trace_expected(expand_job(p.job), m), trace_program(read_program(wrong, m, "t.nc"), m),
                         compare_tolerance(m, 0.0)));
    // No spring pass: the last cutting pass finishes, the roughing ends at the one before (R d).
    // (M24, firstDepth 0.3: its rounded d ends the roughing there; M20x2.5 at 0.4 it does not, as
    // its height rounds up 0.0004 and its last step's d then up 0.001: longhand, 0.0012 mm off)
    const auto q = fanuc_g76_post(fanuc_g76_job(R"("thread": "M24", "startZ": 0, "endZ": -20, "firstDepth": 0.3,
        "springPasses": 0, "infeedAngle": 0, "approachDistance": 6)"),
                                  m);
    const std::vector<std::string> g = g76_lines(q.text);
    REQUIRE_MESSAGE(g.size() == 2, q.text);
    const auto& qop = std::get<TurnThreadOp>(q.job.operations.front());
    // (R: the last step, rounded to the increment that ends the roughing at the pass before it)
    REQUIRE(g[0].rfind("G76 P010000 Q0 R", 0) == 0);
    CHECK(std::abs(std::stod(g[0].substr(16)) - (qop.depths.back() - qop.depths[qop.depths.size() - 2])) <= 0.001 + 1e-9);
    CHECK_FALSE(compare_traces(trace_expected(expand_job(q.job), m), trace_program(read_program(q.text, m, "t.nc"), m),
                               compare_tolerance(m, 0.0)));
}

TEST_CASE("fanuc G76 on fanuc-lathe: an infeed angle off the control's tool angles is written longhand, canned refused") {
    const Machine m = load_machine("fanuc-lathe");
    const std::string op = R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "infeedAngle": 29.5)";
    const auto p = fanuc_g76_post(fanuc_g76_job(op), m);
    CHECK(p.text.find("G76") == std::string::npos);
    CHECK(p.text.find("G32 Z") != std::string::npos);
    CHECK_MESSAGE(p.notes.find("the thread is written longhand because machine fanuc-lathe's G76 cannot carry this thread: its "
                               "tool angle a (twice the infeedAngle, 59 degrees) is not one of 80, 60, 55, 30, 29, 0") !=
                      std::string::npos,
                  p.notes);
    // The longhand passes move as the cycle would: back to the start point after each pass.
    CHECK_FALSE(compare_traces(trace_expected(expand_job(p.job), m), trace_program(read_program(p.text, m, "t.nc"), m),
                               compare_tolerance(m, 0.0)));
    try {
        (void)fanuc_g76_post(fanuc_g76_job(op + R"(, "output": "canned")"), m);
        FAIL("a canned thread Fanuc's G76 cannot carry was not refused");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("/operations/0/output: machine fanuc-lathe's G76 cannot carry this thread: its tool "
                                         "angle a") != std::string::npos);
    }
}

TEST_CASE("fanuc G76 round trip: post, read back, the job's passes within the machine's resolution, many threads") {
    const Machine m = load_machine("fanuc-lathe");
    std::mt19937 rng(30);
    const char* const metric[] = {"M6", "M8", "M10", "M12", "M16", "M20", "M24", "M30x2", "M20x1.5", "M12x1.25", "M36x3"};
    const char* const unified[] = {"1/4-20 UNC", "3/8-16 UNC", "1/2-13 UNC", "3/4-10 UNC", "3/8-24 UNF", "1/2-20 UNF", "1-8 UNC"};
    const double angles[] = {0, 14.5, 15, 27.5, 30, 29.5, 10};
    int canned = 0, longhand = 0, inch_canned = 0, internal_canned = 0, spring0_canned = 0, depth_canned = 0;
    for (int n = 0; n < 160; ++n) {
        const bool is_unified = rng() % 3 == 0;
        const std::string thread = is_unified ? unified[rng() % std::size(unified)] : metric[rng() % std::size(metric)];
        const bool internal = rng() % 3 == 0;
        const bool inch = rng() % 4 == 0;
        const int springs = static_cast<int>(rng() % 4);
        const double angle = angles[rng() % std::size(angles)];
        const bool equal = rng() % 4 == 0;
        const double s = inch ? 1 / 25.4 : 1.0;
        const double first = (0.12 + 0.05 * (rng() % 6)) * s;
        const double least = rng() % 3 == 0 ? (0.05 + 0.01 * (rng() % 5)) * s : 0.0;
        const double length = (8 + rng() % 12) * s;
        std::string op = fmt::format(R"("thread": "{}", "side": "{}", "startZ": 0, "endZ": {}, "firstDepth": {},
            "springPasses": {}, "infeedAngle": {}, "infeed": "{}", "minDepth": {}, "approachDistance": {})",
                                     thread, internal ? "internal" : "external", -length, first, springs, angle,
                                     equal ? "constant-depth" : "constant-area", least, 8 * s);
        std::string job_text = fanuc_g76_job(op, inch ? "inch" : "mm");
        FanucPosted p;
        try {
            p = fanuc_g76_post(job_text, m);
        } catch (const InputError& e) {
            // (a bore too small for the retract, a first depth beyond a fine thread's: not this test's)
            MESSAGE(std::string(e.what()));
            continue;
        }
        const std::vector<std::string> g = g76_lines(p.text);
        const bool is_canned = !g.empty();
        CAPTURE(job_text);
        CAPTURE(p.text);
        if (is_canned) {
            ++canned;
            inch_canned += inch;
            internal_canned += internal;
            spring0_canned += springs == 0;
            depth_canned += equal;
            CHECK(std::find(std::begin(iso::fanuc_g76_tool_angles), std::end(iso::fanuc_g76_tool_angles),
                            static_cast<int>(std::lround(2 * angle))) != std::end(iso::fanuc_g76_tool_angles));
            CHECK(p.text.find("G32") == std::string::npos);
        } else {
            ++longhand;
            CHECK(p.notes.find("written longhand because") != std::string::npos);
        }
        // Canned or longhand, the program makes the job's moves (Fanuc's pattern on fanuc-lathe).
        const auto read = read_program(p.text, m, "t.nc");
        // (within 0.001 mm, as the post holds the cycle's passes to camgen's, and the words' rounding)
        const auto mismatch = compare_traces(trace_expected(expand_job(p.job), m), trace_program(read, m), compare_tolerance(m));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : std::string()));
        // The passes: as many as the job's, the last at the thread's root.
        const auto& top = std::get<TurnThreadOp>(p.job.operations.front());
        std::vector<double> xs;
        for (const ReadEvent& e : read)
            if (const auto* f = std::get_if<ThreadFeed>(&e.event)) xs.push_back(f->to.x);
        REQUIRE(xs.size() == top.depths.size());
        CHECK(std::abs(xs.back() - top.root_radius()) <= 0.001 + 1e-9);
        for (std::size_t k = 0; k < xs.size(); ++k)
            CHECK(std::abs(std::abs(xs[k] - top.surface_radius()) - top.depths[k]) <= 0.001 + 1e-9);
    }
    MESSAGE(fmt::format("canned {}, longhand {}: inch {}, internal {}, without a spring pass {}, constant depth {}", canned,
                        longhand, inch_canned, internal_canned, spring0_canned, depth_canned));
    CHECK(canned >= 40);
    CHECK(longhand >= 20);
    CHECK(internal_canned >= 5);
    CHECK(spring0_canned >= 3);
}

TEST_CASE("fanuc G76: the fanuc-lathe reader refuses a G76 it cannot read, naming the word") {
    const Machine m = load_machine("fanuc-lathe");
    auto refusal_of = [&](const std::string& g76) {
        const std::string program = "%\nO1000\nG18 G40 G80 G98\nT0505\nG97 S500 M3\nG0 X22. Z6.\n" + g76 + "\nG0 Z20.\nM5\nM30\n%\n";
        try {
            (void)read_program(program, m, "t.nc");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refusal_of("G76 P010060 Q50 R0.\nG76 X16.933 Z-20. P1534 Q400 F2.5") == "");
    CHECK(refusal_of("G76 X16.933 Z-20. P1534 Q400 F2.5").find("without its first block") != std::string::npos);
    CHECK(refusal_of("G76 P010560 Q50 R0.\nG76 X16.933 Z-20. P1534 Q400 F2.5").find("straight runout") != std::string::npos);
    CHECK(refusal_of("G76 P010059 Q50 R0.\nG76 X16.933 Z-20. P1534 Q400 F2.5").find("tool angle a 59") != std::string::npos);
    CHECK(refusal_of("G76 P010060 Q50 R0.\nG76 X16.933 Z-20. P1.534 Q400 F2.5").find("P1.534 on G76: in least input") !=
          std::string::npos);
    CHECK(refusal_of("G76 P010060 Q50 R0.\nG76 X16.933 Z-20. R-1. P1534 Q400 F2.5").find("no taper") != std::string::npos);
    CHECK(refusal_of("G76 P010060 Q50 R0.\nG76 X16.933 Z-20. P1534 F2.5").find("the second G76 block needs") !=
          std::string::npos);
    CHECK(refusal_of("G76 P010060 Q50 R0.\nG76 X16.933 Z10. P1534 Q400 F2.5").find("towards the chuck") != std::string::npos);
}

}  // namespace test_fanuc_g76
