// LinuxCNC oracle for constant surface speed (issue 30, item 4): what linuxcnc-lathe writes for a
// turning tool's surfaceSpeed (G96 D<limit> S<m/min>, G95 F per revolution) and for the drill
// after it (G97 S<rpm>) is what rs274 makes of it - SET_SPINDLE_MODE(0 <limit>) with
// SET_SPINDLE_SPEED(0, <m/min>), SET_SPINDLE_MODE(0 0) for rpm, SET_FEED_MODE(0, 1) and the
// feed per revolution - and what camgen's reader reads back.
#include <doctest/doctest.h>

#include <regex>
#include <sstream>

#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/reader/reader.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_surface_speed_oracle {

using namespace camgen;

namespace {

const char* job_text = R"({"clearance": 20, "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 1}},
  "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "surfaceSpeed": 200, "maxRpm": 2500},
            {"number": 2, "type": "drill", "diameter": 5, "tipAngle": 118, "rpm": 1200}],
  "operations": [{"type": "turn-face", "tool": 1, "z": 0, "stepdown": 1, "feedMode": "per-revolution", "feed": 0.2},
                 {"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -10, "safeDistance": 2,
                  "retractDistance": 5, "feedMode": "per-revolution", "plungingFeedrate": 0.1}]})";

// A spindle start as (limit or rpm, surface speed or 0).
struct Start {
    double rpm = 0.0;
    double surface_speed = 0.0;
    bool operator==(const Start&) const = default;
};

}  // namespace

TEST_CASE("rs274 reads linuxcnc-lathe's G96 D S and G97 S as camgen's reader does; F stays per revolution") {
    auto rs274 = oracle::find_rs274();
    if (!rs274) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    const Machine m = load_machine("linuxcnc-lathe");
    std::ostringstream out;
    auto p = make_post(m, out, PostOptions{});
    p->open();
    expand_job(read_job(job_text, "oracle.json"), *p);
    p->close();
    const std::string program = out.str();
    const std::string canon = oracle::run_rs274_canon(*rs274, program);
    INFO(program << "\nrs274:\n" << canon);

    // rs274's spindle starts: the mode (its limit under G96, 0 for rpm) and the speed before each.
    std::vector<Start> interpreted;
    double mode = 0.0, speed = 0.0;
    const std::regex mode_call(R"(SET_SPINDLE_MODE\(0 ([0-9.]+)\))"), speed_call(R"(SET_SPINDLE_SPEED\(0, ([0-9.]+)\))");
    std::istringstream lines(canon);
    for (std::string line; std::getline(lines, line);) {
        std::smatch g;
        if (std::regex_search(line, g, mode_call)) mode = std::stod(g[1].str());
        if (std::regex_search(line, g, speed_call)) speed = std::stod(g[1].str());
        if (line.find("START_SPINDLE_CLOCKWISE") != std::string::npos)
            interpreted.push_back(mode > 0 ? Start{mode, speed} : Start{speed, 0.0});
    }
    CHECK(canon.find("SET_FEED_MODE(0, 1)") != std::string::npos);
    CHECK(canon.find("SET_FEED_RATE(0.2000)") != std::string::npos);

    std::vector<Start> read_back;
    bool per_rev_feed = false;
    for (const ReadEvent& e : read_program(program, m, "oracle.ngc")) {
        if (const auto* s = std::get_if<Spindle>(&e.event); s && s->state != SpindleState::off)
            read_back.push_back({s->rpm, s->surface_speed});
        if (std::holds_alternative<Linear>(e.event) && e.per_revolution == 0.2) per_rev_feed = true;
    }
    CHECK(per_rev_feed);
    const std::vector<Start> expected{{2500, 200}, {1200, 0}};
    CHECK(interpreted == expected);
    CHECK(read_back == expected);
}

}  // namespace test_surface_speed_oracle
