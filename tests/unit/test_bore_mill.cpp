// Bore milling (issue 11, part 7): the geometry of the milled holes as every machine's program
// makes it, read back with camgen's reader (diameter, depth, helix pitch, direction, no long
// feeds through air), the rings and turns, the movement kinds, and bad input.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include <doctest/doctest.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/post/safety.hpp"
#include "camgen/reader/reader.hpp"
#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_bore_mill {

namespace fs = std::filesystem;
using namespace camgen;

namespace {

constexpr double two_pi = 2 * std::numbers::pi;

// A job milling bores of diameter `bore` with a `tool` mm end mill; `keys` add to or override
// the operation's keys (heights: stock top at 0, safe distance 1, retract plane 5).
std::string bore_job(double bore, double tool, const std::string& keys, const std::string& spindle = "cw") {
    return fmt::format(R"({{"name": "t", "units": "mm", "clearance": 10,
  "tools": [{{"number": 1, "type": "end-mill", "diameter": {}, "rpm": 3000, "direction": "{}"}}],
  "operations": [{{"type": "bore-mill", "tool": 1, "diameter": {}, "retractPlane": 5, "safeDistance": 1,
    "feed": 500, {}}}]}})",
                       tool, spindle, bore, keys);
}

// The signed angle (radians, counter-clockwise > 0) a move turns about `c`.
double turned(const camgen::Step& s, Vec2 c) {
    if (s.arc) return s.arc->direction == ArcDirection::ccw ? s.arc->sweep : -s.arc->sweep;
    const double a = std::atan2(s.from.y - c.y, s.from.x - c.x), b = std::atan2(s.to.y - c.y, s.to.x - c.x);
    double d = b - a;
    while (d > std::numbers::pi) d -= two_pi;
    while (d <= -std::numbers::pi) d += two_pi;
    return d;
}

double radius_of(const Vec3& p, Vec2 c) { return std::hypot(p.x - c.x, p.y - c.y); }

// Points along a feed move: the ends of a line and its middle, 64 points along an arc.
std::vector<Vec3> points_of(const camgen::Step& s) {
    std::vector<Vec3> pts;
    if (s.arc) {
        for (int i = 0; i <= 64; ++i) pts.push_back(point_on_arc(*s.arc, i / 64.0));
    } else {
        pts = {s.from, {(s.from.x + s.to.x) / 2, (s.from.y + s.to.y) / 2, (s.from.z + s.to.z) / 2}, s.to};
    }
    return pts;
}

// How much of a feed move runs above the stock top (mm), measured along 256 pieces.
double air_length(const camgen::Step& s, double stock_top) {
    auto at = [&](double t) {
        return s.arc ? point_on_arc(*s.arc, t)
                     : Vec3{s.from.x + (s.to.x - s.from.x) * t, s.from.y + (s.to.y - s.from.y) * t,
                            s.from.z + (s.to.z - s.from.z) * t};
    };
    double air = 0;
    Vec3 a = at(0);
    for (int i = 1; i <= 256; ++i) {
        const Vec3 b = at(i / 256.0);
        if (a.z > stock_top + 1e-6 && b.z > stock_top + 1e-6) air += std::hypot(b.x - a.x, b.y - a.y, b.z - a.z);
        a = b;
    }
    return air;
}

// What one hole's moves make, measured.
struct Measured {
    double bottom_radius = 0.0;   // largest tool centre radius at the lowest Z
    double largest_radius = 0.0;  // largest tool centre radius of any feed point
    double lowest_z = 1e9;
    double helix_drop = 0.0;      // Z the helices go down below the stock top
    double helix_turns = 0.0;     // ... and the turns they make doing it
    bool helix_one_way = true;    // every move of the helices and circles turns the same way
    double turn_sign = 0.0;       // +1 counter-clockwise, -1 clockwise
    double longest_air_feed = 0;  // the longest part of a feed move above the stock top
    double highest_feed_start = -1e9;
    double chord_error = 0.0;     // how far the middle of a straight piece of a circle is inside it
};

// Measures the feed moves of `trace` around each of `holes` (each move belongs to the nearest).
std::vector<Measured> measure(const Trace& trace, const std::vector<Vec2>& holes, double stock_top, double bottom,
                              const std::vector<double>& ring_radii) {
    std::vector<Measured> m(holes.size());
    for (const camgen::Step& s : trace.steps) {
        if (s.kind != StepKind::feed) continue;
        std::size_t k = 0;
        for (std::size_t i = 1; i < holes.size(); ++i)
            if (radius_of(s.to, holes[i]) < radius_of(s.to, holes[k])) k = i;
        Measured& h = m[k];
        const Vec2 c = holes[k];
        h.highest_feed_start = std::max(h.highest_feed_start, s.from.z);
        for (const Vec3& p : points_of(s)) {
            h.lowest_z = std::min(h.lowest_z, p.z);
            h.largest_radius = std::max(h.largest_radius, radius_of(p, c));
            if (std::abs(p.z - bottom) < 1e-6) h.bottom_radius = std::max(h.bottom_radius, radius_of(p, c));
        }
        h.longest_air_feed = std::max(h.longest_air_feed, air_length(s, stock_top));
        // The helices and circles: moves that keep the distance from the centre.
        const bool on_circle = std::abs(radius_of(s.from, c) - radius_of(s.to, c)) < 0.002 && radius_of(s.to, c) > 0.01;
        if (!on_circle) continue;
        const double a = turned(s, c);
        const double sign = a > 0 ? 1.0 : -1.0;
        if (h.turn_sign == 0) h.turn_sign = sign;
        if (sign != h.turn_sign) h.helix_one_way = false;
        if (!s.arc) {
            // A straight piece of a circle (a helix or circle broken into lines): its middle is
            // inside the circle by at most the chord tolerance.
            const Vec3 mid = points_of(s)[1];
            const double r = *std::min_element(ring_radii.begin(), ring_radii.end(), [&](double x, double y) {
                return std::abs(x - radius_of(s.to, c)) < std::abs(y - radius_of(s.to, c));
            });
            h.chord_error = std::max(h.chord_error, r - radius_of(mid, c));
        }
        if (s.to.z < s.from.z - 1e-9 && s.from.z <= stock_top + 1e-6) {
            h.helix_drop += s.from.z - s.to.z;
            h.helix_turns += std::abs(a) / two_pi;
        }
    }
    return m;
}

// Posts `job_json` for every machine, reads each program back and checks every hole.
// `holes`: the hole centres; the job's stock top is Z 0 and its safe distance 1.
void check_bores(const std::string& job_json, const std::vector<Vec2>& holes, double bore, double tool, double depth,
                 double pitch, double finishing_allowance, double expected_sign) {
    const Job job = read_job(job_json, "bores.json");
    const auto& op = std::get<BoreMillOp>(job.operations.at(0));
    const std::vector<double> rings = [&] {
        std::vector<double> r = ring_radii(bore, tool, op.step_over, finishing_allowance);
        r.push_back((bore - tool) / 2);
        return r;
    }();
    const int turns = static_cast<int>(std::ceil(depth / pitch - 1e-9));
    int machines = 0;
    for (const auto& [name, description] : list_machines()) {
        CAPTURE(name);
        const Machine machine = load_machine(name);
        if (machine.kind != MachineKind::mill) continue;  // a lathe refuses a mill job (tested with the lathes)
        std::string program;
        try {
            program = test::post_program(job, machine);
        } catch (const InputError& e) {
            // nccad's machines have no M4: the only refusal allowed.
            CHECK(std::string(e.what()).find("cannot run the spindle counter-clockwise") != std::string::npos);
            continue;
        }
        const Trace trace = trace_program(read_program(program, machine, "bores"), machine);
        const double resolution = 0.001 + (machine.units == Units::inch ? 0.0000254 : 0.0);
        for (const Measured& h : measure(trace, holes, 0.0, -depth, rings)) {
            // The cut edge: tool centre radius (D - d) / 2 at the bottom, so the hole is D.
            CHECK(std::abs(2 * h.bottom_radius + tool - bore) <= 2 * resolution);
            CHECK(h.largest_radius <= (bore - tool) / 2 + resolution);  // never beyond the wall
            CHECK(std::abs(h.lowest_z + depth) <= resolution);
            // Whole turns per ring, at most `pitch` each: exactly the depth over the turns.
            const double rings_cut = static_cast<double>(rings.size() - 1);
            CHECK(std::abs(h.helix_drop - depth * rings_cut) <= 0.01);
            CHECK(std::abs(h.helix_turns - turns * rings_cut) <= 0.01);
            CHECK(h.helix_drop / h.helix_turns <= pitch + 1e-3);
            CHECK(h.helix_one_way);
            CHECK(h.turn_sign == expected_sign);
            // No feed through air longer than the safe distance plus the lead to the ring.
            CHECK(h.longest_air_feed <= 1.0 + (bore - tool) / 2 + resolution);
            CHECK(h.highest_feed_start <= 1.0 + resolution);  // rapids down to the safe distance
            CHECK(h.chord_error <= machine.arcs.chord_tolerance + resolution);
        }
        ++machines;
    }
    CHECK(machines >= (job.tools.begin()->second.direction == SpindleDirection::cw ? 7 : 5));
}

}  // namespace

TEST_CASE("bore-mill: ring radii clear the centre, overlap, step at most stepOver and end at the wall") {
    for (double tool : {3.0, 6.0, 10.0})
        for (double bore : {3.5, 8.0, 15.0, 19.9, 20.0, 40.0, 63.0})
            for (double step : {0.2, 0.5, 1.0})
                for (double allowance : {0.0, 0.2}) {
                    if (bore <= tool + 2 * allowance) continue;
                    CAPTURE(tool);
                    CAPTURE(bore);
                    CAPTURE(step);
                    const std::vector<double> r = ring_radii(bore, tool, step, allowance);
                    REQUIRE(!r.empty());
                    CHECK(r.front() <= tool / 2);                               // the first ring's tool covers the centre
                    CHECK(r.front() > 0);
                    CHECK(r.back() == (bore - tool) / 2 - allowance);          // the last at the wall (less the allowance)
                    for (std::size_t i = 1; i < r.size(); ++i) {
                        CHECK(r[i] > r[i - 1]);
                        CHECK(r[i] - r[i - 1] <= step * tool + 1e-9);           // step over at most stepOver x tool
                    }
                }
    CHECK(ring_radii(15, 10, 0.5, 0) == std::vector<double>{2.5});
    CHECK(ring_radii(40, 10, 0.5, 0).size() == 4);  // 4, 7.67, 11.33, 15
}

TEST_CASE("bore-mill: whole helix turns of at most the pitch, ending at the depth") {
    CHECK(helix_turns(12, 2) == 6);
    CHECK(helix_turns(12.1, 2) == 7);
    CHECK(helix_turns(0.5, 2) == 1);
    CHECK(helix_turns(6, 1.5) == 4);
    for (double drop : {0.3, 1.0, 4.2, 12.0, 25.4})
        for (double pitch : {0.1, 0.7, 1.5, 3.0}) {
            const int n = helix_turns(drop, pitch);
            CHECK(drop / n <= pitch + 1e-12);
            if (n > 1) CHECK(drop / (n - 1) > pitch);
        }
}

TEST_CASE("bore-mill: samples/bores.json on every machine mills 40 and 15 mm holes, read back") {
    const std::string sample = test::read_file(CAMGEN_SOURCE_DIR "/samples/bores.json");
    const Job job = read_job(sample, "bores.json");
    // The first operation: one bore of 40, 12 deep, pitch 2, finished; in a job of its own.
    nlohmann::json j = nlohmann::json::parse(sample);
    nlohmann::json first = j, second = j;
    first["operations"].erase(1);
    second["operations"].erase(0);
    check_bores(first.dump(), {{60, 50}}, 40, 10, 12, 2, 0.2, +1);
    std::vector<Vec2> bolt;
    for (int i = 0; i < 6; ++i) {
        const double a = (30 + 60 * i) * std::numbers::pi / 180;
        bolt.push_back({60 + 35 * std::cos(a), 50 + 35 * std::sin(a)});
    }
    check_bores(second.dump(), bolt, 15, 10, 6, 1.5, 0, +1);
}

TEST_CASE("bore-mill: conventional milling turns clockwise with M3, climb clockwise with M4") {
    const std::vector<Vec2> holes{{0, 0}, {30, 0}};
    const std::string where = R"("line": {"start": [0, 0], "end": [30, 0], "count": 2})";
    check_bores(bore_job(12, 6, R"("endDepth": 3.3, "pitch": 0.8, "direction": "conventional", )" + where), holes, 12, 6,
                3.3, 0.8, 0, -1);
    check_bores(bore_job(12, 6, R"("endDepth": 3.3, "pitch": 0.8, )" + where, "ccw"), holes, 12, 6, 3.3, 0.8, 0, -1);
    check_bores(bore_job(12, 6, R"("endDepth": 3.3, "pitch": 0.8, "direction": "conventional", )" + where, "ccw"), holes,
                12, 6, 3.3, 0.8, 0, +1);
    // A bore wider than twice the tool, with a finishing circle: three rings and the finish.
    check_bores(bore_job(25, 6, R"("endDepth": 2, "pitch": 1, "finishingAllowance": 0.3, "stepOver": 0.6, )" + where),
                holes, 25, 6, 2, 1, 0.3, +1);
}

TEST_CASE("bore-mill: the movements: lead-in, ramp, cutting, finishing, lead-out; feeds by movement") {
    const Job job = read_job(bore_job(20, 6, R"("endDepth": 5, "pitch": 2, "finishingAllowance": 0.25, "stepOver": 0.8,
      "rampFeed": 300, "plungeFeed": 200, "finishingFeed": 150, "holes": [[0, 0]])"),
                             "t.json");
    std::vector<std::pair<Movement, double>> kinds;  // each feed move's kind and feed
    int ramps = 0, helix_turns_seen = 0;
    for (const Event& e : expand_job(job)) {
        if (const auto* l = std::get_if<Linear>(&e)) kinds.emplace_back(l->movement, l->feed);
        if (const auto* a = std::get_if<Arc>(&e)) {
            kinds.emplace_back(a->movement, a->feed);
            if (a->movement == Movement::ramp) {
                ++ramps;
                helix_turns_seen = a->turns + 1;
                CHECK(a->to.z == -5);
                CHECK(a->direction == ArcDirection::ccw);  // climb, M3
            }
        }
    }
    // (20 - 6) / 2 - 0.25 = 6.75 > 3: two rings (2.4 and 6.75, 4.35 apart, at most 0.8 x 6), each
    // lead-in, ramp, circle, lead-out.
    CHECK(ramps == 2);
    CHECK(helix_turns_seen == 3);  // 5 / 2 rounded up
    const std::vector<std::pair<Movement, double>> ring = {
        {Movement::lead_in, 200}, {Movement::ramp, 300}, {Movement::cutting, 500}};
    REQUIRE(kinds.size() == 3 + 1 + 3 + 2 + 1);
    CHECK(std::equal(ring.begin(), ring.end(), kinds.begin()));
    CHECK(kinds[3] == std::pair{Movement::lead_out, 500.0});
    CHECK(std::equal(ring.begin(), ring.end(), kinds.begin() + 4));
    CHECK(kinds[7] == std::pair{Movement::lead_in, 150.0});
    CHECK(kinds[8] == std::pair{Movement::finishing, 150.0});
    CHECK(kinds[9] == std::pair{Movement::lead_out, 500.0});
}

TEST_CASE("bore-mill: the operation's heights reach the safety checks") {
    // The rapid down to the safe distance above each hole passes; one below it is refused.
    const Job job = read_job(bore_job(12, 6, R"("endDepth": 3, "pitch": 1, "holes": [[0, 0], [20, 0]])"), "t.json");
    std::vector<Event> events = expand_job(job);
    const SafetyLimits limits{.clearance = 10.0, .flute_lengths = {}, .longhand = {}};
    CHECK_NOTHROW(check_safety(events, limits));
    auto safe = std::find_if(events.begin(), events.end(), [](const Event& e) {
        const auto* r = std::get_if<Rapid>(&e);
        return r && r->to.z == 1.0;
    });
    REQUIRE(safe != events.end());
    std::get<Rapid>(*safe).to.z = 0.5;
    try {
        check_safety(events, limits);
        FAIL("a rapid below the safe distance passed");
    } catch (const InputError& e) {
        CHECK(e.path() == "/operations/0");
        CHECK(std::string(e.what()).find("below the retract plane") != std::string::npos);
    }
}

TEST_CASE("bore-mill: bad input names the JSON path, exits 1 and writes nothing") {
    const fs::path dir = test::scratch("bore-mill-errors");
    struct Case {
        std::string json;
        std::string path;
        std::vector<std::string> detail;
    };
    const std::vector<Case> cases = {
        {bore_job(10, 10, R"("endDepth": 3, "pitch": 1, "holes": [[0, 0]])"), "/operations/0/diameter",
         {"the bore (diameter 10.000 mm) is not larger than tool 1 (diameter 10.000 mm, /tools/0)"}},
        {bore_job(8, 10, R"("endDepth": 3, "pitch": 1, "holes": [[0, 0]])"), "/operations/0/diameter",
         {"diameter 8.000 mm", "diameter 10.000 mm"}},
        {bore_job(0, 10, R"("endDepth": 3, "pitch": 1, "holes": [[0, 0]])"), "/operations/0/diameter",
         {"diameter must be > 0"}},
        {bore_job(-12, 6, R"("endDepth": 3, "pitch": 1, "holes": [[0, 0]])"), "/operations/0/diameter",
         {"diameter must be > 0"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 0, "holes": [[0, 0]])"), "/operations/0/pitch", {"pitch must be > 0"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": -1, "holes": [[0, 0]])"), "/operations/0/pitch", {"pitch must be > 0"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 0.00001, "holes": [[0, 0]])"), "/operations/0/pitch",
         {"more than 100000 helix turns a hole"}},
        {bore_job(2000, 6, R"("endDepth": 3, "pitch": 0.005, "holes": [[0, 0]])"), "/operations/0/pitch",
         {"more than 100000 helix turns a hole"}},  // 333 rings of 600 turns
        {bore_job(900000, 1, R"("endDepth": 3, "pitch": 1, "stepOver": 0.001, "holes": [[0, 0]])"),
         "/operations/0/stepOver", {"more than 100000 rings"}},
        {bore_job(12, 6, R"("endDepth": -3, "pitch": 1, "holes": [[0, 0]])"), "/operations/0/endDepth",
         {"a relative endDepth must be > 0"}},
        {bore_job(12, 6, R"("endDepth": 0.5, "endDepthIsAbsolute": true, "pitch": 1, "holes": [[0, 0]])"),
         "/operations/0/endDepth", {"endDepth is not below referencePlane, the stock top (bore bottom at Z 0.500 mm"}},
        {bore_job(12, 6, R"("endDepth": 3, "referencePlane": 4.5, "pitch": 1, "holes": [[0, 0]])"),
         "/operations/0/retractPlane", {"retractPlane is below the safe distance"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 1, "finishingAllowance": 3, "holes": [[0, 0]])"),
         "/operations/0/finishingAllowance", {"less than half the difference"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 1, "stepOver": 1.5, "holes": [[0, 0]])"), "/operations/0/stepOver",
         {"stepOver must be > 0 and at most 1"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 1, "direction": "cw", "holes": [[0, 0]])"),
         "/operations/0/direction", {"\"cw\" is not one of \"climb\" or \"conventional\""}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 1, "rampFeed": 0, "holes": [[0, 0]])"), "/operations/0/rampFeed",
         {"rampFeed must be > 0"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 1)"), "/operations/0",
         {"a bore-mill operation needs holes: give at least one of holes, grid, boltCircle, line or drawing (a DXF drawing's circles and points)"}},
        {bore_job(12, 6, R"("endDepth": 3, "pitch": 1, "holes": [])"), "/operations/0/holes",
         {"a bore-mill operation needs at least one hole"}},
    };
    for (const Case& c : cases) {
        CAPTURE(c.json);
        const fs::path job = dir / "job.json";
        std::ofstream(job) << c.json;
        const fs::path out = dir / "out.ngc";
        fs::remove(out);
        const test::Run r = test::run({job.string(), "--machine", "linuxcnc", "-o", out.string()});
        CHECK(r.code == 1);
        CHECK(r.err.find(c.path + ":") != std::string::npos);
        for (const std::string& d : c.detail) CHECK(r.err.find(d) != std::string::npos);
        CHECK(!fs::exists(out));
    }
    // A tool too short for the bore's depth.
    const std::string shallow = test::replace_once(bore_job(12, 6, R"("endDepth": 8, "pitch": 1, "holes": [[0, 0]])"),
                                                   R"("rpm": 3000)", R"("rpm": 3000, "fluteLength": 5)");
    std::ofstream(dir / "job.json") << shallow;
    const test::Run r = test::run({(dir / "job.json").string(), "--machine", "linuxcnc", "-o", (dir / "out.ngc").string()});
    CHECK(r.code == 1);
    CHECK(r.err.find("/operations/0/endDepth: the bore is 8.000 mm deep") != std::string::npos);
    CHECK(!fs::exists(dir / "out.ngc"));
}

TEST_CASE("hole sources: drill and bore-mill read them alike, each naming its own type") {
    auto error_of = [](const std::string& json) -> std::string {
        try {
            read_job(json, "t.json");
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    const std::string header = R"({"clearance": 10, "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 1000}],
      "operations": [)";
    const std::string drill = R"({"type": "drill", "tool": 1, "endDepth": 3, "plungingFeedrate": 100, )";
    const std::string bore = R"({"type": "bore-mill", "tool": 1, "endDepth": 3, "diameter": 10, "pitch": 1, "feed": 100, )";
    CHECK(error_of(header + drill + R"("comment": ""}]})").find(
              "/operations/0: a drill operation needs holes: give at least one of holes, grid, boltCircle, line or drawing (a DXF drawing's circles and points)") !=
          std::string::npos);
    CHECK(error_of(header + drill + R"("holes": []}]})").find(
              "/operations/0/holes: holes is empty: a drill operation needs at least one hole") != std::string::npos);
    CHECK(error_of(header + bore + R"("holes": [[0, 0]], "grid": {"origin": [0, 0], "countX": 0, "countY": 1,
      "spacingX": 1, "spacingY": 1}}]})")
              .find("/operations/0/grid/countX: countX must be 1 or more") != std::string::npos);
    // The same sources give the same holes in the same order, shortest order included.
    const std::string sources = R"("order": "shortest", "holes": [[100, 0], [0, 0]],
      "grid": {"origin": [10, 10], "countX": 2, "countY": 2, "spacingX": 30, "spacingY": 20, "rotation": 15},
      "boltCircle": {"centre": [50, 50], "radius": 20, "count": 5, "startAngle": 10},
      "line": {"start": [0, 80], "end": [90, 80], "count": 4}})";
    const Job job = read_job(header + drill + sources + ", " + bore + sources + "]}", "t.json");
    const auto& d = std::get<DrillOp>(job.operations.at(0));
    const auto& b = std::get<BoreMillOp>(job.operations.at(1));
    CHECK(d.holes.size() == 2 + 4 + 5 + 4);
    CHECK(b.holes == d.holes);
    CHECK(visit_order(b) == visit_order(d));
    CHECK(visit_order(b) != b.holes);  // reordered
}

TEST_CASE("verify follows a helix of a thousand turns turn by turn, and finds a block on the wrong turn") {
    // The comparison looked at every turn of the job's helix for every point of the program: a
    // bore at pitch 0.0006 mm (a fuzz_mutated finding) ran verify for minutes. It now looks at
    // the turns after the last match and at the point's height; it must still place each
    // point on its own turn.
    const std::string job = R"({"name": "h", "units": "mm", "clearance": 10,
      "tools": [{"number": 1, "type": "end-mill", "diameter": 10, "rpm": 4000}],
      "operations": [{"type": "bore-mill", "tool": 1, "diameter": 40, "retractPlane": 5, "safeDistance": 1,
        "endDepth": 12, "pitch": 0.01, "feed": 600, "holes": [[60, 50]]}]})";
    const std::string file = test::file_with("helix-many-turns", job);
    const std::string program = (test::scratch("helix-many-turns-out") / "h.nc").string();
    REQUIRE(test::run({file, "--machine", "grbl", "-o", program, "-q"}).code == 0);
    const test::Run good = test::run({"verify", program, "--machine", "grbl", "--job", file});
    CHECK_MESSAGE(good.code == 0, good.err);
    // One arc block in the middle lifted by half a millimetre (fifty turns up): a mismatch.
    std::vector<std::string> lines = test::lines_of(test::read_file(program));
    REQUIRE(lines.size() > 4000);
    std::size_t mid = lines.size() / 2;
    while (mid < lines.size() && lines[mid].find("Z") == std::string::npos) ++mid;
    REQUIRE(mid < lines.size());
    const std::size_t z = lines[mid].find('Z');
    std::size_t end = lines[mid].find(' ', z);
    const double value = std::stod(lines[mid].substr(z + 1, end == std::string::npos ? std::string::npos : end - z - 1));
    lines[mid] = lines[mid].substr(0, z + 1) + fmt::format("{:.3f}", value + 0.5) +
                 (end == std::string::npos ? std::string() : lines[mid].substr(end));
    std::ofstream(program) << fmt::format("{}\n", fmt::join(lines, "\n"));
    const test::Run bad = test::run({"verify", program, "--machine", "grbl", "--job", file});
    CHECK(bad.code == 1);
    // The first difference is at the lifted block (the turn it is on, which may begin a block
    // or two before it): the moves before it were placed on their own turns.
    const std::string tag = fmt::format("MISMATCH {}:", program);
    const std::size_t at = bad.out.find(tag);
    REQUIRE(at != std::string::npos);
    const int line = std::stoi(bad.out.substr(at + tag.size()));
    CAPTURE(mid + 1);
    CHECK(std::abs(line - static_cast<int>(mid + 1)) <= 3);
}

TEST_CASE("verify finds a steep helix of a tiny radius written as chords, although rounding turns their angles") {
    // A 0.07 mm tool in a 41 mm bore: the innermost ring is a helix of radius 0.028 mm at 3 mm a
    // turn, which kosy writes as chords. A rounded X or Y turns a chord end by degrees, and at
    // that pitch the point at the same angle is 0.0086 mm away while the nearest is 0.005 mm:
    // verify refused camgen's own program (a fuzz_mutated finding).
    const std::string job = R"({"name": "b", "units": "mm", "clearance": 13,
      "tools": [{"number": 1, "type": "end-mill", "diameter": 0.0705777591678899, "rpm": 4000}],
      "operations": [{"type": "bore-mill", "tool": 1, "diameter": 41.3125, "retractPlane": 5, "safeDistance": 1.117,
        "endDepth": 12, "pitch": 3.25, "feed": 600, "rampFeed": 400, "plungeFeed": 300, "finishingAllowance": 0.2,
        "finishingFeed": 400, "holes": [[60, 50]]}]})";
    const std::string file = test::file_with("steep-tiny-helix", job);
    for (const std::string machine : {"kosy", "wabeco", "grbl", "heidenhain"}) {
        CAPTURE(machine);
        const std::string program = (test::scratch("steep-tiny-helix-out") / "b.nc").string();
        const test::Run post = test::run({file, "--machine", machine, "-o", program, "-q"});
        REQUIRE_MESSAGE(post.code == 0, post.err);
        const test::Run verify = test::run({"verify", program, "--machine", machine, "--job", file});
        CHECK_MESSAGE(verify.code == 0, verify.out);
    }
}

TEST_CASE("a helix that moves less than the machine's resolution a turn is refused, naming the operation (fuzz finding 12)") {
    // A bore at pitch 0.00043 mm: 28,160 turns, written on grbl as full circles at one Z
    // (Z-12.000 several times at F400, then the bottom circle at F600), which the read-back
    // could not tell apart from the job's.
    auto refusal = [](const std::string& job, const std::string& machine) {
        try {
            (void)test::post_job(job, machine);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string bore = bore_job(20, 10, R"("endDepth": 12, "pitch": 0.00042614590919896715, "holes": [[60, 53.3125]])");
    for (const std::string machine : {"grbl", "fanuc", "sinumerik", "kosy", "wabeco", "heidenhain"}) {
        CAPTURE(machine);
        CHECK(refusal(bore, machine) ==
              "/operations/0: a helix of 28160 turns moves 0.000426 mm along its axis a turn, below the resolution of "
              "machine " + machine + " (0.001 mm): turns would be written at one height, the tool circling in place (bore-mill "
              "and a path's helix: a larger pitch; a contour's helix ramp: a larger angle or radius)");
        // One unit a turn is a helix (3 mm at 0.001: 3,000 turns).
        CHECK(refusal(bore_job(20, 10, R"("endDepth": 3, "pitch": 0.001, "holes": [[0, 0]])"), machine) == "");
    }
    CHECK(refusal(bore, "linuxcnc") == "");  // 4 decimals
    // A path's helix and a contour's helix ramp, the same way.
    const std::string path = R"({"clearance": 10, "tools": [{"number": 1, "type": "end-mill", "diameter": 4, "rpm": 4000}],
      "operations": [{"type": "path", "tool": 1, "z": -1, "feed": 300, "plungeFeed": 100, "start": [10, 0],
        "path": [{"helix": {"centre": [10, 2], "direction": "ccw", "turns": 3000, "pitch": 0.0005}}]}]})";
    CHECK(refusal(path, "fanuc").starts_with("/operations/0: a helix of 3000 turns moves 0.0005 mm along its axis a turn"));
    const std::string contour = R"({"clearance": 10, "tools": [{"number": 1, "type": "end-mill", "diameter": 4, "rpm": 4000}],
      "operations": [{"type": "contour", "tool": 1, "endDepth": 1, "feed": 300, "plungeFeed": 100, "side": "outside",
        "retractPlane": 5, "safeDistance": 1, "ramp": {"type": "helix", "angle": 0.09, "radius": 0.05},
        "start": [0, 0], "path": [{"line": [20, 0]}, {"line": [20, 20]}, {"line": [0, 20]}, {"line": [0, 0]}]}]})";
    CHECK(refusal(contour, "grbl").starts_with("/operations/0: a helix of "));
    CHECK(refusal(contour, "linuxcnc") == "");
}

TEST_CASE("verify follows a helix of a tiny radius whose centre was rounded, and still finds a turn at the wrong depth") {
    // A 0.032 mm tool: the first ring is a helix of radius 0.013 mm about Y32.5745, written
    // about J-0.001 from Y32.575. Its points lie 0.0005 mm off the job's, but 2.2 degrees round
    // the turn, 0.009 mm of height at 1.5 mm a turn: the nearest point comes after the one at
    // the same angle, which lay before where the last sample was found, so verify skipped it and
    // refused camgen's own program on grbl, fanuc and sinumerik (fuzz finding 14).
    const std::string job = R"({"name": "b", "units": "mm", "clearance": 11,
      "tools": [{"number": 1, "type": "end-mill", "diameter": 0.03166325390338898, "rpm": 4000}],
      "operations": [{"type": "bore-mill", "tool": 1, "diameter": 0.2, "retractPlane": 5, "safeDistance": 1,
        "endDepth": 6, "pitch": 1.5, "feed": 600, "rampFeed": 400, "plungeFeed": 300,
        "holes": [[93.01440132878666, 32.5745]]}]})";
    for (const std::string machine : {"grbl", "fanuc", "sinumerik", "linuxcnc", "kosy", "wabeco", "heidenhain"}) {
        CAPTURE(machine);
        const std::string program = test::post_job(job, machine).text;
        CHECK(test::round_trip(job, program, machine) == "");
    }
    // A turn ending 0.2 mm too deep is found. (0.1 mm is not: a helix this narrow is nearly a
    // line, and at 1.6 mm a turn instead of 1.5 its points stay within 0.005 mm of the job's,
    // inside the 0.008 mm allowed on arcs.)
    const std::string grbl = test::post_job(job, "grbl").text;
    const std::string wrong = test::replace_once(grbl, "X93.027 Y32.575 Z-3 I-0.013", "X93.027 Y32.575 Z-3.2 I-0.013");
    CHECK(test::round_trip(job, wrong, "grbl").find("line 13: the job's ccw arc") == 0);
}

namespace {
const std::vector<std::string> mills = {"fanuc", "grbl", "linuxcnc", "sinumerik", "heidenhain", "kosy", "wabeco"};
}  // namespace

TEST_CASE("verify accepts a bore a hair wider than its tool, written as one plunge under minRadius, on every mill") {
    // Issue 24, item 12: a 10.002 mm bore with a 10 mm tool is a helix of radius 0.001 mm, and
    // under minRadius (0.002 mm) the post writes it as one straight plunge and the bottom circle
    // as nothing, as the README's arc rules say; verify compared them with the job's helix and
    // circle and refused camgen's own program. Radii around the rule and the resolution
    // (0.001 mm; linuxcnc 0.0001), on a centre on the grid and one off it, at a fine pitch and
    // a coarse one, with a ramp, a cutting and a plunge feed of their own.
    for (const std::string& machine : mills) {
        for (const double bore : {10.0002, 10.001, 10.002, 10.0021, 10.0039, 10.0041, 10.0045, 10.006}) {
            for (const std::string hole : {"[20, 30]", "[20.0004, 30.0007]"}) {
                for (const double pitch : {0.1, 1.5}) {
                    CAPTURE(machine);
                    CAPTURE(bore);
                    CAPTURE(hole);
                    CAPTURE(pitch);
                    const std::string job = bore_job(bore, 10, fmt::format(R"("rampFeed": 400, "plungeFeed": 300, "endDepth": 6,
                        "pitch": {}, "holes": [{}])", pitch, hole));
                    const std::string program = test::post_job(job, machine).text;
                    CHECK(test::round_trip(job, program, machine) == "");
                }
            }
        }
    }
}

TEST_CASE("verify at the minRadius boundary: just below it one plunge, at and just above it arcs, both accepted") {
    // The machine's minRadius set to the helix's radius exactly and one step either side of it:
    // the post and verify ask the same rule (written_as_one_line), so the program and the job
    // agree on which side of it the arc is.
    const std::string job_text = bore_job(10.004, 10, R"("rampFeed": 400, "plungeFeed": 300, "endDepth": 6, "pitch": 1.5,
        "holes": [[20.0004, 30.0007]])");
    const Job job = read_job(job_text, "job.json");
    // The radius as the post resolves it: the ring's (bore - tool) / 2 added to the hole's X,
    // less the hole's X.
    const double r = std::abs((20.0004 + (10.004 - 10.0) / 2.0) - 20.0004);
    for (const std::string& machine : mills) {
        struct Case {
            double min_radius;
            bool plunge;
        };
        for (const Case c : {Case{std::nextafter(r, 1.0), true}, Case{r, false}, Case{std::nextafter(r, 0.0), false}}) {
            CAPTURE(machine);
            CAPTURE(c.min_radius - r);
            Machine m = load_machine(machine);
            m.arcs.min_radius = c.min_radius;
            const std::string program = test::post_program(job, m);
            // One plunge: no arc block and no chord between Z0 and the bottom.
            const bool helix_written = program.find("Z-1.5") != std::string::npos || program.find("Z-0.75") != std::string::npos;
            CHECK(helix_written != c.plunge);
            CHECK(test::round_trip_machine(job, program, m) == "");
        }
    }
}

TEST_CASE("verify still refuses a program that differs from a bore written as one plunge") {
    // The job's helix under minRadius is compared as the plunge the post writes, allowed no
    // farther off than the helix strays from it: the program of a bore 0.02 mm beside it, one
    // 0.5 mm shallower, one with the ramp at another feed, or the real helix of a wider bore, is
    // a mismatch (and the other way round).
    auto bore = [](double diameter, const std::string& hole, double depth, double ramp_feed) {
        return bore_job(diameter, 10, fmt::format(R"("rampFeed": {}, "plungeFeed": 300, "endDepth": {}, "pitch": 1.5,
            "holes": [{}])", ramp_feed, depth, hole));
    };
    const std::string job = bore(10.002, "[20, 30]", 6, 400);
    for (const std::string& machine : mills) {
        CAPTURE(machine);
        const std::string program = test::post_job(job, machine).text;
        REQUIRE(test::round_trip(job, program, machine) == "");
        for (const std::string& other : {bore(10.002, "[20.02, 30]", 6, 400), bore(10.002, "[20, 30]", 5.5, 400),
                                         bore(10.002, "[20, 30]", 6, 300), bore(10.1, "[20, 30]", 6, 400)}) {
            CAPTURE(other);
            const std::string different = test::post_job(other, machine).text;
            CHECK(test::round_trip(job, different, machine).find("line ") == 0);
            CHECK(test::round_trip(other, program, machine).find("line ") == 0);
        }
    }
}

}  // namespace test_bore_mill
