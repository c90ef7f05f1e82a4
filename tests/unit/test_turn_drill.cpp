// The turn-drill operation (CNC-Calc onDrilling with its TurnDrillingFields): every parameter
// changes the motion as the manual says, shown on the Z moves of a longhand program worked
// out by hand; bad input is refused at its JSON path.
#include <doctest/doctest.h>

#include "camgen/post/longhand.hpp"
#include "camgen/reader/reader.hpp"
#include "lathe_support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_drill {

using namespace camgen;
using test::z_moves;

namespace {

// A job with one turn-drill from the face at Z0 to Z-20, feed starting at Z2, retract to Z10,
// clearance Z50; `extra` adds keys to the operation. Tool 1: a 10 mm drill, 118 degrees, 800 rpm.
std::string job(const std::string& extra, const std::string& tool_extra = "") {
    return R"({"clearance": 50, "tools": [{"number": 1, "type": "drill", "diameter": 10, "tipAngle": 118, "rpm": 800)" +
           tool_extra + R"(}],
  "operations": [{"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": -20, "safeDistance": 2,
                  "retractDistance": 10)" +
           extra + R"(}]})";
}

// The program on the test lathe (longhand drilling, peck clearance 1 mm).
std::string posted(const std::string& extra, const std::string& machine_extra = "", const std::string& tool_extra = "") {
    return test::post_program(read_job(job(extra, tool_extra), "turn.json"), test::lathe(true, false, machine_extra));
}

// Approach (clearance, retract, feed start) and leave (clearance) around the cycle's own moves.
std::vector<std::string> around(std::vector<std::string> cycle) {
    std::vector<std::string> all{"G0 Z50", "G0 Z10", "G0 Z2"};
    all.insert(all.end(), cycle.begin(), cycle.end());
    all.push_back("G0 Z50");
    return all;
}

InputError error_of(const std::string& text) {
    try {
        (void)read_job(text, "turn.json");
    } catch (const InputError& e) {
        return e;
    }
    FAIL("no error");
    return InputError("", "");
}

}  // namespace

TEST_CASE("turn-drill: the drill stands at X0; plain drilling feeds to endDepth and rapids to retractDistance") {
    const std::string text = posted(R"(, "plungingFeedrate": 100)");
    CHECK(text.find("X0\n") != std::string::npos);
    CHECK(text.find('Y') == std::string::npos);
    CHECK(z_moves(text) == around({"G1 Z-20 F100", "G0 Z10"}));
}

TEST_CASE("turn-drill: pecks with a full retract (peckClearance) and equal later pecks") {
    // From Z2 in pecks of 8: -6, -14, then -22 is past the bottom: -20. After each peck rapid
    // to Z2, back down to 0.5 above the last peck.
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "firstPeckDepth": 8, "peckClearance": 0.5)")) ==
          around({"G1 Z-6 F100", "G0 Z2", "G0 Z-5.5", "G1 Z-14", "G0 Z2", "G0 Z-13.5", "G1 Z-20", "G0 Z10"}));
    // Without peckClearance the machine's (1 mm).
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "firstPeckDepth": 8)")) ==
          around({"G1 Z-6 F100", "G0 Z2", "G0 Z-5", "G1 Z-14", "G0 Z2", "G0 Z-13", "G1 Z-20", "G0 Z10"}));
}

TEST_CASE("turn-drill: subsequentPeckDepths sets every peck after the first") {
    // 8 first, then 5: -6, -11, -16, then -21 is past the bottom: -20.
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "firstPeckDepth": 8, "subsequentPeckDepths": 5,
                           "peckClearance": 0.5)")) ==
          around({"G1 Z-6 F100", "G0 Z2", "G0 Z-5.5", "G1 Z-11", "G0 Z2", "G0 Z-10.5", "G1 Z-16", "G0 Z2", "G0 Z-15.5", "G1 Z-20", "G0 Z10"}));
    // Later pecks larger than the first: 3, then 10: -1, -11, -21 -> -20.
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "firstPeckDepth": 3, "subsequentPeckDepths": 10,
                           "peckClearance": 0.5)")) ==
          around({"G1 Z-1 F100", "G0 Z2", "G0 Z-0.5", "G1 Z-11", "G0 Z2", "G0 Z-10.5", "G1 Z-20", "G0 Z10"}));
}

TEST_CASE("turn-drill: peckRetract breaks the chip: back off, no full retract") {
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "firstPeckDepth": 8, "peckRetract": 0.3)")) ==
          around({"G1 Z-6 F100", "G0 Z-5.7", "G1 Z-14", "G0 Z-13.7", "G1 Z-20", "G0 Z10"}));
}

TEST_CASE("turn-drill: upper and lower dwell") {
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "upperDwell": 0.5, "lowerDwell": 1)")) ==
          around({"G4 P0.5", "G1 Z-20 F100", "G4 P1", "G0 Z10"}));
    // With pecks the upper dwell comes before each peck after a full retract.
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "firstPeckDepth": 12, "peckClearance": 1, "upperDwell": 0.5)")) ==
          around({"G4 P0.5", "G1 Z-10 F100", "G0 Z2", "G4 P0.5", "G0 Z-9", "G1 Z-20", "G0 Z10"}));
}

TEST_CASE("turn-drill: retractFeedrate feeds out to safeDistance") {
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "retractFeedrate": 50)")) ==
          around({"G1 Z-20 F100", "G1 Z2 F50", "G0 Z10"}));
}

TEST_CASE("turn-drill: drill-tip compensation from the tool or from drillDiameter and drillTipAngle") {
    // The tool: (10 / 2) / tan(118 / 2) = 5 / 1.66428 = 3.0043 -> Z-23.004.
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "drillTip": true)")) == around({"G1 Z-23.004 F100", "G0 Z10"}));
    // Its own: (6 / 2) / tan(90 / 2) = 3 -> Z-23.
    CHECK(z_moves(posted(R"(, "plungingFeedrate": 100, "drillTip": true, "drillDiameter": 6, "drillTipAngle": 90)")) ==
          around({"G1 Z-23 F100", "G0 Z10"}));
}

TEST_CASE("turn-drill: pitch taps on the axis at pitch x rpm, spindle reversed at the bottom") {
    const std::string text = posted(R"(, "pitch": 1.5)", R"(, "drilling": {"tapping": "floating"})");
    // 1.5 mm x 800 rpm = 1200 mm/min, in and out.
    CHECK(z_moves(text) == around({"G1 Z-20 F1200", "G1 Z2", "G0 Z10"}));
    CHECK(text.find("G1 Z-20 F1200\nS800 M4\nZ2\nS800 M3\n") != std::string::npos);
}

TEST_CASE("turn-drill: the cycle kind follows the parameters") {
    auto kind = [](const std::string& extra) {
        Job j = read_job(job(extra), "turn.json");
        return std::get<TurnDrillOp>(j.operations.at(0)).cycle.kind;
    };
    CHECK(kind(R"(, "plungingFeedrate": 100)") == CycleKind::drill);
    CHECK(kind(R"(, "plungingFeedrate": 100, "lowerDwell": 1)") == CycleKind::dwell);
    CHECK(kind(R"(, "plungingFeedrate": 100, "firstPeckDepth": 3)") == CycleKind::deep);
    CHECK(kind(R"(, "plungingFeedrate": 100, "firstPeckDepth": 3, "peckRetract": 0.5)") == CycleKind::chip_break);
    CHECK(kind(R"(, "pitch": 1)") == CycleKind::tap);
    Job left = read_job(job(R"(, "pitch": 1)", R"(, "direction": "ccw")"), "turn.json");
    CHECK(std::get<TurnDrillOp>(left.operations.at(0)).cycle.kind == CycleKind::tap_left);
}

TEST_CASE("turn-drill: bad input is refused at its JSON path") {
    auto check = [](const std::string& text, const std::string& path, const std::string& detail) {
        const InputError e = error_of(text);
        INFO(std::string(e.what()));
        CHECK(e.path() == path);
        CHECK(std::string(e.detail()).find(detail) != std::string::npos);
    };
    const std::string above = R"({"clearance": 50, "tools": [{"number": 1, "diameter": 10, "rpm": 800}],
  "operations": [{"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": 5, "safeDistance": 2,
                  "plungingFeedrate": 100}]})";
    check(above, "/operations/0/endDepth", "endDepth (Z 5.000 mm) is not below startDepth (Z 0.000 mm)");
    check(job(R"(, "plungingFeedrate": 100, "firstPeckDepth": 0)"), "/operations/0/firstPeckDepth",
          "a peck depth must be > 0");
    check(job(R"(, "plungingFeedrate": 100, "firstPeckDepth": 4, "subsequentPeckDepths": 0)"),
          "/operations/0/subsequentPeckDepths", "a peck depth must be > 0");
    check(job(R"(, "plungingFeedrate": 100, "peckRetract": 0.5)"), "/operations/0/peckRetract", "it needs firstPeckDepth");
    check(job(R"(, "plungingFeedrate": 100, "firstPeckDepth": 4, "peckRetract": 0.5, "peckClearance": 1)"),
          "/operations/0/peckRetract", "not both");
    check(job(R"(, "pitch": 1, "plungingFeedrate": 100)"), "/operations/0/plungingFeedrate", "no meaning when tapping");
    check(job(""), "/operations/0/plungingFeedrate", "needs plungingFeedrate");
    // A job with one of its planes moved.
    auto moved = [](const std::string& from, const std::string& to) {
        std::string text = job(R"(, "plungingFeedrate": 100)");
        return text.replace(text.find(from), from.size(), to);
    };
    check(moved(R"("safeDistance": 2)", R"("safeDistance": -1)"), "/operations/0/safeDistance", "below startDepth");
    check(moved(R"("retractDistance": 10)", R"("retractDistance": 1)"), "/operations/0/retractDistance",
          "below safeDistance");
    check(job(R"(, "plungingFeedrate": 100, "drillTipAngle": 90)"), "/operations/0/drillTipAngle",
          "no effect without drillTip");
    check(job(R"(, "plungingFeedrate": 100, "lowerDwell": -1)"), "/operations/0/lowerDwell", "cannot be negative");
}

TEST_CASE("turn-drill: a lathe job on a mill is refused, naming the operation and the kinds, exit 1") {
    const std::string file = test::file_with("turn-on-mill", job(R"(, "plungingFeedrate": 100)"));
    test::Run r = test::run({file, "--machine", "fanuc"});
    CHECK(r.code == 1);
    CHECK(r.out.empty());
    CHECK(r.err.find("/operations/0/type: operation \"turn-drill\" (centre drill to Z-20) is made for a lathe, and "
                     "machine fanuc is a mill") != std::string::npos);
}

TEST_CASE("drill (mill): subsequentDepth and peckClearance are the milling side's fields too") {
    // The shared peck model: from safe Z2, 4 then 2: -2, -4, -6 -> bottom -5.
    DrillCycle c;
    c.kind = CycleKind::deep;
    c.safe_z = c.retract_z = 2;
    c.bottom_z = -5;
    c.values.set(DrillField::first_depth, 4);
    c.values.set(DrillField::subsequent_depth, 2);
    CHECK(peck_depths(c) == std::vector<double>{-2, -4, -5});
    // A mill job may give them; the machine's G83 cannot carry them: longhand, with a note.
    std::ostringstream notes;
    PostOptions o;
    o.notes = &notes;
    std::ostringstream out;
    Job j = read_job(test::drill_job(R"("tool": 1, "cycle": "deep", "endDepth": 5, "plungingFeedrate": 100,
                                        "firstDepth": 4, "peckClearance": 0.5)"),
                     "mill.json");
    const Machine linuxcnc = load_machine("linuxcnc");
    auto post = make_post(linuxcnc, out, o);
    post->open();
    expand_job(j, *post);
    post->close();
    CHECK(notes.str().find("G83 cannot carry peckClearance") != std::string::npos);
    // From the retract plane Z20 (no safeDistance) in pecks of 4: back down to 0.5 above Z16.
    CHECK(out.str().find("G1 Z16 F100\nG0 Z20\nZ16.5\nG1 Z12\n") != std::string::npos);
    // With a degression it is refused: both would set the later pecks.
    CHECK_THROWS_WITH_AS(read_job(test::drill_job(R"("tool": 1, "cycle": "deep", "endDepth": 5, "plungingFeedrate": 100,
                                        "firstDepth": 4, "subsequentDepth": 2, "degressionType": "value",
                                        "degression": 1, "minimumDepth": 1)"),
                                  "mill.json"),
                         doctest::Contains("subsequentDepth and a degression"), InputError);
}

TEST_CASE("turn-drill: feeds per revolution: the job's mm/rev, written after the machine's code") {
    const std::string modes = R"(, "drilling": {"tapping": "floating"})";
    // The test lathe's frame with G94/G95.
    Machine m = test::lathe(true, false, modes);
    m.frame.feed_modes = {{FeedMode::per_minute, "G94"}, {FeedMode::per_revolution, "G95"}};
    Job j = read_job(job(R"(, "feedMode": "per-revolution", "plungingFeedrate": 0.12, "retractFeedrate": 0.3)"), "t.json");
    const DrillCycle& c = std::get<TurnDrillOp>(j.operations.at(0)).cycle;
    CHECK(c.feed == doctest::Approx(0.12 * 800));  // the events carry mm/min
    const std::string text = test::post_program(j, m);
    CHECK(text.find("G95\n") < text.find("G1 Z-20"));
    CHECK(z_moves(text) == around({"G1 Z-20 F0.12", "G1 Z2 F0.3", "G0 Z10"}));
    // Read back: F x S is the job's feed per minute.
    std::vector<ReadEvent> back = read_program(text, m, "t.nc");
    std::vector<double> feeds;
    for (const ReadEvent& e : back)
        if (auto* l = std::get_if<Linear>(&e.event)) feeds.push_back(l->feed);
    CHECK(feeds == std::vector<double>{0.12 * 800, 0.3 * 800});
    // A machine without feed modes refuses it, at the operation.
    CHECK_THROWS_WITH_AS(test::post_program(j, test::lathe(true, false)),
                         doctest::Contains("/operations/0/feedMode: machine test-lathe has no feed per-revolution mode"),
                         InputError);
}

TEST_CASE("a per-revolution feed at a spindle speed S rounds reads back within feed x the S resolution") {
    // 0.2296875 mm/rev at 802.3125 rpm is 184.281 mm/min in the job; the program says S802, so
    // the control feeds 184.219 mm/min: the feed per turn is kept, the speed is the machine's.
    // A fuzz_mutated finding: verify refused camgen's own linuxcnc-lathe program.
    const std::string job = R"({"name": "s", "units": "mm", "clearance": 20,
      "tools": [{"number": 2, "type": "drill", "diameter": 10, "rpm": 802.3125, "tipAngle": 118}],
      "operations": [{"type": "turn-drill", "tool": 2, "feedMode": "per-revolution", "plungingFeedrate": 0.2296875,
        "startDepth": 0, "endDepth": -30, "firstPeckDepth": 6, "peckRetract": 1, "safeDistance": 2, "retractDistance": 5}]})";
    const std::string file = test::file_with("per-rev-speed-rounding", job);
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        const std::string program = (test::scratch("per-rev-speed-rounding-out") / "p.nc").string();
        const test::Run post = test::run({file, "--machine", machine, "-o", program, "-q"});
        REQUIRE_MESSAGE(post.code == 0, post.err);
        const test::Run verify = test::run({"verify", program, "--machine", machine, "--job", file});
        CHECK_MESSAGE(verify.code == 0, verify.err);
    }
}

}  // namespace test_turn_drill
