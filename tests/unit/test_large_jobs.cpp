// Large jobs (issue 25): the buffers of a job's text, its packed arrays, its holes and the
// safety check's hole log are reserved once at the counts known, and advised onto huge pages;
// what they hold and what is posted stay the same. (ctest readback/memory holds a million-hole
// post to its page faults.)
#include <doctest/doctest.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/common/large_buffer.hpp"
#include "camgen/post/safety.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_large_jobs {

using namespace camgen;
using test::Run;
using test::run;

namespace {

// The VmFlags line of the mapping of this process that holds `address` ("" if none).
std::string vm_flags_at(const void* address) {
    std::ifstream smaps("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(address);
    bool inside = false;
    for (std::string line; std::getline(smaps, line);) {
        std::uintptr_t start = 0, end = 0;
        // A mapping's first line is "start-end perms offset ..."; its fields follow.
        if (std::sscanf(line.c_str(), "%" SCNxPTR "-%" SCNxPTR " ", &start, &end) == 2 && line.find(' ') > line.find('-'))
            inside = start <= at && at < end;
        else if (inside && line.rfind("VmFlags:", 0) == 0)
            return line;
    }
    return "";
}

// A drilling operation's events: cycle `op` at `holes`, feeding from `safe_z` down to `bottom_z`
// (stock top Z0, retract plane Z5), as expand_job makes them.
void add_cycle(std::vector<Event>& ev, int op, double safe_z, double bottom_z, const std::vector<Vec2>& holes) {
    const std::string path = "/operations/" + std::to_string(op);
    DrillCycle c;
    c.path = path;
    c.retract_z = 5.0;
    c.reference_z = 0.0;
    c.safe_z = safe_z;
    c.bottom_z = bottom_z;
    c.feed = 100.0;
    c.values.set(DrillField::plunging_feedrate, 100.0);
    ev.push_back(OperationStart{"drill", path, std::nullopt});
    ev.push_back(ToolChange{op + 1, 5.0, "drill"});
    ev.push_back(Rapid{{holes.front().x, holes.front().y, 20}});
    ev.push_back(Rapid{{holes.front().x, holes.front().y, 5}});
    ev.push_back(c);
    for (const Vec2& h : holes) ev.push_back(DrillPoint{h});
    ev.push_back(DrillEnd{});
    ev.push_back(Rapid{{holes.back().x, holes.back().y, 20}});
    ev.push_back(OperationEnd{});
}

// Runs the safety check over `events` with its hole log reserved for `holes` holes.
void check_with_reserve(const std::vector<Event>& events, std::size_t holes) {
    SafetyCheck check(SafetyLimits{.clearance = 20.0, .flute_lengths = {}, .longhand = {}});
    check.reserve_holes(holes);
    for (const Event& e : events) check.emit(e);
    check.finish();
}

}  // namespace

TEST_CASE("reserve_large reserves at once, keeps what the vector holds and never shrinks it") {
    std::vector<double> v{1.0, 2.0, 3.0};
    const std::size_t n = std::size_t{1} << 20;  // 8 MB: advised
    reserve_large(v, n);
    CHECK(v.capacity() >= n);
    CHECK(v == std::vector<double>{1.0, 2.0, 3.0});
    const double* data = v.data();
    v.resize(n, 4.0);
    CHECK(v.data() == data);  // filled without moving
    CHECK(v[2] == 3.0);
    CHECK(v[n - 1] == 4.0);
    reserve_large(v, 10);
    CHECK(v.capacity() >= n);
    std::vector<int> small;
    reserve_large(small, 5);
    CHECK(small.capacity() >= 5);
}

TEST_CASE("a large buffer is advised onto huge pages, where the system has them") {
    if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled") ||
        !std::filesystem::exists("/proc/self/smaps")) {
        MESSAGE("no transparent huge pages here: nothing to check");
        return;
    }
    std::vector<char> v;
    reserve_large(v, std::size_t{16} << 20);
    // The first whole 2 MiB page inside the buffer is in a mapping with the advice (VmFlags hg).
    constexpr std::uintptr_t huge_page = std::uintptr_t{2} << 20;
    const auto inside = (reinterpret_cast<std::uintptr_t>(v.data()) + huge_page - 1) & ~(huge_page - 1);
    const std::string flags = vm_flags_at(reinterpret_cast<const void*>(inside));
    INFO(flags);
    CHECK(flags.find(" hg") != std::string::npos);
}

TEST_CASE("a packed array is reserved for its elements at once; one given more room than it filled is shrunk") {
    // Two hole lists and a path; every `[` after the path's first element is one of its lines.
    std::string text = R"({"operations": [{"holes": [[1, 2], [3, 4]]}, {"holes": [[5, 6]], "name": "[[["},
                          {"path": [)";
    for (int i = 0; i < 1000; ++i) text += fmt::format(R"({}{{"line": [{}, {}]}})", i ? ", " : "", i, -i);
    text += R"(]}, {"path": [{"line": [0, 0, 1]}, {"line": [1, 0]}, {"line": [1, 1, 2]}]}]})";
    for (const bool fast : {true, false}) {
        const std::string reader = fast ? "the fast reader" : "nlohmann's parser";
        INFO(reader);
        const json::Document doc = fast ? *json::parse_document_fast(text) : json::parse_document_with_nlohmann(text, "t.json");
        REQUIRE(doc.packed.size() == 4);
        // The hole lists got room for the 1,000-odd `[` after theirs and were shrunk.
        CHECK(doc.packed[0].size() == 2);
        CHECK(doc.packed[0].xyz.capacity() < 20);
        CHECK(doc.packed[0].kinds.capacity() < 10);
        CHECK(doc.packed[1].size() == 1);
        CHECK(doc.packed[1].xyz.capacity() < 20);
        // The long path had room for 1,007 elements: its own 1,000, the last path's four `[`
        // and the three of the name (a `[` in a string counts too: the room is never short).
        // It filled all but 7, and was neither grown nor copied.
        CHECK(doc.packed[2].size() == 1000);
        CHECK(doc.packed[2].xyz.capacity() == 2 * 1007);
        CHECK(doc.packed[2].kinds.capacity() == 1007);
        CHECK(doc.packed[2].x(999) == 999.0);
        CHECK(doc.packed[2].y(999) == -999.0);
        // A path with z: three numbers an element (its room widened, then shrunk to fit).
        CHECK(doc.packed[3].stride == 3);
        CHECK(doc.packed[3].size() == 3);
        CHECK(doc.packed[3].xyz.capacity() == 3 * 3);
        CHECK(doc.packed[3].z(0) == 1.0);
        CHECK(!doc.packed[3].has_z(1));
        CHECK(doc.packed[3].z(2) == 2.0);
    }
}

TEST_CASE("a job file larger than a read block (64 KiB) is read whole, as from standard input") {
    std::string holes;
    for (int i = 0; i < 12007; ++i) holes += fmt::format("{}[{:.3f}, {:.3f}]", i ? ", " : "", i % 100 * 5.0, i / 100 * 5.0);
    const std::string job = R"({"name": "large", "clearance": 10,
 "tools": [{"number": 1, "type": "drill", "diameter": 5, "tipAngle": 118, "rpm": 1500}],
 "operations": [{"type": "drill", "tool": 1, "retractPlane": 10, "safeDistance": 2, "endDepth": 12,
   "plungingFeedrate": 100, "holes": [)" + holes + "]}]}\n";
    REQUIRE(job.size() > 3 * 65536);
    REQUIRE(job.size() % 65536 != 0);
    const Run from_file = run({test::file_with("large-read", job), "--machine", "fanuc"});
    const Run from_stdin = run({"-", "--machine", "fanuc"}, job);
    CHECK(from_file.code == 0);
    CHECK(from_file.err.empty());
    CHECK(from_file.out == from_stdin.out);
    // The last hole is posted: the text's last block was read.
    CHECK(from_file.out.find(" X30.000 Y600.000\n") != std::string::npos);
}

TEST_CASE("the safety check's hole log answers the same whatever room it was given") {
    std::vector<Vec2> row;
    for (int i = 0; i < 300; ++i) row.push_back({i * 5.0, (i % 7) * 5.0});
    // A second operation feeds from Z-2, inside the stock: only where the first drilled. Its
    // lookups alternate with its own holes, which merge the log's sorted runs.
    std::vector<Event> all;
    add_cycle(all, 0, 2.0, -10.0, row);
    add_cycle(all, 1, -2.0, -8.0, row);
    std::vector<Vec2> gap = row;
    gap.erase(gap.begin() + 200);
    std::vector<Event> missing;
    add_cycle(missing, 0, 2.0, -10.0, gap);
    add_cycle(missing, 1, -2.0, -8.0, row);
    for (const std::size_t room : {std::size_t{0}, std::size_t{10}, std::size_t{299}, std::size_t{600}, std::size_t{1} << 20}) {
        INFO("room for " << room << " holes");
        CHECK_NOTHROW(check_with_reserve(all, room));
        CHECK_THROWS_WITH_AS(check_with_reserve(missing, room),
                             doctest::Contains("/operations/1: a feed starts at Z -2.000, below the reference plane "
                                               "(Z 0.000), at X1000.000 Y20.000 where no hole has been drilled"),
                             InputError);
    }
}

}  // namespace test_large_jobs
