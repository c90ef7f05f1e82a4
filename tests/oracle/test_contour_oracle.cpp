// LinuxCNC's interpreter applies cutter compensation itself: for every sample with control
// compensation, camgen's linuxcnc program run through `rs274 -g` with the tool's diameter in
// its tool table cuts the same path as camgen's own computer-compensated program.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../unit/support.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_contour_oracle {

using namespace camgen;
using namespace camgen::oracle;
using camgen::oracle::Step;  // not camgen::Step (analysis/trace.hpp), which a unity build may see too

namespace {

std::string read_text(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

double dist(Vec3 a, Vec3 b) { return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z); }

// The cutting moves of a program: in each run of feed moves between rapids, the moves after
// the first arc (the lead-in) and before the last one (the lead-out). The leads differ by
// construction (camgen's lead arcs touch the offset path, the control's are offset with it);
// what lies between them is the offset profile in every pass.
std::vector<Step> cutting_moves(const std::vector<Step>& steps) {
    std::vector<Step> out;
    std::size_t k = 0;
    while (k < steps.size()) {
        if (steps[k].kind == Step::Kind::traverse || steps[k].kind == Step::Kind::spindle) {
            ++k;
            continue;
        }
        std::size_t end = k;
        while (end < steps.size() && steps[end].kind != Step::Kind::traverse) ++end;
        std::optional<std::size_t> first, last;
        for (std::size_t i = k; i < end; ++i)
            if (steps[i].kind == Step::Kind::arc) {
                if (!first) first = i;
                last = i;
            }
        if (first && *last > *first)
            for (std::size_t i = *first + 1; i < *last; ++i) out.push_back(steps[i]);
        k = end;
    }
    return out;
}

}  // namespace

TEST_CASE("contour: rs274's own compensation of camgen's G41/G42 program cuts camgen's computer-compensated path") {
    const auto rs274 = find_rs274();
    REQUIRE_MESSAGE(rs274, "rs274 not found (install linuxcnc-uspace)");
    const Machine machine = load_machine("linuxcnc");
    int samples = 0;
    for (const auto& entry : std::filesystem::directory_iterator(CAMGEN_SOURCE_DIR "/samples")) {
        if (entry.path().extension() != ".json") continue;
        nlohmann::json job = nlohmann::json::parse(read_text(entry.path()));
        bool control = false;
        for (const auto& op : job["operations"])
            if (op.value("type", "") == "contour" && op.value("compensation", "computer") == "control") control = true;
        if (!control) continue;
        ++samples;
        CAPTURE(entry.path().filename().string());
        nlohmann::json computer = job;
        for (auto& op : computer["operations"])
            if (op.value("type", "") == "contour") op["compensation"] = "computer";
        const Job control_job = read_job(job.dump(), "control.json");
        const std::map<int, double> diameters = test::tool_diameters(control_job);
        const std::string control_program = test::post_program(control_job, machine);
        const std::string computer_program = test::post_program(read_job(computer.dump(), "computer.json"), machine);
        CHECK(control_program.find("G41 D") != std::string::npos);
        CHECK(computer_program.find("G41 D") == std::string::npos);
        // rs274 accepts every entry and exit camgen writes, or this throws with its message.
        const std::vector<Step> rs274_motion = run_rs274(*rs274, control_program, diameters);
        const std::vector<Step> by_control = cutting_moves(rs274_motion);
        // camgen's own read-back of the G41/G42 program (the radius from its tool comment) is
        // the tool centre's path: rs274's motion, move for move from the first feed (before it
        // rs274 starts from the origin, camgen's reader from an unknown position).
        const auto from_first_feed = [](std::vector<Step> steps) {
            const auto feed = std::find_if(steps.begin(), steps.end(), [](const Step& s) { return s.kind == Step::Kind::feed; });
            steps.erase(steps.begin(), feed);
            return steps;
        };
        const std::vector<Step> read_back = from_first_feed(read_with_camgen(control_program, machine));
        const std::vector<Step> rs274_from_feed = from_first_feed(rs274_motion);
        REQUIRE(read_back.size() > 40);
        REQUIRE(read_back.size() == rs274_from_feed.size());
        for (std::size_t i = 0; i < read_back.size(); ++i) {
            CAPTURE(i);
            CAPTURE(describe(read_back[i]));
            CAPTURE(describe(rs274_from_feed[i]));
            CHECK(read_back[i].kind == rs274_from_feed[i].kind);
            CHECK(dist(read_back[i].to, rs274_from_feed[i].to) < 0.001);
            if (read_back[i].kind == Step::Kind::arc) {
                CHECK(std::hypot(read_back[i].centre.x - rs274_from_feed[i].centre.x, read_back[i].centre.y - rs274_from_feed[i].centre.y) < 0.001);
                CHECK(read_back[i].rotation == rs274_from_feed[i].rotation);
            }
        }
        const std::vector<Step> by_camgen = cutting_moves(run_rs274(*rs274, computer_program, diameters));
        REQUIRE(by_camgen.size() > 10);
        REQUIRE(by_control.size() == by_camgen.size());
        for (std::size_t i = 0; i < by_camgen.size(); ++i) {
            const Step &a = by_control[i], &b = by_camgen[i];
            CAPTURE(i);
            CAPTURE(describe(a));
            CAPTURE(describe(b));
            CHECK(a.kind == b.kind);
            CHECK(dist(a.to, b.to) < 0.001);
            CHECK(a.value == doctest::Approx(b.value));
            if (a.kind == Step::Kind::arc) {
                CHECK(std::hypot(a.centre.x - b.centre.x, a.centre.y - b.centre.y) < 0.001);
                CHECK(a.rotation == b.rotation);
            }
        }
    }
    CHECK(samples >= 1);
}

}  // namespace test_contour_oracle
