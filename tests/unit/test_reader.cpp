// The reader: words and codes of each dialect, errors that name the line, canned cycles read
// with the posts' semantics, and the round-trip check catching deliberately broken programs.
#include <cmath>
#include <numbers>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/analysis/stats.hpp"
#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_reader {

using namespace camgen;
using namespace camgen::test;

namespace {

const std::string d_arc_job = R"({"name": "darc", "units": "mm", "clearance": 5,
 "tools": [{"number": 1, "type": "end-mill", "diameter": 4, "rpm": 2000}],
 "operations": [{"type": "path", "tool": 1, "z": -1, "feed": 300, "start": [0, 0],
   "path": [{"line": [10, 0]}, {"arc": {"end": [20, 10], "centre": [10, 10], "direction": "ccw"}}, {"line": [20, 0]}]}]})";

std::vector<Event> motion_events(const std::vector<ReadEvent>& events) {
    std::vector<Event> out;
    for (const ReadEvent& e : events)
        if (!std::holds_alternative<Comment>(e.event)) out.push_back(e.event);
    return out;
}

}  // namespace

// ---- the three defects the round trip must catch ----

TEST_CASE("round trip catches a post that forgets its modal X/Y after an nccad D-arc") {
    std::string good = post_job(d_arc_job, "wabeco").text;
    // The arc ends at (20,10). A post that still believed it was at (10,0) would write the
    // line to (20,0) as "X20" (Y0 "unchanged"): the control would stay at (20,10).
    REQUIRE(good.find("G03 D90 I0 J10\nG01 Y0\n") != std::string::npos);
    CHECK(round_trip(d_arc_job, good, "wabeco") == "");
    std::string broken = replace_once(good, "G03 D90 I0 J10\nG01 Y0\n", "G03 D90 I0 J10\nG01 X20\n");
    std::string m = round_trip(d_arc_job, broken, "wabeco");
    CHECK(m == "line 14: the job's feed move from X20.000 Y10.000 Z-1.000 to X20.000 Y0.000 Z-1.000 is not in the "
               "program (there the program has a rapid move from X20.000 Y10.000 Z-1.000 to X20.000 Y10.000 Z5.000)");
}

TEST_CASE("round trip catches a word dropped on a later hole") {
    std::string job = read_file(CAMGEN_SOURCE_DIR "/samples/plate.json");
    SUBCASE("fanuc canned G81: Y dropped on the fourth hole") {
        std::string good = post_job(job, "fanuc").text;
        CHECK(round_trip(job, good, "fanuc") == "");
        std::string broken = replace_once(good, "N55 X90.000 Y40.000\n", "N55 X90.000\n");
        std::string m = round_trip(job, broken, "fanuc");
        // Line 14 drills the fourth hole where the third was.
        CHECK(m == "line 14: the job's rapid move from X90.000 Y10.000 Z2.000 to X90.000 Y40.000 Z2.000 is not in the "
                   "program (there the program has a feed move from X90.000 Y10.000 Z2.000 to X90.000 Y10.000 Z-1.500)");
    }
    SUBCASE("wabeco G79: Y dropped on the fourth hole") {
        std::string good = post_job(job, "wabeco").text;
        CHECK(round_trip(job, good, "wabeco") == "");
        std::string broken = replace_once(good, "G79 X90 Y40\n", "G79 X90\n");
        std::string m = round_trip(job, broken, "wabeco");
        CHECK(m.starts_with("line 14: the job's rapid move from X90.000 Y10.000 Z2.000 to X90.000 Y40.000 Z2.000 is not in the program"));
    }
    SUBCASE("sinumerik MCALL CYCLE81: Y dropped on the fourth hole line") {
        std::string good = post_job(job, "sinumerik").text;
        CHECK(round_trip(job, good, "sinumerik") == "");
        std::string broken = replace_once(good, "N130 X90.000 Y40.000\n", "N130 X90.000\n");
        std::string m = round_trip(job, broken, "sinumerik");
        CHECK(m.starts_with("line 16: the job's rapid move from X90.000 Y10.000 Z2.000 to X90.000 Y40.000 Z2.000 is not in the program"));
    }
    SUBCASE("heidenhain cycle 200: Y dropped on the fourth M99 call") {
        std::string good = post_job(job, "heidenhain").text;
        CHECK(round_trip(job, good, "heidenhain") == "");
        std::string broken = replace_once(good, "12 L X+90 Y+40 R0 FMAX M99\n", "12 L X+90 R0 FMAX M99\n");
        std::string m = round_trip(job, broken, "heidenhain");
        CHECK(m.starts_with("line 21: the job's rapid move from X90.000 Y10.000 Z2.000 to X90.000 Y40.000 Z2.000 is not in the program"));
    }
}

TEST_CASE("round trip catches a wrong arc direction") {
    std::string job = read_file(CAMGEN_SOURCE_DIR "/samples/bracket.json");
    SUBCASE("fanuc: a 90 degree G3 written as G2 (same end and centre, the long way round)") {
        std::string good = post_job(job, "fanuc").text;
        CHECK(round_trip(job, good, "fanuc") == "");
        std::string m = round_trip(job, replace_once(good, "G3 X70.000 Y10.000", "G2 X70.000 Y10.000"), "fanuc");
        CHECK(m == "line 12: the job's ccw arc from X60.000 Y0.000 Z-3.000 to X70.000 Y10.000 Z-3.000 about X60.000 Y10.000 "
                   "Z-3.000 is not in the program (there the program has a cw arc from X60.000 Y0.000 Z-3.000 to X70.000 "
                   "Y10.000 Z-3.000 about X60.000 Y10.000 Z-3.000)");
    }
    SUBCASE("fanuc: a full circle the other way round (every point on the circle, order wrong)") {
        std::string good = post_job(job, "fanuc").text;
        std::string m = round_trip(job, replace_once(good, "G2 X38.000 Y25.000 I-8.000", "G3 X38.000 Y25.000 I-8.000"), "fanuc");
        CHECK(m.starts_with("line 21: the job's cw arc from X38.000 Y25.000 Z-3.000 to X38.000 Y25.000 Z-3.000"));
    }
    SUBCASE("wabeco: G03 D90 written as G02 D90") {
        std::string good = post_job(job, "wabeco").text;
        CHECK(round_trip(job, good, "wabeco") == "");
        std::string m = round_trip(job, replace_once(good, "G03 D90 I0 J10", "G02 D90 I0 J10"), "wabeco");
        CHECK(m.starts_with("line 12: the job's ccw arc from X60.000 Y0.000 Z-3.000 to X70.000 Y10.000 Z-3.000"));
    }
    SUBCASE("sinumerik: G3 written as G2") {
        std::string good = post_job(job, "sinumerik").text;
        CHECK(round_trip(job, good, "sinumerik") == "");
        std::string m = round_trip(job, replace_once(good, "G3 X70.000 Y10.000", "G2 X70.000 Y10.000"), "sinumerik");
        CHECK(m.starts_with("line 12: the job's ccw arc from X60.000 Y0.000 Z-3.000 to X70.000 Y10.000 Z-3.000"));
    }
    SUBCASE("heidenhain: DR+ flipped to DR-") {
        std::string good = post_job(job, "heidenhain").text;
        CHECK(round_trip(job, good, "heidenhain") == "");
        std::string m = round_trip(job, replace_once(good, "C X+70 Y+10 DR+", "C X+70 Y+10 DR-"), "heidenhain");
        CHECK(m.starts_with("line 11: the job's ccw arc from X60.000 Y0.000 Z-3.000 to X70.000 Y10.000 Z-3.000"));
    }
}

TEST_CASE("round trip catches a wrong feed, a missing dwell and a different tool") {
    std::string job = read_file(CAMGEN_SOURCE_DIR "/samples/plate.json");
    std::string good = post_job(job, "fanuc").text;
    CHECK(round_trip(job, replace_once(good, "R1.000 F120", "R1.000 F130"), "fanuc").find("130.000 mm/min") !=
          std::string::npos);
    CHECK(round_trip(job, replace_once(good, "N85 T2 M6", "N85 T3 M6"), "fanuc") ==
          "line 22: the program changes to tool 3, the job to tool 2");
    CHECK(round_trip(job, replace_once(good, "Z-9.803 R1.000", "Z-9.903 R1.000"), "fanuc") != "");
}

// ---- errors name the line ----

TEST_CASE("an unknown word or code is an error naming the line") {
    std::string fanuc = "%\nO1000\nN10 G17 G21 G90 G94\nN15 T1 M6\nN20 G0 X1.000 Y2.000 W3.000\n";
    CHECK(error_of(fanuc, "fanuc") == "prog.nc:5: unknown word W3.000");
    CHECK(error_of("%\nN10 G17 G21 G90 G94\nN15 G12 X1.000\n", "fanuc") == "prog.nc:3: unknown code G12");
    CHECK(error_of("%\nN10 M98\n", "fanuc") == "prog.nc:2: unknown code M98");
    CHECK(error_of("_\n_\nG90\nG00 X0 Y0 Z5\nG05 X1\n", "wabeco") == "prog.nc:5: unknown code G05");
    CHECK(error_of("_\n_\nG90\nG00 X0 Y0 Q5\n", "wabeco") == "prog.nc:4: unknown word Q5");
    CHECK(error_of("_\n_\nG90\nM10 O7.1\n", "wabeco").starts_with("prog.nc:4: M10 O7.1: only output 6"));
    // A word the dialect knows but that means nothing in this block.
    CHECK(error_of("%\nN10 G17 G21 G90 G94\nN15 T1 M6\nN20 G0 X1.000 Y2.000 Z3.000 Q1.000\n", "fanuc") ==
          "prog.nc:4: Q1.000 has no meaning in this block");
    // A canned cycle the machine does not have (wabeco has only G81).
    CHECK(error_of("_\n_\nG90\nG00 X0 Y0 Z5\nG83 X1 Y1 Z-5 B2 F10\n", "wabeco") == "prog.nc:5: unknown code G83");
}

TEST_CASE("numbers: decimal comma, missing decimal point, exponent") {
    std::string head = "%\nN10 G17 G21 G90 G94\nN15 T1 M6\n";
    CHECK(error_of(head + "N20 G0 X12,530 Y0.000 Z5.000\n", "fanuc").starts_with("prog.nc:4: X12,...: machine fanuc writes '.'"));
    CHECK(error_of(head + "N20 G0 X10 Y0.000 Z5.000\n", "fanuc") ==
          "prog.nc:4: X10 has no decimal point: machine fanuc always writes one, and a Fanuc-style control reads X10 as 0.01 mm");
    CHECK(error_of(head + "N20 G0 X1.18e+06 Y0.000 Z5.000\n", "fanuc")== "prog.nc:4: unknown word e+06");
    // Without a decimal point where the format allows it: nccad writes X10.
    CHECK_NOTHROW(read_program("_\n_\nG90\nG00 X10 Y0 Z5\nG99\n", load_machine("wabeco")));
}

TEST_CASE("motion the machine cannot make, or from an unknown position, is an error") {
    std::string head = "%\nN10 G17 G21 G90 G94\nN15 T1 M6\nN20 S1000 M3\n";
    CHECK(error_of(head + "N25 G1 X1.000 Y1.000 Z1.000 F100\n", "fanuc").starts_with("prog.nc:5: a feed move from an unknown position"));
    CHECK(error_of(head + "N25 G0 X0.000 Y0.000 Z0.000\nN30 G1 X5.000\n", "fanuc") == "prog.nc:6: a feed move without a feed (F)");
    // Both radii of an arc must agree: I/J that do not describe the end are caught.
    CHECK(error_of(head + "N25 G0 X0.000 Y0.000 Z0.000\nN30 G2 X10.000 Y0.000 I4.000 J0.000 F100\n", "fanuc")
              .starts_with("prog.nc:6: the arc's end is not on its circle"));
    // wabeco: arcs only in XY, at most 180 degrees a block, no helices.
    std::string nccad = "_\n_\nG90\nM01 Insert tool 1, spindle 1000 rpm\nM10 O6.1\nG00 X0 Y0\nG00 Z0\n";
    CHECK(error_of(nccad + "G02 D270 I5 J0 F10\n", "wabeco").starts_with("prog.nc:8: an arc of 270.000 degrees in one block"));
    CHECK(error_of(nccad + "G02 X10 Y0 Z-1 I5 J0 F10\n", "wabeco") == "prog.nc:8: a helical arc: machine wabeco makes no helices");
    // The classic nccad form needs the whole end point.
    CHECK(error_of(nccad + "G02 X10 I5 J0 F10\n", "wabeco").starts_with("prog.nc:8: G02 without both X and Y"));
    CHECK(error_of(nccad + "G79 X5 Y5\n", "wabeco") == "prog.nc:8: G79 without a G81 before it");
}

// ---- what the dialects read ----

TEST_CASE("nccad: D-form and classic arcs, feeds in 0.1 mm/s, dwell in 1/18 s, tool messages") {
    Machine m = load_machine("wabeco");
    auto events = read_program("_\n_\n; t\nG90\nM01 Insert tool 4 6 mm end mill - carbide, spindle 3000 rpm\nM10 O6.1\n"
                               "G00 X10 Y0\nG00 Z2\nG01 Z-1 F10\nG03 D90 I-10 J0\nG02 X10 Y0 I0 J-10\nM30 P9\n"
                               "M10 O6.0\nG77\nG99\n",
                               m);
    std::vector<Event> ev = motion_events(events);
    REQUIRE(ev.size() == 8);
    CHECK(std::get<ToolChange>(ev[0]) == ToolChange{4, 6.0, "6 mm end mill - carbide"});
    CHECK(std::get<Spindle>(ev[1]) == Spindle{SpindleState::cw, 3000});
    CHECK(events[3].from_unknown);  // the first rapid after the tool change (after the comment and two events)
    CHECK(std::get<Rapid>(ev[2]).to == Vec3{10, 0, 2});
    // F10 in 0.1 mm/s = 1 mm/s = 60 mm/min.
    CHECK(std::get<Linear>(ev[3]) == Linear{{10, 0, -1}, 60.0});
    // 90 deg ccw about (0,0) from (10,0): ends at (0,10); the control computes it.
    const Arc& a = std::get<Arc>(ev[4]);
    CHECK(a.to.x == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(a.to.y == doctest::Approx(10.0));
    CHECK(a.centre == Vec3{0, 0, -1});
    CHECK(a.direction == ArcDirection::ccw);
    // The control computes the D-arc's end: its uncertainty grows; the classic form states it.
    CHECK(events[5].uncertainty > 0.0);
    CHECK(events[5].uncertainty < 0.002);
    CHECK(events[6].uncertainty == 0.0);
    // The classic form: end written, I/J relative to the start (0,10) -> centre (0,0).
    const Arc& b = std::get<Arc>(ev[5]);
    CHECK(b.to == Vec3{10, 0, -1});
    CHECK(b.centre.x == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(b.centre.y == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(b.direction == ArcDirection::cw);
    CHECK(std::get<Dwell>(ev[6]).seconds == doctest::Approx(0.5));
    CHECK(std::get<Spindle>(ev[7]) == Spindle{SpindleState::off, 0});
}

TEST_CASE("nccad G81/G79: B is the retract plane and the feed starts there") {
    Machine m = load_machine("wabeco");
    auto events = read_program("_\n_\nG90\nM01 Insert tool 1, spindle 1000 rpm\nM10 O6.1\nG00 X10 Y10\nG00 Z10\nG00 Z2\n"
                               "G81 X10 Y10 Z-1.5 B2 F13.3\nG79 X50 Y10\nG00 Z10\nG99\n",
                               m);
    Trace t = trace_program(events, m);
    REQUIRE(t.holes.size() == 2);
    CHECK(t.holes[1].at == Vec2{50, 10});
    CHECK(t.holes[1].bottom_z == -1.5);
    CHECK(t.holes[1].line == 10);
    // Hole 1 from Z2: feed to -1.5 at 13.3 x 6 = 79.8 mm/min, rapid to B2. Hole 2: across at
    // B, feed down, rapid up.
    std::vector<std::string> seen;
    for (const Step& s : t.steps)
        if (s.kind == StepKind::rapid || s.kind == StepKind::feed)
            seen.push_back(fmt::format("{} {:g} {:g} {:g} {:g}", s.kind == StepKind::rapid ? "G0" : "G1", s.to.x, s.to.y, s.to.z,
                                       s.feed));
    CHECK(seen == std::vector<std::string>{"G0 10 10 10 0", "G0 10 10 2 0", "G1 10 10 -1.5 79.8", "G0 10 10 2 0",
                                           "G0 50 10 2 0", "G1 50 10 -1.5 79.8", "G0 50 10 2 0", "G0 50 10 10 0"});
}

TEST_CASE("iso canned cycles: G98 returns to the initial Z, G99 to R, G83 pecks to R, sticky words") {
    Machine m = load_machine("fanuc");
    std::string head = "%\nO1000\nN10 G17 G21 G90 G94\nN15 T1 M6\nN20 S1000 M3\nN25 G0 X0.000 Y0.000\nN30 G43 Z10.000 H1\n";
    auto moves = [&](const std::string& body) {
        Trace t = trace_program(read_program(head + body + "N90 M30\n", m), m);
        std::vector<std::string> seen;
        for (const Step& s : t.steps)
            if ((s.kind == StepKind::rapid || s.kind == StepKind::feed) && s.from_known)
                seen.push_back(fmt::format("{} {:g} {:g} {:g}", s.kind == StepKind::rapid ? "G0" : "G1", s.to.x, s.to.y, s.to.z));
        return seen;
    };
    // G98 from Z10 with R2: back to 10 between holes; the second hole needs only X/Y.
    CHECK(moves("N35 G98 G81 X5.000 Y0.000 Z-3.000 R2.000 F100\nN40 X15.000\nN45 G80\n") ==
          std::vector<std::string>{"G0 5 0 10", "G0 5 0 2", "G1 5 0 -3", "G0 5 0 10", "G0 15 0 10", "G0 15 0 2", "G1 15 0 -3",
                                   "G0 15 0 10"});
    // G99: back to R.
    CHECK(moves("N35 G99 G81 X5.000 Y0.000 Z-3.000 R2.000 F100\nN40 X15.000\nN45 G80\n") ==
          std::vector<std::string>{"G0 5 0 10", "G0 5 0 2", "G1 5 0 -3", "G0 5 0 2", "G0 15 0 2", "G1 15 0 -3", "G0 15 0 2"});
    // G83 Q3 from R2 to Z-7 (fanuc peck clearance 1 mm): feed to -1, rapid to R, rapid to 0,
    // feed to -4, rapid to R, rapid to -3, feed to -7, rapid out.
    CHECK(moves("N35 G99 G83 X0.000 Y0.000 Z-7.000 R2.000 Q3.000 F100\nN40 G80\n") ==
          std::vector<std::string>{"G0 0 0 2", "G1 0 0 -1", "G0 0 0 2", "G0 0 0 0", "G1 0 0 -4", "G0 0 0 2", "G0 0 0 -3",
                                   "G1 0 0 -7", "G0 0 0 2"});
    // G82 P500 on fanuc: P in ms.
    auto ev = read_program(head + "N35 G99 G82 X0.000 Y0.000 Z-2.000 R2.000 P500 F100\nN40 G80\nN45 M30\n", m);
    Trace t = trace_program(ev, m);
    bool dwell = false;
    for (const Step& s : t.steps)
        if (s.kind == StepKind::dwell) dwell = s.seconds == doctest::Approx(0.5);
    CHECK(dwell);
    CHECK(error_of(head + "N35 G99 G83 X0.000 Y0.000 Z-7.000 R2.000 F100\n", "fanuc") == "prog.nc:8: G83 without its peck depth Q");
    CHECK(error_of(head + "N35 G99 G81 X0.000 Y0.000 Z-7.000 R2.000 Q1.000 F100\n", "fanuc")
              .starts_with("prog.nc:8: Q1.000: G81 on machine fanuc takes no peck depth Q"));
}

TEST_CASE("iso arcs: R with sign, absolute centre, XZ plane, inch") {
    std::string head = "%\nN10 G17 G21 G90 G94\nN15 T1 M6\nN20 S1000 M3\nN25 G0 X10.000 Y0.000 Z0.000\n";
    Machine m = load_machine("fanuc");
    auto arc_of = [&](const Machine& mm, const std::string& block) {
        auto ev = read_program(head + block + "N90 M30\n", mm);
        return std::get<Arc>(ev.back().event);
    };
    // R10 from (10,0) to (0,10) ccw: 90 deg, centre (0,0). R-10: 270 deg, centre (10,10).
    Arc a = arc_of(m, "N30 G3 X0.000 Y10.000 R10.000 F100\n");
    CHECK(a.centre.x == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(a.centre.y == doctest::Approx(0.0).epsilon(1e-12));
    Arc b = arc_of(m, "N30 G3 X0.000 Y10.000 R-10.000 F100\n");
    CHECK(b.centre.x == doctest::Approx(10.0));
    CHECK(b.centre.y == doctest::Approx(10.0));
    // The same for cw: R10 centre (10,10), R-10 centre (0,0).
    CHECK(arc_of(m, "N30 G2 X0.000 Y10.000 R10.000 F100\n").centre.x == doctest::Approx(10.0));
    // Absolute centre on a machine that says so.
    Machine abs = m;
    abs.arcs.format = ArcFormat::ijk_absolute;
    Arc c = arc_of(abs, "N30 G3 X0.000 Y10.000 I0.000 J0.000 F100\n");
    CHECK(c.centre == Vec3{0, 0, 0});
    // XZ: I and K, centre relative to the start.
    Arc d = arc_of(m, "N30 G18 G2 X0.000 Z10.000 I-10.000 K0.000 F100\n");
    CHECK(d.plane == Plane::xz);
    CHECK(d.centre == Vec3{0, 0, 0});
    // G20: lengths in inch, feeds in in/min.
    auto ev = read_program("%\nN10 G17 G20 G90 G94\nN15 T1 M6\nN20 G0 X1.0000 Y0.0000 Z0.0000\nN25 G1 X2.0000 F10.0\nN30 M30\n",
                           [] { Machine i = load_machine("fanuc"); i.units = Units::inch; return i; }());
    CHECK(std::get<Linear>(ev.back().event).to.x == doctest::Approx(50.8));
    CHECK(std::get<Linear>(ev.back().event).feed == doctest::Approx(254.0));
}

// ---- statistics ----

TEST_CASE("machining time of a simple program, worked out by hand") {
    // fanuc: maxFeed 10000, rapidRate 15000 mm/min.
    std::string program =
        "%\n"
        "O1000\n"
        "N10 G17 G21 G90 G94\n"
        "N15 T1 M6\n"
        "N20 S1000 M3\n"
        "N25 G0 X0.000 Y0.000\n"     // from the tool-change position: not measured
        "N30 G43 Z5.000 H1\n"
        "N35 G1 Z-1.000 F60\n"       // 6 mm at 60 mm/min = 6 s
        "N40 X100.000 F20000\n"      // 100 mm at 20000, clamped to 10000 mm/min = 0.6 s
        "N45 G4 P1500\n"             // 1.5 s (P in ms on fanuc)
        "N50 G0 Z5.000\n"            // 6 mm at 15000 mm/min = 0.024 s
        "N55 X0.000\n"               // 100 mm at 15000 mm/min = 0.4 s
        "N60 M5\n"
        "N65 M30\n"
        "%\n";
    Machine m = load_machine("fanuc");
    ProgramStats st = compute_stats(trace_program(read_program(program, m), m), m);
    CHECK(st.feed_length == doctest::Approx(106.0));
    CHECK(st.rapid_length == doctest::Approx(106.0));
    CHECK(st.unmeasured_rapids == 1);
    CHECK(st.feed_time == doctest::Approx(6.0 + 0.6));
    CHECK(st.rapid_time == doctest::Approx(0.024 + 0.4));
    CHECK(st.dwell_time == doctest::Approx(1.5));
    CHECK(st.total_time() == doctest::Approx(8.524));
    CHECK(st.clamped_feeds == 1);
    CHECK(*st.lowest_z == -1.0);
    CHECK(st.holes == 0);  // the plunge is followed by a cut, not a retract
    REQUIRE(st.tools.size() == 1);
    CHECK(st.tools[0].box.min == Vec3{0, 0, -1});
    CHECK(st.tools[0].box.max == Vec3{100, 0, 5});
}

TEST_CASE("an arc's bounding box includes its extremes") {
    Step s;
    s.kind = StepKind::feed;
    s.from = {10, 0, 0};
    s.to = {0, -10, 0};
    s.arc = resolve_arc(s.from, Arc{s.to, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 100, 0});  // 270 deg
    Box b = box_of(s);
    CHECK(b.min.x == doctest::Approx(-10));
    CHECK(b.max.y == doctest::Approx(10));
    CHECK(b.min.y == doctest::Approx(-10));
    CHECK(b.max.x == doctest::Approx(10));
}

TEST_CASE("arcs compare as positions visited: split, linearized, or slightly off") {
    // A helix and an XZ arc: wabeco writes both as chords, fanuc as arcs. Either reads back
    // as the motion of the events, within the chord tolerance inside the arc.
    std::vector<Event> events{ToolChange{1, 6, ""}, Spindle{SpindleState::cw, 1000}, Rapid{{10, 0, 5}}, Linear{{10, 0, 0}, 300},
                              Arc{{-10, 0, -2}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 300, 1},
                              Arc{{-20, 0, 8}, {-20, 0, -2}, ArcDirection::cw, Plane::xz, 300, 0}, Rapid{{-20, 0, 10}},
                              Spindle{SpindleState::off, 0}};
    for (const char* name : {"wabeco", "fanuc"}) {
        CAPTURE(name);
        Machine m = load_machine(name);
        std::ostringstream out;
        auto post = make_post(m, out, PostOptions{});
        post->open();
        for (const Event& e : events) post->emit(e);
        post->close();
        Trace actual = trace_program(read_program(out.str(), m), m);
        Trace expected = trace_events(events, m);
        auto mismatch = compare_traces(expected, actual, compare_tolerance(m));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        // One end point moved by 0.002 mm is a mismatch at 0.001 mm.
        std::string text = out.str();
        size_t at = text.find("X-20");
        REQUIRE(at != std::string::npos);
        size_t end = text.find_first_of(" \n", at);
        text.replace(at, end - at, "X-20.002");
        if (m.name == "fanuc") {
            CHECK(compare_traces(expected, trace_program(read_program(text, m), m), compare_tolerance(m)));
        }
    }
}

TEST_CASE("block styles: no separator, decimal comma, sequence numbers, CRLF") {
    // The reader splits words by letter, so a machine that writes "N10G0X10,5Y2" reads back.
    for (const char* name : {"fanuc", "wabeco"}) {
        for (const char* sample : {"plate", "bracket"}) {
            CAPTURE(name);
            CAPTURE(sample);
            Machine m = load_machine(name);
            m.block.separator = "";
            m.decimal_mark = ',';
            m.block.sequence_numbers = true;
            m.block.line_break = "\r\n";
            Job job = read_job(read_file(std::string(CAMGEN_SOURCE_DIR "/samples/") + sample + ".json"), "job.json");
            std::ostringstream out;
            auto post = make_post(m, out, PostOptions{});
            post->open();
            expand_job(job, *post);
            post->close();
            std::string text = out.str();
            CHECK(text.find("X10,5") == std::string::npos);  // (no half millimetres in the samples)
            CHECK(text.find("\r\nN") != std::string::npos);
            auto mismatch = compare_traces(trace_expected(expand_job(job), m), trace_program(read_program(text, m), m), compare_tolerance(m, 0.0));
            CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        }
    }
    Machine m = load_machine("fanuc");
    m.block.separator = "";
    m.decimal_mark = ',';
    auto ev = read_program("%\nN10G17G21G90G94\nN15T1M6\nN20G0X10,500Y-2,250Z5,000\nN25M30\n", m);
    CHECK(std::get<Rapid>(ev.back().event).to == Vec3{10.5, -2.25, 5.0});
}

TEST_CASE("every canned cycle of fanuc reads back as the motion of the job's longhand cycle") {
    // G82 P, G83 Q under G98 with R below the retract plane, G73, G85, G86 (spindle stop and
    // restart), G89 P, G84 (spindle reversal, F = pitch x rpm), and a degressive peck that
    // fanuc writes longhand. The reader expands each canned cycle with longhand_moves.
    const std::string job = R"({"name": "cycles", "clearance": 10,
 "tools": [{"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}, {"number": 2, "type": "tap", "diameter": 6, "rpm": 300}],
 "operations": [
  {"type": "drill", "tool": 1, "cycle": "dwell", "retractPlane": 2, "endDepth": 2, "plungingFeedrate": 100, "bottomDwell": 0.5, "holes": [[0,0],[10,0]]},
  {"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 5, "safeDistance": 1, "endDepth": 7, "firstDepth": 2.5, "plungingFeedrate": 100, "holes": [[0,10],[10,10]]},
  {"type": "drill", "tool": 1, "cycle": "chip-break", "retractPlane": 2, "endDepth": 7, "firstDepth": 3, "plungingFeedrate": 100, "holes": [[0,20],[10,20]]},
  {"type": "drill", "tool": 1, "cycle": "ream", "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0,30]]},
  {"type": "drill", "tool": 1, "cycle": "bore-stop", "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0,40]]},
  {"type": "drill", "tool": 1, "cycle": "bore-dwell", "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 100, "bottomDwell": 1, "holes": [[0,50]]},
  {"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 2, "endDepth": 9, "firstDepth": 3, "degressionType": "value", "degression": 0.5, "minimumDepth": 1, "plungingFeedrate": 100, "holes": [[20,0]]},
  {"type": "drill", "tool": 2, "cycle": "tap", "retractPlane": 5, "safeDistance": 2, "endDepth": 8, "pitch": 1, "holes": [[30,0],[30,10]]}
 ]})";
    std::string program = post_job(job, "fanuc").text;
    for (const char* code : {"G82 ", "G83 ", "G73 ", "G85 ", "G86 ", "G89 ", "G84 "}) CHECK(program.find(code) != std::string::npos);
    CHECK(round_trip(job, program, "fanuc") == "");
    // A dwell of 0.6 s where the job asks 0.5 s is caught.
    CHECK(round_trip(job, replace_once(program, "P500", "P600"), "fanuc").find("dwell") != std::string::npos);
}

}  // namespace test_reader
