// The turn-profile operation: a finishing pass along a profile in XZ given as diameters or
// radii; the four xDiameterProg x iDiameterProg combinations on one of its arcs, with the words
// worked out by hand and read back; bad input refused at its JSON path.
#include <doctest/doctest.h>

#include "camgen/reader/reader.hpp"
#include "lathe_support.hpp"
#include "reader_support.hpp"

using namespace camgen;

namespace {

// LinuxCNC reference test C's arc as a profile: from diameter 40 at Z0 clockwise about
// (diameter 20, Z0) to diameter 20 at Z-10; `x_values` and the points' X as the job gives them.
std::string job(const std::string& x_values = "diameter", const std::string& start = "[40, 0]",
                const std::string& path = R"({"arc": {"end": [20, -10], "centre": [20, 0], "direction": "cw"}})",
                const std::string& retract = "44") {
    return R"({"clearance": 5, "tools": [{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}],
  "operations": [{"type": "turn-profile", "tool": 1, "xValues": ")" +
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

TEST_CASE("turn-profile: the pass, from the clearance along Z to the start, out to retractX and back") {
    const std::vector<Event> ev = expand_job(read_job(job(), "p.json"));
    std::vector<Event> moves;
    for (const Event& e : ev)
        if (std::holds_alternative<Rapid>(e) || std::holds_alternative<Linear>(e) || std::holds_alternative<Arc>(e))
            moves.push_back(e);
    // Radii: start 20, arc to 10 about 10; retract diameter 44 = radius 22.
    const std::vector<Event> expected = {
        Rapid{{20, 0, 5}},
        Linear{{20, 0, 0}, 100, Movement::lead_in},
        Arc{{10, 0, -10}, {10, 0, 0}, ArcDirection::cw, Plane::xz, 100, 0, Movement::finishing},
        Linear{{22, 0, -10}, 100, Movement::lead_out},
        Rapid{{22, 0, 5}},
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
          "X -4 is negative: a diameter is measured from the spindle axis");
    check(job("diameter", "[-2, 0]", R"({"line": [30, -2]})"), "/operations/0/start/0", "is negative");
    check(job("diameter", "[40, 0]", R"({"arc": {"end": [20, -10], "centre": [24, 0], "direction": "cw"}})"),
          "/operations/0/path/0/arc/centre", "it is not the centre of an arc through both");
    check(job("diameter", "[40, 0]", R"({"line": [40, 0]})"), "/operations/0/path/0", "it has no length");
    check(job("diameter", "[40, 0]", R"({"line": [30, -2], "arc": {"end": [20, -10], "centre": [20, 0], "direction": "cw"}})"),
          "/operations/0/path/0", "exactly one of line, arc");
    check(job("diameter", "[40, 0]", R"({"line": [30, -2]})", "-1"), "/operations/0/retractX", "negative");
}

TEST_CASE("turn-profile: an arc under minRadius is one straight move on every lathe, and verify accepts it") {
    // A half circle of radius r in XZ between two lines (radii as given): under the lathes'
    // minRadius (0.002), or under their minLength (0.01 mm: pi r < 0.01 up to r = 0.00318), the
    // post writes it as one straight move, above both as G2; verify --job accepts each, and
    // refuses the program of the same profile 0.05 mm further along Z.
    auto profile = [](double r, double at_z) {
        return fmt::format(R"({{"clearance": 5, "tools": [{{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}}],
  "operations": [{{"type": "turn-profile", "tool": 1, "xValues": "radius", "feed": 100, "start": [20, 0], "retractX": 22,
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
