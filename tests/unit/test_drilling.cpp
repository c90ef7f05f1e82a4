// Drilling on every machine: the key numbers of one hole of each cycle kind in
// samples/drilling.json and samples/tapping.json (worked out by hand), canned/longhand
// choice and its errors, peck depths, hole order, and the cycle table of docs/reference.md.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "camgen/cli/cli.hpp"
#include "camgen/post/capabilities.hpp"
#include "camgen/post/longhand.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_drilling {

using namespace camgen;
using namespace camgen::test;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string drilling(const std::string& machine) {
    return post_job(read_file(CAMGEN_SOURCE_DIR "/samples/drilling.json"), machine).text;
}
std::string tapping(const std::string& machine) {
    return post_job(read_file(CAMGEN_SOURCE_DIR "/samples/tapping.json"), machine).text;
}
// samples/tapping-rigid.json: taps with one speed in and out, which rigid canned cycles carry.
std::string tapping_rigid(const std::string& machine) {
    return post_job(read_file(CAMGEN_SOURCE_DIR "/samples/tapping-rigid.json"), machine).text;
}

// Records events.
struct Recorder : EventSink {
    std::vector<Event> events;
    void emit(const Event& e) override { events.push_back(e); }
};

// XY length of the moves between holes: from each drill point to the next.
double rapid_xy_length(const std::vector<Event>& events) {
    double length = 0.0;
    std::optional<Vec2> last;
    for (const Event& e : events)
        if (const auto* p = std::get_if<DrillPoint>(&e)) {
            if (last) length += std::hypot(p->at.x - last->x, p->at.y - last->y);
            last = p->at;
        }
    return length;
}

std::vector<Vec2> drilled(const std::vector<Event>& events) {
    std::vector<Vec2> v;
    for (const Event& e : events)
        if (const auto* p = std::get_if<DrillPoint>(&e)) v.push_back(p->at);
    return v;
}

}  // namespace

TEST_CASE("fanuc: G82 P in ms, G81/G83/G73/G84/G89 canned, the rest longhand") {
    const std::string t = drilling("fanuc");
    // dwell: grid rotated 10 degrees; retract 5 above R2: G98; 0.5 s = P500.
    CHECK(has(t, "G98 G82 X10.000 Y10.000 Z-2.000 R2.000 P500 F100\n"));
    CHECK(has(t, "X29.696 Y13.473\n"));  // (10 + 20 cos 10, 10 + 20 sin 10)
    // drill: 8 mm + tip 3 / tan(59 deg) = 9.803; R = 0 + 1.
    CHECK(has(t, "G98 G81 X10.000 Y10.000 Z-9.803 R1.000 F120\n"));
    // deep: bolt circle r15 around (50, 30) from 45 degrees.
    CHECK(has(t, "G98 G83 X60.607 Y40.607 Z-20.000 R2.000 Q6.000 F150\n"));
    // deep with degression 2, minimum 2.5, first feed 160 x 0.5, top dwell 0.2 s: longhand
    // from R1: pecks to -5, -9, -11.5, -14, -15; re-approach 1 mm above the last peck.
    CHECK(has(t, "G4 P200\nN230 G1 Z-5.000 F80\nN235 G0 Z1.000\nN240 G4 P200\nN245 Z-4.000\nN250 G1 Z-9.000 F160\n"));
    CHECK(has(t, "G1 Z-11.500\n"));
    CHECK(has(t, "G1 Z-14.000\n"));
    CHECK(has(t, "G1 Z-15.000\nN315 G0 Z10.000\n"));
    // chip-break without a back-off: G73 canned.
    CHECK(has(t, "G98 G73 X10.000 Y55.000 Z-7.000 R1.000 Q2.500 F90\n"));
    // chip-break with peckingRetract 0.3 and factor 0.8: longhand, pecks 2, 1.6, 1.28, ...
    CHECK(has(t, "G1 Z-1.000\nN505 G0 Z-0.700\nN510 G1 Z-2.600\nN515 G0 Z-2.300\nN520 G1 Z-3.880\n"));
    // ream with a retract feed (G85 has none): longhand.
    CHECK(has(t, "G1 Z-10.000 F60\nN605 Z2.000 F300\nN610 G0 Z5.000\n"));
    // bore-stop with a dwell (Fanuc G86 has no P): longhand dwell, stop, rapid out, restart.
    CHECK(has(t, "G1 Z-12.000 F40\nN685 G4 P300\nN690 M5\nN695 G0 Z5.000\nN700 S800 M3\n"));
    CHECK(has(t, "G98 G89 X50.000 Y30.000 Z-14.000 R2.000 P1000\n"));
    const std::string tap = tapping("fanuc");
    // tap: F = 1.25 x 300.
    CHECK(has(tap, "G98 G84 X10.000 Y10.000 Z-12.000 R3.000 F375\n"));
    // tap-left with its own speeds: longhand, M4 at 200 rpm in, M3 at 400 out, 300 restored.
    CHECK(has(tap, "S200 M4\nN100 G1 Z-10.000 F200\nN105 S400 M3\nN110 Z3.000 F400\nN115 S300 M3\n"));
}

TEST_CASE("linuxcnc: P in seconds, 0.254 mm peck clearance, G86 with P, G33.1 rigid tapping") {
    const std::string t = drilling("linuxcnc");
    CHECK(has(t, "G98 G82 X10 Y10 Z-2 R2 P0.5 F100\n"));
    CHECK(has(t, "G98 G83 X60.6066 Y40.6066 Z-20 R2 Q6 F150\n"));
    CHECK(has(t, "G98 G73 X10 Y55 Z-7 R1 Q2.5 F90\n"));
    // longhand degression pecks re-approach 0.254 above the last peck.
    CHECK(has(t, "G1 Z-5 F80\nG0 Z1\nG4 P0.2\nZ-4.746\nG1 Z-9 F160\n"));
    CHECK(has(t, "G98 G86 X50 Y30 Z-12 R2 P0.3 F40\n"));
    CHECK(has(t, "G98 G89 X50 Y30 Z-14 R2 P1\n"));
    const std::string tap = tapping_rigid("linuxcnc");
    CHECK(has(tap, "Z3\nG33.1 Z-12 K1.25\nG0 Z5\nX30\nZ3\nG33.1 Z-12 K1.25\n"));
    CHECK(has(tap, "S300 M4\nZ3\nG33.1 Z-10 K1\n"));
    CHECK_FALSE(has(tap, "G84"));
    CHECK_FALSE(has(tap, "\nG1 "));
    // Separate tapping and retract speeds: G33.1 cannot carry them, and longhand would break the tap.
    CHECK_THROWS_WITH_AS(tapping("linuxcnc"),
                         doctest::Contains("machine linuxcnc taps rigidly and its G33.1 cannot carry tappingSpeed, retractSpeed"),
                         InputError);
}

TEST_CASE("grbl: everything longhand, no G98/G99/G80/M6, G4 P in seconds, M0 for tools") {
    CHECK_THROWS_WITH_AS(tapping("grbl"), doctest::Contains("machine grbl cannot synchronise the spindle to the feed"),
                         InputError);
    for (const std::string& t : {drilling("grbl")}) {
        for (std::string banned : {"G73", "G8", "G98", "G99", "M6\n", "G43", "%"}) {
            INFO(banned);
            CHECK_FALSE(has(t, banned));
        }
    }
    const std::string t = drilling("grbl");
    CHECK(has(t, "(Insert tool 1: 10 mm spot drill - spot drill 90 deg)\nM0\nS1500 M3\n"));
    CHECK(has(t, "G1 Z-2 F100\nG4 P0.5\nG0 Z5\n"));
    // deep on the bolt circle, pecks of 6 from R2: -4, -10, -16, -20; re-approach 0.5 above.
    CHECK(has(t, "Z2\nG1 Z-4 F150\nG0 Z2\nZ-3.5\nG1 Z-10\nG0 Z2\nZ-9.5\nG1 Z-16\nG0 Z2\nZ-15.5\nG1 Z-20\nG0 Z10\n"));
    // chip-break: back off 0.5 after pecks of 2.5 from R1.
    CHECK(has(t, "G1 Z-1.5 F90\nG0 Z-1\nG1 Z-4\nG0 Z-3.5\nG1 Z-6.5\nG0 Z-6\nG1 Z-7\nG0 Z3\n"));
    // bore-dwell feeds out to R (the grbl machine emulates Fanuc G89).
    CHECK(has(t, "Z2\nG1 Z-14\nG4 P1\nZ2\nG0 Z10\n"));
}

TEST_CASE("wabeco: longhand pecks with 1 mm clearance, dwell in 1/18 s, no tapping") {
    const std::string t = drilling("wabeco");
    CHECK(has(t, "G01 Z-2 F16.7\nM30 P9\nG00 Z5\n"));   // 100 mm/min = 16.7 x 0.1 mm/s; 0.5 s = 9/18 s
    CHECK(has(t, "G01 Z-4 F25\nG00 Z2\nG00 Z-3\nG01 Z-10\n"));
    CHECK_FALSE(has(t, "G81"));  // every cycle here has a safe distance, which G81 ... B cannot carry
    CHECK_THROWS_WITH_AS(tapping("wabeco"),
                         doctest::Contains("machine wabeco cannot tap: its spindle cannot run counter-clockwise, so a "
                                           "right-hand tap cannot be backed out of the hole"),
                         InputError);
}

TEST_CASE("sinumerik: MCALL CYCLE81-89 parameter lists") {
    const std::string t = drilling("sinumerik");
    CHECK(has(t, "F100\nN90 MCALL CYCLE82(5.000, 0.000, 2.000, -2.000, , 0.5)\nN100 G0 X10.000 Y10.000\n"));
    CHECK(has(t, "MCALL CYCLE81(5.000, 0.000, 1.000, -9.803)\n"));
    // deep: FDEP = R2 - 6 = -4, FRF 1, VARI 1, _DIS1 = peck clearance 1.
    CHECK(has(t, "MCALL CYCLE83(10.000, 0.000, 2.000, -20.000, , -4.000, , , , , 1.000, 1, , , , , 1.000)\n"));
    // degression: FDEP 1 - 6 = -5, DAM 2, DTS 0.2, FRF 0.5, _MDEP 2.5.
    CHECK(has(t, "MCALL CYCLE83(10.000, 0.000, 1.000, -15.000, , -5.000, , 2.000, , 0.2, 0.500, 1, , 2.500, , , 1.000)\n"));
    // chip-break: VARI 0, _VRT = peck clearance 1.
    CHECK(has(t, "MCALL CYCLE83(3.000, 0.000, 1.000, -7.000, , -1.500, , , , , 1.000, 0, , , 1.000)\n"));
    // a degression factor: DAM takes values only -> longhand.
    CHECK(has(t, "G1 Z-1.000\nN760 G0 Z-0.700\n"));
    CHECK(has(t, "MCALL CYCLE85(5.000, 0.000, 2.000, -10.000, , , 60, 300)\n"));
    CHECK(has(t, "MCALL CYCLE86(5.000, 0.000, 2.000, -12.000, , 0.3, 3, 0, 0, 0, 0)\n"));
    CHECK(has(t, "MCALL CYCLE89(10.000, 0.000, 2.000, -14.000, , 1)\n"));
    CHECK(has(t, "N1150 MCALL\n"));
    const std::string tap = tapping("sinumerik");
    CHECK(has(tap, "MCALL CYCLE84(5.000, 0.000, 3.000, -12.000, , , 3, , 1.250, 0, 300, 300)\n"));
    CHECK(has(tap, "MCALL CYCLE84(5.000, 0.000, 3.000, -10.000, , , 3, , -1.000, 0, 200, 400)\n"));
}

TEST_CASE("heidenhain: CYCL DEF 200/203/207 Q values, M99 per hole, the rest longhand") {
    const std::string t = drilling("heidenhain");
    CHECK(has(t, "CYCL DEF 200 DRILLING ~\n  Q200=+2 ;SET-UP CLEARANCE ~\n  Q201=-2 ;DEPTH ~\n  Q206=+100 ;FEED RATE FOR PLNGNG ~\n"
                 "  Q202=+2 ;PLUNGING DEPTH ~\n  Q210=+0 ;DWELL TIME AT TOP ~\n  Q203=+0 ;SURFACE COORDINATE ~\n"
                 "  Q204=+5 ;2ND SET-UP CLEARANCE ~\n  Q211=+0.5 ;DWELL TIME AT DEPTH\n"));
    CHECK(has(t, " L X+10 Y+10 R0 FMAX M99\n"));
    CHECK(has(t, "CYCL DEF 203 UNIVERSAL DRILLING ~\n  Q200=+2 ;SET-UP CLEARANCE ~\n  Q201=-20 ;DEPTH ~\n"
                 "  Q206=+150 ;FEED RATE FOR PLNGNG ~\n  Q202=+6 ;PLUNGING DEPTH ~\n"));
    CHECK(has(t, "  Q213=+0 ;NR OF BREAKS ~\n"));
    CHECK(has(t, "  Q213=+99 ;NR OF BREAKS ~\n  Q205=+0 ;MIN. PLUNGING DEPTH ~\n  Q211=+0 ;DWELL TIME AT DEPTH ~\n"
                 "  Q208=+99999 ;RETRACTION FEED RATE ~\n  Q256=+0.5 ;DIST FOR CHIP BRKNG\n"));
    // the first-feed factor has no Q parameter: longhand, first peck at 80.
    CHECK(has(t, "CYCL DEF 9.1 DWELL 0.2\n"));
    CHECK(has(t, " L Z-5 F80\n"));
    CHECK_THROWS_WITH_AS(tapping("heidenhain"), doctest::Contains("machine heidenhain taps rigidly"), InputError);
    const std::string tap = tapping_rigid("heidenhain");
    CHECK(has(tap, "CYCL DEF 207 RIGID TAPPING NEW ~\n  Q200=+3 ;SET-UP CLEARANCE ~\n  Q201=-12 ;DEPTH ~\n"
                   "  Q239=+1.25 ;PITCH ~\n  Q203=+0 ;SURFACE COORDINATE ~\n  Q204=+5 ;2ND SET-UP CLEARANCE\n"));
    CHECK(has(tap, "  Q239=-1 ;PITCH ~\n"));
}

TEST_CASE("output canned names each parameter the machine's cycle lacks; output longhand forces longhand") {
    const std::string job = R"({"clearance": 10, "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
      "operations": [{"type": "drill", "tool": 1, "cycle": "deep", "endDepth": 10, "firstDepth": 2,
      "plungingFeedrate": 100, "firstFeedrateFactor": 0.5, "topDwell": 1, "output": "canned", "holes": [[0, 0]]}]})";
    try {
        post_job(job, "fanuc");
        FAIL("accepted");
    } catch (const InputError& e) {
        CHECK(e.path() == "/operations/0/output");
        CHECK(has(e.detail(), "machine fanuc's G83 cannot carry firstFeedrateFactor, topDwell; it carries: "
                              "safeDistance, plungingFeedrate, firstDepth"));
    }
    CHECK(has(post_job(job, "sinumerik").text, "MCALL CYCLE83("));
    CHECK_THROWS_WITH_AS(post_job(job, "grbl"), doctest::Contains("machine grbl has no canned cycle for \"deep\""),
                         InputError);
    // A value the cycle cannot express: Sinumerik's DAM is a value, not a factor.
    std::string factor = job;
    factor.replace(factor.find("\"firstFeedrateFactor\": 0.5, \"topDwell\": 1"), 41,
                   "\"degressionType\": \"factor\", \"degression\": 0.8, \"minimumDepth\": 1");
    CHECK_THROWS_WITH_AS(post_job(factor, "sinumerik"), doctest::Contains("DAM takes a degression value, not a factor"),
                         InputError);
    std::string longhand = job;
    longhand.replace(longhand.find("\"canned\""), 8, "\"longhand\"");
    CHECK_FALSE(has(post_job(longhand, "sinumerik").text, "CYCLE83"));
}

TEST_CASE("peck depths: from the feed-start plane, degression bounded by minimumDepth, last at the bottom") {
    DrillCycle c;
    c.kind = CycleKind::deep;
    c.safe_z = 2.0;
    c.bottom_z = -7.0;
    c.values.set(DrillField::first_depth, 3.0);
    CHECK(peck_depths(c) == std::vector<double>{-1.0, -4.0, -7.0});
    c.values.set_degression_type(DegressionType::value);
    c.values.set(DrillField::degression, 1.0);
    c.values.set(DrillField::minimum_depth, 1.5);
    c.bottom_z = -10.0;
    // 3, 2, 1.5, 1.5, ... from 2: -1, -3, -4.5, -6, -7.5, -9, -10
    CHECK(peck_depths(c) == std::vector<double>{-1.0, -3.0, -4.5, -6.0, -7.5, -9.0, -10.0});
    c.kind = CycleKind::drill;
    CHECK(peck_depths(c) == std::vector<double>{-10.0});
}

TEST_CASE("order shortest: same holes, first hole first, measurably shorter rapid path") {
    // Holes on a line given in zig-zag order: as given the tool crosses the plate again and again.
    std::string holes;
    for (int i = 0; i < 10; ++i) holes += fmt::format("{}[{}, 0]", i ? ", " : "", i % 2 ? 100 - 10 * (i / 2) : 10 * (i / 2));
    auto job = [&](const char* order) {
        return fmt::format(R"({{"clearance": 10, "tools": [{{"number": 1, "diameter": 5, "rpm": 1000}}],
          "operations": [{{"type": "drill", "tool": 1, "endDepth": 3, "plungingFeedrate": 100,
          "order": "{}", "holes": [{}]}}]}})", order, holes);
    };
    Recorder given, shortest;
    expand_job(read_job(job("as-given"), "j.json"), given);
    expand_job(read_job(job("shortest"), "j.json"), shortest);
    const double a = rapid_xy_length(given.events), b = rapid_xy_length(shortest.events);
    // as given (0, 100, 10, 90, ..., 40, 60): 100 + 90 + ... + 20 = 540; shortest: along the
    // line from 0 to 100 = 100.
    CHECK(a == doctest::Approx(540.0));
    CHECK(b == doctest::Approx(100.0));
    // --stats reads the program back and counts the same rapid XY path (the first approach
    // after the tool change, from an unknown position, is not counted).
    for (const char* order : {"as-given", "shortest"}) {
        const std::string text = job(order);
        std::vector<const char*> argv{"camgen", "-", "--machine", "fanuc", "--stats"};
        std::istringstream in(text);
        std::ostringstream out, err;
        CHECK(run_cli(static_cast<int>(argv.size()), argv.data(), in, out, err) == 0);
        CHECK(has(err.str(), std::string(order) == "shortest" ? "rapid in XY    100.000 mm\n" : "rapid in XY    540.000 mm\n"));
        CHECK(has(err.str(), "holes          10\n"));
    }
    auto g = drilled(given.events), s = drilled(shortest.events);
    CHECK(s.front() == g.front());
    auto key = [](Vec2 p, Vec2 q) { return std::tie(p.x, p.y) < std::tie(q.x, q.y); };
    std::sort(g.begin(), g.end(), key);
    std::sort(s.begin(), s.end(), key);
    CHECK(g == s);
}

TEST_CASE("order shortest: nearest neighbour plus 2-opt gives a good tour of random holes") {
    // 300 random holes: the result must be a good tour, far shorter than the given order.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 100.0);
    std::vector<Vec2> pts(300);
    for (Vec2& p : pts) p = {u(rng), u(rng)};
    auto length = [](const std::vector<Vec2>& v) {
        double l = 0;
        for (size_t i = 1; i < v.size(); ++i) l += std::hypot(v[i].x - v[i - 1].x, v[i].y - v[i - 1].y);
        return l;
    };
    std::vector<Vec2> order = shortest_order(pts);
    CHECK(order.front() == pts.front());
    CHECK(order.size() == pts.size());
    // For these holes nearest neighbour alone gives 0.92 sqrt(nA), with 2-opt 0.82 sqrt(nA)
    // (the optimum is about 0.75 sqrt(nA) for a path).
    CHECK(length(order) < 0.86 * std::sqrt(300.0 * 100 * 100));
    CHECK(length(order) < length(pts) / 5);
}

TEST_CASE("order shortest: 2-opt at its bound of 2000 holes finishes") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 500.0);
    std::vector<Vec2> pts(max_two_opt_holes);
    for (Vec2& p : pts) p = {u(rng), u(rng)};
    CHECK(shortest_order(pts).size() == pts.size());
}

TEST_CASE("order shortest stays fast for large jobs (nearest neighbour on a grid, no 2-opt above the bound)") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1000.0);
    std::vector<Vec2> pts(200000);
    for (Vec2& p : pts) p = {u(rng), u(rng)};
    std::vector<Vec2> order = shortest_order(pts);
    REQUIRE(order.size() == pts.size());
    CHECK(order.front() == pts.front());
    double l = 0;
    for (size_t i = 1; i < order.size(); ++i) l += std::hypot(order[i].x - order[i - 1].x, order[i].y - order[i - 1].y);
    // Nearest neighbour is within about 25 % of the optimum ~ 0.7124 sqrt(n A).
    CHECK(l < 1.3 * 0.7124 * std::sqrt(200000.0 * 1000 * 1000));
}

namespace {

// docs/reference.md's table of cycle kinds x machines of one kind, generated from the machine files.
std::string cycle_table(MachineKind kind) {
    std::vector<Machine> machines;
    for (const auto& [name, description] : list_machines())
        if (Machine m = load_machine(name); m.kind == kind) machines.push_back(std::move(m));
    std::string s = "| cycle |";
    for (const Machine& m : machines) s += " " + m.name + " |";
    s += "\n| --- |";
    for (size_t i = 0; i < machines.size(); ++i) s += " --- |";
    s += "\n";
    for (CycleKind k : {CycleKind::drill, CycleKind::dwell, CycleKind::deep, CycleKind::chip_break, CycleKind::tap,
                        CycleKind::tap_left, CycleKind::ream, CycleKind::bore_stop, CycleKind::bore_dwell}) {
        // A turn-drill makes no reaming or boring cycles.
        if (kind == MachineKind::lathe && (k == CycleKind::ream || k == CycleKind::bore_stop || k == CycleKind::bore_dwell))
            continue;
        s += fmt::format("| `{}` |", std::string(name_of(cycle_kinds, k)));
        for (const Machine& m : machines) {
            // What the post makes of the kind (the capability its refusals and --describe-machine use).
            const MachineCapabilities can = machine_capabilities(m);
            const auto c = std::find_if(can.cycles.begin(), can.cycles.end(), [&](const CycleCapability& x) { return x.kind == k; });
            REQUIRE(c != can.cycles.end());
            if (c->refused) s += " refused |";
            else s += c->canned ? fmt::format(" `{}` |", c->canned->name) : std::string(" longhand |");
        }
        s += "\n";
    }
    // How each machine taps (drilling.tapping).
    s += "| tapping |";
    for (const Machine& m : machines)
        s += m.tapping == TappingMode::rigid ? " rigid |" : m.tapping == TappingMode::floating ? " floating |" : " none |";
    s += "\n";
    return s;
}

}  // namespace

TEST_CASE("docs/reference.md's cycle table equals the machines' drilling tables and --describe-machine") {
    for (MachineKind kind : {MachineKind::mill, MachineKind::lathe}) {
        const std::string table = cycle_table(kind);
        INFO("docs/reference.md must contain this table (under Machines):\n" << table);
        CHECK(has(read_file(CAMGEN_SOURCE_DIR "/docs/reference.md"), table));
    }
    for (const auto& listed : list_machines()) {
        const std::string& name = listed.first;
        const Machine m = load_machine(name);
        const std::string d = describe_machine(m);
        for (const CycleCapability& c : machine_capabilities(m).cycles) {
            std::string label = fmt::format("{:<24}", std::string(name_of(cycle_kinds, c.kind)));
            INFO(name << " " << std::string(name_of(cycle_kinds, c.kind)));
            CHECK(has(d, "  " + label +
                             (c.refused ? "refused: " : c.canned ? "canned " + c.canned->name + ";" : std::string("longhand"))));
        }
    }
}

}  // namespace test_drilling
