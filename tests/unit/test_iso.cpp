// The fanuc (ISO) post: program frame, tool change with G43, canned drilling with G98/G99,
// arcs, inch output, compensation retained until a linear move.
#include <doctest/doctest.h>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_iso {

using namespace camgen;
using namespace camgen::test;

TEST_CASE("fanuc plate: program frame, G43 on the first Z move, G99 and G98 cycles, G80") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/plate.json"), "fanuc");
    auto lines = lines_of(p.text);
    CHECK(lines[0] == "%");
    CHECK(lines[1] == "O1000 (plate)");
    CHECK(lines[2] == "N10 G40 G49 G80 G17 G90 G94 G21");
    CHECK(lines.back() == "%");
    CHECK(lines[lines.size() - 2].ends_with(" M30"));
    CHECK(p.text.find("N15 T1 M6\nN20 S1500 M3\nN25 G0 G43 Z10.000 H1\nN30 X10.000 Y10.000\n") != std::string::npos);
    // Spot drilling: retract plane = feed start: G99, R2.
    CHECK(p.text.find("G99 G81 X10.000 Y10.000 Z-1.500 R2.000 F80\n") != std::string::npos);
    // Through drilling: retract plane 5 above R1: G98 from Z5; depth 8 + tip 3/tan(59 deg).
    CHECK(p.text.find("N105 Z5.000\nN110 G98 G81 X10.000 Y10.000 Z-9.803 R1.000 F120\n") != std::string::npos);
    // Every later hole repeats both coordinates, so none is lost to modality.
    CHECK(p.text.find("X90.000 Y10.000\n") != std::string::npos);
    CHECK(p.text.find("X90.000 Y40.000\n") != std::string::npos);
    // Each cycle is cancelled, and the Z after it is written again (the control is at R/Z5).
    CHECK(p.text.find("G80\nN75 G0 Z10.000\n") != std::string::npos);
    // The spindle stops before the tool change.
    CHECK(p.text.find("N80 M5\n(drill through the 8 mm plate)\n(T2 6 mm drill - HSS jobber)\nN85 T2 M6\n") !=
          std::string::npos);
}

TEST_CASE("fanuc bracket arcs: I/J relative to the start, end point always written") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/bracket.json"), "fanuc");
    CHECK(p.text.find("G3 X70.000 Y10.000 I0.000 J10.000\n") != std::string::npos);
    // 270 degrees in one block: I/J say which way round.
    CHECK(p.text.find("G3 X60.000 Y50.000 I0.000 J10.000\n") != std::string::npos);
    // Full circle: end = start, both written.
    CHECK(p.text.find("G2 X38.000 Y25.000 I-8.000 J0.000 F400\n") != std::string::npos);
}

TEST_CASE("fanuc inch output: G20, lengths and feeds converted, 4 decimals") {
    Job job = read_job(read_file(CAMGEN_SOURCE_DIR "/samples/plate.json"), "plate.json");
    Machine m = load_machine("fanuc");
    m.units = Units::inch;
    std::ostringstream out;
    auto post = make_post(m, out, {});
    post->open();
    expand_job(job, *post);
    post->close();
    std::string t = out.str();
    CHECK(t.find("G40 G49 G80 G17 G90 G94 G20") != std::string::npos);
    // 10 mm = 0.3937 in; 80 mm/min = 3.1 in/min; Z-1.5 mm = -0.0591 in.
    CHECK(t.find("G99 G81 X0.3937 Y0.3937 Z-0.0591 R0.0787 F3.1\n") != std::string::npos);
}

TEST_CASE("compensation is retained and written by the next linear move, not by an arc") {
    Machine m = load_machine("fanuc");
    std::ostringstream out;
    PostOptions o;
    o.snippet = true;
    auto post = make_post(m, out, o);
    post->open();
    post->emit(ToolChange{4, 8.0, ""});
    post->emit(Rapid{{0, 0, 5}});
    post->emit(Compensation{CompensationSide::left});
    post->emit(Linear{{10, 0, 5}, 300});
    post->emit(Compensation{CompensationSide::off});
    post->emit(Arc{{20, 10, 5}, {10, 10, 5}, ArcDirection::ccw, Plane::xy, 300, 0});
    post->emit(Linear{{20, 20, 5}, 300});
    post->close();
    std::string t = out.str();
    CHECK(t.find("G41 D4 G1 X10.000 F300\n") != std::string::npos);
    CHECK(t.find("G3 X20.000 Y10.000 I0.000 J10.000\n") != std::string::npos);
    CHECK(t.find("G40 G1 Y20.000\n") != std::string::npos);
}

TEST_CASE("G18 and G19 arcs carry the plane word and the right centre words") {
    Machine m = load_machine("fanuc");
    std::ostringstream out;
    PostOptions o;
    o.snippet = true;
    auto post = make_post(m, out, o);
    post->open();
    post->emit(ToolChange{1, 6.0, ""});
    post->emit(Rapid{{0, 0, 0}});
    post->emit(Arc{{10, 0, 10}, {10, 0, 0}, ArcDirection::cw, Plane::xz, 100, 0});
    post->emit(Arc{{10, 10, 20}, {10, 10, 10}, ArcDirection::ccw, Plane::yz, 100, 0});
    post->emit(Arc{{20, 10, 20}, {15, 10, 20}, ArcDirection::ccw, Plane::xy, 100, 0});
    post->close();
    std::string t = out.str();
    CHECK(t.find("G18 G2 X10.000 Z10.000 I10.000 K0.000 F100\n") != std::string::npos);
    CHECK(t.find("G19 G3 Y10.000 Z20.000 J10.000 K0.000\n") != std::string::npos);
    // G3 is modal: the plane word changes, the motion word need not be repeated.
    CHECK(t.find("G17 X20.000 Y10.000 I5.000 J0.000\n") != std::string::npos);
}

TEST_CASE("a spindle speed above the machine's maxRpm is an error naming the operation") {
    const char* job = R"({"clearance": 5, "tools": [{"number": 1, "diameter": 6, "rpm": 30000}],
      "operations": [{"type": "drill", "tool": 1, "endDepth": 3, "plungingFeedrate": 50, "holes": [[0, 0]]}]})";
    for (const char* machine : {"fanuc", "linuxcnc", "sinumerik", "heidenhain"}) {
        CAPTURE(machine);
        try {
            post_job(job, machine);
            FAIL("expected an error");
        } catch (const InputError& e) {
            CHECK(e.path() == "/operations/0");
            CHECK(std::string(e.what()).find("spindle speed 30000 rpm is above the limit of machine") != std::string::npos);
        }
    }
}

}  // namespace test_iso
