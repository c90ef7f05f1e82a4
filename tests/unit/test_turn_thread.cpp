// turn-thread (issue 30): the passes' depths by the infeed rule, worked out here on their own;
// each pass as rapids in air and one synchronised move along Z; the programs of the three lathes
// (LinuxCNC G33 Z K, Fanuc G32 Z F, Sinumerik G33 Z K) read back to the job's moves; refusals
// with their JSON paths.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/vocabulary/threads.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_thread {

using namespace camgen;

namespace {

std::string refusal(const std::string& text) {
    try {
        (void)read_job(text, "thread.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const char* const thread_tool =
    R"({"number": 5, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 500})";

// The thread alone, without a stock (a thread is cut on a diameter turned to its major, which a
// bar nothing turned is not: check_blade_material), or on `stock`.
std::string job(const std::string& op, const std::string& tool = thread_tool, const std::string& stock = "") {
    return R"({"clearance": 20, )" + stock + R"("tools": [)" + tool + R"(], "operations": [{"type": "turn-thread", "tool": 5, )" + op +
           "}]}";
}
// A D20 bar 70 long, its face at Z0: an M20 is cut on it as it is.
const std::string d20_bar = R"("stock": {"bar": {"diameter": 20, "length": 70, "faceZ": 0}}, )";

}  // namespace

TEST_CASE("turn-thread: the depths follow the infeed rule, the last is the thread's depth") {
    // Constant area: first x sqrt(n) below the total (0.613435 x 2.5 = 1.533588 for M20x2.5).
    const Job j = read_job(job(R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "springPasses": 1)"),
                           "t.json");
    const auto& op = std::get<TurnThreadOp>(j.operations.front());
    const double total = 0.613435 * 2.5;
    REQUIRE(op.depths.size() == 16);  // ceil((1.533588 / 0.4)^2) = 15 passes, then a spring pass
    for (std::size_t n = 1; n < 15; ++n) CHECK(op.depths[n - 1] == doctest::Approx(0.4 * std::sqrt(double(n))).epsilon(1e-9));
    CHECK(op.depths[14] == doctest::Approx(total).epsilon(1e-6));
    CHECK(op.depths[15] == doctest::Approx(total).epsilon(1e-6));
    // A least depth: each step at least 0.15 mm.
    const Job least_job =
        read_job(job(R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "minDepth": 0.15, "springPasses": 0)"),
                 "t.json");
    const auto& least = std::get<TurnThreadOp>(least_job.operations.front());
    // (the last step takes what is left to the full depth, which may be less)
    for (std::size_t n = 1; n + 1 < least.depths.size(); ++n) CHECK(least.depths[n] - least.depths[n - 1] >= 0.15 - 1e-9);
    CHECK(least.depths.back() == doctest::Approx(total).epsilon(1e-6));
    CHECK(least.depths.size() < 15);
    // Constant depth: equal steps of at most firstDepth.
    const Job equal_job =
        read_job(job(R"("thread": "M12", "side": "internal", "startZ": 0, "endZ": -10, "infeed": "constant-depth", "firstDepth": 0.2, "springPasses": 0)"),
                 "t.json");
    const auto& equal = std::get<TurnThreadOp>(equal_job.operations.front());
    const double internal_total = (12 - internal_minor_diameter(12, 1.75)) / 2;  // 5/8 H
    CHECK(internal_total == doctest::Approx(0.541266 * 1.75).epsilon(1e-6));
    const int n = static_cast<int>(std::ceil(internal_total / 0.2));
    REQUIRE(equal.depths.size() == static_cast<std::size_t>(n));
    for (int k = 1; k <= n; ++k) CHECK(equal.depths[k - 1] == doctest::Approx(internal_total * k / n));
}

TEST_CASE("turn-thread: each pass rapids in air, cuts one synchronised move along Z, rapids out and back") {
    std::mt19937 rng(30);
    for (int n = 0; n < 40; ++n) {
        const bool internal = n % 2 == 1;
        const char* sizes[] = {"M8", "M10", "M16x1.5", "M20x2.5", "M24", "1/2-13 UNC", "3/4-16 UNF"};
        const std::string size = sizes[rng() % 7];
        const int starts = n % 4 == 3 ? 3 : 1;
        const double angle = n % 3 == 0 ? 0.0 : 29.5;
        const Job j = read_job(job(fmt::format(R"("thread": "{}", "side": "{}", "startZ": -2, "endZ": -15, "starts": {},
                                                "firstDepth": 0.25, "infeedAngle": {}, "approachDistance": 4,
                                                "output": "longhand")",
                                               size, internal ? "internal" : "external", starts, angle)),
                               "t.json");
        const auto& op = std::get<TurnThreadOp>(j.operations.front());
        INFO(size << (internal ? " internal" : " external"));
        const double surface = op.surface_radius(), out = internal ? -1.0 : 1.0;
        Vec3 at{0, 0, 20};
        bool known = false;
        int threads = 0;
        for (const Event& e : expand_job(j)) {
            if (const auto* r = std::get_if<Rapid>(&e)) {
                if (known) {
                    // Along Z only outside the thread (inside the bore); in X only beyond startZ
                    // or out at endZ.
                    if (std::abs(r->to.z - at.z) > 1e-9) CHECK(out * (r->to.x - surface) > 0);
                    if (std::abs(r->to.x - at.x) > 1e-9 && out * (r->to.x - at.x) < 0) CHECK(r->to.z > op.start_z);
                }
                at = r->to;
                known = true;
            } else if (const auto* t = std::get_if<ThreadFeed>(&e)) {
                REQUIRE(known);
                ++threads;
                CHECK(t->lead == doctest::Approx(op.pitch * starts));
                CHECK(t->to.x == at.x);
                CHECK(t->to.z == op.end_z);
                CHECK(at.z > op.start_z);  // every pass starts beyond the thread
                // The flank infeed: the start moves by -depth x tan(angle) (and one pitch a start).
                const double depth = out * (surface - t->to.x);
                const int start = (threads - 1) / static_cast<int>(op.depths.size());
                CHECK(at.z == doctest::Approx(op.start_z + op.approach + start * op.pitch -
                                              depth * std::tan(angle * std::numbers::pi / 180)));
                at = t->to;
            } else {
                CHECK(!std::holds_alternative<Linear>(e));
                CHECK(!std::holds_alternative<Arc>(e));
            }
        }
        CHECK(threads == static_cast<int>(op.depths.size()) * starts);
        CHECK(at.z == 20.0);
    }
}

TEST_CASE("turn-thread: the three lathes write the shaft's thread (its minDepth: longhand) and read it back as the job's moves") {
    std::ifstream f(CAMGEN_SOURCE_DIR "/samples/shaft.json");
    std::stringstream text;
    text << f.rdbuf();
    const Job j = read_job(text.str(), "shaft.json");
    for (const char* name : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        INFO(name);
        const Machine machine = load_machine(name);
        const std::string program = test::post_program(j, machine);
        const bool fanuc = std::string(name) == "fanuc-lathe", lcnc = std::string(name) == "linuxcnc-lathe";
        // (the passes of the cycle: the last two reach endZ)
        const std::string word = fanuc ? "G32 Z-11.000 F2.0000" : lcnc ? "G33 Z-11 K2\n" : "G33 Z-11.000 K2\n";
        const std::string broken = fanuc ? "G32 Z-11.000 F2.5000" : lcnc ? "G33 Z-11 K2.5\n" : "G33 Z-11.000 K2.5\n";
        CHECK_MESSAGE(program.find(word) != std::string::npos, program);
        const Trace read = trace_program(read_program(program, machine, "t.nc"), machine);
        const auto mismatch = compare_traces(trace_expected(expand_job(j), machine), read, compare_tolerance(machine, 0.0));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        // Broken: another lead in one pass is a mismatch.
        std::string wrong = program;
        if (const std::size_t at = wrong.find(word); at != std::string::npos) wrong.replace(at, word.size(), broken);
        REQUIRE(wrong != program);
        {
            const Trace bad = trace_program(read_program(wrong, machine, "t.nc"), machine);
            CHECK(compare_traces(trace_expected(expand_job(j), machine), bad, compare_tolerance(machine, 0.0)));
        }
    }
}

TEST_CASE("turn-thread output: G76 on linuxcnc-lathe where it carries the thread, else longhand with a note, or refused") {
    const Machine lcnc = load_machine("linuxcnc-lathe");
    // The program and the notes.
    auto posted = [&](const std::string& op, const Machine& m) { return test::post_noted(job(op), m, "t.json"); };
    // The G76 block of a program.
    auto g76_line = [](const std::string& text) {
        const std::size_t at = text.find("G76 ");
        return at == std::string::npos ? std::string() : text.substr(at, text.find('\n', at) - at);
    };
    // The words: P the lead, Z the end, I the crest from the drive line (a diameter under G7,
    // negative outside), J the first depth and K the thread's depth (diameters), R2 constant
    // area, Q the flank angle, H the spring passes.
    {
        const auto p = posted(R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "springPasses": 2,
                                 "infeedAngle": 29.5, "approachDistance": 6, "retract": 1)",
                              lcnc);
        // (K: 2 x 0.613435 x 2.5 = 3.0672 as a diameter)
        CHECK_MESSAGE(p.text.find("\nZ6\nG76 P2.5 Z-20 I-2 J0.8 K3.067") != std::string::npos, p.text);
        CHECK(p.text.find(" R2 Q29.5 H2\n") != std::string::npos);
        CHECK(p.text.find("G33") == std::string::npos);
        // Read back: the passes the control makes, as the job's.
        const Job j = read_job(job(R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "springPasses": 2,
                                      "infeedAngle": 29.5, "approachDistance": 6, "retract": 1)"),
                               "t.json");
        const Trace read = trace_program(read_program(p.text, lcnc, "t.nc"), lcnc);
        CHECK_FALSE(compare_traces(trace_expected(expand_job(j), lcnc), read, compare_tolerance(lcnc, 0.0)));
        int feeds = 0;
        for (const ReadEvent& e : read_program(p.text, lcnc, "t.nc"))
            if (std::holds_alternative<ThreadFeed>(e.event)) ++feeds;
        CHECK(feeds == static_cast<int>(std::get<TurnThreadOp>(j.operations.front()).depths.size()));
        // A J off by one increment is another thread: the comparison finds it.
        std::string wrong = p.text;
        wrong.replace(wrong.find(" J0.8 "), 6, " J0.6 ");
        CHECK(compare_traces(trace_expected(expand_job(j), lcnc), trace_program(read_program(wrong, lcnc, "t.nc"), lcnc),
                             compare_tolerance(lcnc, 0.0)));
    }
    // Constant depth: R1 with J the equal step; internal: I positive.
    {
        const auto p = posted(R"("thread": "M24", "side": "internal", "startZ": 0, "endZ": -15, "infeed": "constant-depth",
                                 "firstDepth": 0.2, "springPasses": 0, "infeedAngle": 0)",
                              lcnc);
        CHECK_MESSAGE(p.text.find(" R1\n") != std::string::npos, p.text);
        CHECK(p.text.find("G76 P3 Z-15 I2 ") != std::string::npos);
        CHECK(g76_line(p.text).find(" Q") == std::string::npos);
        CHECK(g76_line(p.text).find(" H") == std::string::npos);
    }
    // A least depth that changes the passes: G76 has none, so longhand, with a note.
    {
        const std::string op = R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "minDepth": 0.15)";
        const auto p = posted(op, lcnc);
        CHECK(p.text.find("G76") == std::string::npos);
        CHECK(p.text.find("G33 Z-20 K2.5") != std::string::npos);
        CHECK_MESSAGE(p.notes.find("/operations/0 (turn thread M20x2.5): the thread is written longhand because "
                                      "machine linuxcnc-lathe's G76 cannot carry minDepth") != std::string::npos,
                      p.notes);
        try {
            (void)posted(op + R"(, "output": "canned")", lcnc);
            FAIL("a canned thread G76 cannot carry was not refused");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find("/operations/0/output: machine linuxcnc-lathe's G76 cannot carry minDepth; "
                                             "use \"auto\" or \"longhand\"") != std::string::npos);
        }
        // A least depth no step is below: not used, G76.
        CHECK(posted(R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "minDepth": 0.01)", lcnc)
                  .text.find("G76") != std::string::npos);
    }
    // output longhand: G33 passes to endZ; sinumerik-lathe (no threading cycle yet): longhand, no
    // note, and canned refused (fanuc-lathe's G76: test_fanuc_g76.cpp).
    {
        const std::string op = R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4)";
        CHECK(posted(op + R"(, "output": "longhand")", lcnc).text.find("G76") == std::string::npos);
        const auto sinumerik = posted(op, load_machine("sinumerik-lathe"));
        CHECK(sinumerik.text.find("G33") != std::string::npos);
        CHECK(sinumerik.notes.find("longhand") == std::string::npos);
        try {
            (void)posted(op + R"(, "output": "canned")", load_machine("sinumerik-lathe"));
            FAIL("a canned thread on a machine without a threading cycle was not refused");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find("/operations/0/output: machine sinumerik-lathe has no canned threading cycle") !=
                  std::string::npos);
        }
    }
    // The cycle's moves and the longhand passes cut the same thread: the same depths and starts,
    // the passes of the cycle end short of endZ by (depth - d) tan(angle), the last at endZ.
    {
        const Job j = read_job(job(R"("thread": "M16", "startZ": 0, "endZ": -12, "firstDepth": 0.3, "infeedAngle": 29.5)"),
                               "t.json");
        const auto& op = std::get<TurnThreadOp>(j.operations.front());
        const ThreadCycle c = thread_cycle(op, 0);
        const double total = c.depth, t = std::tan(29.5 * std::numbers::pi / 180);
        std::size_t pass = 0;
        Vec3 at = c.start;
        for (const Event& e : thread_cycle_moves(c)) {
            if (const auto* r = std::get_if<Rapid>(&e)) {
                at = r->to;
                continue;
            }
            const auto& f = std::get<ThreadFeed>(e);
            const double d = op.depths[pass++];
            CHECK(f.to.x == doctest::Approx(op.surface_radius() - d));
            CHECK(at.z == doctest::Approx(op.start_z + op.approach - d * t));
            CHECK(f.to.z == doctest::Approx(op.end_z + (total - d) * t));
            at = f.to;
        }
        CHECK(pass == op.depths.size());
        CHECK(at.z == doctest::Approx(op.end_z));
    }
}

TEST_CASE("turn-thread: the linuxcnc-lathe reader refuses a G76 it cannot read, naming the word") {
    const Machine lcnc = load_machine("linuxcnc-lathe");
    auto refusal_of = [&](const std::string& g76) {
        const std::string program = "G18 G7 G90 G21\nT5 M6\nS500 M3\nG0 X22 Z6\n" + g76 + "\nG0 Z20\nM5\nM2\n";
        try {
            (void)read_program(program, lcnc, "t.ngc");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refusal_of("G76 P2.5 Z-20 I-2 J0.8 K3.0672 R2 Q29.5 H1").empty());
    CHECK(refusal_of("G76 P2.5 Z-20 I-2 J0.8 K3.0672 R2 Q29.5 H1.5").find("H1.5 on G76: the spring passes are a whole number") !=
          std::string::npos);
    // (an exit taper steeper than 45 degrees: test_thread_runout.cpp)
    CHECK(refusal_of("G76 P2.5 Z-20 I-2 J0.8 K3.0672 E1 L2").find("E1") != std::string::npos);
    CHECK(refusal_of("G76 P2.5 Z10 I-2 J0.8 K3.0672").find("towards the chuck") != std::string::npos);
    CHECK(refusal_of("G76 P2.5 Z-20 I-2 K3.0672").find("G76 needs P, Z, I, J and K") != std::string::npos);
    // A machine without the cycle does not know G76; fanuc-lathe's is another cycle.
    CHECK_THROWS_AS((void)read_program("G18 G90 G21\nT5 M6\nS500 M3\nG0 X22 Z6\nG76 P2.5 Z-20 I-2 J0.8 K3.0672\nM2\n",
                                       load_machine("sinumerik-lathe"), "t.nc"),
                    InputError);
    CHECK_THROWS_AS((void)read_program("G18 G90 G21\nT5 M6\nS500 M3\nG0 X22 Z6\nG76 P2.5 Z-20 I-2 J0.8 K3.0672\nM2\n",
                                       load_machine("fanuc-lathe"), "t.nc"),
                    InputError);
}

TEST_CASE("turn-thread: machine files' threadingCycles are checked with their paths") {
    std::ifstream f(CAMGEN_SOURCE_DIR "/machines/linuxcnc-lathe.json");
    std::stringstream buf;
    buf << f.rdbuf();
    const std::string file = buf.str();
    const std::string cycle = R"({"name": "G76", "kind": "thread", "style": "linuxcnc-g76",
     "fields": ["constant-depth", "constant-area", "infeedAngle", "springPasses", "runout"]})";
    REQUIRE(file.find(cycle) != std::string::npos);
    CHECK_NOTHROW((void)parse_machine(file, "m", "m.json"));
    auto refused = [&](const std::string& with) {
        std::string text = file;
        text.replace(text.find(cycle), cycle.size(), with);
        try {
            (void)parse_machine(text, "m", "m.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refused(R"({"name": "G76", "kind": "thread", "style": "linuxcnc-g76", "fields": ["minDepht"]})")
              .find("/threadingCycles/0/fields/0") != std::string::npos);
    CHECK(refused(R"({"name": "G76", "kind": "thread", "style": "haas-g76"})").find("/threadingCycles/0/style") !=
          std::string::npos);
    CHECK(refused(R"({"name": "G76", "style": "linuxcnc-g76"})").find("/threadingCycles/0") != std::string::npos);
}

TEST_CASE("turn-thread: refusals name their key") {
    CHECK(refusal(job(R"("thread": "M21", "startZ": 0, "endZ": -10, "firstDepth": 0.2)")).find("/operations/0/thread:") !=
          std::string::npos);
    CHECK(refusal(job(R"("thread": "M20x1.25", "startZ": 0, "endZ": -10, "firstDepth": 0.2)")).find("/operations/0/thread:") !=
          std::string::npos);
    CHECK(refusal(job(R"("majorDiameter": 20, "minorDiameter": 18, "pitch": 0, "startZ": 0, "endZ": -10, "firstDepth": 0.2)"))
              .find("/operations/0/pitch") != std::string::npos);
    CHECK(refusal(job(R"("majorDiameter": 20, "minorDiameter": 18, "pitch": -1, "startZ": 0, "endZ": -10, "firstDepth": 0.2)"))
              .find("/operations/0/pitch") != std::string::npos);
    CHECK(refusal(job(R"("thread": "M20", "startZ": 0, "endZ": -80, "firstDepth": 0.2)", thread_tool, d20_bar))
              .find("/operations/0/endZ: the thread ends at Z -80.000 mm, beyond the bar's far end (Z -70.000 mm)") != std::string::npos);
    CHECK(refusal(job(R"("thread": "M20", "startZ": 0, "endZ": -10, "firstDepth": 0.2)",
                      R"({"number": 5, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 55, "rpm": 500})"))
              .find("/operations/0/tool: tool 5 has a profileAngle of 55 degrees; M20x2.5 has the 60-degree profile") !=
          std::string::npos);
    CHECK(refusal(job(R"("thread": "M20", "startZ": 0, "endZ": -10, "firstDepth": 0.2)",
                      R"({"number": 5, "type": "turning-tool", "noseRadius": 0.4, "rpm": 500})"))
              .find("/operations/0/tool: a turn-thread needs a threading-tool") != std::string::npos);
    CHECK(refusal(job(R"("thread": "M20", "hand": "left", "startZ": 0, "endZ": -10, "firstDepth": 0.2)"))
              .find("/operations/0/hand: a left-hand thread is cut towards the chuck with the spindle turning ccw") !=
          std::string::npos);
    // (a chamfered runout is cut: test_thread_runout.cpp)
    CHECK(refusal(job(R"("thread": "M20", "runout": "chamfered", "startZ": 0, "endZ": -10, "firstDepth": 0.2)")).empty());
    CHECK(refusal(job(R"("thread": "M20", "startZ": 0, "endZ": 5, "firstDepth": 0.2)")).find("/operations/0/endZ") !=
          std::string::npos);
    CHECK(refusal(job(R"("thread": "M20", "startZ": 0, "endZ": -10, "firstDepth": 3)")).find("/operations/0/firstDepth") !=
          std::string::npos);
    CHECK(refusal(job(R"("thread": "M48", "startZ": 0, "endZ": -10, "firstDepth": 0.5)", thread_tool,
                      R"("stock": {"bar": {"diameter": 44, "length": 70, "faceZ": 0}}, )"))
              .find("/operations/0/thread: M48x5 has a major diameter of 48") !=
          std::string::npos);
    CHECK(refusal(job(R"("thread": "M48", "startZ": 0, "endZ": -10, "firstDepth": 0.05)")).find("/operations/0/firstDepth: firstDepth 0.050 mm makes more than 200 passes") !=
          std::string::npos);
    // A thread on a mill: the operation is for lathes.
    const Job j = read_job(job(R"("thread": "M20", "startZ": 0, "endZ": -10, "firstDepth": 0.2)"), "t.json");
    const Job no_bar = read_job(R"({"clearance": 20, "tools": [)" + std::string(thread_tool) +
                                    R"(], "operations": [{"type": "turn-thread", "tool": 5, "thread": "M20", "startZ": 0, "endZ": -10, "firstDepth": 0.2}]})",
                                "t.json");
    try {
        check_machine_kind(no_bar, MachineKind::mill, "linuxcnc");
        FAIL("a turn-thread on a mill was not refused");
    } catch (const InputError& e) {
        CHECK(e.path() == "/operations/0/type");
        CHECK(e.detail().find("is made for a lathe, and machine linuxcnc is a mill") != std::string::npos);
    }
    // A machine that cuts no threads: the post refuses, naming the operation.
    const Machine mill_lathe = load_machine("linuxcnc-lathe");
    CHECK_NOTHROW((void)test::post_program(j, mill_lathe));
}

TEST_CASE("turn-thread: the tool's tip must point at the thread's root (-X outside, +X inside), or have no orientation") {
    auto tool = [](int orientation) {
        return fmt::format(R"({{"number": 5, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 500, "orientation": {}}})",
                           orientation);
    };
    const std::string outside = R"("thread": "M20", "startZ": 0, "endZ": -10, "firstDepth": 0.2)";
    const std::string inside = R"("thread": "M20", "side": "internal", "startZ": 0, "endZ": -10, "firstDepth": 0.2)";
    for (int o = 1; o <= 9; ++o) {
        CAPTURE(o);
        const bool in = o == 3 || o == 4 || o == 8, out = o == 1 || o == 2 || o == 6;
        CHECK(refusal(job(outside, tool(o))).empty() == out);
        CHECK(refusal(job(inside, tool(o))).empty() == in);
    }
    CHECK(refusal(job(inside, tool(6))).find("/operations/0/tool: an internal thread needs a threading-tool whose tip points to "
                                             "+X, at the bore's wall (orientation 3, 4 or 8); tool 5 has orientation 6") !=
          std::string::npos);
    CHECK(refusal(job(outside, tool(8))).find("/operations/0/tool: an external thread needs a threading-tool whose tip points "
                                              "to -X, at the axis (orientation 1, 2 or 6); tool 5 has orientation 8") !=
          std::string::npos);
    CHECK(refusal(job(inside)).empty());
    CHECK(refusal(job(outside)).empty());
}

}  // namespace test_turn_thread
