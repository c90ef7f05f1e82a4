// Issue 9 part 8: the safety checks on the events that run before any text is written.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "camgen/post/safety.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_safety {

using namespace camgen;
using test::post_job;
using test::Run;
using test::run;
using test::drill_job;
using test::file_with;

namespace {


// The events of one drilling operation at (10, 10) and (30, 10), as expand_job makes them, with
// the planes given (absolute Z): a stock top, a retract plane and a feed-start plane.
std::vector<Event> cycle_events(double reference_z, double retract_z, double safe_z) {
    DrillCycle c;
    c.kind = CycleKind::drill;
    c.path = "/operations/0";
    c.retract_z = retract_z;
    c.reference_z = reference_z;
    c.safe_z = safe_z;
    c.bottom_z = reference_z - 4.0;
    c.feed = 100.0;
    c.spindle_rpm = 1000.0;
    c.values.set(DrillField::plunging_feedrate, 100.0);
    return {OperationStart{"drill", "/operations/0", std::nullopt}, ToolChange{1, 5.0, "5 mm drill"},
            Spindle{SpindleState::cw, 1000.0}, Rapid{{10, 10, 20}}, Rapid{{10, 10, retract_z}}, c,
            DrillPoint{{10, 10}}, DrillPoint{{30, 10}}, DrillEnd{}, Rapid{{30, 10, 20}}, OperationEnd{}};
}

}  // namespace

TEST_CASE("safety: a retract plane below the reference plane is refused and nothing is written") {
    // The feed starts 2 mm above the surface, but between holes the tool rapids at Z3, 2 mm
    // inside the stock whose top is at Z5.
    const std::string op = R"("tool": 1, "referencePlane": 5, "retractPlane": 3, "safeDistance": 2, "safeDistanceIsAbsolute": true,
 "endDepth": 4, "plungingFeedrate": 100)";
    const std::filesystem::path out = test::scratch("safety-retract") / "p.nc";
    Run r = run({file_with("retract", drill_job(op)), "--machine", "fanuc", "-o", out.string()});
    CHECK(r.code == 1);
    // The job reading refuses it first, naming the key and the values.
    CHECK(r.err.find("/operations/0/retractPlane: retractPlane (Z 3.000 mm) is not above referencePlane, the stock top "
                     "(Z 5.000 mm): between holes the tool would rapid through the material") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
    // And the check on the events refuses the motion itself.
    try {
        check_safety(cycle_events(5.0, 3.0, 2.0 + 5.0), SafetyLimits{20.0, {}, {}});
        FAIL("check_safety accepted a retract plane inside the stock");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("/operations/0/retractPlane: the retract plane (Z 3.000) is below the reference "
                                         "plane (Z 5.000)") != std::string::npos);
    }
    Run s = run({file_with("retract", drill_job(op)), "--machine", "fanuc"});
    CHECK(s.out == "");
}

TEST_CASE("safety: a feed that starts below the reference plane where no hole is") {
    // An absolute safe distance under the stock top: the rapid approach ends inside the stock.
    const std::string op = R"("tool": 1, "referencePlane": 5, "retractPlane": 8, "safeDistance": 3, "safeDistanceIsAbsolute": true,
 "endDepth": 4, "plungingFeedrate": 100)";
    Run r = run({file_with("feed", drill_job(op)), "--machine", "linuxcnc"});
    CHECK(r.code == 1);
    CHECK(r.out == "");
    CHECK(r.err.find("/operations/0/safeDistance: the safe distance (Z 3.000 mm) is below referencePlane, the stock top "
                     "(Z 5.000 mm): the rapid approach would end inside the material") != std::string::npos);
    try {
        check_safety(cycle_events(5.0, 8.0, 3.0), SafetyLimits{20.0, {}, {}});
        FAIL("check_safety accepted a feed starting inside the stock");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("/operations/0: a feed starts at Z 3.000, below the reference plane (Z 5.000), at "
                                         "X10.000 Y10.000 where no hole has been drilled") != std::string::npos);
    }
}

TEST_CASE("safety: the clearance below an operation's retract plane") {
    const std::string op = R"("tool": 1, "retractPlane": 30, "endDepth": 4, "plungingFeedrate": 100)";
    Run r = run({file_with("clearance", drill_job(op)), "--machine", "fanuc"});
    CHECK(r.code == 1);
    CHECK(r.out == "");
    CHECK(r.err.find("/operations/0/retractPlane: the clearance (Z 20.000) is below the retract plane (Z 30.000)") !=
          std::string::npos);
}

TEST_CASE("safety: a hole deeper than the tool's fluteLength") {
    const std::string op = R"("tool": 1, "retractPlane": 5, "endDepth": 25, "plungingFeedrate": 100)";
    Run r = run({file_with("flute", drill_job(op, R"(, "fluteLength": 20)")), "--machine", "fanuc"});
    CHECK(r.code == 1);
    CHECK(r.out == "");
    CHECK(r.err.find("/operations/0/endDepth: the hole is 25.000 mm deep below the reference plane, but tool 1 has a "
                     "fluteLength of 20.000 mm") != std::string::npos);
    CHECK(run({file_with("flute-ok", drill_job(R"("tool": 1, "retractPlane": 5, "endDepth": 20, "plungingFeedrate": 100)",
                                               R"(, "fluteLength": 20)")),
               "--machine", "fanuc"})
              .code == 0);
    // fluteLength is a tool key of the job schema.
    CHECK(run({"schema", "job"}).out.find("\"fluteLength\"") != std::string::npos);
}

TEST_CASE("safety: a rapid below the retract plane other than the final approach") {
    auto start = [](std::vector<Event>& ev) {
        ev.push_back(OperationStart{"op", "/operations/3", std::nullopt});
        ev.push_back(ToolChange{1, 5.0, "drill"});
        ev.push_back(Rapid{{0, 0, 20}});
    };
    SafetyLimits limits{20.0, {}, {}};
    // Across at Z1, below the clearance that is this contour's retract plane.
    std::vector<Event> across;
    start(across);
    across.push_back(Rapid{{0, 0, 1}});
    across.push_back(Rapid{{50, 0, 1}});
    CHECK_THROWS_WITH_AS(check_safety(across, limits),
                         doctest::Contains("/operations/3: a rapid down to Z 1.000 at X0.000 Y0.000 goes below the retract plane"),
                         InputError);
    // The same inside a drilling cycle's operation, between holes below its retract plane.
    DrillCycle c;
    c.path = "/operations/3";
    c.retract_z = 5;
    c.reference_z = 0;
    c.safe_z = 2;
    c.bottom_z = -5;
    c.feed = 100;
    c.values.set(DrillField::plunging_feedrate, 100.0);
    std::vector<Event> drill;
    start(drill);
    drill.push_back(Rapid{{0, 0, 5}});
    drill.push_back(c);
    drill.push_back(DrillPoint{{0, 0}});
    drill.push_back(DrillEnd{});
    drill.push_back(Rapid{{0, 0, 2}});
    drill.push_back(Rapid{{10, 0, 2}});
    CHECK_THROWS_WITH_AS(check_safety(drill, limits),
                         doctest::Contains("/operations/3: a rapid from X0.000 Y0.000 to X10.000 Y0.000 runs at Z 2.000, "
                                           "below the retract plane (Z 5.000)"),
                         InputError);
    // Down at rapid where no hole is.
    std::vector<Event> down;
    start(down);
    down.push_back(Rapid{{0, 0, 5}});
    down.push_back(c);
    down.push_back(DrillPoint{{0, 0}});
    down.push_back(DrillEnd{});
    down.push_back(Rapid{{10, 0, 5}});
    down.push_back(Rapid{{10, 0, -1}});
    CHECK_THROWS_WITH_AS(check_safety(down, limits), doctest::Contains("where no hole has been drilled that deep"), InputError);
    // Back into the hole just drilled (as a deep cycle's re-approach): allowed.
    std::vector<Event> back;
    start(back);
    back.push_back(Rapid{{0, 0, 5}});
    back.push_back(c);
    back.push_back(DrillPoint{{0, 0}});
    back.push_back(DrillEnd{});
    back.push_back(Rapid{{0, 0, -4}});
    CHECK_NOTHROW(check_safety(back, limits));
}

TEST_CASE("safety: every sample passes on every machine that can run it") {
    for (const char* sample : {"plate", "bracket", "drilling", "arcs", "tapping"}) {
        Job job = read_job(test::read_file(CAMGEN_SOURCE_DIR "/samples/" + std::string(sample) + ".json"), sample);
        SafetyLimits limits{job.clearance, {}, load_machine("fanuc").longhand()};
        CAPTURE(sample);
        CHECK_NOTHROW(check_safety(expand_job(job), limits));
    }
}

TEST_CASE("safety: the table of drilled holes answers as a map of every hole's lowest Z") {
    // Holes on a 7 x 7 grid drilled in a scrambled order, some twice (the second drilling
    // shallower or deeper), with lookups of other holes between the drillings, so that the log
    // is sorted into runs of many sizes and merged; every answer is checked against a map.
    DrilledHoles holes;
    std::map<std::pair<int, int>, double> lowest;
    auto check_all = [&] {
        for (int i = 0; i < 7; ++i)
            for (int j = 0; j < 7; ++j) {
                const Vec2 at{i * 2.5, j * -1.25};
                const auto it = lowest.find({i, j});
                const std::optional<double> depth = holes.depth_at(at);
                CAPTURE(i);
                CAPTURE(j);
                REQUIRE(depth.has_value() == (it != lowest.end()));
                if (!depth) continue;
                CHECK(*depth == it->second);
                CHECK(holes.reaches(at, it->second, 1e-6));
                CHECK(holes.reaches(at, it->second + 1.0, 1e-6));
                CHECK_FALSE(holes.reaches(at, it->second - 0.01, 1e-6));
            }
    };
    unsigned state = 12345;
    for (int n = 0; n < 400; ++n) {
        state = state * 1103515245u + 12345u;
        const int cell = static_cast<int>((state >> 8) % 49), i = cell / 7, j = cell % 7;
        const double z = -static_cast<double>((state >> 16) % 40) / 4.0;
        // A cycle's pecks deepen the hole they are in, step by step.
        for (double peck = 0.0; peck >= z; peck -= 1.5) holes.drill({i * 2.5, j * -1.25}, peck);
        holes.drill({i * 2.5, j * -1.25}, z);
        const auto [it, added] = lowest.try_emplace({i, j}, z);
        it->second = std::min({it->second, z, 0.0});
        if (n % 13 == 0 || n < 20) check_all();
    }
    check_all();
    CHECK_FALSE(holes.depth_at({1.0, 1.0}));
    CHECK_FALSE(holes.reaches({1.0, 1.0}, 5.0, 1e-6));
    // The same place within rounding to the nanometre.
    CHECK(holes.depth_at({2.5 + 1e-10, -1.25}) == holes.depth_at({2.5, -1.25}));
}

namespace {
// A drilling cycle of /operations/<op> (plain drill, feed from safe_z to bottom_z) at `holes`,
// from the clearance (Z20), with its planes as the operation's.
void add_cycle(std::vector<Event>& ev, int op, double reference_z, double safe_z, double bottom_z,
               const std::vector<Vec2>& holes) {
    const std::string path = "/operations/" + std::to_string(op);
    DrillCycle c;
    c.kind = CycleKind::drill;
    c.path = path;
    c.retract_z = 5;
    c.reference_z = reference_z;
    c.safe_z = safe_z;
    c.bottom_z = bottom_z;
    c.feed = 100;
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
}  // namespace

TEST_CASE("safety: each hole of a cycle is checked, though holes of one shape are checked once") {
    const SafetyLimits limits{20.0, {}, {}};
    std::vector<Vec2> row;
    for (int i = 0; i < 1000; ++i) row.push_back({i * 5.0, 0.0});
    // A second operation feeds from Z-2, inside the stock (top Z0): only where the first drilled.
    // Its first hole passes because of the first operation's hole, not by its own feeds: the
    // next hole must be checked again, and fails.
    std::vector<Event> second;
    add_cycle(second, 0, 0.0, 2.0, -10.0, {{0, 0}});
    add_cycle(second, 1, 0.0, -2.0, -8.0, {{0, 0}, {5, 0}});
    CHECK_THROWS_WITH_AS(check_safety(second, limits),
                         doctest::Contains("/operations/1: a feed starts at Z -2.000, below the reference plane (Z "
                                           "0.000), at X5.000 Y0.000 where no hole has been drilled"),
                         InputError);
    // Every hole of the first is drilled: the second passes at each, and fails at the one hole
    // the first left out (the 701st), after 700 that passed.
    std::vector<Event> all;
    add_cycle(all, 0, 0.0, 2.0, -10.0, row);
    add_cycle(all, 1, 0.0, -2.0, -8.0, row);
    CHECK_NOTHROW(check_safety(all, limits));
    std::vector<Vec2> gap = row;
    gap.erase(gap.begin() + 700);
    std::vector<Event> missing;
    add_cycle(missing, 0, 0.0, 2.0, -10.0, gap);
    add_cycle(missing, 1, 0.0, -2.0, -8.0, row);
    CHECK_THROWS_WITH_AS(check_safety(missing, limits), doctest::Contains("at X3500.000 Y0.000 where no hole"), InputError);
    // Deeper than the first drilled: refused at the first hole too deep, whatever came before.
    std::vector<Event> deeper;
    add_cycle(deeper, 0, 0.0, 2.0, -10.0, row);
    add_cycle(deeper, 1, 0.0, 2.0, -12.0, std::vector<Vec2>(row.begin(), row.begin() + 3));
    add_cycle(deeper, 2, 0.0, -11.0, -14.0, std::vector<Vec2>(row.begin(), row.begin() + 10));
    CHECK_THROWS_WITH_AS(check_safety(deeper, limits),
                         doctest::Contains("/operations/2: a feed starts at Z -11.000, below the reference plane (Z "
                                           "0.000), at X15.000 Y0.000"),
                         InputError);
    // The holes of a cycle checked once still count as drilled: a later rapid back into one.
    std::vector<Event> back;
    add_cycle(back, 0, 0.0, 2.0, -10.0, row);
    back.push_back(OperationStart{"contour", "/operations/1", std::nullopt});
    back.push_back(Rapid{{2500, 0, 20}});
    back.push_back(Rapid{{2500, 0, -9}});
    back.push_back(Rapid{{2500, 0, 20}});
    CHECK_NOTHROW(check_safety(back, limits));
    back.push_back(Rapid{{2502.5, 0, 20}});
    back.push_back(Rapid{{2502.5, 0, -9}});
    CHECK_THROWS_WITH_AS(check_safety(back, limits), doctest::Contains("a rapid down to Z -9.000 at X2502.500"), InputError);
}

TEST_CASE("safety: on a lathe a turning operation comes down the axis to its start; a drilling one does not rapid below its plane") {
    // (An exploratory tester: a turn-profile starting at X0 was refused with the drilling rule,
    // "a rapid down to Z 1.000 at X0.000 Y0.000 goes below the retract plane".)
    const SafetyLimits lathe{20.0, {}, {}, MachineKind::lathe};
    auto events = [](std::optional<OperationPlanes> planes) {
        return std::vector<Event>{OperationStart{"op", "/operations/0", std::nullopt, {}, planes}, ToolChange{1, 0.8, "turning tool"},
                                  Spindle{SpindleState::cw, 1000.0}, Rapid{{0, 0, 20}}, Rapid{{0, 0, 1}},
                                  Linear{{0, 0, 0}, 100.0, Movement::cutting}, Linear{{14, 0, 0}, 100.0, Movement::cutting},
                                  Rapid{{22, 0, 20}}, OperationEnd{}};
    };
    CHECK_NOTHROW(check_safety(events(std::nullopt), lathe));
    CHECK_THROWS_WITH_AS(check_safety(events(OperationPlanes{5.0, 0.0, 3.0}), lathe),
                         doctest::Contains("a rapid down to Z 1.000 at X0.000 Y0.000 goes below the retract plane (Z 5.000)"),
                         InputError);
    // The shaft's finishing started on the axis posts on the three lathes.
    std::string job = test::read_file(CAMGEN_SOURCE_DIR "/samples/shaft-control.json");
    const std::size_t at = job.find("\"type\": \"turn-profile\"");
    REQUIRE(at != std::string::npos);
    const std::size_t start = job.find("\"start\": [", at);
    REQUIRE(start != std::string::npos);
    job.replace(start, job.find(']', start) + 1 - start, "\"start\": [0, 0]");
    for (const char* m : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        CAPTURE(m);
        const Run r = run({file_with("axis-start", job), "--machine", m, "-q"});
        CHECK(r.err == "");
        CHECK(r.code == 0);
    }
}

}  // namespace test_safety
