// LinuxCNC oracle for thread milling (issue 29, item 2): the linuxcnc and fanuc programs of
// samples/thread.json run through rs274 -g to PROGRAM_END, move for move as camgen reads them,
// and in rs274's own arcs the helix of every pass advances exactly the thread's pitch per
// whole turn, the partial last turn within what the written resolution allows, and the last
// pass's radius is the one the thread table gives.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/vocabulary/threads.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_thread_mill_oracle {

using namespace camgen;
using OStep = camgen::oracle::Step;

namespace {

constexpr double two_pi = 2 * std::numbers::pi;

std::string thread_read_text(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// One thread of the sample: its axis, pitch and the radius its last pass's tool centre must have.
struct ThreadCase {
    Vec2 axis;
    double pitch;
    double last_radius;
    bool internal;
};

// What rs274's helix arcs about one axis show.
struct HelixMeasure {
    int whole_turn_arcs = 0;        // arcs back to their start: full turns
    double worst_whole = 0.0;       // mm, the largest |dZ / turns - pitch| of those
    int partial_arcs = 0;
    double worst_partial = 0.0;     // mm, the largest |dZ / (sweep / 2 pi) - pitch| of the others
    double last_radius = 0.0;       // mm, the radius of the last helix arc
};

HelixMeasure measure(const std::vector<OStep>& steps, const ThreadCase& t) {
    HelixMeasure m;
    Vec3 at{};
    for (const OStep& s : steps) {
        if (s.kind == OStep::Kind::arc && std::hypot(s.centre.x - t.axis.x, s.centre.y - t.axis.y) < 1e-6 &&
            std::abs(s.to.z - at.z) > 1e-9) {
            const double r = std::hypot(at.x - t.axis.x, at.y - t.axis.y);
            const double a0 = std::atan2(at.y - t.axis.y, at.x - t.axis.x), a1 = std::atan2(s.to.y - t.axis.y, s.to.x - t.axis.x);
            const int turns = std::abs(s.rotation);
            double sweep = s.rotation > 0 ? a1 - a0 : a0 - a1;
            while (sweep <= 1e-12) sweep += two_pi;
            const bool closed = std::hypot(s.to.x - at.x, s.to.y - at.y) < 1e-9;
            if (closed) sweep = two_pi;
            sweep += (turns - 1) * two_pi;
            const double per_turn = std::abs(s.to.z - at.z) / (sweep / two_pi);
            if (closed) {
                ++m.whole_turn_arcs;
                m.worst_whole = std::max(m.worst_whole, std::abs(per_turn - t.pitch));
            } else {
                ++m.partial_arcs;
                m.worst_partial = std::max(m.worst_partial, std::abs(per_turn - t.pitch));
            }
            m.last_radius = r;
        }
        if (s.kind == OStep::Kind::traverse || s.kind == OStep::Kind::feed || s.kind == OStep::Kind::arc) at = s.to;
    }
    return m;
}

}  // namespace

TEST_CASE("thread milling: rs274 runs samples/thread.json for linuxcnc and fanuc; its helices advance exactly the pitch") {
    const std::string rs274 = oracle::find_rs274().value_or("");
    REQUIRE_MESSAGE(!rs274.empty(), "rs274 (LinuxCNC's standalone interpreter) was not found");
    Job job = read_job(thread_read_text(CAMGEN_SOURCE_DIR "/samples/thread.json"), "thread.json");
    // Without the tap drill's G83: its pecks' retracts are LinuxCNC's and Fanuc's own matter
    // (tests/oracle/test_oracle.cpp), not the thread's.
    REQUIRE(std::holds_alternative<DrillOp>(job.operations.front()));
    job.operations.erase(job.operations.begin());
    // M10x1.5 internal with the 6 mm thread mill: the tool centre at D / 2 - 3; M16x2 external:
    // at d3 / 2 + 3.
    const ThreadCase cases[] = {{{25, 30}, 1.5, 10.0 / 2 - 3, true},
                                {{70, 30}, 2.0, external_minor_diameter(16, 2) / 2 + 3, false}};
    for (const char* name : {"linuxcnc", "fanuc"}) {
        INFO(std::string(name));
        const Machine machine = load_machine(name);
        const std::string program = oracle::posted_program(job, machine);
        std::vector<OStep> theirs;
        REQUIRE_NOTHROW(theirs = oracle::run_rs274(rs274, program));
        // camgen reads the program as rs274 runs it (from the first feed on).
        oracle::check_read_as_run(theirs, program, machine);
        const Trace read = trace_program(read_program(program, machine, "thread.ngc"), machine);
        const auto mismatch = compare_traces(trace_expected(expand_job(job), machine), read, compare_tolerance(machine, 0.0));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));

        // The written resolution (0.0001 mm on linuxcnc, 0.001 on fanuc) moves a partial turn's
        // end point by up to half a step in X and Y: its angle by that over the radius.
        const double step = std::string(name) == "linuxcnc" ? 0.0001 : 0.001;
        for (const ThreadCase& t : cases) {
            INFO("axis " << t.axis.x << " " << t.axis.y);
            const HelixMeasure m = measure(theirs, t);
            MESSAGE(name << " thread at (" << t.axis.x << ", " << t.axis.y << "): " << m.whole_turn_arcs
                         << " whole-turn arcs, worst " << m.worst_whole << " mm per turn; " << m.partial_arcs
                         << " partial arcs, worst " << m.worst_partial << " mm per turn; last radius " << m.last_radius);
            CHECK(m.whole_turn_arcs > 0);
            CHECK(m.worst_whole <= 1e-6);
            const double angle_error = 2 * (step * std::numbers::sqrt2 / 2) / t.last_radius;
            CHECK(m.worst_partial <= t.pitch * angle_error / (two_pi / 3) + 1e-9);
            // The final radius: tool centre + tool radius = D / 2 (internal), - tool radius = d3 / 2.
            CHECK(std::abs(m.last_radius - t.last_radius) <= step);
        }
        // The internal thread is 12.5 deep at 1.5: each of its 3 passes has a partial third turn.
        CHECK(measure(theirs, cases[0]).partial_arcs == 3);
    }
}

}  // namespace test_thread_mill_oracle
