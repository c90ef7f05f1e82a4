// The lathe simulation of face grooves (issue 30): the turned part holds rings of air inside the
// material (LatheGap), so that a face blade sweeping a ring inside the end face removes it; the
// design check designs a face groove's ring (LatheRingDesign). Many random face grooves (with a
// bore and without, chamfers, pecks, rings that reach the bar's outside or its bore) posted on
// the three lathes simulate as designed, remove the ring's volume, and write no "not swept" or
// "not checked"; a groove 0.2 mm too deep, too wide or too shallow is caught at its path; the
// bushing sample simulates as designed.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <string>

#include <fmt/format.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/simulation/simulation.hpp"
#include "support.hpp"

namespace test_face_groove_sim {

using namespace camgen;

namespace {

struct FaceGroove {
    std::string text;
    double lo = 0, hi = 0, depth = 0, c = 0;  // radii, mm
    bool inside = true;                       // the ring (with its chamfers) lies inside the material
};

// A bar of D40 (a bore of D16 or none), 60 long, its face at Z0; a random face groove in it.
FaceGroove random_face_groove(std::mt19937& rng, int n) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto mm = [](double v) { return std::round(v * 1000) / 1000; };
    FaceGroove g;
    const bool bore = n % 2 == 0;
    const double w = mm(1.5 + 2.0 * u(rng));
    const double width = u(rng) < 0.3 ? w : mm(w + 4.0 * u(rng));
    const double depth = mm(0.5 + 5.0 * u(rng));
    g.depth = depth;
    if (u(rng) < 0.6) g.c = mm(std::min(depth * 0.9, 0.1 + 0.8 * u(rng)));
    // Most rings inside the face; some reach the bar's outside, some (with a bore) the bore.
    const int kind = n % 7 == 3 ? 1 : (n % 7 == 5 && bore) ? 2 : 0;
    if (kind == 1) {
        g.c = 0;
        g.hi = 20, g.lo = g.hi - width;
    } else if (kind == 2) {
        g.lo = 8, g.hi = g.lo + width;
    } else {
        g.lo = mm(9.5 + 3.0 * u(rng));
        g.hi = g.lo + width;
        if (g.hi + g.c > 19.9) g.c = 0;
    }
    g.inside = kind == 0;
    const double approach = mm(0.3 + 1.2 * u(rng));
    std::string extra;
    if (u(rng) < 0.6) extra += fmt::format(R"(, "peckDepth": {:.3f})", 0.3 + 2.0 * u(rng));
    if (extra.find("peck") != std::string::npos && u(rng) < 0.5) extra += R"(, "fullRetract": true)";
    if (width > w && u(rng) < 0.5) extra += fmt::format(R"(, "stepover": {:.3f})", w * (0.3 + 0.7 * u(rng)));
    if (u(rng) < 0.3) extra += R"(, "dwell": 0.2)";
    if (u(rng) < 0.3) extra += R"(, "finishAllowance": 0)";
    if (g.c > 0) extra += fmt::format(R"(, "chamfer": {:.3f})", g.c);
    // Every third bar is faced first, from Z1 to Z0.
    const bool faced = n % 3 == 1;
    g.text = fmt::format(
        R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": {}{}}}}},
  "tools": [{{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 600, "orientation": 7}},
            {{"number": 2, "type": "turning-tool", "noseRadius": 0.4, "orientation": 2, "rpm": 900}}],
  "operations": [{}{{"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": {:.3f}, "outerX": {:.3f},
                   "depth": {:.3f}, "approachDistance": {:.3f}{}}}]}})",
        faced ? 1 : 0, bore ? R"(, "boreDiameter": 16)" : "", w,
        faced ? R"({"type": "turn-face", "tool": 2, "z": 0, "stepdown": 0.5, "feed": 60}, )" : "", 2 * g.lo, 2 * g.hi, depth,
        approach, extra);
    return g;
}

// The removed volume camgen simulate prints for the face groove (the last operation).
double removed_by_groove(const std::string& out) {
    const std::regex line("operation /operations/[0-9]+: removed ([0-9.]+) mm\\^3");
    double last = -1;
    for (auto it = std::sregex_iterator(out.begin(), out.end(), line); it != std::sregex_iterator(); ++it)
        last = std::stod((*it)[1]);
    return last;
}

}  // namespace

TEST_CASE("face groove simulation: random face grooves on the three lathes remove their ring and simulate as designed") {
    std::mt19937 rng(3030);
    const std::filesystem::path dir = test::scratch("face-groove-sim");
    int k = 0;
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        for (int n = 0; n < 14; ++n, ++k) {
            const FaceGroove g = random_face_groove(rng, n);
            INFO(machine << ": " << g.text);
            const std::string job = (dir / fmt::format("f{}.json", k)).string();
            std::ofstream(job) << g.text;
            const std::string nc = (dir / fmt::format("f{}.nc", k)).string();
            const test::Run posted = test::run({job, "--machine", machine, "-q", "-o", nc});
            REQUIRE_MESSAGE(posted.code == 0, posted.err);
            const test::Run r = test::run({"simulate", nc, "--machine", machine, "--job", job});
            CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
            CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
            CHECK_MESSAGE(r.out.find("1 face groove,") != std::string::npos, r.out);
            CHECK_MESSAGE(r.out.find("not swept") == std::string::npos, r.out);
            CHECK_MESSAGE(r.out.find("not checked") == std::string::npos, r.out);
            CHECK_MESSAGE(r.out.find("crash") == std::string::npos, r.out);
            if (g.inside) {
                // The ring and its two chamfers' triangles (centroids a third of the chamfer out).
                const double ring = pi * (g.hi * g.hi - g.lo * g.lo) * g.depth;
                const double chamfers = pi * g.c * g.c * ((g.lo - g.c / 3) + (g.hi + g.c / 3));
                const double removed = removed_by_groove(r.out);
                CHECK_MESSAGE(std::abs(removed - (ring + chamfers)) <= 0.002 * (ring + chamfers) + 0.05,
                              r.out << "\nexpected " << ring + chamfers);
            }
        }
    }
}

TEST_CASE("face groove simulation: a face groove 0.2 mm too deep, too wide or too shallow is caught at its path") {
    const std::filesystem::path dir = test::scratch("face-groove-wrong");
    auto write = [&](const std::string& name, const std::string& keys, bool bore) {
        const std::string path = (dir / (name + ".json")).string();
        std::ofstream(path) << fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0{}}}}},
  "tools": [{{"number": 1, "type": "grooving-tool", "width": 3, "rpm": 600, "orientation": 7}}],
  "operations": [{{"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0{}}}]}})",
            bore ? R"(, "boreDiameter": 16)" : "", keys);
        return path;
    };
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        for (const bool bore : {true, false}) {
            const std::string base = R"(, "peckDepth": 0.8, "chamfer": 0.3)";
            const std::string designed = write("designed", R"(, "innerX": 24, "outerX": 32, "bottomZ": -3)" + base, bore);
            struct Wrong {
                std::string keys, expect;
                int code;
            };
            for (const Wrong& w : {Wrong{R"(, "innerX": 24, "outerX": 32, "bottomZ": -3.2)", "error: gouge: /operations/0 \\(the part "
                                                                                          "below the face groove\\): material removed "
                                                                                          "0\\.(19[5-9]|2)",
                                         1},
                                   Wrong{R"(, "innerX": 24, "outerX": 32.4, "bottomZ": -3)", "error: gouge: /operations/0 \\(the part "
                                                                                           "around the face groove\\): material "
                                                                                           "removed 0\\.(19[5-9]|2)",
                                         1},
                                   Wrong{R"(, "innerX": 23.6, "outerX": 32, "bottomZ": -3)", "error: gouge: /operations/0 \\(the part "
                                                                                           "around the face groove\\): material "
                                                                                           "removed 0\\.(19[5-9]|2)",
                                         1},
                                   Wrong{R"(, "innerX": 24, "outerX": 32, "bottomZ": -2.8)", "warning: /operations/0 \\(the face "
                                                                                           "groove\\): material left",
                                         0}}) {
                const std::string wrong = write("wrong", w.keys + base, bore);
                const std::string nc = (dir / "wrong.nc").string();
                REQUIRE(test::run({wrong, "--machine", machine, "-q", "-o", nc}).code == 0);
                const test::Run r = test::run({"simulate", nc, "--machine", machine, "--job", designed});
                INFO(machine << w.keys << (bore ? " bore" : ""));
                CHECK_MESSAGE(r.code == w.code, std::string(r.out + r.err));
                CHECK_MESSAGE(std::regex_search(r.out, std::regex(w.expect)), r.out);
                CHECK_MESSAGE(r.out.find("  the part is as designed") == std::string::npos, r.out);
            }
            // The right one is as designed.
            const std::string nc = (dir / "right.nc").string();
            REQUIRE(test::run({designed, "--machine", machine, "-q", "-o", nc}).code == 0);
            const test::Run r = test::run({"simulate", nc, "--machine", machine, "--job", designed});
            CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
            CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
        }
    }
}

TEST_CASE("face groove simulation: a ring of air inside the material is held, widened, merged and opened to the outside") {
    // Steps of a face blade 2 wide straight into the face of a bar of radius 20 (bore radius 5).
    Machine m = load_machine("linuxcnc-lathe");
    SimStock bar;
    bar.kind = SimStock::Kind::bar;
    bar.bar_diameter = 40, bar.bar_length = 10, bar.face_z = 0, bar.bore_diameter = 10;
    ToolShape blade;
    blade.form = ToolForm::blade, blade.diameter = 2, blade.orientation = 7;
    SimOptions options;
    options.resolution = 0.01;
    Simulator sim(m, bar, {{1, blade}}, options);
    int line = 0;
    auto plunge = [&](double x, double z) {
        Step s;
        s.kind = StepKind::feed, s.tool = 1, s.line = ++line, s.from_known = true;
        s.from = {x, 0, 1}, s.to = {x, 0, z};
        sim.step(s);
    };
    plunge(10, -2);  // a ring from 10 to 12, 2 deep
    const LatheProfile& p = sim.result().lathe;
    const int top = p.nz - 1;  // the sample just below the face
    REQUIRE(p.gaps_at(top) != nullptr);
    CHECK(p.gaps_at(top)->size() == 1);
    CHECK((*p.gaps_at(top))[0].lo == doctest::Approx(10));
    CHECK((*p.gaps_at(top))[0].hi == doctest::Approx(12));
    CHECK(p.outside[static_cast<std::size_t>(top)] == 20);
    CHECK(p.bore[static_cast<std::size_t>(top)] == 5);
    CHECK(sim.result().removed_volume == doctest::Approx(pi * (144 - 100) * 2).epsilon(1e-9));
    plunge(14, -1);  // a second ring, apart
    CHECK(p.gaps_at(top)->size() == 2);
    plunge(12, -1);  // touches both: one ring 10 to 16 at the top
    REQUIRE(p.gaps_at(top)->size() == 1);
    CHECK((*p.gaps_at(top))[0].hi == doctest::Approx(16));
    CHECK(sim.result().removed_volume == doctest::Approx(pi * (144 - 100) * 2 + pi * (256 - 144) * 1).epsilon(1e-9));
    plunge(16.5, -0.5);  // a ring 16.5 to 18.5 at the top
    plunge(6, -0.5);     // and one 6 to 8
    REQUIRE(p.gaps_at(top)->size() == 3);
    plunge(18, -0.5);  // reaches the outside and opens the ring beside it: the outside falls to 16.5
    CHECK(p.outside[static_cast<std::size_t>(top)] == doctest::Approx(16.5));
    CHECK(p.outside_lines[static_cast<std::size_t>(top)] == line);
    plunge(4.5, -0.5);  // reaches the bore and opens the ring beside it: the bore rises to 8
    CHECK(p.bore[static_cast<std::size_t>(top)] == doctest::Approx(8));
    REQUIRE(p.gaps_at(top)->size() == 1);
    CHECK((*p.gaps_at(top))[0].lo == doctest::Approx(10));
    CHECK(lathe_material_within(p.outside[static_cast<std::size_t>(top)], p.bore[static_cast<std::size_t>(top)], p.gaps_at(top),
                                0, 100) == doctest::Approx(2 + 0.5));
    CHECK(lathe_material_within(p.outside[static_cast<std::size_t>(top)], p.bore[static_cast<std::size_t>(top)], p.gaps_at(top),
                                0, 100, true) == doctest::Approx(2));
    // Below the rings the bar is as it was.
    CHECK(p.gaps_at(0) == nullptr);
    CHECK(p.outside[0] == 20);
    // The volume left is the material's area summed over the samples.
    double left = 0;
    for (int k = 0; k < p.nz; ++k)
        left += lathe_material_area(p.outside[static_cast<std::size_t>(k)], p.bore[static_cast<std::size_t>(k)], p.gaps_at(k)) * p.dz;
    CHECK(sim.result().initial_volume - sim.result().removed_volume == doctest::Approx(left).epsilon(1e-9));
}

TEST_CASE("face groove simulation: a rapid of a face blade into the face is a crash; one down its own ring is not") {
    Machine m = load_machine("linuxcnc-lathe");
    SimStock bar;
    bar.kind = SimStock::Kind::bar;
    bar.bar_diameter = 40, bar.bar_length = 10, bar.face_z = 0;
    ToolShape blade;
    blade.form = ToolForm::blade, blade.diameter = 2, blade.orientation = 7;
    SimOptions options;
    options.resolution = 0.01;
    Simulator sim(m, bar, {{1, blade}}, options);
    auto move = [&](StepKind kind, double x, double z0, double z1, int line) {
        Step s;
        s.kind = kind, s.tool = 1, s.line = line, s.from_known = true;
        s.from = {x, 0, z0}, s.to = {x, 0, z1};
        sim.step(s);
    };
    move(StepKind::feed, 10, 1, -2, 1);    // the ring 10 to 12, 2 deep
    move(StepKind::rapid, 10, 1, -1.5, 2);  // down it again: air
    CHECK(sim.result().errors.empty());
    move(StepKind::rapid, 10.5, 1, -1, 3);  // half a blade beside it, into the face
    REQUIRE(sim.result().errors.size() == 1);
    CHECK(sim.result().errors[0].line == 3);
    CHECK(sim.result().errors[0].message.find("a rapid removes material (a crash): 0.5 mm deep") != std::string::npos);
}

TEST_CASE("face groove simulation: the bushing sample simulates as designed, its face groove swept and checked") {
    const std::filesystem::path dir = test::scratch("face-groove-bushing");
    const std::string job = std::string(CAMGEN_SOURCE_DIR) + "/samples/bushing.json";
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        INFO(machine);
        const std::string nc = (dir / "bushing.nc").string();
        REQUIRE(test::run({job, "--machine", machine, "-q", "-o", nc}).code == 0);
        const test::Run r = test::run({"simulate", nc, "--machine", machine, "--job", job});
        CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
        CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
        CHECK_MESSAGE(r.out.find("not swept") == std::string::npos, r.out);
        CHECK_MESSAGE(r.out.find("not checked") == std::string::npos, r.out);
        // The ring D28 to D36, 3 deep, and its 0.3 mm chamfers.
        std::smatch m;
        REQUIRE(std::regex_search(r.out, m, std::regex("operation /operations/3: removed ([0-9.]+) mm\\^3")));
        const double expected = pi * (18 * 18 - 14 * 14) * 3 + pi * 0.09 * ((14 - 0.1) + (18 + 0.1));
        CHECK(std::stod(m[1]) == doctest::Approx(expected).epsilon(0.002));
    }
}

}  // namespace test_face_groove_sim
