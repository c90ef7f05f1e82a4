// Arcs: the plane convention, the four output forms in every plane, the arc-breaking rules
// (each alone, with hand-worked numbers), rounded arcs staying on the circle, the nccad D
// form, the kosy machine, and linearized arcs and helices measured against the true curve.
// Geometry of the output is checked with the interpreter in support.hpp, which reads the
// words on its own and does not use camgen's arc code.
#include <cmath>
#include <numbers>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "camgen/post/arc_output.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_arcs {

using namespace camgen;
using namespace camgen::test;

namespace {

constexpr double pi = std::numbers::pi;

ArcGeometry arc_from(Vec3 start, Vec3 to, Vec3 centre, ArcDirection dir, Plane plane = Plane::xy, int turns = 0) {
    return resolve_arc(start, Arc{to, centre, dir, plane, 100.0, turns});
}

// The arc moves of a program, in order.
std::vector<NcMove> arc_moves(const std::vector<NcMove>& moves) {
    std::vector<NcMove> out;
    for (const NcMove& m : moves)
        if (m.g >= 2) out.push_back(m);
    return out;
}

// Largest distance of the points of `path` (sampled, midpoints included) from the true arc:
// the in-plane distance from its circle and, along the normal axis, from where a helix is at
// that angle. `path` must run along the arc in its direction.
double deviation_from_arc(const ArcGeometry& arc, const std::vector<Vec3>& path) {
    const PlanePoint c = to_plane(arc.centre, arc.plane), s = to_plane(arc.start, arc.plane), e = to_plane(arc.end, arc.plane);
    const double sign = arc.direction == ArcDirection::ccw ? 1.0 : -1.0;
    double worst = 0.0, travelled = 0.0, last = arc.start_angle;
    for (const Vec3& p : path) {
        PlanePoint q = to_plane(p, arc.plane);
        double a = std::atan2(q.v - c.v, q.u - c.u);
        double step = std::remainder(a - last, 2 * pi);  // unwrap: small steps along the arc
        travelled += sign * step;
        last = a;
        double radial = std::abs(std::hypot(q.u - c.u, q.v - c.v) - arc.radius);
        double along = std::abs(q.w - (s.w + (e.w - s.w) * travelled / arc.sweep));
        worst = std::max(worst, std::hypot(radial, along));
    }
    return worst;
}

// The path of consecutive moves, sampled `per_move` times each (so chord midpoints are in it).
std::vector<Vec3> sampled(const std::vector<NcMove>& moves, int per_move) {
    std::vector<Vec3> out;
    for (const NcMove& m : moves)
        for (int k = 1; k <= per_move; ++k) out.push_back(m.at(double(k) / per_move));
    return out;
}

Machine fanuc_with(ArcFormat form) {
    Machine m = load_machine("fanuc");
    m.arcs.format = form;
    m.block.sequence_numbers = false;
    return m;
}

}  // namespace

// ---------------------------------------------------------------- plane convention

TEST_CASE("plane convention: G3 turns positively about +Z, +Y, +X (G18 seen from +Y)") {
    // A quarter arc ccw about the origin in each plane, radius 10. Turning +45 degrees about
    // the normal (right-hand rule) takes the start to the midpoint:
    //   G17 about +Z: (10,0,0) -> (7.071, 7.071, 0), ends at (0, 10, 0)
    //   G18 about +Y: (10,0,0) -> x' = 10 cos 45, z' = -10 sin 45 = (7.071, 0, -7.071), ends at (0, 0, -10)
    //   G19 about +X: (0,10,0) -> y' = 10 cos 45, z' = 10 sin 45 = (0, 7.071, 7.071), ends at (0, 0, 10)
    // (G18 is the plane where a post that thinks "seen from the front, -Y" gets G2 and G3 swapped.)
    const double h = 10.0 / std::numbers::sqrt2;
    struct Case {
        Plane plane;
        Vec3 start, end, mid;
    } cases[] = {
        {Plane::xy, {10, 0, 0}, {0, 10, 0}, {h, h, 0}},
        {Plane::xz, {10, 0, 0}, {0, 0, -10}, {h, 0, -h}},
        {Plane::yz, {0, 10, 0}, {0, 0, 10}, {0, h, h}},
    };
    for (const Case& c : cases) {
        ArcGeometry g = arc_from(c.start, c.end, {0, 0, 0}, ArcDirection::ccw, c.plane);
        CHECK(g.sweep == doctest::Approx(pi / 2));  // a quarter, not three quarters
        Vec3 m = point_on_arc(g, 0.5);
        CHECK(m.x == doctest::Approx(c.mid.x));
        CHECK(m.y == doctest::Approx(c.mid.y));
        CHECK(m.z == doctest::Approx(c.mid.z));
        // The same, independent of the numbers: (start x mid) points along the normal.
        CHECK(dot(cross(c.start, m), normal_of(c.plane)) > 0);
        // And cw goes the other way round: three quarters.
        CHECK(arc_from(c.start, c.end, {0, 0, 0}, ArcDirection::cw, c.plane).sweep == doctest::Approx(3 * pi / 2));
    }
}

TEST_CASE("fanuc arcs sample: the G18 arc G2 dips to Z-6 and the G19 arc G3 dips to Z-6") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/arcs.json"), "fanuc");
    CHECK(p.text.find("G18 G2 X210.000 Z-1.000 I5.000 K0.000 F300\n") != std::string::npos);
    CHECK(p.text.find("G19 G3 Y10.000 Z-1.000 J5.000 K0.000\n") != std::string::npos);
    auto arcs = arc_moves(interpret(p.text, ArcFormat::ijk_relative));
    REQUIRE(arcs.size() == 13);  // 4 + 4 in the first two operations, 3 helix turns, 2
    const NcMove& xz = arcs[11];
    const NcMove& yz = arcs[12];
    CHECK(xz.sweep == doctest::Approx(pi));
    Vec3 m = xz.at(0.5);
    CHECK(m.x == doctest::Approx(205));
    CHECK(m.z == doctest::Approx(-6));  // below the start: into the material
    m = yz.at(0.5);
    CHECK(m.y == doctest::Approx(5));
    CHECK(m.z == doctest::Approx(-6));
}

// ---------------------------------------------------------------- output forms

TEST_CASE("every arc form, every plane, both directions, 90 to 360 degrees: the control's path is the arc") {
    // An awkward circle: centre and radius not on the 0.001 grid, start at 20 degrees, so
    // every end point is rounded and the fitting of the centre words is exercised.
    const Vec3 centre{3.3217, -7.1043, 2.2061};
    const double r = 12.3456;
    for (ArcFormat form : {ArcFormat::ijk_relative, ArcFormat::ijk_absolute, ArcFormat::radius}) {
        Machine machine = fanuc_with(form);
        for (Plane plane : {Plane::xy, Plane::xz, Plane::yz})
            for (ArcDirection dir : {ArcDirection::cw, ArcDirection::ccw})
                for (double degrees : {90.0, 180.0, 270.0, 360.0}) {
                    CAPTURE(static_cast<int>(form));
                    CAPTURE(static_cast<int>(plane));
                    CAPTURE(static_cast<int>(dir));
                    CAPTURE(degrees);
                    PlanePoint c = to_plane(centre, plane);
                    double a0 = 20.0 * pi / 180, a1 = a0 + (dir == ArcDirection::ccw ? 1 : -1) * degrees * pi / 180;
                    Vec3 start = from_plane({c.u + r * std::cos(a0), c.v + r * std::sin(a0), c.w}, plane);
                    Vec3 end = from_plane({c.u + r * std::cos(a1), c.v + r * std::sin(a1), c.w}, plane);
                    if (degrees == 360.0) end = start;
                    std::string nc = post_events(machine, {ToolChange{1, 6, ""}, Rapid{start}, Arc{end, centre, dir, plane, 200, 0}});
                    auto moves = interpret(nc, form);
                    auto arcs = arc_moves(moves);
                    REQUIRE(!arcs.empty());
                    // The radius form needs two blocks for a full circle; nobody needs more
                    // than four here.
                    CHECK(arcs.size() <= 4);
                    if (form == ArcFormat::radius && degrees == 360.0) CHECK(arcs.size() >= 2);
                    for (const NcMove& m : arcs) CHECK(std::abs(m.radius_start - m.radius_end) <= machine.tolerance);
                    ArcGeometry truth = arc_from(start, end, centre, dir, plane);
                    // Every point the control runs through lies on the circle...
                    CHECK(deviation_from_arc(truth, sampled(arcs, 16)) <= 0.002 + 0.0009);
                    // ... it ends at the end, and it went the right way round: the arc's
                    // quarter points are on the control's path.
                    CHECK(length(arcs.back().to - end) <= 0.0009);
                    auto path = sampled(arcs, 256);
                    for (double t : {0.25, 0.5, 0.75}) {
                        Vec3 q = point_on_arc(truth, t);
                        double nearest = 1e9;
                        for (const Vec3& p : path) nearest = std::min(nearest, length(p - q));
                        CHECK(nearest < 0.2);  // 256 samples a block: at most ~0.3 mm apart
                    }
                    double total = 0;
                    for (const NcMove& m : arcs) total += m.sweep;
                    CHECK(total == doctest::Approx(degrees * pi / 180).epsilon(1e-4));
                }
    }
}

TEST_CASE("plane words G17/G18/G19 and the three ISO forms, by hand") {
    Machine m = fanuc_with(ArcFormat::ijk_relative);
    std::string nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{0, 0, 0}},
                                     Arc{{10, 0, 0}, {5, 0, 0}, ArcDirection::cw, Plane::xz, 100, 0},
                                     Arc{{20, 0, 0}, {15, 0, 0}, ArcDirection::cw, Plane::xz, 100, 0},
                                     Arc{{30, 0, 0}, {25, 0, 0}, ArcDirection::cw, Plane::xy, 100, 0}});
    // G18 once (modal), then G17 for the XY arc; I/J/K relative to the start.
    CHECK(nc.find("G18 G2 X10.000 Z0.000 I5.000 K0.000 F100\nX20.000 Z0.000 I5.000 K0.000\nG17 X30.000 Y0.000 I5.000 J0.000\n") !=
          std::string::npos);
    // Absolute centre form: I, J, K are the centre's coordinates.
    m.arcs.format = ArcFormat::ijk_absolute;
    nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{0, 0, 0}}, Arc{{10, 0, 0}, {5, 0, 0}, ArcDirection::cw, Plane::xz, 100, 0}});
    CHECK(nc.find("G18 G2 X10.000 Z0.000 I5.000 K0.000 F100\n") != std::string::npos);
    nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{1, 2, 3}}, Arc{{1, 12, 3}, {1, 7, 3}, ArcDirection::ccw, Plane::yz, 100, 0}});
    CHECK(nc.find("G19 G3 Y12.000 Z3.000 J7.000 K3.000 F100\n") != std::string::npos);
    // Radius form: negative R over 180 degrees. 270 degrees ccw in XY from (10,0) about the
    // origin, at most 180 a block: two blocks of 135 degrees, each R10 (both below 180).
    m.arcs.format = ArcFormat::radius;
    nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{10, 0, 0}}, Arc{{0, -10, 0}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 100, 0}});
    CHECK(nc.find("G3 X-7.071 Y7.071 R10.000 F100\nX0.000 Y-10.000 R10.000\n") != std::string::npos);
    m.arcs.max_sweep = 360;
    m.arcs.format = ArcFormat::radius;
    // With 270 allowed in one block... the radius form still caps it at 180: same output.
    CHECK(post_events(m, {ToolChange{1, 6, ""}, Rapid{{10, 0, 0}}, Arc{{0, -10, 0}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 100, 0}}) == nc);
}

TEST_CASE("radius form: R is negative for a block over 180 degrees") {
    Machine m = fanuc_with(ArcFormat::radius);
    m.arcs.max_sweep = 360;
    // A plan that leaves 270 degrees whole is impossible for R (capped at 180), so check the
    // sign on a block as on_circular writes it: fit a 200-degree piece directly.
    ArcGeometry g = arc_from({10, 0, 0}, {10 * std::cos(200 * pi / 180), 10 * std::sin(200 * pi / 180), 0}, {0, 0, 0},
                             ArcDirection::ccw);
    CHECK(g.sweep == doctest::Approx(200 * pi / 180));
    ArcWordFormats f{m.format("xyz"), m.format("ijk"), m.format("angle"), ArcFormat::radius, 0.002};
    ArcFit fit = fit_arc_block(g, {10, 0, 0}, f);
    REQUIRE(fit.result == ArcFitResult::ok);
    CHECK(fit.block.radius == doctest::Approx(10));
    CHECK(fit.block.sweep > pi);  // so on_circular writes R-10.000
}

// ---------------------------------------------------------------- nccad D form

TEST_CASE("wabeco D form: 90, 180, 270 and 360 degrees cw and ccw, D, I, J and the end by hand") {
    // Every arc starts at (10, 0) about the origin, radius 10; at most 180 degrees a block.
    // I and J are the centre minus the block's start: -10, 0 for the first block.
    //  90 ccw: D90 to (0, 10);  90 cw: D90 to (0, -10).
    // 180: D180 to (-10, 0) either way.
    // 270 ccw: two blocks of 135: to (10 cos 135, 10 sin 135) = (-7.071, 7.071), then
    //          I = 0 - (-7.0711) = 7.071, J = -7.071, to (0, -10).
    // 270 cw: to (-7.071, -7.071), then I 7.071 J 7.071, to (0, 10).
    // 360: D180 to (-10, 0), then I 10 J 0, D180 back to (10, 0).
    const double h = 10.0 / std::numbers::sqrt2;
    struct Case {
        ArcDirection dir;
        Vec3 end;
        std::vector<std::string> blocks;
        std::vector<Vec3> ends;
    } cases[] = {
        {ArcDirection::ccw, {0, 10, 0}, {"G03 D90 I-10 J0 F16.7"}, {{0, 10, 0}}},
        {ArcDirection::cw, {0, -10, 0}, {"G02 D90 I-10 J0 F16.7"}, {{0, -10, 0}}},
        {ArcDirection::ccw, {-10, 0, 0}, {"G03 D180 I-10 J0 F16.7"}, {{-10, 0, 0}}},
        {ArcDirection::cw, {-10, 0, 0}, {"G02 D180 I-10 J0 F16.7"}, {{-10, 0, 0}}},
        {ArcDirection::ccw, {0, -10, 0}, {"G03 D135 I-10 J0 F16.7", "G03 D135 I7.071 J-7.071"}, {{-h, h, 0}, {0, -10, 0}}},
        {ArcDirection::cw, {0, 10, 0}, {"G02 D135 I-10 J0 F16.7", "G02 D135 I7.071 J7.071"}, {{-h, -h, 0}, {0, 10, 0}}},
        {ArcDirection::ccw, {10, 0, 0}, {"G03 D180 I-10 J0 F16.7", "G03 D180 I10 J0"}, {{-10, 0, 0}, {10, 0, 0}}},
        {ArcDirection::cw, {10, 0, 0}, {"G02 D180 I-10 J0 F16.7", "G02 D180 I10 J0"}, {{-10, 0, 0}, {10, 0, 0}}},
    };
    Machine m = load_machine("wabeco");
    for (const Case& c : cases) {
        std::string nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{10, 0, 0}}, Arc{c.end, {0, 0, 0}, c.dir, Plane::xy, 100, 0}});
        auto arcs = arc_moves(interpret(nc, ArcFormat::nccad_angle));
        REQUIRE(arcs.size() == c.blocks.size());
        for (size_t i = 0; i < arcs.size(); ++i) {
            CHECK(arcs[i].line == c.blocks[i]);
            CHECK(length(arcs[i].to - c.ends[i]) < 0.001);
        }
    }
}

TEST_CASE("wabeco D form: a chain of D arcs does not drift (the next I/J are from where the control is)") {
    // 36 arcs of 100 degrees cw round a circle of radius 7.0711 about (1.2345, 2.3456): ten
    // turns, every end off the 0.001 grid. A D arc ends where the control computes, up to the
    // arc tolerance from the rounded end; if the next I/J were taken from the rounded end, the
    // errors would add up (about 0.025 mm here). They must stay within the tolerance (plus
    // the rounding of the end itself) at every block.
    const Vec3 c{1.2345, 2.3456, 0};
    const double r = 7.0711;
    auto at = [&](double deg) { return Vec3{c.x + r * std::cos(deg * pi / 180), c.y + r * std::sin(deg * pi / 180), 0}; };
    std::vector<Event> ev{ToolChange{1, 6, ""}, Rapid{at(0)}};
    for (int k = 1; k <= 36; ++k) ev.push_back(Arc{at(-100.0 * k), c, ArcDirection::cw, Plane::xy, 100, 0});
    Machine m = load_machine("wabeco");
    auto arcs = arc_moves(interpret(post_events(m, ev), ArcFormat::nccad_angle));
    REQUIRE(arcs.size() == 36);
    for (size_t i = 0; i < arcs.size(); ++i) CHECK(length(arcs[i].to - at(-100.0 * double(i + 1))) <= m.tolerance + 0.0007);
}

// ---------------------------------------------------------------- arc-breaking rules, one at a time

namespace {
// No rule active except what a case sets: all planes, helices, any sweep, no radius or length
// limits, 1 segment minimum.
ArcSettings bare() {
    ArcSettings s;
    s.max_sweep = 360;
    return s;
}
}  // namespace

TEST_CASE("rule: an unsupported plane becomes lines by the chord tolerance") {
    // r = 10, 90 degrees, tolerance 0.005: a chord of angle a deviates r (1 - cos(a/2)).
    // Largest a: 2 acos(1 - 0.005/10) = 2 x 0.0316241 = 0.0632481 rad; (pi/2) / 0.0632481 =
    // 24.84 -> 25 segments. Check: 25 -> 10 (1 - cos(pi/100)) = 0.004934 <= 0.005;
    // 24 -> 10 (1 - cos(pi/96)) = 0.005354 > 0.005.
    ArcSettings s = bare();
    s.planes = {Plane::xy};
    ArcGeometry g = arc_from({10, 0, 0}, {0, 0, -10}, {0, 0, 0}, ArcDirection::ccw, Plane::xz);
    ArcPlan p = plan_arc(g, s, 0.005);
    CHECK(p.treatment == ArcTreatment::lines);
    CHECK(p.count == 25);
    CHECK(p.reason == "plane not supported");
    // The same arc in XY is an arc.
    ArcGeometry xy = arc_from({10, 0, 0}, {0, 10, 0}, {0, 0, 0}, ArcDirection::ccw);
    CHECK(plan_arc(xy, s, 0.005).treatment == ArcTreatment::arcs);
}

TEST_CASE("rule: a helix on a machine without helices becomes lines") {
    ArcSettings s = bare();
    ArcGeometry helix = arc_from({10, 0, 0}, {0, 10, -4}, {0, 0, 0}, ArcDirection::ccw);
    CHECK(plan_arc(helix, s, 0.005).treatment == ArcTreatment::arcs);
    s.helical = false;
    ArcPlan p = plan_arc(helix, s, 0.005);
    CHECK(p.treatment == ArcTreatment::lines);
    CHECK(p.count == 25);  // as the plane case: the in-plane sagitta decides
}

TEST_CASE("rule: a radius above maxRadius becomes lines") {
    // r = 1522 (the sample's large arc: 1522^2 = 78^2 + 1520^2), sweep acos(1520/1522) =
    // 0.0512708 rad; largest chord angle 2 acos(1 - 0.005/1522) = 2 x 0.00256326 =
    // 0.00512652 rad; 0.0512708 / 0.00512652 = 10.001 -> 11 segments.
    ArcSettings s = bare();
    ArcGeometry g = arc_from({100, 20, 0}, {178, 22, 0}, {100, 1542, 0}, ArcDirection::ccw);
    CHECK(g.radius == doctest::Approx(1522));
    CHECK(plan_arc(g, s, 0.005).treatment == ArcTreatment::arcs);
    s.max_radius = 1522.5;
    CHECK(plan_arc(g, s, 0.005).treatment == ArcTreatment::arcs);
    s.max_radius = 1000;
    ArcPlan p = plan_arc(g, s, 0.005);
    CHECK(p.treatment == ArcTreatment::lines);
    CHECK(p.count == 11);
}

TEST_CASE("rule: a radius below minRadius is one straight move") {
    ArcSettings s = bare();
    // r = 0.0015, a half circle: length 0.0047 mm.
    ArcGeometry g = arc_from({0.0015, 0, 0}, {-0.0015, 0, 0}, {0, 0, 0}, ArcDirection::ccw);
    CHECK(plan_arc(g, s, 0.005).treatment == ArcTreatment::arcs);
    s.min_radius = 0.002;
    ArcPlan p = plan_arc(g, s, 0.005);
    CHECK(p.treatment == ArcTreatment::one_line);
    CHECK(p.count == 1);
    s.min_radius = 0.0015;  // not below: equal
    CHECK(plan_arc(g, s, 0.005).treatment == ArcTreatment::arcs);
}

TEST_CASE("rule: an arc shorter than minLength is one straight move; a helix counts its depth") {
    ArcSettings s = bare();
    s.min_length = 0.01;
    // r = 1: 0.5 degrees is 1 x 0.0087266 = 0.0087 mm < 0.01; 1 degree is 0.01745 mm.
    auto at = [](double deg) { return Vec3{std::cos(deg * pi / 180), std::sin(deg * pi / 180), 0}; };
    CHECK(plan_arc(arc_from({1, 0, 0}, at(0.5), {0, 0, 0}, ArcDirection::ccw), s, 0.005).treatment == ArcTreatment::one_line);
    CHECK(plan_arc(arc_from({1, 0, 0}, at(1.0), {0, 0, 0}, ArcDirection::ccw), s, 0.005).treatment == ArcTreatment::arcs);
    // The 0.5 degree arc going down 0.006 mm: length sqrt(0.0087266^2 + 0.006^2) = 0.01059 >= 0.01.
    Vec3 down = at(0.5);
    down.z = -0.006;
    ArcGeometry h = arc_from({1, 0, 0}, down, {0, 0, 0}, ArcDirection::ccw);
    CHECK(arc_length(h) == doctest::Approx(0.010590).epsilon(1e-4));
    CHECK(plan_arc(h, s, 0.005).treatment == ArcTreatment::arcs);
}

TEST_CASE("rule: the chord tolerance is the operation's, capped by the machine's (or absolute)") {
    ArcSettings s = bare();
    s.chord_tolerance = 0.005;
    CHECK(effective_chord_tolerance(s, std::nullopt) == 0.005);
    CHECK(effective_chord_tolerance(s, 0.001) == 0.001);
    CHECK(effective_chord_tolerance(s, 0.01) == 0.005);  // never above CIRC_TOL
    s.tolerance_mode = ChordToleranceMode::absolute;
    CHECK(effective_chord_tolerance(s, 0.001) == 0.005);
    // r = 10, 90 degrees at 0.001: 2 acos(1 - 0.0001) = 2 x 0.0141422 = 0.0282844 rad;
    // (pi/2) / 0.0282844 = 55.54 -> 56 segments.
    s.planes = {};
    ArcGeometry g = arc_from({10, 0, 0}, {0, 10, 0}, {0, 0, 0}, ArcDirection::ccw);
    CHECK(plan_arc(g, s, 0.001).count == 56);
    CHECK(plan_arc(g, s, 0.005).count == 25);
}

TEST_CASE("rule: the operation's tolerance reaches the post from the job") {
    // A 90-degree XZ arc, r = 10, on wabeco (XY only): 25 lines at the machine's 0.005, 56 at
    // the operation's 0.001 (see above); 0.05 is capped at 0.005.
    auto job = [](const std::string& tol) {
        return R"({"clearance": 20, "tools": [{"number": 1, "diameter": 6, "rpm": 2000, "type": "end-mill"}],
          "operations": [{"type": "path", "tool": 1, "z": 0, "feed": 300, )" + tol + R"("start": [10, 0],
            "path": [{"arc": {"plane": "xz", "end": [0, 0, -10], "centre": [0, 0, 0], "direction": "ccw"}}]}]})";
    };
    auto feed_lines = [](const std::string& text) {
        int n = 0;
        for (const auto& l : lines_of(text))
            if (l.rfind("G01 X", 0) == 0) ++n;
        return n;
    };
    CHECK(feed_lines(post_job(job(""), "wabeco").text) == 25);
    CHECK(feed_lines(post_job(job(R"("tolerance": 0.001, )"), "wabeco").text) == 56);
    CHECK(feed_lines(post_job(job(R"("tolerance": 0.05, )"), "wabeco").text) == 25);
}

TEST_CASE("rule: minSegments raises the count") {
    ArcSettings s = bare();
    s.planes = {};
    ArcGeometry g = arc_from({10, 0, 0}, {0, 10, 0}, {0, 0, 0}, ArcDirection::ccw);
    s.min_segments = 40;
    CHECK(plan_arc(g, s, 0.005).count == 40);
    s.min_segments = 10;  // below the tolerance's 25: no effect
    CHECK(plan_arc(g, s, 0.005).count == 25);
}

TEST_CASE("rule: maxSegmentLength raises the count until every chord fits") {
    ArcSettings s = bare();
    s.planes = {};
    s.max_segment_length = 0.5;
    // r = 10, 90 degrees: chord(n) = 20 sin(pi / 4n) <= 0.5 -> pi/4n <= asin(0.025) =
    // 0.0250026 -> n >= 31.41 -> 32. chord(31) = 20 sin(pi/124) = 0.50665 > 0.5;
    // chord(32) = 20 sin(pi/128) = 0.49082.
    ArcGeometry g = arc_from({10, 0, 0}, {0, 10, 0}, {0, 0, 0}, ArcDirection::ccw);
    CHECK(plan_arc(g, s, 0.005).count == 32);
    CHECK(chord_length(g, 31) == doctest::Approx(0.50665).epsilon(1e-4));
    CHECK(chord_length(g, 32) == doctest::Approx(0.49082).epsilon(1e-4));
    // Going down 8 mm on the way the chord is longer: hypot(20 sin(pi/4n), 8/n).
    // n = 35: hypot(0.448762, 0.228571) = 0.50362 > 0.5; n = 36: hypot(0.436298, 0.222222) = 0.48963.
    ArcGeometry h = arc_from({10, 0, 0}, {0, 10, -8}, {0, 0, 0}, ArcDirection::ccw);
    CHECK(plan_arc(h, s, 0.005).count == 36);
    // A limit the tolerance already meets changes nothing.
    s.max_segment_length = 5;
    CHECK(plan_arc(g, s, 0.005).count == 25);
}

TEST_CASE("rule: an arc that needs more chords than the limit says how many; up to the limit it is broken") {
    // Issue 24, item 11: the count was capped at 10,000,000, so a longer helix was written in
    // chords too long for the tolerance (0.49 mm off its circle) without a word.
    ArcSettings s = bare();
    s.helical = false;
    // Radius 0.004 below the tolerance 0.005: two chords a turn (each half a turn). 5,000,000
    // turns is the limit exactly; a quarter turn more needs one chord more.
    const ArcGeometry at_limit = arc_from({0.004, 0, 0}, {0.004, 0, -5}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 4'999'999);
    CHECK(segment_count(at_limit, s, 0.005) == max_arc_chords);
    CHECK(plan_arc(at_limit, s, 0.005).count == 10'000'000);
    const double quarter = 2 * pi * 5'000'000.25;
    const ArcGeometry over = resolve_arc({0.004, 0, 0}, Arc{{0.004 * std::cos(quarter), 0.004 * std::sin(quarter), -5}, {0, 0, 0},
                                                            ArcDirection::ccw, Plane::xy, 100.0, 5'000'000});
    CHECK(segment_count(over, s, 0.005) == 10'000'001);
    // Radius 50, 7000 turns at tolerance 0.0001: a chord may turn 2 acos(1 - 0.0001/50) =
    // 0.00400000067 rad; 7000 x 2 pi / that = 10,995,572.46 -> 10,995,573 chords, not 10,000,000.
    const ArcGeometry wide = arc_from({50, 0, 0}, {50, 0, -7}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 6999);
    const ArcPlan p = plan_arc(wide, s, 0.0001);
    CHECK(p.treatment == ArcTreatment::lines);
    CHECK(p.count == 10'995'573);
    // maxSegmentLength beyond the limit: radius 10, 1000 turns flat = 62,831.85 mm in chords of
    // at most 0.005 mm: 12,566,371 (the tolerance alone: 1000 x 2 pi / (2 acos(1 - 0.005/10)) =
    // 99,341.4 -> 99,342).
    s.planes = {};
    s.max_segment_length = 0.005;
    const ArcGeometry flat = arc_from({10, 0, 0}, {10, 0, 0}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 999);
    CHECK(segment_count(flat, s, 0.005) == 12'566'371);
    s.max_segment_length.reset();
    CHECK(segment_count(flat, s, 0.005) == 99'342);
}

TEST_CASE("rule: an arc the post would break into more chords than the limit is an error naming the operation") {
    // A 300 mm bore with a 200 mm tool: one helix of radius 50, 7000 turns (7 mm at 0.001 mm a
    // turn), which wabeco (no helices) breaks into chords of the operation's 0.0001 mm: 10,995,573
    // (above). Refused before it is written, the numbers in the message; standard output and the
    // -o file stay empty.
    const std::string job = R"({"name": "t", "units": "mm", "clearance": 10,
      "tools": [{"number": 1, "type": "end-mill", "diameter": 200, "rpm": 1000}],
      "operations": [{"type": "bore-mill", "tool": 1, "diameter": 300, "retractPlane": 5, "safeDistance": 1,
        "feed": 500, "endDepth": 7, "pitch": 0.001, "tolerance": 0.0001, "holes": [[0, 0]]}]})";
    std::string message;
    try {
        (void)post_job(job, "wabeco");
    } catch (const InputError& e) {
        message = e.what();
    }
    CHECK(message ==
          "/operations/0: a helix of 7000 turns of radius 50 mm, which machine wabeco writes as straight moves (helix not "
          "supported), needs 10995573 of them to keep within the chord tolerance of 0.0001 mm; at most 10000000 are written "
          "for one arc (fewer turns or a larger pitch, a larger tolerance up to the machine's chordTolerance 0.005 mm, or a "
          "machine that writes it as arcs)");
    const std::string file = file_with("chord-limit", job);
    const std::string out = (scratch("chord-limit-out") / "t.knc").string();
    const Run r = run({file, "--machine", "wabeco", "-o", out});
    CHECK(r.code != 0);
    CHECK(r.err.find("needs 10995573 of them") != std::string::npos);
    CHECK(!std::filesystem::exists(out));
    // The same bore on a machine that writes helices: 7000 helical turns, no chords.
    CHECK(post_job(job, "grbl").text.find("G3") != std::string::npos);
}

TEST_CASE("rule: segments are equal and the last ends exactly at the arc's end") {
    ArcGeometry g = arc_from({10, 0, 0}, {10 * std::cos(1.75), 10 * std::sin(1.75), -3.1}, {0, 0, 0}, ArcDirection::ccw);
    auto points = linearize_arc(g, 25);
    REQUIRE(points.size() == 25);
    CHECK(points.back() == g.end);  // bit for bit
    Vec3 prev = g.start;
    for (const Vec3& p : points) {
        CHECK(length(p - prev) == doctest::Approx(chord_length(g, 25)).epsilon(1e-9));
        prev = p;
    }
}

TEST_CASE("rule: maxSweep splits into equal pieces; the radius form at most 180 a block") {
    ArcSettings s = bare();
    ArcGeometry three_quarters = arc_from({10, 0, 0}, {0, -10, 0}, {0, 0, 0}, ArcDirection::ccw);
    ArcGeometry full = arc_from({10, 0, 0}, {10, 0, 0}, {0, 0, 0}, ArcDirection::ccw);
    ArcGeometry helix3 = arc_from({10, 0, 0}, {10, 0, -6}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 2);
    CHECK(helix3.sweep == doctest::Approx(6 * pi));
    CHECK(plan_arc(three_quarters, s, 0.005).count == 1);
    CHECK(plan_arc(full, s, 0.005).count == 1);
    CHECK(plan_arc(helix3, s, 0.005).count == 3);
    s.max_sweep = 180;
    CHECK(plan_arc(three_quarters, s, 0.005).count == 2);
    CHECK(plan_arc(full, s, 0.005).count == 2);
    s.max_sweep = 90;
    CHECK(plan_arc(three_quarters, s, 0.005).count == 3);
    s.max_sweep = 360;
    s.format = ArcFormat::radius;
    CHECK(plan_arc(full, s, 0.005).count == 2);
    CHECK(plan_arc(helix3, s, 0.005).count == 6);
    // The pieces of a 3-turn helix each go down a third.
    auto pieces = split_arc(helix3, 3);
    CHECK(pieces[0].end.z == doctest::Approx(-2));
    CHECK(pieces[1].end.z == doctest::Approx(-4));
    CHECK(pieces[2].end == helix3.end);
}

// ---------------------------------------------------------------- rounded arcs stay on the circle

TEST_CASE("rounding: a tiny arc whose rounded ends coincide is a straight move, never a full circle") {
    Machine m = load_machine("fanuc");
    m.arcs.min_radius.reset();
    m.arcs.min_length.reset();
    // r = 0.001 about (5, 5), 20 degrees ccw from (5.001, 5): the end (5.00094, 5.00034)
    // rounds to X5.001 Y5.000, the start's words. As an arc block that reads as 360 degrees.
    Vec3 end{5 + 0.001 * std::cos(20 * pi / 180), 5 + 0.001 * std::sin(20 * pi / 180), 0};
    std::string nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{5.001, 5, 0}}, Arc{end, {5, 5, 0}, ArcDirection::ccw, Plane::xy, 100, 0}});
    CHECK(nc.find("G3") == std::string::npos);
    CHECK(nc.find("G2") == std::string::npos);
    ArcWordFormats f{m.format("xyz"), m.format("ijk"), m.format("angle"), ArcFormat::ijk_relative, 0.002};
    CHECK(fit_arc_block(arc_from({5.001, 5, 0}, end, {5, 5, 0}, ArcDirection::ccw), {5.001, 5, 0}, f).result ==
          ArcFitResult::degenerate);
    // A real full circle of the same radius is written as one.
    nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{5.001, 5, 0}}, Arc{{5.001, 5, 0}, {5, 5, 0}, ArcDirection::ccw, Plane::xy, 100, 0}});
    CHECK(nc.find("G3 X5.001 Y5.000 I-0.001 J0.000 F100\n") != std::string::npos);
    // nccad: a sweep that rounds to D0 is a straight move too.
    Machine w = load_machine("wabeco");
    w.arcs.min_radius.reset();
    w.arcs.min_length.reset();
    Vec3 e2{10 * std::cos(0.0004 * pi / 180), 10 * std::sin(0.0004 * pi / 180), 0};  // 0.0004 degrees: D0.000
    nc = post_events(w, {ToolChange{1, 6, ""}, Rapid{{10, 0, 0}}, Arc{e2, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 100, 0}});
    CHECK(nc.find(" D") == std::string::npos);
}

TEST_CASE("rounding: centre words are adjusted when plain rounding puts the ends on different circles") {
    // A machine with 2 decimals. Arc cw from (0,0) about (10.004, 0.004), 90 degrees: the
    // end is (10.004, 10.008) (r = 10.0040008, straight above the centre), written X10.00 Y10.01.
    // Plain rounding gives I10.00 J0.00: centre (10, 0); start radius 10.000, end radius
    // |(10.00, 10.01) - (10, 0)| = 10.010: 0.010 apart, more than the 0.002 tolerance.
    // Moving J to 0.01 (centre (10.00, 0.01)): start radius sqrt(10^2 + 0.01^2) = 10.000005,
    // end radius 10.00 - 0.01 = 10.000: 0.000005 apart.
    Machine m = load_machine("fanuc");
    nc::FormatSpec two;
    two.decimals = 2;
    two.force_decimal = true;
    m.formats["xyz"] = two;
    m.formats["ijk"] = two;
    const double r = std::hypot(10.004, 0.004);
    std::string nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{0, 0, 0}},
                                     Arc{{10.004, 0.004 + r, 0}, {10.004, 0.004, 0}, ArcDirection::cw, Plane::xy, 100, 0}});
    CHECK(nc.find("G2 X10.00 Y10.01 I10.00 J0.00") == std::string::npos);
    auto arcs = arc_moves(interpret(nc, ArcFormat::ijk_relative));
    REQUIRE(arcs.size() == 1);
    CHECK(arcs[0].line.find("G2 X10.00 Y10.01 I") != std::string::npos);
    CHECK(std::abs(arcs[0].radius_start - arcs[0].radius_end) <= 0.002);
    CHECK(arcs[0].sweep == doctest::Approx(pi / 2).epsilon(0.01));
}

TEST_CASE("rounding: a radius-form half circle whose rounded chord makes R unstable is split") {
    // r = 10 about the origin, ccw from 10 to 190 degrees. The start (9.848078, 1.736482) is
    // written (9.848, 1.736), the end (-9.848, -1.736): half chord |(9.848, 1.736)| = 9.999840.
    // With R10.000 the control puts the centre sqrt(10^2 - 9.999840^2) = 0.0566 mm off the
    // chord's middle, so the arc bulges 0.057 mm off the circle. Two 90-degree blocks have
    // half chords of about 7.07, where that sensitivity is gone.
    Machine m = fanuc_with(ArcFormat::radius);
    auto at = [](double deg) { return Vec3{10 * std::cos(deg * pi / 180), 10 * std::sin(deg * pi / 180), 0}; };
    std::string nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{at(10)}, Arc{at(190), {0, 0, 0}, ArcDirection::ccw, Plane::xy, 100, 0}});
    auto arcs = arc_moves(interpret(nc, ArcFormat::radius));
    REQUIRE(arcs.size() == 2);
    CHECK(arcs[0].line.find("G3 X-1.736 Y9.848 R10.000 F100") != std::string::npos);
    ArcGeometry truth = arc_from(at(10), at(190), {0, 0, 0}, ArcDirection::ccw);
    CHECK(deviation_from_arc(truth, sampled(arcs, 32)) <= 0.002 + 0.0007);
    // Where the ends are exact, a half circle stays one block.
    nc = post_events(m, {ToolChange{1, 6, ""}, Rapid{{10, 0, 0}}, Arc{{-10, 0, 0}, {0, 0, 0}, ArcDirection::ccw, Plane::xy, 100, 0}});
    CHECK(arc_moves(interpret(nc, ArcFormat::radius)).size() == 1);
}

TEST_CASE("rounding: every arc block of every sample keeps its radii within the machine's tolerance") {
    for (const char* machine : {"fanuc", "kosy"})
        for (const char* sample : {"arcs", "bracket"}) {
            CAPTURE(machine);
            CAPTURE(sample);
            Posted p = post_job(read_file(std::string(CAMGEN_SOURCE_DIR "/samples/") + sample + ".json"), machine);
            for (const NcMove& m : arc_moves(interpret(p.text, ArcFormat::ijk_relative)))
                CHECK(std::abs(m.radius_start - m.radius_end) <= 0.002);
        }
}

// ---------------------------------------------------------------- kosy

TEST_CASE("kosy: classic G02 X Y I J with X and Y on every arc block, at most 180 degrees") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/arcs.json"), "kosy");
    auto lines = lines_of(p.text);
    CHECK(lines[0] == "_");
    CHECK(lines[1] == "_");
    CHECK(lines[3] == "G90");
    CHECK(lines[lines.size() - 3] == "M10 O6.0");
    CHECK(lines[lines.size() - 2] == "G77");
    CHECK(lines.back() == "G99");
    CHECK(p.text.find(" D") == std::string::npos);
    // 300 mm/min = 5 mm/s = F50 in 0.1 mm/s.
    CHECK(p.text.find("G03 X10 Y10 I-10 J0 F50\n") != std::string::npos);
    // X is unchanged (10) and still written.
    CHECK(p.text.find("G03 X10 Y30 I0 J10\n") != std::string::npos);
    auto arcs = arc_moves(interpret(p.text, ArcFormat::ijk_relative));
    CHECK(arcs.size() == 12);  // 1 + 1 + 2 + 2 per direction
    for (const NcMove& m : arcs) {
        auto w = words_of(m.line);
        CHECK(w.count('X'));
        CHECK(w.count('Y'));
        CHECK(!w.count('Z'));
        CHECK(m.sweep <= pi + 1e-9);
    }
    // No arc in another plane and no helix: only G02/G03 with X Y I J.
    CHECK(p.text.find("G17") == std::string::npos);
    CHECK(p.text.find("K") == std::string::npos);
}

TEST_CASE("kosy describes its feed unit choice") {
    Machine m = load_machine("kosy");
    CHECK(m.feed_unit == FeedUnit::tenth_mm_per_second);
    CHECK(m.arcs.format == ArcFormat::ijk_relative);
    CHECK(m.arcs.force_xy);
    CHECK(m.arcs.planes == std::vector<Plane>{Plane::xy});
    CHECK(!m.arcs.helical);
    CHECK(m.arcs.max_sweep == 180);
    std::string d = describe_machine(m);
    CHECK(d.find("0.1 mm/s") != std::string::npos);
    CHECK(d.find("FreeCAD") != std::string::npos);
}

// ---------------------------------------------------------------- linearized arcs measured

namespace {
// samples/arcs.json with only operation `op`, posted for `machine`, and the feed moves after
// the plunge (the path), interpreted.
std::vector<NcMove> sample_path(const std::string& machine, int op, Vec3 start) {
    nlohmann::json job = nlohmann::json::parse(read_file(CAMGEN_SOURCE_DIR "/samples/arcs.json"));
    job["operations"] = nlohmann::json::array({job["operations"][op]});
    Posted p = post_job(job.dump(), machine);
    std::vector<NcMove> path;
    bool plunged = false;
    for (const NcMove& m : interpret(p.text, ArcFormat::ijk_relative)) {
        if (m.g == 1 && !plunged) {
            plunged = true;  // the plunge to depth
            continue;
        }
        if (plunged && m.g != 0) path.push_back(m);
        if (plunged && m.g == 0) break;
    }
    REQUIRE(!path.empty());
    CHECK(length(path.front().from - start) < 1e-9);
    return path;
}
}  // namespace

TEST_CASE("linearized arcs stay within the chord tolerance, chord midpoints included") {
    for (const char* machine : {"wabeco", "kosy"}) {
        CAPTURE(machine);
        const double tol = load_machine(machine).arcs.chord_tolerance;
        const double rounding = 0.0005 * std::sqrt(3.0);  // the 3-decimal words, in X, Y and Z
        // The XZ arc (G18 cw: dips to Z-6), then the YZ arc (G19 ccw: dips to Z-6).
        auto path = sample_path(machine, 4, {200, 0, -1});
        ArcGeometry xz = arc_from({200, 0, -1}, {210, 0, -1}, {205, 0, -1}, ArcDirection::cw, Plane::xz);
        ArcGeometry yz = arc_from({210, 0, -1}, {210, 10, -1}, {210, 5, -1}, ArcDirection::ccw, Plane::yz);
        std::vector<NcMove> first, second;
        for (const NcMove& m : path) (m.from.y < 1e-9 && m.to.y < 1e-9 ? first : second).push_back(m);
        REQUIRE(first.size() == 36);  // pi / (2 acos(1 - 0.005/5)) = 35.1 -> 36
        REQUIRE(second.size() == 36);
        double d1 = deviation_from_arc(xz, sampled(first, 8)), d2 = deviation_from_arc(yz, sampled(second, 8));
        CHECK(d1 <= tol + rounding);
        CHECK(d2 <= tol + rounding);
        // ... and not needlessly fine: the sagitta of 36 chords is 5 (1 - cos(pi/72)) = 0.0048.
        CHECK(d1 > 0.8 * tol);
        CHECK(d2 > 0.8 * tol);
        CHECK(first[17].to.z == doctest::Approx(-6));  // the 18th of 36 ends at the bottom of the dip
        // The arc above the maximum radius (1522 mm, 11 chords).
        auto big = sample_path(machine, 2, {100, 0, -1});
        REQUIRE(big.size() == 13);  // the tiny arc's line, the line to (100, 20), 11 chords
        ArcGeometry large = arc_from({100, 20, -1}, {178, 22, -1}, {100, 1542, -1}, ArcDirection::ccw);
        std::vector<NcMove> chords(big.begin() + 2, big.end());
        CHECK(deviation_from_arc(large, sampled(chords, 8)) <= tol + rounding);
        CHECK(length(chords.back().to - Vec3{178, 22, -1}) < 1e-9);
        // The tiny arc: one straight move to its end.
        CHECK(big[0].line == "G01 X100.004 Y0.004 F50");
    }
}

TEST_CASE("linearized helix: within tolerance, and 2 mm down every turn") {
    for (const char* machine : {"wabeco", "kosy"}) {
        CAPTURE(machine);
        const double tol = load_machine(machine).arcs.chord_tolerance;
        auto path = sample_path(machine, 3, {150, 0, -1});
        // r = 2, 3 turns: 6 pi / (2 acos(1 - 0.005/2)) = 6 pi / 0.141451 = 133.3 -> 134 chords.
        REQUIRE(path.size() == 134);
        ArcGeometry helix = arc_from({150, 0, -1}, {150, 0, -7}, {150, 2, -1}, ArcDirection::ccw, Plane::xy, 2);
        CHECK(deviation_from_arc(helix, sampled(path, 8)) <= tol + 0.0005 * std::sqrt(3.0));
        // Depth per turn: unwrap the angle of every segment end, and compare Z with
        // -1 - 2 x (turns so far); also find Z where each turn completes.
        double travelled = 0, last = -pi / 2;  // the start (150, 0) is straight below the centre
        std::vector<double> z_at_turn{-1.0};
        Vec3 prev = path.front().from;
        for (const NcMove& m : path) {
            double a = std::atan2(m.to.y - 2, m.to.x - 150);
            double before = travelled;
            travelled += std::remainder(a - last, 2 * pi);
            last = a;
            CHECK(std::abs(m.to.z - (-1 - 2 * travelled / (2 * pi))) < 0.001);
            // A turn completes inside this segment: interpolate Z at that angle.
            double turn = std::floor(travelled / (2 * pi) + 1e-9);
            if (turn > std::floor(before / (2 * pi) + 1e-9)) {
                double t = (turn * 2 * pi - before) / (travelled - before);
                z_at_turn.push_back(prev.z + (m.to.z - prev.z) * t);
            }
            prev = m.to;
        }
        CHECK(travelled == doctest::Approx(6 * pi));
        REQUIRE(z_at_turn.size() == 4);
        for (size_t k = 1; k < z_at_turn.size(); ++k) CHECK(z_at_turn[k] - z_at_turn[k - 1] == doctest::Approx(-2).epsilon(0.001));
        CHECK(path.back().to.z == -7);
    }
}

TEST_CASE("fanuc writes the 3-turn helix as three full-turn helical blocks") {
    Posted p = post_job(read_file(CAMGEN_SOURCE_DIR "/samples/arcs.json"), "fanuc");
    CHECK(p.text.find("G3 X150.000 Y0.000 Z-3.000 I0.000 J2.000 F300\n") != std::string::npos);
    CHECK(p.text.find("X150.000 Y0.000 Z-5.000 I0.000 J2.000\n") != std::string::npos);
    CHECK(p.text.find("X150.000 Y0.000 Z-7.000 I0.000 J2.000\n") != std::string::npos);
}

// ---------------------------------------------------------------- machine file keys

TEST_CASE("machine file: arc settings are read, checked, and described") {
    auto machine = [](const std::string& arcs) {
        return parse_machine(R"({"description": "t", "dialect": "iso", "extension": "nc",
  "arcs": )" + arcs + "}",
                             "t", "t.json");
    };
    Machine m = machine(R"({"format": "radius", "maxSweep": 90, "helical": false, "planes": ["xy", "yz"],
    "chordTolerance": 0.01, "chordToleranceMode": "absolute", "maxRadius": 500, "minRadius": 0.05,
    "minLength": 0.1, "minSegments": 4, "maxSegmentLength": 2, "forceXY": false})");
    CHECK(m.arcs.format == ArcFormat::radius);
    CHECK(m.arcs.max_sweep == 90);
    CHECK(!m.arcs.helical);
    CHECK(m.arcs.planes == std::vector<Plane>{Plane::xy, Plane::yz});
    CHECK(m.arcs.chord_tolerance == 0.01);
    CHECK(m.arcs.tolerance_mode == ChordToleranceMode::absolute);
    CHECK(m.arcs.max_radius == 500);
    CHECK(m.arcs.min_radius == 0.05);
    CHECK(m.arcs.min_length == 0.1);
    CHECK(m.arcs.min_segments == 4);
    CHECK(m.arcs.max_segment_length == 2);
    CHECK(!m.arcs.force_xy);
    std::string d = describe_machine(m);
    CHECK(d.find("radius above 500 mm; at least 4 segment(s), each at most 2 mm") != std::string::npos);
    CHECK(d.find("radius below 0.05 mm, length below 0.1 mm") != std::string::npos);
    CHECK(d.find("xy, yz (others as lines)") != std::string::npos);
    // Defaults: no limits, the operation's tolerance may tighten the machine's.
    Machine plain = machine("{}");
    CHECK(!plain.arcs.max_radius);
    CHECK(!plain.arcs.min_radius);
    CHECK(!plain.arcs.min_length);
    CHECK(plain.arcs.min_segments == 1);
    CHECK(plain.arcs.tolerance_mode == ChordToleranceMode::operation);
    CHECK(plain.tolerance == 0.002);

    auto error = [&](const std::string& arcs, const std::string& path, const std::string& text) {
        try {
            machine(arcs);
            FAIL("expected an error for " << arcs);
        } catch (const InputError& e) {
            CHECK(e.path() == path);
            CHECK(std::string(e.what()).find(text) != std::string::npos);
        }
    };
    error(R"({"maxRadius": 0})", "/arcs/maxRadius", "maxRadius must be > 0");
    error(R"({"minLength": -1})", "/arcs/minLength", "minLength must be > 0");
    error(R"({"minSegments": 0})", "/arcs/minSegments", "minSegments must be between 1 and 100000");
    error(R"({"minRadius": 5, "maxRadius": 2})", "/arcs/minRadius", "minRadius must be below maxRadius");
    error(R"({"chordToleranceMode": "relative"})", "/arcs/chordToleranceMode", "\"relative\" is not one of");
    error(R"({"format": "nccad-angle", "maxSweep": 180, "planes": ["xy"]})", "/arcs/helical", "cannot write a helix");
    error(R"({"format": "nccad-angle", "maxSweep": 180, "helical": false})", "/arcs/planes", "XY arcs only");
    error(R"({"format": "nccad-angle", "helical": false, "planes": ["xy"]})", "/arcs/maxSweep", "at most 180 degrees");
    error(R"({"maxSegmentLenght": 2})", "/arcs/maxSegmentLenght", "did you mean \"maxSegmentLength\"");
}

TEST_CASE("fanuc breaks the 1522 mm arc into 11 chords within its tolerance") {
    auto big = sample_path("fanuc", 2, {100, 0, -1});
    REQUIRE(big.size() == 13);
    std::vector<NcMove> chords(big.begin() + 2, big.end());
    ArcGeometry large = arc_from({100, 20, -1}, {178, 22, -1}, {100, 1542, -1}, ArcDirection::ccw);
    double d = deviation_from_arc(large, sampled(chords, 8));
    CHECK(d <= load_machine("fanuc").arcs.chord_tolerance + 0.0007);
    // 11 chords of 0.0512708 / 11 = 0.00466098 rad: sagitta 1522 (1 - cos(0.00233049)) = 0.004133.
    CHECK(d > 0.004);
}

TEST_CASE("a full circle cut in two halves at the 180 degree limit reads back although rounding widens one half") {
    // Radius hypot(3.8125, 10) = 10.702: the halves end at points whose rounded words give
    // 180.005 degrees on kosy (3 decimals). A fuzz_mutated finding: verify refused camgen's own
    // program ("an arc of 180.005 degrees in one block").
    const std::string job = R"({"name": "c", "units": "mm", "clearance": 10,
      "tools": [{"number": 5, "type": "end-mill", "diameter": 4, "rpm": 4000}],
      "operations": [{"type": "path", "tool": 5, "z": -1, "feed": 300, "start": [20, 40],
        "path": [{"arc": {"centre": [23.8125, 50], "direction": "ccw", "end": [20, 40]}}]}]})";
    const std::string file = file_with("full-circle-halves", job);
    const std::string program = scratch("full-circle-halves-out") / "c.knc";
    REQUIRE(run({file, "--machine", "kosy", "-o", program}).code == 0);
    const Run verify = run({"verify", program, "--machine", "kosy", "--job", file});
    CHECK_MESSAGE(verify.code == 0, verify.err);
}

TEST_CASE("a half circle whose centre word rounds off the chord is refitted, not written wider than 180 degrees") {
    // The centre (60, 64.0625) is half a grid step off the rounded ends' chord (Y 64.063), so
    // plain rounding writes J-0.001 and the second half of the circle reads as 180.029 degrees
    // on kosy, more than rounding can explain. A fuzz_mutated finding (a bore milled at
    // Y 64.0625): verify refused camgen's own program. The fit must keep each block within the
    // machine's per-block sweep.
    const std::string job = R"({"name": "c", "units": "mm", "clearance": 10,
      "tools": [{"number": 1, "type": "end-mill", "diameter": 10, "rpm": 4000}],
      "operations": [{"type": "path", "tool": 1, "z": -1, "feed": 300, "start": [64, 64.0625],
        "path": [{"arc": {"centre": [60, 64.0625], "direction": "ccw", "end": [64, 64.0625]}}]}]})";
    const std::string file = file_with("half-circle-off-chord", job);
    for (const std::string machine : {"kosy", "wabeco", "fanuc", "sinumerik", "heidenhain", "linuxcnc", "grbl"}) {
        CAPTURE(machine);
        const std::string program = scratch("half-circle-off-chord-out") / "c.nc";
        REQUIRE(run({file, "--machine", machine, "-o", program}).code == 0);
        const Run verify = run({"verify", program, "--machine", machine, "--job", file});
        CHECK_MESSAGE(verify.code == 0, verify.err);
    }
}

}  // namespace test_arcs
