// Field failures (REFERENCE.md §6, tests/unit/test_field_failures.cpp) checked against the real
// LinuxCNC interpreter, rs274, on the machines whose programs it runs: "G98 treated as G99".
// (The canned-cycle words LinuxCNC requires, G86/G89 with P, are checked in test_oracle.cpp.)
#include <doctest/doctest.h>

#include <cmath>

#include "../unit/support.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_field_failures_oracle {

using namespace camgen;

TEST_CASE("field failure: G98 treated as G99 (rs274)") {
    // Four holes, R at Z2, retract plane Z10: between holes rs274 must traverse at Z10; with the
    // retract plane at R, at Z2.
    const std::optional<std::string> rs274 = oracle::find_rs274();
    REQUIRE_MESSAGE(rs274, "rs274 (linuxcnc-uspace) is not installed");
    for (const char* name : {"fanuc", "linuxcnc"}) {
        for (double retract : {10.0, 2.0}) {
            INFO(name << " retract plane Z" << retract);
            const std::string job = R"({"clearance": 20, "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
 "operations": [{"type": "drill", "tool": 1, "safeDistance": 2, "endDepth": 5, "plungingFeedrate": 100, "retractPlane": )" +
                                    std::to_string(retract) + R"(, "holes": [[10, 10], [30, 10], [30, 25], [10, 25]]}]})";
            const std::string program = test::post_program(read_job(job, "job.json"), load_machine(name));
            std::vector<oracle::Step> steps;
            REQUIRE_NOTHROW(steps = oracle::run_rs274(*rs274, program));
            bool drilling = false;
            int across = 0;
            oracle::Step last;
            for (const oracle::Step& s : steps) {
                if (s.kind == oracle::Step::Kind::feed) drilling = true;
                const bool moves_xy = std::hypot(s.to.x - last.to.x, s.to.y - last.to.y) > 1e-6;
                if (drilling && s.kind == oracle::Step::Kind::traverse && moves_xy && across < 3) {
                    CHECK(s.to.z == doctest::Approx(retract));
                    CHECK(last.to.z == doctest::Approx(retract));
                    ++across;
                }
                if (s.kind != oracle::Step::Kind::spindle && s.kind != oracle::Step::Kind::dwell) last = s;
            }
            CHECK(across == 3);
        }
    }
}

}  // namespace test_field_failures_oracle
