// turn-groove's internal and face grooves (issue 30, "side"): the keys of another side and the
// tools that do not fit refused at their paths; many random internal and face grooves whose
// moves keep the blade inside the groove and in air (inside the bore, off its wall; above the
// face), with nothing beyond the groove's walls and bottom; the lathe simulation of random
// internal grooves on the three lathes says "as designed", a groove 0.2 mm too deep or too wide
// is a gouge; Fanuc T's G75 carries a plain internal groove (X rising) and reads back as
// camgen's moves; a face groove G74 cannot carry is longhand: a note under auto, an error naming
// the path under canned (the plain ones: test_fanuc_g74_groove.cpp). (A face groove's simulation
// and design check: test_face_groove_sim.cpp.)
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "support.hpp"

namespace test_groove_sides {

using namespace camgen;

namespace {

std::string refusal(const std::string& text) {
    try {
        (void)read_job(text, "groove.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A bar of D40 with a bore of D16, 60 long, its face at Z0.
std::string bushing_job(const std::string& tool, const std::string& op) {
    return fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0, "boreDiameter": 16}}}},
  "tools": [{}], "operations": [{}]}})",
                       tool, op);
}

// The programmed point's moves (X radius, Z), the cycle's moves expanded.
struct SideMove {
    Vec3 from, to;
    bool rapid = false;
};
std::vector<SideMove> side_moves(const Job& job) {
    std::vector<SideMove> out;
    std::optional<Vec3> at;
    std::vector<Event> events;
    for (const Event& e : expand_job(job)) {
        if (const auto* c = std::get_if<GrooveCycle>(&e)) {
            const std::vector<Event> m = groove_cycle_moves(*c);
            events.insert(events.end(), m.begin(), m.end());
        } else {
            events.push_back(e);
        }
    }
    for (const Event& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            if (at) out.push_back({*at, r->to, true});
            at = r->to;
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            REQUIRE(at);
            out.push_back({*at, l->to, false});
            at = l->to;
        }
    }
    return out;
}

struct RandomGroove {
    std::string text;
    double w = 0, lo = 0, hi = 0, surface = 0, bottom = 0, c = 0, approach = 0;
    bool right = false;
};

// A random internal groove in the D16 bore: between Z -3 and -50, 0.5 to 5 deep.
RandomGroove random_internal(std::mt19937& rng, const std::string& output = "auto", bool plain = false) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    RandomGroove g;
    g.w = std::round((1.5 + 2.5 * u(rng)) * 1000) / 1000;
    const double width = u(rng) < 0.3 ? g.w : std::round((g.w + 8.0 * u(rng)) * 1000) / 1000;
    const double depth = std::round((0.5 + 4.5 * u(rng)) * 1000) / 1000;
    g.hi = std::round((-3.0 - 35.0 * u(rng)) * 1000) / 1000;
    g.lo = g.hi - width;
    g.right = u(rng) < 0.5;
    g.approach = std::round((0.3 + 1.5 * u(rng)) * 1000) / 1000;
    g.surface = 8, g.bottom = 8 + depth;
    std::string extra = fmt::format(R"(, "output": "{}")", output);
    double peck = 0.0;
    if (u(rng) < 0.6) extra += fmt::format(R"(, "peckDepth": {:.3f})", peck = 0.3 + 2.0 * u(rng));
    // (a back-off at most the peck: the control refuses a longer one)
    if (extra.find("peck") != std::string::npos && u(rng) < 0.5)
        extra += fmt::format(R"(, "peckRetract": {:.3f})", std::min(0.1 + 0.3 * u(rng), std::floor(peck * 1000) / 1000));
    if (width > g.w && u(rng) < 0.5) extra += fmt::format(R"(, "stepover": {:.3f})", g.w * (0.3 + 0.7 * u(rng)));
    if (plain) {
        extra += R"(, "finishAllowance": 0)";
    } else {
        if (u(rng) < 0.5) g.c = std::round(std::min(depth * 0.9, 0.2 + 1.0 * u(rng)) * 1000) / 1000;
        extra += fmt::format(R"(, "chamfer": {:.3f})", g.c);
        if (u(rng) < 0.3) extra += R"(, "dwell": 0.3)";
        if (extra.find("peckD") != std::string::npos && u(rng) < 0.5) extra += R"(, "fullRetract": true)";
    }
    g.text = bushing_job(
        fmt::format(R"({{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 600, "orientation": {}}})", g.w,
                    g.right ? 4 : 3),
        fmt::format(R"({{"type": "turn-groove", "side": "internal", "tool": 1, "feed": 30, "z": {:.3f}, "width": {:.3f},
                         "depth": {:.3f}, "approachDistance": {:.3f}{}}})",
                    g.hi, width, depth, g.approach, extra));
    return g;
}

// A random face groove in the end face at Z0, a ring between X 20 and X 36 (radius 10 to 18).
RandomGroove random_face(std::mt19937& rng, const std::string& output = "auto") {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    RandomGroove g;
    g.w = std::round((1.5 + 2.0 * u(rng)) * 1000) / 1000;
    const double width = u(rng) < 0.3 ? g.w : std::round((g.w + 3.0 * u(rng)) * 1000) / 1000;
    g.lo = std::round((10.5 + 2.0 * u(rng)) * 1000) / 1000;  // inner radius
    g.hi = g.lo + width;
    const double depth = std::round((0.5 + 6.0 * u(rng)) * 1000) / 1000;
    g.approach = std::round((0.3 + 1.5 * u(rng)) * 1000) / 1000;
    g.surface = 0, g.bottom = -depth;
    std::string extra = fmt::format(R"(, "output": "{}")", output);
    if (u(rng) < 0.6) extra += fmt::format(R"(, "peckDepth": {:.3f})", 0.3 + 2.0 * u(rng));
    if (extra.find("peck") != std::string::npos && u(rng) < 0.5) extra += R"(, "fullRetract": true)";
    if (width > g.w && u(rng) < 0.5) extra += fmt::format(R"(, "stepover": {:.3f})", g.w * (0.3 + 0.7 * u(rng)));
    if (u(rng) < 0.5) g.c = std::round(std::min(depth * 0.9, 0.2 + 0.8 * u(rng)) * 1000) / 1000;
    extra += fmt::format(R"(, "chamfer": {:.3f})", g.c);
    if (u(rng) < 0.3) extra += R"(, "dwell": 0.3)";
    g.text = bushing_job(
        fmt::format(R"({{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 600, "orientation": 7}})", g.w),
        fmt::format(R"({{"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": {:.3f}, "outerX": {:.3f},
                         "depth": {:.3f}, "approachDistance": {:.3f}{}}})",
                    2 * g.lo, 2 * g.hi, depth, g.approach, extra));
    return g;
}

test::Posted posted(const std::string& text, const Machine& m) { return test::post_noted(text, m, "g.json"); }

}  // namespace

TEST_CASE("turn-groove sides: keys of another side and tools that do not fit are refused at their paths") {
    const std::string inner = R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 600, "orientation": 3})";
    const std::string outer = R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 600})";
    const std::string facer = R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 600, "orientation": 7})";
    auto internal = [&](const std::string& tool, const std::string& keys) {
        return refusal(bushing_job(tool, R"({"type": "turn-groove", "side": "internal", "tool": 1, "feed": 30, "z": -10)" + keys + "}"));
    };
    auto face = [&](const std::string& tool, const std::string& keys) {
        return refusal(bushing_job(tool, R"({"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0)" + keys + "}"));
    };
    CHECK(internal(inner, R"(, "width": 4, "depth": 2)") == "");
    CHECK(face(facer, R"(, "innerX": 22, "outerX": 30, "depth": 2)") == "");
    // The blade must cut towards +X in a bore, its edge face -Z on a face.
    CHECK(internal(outer, R"(, "width": 4, "depth": 2)").find("/operations/0/tool: an internal turn-groove needs a grooving-tool "
                                                              "whose blade cuts towards +X") != std::string::npos);
    CHECK(internal(facer, R"(, "width": 4, "depth": 2)").find("tool 1 has 7") != std::string::npos);
    CHECK(face(outer, R"(, "innerX": 22, "outerX": 30, "depth": 2)").find("/operations/0/tool: a face turn-groove needs a "
                                                                          "grooving-tool whose blade's edge faces -Z") !=
          std::string::npos);
    CHECK(refusal(bushing_job(inner, R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 4, "depth": 2})"))
              .find("/operations/0/tool: tool 1 has orientation 3") != std::string::npos);
    // The blade must fit the groove.
    CHECK(internal(inner, R"(, "width": 2.5, "depth": 2)").find("/operations/0/width: the groove's width 2.500 mm is narrower "
                                                                "than tool 1's width 3.000 mm") != std::string::npos);
    CHECK(face(facer, R"(, "innerX": 22, "outerX": 26, "depth": 2)").find("/operations/0/outerX: the groove is 2.000 mm wide (radial, "
                                                                          "outerX - innerX), narrower than tool 1's width 3.000 mm") !=
          std::string::npos);
    // Keys of another side.
    CHECK(face(facer, R"(, "innerX": 22, "outerX": 30, "depth": 2, "width": 4)").find("/operations/0/width: a face groove has no "
                                                                                      "width") != std::string::npos);
    CHECK(face(facer, R"(, "innerX": 22, "outerX": 30, "bottomX": 4)").find("/operations/0/bottomX: a face groove has no "
                                                                            "bottomX") != std::string::npos);
    CHECK(face(facer, R"(, "innerX": 22, "depth": 2)").find("/operations/0/outerX: give a face groove's innerX and outerX") !=
          std::string::npos);
    CHECK(internal(inner, R"(, "width": 4, "depth": 2, "innerX": 3)").find("/operations/0/innerX: an internal groove has "
                                                                           "no innerX") != std::string::npos);
    // Internal: the bottom outward of the bore, inside the bar; the blade off the axis.
    CHECK(internal(inner, R"(, "width": 4, "bottomX": 14)").find("/operations/0/bottomX: bottomX 14.000 mm is not beyond startX 16.000 mm") !=
          std::string::npos);
    CHECK(internal(inner, R"(, "width": 4, "depth": 12)").find("/operations/0/depth: the groove's bottom X 40.000 mm reaches "
                                                               "the bar's outside") != std::string::npos);
    CHECK(internal(inner, R"(, "width": 4, "depth": 2, "startX": 12)").find("/operations/0/startX: startX 12.000 mm is inside the "
                                                                            "bar's bore") != std::string::npos);
    CHECK(internal(inner, R"(, "width": 4, "depth": 2, "approachDistance": 8)")
              .find("/operations/0/approachDistance: approachDistance 8.000 mm from the bore's X 16.000 mm reaches the "
                    "spindle axis") !=
          std::string::npos);
    // Face: within the bar's face, below the clearance.
    CHECK(face(facer, R"(, "innerX": 22, "outerX": 42, "depth": 2)").find("/operations/0/outerX: outerX 42.000 mm is beyond the "
                                                                          "bar's X 40.000 mm") != std::string::npos);
    CHECK(face(facer, R"(, "innerX": 22, "outerX": 30, "bottomZ": 1)").find("/operations/0/bottomZ: bottomZ 1.000 mm is not below z 0.000 mm") !=
          std::string::npos);
    CHECK(face(facer, R"(, "innerX": 22, "outerX": 30, "depth": 2, "chamfer": 12)").find("/operations/0/chamfer") !=
          std::string::npos);
    // Below the bar's face its blade comes down through the bar (check_blade_material, before
    // the check that its moves along X at z + approachDistance lie beyond the face).
    const std::string below = refusal(bushing_job(facer, R"({"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": -3,
                                        "innerX": 22, "outerX": 30, "depth": 2})"));
    CHECK_MESSAGE(below.find("/operations/0/z: the blade's rapid from X ") != std::string::npos, below);
    CHECK_MESSAGE(below.find("runs through the bar's solid between Z -2.000 mm and Z 0.000 mm") != std::string::npos, below);
    // A face groove's inner chamfer is entered approachDistance inside its start: not past the axis.
    const std::string near_axis = R"({"name": "t", "units": "mm", "clearance": 20, "stock": {"bar": {"diameter": 40, "length": 40, "faceZ": 0}},
 "tools": [{"number": 1, "type": "grooving-tool", "width": 3, "rpm": 600, "orientation": 7}],
 "operations": [{"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": 2, "outerX": 12, "depth": 2,
                 "chamfer": 0.5 APPROACH}]})";
    auto with_approach = [&](const std::string& a) {
        std::string t = near_axis;
        return t.replace(t.find(" APPROACH"), 9, a);
    };
    CHECK(refusal(with_approach("")).find("/operations/0/approachDistance: the inner chamfer (at X 2.000 mm, chamfer 0.500 mm) "
                                          "is entered from approachDistance 1.000 mm inside it, past the spindle axis") !=
          std::string::npos);
    CHECK(refusal(with_approach(R"(, "approachDistance": 0.5)")) == "");
    // An external groove with an internal or face tool: the refusal names the side.
    CHECK(refusal(bushing_job(inner, R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 4, "depth": 2})"))
              .find("(3 and 4 are an internal groove's: \"side\": \"internal\")") != std::string::npos);
}

TEST_CASE("turn-groove sides: random internal and face grooves keep the blade in air and within the groove") {
    std::mt19937 rng(3130);
    for (int n = 0; n < 150; ++n) {
        const bool face = n % 2 == 1;
        const RandomGroove g = face ? random_face(rng) : random_internal(rng);
        INFO(g.text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(g.text, "g.json"));
        const std::vector<SideMove> moves = side_moves(job);
        REQUIRE(!moves.empty());
        const double eps = 1e-6;
        // In the groove's depth coordinate d (falling into the material: -radius inside a bore,
        // Z on a face) and step coordinate u (Z inside, radius on a face): the material's top
        // T(u): the bottom between the walls, the chamfers' 45-degree slopes beside them, the
        // surface beyond. The blade's edge covers u .. u + w at its d; it must stay at or above
        // T over all of it (T is piecewise linear: its least at the ends or its corners).
        const double sd = face ? g.surface : -g.surface, bd = face ? g.bottom : -g.bottom;
        auto T = [&](double u) {
            if (u >= g.lo && u <= g.hi) return bd;
            const double e = u < g.lo ? g.lo - u : u - g.hi;
            return e < g.c ? sd - g.c + e : sd;
        };
        auto check_at = [&](const Vec3& p) {
            const double d = face ? p.z : -p.x;
            const double u0 = face ? p.x : p.z - (g.right ? g.w : 0.0), u1 = u0 + g.w;
            double least = std::min(T(u0), T(u1));
            for (double c : {g.lo, g.hi, g.lo - g.c, g.hi + g.c})
                if (c > u0 && c < u1) least = std::min(least, T(c));
            CHECK(d >= least - eps);  // never in what the part keeps, never beyond the bottom or the walls
            if (!face) CHECK(p.x > 0);  // never across the axis
        };
        for (const SideMove& m : moves) {
            INFO("move to X" << m.to.x << " Z" << m.to.z << (m.rapid ? " rapid" : " feed"));
            check_at(m.from), check_at(m.to);
            // Along the step coordinate only in air (beyond approachDistance off the surface),
            // but for the finishing pass along the bottom.
            const double du = face ? m.to.x - m.from.x : m.to.z - m.from.z;
            const double dd = face ? m.to.z - m.from.z : m.to.x - m.from.x;
            const double d = face ? m.to.z : -m.to.x;
            if (std::abs(du) > eps && std::abs(dd) < eps && std::abs(d - bd) > eps) CHECK(d >= sd + g.approach - eps);
            if (std::abs(du) > eps && std::abs(dd) < eps && std::abs(d - bd) <= eps) CHECK(!m.rapid);
        }
    }
}

TEST_CASE("turn-groove sides: random internal grooves simulate as designed on the three lathes; 0.2 mm too deep or wide is a "
          "gouge") {
    std::mt19937 rng(3131);
    const std::filesystem::path dir = test::scratch("groove-sides");
    int k = 0;
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        for (int n = 0; n < 6; ++n, ++k) {
            const RandomGroove g = random_internal(rng, "auto", n % 2 == 0);
            INFO(machine << ": " << g.text);
            const std::string job = (dir / fmt::format("g{}.json", k)).string();
            std::ofstream(job) << g.text;
            const std::string nc = (dir / fmt::format("g{}.nc", k)).string();
            const test::Run posted_run = test::run({job, "--machine", machine, "-q", "-o", nc});
            REQUIRE_MESSAGE(posted_run.code == 0, posted_run.err);
            const test::Run clean = test::run({"simulate", nc, "--machine", machine, "--job", job});
            CHECK_MESSAGE(clean.code == 0, std::string(clean.out + clean.err));
            CHECK_MESSAGE(clean.out.find("  the part is as designed\n") != std::string::npos, clean.out);
            CHECK_MESSAGE(clean.out.find("crash") == std::string::npos, clean.out);
            const test::Run verify = test::run({"verify", nc, "--machine", machine, "--job", job});
            CHECK_MESSAGE(verify.code == 0, std::string(verify.out + verify.err));
        }
    }
    // A groove 0.2 mm too deep (a job whose groove is deeper, simulated against the one designed)
    // and one 0.2 mm too wide: gouges at their path.
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        const std::string tool = R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 600, "orientation": 3})";
        auto write = [&](const std::string& name, const std::string& keys) {
            const std::string path = (dir / (name + ".json")).string();
            std::ofstream(path) << bushing_job(
                tool, R"({"type": "turn-groove", "side": "internal", "tool": 1, "feed": 30, "z": -12)" + keys + "}");
            return path;
        };
        const std::string designed = write("designed", R"(, "width": 5, "depth": 2, "peckDepth": 0.7, "finishAllowance": 0)");
        for (const std::string& keys : {std::string(R"(, "width": 5, "depth": 2.2, "peckDepth": 0.7, "finishAllowance": 0)"),
                                        std::string(R"(, "width": 5.2, "depth": 2, "peckDepth": 0.7, "finishAllowance": 0)")}) {
            const std::string wrong = write("wrong", keys);
            const std::string nc = (dir / "wrong.nc").string();
            REQUIRE(test::run({wrong, "--machine", machine, "-q", "-o", nc}).code == 0);
            const test::Run r = test::run({"simulate", nc, "--machine", machine, "--job", designed});
            INFO(machine << keys);
            CHECK(r.code == 1);
            CHECK_MESSAGE(r.out.find("error: gouge: /operations/0 (") != std::string::npos, r.out);
        }
    }
}

TEST_CASE("turn-groove sides: a rapid into the bore's wall is refused at startX") {
    // A bore of D12 only: the internal groove's blade comes along Z at X14 (startX 16, approach 1).
    const std::filesystem::path dir = test::scratch("groove-sides-crash");
    const std::string job = (dir / "c.json").string();
    std::ofstream(job) << fmt::format(
        R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0, "boreDiameter": 12}}}},
  "tools": [{{"number": 1, "type": "grooving-tool", "width": 3, "rpm": 600, "orientation": 3}}],
  "operations": [{{"type": "turn-groove", "side": "internal", "tool": 1, "feed": 30, "z": -12, "width": 4, "startX": 16,
                   "depth": 2}}]}})");
    // (camgen posted it once and the simulation found the crash; check_blade_material now
    // refuses it, with the bar's solid it would run through.)
    const std::string nc = (dir / "c.ngc").string();
    const test::Run r = test::run({job, "--machine", "linuxcnc-lathe", "-q", "-o", nc});
    CHECK(r.code == 1);
    CHECK_MESSAGE(r.err.find("/operations/0/startX: the blade's rapid along Z at X 14.000 mm from Z 10.000 mm to Z -15.000 mm "
                             "runs through the bar's solid between Z -15.000 mm and Z 0.000 mm") != std::string::npos,
                  r.err);
    CHECK(!std::filesystem::exists(nc));
}

TEST_CASE("turn-groove sides: fanuc-lathe writes a plain internal groove as G75 with X rising and reads it back; a face groove "
          "G74 cannot carry is longhand") {
    const Machine fanuc = load_machine("fanuc-lathe");
    std::mt19937 rng(3132);
    int canned = 0;
    for (int n = 0; n < 40; ++n) {
        const RandomGroove g = random_internal(rng, "canned", true);
        INFO(g.text);
        const test::Posted p = posted(g.text, fanuc);
        CHECK(p.text.find("G75 R") != std::string::npos);
        // X of the G75 block beyond the start point's (a diameter): the bottom.
        const std::smatch m = [&] {
            std::smatch s;
            std::regex_search(p.text, s, std::regex(R"(G75 X([0-9.]+) Z)"));
            return s;
        }();
        REQUIRE(m.size() == 2);
        CHECK(std::abs(std::stod(m[1]) - 2 * (g.bottom)) < 0.0015);
        canned += 1;
        // Read back, the program's moves are the job's.
        const std::filesystem::path dir = test::scratch("groove-sides-g75");
        const std::string job = (dir / "g.json").string(), nc = (dir / "g.nc").string();
        std::ofstream(job) << g.text;
        std::ofstream(nc) << p.text;
        const test::Run v = test::run({"verify", nc, "--machine", "fanuc-lathe", "--job", job});
        CHECK_MESSAGE(v.code == 0, std::string(v.out + v.err));
    }
    CHECK(canned == 40);
    // A face groove G74 cannot carry (a finishing pass): longhand with a note under auto; canned
    // refuses it at its path (test_fanuc_g74_groove.cpp: the plain ones are written as G74).
    const std::string facer = R"({"number": 1, "type": "grooving-tool", "width": 2, "rpm": 600, "orientation": 7})";
    const std::string face = R"({"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": 22, "outerX": 30,
                                 "depth": 2)";
    const test::Posted p = posted(bushing_job(facer, face + "}"), fanuc);
    CHECK(p.text.find("G75") == std::string::npos);
    CHECK(p.text.find("G74") == std::string::npos);
    CHECK_MESSAGE(p.notes.find("the groove is written longhand because machine fanuc-lathe's G74 cannot carry finishPass") !=
                      std::string::npos,
                  p.notes);
    try {
        (void)posted(bushing_job(facer, face + R"(, "output": "canned"})"), fanuc);
        FAIL("a canned face groove was written");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("/operations/0/output: machine fanuc-lathe's G74 cannot carry finishPass") !=
              std::string::npos);
    }
    // LinuxCNC and Sinumerik: longhand, no note (they have no grooving cycle).
    for (const std::string machine : {"linuxcnc-lathe", "sinumerik-lathe"}) {
        const test::Posted q = posted(random_internal(rng, "auto", true).text, load_machine(machine));
        CHECK(q.text.find("G75") == std::string::npos);
        CHECK(q.text.find("G1 ") != std::string::npos);
    }
}

}  // namespace test_groove_sides
