// The readers of the dialects that came with the new machines: GRBL's tool change (comment +
// M0), LinuxCNC G33.1, Sinumerik (MCALL CYCLE8x, G4 F, CR=) and Heidenhain conversational
// (L/CC/C, TOOL CALL, cycles 9/200/203/207). Each canned cycle must read back as the longhand
// motion camgen means by it; moves worked out by hand; broken programs and cycle parameters
// caught; errors name the line.
#include <doctest/doctest.h>

#include <algorithm>

#include <nlohmann/json.hpp>
#include <fmt/format.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_reader_dialects {

using namespace camgen;
using namespace camgen::test;

namespace {

// Every cycle kind, with the parameters that make each machine write its canned cycles where
// it has them (peckingRetract + retractFeedrate: Heidenhain 203; topDwell, bottomDwell,
// firstFeedrateFactor: Sinumerik CYCLE83; tapping and retract speeds: CYCLE84; a left-hand
// tap without them: G74, G33.1 under M4, CYCLE84 PIT<0, 207 Q239<0).
const std::string cycles_job = R"({"name": "cycles", "clearance": 10,
 "tools": [{"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}, {"number": 2, "type": "tap", "diameter": 6, "rpm": 300},
           {"number": 3, "type": "tap", "diameter": 6, "rpm": 300}],
 "operations": [
  {"type": "drill", "tool": 1, "cycle": "drill", "retractPlane": 5, "safeDistance": 1, "endDepth": 4, "plungingFeedrate": 100, "holes": [[60,0],[60,10]]},
  {"type": "drill", "tool": 1, "cycle": "dwell", "retractPlane": 2, "endDepth": 2, "plungingFeedrate": 100, "bottomDwell": 0.5, "holes": [[0,0],[10,0]]},
  {"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 5, "safeDistance": 1, "endDepth": 7, "firstDepth": 2.5, "plungingFeedrate": 100, "holes": [[0,10],[10,10]]},
  {"type": "drill", "tool": 1, "cycle": "chip-break", "retractPlane": 2, "endDepth": 7, "firstDepth": 3, "plungingFeedrate": 100, "holes": [[0,20],[10,20]]},
  {"type": "drill", "tool": 1, "cycle": "chip-break", "retractPlane": 2, "endDepth": 7, "firstDepth": 2, "peckingRetract": 0.3, "retractFeedrate": 300, "plungingFeedrate": 100, "holes": [[20,20]]},
  {"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 3, "safeDistance": 1, "endDepth": 8, "firstDepth": 3, "topDwell": 0.2, "bottomDwell": 0.3, "firstFeedrateFactor": 0.5, "plungingFeedrate": 100, "holes": [[20,30]]},
  {"type": "drill", "tool": 1, "cycle": "ream", "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0,30]]},
  {"type": "drill", "tool": 1, "cycle": "ream", "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 100, "retractFeedrate": 300, "holes": [[20,40]]},
  {"type": "drill", "tool": 1, "cycle": "bore-stop", "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0,40]]},
  {"type": "drill", "tool": 1, "cycle": "bore-dwell", "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 100, "bottomDwell": 1, "holes": [[0,50]]},
  {"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 2, "endDepth": 9, "firstDepth": 3, "degressionType": "value", "degression": 0.5, "minimumDepth": 1, "plungingFeedrate": 100, "holes": [[20,0]]},
  {"type": "drill", "tool": 2, "cycle": "tap", "retractPlane": 5, "safeDistance": 2, "endDepth": 8, "pitch": 1, "holes": [[30,0],[30,10]]},
  {"type": "drill", "tool": 2, "cycle": "tap", "retractPlane": 5, "safeDistance": 2, "endDepth": 8, "pitch": 1, "tappingSpeed": 200, "retractSpeed": 400, "holes": [[50,0]]},
  {"type": "drill", "tool": 3, "cycle": "tap-left", "retractPlane": 5, "safeDistance": 2, "endDepth": 8, "pitch": 1, "holes": [[40,0],[40,10]]}
 ]})";

// cycles_job as `machine` can run it: a rigid-tapping machine has no tap with its own speeds
// (op 12) unless its canned cycle carries them, a machine that cannot tap has no taps.
std::string cycles_for(const std::string& machine) {
    const Machine m = load_machine(machine);
    const DrillingCycleSpec* tap = m.canned_cycle(CycleKind::tap);
    const bool speeds = tap && std::find(tap->fields.begin(), tap->fields.end(), DrillField::tapping_speed) != tap->fields.end();
    nlohmann::json job = nlohmann::json::parse(cycles_job);
    auto& ops = job["operations"];
    if (m.tapping == TappingMode::none) ops.erase(ops.begin() + 11, ops.end());
    else if (m.tapping == TappingMode::rigid && !speeds) ops.erase(ops.begin() + 12);
    return job.dump();
}

size_t count_of(const std::string& text, const std::string& part) {
    size_t n = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

// The moves and spindle changes of a program, one string each: "G0 x y z", "G1 x y z F",
// "S cw 300", "dwell 0.5".
std::vector<std::string> moves_of(const std::string& program, const std::string& machine_name) {
    Machine m = load_machine(machine_name);
    Trace t = trace_program(read_program(program, m, "prog"), m);
    std::vector<std::string> out;
    for (const Step& s : t.steps) {
        if ((s.kind == StepKind::rapid || s.kind == StepKind::feed) && s.from_known)
            out.push_back(s.kind == StepKind::rapid ? fmt::format("G0 {:g} {:g} {:g}", s.to.x, s.to.y, s.to.z)
                                                    : fmt::format("G1 {:g} {:g} {:g} F{:g}", s.to.x, s.to.y, s.to.z, s.feed));
        if (s.kind == StepKind::spindle)
            out.push_back(fmt::format("S {} {:g}", s.spindle == SpindleState::cw ? "cw" : s.spindle == SpindleState::ccw ? "ccw" : "off", s.rpm));
        if (s.kind == StepKind::dwell) out.push_back(fmt::format("dwell {:g}", s.seconds));
    }
    return out;
}

// The moves after the first `skip` of a program.
std::vector<std::string> after(std::vector<std::string> moves, size_t skip) {
    REQUIRE(moves.size() >= skip);
    moves.erase(moves.begin(), moves.begin() + static_cast<std::ptrdiff_t>(skip));
    return moves;
}

const std::string sinumerik_head = "; t\nN10 G17 G71 G90 G94\nN20 T1 D1\nN30 M6\nN40 S1000 M3\nN50 G0 X0.000 Y0.000\nN60 Z10.000\n";
const std::string heidenhain_head = "0 BEGIN PGM t MM\n1 TOOL CALL 1 Z S1000\n2 M3\n3 L X+0 Y+0 R0 FMAX\n4 L Z+10 R0 FMAX\n";
const std::string heidenhain_203 =
    "5 CYCL DEF 203 UNIVERSAL DRILLING ~\n  Q200=+2 ;SET-UP CLEARANCE ~\n  Q201=-7 ;DEPTH ~\n  Q206=+100 ;FEED ~\n"
    "  Q202=+3 ;PLUNGING DEPTH ~\n  Q210=+0 ;DWELL TIME AT TOP ~\n  Q203=+0 ;SURFACE COORDINATE ~\n"
    "  Q204=+10 ;2ND SET-UP CLEARANCE ~\n  Q212=+0 ;DECREMENT ~\n  Q213=+0 ;NR OF BREAKS ~\n"
    "  Q205=+0 ;MIN. PLUNGING DEPTH ~\n  Q211=+0 ;DWELL TIME AT DEPTH ~\n  Q208=+99999 ;RETRACTION FEED RATE ~\n"
    "  Q256=+0.5 ;DIST FOR CHIP BRKNG\n";

}  // namespace

TEST_CASE("every canned cycle of every machine reads back as the motion of the job's longhand cycle") {
    struct Expect {
        const char* machine;
        std::vector<std::pair<std::string, size_t>> written;  // text and how often the program has it
    };
    const std::vector<Expect> expect = {
        {"fanuc", {{"G81 ", 1}, {"G82 ", 1}, {"G83 ", 1}, {"G73 ", 1}, {"G85 ", 1}, {"G86 ", 1}, {"G89 ", 1}, {"G84 ", 1}, {"G74 ", 1}}},
        {"linuxcnc", {{"G81 ", 1}, {"G82 ", 1}, {"G83 ", 1}, {"G73 ", 1}, {"G85 ", 1}, {"G86 ", 1}, {"G89 ", 1},
                      {"G33.1 Z-8 K1\n", 4}, {"S300 M4\nZ2\nG33.1", 1}}},
        {"sinumerik", {{"CYCLE81(", 1}, {"CYCLE82(", 1}, {"CYCLE83(", 4}, {", 0.3, 1.000)", 1}, {"CYCLE85(", 2},
                       {", 100, 300)", 1}, {"CYCLE86(", 1}, {"CYCLE89(", 1}, {"CYCLE84(", 3}, {", 0, 200, 400)", 1},
                       {", -1.000, 0, 300, 300)", 1}}},
        {"heidenhain", {{"CYCL DEF 200 ", 2}, {"CYCL DEF 203 ", 4}, {"Q213=+99 ", 2}, {"Q208=+300 ", 1}, {"Q256=+0.3 ", 1},
                        {"Q212=+0.5 ", 1}, {"CYCL DEF 207 ", 2}, {"Q239=-1 ", 1}}},
        {"grbl", {{"G8", 0}, {"G7", 0}, {"G33", 0}, {"M0\n", 1}}},
    };
    for (const Expect& e : expect) {
        CAPTURE(e.machine);
        const std::string job = cycles_for(e.machine);
        std::string program = post_job(job, e.machine).text;
        for (const auto& word : e.written) {
            const auto& text = word.first;
            const auto n = word.second;
            CAPTURE(text);
            CHECK(count_of(program, text) == n);
        }
        CHECK(round_trip(job, program, e.machine) == "");
    }
}

TEST_CASE("round trip catches a wrong cycle parameter on the new machines") {
    SUBCASE("sinumerik CYCLE83: first depth FDEP 1 mm short") {
        std::string p = post_job(cycles_for("sinumerik"), "sinumerik").text;
        std::string m = round_trip(cycles_for("sinumerik"), replace_once(p, "-7.000, , -1.500,", "-7.000, , -0.500,"), "sinumerik");
        CHECK(m.find("the job's feed move from X0.000 Y10.000 Z1.000 to X0.000 Y10.000 Z-1.500 is not in the program") !=
              std::string::npos);
    }
    SUBCASE("sinumerik CYCLE84: retract speed SST1") {
        std::string p = post_job(cycles_for("sinumerik"), "sinumerik").text;
        CHECK(round_trip(cycles_for("sinumerik"), replace_once(p, ", 0, 200, 400)", ", 0, 200, 300)"), "sinumerik")
                  .find("the program sets spindle ccw at 300.000 rpm, the job spindle ccw at 400.000 rpm") != std::string::npos);
    }
    SUBCASE("heidenhain 203: full retract (Q213=0) where the job breaks chips") {
        std::string p = post_job(cycles_for("heidenhain"), "heidenhain").text;
        std::string broken = replace_once(p, "Q213=+99 ;NR OF BREAKS ~\n  Q205=+0 ;MIN. PLUNGING DEPTH ~\n  Q211=+0 ;DWELL TIME AT DEPTH ~\n  Q208=+99999",
                                          "Q213=+0 ;NR OF BREAKS ~\n  Q205=+0 ;MIN. PLUNGING DEPTH ~\n  Q211=+0 ;DWELL TIME AT DEPTH ~\n  Q208=+99999");
        CHECK(round_trip(cycles_for("heidenhain"), broken, "heidenhain") != "");
    }
    SUBCASE("heidenhain 203: chip-break distance Q256") {
        std::string p = post_job(cycles_for("heidenhain"), "heidenhain").text;
        CHECK(round_trip(cycles_for("heidenhain"), replace_once(p, "Q256=+0.3 ", "Q256=+0.5 "), "heidenhain")
                  .find("the program's rapid move from X20.000 Y20.000 Z0.000 to X20.000 Y20.000 Z0.500 is not in the job") !=
              std::string::npos);
    }
    SUBCASE("heidenhain 207: the hand of a tap (Q239 sign)") {
        std::string p = post_job(cycles_for("heidenhain"), "heidenhain").text;
        CHECK(round_trip(cycles_for("heidenhain"), replace_once(p, "Q239=-1 ", "Q239=+1 "), "heidenhain")
                  .find("spindle") != std::string::npos);
    }
    SUBCASE("linuxcnc G33.1: a left-hand tap without its M4") {
        std::string p = post_job(cycles_for("linuxcnc"), "linuxcnc").text;
        // Under M3 the same G33.1 taps right-handed.
        CHECK(round_trip(cycles_for("linuxcnc"), replace_once(p, "S300 M4\nZ2\n", "Z2\n"), "linuxcnc")
                  .find("the program sets spindle cw at 300.000 rpm, the job spindle ccw at 300.000 rpm") != std::string::npos);
    }
}

// ---- GRBL and LinuxCNC (iso) ----

TEST_CASE("grbl: a tool change is the comment (Insert tool n: ...) and M0 on the next line") {
    Machine m = load_machine("grbl");
    auto ev = read_program("(t)\nG17 G21 G90 G94\n(Insert tool 5: 4 mm end mill - cutter)\nM0\nS4000 M3\nG0 X1 Y2\nZ3\nM5\nM2\n", m);
    std::vector<ToolChange> changes;
    for (const ReadEvent& e : ev)
        if (const auto* t = std::get_if<ToolChange>(&e.event)) changes.push_back(*t);
    REQUIRE(changes.size() == 1);
    CHECK(changes[0] == ToolChange{5, 4.0, "4 mm end mill - cutter"});
    // Without a description.
    CHECK(error_of("G17 G21 G90 G94\n(Insert tool 5)\nM0\nM2\n", "grbl") == "");
    std::string head = "G17 G21 G90 G94\n";
    // M0 without the comment is a stop for the operator (its message the block's comment); M1
    // is no stop on GRBL, which ignores it.
    CHECK(error_of(head + "M0 (look)\nM2\n", "grbl") == "");
    // Its comment is the stop's message (a Comment event first, as every comment).
    CHECK(read_program(head + "M0 (look)\nM2\n", m).at(1).event == Event{Stop{StopKind::mandatory, "look"}});
    CHECK(error_of(head + "M1\n", "grbl").starts_with("prog.nc:2: M1: machine grbl ignores M1 (it has no optional stop switch)"));
    CHECK(error_of(head + "(Insert tool 5: drill)\nS1000 M3\nM0\n", "grbl")
              .starts_with("prog.nc:3: the tool change announced on line 2 (Insert tool 5) is not made"));
    CHECK(error_of(head + "(Insert tool 5: drill)\n", "grbl").starts_with("prog.nc:2: the tool change announced on line 2"));
    CHECK(error_of(head + "T5 M6\n", "grbl").starts_with("prog.nc:2: T5: machine grbl has no tool changer"));
    CHECK(error_of(head + "(Insert tool five)\nM0\n", "grbl").starts_with("prog.nc:2: (Insert tool five): no tool number"));
    // On an M6 machine the same comment is only a comment, and M0 only a pause.
    CHECK(error_of("%\nN10 G17 G21 G90 G94\n(Insert tool 5: drill)\nN15 M0\nN20 M30\n", "fanuc") == "");
}

TEST_CASE("linuxcnc G33.1: in to Z at pitch x speed, spindle reversed, out to the start Z, spindle restored") {
    const std::string head = "G17 G21 G90 G94\nT7 M6\nS300 M3\nG0 X10 Y10\nG43 Z5 H7\nZ3\n";
    // 1.25 mm x 300 rpm = 375 mm/min both ways; back to Z3 where the tap started.
    CHECK(after(moves_of(head + "G33.1 Z-12 K1.25\nG0 Z5\nM5\nM2\n", "linuxcnc"), 1) ==
          std::vector<std::string>{"G0 10 10 3", "G1 10 10 -12 F375", "S ccw 300", "G1 10 10 3 F375", "S cw 300", "G0 10 10 5",
                                   "S off 0"});
    // Under M4 a left-hand tap: reversed to M3 at the bottom, M4 again at the top.
    CHECK(after(moves_of(head + "S300 M4\nG33.1 Z-12 K1\nS300 M3\nM2\n", "linuxcnc"), 1) ==
          std::vector<std::string>{"G0 10 10 3", "S ccw 300", "G1 10 10 -12 F300", "S cw 300", "G1 10 10 3 F300", "S ccw 300",
                                   "S cw 300"});
    CHECK(error_of(head + "M5\nG33.1 Z-12 K1.25\n", "linuxcnc") == "prog.nc:8: G33.1 with the spindle off: rigid tapping follows the spindle");
    CHECK(error_of(head + "G33.1 X20 Z-12 K1.25\n", "linuxcnc").starts_with("prog.nc:7: X20 on G33.1"));
    CHECK(error_of(head + "G33.1 Z-12\n", "linuxcnc") == "prog.nc:7: G33.1 needs the hole bottom Z and the pitch K");
    CHECK(error_of(head + "G33.1 Z5 K1\n", "linuxcnc") == "prog.nc:7: G33.1 Z5: the bottom is not below the start Z");
    // fanuc has no G33.1.
    CHECK(error_of("%\nN10 G17 G21 G90 G94\nN15 G33.1 Z-1.000 K1.000\n", "fanuc").starts_with("prog.nc:3: G33.1 (rigid tapping) is not a cycle of machine fanuc"));
}

// ---- Sinumerik ----

TEST_CASE("sinumerik CYCLE83 pecks worked out by hand; G4 F is a dwell, not a feed; CR= arcs") {
    // safe = RFP 0 + SDIS 2; FDEP -1: first peck 3 mm; no DAM: pecks of 3 to -7; VARI 1: back
    // to the safe plane after each, then down to 1 mm (_DIS1) above the last peck; out to RTP 10.
    std::string p = sinumerik_head + "N70 F100\nN80 MCALL CYCLE83(10.000, 0.000, 2.000, -7.000, , -1.000, , , , , 1.000, 1, , , , , 1.000)\n"
                                     "N90 G0 X0.000 Y0.000\nN100 MCALL\nN110 M30\n";
    CHECK(after(moves_of(p, "sinumerik"), 1) ==
          std::vector<std::string>{"G0 0 0 2", "G1 0 0 -1 F100", "G0 0 0 2", "G0 0 0 0", "G1 0 0 -4 F100", "G0 0 0 2", "G0 0 0 -3",
                                   "G1 0 0 -7 F100", "G0 0 0 10"});
    // VARI 0 (chip breaking), _VRT 0.3: back off 0.3 only; FRF 0.5 halves the first feed.
    std::string q = sinumerik_head + "N70 F100\nN80 MCALL CYCLE83(10.000, 0.000, 2.000, -7.000, , -1.000, , , , , 0.500, 0, , , 0.300)\n"
                                     "N90 G0 X0.000 Y0.000\nN100 MCALL\nN110 M30\n";
    CHECK(after(moves_of(q, "sinumerik"), 1) ==
          std::vector<std::string>{"G0 0 0 2", "G1 0 0 -1 F50", "G0 0 0 -0.7", "G1 0 0 -4 F100", "G0 0 0 -3.7", "G1 0 0 -7 F100",
                                   "G0 0 0 10"});
    // G4 F0.5: half a second; the feed F100 stays.
    auto m = moves_of(sinumerik_head + "N70 G1 Z5.000 F100\nN80 G4 F0.5\nN90 G1 Z4.000\nN100 M30\n", "sinumerik");
    CHECK(after(m, 1) == std::vector<std::string>{"G1 0 0 5 F100", "dwell 0.5", "G1 0 0 4 F100"});
    // CR=: 90 degrees ccw from (10,0) to (0,10) about (0,0); CR=-10 the 270 degrees about (10,10).
    Machine mm = load_machine("sinumerik");
    auto arc_end = [&](const std::string& block) {
        auto ev = read_program(sinumerik_head + "N70 G0 X10.000 Y0.000 Z0.000\n" + block + "N90 M30\n", mm);
        return std::get<Arc>(ev.back().event).centre;
    };
    Vec3 c = arc_end("N80 G3 X0.000 Y10.000 CR=10.000 F100\n");
    CHECK(c.x == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(c.y == doctest::Approx(0.0).epsilon(1e-12));
    c = arc_end("N80 G3 X0.000 Y10.000 CR=-10.000 F100\n");
    CHECK(c.x == doctest::Approx(10.0));
    CHECK(c.y == doctest::Approx(10.0));
}

TEST_CASE("sinumerik: what the post never writes is an error naming the line") {
    const std::string h = sinumerik_head + "N70 F100\n";
    const std::string call = "N80 MCALL CYCLE81(10.000, 0.000, 2.000, -7.000)\n";
    CHECK(error_of(h + "N80 MCALL\n", "sinumerik") == "prog.nc:9: MCALL without a modal cycle call to end");
    CHECK(error_of(h + "N80 MCALL CYCLE87(10.000, 0.000, 2.000, -7.000)\n", "sinumerik")
              .starts_with("prog.nc:9: CYCLE87 is not a cycle of machine sinumerik (it has: CYCLE81, CYCLE82"));
    CHECK(error_of(h + call + "N90 G0 X1.000 Y1.000\n", "sinumerik")
              .starts_with("prog.nc:10: the program ends with the modal call CYCLE81 of line 9 still active"));
    CHECK(error_of(h + call + "N90 G0 Z20.000\n", "sinumerik")
              .starts_with("prog.nc:10: under the modal call CYCLE81 of line 9 camgen writes only G0 X Y hole positions"));
    CHECK(error_of(h + call + "N90 T2 D1\nN100 M6\n", "sinumerik") ==
          "prog.nc:11: a tool change while the modal call CYCLE81 of line 9 is active");
    CHECK(error_of(h + "N80 MCALL CYCLE81(10.000, 0.000, 2.000, , -7.000)\n", "sinumerik") ==
          "prog.nc:9: CYCLE81 without the final drilling depth DP (parameter 4)");
    CHECK(error_of(h + "N80 MCALL CYCLE81(10.000, 0.000, 2.000, -7.000, , 1)\n", "sinumerik") ==
          "prog.nc:9: CYCLE81 takes at most 5 parameters, not 6");
    CHECK(error_of(h + "N80 MCALL CYCLE83(10.000, 0.000, 2.000, -7.000, , -1.000, , , 0.5, , 1.000, 1, , , , , 1.000)\n",
                   "sinumerik")
              .starts_with("prog.nc:9: CYCLE83: DTB = 0.5: a dwell at every peck depth"));
    CHECK(error_of(h + "N80 MCALL CYCLE83(10.000, 0.000, 2.000, -7.000, , -1.000, , , , , 1.000, 1, , , , , 0.500)\n",
                   "sinumerik") == "prog.nc:9: CYCLE83: _DIS1 = 0.500: machine sinumerik re-approaches 1 mm above the last peck");
    CHECK(error_of(h + "N80 MCALL CYCLE84(10.000, 0.000, 2.000, -7.000, , , 3, , 0, 0, 300, 300)\n", "sinumerik") ==
          "prog.nc:9: CYCLE84: the pitch PIT must not be 0");
    CHECK(error_of(h + "N80 MCALL CYCLE86(10.000, 0.000, 2.000, -7.000, , , 3, 1.000, 0, 0, 0)\n", "sinumerik") ==
          "prog.nc:9: CYCLE86: RPA = 1.000: camgen writes it 0 and reads no other value");
    CHECK(error_of(sinumerik_head + "N70 MCALL CYCLE81(10.000, 0.000, 2.000, -7.000)\n", "sinumerik") ==
          "prog.nc:8: CYCLE81 without a feed F before it");
    // R is no Sinumerik address: radii are CR=.
    CHECK(error_of(sinumerik_head + "N70 G2 X1.000 Y1.000 R5.000 F100\n", "sinumerik") == "prog.nc:8: unknown word R5.000");
    CHECK(error_of(sinumerik_head + "N70 G4 F0.5 X1.000\n", "sinumerik").starts_with("prog.nc:8: G4 must stand in a block of its own"));
    CHECK(error_of(sinumerik_head + "N70 M30\nN80 G0 X1.000\n", "sinumerik") == "prog.nc:9: a block after the end of the program");
}

// ---- Heidenhain ----

TEST_CASE("heidenhain 203 pecks and L/C moves worked out by hand") {
    // Q203 0 + Q200 2 = the safe plane 2, depth 0 - 7; Q202 3: pecks to -1, -4, -7; Q213 0:
    // back to the safe plane, down to the machine's peckClearance 0.5 above the last peck;
    // out to Q204 10 at FMAX (Q208 99999).
    std::string p = heidenhain_head + heidenhain_203 + "6 L X+0 Y+0 R0 FMAX M99\n7 M30\n8 END PGM t MM\n";
    CHECK(after(moves_of(p, "heidenhain"), 1) ==
          std::vector<std::string>{"G0 0 0 2", "G1 0 0 -1 F100", "G0 0 0 2", "G0 0 0 -0.5", "G1 0 0 -4 F100", "G0 0 0 2",
                                   "G0 0 0 -3.5", "G1 0 0 -7 F100", "G0 0 0 10"});
    // Q213 99: chip breaking, Q256 0.3 back, Q208 300 out of the finished hole to the safe plane.
    std::string q = replace_once(replace_once(replace_once(p, "Q213=+0 ", "Q213=+99 "), "Q256=+0.5", "Q256=+0.3"), "Q208=+99999", "Q208=+300");
    CHECK(after(moves_of(q, "heidenhain"), 1) ==
          std::vector<std::string>{"G0 0 0 2", "G1 0 0 -1 F100", "G0 0 0 -0.7", "G1 0 0 -4 F100", "G0 0 0 -3.7", "G1 0 0 -7 F100",
                                   "G1 0 0 2 F300", "G0 0 0 10"});
    // FMAX holds for its block only; F stays; C turns about the last CC; cycle 9 dwells.
    std::string r = heidenhain_head +
                    "5 L Z-1 F200\n6 L X+10 R0 FMAX\n7 L Y+10\n8 CC X+10 Y+0\n9 C X+20 Y+0 DR- F300\n10 CYCL DEF 9.0 DWELL TIME\n"
                    "11 CYCL DEF 9.1 DWELL 1.5\n12 TOOL CALL Z S500\n13 M4\n14 M30\n15 END PGM t MM\n";
    CHECK(after(moves_of(r, "heidenhain"), 1) ==
          std::vector<std::string>{"G1 0 0 -1 F200", "G0 10 0 -1", "G1 10 10 -1 F200", "G1 20 0 -1 F300", "dwell 1.5", "S cw 500",
                                   "S ccw 500"});
    Machine m = load_machine("heidenhain");
    auto ev = read_program(r, m);
    const Arc* arc = nullptr;
    for (const ReadEvent& e : ev)
        if (const auto* a = std::get_if<Arc>(&e.event)) arc = a;
    REQUIRE(arc);
    CHECK(*arc == Arc{{20, 0, -1}, {10, 0, -1}, ArcDirection::cw, Plane::xy, 300, 0});
}

TEST_CASE("heidenhain: what the post never writes is an error naming the line") {
    const std::string end = "6 M30\n7 END PGM t MM\n";
    CHECK(error_of("1 BEGIN PGM t MM\n", "heidenhain") == "prog.nc:1: block number 1 where 0 comes next");
    CHECK(error_of("0 BEGIN PGM t MM\nL X+1 R0 FMAX\n", "heidenhain").starts_with("prog.nc:2: a block without its number"));
    CHECK(error_of("0 L X+1 R0 FMAX\n", "heidenhain") == "prog.nc:1: the program must begin with BEGIN PGM");
    CHECK(error_of(heidenhain_head + "5 C X+1 Y+0 DR+ F100\n", "heidenhain") == "prog.nc:6: C without a circle centre CC before it");
    CHECK(error_of(heidenhain_head + "5 CC X+5 Y+0\n6 C X+10 Y+0 F100\n", "heidenhain") == "prog.nc:7: C without its direction DR+ or DR-");
    CHECK(error_of(heidenhain_head + "5 CC X+5\n", "heidenhain") == "prog.nc:6: CC needs both X and Y (the circle centre)");
    CHECK(error_of(heidenhain_head + "5 L X+1 Y+2 R0 FMAX M99\n", "heidenhain") ==
          "prog.nc:6: M99 without a drilling cycle defined (CYCL DEF 200, 203 or 207)");
    CHECK(error_of(heidenhain_head + "5 CYCL DEF 9.0 DWELL TIME\n6 L Z+1 R0 FMAX\n", "heidenhain") ==
          "prog.nc:7: CYCL DEF 9.0 on line 6 without its CYCL DEF 9.1 DWELL");
    CHECK(error_of(heidenhain_head + replace_once(heidenhain_203, "  Q210=+0 ;DWELL TIME AT TOP ~\n", ""), "heidenhain") ==
          "prog.nc:11: Q203 where cycle 203 has Q210 next");
    CHECK(error_of(heidenhain_head + replace_once(heidenhain_203, "Q213=+0 ", "Q213=+1 "), "heidenhain")
              .starts_with("prog.nc:19: cycle 203: Q213=+1: 3 pecks make more chip breaks than that"));
    CHECK(error_of(heidenhain_head + replace_once(heidenhain_203, "Q201=-7 ", "Q201=+7 "), "heidenhain") ==
          "prog.nc:19: cycle 203: Q201=+7: the depth must be negative (below the surface)");
    CHECK(error_of(heidenhain_head + "5 CYCL DEF 200 DRILLING ~\n  Q200=+2 ~\n  Q201=-7 ~\n  Q206=+100 ~\n  Q202=+3 ~\n  Q210=+0 ~\n"
                                     "  Q203=+0 ~\n  Q204=+10 ~\n  Q211=+0\n",
                   "heidenhain") ==
          "prog.nc:14: cycle 200: Q202=+3: a plunging depth less than the depth pecks: camgen writes pecking as cycle 203");
    CHECK(error_of(heidenhain_head + "5 CYCL DEF 208 BORE MILLING ~\n", "heidenhain") == "prog.nc:6: camgen cannot read cycle 208");
    CHECK(error_of(heidenhain_head + "5 L Z+1 FMAX F100\n", "heidenhain") == "prog.nc:6: two F words in one block");
    CHECK(error_of(heidenhain_head + "5 L X+1 Y+2 Z+3 W+4 R0 FMAX\n", "heidenhain") == "prog.nc:6: unknown word W+4");
    CHECK(error_of(heidenhain_head + "5 M30\n6 END PGM other MM\n", "heidenhain") == "prog.nc:7: END PGM other ends a program named t");
    CHECK(error_of(heidenhain_head + "5 M30\n", "heidenhain") == "prog.nc:6: the program does not end with END PGM");
    CHECK(error_of(heidenhain_head + "5 L X+1 R0 FMAX\n" + end, "heidenhain") == "");
}

TEST_CASE("inch programs: cycle parameters in inches; Sinumerik FRF stays a factor, Heidenhain Q208 FMAX stays 99999") {
    const std::string job = R"({"name": "inch", "clearance": 10, "tools": [{"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}],
 "operations": [{"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 10, "safeDistance": 2, "endDepth": 20,
   "firstDepth": 5, "firstFeedrateFactor": 0.5, "plungingFeedrate": 100, "holes": [[0, 0]]},
  {"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 10, "safeDistance": 2, "endDepth": 20,
   "firstDepth": 5, "plungingFeedrate": 100, "holes": [[10, 0]]}]})";
    auto post_inch = [&](const std::string& name) {
        Machine m = load_machine(name);
        m.units = Units::inch;
        Job j = read_job(job, "job.json");
        std::ostringstream out;
        auto post = make_post(m, out, PostOptions{});
        post->open();
        expand_job(j, *post);
        post->close();
        CHECK(round_trip_machine(j, out.str(), m) == "");
        return out.str();
    };
    // RTP 10 mm = 0.3937 in, SDIS 2 mm = 0.0787 in, DP -0.7874, FDEP from the written plane:
    // 0.0787 - 5 mm (0.19685 in) = -0.11815 = -0.1182, so the control's peck is 0.1969 in;
    // FRF 0.5 whatever the units; _DIS1 the 1 mm clearance = 0.0394 in.
    CHECK(post_inch("sinumerik").find("CYCLE83(0.3937, 0.0000, 0.0787, -0.7874, , -0.1182, , , , , 0.500, 1, , , , , 0.0394)") !=
          std::string::npos);
    // Q206: 100 mm/min = 3.94 in/min (two decimals: 1 mm/min is 0.04, not 0.0); Q208 99999 (FMAX) as written.
    std::string tnc = post_inch("heidenhain");
    CHECK(tnc.find("Q206=+3.94 ;") != std::string::npos);
    CHECK(tnc.find("Q208=+99999 ;") != std::string::npos);
}

TEST_CASE("sinumerik: G700/G710 set positions and feeds; G70/G71 only positions, so only the machine's own is read") {
    // The post writes G700 (inch) or G710 (mm): F in the program's unit whatever the control's
    // base system (802D sl manual: "feedrates ... are not influenced by G70/G71. G700/G710,
    // however, influences additionally the feedrate F").
    Machine inch = load_machine("sinumerik");
    inch.units = Units::inch;
    const std::string job = R"({"clearance": 10, "tools": [{"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}],
 "operations": [{"type": "drill", "tool": 1, "retractPlane": 10, "safeDistance": 2, "endDepth": 5,
   "plungingFeedrate": 80, "holes": [[0, 0]]}]})";
    const std::string inch_program = test::post_program(read_job(job, "job.json"), inch);
    CHECK(inch_program.find(" G700\n") != std::string::npos);
    CHECK(round_trip_machine(read_job(job, "job.json"), inch_program, inch) == "");
    CHECK(post_job(job, "sinumerik").text.find(" G710\n") != std::string::npos);
    // Read on the metric machine: G700 F3.15 is 80 mm/min; G710 and G71 mean mm and mm/min.
    const std::string body = "N20 T1 D1\nN30 M6\nN40 S1000 M3\nN50 G0 X0.000 Y0.000 Z0.100\nN60 G1 Z-0.100 F3.15\nN70 M30\n";
    const auto feed_of = [&](const std::string& units) {
        double f = 0;
        for (const ReadEvent& e : read_program("N10 G17 G90 G94 " + units + "\n" + body, load_machine("sinumerik"), "p.mpf"))
            if (const auto* m = std::get_if<Linear>(&e.event)) f = m->feed;
        return f;
    };
    CHECK(feed_of("G700") == doctest::Approx(3.15 * 25.4));
    CHECK(feed_of("G710") == doctest::Approx(3.15));
    CHECK(feed_of("G71") == doctest::Approx(3.15));
    // G70 on a metric control: inch positions, F still mm/min; camgen reads G700 only.
    CHECK(error_of("N10 G17 G90 G94 G70\n" + body, "sinumerik") ==
          "prog.nc:1: G70 sets inch positions but leaves F in the control's base system (mm, machine sinumerik): camgen "
          "reads G700 (positions and feeds) instead");
    std::string refusal;
    try {
        (void)read_program("N10 G17 G90 G94 G71\n" + body, inch, "prog.nc");
    } catch (const InputError& e) {
        refusal = e.what();
    }
    CHECK(refusal ==
          "prog.nc:1: G71 sets mm positions but leaves F in the control's base system (inch, machine sinumerik): camgen "
          "reads G710 (positions and feeds) instead");
}

}  // namespace test_reader_dialects
