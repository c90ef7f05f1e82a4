// The lathe machines' own words: fanuc-lathe's T0101, G50 S / G97 S, G98/G99 and two-block
// G74 with Q in least increments; linuxcnc-lathe's G17 ... G18 around its cycles; and the
// readers' refusals of what those controls would read differently.
#include <doctest/doctest.h>

#include <regex>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "lathe_support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_lathe_posts {

using namespace camgen;

namespace {

// One turn-drill on a 10 mm drill at 800 rpm from Z0 to Z-20, feed from Z2, retract Z5.
std::string job(const std::string& extra) {
    return R"({"clearance": 20, "tools": [{"number": 3, "diameter": 10, "rpm": 800}],
  "operations": [{"type": "turn-drill", "tool": 3, "startDepth": 0, "endDepth": -20, "safeDistance": 2,
                  "retractDistance": 5)" +
           extra + "}]}";
}

std::string post(const std::string& extra, const std::string& machine) {
    return test::post_program(read_job(job(extra), "t.json"), load_machine(machine));
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("fanuc-lathe: T0101, G50 S<maxRpm> then G97 S M3, G99 and feeds per revolution") {
    const std::string text = post(R"(, "feedMode": "per-revolution", "plungingFeedrate": 0.1234)", "fanuc-lathe");
    INFO(text);
    CHECK(has(text, "N15 G99\n"));
    CHECK(has(text, " T0303\n"));
    CHECK(has(text, " G50 S3000\n"));
    CHECK(has(text, " G97 S800 M3\n"));
    CHECK(text.find("G50") < text.find("G97"));
    // Four decimals: a tenth of a micrometre per revolution is 0.4 mm/min at 4000 rpm.
    CHECK(has(text, " G1 Z-20.000 F0.1234\n"));
    CHECK_FALSE(has(text, "G90"));  // system A: G90 is a turning cycle
    CHECK_FALSE(has(text, "M6"));
}

TEST_CASE("fanuc-lathe: chip-break pecks are the two-block G74, Q in micrometres without a decimal point") {
    const std::string text = post(R"(, "plungingFeedrate": 90, "firstPeckDepth": 4.5, "peckRetract": 0.8)", "fanuc-lathe");
    INFO(text);
    // The start point X0 Z2 (safeDistance), R(e) = peckRetract, Q = 4.5 mm = 4500 um, back to Z5.
    CHECK(has(text, " X0.000\n"));
    CHECK(has(text, " Z2.000\n"));
    CHECK(has(text, " G74 R0.800\n"));
    CHECK(has(text, " G74 Z-20.000 Q4500 F90\n"));
    CHECK(text.find("G74 Z") < text.find("G0 Z5.000"));
    // It reads back as the pecks the job asked for.
    const std::vector<ReadEvent> back = read_program(text, load_machine("fanuc-lathe"), "t.nc");
    const DrillCycle* c = nullptr;
    for (const ReadEvent& e : back)
        if (auto* d = std::get_if<DrillCycle>(&e.event)) c = d;
    REQUIRE(c != nullptr);
    CHECK(c->kind == CycleKind::chip_break);
    CHECK(c->safe_z == doctest::Approx(2));
    CHECK(c->bottom_z == doctest::Approx(-20));
    CHECK(*c->values.get(DrillField::first_depth) == doctest::Approx(4.5));
    CHECK(*c->values.get(DrillField::pecking_retract) == doctest::Approx(0.8));
    // Full-retract pecks (no peckRetract) have no Fanuc T cycle here: longhand.
    const std::string deep = post(R"(, "plungingFeedrate": 90, "firstPeckDepth": 4.5)", "fanuc-lathe");
    CHECK_FALSE(has(deep, "G74"));
    CHECK(has(deep, " G1 Z-2.500 F90\n"));
}

TEST_CASE("fanuc-lathe: the reader refuses a G74 Q with a decimal point; reads a turret call of another offset") {
    const Machine m = load_machine("fanuc-lathe");
    std::string text = post(R"(, "plungingFeedrate": 90, "firstPeckDepth": 4.5, "peckRetract": 0.8)", "fanuc-lathe");
    std::string dotted = text;
    dotted.replace(dotted.find("Q4500"), 5, "Q4.5");
    CHECK_THROWS_WITH_AS(read_program(dotted, m, "t.nc"), doctest::Contains("least input increments"), InputError);
    std::string offset = text;
    offset.replace(offset.find("T0303"), 5, "T0304");
    // Tool 3 with offset 04 is read (verify --job finds it is not the post's T0303:
    // test_verify_offsets.cpp); a call without an offset number is refused.
    bool called = false;
    for (const ReadEvent& e : read_program(offset, m, "t.nc"))
        if (std::holds_alternative<Rapid>(e.event)) called = called || e.offsets.length == "T0304";
    CHECK(called);
    std::string bare = text;
    bare.replace(bare.find("T0303"), 5, "T03");
    CHECK_THROWS_WITH_AS(read_program(bare, m, "t.nc"), doctest::Contains("T03: machine fanuc-lathe calls tool n with offset m"), InputError);
    // G7 means nothing to a Fanuc; the lathe reader refuses a canned cycle under G18.
    CHECK_THROWS_AS(read_program("%\nO1000\nN10 G7\nM30\n%\n", m, "t.nc"), InputError);
}

TEST_CASE("linuxcnc-lathe: canned cycles between G17 and G18; the reader refuses one under G18") {
    const std::string text = post(R"(, "plungingFeedrate": 90, "firstPeckDepth": 5)", "linuxcnc-lathe");
    INFO(text);
    CHECK(has(text, "G18 G7 G40 G80 G90 G94 G21\n"));
    CHECK(has(text, "Z5\nG17\nG98 G83 X0 Z-20 R2 Q5 F90\nG80\nG18\n"));
    std::string under_g18 = text;
    under_g18.erase(under_g18.find("G17\n"), 4);
    CHECK_THROWS_WITH_AS(read_program(under_g18, load_machine("linuxcnc-lathe"), "t.ngc"),
                         doctest::Contains("G83 under G18: it would drill along Y"), InputError);
    // G8 (radius mode) contradicts the machine's xDiameterProg.
    std::string g8 = text;
    g8.replace(g8.find("G7 "), 3, "G8 ");
    CHECK_THROWS_WITH_AS(read_program(g8, load_machine("linuxcnc-lathe"), "t.ngc"),
                         doctest::Contains("programs X as a diameter (G7)"), InputError);
}

TEST_CASE("lathe machines describe their TurnDrillingFields") {
    const std::string d = describe_machine(load_machine("fanuc-lathe"));
    CHECK(has(d, "drilling cycles (TurnDrillingFields; the feed-start plane always)"));
    CHECK(has(d, "canned G74; fields: plungingFeedrate, firstPeckDepth, peckRetract"));
    CHECK(has(d, "feedModes               per-minute G98, per-revolution G99"));
    const std::string l = describe_machine(load_machine("linuxcnc-lathe"));
    CHECK(has(l, "canned G83; fields: plungingFeedrate, firstPeckDepth, peckClearance"));
    // Their threading cycles (turn-thread's output).
    CHECK(has(l, "threading cycles (turn-thread)\n"));
    CHECK(has(l, "G76 (linuxcnc-g76): constant-depth, constant-area, infeedAngle, springPasses, runout\n"));
    CHECK(has(d, "longhand\n"));
}

TEST_CASE("sinumerik-lathe: DIAMON and G18; axial drilling as G17, MCALL CYCLE83 at X0, MCALL, G18") {
    const std::string text = post(R"(, "feedMode": "per-revolution", "plungingFeedrate": 0.1, "firstPeckDepth": 5,
                                      "peckRetract": 0.5)", "sinumerik-lathe");
    INFO(text);
    CHECK(has(text, "N10 G18 DIAMON G40 G90 G94 G710\n"));
    CHECK(has(text, " G95\n"));
    // RTP 5, RFP 0, SDIS 2, DP -20, FDEP 2 - 5 = -3, FRF 1, VARI 0 (chip break), _VRT 0.5.
    CHECK(has(text, " G17\nN"));
    CHECK(has(text, " F0.1\n"));
    CHECK(has(text, " MCALL CYCLE83(5.000, 0.000, 2.000, -20.000, , -3.000, , , , , 1.000, 0, , , 0.500)\n"));
    CHECK(has(text, " G0 X0.000\n"));
    CHECK(text.find(" MCALL\n") < text.find(" G18\n", text.find("MCALL CYCLE83")));
    // Read back: the cycle at X0 with the job's pecks; DIAMON where the machine has no
    // diameter X is refused.
    const std::vector<ReadEvent> back = read_program(text, load_machine("sinumerik-lathe"), "t.mpf");
    const DrillPoint* point = nullptr;
    for (const ReadEvent& e : back)
        if (auto* p = std::get_if<DrillPoint>(&e.event)) point = p;
    REQUIRE(point != nullptr);
    CHECK(point->at.x == 0.0);
    CHECK_THROWS_WITH_AS(read_program(text, load_machine("sinumerik"), "t.mpf"),
                         doctest::Contains("DIAMON: machine sinumerik does not program X as a diameter"), InputError);
    // A peckClearance other than _DIS1's goes longhand.
    const std::string deep = post(R"(, "plungingFeedrate": 90, "firstPeckDepth": 5, "peckClearance": 0.3)", "sinumerik-lathe");
    CHECK_FALSE(has(deep, "CYCLE83"));
}

TEST_CASE("--plot of a lathe program is an XZ half-section: Z across, the radius up, the profile's arc an arc") {
    const std::string dir = test::scratch("lathe-plot").string();
    const std::string shaft = CAMGEN_SOURCE_DIR "/samples/shaft.json";
    test::Run r = test::run({shaft, "--machine", "fanuc-lathe", "-q", "--plot", dir + "/s.svg"});
    REQUIRE(r.code == 0);
    const std::string svg = test::read_file(dir + "/s.svg");
    CHECK(has(svg, "XZ half-section</text>"));
    CHECK(has(svg, ">Z mm</text>"));
    CHECK(has(svg, ">X mm (diameter)</text>"));  // fanuc-lathe programs diameters
    CHECK(has(svg, ">Z0 X0</text>"));
    // The R5 fillet is drawn as an SVG arc (the section maps G18 arcs onto the drawing's plane).
    CHECK(std::regex_search(svg, std::regex("A[0-9.]+,[0-9.]+ 0 0 [01] ")));
    // A mill's plot stays the XY view.
    test::Run m = test::run({CAMGEN_SOURCE_DIR "/samples/plate.json", "--machine", "fanuc", "--plot", dir + "/p.svg"});
    REQUIRE(m.code == 0);
    CHECK(has(test::read_file(dir + "/p.svg"), "XY view</text>"));
}

TEST_CASE("fanuc-lathe with G83 X0 Z R Q F instead of G74 (the machine-file alternative): no G98/G99 in the block") {
    // In G code system A G98/G99 are feed modes: a return level word would switch the feed.
    Machine m = load_machine("fanuc-lathe");
    m.drilling = {DrillingCycleSpec{"G83", CycleKind::deep, true, CannedStyle::standard,
                                    {DrillField::safe_distance, DrillField::plunging_feedrate, DrillField::first_depth,
                                     DrillField::peck_clearance}}};
    const Job j = read_job(job(R"(, "feedMode": "per-revolution", "plungingFeedrate": 0.1, "firstPeckDepth": 6)"), "t.json");
    const std::string text = test::post_program(j, m);
    INFO(text);
    CHECK(has(text, " G83 X0.000 Z-20.000 R2.000 Q6.000 F0.1000\n"));
    CHECK(text.find("G98 G83") == std::string::npos);
    CHECK(text.find("G99 G83") == std::string::npos);
    // It reads back as the job (the cycle returns to the retract plane it started from).
    const Trace expected = trace_expected(expand_job(j), m);
    const Trace actual = trace_program(read_program(text, m, "t.nc"), m);
    CHECK_FALSE(compare_traces(expected, actual, compare_tolerance(m, read_resolution(m))));
}

}  // namespace test_lathe_posts
