// Reading job files: values, defaults, units, hole patterns, and every validation error with
// its JSON path and line.
#include <numbers>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/registry.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_job_json {

using namespace camgen;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

InputError job_error(const std::string& text) {
    try {
        read_job(text, "job.json");
    } catch (const InputError& e) {
        return e;
    }
    FAIL("read_job accepted:\n" << text);
    return InputError("", "");
}

// Checks that `text` is rejected at `path`, line `line`, with a message containing `detail`.
void check_error(const std::string& text, const std::string& path, int line,
                 const std::string& detail) {
    const InputError e = job_error(text);
    INFO("message: " << std::string(e.what()));
    CHECK(e.path() == path);
    CHECK(e.line() == line);
    CHECK(e.source() == "job.json");
    CHECK(contains(e.what(), "job.json:" + std::to_string(line) + ": " + (path.empty() ? "" : path + ": ")));
    CHECK(contains(e.detail(), detail));
}

// A job with one drill operation; `rest` continues the operation object from line 10.
std::string drill_job(const std::string& rest) {
    return R"({
  "clearance": 10,
  "tools": [
    {"number": 1, "diameter": 5, "rpm": 1000},
    {"number": 2, "diameter": 6, "rpm": 800, "tipAngle": 118}
  ],
  "operations": [
    {
      "type": "drill",
)" + rest + R"(
    }
  ]
})";
}

// A job with one contour operation; `rest` continues the operation object from line 9.
std::string contour_job(const std::string& rest) {
    return R"({
  "clearance": 10,
  "tools": [
    {"number": 3, "type": "end-mill", "diameter": 6, "rpm": 12000}
  ],
  "operations": [
    {
      "type": "path",
      "tool": 3,
)" + rest + R"(
    }
  ]
})";
}

const DrillOp& drill(const Job& job, std::size_t i = 0) { return std::get<DrillOp>(job.operations.at(i)); }

void check_point(const Vec2& p, double x, double y) {
    CHECK(p.x == doctest::Approx(x).epsilon(1e-12));
    CHECK(p.y == doctest::Approx(y).epsilon(1e-12));
}

}  // namespace

TEST_CASE("a valid job: values and defaults") {
    const Job job = read_job(R"({
  "clearance": 15,
  "tools": [
    {"number": 4, "diameter": 8.5, "rpm": 900},
    {"number": 1, "type": "spot-drill", "diameter": 10, "tipAngle": 90, "rpm": 2000,
     "direction": "ccw", "comment": "NC spot"}
  ],
  "operations": [
    {"type": "drill", "tool": 4, "endDepth": 12, "plungingFeedrate": 120,
     "holes": [[1, 2], {"x": 3, "y": -4}]},
    {"type": "drill", "tool": 1, "comment": "spot", "cycle": "deep", "retractPlane": 5,
     "referencePlane": -1, "safeDistance": 2, "endDepth": -20, "endDepthIsAbsolute": true,
     "firstDepth": 4, "degressionType": "value", "degression": 0.5, "minimumDepth": 1,
     "retractFeedrate": 500, "plungingFeedrate": 80, "firstFeedrateFactor": 0.5,
     "topDwell": 0.2, "bottomDwell": 0, "drillTip": true, "output": "longhand",
     "order": "shortest", "line": {"start": [0, 0], "end": [10, 0], "count": 2}},
    {"type": "path", "tool": 1, "z": -2, "feed": 300, "start": [0, 0],
     "path": [{"line": [10, 0]}, {"arc": {"end": [0, 0], "centre": [5, 0], "direction": "ccw"}}]}
  ]
})",
                             "work/parts/bracket.json");
    CHECK(job.name == "bracket");
    CHECK(job.units == Units::mm);
    CHECK(job.clearance == 15);
    REQUIRE(job.tools.size() == 2);

    const Tool& t4 = job.tools.at(4);
    CHECK(t4.number == 4);
    CHECK(t4.type == ToolType::drill);
    CHECK(t4.diameter == 8.5);
    CHECK_FALSE(t4.tip_angle.has_value());
    CHECK(t4.rpm == 900);
    CHECK(t4.direction == SpindleDirection::cw);
    CHECK(t4.comment == "");
    CHECK(t4.path == "/tools/0");
    const Tool& t1 = job.tools.at(1);
    CHECK(t1.type == ToolType::spot_drill);
    CHECK(t1.tip_angle == 90.0);
    CHECK(t1.direction == SpindleDirection::ccw);
    CHECK(t1.comment == "NC spot");
    CHECK(t1.path == "/tools/1");

    REQUIRE(job.operations.size() == 3);
    const DrillOp& a = drill(job, 0);
    CHECK(a.path == "/operations/0");
    CHECK(a.tool == 4);
    CHECK(a.comment == "");
    CHECK(a.order == HoleOrder::as_given);
    const DrillParams& pa = a.params;
    CHECK(pa.kind == CycleKind::drill);
    CHECK(pa.retract_plane == 15);  // defaults to the clearance
    CHECK(pa.reference_plane == 0);
    CHECK_FALSE(pa.safe_distance.has_value());
    CHECK_FALSE(pa.safe_distance_is_absolute);
    CHECK(pa.end_depth == 12);
    CHECK_FALSE(pa.end_depth_is_absolute);
    CHECK(pa.values.degression_type() == DegressionType::none);
    CHECK(pa.values.get(DrillField::plunging_feedrate) == 120.0);
    CHECK_FALSE(pa.values.get(DrillField::retract_feedrate).has_value());
    CHECK_FALSE(pa.values.get(DrillField::top_dwell).has_value());
    CHECK_FALSE(pa.values.get(DrillField::bottom_dwell).has_value());
    CHECK_FALSE(pa.values.get(DrillField::first_depth).has_value());
    CHECK_FALSE(pa.drill_tip);
    CHECK(pa.output == CycleOutput::automatic);
    REQUIRE(a.holes.size() == 2);
    CHECK(a.holes[0] == Vec2{1, 2});
    CHECK(a.holes[1] == Vec2{3, -4});

    const DrillOp& b = drill(job, 1);
    CHECK(b.comment == "spot");
    CHECK(b.order == HoleOrder::shortest);
    const DrillParams& pb = b.params;
    CHECK(pb.kind == CycleKind::deep);
    CHECK(pb.retract_plane == 5);
    CHECK(pb.reference_plane == -1);
    CHECK(pb.safe_distance == 2.0);
    CHECK(pb.end_depth == -20);
    CHECK(pb.end_depth_is_absolute);
    CHECK(pb.values.get(DrillField::first_depth) == 4.0);
    CHECK(pb.values.degression_type() == DegressionType::value);
    CHECK(pb.values.get(DrillField::degression) == 0.5);
    CHECK(pb.values.get(DrillField::minimum_depth) == 1.0);
    CHECK(pb.values.get(DrillField::retract_feedrate) == 500.0);
    CHECK(pb.values.get(DrillField::plunging_feedrate) == 80.0);
    CHECK(pb.values.get(DrillField::first_feedrate_factor) == 0.5);
    CHECK(pb.values.get(DrillField::top_dwell) == 0.2);
    CHECK(pb.values.get(DrillField::bottom_dwell) == 0.0);
    CHECK(pb.drill_tip);
    CHECK(pb.output == CycleOutput::longhand);
    REQUIRE(b.holes.size() == 2);

    const auto& c = std::get<PathOp>(job.operations.at(2));
    CHECK(c.path == "/operations/2");
    CHECK(c.tool == 1);
    CHECK(c.z == -2);
    CHECK(c.feed == 300);
    CHECK_FALSE(c.plunge_feed.has_value());
    CHECK(c.start == Vec2{0, 0});
    REQUIRE(c.elements.size() == 2);
    CHECK(std::get<PathLine>(c.elements[0]).end == Vec3{10, 0, -2});  // [x, y] is at the depth
    const auto& arc = std::get<PathArc>(c.elements[1]);
    CHECK(arc.end == Vec3{0, 0, -2});
    CHECK(arc.centre == Vec3{5, 0, -2});
    CHECK(arc.plane == Plane::xy);
    CHECK(arc.direction == ArcDirection::ccw);
    CHECK(c.element_path(1) == "/operations/2/path/1");
}

TEST_CASE("name: explicit, file stem, or \"job\"; operations may be empty") {
    const std::string body = R"("clearance": 5, "tools": [{"number": 1, "diameter": 3, "rpm": 100}], "operations": [])";
    CHECK(read_job("{\"name\": \"Plate A\", " + body + "}", "x.json").name == "Plate A");
    CHECK(read_job("{" + body + "}", "x.json").name == "x");
    CHECK(read_job("{" + body + "}", "<stdin>").name == "job");
    CHECK(read_job("{" + body + "}", "").name == "job");
    CHECK(read_job("{" + body + "}", "x.json").operations.empty());
}

TEST_CASE("inch input is converted to mm; rpm, angles, seconds and factors are not") {
    const Job job = read_job(R"({
  "units": "inch",
  "clearance": 1,
  "tools": [{"number": 1, "diameter": 0.25, "tipAngle": 118, "rpm": 1000}],
  "operations": [
    {"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 0.5, "referencePlane": 0.1,
     "safeDistance": 0.1, "endDepth": 0.5, "firstDepth": 0.2, "degressionType": "factor",
     "degression": 0.8, "minimumDepth": 0.05, "plungingFeedrate": 10, "retractFeedrate": 20,
     "firstFeedrateFactor": 0.5, "bottomDwell": 1.5,
     "holes": [[1, 2]],
     "grid": {"origin": [1, 1], "countX": 2, "countY": 1, "spacingX": 0.5, "spacingY": 1, "rotation": 90},
     "boltCircle": {"centre": [0, 0], "radius": 1, "count": 1, "startAngle": 90}},
    {"type": "drill", "tool": 1, "cycle": "chip-break", "endDepth": 0.25, "firstDepth": 0.1,
     "peckingRetract": 0.02, "degressionType": "value", "degression": 0.01, "minimumDepth": 0.03,
     "plungingFeedrate": 5, "line": {"start": [0, 0], "end": [2, 0], "count": 3}},
    {"type": "drill", "tool": 1, "cycle": "tap", "endDepth": 0.5, "pitch": 0.05,
     "tappingSpeed": 300, "retractSpeed": 600, "holes": [[0, 0]]},
    {"type": "path", "tool": 1, "z": -0.1, "feed": 10, "plungeFeed": 5, "start": [0, 0],
     "path": [{"line": [1, 0]}, {"arc": {"end": [1, 0], "centre": [0.5, 0], "direction": "cw"}}]}
  ]
})",
                             "in.json");
    CHECK(job.units == Units::inch);
    CHECK(job.clearance == doctest::Approx(25.4));
    const Tool& tool = job.tools.at(1);
    CHECK(tool.diameter == doctest::Approx(6.35));
    CHECK(tool.rpm == 1000);
    CHECK(tool.tip_angle == 118.0);

    const DrillParams& p = drill(job, 0).params;
    CHECK(p.retract_plane == doctest::Approx(12.7));
    CHECK(p.reference_plane == doctest::Approx(2.54));
    CHECK(*p.safe_distance == doctest::Approx(2.54));
    CHECK(p.end_depth == doctest::Approx(12.7));
    CHECK(*p.values.get(DrillField::first_depth) == doctest::Approx(5.08));
    CHECK(*p.values.get(DrillField::degression) == doctest::Approx(0.8));  // a factor: unchanged
    CHECK(*p.values.get(DrillField::minimum_depth) == doctest::Approx(1.27));
    CHECK(*p.values.get(DrillField::plunging_feedrate) == doctest::Approx(254));
    CHECK(*p.values.get(DrillField::retract_feedrate) == doctest::Approx(508));
    CHECK(*p.values.get(DrillField::first_feedrate_factor) == 0.5);
    CHECK(*p.values.get(DrillField::bottom_dwell) == 1.5);
    const auto& holes = drill(job, 0).holes;
    REQUIRE(holes.size() == 4);
    check_point(holes[0], 25.4, 50.8);
    check_point(holes[1], 25.4, 25.4);  // grid origin
    check_point(holes[2], 25.4, 38.1);  // + 0.5 in along X rotated by 90 degrees
    check_point(holes[3], 0, 25.4);     // bolt circle at 90 degrees

    const DrillOp& cb = drill(job, 1);
    CHECK(*cb.params.values.get(DrillField::pecking_retract) == doctest::Approx(0.508));
    CHECK(*cb.params.values.get(DrillField::degression) == doctest::Approx(0.254));  // a value: converted
    REQUIRE(cb.holes.size() == 3);
    check_point(cb.holes[1], 25.4, 0);
    check_point(cb.holes[2], 50.8, 0);

    const DrillParams& tap = drill(job, 2).params;
    CHECK(tap.kind == CycleKind::tap);
    CHECK(*tap.values.get(DrillField::pitch) == doctest::Approx(1.27));
    CHECK(*tap.values.get(DrillField::tapping_speed) == 300);
    CHECK(*tap.values.get(DrillField::retract_speed) == 600);
    CHECK_FALSE(tap.values.get(DrillField::plunging_feedrate).has_value());

    const auto& c = std::get<PathOp>(job.operations.at(3));
    CHECK(c.z == doctest::Approx(-2.54));
    CHECK(c.feed == doctest::Approx(254));
    CHECK(*c.plunge_feed == doctest::Approx(127));
    check_point({std::get<PathLine>(c.elements[0]).end.x, std::get<PathLine>(c.elements[0]).end.y}, 25.4, 0);
    check_point({std::get<PathArc>(c.elements[1]).centre.x, std::get<PathArc>(c.elements[1]).centre.y}, 12.7, 0);
}

TEST_CASE("hole patterns") {
    SUBCASE("grid: row by row, X fastest") {
        const auto h = drill(read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "grid": {"origin": [0, 0], "countX": 2, "countY": 2, "spacingX": 10, "spacingY": 20})"),
                                       "j.json"))
                            .holes;
        REQUIRE(h.size() == 4);
        CHECK(h[0] == Vec2{0, 0});
        CHECK(h[1] == Vec2{10, 0});
        CHECK(h[2] == Vec2{0, 20});
        CHECK(h[3] == Vec2{10, 20});
    }
    SUBCASE("grid rotated 90 degrees about its origin") {
        const auto h = drill(read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "grid": {"origin": [10, 20], "countX": 3, "countY": 2, "spacingX": 5, "spacingY": 4,
               "rotation": 90})"),
                                       "j.json"))
                            .holes;
        REQUIRE(h.size() == 6);
        // local (i*5, j*4) turned by 90 degrees is (-j*4, i*5)
        CHECK(h[0] == Vec2{10, 20});
        CHECK(h[1] == Vec2{10, 25});
        CHECK(h[2] == Vec2{10, 30});
        CHECK(h[3] == Vec2{6, 20});
        CHECK(h[4] == Vec2{6, 25});
        CHECK(h[5] == Vec2{6, 30});
    }
    SUBCASE("bolt circle of 4 starting at 45 degrees, counter-clockwise") {
        const auto h = drill(read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "boltCircle": {"centre": [100, 50], "radius": 10, "count": 4, "startAngle": 45})"),
                                       "j.json"))
                            .holes;
        REQUIRE(h.size() == 4);
        const double d = 10 / std::sqrt(2.0);  // 7.0710678...
        check_point(h[0], 100 + d, 50 + d);
        check_point(h[1], 100 - d, 50 + d);
        check_point(h[2], 100 - d, 50 - d);
        check_point(h[3], 100 + d, 50 - d);
    }
    SUBCASE("bolt circle default start angle is 0") {
        const auto h = drill(read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "boltCircle": {"centre": [0, 0], "radius": 2, "count": 3})"),
                                       "j.json"))
                            .holes;
        REQUIRE(h.size() == 3);
        check_point(h[0], 2, 0);
        check_point(h[1], -1, std::sqrt(3.0));
        check_point(h[2], -1, -std::sqrt(3.0));
    }
    SUBCASE("line of 3 includes both ends; line of 1 is its start") {
        const Job job = read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "line": {"start": [0, 0], "end": [10, 20], "count": 3})"),
                                 "j.json");
        const auto& h = drill(job).holes;
        REQUIRE(h.size() == 3);
        CHECK(h[0] == Vec2{0, 0});
        CHECK(h[1] == Vec2{5, 10});
        CHECK(h[2] == Vec2{10, 20});
        const auto one = drill(read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "line": {"start": [7, 8], "end": [10, 20], "count": 1})"),
                                         "j.json"))
                              .holes;
        REQUIRE(one.size() == 1);
        CHECK(one[0] == Vec2{7, 8});
    }
    SUBCASE("sources are concatenated as holes, grid, boltCircle, line whatever the file order") {
        const auto h = drill(read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "line": {"start": [50, 50], "end": [60, 50], "count": 2},
      "boltCircle": {"centre": [0, 0], "radius": 1, "count": 1},
      "grid": {"origin": [30, 30], "countX": 1, "countY": 1, "spacingX": 1, "spacingY": 1},
      "holes": [{"x": 1, "y": 2}, [3, 4]])"),
                                       "j.json"))
                            .holes;
        REQUIRE(h.size() == 6);
        CHECK(h[0] == Vec2{1, 2});
        CHECK(h[1] == Vec2{3, 4});
        CHECK(h[2] == Vec2{30, 30});
        CHECK(h[3] == Vec2{1, 0});
        CHECK(h[4] == Vec2{50, 50});
        CHECK(h[5] == Vec2{60, 50});
    }
}

TEST_CASE("errors at the top level") {
    check_error(R"({
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": []
})",
                "/clearance", 1, "required key \"clearance\" is missing");
    check_error(R"({
  "clearance": "high",
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": []
})",
                "/clearance", 2, "expected a number, got a string \"high\"");
    check_error(R"({
  "clearance": 5,
  "units": "inches",
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": []
})",
                "/units", 3, "\"inches\" is not one of \"mm\" or \"inch\" (did you mean \"inch\"?)");
    check_error(R"({
  "clearance": 5,
  "tools": [],
  "operations": []
})",
                "/tools", 3, "at least one tool");
    check_error(R"({
  "clearance": 5,
  "tools": {"number": 1},
  "operations": []
})",
                "/tools", 3, "expected an array, got an object");
    check_error(R"({
  "clearance": 5,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}]
})",
                "/operations", 1, "required key \"operations\" is missing");
    check_error(R"({
  "clearance": 5,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": [],
  "stock": {"min": [0, 0, 0], "max": [1, 1, 1]}
})",
                "/stock/min", 5, "min belongs in the stock's box: \"stock\": {\"box\": {\"min\": ...}}");
    check_error(R"({
  "clearence": 5,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": []
})",
                "/clearence", 2, "unknown key \"clearence\" (did you mean \"clearance\"?)");
    check_error("[1, 2]", "", 1, "expected an object, got an array");
}

TEST_CASE("NaN, Infinity and overflowing numbers are rejected with their line") {
    for (const char* bad : {"NaN", "Infinity", "-Infinity"}) {
        CAPTURE(bad);
        const InputError e = job_error(drill_job(std::string(R"(      "tool": 1,
      "endDepth": )") + bad + R"(,
      "plungingFeedrate": 100, "holes": [[0, 0]])"));
        CHECK(e.line() == 11);
        CHECK(contains(e.what(), "job.json:11: line 11, column 19: NaN and Infinity are not valid JSON numbers"));
    }
    const InputError e = job_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "holes": [[0, 0],
                [1e999, 0]])"));
    CHECK(e.line() == 12);
    CHECK(contains(e.what(), "1e999"));
}

TEST_CASE("tool errors") {
    check_error(R"({
  "clearance": 5,
  "tools": [
    {"number": 3, "diameter": 5, "rpm": 1000},
    {"number": 3, "diameter": 6, "rpm": 1000}
  ],
  "operations": []
})",
                "/tools/1/number", 5, "tool number 3 is already used by /tools/0");
    auto tool_error = [](const std::string& tool, const std::string& path, const std::string& detail) {
        check_error(R"({
  "clearance": 5,
  "tools": [
    {"number": 1, "diameter": 5, "rpm": 1000},
    )" + tool + R"(
  ],
  "operations": []
})",
                    path, 5, detail);
    };
    tool_error(R"({"number": 0, "diameter": 5, "rpm": 1000})", "/tools/1/number", "1 or more");
    tool_error(R"({"number": 2.5, "diameter": 5, "rpm": 1000})", "/tools/1/number", "expected an integer, got 2.5");
    tool_error(R"({"number": 2, "diameter": 0, "rpm": 1000})", "/tools/1/diameter", "diameter must be > 0");
    tool_error(R"({"number": 2, "rpm": 1000})", "/tools/1/diameter", "required key \"diameter\" is missing");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 0})", "/tools/1/rpm", "rpm must be > 0");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": "fast"})", "/tools/1/rpm", "expected a number, got a string");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 10, "tipAngle": 180})", "/tools/1/tipAngle", "between 30 (inclusive) and 180");
    // A typo of 1 for 118 would add 143 diameters of tip length with drillTip; 1e-6 would add 340 km.
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 10, "tipAngle": 1})", "/tools/1/tipAngle",
               "tipAngle 1 degrees is not a drill point");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 10, "tipAngle": 0.000001})", "/tools/1/tipAngle",
               "is not a drill point");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 10, "type": "endmill"})", "/tools/1/type",
               "(did you mean \"end-mill\"?)");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 10, "direction": "left"})", "/tools/1/direction",
               "\"left\" is not one of \"cw\" or \"ccw\"");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 10, "comment": 7})", "/tools/1/comment", "expected a string");
    tool_error(R"({"number": 2, "diameter": 5, "rpm": 10, "speed": 7})", "/tools/1/speed", "unknown key \"speed\"");
    tool_error(R"("T2")", "/tools/1", "expected an object, got a string \"T2\"");
}

TEST_CASE("operation errors: type, tool, unknown keys") {
    check_error(drill_job(R"(      "tool": 7, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]])"),
                "/operations/0/tool", 10, "tool 7 is not in /tools");
    check_error(drill_job(R"(      "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]])"),
                "/operations/0/tool", 8, "required key \"tool\" is missing");
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "holez": [[0, 0]])"),
                "/operations/0/holez", 11, "unknown key \"holez\" (did you mean \"holes\"?)");
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]],
      "Cycle": "deep")"),
                "/operations/0/Cycle", 11, "(did you mean \"cycle\"?)");
    check_error(R"({
  "clearance": 5,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": [
    {"type": "drill", "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]]},
    {"type": "mill", "tool": 1}
  ]
})",
                "/operations/1/type", 6,
                "\"mill\" is not one of \"drill\", \"contour\", \"path\", \"bore-mill\", \"turn-drill\", \"turn-profile\", \"turn-face\", \"turn-rough\", \"stop\", \"custom\", \"pocket\", \"face\", \"thread-mill\", \"engrave\", \"chamfer\", \"turn-groove\", \"turn-part\" or \"turn-thread\"");
    check_error(R"({
  "clearance": 5,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": [
    {"tool": 1}
  ]
})",
                "/operations/0/type", 5, "required key \"type\" is missing");
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]],
      "cycle": "peck")"),
                "/operations/0/cycle", 11,
                "\"peck\" is not one of \"drill\", \"dwell\", \"deep\", \"chip-break\", \"tap\", "
                "\"tap-left\", \"ream\", \"bore-stop\" or \"bore-dwell\"");
}

TEST_CASE("a cycle rejects parameters it does not use") {
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]],
      "firstDepth": 2)"),
                "/operations/0/firstDepth", 11,
                "firstDepth is not used by cycle drill (it uses: plungingFeedrate, retractFeedrate, "
                "topDwell)");
    check_error(drill_job(R"(      "tool": 1, "cycle": "tap", "endDepth": 5, "pitch": 1, "holes": [[0, 0]],
      "plungingFeedrate": 100)"),
                "/operations/0/plungingFeedrate", 11,
                "plungingFeedrate is not used by cycle tap (it uses: pitch, tappingSpeed, "
                "retractSpeed, bottomDwell)");
    // Two unused parameters: the one earlier in the file is reported.
    check_error(drill_job(R"(      "tool": 1, "cycle": "tap", "endDepth": 5, "pitch": 1, "holes": [[0, 0]],
      "firstDepth": 2,
      "plungingFeedrate": 100)"),
                "/operations/0/firstDepth", 11, "firstDepth is not used by cycle tap");
    check_error(drill_job(R"(      "tool": 1, "cycle": "bore-stop", "endDepth": 5, "plungingFeedrate": 1,
      "holes": [[0, 0]],
      "retractFeedrate": 100)"),
                "/operations/0/retractFeedrate", 12, "not used by cycle bore-stop");
    check_error(drill_job(R"(      "tool": 1, "cycle": "deep", "endDepth": 5, "plungingFeedrate": 1,
      "firstDepth": 1, "holes": [[0, 0]], "peckingRetract": 0.2)"),
                "/operations/0/peckingRetract", 11, "not used by cycle deep");
    check_error(drill_job(R"(      "tool": 1, "cycle": "ream", "endDepth": 5, "plungingFeedrate": 1,
      "holes": [[0, 0]], "topDwell": 1)"),
                "/operations/0/topDwell", 11, "not used by cycle ream");
    check_error(drill_job(R"(      "tool": 1, "cycle": "dwell", "endDepth": 5, "plungingFeedrate": 1,
      "bottomDwell": 1, "holes": [[0, 0]], "pitch": 1)"),
                "/operations/0/pitch", 11, "not used by cycle dwell");
    check_error(drill_job(R"(      "tool": 1, "cycle": "tap-left", "endDepth": 5, "pitch": 1,
      "holes": [[0, 0]], "degressionType": "none")"),
                "/operations/0/degressionType", 11, "not used by cycle tap-left");
}

TEST_CASE("required cycle parameters") {
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "holes": [[0, 0]])"),
                "/operations/0/plungingFeedrate", 8, "cycle drill needs plungingFeedrate");
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]])"),
                "/operations/0/endDepth", 8, "required key \"endDepth\" is missing");
    check_error(drill_job(R"(      "tool": 1, "cycle": "dwell", "endDepth": 5, "plungingFeedrate": 100,
      "holes": [[0, 0]])"),
                "/operations/0/bottomDwell", 8, "cycle dwell needs bottomDwell");
    check_error(drill_job(R"(      "tool": 1, "cycle": "bore-dwell", "endDepth": 5, "plungingFeedrate": 100,
      "holes": [[0, 0]])"),
                "/operations/0/bottomDwell", 8, "cycle bore-dwell needs bottomDwell");
    check_error(drill_job(R"(      "tool": 1, "cycle": "chip-break", "endDepth": 5, "plungingFeedrate": 100,
      "holes": [[0, 0]])"),
                "/operations/0/firstDepth", 8, "cycle chip-break needs firstDepth");
    check_error(drill_job(R"(      "tool": 1, "cycle": "tap", "endDepth": 5, "holes": [[0, 0]])"),
                "/operations/0/pitch", 8, "cycle tap needs pitch");
}

TEST_CASE("planes and depths") {
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]],
      "endDepth": 0)"),
                "/operations/0/endDepth", 11, "a relative endDepth must be > 0");
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]],
      "safeDistance": 2,
      "endDepth": 3, "endDepthIsAbsolute": true)"),
                "/operations/0/endDepth", 12, "endDepth is above the safe distance");
    // Relative safe distance measured from the reference plane: safe Z = -5 + 2 = -3; bottom -3.
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]],
      "referencePlane": -5, "safeDistance": 2,
      "endDepth": -3, "endDepthIsAbsolute": true)"),
                "/operations/0/endDepth", 12, "endDepth is above the safe distance");
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]], "endDepth": 3,
      "retractPlane": 1,
      "safeDistance": 2)"),
                "/operations/0/retractPlane", 11, "retractPlane is below the safe distance");
    // retractPlane defaults to the clearance (10); an absolute safe Z of 12 is above it.
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]], "endDepth": 3,
      "safeDistance": 12, "safeDistanceIsAbsolute": true)"),
                "/operations/0/retractPlane", 8, "retractPlane is below the safe distance");
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]], "endDepth": 3,
      "safeDistance": -1)"),
                "/operations/0/safeDistance", 11, "a relative safeDistance cannot be negative");
    // An absolute negative safe distance is fine when the hole is below it.
    CHECK_NOTHROW(read_job(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]],
      "referencePlane": -2, "safeDistance": -1, "safeDistanceIsAbsolute": true, "endDepth": 3)"),
                           "j.json"));
    check_error(drill_job(R"(      "tool": 1, "plungingFeedrate": 100, "holes": [[0, 0]], "endDepth": 3,
      "endDepthIsAbsolute": "yes")"),
                "/operations/0/endDepthIsAbsolute", 11, "expected true or false, got a string");
}

TEST_CASE("feeds, dwells, pecks and speeds must be positive") {
    auto bad = [](const std::string& cycle_and_key, const std::string& key, const std::string& detail) {
        check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "holes": [[0, 0]],
      )" + cycle_and_key),
                    "/operations/0/" + key, 11, detail);
    };
    bad(R"("plungingFeedrate": 0)", "plungingFeedrate", "plungingFeedrate must be > 0");
    bad(R"("plungingFeedrate": 10, "retractFeedrate": -1)", "retractFeedrate", "retractFeedrate must be > 0");
    bad(R"("plungingFeedrate": 10, "topDwell": -0.5)", "topDwell", "a dwell cannot be negative");
    bad(R"("cycle": "dwell", "plungingFeedrate": 10, "bottomDwell": -1)", "bottomDwell", "a dwell cannot be negative");
    bad(R"("cycle": "deep", "plungingFeedrate": 10, "firstDepth": 0)", "firstDepth", "a peck depth must be > 0");
    bad(R"("cycle": "deep", "plungingFeedrate": 10, "firstDepth": 1, "firstFeedrateFactor": 0)",
        "firstFeedrateFactor", "firstFeedrateFactor must be > 0");
    bad(R"("cycle": "chip-break", "plungingFeedrate": 10, "firstDepth": 1, "peckingRetract": 0)",
        "peckingRetract", "peckingRetract must be > 0");
    bad(R"("cycle": "deep", "plungingFeedrate": 10, "firstDepth": 1, "degressionType": "value", "degression": 0.1, "minimumDepth": 0)",
        "minimumDepth", "minimumDepth must be > 0");
    bad(R"("cycle": "tap", "pitch": 0)", "pitch", "pitch must be > 0");
    bad(R"("cycle": "tap", "pitch": 1, "tappingSpeed": 0)", "tappingSpeed", "tappingSpeed must be > 0");
    bad(R"("cycle": "tap-left", "pitch": 1, "retractSpeed": -5)", "retractSpeed", "retractSpeed must be > 0");
    bad(R"("plungingFeedrate": "fast")", "plungingFeedrate", "expected a number, got a string \"fast\"");
}

TEST_CASE("degression") {
    const std::string deep = R"(      "tool": 1, "cycle": "deep", "endDepth": 20, "plungingFeedrate": 100,
      "firstDepth": 5, "holes": [[0, 0]],
)";
    check_error(drill_job(deep + R"(      "degressionType": "value", "degression": 1)"),
                "/operations/0/degressionType", 12,
                "a degression needs a positive minimumDepth, or the pecks shrink towards zero forever");
    check_error(drill_job(deep + R"(      "degressionType": "factor", "degression": 0.5)"),
                "/operations/0/degressionType", 12, "a degression needs a positive minimumDepth");
    check_error(drill_job(deep + R"(      "degressionType": "factor", "minimumDepth": 1,
      "degression": 1.5)"),
                "/operations/0/degression", 13, "0 < degression <= 1");
    check_error(drill_job(deep + R"(      "degressionType": "value", "minimumDepth": 1)"),
                "/operations/0/degression", 8, "degressionType value needs a degression > 0");
    check_error(drill_job(deep + R"(      "degressionType": "value", "minimumDepth": 1, "degression": -1)"),
                "/operations/0/degression", 12, "degressionType value needs a degression > 0");
    check_error(drill_job(deep + R"(      "degression": 1)"),
                "/operations/0/degression", 12, "degression has no effect without degressionType");
    check_error(drill_job(deep + R"(      "degressionType": "none", "minimumDepth": 1)"),
                "/operations/0/minimumDepth", 12, "minimumDepth has no effect without degressionType");
    check_error(drill_job(deep + R"(      "degressionType": "linear")"),
                "/operations/0/degressionType", 12, "\"linear\" is not one of \"none\", \"value\" or \"factor\"");
    const Job ok = read_job(drill_job(deep + R"(      "degressionType": "factor", "degression": 1, "minimumDepth": 1)"),
                            "j.json");
    CHECK(drill(ok).params.values.degression_type() == DegressionType::factor);
    CHECK(drill(ok).params.values.get(DrillField::degression) == 1.0);
}

TEST_CASE("drillTip needs a tool with a tipAngle") {
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]],
      "drillTip": true)"),
                "/operations/0/drillTip", 11, "tool 1 (/tools/0) has none");
    const Job ok = read_job(drill_job(R"(      "tool": 2, "endDepth": 5, "plungingFeedrate": 100,
      "holes": [[0, 0]], "drillTip": true)"),
                            "j.json");
    CHECK(drill(ok).params.drill_tip);
    CHECK(drill(ok).tool == 2);
}

TEST_CASE("output and order choices") {
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]],
      "output": "canned", "order": "nearest")"),
                "/operations/0/order", 11, "\"nearest\" is not one of \"as-given\" or \"shortest\"");
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]],
      "output": "G81")"),
                "/operations/0/output", 11, "\"G81\" is not one of \"auto\", \"canned\" or \"longhand\"");
    const Job ok = read_job(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
      "holes": [[0, 0]], "output": "canned", "order": "shortest")"),
                            "j.json");
    CHECK(drill(ok).params.output == CycleOutput::canned);
    CHECK(drill(ok).order == HoleOrder::shortest);
}

TEST_CASE("hole source errors, at nested levels") {
    const std::string head = R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100,
)";
    check_error(drill_job(R"(      "tool": 1, "endDepth": 5, "plungingFeedrate": 100)"),
                "/operations/0", 8, "needs holes: give at least one of holes, grid, boltCircle, line or drawing (a DXF drawing's circles and points)");
    check_error(drill_job(head + R"(      "holes": [])"), "/operations/0/holes", 11, "at least one hole");
    check_error(drill_job(head + R"(      "holes": [[0, 0],
                [1, "a"]])"),
                "/operations/0/holes/1/1", 12, "expected a number, got a string \"a\"");
    check_error(drill_job(head + R"(      "holes": [[0, 0], [1, 2, 3]])"), "/operations/0/holes/1", 11,
                "expected a point [x, y], got an array");
    check_error(drill_job(head + R"(      "holes": [
        {"x": 1,
         "z": 2}])"),
                "/operations/0/holes/0/z", 13, "unknown key \"z\" (did you mean \"x\"?)");
    check_error(drill_job(head + R"(      "holes": [{"x": 1}])"), "/operations/0/holes/0/y", 11,
                "required key \"y\" is missing");
    check_error(drill_job(head + R"(      "holes": [5])"), "/operations/0/holes/0", 11,
                "expected a hole [x, y] or {\"x\": ..., \"y\": ...}, got a number (5)");
    check_error(drill_job(head + R"(      "holes": {"x": 1, "y": 2})"), "/operations/0/holes", 11,
                "expected an array, got an object");
    check_error(drill_job(head + R"(      "grid": {"origin": [0, 0], "countX": 0, "countY": 1, "spacingX": 1, "spacingY": 1})"),
                "/operations/0/grid/countX", 11, "countX must be 1 or more");
    check_error(drill_job(head + R"(      "grid": {"origin": [0, 0], "countX": 2, "countY": 1.5, "spacingX": 1, "spacingY": 1})"),
                "/operations/0/grid/countY", 11, "expected an integer, got 1.5");
    check_error(drill_job(head + R"(      "grid": {"origin": [0, 0], "countX": 2, "countY": 1,
               "spacingx": 1, "spacingY": 1})"),
                "/operations/0/grid/spacingx", 12, "(did you mean \"spacingX\"?)");
    check_error(drill_job(head + R"(      "grid": {"origin": [0, 0], "countX": 2, "countY": 1, "spacingY": 1})"),
                "/operations/0/grid/spacingX", 11, "required key \"spacingX\" is missing");
    check_error(drill_job(head + R"(      "grid": {
        "origin": ["a", 0], "countX": 2, "countY": 1, "spacingX": 1, "spacingY": 1})"),
                "/operations/0/grid/origin/0", 12, "expected a number, got a string \"a\"");
    check_error(drill_job(head + R"(      "grid": {"origin": [0, 0], "countX": 100000, "countY": 100000, "spacingX": 1, "spacingY": 1})"),
                "/operations/0/grid", 11, "too many");
    check_error(drill_job(head + R"(      "grid": [0, 0])"), "/operations/0/grid", 11, "expected an object, got an array");
    check_error(drill_job(head + R"(      "boltCircle": {"centre": [0, 0],
        "radius": 0, "count": 4})"),
                "/operations/0/boltCircle/radius", 12, "radius must be > 0");
    check_error(drill_job(head + R"(      "boltCircle": {"centre": [0, 0], "radius": 5, "count": 0})"),
                "/operations/0/boltCircle/count", 11, "count must be 1 or more");
    check_error(drill_job(head + R"(      "boltCircle": {"center": [0, 0], "radius": 5, "count": 3})"),
                "/operations/0/boltCircle/center", 11, "(did you mean \"centre\"?)");
    check_error(drill_job(head + R"(      "line": {"start": [0, 0], "end": [1, 1], "count": 0})"),
                "/operations/0/line/count", 11, "count must be 1 or more");
    check_error(drill_job(head + R"(      "line": {"start": [0, 0], "end": "here", "count": 2})"),
                "/operations/0/line/end", 11, "expected a point [x, y], got a string \"here\"");
}

TEST_CASE("contour operations") {
    const std::string ok = R"(      "z": -1, "feed": 400, "start": [10, 0],
      "path": [
        {"arc": {"end": [10, 0], "centre": [0, 0], "direction": "cw"}}
      ])";
    const Job job = read_job(contour_job(ok), "c.json");
    const auto& c = std::get<PathOp>(job.operations.at(0));
    CHECK(c.tool == 3);
    REQUIRE(c.elements.size() == 1);
    const auto& full = std::get<PathArc>(c.elements[0]);
    CHECK(full.end == Vec3{10, 0, -1});  // end == start: a full circle
    CHECK(full.direction == ArcDirection::cw);
    CHECK(c.element_path(0) == "/operations/0/path/0");

    check_error(contour_job(R"(      "z": 10, "feed": 400, "start": [0, 0], "path": [{"line": [1, 0]}])"),
                "/operations/0/z", 10, "z is above the clearance");
    check_error(contour_job(R"(      "z": -1, "feed": 0, "start": [0, 0], "path": [{"line": [1, 0]}])"),
                "/operations/0/feed", 10, "feed must be > 0");
    check_error(contour_job(R"(      "z": -1, "start": [0, 0], "path": [{"line": [1, 0]}])"),
                "/operations/0/feed", 7, "required key \"feed\" is missing");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "plungeFeed": -2, "start": [0, 0], "path": [{"line": [1, 0]}])"),
                "/operations/0/plungeFeed", 10, "plungeFeed must be > 0");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "path": [{"line": [1, 0]}])"),
                "/operations/0/start", 7, "required key \"start\" is missing");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0], "path": [])"),
                "/operations/0/path", 10, "a path needs at least one element");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [
        {"line": [1, 0]},
        {"line": [2, 0], "arc": {"end": [0, 0], "centre": [1, 0], "direction": "cw"}}
      ])"),
                "/operations/0/path/1", 13, "exactly one of \"line\", \"arc\" or \"helix\"");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [{}])"),
                "/operations/0/path/0", 11, "exactly one of \"line\", \"arc\" or \"helix\"");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [{"lines": [1, 0]}])"),
                "/operations/0/path/0/lines", 11, "unknown key \"lines\" (did you mean \"line\"?)");
    // start (0,0) is 12 from the centre (12,0); end (12,12.5) is 12.5 from it.
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [
        {"arc":
          {"end": [12, 12.5], "centre": [12, 0], "direction": "ccw"}}
      ])"),
                "/operations/0/path/0/arc", 12, "start is 12.000 mm from the centre but end is 12.500 mm");
    // The arc starts where the previous element ended.
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [
        {"line": [5, 0]},
        {"arc": {"end": [0, 0], "centre": [2, 0], "direction": "ccw"}}
      ])"),
                "/operations/0/path/1/arc", 13, "start is 3.000 mm from the centre but end is 2.000 mm");
    // Within 0.001 mm is accepted.
    CHECK_NOTHROW(read_job(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [{"arc": {"end": [20.0009, 0], "centre": [10, 0], "direction": "ccw"}}])"),
                           "c.json"));
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [{"arc": {"end": [0, 0], "centre": [0.0001, 0], "direction": "ccw"}}])"),
                "/operations/0/path/0/arc", 11, "must be more than 0.0005 mm");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [{"arc": {"end": [2, 0], "centre": [1, 0],
                        "direction": "clockwise"}}])"),
                "/operations/0/path/0/arc/direction", 12, "\"clockwise\" is not one of \"cw\" or \"ccw\"");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [{"arc": {"end": [2, 0], "centre": [1, 0]}}])"),
                "/operations/0/path/0/arc/direction", 11, "required key \"direction\" is missing");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0],
      "path": [{"line": [2, "x"]}])"),
                "/operations/0/path/0/line/1", 11, "expected a number, got a string \"x\"");
    check_error(contour_job(R"(      "z": -1, "feed": 1, "start": [0, 0], "path": [{"line": [1, 0]}],
      "endDepth": 3)"),
                "/operations/0/endDepth", 11, "unknown key \"endDepth\"");
}

TEST_CASE("read_job_file") {
    const auto dir = std::filesystem::temp_directory_path();
    const auto file = dir / "camgen_test_read_job_file_plate.json";
    {
        std::ofstream out(file);
        out << R"({"clearance": 5, "tools": [{"number": 1, "diameter": 3, "rpm": 100}],
"operations": [{"type": "drill", "tool": 1, "endDepth": 1, "plungingFeedrate": 1,
"holes": [[0, 0]], "cycle": "tap"}]})";
    }
    const InputError e = [&] {
        try {
            read_job_file(file.string());
        } catch (const InputError& error) {
            return error;
        }
        return InputError("", "");
    }();
    CHECK(e.source() == file.string());
    CHECK(e.line() == 2);

    {
        std::ofstream out(file);
        out << R"({"clearance": 5, "tools": [{"number": 1, "diameter": 3, "rpm": 100}], "operations": []})";
    }
    CHECK(read_job_file(file.string()).name == "camgen_test_read_job_file_plate");
    std::filesystem::remove(file);

    try {
        read_job_file((dir / "camgen_no_such_file.json").string());
        FAIL("no IoError");
    } catch (const IoError& error) {
        CHECK(contains(error.what(), "cannot read "));
        CHECK(contains(error.what(), "camgen_no_such_file.json: No such file or directory"));
    }
    CHECK_THROWS_AS(read_job_file(dir.string()), IoError);
}

TEST_CASE("contour: 3D points, arcs in XZ and YZ, helices, tolerance") {
    const Job job = read_job(contour_job(R"(      "z": -1, "feed": 400, "tolerance": 0.002, "start": [0, 0],
      "path": [
        {"line": [10, 0, -2]},
        {"arc": {"plane": "xz", "end": [20, 0, -2], "centre": [15, 0, -2], "direction": "cw"}},
        {"arc": {"plane": "yz", "end": [20, 10, -2], "centre": [20, 5, -2], "direction": "ccw"}},
        {"arc": {"end": [20, 10, -4], "centre": [20, 5], "direction": "cw"}},
        {"helix": {"centre": [20, 7], "direction": "ccw", "z": -9.5, "pitch": 2}},
        {"helix": {"centre": [20, 7], "direction": "cw", "turns": 2, "pitch": 0.5}},
        {"line": [0, 0]}
      ])"),
                             "c.json");
    const auto& c = std::get<PathOp>(job.operations.at(0));
    CHECK(*c.tolerance == 0.002);
    REQUIRE(c.elements.size() == 7);
    CHECK(std::get<PathLine>(c.elements[0]).end == Vec3{10, 0, -2});
    const auto& xz = std::get<PathArc>(c.elements[1]);
    CHECK(xz.plane == Plane::xz);
    CHECK(xz.centre == Vec3{15, 0, -2});
    CHECK(std::get<PathArc>(c.elements[2]).plane == Plane::yz);
    // An XY arc whose end is lower: a helical arc; its centre is at the start's Z.
    const auto& helical = std::get<PathArc>(c.elements[3]);
    CHECK(helical.end == Vec3{20, 10, -4});
    CHECK(helical.centre == Vec3{20, 5, -2});
    // From Z-4 to Z-9.5 at exactly 2 per turn: 5.5 / 2 = 2.75 turns, 2 whole and three
    // quarters, ending three quarter turns on from (20, 10) about (20, 7): (23, 7) (issue 29:
    // before, 3 whole turns of 1.833).
    const auto& h1 = std::get<PathHelix>(c.elements[4]);
    CHECK(h1.turns == 2);
    CHECK(h1.partial == doctest::Approx(1.5 * std::numbers::pi));
    CHECK(h1.end.x == doctest::Approx(23));
    CHECK(h1.end.y == doctest::Approx(7));
    CHECK(h1.end_z == -9.5);
    CHECK(h1.centre == Vec2{20, 7});
    // 2 turns of 0.5 down: Z-10.5.
    const auto& h2 = std::get<PathHelix>(c.elements[5]);
    CHECK(h2.turns == 2);
    CHECK(h2.end_z == -10.5);
    CHECK(h2.direction == ArcDirection::cw);
    // [x, y] keeps the current Z (the helix's end), as G1 X Y does: no diagonal back to z.
    CHECK(std::get<PathLine>(c.elements[6]).end == Vec3{0, 0, -10.5});

    // The helix as an event: one Arc, end above/below the start, extra turns counted.
    struct Recorder : EventSink {
        std::vector<Event> events;
        void emit(const Event& e) override { events.push_back(e); }
    } rec;
    expand_job(job, rec);
    std::vector<Arc> arcs;
    for (const Event& e : rec.events)
        if (const auto* a = std::get_if<Arc>(&e)) arcs.push_back(*a);
    REQUIRE(arcs.size() == 5);
    // The partial helix: its own sweep is the three quarters, both whole turns are extra.
    CHECK(arcs[3].to.x == doctest::Approx(23));
    CHECK(arcs[3].to.y == doctest::Approx(7));
    CHECK(arcs[3].to.z == -9.5);
    CHECK(arcs[3].centre == Vec3{20, 7, -4});
    CHECK(arcs[3].turns == 2);
    CHECK(arcs[3].direction == ArcDirection::ccw);
    CHECK(arcs[4].to.x == arcs[3].to.x);
    CHECK(arcs[4].to.y == arcs[3].to.y);
    CHECK(arcs[4].to.z == -10.5);
    CHECK(arcs[4].centre == Vec3{20, 7, -9.5});
    CHECK(arcs[4].turns == 1);
    CHECK(arcs[4].direction == ArcDirection::cw);
    CHECK(std::get<OperationStart>(rec.events.at(0)).tolerance == 0.002);
}

TEST_CASE("contour: errors of 3D elements name their JSON path") {
    auto path_of = [](const std::string& elements) {
        return contour_job(R"(      "z": -1, "feed": 400, "start": [0, 0],
      "path": [)" + elements + "]");
    };
    check_error(path_of(R"({"line": [1, 2, 3, 4]})"), "/operations/0/path/0/line", 11, "expected a point [x, y] or [x, y, z]");
    check_error(path_of(R"({"line": [1, 2, 12]})"), "/operations/0/path/0/line", 11, "at or above the clearance");
    check_error(path_of(R"({"arc": {"plane": "xz", "end": [10, 0, -1], "centre": [5, 0], "direction": "cw"}})"),
                "/operations/0/path/0/arc/centre", 11, "an xz arc needs its centre as [x, y, z]");
    check_error(path_of(R"({"arc": {"plane": "xz", "end": [10, 0, -1], "centre": [5, 3, -1], "direction": "cw"}})"),
                "/operations/0/path/0/arc/centre", 11, "the centre's y (3.000 mm) must be the start's y (0.000 mm) in an xz arc");
    // Equidistance in the arc's plane: in XZ the start (x 0, z -1) is 5 from (5, -1), the end
    // (x 10, z -2) is sqrt(25 + 1) = 5.099 from it.
    check_error(path_of(R"({"arc": {"plane": "xz", "end": [10, 0, -2], "centre": [5, 0, -1], "direction": "cw"}})"),
                "/operations/0/path/0/arc", 11, "start is 5.000 mm from the centre but end is 5.099 mm (in the xz plane)");
    // ccw in XZ from (0, z -1) about (5, z -1) goes up over the top (Z 4): above the clearance 10? No: 4 < 10.
    CHECK_NOTHROW(read_job(path_of(R"({"arc": {"plane": "xz", "end": [10, 0, -1], "centre": [5, 0, -1], "direction": "ccw"}})"), "j.json"));
    // With radius 12 the top is at Z 11: above the clearance.
    check_error(path_of(R"({"arc": {"plane": "xz", "end": [24, 0, -1], "centre": [12, 0, -1], "direction": "ccw"}})"),
                "/operations/0/path/0/arc", 11, "the arc reaches Z 11.000 mm, at or above the clearance");
    check_error(path_of(R"({"arc": {"plane": "xy", "end": [2, 0], "centre": [1, 0, 4], "direction": "cw"}})"),
                "/operations/0/path/0/arc/centre", 11, "the centre's z (4.000 mm) must be the start's z (-1.000 mm)");
    check_error(path_of(R"({"arc": {"plane": "uv", "end": [2, 0], "centre": [1, 0], "direction": "cw"}})"),
                "/operations/0/path/0/arc/plane", 11, "\"uv\" is not one of");
    check_error(path_of(R"({"helix": {"centre": [0, 2], "direction": "cw", "turns": 2}})"),
                "/operations/0/path/0/helix", 11, "exactly two of \"z\" (end Z), \"turns\" and \"pitch\"");
    check_error(path_of(R"({"helix": {"centre": [0, 2], "direction": "cw", "turns": 2, "pitch": 1, "z": -3}})"),
                "/operations/0/path/0/helix", 11, "exactly two of");
    check_error(path_of(R"({"helix": {"centre": [0, 2], "direction": "cw", "turns": 0, "z": -3}})"),
                "/operations/0/path/0/helix/turns", 11, "turns must be a whole number from 1 to 100000");
    check_error(path_of(R"({"helix": {"centre": [0, 2], "direction": "cw", "turns": 2, "pitch": -1}})"),
                "/operations/0/path/0/helix/pitch", 11, "pitch must be > 0");
    check_error(path_of(R"({"helix": {"centre": [0, 2], "direction": "cw", "turns": 2, "z": -1}})"),
                "/operations/0/path/0/helix/z", 11, "a helix must change Z");
    check_error(path_of(R"({"helix": {"centre": [0, 0], "direction": "cw", "turns": 2, "z": -3}})"),
                "/operations/0/path/0/helix/centre", 11, "the helix radius is 0.0000 mm");
    check_error(path_of(R"({"helix": {"centre": [0, 2], "direction": "cw", "turns": 2, "z": 12}})"),
                "/operations/0/path/0/helix/z", 11, "at or above the clearance");
    check_error(path_of(R"({"helix": {"centre": [0, 2], "direction": "cw", "turn": 2, "z": -3}})"),
                "/operations/0/path/0/helix/turn", 11, "unknown key \"turn\" (did you mean \"turns\"?)");
    check_error(contour_job(R"(      "z": -1, "feed": 400, "tolerance": 0, "start": [0, 0], "path": [{"line": [1, 0]}])"),
                "/operations/0/tolerance", 10, "tolerance must be at least 0.0001 mm");
    check_error(contour_job(R"(      "z": -1, "feed": 400, "tolerance": 0.00001, "start": [0, 0], "path": [{"line": [1, 0]}])"),
                "/operations/0/tolerance", 10, "tolerance must be at least 0.0001 mm");
}

}  // namespace test_job_json
