// The chamfer operation (issue 29, item 3): its depth and offset from the tool's cone (the tip
// tipClearance below the chamfer's lower edge, the tool centre where its cone passes through
// that edge), measured back from the moves it makes; along profiles and around holes; the
// part-aware check; the tools it refuses (a tool of another type, a cone of another angle, a
// cone too short for the chamfer, a tool that does not fit the hole), each at its JSON path; and
// the simulation that checks a chamfer against its designed face.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/job/tool_geometry.hpp"
#include "camgen/operations/design.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_chamfer {

namespace fs = std::filesystem;
using namespace camgen;

namespace {

const std::string chamfer_samples = CAMGEN_SOURCE_DIR "/samples/";

// A job with a V-bit (tool 3, `tool` keys) and one chamfer operation (`keys`), the stock top at
// Z0, along the square 0..40 x 0..30 unless `keys` gives the edge.
std::string chamfer_job(const std::string& keys, const std::string& tool = R"("type": "v-bit", "diameter": 6, "tipAngle": 90)") {
    return fmt::format(R"({{"name": "t", "units": "mm", "clearance": 15,
  "tools": [{{"number": 3, {}, "rpm": 10000}},
            {{"number": 5, "type": "spot-drill", "diameter": 6, "tipAngle": 90, "rpm": 3000}}],
  "operations": [{{"type": "chamfer", "tool": 3, "retractPlane": 5, "safeDistance": 1, "feed": 300, {}}}]}})",
                       tool, keys);
}
const std::string chamfer_square = R"("start": [0, 0], "path": [{"line": [40, 0]}, {"line": [40, 30]}, {"line": [0, 30]}, {"line": [0, 0]}])";

struct ChamferRecorder : EventSink {
    std::vector<Event> events;
    void emit(const Event& e) override { events.push_back(e); }
};

std::vector<Event> chamfer_events(const std::string& job_text) {
    ChamferRecorder r;
    expand_job(read_job(job_text, "t.json"), r);
    return r.events;
}

void chamfer_refused(const std::string& job_text, const std::string& path, const std::string& text) {
    try {
        read_job(job_text, "t.json");
        FAIL("no error for " << path);
    } catch (const InputError& e) {
        const std::string what = e.what();
        CHECK_MESSAGE(what.find(path + ":") != std::string::npos, what);
        CHECK_MESSAGE(what.find(text) != std::string::npos, what);
    }
}

// The feed moves' end points (lines and arcs) and the lowest Z they reach.
struct ChamferFeeds {
    std::vector<Vec3> ends;
    double lowest = std::numeric_limits<double>::infinity();
};
ChamferFeeds chamfer_feeds(const std::vector<Event>& events) {
    ChamferFeeds f;
    for (const Event& e : events) {
        Vec3 to;
        if (const auto* l = std::get_if<Linear>(&e)) to = l->to;
        else if (const auto* a = std::get_if<Arc>(&e)) to = a->to;
        else continue;
        f.ends.push_back(to);
        f.lowest = std::min(f.lowest, to.z);
    }
    return f;
}

// Distance from the rectangle x0..x1, y0..y1 (outside positive), written here and not taken
// from camgen's geometry.
double chamfer_rect_distance(Vec3 p, double x0, double y0, double x1, double y1) {
    const double dx = std::max({x0 - p.x, 0.0, p.x - x1}), dy = std::max({y0 - p.y, 0.0, p.y - y1});
    if (dx > 0 || dy > 0) return std::hypot(dx, dy);
    return -std::min({p.x - x0, x1 - p.x, p.y - y0, y1 - p.y});
}

}  // namespace

TEST_CASE("chamfer: the effective diameter of a V at a height, and the height of a diameter") {
    Tool v;
    v.type = ToolType::v_bit;
    v.diameter = 6;
    v.tip_angle = 90;
    CHECK(cone_diameter_at(v, 0.0) == doctest::Approx(0.0));
    CHECK(cone_diameter_at(v, 1.0) == doctest::Approx(2.0));
    CHECK(cone_diameter_at(v, 10.0) == doctest::Approx(6.0));  // at most the tool's diameter
    v.tip_angle = 60;
    v.tip_diameter = 0.4;
    CHECK(cone_diameter_at(v, 1.0) == doctest::Approx(0.4 + 2.0 * std::tan(30.0 * std::acos(-1.0) / 180.0)));
    CHECK(cone_height_for(v, cone_diameter_at(v, 1.7)) == doctest::Approx(1.7));
    CHECK(is_cone_tool(v));
    v.type = ToolType::spot_drill;
    CHECK_FALSE(is_cone_tool(v));
}

TEST_CASE("chamfer: along a square with a 90-degree V-bit, the tip 0.2 below the 0.5 chamfer, the centre 0.2 outside the edge") {
    const ChamferFeeds f = chamfer_feeds(chamfer_events(chamfer_job(R"("width": 0.5, )" + chamfer_square)));
    REQUIRE(!f.ends.empty());
    CHECK(f.lowest == doctest::Approx(-0.7).epsilon(1e-12));
    // Every move at the tip's depth keeps the centre 0.2 outside the square, the corners' arcs too.
    double nearest = 1e9;
    int at_offset = 0;
    for (const Vec3 p : f.ends)
        if (std::abs(p.z - f.lowest) < 1e-9) {
            const double d = chamfer_rect_distance(p, 0, 0, 40, 30);
            nearest = std::min(nearest, d);
            if (std::abs(d - 0.2) < 1e-9) ++at_offset;
        }
    CHECK(nearest == doctest::Approx(0.2).epsilon(1e-12));
    CHECK(at_offset >= 8);
    // The cone left: at the top face it reaches 0.7 from the axis, 0.5 into the part; it meets
    // the wall's line 0.2 above its tip: 0.5 below the top.
    const double width = (0.0 - f.lowest) * std::tan(45.0 * std::acos(-1.0) / 180.0) - nearest;
    const double depth = -(f.lowest + nearest / std::tan(45.0 * std::acos(-1.0) / 180.0));
    CHECK(std::abs(width - 0.5) <= 1e-9);
    CHECK(std::abs(depth - 0.5) <= 1e-9);
}

TEST_CASE("chamfer: a 30-degree chamfer 1 wide with a 60-degree chamfer mill of tip diameter 1 and tipClearance 0.5") {
    const std::string tool = R"("type": "chamfer-mill", "diameter": 10, "tipAngle": 60, "tipDiameter": 1)";
    const ChamferFeeds f = chamfer_feeds(chamfer_events(chamfer_job(R"("width": 1, "angle": 30, "tipClearance": 0.5, )" + chamfer_square, tool)));
    const double t = std::tan(30.0 * std::acos(-1.0) / 180.0);
    // Vertical leg 1 / tan 30; the tip 0.5 below it; the centre 0.5 + 0.5 tan 30 out.
    CHECK(f.lowest == doctest::Approx(-(1.0 / t + 0.5)));
    double nearest = 1e9;
    for (const Vec3 p : f.ends)
        if (std::abs(p.z - f.lowest) < 1e-9) nearest = std::min(nearest, chamfer_rect_distance(p, 0, 0, 40, 30));
    CHECK(nearest == doctest::Approx(0.5 + 0.5 * t));
    const double width = 0.5 + (0.0 - f.lowest) * t - nearest;
    CHECK(width == doctest::Approx(1.0));
}

TEST_CASE("chamfer: depth passes go down in equal steps to the tip's depth at one offset") {
    const ChamferFeeds f = chamfer_feeds(chamfer_events(chamfer_job(R"("width": 0.5, "passes": 2, )" + chamfer_square)));
    std::vector<double> levels;
    for (const Vec3 p : f.ends)
        if (std::abs(chamfer_rect_distance(p, 0, 0, 40, 30) - 0.2) < 1e-9 &&
            std::find_if(levels.begin(), levels.end(), [&](double z) { return std::abs(z - p.z) < 1e-9; }) == levels.end())
            levels.push_back(p.z);
    std::sort(levels.begin(), levels.end());
    REQUIRE(levels.size() == 2);
    CHECK(levels[0] == doctest::Approx(-0.7));
    CHECK(levels[1] == doctest::Approx(-0.35));
}

TEST_CASE("chamfer: a hole's edge: one circle about its centre, entered on a half circle from the centre") {
    const std::string tool = R"("type": "chamfer-mill", "diameter": 12, "tipAngle": 90, "tipDiameter": 1)";
    const std::vector<Event> events =
        chamfer_events(chamfer_job(R"("width": 1, "diameter": 8, "holes": [[10, 10], [30, 10]])", tool));
    const ChamferFeeds f = chamfer_feeds(events);
    CHECK(f.lowest == doctest::Approx(-1.2));
    // The tool centre 0.5 + 0.2 inside the edge: on a circle of radius 3.3.
    int on_circle = 0;
    for (const Event& e : events)
        if (const auto* a = std::get_if<Arc>(&e); a && a->movement == Movement::cutting) {
            const double r = std::hypot(a->to.x - a->centre.x, a->to.y - a->centre.y);
            CHECK(r == doctest::Approx(3.3));
            CHECK(a->to.z == doctest::Approx(-1.2));
            ++on_circle;
        }
    CHECK(on_circle == 4);
    // It goes down at each hole's centre.
    int down_at_centre = 0;
    for (const Event& e : events)
        if (const auto* l = std::get_if<Linear>(&e); l && l->movement == Movement::plunge)
            if ((std::abs(l->to.x - 10) < 1e-9 || std::abs(l->to.x - 30) < 1e-9) && std::abs(l->to.y - 10) < 1e-9) ++down_at_centre;
    CHECK(down_at_centre == 2);
}

TEST_CASE("chamfer: the tip depth and the offset are told in the operation's notes (--events)") {
    const std::vector<Event> events = chamfer_events(chamfer_job(R"("width": 0.5, )" + chamfer_square));
    bool told = false;
    for (const Event& e : events)
        if (const auto* s = std::get_if<OperationStart>(&e))
            for (const std::string& n : s->notes)
                if (n.find("tip at Z -0.700 mm (0.700 mm below the top face") != std::string::npos && n.find("tool centre 0.200 mm from the edge") != std::string::npos)
                    told = true;
    CHECK(told);
}

TEST_CASE("chamfer: a tool that cannot cut it is refused at the JSON path, naming the tool and the numbers") {
    // Another type of tool.
    chamfer_refused(fmt::format(R"({{"name": "t", "units": "mm", "clearance": 15,
  "tools": [{{"number": 5, "type": "spot-drill", "diameter": 6, "tipAngle": 90, "rpm": 3000}}],
  "operations": [{{"type": "chamfer", "tool": 5, "feed": 300, "width": 0.5, {}}}]}})", chamfer_square),
                    "/operations/0/tool", "tool 5 (/tools/0) is a spot drill: a chamfer is cut with the cone of a tool of type");
    // A cone of another angle.
    chamfer_refused(chamfer_job(R"("width": 0.5, "angle": 45, )" + chamfer_square, R"("type": "v-bit", "diameter": 6, "tipAngle": 60)"),
                    "/operations/0/angle", "tip angle of 60 degrees: its cone cuts at 30 degrees from the wall, but the chamfer's angle is 45");
    chamfer_refused(chamfer_job(R"("width": 0.5, )" + chamfer_square, R"("type": "chamfer-mill", "diameter": 6, "tipAngle": 120)"),
                    "/operations/0/tool", "but the chamfer's angle is 45 degrees; use a tool of tipAngle 90");
    // A cone too short: 2.8 + 0.2 = 3 > 2.5.
    chamfer_refused(chamfer_job(R"("width": 2.8, )" + chamfer_square, R"("type": "v-bit", "diameter": 5, "tipAngle": 90)"),
                    "/operations/0/width", "to reach 3.000 mm from its axis at the top face (the offset 0.200 mm from its tip diameter "
                                           "0.000 mm and tipClearance 0.200 mm, plus the width 2.800 mm), but the tool's diameter "
                                           "5.000 mm reaches 2.500 mm");
    chamfer_refused(chamfer_job(R"("width": 2, )" + chamfer_square, R"("type": "v-bit", "diameter": 6, "tipAngle": 90, "fluteLength": 2)"),
                    "/operations/0/width", "the tip goes 2.200 mm below the top face");
    // A hole the tool does not fit: the centre 1.2 inside the edge of a 2.4 hole.
    chamfer_refused(chamfer_job(R"("width": 0.3, "diameter": 2.4, "holes": [[10, 10]])",
                                R"("type": "chamfer-mill", "diameter": 6, "tipAngle": 90, "tipDiameter": 2)"),
                    "/operations/0/diameter", "does not fit the hole (diameter 2.400 mm)");
    // Side on, and a profile's keys on holes.
    chamfer_refused(chamfer_job(R"("width": 0.5, "side": "on", )" + chamfer_square), "/operations/0/side", "on the air side");
    chamfer_refused(chamfer_job(R"("width": 0.5, "diameter": 8, "side": "outside", "holes": [[10, 10]])"),
                    "/operations/0/side", "a hole's chamfer is a circle");
    chamfer_refused(chamfer_job(R"("width": 0.5, "tipClearance": -0.1, )" + chamfer_square), "/operations/0/tipClearance", ">= 0");
}

TEST_CASE("chamfer: a lead-in through the part is refused by the part-aware check") {
    // Inside the 40 x 30 square a half-circle lead of radius 20 starts 40 from the wall: beyond
    // the opposite wall, in the part.
    chamfer_refused(chamfer_job(R"("width": 0.5, "side": "inside", "leadIn": {"type": "arc", "radius": 20, "sweep": 180}, )" +
                                chamfer_square),
                    "/operations/0/leadIn", "in the material");
    // Without the lead it is cut.
    CHECK_NOTHROW(read_job(chamfer_job(R"("width": 0.5, "side": "inside", )" + chamfer_square), "t.json"));
}

TEST_CASE("chamfer: the design's face slopes from the edge; the part beyond it is kept") {
    const std::string text = test::read_file(chamfer_samples + "chamfer.json");
    const Job job = read_job(text, "chamfer.json");
    const PartDesign d = part_design(job);
    int faces = 0;
    for (const DesignCut& c : d.cuts) {
        if (c.what == "the chamfer") {
            ++faces;
            // 0.5 x 45 from the outline: 0.5 below the top at the edge, the top 0.5 in.
            CHECK(c.floor.at({20, 0}) == doctest::Approx(-0.5));
            CHECK(c.floor.at({20, 0.5}) == doctest::Approx(0.0));
            CHECK(c.floor.at({20, 0.25}) == doctest::Approx(-0.25));
        }
        if (c.what == "the chamfer of hole") {
            ++faces;
            DesignFloor f = c.floor;
            f.apex = Vec2{15, 20};
            CHECK(f.at({19, 20}) == doctest::Approx(-1.0));
            CHECK(f.at({20, 20}) == doctest::Approx(0.0));
        }
        if (c.what == "the tool's cone beside the chamfer") CHECK(c.floor.at({20, -5}) == doctest::Approx(-0.7));
    }
    CHECK(faces == 2);
    bool kept = false;
    for (const DesignKeep& k : d.keeps) kept = kept || k.what == "the part inside the chamfer";
    CHECK(kept);
}

TEST_CASE("camgen simulate: samples/chamfer.json's chamfers as designed on every mill; 0.05 too deep or too wide is a gouge") {
    const fs::path dir = test::scratch("simulate-chamfer");
    const std::string job = chamfer_samples + "chamfer.json";
    for (const char* machine : {"fanuc", "linuxcnc", "grbl", "sinumerik", "heidenhain", "wabeco", "kosy"}) {
        CAPTURE(machine);
        const std::string program = (dir / "p.nc").string();
        REQUIRE(test::run({job, "--machine", machine, "-q", "-o", program}).code == 0);
        const test::Run r = test::run({"simulate", program, "--machine", machine, "--job", job, "--resolution", "0.05"});
        CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
        CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
    }
    const std::string text = test::read_file(job);
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string t = text;
        const std::size_t at = t.find(from);
        REQUIRE(at != std::string::npos);
        t.replace(at, from.size(), to);
        return t;
    };
    // The outline's chamfer 0.05 too wide (0.55) and the holes' (1.05), posted and simulated
    // against the sample.
    const std::vector<std::pair<std::string, std::string>> wrong = {
        {replaced("\"width\": 0.5,", "\"width\": 0.55,"), "/operations/2 (the chamfer)"},
        {replaced("\"width\": 1,", "\"width\": 1.05,"), "/operations/3 (the chamfer of hole 0 at (15, 20))"},
    };
    for (const auto& [bad, owner] : wrong) {
        CAPTURE(owner);
        const std::string bad_job = (dir / "bad.json").string();
        std::ofstream(bad_job) << bad;
        for (const char* machine : {"linuxcnc", "wabeco"}) {
            CAPTURE(machine);
            const std::string program = (dir / "bad.nc").string();
            REQUIRE(test::run({bad_job, "--machine", machine, "-q", "-o", program}).code == 0);
            const test::Run r = test::run({"simulate", program, "--machine", machine, "--job", job, "--resolution", "0.05"});
            CHECK(r.code == 1);
            CHECK_MESSAGE(r.out.find("error: gouge: " + owner + ": material removed 0.0") != std::string::npos, r.out);
        }
    }
    // The outline's chamfer 0.05 too deep: its program's tip depth Z-0.7 made Z-0.75 by hand
    // (the plunge; the moves after it keep its Z).
    const std::string program = (dir / "deep.ngc").string();
    REQUIRE(test::run({job, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    std::string nc = test::read_file(program);
    int edits = 0;
    for (std::size_t at = nc.find("Z-0.7 "); at != std::string::npos; at = nc.find("Z-0.7 ", at + 7)) {
        nc.replace(at, 6, "Z-0.75 ");
        ++edits;
    }
    REQUIRE(edits > 0);
    std::ofstream(program) << nc;
    const test::Run r = test::run({"simulate", program, "--machine", "linuxcnc", "--job", job, "--resolution", "0.05"});
    CHECK(r.code == 1);
    CHECK_MESSAGE(r.out.find("error: gouge: /operations/2 (the chamfer): material removed 0.0") != std::string::npos, r.out);
}

}  // namespace test_chamfer
