// A lathe's turning tool is swept as its nose circle plus the insert's two flanks
// (ToolShape::flank_lo/hi, from insertAngle and approachAngle), its body on the side its
// orientation says: a back taper within the end edge's clearance keeps the finished diameter
// behind it, one steeper than it is rubbed by the end edge; left-hand (1) and boring (3) tools
// are the right-hand outside tool (2) mirrored; and through camgen simulate, a relief the insert
// clears is as designed, the same cut by a tool without angles is a gouge.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <doctest/doctest.h>

#include "camgen/geometry/compensation.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/simulation/simulation.hpp"
#include "support.hpp"

namespace test_lathe_sweep {

namespace fs = std::filesystem;
using namespace camgen;

namespace {

constexpr double deg = 3.14159265358979323846 / 180.0;
constexpr double nose = 0.4;
constexpr double taper = 3.0;  // degrees: the back taper falls towards the chuck at this

Step move(StepKind kind, Vec2 tip_zr) {
    Step s;
    s.kind = kind;
    s.to = {tip_zr.y, 0, tip_zr.x};
    s.tool = 1;
    s.feed = kind == StepKind::feed ? 100 : 0;
    return s;
}

// The nose centre's path (Z, radius) of a right-hand cut: along radius 15 from Z5 to Z-10,
// down a back taper falling 3 degrees towards the chuck to Z-19, up to radius 25 and back out
// to Z5. Its profile: radius 15 from Z0 to Z-10, then 15 - (-10 - z) tan 3.
std::vector<Vec2> centre_path() {
    const double s = std::sin(taper * deg), c = std::cos(taper * deg), t = std::tan(taper * deg);
    auto on_taper = [&](double zc) { return Vec2{zc, 15 + (zc + nose * s + 10) * t + nose * c}; };
    return {{5, 25}, {5, 15 + nose}, {-10, 15 + nose}, on_taper(-10 + nose * s), on_taper(-19), {-19, 25}, {5, 25}};
}

// The path's steps for a tool of `orientation`, the centres mapped by `f` first (a mirror),
// each point the imaginary tip (the centre plus lathe_tip_offset).
template <class F>
std::vector<Step> steps_of(int orientation, F f) {
    std::vector<Step> out;
    const Vec2 tip = lathe_tip_offset(orientation, nose);
    const std::vector<Vec2> path = centre_path();
    Vec2 prev = f(path[0]) + tip;
    for (std::size_t i = 1; i < path.size(); ++i) {
        const Vec2 q = f(path[i]) + tip;
        Step s = move(i == 1 || i + 1 == path.size() ? StepKind::rapid : StepKind::feed, q);
        s.from = {prev.y, 0, prev.x};
        s.line = static_cast<int>(i);
        out.push_back(s);
        prev = q;
    }
    return out;
}

// A bar of `diameter` (a tube of `bore`), Z-60 to Z0, sampled every 0.01 mm.
SimResult sweep(const std::vector<Step>& steps, int orientation, double lo, double hi, double diameter = 40,
                double bore = 0) {
    SimStock bar;
    bar.kind = SimStock::Kind::bar;
    bar.bar_diameter = diameter;
    bar.bar_length = 60;
    bar.face_z = 0;
    if (bore > 0) bar.bore_diameter = bore;
    ToolShape t;
    t.form = ToolForm::turning;
    t.nose_radius = nose;
    t.orientation = orientation;
    t.flank_lo = lo, t.flank_hi = hi;
    SimOptions o;
    o.resolution = 0.01;
    return simulate(steps, load_machine("linuxcnc-lathe"), bar, {{1, t}}, o);
}

Vec2 same(Vec2 p) { return p; }

// The sample that holds Z z, its centre's Z and its outside radius.
int sample_at(const SimResult& r, double z) { return static_cast<int>(std::floor((z - r.lathe.z0) / r.lathe.dz)); }
double outside_at(const SimResult& r, double z) { return r.lathe.outside[static_cast<std::size_t>(sample_at(r, z))]; }

}  // namespace

TEST_CASE("lathe sweep: a back taper within the end edge's clearance keeps the diameter behind it; steeper, the end edge rubs it") {
    // 80-degree insert in a 95-degree holder: flanks at 5 and 85 degrees; it clears the 3-degree taper.
    const SimResult c = sweep(steps_of(2, same), 2, 5, 85);
    CHECK(c.errors.empty());
    double worst = 0;
    for (double z = -9.5; z <= -0.5; z += 0.25) worst = std::max(worst, std::abs(outside_at(c, z) - 15));
    MESSAGE("C insert: worst departure from radius 15 over Z-9.5..-0.5: " << worst);
    CHECK(worst < 1e-9);
    // Along the taper: the profile (the chord round the corner at Z-10 dips below it by n (1 - cos 1.5)).
    for (double z = -18; z <= -11; z += 0.5)
        CHECK(std::abs(outside_at(c, z) - (15 + (z + 10) * std::tan(taper * deg))) < 0.001);
    // An insert whose end edge clears 2 degrees: from the taper's lowest centre (-19) the edge
    // rises 2 degrees towards +Z and cuts the radius 15 behind the taper to that line.
    const SimResult r = sweep(steps_of(2, same), 2, 2, 85);
    const Vec2 e = centre_path()[4];
    const double s2 = std::sin(2 * deg), c2 = std::cos(2 * deg), t2 = std::tan(2 * deg);
    int rubbed = 0;
    for (double z = -9.5; z <= -0.5; z += 0.5) {
        const double zc = r.lathe.z(sample_at(r, z));
        const double flank = e.y - nose * c2 + (zc - e.x - nose * s2) * t2;
        CAPTURE(z);
        CHECK(outside_at(r, z) == doctest::Approx(std::min(15.0, flank)).epsilon(1e-9));
        rubbed += flank < 15 - 0.01;
    }
    CHECK(rubbed >= 8);  // Z-9.5 to Z-6: up to 0.14 mm into the radius 15
    // Without angles (the end edge along Z): the taper's lowest radius all the way to the face.
    const SimResult q = sweep(steps_of(2, same), 2, 0, 90);
    for (double z = -9.5; z <= -0.5; z += 0.5) CHECK(outside_at(q, z) == doctest::Approx(e.y - nose).epsilon(1e-9));
    // The feed down the taper made a rapid: a crash.
    std::vector<Step> rapid = steps_of(2, same);
    rapid[3].kind = StepKind::rapid;
    CHECK(sweep(rapid, 2, 5, 85).errors.size() == 1);
    CHECK(c.removed_volume < q.removed_volume);
}

TEST_CASE("lathe sweep: orientation 1 cuts the mirror image of orientation 2; orientation 3, in a tube, of orientation 1") {
    // The bar is Z-60..0; mirrored about Z-30 a sample k is sample nz - 1 - k.
    auto mirror_z = [](Vec2 p) { return Vec2{-60 - p.x, p.y}; };
    for (const auto& [lo, hi] : {std::pair{5.0, 85.0}, {0.0, 90.0}, {52.0, 87.0}}) {
        CAPTURE(lo);
        const SimResult right = sweep(steps_of(2, same), 2, lo, hi);
        const SimResult left = sweep(steps_of(1, mirror_z), 1, lo, hi);
        const int nz = right.lathe.nz;
        REQUIRE(left.lathe.nz == nz);
        int differ = 0;
        for (int k = 0; k < nz; ++k)
            differ += std::abs(right.lathe.outside[static_cast<std::size_t>(k)] -
                               left.lathe.outside[static_cast<std::size_t>(nz - 1 - k)]) > 1e-9;
        CHECK(differ == 0);
        CHECK(left.removed_volume == doctest::Approx(right.removed_volume).epsilon(1e-9));
        // The left-hand tool's body lies towards -Z: the radius 15 it keeps beyond Z-50 stays
        // (a body towards +Z, as every tool had before, cut it to the taper's bottom or lower).
        if (lo > taper)
            for (double z = -59.5; z <= -50.5; z += 0.5) CHECK(outside_at(left, z) == doctest::Approx(15).epsilon(1e-9));
        CHECK(left.errors.empty());

        // Orientation 3 in a tube (D60, bore D20): the left-hand cut mirrored in Z and in the
        // radius about 20 (the outside at 25 is the bore at 15), against the orientation-1 cut
        // of the same tube 10 mm further out.
        auto out = [](Vec2 p) { return Vec2{p.x, p.y + 10}; };
        auto in = [&](Vec2 p) { return Vec2{p.x, 40 - (p.y + 10)}; };
        const SimResult one = sweep(steps_of(1, [&](Vec2 p) { return out(mirror_z(p)); }), 1, lo, hi, 60, 20);
        const SimResult three = sweep(steps_of(3, [&](Vec2 p) { return in(p); }), 3, lo, hi, 60, 20);
        int mirrored = 0, cut = 0;
        for (int k = 0; k < nz; ++k) {
            const double o = one.lathe.outside[static_cast<std::size_t>(k)];
            const double b = three.lathe.bore[static_cast<std::size_t>(nz - 1 - k)];
            mirrored += std::abs((40 - o) - b) <= 1e-9;
            cut += b > 10 + 1e-9;
        }
        CHECK(mirrored == nz);
        CHECK(cut > nz / 4);
        CHECK(three.errors.empty());
    }
}

TEST_CASE("camgen simulate: a relief within the insert's clearance is as designed; a tool without insert angles gouges it") {
    // D30 to Z-10, a relief falling 4.3 degrees towards the chuck to D29.7 (an 80-degree insert in
    // a 95-degree holder clears 5), D34 from Z-17: roughed and finished by the same tool. Before
    // the flanks were swept, the end edge was taken along Z: 0.15 mm into the D30 behind the relief.
    const fs::path dir = test::scratch("lathe-sweep");
    const std::string path = R"("path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -10]}, {"line": [29.7, -12]},
            {"line": [29.7, -15]}, {"line": [34, -17]}, {"line": [34, -25]}])";
    auto job_text = [&](const std::string& angles) {
        return R"({"clearance": 20, "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 0}},
 "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4)" + angles + R"(, "rpm": 800}],
 "operations": [
  {"type": "turn-rough", "tool": 1, "feedMode": "per-revolution", "feed": 0.25, "depthOfCut": 1.5, "allowanceX": 0.4,
   "allowanceZ": 0.1, "start": [24, 0], )" + path + R"(},
  {"type": "turn-profile", "tool": 1, "xValues": "diameter", "feedMode": "per-revolution", "feed": 0.1,
   "start": [24, 0], "retractX": 44, )" + path + "}]}";
    };
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        for (const bool angles : {true, false}) {
            CAPTURE(angles);
            const std::string job = (dir / (angles ? "relief.json" : "relief-noangles.json")).string();
            std::ofstream(job) << job_text(angles ? R"(, "insertAngle": 80, "approachAngle": 95)" : "");
            const std::string program = (dir / (machine + (angles ? ".nc" : "-noangles.nc"))).string();
            REQUIRE(test::run({job, "--machine", machine, "-q", "-o", program}).code == 0);
            const test::Run r = test::run({"simulate", program, "--machine", machine, "--job", job});
            if (angles) {
                CHECK_MESSAGE(r.code == 0, r.out << r.err);
                CHECK_MESSAGE(r.out.find("the part is as designed") != std::string::npos, r.out);
                CHECK_MESSAGE(r.out.find("warning:") == std::string::npos, r.out);
            } else {
                CHECK(r.code == 1);
                CHECK_MESSAGE(r.out.find("error: gouge: /operations/1 (the part inside the profile): material removed 0.15 mm "
                                         "inside the designed radius 15") != std::string::npos,
                              r.out);
            }
        }
    }
}

}  // namespace test_lathe_sweep
