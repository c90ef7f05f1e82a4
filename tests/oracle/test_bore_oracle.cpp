// LinuxCNC oracle for bore milling (issue 11, part 7): the program camgen writes for the
// `linuxcnc` machine from samples/bores.json and from bores milled conventionally with a
// counter-clockwise spindle runs through rs274 -g, and rs274's straight and arc feeds (end
// points, centres, turn direction, feeds) and traverses are camgen's reading of the same program,
// which in turn is the motion of the job.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen_motion.hpp"
#include "camgen/operations/registry.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_bore_oracle {

using namespace camgen;
using OStep = camgen::oracle::Step;

namespace {

// The steps from the first feed on: before it the two sides know the start differently
// (rs274 from its origin, camgen from the tool change).
std::vector<OStep> from_first_feed(const std::vector<OStep>& steps) {
    auto it = std::find_if(steps.begin(), steps.end(),
                           [](const OStep& s) { return s.kind == OStep::Kind::feed || s.kind == OStep::Kind::arc; });
    return {it, steps.end()};
}

bool near(const Vec3& a, const Vec3& b) {
    return std::abs(a.x - b.x) <= 0.001 && std::abs(a.y - b.y) <= 0.001 && std::abs(a.z - b.z) <= 0.001;
}

// rs274 accepts the program and moves as camgen reads it; camgen's reading is the job's motion.
// Returns the number of arcs compared.
int check_job(const std::string& job_text) {
    const std::string rs274 = oracle::find_rs274().value_or("");
    REQUIRE_MESSAGE(!rs274.empty(), "rs274 (LinuxCNC's standalone interpreter) was not found");
    const Job job = read_job(job_text, "bores.json");
    const Machine machine = load_machine("linuxcnc");
    const std::string program = oracle::posted_program(job, machine);
    std::vector<OStep> theirs;
    REQUIRE_NOTHROW(theirs = from_first_feed(oracle::run_rs274(rs274, program)));
    const std::vector<OStep> ours = from_first_feed(oracle::read_with_camgen(program, machine));
    REQUIRE(theirs.size() == ours.size());
    int arcs = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const OStep& a = theirs[i];
        const OStep& b = ours[i];
        INFO("step " << i << ": rs274 " << oracle::describe(a) << ", camgen " << oracle::describe(b));
        CHECK(a.kind == b.kind);
        CHECK(near(a.to, b.to));
        CHECK(std::abs(a.value - b.value) <= 0.001);
        if (a.kind == OStep::Kind::arc) {
            CHECK(std::abs(a.centre.x - b.centre.x) <= 0.001);
            CHECK(std::abs(a.centre.y - b.centre.y) <= 0.001);
            CHECK(a.rotation == b.rotation);
            ++arcs;
        }
    }
    const Trace read = trace_program(read_program(program, machine, "bores.ngc"), machine);
    const auto mismatch = compare_traces(trace_expected(expand_job(job), machine), read, compare_tolerance(machine, 0.0));
    CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
    return arcs;
}

std::string read_text(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("bore milling: rs274 runs the linuxcnc program of samples/bores.json as camgen reads it") {
    // Four rings of six turns and a circle each, the finishing circle; six bores of four turns
    // and a circle.
    CHECK(check_job(read_text(CAMGEN_SOURCE_DIR "/samples/bores.json")) == 4 * 7 + 1 + 6 * 5);
}

TEST_CASE("bore milling: conventional with a counter-clockwise spindle, relative heights, runs through rs274") {
    const std::string job = R"({"name": "t", "units": "mm", "clearance": 30,
      "tools": [{"number": 4, "type": "end-mill", "diameter": 6, "rpm": 3000, "direction": "ccw"}],
      "operations": [{"type": "bore-mill", "tool": 4, "diameter": 9.5, "direction": "conventional",
        "referencePlane": 10, "retractPlane": 15, "safeDistance": 2, "endDepth": 4.2, "pitch": 1,
        "finishingAllowance": 0.1, "feed": 500, "finishingFeed": 250,
        "grid": {"origin": [0, 0], "countX": 2, "countY": 2, "spacingX": 20, "spacingY": 15}, "order": "shortest"}]})";
    // 5 helix turns (4.2 / 1 rounded up), the bottom circle and the finishing circle per hole.
    CHECK(check_job(job) == 4 * 7);
}

}  // namespace test_bore_oracle
