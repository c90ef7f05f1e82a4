// The job's stock (issue 27, step 1): its forms read in mm and inch, each error at its JSON path
// and line, the checks that use it (clearance and retract planes above its top, a face's top,
// a cut below its bottom), face facing its outline, and the tool shapes (bull-nose, chamfer
// mill, V-bit) with the operations that take them.
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "camgen/operations/stock.hpp"
#include "camgen/post/safety.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_stock {

using namespace camgen;
using Json = nlohmann::json;
using test::file_with;

// A mill job with `stock` (JSON text, or empty: none) and `operations` (JSON text of the array),
// one tool per line so that errors name known lines: the stock starts on line 3.
std::string stock_job(const std::string& stock, const std::string& operations = "[]", const std::string& units = "mm",
                      double clearance = 15) {
    return "{\"units\": \"" + units + "\", \"clearance\": " + std::to_string(clearance) + ",\n" +
           (stock.empty() ? std::string("\n") : "\"stock\": " + stock + ",\n") +
           "\"tools\": [{\"number\": 1, \"type\": \"end-mill\", \"diameter\": 6, \"rpm\": 8000},\n"
           "  {\"number\": 2, \"type\": \"spot-drill\", \"diameter\": 10, \"tipAngle\": 90, \"rpm\": 2000}],\n"
           "\"operations\": " +
           operations + "}\n";
}

// The error read_job throws for `text` ("" if it reads).
std::string stock_error(const std::string& text) {
    try {
        (void)read_job(text, "test.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const std::string stock_contour = R"({"type": "contour", "tool": 1, "endDepth": DEPTH, "side": "outside", "feed": 500,
  "start": [0, 0], "path": [{"line": [40, 0]}, {"line": [40, 30]}, {"line": [0, 30]}, {"line": [0, 0]}]})";

std::string contour_at(const std::string& depth) {
    std::string s = stock_contour;
    s.replace(s.find("DEPTH"), 5, depth);
    return "[" + s + "]";
}

TEST_CASE("stock: a box by min and max corners, in mm and in inch") {
    const Job job = read_job(stock_job(R"({"box": {"min": [-5, -6, -10], "max": [100, 70, 0.5]}})"), "test.json");
    REQUIRE(job.stock);
    CHECK(job.stock->shape == StockShape::box);
    CHECK(job.stock->min.x == -5);
    CHECK(job.stock->min.y == -6);
    CHECK(job.stock->bottom() == -10);
    CHECK(job.stock->max.x == 100);
    CHECK(job.stock->max.y == 70);
    CHECK(job.stock->top() == 0.5);
    CHECK(job.stock->path == "/stock/box");
    CHECK(job.stock->line == 2);
    // Its outline is the box's rectangle, closed.
    CHECK(job.stock->outline.segments.size() == 4);
    CHECK(job.stock->outline.segments.back().end == job.stock->outline.start);
    const Job inch = read_job(stock_job(R"({"box": {"min": [0, 0, -1], "max": [4, 2, 0]}})", "[]", "inch", 1), "test.json");
    CHECK(inch.stock->max.x == doctest::Approx(101.6));
    CHECK(inch.stock->bottom() == doctest::Approx(-25.4));
    // No stock: none.
    CHECK_FALSE(read_job(stock_job(""), "test.json").stock);
}

TEST_CASE("stock: a box by size has its top at Z0 and its min corner at X0 Y0 unless origin says otherwise") {
    const Job job = read_job(stock_job(R"({"box": {"size": [100, 70, 12]}})"), "test.json");
    CHECK(job.stock->min == Vec3{0, 0, -12});
    CHECK(job.stock->max == Vec3{100, 70, 0});
    const Job moved = read_job(stock_job(R"({"box": {"size": [100, 70, 12], "origin": [-50, -35, -2]}})"), "test.json");
    CHECK(moved.stock->min == Vec3{-50, -35, -2});
    CHECK(moved.stock->max == Vec3{50, 35, 10});
    const Job inch = read_job(stock_job(R"({"box": {"size": [2, 1, 0.5]}})", "[]", "inch", 1), "test.json");
    CHECK(inch.stock->min.z == doctest::Approx(-12.7));
    CHECK(inch.stock->max.x == doctest::Approx(50.8));
}

TEST_CASE("stock: a closed profile with top and bottom, its bounding box from its arcs") {
    const Job job = read_job(stock_job(R"({"profile": {"start": [0, 0], "path": [{"line": [50, 0]},
      {"arc": {"end": [50, 40], "centre": [50, 20], "direction": "ccw"}}, {"line": [0, 40]}, {"line": [0, 0]}],
      "top": 1, "bottom": -8}})"),
                               "test.json");
    REQUIRE(job.stock);
    CHECK(job.stock->shape == StockShape::profile);
    CHECK(job.stock->top() == 1);
    CHECK(job.stock->bottom() == -8);
    CHECK(job.stock->max.x == doctest::Approx(70).epsilon(1e-4));  // the arc bulges 20 beyond X50
    CHECK(job.stock->min.y == doctest::Approx(0));
    CHECK(job.stock->max.y == doctest::Approx(40));
    CHECK(job.stock->path == "/stock/profile");
    const Job inch = read_job(stock_job(R"({"profile": {"start": [0, 0], "path": [{"line": [1, 0]}, {"line": [1, 1]},
      {"line": [0, 0]}], "top": 0, "bottom": -0.25}})",
                                        "[]", "inch", 1),
                               "test.json");
    CHECK(inch.stock->max.x == doctest::Approx(25.4));
    CHECK(inch.stock->bottom() == doctest::Approx(-6.35));
}

TEST_CASE("stock: a lathe's bar, in mm and in inch") {
    const Job job = read_job(stock_job(R"({"bar": {"diameter": 40, "length": 120, "faceZ": 2, "boreDiameter": 12}})"), "test.json");
    REQUIRE(job.stock);
    CHECK(job.stock->shape == StockShape::bar);
    CHECK_FALSE(job.stock->for_mill());
    CHECK(job.stock->diameter == 40);
    CHECK(job.stock->length == 120);
    CHECK(job.stock->face_z == 2);
    CHECK(job.stock->bore_diameter == 12.0);
    CHECK(job.stock->top() == 2);
    CHECK(job.stock->bottom() == -118);
    const Job inch = read_job(stock_job(R"({"bar": {"diameter": 2, "length": 4}})", "[]", "inch", 1), "test.json");
    CHECK(inch.stock->diameter == doctest::Approx(50.8));
    CHECK(inch.stock->face_z == 0);
    CHECK_FALSE(inch.stock->bore_diameter);
}

TEST_CASE("stock: each error names its JSON path and line") {
    const auto error = [](const std::string& stock) { return stock_error(stock_job(stock)); };
    CHECK(error(R"({"box": {"min": [0, 0, 0],
      "max": [10, 10, -5]}})") == "test.json:3: /stock/box/max/2: max Z (-5.000 mm) must be above min Z (0.000 mm)");
    CHECK(error(R"({"box": {"min": [0, 0, -5], "max": [0, 10, 0]}})") ==
          "test.json:2: /stock/box/max/0: max X (0.000 mm) must be above min X (0.000 mm)");
    CHECK(error(R"({"box": {"size": [10, 0, 5]}})") == "test.json:2: /stock/box/size/1: the size in Y (0.000 mm) must be more than 0");
    CHECK(error(R"({"box": {"min": [0, 0, -5], "size": [10, 10, 5]}})") ==
          "test.json:2: /stock/box: a stock box needs either min and max, or size (and origin)");
    CHECK(error(R"({"box": {"min": [0, 0, -5]}})").find("test.json:2: /stock/box") == 0);
    CHECK(error(R"({"box": {"size": [10, 10, 5], "max": [1, 1, 1]}})").find("/stock/box/max: max goes with min") != std::string::npos);
    CHECK(error(R"({"box": {"min": [0, 0, -5], "max": [1, 1, 1], "origin": [0, 0, 0]}})").find("/stock/box/origin: origin goes with size") !=
          std::string::npos);
    CHECK(error(R"({"box": {"min": [0, 0], "max": [1, 1, 1]}})") ==
          "test.json:2: /stock/box/min: expected a point [x, y, z], got an array");
    CHECK(error(R"({"box": {"sise": [1, 1, 1]}})") == "test.json:2: /stock/box/sise: unknown key \"sise\" (did you mean \"size\"?)");
    CHECK(error(R"({"boxx": {"size": [1, 1, 1]}})") == "test.json:2: /stock/boxx: unknown key \"boxx\" (did you mean \"box\"?)");
    CHECK(error(R"({})") == "test.json:2: /stock: a stock is exactly one of box, profile (mills) or bar (lathes)");
    CHECK(error(R"({"box": {"size": [1, 1, 1]}, "bar": {"diameter": 1, "length": 1}})") ==
          "test.json:2: /stock/bar: a stock is exactly one of box, profile (mills) or bar (lathes)");
    CHECK(error(R"([1])") == "test.json:2: /stock: expected an object, got an array");
    CHECK(error(R"({"profile": {"start": [0, 0], "path": [{"line": [10, 0]}, {"line": [10, 10]}], "top": 0, "bottom": -5}})")
              .find("test.json:2: /stock/profile/path: the stock's outline must be closed") == 0);
    CHECK(error(R"({"profile": {"start": [0, 0], "path": [{"line": [10, 0]}, {"line": [10, 10]}, {"line": [0, 0]}],
      "top": 0, "bottom": 0}})") == "test.json:3: /stock/profile/bottom: bottom (Z 0.000 mm) must be below top (Z 0.000 mm)");
    CHECK(error(R"({"profile": {"start": [0, 0], "path": [{"line": [10, 0]}, {"line": [10, 10]}, {"line": [0, 0]}], "top": 0}})") ==
          "test.json:2: /stock/profile/bottom: required key \"bottom\" is missing");
    CHECK(error(R"({"bar": {"diameter": 20, "length": 50, "boreDiameter": 20}})") ==
          "test.json:2: /stock/bar/boreDiameter: boreDiameter 20.000 mm must be more than 0 and less than the bar's diameter (20.000 mm)");
    CHECK(error(R"({"bar": {"diameter": 0, "length": 50}})") == "test.json:2: /stock/bar/diameter: a bar's diameter must be > 0");
    CHECK(error(R"({"bar": {"diameter": 10, "length": -1}})") == "test.json:2: /stock/bar/length: a bar's length must be > 0");
    // Inch jobs say their values in inch.
    CHECK(stock_error(stock_job(R"({"box": {"min": [0, 0, 0], "max": [1, 1, -0.5]}})", "[]", "inch", 1)) ==
          "test.json:2: /stock/box/max/2: max Z (-0.5000 in) must be above min Z (0.0000 in)");
}

TEST_CASE("stock: the clearance must be above the stock top, read with the other errors of the job") {
    CHECK(stock_error(stock_job(R"({"box": {"size": [10, 10, 5], "origin": [0, 0, 12]}})")) ==
          "test.json:1: /clearance: the clearance (Z 15.000 mm) is not above the stock top (Z 17.000 mm, /stock/box): moves "
          "between operations would run through the material");
    CHECK(stock_error(stock_job(R"({"bar": {"diameter": 10, "length": 10, "faceZ": 15}})"))
              .find("/clearance: the clearance (Z 15.000 mm) is not above the bar's face (Z 15.000 mm, /stock/bar)") !=
          std::string::npos);
    // A stock's error and an operation's are reported together.
    const std::string both = stock_error(stock_job(R"({"box": {"size": [10, 10, 0]}})", R"([{"type": "drill", "tool": 9,
      "holes": [[1, 1]], "endDepth": 1, "plungingFeedrate": 100}])"));
    CHECK(both.find("/stock/box/size/2") != std::string::npos);
    CHECK(both.find("/operations/0/tool: tool 9 is not in /tools") != std::string::npos);
}

TEST_CASE("stock: a bar on a mill and a box on a lathe are refused at the stock, naming both kinds") {
    const Job bar = read_job(stock_job(R"({"bar": {"diameter": 40, "length": 100}})"), "test.json");
    try {
        check_machine_kind(bar, MachineKind::mill, "fanuc");
        FAIL("a bar on a mill was accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()) ==
              "test.json:2: /stock/bar: a stock bar is for a lathe, and machine fanuc is a mill: give a mill's stock as a box or profile");
    }
    const Job box = read_job(stock_job(R"({"box": {"size": [10, 10, 5]}})"), "test.json");
    CHECK_THROWS_WITH_AS(check_machine_kind(box, MachineKind::lathe, "fanuc-lathe"),
                         "test.json:2: /stock/box: a stock box or profile is for a mill, and machine fanuc-lathe is a lathe: give a "
                         "lathe's stock as a bar",
                         InputError);
    CHECK_NOTHROW(check_machine_kind(box, MachineKind::mill, "fanuc"));
    // On the command line too, nothing written.
    const std::string file = file_with("bar-on-mill.json", stock_job(R"({"bar": {"diameter": 40, "length": 100}})"));
    const test::Run r = test::run({file, "--machine", "fanuc"});
    CHECK(r.code == 1);
    CHECK(r.out.empty());
    CHECK(r.err.find("/stock/bar: a stock bar is for a lathe") != std::string::npos);
}

TEST_CASE("stock: an operation's retract plane must be above the stock top; its reference plane defaults to it") {
    const std::string stock = R"({"box": {"size": [50, 40, 10], "origin": [0, 0, -7]}})";  // top at Z3
    CHECK(stock_error(stock_job(stock, R"([{"type": "drill", "tool": 2,
      "holes": [[5, 5]], "retractPlane": 2, "referencePlane": 0, "endDepth": 1, "plungingFeedrate": 100}])")) ==
          "test.json:6: /operations/0/retractPlane: retractPlane (Z 2.000 mm) is not above the stock top (Z 3.000 mm, "
          "/stock/box): between holes the tool would rapid through the material");
    // Without referencePlane a drill starts at the stock top.
    const Job job = read_job(stock_job(stock, R"([{"type": "drill", "tool": 2, "holes": [[5, 5]], "endDepth": 1, "plungingFeedrate": 100}])"), "test.json");
    CHECK(std::get<DrillOp>(job.operations.at(0)).params.reference_plane == 3);
    // Without a stock it is Z0, as always.
    const Job none = read_job(stock_job("", R"([{"type": "drill", "tool": 2, "holes": [[5, 5]], "endDepth": 1, "plungingFeedrate": 100}])"), "test.json");
    CHECK(std::get<DrillOp>(none.operations.at(0)).params.reference_plane == 0);
    // A reference plane below the stock top is an operation's own business (a drill from a counterbore's floor).
    CHECK_NOTHROW(read_job(stock_job(stock, R"([{"type": "drill", "tool": 2, "holes": [[5, 5]], "referencePlane": -2,
      "endDepth": 1, "plungingFeedrate": 100}])"),
                           "test.json"));
}

TEST_CASE("stock: a face starts at the stock top, and without an area faces the stock's outline") {
    const std::string stock = R"({"box": {"min": [0, 0, -10], "max": [100, 60, 1]}})";
    const std::string face = R"({"type": "face", "tool": 1, "endDepth": 1, "feed": 600, "overhang": 2, "stepOver": 4})";
    CHECK(stock_error(stock_job(stock, R"([{"type": "face", "tool": 1, "referencePlane": 0, "endDepth": 1,
      "feed": 600}])")) == "test.json:5: /operations/0/referencePlane: referencePlane (Z 0.000 mm) is not the stock top (Z 1.000 "
                          "mm, /stock/box): a face starts at the stock top (leave referencePlane out to take it)");
    const Job job = read_job(stock_job(stock, "[" + face + "]"), "test.json");
    const auto& op = std::get<FaceOp>(job.operations.at(0));
    CHECK(op.heights.reference_plane == 1);
    double lo_x = 1e9, hi_x = -1e9, lo_y = 1e9, hi_y = -1e9;
    for (const auto& [a, b] : op.row_paths)
        for (Vec2 p : {a, b}) {
            lo_x = std::min(lo_x, p.x);
            hi_x = std::max(hi_x, p.x);
            lo_y = std::min(lo_y, p.y);
            hi_y = std::max(hi_y, p.y);
        }
    // The rows run past the box by the tool radius and the overhang (3 + 2).
    CHECK(lo_x == doctest::Approx(-5));
    CHECK(hi_x == doctest::Approx(105));
    CHECK(lo_y > -5);
    CHECK(lo_y < 0);
    CHECK(hi_y > 60);
    CHECK(hi_y < 65);
    // A stock profile is faced over its outline.
    const Job round = read_job(stock_job(R"({"profile": {"start": [-20, 0], "path": [{"arc": {"end": [-20, 0], "centre": [0, 0],
      "direction": "ccw"}}], "top": 0, "bottom": -5}})",
                                         "[" + face + "]"),
                               "test.json");
    double reach = 0;
    for (const auto& [a, b] : std::get<FaceOp>(round.operations.at(0)).row_paths) reach = std::max({reach, std::hypot(a.x, a.y), std::hypot(b.x, b.y)});
    CHECK(reach == doctest::Approx(25).epsilon(1e-3));
    // Without an area and without a stock, or with a bar, there is nothing to face.
    CHECK(stock_error(stock_job("", "[" + face + "]")) ==
          "test.json:5: /operations/0: a face needs a rectangle, start and path, a profile, or a stock (box or profile) in the job to face");
    CHECK(stock_error(stock_job(R"({"bar": {"diameter": 40, "length": 100}})", "[" + face + "]")).find(
              "/operations/0: a face needs a rectangle, start and path, or a profile: the job's stock is a lathe's bar") != std::string::npos);
}

TEST_CASE("stock: a cut below the stock bottom is a warning naming the operation, its lowest Z and the bottom") {
    const std::string plate = R"({"box": {"min": [-10, -10, -10], "max": [50, 40, 0]}})";
    const std::string deep = file_with("deep-contour.json", stock_job(plate, contour_at("30")));
    const test::Run r = test::run({deep, "--machine", "fanuc"});
    CHECK(r.code == 0);
    CHECK(r.err.find("camgen: warning: /operations/0: the operation goes down to Z -30.000, 20.000 mm below the stock bottom "
                     "(Z -10.000): into what holds the stock") != std::string::npos);
    // Within the plate: no warning; without a stock: none either.
    CHECK(test::run({file_with("shallow-contour.json", stock_job(plate, contour_at("10"))), "--machine", "fanuc"}).err.find("warning") ==
          std::string::npos);
    CHECK(test::run({file_with("no-stock-contour.json", stock_job("", contour_at("30"))), "--machine", "fanuc"}).err.find("warning") ==
          std::string::npos);
    // A drilling cycle's bottom counts, on a machine that writes it canned.
    const std::string drill = file_with("deep-drill.json", stock_job(plate, R"([{"type": "drill", "tool": 2, "holes": [[5, 5]],
      "endDepth": 12, "plungingFeedrate": 100}])"));
    CHECK(test::run({drill, "--machine", "fanuc"}).err.find("/operations/0: the operation goes down to Z -12.000, 2.000 mm below") !=
          std::string::npos);
    // The warning writes nothing into the program: it is the same with and without the stock.
    const std::string same = file_with("deep-contour-plain.json", stock_job("", contour_at("30")));
    const auto body = [](const std::string& program) { return program.substr(program.find("N10")); };
    CHECK(body(test::run({same, "--machine", "fanuc"}).out) == body(r.out));
}

TEST_CASE("stock: the safety check's warning comes from the events, on its own") {
    std::ostringstream warnings;
    SafetyCheck check(SafetyLimits{.clearance = 20, .flute_lengths = {}, .longhand = {}});
    check.warn_below_stock(-5.0, warnings);
    std::vector<Event> events{OperationStart{"path", "/operations/3", std::nullopt, {}, std::nullopt, FeedMode::per_minute},
                              ToolChange{1, 6, "6 mm end mill"},
                              Rapid{{0, 0, 20}},
                              Linear{{0, 0, 1}, 100},
                              Linear{{0, 0, -4}, 100},
                              // An arc in XZ that dips to Z -6 between its ends at Z -4.
                              Arc{{4, 0, -4}, {2, 0, -4}, ArcDirection::cw, Plane::xz, 100},
                              Rapid{{4, 0, 20}},
                              OperationEnd{}};
    for (const Event& e : events) check.emit(e);
    check.finish();
    CHECK(warnings.str().find("/operations/3: the operation goes down to Z -6.000, 1.000 mm below the stock bottom (Z -5.000)") !=
          std::string::npos);
}

TEST_CASE("stock: --events has the stock first, and nothing more without one") {
    const test::Run r = test::run({file_with("events-stock.json", stock_job(R"({"box": {"size": [120, 80, 12]}})")), "--events"});
    CHECK(r.code == 0);
    CHECK(test::lines_of(r.out).at(0) == R"({"event":"stock","shape":"box","path":"/stock/box","min":[0.0,0.0,-12.0],"max":[120.0,80.0,0.0]})");
    const test::Run bar = test::run({file_with("events-bar.json", stock_job(R"({"bar": {"diameter": 40, "length": 100, "boreDiameter": 10}})")),
                                     "--events"});
    CHECK(test::lines_of(bar.out).at(0).find(R"("diameter":40.0,"length":100.0,"faceZ":0.0,"boreDiameter":10.0)") != std::string::npos);
    const test::Run none = test::run({file_with("events-none.json", stock_job("")), "--events"});
    CHECK(none.out.find("stock") == std::string::npos);
}

// ---- Tool shapes

std::string tool_job(const std::string& tool, const std::string& operations = "[]") {
    return "{\"clearance\": 10,\n\"tools\": [" + tool + "],\n\"operations\": " + operations + "}\n";
}

TEST_CASE("tools: bull-nose, chamfer-mill and v-bit read with their shapes, in mm and inch") {
    const Job bull = read_job(tool_job(R"({"number": 1, "type": "bull-nose", "diameter": 10, "cornerRadius": 1, "rpm": 5000})"), "t.json");
    CHECK(bull.tools.at(1).type == ToolType::bull_nose);
    CHECK(bull.tools.at(1).corner_radius == 1.0);
    CHECK_FALSE(bull.tools.at(1).centre_cutting);
    const Job vbit = read_job(tool_job(R"({"number": 1, "type": "v-bit", "diameter": 6, "tipAngle": 60, "tipDiameter": 0.2,
      "rpm": 18000})"),
                              "t.json");
    CHECK(vbit.tools.at(1).tip_angle == 60.0);
    CHECK(vbit.tools.at(1).tip_diameter == 0.2);
    CHECK(vbit.tools.at(1).centre_cutting);
    const Job chamfer = read_job(tool_job(R"({"number": 1, "type": "chamfer-mill", "diameter": 12, "tipAngle": 90, "rpm": 6000})"), "t.json");
    CHECK(chamfer.tools.at(1).tip_diameter == 0.0);
    CHECK_FALSE(chamfer.tools.at(1).centre_cutting);
    const Job inch = read_job("{\"units\": \"inch\", \"clearance\": 1, \"tools\": [{\"number\": 1, \"type\": \"bull-nose\", "
                              "\"diameter\": 0.5, \"cornerRadius\": 0.25, \"rpm\": 5000}, {\"number\": 2, \"type\": \"v-bit\", "
                              "\"diameter\": 0.25, \"tipAngle\": 30, \"tipDiameter\": 0.01, \"rpm\": 5000}], \"operations\": []}",
                              "t.json");
    CHECK(inch.tools.at(1).corner_radius.value() == doctest::Approx(6.35));
    CHECK(inch.tools.at(2).tip_diameter == doctest::Approx(0.254));
    // The tool list names the shapes.
    const std::string program = test::post_job(tool_job(R"({"number": 1, "type": "bull-nose", "diameter": 10, "cornerRadius": 1,
      "rpm": 5000})",
                                                        R"([{"type": "path", "tool": 1, "z": -1, "start": [0, 0], "path": [{"line": [10, 0]}],
      "feed": 300}])"),
                                               "linuxcnc")
                                    .text;
    CHECK(program.find("bull-nose end mill") != std::string::npos);
}

TEST_CASE("tools: the shape keys' errors name their path and line") {
    const auto error = [](const std::string& tool) { return stock_error(tool_job(tool)); };
    CHECK(stock_error(tool_job(R"({"number": 1, "type": "bull-nose", "diameter": 10, "rpm": 5000})")) ==
          "test.json:2: /tools/0/cornerRadius: a bull-nose end mill needs its cornerRadius");
    CHECK(error(R"({"number": 1, "type": "bull-nose", "diameter": 10, "cornerRadius": 5.5, "rpm": 5000})") ==
          "test.json:2: /tools/0/cornerRadius: cornerRadius 5.500 mm must be more than 0 and at most half the diameter (5.000 mm); "
          "a corner radius of half the diameter is a ball-mill");
    CHECK(error(R"({"number": 1, "type": "bull-nose", "diameter": 10, "cornerRadius": 0, "rpm": 5000})").find(
              "/tools/0/cornerRadius: cornerRadius 0.000 mm must be more than 0") != std::string::npos);
    CHECK(error(R"({"number": 1, "type": "end-mill", "diameter": 10, "cornerRadius": 1, "rpm": 5000})") ==
          "test.json:2: /tools/0/cornerRadius: cornerRadius is for a bull-nose end mill, not an end-mill (a ball-mill's is half its "
          "diameter)");
    CHECK(error(R"({"number": 1, "type": "v-bit", "diameter": 6, "rpm": 5000})") ==
          "test.json:2: /tools/0/tipAngle: a v-bit needs its tipAngle (the included angle of its point)");
    CHECK(error(R"({"number": 1, "type": "chamfer-mill", "diameter": 6, "tipAngle": 180, "rpm": 5000})") ==
          "test.json:2: /tools/0/tipAngle: tipAngle 180 degrees is not a chamfer-mill's point: it must be more than 0 and less "
          "than 180 degrees");
    CHECK(error(R"({"number": 1, "type": "v-bit", "diameter": 6, "tipAngle": 60, "tipDiameter": 6, "rpm": 5000})") ==
          "test.json:2: /tools/0/tipDiameter: tipDiameter 6.000 mm must be at least 0 and less than the diameter (6.000 mm)");
    CHECK(error(R"({"number": 1, "type": "drill", "diameter": 6, "tipDiameter": 1, "rpm": 5000})") ==
          "test.json:2: /tools/0/tipDiameter: tipDiameter is for a chamfer-mill, v-bit or engraver, not a drill");
    // A drill's point keeps its bounds; a V-bit may be finer.
    CHECK(error(R"({"number": 1, "type": "drill", "diameter": 6, "tipAngle": 20, "rpm": 5000})").find("is not a drill point") !=
          std::string::npos);
    CHECK(error(R"({"number": 1, "type": "v-bit", "diameter": 6, "tipAngle": 20, "rpm": 5000})").empty());
    CHECK(error(R"({"number": 1, "type": "v-bits", "diameter": 6, "rpm": 5000})").find("did you mean \"v-bit\"") != std::string::npos);
}

TEST_CASE("tools: contour, pocket and face refuse a chamfer mill or V-bit; path takes any milling tool") {
    const std::string tools = R"({"number": 1, "type": "v-bit", "diameter": 6, "tipAngle": 60, "rpm": 18000},
      {"number": 2, "type": "chamfer-mill", "diameter": 10, "tipAngle": 90, "rpm": 6000},
      {"number": 3, "type": "bull-nose", "diameter": 10, "cornerRadius": 1, "rpm": 6000},
      {"number": 4, "type": "ball-mill", "diameter": 6, "rpm": 6000},
      {"number": 5, "type": "spot-drill", "diameter": 10, "tipAngle": 90, "rpm": 1500},
      {"number": 6, "type": "reamer", "diameter": 8, "rpm": 300},
      {"number": 7, "type": "tap", "diameter": 8, "rpm": 300},
      {"number": 8, "type": "drill", "diameter": 8, "rpm": 800},
      {"number": 9, "diameter": 8, "rpm": 800},
      {"number": 10, "type": "engraver", "diameter": 3, "tipAngle": 30, "tipDiameter": 0.2, "rpm": 18000})";
    const std::string square = R"("start": [0, 0], "path": [{"line": [40, 0]}, {"line": [40, 30]}, {"line": [0, 30]}, {"line": [0, 0]}])";
    const auto op = [&](const std::string& type, int tool) {
        std::string extra = type == "contour" ? R"("side": "outside", )" : "";
        return stock_error(tool_job(tools, "[{\"type\": \"" + type + "\", \"tool\": " + std::to_string(tool) + ", " + extra +
                                               "\"endDepth\": 1, \"feed\": 500, " + square + "}]"));
    };
    CHECK(op("contour", 1) ==
          "test.json:12: /operations/0/tool: tool 1 is a V-bit: a contour cuts with an end mill, a ball mill or a bull-nose end mill "
          "(the side of a pointed tool is not its diameter); a chamfer mill or a V-bit cuts chamfers with the chamfer operation");
    CHECK(op("pocket", 2).find("/operations/0/tool: tool 2 is a chamfer mill: a pocket cuts with") != std::string::npos);
    CHECK(op("face", 1).find("/operations/0/tool: tool 1 is a V-bit: a face cuts with") != std::string::npos);
    // The issue's spot drill along a contour (it was offset by its full diameter and cut air), a reamer, a tap.
    CHECK(op("contour", 5) ==
          "test.json:12: /operations/0/tool: tool 5 is a spot drill: a contour cuts with an end mill, a ball mill or a bull-nose "
          "end mill (its side cuts along the profile; a spot drill's does not)");
    CHECK(op("pocket", 6).find("/operations/0/tool: tool 6 is a reamer: a pocket cuts with") != std::string::npos);
    CHECK(op("face", 7).find("/operations/0/tool: tool 7 is a tap: a face cuts with") != std::string::npos);
    CHECK(op("contour", 10).find("/operations/0/tool: tool 10 is an engraver: a contour cuts with") != std::string::npos);
    // A tool typed drill is refused, with the way out; one given no type (a drill by default)
    // mills, with a note that says so.
    CHECK(op("contour", 8) ==
          "test.json:12: /operations/0/tool: tool 8 is a drill: a contour cuts with an end mill, a ball mill or a bull-nose "
          "end mill (its side cuts along the profile; a drill's does not); give an end mill \"type\": \"end-mill\"");
    CHECK(op("pocket", 8).find("/operations/0/tool: tool 8 is a drill: a pocket cuts with") != std::string::npos);
    CHECK(op("face", 8).find("/operations/0/tool: tool 8 is a drill: a face cuts with") != std::string::npos);
    for (const char* type : {"contour", "pocket", "face"})
        for (int tool : {3, 4, 9}) {
            CAPTURE(type);
            CAPTURE(tool);
            CHECK(op(type, tool).empty());
        }
    for (const char* type : {"contour", "pocket", "face"})
        for (int tool : {3, 9}) {
            CAPTURE(type);
            std::string extra = std::string(type) == "contour" ? R"("side": "outside", )" : "";
            const Job job = read_job(tool_job(tools, "[{\"type\": \"" + std::string(type) + "\", \"tool\": " + std::to_string(tool) +
                                                         ", " + extra + "\"endDepth\": 1, \"feed\": 500, " + square + "}]"),
                                     "test.json");
            std::vector<std::string> notes;
            if (const auto* c = std::get_if<ContourOp>(&job.operations.at(0))) notes = c->notes;
            if (const auto* c = std::get_if<PocketOp>(&job.operations.at(0))) notes = c->notes;
            if (const auto* c = std::get_if<FaceOp>(&job.operations.at(0))) notes = c->notes;
            const bool noted = std::any_of(notes.begin(), notes.end(), [](const std::string& n) {
                return n.find("has no type: it mills as an end mill (a tool without a type is a drill") != std::string::npos;
            });
            CHECK(noted == (tool == 9));
        }
    // An engraving line with a V-bit is a path.
    CHECK_NOTHROW(read_job(tool_job(tools, R"([{"type": "path", "tool": 1, "z": -0.3, "start": [0, 0],
      "path": [{"line": [10, 0]}], "feed": 300}])"),
                           "test.json"));
}

}  // namespace test_stock
