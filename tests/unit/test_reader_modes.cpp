// The reader's modes that decide what the control cuts, where it must refuse what it cannot read
// as the control does: the plane of a drilling cycle and of cutter compensation, a lathe's
// diameter mode, a tap cycle's spindle direction, and messages in the program's terms.
// (rs274 facts: /work/shared/reference/rs274/A_g18_g83_drills_along_y, M_comp_lathe_tool_needs_g18,
// O_g74_is_left_tap; the others are quoted where they are checked.)
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "reader_support.hpp"
#include "support.hpp"

namespace test_reader_modes {

using namespace camgen;
using namespace camgen::test;

namespace {

const std::string samples = CAMGEN_SOURCE_DIR "/samples/";

std::string posted(const std::string& sample, const std::string& machine) {
    return post_job(read_file(samples + sample + ".json"), machine).text;
}

// The first difference between the sample's job and its program edited once.
std::string edited_round_trip(const std::string& sample, const std::string& machine, const std::string& from,
                              const std::string& to) {
    const std::string program = replace_once(posted(sample, machine), from, to);
    try {
        return round_trip(read_file(samples + sample + ".json"), program, machine);
    } catch (const InputError& e) {
        return std::string("error: ") + e.what();
    }
}

}  // namespace

TEST_CASE("a drilling cycle outside G17 on a mill is refused, naming the line and the plane") {
    // rs274: G19 G98 G81 X50 Y10 Z-3 R60 rapids along X (it drills along the plane's normal).
    const std::string iso = posted("drilling", "linuxcnc");
    const std::string e = error_of(replace_once(iso, "G98 G82 X10 Y10", "G19 G98 G82 X10 Y10"), "linuxcnc");
    CHECK(e.find("prog.nc:10: G82 under G19") != std::string::npos);
    CHECK(e.find("G82 under G19: it would drill along X") != std::string::npos);
    const std::string fanuc = posted("drilling", "fanuc");
    CHECK(error_of(replace_once(fanuc, "G98 G82 X10.000 Y10.000", "G18 G98 G82 X10.000 Y10.000"), "fanuc")
              .find("G82 under G18: it would drill along Y") != std::string::npos);
    CHECK(error_of(fanuc, "fanuc").empty());
    CHECK(error_of(iso, "linuxcnc").empty());

    const std::string sin = posted("drilling", "sinumerik");
    const std::string s = error_of(replace_once(sin, "N90 MCALL CYCLE82", "N85 G18\nN90 MCALL CYCLE82"), "sinumerik");
    CHECK(s.find("CYCLE82 under G18: it would drill along Y") != std::string::npos);
    CHECK(error_of(sin, "sinumerik").empty());
}

TEST_CASE("G41/G42 outside the plane camgen compensates in is refused") {
    // rs274 (a mill): G41 under G18 offsets in XZ; under G19 "Cutter radius compensation allowed
    // only in XY, XZ planes"; G18 under G41 "Cannot change planes with cutter radius compensation
    // on" (also with G40 in the same block).
    const std::string iso = posted("plate-outline-control", "linuxcnc");
    const std::string under_g18 = error_of(replace_once(iso, "G41 D4 Y-10.3 F500", "G18\nG41 D4 Y-10.3 F500"), "linuxcnc");
    CHECK(under_g18.find("G41 under G18: the control would offset the tool in the XZ plane") != std::string::npos);
    const std::string change = error_of(replace_once(iso, "G41 D4 Y-10.3 F500", "G41 D4 Y-10.3 F500\nG18"), "linuxcnc");
    CHECK(change.find("G18: cannot change planes with cutter radius compensation on") != std::string::npos);
    CHECK(error_of(iso, "linuxcnc").empty());

    const std::string sin = posted("plate-outline-control", "sinumerik");
    CHECK(error_of(replace_once(sin, "N100 G41 Y-10.300", "N95 G19\nN100 G41 Y-10.300"), "sinumerik")
              .find("G41 under G19: the control would offset the tool in the YZ plane") != std::string::npos);
    CHECK(error_of(replace_once(sin, "N100 G41 Y-10.300 F500", "N100 G41 Y-10.300 F500\nN105 G18"), "sinumerik")
              .find("G18 under G41/G42: camgen reads a change of plane only with G40 in force") != std::string::npos);
    CHECK(error_of(sin, "sinumerik").empty());

    // A lathe tool's G41/G42 only under G18 (rs274: "G42 with lathe tool, but plane is not G18").
    const std::string lathe = posted("shaft-control", "linuxcnc-lathe");
    CHECK(error_of(replace_once(lathe, "G42 G1 Z0 F0.1", "G17\nG42 G1 Z0 F0.1"), "linuxcnc-lathe")
              .find("G42 with lathe tool, but plane is not G18 (it is G17)") != std::string::npos);
    CHECK(error_of(lathe, "linuxcnc-lathe").empty());
}

TEST_CASE("a lathe program without its diameter mode word is refused at its first X") {
    // LinuxCNC powers up in G8 (radius): rs274 moves to X46 where the program means a diameter of 46.
    const std::string lc = posted("shaft", "linuxcnc-lathe");
    const std::string e = error_of(replace_once(lc, "G18 G7 G40", "G18 G40"), "linuxcnc-lathe");
    CHECK(e.find("X before G7: machine linuxcnc-lathe programs X as a diameter") != std::string::npos);
    CHECK(error_of(lc, "linuxcnc-lathe").empty());

    const std::string sin = posted("shaft", "sinumerik-lathe");
    CHECK(error_of(replace_once(sin, "N10 G18 DIAMON G40", "N10 G18 G40"), "sinumerik-lathe")
              .find("X before DIAMON: machine sinumerik-lathe programs X as a diameter") != std::string::npos);
    CHECK(error_of(replace_once(sin, "N10 G18 DIAMON G40", "N10 G18 DIAMOF G40"), "sinumerik-lathe").find("DIAMOF (X as a radius)") !=
          std::string::npos);
    CHECK(error_of(sin, "sinumerik-lathe").empty());
}

TEST_CASE("a tap cycle taps with the running spindle: G74 under M3 is a mismatch, M4 before G74 matches") {
    // rs274: "Spindle turning clockwise in G74", "Spindle turning counterclockwise in G84",
    // "Spindle not turning in G74". camgen's post writes M4 before G74.
    const std::string job = R"({"name": "tapping", "units": "mm", "clearance": 20,
 "tools": [{"number": 7, "type": "tap", "diameter": 8, "rpm": 300}, {"number": 8, "type": "tap", "diameter": 6, "rpm": 300}],
 "operations": [{"type": "drill", "tool": 7, "cycle": "tap", "retractPlane": 5, "safeDistance": 3, "endDepth": 12, "pitch": 1.25,
   "holes": [[10, 10], [30, 10]]},
  {"type": "drill", "tool": 8, "cycle": "tap-left", "retractPlane": 5, "safeDistance": 3, "endDepth": 10, "pitch": 1,
   "holes": [[10, 40], [30, 40]]}]})";
    const std::string program = post_job(job, "fanuc").text;
    CHECK(round_trip(job, program, "fanuc").empty());
    const size_t g74 = program.find("G74");
    REQUIRE(g74 != std::string::npos);
    const size_t m4 = program.rfind("M4", g74);
    REQUIRE(m4 != std::string::npos);
    std::string wrong = program;
    wrong[m4 + 1] = '3';
    const std::string e = error_of(wrong, "fanuc");
    CHECK(e.find("G74 with the spindle turning clockwise (M3)") != std::string::npos);
    // With the job it is the program's first difference, at the G74 line.
    const Machine m = load_machine("fanuc");
    bool refused = false;
    try {
        (void)trace_program(read_program(wrong, m, "prog"), m);
    } catch (const ControlRefusal& x) {
        refused = std::string(x.what()).find("G74 with the spindle turning clockwise") != std::string::npos;
    }
    CHECK(refused);
    const size_t g84 = program.find("G84");
    REQUIRE(g84 != std::string::npos);
    const size_t m3 = program.rfind("M3", g84);
    REQUIRE(m3 != std::string::npos);
    std::string wrong84 = program;
    wrong84[m3 + 1] = '4';
    CHECK(error_of(wrong84, "fanuc").find("G84 with the spindle turning counterclockwise (M4)") != std::string::npos);
    std::string off = program;
    off.replace(m3, 2, "M5");
    CHECK(error_of(off, "fanuc").find("G84 with the spindle off") != std::string::npos);
}

TEST_CASE("mismatch positions on a diameter lathe are in the program's terms") {
    const std::string m = edited_round_trip("shaft", "fanuc-lathe", "N280 G71 U1.500", "N280 G71 U2.000");
    CAPTURE(m);
    CHECK(!m.empty());
    CHECK(m.find(" Y") == std::string::npos);
    CHECK(m.find("X44.000") != std::string::npos);
}

TEST_CASE("an arc entry into compensation is camgen's limit, not the control's refusal") {
    // LinuxCNC runs it (/work/shared/reference/rs274/P_comp_entry_arc_r5).
    const std::string iso = posted("plate-outline-control", "linuxcnc");
    const std::string program = replace_once(iso, "G41 D4 Y-10.3 F500", "G1 Y-10.3 F500\nG41 D4");
    const Machine m = load_machine("linuxcnc");
    std::string e;
    try {
        (void)trace_program(read_program(program, m, "prog"), m);
    } catch (const InputError& x) {
        e = x.what();
    }
    CAPTURE(e);
    CHECK(e.find("camgen cannot model this: an arc as the first move after G41/G42") != std::string::npos);
    CHECK(e.find("the control refuses") == std::string::npos);
}

TEST_CASE("words GRBL 1.1 refuses are refused on grbl and read as before elsewhere") {
    // grbl.json: cutterCompensation false, lengthOffsetH, returnLevels and arcTurns false.
    const std::string grbl = posted("arcs", "grbl");
    CHECK(error_of(grbl, "grbl").empty());
    const std::string before = "G1 Z-1 F100\nG3 X10 Y10 I-10 J0 F300";
    CHECK(error_of(replace_once(grbl, before, "G98\n" + before), "grbl").find("G98: machine grbl has no canned cycle return levels") !=
          std::string::npos);
    CHECK(error_of(replace_once(grbl, before, "G43 H5\n" + before), "grbl").find("G43: machine grbl takes no tool length offset") !=
          std::string::npos);
    CHECK(error_of(replace_once(grbl, before, "G41 D5\n" + before), "grbl").find("G41: machine grbl has no cutter radius compensation") !=
          std::string::npos);
    CHECK(error_of(replace_once(grbl, "G3 X10 Y10 I-10 J0 F300", "G3 X10 Y10 I-10 J0 P1 F300"), "grbl")
              .find("P1 on an arc: machine grbl takes no number of turns") != std::string::npos);

    // LinuxCNC: P1 on an arc is one turn, the same arc; G98 alone is read.
    const std::string lc = posted("arcs", "linuxcnc");
    const std::string arc = lc.substr(lc.find("G3 X10 Y10"), lc.find('\n', lc.find("G3 X10 Y10")) - lc.find("G3 X10 Y10"));
    CHECK(round_trip(read_file(samples + "arcs.json"), replace_once(lc, arc, arc + " P1"), "linuxcnc").empty());
    CHECK(error_of(replace_once(lc, arc, "G98\n" + arc), "linuxcnc").empty());
}

TEST_CASE("G41 without D: LinuxCNC offsets by the tool in the spindle, other ISO mills refuse it") {
    // rs274 (tool table T1 D0.3937 in = 10 mm): T1 M6 G41 then G1 X20 Y0 from X0 Y0 feeds to X15 Y5,
    // the loaded tool's radius to the left.
    const std::string job = read_file(samples + "plate-outline-control.json");
    const std::string lc = posted("plate-outline-control", "linuxcnc");
    CHECK(round_trip(job, replace_once(lc, "G41 D4 Y-10.3 F500", "G41 Y-10.3 F500"), "linuxcnc").empty());
    const std::string fanuc = posted("plate-outline-control", "fanuc");
    CHECK(error_of(replace_once(fanuc, "G41 D4 Y-10.300 F500", "G41 Y-10.300 F500"), "fanuc").find("G41 without its offset number D") !=
          std::string::npos);
}

}  // namespace test_reader_modes
