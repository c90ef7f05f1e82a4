// Tabs of the contour operation (issue 24): spread by length clear of the corners, on straight
// runs rather than path elements, at explicit places (distances or points), with ramped
// flanks; the passes, the `along` ramp and its way back all stay at or above a tab's top over
// its interval; and each refusal names the JSON path.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/geometry/offset.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_contour_tabs {

using namespace camgen;

namespace {

// The tool centre at points along every feed move of a job (~0.05 mm apart, Z linear), with
// the move's kind; rapids left out.
struct Sample {
    Vec3 p;
    Movement movement;
};

std::vector<Sample> feed_samples(const std::vector<Event>& events) {
    std::vector<Sample> out;
    Vec3 at{};
    for (const Event& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            at = r->to;
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            const double d = std::hypot(l->to.x - at.x, l->to.y - at.y, l->to.z - at.z);
            const int n = std::max(1, static_cast<int>(d / 0.05));
            for (int k = 0; k <= n; ++k) {
                const double t = static_cast<double>(k) / n;
                out.push_back({{at.x + (l->to.x - at.x) * t, at.y + (l->to.y - at.y) * t, at.z + (l->to.z - at.z) * t}, l->movement});
            }
            at = l->to;
        } else if (const auto* a = std::get_if<Arc>(&e)) {
            const double r = std::hypot(at.x - a->centre.x, at.y - a->centre.y);
            const double a0 = std::atan2(at.y - a->centre.y, at.x - a->centre.x);
            const double a1 = std::atan2(a->to.y - a->centre.y, a->to.x - a->centre.x);
            double sweep = a->direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
            while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
            sweep += 2 * std::numbers::pi * a->turns;
            const int n = std::max(2, static_cast<int>(r * sweep / 0.05));
            for (int k = 0; k <= n; ++k) {
                const double t = static_cast<double>(k) / n;
                const double ang = a0 + (a->direction == ArcDirection::ccw ? 1 : -1) * sweep * t;
                out.push_back({{a->centre.x + r * std::cos(ang), a->centre.y + r * std::sin(ang), at.z + (a->to.z - at.z) * t}, a->movement});
            }
            at = a->to;
        }
    }
    return out;
}

// A contour job on tool 2 (`diameter`), a through-cut `depth` deep from Z0 cut outside the
// closed profile `start` / `path`, with `members` added.
std::string tab_job(const std::string& start, const std::string& path, double diameter, double depth, const std::string& members) {
    return fmt::format(R"({{"name": "t", "units": "mm", "clearance": 15,
  "tools": [{{"number": 2, "type": "end-mill", "diameter": {}, "rpm": 6000}}],
  "operations": [{{"type": "contour", "tool": 2, "retractPlane": 5, "safeDistance": 2, "endDepth": {}, "feed": 800,
    "plungeFeed": 200, "start": {}, "path": {}, {}}}]}})",
                       diameter, depth, start, path, members);
}

// A w x h rectangle from (0, 0), drawn counter-clockwise.
std::string rectangle(double w, double h) {
    return fmt::format(R"([{{"line": [{0}, 0]}}, {{"line": [{0}, {1}]}}, {{"line": [0, {1}]}}, {{"line": [0, 0]}}])", w, h);
}

const ContourOp& contour_of(const Job& job) { return std::get<ContourOp>(job.operations.at(0)); }

// How far `p` is along the tab centred `c` mm along the profile as drawn, measured along the
// profile's tangent there (nullopt: `p` is not beside that stretch of the profile: farther
// than `reach` from its line).
std::optional<double> offset_along_tab(const ContourOp& op, double c, Vec3 p, double reach) {
    const ProfilePoint x = point_at(op.profile, c);
    const Vec2 v{p.x - x.point.x, p.y - x.point.y};
    const double across = std::abs(x.tangent.x * v.y - x.tangent.y * v.x);
    if (across > reach) return std::nullopt;
    return v.x * x.tangent.x + v.y * x.tangent.y;
}

// The side of the rectangle `w` x `h` (0 bottom, 1 right, 2 top, 3 left) a distance along its
// outline is on, and how far that is from the nearest corner.
std::pair<int, double> side_of(double along, double w, double h) {
    const double ends[] = {w, w + h, 2 * w + h, 2 * w + 2 * h};
    double from = 0;
    for (int s = 0; s < 4; ++s) {
        if (along <= ends[s]) return {s, std::min(along - from, ends[s] - along)};
        from = ends[s];
    }
    return {3, 0};
}

}  // namespace

TEST_CASE("tabs: four on a 120 x 80 outline go one on each side, none within the tool radius plus a tab's width of a corner") {
    // Issue 24: evenly spaced from the start put four tabs about 7.6 mm from the corners of the
    // long sides and none on the short ones.
    const double r = 5, width = 6;
    const Job job = read_job(tab_job("[0, 0]", rectangle(120, 80), 2 * r, 4, R"("tabs": {"count": 4, "width": 6, "height": 1.5})"), "t.json");
    const ContourOp& op = contour_of(job);
    REQUIRE(op.tabs);
    REQUIRE(op.tabs->centres.size() == 4);
    std::vector<int> per_side(4, 0);
    for (double c : op.tabs->centres) {
        const auto [side, from_corner] = side_of(c, 120, 80);
        ++per_side[side];
        CHECK(from_corner >= r + width);
    }
    CHECK(per_side == std::vector<int>{1, 1, 1, 1});
    // The pass at the bottom rises over each tab: samples at the tab top over 4 stretches.
    const double top = -4 + 1.5;
    int rises = 0;
    bool up = false;
    for (const Sample& s : feed_samples(expand_job(job)))
        if (s.movement == Movement::cutting) {
            const bool now = std::abs(s.p.z - top) < 1e-9;
            if (now && !up) ++rises;
            up = now;
        }
    CHECK(rises == 4);
}

TEST_CASE("tabs: more tabs than sides go on every side, more on the long ones, evenly and clear of corners and each other") {
    const double r = 5, width = 6, half = width / 2 + r;
    for (int count : {2, 3, 6, 8, 11}) {
        CAPTURE(count);
        const Job job = read_job(
            tab_job("[0, 0]", rectangle(120, 80), 2 * r, 4, fmt::format(R"("tabs": {{"count": {}, "width": 6, "height": 1.5}})", count)),
            "t.json");
        const std::vector<double>& c = contour_of(job).tabs->centres;
        REQUIRE(c.size() == static_cast<std::size_t>(count));
        CHECK(std::is_sorted(c.begin(), c.end()));
        std::vector<int> per_side(4, 0);
        for (std::size_t k = 0; k < c.size(); ++k) {
            const auto [side, from_corner] = side_of(c[k], 120, 80);
            ++per_side[side];
            CHECK(from_corner >= half - 1e-9);
            if (k > 0) CHECK(c[k] - c[k - 1] >= 2 * half - 1e-9);
        }
        if (count >= 4) CHECK(std::count(per_side.begin(), per_side.end(), 0) == 0);
        CHECK(per_side[0] >= per_side[1]);  // 120 against 80
        CHECK(per_side[2] >= per_side[3]);
        if (count == 2) CHECK(per_side == std::vector<int>{1, 0, 1, 0});  // the two long sides
        // Deterministic: the same job plans the same places.
        CHECK(contour_of(read_job(tab_job("[0, 0]", rectangle(120, 80), 2 * r, 4,
                                          fmt::format(R"("tabs": {{"count": {}, "width": 6, "height": 1.5}})", count)),
                                  "t.json"))
                  .tabs->centres == c);
    }
}

TEST_CASE("tabs: spread tabs go on the straight sides before the corner arcs; a circle takes them evenly, clear of its start") {
    // The plate sample's outline (200 x 120, R10 corners): eight tabs, all on the four sides.
    const std::string plate = R"([{"line": [190, 0]}, {"arc": {"end": [200, 10], "centre": [190, 10], "direction": "ccw"}},
      {"line": [200, 110]}, {"arc": {"end": [190, 120], "centre": [190, 110], "direction": "ccw"}}, {"line": [10, 120]},
      {"arc": {"end": [0, 110], "centre": [10, 110], "direction": "ccw"}}, {"line": [0, 10]},
      {"arc": {"end": [10, 0], "centre": [10, 10], "direction": "ccw"}}])";
    const Job job = read_job(tab_job("[10, 0]", plate, 10, 6, R"("tabs": {"count": 8, "width": 6, "height": 1.5})"), "t.json");
    const ContourOp& op = contour_of(job);
    REQUIRE(op.tabs->centres.size() == 8);
    for (double c : op.tabs->centres) {
        CAPTURE(c);
        CHECK_FALSE(op.profile.segments.at(point_at(op.profile, c).segment).centre.has_value());
    }
    // A circle of radius 50 drawn as two arcs from (50, 0): one run (the arcs' joint at (-50, 0)
    // is no corner), three tabs evenly over its room, which leaves the start clear.
    const std::string circle = R"([{"arc": {"end": [-50, 0], "centre": [0, 0], "direction": "ccw"}}, {"arc": {"end": [50, 0], "centre": [0, 0], "direction": "ccw"}}])";
    const Job round = read_job(tab_job("[50, 0]", circle, 6, 5, R"("tabs": {"count": 3, "width": 5, "height": 1})"), "t.json");
    const std::vector<double>& c = contour_of(round).tabs->centres;
    REQUIRE(c.size() == 3);
    const double total = 2 * std::numbers::pi * 50;
    const double half_on_profile = (2.5 + 3) * 50 / 53;  // the tool path's radius is 53
    const double room = total - 2 * half_on_profile;
    CHECK(c[0] == doctest::Approx(half_on_profile + room / 6));
    CHECK(c[1] - c[0] == doctest::Approx(room / 3));
    CHECK(c[2] - c[1] == doctest::Approx(room / 3));
    CHECK(total - c[2] == doctest::Approx(half_on_profile + room / 6));
}

TEST_CASE("tabs: a 40 x 30 outline started in the middle of a side takes a 12 mm tab on that side, clear of the start") {
    // Issue 24: started at (60, 0), the 40 mm side is drawn as 10 + 30 mm; a 12 mm tab was
    // refused against "the shortest side 10.000 mm". The side is one straight run.
    const std::string path = R"([{"line": [90, 0]}, {"line": [90, 30]}, {"line": [50, 30]}, {"line": [50, 0]}, {"line": [60, 0]}])";
    const Job job = read_job(tab_job("[60, 0]", path, 6, 5, R"("tabs": {"count": 4, "width": 12, "height": 1})"), "t.json");
    const ContourOp& op = contour_of(job);
    REQUIRE(op.tabs->centres.size() == 4);
    const double half = 6 + 3;
    int on_bottom = 0;
    for (double c : op.tabs->centres) {
        const Vec2 x = point_at(op.profile, c).point;
        if (std::abs(x.y) > 1e-9) continue;
        ++on_bottom;
        CHECK(x.x - half >= 50 - 1e-9);  // on the run, clear of its corners
        CHECK(x.x + half <= 90 + 1e-9);
        CHECK(std::abs(x.x - 60) >= half - 1e-9);  // and of the start, where the tool goes down
    }
    CHECK(on_bottom == 1);
    // Placed by hand on the run across the elements' joint... a tab foot over (60, 0) is the
    // start; one at x = 80 on the 30 mm element and one on a side drawn in three pieces fit.
    CHECK_NOTHROW(read_job(tab_job("[60, 0]", path, 6, 5, R"("tabs": {"at": [20], "width": 12, "height": 1})"), "t.json"));
    const std::string pieces = R"([{"line": [50, 0]}, {"line": [56, 0]}, {"line": [120, 0]}, {"line": [120, 80]}, {"line": [0, 80]}, {"line": [0, 0]}])";
    const Job by_hand = read_job(tab_job("[0, 0]", pieces, 10, 4, R"("tabs": {"at": [53], "width": 12, "height": 1})"), "t.json");
    CHECK(contour_of(by_hand).tabs->centres == std::vector<double>{53});
}

TEST_CASE("tabs: the along ramp and its way back rise over the tabs: no tool position below a tab's top within its interval") {
    // Issue 24: outline 60 x 40, 4 tabs 3 mm high, ramp at 1 degree: the ramp (2 / tan 1deg =
    // 114.6 mm long on each pass) and its way back at the pass depth cut through two tabs.
    const double r = 3, width = 4, half = width / 2 + r;
    const Job job = read_job(tab_job("[0, 0]", rectangle(60, 40), 2 * r, 6,
                                     R"("stepDown": 2, "ramp": {"type": "along", "angle": 1}, "tabs": {"count": 4, "width": 4, "height": 3})"),
                             "t.json");
    const ContourOp& op = contour_of(job);
    REQUIRE(op.tabs->centres.size() == 4);
    const double top = -6 + 3;
    int checked = 0, ramp_over_tabs = 0, below_top = 0;
    for (const Sample& s : feed_samples(expand_job(job))) {
        if (s.p.z < top - 1e-6) ++below_top;
        for (double c : op.tabs->centres) {
            const std::optional<double> u = offset_along_tab(op, c, s.p, r + 1e-3);
            if (!u || std::abs(*u) >= half - 1e-6) continue;
            ++checked;
            CHECK(s.p.z >= top - 1e-6);
            if (s.movement == Movement::ramp) ++ramp_over_tabs;
        }
    }
    CHECK(below_top > 1000);
    CHECK(checked > 500);
    CHECK(ramp_over_tabs > 100);  // the ramps did cross tabs (and rose over them)
    // The ramp still reaches each pass depth: the deepest ramp sample is the bottom.
    double lowest_ramp = 0;
    for (const Sample& s : feed_samples(expand_job(job)))
        if (s.movement == Movement::ramp) lowest_ramp = std::min(lowest_ramp, s.p.z);
    CHECK(lowest_ramp == doctest::Approx(-6));
}

TEST_CASE("tabs: explicit places, as distances along the profile or points near it, are where the tool rises") {
    const double r = 5, half = 3 + r;
    // 30 mm along the bottom side, and the point (121, 40) beside the right side: its nearest
    // point (120, 40) is 120 + 40 = 160 mm along.
    const Job job = read_job(tab_job("[0, 0]", rectangle(120, 80), 2 * r, 4, R"("tabs": {"at": [30, [121, 40]], "width": 6, "height": 1.5})"),
                             "t.json");
    const ContourOp& op = contour_of(job);
    REQUIRE(op.tabs->centres.size() == 2);
    CHECK(op.tabs->centres[0] == doctest::Approx(30));
    CHECK(op.tabs->centres[1] == doctest::Approx(160));
    const double top = -4 + 1.5;
    int inside = 0, outside = 0;
    for (const Sample& s : feed_samples(expand_job(job))) {
        if (s.movement != Movement::cutting) continue;
        bool in_tab = false, at_edge = false;  // at an edge: the straight climb
        for (double c : op.tabs->centres) {
            const std::optional<double> u = offset_along_tab(op, c, s.p, r + 1e-3);
            if (u && std::abs(*u) < half - 1e-6) in_tab = true;
            if (u && std::abs(std::abs(*u) - half) <= 1e-6) at_edge = true;
        }
        if (at_edge) continue;
        if (in_tab) {
            CHECK(s.p.z == doctest::Approx(top));
            ++inside;
        } else if (std::abs(s.p.z - top) > 1e-9) {
            CHECK(s.p.z == doctest::Approx(-4));
            ++outside;
        }
    }
    CHECK(inside > 2 * 250);  // 2 x 16 mm at 0.05
    CHECK(outside > 1000);
}

TEST_CASE("tabs: ramped tabs are trapezoids: the tool climbs and descends along the path at the flank angle") {
    const double r = 5, half = 3 + r, height = 2, angle = 30;
    const double slope = std::tan(angle * std::numbers::pi / 180);
    const Job job = read_job(tab_job("[0, 0]", rectangle(120, 80), 2 * r, 4, R"("tabs": {"count": 4, "width": 6, "height": 2, "rampAngle": 30})"),
                             "t.json");
    const ContourOp& op = contour_of(job);
    REQUIRE(op.tabs->centres.size() == 4);
    const double z = -4, top = z + height;
    int on_flank = 0, on_top = 0;
    for (const Sample& s : feed_samples(expand_job(job))) {
        if (s.movement != Movement::cutting) continue;
        double expected = z;  // the pass depth, or the tab outline where it is higher
        for (double c : op.tabs->centres) {
            const std::optional<double> u = offset_along_tab(op, c, s.p, r + 1e-3);
            if (!u) continue;
            const double beyond = std::abs(*u) - half;
            expected = std::max(expected, beyond <= 0 ? top : top - beyond * slope);
        }
        CHECK(s.p.z == doctest::Approx(expected).epsilon(1e-6));
        if (s.p.z > z + 1e-6 && s.p.z < top - 1e-6) ++on_flank;
        if (std::abs(s.p.z - top) < 1e-9) ++on_top;
    }
    // Each flank is height / tan 30 = 3.46 mm long: 8 of them at 0.05 mm.
    CHECK(on_flank > 8 * 60);
    CHECK(on_top > 4 * 300);
    // No straight climb: every feed move that changes Z in the pass also moves in XY.
    Vec3 at{};
    int vertical_up = 0;
    for (const Event& e : expand_job(job)) {
        if (const auto* l = std::get_if<Linear>(&e)) {
            if (l->movement == Movement::cutting && l->to.z > at.z + 1e-9 && std::hypot(l->to.x - at.x, l->to.y - at.y) < 1e-9) ++vertical_up;
            at = l->to;
        } else if (const auto* a = std::get_if<Arc>(&e)) {
            at = a->to;
        } else if (const auto* rp = std::get_if<Rapid>(&e)) {
            at = rp->to;
        }
    }
    CHECK(vertical_up == 0);
}

TEST_CASE("tabs: refusals name the JSON path: a tab off its run, over the start, overlapping, too many, too wide") {
    const std::string path40 = R"([{"line": [90, 0]}, {"line": [90, 30]}, {"line": [50, 30]}, {"line": [50, 0]}, {"line": [60, 0]}])";
    struct Case {
        std::string job;
        std::string text;
    };
    const Case cases[] = {
        // 25 mm along is x = 85: a 12 mm tab reaches x = 91, past the 40 mm run's corner.
        {tab_job("[60, 0]", path40, 6, 5, R"("tabs": {"at": [25], "width": 12, "height": 1})"),
         "/operations/0/tabs/at/0: a tab 12.000 mm wide at its foot at 25.000 mm along the profile does not fit on the straight run it "
         "sits on, which is 40.000 mm long"},
        // With flanks the foot is wider: 4 + 2 x 1 / tan 45 = 6 on the 10 mm run to the corner.
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"at": [118], "width": 4, "height": 1, "rampAngle": 45})"),
         "/operations/0/tabs/at/0: a tab 6.000 mm wide at its foot at 118.000 mm"},
        {tab_job("[60, 0]", path40, 6, 5, R"("tabs": {"at": [3], "width": 4, "height": 1})"),
         "/operations/0/tabs/at/0: the tab at 3.000 mm is closer than 5.000 mm to the profile's start"},
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"at": [30, 40], "width": 6, "height": 1})"),
         "/operations/0/tabs/at/1: this tab and the one at /operations/0/tabs/at/0 overlap: their centres are 10.000 mm apart"},
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"at": [[60, 20]], "width": 6, "height": 1})"),
         "/operations/0/tabs/at/0: this point is 20.000 mm from the profile, more than the tool's diameter (10.000 mm)"},
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"at": [400.5], "width": 6, "height": 1})"),
         "/operations/0/tabs/at/0: 400.500 mm is not on the profile: it is 400.000 mm long"},
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"at": ["x"], "width": 6, "height": 1})"),
         "/operations/0/tabs/at/0: expected a distance along the profile or a point [x, y], got a string"},
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"count": 30, "width": 6, "height": 1})"),
         "/operations/0/tabs/count: 30 tabs 6.000 mm wide do not fit on this profile"},
        {tab_job("[0, 0]", rectangle(100, 60), 10, 4, R"("tabs": {"count": 2, "width": 95, "height": 1})"),
         "/operations/0/tabs/width: a tab 95.000 mm wide does not fit on any straight run or arc of this profile"},
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"count": 2, "at": [30], "width": 6, "height": 1})"),
         "/operations/0/tabs: tabs need exactly one of count, spacing or at"},
        {tab_job("[0, 0]", rectangle(120, 80), 10, 4, R"("tabs": {"count": 2, "width": 6, "height": 1, "rampAngle": 0})"),
         "/operations/0/tabs/rampAngle: rampAngle must be more than 0 and at most 90 degrees"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.text);
        CHECK_THROWS_WITH_AS(read_job(c.job, "t.json"), doctest::Contains(c.text.c_str()), InputError);
    }
    // The count that is refused fits with the room the message names.
    try {
        read_job(cases[7].job, "t.json");
    } catch (const InputError& e) {
        const std::string what = e.what();
        const std::size_t at = what.find("hold ");
        REQUIRE(at != std::string::npos);
        const int fit = std::stoi(what.substr(at + 5));
        CHECK(fit > 4);
        CHECK_NOTHROW(read_job(tab_job("[0, 0]", rectangle(120, 80), 10, 4, fmt::format(R"("tabs": {{"count": {}, "width": 6, "height": 1}})", fit)),
                               "t.json"));
        CHECK_THROWS(read_job(tab_job("[0, 0]", rectangle(120, 80), 10, 4, fmt::format(R"("tabs": {{"count": {}, "width": 6, "height": 1}})", fit + 1)),
                              "t.json"));
    }
}

}  // namespace test_contour_tabs
