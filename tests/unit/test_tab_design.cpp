// A contour's tab as designed is what its cutter leaves standing at the tab's top (design.cpp):
// the band within the tool's radius of the centre path's stretch over the tab, less the discs of
// every other tool position. Jobs of circles and rectangles, inside and outside, tabs on straight
// sides, arcs and across corners, computer and control compensation, posted and simulated
// against their job: no finding. A tab cut away (by the program edited, or by a later operation)
// is still a gouge of it.
#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/region.hpp"
#include "camgen/operations/design.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_tab_design {

using namespace camgen;
namespace fs = std::filesystem;

namespace {

// The tester's job (an outside circle of 20 with a 10 mm tool, one tab 5 wide and 2 high).
const char* circle_job = R"({"clearance":10,"stock":{"box":{"min":[-30,-30,-8],"max":[30,30,0]}},
 "tools":[{"number":1,"type":"end-mill","diameter":10,"rpm":8000}],
 "operations":[{"type":"contour","tool":1,"endDepth":8,"feed":500,"side":"outside",
   "profile":{"circle":{"centre":[0,0],"diameter":20}},"tabs":{"count":1,"width":5,"height":2}}]})";

const DesignCut* tab_cut(const PartDesign& d, const std::string& what) {
    const DesignCut* found = nullptr;
    for (const DesignCut& c : d.cuts)
        if (c.what == what) {
            CHECK_MESSAGE(!found, std::string("one region for " + what));
            found = &c;
        }
    return found;
}

// One job of the family the loop posts: a profile, its side, the tool, the tabs, compensation.
struct Case {
    std::string shape;  // "circle", "corner" (a tab beside a rectangle's corner), "corners" (two), "middle"
    std::string side;
    double tool = 10, width = 5, height = 2, ramp = 90;
    std::string compensation = "computer";
    bool finishing = false;
};

nlohmann::json job_of(const Case& c) {
    using nlohmann::json;
    const double depth = 8;
    json op = {{"type", "contour"}, {"tool", 1}, {"endDepth", depth}, {"feed", 500}, {"side", c.side},
               {"compensation", c.compensation}, {"stepDown", 3}};
    if (c.finishing) op["finishing"] = {{"radialStock", 0.3}};
    if (c.compensation != "computer") op["leadIn"] = op["leadOut"] = {{"type", "arc"}, {"radius", c.tool * 0.75}};
    const double flank = c.ramp < 90 ? c.height / std::tan(c.ramp * std::numbers::pi / 180) : 0.0;
    const double foot = c.width + 2 * flank;
    json tabs = {{"width", c.width}, {"height", c.height}};
    if (c.ramp < 90) tabs["rampAngle"] = c.ramp;
    double w = 0, h = 0;
    if (c.shape == "circle") {
        const double d = c.side == "inside" ? 60 : 24;
        op["profile"] = {{"circle", {{"centre", {d / 2, d / 2}}, {"diameter", d}}}};
        tabs["count"] = 3;
        w = h = d;
    } else {
        w = 60, h = 44;
        // Started in the middle of the bottom side (where control compensation has room to
        // come on inside), counter-clockwise.
        op["start"] = {w / 2, 0};
        op["path"] = json::array({{{"line", {w, 0}}}, {{"line", {w, h}}}, {{"line", {0, h}}}, {{"line", {0, 0}}}, {{"line", {w / 2, 0}}}});
        // Beside the corners at (w, 0) and (w, h), 0.2 mm short of each at its foot: the tool's
        // stretch goes round the corner of its path.
        if (c.shape == "middle") tabs["at"] = {w / 2 + h / 2, w + h};
        else if (c.shape == "corner") tabs["at"] = {w / 2 - foot / 2 - 0.2};
        else tabs["at"] = {w / 2 - foot / 2 - 0.2, w / 2 + h - foot / 2 - 0.2};
    }
    op["tabs"] = tabs;
    const double m = 2 * c.tool + 3;
    return {{"clearance", 10},
            {"stock", {{"box", {{"min", {-m, -m, -depth}}, {"max", {w + m, h + m, 0}}}}}},
            {"tools", json::array({{{"number", 1}, {"type", "end-mill"}, {"diameter", c.tool}, {"rpm", 8000}}})},
            {"operations", json::array({op})}};
}

}  // namespace

TEST_CASE("tab design: on a straight side, what the tool leaves: width x diameter and the corners its round ends leave") {
    // A 30 x 20 plate cut outside with an 8 mm tool, one tab 5 wide at 15 along the bottom side:
    // the tool (its centre on y = -4) is up over x = 15 -+ 6.5.
    const Job job = read_job(R"({"name": "t", "units": "mm", "clearance": 10,
      "tools": [{"number": 1, "type": "end-mill", "diameter": 8, "rpm": 8000}],
      "operations": [{"type": "contour", "tool": 1, "retractPlane": 2, "endDepth": 6, "side": "outside", "feed": 500,
        "plungeFeed": 100, "tabs": {"at": [15], "width": 5, "height": 2},
        "start": [0, 0], "path": [{"line": [30, 0]}, {"line": [30, 20]}, {"line": [0, 20]}, {"line": [0, 0]}]}]})",
                             "job.json");
    const PartDesign d = part_design(job);
    const DesignCut* tab = tab_cut(d, "tab 0");
    REQUIRE(tab);
    CHECK(tab->overrides);
    CHECK(tab->floor.z == doctest::Approx(-4));
    CHECK(tab->region.islands.empty());
    CHECK(region_area(tab->region) == doctest::Approx(5 * 8 + (4 - std::numbers::pi) * 16).epsilon(0.003));
    // At the wall it is the up-stretch wide (13), on the tool's centre line the tab's width (5).
    for (const Vec2 p : {Vec2{9.3, -0.05}, Vec2{20.7, -0.05}, Vec2{9.3, -7.95}, Vec2{12.6, -4}, Vec2{17.4, -4}, Vec2{15, -0.05}, Vec2{15, -7.95}})
        CHECK_MESSAGE(region_contains(tab->region, p), p.x, " ", p.y);
    for (const Vec2 p : {Vec2{8.4, -0.05}, Vec2{21.6, -0.05}, Vec2{12.4, -4}, Vec2{17.6, -4}, Vec2{9, -2}, Vec2{15, 0.05}, Vec2{15, -8.05}})
        CHECK_MESSAGE(!region_contains(tab->region, p), p.x, " ", p.y);
    // Its ends: the tool's centre line over the stretch and a radius more each side, within
    // its radius; the tool may cut there to the bottom or not.
    const DesignCut* ends = tab_cut(d, "the ends of tab 0");
    REQUIRE(ends);
    CHECK(ends->may_leave);
    CHECK(!ends->overrides);
    CHECK(ends->floor.z == doctest::Approx(-6));
    CHECK(region_area(ends->region) == doctest::Approx(21 * 8 + std::numbers::pi * 16).epsilon(0.003));
    for (const Vec2 p : {Vec2{4.6, -0.05}, Vec2{25.4, -7.95}, Vec2{15, -4}})
        CHECK_MESSAGE(region_contains(ends->region, p), p.x, " ", p.y);
}

TEST_CASE("tab design: on the tester's circle the tab follows the tool's own path: wide at the wall, the tab's width on its centre line") {
    const Job job = read_job(circle_job, "job.json");
    const ContourOp& op = std::get<ContourOp>(job.operations[0]);
    REQUIRE(op.tabs);
    REQUIRE(op.tabs->centres.size() == 1);
    const Vec2 c = point_at(op.profile, op.tabs->centres[0]).point;
    const double at = std::atan2(c.y, c.x);
    const PartDesign d = part_design(job);
    const DesignCut* tab = tab_cut(d, "tab 0");
    REQUIRE(tab);
    // The tool's centre (radius 15) is up over 7.5 mm each side: 0.5 rad. Its disc there
    // reaches the wall (radius 10) at 0.5 rad, and the centre line at 0.5 - 2 asin(5 / 30).
    auto polar = [&](double radius, double angle) { return Vec2{radius * std::cos(at + angle), radius * std::sin(at + angle)}; };
    const double narrow = 0.5 - 2 * std::asin(5.0 / 30.0);
    for (const double sign : {-1.0, 1.0}) {
        CHECK(region_contains(tab->region, polar(10.05, sign * 0.42)));
        CHECK(!region_contains(tab->region, polar(10.05, sign * 0.53)));
        CHECK(region_contains(tab->region, polar(15, sign * (narrow - 0.02))));
        CHECK(!region_contains(tab->region, polar(15, sign * (narrow + 0.02))));
        CHECK(!region_contains(tab->region, polar(9.95, sign * 0.1)));
        CHECK(!region_contains(tab->region, polar(20.05, sign * 0.1)));
    }
    CHECK(15 * 2 * narrow == doctest::Approx(op.tabs->width).epsilon(0.02));
}

TEST_CASE("camgen simulate: tabs of circles and rectangles, inside and outside, by the corners, as designed on linuxcnc") {
    const fs::path dir = test::scratch("simulate-tab-design");
    std::vector<Case> cases;
    const char* shapes[] = {"circle", "corner", "corners", "middle"};
    const double tools[] = {10, 6, 4, 12};
    const double widths[] = {5, 2, 3, 8};
    const double ramps[] = {90, 45, 60};
    const char* modes[] = {"computer", "control", "wear"};
    // The tester's job first, then every shape on both sides, the sizes, flanks and modes
    // turning at different rates.
    for (int k = 0; k < 24; ++k) {
        Case c;
        c.shape = shapes[k % 4];
        c.side = (k / 4) % 2 ? "inside" : "outside";
        c.tool = tools[(k / 2) % 4];
        c.width = widths[(k / 3) % 4];
        c.ramp = ramps[k % 3];
        c.compensation = modes[(k / 5) % 3];
        c.finishing = k % 7 == 3;
        // Under control compensation camgen refuses a tab whose flank ends within the radius of
        // an inside corner (the part guard: the control's offset of the short move there would
        // cut the wall); those go mid-side.
        if (c.compensation == "control" && c.side == "inside" && c.shape.starts_with("corner")) c.shape = "middle";
        cases.push_back(c);
    }
    const std::string program = (dir / "p.ngc").string(), job_file = (dir / "job.json").string();
    int checked = 0;
    auto simulate = [&](const std::string& text) {
        std::ofstream(job_file) << text;
        const test::Run post = test::run({job_file, "--machine", "linuxcnc", "-q", "-o", program});
        REQUIRE_MESSAGE(post.code == 0, post.err);
        return test::run({"simulate", program, "--machine", "linuxcnc", "--job", job_file, "--resolution", "0.05"});
    };
    {
        const test::Run r = simulate(circle_job);
        CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
        CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
        ++checked;
    }
    for (const Case& c : cases) {
        const std::string text = job_of(c).dump();
        CAPTURE(text);
        const test::Run r = simulate(text);
        CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
        CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
        CHECK_MESSAGE(r.out.find("material left") == std::string::npos, r.out);
        ++checked;
    }
    CHECK(checked == 25);
}

TEST_CASE("camgen simulate: a tab cut away, by the program edited or by a later operation, is a gouge of that tab") {
    const fs::path dir = test::scratch("simulate-tab-cut-away");
    const std::string program = (dir / "p.ngc").string(), job_file = (dir / "job.json").string();
    std::ofstream(job_file) << circle_job;
    REQUIRE(test::run({job_file, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    SUBCASE("the moves up to the tab's top (Z-6) left out: the tool stays at the bottom") {
        std::string kept, line;
        std::ifstream in(program);
        int dropped = 0;
        while (std::getline(in, line)) {
            if (line == "G1 Z-6") {
                ++dropped;
                continue;
            }
            kept += line + "\n";
        }
        REQUIRE(dropped == 1);
        std::ofstream(program) << kept;
    }
    SUBCASE("a second contour without tabs after it") {
        nlohmann::json j = nlohmann::json::parse(circle_job);
        nlohmann::json again = j["operations"][0];
        again.erase("tabs");
        j["operations"].push_back(again);
        std::ofstream(job_file) << j.dump();
        REQUIRE(test::run({job_file, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    }
    const test::Run r = test::run({"simulate", program, "--machine", "linuxcnc", "--job", job_file, "--resolution", "0.05"});
    CHECK(r.code == 1);
    CHECK_MESSAGE(r.out.find("error: gouge: /operations/0 (tab 0): material removed 2 mm below the designed -6") != std::string::npos, r.out);
}

}  // namespace test_tab_design
