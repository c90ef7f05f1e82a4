// LinuxCNC oracle for turning (issue 30): the linuxcnc-lathe programs of turn-face, turn-rough
// and turn-profile (the sample shaft, and many random roughing profiles, rising and with
// undercuts) run through rs274 in lathe mode (G18, G7) to their end, and every move rs274 makes
// ends where camgen's own reading of the program says, within 0.001 mm.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include <fmt/format.h>

#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_rough_oracle {

using namespace camgen;

namespace {

std::string rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A move's end in (X radius, Z), whether it was a rapid or an arc (rs274's moves: oracle::xz_moves).
using EndPoint = oracle::XzMove;

// Runs the job's linuxcnc-lathe program through rs274 and compares its moves with camgen's
// reading; the worst difference, mm.
double run_and_compare(const Job& job) {
    const Machine m = load_machine("linuxcnc-lathe");
    const std::string program = oracle::posted_program(job, m);
    INFO(program);
    std::string canon;
    REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(rs274(), program));
    // From the first feed on (rs274 starts at its origin, camgen's reading from the tool change).
    auto from_first_feed = [](std::vector<EndPoint> v) {
        const auto it = std::find_if(v.begin(), v.end(), [](const EndPoint& e) { return !e.rapid; });
        return std::vector<EndPoint>(it, v.end());
    };
    const std::vector<EndPoint> theirs = from_first_feed(oracle::xz_moves(canon)), ours = from_first_feed(oracle::camgen_xz_moves(program, m));
    REQUIRE(theirs.size() == ours.size());
    double worst = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        INFO("move " << i);
        CHECK(theirs[i].rapid == ours[i].rapid);
        CHECK(theirs[i].arc == ours[i].arc);
        worst = std::max({worst, std::abs(theirs[i].x - ours[i].x), std::abs(theirs[i].z - ours[i].z)});
    }
    CHECK(worst <= 0.001);
    return worst;
}

}  // namespace

TEST_CASE("linuxcnc-lathe: the sample shaft (face, drill, rough, finish) runs in rs274 as camgen reads it") {
    std::ifstream f(CAMGEN_SOURCE_DIR "/samples/shaft.json");
    std::stringstream text;
    text << f.rdbuf();
    const Job job = read_job(text.str(), "shaft.json");
    const double worst = run_and_compare(job);
    MESSAGE("shaft on linuxcnc-lathe: rs274 and camgen's reading differ by at most " << worst << " mm");
}

TEST_CASE("linuxcnc-lathe: random turn-face and turn-rough jobs (along Z and along X) run in rs274 as camgen reads them") {
    std::mt19937 rng(3030);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0;
    for (int n = 0; n < 24; ++n) {
        // A profile from Z0 towards -Z, diameters 4 to 28, with undercuts on odd cases.
        std::vector<std::pair<double, double>> pts{{0.0, 4.0 + 8.0 * u(rng)}};  // (z, diameter)
        const int count = 3 + static_cast<int>(u(rng) * 4);
        for (int i = 0; i < count; ++i) {
            const auto [z, d] = pts.back();
            const double dz = 1.0 + 4.0 * u(rng);
            double nd = d + 6.0 * u(rng);
            if (n % 2 == 1 && u(rng) < 0.4) nd = d - std::min(2.0 * dz * 1.1, 4.0 * u(rng));
            nd = std::clamp(nd, 2.0, 28.0);
            pts.push_back({z - dz, nd});
        }
        std::string path;
        for (std::size_t i = 1; i < pts.size(); ++i)
            path += fmt::format("{}{{\"line\": [{:.3f}, {:.3f}]}}", i > 1 ? ", " : "", pts[i].second, pts[i].first);
        const std::string text = fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 30, "length": 60, "faceZ": 0.8}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "insertAngle": 35, "approachAngle": 93, "rpm": 1200}}],
  "operations": [{{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.3}},
                 {{"type": "turn-rough", "tool": 1, "feedMode": "per-revolution", "feed": 0.2, "depthOfCut": {:.2f},
                   "allowanceX": {:.2f}, "allowanceZ": {:.2f}, "start": [{:.3f}, 0], "path": [{}], "direction": "{}"}}]}})",
            0.8 + u(rng), 0.4 * u(rng), 0.1 * u(rng), pts[0].second, path, n % 4 >= 2 ? "x" : "z");
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "rough.json"));
        worst = std::max(worst, run_and_compare(job));
    }
    MESSAGE("24 random turning jobs (12 roughing along X) on linuxcnc-lathe: rs274 and camgen's reading differ by at most " << worst << " mm");
}

}  // namespace test_turn_rough_oracle
