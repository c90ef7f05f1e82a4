// The wabeco (nccad75) post: D-form arcs checked against hand-computed geometry, the program
// frame, feeds in 0.1 mm/s, drilling as G81/G79, dwell in 1/18 s.
#include <cmath>
#include <numbers>

#include <doctest/doctest.h>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_nccad {

using namespace camgen;
using namespace camgen::test;

namespace {

// A tiny nccad interpreter for the words the wabeco post writes: follows the position
// through G00/G01 and D-form arcs and records the end of every block.
struct Step {
    std::string line;
    double x, y;
};

std::vector<Step> follow(const std::string& program) {
    std::vector<Step> steps;
    double x = 0, y = 0;
    for (const std::string& line : lines_of(program)) {
        if (line.empty() || line[0] == ';' || line[0] == '_') continue;
        auto w = words_of(line);
        if (!w.count('G')) continue;
        int g = std::stoi(w['G']);
        if ((g == 2 || g == 3) && w.count('D')) {
            double d = std::stod(w['D']) * std::numbers::pi / 180.0;
            double cx = x + std::stod(w['I']), cy = y + std::stod(w['J']);
            double a = std::atan2(y - cy, x - cx) + (g == 3 ? d : -d);
            double r = std::hypot(x - cx, y - cy);
            x = cx + r * std::cos(a);
            y = cy + r * std::sin(a);
        } else if (g == 0 || g == 1) {
            if (w.count('X')) x = std::stod(w['X']);
            if (w.count('Y')) y = std::stod(w['Y']);
        }
        steps.push_back({line, x, y});
    }
    return steps;
}

const Step& find(const std::vector<Step>& steps, const std::string& line, int nth = 0) {
    for (const Step& s : steps)
        if (s.line == line && nth-- == 0) return s;
    FAIL("no block " << line);
    return steps.front();
}

}  // namespace

TEST_CASE("wabeco bracket: every D-arc's sweep, I, J and end agree with the geometry") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/bracket.json"), "wabeco");
    auto steps = follow(p.text);
    // 90 deg ccw from (60,0) around (60,10): D90, I0 J10, ends at (70,10).
    const Step& a1 = find(steps, "G03 D90 I0 J10");
    CHECK(a1.x == doctest::Approx(70).epsilon(1e-4));
    CHECK(a1.y == doctest::Approx(10).epsilon(1e-4));
    // 270 deg ccw from (70,40) around (70,50), split in two 135 deg pieces: the first ends at
    // (70 + 10 cos 45, 50 + 10 sin 45) = (77.071, 57.071); the second starts there with
    // I = 70 - 77.071, J = 50 - 57.071 and ends at (60,50).
    const Step& a2 = find(steps, "G03 D135 I0 J10");
    CHECK(a2.x == doctest::Approx(77.0711).epsilon(1e-5));
    CHECK(a2.y == doctest::Approx(57.0711).epsilon(1e-5));
    const Step& a3 = find(steps, "G03 D135 I-7.071 J-7.071");
    CHECK(std::abs(a3.x - 60) < 0.001);
    CHECK(std::abs(a3.y - 50) < 0.001);
    // The move after the arc relies on the post knowing it stands at (60,50): only X is written.
    auto it = std::find_if(steps.begin(), steps.end(), [&](const Step& s) { return &s == &a3; });
    REQUIRE(it + 1 != steps.end());
    CHECK((it + 1)->line == "G01 X0");
    CHECK((it + 1)->y == doctest::Approx(50));
    // The full circle cw from (38,25) around (30,25): two blocks of 180 deg.
    const Step& c1 = find(steps, "G02 D180 I-8 J0 F66.7");
    CHECK(c1.x == doctest::Approx(22).epsilon(1e-6));
    CHECK(c1.y == doctest::Approx(25).epsilon(1e-6));
    const Step& c2 = find(steps, "G02 D180 I8 J0");
    CHECK(c2.x == doctest::Approx(38).epsilon(1e-6));
    CHECK(c2.y == doctest::Approx(25).epsilon(1e-6));
    // No arc block carries an end point or a sweep over 180 degrees.
    for (const Step& s : steps) {
        auto w = words_of(s.line);
        if (w.count('D')) {
            CHECK(!w.count('X'));
            CHECK(!w.count('Y'));
            CHECK(std::stod(w['D']) <= 180.0);
            CHECK(std::stod(w['D']) > 0.0);
        }
    }
}

TEST_CASE("wabeco program frame, spindle, tool change message and drilling") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/plate.json"), "wabeco");
    auto lines = lines_of(p.text);
    REQUIRE(lines.size() > 8);
    CHECK(lines[0] == "_");
    CHECK(lines[1] == "_");
    CHECK(lines[3] == "G90");
    CHECK(p.text.find("M01 Insert tool 1 10 mm spot drill - spot drill 90 deg, spindle 1500 rpm\nM10 O6.1\n") !=
          std::string::npos);
    // 80 mm/min = 13.33 (0.1 mm/s); the retract plane is B.
    CHECK(p.text.find("G81 X10 Y10 Z-1.5 B2 F13.3\nG79 X50 Y10\n") != std::string::npos);
    // Every hole of the canned cycle is written with both coordinates.
    CHECK(p.text.find("G79 X90 Y40\nG79 X50 Y40\nG79 X10 Y40\n") != std::string::npos);
    // The second operation has a safe distance, which nccad's G81 cannot carry: longhand.
    CHECK(p.text.find("G00 Z1\nG01 Z-9.803 F20\nG00 Z5\n") != std::string::npos);
    CHECK(lines[lines.size() - 3] == "M10 O6.0");
    CHECK(lines[lines.size() - 2] == "G77");
    CHECK(lines.back() == "G99");
    CHECK(p.warnings.empty());
}

TEST_CASE("wabeco clamps feeds above 100 mm/s with a warning") {
    const char* job = R"({"clearance": 5, "tools": [{"number": 1, "diameter": 6, "rpm": 2000, "type": "end-mill"}],
      "operations": [{"type": "path", "tool": 1, "z": -1, "feed": 9000, "plungeFeed": 60, "start": [0, 0], "path": [{"line": [10, 0]}]}]})";
    Posted p = post_job(job, "wabeco");
    CHECK(p.text.find("G01 Z-1 F10\nG01 X10 F1000\n") != std::string::npos);
    CHECK(p.warnings == "camgen: warning: /operations/0: feed 9000 mm/min is above the limit of machine wabeco; clamped to 6000 mm/min\n");
}

TEST_CASE("wabeco rejects a counter-clockwise spindle with the operation's path") {
    const char* job = R"({"clearance": 5, "tools": [{"number": 1, "diameter": 6, "rpm": 2000, "direction": "ccw"}],
      "operations": [{"type": "drill", "tool": 1, "endDepth": 3, "plungingFeedrate": 50, "holes": [[0, 0]]}]})";
    try {
        post_job(job, "wabeco");
        FAIL("expected an error");
    } catch (const InputError& e) {
        CHECK(e.path() == "/operations/0");
        CHECK(std::string(e.what()).find("counter-clockwise") != std::string::npos);
    }
}

TEST_CASE("wabeco snippet has no program frame") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/plate.json"), "wabeco", true);
    CHECK(p.text.rfind("; spot six holes\n", 0) == 0);
    CHECK(p.text.find("G77") == std::string::npos);
    CHECK(p.text.find("G99") == std::string::npos);
}

}  // namespace test_nccad
