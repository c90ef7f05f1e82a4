// Material simulation: analytic volumes within bounds derived from the resolution, the same
// shapes sampled at the cells' centres exactly, crashes and cuts beyond the flutes at their
// lines, and the samples simulated clean.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/simulation/simulation.hpp"
#include "support.hpp"

namespace test_simulation {

using namespace camgen;

constexpr double pi_ = 3.14159265358979323846;

Step move(StepKind kind, Vec3 a, Vec3 b, int tool = 1, int line = 0) {
    Step s;
    s.kind = kind;
    s.from = a;
    s.to = b;
    s.tool = tool;
    s.line = line;
    s.feed = kind == StepKind::feed ? 300 : 0;
    return s;
}

Step arc(Vec3 a, Vec3 to, Vec3 centre, ArcDirection dir, int turns = 0, int tool = 1) {
    Step s = move(StepKind::feed, a, to, tool);
    s.arc = resolve_arc(a, ArcSpec{to, centre, dir, Plane::xy, turns});
    return s;
}

SimStock box(Vec3 lo, Vec3 hi) {
    SimStock s;
    s.kind = SimStock::Kind::box;
    s.min = lo;
    s.max = hi;
    return s;
}

ToolShape shape(ToolForm form, double d = 0.0) {
    ToolShape t;
    t.form = form;
    t.diameter = d;
    return t;
}

ToolShape flat(double d) { return shape(ToolForm::flat, d); }

// The volume below the stock's top a field lost, summed over its cells, and the same with the
// expected depth at each cell's centre given by `depth(x, y)` (the sampled reference).
double sampled(const HeightField& f, auto depth) {
    double v = 0;
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) v += std::min(depth(f.x(i), f.y(j)), f.top - f.bottom);
    return v * f.cell * f.cell;
}

// Every cell's height equals top - depth(x, y) (within float rounding), except cells whose
// centre lies in `ambiguous(x, y)` (within a tolerance of an edge). Returns the cells that differ.
int differing(const HeightField& f, auto depth, auto ambiguous) {
    int bad = 0;
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) {
            if (ambiguous(f.x(i), f.y(j))) continue;
            const double want = std::max(f.bottom, f.top - depth(f.x(i), f.y(j)));
            if (std::abs(f.at(i, j) - want) > 1e-4) ++bad;
        }
    return bad;
}

// The volume a field lost.
double removed(const HeightField& f) {
    double v = 0;
    for (float h : f.heights) v += f.top - h;
    return v * f.cell * f.cell;
}

// A cell-centre sampling of a region whose boundary has length P differs from the region's
// area only in cells the boundary crosses: each lies within a cell's diagonal of the boundary,
// in a band of area at most 2 x diagonal x P (+ the ends' discs for an open curve, none here),
// and each is off by at most its own area. So |V - exact| <= depth x 2 x sqrt(2) x cell x P.
double boundary_bound(double cell, double perimeter, double depth) { return depth * 2 * std::sqrt(2.0) * cell * perimeter; }

TEST_CASE("simulation: a flat-bottom bore by helix removes pi r^2 d, every cell exact at its centre") {
    const Machine m = load_machine("linuxcnc");
    // 6 mm end mill on a helix of radius 2 around (50, 50): a bore of radius 5, 5 mm deep,
    // 5 turns down, then a full circle at the bottom.
    const double a = 5, d = 5;
    std::vector<Step> steps = {
        move(StepKind::rapid, {52, 50, 5}, {52, 50, 1}),
        move(StepKind::feed, {52, 50, 1}, {52, 50, 0}),
        arc({52, 50, 0}, {52, 50, -d}, {50, 50, 0}, ArcDirection::ccw, 4),
        arc({52, 50, -d}, {52, 50, -d}, {50, 50, -d}, ArcDirection::ccw),
        move(StepKind::feed, {52, 50, -d}, {50, 50, -d}),
        move(StepKind::rapid, {50, 50, -d}, {50, 50, 5}),
    };
    SimOptions o;
    o.resolution = 0.1;
    const SimResult r = simulate(steps, m, box({30, 30, -20}, {70, 70, 0}), {{1, flat(6)}}, o);
    CHECK(r.errors.empty());
    CHECK(r.field.nx == 400);
    CHECK(r.field.ny == 400);
    const double exact = pi_ * a * a * d;
    const double bound = boundary_bound(0.1, 2 * pi_ * a, d);
    MESSAGE("bore: removed ", r.removed_volume, " exact ", exact, " bound ", bound);
    CHECK(std::abs(r.removed_volume - exact) <= bound);
    CHECK(std::abs(removed(r.field) - r.removed_volume) < 1e-6 * exact);
    // The helix is chords within cell/8 of the arc, inside it: no cell beyond radius 5 is
    // touched, every cell within is at the bottom.
    auto depth = [&](double x, double y) { return std::hypot(x - 50, y - 50) <= a ? d : 0.0; };
    CHECK(differing(r.field, depth, [](double, double) { return false; }) == 0);
    CHECK(std::abs(r.removed_volume - sampled(r.field, depth)) < 1e-6 * exact);
    REQUIRE(r.tools.size() == 1);
    CHECK(r.tools[0].volume == doctest::Approx(r.removed_volume));
}

TEST_CASE("simulation: a sloping straight move leaves each tool's lowest surface, checked against a dense search") {
    const Machine m = load_machine("linuxcnc");
    ToolShape ball = shape(ToolForm::ball, 6), bull = shape(ToolForm::bull_nose, 6), cone = shape(ToolForm::cone, 6),
              vbit = shape(ToolForm::cone, 6);
    bull.corner_radius = 1;
    cone.tip_angle = 90;
    vbit.tip_angle = 60;
    vbit.tip_diameter = 1;
    // A ramp along X and one along a diagonal, from above the stock to 3 mm into it.
    const Vec3 ramps[][2] = {{{5, 50, 1}, {35, 50, -3}}, {{5, 44, 0.5}, {30, 56, -2}}};
    for (const ToolShape& t : {flat(6), ball, bull, cone, vbit}) {
        for (const auto& ramp : ramps) {
            CAPTURE(static_cast<int>(t.form));
            CAPTURE(ramp[1].y);
            SimOptions o;
            o.resolution = 0.25;
            const SimResult r =
                simulate({move(StepKind::feed, ramp[0], ramp[1])}, m, box({0, 40, -10}, {40, 60, 0}), {{1, t}}, o);
            const HeightField& f = r.field;
            const double R = 3;
            auto surface = [&](double d) {  // the tool's lowest surface above its tip, as the header defines it
                switch (t.form) {
                case ToolForm::ball: return R - std::sqrt(R * R - d * d);
                case ToolForm::bull_nose: return d <= 2 ? 0.0 : 1 - std::sqrt(std::max(0.0, 1 - (d - 2) * (d - 2)));
                case ToolForm::cone: return d <= t.tip_diameter / 2 ? 0.0 : (d - t.tip_diameter / 2) / std::tan(t.tip_angle / 2 * pi_ / 180);
                default: return 0.0;
                }
            };
            // The lowest surface over 1500 positions along the move (and its ends): at most the
            // exact one plus the surface's rise over half a step (0.01 mm along the move) at its
            // steepest away from the rim (cone: 1.8 x; ball and bull within 0.03).
            int worse = 0, higher = 0;
            for (int j = 0; j < f.ny; ++j)
                for (int i = 0; i < f.nx; ++i) {
                    double best = f.top;
                    for (int k = 0; k <= 1500; ++k) {
                        const double u = k / 1500.0;
                        const Vec3 p{ramp[0].x + u * (ramp[1].x - ramp[0].x), ramp[0].y + u * (ramp[1].y - ramp[0].y),
                                     ramp[0].z + u * (ramp[1].z - ramp[0].z)};
                        const double d = std::hypot(f.x(i) - p.x, f.y(j) - p.y);
                        if (d <= R) best = std::min(best, p.z + surface(d));
                    }
                    const double h = f.at(i, j);
                    if (h > best + 1e-5) ++higher;          // the sweep left material the tool passed through
                    if (h < best - 0.03) ++worse;           // the sweep cut below every position's surface
                }
            CHECK(higher == 0);
            CHECK(worse == 0);
        }
    }
}

TEST_CASE("simulation: probes are swept exactly as cells' centres are, wherever they lie") {
    const Machine m = load_machine("linuxcnc");
    ToolShape ball = shape(ToolForm::ball, 6), bull = shape(ToolForm::bull_nose, 6), vbit = shape(ToolForm::cone, 6);
    bull.corner_radius = 1;
    vbit.tip_angle = 60;
    vbit.tip_diameter = 1;
    // A ramp, a level line, a plunge, a level arc and a helix (chords), lines 1 to 5.
    std::vector<Step> steps{move(StepKind::feed, {5, 44, 0.5}, {30, 56, -2}, 1, 1), move(StepKind::feed, {5, 47, -1}, {35, 47, -1}, 1, 2),
                            move(StepKind::feed, {20, 52, 1}, {20, 52, -3}, 1, 3)};
    steps.push_back(arc({10, 50, -0.5}, {30, 50, -0.5}, {20, 50, 0}, ArcDirection::ccw));
    steps.back().line = 4;
    steps.push_back(arc({28, 50, 0.2}, {12, 50, -1.5}, {20, 50, 0}, ArcDirection::cw));
    steps.back().line = 5;
    for (const ToolShape& t : {flat(6), ball, bull, vbit}) {
        CAPTURE(static_cast<int>(t.form));
        SimOptions o;
        o.resolution = 0.25;
        // Every cell's centre, and points between them.
        for (int j = 0; j < 80; ++j)
            for (int i = 0; i < 160; ++i) o.probes.push_back({0.125 + 0.25 * i, 40.125 + 0.25 * j});
        SimOptions fine = o;
        fine.resolution = 0.25 / 3;
        const SimResult r = simulate(steps, m, box({0, 40, -10}, {40, 60, 0}), {{1, t}}, o);
        const SimResult rf = simulate(steps, m, box({0, 40, -10}, {40, 60, 0}), {{1, t}}, fine);
        REQUIRE(r.probe_heights.size() == o.probes.size());
        int differ = 0, lines_differ = 0, cut = 0, fine_differ = 0;
        for (int j = 0; j < 80; ++j)
            for (int i = 0; i < 160; ++i) {
                const std::size_t k = static_cast<std::size_t>(j) * 160 + static_cast<std::size_t>(i);
                // The field holds floats, the probes doubles.
                if (std::abs(r.probe_heights[k] - r.field.at(i, j)) > 1e-5) ++differ;
                if (r.probe_lines[k] != r.field.lines[k]) ++lines_differ;
                cut += r.probe_heights[k] < 0;
                // At a third of the cell the same point is a cell's centre too: (3i+1, 3j+1).
                if (std::abs(rf.probe_heights[k] - rf.field.at(3 * i + 1, 3 * j + 1)) > 1e-5) ++fine_differ;
            }
        CHECK(differ == 0);
        CHECK(lines_differ == 0);
        CHECK(fine_differ == 0);
        CHECK(cut > 1000);
    }
    // A probe outside the stock has no height.
    SimOptions o;
    o.probes = {{50, 50}, {20, 52}};
    const SimResult r = simulate(steps, m, box({0, 40, -10}, {40, 60, 0}), {{1, flat(6)}}, o);
    CHECK(std::isnan(r.probe_heights[0]));
    CHECK(r.probe_heights[1] == doctest::Approx(-3));
    CHECK(r.probe_lines[1] == 3);
}

TEST_CASE("simulation: a drilled hole removes its cylinder and its cone") {
    const Machine m = load_machine("linuxcnc");
    const double R = 3, depth_ = 10;
    ToolShape drill = shape(ToolForm::cone, 2 * R);
    drill.tip_angle = 118;
    const double slope = 1 / std::tan(59 * pi_ / 180), hc = R * slope;
    std::vector<Step> steps = {move(StepKind::rapid, {50, 50, 5}, {50, 50, 2}),
                               move(StepKind::feed, {50, 50, 2}, {50, 50, -depth_}),
                               move(StepKind::rapid, {50, 50, -depth_}, {50, 50, 5})};
    SimOptions o;
    o.resolution = 0.05;
    const SimResult r = simulate(steps, m, box({40, 40, -20}, {60, 60, 0}), {{1, drill}}, o);
    CHECK(r.errors.empty());
    const double exact = pi_ * R * R * (depth_ - hc) + pi_ * R * R * hc / 3;
    // The boundary cells (as for the bore), and inside, the cone's height varies by at most
    // slope x half a cell's diagonal across a cell from its centre's.
    const double bound = boundary_bound(0.05, 2 * pi_ * R, depth_) + pi_ * R * R * slope * 0.05 * std::sqrt(0.5);
    MESSAGE("drill: removed ", r.removed_volume, " exact ", exact, " bound ", bound);
    CHECK(std::abs(r.removed_volume - exact) <= bound);
    auto depth = [&](double x, double y) {
        const double rho = std::hypot(x - 50, y - 50);
        return rho <= R ? depth_ - rho * slope : 0.0;
    };
    CHECK(differing(r.field, depth, [](double, double) { return false; }) == 0);
    CHECK(std::abs(r.removed_volume - sampled(r.field, depth)) < 1e-5 * exact);
}

TEST_CASE("simulation: a slot removes its stadium, at full radial engagement") {
    const Machine m = load_machine("linuxcnc");
    const double R = 3, d = 2;
    std::vector<Step> steps = {move(StepKind::rapid, {20, 50, 5}, {20, 50, 1}, 1, 10),
                               move(StepKind::feed, {20, 50, 1}, {20, 50, -d}, 1, 11),
                               move(StepKind::feed, {20, 50, -d}, {80, 50, -d}, 1, 12),
                               move(StepKind::rapid, {80, 50, -d}, {80, 50, 5}, 1, 13)};
    SimOptions o;
    o.resolution = 0.1;
    const SimResult r = simulate(steps, m, box({0, 0, -10}, {100, 100, 0}), {{1, flat(2 * R)}}, o);
    CHECK(r.errors.empty());
    const double exact = (60 * 2 * R + pi_ * R * R) * d;
    const double bound = boundary_bound(0.1, 2 * 60 + 2 * pi_ * R, d);
    MESSAGE("slot: removed ", r.removed_volume, " exact ", exact, " bound ", bound);
    CHECK(std::abs(r.removed_volume - exact) <= bound);
    auto depth = [&](double x, double y) {
        const double t = std::clamp((x - 20) / 60, 0.0, 1.0);
        return std::hypot(x - (20 + 60 * t), y - 50) <= R ? d : 0.0;
    };
    CHECK(differing(r.field, depth, [](double, double) { return false; }) == 0);
    REQUIRE(r.tools.size() == 1);
    CHECK(r.tools[0].max_engagement == doctest::Approx(1.0));
    CHECK(r.tools[0].engagement_line == 12);
}

TEST_CASE("simulation: a face pass of overlapping rows removes the stock's top, engaged by its step-over") {
    const Machine m = load_machine("linuxcnc");
    // 10 mm end mill, rows 6 mm apart (60 %), 1 mm off a 40 x 30 box, rows beyond its edges.
    std::vector<Step> steps;
    Vec3 at{-8, -1, 5};
    steps.push_back(move(StepKind::rapid, at, {-8, -1, -1}));
    at = {-8, -1, -1};
    bool right = true;
    for (double y = -1; y <= 30; y += 6) {
        if (y != -1) {
            steps.push_back(move(StepKind::feed, at, {at.x, y, -1}));
            at = {at.x, y, -1};
        }
        const Vec3 end{right ? 48.0 : -8.0, y, -1};
        steps.push_back(move(StepKind::feed, at, end));
        at = end;
        right = !right;
    }
    SimOptions o;
    o.resolution = 0.1;
    const SimResult r = simulate(steps, m, box({0, 0, -10}, {40, 30, 0}), {{1, flat(10)}}, o);
    CHECK(r.errors.empty());
    // The box's edges fall on cell edges: every cell is inside, the volume is exact.
    CHECK(r.removed_volume == doctest::Approx(40 * 30 * 1.0).epsilon(1e-6));
    CHECK(differing(r.field, [](double, double) { return 1.0; }, [](double, double) { return false; }) == 0);
    // The inner rows cut 6 of their 10 mm (the first 4, the last 2): 60 %, within a sample's
    // width (1/100 of the diameter) and the rows' ends.
    REQUIRE(r.tools.size() == 1);
    CHECK(std::abs(r.tools[0].max_engagement - 0.6) <= 0.02);
}

// A pocket job: a circle of radius 20 around (50, 50) less an island of radius 5, 3 mm deep.
const char* const pocket_job = R"({"name": "ring", "units": "mm", "clearance": 10,
 "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 8000, "fluteLength": 12}],
 "operations": [{"type": "pocket", "tool": 1, "retractPlane": 5, "safeDistance": 1, "endDepth": 3,
   "start": [70, 50], "path": [{"arc": {"end": [70, 50], "centre": [50, 50], "direction": "ccw"}}],
   "islands": [{"start": [55, 50], "path": [{"arc": {"end": [55, 50], "centre": [50, 50], "direction": "cw"}}]}],
   "strategy": "offset", "stepOverPercent": 40, "ramp": {"type": "helix", "angle": 3, "radius": 2},
   "feed": 600, "plungeFeed": 150}]})";

// The steps of a job posted for a machine and read back.
std::vector<Step> posted_steps(const std::string& job_json, const Machine& m, const std::string& machine_name) {
    const Job job = read_job(job_json, "test.json");
    const std::string text = test::post_job(job_json, machine_name).text;
    TraceOptions options;
    for (const auto& [n, t] : job.tools) options.compensation_radii[n] = t.diameter / 2;
    return trace_program(read_program(text, m, "p"), m, options).steps;
}

TEST_CASE("simulation: a posted pocket with an island removes area x depth, the island left standing") {
    const Machine m = load_machine("linuxcnc");
    const Job job = read_job(pocket_job, "test.json");
    const std::vector<Step> steps = posted_steps(pocket_job, m, "linuxcnc");
    SimOptions o;
    o.resolution = 0.1;
    o.operations = {{1, "operations[0]"}};
    const SimResult r = simulate(steps, m, box({20, 20, -10}, {80, 80, 0}), tool_shapes(job.tools), o);
    CHECK(r.errors.empty());
    const double exact = pi_ * (20 * 20 - 5 * 5) * 3;
    const double bound = boundary_bound(0.1, 2 * pi_ * 25, 3);
    MESSAGE("pocket: removed ", r.removed_volume, " exact ", exact, " bound ", bound);
    CHECK(std::abs(r.removed_volume - exact) <= bound);
    // The program's coordinates are rounded to 0.001 mm: cells within 0.005 of a wall may go
    // either way; every other cell is exact (no material left, none taken from the island).
    auto depth = [](double x, double y) {
        const double rho = std::hypot(x - 50, y - 50);
        return rho >= 5 && rho <= 20 ? 3.0 : 0.0;
    };
    auto near_wall = [](double x, double y) {
        const double rho = std::hypot(x - 50, y - 50);
        return std::abs(rho - 5) < 0.005 || std::abs(rho - 20) < 0.005;
    };
    CHECK(differing(r.field, depth, near_wall) == 0);
    REQUIRE(r.operations.size() == 1);
    CHECK(r.operations[0].name == "operations[0]");
    CHECK(r.operations[0].volume == doctest::Approx(r.removed_volume));
    CHECK(r.operations[0].max_engagement > 0.3);
    CHECK(r.operations[0].max_engagement <= 1.0);
    CHECK(r.stats.total_time() > 0);
}

TEST_CASE("simulation: a turned shaft removes the bar's volume of revolution beyond its profile") {
    const Machine m = load_machine("linuxcnc-lathe");
    REQUIRE(m.kind == MachineKind::lathe);
    // A D40 bar 100 long, face at Z0: face 1 mm (to X0), then turn to radius 15 for 49 mm.
    SimStock bar;
    bar.kind = SimStock::Kind::bar;
    bar.bar_diameter = 40;
    bar.bar_length = 100;
    bar.face_z = 0;
    ToolShape tip = shape(ToolForm::turning);
    std::vector<Step> steps = {move(StepKind::rapid, {22, 0, 2}, {22, 0, -1}, 1, 5),
                               move(StepKind::feed, {22, 0, -1}, {0, 0, -1}, 1, 6),
                               move(StepKind::rapid, {0, 0, -1}, {0, 0, 2}, 1, 7),
                               move(StepKind::rapid, {0, 0, 2}, {15, 0, 2}, 1, 8),
                               move(StepKind::feed, {15, 0, 2}, {15, 0, -50}, 1, 9),
                               move(StepKind::feed, {15, 0, -50}, {22, 0, -50}, 1, 10),
                               move(StepKind::rapid, {22, 0, -50}, {22, 0, 2}, 1, 11)};
    SimOptions o;
    o.resolution = 0.01;
    const SimResult r = simulate(steps, m, bar, {{1, tip}}, o);
    CHECK(r.errors.empty());
    CHECK(r.cells == 10000);
    CHECK(r.initial_volume == doctest::Approx(pi_ * 400 * 100).epsilon(1e-9));
    const double exact = pi_ * 400 * 1 + pi_ * (400 - 225) * 49;
    // Samples are exact in radius; each Z edge (the face at -1, the shoulder at -50) may take or
    // leave one sample of its ring: |V - exact| <= dz x (pi 20^2 + pi (20^2 - 15^2)).
    const double bound = 0.01 * (pi_ * 400 + pi_ * (400 - 225));
    MESSAGE("shaft: removed ", r.removed_volume, " exact ", exact, " bound ", bound);
    CHECK(std::abs(r.removed_volume - exact) <= bound);
    for (int k = 0; k < r.lathe.nz; ++k) {
        const double z = r.lathe.z(k);
        const double want = z > -1 ? 0.0 : z > -50 ? 15.0 : 20.0;
        if (std::abs(z + 1) < 0.01 || std::abs(z + 50) < 0.01) continue;
        CHECK_MESSAGE(std::abs(r.lathe.outside[k] - want) < 1e-9, "z ", z);
    }
}

TEST_CASE("simulation: a lathe's drill on the axis bores its radius above its point") {
    const Machine m = load_machine("linuxcnc-lathe");
    SimStock bar;
    bar.kind = SimStock::Kind::bar;
    bar.bar_diameter = 40;
    bar.bar_length = 100;
    ToolShape drill = shape(ToolForm::cone, 10);
    drill.tip_angle = 118;
    const double slope = 1 / std::tan(59 * pi_ / 180), hc = 5 * slope;
    std::vector<Step> steps = {move(StepKind::rapid, {0, 0, 5}, {0, 0, 2}),
                               move(StepKind::feed, {0, 0, 2}, {0, 0, -30}),
                               move(StepKind::rapid, {0, 0, -30}, {0, 0, 5})};
    SimOptions o;
    o.resolution = 0.01;
    const SimResult r = simulate(steps, m, bar, {{1, drill}}, o);
    CHECK(r.errors.empty());
    const double exact = pi_ * 25 * (30 - hc) + pi_ * 25 * hc / 3;
    // The cone's radius is exact at each sample; the midpoint rule on pi r(z)^2 over the cone
    // errs by at most dz^2/24 x its second derivative (2 pi / slope^2) per unit length, and the
    // face's edge by one sample.
    const double bound = 0.01 * pi_ * 25 + hc * 0.01 * 0.01 / 24 * 2 * pi_ / (slope * slope);
    MESSAGE("lathe drill: removed ", r.removed_volume, " exact ", exact, " bound ", bound);
    CHECK(std::abs(r.removed_volume - exact) <= bound);
}

TEST_CASE("simulation: a bar with a bore holds the ring between them") {
    const Machine m = load_machine("linuxcnc-lathe");
    SimStock tube;
    tube.kind = SimStock::Kind::bar;
    tube.bar_diameter = 40;
    tube.bar_length = 50;
    tube.face_z = 10;
    tube.bore_diameter = 10;
    SimOptions o;
    o.resolution = 0.01;
    const SimResult r = simulate({}, m, tube, {}, o);
    CHECK(r.initial_volume == doctest::Approx(pi_ * (400 - 25) * 50).epsilon(1e-9));
    CHECK(r.lathe.z0 == doctest::Approx(-40));
    tube.bore_diameter = 40;
    CHECK_THROWS_AS(simulate({}, m, tube, {}, o), SimInputError);
}

TEST_CASE("simulation: a Simulator fed as a stream names the operation begun, per tool and per operation") {
    const Machine m = load_machine("linuxcnc");
    SimOptions o;
    o.resolution = 0.1;
    Simulator sim(m, box({0, 0, -10}, {50, 50, 0}), {{1, flat(6)}, {2, flat(4)}}, o);
    sim.begin_operation("operations[0]");
    sim.step(move(StepKind::feed, {10, 10, 1}, {10, 10, -1}, 1, 0));
    sim.begin_operation("operations[1]");
    sim.step(move(StepKind::feed, {30, 30, 1}, {30, 30, -1}, 1, 0));
    sim.step(move(StepKind::feed, {30, 10, 1}, {30, 10, -2}, 2, 0));
    sim.finish({});
    const SimResult& r = sim.result();
    REQUIRE(r.tools.size() == 2);
    REQUIRE(r.operations.size() == 2);
    CHECK(r.operations[0].name == "operations[0]");
    CHECK(r.operations[1].name == "operations[1]");
    CHECK(r.operations[1].volume == doctest::Approx(r.operations[0].volume + r.tools[1].volume));
    CHECK(r.tools[0].name == "T1");
    CHECK(r.tools[1].name == "T2");
    CHECK(r.tools[0].volume == doctest::Approx(2 * r.operations[0].volume));
}

// A linuxcnc program around one move under test; `tools` the shapes.
SimResult run_program(const std::string& body, const std::map<int, ToolShape>& tools) {
    const Machine m = load_machine("linuxcnc");
    const std::string text = "(t)\nG17 G21 G90 G94\nT1 M6\nS1000 M3\nG0 X50 Y50 Z5\n" + body + "G0 Z5\nM5\nM2\n";
    const Trace trace = trace_program(read_program(text, m, "p"), m);
    SimOptions o;
    o.resolution = 0.1;
    return simulate(trace.steps, m, box({0, 0, -20}, {100, 100, 0}), tools, o);
}

TEST_CASE("simulation: a rapid through the stock is a crash at its line") {
    const SimResult r = run_program("G1 Z1 F200\nG0 Z-2\n", {{1, flat(6)}});
    REQUIRE(r.errors.size() == 1);
    CHECK(r.errors[0].line == 7);
    CHECK(r.errors[0].message.find("a rapid removes material (a crash): 2 mm deep") == 0);
    // The same depth at feed is no crash.
    CHECK(run_program("G1 Z1 F200\nG1 Z-2\n", {{1, flat(6)}}).errors.empty());
    // A rapid down to the surface, or 0.001 mm into it (the program's rounding), is none.
    CHECK(run_program("G0 Z0\n", {{1, flat(6)}}).errors.empty());
    CHECK(run_program("G0 Z-0.001\n", {{1, flat(6)}}).errors.empty());
    // A rapid sideways through the stock at Z-1.
    const SimResult side = run_program("G0 X-10\nG0 Z-1\nG0 X110\n", {{1, flat(6)}});
    REQUIRE(side.errors.size() == 1);
    CHECK(side.errors[0].line == 8);
}

TEST_CASE("simulation: a feed deeper than the tool's flute length is an error at its line") {
    ToolShape t = flat(6);
    t.flute_length = 5;
    const SimResult r = run_program("G1 Z1 F200\nG1 Z-8\n", {{1, t}});
    REQUIRE(r.errors.size() == 1);
    CHECK(r.errors[0].line == 7);
    CHECK(r.errors[0].message == "a feed cuts 8 mm below the stock's surface, deeper than tool 1's fluteLength 5 mm");
    // In two steps of 4 mm each cut is within the flutes.
    CHECK(run_program("G1 Z1 F200\nG1 Z-4\nG1 Z-8\n", {{1, t}}).errors.empty());
    CHECK(run_program("G1 Z1 F200\nG1 Z-5\n", {{1, t}}).errors.empty());
}

TEST_CASE("simulation: a tool without a shape, and stock that has no volume, are refused") {
    CHECK_THROWS_WITH_AS(run_program("G1 Z-1 F200\n", {{2, flat(6)}}), "line 5: tool 1 has no shape to simulate",
                         SimInputError);
    const Machine m = load_machine("linuxcnc");
    CHECK_THROWS_AS(simulate({}, m, box({0, 0, 0}, {10, 10, 0}), {}), SimInputError);
    CHECK_THROWS_AS(simulate({}, m, box({0, 0, -1}, {10, 10, 0}), {{1, shape(ToolForm::flat, 0)}}), SimInputError);
}

TEST_CASE("simulation: the default resolution keeps within the cell budget and says so") {
    const Machine m = load_machine("linuxcnc");
    const SimResult r = simulate({}, m, box({0, 0, -8}, {100, 50, 0}), {});
    CHECK(r.cells <= 4'000'000);
    CHECK(r.resolution == doctest::Approx(0.036));  // sqrt(5000 / 4e6) = 0.0354, up to whole microns
    CHECK(r.initial_volume == doctest::Approx(100 * 50 * 8).epsilon(1e-3));
    const std::string text = format_simulation(r);
    CHECK(text.find("height field of 2778 x 1389 cells of 0.036 mm") != std::string::npos);
}

TEST_CASE("simulation: a stock given as a closed profile holds material inside it only") {
    const Machine m = load_machine("linuxcnc");
    SimStock s;
    s.kind = SimStock::Kind::profile;
    s.profile.start = {10, 0};
    s.profile.segments = {{{10, 0}, Vec2{0, 0}, ArcDirection::ccw}};  // a circle of radius 10
    s.top = 0;
    s.bottom = -5;
    SimOptions o;
    o.resolution = 0.05;
    const SimResult r = simulate({}, m, s, {}, o);
    CHECK(std::abs(r.initial_volume - pi_ * 100 * 5) <= boundary_bound(0.05, 2 * pi_ * 10, 5));
}

// The samples, posted and read back, simulate without an error.
std::string sample_text(const std::string& name) {
    std::ifstream in(CAMGEN_SOURCE_DIR "/samples/" + name);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST_CASE("simulation: the samples simulate clean") {
    struct Case {
        const char* file;
        const char* machine;
        SimStock stock;
    };
    SimStock shaft;
    shaft.kind = SimStock::Kind::bar;
    shaft.bar_diameter = 44;  // the shaft's stock
    shaft.bar_length = 70;
    shaft.face_z = 1;
    const Case cases[] = {
        {"plate.json", "linuxcnc", box({0, 0, -8}, {100, 50, 0})},
        {"pocket.json", "linuxcnc", box({0, 0, -10}, {100, 70, 0})},
        {"face.json", "fanuc", box({0, 0, -10}, {100, 70, 1})},
        {"bores.json", "linuxcnc", box({0, 0, -20}, {110, 100, 0})},
        {"shaft.json", "linuxcnc-lathe", shaft},
    };
    for (const Case& c : cases) {
        CAPTURE(c.file);
        const std::string json = sample_text(c.file);
        const Machine m = load_machine(c.machine);
        const Job job = read_job(json, c.file);
        const SimResult r = simulate(posted_steps(json, m, c.machine), m, c.stock, tool_shapes(job.tools));
        for (const SimReport& e : r.errors) MESSAGE(c.file, " line ", e.line, ": ", e.message);
        CHECK(r.errors.empty());
        CHECK(r.removed_volume > 0);
    }
}

TEST_CASE("camgen simulate: the plate in its box is clean, a rapid into it exits 1 at its line, bad stock is usage") {
    namespace fs = std::filesystem;
    const fs::path dir = test::scratch("simulate-cli");
    const std::string job = CAMGEN_SOURCE_DIR "/samples/plate.json";
    const std::string program = (dir / "plate.ngc").string();
    REQUIRE(test::run({job, "--machine", "linuxcnc", "-o", program}).code == 0);
    test::Run ok = test::run({"simulate", program, "--machine", "linuxcnc", "--job", job, "--stock-box", "0,0,-8,100,50,0",
                              "--resolution", "0.05"});
    CHECK(ok.code == 0);
    CHECK(ok.out.find("simulation: mill, height field of 2000 x 1000 cells of 0.05 mm (2000000 cells)\n") != std::string::npos);
    CHECK(ok.out.find("stock: 40000 mm^3, removed ") != std::string::npos);
    CHECK(ok.out.find("tool T2: removed ") != std::string::npos);
    CHECK(ok.out.find("machining time: 51.4 s\n") != std::string::npos);
    CHECK(ok.out.find("simulation: no errors\n") != std::string::npos);
    // The program is the job's own: each line has its operation, the volumes add up.
    CHECK(ok.out.find("note: ") == std::string::npos);
    CHECK(ok.out.find("operation /operations/0: removed ") != std::string::npos);
    CHECK(ok.out.find("operation /operations/1: removed ") != std::string::npos);
    // The spot drill's rapid to R2 made a rapid to Z-1: a crash at its line (9 of the program),
    // the cone's point 0.986 mm deep at the nearest cell centre of the default field (0.036 mm).
    std::string text = test::read_file(program);
    const std::string z2 = "\nZ2\n";
    REQUIRE(text.find(z2) != std::string::npos);
    text.replace(text.find(z2), z2.size(), "\nZ-1\n");
    const std::string crashing = (dir / "crash.ngc").string();
    std::ofstream(crashing) << text;
    test::Run crash = test::run({"simulate", crashing, "--machine", "linuxcnc", "--job", job, "--stock-box", "0,0,-8,100,50,0"});
    CHECK(crash.code == 1);
    CHECK(crash.out.find("note: 1 line of the program differs from what the job posts: counted with the operation of the line "
                         "before\n") != std::string::npos);
    CHECK(crash.out.find("error: line 9 (/operations/0), tool 1: a rapid removes material (a crash): 0.986 mm deep") !=
          std::string::npos);
    CHECK(crash.out.find("simulation: 1 error\n") != std::string::npos);
    // The stock is required, of the machine's kind, and has a volume.
    CHECK(test::run({"simulate", program, "--machine", "linuxcnc", "--job", job}).code == 2);
    CHECK(test::run({"simulate", program, "--machine", "linuxcnc", "--job", job, "--bar", "40,60"}).code == 2);
    test::Run flat_box = test::run({"simulate", program, "--machine", "linuxcnc", "--job", job, "--stock-box", "0,0,0,100,50,0"});
    CHECK(flat_box.code == 2);
    CHECK(flat_box.err == "camgen: cannot simulate: the stock has no volume\n");
    test::Run words = test::run({"simulate", program, "--machine", "linuxcnc", "--job", job, "--stock-box", "0,0,-8,100,50"});
    CHECK(words.code == 2);
    CHECK(words.err == "camgen: --stock-box takes x0,y0,z0,x1,y1,z1 in mm, not \"0,0,-8,100,50\"\n");
}

TEST_CASE("simulation: a thread mill cutting far more than a thread's depth gets a note at its line") {
    // An external M16 milled with no boss made first: the tool helixes through solid stock at
    // full engagement (an exploratory tester's job); the same thread on a boss turned... here
    // milled first by a contour is engaged a thread's depth only.
    const Machine m = load_machine("linuxcnc");
    auto job_text = [](bool boss) {
        return fmt::format(R"({{"clearance": 10, "stock": {{"box": {{"min": [0, 0, -20], "max": [60, 60, 0]}}}},
          "tools": [{{"number": 1, "type": "end-mill", "diameter": 10, "rpm": 8000}},
                    {{"number": 3, "type": "thread-mill", "diameter": 8, "minPitch": 1, "maxPitch": 2.5, "rpm": 6000}}],
          "operations": [{}{{"type": "thread-mill", "tool": 3, "thread": "M16", "side": "external", "retractPlane": 5,
                           "safeDistance": 1, "endDepth": 10, "feed": 400, "holes": [[30, 30]]}}]}})",
                           boss ? R"({"type": "contour", "tool": 1, "side": "outside", "endDepth": 11, "stepDown": 2, "feed": 500,
                                      "profile": {"circle": {"centre": [30, 30], "diameter": 16}}}, )"
                                : "");
    };
    for (bool boss : {false, true}) {
        CAPTURE(boss);
        const std::string text = job_text(boss);
        const Job job = read_job(text, "test.json");
        SimOptions o;
        o.resolution = 0.1;
        const SimResult r = simulate(posted_steps(text, m, "linuxcnc"), m, box({0, 0, -20}, {60, 60, 0}), tool_shapes(job.tools), o);
        CHECK(r.errors.empty());
        bool noted = false;
        for (const std::string& n : r.notes) noted = noted || n.find("tool 3, a thread mill, cuts") != std::string::npos;
        CHECK(noted == !boss);
    }
}

}  // namespace test_simulation
