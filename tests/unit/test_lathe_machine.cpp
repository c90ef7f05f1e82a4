// Lathe machines: the machine kind and its refusals, xDiameterProg / iDiameterProg (CNC-Calc
// section 1 and the backplot table of section 7) and the axes' own formats. The four diameter
// combinations are posted on one arc with the words worked out by hand, and read back.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "lathe_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_lathe_machine {

using namespace camgen;
using camgen::test::Run;
using camgen::test::run;

namespace {

using test::lathe;
using test::lathe_text;

// The arc of LinuxCNC test C (reference/rs274/C): from radius 20 at Z0, clockwise about
// (radius 10, Z0) to radius 10 at Z-10; the tool comes from radius 20 at Z5.
std::vector<Event> arc_events() {
    return {ToolChange{1, 0.8, "turning tool"},
            Spindle{SpindleState::cw, 1000},
            Rapid{{20, 0, 5}},
            Linear{{20, 0, 0}, 100},
            Arc{{10, 0, -10}, {10, 0, 0}, ArcDirection::cw, Plane::xz, 100}};
}

std::string post_events(const Machine& machine, const std::vector<Event>& events) {
    std::ostringstream out;
    auto post = make_post(machine, out, PostOptions{});
    post->open();
    for (const Event& e : events) post->emit(e);
    post->close();
    return out.str();
}

// The last block of `text` that starts with `prefix`.
std::string block_starting(const std::string& text, const std::string& prefix) {
    std::string found;
    for (const std::string& line : test::lines_of(text))
        if (line.rfind(prefix, 0) == 0) found = line;
    return found;
}

}  // namespace

TEST_CASE("lathe: the four xDiameterProg x iDiameterProg combinations on one arc, and each reads back") {
    struct Case {
        bool x, i;
        std::string approach;  // the rapid to radius 20 (after G0 Z5, modal G0)
        std::string arc;       // the arc block
    };
    // X: radius 20 -> 20 or diameter 40; the end radius 10 -> 10 or 20. I = centre - start
    // along X = 10 - 20 = -10 as a radius, -20 as a diameter; but CNC-Calc's table: the I flag
    // counts only with diameter X (x=false, i=true writes radii).
    const Case cases[] = {
        {false, false, "X20", "G2 X10 Z-10 I-10 K0"},
        {false, true, "X20", "G2 X10 Z-10 I-10 K0"},
        {true, false, "X40", "G2 X20 Z-10 I-10 K0"},
        {true, true, "X40", "G2 X20 Z-10 I-20 K0"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.x);
        CAPTURE(c.i);
        const Machine m = lathe(c.x, c.i);
        const std::string text = post_events(m, arc_events());
        CHECK(block_starting(text, "X") == c.approach);
        CHECK(block_starting(text, "G1") == "G1 Z0 F100");
        CHECK(block_starting(text, "G2") == c.arc);
        // Read back with the same globals (CNC-Calc section 7): the job's radius and centre.
        std::vector<ReadEvent> back = read_program(text, m, "arc.nc");
        const Arc* arc = nullptr;
        for (const ReadEvent& e : back)
            if (auto* a = std::get_if<Arc>(&e.event)) arc = a;
        REQUIRE(arc != nullptr);
        CHECK(arc->to.x == doctest::Approx(10));
        CHECK(arc->to.z == doctest::Approx(-10));
        CHECK(arc->centre.x == doctest::Approx(10));
        CHECK(arc->centre.z == doctest::Approx(0));
        CHECK(arc->direction == ArcDirection::cw);
        CHECK(arc->plane == Plane::xz);
    }
}

TEST_CASE("lathe: a diameter X read with radius globals is twice as far out (the backplot must match the post)") {
    const std::string text = post_events(lathe(true, false), arc_events());
    // The same program read as radius programming: the arc's radii differ, so it is refused.
    CHECK_THROWS_WITH_AS(read_program(text, lathe(false, false), "arc.nc"), doctest::Contains("radi"), InputError);
}

TEST_CASE("lathe: X has its own format, doubled under xDiameterProg; Z keeps xyz's") {
    const Machine m = lathe(true, false, R"(, "inchFormats": {"xyz": {"decimals": 4}})");
    CHECK(m.kind == MachineKind::lathe);
    CHECK(m.format("x").format(12.5) == "25");
    CHECK(m.format("z").format(12.5) == "12.5");
    CHECK(m.format("i").format(12.5) == "12.5");
    // A format of X's own (padded; its decimals are xyz's, test_machine_checks), still a diameter.
    const Machine own = parse_machine(
        lathe_text(true, true, "", R"("xyz": {"decimals": 2}, "x": {"width": 3, "zeropad": true})"), "own", "own.json");
    CHECK(own.format("x").format(1.2345) == "002.47");
    CHECK(own.format("i").format(1.25) == "2.5");
    CHECK(own.format("xyz").format(1.2345) == "1.23");
}

TEST_CASE("lathe: xDiameterProg and iDiameterProg are refused on a mill, naming the key") {
    const std::string text = R"({"description": "m", "dialect": "iso", "extension": "nc",
  "globals": {"xDiameterProg": true}})";
    CHECK_THROWS_WITH_AS(parse_machine(text, "m", "m.json"),
                         doctest::Contains("/globals/xDiameterProg: xDiameterProg is for lathes"), InputError);
    const std::string kind = R"({"description": "m", "dialect": "iso", "extension": "nc", "kind": "turret"})";
    CHECK_THROWS_WITH_AS(parse_machine(kind, "m", "m.json"), doctest::Contains("/kind"), InputError);
}

TEST_CASE("lathe: a mill job on a lathe machine is refused, naming the operation and the kinds, exit 1") {
    const std::string dir = test::scratch("lathe-kind").string();
    const std::string machine_file = dir + "/lathe.json";
    std::ofstream(machine_file) << lathe_text(true, false);
    const std::string job = test::file_with("mill-on-lathe", test::drill_job(R"("tool": 1, "endDepth": 5, "plungingFeedrate": 100)"));
    Run r = run({job, "--machine", machine_file});
    CHECK(r.code == 1);
    CHECK(r.out.empty());
    CHECK(r.err.find("/operations/0/type") != std::string::npos);
    CHECK(r.err.find("operation \"drill\" (drill 2 holes) is made for a mill, and machine lathe is a lathe") !=
          std::string::npos);
    // verify --job refuses it too.
    Run v = run({"verify", "-", "--machine", machine_file, "--job", job}, "G18\nM30\n");
    CHECK(v.code == 1);
    CHECK(v.err.find("is made for a mill, and machine lathe is a lathe") != std::string::npos);
}

TEST_CASE("lathe: --describe-machine says the kind and the diameter globals") {
    const std::string dir = test::scratch("lathe-describe").string();
    std::ofstream(dir + "/l.json") << lathe_text(true, true);
    Run r = run({"--describe-machine", dir + "/l.json"});
    CHECK(r.code == 0);
    CHECK(r.out.find("kind                    lathe") != std::string::npos);
    CHECK(r.out.find("xDiameterProg           yes: X words are diameters") != std::string::npos);
    CHECK(r.out.find("iDiameterProg           yes: I words are diameters") != std::string::npos);
    Run mill = run({"--describe-machine", "fanuc"});
    CHECK(mill.out.find("kind                    mill") != std::string::npos);
    CHECK(mill.out.find("xDiameterProg") == std::string::npos);
}

TEST_CASE("lathe: read back, a feed along Z turns the work; only a drill on the axis plunges") {
    for (const char* name : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        INFO(name);
        const Machine m = load_machine(name);
        const Trace trace = trace_program(read_program(test::post_job(test::read_file(CAMGEN_SOURCE_DIR "/samples/shaft.json"), name).text, m, "p"), m);
        const ProgramStats stats = compute_stats(trace, m);
        const auto length = [&](Movement kind) { return stats.movement_length[static_cast<std::size_t>(kind)]; };
        // The shaft: a centre drill and a drill on the axis (tools 1 and 2), turning tools 4 (face,
        // rough) and 3 (finish), the grooving tool 5, the parting tool 6 (their plunges in X turn) and the threading tool 7.
        REQUIRE(stats.tools.size() == 7);
        double drills = 0, turning = 0;
        for (const ToolStats& t : stats.tools) (t.tool <= 2 ? drills : turning) += t.feed_length;
        CHECK(length(Movement::plunge) == doctest::Approx(drills));
        CHECK(length(Movement::cutting) == doctest::Approx(turning));
        CHECK(length(Movement::ramp) == 0.0);
    }
}

}  // namespace test_lathe_machine
