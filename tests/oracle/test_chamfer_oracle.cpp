// LinuxCNC oracle for the chamfer operation (issue 29, item 3): the linuxcnc and fanuc programs
// of samples/chamfer.json run through rs274 -g to PROGRAM_END, move for move as camgen reads
// them; and the chamfers the tools' cones leave, computed from rs274's tool positions and the
// tools' geometry (not from camgen's planning), are the job's: the outline's 0.5 x 45 with the
// 90-degree V-bit, the holes' 1 x 45 with the 90-degree chamfer mill of tip diameter 1.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "camgen/operations/registry.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_chamfer_oracle {

using namespace camgen;
using OStep = camgen::oracle::Step;

namespace {

std::string chamfer_read_text(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// Distance from the sample's plate outline, 0..80 x 0..40 with corners of radius 5 (outside
// positive).
double plate_distance(double x, double y) {
    const double qx = std::abs(x - 40.0) - (40.0 - 5.0), qy = std::abs(y - 20.0) - (20.0 - 5.0);
    const double out = std::hypot(std::max(qx, 0.0), std::max(qy, 0.0));
    return out + std::min(std::max(qx, qy), 0.0) - 5.0;
}

// The points of rs274's moves while the spindle turns at `rpm` (the tool's), arcs sampled.
struct ToolPoints {
    std::vector<Vec3> points;
    double lowest = std::numeric_limits<double>::infinity();
};
ToolPoints points_at_rpm(const std::vector<OStep>& steps, double rpm) {
    ToolPoints t;
    Vec3 at{};
    double turning = 0.0;
    for (const OStep& s : steps) {
        if (s.kind == OStep::Kind::spindle) turning = s.value;
        if (s.kind != OStep::Kind::traverse && s.kind != OStep::Kind::feed && s.kind != OStep::Kind::arc) continue;
        if (std::abs(turning - rpm) < 0.5 && s.kind != OStep::Kind::traverse) {
            if (s.kind == OStep::Kind::arc) {
                const double r0 = std::hypot(at.x - s.centre.x, at.y - s.centre.y);
                const double a0 = std::atan2(at.y - s.centre.y, at.x - s.centre.x);
                const double a1 = std::atan2(s.to.y - s.centre.y, s.to.x - s.centre.x);
                double sweep = s.rotation > 0 ? a1 - a0 : a0 - a1;
                while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
                for (int k = 1; k <= 64; ++k) {
                    const double a = a0 + (s.rotation > 0 ? 1 : -1) * sweep * k / 64;
                    t.points.push_back({s.centre.x + r0 * std::cos(a), s.centre.y + r0 * std::sin(a), at.z + (s.to.z - at.z) * k / 64});
                }
            }
            t.points.push_back(s.to);
            t.lowest = std::min(t.lowest, s.to.z);
        }
        at = s.to;
    }
    return t;
}

}  // namespace

TEST_CASE("chamfer: rs274 runs samples/chamfer.json for linuxcnc and fanuc; the cones leave the chamfers asked") {
    const std::string rs274 = oracle::find_rs274().value_or("");
    REQUIRE_MESSAGE(!rs274.empty(), "rs274 (LinuxCNC's standalone interpreter) was not found");
    Job job = read_job(chamfer_read_text(CAMGEN_SOURCE_DIR "/samples/chamfer.json"), "chamfer.json");
    // Without the drill's G83: its pecks are LinuxCNC's and Fanuc's own matter (test_oracle.cpp).
    REQUIRE(std::holds_alternative<DrillOp>(job.operations[1]));
    job.operations.erase(job.operations.begin() + 1);
    const double t45 = std::tan(45.0 * std::numbers::pi / 180.0);
    for (const char* name : {"linuxcnc", "fanuc"}) {
        INFO(std::string(name));
        const Machine machine = load_machine(name);
        const std::string program = oracle::posted_program(job, machine);
        std::vector<OStep> theirs;
        REQUIRE_NOTHROW(theirs = oracle::run_rs274(rs274, program));
        // camgen reads the program as rs274 runs it (from the first feed on).
        oracle::check_read_as_run(theirs, program, machine);

        // The outline: the V-bit (10000 rpm, pointed, 90 degrees). At its lowest the tool centre
        // nearest the outline sets the chamfer: the cone reaches (0 - tip Z) tan 45 from the axis at
        // the top face, and meets the wall's line d / tan 45 above the tip.
        const ToolPoints v = points_at_rpm(theirs, 10000);
        REQUIRE(!v.points.empty());
        double nearest = std::numeric_limits<double>::infinity();
        int along = 0;
        for (const Vec3& p : v.points)
            if (p.z < 0.0) {
                // Below the top face the centre never comes nearer than at the tip's depth.
                const double d = plate_distance(p.x, p.y);
                if (std::abs(p.z - v.lowest) < 1e-9) {
                    nearest = std::min(nearest, d);
                    if (std::abs(d - 0.2) < 0.001) ++along;
                }
            }
        for (const Vec3& p : v.points)
            if (p.z < 0.0) CHECK(plate_distance(p.x, p.y) >= nearest - 1e-9);
        const double width = (0.0 - v.lowest) * t45 - nearest, depth = -(v.lowest + nearest / t45);
        MESSAGE(std::string(name) << " outline chamfer: tip Z " << v.lowest << ", centre " << nearest << " from the edge: width " << width
                     << ", depth " << depth << " (" << along << " points along it)");
        CHECK(std::abs(width - 0.5) <= 0.001);
        CHECK(std::abs(depth - 0.5) <= 0.001);
        CHECK(along > 100);

        // The holes: the chamfer mill (6000 rpm, tip diameter 1). The centre farthest from each
        // hole's axis at the tip's depth: the edge (radius 4) minus that is its offset.
        const ToolPoints c = points_at_rpm(theirs, 6000);
        REQUIRE(!c.points.empty());
        for (const Vec2 axis : {Vec2{15, 20}, Vec2{65, 20}}) {
            double farthest = 0.0;
            for (const Vec3& p : c.points)
                if (p.z < 0.0 && std::hypot(p.x - axis.x, p.y - axis.y) < 4.0) {
                    const double r = std::hypot(p.x - axis.x, p.y - axis.y);
                    if (std::abs(p.z - c.lowest) < 1e-9) farthest = std::max(farthest, r);
                }
            const double offset = 4.0 - farthest;
            const double hole_width = 0.5 + (0.0 - c.lowest) * t45 - offset, hole_depth = -(c.lowest + (offset - 0.5) / t45);
            MESSAGE(std::string(name) << " hole (" << axis.x << ", " << axis.y << ") chamfer: width " << hole_width << ", depth " << hole_depth);
            CHECK(std::abs(hole_width - 1.0) <= 0.001);
            CHECK(std::abs(hole_depth - 1.0) <= 0.001);
        }
    }
}

}  // namespace test_chamfer_oracle
