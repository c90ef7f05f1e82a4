// The failure modes seen in the field (REFERENCE.md §6): one test per mode, named
// "field failure: <mode>" (`camgen_tests -tc='field failure*'`), each run on every built-in
// machine where the mode applies and asserting on the program camgen really writes, read back
// through the machine's own reader. Each test also checks the list of machines it ran on, so
// the table in docs/development.md ("Failure modes seen in the field") cannot silently go stale.
// The LinuxCNC oracle half (rs274) is in tests/oracle/ (test_field_failures_oracle.cpp, and
// test_oracle.cpp for G86/G89 without P), named the same way; quadratic output on large jobs
// is measured by bench/, not timed here.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <clocale>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <locale>
#include <numbers>
#include <random>
#include <regex>
#include <thread>

#include <fmt/format.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_field_failures {

using namespace camgen;
using namespace camgen::test;
namespace fs = std::filesystem;

namespace {

// Runs `check` for every built-in mill that `applies` to (INFO names it) and returns the
// names it ran on, in list_machines order. The failure modes' jobs are mill jobs, which a lathe
// refuses; the lathes' own motion is tested in test_turn_drill.cpp, test_turn_profile.cpp and
// test_lathe_posts.cpp.
std::vector<std::string> for_machines(const std::function<bool(const Machine&)>& applies,
                                      const std::function<void(const Machine&)>& check) {
    std::vector<std::string> ran;
    for (const auto& listed : list_machines()) {
        const Machine m = load_machine(listed.first);
        if (m.kind != MachineKind::mill || !applies(m)) continue;
        INFO("machine " << m.name);
        check(m);
        ran.push_back(m.name);
    }
    return ran;
}

bool every(const Machine&) { return true; }
const std::vector<std::string> all_machines = {"fanuc", "grbl", "heidenhain", "kosy", "linuxcnc", "sinumerik", "wabeco"};

// A program as written and as the machine's reader reads it back.
struct ReadBack {
    std::string text;
    std::vector<ReadEvent> events;
    Trace trace;
};

ReadBack post_and_read(const Job& job, const Machine& m) {
    ReadBack r;
    r.text = post_program(job, m);
    REQUIRE_NOTHROW(r.events = read_program(r.text, m, "prog"));
    r.trace = trace_program(r.events, m);
    return r;
}

ReadBack post_and_read(const std::string& job_json, const Machine& m) { return post_and_read(read_job(job_json, "job.json"), m); }

// The message of the InputError posting `job` on `m` raises ("" when it posts).
std::string refusal(const std::string& job_json, const Machine& m) {
    try {
        (void)post_program(read_job(job_json, "job.json"), m);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A job of one drilling operation (its keys in `op`) on a 5 mm drill, tool 1, and an M8 tap,
// tool 2; the stock top (referencePlane) at Z0 unless `op` says otherwise.
std::string holes_job(const std::string& op, const std::string& holes = "[[10, 10], [30, 10], [30, 25], [10, 25]]",
                      double clearance = 20) {
    return fmt::format(R"({{"name": "field", "clearance": {}, "tools": [
  {{"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}},
  {{"number": 2, "type": "tap", "diameter": 8, "rpm": 300}}],
 "operations": [{{"type": "drill", {}, "holes": {}}}]}})",
                       clearance, op, holes);
}

// A job of one tool-centre path on a 4 mm end mill, its path elements given as JSON.
std::string path_job(const std::string& start, const std::string& path, double feed = 300) {
    return fmt::format(R"({{"name": "field", "clearance": 10, "tools": [{{"number": 5, "type": "end-mill", "diameter": 4, "rpm": 4000}}],
 "operations": [{{"type": "path", "tool": 5, "z": -1, "feed": {}, "plungeFeed": 100, "start": {}, "path": {}}}]}})",
                       feed, start, path);
}

std::string sample(const std::string& name) { return read_file(CAMGEN_SOURCE_DIR "/samples/" + name + ".json"); }

// The samples the machine can run (those without an .err golden file).
std::vector<std::string> samples_for(const Machine& m) {
    std::vector<std::string> out;
    for (const auto& f : fs::directory_iterator(CAMGEN_SOURCE_DIR "/samples")) {
        if (f.path().extension() != ".json") continue;
        const std::string stem = f.path().stem().string();
        if (!fs::exists(fs::path(CAMGEN_SOURCE_DIR "/tests/golden") / m.name / (stem + ".err"))) out.push_back(stem);
    }
    std::sort(out.begin(), out.end());
    return out;
}

double xy_distance(Vec3 a, Vec3 b) { return std::hypot(a.x - b.x, a.y - b.y); }

// The feed path of a trace sampled densely (arcs along the arc, lines along the line).
std::vector<Vec3> feed_path(const Trace& t) {
    std::vector<Vec3> out;
    for (const Step& s : t.steps) {
        if (s.kind != StepKind::feed) continue;
        for (int k = 0; k <= 64; ++k) {
            const double f = k / 64.0;
            out.push_back(s.arc ? point_on_arc(*s.arc, f) : s.from + (s.to - s.from) * f);
        }
    }
    return out;
}

double nearest(const std::vector<Vec3>& path, Vec3 p) {
    double best = 1e300;
    for (const Vec3& q : path) best = std::min(best, length(q - p));
    return best;
}

// The arc steps of a trace whose centre is within 0.01 mm of `centre` in the arc's plane.
std::vector<ArcGeometry> arcs_about(const Trace& t, Vec3 centre) {
    std::vector<ArcGeometry> out;
    for (const Step& s : t.steps)
        if (s.arc && xy_distance(s.arc->centre, centre) < 0.01) out.push_back(*s.arc);
    return out;
}

}  // namespace

TEST_CASE("field failure: rapids below R or through the stock") {
    // Deep holes (pecks re-approach inside the hole at rapid), stock top Z0, R at Z2, retract Z10.
    const std::string job = holes_job(R"("tool": 1, "cycle": "deep", "retractPlane": 10, "safeDistance": 2, "endDepth": 9,
        "firstDepth": 3, "plungingFeedrate": 100)");
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack r = post_and_read(job, m);
        const double slack = read_resolution(m).position + 1e-9;
        std::vector<std::pair<Vec3, double>> drilled;  // XY and the deepest Z fed to there
        int into_holes = 0;
        for (const Step& s : r.trace.steps) {
            if (s.kind == StepKind::feed && xy_distance(s.from, s.to) < 1e-6 && s.to.z < s.from.z) {
                auto at = std::find_if(drilled.begin(), drilled.end(), [&](auto& d) { return xy_distance(d.first, s.to) < 1e-6; });
                if (at == drilled.end()) drilled.push_back({s.to, s.to.z});
                else at->second = std::min(at->second, s.to.z);
            }
            if (s.kind != StepKind::rapid || !s.from_known) continue;
            CAPTURE(s.line);
            // Across only above R: never through the stock nor below the plane the job gave.
            if (xy_distance(s.from, s.to) > 1e-6) CHECK(std::min(s.from.z, s.to.z) >= 2.0 - slack);
            // Below the stock top only straight down into a hole already drilled that deep.
            if (s.to.z < -slack) {
                CHECK(xy_distance(s.from, s.to) < 1e-6);
                auto at = std::find_if(drilled.begin(), drilled.end(), [&](auto& d) { return xy_distance(d.first, s.to) < 1e-6; });
                REQUIRE_MESSAGE(at != drilled.end(), "a rapid below the stock top where no hole is");
                CHECK(at->second <= s.to.z + slack);
                ++into_holes;
            }
        }
        CHECK(r.trace.holes.size() == 4);
        CHECK(into_holes >= 4);  // the peck re-approaches: the rule above was exercised
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: G98 treated as G99") {
    // Between holes the tool must travel at the retract plane (Z10, over clamps) when the job
    // asks for it, and at R (Z2) only when the retract plane is R.
    const auto ran = for_machines(every, [&](const Machine& m) {
        for (double retract : {10.0, 2.0}) {
            CAPTURE(retract);
            const std::string job = holes_job(fmt::format(R"("tool": 1, "retractPlane": {}, "safeDistance": 2, "endDepth": 5,
                "plungingFeedrate": 100)", retract));
            const ReadBack r = post_and_read(job, m);
            bool drilling = false;
            int across = 0;
            for (const Step& s : r.trace.steps) {
                if (s.kind == StepKind::feed) drilling = true;
                if (!drilling || s.kind != StepKind::rapid || xy_distance(s.from, s.to) < 1e-6) continue;
                if (across == 3) break;  // the three moves between the four holes
                CAPTURE(s.line);
                CHECK(s.from.z == doctest::Approx(retract));
                ++across;
            }
            CHECK(across == 3);
            // Where the control has both modes, the cycle names the one it means, never trusting
            // the control's default.
            if (m.dialect == "iso" && m.canned_cycle(CycleKind::drill))
                CHECK(has(r.text, retract > 2 ? "G98 G81" : "G99 G81"));
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: words dropped on later holes (only the first hole drilled)") {
    // Holes that share X or Y with the one before: a post that drops an "unchanged" word, or a
    // cycle the control does not repeat, drills fewer holes or drills one twice. Every block that
    // drills a hole of a canned cycle states both X and Y (controls that forget the other one
    // exist: nccad with its classic arcs, some DNC editors), and reads back as the hole.
    const std::vector<Vec2> holes = {{10, 10}, {30, 10}, {30, 25}, {10, 25}, {10, 40}};
    const std::string job = holes_job(R"("tool": 1, "retractPlane": 5, "endDepth": 6, "plungingFeedrate": 100)",
                                      "[[10, 10], [30, 10], [30, 25], [10, 25], [10, 40]]");
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack r = post_and_read(job, m);
        REQUIRE(r.trace.holes.size() == holes.size());
        for (size_t i = 0; i < holes.size(); ++i) {
            CAPTURE(i);
            CHECK(r.trace.holes[i].at.x == doctest::Approx(holes[i].x));
            CHECK(r.trace.holes[i].at.y == doctest::Approx(holes[i].y));
            CHECK(r.trace.holes[i].bottom_z == doctest::Approx(-6));
        }
        CHECK(round_trip(job, r.text, m.name) == "");
        const auto lines = lines_of(r.text);
        int points = 0;
        for (const ReadEvent& e : r.events)
            if (std::holds_alternative<DrillPoint>(e.event)) {
                const auto w = words_of(lines.at(e.line - 1));
                CAPTURE(lines.at(e.line - 1));
                CHECK((w.count('X') && w.count('Y')));
                ++points;
            }
        // Canned where the machine has G81 (or its equivalent); grbl drills longhand.
        CHECK(points == (m.canned_cycle(CycleKind::drill) ? int(holes.size()) : 0));
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: codes the control rejects (G98 or G81 on GRBL, G99 inside an nccad program)") {
    // Every program of every sample is read by the machine's reader, which refuses any word or
    // code the control does not have.
    const auto ran = for_machines(every, [&](const Machine& m) {
        for (const std::string& s : samples_for(m)) {
            CAPTURE(s);
            const std::vector<std::string> lines = lines_of(post_and_read(sample(s), m).text);
            for (const std::string& line : lines) {
                const auto w = words_of(line);
                // GRBL has no canned cycles, no G98/G99 and no M6: it stops with "Unsupported command".
                if (m.name == "grbl") {
                    CAPTURE(line);
                    for (const char* code : {"G73", "G74", "G80", "G81", "G82", "G83", "G84", "G85", "G86", "G89", "G98", "G99", "M6", "M06", "M29"})
                        CHECK_FALSE(has(" " + line + " ", std::string(" ") + code + " "));
                }
                // nccad's G99 ends the program: never as a cycle's return mode.
                if (m.dialect == "nccad" && w.count('G') && std::stod(w.at('G')) == 99) CHECK(&line == &lines.back());
            }
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: wrong arc direction in G18/G19") {
    // The arcs sample's XZ arc (cw) and YZ arc (ccw) both dip into the material to Z-6 at their
    // middle; the wrong direction would bulge up to Z+4. Read back by the machine's reader and,
    // for the ISO and nccad dialects, by the interpreter of support.hpp that uses no camgen arc code.
    const std::string job = path_job("[200, 0]", R"([
        {"arc": {"plane": "xz", "end": [210, 0, -1], "centre": [205, 0, -1], "direction": "cw"}},
        {"arc": {"plane": "yz", "end": [210, 10, -1], "centre": [210, 5, -1], "direction": "ccw"}}])");
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack r = post_and_read(job, m);
        const std::vector<Vec3> path = feed_path(r.trace);
        const double tolerance = m.arcs.chord_tolerance + 2 * read_resolution(m).position;
        for (Vec3 bottom : {Vec3{205, 0, -6}, Vec3{210, 5, -6}}) CHECK(nearest(path, bottom) <= tolerance);
        for (Vec3 wrong : {Vec3{205, 0, 4}, Vec3{210, 5, 4}}) CHECK(nearest(path, wrong) > 5);
        if (m.dialect == "iso" || m.dialect == "nccad") {
            std::vector<Vec3> independent;
            for (const NcMove& mv : interpret(r.text, m.arcs.format))
                for (int k = 0; k <= 64; ++k) independent.push_back(mv.at(k / 64.0));
            for (Vec3 bottom : {Vec3{205, 0, -6}, Vec3{210, 5, -6}}) CHECK(nearest(independent, bottom) <= tolerance);
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: rounded arc end points off the circle") {
    // A chain of 300 awkward arcs (radii, centres and sweeps off the output grid, from a fixed
    // seed): as written, each arc block's end must lie on the circle through its start about its
    // centre, within the machine's tolerance. Plain rounding of the words misses that on some.
    std::mt19937 rng(20261130);
    auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * (rng() / 4294967296.0); };
    double x = 0, y = 0;
    std::string path;
    for (int k = 0; k < 300; ++k) {
        const double r = uniform(2, 40), to_centre = uniform(0, 2 * std::numbers::pi);
        const double sweep = uniform(15, 175) * std::numbers::pi / 180, sign = rng() % 2 ? 1.0 : -1.0;
        const double cx = x + r * std::cos(to_centre), cy = y + r * std::sin(to_centre);
        const double a = std::atan2(y - cy, x - cx) + sign * sweep;
        x = cx + r * std::cos(a);
        y = cy + r * std::sin(a);
        path += fmt::format(R"({}{{"arc": {{"end": [{:.10f}, {:.10f}], "centre": [{:.10f}, {:.10f}], "direction": "{}"}}}})",
                            k ? ", " : "", x, y, cx, cy, sign > 0 ? "ccw" : "cw");
    }
    const std::string job = path_job("[0, 0]", "[" + path + "]");
    const auto ran = for_machines(every, [&](const Machine& machine) {
        // At the built-in resolutions plain rounding is rarely off by more than the tolerance;
        // the same machine writing lengths with 2 decimals shows the words are fitted, not rounded.
        Machine coarse = machine;
        for (const char* key : {"xyz", "ijk"}) {
            nc::FormatSpec spec = coarse.formats.count(key) ? coarse.formats.at(key) : nc::FormatSpec{};
            spec.decimals = 2;
            coarse.formats[key] = spec;
        }
        for (const Machine& m : {machine, coarse}) {
            for (const std::string& text : {job, sample("bracket"), sample("arcs")}) {
                CAPTURE(m.format("xyz").spec().decimals);
                const ReadBack rb = post_and_read(text, m);
                int arcs = 0;
                for (const Step& s : rb.trace.steps) {
                    if (!s.arc) continue;
                    const PlanePoint c = to_plane(s.arc->centre, s.arc->plane), a = to_plane(s.from, s.arc->plane),
                                     b = to_plane(s.to, s.arc->plane);
                    CAPTURE(s.line);
                    CHECK(std::abs(std::hypot(a.u - c.u, a.v - c.v) - std::hypot(b.u - c.u, b.v - c.v)) <= m.tolerance);
                    ++arcs;
                }
                CHECK(arcs >= 2);
            }
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: full circles and tiny arcs read as 360 degrees") {
    // A full circle must be read as one turn, never as nothing; an arc of r = 0.001 whose rounded
    // ends coincide must never be read as a full turn (a 360-degree arc block).
    const double tiny = 20 * std::numbers::pi / 180;
    const std::string job = path_job("[30, 10]", fmt::format(R"([
        {{"arc": {{"end": [30, 10], "centre": [20, 10], "direction": "cw"}}}},
        {{"line": [5.001, 5]}},
        {{"arc": {{"end": [{:.10f}, {:.10f}], "centre": [5, 5], "direction": "ccw"}}}}])",
                                                                5 + 0.001 * std::cos(tiny), 5 + 0.001 * std::sin(tiny)));
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack r = post_and_read(job, m);
        double turn = 0;
        for (const ArcGeometry& a : arcs_about(r.trace, {20, 10, 0})) turn += a.sweep;
        CHECK(turn == doctest::Approx(2 * std::numbers::pi).epsilon(1e-4));
        for (const ArcGeometry& a : arcs_about(r.trace, {5, 5, 0})) CHECK(a.sweep * a.radius < 0.01);
        CHECK(round_trip(job, r.text, m.name) == "");
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: helices sent to controls that cannot do them") {
    const std::string job = path_job("[150, 0]", R"([{"helix": {"centre": [150, 2], "direction": "ccw", "turns": 3, "z": -7}}])");
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack r = post_and_read(job, m);
        int helical = 0;
        for (const Step& s : r.trace.steps)
            if (s.arc && std::abs(s.to.z - s.from.z) > 1e-9) ++helical;
        // Linearized where the control has no helix, kept as helical blocks where it has.
        if (m.arcs.helical) CHECK(helical >= 3);
        else CHECK(helical == 0);
        CHECK(round_trip(job, r.text, m.name) == "");
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: inch and mm mixed up") {
    // An inch job is converted as it is read; inch output states its unit and reads back as the
    // job; a control without an inch mode is never given inch numbers.
    const std::string mm_job = holes_job(R"("tool": 1, "retractPlane": 5, "endDepth": 6, "plungingFeedrate": 100)", "[[25.4, 50.8]]");
    std::string inch_job = holes_job(R"("tool": 1, "retractPlane": 0.2, "endDepth": 0.25, "plungingFeedrate": 4)", "[[1, 2]]", 0.8);
    inch_job = replace_once(inch_job, R"("name": "field",)", R"("name": "field", "units": "inch",)");
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack from_inch = post_and_read(inch_job, m);
        REQUIRE(from_inch.trace.holes.size() == 1);
        CHECK(from_inch.trace.holes[0].at.x == doctest::Approx(25.4));
        CHECK(from_inch.trace.holes[0].at.y == doctest::Approx(50.8));
        CHECK(from_inch.trace.holes[0].bottom_z == doctest::Approx(-6.35));
        if (m.accepts(Units::inch)) {
            Machine inch = m;
            inch.units = Units::inch;
            const Job job = read_job(mm_job, "job.json");
            const std::string text = post_program(job, inch);
            CHECK((has(text, "G20") || has(text, "G70") || has(text, " INCH\n")));
            CHECK(round_trip_machine(job, text, inch) == "");
        } else {
            const Run cli = run({file_with("inch-" + m.name, mm_job), "--machine", m.name, "--units", "inch"});
            CHECK(cli.code == 2);
            CHECK(cli.out == "");
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: a unit switch that changes coordinates but not feeds") {
    // 254 mm/min is 10 in/min: written in inch, the feed must read back as 254 mm/min, not 25.4x faster.
    const std::string job = path_job("[0, 0]", R"([{"line": [25.4, 0]}])", 254);
    const auto ran = for_machines([](const Machine& m) { return m.accepts(Units::inch); }, [&](const Machine& m) {
        Machine inch = m;
        inch.units = Units::inch;
        ReadResolution res;
        const std::string text = post_program(read_job(job, "job.json"), inch);
        const Trace t = trace_program(read_program(text, inch, "prog", &res), inch);
        int feeds = 0;
        for (const Step& s : t.steps)
            if (s.kind == StepKind::feed && xy_distance(s.from, s.to) > 1) {
                CHECK(s.feed == doctest::Approx(254).epsilon(1e-6));
                CHECK(s.to.x == doctest::Approx(25.4));
                // The reader shares the machine's formats: the words themselves must say 10 in/min and 1 in.
                const auto w = words_of(lines_of(text).at(s.line - 1));
                CHECK(std::stod(w.at('F')) == 10);
                CHECK(std::stod(w.at('X')) == 1);
                ++feeds;
            }
        CHECK(feeds == 1);
    });
    CHECK(ran == std::vector<std::string>{"fanuc", "grbl", "heidenhain", "linuxcnc", "sinumerik"});
}

TEST_CASE("field failure: a decimal comma from the process locale") {
    // The program is the same under a locale whose decimal mark is a comma (X12,53).
    const std::string job = sample("bracket");
    const auto ran = for_machines(every, [&](const Machine& m) {
        const std::string plain = post_program(read_job(job, "job.json"), m);
        const std::locale previous;
        const std::string saved = std::setlocale(LC_ALL, nullptr);
        REQUIRE_NOTHROW(std::locale::global(std::locale("de_DE.UTF-8")));  // scripts/install-deps --tests makes it
        std::setlocale(LC_ALL, "de_DE.UTF-8");
        const std::string german = post_program(read_job(job, "job.json"), m);
        std::locale::global(previous);
        std::setlocale(LC_ALL, saved.c_str());
        CHECK(german == plain);
        CHECK_FALSE(std::regex_search(german, std::regex("[0-9],[0-9]")));
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: exponent notation (F1.18e+06)") {
    // Values far beyond and far below the output's resolution: a feed of 987654.321 mm/min
    // (clamped), coordinates of 1e-7 mm and 123456.789 mm, given in exponent form.
    const std::string job = path_job("[1e-7, 1E-7]", R"([{"line": [1.23456789e5, 1e-7]}, {"line": [1e-7, 2.5e-8]}])", 987654.321);
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack r = post_and_read(job, m);
        CHECK(bad_number(r.text) == "");
        CHECK_FALSE(has(r.text, "e+"));
        CHECK_FALSE(has(r.text, "e-0"));
        CHECK(has(r.text, "123456.789"));
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: a missing decimal point read as 1/1000 on a Fanuc-style control") {
    // Where the control reads X10 as 0.01 mm, every length word carries its decimal point; the
    // reader refuses a word without one.
    const auto ran = for_machines([](const Machine& m) { return m.formats.at("xyz").force_decimal; }, [&](const Machine& m) {
        for (const std::string& s : samples_for(m)) {
            CAPTURE(s);
            for (std::string line : lines_of(post_and_read(sample(s), m).text))
                for (const auto& [letter, value] : words_of(line.substr(0, line.find_first_of("(;"))))
                    if (has("XYZIJKRQ", std::string(1, letter)) && !value.empty() && std::isdigit(static_cast<unsigned char>(value.back()))) {
                        CAPTURE(line);
                        CHECK(has(value, "."));
                    }
        }
    });
    CHECK(ran == std::vector<std::string>{"fanuc", "sinumerik"});
    CHECK(error_of("%\nN10 G17 G21 G90 G94\nN15 T1 M6\nN20 G0 X10 Y0.000 Z5.000\n", "fanuc").find("has no decimal point") != std::string::npos);
}

TEST_CASE("field failure: F0 or feeds above the machine's limit") {
    const auto ran = for_machines(every, [&](const Machine& m) {
        // A feed of 0 is refused as the job is read.
        CHECK(has(refusal(path_job("[0, 0]", R"([{"line": [10, 0]}])", 0), m), "/operations/0/feed"));
        // A feed that would round to F0, and one above the limit: what is written reads back
        // between the machine's limits.
        for (double feed : {0.001, 1e6}) {
            CAPTURE(feed);
            const ReadBack r = post_and_read(path_job("[0, 0]", R"([{"line": [10, 0]}])", feed), m);
            int feeds = 0;
            for (const Step& s : r.trace.steps)
                if (s.kind == StepKind::feed) {
                    CHECK(s.feed > 0);
                    CHECK(s.feed <= m.limits.max_feed + read_resolution(m).feed);
                    ++feeds;
                }
            CHECK(feeds >= 1);
        }
        // In inch, 1 mm/min would be F0 on a machine writing whole in/min: refused, never F0.
        if (m.accepts(Units::inch)) {
            Machine inch = m;
            inch.units = Units::inch;
            std::string text;
            try {
                text = post_program(read_job(path_job("[0, 0]", R"([{"line": [10, 0]}])", 1), "job.json"), inch);
            } catch (const InputError& e) {
                CHECK(has(e.what(), "would be written as F0"));
            }
            for (const std::string& line : lines_of(text))
                if (const auto w = words_of(line); w.count('F') && std::isdigit(static_cast<unsigned char>(w.at('F')[0])))
                    CHECK(std::stod(w.at('F')) > 0);
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: negative or zero pecks looping forever") {
    auto deep = [](const std::string& peck) {
        return holes_job(R"("tool": 1, "cycle": "deep", "retractPlane": 5, "endDepth": 18, "plungingFeedrate": 100, "firstDepth": )" + peck);
    };
    const auto ran = for_machines(every, [&](const Machine& m) {
        CHECK(has(refusal(deep("0"), m), "/operations/0/firstDepth: a peck depth must be > 0"));
        CHECK(has(refusal(deep("-1"), m), "/operations/0/firstDepth: a peck depth must be > 0"));
        // Below the resolution (written as 0) or so small that the pecks are beyond count.
        const std::string tiny = refusal(deep("0.00001"), m);
        CHECK((has(tiny, "below the resolution") || has(tiny, "more than 10000 pecks")));
        CHECK(has(refusal(deep("0.001"), m), "more than 10000 pecks for one hole"));
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: truncated output files") {
    // A run that fails part way (the second operation's speed would be written as S0) leaves
    // the old file as it was; a complete program ends with the control's end of program, and a
    // program cut short is refused when read back.
    const std::string fails_late = R"({"name": "field", "clearance": 20, "tools": [
  {"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}, {"number": 2, "type": "drill", "diameter": 5, "rpm": 0.4}],
 "operations": [{"type": "drill", "tool": 1, "retractPlane": 5, "endDepth": 6, "plungingFeedrate": 100, "holes": [[10, 10]]},
   {"type": "drill", "tool": 2, "retractPlane": 5, "endDepth": 6, "plungingFeedrate": 100, "holes": [[10, 10]]}]})";
    const auto ran = for_machines(every, [&](const Machine& m) {
        const fs::path dir = scratch("field-truncated-" + m.name);
        const fs::path out = dir / ("part." + m.extension);
        std::ofstream(out) << "old program\n";
        const Run bad = run({file_with("trunc-" + m.name, fails_late), "--machine", m.name, "-o", out.string()});
        CHECK(bad.code == 1);
        CHECK(read_file(out.string()) == "old program\n");
        CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
        const std::string text = post_and_read(sample("plate"), m).text;
        const auto lines = lines_of(text);
        for (size_t keep : {lines.size() / 2, lines.size() - 2}) {
            std::string cut;
            for (size_t i = 0; i < keep; ++i) cut += lines[i] + "\n";
            CAPTURE(keep);
            CHECK(error_of(cut, m.name) != "");
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: XY rapid before Z after a manual tool change") {
    // At the program start and after every tool change (an operator's M0 included) the tool's
    // height is unknown: the operator may have touched off on the stock. Read back, the first
    // rapid of each such stretch must have moved Z alone first, up to the job's clearance, and
    // only then X and Y.
    const auto ran = for_machines(every, [&](const Machine& m) {
        for (const std::string& s : samples_for(m)) {
            CAPTURE(s);
            const Job job = read_job(sample(s), s);
            const ReadBack r = post_and_read(job, m);
            const double slack = read_resolution(m).position;
            int approaches = 0;
            for (const ReadEvent& e : r.events) {
                const auto* rapid = std::get_if<Rapid>(&e.event);
                if (!rapid || !e.from_unknown) continue;
                CAPTURE(e.line);
                CHECK_MESSAGE(e.approach == Approach::z_first, "X or Y moved before Z while the height was unknown");
                CHECK_MESSAGE(rapid->to.z >= job.clearance - slack, "across below the clearance " << job.clearance << " at Z " << rapid->to.z);
                ++approaches;
            }
            CHECK(approaches >= 1);
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: tapping as plain feeds with a spindle reversal on a control that cannot synchronise") {
    // Where the control synchronises (or the machine file says a floating holder is fitted) the
    // tap is the control's own cycle; where it cannot, the tap is refused, never written as G1
    // moves with M4 that break a rigid tap (GRBL); asked for longhand on a rigid machine: refused.
    const std::string tap = holes_job(R"("tool": 2, "cycle": "tap", "retractPlane": 5, "safeDistance": 3, "endDepth": 12, "pitch": 1.25)");
    const std::string longhand = holes_job(R"("tool": 2, "cycle": "tap", "retractPlane": 5, "endDepth": 12, "pitch": 1.25, "output": "longhand")");
    const auto ran = for_machines(every, [&](const Machine& m) {
        if (m.tapping == TappingMode::none) {
            CHECK(has(refusal(tap, m), "/operations/0"));
            CHECK(has(refusal(tap, m), "cannot"));
            return;
        }
        int canned_taps = 0;
        for (const ReadEvent& e : post_and_read(tap, m).events)
            if (const auto* c = std::get_if<DrillCycle>(&e.event); c && c->kind == CycleKind::tap) ++canned_taps;
        CHECK(canned_taps >= 1);
        if (m.tapping == TappingMode::rigid) CHECK(has(refusal(longhand, m), "taps rigidly"));
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: a tap's feed clamped to the machine's limit") {
    // M12 x 1.75 at 12000 rpm: 21000 mm/min, above every built-in machine's maxFeed. The feed
    // must match the pitch: refused, never clamped.
    const std::string fast = holes_job(R"("tool": 2, "cycle": "tap", "retractPlane": 5, "safeDistance": 2, "endDepth": 10, "pitch": 1.75)", "[[10, 10]]");
    auto at_rpm = [&](const std::string& rpm) { return replace_once(fast, R"("rpm": 300)", R"("rpm": )" + rpm); };
    const auto ran = for_machines([](const Machine& m) { return m.tapping != TappingMode::none; }, [&](const Machine& m) {
        const std::string e = refusal(at_rpm("12000"), m);
        CHECK(has(e, "/operations/0/pitch: the tap's feed 21000 mm/min (pitch 1.75 mm x 12000 rpm) is above the limit of machine"));
        CHECK(has(e, "a tapping feed is never clamped, it must match the pitch"));
        // At a speed the machine can follow, the tap reads back at F = pitch x rpm.
        int taps = 0;
        for (const ReadEvent& ev : post_and_read(at_rpm("1000"), m).events)
            if (const auto* c = std::get_if<DrillCycle>(&ev.event); c && c->kind == CycleKind::tap) {
                CHECK(c->feed == doctest::Approx(1750));
                ++taps;
            }
        CHECK(taps == 1);
    });
    CHECK(ran == std::vector<std::string>{"fanuc", "heidenhain", "linuxcnc", "sinumerik"});
}

TEST_CASE("field failure: retract plane, clearance or safe distance below the stock top") {
    // Stock top at Z5: each of the three planes below it (or the clearance below the retract
    // plane) is refused with the key's path, and nothing is written.
    struct Case {
        const char* op;
        double clearance;
        const char* message;
    } cases[] = {
        {R"("referencePlane": 5, "retractPlane": 3, "safeDistance": 2, "safeDistanceIsAbsolute": true)", 20,
         "/operations/0/retractPlane: retractPlane (Z 3.000 mm) is not above referencePlane"},
        {R"("referencePlane": 5, "retractPlane": 8, "safeDistance": 3, "safeDistanceIsAbsolute": true)", 20,
         "/operations/0/safeDistance: the safe distance (Z 3.000 mm) is below referencePlane"},
        {R"("referencePlane": 5, "retractPlane": 30)", 20, "/operations/0/retractPlane: the clearance (Z 20.000) is below the retract plane"},
        {R"("referencePlane": 5, "retractPlane": 8)", 4, "the clearance"},
    };
    const auto ran = for_machines(every, [&](const Machine& m) {
        for (const Case& c : cases) {
            CAPTURE(c.op);
            const std::string job = holes_job(std::string(R"("tool": 1, "endDepth": 4, "plungingFeedrate": 100, )") + c.op,
                                              "[[10, 10], [30, 10]]", c.clearance);
            const Run r = run({"-", "--machine", m.name}, job);
            CHECK(r.code == 1);
            CHECK(r.out == "");
            CHECK(has(r.err, c.message));
        }
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: comment text copied raw (')', control bytes, '%')") {
    // Text from the job (names, tool comments, operation comments) reaches the program only as
    // safe text: printable ASCII, no control bytes that could end or split a block, no comment
    // terminators, no '%' inside a Fanuc program body.
    const std::string nasty = R"(a\u000bG0 Z-50\u000cM30\u0000 100% (x) \u007f \u00d810 Bohrung f\u00fcr M6 \u2603;)";
    const std::string job = R"({"name": ")" + nasty + R"(", "clearance": 10,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000, "comment": ")" + nasty + R"("}],
  "operations": [{"type": "drill", "tool": 1, "comment": ")" + nasty + R"(", "endDepth": 2,
                  "plungingFeedrate": 100, "holes": [[0, 0]]}]})";
    const auto ran = for_machines(every, [&](const Machine& m) {
        const ReadBack r = post_and_read(job, m);
        const bool parentheses = m.block.comment_style == nc::CommentStyle::parentheses;
        for (char c : r.text) {
            const unsigned char u = static_cast<unsigned char>(c);
            CHECK_MESSAGE((u == '\n' || u == '\r' || (u >= 0x20 && u < 0x7F)), "byte " << int(u));
        }
        for (const std::string& line : lines_of(r.text)) {
            // '%' only as Fanuc's tape marks, alone on a line.
            if (has(line, "%")) CHECK(line == "%");
            // A parenthesised comment never holds another '(' or ')'.
            const auto open = line.find('(');
            if (parentheses && open != std::string::npos) {
                CHECK(line.find('(', open + 1) == std::string::npos);
                CHECK(line.find(')') == line.size() - 1);
            }
        }
        // No text became a block: the program moves exactly as the job (no G0 Z-50, no M30).
        CHECK(round_trip(job, r.text, m.name) == "");
        // The text is still readable: umlauts and the diameter sign spelt out, the rest kept.
        CHECK(has(r.text, "D10 Bohrung fuer M6"));
        CHECK(has(r.text, "100pct"));
    });
    CHECK(ran == all_machines);
}

TEST_CASE("field failure: output renamed over a FIFO or device used for DNC") {
    // A FIFO is written into and stays what it is; no temporary is left. (A character device
    // takes the same path, every file that is not a regular one; it is not tried here, because
    // a broken camgen would replace the system's /dev/null.)
    const auto ran = for_machines(every, [&](const Machine& m) {
        const fs::path dir = scratch("field-fifo-" + m.name);
        const fs::path fifo = dir / "dnc";
        REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
        // The read end is open (without waiting for a writer) before camgen runs, and polled
        // until camgen is done: a camgen that replaced the FIFO leaves it empty, never a hang.
        const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
        REQUIRE(fd >= 0);
        std::atomic<bool> done = false;
        std::string received;
        std::thread reader([&] {
            char buffer[4096];
            for (;;) {
                const ssize_t n = ::read(fd, buffer, sizeof buffer);
                if (n > 0) received.append(buffer, static_cast<size_t>(n));
                else if (n == 0 && done) break;
                else std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
        });
        const Run r = run({CAMGEN_SOURCE_DIR "/samples/plate.json", "--machine", m.name, "-o", fifo.string()});
        done = true;
        reader.join();
        ::close(fd);
        CHECK(r.code == 0);
        struct stat st {};
        REQUIRE(::lstat(fifo.c_str(), &st) == 0);
        CHECK(S_ISFIFO(st.st_mode));
        CHECK(received == post_program(read_job(sample("plate"), CAMGEN_SOURCE_DIR "/samples/plate.json"), m));
        CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
    });
    CHECK(ran == all_machines);
}

}  // namespace test_field_failures
