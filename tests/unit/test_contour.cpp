// The contour operation, tested by its geometry: the tool centre's distance from the profile,
// the depth of each pass, the tabs, where compensation changes, how long the tool feeds
// through air; and each bad input with its JSON path.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/analysis/stats.hpp"
#include "camgen/geometry/offset.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_contour {

using namespace camgen;
using namespace camgen::test;

namespace {

// A move of the tool centre, with the Z it starts at.
struct Move {
    Vec3 from, to;
    std::optional<Vec2> centre;
    ArcDirection direction = ArcDirection::ccw;
    Movement movement = Movement::cutting;
    bool rapid = false;
};

// The moves of a job's first operation's events (positions resolved).
std::vector<Move> moves_of(const std::vector<Event>& events) {
    std::vector<Move> out;
    Vec3 at{};
    for (const Event& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            out.push_back({at, r->to, std::nullopt, ArcDirection::ccw, Movement::cutting, true});
            at = r->to;
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            out.push_back({at, l->to, std::nullopt, ArcDirection::ccw, l->movement, false});
            at = l->to;
        } else if (const auto* a = std::get_if<Arc>(&e)) {
            out.push_back({at, a->to, Vec2{a->centre.x, a->centre.y}, a->direction, a->movement, false});
            at = a->to;
        }
    }
    return out;
}

// Points along a move every ~0.05 mm (XY; Z linear), ends included.
std::vector<Vec3> samples_of(const Move& m) {
    std::vector<Vec3> out;
    if (!m.centre) {
        const double l = std::hypot(m.to.x - m.from.x, m.to.y - m.from.y);
        const int n = std::max(1, static_cast<int>(l / 0.05));
        for (int k = 0; k <= n; ++k) {
            const double t = static_cast<double>(k) / n;
            out.push_back({m.from.x + (m.to.x - m.from.x) * t, m.from.y + (m.to.y - m.from.y) * t, m.from.z + (m.to.z - m.from.z) * t});
        }
        return out;
    }
    const Vec2 c = *m.centre;
    const double r = std::hypot(m.from.x - c.x, m.from.y - c.y);
    const double a0 = std::atan2(m.from.y - c.y, m.from.x - c.x), a1 = std::atan2(m.to.y - c.y, m.to.x - c.x);
    double sweep = m.direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
    while (sweep <= 1e-12) sweep += 2 * std::numbers::pi;
    const int n = std::max(2, static_cast<int>(r * sweep / 0.05));
    for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        const double a = a0 + (m.direction == ArcDirection::ccw ? 1 : -1) * sweep * t;
        out.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a), m.from.z + (m.to.z - m.from.z) * t});
    }
    return out;
}

std::string sample_text(const std::string& name) { return read_file(CAMGEN_SOURCE_DIR "/samples/" + name + ".json"); }

// A job of one contour on a 10 mm end mill (tool 4) around a 100 x 60 rectangle drawn
// counter-clockwise, with `members` added to the operation.
std::string rectangle_job(const std::string& members) {
    return R"({"name": "r", "units": "mm", "clearance": 15,
  "tools": [{"number": 4, "type": "end-mill", "diameter": 10, "rpm": 6000}],
  "operations": [{"type": "contour", "tool": 4, "retractPlane": 5, "safeDistance": 2, "endDepth": 4, "feed": 800,
    "start": [0, 0], "path": [{"line": [100, 0]}, {"line": [100, 60]}, {"line": [0, 60]}, {"line": [0, 0]}])" +
           (members.empty() ? "" : ", " + members) + "}]}";
}

// The profile of the first contour of a job.
Profile profile_of(const Job& job) { return std::get<ContourOp>(job.operations.at(0)).profile; }

}  // namespace

TEST_CASE("contour: pass depths are equal steps, or full steps and a smaller last one") {
    CHECK(pass_depths(0, -6, std::nullopt, true) == std::vector<double>{-6});
    CHECK(pass_depths(0, -6, 10.0, true) == std::vector<double>{-6});
    const std::vector<double> equal = pass_depths(0, -5.8, 2.5, true);  // 3 steps of 1.9333
    REQUIRE(equal.size() == 3);
    CHECK(equal[0] == doctest::Approx(-5.8 / 3));
    CHECK(equal[1] == doctest::Approx(-5.8 * 2 / 3));
    CHECK(equal[2] == -5.8);
    CHECK(pass_depths(0, -5.8, 2.5, false) == std::vector<double>{-2.5, -5.0, -5.8});
    CHECK(pass_depths(1, -5, 2, true) == std::vector<double>{-1, -3, -5});
}

TEST_CASE("contour: the computer-offset tool centre is at the radius (plus stock) from the profile everywhere, never closer") {
    const Job job = read_job(sample_text("plate-outline"), "plate-outline.json");
    const Profile profile = profile_of(job);
    const auto& op = std::get<ContourOp>(job.operations.at(0));
    const double r = 5.0, stock = op.finishing->radial_stock;
    int checked_rough = 0, checked_finish = 0;
    for (const Move& m : moves_of(expand_job(job))) {
        if (m.rapid || (m.movement != Movement::cutting && m.movement != Movement::finishing)) continue;
        const double expected = m.movement == Movement::finishing ? r : r + stock;
        for (const Vec3& p : samples_of(m)) {
            const double d = distance_to(profile, {p.x, p.y});
            CHECK(d == doctest::Approx(expected).epsilon(1e-9).scale(1));
            CHECK(d > expected - 1e-6);
            (m.movement == Movement::finishing ? checked_finish : checked_rough)++;
        }
    }
    CHECK(checked_rough > 10000);
    CHECK(checked_finish > 5000);
}

TEST_CASE("contour: each pass cuts at its depth, the finishing pass at the bottom, tabs rise to their height") {
    const Job job = read_job(sample_text("plate-outline"), "plate-outline.json");
    // endDepth 6 below the stock top at 0; roughing to 6 - 0.2 (axial stock) in 3 equal steps
    // of 1.9333 (stepDown 2.5); tabs 1.5 high: the tool rises to Z-4.5 over them.
    std::map<double, int> cutting_at;  // Z of flat cutting moves (rounded to 0.0001) -> count
    int rises = 0;
    std::set<double> finishing_z;
    for (const Move& m : moves_of(expand_job(job))) {
        if (m.rapid) continue;
        const bool flat = std::abs(m.from.z - m.to.z) < 1e-9;
        if (m.movement == Movement::cutting && flat) cutting_at[std::round(m.to.z * 1e4) / 1e4]++;
        if (m.movement == Movement::finishing && flat) finishing_z.insert(std::round(m.to.z * 1e4) / 1e4);
        if (!flat && m.to.z > m.from.z && std::abs(m.to.x - m.from.x) < 1e-9 && std::abs(m.to.z - -4.5) < 1e-9) ++rises;
    }
    std::set<double> levels;
    for (const auto& [z, n] : cutting_at) levels.insert(z);
    CHECK(levels == std::set<double>{-5.8, -4.5, -3.8667, -1.9333});
    CHECK(finishing_z == std::set<double>{-6.0, -4.5});
    CHECK(rises == 8);  // four tabs on the last roughing pass and on the finishing pass
    // The lowest Z of the program is the bottom.
    double lowest = 0;
    for (const Move& m : moves_of(expand_job(job))) lowest = std::min(lowest, m.to.z);
    CHECK(lowest == -6.0);
}

TEST_CASE("contour: climb outside a counter-clockwise profile walks it clockwise; conventional and inside turn it round") {
    struct Case {
        std::string members;
        ArcDirection corner;  // the direction of the cut's corner arcs
    };
    for (const Case& c : {Case{R"("side": "outside")", ArcDirection::cw}, Case{R"("side": "outside", "direction": "conventional")", ArcDirection::ccw},
                          Case{R"("side": "inside")", ArcDirection::ccw}}) {
        CAPTURE(c.members);
        const Job job = read_job(rectangle_job(c.members), "r.json");
        int arcs = 0;
        for (const Move& m : moves_of(expand_job(job)))
            if (m.centre && m.movement == Movement::cutting) {
                CHECK(m.direction == c.corner);
                ++arcs;
            }
        // Outside: an arc around each convex corner; inside: the sharp corners stay sharp.
        CHECK(arcs == (c.members.find("inside") == std::string::npos ? 4 : 0));
    }
}

TEST_CASE("contour: with control compensation G41/G42/G40 are only on straight feed moves, and the program is the profile") {
    for (const char* machine : {"fanuc", "linuxcnc", "sinumerik"}) {
        CAPTURE(machine);
        const Posted p = post_job(sample_text("plate-outline-control"), machine);
        std::string motion = "G0";
        int switches = 0;
        for (const std::string& line : lines_of(p.text)) {
            for (const char* g : {"G0 ", "G1 ", "G2 ", "G3 "})
                if ((line + " ").find(g) != std::string::npos) motion = std::string(g).substr(0, 2);
            // Comments and the start block's reset (with G17) are not moves.
            if (line.find('(') != std::string::npos || line.find(';') != std::string::npos || line.find("G17") != std::string::npos)
                continue;
            for (const char* g : {"G41", "G42", "G40"})
                if (line.find(g) != std::string::npos) {
                    CAPTURE(line);
                    CHECK(motion == "G1");
                    ++switches;
                }
        }
        CHECK(switches == 4);  // on and off, for the roughing and the finishing pass
    }
    // Heidenhain: RL on an L block, R0 on an L block.
    const Posted h = post_job(sample_text("plate-outline-control"), "heidenhain");
    int rl = 0;
    for (const std::string& line : lines_of(h.text))
        if (line.find(" RL") != std::string::npos || (line.find(" R0") != std::string::npos && line.find("FMAX") == std::string::npos)) {
            CAPTURE(line);
            CHECK(line.find(" L ") != std::string::npos);
            ++rl;
        }
    CHECK(rl == 4);
    // The programmed path of the last pass is the profile itself: its corner arcs are R10.
    const Posted f = post_job(sample_text("plate-outline-control"), "fanuc");
    CHECK(f.text.find("G2 X0.000 Y10.000 I0.000 J10.000") != std::string::npos);
}

TEST_CASE("contour: no feed move through the air is longer than the safe distance plus the lead") {
    for (const char* sample : {"plate-outline", "plate-outline-control", "pocket-wall"}) {
        CAPTURE(sample);
        const Job job = read_job(sample_text(sample), std::string(sample) + ".json");
        const auto& op = std::get<ContourOp>(job.operations.at(0));
        const Planes z = resolve_planes(op.heights);
        // The lead-in may be at the stock top (a ramp along the profile), its entry line too.
        const double lead = std::max({op.lead_in.length, op.lead_in.radius * op.lead_in.sweep * std::numbers::pi / 180, 0.0}) +
                            1.1 * op.tool_radius;
        for (const Move& m : moves_of(expand_job(job))) {
            if (m.rapid) continue;
            const double above = std::max(0.0, std::max(m.from.z, m.to.z) - z.reference_z);
            const double xy = std::hypot(m.to.x - m.from.x, m.to.y - m.from.y);
            if (xy < 1e-9) {
                CHECK(above <= z.safe_z - z.reference_z + 1e-9);  // a plunge: at most the safe distance in air
            } else if (std::min(m.from.z, m.to.z) >= z.reference_z) {
                CHECK(xy <= lead + 1e-9);
            }
        }
    }
}

TEST_CASE("contour: the old depth key is refused, saying what replaced it") {
    const std::string job = rectangle_job(R"("depth": -3)");
    CHECK_THROWS_WITH_AS(read_job(job, "r.json"), doctest::Contains("/operations/0/depth: depth was replaced by endDepth"), InputError);
}

TEST_CASE("contour: bad input is an error naming the JSON path, exit 1 and no output file") {
    struct Case {
        std::string job;
        std::string machine;
        std::string path;
        std::string text;
    };
    const std::string crossing = R"({"name": "r", "units": "mm", "clearance": 15,
  "tools": [{"number": 4, "type": "end-mill", "diameter": 10, "rpm": 6000}],
  "operations": [{"type": "contour", "tool": 4, "endDepth": 4, "feed": 800,
    "start": [0, 0], "path": [{"line": [100, 60]}, {"line": [100, 0]}, {"line": [0, 60]}, {"line": [0, 0]}]}]})";
    const std::string open_inside = R"({"name": "r", "units": "mm", "clearance": 15,
  "tools": [{"number": 4, "type": "end-mill", "diameter": 10, "rpm": 6000}],
  "operations": [{"type": "contour", "tool": 4, "endDepth": 4, "feed": 800, "side": "inside",
    "start": [0, 0], "path": [{"line": [100, 0]}, {"line": [100, 60]}]}]})";
    std::string small = rectangle_job(R"("side": "inside")");
    small.replace(small.find(R"("diameter": 10)"), 14, R"("diameter": 70)");
    const Case cases[] = {
        {crossing, "fanuc", "/operations/0/path", "crosses or touches itself"},
        {open_inside, "fanuc", "/operations/0/side", "side inside needs a closed profile"},
        {small, "fanuc", "/operations/0/path", "does not fit inside the profile"},
        {rectangle_job(R"("stepDown": 0)"), "fanuc", "/operations/0/stepDown", "stepDown must be > 0"},
        {rectangle_job(R"("tabs": {"count": 2, "width": 95, "height": 1})"), "fanuc", "/operations/0/tabs/width",
         "does not fit on any straight run or arc of this profile"},
        {sample_text("plate-outline-control"), "grbl", "/operations/0/compensation", "has no cutter radius compensation"},
        {rectangle_job(R"("path": [{"line": [100, 0]}, {"line": [100, 0]}, {"line": [0, 0]}])"), "fanuc", "", ""},
    };
    for (std::size_t k = 0; k + 1 < std::size(cases); ++k) {
        const Case& c = cases[k];
        CAPTURE(c.text);
        const std::string file = file_with(fmt::format("contour-bad-{}", k), c.job);
        const std::filesystem::path out = scratch(fmt::format("contour-bad-out-{}", k)) / "p.nc";
        const Run r = run({file, "--machine", c.machine, "-o", out.string()});
        CHECK(r.code == 1);
        CHECK(r.err.find(c.path + ": ") != std::string::npos);
        CHECK(r.err.find(c.text) != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(out));
    }
}

TEST_CASE("contour: a zero-length element is refused naming the element") {
    const std::string job = R"({"name": "r", "units": "mm", "clearance": 15,
  "tools": [{"number": 4, "type": "end-mill", "diameter": 10, "rpm": 6000}],
  "operations": [{"type": "contour", "tool": 4, "endDepth": 4, "feed": 800,
    "start": [0, 0], "path": [{"line": [100, 0]}, {"line": [100, 0]}, {"line": [100, 60]}, {"line": [0, 0]}]}]})";
    CHECK_THROWS_WITH_AS(read_job(job, "r.json"), doctest::Contains("/operations/0/path/1: this element is shorter than"), InputError);
}

TEST_CASE("contour: a concave corner arc tighter than the tool is trimmed, never gouged, with a note naming the element") {
    // An inside cut of a rectangle whose corners are R2 arcs, with a 10 mm tool: the tool
    // cannot follow R2; the offset corners are sharp and a note names each arc.
    const std::string job = R"({"name": "r", "units": "mm", "clearance": 15,
  "tools": [{"number": 4, "type": "end-mill", "diameter": 10, "rpm": 6000}],
  "operations": [{"type": "contour", "tool": 4, "endDepth": 4, "feed": 800, "side": "inside",
    "start": [2, 0], "path": [{"line": [98, 0]}, {"arc": {"end": [100, 2], "centre": [98, 2], "direction": "ccw"}},
      {"line": [100, 58]}, {"arc": {"end": [98, 60], "centre": [98, 58], "direction": "ccw"}}, {"line": [2, 60]},
      {"arc": {"end": [0, 58], "centre": [2, 58], "direction": "ccw"}}, {"line": [0, 2]},
      {"arc": {"end": [2, 0], "centre": [2, 2], "direction": "ccw"}}]}]})";
    const Job j = read_job(job, "r.json");
    const auto& op = std::get<ContourOp>(j.operations.at(0));
    REQUIRE(op.notes.size() == 4);
    CHECK(op.notes[0].find("/operations/0/path/") == 0);
    for (const Move& m : moves_of(expand_job(j)))
        if (!m.rapid && m.movement == Movement::cutting)
            for (const Vec3& p : samples_of(m)) CHECK(distance_to(op.profile, {p.x, p.y}) > 5.0 - 1e-6);
    // The CLI prints the notes.
    const Run r = run({file_with("contour-note", job), "--machine", "fanuc", "-o", (scratch("contour-note-out") / "p.nc").string()});
    CHECK(r.code == 0);
    CHECK(r.err.find("camgen: note: /operations/0 (contour): /operations/0/path/") != std::string::npos);
}

TEST_CASE("contour: wear compensation cuts camgen's offset path and switches G41 on for the wear; inverse wear writes G42") {
    for (const auto& [mode, word] : {std::pair{"wear", "G41 D4"}, std::pair{"inverse-wear", "G42 D4"}}) {
        CAPTURE(mode);
        const std::string job = rectangle_job(fmt::format(R"("compensation": "{}")", mode));
        const Job j = read_job(job, "r.json");
        const Profile profile = profile_of(j);
        int samples = 0;
        for (const Move& m : moves_of(expand_job(j)))
            if (!m.rapid && m.movement == Movement::cutting)
                for (const Vec3& p : samples_of(m)) {
                    CHECK(distance_to(profile, {p.x, p.y}) == doctest::Approx(5.0));
                    ++samples;
                }
        CHECK(samples > 1000);
        const Posted posted = post_job(job, "fanuc");
        CHECK(posted.text.find(word) != std::string::npos);
        // G40 is carried by a straight feed move (G1 is modal from the pass before it).
        bool g40_on_a_line = false;
        for (const std::string& line : lines_of(posted.text))
            if (line.find("G40 ") != std::string::npos && line.find(" X") != std::string::npos)
                g40_on_a_line = line.find("G0") == std::string::npos && line.find("G2") == std::string::npos &&
                                line.find("G3") == std::string::npos;
        CHECK(g40_on_a_line);
    }
}

TEST_CASE("contour: a ramp along the profile descends at its angle, then goes back at depth before the full pass") {
    // One pass 4 deep from the stock top at 0 on a closed rectangle, ramp 10 degrees: the ramp
    // runs 4 / tan(10 deg) = 22.685 mm along the offset path, down from Z0 to Z-4.
    const Job j = read_job(rectangle_job(R"("ramp": {"type": "along", "angle": 10}, "rampFeed": 300)"), "r.json");
    double ramp_down = 0.0, ramp_back = 0.0;
    double lowest_before_cut = 0.0;
    bool cut = false;
    for (const Move& m : moves_of(expand_job(j))) {
        if (m.rapid) continue;
        const double xy = std::hypot(m.to.x - m.from.x, m.to.y - m.from.y);
        if (m.movement == Movement::ramp) {
            CHECK_FALSE(cut);
            if (m.to.z < m.from.z - 1e-9) {
                CHECK((m.from.z - m.to.z) / xy == doctest::Approx(std::tan(10 * std::numbers::pi / 180)));
                ramp_down += xy;
            } else {
                CHECK(m.to.z == doctest::Approx(-4.0));
                ramp_back += xy;
            }
        }
        if (m.movement == Movement::plunge) lowest_before_cut = std::min(lowest_before_cut, m.to.z);
        if (m.movement == Movement::cutting) cut = true;
    }
    CHECK(ramp_down == doctest::Approx(4 / std::tan(10 * std::numbers::pi / 180)));
    CHECK(ramp_back == doctest::Approx(ramp_down));
    CHECK(lowest_before_cut == doctest::Approx(0.0));  // no plunge into the stock: down to the top only
}

TEST_CASE("contour: statistics tell the movement kinds apart") {
    // From the job's events: every kind the operation used, lead-in and lead-out included.
    const Job j = read_job(sample_text("plate-outline"), "plate-outline.json");
    const Machine m = load_machine("fanuc");
    const ProgramStats from_job = compute_stats(trace_events(expand_job(j), m), m);
    for (Movement k : {Movement::cutting, Movement::plunge, Movement::lead_in, Movement::lead_out, Movement::finishing}) {
        CAPTURE(name_of(movements, k));
        CHECK(from_job.movement_length[static_cast<std::size_t>(k)] > 0);
    }
    // The lead-in is a quarter circle of radius 8, once for roughing and once for finishing.
    CHECK(from_job.movement_length[static_cast<std::size_t>(Movement::lead_in)] == doctest::Approx(2 * 8 * std::numbers::pi / 2));
    // Read back from a program, the motion shows the plunges and the helix ramp.
    const Run r = run({CAMGEN_SOURCE_DIR "/samples/pocket-wall.json", "--machine", "linuxcnc", "--stats", "-o",
                       (scratch("contour-stats") / "p.ngc").string()});
    REQUIRE(r.code == 0);
    CHECK(r.err.find("feed by kind   cutting ") != std::string::npos);
    CHECK(r.err.find(", plunge ") != std::string::npos);
    CHECK(r.err.find(", ramp ") != std::string::npos);
}

TEST_CASE("contour: the backplot draws the width the tool cuts, one band per tool and depth, darker deeper") {
    const std::filesystem::path dir = scratch("contour-plot");
    const Run r = run({CAMGEN_SOURCE_DIR "/samples/plate-outline.json", "--machine", "fanuc", "-o", (dir / "p.nc").string(), "--plot",
                       (dir / "p.svg").string()});
    REQUIRE(r.code == 0);
    const std::string svg = read_file((dir / "p.svg").string());
    // Depth levels of the feed moves in XY: three roughing passes, the tab tops, the finishing pass.
    std::vector<double> opacities;
    for (std::size_t at = svg.find("stroke-linecap=\"round\" stroke-linejoin=\"round\" stroke-opacity=\""); at != std::string::npos;
         at = svg.find("stroke-linecap=\"round\" stroke-linejoin=\"round\" stroke-opacity=\"", at + 1)) {
        const std::size_t v = svg.find("stroke-opacity=\"", at) + 16;
        opacities.push_back(std::stod(svg.substr(v, svg.find('"', v) - v)));
    }
    CHECK(opacities.size() == 5);
    // Bands are drawn from the deepest (lowest Z, darkest) to the shallowest.
    CHECK(std::is_sorted(opacities.rbegin(), opacities.rend()));
    CHECK(opacities.front() == doctest::Approx(0.25));
}

TEST_CASE("contour: with control compensation a straight lead shorter than the tool radius is lengthened, with a note") {
    const Job j = read_job(rectangle_job(R"("compensation": "control", "leadIn": {"type": "line", "length": 2}, "leadOut": {"type": "line", "length": 2, "angle": 90})"), "r.json");
    const auto& op = std::get<ContourOp>(j.operations.at(0));
    CHECK(op.lead_in.length == doctest::Approx(5.5));
    CHECK(op.lead_out.length == doctest::Approx(5.5));
    REQUIRE(op.notes.size() == 2);
    CHECK(op.notes[0].find("/operations/0/leadIn: the line is 2.000 mm long") != std::string::npos);
    // The entry move carrying G41 is then long enough for LinuxCNC (the rs274 oracle runs the
    // samples; here the length is checked in the program).
    const Posted p = post_job(rectangle_job(R"("compensation": "control", "leadIn": {"type": "line", "length": 2})"), "linuxcnc");
    // The walk starts up the left side: the lead (made 5.5 long) ends 5.5 before the start, a run
    // of the switch length (5.5) along the tangent takes it onto the start.
    CHECK(p.text.find("X0 Y-11\n") != std::string::npos);
    CHECK(p.text.find("G41 D4 Y-5.5\nY0\n") != std::string::npos);
}

TEST_CASE("contour: a near-tangent pocket (fuzz finding) is cut at the tool radius everywhere, or refused; never cut wrong") {
    // pocket-wall with its joints moved by up to 0.08 mm: the offset once lost the pocket's
    // bottom side and wrote an "arc" whose end lay 49 mm from its centre.
    const std::string job = R"({"clearance":15,"name":"pocket-wall","operations":[{"direction":"climb","endDepth":8,"feed":600,
      "leadIn":{"angle":90,"length":4,"type":"line"},"leadOut":{"angle":90,"length":6.6875,"type":"line"},
      "path":[{"line":[121.92,40]},{"arc":{"centre":[122,48],"direction":"ccw","end":[130,48]}},{"line":[130,72]},
        {"arc":{"centre":[122,72],"direction":"ccw","end":[122,80]}},{"line":[78,80]},{"arc":{"centre":[78,72],"direction":"ccw","end":[70,72]}},
        {"line":[70,48.006]},{"arc":{"centre":[78,48],"direction":"ccw","end":[78,40]}}],
      "plungeFeed":150,"ramp":{"angle":3,"radius":2,"type":"helix"},"rampFeed":400,"retractPlane":5,"safeDistance":1,"side":"inside",
      "start":[78,40],"stepDown":2,"tool":2,"type":"contour"}],
      "tools":[{"diameter":6,"number":2,"rpm":6000,"type":"end-mill"}],"units":"mm"})";
    try {
        const Job j = read_job(job, "pw.json");
        const Profile profile = profile_of(j);
        double along = 0.0;
        for (const Move& m : moves_of(expand_job(j)))
            if (!m.rapid && m.movement == Movement::cutting)
                for (const Vec3& p : samples_of(m)) {
                    CHECK(distance_to(profile, {p.x, p.y}) == doctest::Approx(3.0).epsilon(1e-6));
                    along += 0.05;
                }
        CHECK(along > 4 * 150);  // four passes around a 60 x 40 pocket
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("camgen could not offset this profile") != std::string::npos);
    }
}

TEST_CASE("contour: the finishing step finishes the wall in several depths") {
    // 4 deep, roughing in one pass leaving 0.5 on the wall; finishing in steps of at most 1.5:
    // three equal passes of 4/3 at the final offset.
    const Job j = read_job(rectangle_job(R"("finishing": {"radialStock": 0.5, "stepDown": 1.5})"), "r.json");
    std::set<long> finishing_levels;
    for (const Move& m : moves_of(expand_job(j)))
        if (!m.rapid && m.movement == Movement::finishing && std::abs(m.to.z - m.from.z) < 1e-9)
            finishing_levels.insert(std::lround(m.to.z * 1e4));
    CHECK(finishing_levels == std::set<long>{-13333, -26667, -40000});
    CHECK_THROWS_WITH_AS(read_job(rectangle_job(R"("finishing": {"stepDown": 0})"), "r.json"),
                         doctest::Contains("/operations/0/finishing/stepDown: stepDown must be > 0"), InputError);
}

}  // namespace test_contour
