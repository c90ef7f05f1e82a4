// LinuxCNC oracle (issue 4, part 7): for G81, G82, G83, G73, G85, G86 and G89, under G98 and
// G99, from a start Z above and below R, the canned program camgen writes for the `linuxcnc`
// machine and camgen's longhand program for the same cycle are both run through rs274 -g;
// their traverse and feed end points (within 0.001 mm), feeds, dwells and spindle changes
// must be identical. camgen's own reader must expand the canned programs as rs274 does.
// rs274 missing is a failure, never a silent pass.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "camgen/events/events.hpp"
#include "camgen/post/longhand.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "../unit/support.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_oracle {

using namespace camgen;
using OStep = camgen::oracle::Step;

namespace {

std::string rs274_path() {
    auto p = oracle::find_rs274();
    if (!p)
        FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace "
             "(scripts/install-deps --tests) or set CAMGEN_RS274 to its path");
    return *p;
}

struct Case {
    CycleKind kind;
    int mode;          // 98 or 99: the mode the canned program runs in
    double start_z;    // the tool's Z before the cycle
};

constexpr double r_plane = 2.0;
constexpr double bottom = -7.0;
const std::vector<Vec2> holes = {{10, 10}, {30, 10}, {30, 25}};

DrillCycle make_cycle(CycleKind kind, double retract_z, CycleOutput output) {
    DrillCycle c;
    c.kind = kind;
    c.output = output;
    c.path = "/operations/0";
    c.retract_z = retract_z;
    c.reference_z = 0.0;
    c.safe_z = r_plane;
    c.bottom_z = bottom;
    c.feed = 100.0;
    c.spindle_rpm = 1000.0;
    c.values.set(DrillField::plunging_feedrate, 100.0);
    if (kind == CycleKind::deep || kind == CycleKind::chip_break) c.values.set(DrillField::first_depth, 3.0);
    if (kind == CycleKind::dwell || kind == CycleKind::bore_dwell || kind == CycleKind::bore_stop)
        c.values.set(DrillField::bottom_dwell, 0.5);
    return c;
}

// The whole program for one cycle over `points`, starting from (0, 0, start_z).
std::string post(const DrillCycle& cycle, double start_z, const std::vector<Vec2>& points = holes) {
    Machine m = load_machine("linuxcnc");
    std::ostringstream out;
    PostOptions o;
    o.program_name = "oracle";
    auto p = make_post(m, out, o);
    p->open();
    p->emit(OperationStart{"oracle", "/operations/0", std::nullopt});
    p->emit(ToolChange{1, 6.0, "drill"});
    p->emit(Spindle{SpindleState::cw, 1000.0});
    p->emit(Rapid{{0, 0, start_z}});
    p->emit(cycle);
    for (Vec2 h : points) p->emit(DrillPoint{h});
    p->emit(DrillEnd{});
    Vec2 last = points.back();
    p->emit(Rapid{{last.x, last.y, 20.0}});
    p->emit(Spindle{SpindleState::off, 0.0});
    p->emit(OperationEnd{});
    p->close();
    return out.str();
}

std::string listing(const std::vector<OStep>& steps) {
    std::string s;
    for (const OStep& st : steps) s += "  " + oracle::describe(st) + "\n";
    return s;
}

void check_same(const std::vector<OStep>& canned, const std::vector<OStep>& longhand) {
    INFO("canned (rs274):\n" << listing(canned) << "longhand (rs274):\n" << listing(longhand));
    REQUIRE(canned.size() == longhand.size());
    for (size_t i = 0; i < canned.size(); ++i) {
        const OStep& a = canned[i];
        const OStep& b = longhand[i];
        INFO("step " << i << ": " << oracle::describe(a) << " vs " << oracle::describe(b));
        CHECK(a.kind == b.kind);
        CHECK(std::abs(a.to.x - b.to.x) <= 0.001);
        CHECK(std::abs(a.to.y - b.to.y) <= 0.001);
        CHECK(std::abs(a.to.z - b.to.z) <= 0.001);
        CHECK(std::abs(a.value - b.value) <= 0.001);
        CHECK(a.spindle == b.spindle);
    }
}

const char* code(CycleKind k) {
    switch (k) {
        case CycleKind::drill: return "G81";
        case CycleKind::dwell: return "G82";
        case CycleKind::deep: return "G83";
        case CycleKind::chip_break: return "G73";
        case CycleKind::ream: return "G85";
        case CycleKind::bore_stop: return "G86";
        case CycleKind::bore_dwell: return "G89";
        default: return "?";
    }
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("rs274 is installed: the oracle tests cannot be skipped") {
    const std::string rs274 = rs274_path();
    auto steps = oracle::run_rs274(rs274, "G21 G90\nG0 X1 Y2 Z3\nG1 Z-1 F50\nG4 P0.5\nM2\n");
    REQUIRE(steps.size() == 3);
    CHECK(oracle::describe(steps[0]) == "traverse (1.0000, 2.0000, 3.0000)");
    CHECK(oracle::describe(steps[1]) == "feed (1.0000, 2.0000, -1.0000) F50.0000");
    CHECK(oracle::describe(steps[2]) == "dwell 0.5000 s");
    // A program rs274 rejects is an error, not an empty list.
    CHECK_THROWS_WITH_AS(oracle::run_rs274(rs274, "G0 X1\nG81 X1 Y1 Z-1 F10\nM2\n"),
                         doctest::Contains("R clearance plane unspecified"), std::runtime_error);
}

TEST_CASE("canned cycles on linuxcnc move exactly as camgen's longhand: G98/G99, start above/below R") {
    const std::string rs274 = rs274_path();
    for (CycleKind kind : {CycleKind::drill, CycleKind::dwell, CycleKind::deep, CycleKind::chip_break,
                           CycleKind::ream, CycleKind::bore_stop, CycleKind::bore_dwell}) {
        for (Case c : {Case{kind, 98, 10.0}, Case{kind, 99, 10.0}, Case{kind, 98, 0.5}, Case{kind, 99, 0.5}}) {
            // G98 returns to the start Z when it is above R; from below R both modes return to R.
            const double retract = c.mode == 98 ? std::max(c.start_z, r_plane) : r_plane;
            std::string canned = post(make_cycle(kind, retract, CycleOutput::canned), c.start_z);
            const std::string longhand = post(make_cycle(kind, retract, CycleOutput::longhand), c.start_z);
            // camgen writes G99 when the retract level is R; run the G98 case as G98.
            const int written = retract > r_plane ? 98 : 99;
            if (written != c.mode) {
                auto at = canned.find(fmt::format("G{} {}", written, code(kind)));
                REQUIRE(at != std::string::npos);
                canned.replace(at, 3, fmt::format("G{}", c.mode));
            }
            INFO(fmt::format("{} G{} from Z{}\n--- canned ---\n{}--- longhand ---\n{}", code(kind), c.mode, c.start_z,
                             canned, longhand));
            REQUIRE(contains(canned, fmt::format("G{} {} X10 Y10 Z-7 R2", c.mode, code(kind))));
            REQUIRE_FALSE(contains(longhand, code(kind)));
            check_same(oracle::run_rs274(rs274, canned), oracle::run_rs274(rs274, longhand));
        }
    }
}

TEST_CASE("worked example: G99 G73 X10 Y10 Z-7 R2 Q3 and its longhand") {
    const std::string rs274 = rs274_path();
    DrillCycle c = make_cycle(CycleKind::chip_break, r_plane, CycleOutput::canned);
    const std::string canned = post(c, r_plane, {{10, 10}});
    REQUIRE(contains(canned, "G99 G73 X10 Y10 Z-7 R2 Q3 F100\n"));
    c.output = CycleOutput::longhand;
    const std::string longhand = post(c, r_plane, {{10, 10}});
    // From (0, 0, 2): across to the hole at R, then pecks of 3 mm from R with a back-off of
    // the peck clearance after each, the last one ending at Z-7 (LinuxCNC G73 semantics).
    const std::vector<std::pair<char, double>> expected = {{'T', 2},  {'F', -1},     {'T', -0.746}, {'F', -4},
                                                          {'T', -3.746}, {'F', -7}, {'T', 2}};
    for (const std::string& program : {canned, longhand}) {
        INFO(program);
        auto steps = oracle::run_rs274(rs274, program);
        // Skip the tool-change approach: find the traverse to (10, 10, 2).
        size_t i = 0;
        while (i < steps.size() && !(steps[i].to.x == 10 && steps[i].to.y == 10)) ++i;
        REQUIRE(i + expected.size() <= steps.size());
        for (size_t k = 0; k < expected.size(); ++k) {
            const OStep& s = steps[i + k];
            INFO("step " << k << ": " << oracle::describe(s));
            CHECK(s.kind == (expected[k].first == 'T' ? OStep::Kind::traverse : OStep::Kind::feed));
            CHECK(s.to.z == doctest::Approx(expected[k].second).epsilon(1e-9));
            if (s.kind == OStep::Kind::feed) CHECK(s.value == 100.0);
        }
    }
}

TEST_CASE("FreeCAD 0.20 grbl defect: G83 under G98 from Z10 with R2 feeds its first peck from R") {
    const std::string rs274 = rs274_path();
    DrillCycle c = make_cycle(CycleKind::deep, 10.0, CycleOutput::longhand);
    // The events themselves: rapid down to R, then the first feed from R to R - Q.
    std::vector<LonghandMove> ev = longhand_moves(c, {10, 10, 10}, {10, 10}, load_machine("linuxcnc").longhand());
    REQUIRE(ev.size() >= 2);
    CHECK(std::get<Rapid>(ev[0]).to.z == 2.0);
    CHECK(std::get<Linear>(ev[1]).to.z == -1.0);
    // And on the control: canned G98 G83 and the longhand agree, the first feed starting at Z2.
    const std::string longhand = post(c, 10.0, {{10, 10}});
    c.output = CycleOutput::canned;
    const std::string canned = post(c, 10.0, {{10, 10}});
    REQUIRE(contains(canned, "G98 G83 X10 Y10 Z-7 R2 Q3 F100\n"));
    auto a = oracle::run_rs274(rs274, canned);
    auto b = oracle::run_rs274(rs274, longhand);
    check_same(a, b);
    size_t first_feed = 0;
    while (first_feed < b.size() && b[first_feed].kind != OStep::Kind::feed) ++first_feed;
    REQUIRE(first_feed > 0);
    REQUIRE(first_feed < b.size());
    CHECK(b[first_feed - 1].to.z == 2.0);  // the move before the first feed ends at R
    CHECK(b[first_feed].to.z == -1.0);
}

TEST_CASE("every linuxcnc golden file runs through rs274; G33.1 is a rigid tap to the hole bottom") {
    const std::string rs274 = rs274_path();
    namespace fs = std::filesystem;
    int files = 0;
    int rigid_taps_checked = 0;
    for (const auto& entry : fs::directory_iterator(CAMGEN_SOURCE_DIR "/tests/golden/linuxcnc")) {
        if (entry.path().extension() != ".ngc") continue;
        ++files;
        std::ifstream f(entry.path());
        std::stringstream text;
        text << f.rdbuf();
        INFO(entry.path().string());
        std::vector<OStep> steps;
        // The sample's tools in the tool table: cutter compensation offsets by their radius.
        const fs::path sample = fs::path(CAMGEN_SOURCE_DIR "/samples") / (entry.path().stem().string() + ".json");
        std::ifstream job_file(sample);
        std::stringstream job_text;
        job_text << job_file.rdbuf();
        const std::map<int, double> diameters = test::tool_diameters(read_job(job_text.str(), sample.string()));
        REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274, text.str(), diameters));
        CHECK_FALSE(steps.empty());
        if (entry.path().stem() == "tapping-rigid") {
            // Two M8 holes to Z-12, two left-hand M6 holes to Z-10.
            int taps = 0;
            for (const OStep& s : steps)
                if (s.kind == OStep::Kind::rigid_tap) {
                    ++taps;
                    CHECK((s.to.z == -12.0 || s.to.z == -10.0));
                }
            CHECK(taps == 4);
            ++rigid_taps_checked;
        }
    }
    CHECK(files >= 3);
    CHECK(rigid_taps_checked == 1);
}

namespace {

// The steps from the first move that reaches the first hole's XY on: the approach after the
// tool change differs in how the two sides know the start (rs274 from its origin).
std::vector<OStep> from_first_hole(const std::vector<OStep>& steps) {
    auto it = std::find_if(steps.begin(), steps.end(), [](const OStep& s) {
        return (s.kind == OStep::Kind::traverse || s.kind == OStep::Kind::feed) && s.to.x == holes[0].x && s.to.y == holes[0].y;
    });
    return {it, steps.end()};
}

}  // namespace

TEST_CASE("camgen's reader expands the canned cycles exactly as LinuxCNC does") {
    const std::string rs274 = rs274_path();
    const Machine machine = load_machine("linuxcnc");
    int compared = 0;
    for (CycleKind kind : {CycleKind::drill, CycleKind::dwell, CycleKind::deep, CycleKind::chip_break,
                           CycleKind::ream, CycleKind::bore_stop, CycleKind::bore_dwell}) {
        for (double start_z : {10.0, 0.5}) {
            const double retract = std::max(start_z, r_plane);
            const std::string canned = post(make_cycle(kind, retract, CycleOutput::canned), start_z);
            INFO(fmt::format("{} from Z{}\n{}", code(kind), start_z, canned));
            REQUIRE(contains(canned, fmt::format(" {} X10 Y10 Z-7 R2", code(kind))));
            auto oracle_steps = from_first_hole(oracle::run_rs274(rs274, canned));
            auto camgen_steps = from_first_hole(oracle::read_with_camgen(canned, machine));
            REQUIRE(oracle_steps.size() > 3);
            check_same(oracle_steps, camgen_steps);
            ++compared;
        }
    }
    CHECK(compared == 14);
}

namespace {

// One combination of the optional parameters a linuxcnc canned cycle carries.
struct Variant {
    std::string name;           // for messages
    double retract_z;           // retract plane; R is r_plane (equal: no safeDistance)
    std::optional<double> dwell;  // bottomDwell, absent when nullopt
    std::optional<double> peck;   // firstDepth of the pecking kinds
};

// Every combination of the optional fields linuxcnc's canned cycle of `kind` carries: with
// and without a separate feed-start plane, without a dwell, with a zero and with a real dwell,
// one peck and several.
std::vector<Variant> variants(CycleKind kind, const DrillingCycleSpec& spec) {
    auto carries = [&](DrillField f) { return std::find(spec.fields.begin(), spec.fields.end(), f) != spec.fields.end(); };
    std::vector<std::optional<double>> dwells = {std::nullopt};
    if (carries(DrillField::bottom_dwell)) dwells = {std::nullopt, 0.0, 0.5};
    if (info(DrillField::bottom_dwell).required_by.contains(kind)) dwells = {0.0, 0.5};
    std::vector<std::optional<double>> pecks = {std::nullopt};
    if (is_pecking(kind)) pecks = {3.0, 20.0};
    std::vector<Variant> out;
    for (double retract : {r_plane, 10.0})
        for (auto dwell : dwells)
            for (auto peck : pecks)
                out.push_back({fmt::format("retract {}, dwell {}, peck {}", retract, dwell ? fmt::format("{}", *dwell) : "none",
                                           peck ? fmt::format("{}", *peck) : "none"),
                               retract, dwell, peck});
    return out;
}

}  // namespace

// Field failure (REFERENCE.md §6): LinuxCNC G86/G89 without P ("Dwell time p word missing").
TEST_CASE("field failure: a canned-cycle word the control requires left out (G86/G89 without P): every linuxcnc "
          "canned cycle is word-complete with and without each optional parameter") {
    const std::string rs274 = rs274_path();
    const Machine machine = load_machine("linuxcnc");
    int compared = 0;
    for (CycleKind kind : {CycleKind::drill, CycleKind::dwell, CycleKind::deep, CycleKind::chip_break,
                           CycleKind::ream, CycleKind::bore_stop, CycleKind::bore_dwell}) {
        const DrillingCycleSpec* spec = machine.canned_cycle(kind);
        REQUIRE(spec);
        for (const Variant& v : variants(kind, *spec)) {
            DrillCycle c = make_cycle(kind, v.retract_z, CycleOutput::canned);
            c.values.set(DrillField::bottom_dwell, v.dwell);
            c.values.set(DrillField::first_depth, v.peck);
            const std::string canned = post(c, 10.0);
            c.output = CycleOutput::longhand;
            const std::string longhand = post(c, 10.0);
            INFO(fmt::format("{} {}\n--- canned ---\n{}--- longhand ---\n{}", code(kind), v.name, canned, longhand));
            REQUIRE(contains(canned, fmt::format(" {} X10 Y10 Z-7 R2", code(kind))));
            std::vector<OStep> a, b;
            REQUIRE_NOTHROW(a = oracle::run_rs274(rs274, canned));
            REQUIRE_NOTHROW(b = oracle::run_rs274(rs274, longhand));
            check_same(a, b);
            // camgen's own reader accepts what it wrote (P0 included) and moves the same way.
            check_same(from_first_hole(a), from_first_hole(oracle::read_with_camgen(canned, machine)));
            ++compared;
        }
    }
    CHECK(compared == 2 * (1 + 2 + 2 + 2 + 1 + 3 + 2));
}

}  // namespace test_oracle
