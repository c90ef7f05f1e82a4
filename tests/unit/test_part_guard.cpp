// Nothing cuts where it should not (issue 24): every tool position a contour makes, the moves
// camgen adds itself too (plunges, leads, ramps, helices, compensation entries and exits), stays
// outside the material the job keeps, with computer or control compensation; a job whose moves
// would not is refused naming the move. The tool centre under G41/G42 is what the control cuts
// (CutterCompensation, proven against rs274 in tests/oracle); distances here are measured on a
// fine sampling of the profile (Boost.Geometry-free, independent of the guard's exact ones).
#include <cmath>
#include <fstream>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/geometry/clearance.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/geometry/offset.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_part_guard {

using namespace camgen;
using namespace camgen::test;

namespace {

// A contour job: one 10 mm tool (unless `diameter`), the operation's keys given as JSON text.
std::string contour_job(const std::string& keys, double diameter = 10) {
    return fmt::format(R"({{"name": "guard", "units": "mm", "clearance": 20,
      "tools": [{{"number": 1, "type": "end-mill", "diameter": {}, "rpm": 6000}}],
      "operations": [{{"type": "contour", "tool": 1, "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "feed": 500, {}}}]}})",
                       diameter, keys);
}

// A rectangle from (x0, y0) to (x1, y1), drawn counter-clockwise from `start` on its bottom side.
std::string rectangle(double x0, double y0, double x1, double y1, double start_x) {
    return fmt::format(R"("start": [{0}, {1}], "path": [{{"line": [{2}, {1}]}}, {{"line": [{2}, {3}]}}, {{"line": [{4}, {3}]}},
                        {{"line": [{4}, {1}]}}{5}])",
                       start_x, y0, x1, y1, x0, start_x == x0 ? "" : fmt::format(R"(, {{"line": [{}, {}]}})", start_x, y0));
}

// The tool-centre positions of a job's events, every ~0.05 mm, G41/G42 applied as LinuxCNC does
// with the control's radius `comp_radius`.
std::vector<Vec3> tool_centre_points(const std::vector<Event>& events, double comp_radius) {
    std::vector<Vec3> out;
    Vec3 at{};
    bool known = false;
    CutterCompensation comp([&](const CompMove& m) {
        if (!known) {
            at = m.end;
            known = true;
            out.push_back(at);
            return;
        }
        const int n = 200;
        for (int k = 1; k <= n; ++k) {
            const double t = static_cast<double>(k) / n;
            Vec3 p;
            if (m.kind == CompMove::Kind::arc) {
                const double sweep = arc_sweep({at.x, at.y}, m.centre, m.direction, m.turns, {m.end.x, m.end.y});
                const double r = std::hypot(at.x - m.centre.x, at.y - m.centre.y);
                const double a0 = std::atan2(at.y - m.centre.y, at.x - m.centre.x);
                p = {m.centre.x + r * std::cos(a0 + sweep * t), m.centre.y + r * std::sin(a0 + sweep * t), at.z + (m.end.z - at.z) * t};
            } else {
                p = at + (m.end - at) * t;
            }
            out.push_back(p);
        }
        at = m.end;
    });
    for (const Event& e : events) {
        std::optional<CompError> err;
        if (const auto* r = std::get_if<Rapid>(&e)) {
            CompMove m;
            m.kind = CompMove::Kind::rapid;
            m.end = r->to;
            err = comp.move(m);
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            CompMove m;
            m.end = l->to;
            err = comp.move(m);
        } else if (const auto* a = std::get_if<Arc>(&e)) {
            CompMove m;
            m.kind = CompMove::Kind::arc;
            m.end = a->to;
            m.centre = {a->centre.x, a->centre.y};
            m.direction = a->direction;
            m.turns = a->turns;
            err = comp.move(m);
        } else if (const auto* c = std::get_if<Compensation>(&e)) {
            err = c->side == CompensationSide::off ? comp.off(0)
                                                   : comp.on(c->side == CompensationSide::left ? CompSide::left : CompSide::right,
                                                             comp_radius, 0);
        }
        REQUIRE_MESSAGE(!err, "the control refuses: ", err ? err->message : "");
    }
    comp.flush();
    return out;
}

// The closest the tool centre comes to the profile below the stock top `top`, and whether it
// was ever on the material side (inside the profile for an outline, outside for a pocket).
struct Clearance {
    double closest = 1e300;
    bool in_material = false;
    int checked = 0;
};

Clearance clearance_of(const std::vector<Vec3>& points, const Profile& part, bool material_inside, double top) {
    Clearance c;
    for (const Vec3& p : points) {
        if (p.z >= top - 1e-9) continue;
        ++c.checked;
        const double d = distance_to(part, {p.x, p.y});
        c.closest = std::min(c.closest, d);
        if (d > 1e-6 && contains(part, {p.x, p.y}) == material_inside) c.in_material = true;
    }
    return c;
}

const Profile& profile_of(const Job& job) { return std::get<ContourOp>(job.operations.at(0)).profile; }

void check_clear(const std::string& job_text, bool material_inside, double keep) {
    const Job job = read_job(job_text, "guard.json");
    const auto& op = std::get<ContourOp>(job.operations.at(0));
    const double comp_radius = op.compensation == CompensationMode::control ? op.tool_radius : 0.0;
    const Clearance c = clearance_of(tool_centre_points(expand_job(job), comp_radius), profile_of(job), material_inside, 0.0);
    CHECK(c.checked > 100);
    CHECK(c.closest >= keep - 0.003);
    CHECK_FALSE(c.in_material);
}

}  // namespace

TEST_CASE("guard: control compensation without a lead enters square to the path, clear of the part (issue 24 case 1)") {
    // Outline 50 x 30 cut outside, started mid-side and at a corner; a pocket wall started mid-side.
    for (const char* side : {"outside", "inside"}) {
        for (double start : {25.0, 0.0}) {
            if (std::string(side) == "inside" && start == 0.0) continue;  // a pocket corner: refused below
            CAPTURE(side);
            CAPTURE(start);
            const std::string job = contour_job(rectangle(0, 0, 50, 30, start) + fmt::format(R"(, "side": "{}", "compensation": "control")", side));
            check_clear(job, std::string(side) == "outside", 5.0);
            // The plunge is where the tool is clear: not on the profile's line.
            const Job j = read_job(job, "guard.json");
            bool plunge_checked = false;
            for (const Event& e : expand_job(j))
                if (const auto* l = std::get_if<Linear>(&e); l && l->movement == Movement::plunge) {
                    CHECK(distance_to(profile_of(j), {l->to.x, l->to.y}) > 5.0);
                    plunge_checked = true;
                    break;
                }
            CHECK(plunge_checked);
        }
    }
}

TEST_CASE("guard: a pocket wall started at a corner with control compensation is refused at the lead-in, not cut") {
    const std::string job = contour_job(rectangle(0, 0, 50, 30, 0) + R"(, "side": "inside", "compensation": "control")");
    // (No leadIn in the job: the start, where the tool goes down, is named.)
    CHECK_THROWS_WITH_AS(read_job(job, "guard.json"), doctest::Contains("/operations/0/start: the plunge at the lead-in's start puts the tool centre"), InputError);
    CHECK_THROWS_WITH_AS(read_job(job, "guard.json"), doctest::Contains("start the profile in the middle of a straight side"), InputError);
}

TEST_CASE("guard: leads, lead arcs and helix ramps that cut into a pocket wall are refused naming the move (issue 24 case 2)") {
    const std::string pocket = rectangle(0, 0, 50, 30, 0) + R"(, "side": "inside")";
    CHECK_THROWS_WITH_AS(read_job(contour_job(pocket + R"(, "leadIn": {"type": "line", "length": 3})"), "guard.json"),
                         doctest::Contains("/operations/0/leadIn: the plunge at the lead-in's start brings the tool centre 2.000 mm from the profile at (2.000, 5.000, -3.000): it cuts 3.000 mm into what the part keeps"), InputError);
    CHECK_THROWS_WITH_AS(read_job(contour_job(pocket + R"(, "leadIn": {"type": "arc", "radius": 40})"), "guard.json"),
                         doctest::Contains("/operations/0/leadIn: the plunge at the lead-in's start puts the tool centre at (-35.000, 45.000, -3.000), outside the profile: in the material"), InputError);
    CHECK_THROWS_WITH_AS(read_job(contour_job(rectangle(0, 0, 50, 30, 25) + R"(, "side": "inside", "ramp": {"type": "helix", "radius": 30})"),
                                  "guard.json"),
                         doctest::Contains("/operations/0/ramp: the ramp brings the tool centre"), InputError);
    // An L-shaped pocket, 3 mm tool, helix radius 1, a 3 mm line lead at 90 degrees from a corner:
    // 0.16 mm into the wall.
    const std::string l_pocket = R"("start": [0, 0], "path": [{"line": [40, 0]}, {"line": [40, 10]}, {"line": [10, 10]},
        {"line": [10, 30]}, {"line": [0, 30]}, {"line": [0, 0]}], "side": "inside",
        "ramp": {"type": "helix", "radius": 1}, "leadIn": {"type": "line", "length": 3, "angle": 90})";
    CHECK_THROWS_WITH_AS(read_job(contour_job(l_pocket, 3), "guard.json"), doctest::Contains("/operations/0/"), InputError);
    // The same pocket started mid-side with room for the lead is cut, clear of every wall.
    const std::string l_mid = R"("start": [20, 0], "path": [{"line": [40, 0]}, {"line": [40, 10]}, {"line": [10, 10]},
        {"line": [10, 30]}, {"line": [0, 30]}, {"line": [0, 0]}, {"line": [20, 0]}], "side": "inside",
        "ramp": {"type": "helix", "radius": 1}, "leadIn": {"type": "line", "length": 3, "angle": 90})";
    check_clear(contour_job(l_mid, 3), false, 1.5);
}

TEST_CASE("guard: an along ramp under control compensation is refused, saying why (issue 24 case 3)") {
    const std::string job =
        contour_job(rectangle(0, 0, 50, 30, 25) + R"(, "side": "outside", "compensation": "control", "ramp": {"type": "along", "angle": 3})");
    CHECK_THROWS_WITH_AS(read_job(job, "guard.json"), doctest::Contains("/operations/0/ramp/type: an along ramp"), InputError);
    CHECK_THROWS_WITH_AS(read_job(job, "guard.json"), doctest::Contains("reverses the path"), InputError);
}

TEST_CASE("guard: control compensation is checked for fit as the control offsets it (issue 24 case 4)") {
    // A 9 mm wide pocket and a 10 mm tool.
    CHECK_THROWS_WITH_AS(read_job(contour_job(rectangle(0, 0, 50, 9, 25) + R"(, "side": "inside", "compensation": "control")"), "guard.json"),
                         doctest::Contains("/operations/0"), InputError);
    // A 6 mm notch in an outline.
    const std::string notch = R"("start": [10, 0], "path": [{"line": [50, 0]}, {"line": [50, 30]}, {"line": [28, 30]}, {"line": [28, 20]},
        {"line": [22, 20]}, {"line": [22, 30]}, {"line": [0, 30]}, {"line": [0, 0]}, {"line": [10, 0]}], "side": "outside",
        "compensation": "control")";
    CHECK_THROWS_WITH_AS(read_job(contour_job(notch), "guard.json"), doctest::Contains("/operations/0"), InputError);
    // Pocket corners of R2 with a 10 mm tool: the control refuses the arcs.
    const std::string r2 = R"("start": [25, 0], "path": [{"line": [48, 0]}, {"arc": {"end": [50, 2], "centre": [48, 2], "direction": "ccw"}},
        {"line": [50, 28]}, {"arc": {"end": [48, 30], "centre": [48, 28], "direction": "ccw"}}, {"line": [2, 30]},
        {"arc": {"end": [0, 28], "centre": [2, 28], "direction": "ccw"}}, {"line": [0, 2]},
        {"arc": {"end": [2, 0], "centre": [2, 2], "direction": "ccw"}}, {"line": [25, 0]}], "side": "inside", "compensation": "control")";
    CHECK_THROWS_WITH_AS(read_job(contour_job(r2), "guard.json"), doctest::Contains("/operations/0/compensation: the control would refuse"),
                         InputError);
    CHECK_THROWS_WITH_AS(read_job(contour_job(r2), "guard.json"), doctest::Contains("Tool radius not less than arc radius with comp"),
                         InputError);
    // The same pocket with computer compensation is refused too (the tool does not fit the
    // corners), and with a 3 mm tool it is cut, clear.
    check_clear(contour_job(R"("start": [25, 0], "path": [{"line": [48, 0]}, {"arc": {"end": [50, 2], "centre": [48, 2], "direction": "ccw"}},
        {"line": [50, 28]}, {"arc": {"end": [48, 30], "centre": [48, 28], "direction": "ccw"}}, {"line": [2, 30]},
        {"arc": {"end": [0, 28], "centre": [2, 28], "direction": "ccw"}}, {"line": [0, 2]},
        {"arc": {"end": [2, 0], "centre": [2, 2], "direction": "ccw"}}, {"line": [25, 0]}], "side": "inside", "compensation": "control")", 3),
                false, 1.5);
}

TEST_CASE("guard: a square line lead under control compensation leaves no stock at the start (issue 24 case 6)") {
    // The tool-centre path reaches the offset line at the profile's start or before it: every
    // point of the first side's offset from the start on is cut.
    const std::string job = contour_job(rectangle(0, 0, 50, 30, 25) +
                                        R"(, "side": "outside", "compensation": "control", "leadIn": {"type": "line", "length": 8, "angle": 90},
                                           "leadOut": {"type": "line", "length": 8, "angle": 90})");
    const auto points = tool_centre_points(expand_job(read_job(job, "guard.json")), 5.0);
    // Outside a ccw rectangle, climb with M3: walked clockwise, so from (25, 0) towards x = 0 along
    // y = -5. Every x from 0 to 25 on y = -5 is reached by the tool at depth.
    for (double x = 0.5; x <= 25.0; x += 0.5) {
        double best = 1e9;
        for (const Vec3& p : points)
            if (p.z < -2.9) best = std::min(best, std::hypot(p.x - x, p.y + 5));
        CAPTURE(x);
        CHECK(best < 0.06);
    }
    check_clear(job, true, 5.0);
}

TEST_CASE("guard: ProfileClearance distances are exact for lines and arcs") {
    Profile square;
    square.start = {0, 0};
    square.segments = {{{10, 0}, std::nullopt}, {{10, 10}, std::nullopt}, {{0, 10}, std::nullopt}, {{0, 0}, std::nullopt}};
    const ProfileClearance c(square, 5);
    CHECK(c.nearest(Vec2{5, -3}).distance == doctest::Approx(3));
    CHECK(c.nearest(Vec2{13, 14}).distance >= 5);  // beyond the reach
    CHECK(c.inside({5, 5}));
    CHECK_FALSE(c.inside({-1, 5}));
    CHECK_FALSE(c.inside({5, 0.0 - 1e-9}));
    // A move: an arc about (5, -4) of radius 2 passing below the bottom side, 2 mm away.
    PathPiece arc{{3, -4}, {{7, -4}, Vec2{5, -4}, ArcDirection::ccw}};  // ccw from the left: the lower half
    CHECK(c.nearest(arc).distance == doctest::Approx(4));
    PathPiece upper{{3, -4}, {{7, -4}, Vec2{5, -4}, ArcDirection::cw}};  // the upper half, 2 mm from y = 0
    CHECK(c.nearest(upper).distance == doctest::Approx(2));
    // A line crossing the profile: 0.
    CHECK(c.nearest(PathPiece{{-1, 5}, {{1, 5}, std::nullopt}}).distance == doctest::Approx(0));
    // A circle profile: inside test through its arcs.
    Profile circle;
    circle.start = {10, 0};
    circle.segments = {{{-10, 0}, Vec2{0, 0}, ArcDirection::ccw}, {{10, 0}, Vec2{0, 0}, ArcDirection::ccw}};
    const ProfileClearance cc(circle, 3);
    CHECK(cc.inside({0, 0}));
    CHECK(cc.inside({9.9, 0}));
    CHECK(cc.inside({0, 9.9}));
    CHECK_FALSE(cc.inside({10.1, 0}));
    CHECK_FALSE(cc.inside({0, -10.1}));
    CHECK(cc.nearest(Vec2{0, 12}).distance == doctest::Approx(2));
    CHECK(cc.nearest(PathPiece{{-5, 12}, {{5, 12}, std::nullopt}}).distance == doctest::Approx(2));
}

TEST_CASE("guard: a machine that writes XY arcs as chords does not get control compensation (every chord a corner to offset)") {
    const auto dir = scratch("guard-chords");
    const std::string machine = (dir / "chords.json").string();
    std::ofstream(machine) << R"({"extends": "linuxcnc", "arcs": {"planes": ["xz", "yz"]}})";
    const std::string out = (dir / "out.ngc").string();
    const Run r = run({std::string(CAMGEN_SOURCE_DIR) + "/samples/plate-outline-control.json", "--machine", machine, "-o", out});
    CHECK(r.code == 1);
    CHECK(r.err.find("/operations/0/compensation: machine") != std::string::npos);
    CHECK(r.err.find("writes arcs in XY as straight moves") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
    // Computer compensation on the same machine posts.
    const Run ok = run({std::string(CAMGEN_SOURCE_DIR) + "/samples/plate-outline.json", "--machine", machine, "-o", out});
    CHECK(ok.code == 0);
}

TEST_CASE("guard: an offset's corner arc whose ends are a hair apart is not a full circle (a false gouge found on a 100,000-segment outline)") {
    Profile line;
    line.start = {0, 0};
    line.segments = {{{10, 0}, std::nullopt}};
    const ProfileClearance c(line, 5);
    // A convex corner arc of radius 3 about (5, 3), turning by almost nothing at its bottom.
    const PathPiece corner{{5, 0}, {{5 + 1e-8, 0}, Vec2{5, 3}, ArcDirection::ccw}};
    CHECK(c.nearest(corner).distance < 1e-6);  // it touches the line at (5, 0) only
    const PathPiece above{{5, 3}, {{5 + 1e-8, 3}, Vec2{5, 6}, ArcDirection::ccw}};
    CHECK(c.nearest(above).distance == doctest::Approx(3));  // not the circle through (5, 9) and (5, 3) only: its points stay at y = 3
    // A full circle (ends the same) sweeps the whole circle: down to y = 0 from a centre at y = 4.
    const PathPiece full{{5, 7}, {{5, 7}, Vec2{5, 4}, ArcDirection::ccw}};
    CHECK(c.nearest(full).distance == doctest::Approx(1));
}

TEST_CASE("guard: a tool centre inside the kept material is said to be inside, with the depth it cuts") {
    // An L-shaped part cut outside, 6 mm tool, a 12 mm line lead at 0 degrees from (40, 20): the
    // plunge at (28, 20) + 3 mm square is 2 mm inside the notch's wall x = 30, so the tool cuts
    // 5 mm into the part (found by an exploratory tester: the message said 2 mm from the profile,
    // 1 mm in).
    const std::string keys = R"("side": "outside", "compensation": "computer", "leadIn": {"type": "line", "length": 12, "angle": 0},
        "start": [40, 20], "path": [{"line": [50, 20]}, {"line": [50, 0]}, {"line": [0, 0]}, {"line": [0, 50]}, {"line": [30, 50]},
                                   {"line": [30, 20]}, {"line": [40, 20]}])";
    CHECK_THROWS_WITH_AS(read_job(contour_job(keys, 6), "guard.json"),
                         doctest::Contains("/operations/0/leadIn: the plunge at the lead-in's start brings the tool centre inside the "
                                           "material the part keeps, 2.000 mm from the profile at (28.000, 23.000, -3.000): it cuts "
                                           "5.000 mm into it"),
                         InputError);
}

}  // namespace test_part_guard
