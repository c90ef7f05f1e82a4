// The dialect registry and what a dialect folder shares between its post and its reader:
// one table names both sides, the D register of a compensation, the rigid-tapping style of
// a drilling cycle, and the ISO settings both sides share.
#include <doctest/doctest.h>

#include <sstream>

#include "camgen/common/error.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "machines/iso/iso_settings.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_dialects {

using namespace camgen;
using test::post_events;

TEST_CASE("every dialect of the registry has a post and a reader; an unknown one has neither") {
    for (const char* name : {"fanuc", "linuxcnc", "grbl", "wabeco", "kosy", "sinumerik", "heidenhain"}) {
        const Machine m = load_machine(name);
        INFO(name);
        CHECK(has_reader(m.dialect));
        std::ostringstream out;
        CHECK(make_post(m, out, {}) != nullptr);
    }
    Machine m = load_machine("fanuc");
    m.dialect = "klingon";
    CHECK(!has_reader(m.dialect));
    std::ostringstream out;
    CHECK_THROWS_WITH_AS(make_post(m, out, {}),
                         doctest::Contains("unknown dialect \"klingon\"; dialects: heidenhain, iso, iso-lathe, nccad, sinumerik, sinumerik-lathe"),
                         InputError);
    CHECK_THROWS_WITH_AS(read_program("", m), doctest::Contains("it reads: iso, iso-lathe, nccad, sinumerik, sinumerik-lathe, heidenhain"),
                         InputError);
}

TEST_CASE("the compensation word names the D register when the event gives one, else the tool") {
    const Machine m = load_machine("fanuc");
    const std::string t = post_events(m, {ToolChange{4, 8.0, ""}, Rapid{{0, 0, 5}},
                                          Compensation{CompensationSide::left, 14, 4.0}, Linear{{10, 0, 5}, 300},
                                          Compensation{CompensationSide::right}, Linear{{20, 0, 5}, 300}});
    CHECK(t.find("G41 D14 G1 X10.000 F300\n") != std::string::npos);
    CHECK(t.find("G42 D4 X20.000\n") != std::string::npos);
}

TEST_CASE("Heidenhain writes the compensation word after the coordinates of its L block") {
    const Machine m = load_machine("heidenhain");
    const std::string t = post_events(m, {ToolChange{1, 6.0, ""}, Rapid{{0, 0, 5}},
                                          Compensation{CompensationSide::right}, Linear{{10, 0, 5}, 300}});
    CHECK(t.find("L X+10 RR F300\n") != std::string::npos);
}

TEST_CASE("a drilling cycle's style makes it rigid tapping, not its name") {
    const Machine linuxcnc = load_machine("linuxcnc");
    const DrillingCycleSpec* tap = linuxcnc.canned_cycle(CycleKind::tap);
    REQUIRE(tap != nullptr);
    CHECK(tap->style == CannedStyle::rigid_g33_1);
    CHECK(load_machine("fanuc").canned_cycle(CycleKind::tap)->style == CannedStyle::standard);
}

TEST_CASE("the post and the reader share the ISO settings read with the machine") {
    // One struct, read once: a machine made in code takes the dialect's defaults on both sides.
    const Machine grbl = load_machine("grbl");
    REQUIRE(grbl.settings);
    const auto& s = settings_of<iso::Settings>(grbl);
    CHECK(s.tool_change == iso::ToolChangeStyle::pause);
    CHECK_FALSE(s.stop.optional_stop);
    CHECK(s.end_code == "M2");
    Machine bare = grbl;
    bare.settings = nullptr;
    CHECK(settings_of<iso::Settings>(bare).tool_change == iso::ToolChangeStyle::m6);
    // Another dialect's struct is a programming error, not a machine's.
    CHECK_THROWS_AS(settings_of<iso::LatheSettings>(grbl), std::logic_error);
    CHECK(settings_of<iso::LatheSettings>(load_machine("fanuc-lathe")).tool_call == iso::LatheToolCall::turret);
}

TEST_CASE("the ISO reader takes G7/G8 where the start block selects one, on a mill too; G50 only on the lathe") {
    // The start block decides, not the lathe variant: a mill in radius mode (G8) writes it in
    // every custom block's read-back.
    Machine mill = load_machine("linuxcnc");
    CHECK_THROWS_WITH_AS(read_program("G8\nM2\n", mill), doctest::Contains("unknown code G8"), InputError);
    mill.frame.start_block.push_back("G8");
    CHECK_NOTHROW(read_program("G8\nG0 X1 Y2 Z3\nM2\n", mill));
    CHECK_THROWS_WITH_AS(read_program("G7\nM2\n", mill), doctest::Contains("programs X as a radius (G8)"), InputError);
    // Fanuc T's spindle limit is the lathe variant's word.
    CHECK_THROWS_WITH_AS(read_program("G50 S3000\nM30\n", load_machine("fanuc")), doctest::Contains("unknown code G50"),
                         InputError);
    CHECK_NOTHROW(read_program("%\nO1000\nG50 S3000\nG97 S500 M3\nM30\n%\n", load_machine("fanuc-lathe")));
}

TEST_CASE("Sinumerik writes CR= for the radius and states the end point even where forceXY is off") {
    Machine m = load_machine("sinumerik");
    m.arcs.format = ArcFormat::radius;
    m.arcs.force_xy = false;
    const std::string t = post_events(m, {ToolChange{1, 6.0, ""}, Rapid{{0, 0, 5}},
                                          Arc{{0, 10, 5}, {0, 5, 5}, ArcDirection::ccw, Plane::xy, 300, 0}});
    CHECK(t.find("G17 G3 X0.000 Y10.000 CR=5.000 F300\n") != std::string::npos);
}

}  // namespace test_dialects
