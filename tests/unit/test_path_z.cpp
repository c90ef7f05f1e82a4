// Issue 25 item 2: in a path, a point [x, y] keeps the current Z (where the element before it
// ended), as a G1 X Y block does; it never goes back to the operation's z. A thread-milling exit
// {"line": [90, 40]} after a helix up to Z0 runs at Z0, not as a diagonal feed down through the
// thread just cut. Checked on every built-in machine by reading the posted program back.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "camgen/events/visit.hpp"
#include "camgen/reader/reader.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_path_z {

using namespace camgen;
using test::Run;
using test::run;

namespace {

// Three paths, each ending in a 2D element after one that changed Z:
// A: thread milling in a bore at X90 Y40: in to the thread at Z-9.5, a helix up to Z0, the
//    exit [90, 40] (elements read as JSON: the path is not all lines);
// B: lines only (read straight into numbers): down to Z-3 by [10, 0, -3], then [20, 0];
// C: a line down to Z-2, then an XY arc whose end is [50, 10].
const char* path_job = R"({"name": "path-z", "units": "mm", "clearance": 10,
 "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 3000}],
 "operations": [
  {"type": "path", "tool": 1, "comment": "thread", "z": -9.5, "feed": 300, "start": [90, 40],
   "path": [{"line": [90, 32]}, {"helix": {"centre": [90, 40], "direction": "ccw", "z": 0, "turns": 6}},
            {"line": [90, 40]}]},
  {"type": "path", "tool": 1, "comment": "lines", "z": -1, "feed": 300, "start": [0, 0],
   "path": [{"line": [10, 0, -3]}, {"line": [20, 0]}]},
  {"type": "path", "tool": 1, "comment": "arc", "z": -1, "feed": 300, "start": [30, 0],
   "path": [{"line": [40, 0, -2]}, {"arc": {"end": [50, 10], "centre": [40, 10], "direction": "ccw"}}]}
 ]})";

// The end of the last feed move (line or arc) of the program that ends at X `x` Y `y`.
std::optional<Vec3> last_feed_end_at(const std::vector<ReadEvent>& events, double x, double y) {
    std::optional<Vec3> found;
    for (const ReadEvent& e : events) {
        std::optional<Vec3> end;
        if (const auto* l = std::get_if<Linear>(&e.event)) end = l->to;
        if (const auto* a = std::get_if<Arc>(&e.event)) end = a->to;
        if (end && std::abs(end->x - x) < 0.001 && std::abs(end->y - y) < 0.001) found = end;
    }
    return found;
}

}  // namespace

TEST_CASE("path: a point [x, y] keeps the current Z on every machine (read back), and verify --job agrees") {
    const std::filesystem::path dir = test::scratch("path-z");
    const std::string job = (dir / "path-z.json").string();
    std::ofstream(job) << path_job;
    for (const auto& [name, description] : list_machines()) {
        INFO("machine " << name);
        const Machine machine = load_machine(name);
        const std::string program = (dir / (name + "." + machine.extension)).string();
        const Run r = run({job, "--machine", name, "-o", program, "--quiet"});
        if (machine.kind == MachineKind::lathe) {
            // A path is a milling operation: a lathe refuses it, nothing is written.
            CHECK(r.code == 1);
            CHECK(r.err.find("/operations/0") != std::string::npos);
            CHECK_FALSE(std::filesystem::exists(program));
            continue;
        }
        REQUIRE_MESSAGE(r.code == 0, r.err);
        const std::vector<ReadEvent> events = read_program(test::read_file(program), machine, program);
        const std::optional<Vec3> exit = last_feed_end_at(events, 90, 40);
        REQUIRE(exit);
        CHECK(std::abs(exit->z - 0.0) < 0.001);
        const std::optional<Vec3> line = last_feed_end_at(events, 20, 0);
        REQUIRE(line);
        CHECK(std::abs(line->z + 3.0) < 0.001);
        const std::optional<Vec3> arc = last_feed_end_at(events, 50, 10);
        REQUIRE(arc);
        CHECK(std::abs(arc->z + 2.0) < 0.001);
        // The program read back is the job's motion.
        const Run v = run({"verify", program, "--machine", name, "--job", job});
        CHECK_MESSAGE(v.code == 0, v.out << v.err);
    }
}

TEST_CASE("path: the job's motion has [x, y] at the current Z (events), also for an arc's end") {
    const Job job = read_job(path_job, "path-z.json");
    REQUIRE(job.operations.size() == 3);
    const auto& thread = std::get<PathOp>(job.operations[0]);
    REQUIRE(thread.elements.size() == 3);
    CHECK(std::get<PathLine>(thread.elements[0]).end.z == -9.5);  // before any Z change: the operation's z
    CHECK(std::get<PathLine>(thread.elements[2]).end.z == 0.0);
    const auto& lines = std::get<PathOp>(job.operations[1]);
    CHECK(std::get<PathLine>(lines.elements[1]).end.z == -3.0);
    const auto& arc = std::get<PathOp>(job.operations[2]);
    const PathArc& a = std::get<PathArc>(arc.elements[1]);
    CHECK(a.end.z == -2.0);
    CHECK(a.centre.z == -2.0);
}

}  // namespace test_path_z
