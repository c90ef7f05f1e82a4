// turn-rough's output (issue 30 item 2): a TurnCycle (LinuxCNC's G71 with the boundary as its
// profile subroutine, G72 along X) where the control's cycle makes the roughing, longhand otherwise; the
// linuxcnc-lathe program and its reading back; the notes and refusals with their JSON paths.
#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/turn_rough/turn_rough.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_rough_cycle {

using namespace camgen;

namespace {

// A bar of diameter 40 faced at Z0.5 to Z0, turned to a shaft with a face, a chamfer, a taper and
// an arc (a face first: with the nose made up for, a chamfer first would start the tip's path
// below the boundary's start, inside the faced bar, and the cycle would not be used).
std::string rc_job(const std::string& op_extra, const std::string& path = "") {
    const std::string p = path.empty() ? R"([{"line": [18, 0]}, {"line": [20, -1]}, {"line": [20, -15]}, {"line": [26, -20]},
        {"arc": {"end": [32, -23], "centre": [26, -23], "direction": "ccw"}}, {"line": [32, -35]}])"
                                       : path;
    return fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0.5}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.5}},
                 {{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": 1.5, "allowanceX": 0.4, "allowanceZ": 0.1,
                   "start": [16, 0], "path": {}{}}}]}})",
                       p, op_extra);
}

test::Posted rc_posted(const std::string& text, const Machine& m) { return test::post_noted(text, m, "rc.json"); }

std::string rc_refusal(const std::string& text, const Machine& m) {
    try {
        (void)rc_posted(text, m);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("turn-rough output: G71 with its profile subroutine on linuxcnc-lathe, read back as the job's moves") {
    const Machine lcnc = load_machine("linuxcnc-lathe");
    for (const char* nose : {"", R"(, "compensation": "none")"}) {
        CAPTURE(nose);
        const std::string text = rc_job(nose);
        const Job j = read_job(text, "rc.json");
        const auto& op = std::get<TurnRoughOp>(j.operations.at(1));
        CHECK(op.bar_face == 0.0);
        const TurnCycle c = turn_cycle(op);
        REQUIRE_FALSE(c.refusal);
        // The start beyond the part, at most a pass below the bar; I at most depthOfCut.
        CHECK(c.start.z > op.tip_boundary.start.x);
        CHECK(c.start.x <= 20.0);
        CHECK(c.start.x >= 20.0 - 1.5);
        CHECK(c.depth <= 1.5);
        CHECK(c.retract <= c.depth / 2 + 1e-9);
        const auto p = rc_posted(text, lcnc);
        CHECK_MESSAGE(p.text.find("o100 sub\nG1 X") != std::string::npos, p.text);
        CHECK(p.text.find("o100 endsub\nG71 Q100 D0 I") != std::string::npos);
        CHECK(p.notes.find("longhand") == std::string::npos);
        // Read back: the control's moves are the job's (verify --job, within its 0.001 mm: the
        // control's moves are those of the rounded subroutine).
        const Trace read = trace_program(read_program(p.text, lcnc, "t.ngc"), lcnc);
        const auto mismatch = compare_traces(trace_expected(expand_job(j), lcnc), read, compare_tolerance(lcnc));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        // Another depth of cut in the G71 block is another roughing: found.
        std::string wrong = p.text;
        const std::size_t at = wrong.find("D0 I");
        REQUIRE(at != std::string::npos);
        const std::size_t end = wrong.find(' ', at + 3);
        wrong.replace(at + 3, end - (at + 3), "I0.4");
        CHECK(compare_traces(trace_expected(expand_job(j), lcnc), trace_program(read_program(wrong, lcnc, "t.ngc"), lcnc),
                             compare_tolerance(lcnc)));
        // sinumerik-lathe has no roughing cycle: the control's moves longhand, read back as the
        // job's, no note; fanuc-lathe writes its own G71 (test_fanuc_g71), read back as the job's.
        for (const char* name : {"fanuc-lathe", "sinumerik-lathe"}) {
            CAPTURE(name);
            const Machine m = load_machine(name);
            const auto q = rc_posted(text, m);
            CHECK(q.text.find("G71 Q") == std::string::npos);
            CHECK((q.text.find("G71 U") != std::string::npos) == (std::string(name) == "fanuc-lathe"));
            CHECK(q.notes.find("longhand") == std::string::npos);
            const auto miss = compare_traces(trace_expected(expand_job(j), m),
                                             trace_program(read_program(q.text, m, "t.nc"), m), compare_tolerance(m));
            CHECK_MESSAGE(!miss, (miss ? miss->message : ""));
        }
    }
}

TEST_CASE("turn-rough output along X: G72 with its profile subroutine on linuxcnc-lathe, read back as the job's moves") {
    const Machine lcnc = load_machine("linuxcnc-lathe");
    for (const char* nose : {R"(, "direction": "x")", R"(, "direction": "x", "compensation": "none")"}) {
        CAPTURE(nose);
        const std::string text = rc_job(nose);
        const Job j = read_job(text, "rc.json");
        const auto& op = std::get<TurnRoughOp>(j.operations.at(1));
        const TurnCycle c = turn_cycle(op);
        REQUIRE_FALSE(c.refusal);
        CHECK(c.along_x);
        // A machine of Fanuc's roughing pattern takes Fanuc's G72 along X (test_fanuc_g72): the
        // same levels, each pass back along X to A (one depth of cut beyond the start in Z), the
        // tool ending at A.
        const std::vector<LatheCycleMove> fanuc_path = turn_cycle_path(c, RoughCyclePattern::fanuc_g71);
        CHECK(fanuc_path != c.moves);
        CHECK(fanuc_path.back().end == Vec2{c.start.z + c.depth, c.start.x});
        // The start outside the bar, its Z (the first level) at most a pass below the faced Z0;
        // the sub from the top of the end face (at the bar) back to the boundary's start.
        CHECK(c.start.x == doctest::Approx(20.0 + 1.0));
        CHECK(c.start.z <= 0.0);
        CHECK(c.start.z >= -1.5);
        CHECK(c.depth <= 1.5);
        CHECK(c.profile.start.y == doctest::Approx(20.0));
        CHECK(c.profile.segments.back().end == op.tip_boundary.start);
        const auto p = rc_posted(text, lcnc);
        CHECK_MESSAGE(p.text.find("o100 sub\nG1 X40 Z") != std::string::npos, p.text);
        CHECK(p.text.find("o100 endsub\nG72 Q100 D0 I") != std::string::npos);
        CHECK(p.text.find("G71") == std::string::npos);
        CHECK(p.notes.find("longhand") == std::string::npos);
        const Trace read = trace_program(read_program(p.text, lcnc, "t.ngc"), lcnc);
        const auto mismatch = compare_traces(trace_expected(expand_job(j), lcnc), read, compare_tolerance(lcnc));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        // Another depth of cut in the G72 block is another roughing: found.
        std::string wrong = p.text;
        const std::size_t at = wrong.find("D0 I");
        REQUIRE(at != std::string::npos);
        const std::size_t end = wrong.find(' ', at + 3);
        wrong.replace(at + 3, end - (at + 3), "I0.4");
        CHECK(compare_traces(trace_expected(expand_job(j), lcnc), trace_program(read_program(wrong, lcnc, "t.ngc"), lcnc),
                             compare_tolerance(lcnc)));
        // longhand: camgen's passes along X, no cycle.
        const auto l = rc_posted(rc_job(std::string(nose) + R"(, "output": "longhand")"), lcnc);
        CHECK(l.text.find("G72") == std::string::npos);
        // fanuc-lathe writes its own G72 (test_fanuc_g72), read back as the job's, no note.
        const Machine fanuc = load_machine("fanuc-lathe");
        const auto q = rc_posted(text, fanuc);
        CHECK(q.text.find("G72 W") != std::string::npos);
        CHECK(q.notes.find("longhand") == std::string::npos);
        const auto miss = compare_traces(trace_expected(expand_job(j), fanuc), trace_program(read_program(q.text, fanuc, "t.nc"), fanuc),
                                         compare_tolerance(fanuc));
        CHECK_MESSAGE(!miss, (miss ? miss->message : ""));
    }
}

TEST_CASE("turn-rough output along X: no level of G72 within 0.005 mm of the Z of a corner of its sub") {
    for (double doc : {1.0, 2.0, 0.5, 2.5}) {
        CAPTURE(doc);
        const std::string text = fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": {}, "compensation": "none", "direction": "x",
                   "start": [10, 0], "path": [{{"line": [20, -2]}}, {{"line": [20, -5]}}, {{"line": [30, -5]}}, {{"line": [30, -10]}}, {{"line": [36, -12]}}]}}]}})",
            doc);
        const Job j = read_job(text, "rc.json");
        const auto& op = std::get<TurnRoughOp>(j.operations.at(0));
        const TurnCycle c = turn_cycle(op);
        REQUIRE_FALSE(c.refusal);
        CHECK(c.depth <= doc);
        for (double level = c.start.z; level > -12 - 0.01; level -= c.depth)
            for (double corner : {0.0, -2.0, -5.0, -10.0, -12.0}) CHECK(std::abs(level - corner) >= 0.005 - 1e-9);
    }
}

TEST_CASE("turn-rough output: longhand where the cycle would not make the roughing (a note), refused under canned") {
    const Machine lcnc = load_machine("linuxcnc-lathe");
    const Machine fanuc = load_machine("fanuc-lathe");
    // An undercut: G71 (type I) does not rough a pocket.
    const std::string under = R"([{"line": [18, 0]}, {"line": [20, -1]}, {"line": [20, -10]}, {"line": [17, -13]}, {"line": [17, -18]},
        {"line": [26, -22]}, {"line": [26, -30]}])";
    {
        const auto p = rc_posted(rc_job(R"(, "compensation": "none")", under), lcnc);
        CHECK(p.text.find("G71") == std::string::npos);
        CHECK_MESSAGE(p.notes.find("/operations/1 (turn rough): the roughing is written longhand because machine "
                                      "linuxcnc-lathe's G71 would not cut these passes: element 3 falls in radius (a pocket)") !=
                          std::string::npos,
                      p.notes);
        CHECK(rc_refusal(rc_job(R"(, "compensation": "none", "output": "canned")", under), lcnc)
                  .find("/operations/1/output: machine linuxcnc-lathe's G71 would not cut these passes: element 3 falls in "
                        "radius (a pocket); use \"auto\" or \"longhand\"") != std::string::npos);
        // fanuc-lathe's G71 (type I) does not rough a pocket either: longhand with the note.
        CHECK(rc_posted(rc_job(R"(, "compensation": "none")", under), fanuc)
                  .notes.find("machine fanuc-lathe's G71 would not cut these passes") != std::string::npos);
    }
    const Machine sinumerik = load_machine("sinumerik-lathe");
    CHECK(rc_refusal(rc_job(R"(, "output": "canned")"), sinumerik)
              .find("/operations/1/output: machine sinumerik-lathe has no canned roughing cycle along Z (roughingCycles)") !=
          std::string::npos);
    // longhand: no cycle, the passes as before.
    CHECK(rc_posted(rc_job(R"(, "output": "longhand")"), lcnc).text.find("G71") == std::string::npos);
    // Along X: an undercut (X falling along the profile) is a pocket for G72 (element 4 of its
    // sub, which runs from the end face back: the profile's element 3): longhand with a note,
    // refused under canned, on fanuc-lathe too.
    {
        const auto p = rc_posted(rc_job(R"(, "compensation": "none", "direction": "x")", under), lcnc);
        CHECK(p.text.find("G72") == std::string::npos);
        CHECK_MESSAGE(p.notes.find("/operations/1 (turn rough): the roughing is written longhand because machine "
                                      "linuxcnc-lathe's G72 would not cut these passes: element 4 turns back towards +X") !=
                          std::string::npos,
                      p.notes);
        CHECK(rc_refusal(rc_job(R"(, "compensation": "none", "direction": "x", "output": "canned")", under), lcnc)
                  .find("/operations/1/output: machine linuxcnc-lathe's G72 would not cut these passes") != std::string::npos);
        CHECK(rc_refusal(rc_job(R"(, "compensation": "none", "direction": "x", "output": "canned")", under), fanuc)
                  .find("/operations/1/output: machine fanuc-lathe's G72 would not cut these passes: element 4 turns back "
                        "towards +X") != std::string::npos);
        CHECK(rc_posted(rc_job(R"(, "compensation": "none", "direction": "x")", under), fanuc)
                  .notes.find("machine fanuc-lathe's G72 would not cut these passes") != std::string::npos);
    }
    // A bar not faced to the profile's start: the cycle's line down to it would run through the
    // stub, so it is refused, and the note says why.
    const std::string unfaced = fmt::format(
        R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0.05}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": 1.5, "compensation": "none",
                   "start": [18, 0], "path": [{{"line": [20, -1]}}, {{"line": [20, -15]}}, {{"line": [32, -20]}}]}}]}})");
    const auto u = rc_posted(unfaced, lcnc);
    CHECK(u.text.find("G71") == std::string::npos);
    CHECK_MESSAGE(u.notes.find("inside the bar whose face is at Z 0.05") != std::string::npos, u.notes);
}

TEST_CASE("turn-rough output: no level of the cycle within 0.005 mm of a corner of its boundary") {
    // Depths that land a level from the bar on the profile's radii: another start or I is taken.
    for (double doc : {1.0, 2.0, 0.5, 2.5}) {
        CAPTURE(doc);
        const std::string text = fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": {}, "compensation": "none",
                   "start": [20, 0], "path": [{{"line": [20, -5]}}, {{"line": [30, -5]}}, {{"line": [30, -10]}}, {{"line": [36, -12]}}]}}]}})",
            doc);
        const Job j = read_job(text, "rc.json");
        const auto& op = std::get<TurnRoughOp>(j.operations.at(0));
        const TurnCycle c = turn_cycle(op);
        REQUIRE_FALSE(c.refusal);
        CHECK(c.depth <= doc);
        for (double level = c.start.x; level > 10 - 0.01; level -= c.depth)
            for (double corner : {10.0, 15.0, 18.0}) CHECK(std::abs(level - corner) >= 0.005 - 1e-9);
    }
}

TEST_CASE("turn-rough: a fillet rising from a shoulder's corner is canned, not taken for a pocket by a rounding error") {
    // The shaft in inch-sized mm (an exploratory tester): the R5.08 fillet's start lies at its
    // centre's Z; offset by the nose and shifted by the allowances it came out 1e-15 mm on the
    // falling side, and "output": "canned" was refused as "an arc that falls in radius (a pocket)".
    const std::string job = R"({"name":"fp","units":"mm","clearance":20,"stock":{"bar":{"diameter":44.45,"length":76,"faceZ":0}},
 "tools":[{"number":4,"type":"turning-tool","noseRadius":0.7874,"orientation":2,"rpm":1000}],
 "operations":[{"type":"turn-rough","tool":4,"feed":0.25,"feedMode":"per-revolution","depthOfCut":1.524,
   "allowanceX":0.4064,"allowanceZ":0.1016,"start":[0,0],"output":"canned",
   "path":[{"line":[27.94,0]},{"line":[30.48,-1.27]},{"line":[30.48,-20.32]},
           {"arc":{"end":[40.64,-25.4],"centre":[40.64,-20.32],"direction":"cw"}},{"line":[40.64,-40.64]}]}]})";
    for (const char* m : {"linuxcnc-lathe", "fanuc-lathe"}) {
        CAPTURE(m);
        std::string program;
        CHECK_NOTHROW(program = rc_posted(job, load_machine(m)).text);
        CHECK(program.find("G71") != std::string::npos);
    }
}

}  // namespace test_turn_rough_cycle
