// The turn-profile operation: a finishing pass along a profile in XZ given as diameters or
// radii; the four xDiameterProg x iDiameterProg combinations on one of its arcs, with the words
// worked out by hand and read back; bad input refused at its JSON path.
#include <doctest/doctest.h>

#include <cmath>

#include "camgen/reader/reader.hpp"
#include "lathe_support.hpp"
#include "reader_support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_profile {

using namespace camgen;

namespace {

// LinuxCNC reference test C's arc as a profile: from diameter 40 at Z0 clockwise about
// (diameter 20, Z0) to diameter 20 at Z-10 (three quarters of a turn, up to Z10 and down to
// the spindle axis, which it touches); `x_values` and the points' X as the job gives them.
std::string job(const std::string& x_values = "diameter", const std::string& start = "[40, 0]",
                const std::string& path = R"({"arc": {"end": [20, -10], "centre": [20, 0], "direction": "cw"}})",
                const std::string& retract = "44") {
    return R"({"clearance": 15, "tools": [{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}],
  "operations": [{"type": "turn-profile", "tool": 1, "compensation": "none", "xValues": ")" +
           x_values + R"(", "feed": 100, "start": )" + start + R"(, "retractX": )" + retract + R"(, "path": [)" + path +
           "]}]}";
}

std::string line_with(const std::string& text, const std::string& prefix) {
    for (const std::string& l : test::lines_of(text))
        if (l.rfind(prefix, 0) == 0) return l;
    return "";
}

InputError error_of(const std::string& text) {
    try {
        (void)read_job(text, "p.json");
    } catch (const InputError& e) {
        return e;
    }
    FAIL("no error");
    return InputError("", "");
}

}  // namespace

TEST_CASE("turn-profile: the pass, from the clearance along Z to the start, lifted off, out to retractX and back") {
    const std::vector<Event> ev = expand_job(read_job(job(), "p.json"));
    std::vector<Event> moves;
    for (const Event& e : ev)
        if (std::holds_alternative<Rapid>(e) || std::holds_alternative<Linear>(e) || std::holds_alternative<Arc>(e))
            moves.push_back(e);
    // Radii: start 20, arc to 10 about 10; retract diameter 44 = radius 22. A rapid to 1 mm
    // (approachDistance) before the start, a feed for the rest; off the end by 0.5 mm (lift) at
    // 45 degrees, +Z and +X (orientation 2), then rapids.
    const double l = 0.5 * (1.0 / std::hypot(1.0, 1.0));
    const std::vector<Event> expected = {
        Rapid{{20, 0, 15}},
        Rapid{{20, 0, 1}},
        Linear{{20, 0, 0}, 100, Movement::lead_in},
        Arc{{10, 0, -10}, {10, 0, 0}, ArcDirection::cw, Plane::xz, 100, 0, Movement::finishing},
        Linear{{10 + l, 0, -10 + l}, 100, Movement::lead_out},
        Rapid{{22, 0, -10 + l}},
        Rapid{{22, 0, 15}},
    };
    CHECK(moves == expected);
    // The same profile in radii.
    CHECK(expand_job(read_job(job("radius", "[20, 0]", R"({"arc": {"end": [10, -10], "centre": [10, 0], "direction": "cw"}})",
                                  "22"),
                              "p.json")) == ev);
}

TEST_CASE("turn-profile: xDiameterProg x iDiameterProg on its arc, words by hand, read back") {
    struct Case {
        bool x, i;
        std::string start, arc;
    };
    // Radius 20 -> X20 or X40; end radius 10 -> X10 or X20; I = 10 - 20 = -10 as a radius, -20
    // as a diameter (only with diameter X: CNC-Calc section 7).
    const Case cases[] = {
        {false, false, "X20", "G2 X10 Z-10 I-10 K0"},
        {false, true, "X20", "G2 X10 Z-10 I-10 K0"},
        {true, false, "X40", "G2 X20 Z-10 I-10 K0"},
        {true, true, "X40", "G2 X20 Z-10 I-20 K0"},
    };
    const Job j = read_job(job(), "p.json");
    for (const Case& c : cases) {
        CAPTURE(c.x);
        CAPTURE(c.i);
        const Machine m = test::lathe(c.x, c.i);
        const std::string text = test::post_program(j, m);
        CHECK(line_with(text, "X") == c.start);
        CHECK(line_with(text, "G2") == c.arc);
        std::vector<ReadEvent> back = read_program(text, m, "p.nc");
        const Arc* arc = nullptr;
        for (const ReadEvent& e : back)
            if (auto* a = std::get_if<Arc>(&e.event)) arc = a;
        REQUIRE(arc != nullptr);
        CHECK(arc->to.x == doctest::Approx(10));
        CHECK(arc->centre.x == doctest::Approx(10));
        CHECK(arc->to.z == doctest::Approx(-10));
    }
}

TEST_CASE("turn-profile: bad input at its JSON path") {
    auto check = [](const std::string& text, const std::string& path, const std::string& detail) {
        const InputError e = error_of(text);
        INFO(std::string(e.what()));
        CHECK(e.path() == path);
        CHECK(std::string(e.detail()).find(detail) != std::string::npos);
    };
    check(job("diameter", "[40, 0]", R"({"line": [30, -2]}, {"line": [-4, -5]})"), "/operations/0/path/1/line/0",
          "X -4.000 mm is negative: a diameter is measured from the spindle axis");
    check(job("diameter", "[-2, 0]", R"({"line": [30, -2]})"), "/operations/0/start/0", "is negative");
    check(job("diameter", "[40, 0]", R"({"arc": {"end": [20, -10], "centre": [24, 0], "direction": "cw"}})"),
          "/operations/0/path/0/arc/centre", "it is not the centre of an arc through both");
    check(job("diameter", "[40, 0]", R"({"line": [40, 0]})"), "/operations/0/path/0", "it has no length");
    check(job("diameter", "[40, 0]", R"({"line": [30, -2], "arc": {"end": [20, -10], "centre": [20, 0], "direction": "cw"}})"),
          "/operations/0/path/0", "exactly one of line, arc");
    check(job("diameter", "[40, 0]", R"({"line": [30, -2]})", "-1"), "/operations/0/retractX", "negative");
}

namespace {

// A job of turn-profiles (each given by its keys after "type" and "tool") with clearance
// `clearance`, X as diameters.
std::string profiles_job(const std::vector<std::string>& ops, const std::string& clearance = "20") {
    std::string list;
    for (const std::string& op : ops)
        list += (list.empty() ? "" : ", ") + std::string(R"({"type": "turn-profile", "tool": 1, "compensation": "none", "feed": 100, )") + op + "}";
    return R"({"clearance": )" + clearance +
           R"(, "tools": [{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}], "operations": [)" + list +
           "]}";
}

// The shaft of samples/shaft.json: chamfer, diameter 30, R5 fillet, diameter 40 to Z-40.
const std::string shaft_path =
    R"("start": [24, 0], "path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]},
       {"arc": {"end": [40, -25], "centre": [40, -20], "direction": "cw"}}, {"line": [40, -40]}])";

void check_refused(const std::string& text, const std::string& path, const std::vector<std::string>& details) {
    const InputError e = error_of(text);
    INFO(std::string(e.what()));
    CHECK(e.path() == path);
    for (const std::string& d : details) CHECK(std::string(e.detail()).find(d) != std::string::npos);
}

}  // namespace

TEST_CASE("turn-profile: an arc whose sweep passes below the spindle axis is refused at the arc") {
    // From diameter 12.4 at Z-5 counter-clockwise about (diameter 2, Z-5), radius 5.2, to
    // diameter 2 at Z0.2: ends and centre above the axis, but three quarters of a turn that
    // passes radius 1 - 5.2 = -4.2 at Z-5.
    const std::string arc = R"({"arc": {"end": [2, 0.2], "centre": [2, -5], "direction": "ccw"}})";
    check_refused(profiles_job({R"("start": [12.4, -5], "retractX": 20, "path": [)" + arc + "]"}), "/operations/0/path/0/arc",
                  {"sweeps through the spindle axis", "reaches X -8.400 mm (diameter) at Z -5.000 mm"});
    check_refused(profiles_job({R"("xValues": "radius", "start": [6.2, -5], "retractX": 10, "path": [{"arc": {"end": [1, 0.2], "centre": [1, -5], "direction": "ccw"}}])"}),
                  "/operations/0/path/0/arc", {"reaches X -4.200 mm (radius)"});
    // The same ends and centre the other way round: a quarter turn, above the axis.
    CHECK_NOTHROW(read_job(profiles_job({R"("start": [12.4, -5], "retractX": 20, "path": [{"arc": {"end": [2, 0.2], "centre": [2, -5], "direction": "cw"}}])"}),
                           "p.json"));
}

TEST_CASE("turn-profile: a profile that crosses or touches itself is refused at the element that does it") {
    // Element 2 runs back from (diameter 40, Z-10) to (diameter 20, Z0) across element 0.
    check_refused(profiles_job({R"("start": [40, 0], "retractX": 44, "path": [{"line": [20, -10]}, {"line": [40, -10]}, {"line": [20, 0]}])"}),
                  "/operations/0/path/2", {"crosses or touches the profile before it"});
    // Element 3 ends on the end of element 0.
    check_refused(profiles_job({R"("start": [40, 0], "retractX": 44, "path": [{"line": [20, -10]}, {"line": [20, -20]}, {"line": [30, -15]}, {"line": [20, -10]}])"}),
                  "/operations/0/path/3", {"crosses or touches"});
    // An arc that swings back across the line before it.
    check_refused(profiles_job({R"("start": [30, 0], "retractX": 44, "path": [{"line": [30, -10]}, {"arc": {"end": [30, -4], "centre": [30, -7], "direction": "cw"}}])"}),
                  "/operations/0/path/1", {"crosses or touches"});
}

TEST_CASE("turn-profile: every point of the profile below the clearance") {
    // The start at Z30 with the clearance at Z10: the tool would rapid to Z10 inside the part
    // and feed up to it.
    check_refused(profiles_job({R"("start": [20, 30], "retractX": 44, "path": [{"line": [20, 0]}])"}, "10"), "/operations/0/start/1",
                  {"the start is at Z 30.000 mm, at or above the clearance (Z 10.000 mm)"});
    check_refused(profiles_job({R"("start": [20, 0], "retractX": 44, "path": [{"line": [30, 12]}])"}, "10"), "/operations/0/path/0/line",
                  {"the line reaches Z 12.000 mm, at or above the clearance (Z 10.000 mm)"});
    // Test C's arc rises to Z10 between its ends at Z0 and Z-10.
    check_refused(job().replace(job().find("\"clearance\": 15"), 15, "\"clearance\": 5"), "/operations/0/path/0/arc",
                  {"the arc reaches Z 10.000 mm, at or above the clearance (Z 5.000 mm)"});
}

TEST_CASE("turn-profile: retractX inside the part is refused; the return stays outside the material") {
    // The shaft is 28 to 40 in diameter: a return at diameter 10 runs through all of it.
    check_refused(profiles_job({shaft_path + R"(, "retractX": 10)"}), "/operations/0/retractX",
                  {"retractX 10.000 mm is inside the part", "from the profile's end (Z -40.000 mm) to the clearance (Z 20.000 mm)",
                   "runs through the material that this profile keeps, up to X 40.000 mm between Z -40.000 mm and Z 0.000 mm"});
    // Diameter 38 clears the diameter 30 but not the 40 before the fillet.
    check_refused(profiles_job({shaft_path + R"(, "retractX": 38)"}), "/operations/0/retractX",
                  {"retractX 38.000 mm is inside the part", "up to X 40.000 mm between Z -40.000 mm and Z -24.8"});
    // On the largest diameter or beyond it: in the air.
    CHECK_NOTHROW(read_job(profiles_job({shaft_path + R"(, "retractX": 40)"}), "p.json"));
    CHECK_NOTHROW(read_job(profiles_job({shaft_path + R"(, "retractX": 44)"}), "p.json"));
}

TEST_CASE("turn-profile: the approach along Z stays out of the material this and earlier profiles keep") {
    // A second profile starting at diameter 34 and Z-30: its approach from the clearance
    // feeds through the diameter 40 the first one finished, from the fillet down.
    check_refused(profiles_job({shaft_path + R"(, "retractX": 44)", R"("start": [34, -30], "retractX": 44, "path": [{"line": [34, -35]}])"}),
                  "/operations/1/start",
                  {"the approach runs along Z at X 34.000 mm from the clearance (Z 20.000 mm) down to the start (Z -30.000 mm)",
                   "through the material that the profile of /operations/0 keeps: X up to 40.000 mm between Z -30.000 mm and Z -23.9"});
    // A profile that grows towards +Z keeps material over its own start.
    check_refused(profiles_job({R"("start": [20, -10], "retractX": 44, "path": [{"line": [30, 0]}])"}), "/operations/0/start",
                  {"through the material that this profile keeps: X up to 30.000 mm between Z -10.000 mm and Z 0.000 mm"});
    // Passes at smaller and smaller diameters from the face: each approach comes down in the
    // air in front of the face, and each return clears what the passes left: the diameter 38
    // of the first pass is gone where the second one cut to 36.
    CHECK_NOTHROW(read_job(profiles_job({R"("start": [38, 0], "retractX": 42, "path": [{"line": [38, -40]}])",
                                         R"("start": [36, 0], "retractX": 37, "path": [{"line": [36, -40]}])"}),
                           "p.json"));
    // A second pass behind a shoulder: it starts on the first pass's diameter 38 at Z-20 and
    // cuts 36 to Z-40; its return at diameter 37 runs into the 38 left in front of it.
    check_refused(profiles_job({R"("start": [38, 0], "retractX": 42, "path": [{"line": [38, -40]}])",
                                R"("start": [38, -20], "retractX": 37, "path": [{"line": [36, -20]}, {"line": [36, -40]}])"}),
                  "/operations/1/retractX",
                  {"the profile of /operations/0 keeps, up to X 38.000 mm between Z -20.000 mm and Z 0.000 mm"});
    CHECK_NOTHROW(read_job(profiles_job({R"("start": [38, 0], "retractX": 42, "path": [{"line": [38, -40]}])",
                                         R"("start": [38, -20], "retractX": 39, "path": [{"line": [36, -20]}, {"line": [36, -40]}])"}),
                           "p.json"));
}

TEST_CASE("turn-profile: an arc under minRadius is one straight move on every lathe, and verify accepts it") {
    // A half circle of radius r in XZ between two lines (radii as given): under the lathes'
    // minRadius (0.002), or under their minLength (0.01 mm: pi r < 0.01 up to r = 0.00318), the
    // post writes it as one straight move, above both as G2; verify --job accepts each, and
    // refuses the program of the same profile 0.05 mm further along Z.
    auto profile = [](double r, double at_z) {
        return fmt::format(R"({{"clearance": 5, "tools": [{{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}}],
  "operations": [{{"type": "turn-profile", "tool": 1, "compensation": "none", "xValues": "radius", "feed": 100, "start": [20, 0], "retractX": 22,
    "path": [{{"line": [20, {}]}}, {{"arc": {{"end": [20, {}], "centre": [20, {}], "direction": "cw"}}}}, {{"line": [15, -10]}}]}}]}})",
                           at_z, at_z - 2 * r, at_z - r);
    };
    for (const std::string machine : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        for (const double r : {0.001, 0.0019, 0.0021, 0.004}) {
            CAPTURE(machine);
            CAPTURE(r);
            const std::string job = profile(r, -5);
            const std::string program = test::post_job(job, machine).text;
            CHECK((program.find("G2 X") != std::string::npos) == (r > 0.0032));
            CHECK(test::round_trip(job, program, machine) == "");
            CHECK(test::round_trip(job, test::post_job(profile(r, -5.05), machine).text, machine).find("line ") == 0);
        }
    }
}

}  // namespace test_turn_profile
