// The job's design (operations/design.hpp): what each operation cuts and keeps, as regions
// with heights, and the rows of a region on a raster (geometry/region.hpp RegionRows) that a
// simulated part is checked with.
#include <cmath>
#include <numbers>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "camgen/geometry/region.hpp"
#include "camgen/operations/design.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

namespace test_design {

using namespace camgen;

namespace {

const std::string samples = CAMGEN_SOURCE_DIR "/samples/";

Profile rectangle(double x0, double y0, double x1, double y1) {
    Profile p;
    p.start = {x0, y0};
    for (Vec2 v : {Vec2{x1, y0}, Vec2{x1, y1}, Vec2{x0, y1}, Vec2{x0, y0}}) p.segments.push_back({v, std::nullopt, ArcDirection::ccw});
    return p;
}

Profile circle(Vec2 c, double r) {
    Profile p;
    p.start = {c.x + r, c.y};
    p.segments.push_back({{c.x - r, c.y}, c, ArcDirection::cw});
    p.segments.push_back({{c.x + r, c.y}, c, ArcDirection::cw});
    return p;
}

Job job_of(const std::string& text) { return read_job(text, "job.json"); }

const DesignCut* cut_named(const PartDesign& d, const std::string& what) {
    for (const DesignCut& c : d.cuts)
        if (c.what == what) return &c;
    return nullptr;
}

}  // namespace

TEST_CASE("region rows: a rectangle less a circle, crossings exact on lines and arcs") {
    PlaneRegion r{rectangle(0, 0, 100, 50), {circle({40, 25}, 10)}};
    const RegionRows rows(r);
    const auto b = rows.bounds();
    CHECK(b[0] == doctest::Approx(0));
    CHECK(b[3] == doctest::Approx(50));
    // Through the circle's centre: two spans, the circle's crossings at 30 and 50.
    auto s = rows.spans(25.0 + 1e-9);
    REQUIRE(s.size() == 2);
    CHECK(s[0].first == doctest::Approx(0).epsilon(1e-12));
    CHECK(s[0].second == doctest::Approx(30).epsilon(1e-9));
    CHECK(s[1].first == doctest::Approx(50).epsilon(1e-9));
    CHECK(s[1].second == doctest::Approx(100).epsilon(1e-12));
    // At y = 31: the circle's chord at 40 +- sqrt(100 - 36) = 40 +- 8.
    s = rows.spans(31.0);
    REQUIRE(s.size() == 2);
    CHECK(s[0].second == doctest::Approx(32).epsilon(1e-12));
    CHECK(s[1].first == doctest::Approx(48).epsilon(1e-12));
    // Above the circle one span, outside the region none.
    CHECK(rows.spans(40.0).size() == 1);
    CHECK(rows.spans(60.0).empty());
    CHECK(rows.spans(-1.0).empty());
}

TEST_CASE("design: a pocket cuts its region less its islands down to its bottom and keeps its islands") {
    const Job job = job_of(test::read_file(samples + "pocket.json"));
    const PartDesign d = part_design(job);
    const DesignCut* pocket = cut_named(d, "the pocket");
    REQUIRE(pocket);
    CHECK(pocket->path == "/operations/0");
    CHECK(pocket->floor.z == doctest::Approx(-6));
    CHECK(pocket->top_z == doctest::Approx(0));
    const PocketOp& op = std::get<PocketOp>(job.operations[0]);
    // Its region less the fillet of the tool's radius (3 mm) its one sharp corner keeps.
    CHECK(region_area(pocket->region) == doctest::Approx(region_area(op.region) - (9.0 - std::numbers::pi * 9.0 / 4.0)).epsilon(1e-9));
    std::size_t islands = 0;
    for (const DesignKeep& k : d.keeps) islands += k.what.rfind("island", 0) == 0;
    CHECK(islands == op.region.islands.size());
    // The band kept around the pocket: one tool diameter (6 mm) beyond its outline.
    bool around = false;
    for (const DesignKeep& k : d.keeps)
        if (k.what == "the part around the pocket" && k.path == "/operations/0") {
            around = true;
            PlaneRegion outline{op.region.outer, {}};
            const double ring = region_area(k.region);
            // Steiner: the outline's perimeter x 6 + pi 6^2 (its corners convex or sharp).
            CHECK(ring == doctest::Approx(profile_length(op.region.outer) * 6 + std::numbers::pi * 36).epsilon(0.01));
            CHECK(region_contains(k.region, Vec2{op.region.outer.start.x, op.region.outer.start.y - 3.0}));
        }
    CHECK(around);
}

TEST_CASE("design: a contour outside keeps the part and cuts a band of the tool's diameter; tabs raise its floor") {
    nlohmann::json j = nlohmann::json::parse(test::read_file(samples + "plate-outline.json"));
    const Job job = job_of(j.dump());
    const PartDesign d = part_design(job);
    const ContourOp& op = std::get<ContourOp>(job.operations[0]);
    const DesignCut* band = cut_named(d, "the band beside the contour's wall");
    REQUIRE(band);
    const double wall = op.stock_to_leave;
    PlaneRegion shape{op.profile, {}};
    const double part_area = region_area(shape);
    // The band's area: the wall grown by D less the wall (Steiner: perimeter x D + pi D^2 for a
    // convex outline, the corners' arcs exact).
    const double diameter = 2.0 * op.tool_radius;
    const double perimeter = profile_length(op.profile);
    CHECK(region_area(band->region) == doctest::Approx(perimeter * diameter + 2 * std::numbers::pi * wall * diameter +
                                                        std::numbers::pi * diameter * diameter).epsilon(1e-6));
    bool part = false;
    for (const DesignKeep& k : d.keeps)
        if (k.what == "the part inside the contour") {
            part = true;
            CHECK(region_area(k.region) >= part_area);
        }
    CHECK(part);
    if (op.tabs) {
        REQUIRE(!op.tabs->centres.empty());
        const DesignCut* tab = cut_named(d, "tab 0");
        REQUIRE(tab);
        CHECK(tab->overrides);
        CHECK(tab->floor.z == doctest::Approx(band->floor.z + op.tabs->height));
        // What the cutter leaves standing on a straight side: the tool is up over the tab's
        // width and its radius each side, so the kept stretch is width x the band's width (the
        // diameter, and the roughing pass's radial stock beyond) plus the corners the tool's
        // round ends leave beside the up-stretch, (4 - pi) r^2.
        const double r = op.tool_radius, stock = op.finishing ? op.finishing->radial_stock : 0.0;
        CHECK(region_area(tab->region) ==
              doctest::Approx(op.tabs->width * (diameter + stock) + (4 - std::numbers::pi) * r * r).epsilon(0.01));
        const DesignCut* ends = cut_named(d, "the ends of tab 0");
        REQUIRE(ends);
        CHECK(ends->may_leave);
    }
}

TEST_CASE("design: drilled holes cut the tool's disc with its point, bores their diameter; paths are named unchecked") {
    const Job job = job_of(R"({"name": "d", "units": "mm", "clearance": 10,
      "tools": [{"number": 1, "type": "drill", "diameter": 8, "tipAngle": 118, "rpm": 1000},
                {"number": 2, "type": "end-mill", "diameter": 6, "rpm": 8000}],
      "operations": [
        {"type": "drill", "tool": 1, "retractPlane": 2, "endDepth": 12, "plungingFeedrate": 100, "holes": [[10, 10], [30, 10]]},
        {"type": "bore-mill", "tool": 2, "diameter": 20, "retractPlane": 2, "endDepth": 5, "pitch": 1, "feed": 300, "rampFeed": 200, "holes": [[60, 20]]},
        {"type": "path", "tool": 2, "z": 1, "feed": 300, "start": [0, 0], "path": [{"line": [10, 0]}]}]})");
    const PartDesign d = part_design(job);
    // Each operation's holes are one cut of discs and one keep of rings around them.
    REQUIRE(d.cuts.size() == 2);
    REQUIRE(d.keeps.size() == 2);
    CHECK(design_cut_count(d) == 3);
    CHECK(design_keep_count(d) == 3);
    const DesignCut& drilled = d.cuts[0];
    CHECK(drilled.path == "/operations/0");
    CHECK(drilled.what == "hole");
    REQUIRE(drilled.discs);
    CHECK(drilled.discs->centres == std::vector<Vec2>{{10, 10}, {30, 10}});
    CHECK(drilled.discs->radius == doctest::Approx(4));
    CHECK(drilled.discs->hole == 0);
    CHECK(drilled.region.outer.segments.empty());
    CHECK(drilled.floor.z == doctest::Approx(-12));
    REQUIRE(drilled.floor.apex);  // at each hole's centre: the check places it
    // At the hole's edge the point rises by r / tan(59 deg).
    DesignFloor at_hole1 = drilled.floor;
    at_hole1.apex = Vec2{30, 10};
    CHECK(at_hole1.at({34, 10}) == doctest::Approx(-12 + 4 / std::tan(59.0 * std::numbers::pi / 180)));
    // The part around them: rings from the hole out by one tool diameter (8 mm).
    REQUIRE(d.keeps[0].discs);
    CHECK(d.keeps[0].what == "the part around hole");
    CHECK(d.keeps[0].discs->radius == doctest::Approx(12));
    CHECK(d.keeps[0].discs->hole == doctest::Approx(4));
    const DesignCut& bore = d.cuts[1];
    REQUIRE(bore.discs);
    CHECK(bore.path == "/operations/1");
    CHECK(bore.discs->centres == std::vector<Vec2>{{60, 20}});
    CHECK(!bore.floor.apex);
    CHECK(bore.floor.z == doctest::Approx(-5));
    CHECK(bore.discs->radius == doctest::Approx(10));
    REQUIRE(d.unchecked.size() == 1);
    CHECK(d.unchecked[0] == "/operations/2: a path has no designed part");
}

}  // namespace test_design
