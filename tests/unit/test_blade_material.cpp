// The rapids of turn-groove and turn-part against the material earlier operations keep
// (check_blade_material): the tester's jobs (a groove whose startX lies below the D40 an earlier
// turn-profile keeps; its chamfer's rapid through the shoulder; an internal groove below the
// drilled bore) refused at startX, naming the material; and many generated jobs (profiles with
// shoulders up and down, external, internal and face grooves on both sides of them, with a bar
// and without) where each refusal is a job whose rapids, worked out here from its keys, would
// cross kept material or the bar's solid, and each accepted one (with a bar) posts and
// simulates without a crash on the three lathes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "blade_support.hpp"

namespace test_blade_material {

using namespace camgen;

namespace {

using test::crosses;
using test::shoulder;
using test::simulates_without_crash;
using Profile = test::TurnedProfile;
std::string refusal(const std::string& text) { return test::job_refusal(text); }
std::string job(const std::string& stock, const std::string& operations) { return test::blade_job(stock, operations); }

const std::string bar44 = R"(, "stock": {"bar": {"diameter": 44, "length": 70, "faceZ": 0}})";
const std::string d30_then_d40 =
    R"({"type": "turn-profile", "tool": 3, "feed": 0.1, "feedMode": "per-revolution", "start": [0, 0], "retractX": 44,
  "path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]}, {"line": [40, -20]}, {"line": [40, -40]}]})";

}  // namespace

TEST_CASE("blade material: the tester's grooves through the D40 and below the drilled bore are refused at startX") {
    const std::string g2 = job(bar44, d30_then_d40 + R"(, {"type": "turn-groove", "tool": 5, "feed": 0.05, "feedMode": "per-revolution",
      "startX": 30, "z": -25, "width": 4, "bottomX": 26})");
    const std::string e2 = refusal(g2);
    CHECK_MESSAGE(e2.find("/operations/1/startX: ") != std::string::npos, e2);
    CHECK_MESSAGE(e2.find("the profile of /operations/0 keeps: X up to 40.000 mm") != std::string::npos, e2);
    const std::string g1 = job(bar44, d30_then_d40 + R"(, {"type": "turn-groove", "tool": 5, "feed": 0.05, "feedMode": "per-revolution",
      "startX": 30, "z": -16, "width": 4, "bottomX": 26, "chamfer": 0.5})");
    const std::string e1 = refusal(g1);
    CHECK_MESSAGE(e1.find("/operations/1/startX: the blade's rapid along Z at X 32.000 mm from Z -19.000 mm to Z -21.500 mm") != std::string::npos, e1);
    CHECK_MESSAGE(e1.find("the profile of /operations/0 keeps: X up to 40.000 mm between Z -21.500 mm and Z -20.000 mm") != std::string::npos, e1);
    // The same groove without the chamfer ends at the shoulder's face: it is read.
    CHECK(refusal(job(bar44, d30_then_d40 + R"(, {"type": "turn-groove", "tool": 5, "feed": 0.05, "feedMode": "per-revolution",
      "startX": 30, "z": -16, "width": 4, "bottomX": 26})")) == "");
    // startX the D40 there: read.
    CHECK(refusal(job(bar44, d30_then_d40 + R"(, {"type": "turn-groove", "tool": 5, "feed": 0.05, "feedMode": "per-revolution",
      "startX": 40, "z": -25, "width": 4, "bottomX": 36})")) == "");
    const std::string ig = job(bar44, R"({"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -20, "safeDistance": 2,
      "plungingFeedrate": 0.1, "feedMode": "per-revolution"},
      {"type": "turn-groove", "tool": 8, "side": "internal", "feed": 0.04, "feedMode": "per-revolution", "startX": 16, "z": -20,
       "width": 4, "bottomX": 19})");
    const std::string ei = refusal(ig);
    CHECK_MESSAGE(ei.find("/operations/1/startX: the blade's rapid along Z at X 14.000 mm from Z 20.000 mm to Z -22.500 mm runs "
                          "through the bar's solid between Z -22.500 mm and Z -15.794 mm") != std::string::npos,
                  ei);
    // Within the drilled bore's full diameter: read.
    CHECK(refusal(job(bar44, R"({"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -20, "safeDistance": 2,
      "plungingFeedrate": 0.1, "feedMode": "per-revolution"},
      {"type": "turn-groove", "tool": 8, "side": "internal", "feed": 0.04, "feedMode": "per-revolution", "startX": 16, "z": -10,
       "width": 4, "bottomX": 19})")) == "");
    // A tube's bore: read anywhere.
    CHECK(refusal(job(R"(, "stock": {"bar": {"diameter": 44, "length": 70, "faceZ": 0, "boreDiameter": 16}})",
                      R"({"type": "turn-groove", "tool": 8, "side": "internal", "feed": 0.04, "feedMode": "per-revolution",
       "startX": 16, "z": -40, "width": 4, "bottomX": 19})")) == "");
}

TEST_CASE("blade material: turn-part and a face groove covered by kept material are refused") {
    // No bar: the part-off comes in along Z at X32, through the D40 and the taper that the
    // profile keeps from the face to Z-25.
    const Profile down = shoulder(40, 30, -15);  // down to D30 at Z-25
    const std::string part = job("", down.json + R"(, {"type": "turn-part", "tool": 6, "feed": 0.05, "feedMode": "per-revolution",
      "startX": 30, "z": -30})");
    const std::string ep = refusal(part);
    CHECK_MESSAGE(ep.find("/operations/1/startX: the blade's rapid along Z at X 32.000 mm from Z 20.000 mm to Z -33.000 mm runs "
                          "through the material that the profile of /operations/0 keeps: X up to 40.000 mm") != std::string::npos,
                  ep);
    // With the bar it comes in outside it: read.
    CHECK(refusal(job(bar44, down.json + R"(, {"type": "turn-part", "tool": 6, "feed": 0.05, "feedMode": "per-revolution",
      "startX": 30, "z": -30})")) == "");
    // A face groove in the D40's shoulder face at Z-20, reaching inside the D30: its blade comes
    // down through the D30.
    const std::string face = job("", d30_then_d40 + R"(, {"type": "turn-groove", "tool": 9, "side": "face", "feed": 0.04,
      "feedMode": "per-revolution", "z": -20, "innerX": 28, "outerX": 36, "depth": 2})");
    const std::string ef = refusal(face);
    CHECK_MESSAGE(ef.find("/operations/1/z: the blade's rapid from X ") != std::string::npos, ef);
    CHECK_MESSAGE(ef.find("X up to 30.000 mm") != std::string::npos, ef);
    CHECK_MESSAGE(ef.find("the profile of /operations/0 keeps") != std::string::npos, ef);
    CHECK(refusal(job("", d30_then_d40 + R"(, {"type": "turn-groove", "tool": 9, "side": "face", "feed": 0.04,
      "feedMode": "per-revolution", "z": -20, "innerX": 31, "outerX": 38, "depth": 2})")) == "");
}

TEST_CASE("blade material: generated grooves refused only where a rapid would cross kept material; the rest simulate without a crash") {
    std::mt19937 rng(4711);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto half = [&](double lo, double hi) { return std::round((lo + (hi - lo) * u(rng)) * 2) / 2; };
    const std::filesystem::path dir = test::scratch("blade-material");
    int refused = 0, read = 0, k = 0;
    for (int n = 0; n < 60; ++n) {
        const bool up = n % 2 == 0;
        const double a = up ? half(26, 34) : half(36, 42), b = up ? half(a + 4, 42) : half(std::max(26.0, a - 8), a - 4);
        const double s = half(-25, -12);
        const Profile p = shoulder(a, b, s);
        const int kind = n % 5;  // 0-2 external, 3 internal, 4 face
        // (A face groove below the bar's face is refused for the bar: without one, the profile alone
        // says where the material is.)
        const bool bar = kind == 4 ? false : n % 7 != 6 || kind == 3;
        std::string op;
        bool crash = false;
        if (kind <= 2) {
            // On either diameter, or on the other one's side of the shoulder.
            const double start = u(rng) < 0.5 ? a : b;
            const double width = half(3, 6), z = half(-31, -3) /* within the profile, which ends at Z-40 */, approach = u(rng) < 0.5 ? 1.0 : half(0.5, 2);
            const double chamfer = u(rng) < 0.4 ? 0.5 : 0.0;
            op = fmt::format(R"({{"type": "turn-groove", "tool": 5, "feed": 0.05, "feedMode": "per-revolution", "startX": {},
              "z": {}, "width": {}, "bottomX": {}, "approachDistance": {}, "chamfer": {}}})",
                             start, z, width, start - 4, approach, chamfer);
            const double air = start / 2 + approach, out = (bar ? 22 : start / 2) + approach;
            const double reach = chamfer > 0 ? chamfer + approach : 0.0;
            crash = crosses(p, air, z - width - reach, z + reach) || crosses(p, out, z - width, 20);
        } else if (kind == 3) {
            // An internal groove in a drilled bore (D16, its point at Z-20, full to Z-15.19).
            const double z = half(-26, -3), approach = 1.0;
            op = fmt::format(R"({{"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -20, "safeDistance": 2,
              "plungingFeedrate": 0.1, "feedMode": "per-revolution"}},
              {{"type": "turn-groove", "tool": 8, "side": "internal", "feed": 0.04, "feedMode": "per-revolution",
               "startX": 16, "z": {}, "width": 3, "bottomX": 19, "approachDistance": {}}})",
                             z, approach);
            const double air = 8 - approach;
            crash = z - 3 < -20 + air / std::tan(59.0 * std::acos(-1.0) / 180) - 0.004;
        } else {
            // A face groove in the shoulder's face (an up shoulder: D a to D b at Z s).
            const double inner = half(std::min(a, b) - 4, std::max(a, b) - 8);
            op = fmt::format(R"({{"type": "turn-groove", "tool": 9, "side": "face", "feed": 0.04, "feedMode": "per-revolution",
              "z": {}, "innerX": {}, "outerX": {}, "depth": 2}})",
                             s, inner, inner + 7);
            crash = crosses(p, inner / 2, s + 1, 20);
        }
        const std::string text = job(bar ? bar44 : "", p.json + ", " + op);
        const std::string e = refusal(text);
        INFO(text);
        if (!e.empty()) {
            ++refused;
            CHECK_MESSAGE(crash, e);
            CHECK_MESSAGE((e.find("/startX: the blade's rapid") != std::string::npos ||
                           e.find("/z: the blade's rapid") != std::string::npos),
                          e);
            continue;
        }
        ++read;
        CHECK_MESSAGE(!crash, "read, though a rapid crosses the kept material");
        if (bar) simulates_without_crash(text, dir, k++);
    }
    // Both kinds were made.
    CHECK(refused >= 10);
    CHECK(read >= 10);
}

}  // namespace test_blade_material
