// A simulated part against the job's design (simulation/design_check.hpp): a part made exactly
// as designed has no finding; a gouge into an island, a floor cut too deep, material left in a
// pocket's corner and a tab cut away are each found, named by operation and cut or keep.
#include <cmath>
#include <functional>

#include <doctest/doctest.h>

#include "camgen/geometry/region.hpp"
#include "camgen/operations/design.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/simulation/design_check.hpp"

namespace test_design_check {

using namespace camgen;

namespace {

// A pocket 40 x 30 from (0, 0) with a round island of radius 5 at (20, 15), 5 deep, a 6 mm tool.
const char* pocket_job = R"({"name": "p", "units": "mm", "clearance": 10,
  "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 8000, "centreCutting": true}],
  "operations": [{"type": "pocket", "tool": 1, "retractPlane": 2, "endDepth": 5, "feed": 500, "plungeFeed": 100,
    "start": [0, 0], "path": [{"line": [40, 0]}, {"line": [40, 30]}, {"line": [0, 30]}, {"line": [0, 0]}],
    "islands": [{"start": [25, 15], "path": [{"arc": {"end": [15, 15], "centre": [20, 15], "direction": "ccw"}},
                                             {"arc": {"end": [25, 15], "centre": [20, 15], "direction": "ccw"}}]}]}]})";

bool in_pocket(Vec2 p) { return p.x > 0 && p.x < 40 && p.y > 0 && p.y < 30 && std::hypot(p.x - 20, p.y - 15) > 5; }

struct Grid {
    double cell = 0.1;
    std::size_t nx = 700, ny = 600;  // from (-10, -10)
    std::function<double(Vec2)> top;
    HeightGridView view() const {
        HeightGridView g;
        g.x0 = -10, g.y0 = -10, g.cell = cell, g.nx = nx, g.ny = ny;
        g.height = [this](std::size_t i, std::size_t j) { return top({-10 + (i + 0.5) * cell, -10 + (j + 0.5) * cell}); };
        g.line = [](std::size_t, std::size_t) { return 42; };
        return g;
    }
};

std::vector<DesignFinding> check(const std::string& job_text, std::function<double(Vec2)> top) {
    const Job job = read_job(job_text, "job.json");
    Grid g;
    g.top = std::move(top);
    return check_design(part_design(job), g.view(), 0.01, 0.1 * std::sqrt(2.0) / 2 + 0.01);
}

}  // namespace

TEST_CASE("design check: a pocket cut as designed has no finding") {
    const auto found = check(pocket_job, [](Vec2 p) { return in_pocket(p) ? -5.0 : 0.0; });
    for (const DesignFinding& f : found) MESSAGE(f.message());
    CHECK(found.empty());
}

TEST_CASE("design check: a gouge into an island, a floor too deep and material left are found and named") {
    SUBCASE("0.3 mm into the island's side, 2 mm deep") {
        const auto found = check(pocket_job, [](Vec2 p) {
            if (in_pocket(p)) return -5.0;
            // the island's edge cut 0.3 mm deep in a small patch on its right side
            const double r = std::hypot(p.x - 20, p.y - 15);
            return (r > 4.7 && r < 5.5 && std::abs(p.y - 15) < 1 && p.x > 20) ? -2.0 : 0.0;
        });
        REQUIRE(found.size() == 1);
        CHECK(found[0].kind == DesignFinding::Kind::gouge);
        CHECK(found[0].what == "island 0");
        CHECK(found[0].path == "/operations/0");
        CHECK(found[0].amount == doctest::Approx(2.0));
        CHECK(found[0].line == 42);
        CHECK(found[0].message().find("/operations/0 (island 0): material removed 2 mm below the designed 0 at (") == 0);
    }
    SUBCASE("the floor 0.05 mm too deep") {
        const auto found = check(pocket_job, [](Vec2 p) { return in_pocket(p) ? (p.x > 30 ? -5.05 : -5.0) : 0.0; });
        REQUIRE(found.size() == 1);
        CHECK(found[0].what == "the pocket");
        CHECK(found[0].amount == doctest::Approx(0.05));
    }
    SUBCASE("material left in a corner") {
        const auto found = check(pocket_job, [](Vec2 p) {
            if (!in_pocket(p)) return 0.0;
            return (p.x < 2 && p.y < 2) ? -4.0 : -5.0;
        });
        REQUIRE(found.size() == 1);
        CHECK(found[0].kind == DesignFinding::Kind::left);
        CHECK(found[0].what == "the pocket");
        CHECK(found[0].amount == doctest::Approx(1.0));
        CHECK(found[0].at.x < 2);
        CHECK(found[0].message().find("material left 1 mm above its floor") != std::string::npos);
    }
    SUBCASE("within the tolerance nothing") {
        CHECK(check(pocket_job, [](Vec2 p) { return in_pocket(p) ? -5.005 : 0.0; }).empty());
    }
}

TEST_CASE("design check: a tab cut away is a gouge of its contour's tab") {
    // A 30 x 20 plate from (0, 0) cut outside 6 deep with an 8 mm tool, one tab of 5 x 2 at
    // 15 mm along the bottom side.
    const char* job = R"({"name": "t", "units": "mm", "clearance": 10,
      "tools": [{"number": 1, "type": "end-mill", "diameter": 8, "rpm": 8000}],
      "operations": [{"type": "contour", "tool": 1, "retractPlane": 2, "endDepth": 6, "side": "outside", "feed": 500,
        "plungeFeed": 100, "tabs": {"at": [15], "width": 5, "height": 2},
        "start": [0, 0], "path": [{"line": [30, 0]}, {"line": [30, 20]}, {"line": [0, 20]}, {"line": [0, 0]}]}]})";
    auto band = [](Vec2 p) {
        const bool part = p.x >= 0 && p.x <= 30 && p.y >= 0 && p.y <= 20;
        return !part;  // everything outside is cut (the band and beyond)
    };
    // What the cutter leaves: the tool (its centre on y = -4) up over 15 +- (2.5 + 4), so the
    // kept stretch less the discs of the tool's last positions down each side.
    auto tab = [](Vec2 p) {
        return p.y < 0 && p.y > -8 && std::abs(p.x - 15) < 6.5 && std::hypot(p.x - 8.5, p.y + 4) > 4 && std::hypot(p.x - 21.5, p.y + 4) > 4;
    };
    SUBCASE("kept") {
        const auto found = check(job, [&](Vec2 p) { return band(p) ? (tab(p) ? -4.0 : -6.0) : 0.0; });
        for (const DesignFinding& f : found) MESSAGE(f.message());
        CHECK(found.empty());
    }
    SUBCASE("cut away") {
        const auto found = check(job, [&](Vec2 p) { return band(p) ? -6.0 : 0.0; });
        REQUIRE(found.size() == 1);
        CHECK(found[0].what == "tab 0");
        CHECK(found[0].amount == doctest::Approx(2.0));
    }
    SUBCASE("its middle 3 mm cut away, or 1 mm of a corner the tool's round end leaves beside the width") {
        for (auto bite : std::vector<std::function<bool(Vec2)>>{[](Vec2 p) { return std::abs(p.x - 15) < 1.5; },
                                                                [](Vec2 p) { return p.x > 10.5 && p.x < 11.5 && p.y > -1; }}) {
            const auto found = check(job, [&](Vec2 p) { return band(p) ? (tab(p) && !bite(p) ? -4.0 : -6.0) : 0.0; });
            REQUIRE(found.size() == 1);
            CHECK(found[0].what == "tab 0");
            CHECK(found[0].amount == doctest::Approx(2.0));
        }
    }
}

}  // namespace test_design_check
