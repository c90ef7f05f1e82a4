// LinuxCNC oracle for the linuxcnc-lathe machine (issue 12): every turn-drill cycle the machine
// writes canned (G17, G98 G81/G82/G83/G73 X0 Z R, G80, G18) moves through rs274 exactly as
// camgen's longhand of the same cycle, with every TurnDrillingFields combination it carries,
// feeds per minute and per revolution; and X written in G7 reads back in rs274 as the job's
// radius, I staying a radius.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "camgen/operations/registry.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_lathe_oracle {

using namespace camgen;
using OStep = camgen::oracle::Step;

namespace {

std::string rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A shaft job with one turn-drill; `fields` are its TurnDrillingFields and feedMode.
std::string post_turn_drill(const std::string& fields, const std::string& output) {
    const std::string text = R"({"clearance": 20, "tools": [{"number": 1, "diameter": 8, "tipAngle": 118, "rpm": 1000}],
  "operations": [{"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": -17, "safeDistance": 2,
                  "retractDistance": 6, "output": ")" + output + "\"" + fields + "}]}";
    Job job = read_job(text, "oracle.json");
    const Machine m = load_machine("linuxcnc-lathe");
    std::ostringstream out;
    auto p = make_post(m, out, PostOptions{});
    p->open();
    expand_job(job, *p);
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
        INFO("step " << i);
        CHECK(canned[i].kind == longhand[i].kind);
        CHECK(std::abs(canned[i].to.x - longhand[i].to.x) <= 0.001);
        CHECK(std::abs(canned[i].to.y - longhand[i].to.y) <= 0.001);
        CHECK(std::abs(canned[i].to.z - longhand[i].to.z) <= 0.001);
        CHECK(std::abs(canned[i].value - longhand[i].value) <= 0.0001);
    }
}

}  // namespace

TEST_CASE("linuxcnc-lathe: every canned turn-drill moves through rs274 as its longhand") {
    const std::string path = rs274();
    struct Case {
        std::string fields, code;
    };
    const Case cases[] = {
        {R"(, "plungingFeedrate": 120)", "G98 G81 X0 Z-17 R2 F120"},
        {R"(, "plungingFeedrate": 120, "lowerDwell": 0.5)", "G98 G82 X0 Z-17 R2 P0.5 F120"},
        {R"(, "plungingFeedrate": 120, "firstPeckDepth": 5)", "G98 G83 X0 Z-17 R2 Q5 F120"},
        {R"(, "plungingFeedrate": 120, "firstPeckDepth": 5, "peckClearance": 0.254)", "G98 G83 X0 Z-17 R2 Q5 F120"},
        {R"(, "plungingFeedrate": 120, "firstPeckDepth": 5, "peckRetract": 0.254)", "G98 G73 X0 Z-17 R2 Q5 F120"},
        {R"(, "plungingFeedrate": 0.1, "firstPeckDepth": 4, "feedMode": "per-revolution")",
         "G98 G83 X0 Z-17 R2 Q4 F0.1"},
        {R"(, "plungingFeedrate": 0.08, "feedMode": "per-revolution", "drillTip": true)",
         "G98 G81 X0 Z-19.4034 R2 F0.08"},
    };
    for (const Case& c : cases) {
        const std::string canned = post_turn_drill(c.fields, "canned");
        const std::string longhand = post_turn_drill(c.fields, "longhand");
        INFO("--- canned ---\n" << canned << "--- longhand ---\n" << longhand);
        REQUIRE(canned.find("G17\n" + c.code + "\nG80\nG18\n") != std::string::npos);
        REQUIRE(longhand.find("G17") == std::string::npos);
        check_same(oracle::run_rs274(path, canned), oracle::run_rs274(path, longhand));
    }
}

TEST_CASE("linuxcnc-lathe: peck values the control cannot write go longhand (auto) or are refused (canned)") {
    // LinuxCNC's G83 comes back to 0.254 mm above the last peck: 0.5 cannot be canned.
    const std::string text = post_turn_drill(R"(, "plungingFeedrate": 120, "firstPeckDepth": 5, "peckClearance": 0.5)", "auto");
    CHECK(text.find("G83") == std::string::npos);
    CHECK(text.find("\nZ-2.5\n") != std::string::npos);  // 0.5 above the first peck at Z-3
    CHECK_THROWS_WITH_AS(post_turn_drill(R"(, "plungingFeedrate": 120, "firstPeckDepth": 5, "peckRetract": 1)", "canned"),
                         doctest::Contains("its back-off is the control's, 0.254 mm"), InputError);
}

TEST_CASE("linuxcnc-lathe: X in G7 reads back in rs274 as the job's radius, I as a radius") {
    // Radius 15 at Z2, feed to Z0, then a quarter circle from (radius 15, Z0) about
    // (15, -5) to (10, -5).
    const Machine m = load_machine("linuxcnc-lathe");
    std::ostringstream out;
    auto p = make_post(m, out, PostOptions{});
    p->open();
    p->emit(OperationStart{"radius", "/operations/0", std::nullopt});
    p->emit(ToolChange{1, 0.8, "turning tool"});
    p->emit(Spindle{SpindleState::cw, 1000});
    p->emit(Rapid{{15, 0, 2}});
    p->emit(Linear{{15, 0, 0}, 100});
    p->emit(Arc{{10, 0, -5}, {15, 0, -5}, ArcDirection::ccw, Plane::xz, 100});
    p->emit(OperationEnd{});
    p->close();
    const std::string text = out.str();
    INFO(text);
    // X as diameters (30, 20), I = 15 - 15 = 0, K = -5 - 0 = -5 as radii.
    CHECK(text.find("X30\n") != std::string::npos);
    CHECK(text.find("G3 X20 Z-5 I0 K-5\n") != std::string::npos);
    // rs274 refuses an arc whose end is off its circle (reference test D: I as a diameter), so
    // running at all says the radii agree; its traverse says X30 is radius 15.
    std::vector<OStep> steps;
    REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274(), text));
    bool at_radius_15 = false;
    for (const OStep& s : steps)
        if (s.kind == OStep::Kind::traverse && std::abs(s.to.x - 15) < 1e-4 && std::abs(s.to.z - 2) < 1e-4) at_radius_15 = true;
    CHECK(at_radius_15);
    // The same program with I written as a diameter (I-10 for a radius offset of -5... here
    // K): LinuxCNC rejects diameter offsets, as camgen's iDiameterProg false says.
    std::string wrong = text;
    wrong.replace(wrong.find("K-5"), 3, "K-10");
    CHECK_THROWS_AS(oracle::run_rs274(rs274(), wrong), std::runtime_error);
}

TEST_CASE("every linuxcnc-lathe golden file runs through rs274") {
    namespace fs = std::filesystem;
    int files = 0;
    for (const auto& entry : fs::directory_iterator(CAMGEN_SOURCE_DIR "/tests/golden/linuxcnc-lathe")) {
        if (entry.path().extension() != ".ngc") continue;
        ++files;
        std::ifstream f(entry.path());
        std::stringstream text;
        text << f.rdbuf();
        INFO(entry.path().string());
        // A program with nose-radius compensation names what the tool table must hold (its
        // comment): rs274's table gets it.
        std::map<int, double> diameters;
        std::map<int, int> orientations;
        const std::regex table(R"(tool table T(\d+) D([0-9.]+) nose diameter, Q(\d))");
        const std::string program = text.str();
        for (auto it = std::sregex_iterator(program.begin(), program.end(), table); it != std::sregex_iterator(); ++it) {
            diameters[std::stoi((*it)[1])] = std::stod((*it)[2]);
            orientations[std::stoi((*it)[1])] = std::stoi((*it)[3]);
        }
        std::vector<OStep> steps;
        REQUIRE_NOTHROW(steps = oracle::parse_canon(oracle::run_rs274_canon(rs274(), program, diameters, orientations)));
        // Nothing leaves the XZ plane, and no tip goes below the spindle axis by more than its nose's
        // radius (a face to the centre takes the nose's centre onto the axis, so that its round
        // leaves no nub: the tip then stands a nose radius past it).
        double nose = 0.0;
        {
            std::ifstream sample(std::string(CAMGEN_SOURCE_DIR "/samples/") + entry.path().stem().string() + ".json");
            REQUIRE(sample);
            std::stringstream job_text;
            job_text << sample.rdbuf();
            const Job job = read_job(job_text.str(), "sample.json");
            for (const auto& [number, tool] : job.tools)
                if (tool.type == ToolType::turning_tool) nose = std::max(nose, tool.diameter / 2);
        }
        for (const OStep& s : steps) {
            CHECK(s.to.y == 0.0);
            CHECK(s.to.x >= -nose - 1e-9);
        }
    }
    CHECK(files >= 1);
}

TEST_CASE("linuxcnc-lathe: tapping on the axis is G33.1 under G17, a rigid tap to the hole's bottom in rs274") {
    // A rigid tap has no longhand (the machine taps rigidly): rs274 shows the synchronised move.
    const std::string text = post_turn_drill(R"(, "pitch": 1.25)", "auto");
    INFO(text);
    REQUIRE(text.find("G17\n") != std::string::npos);
    REQUIRE(text.find("G33.1 Z-17 K1.25\n") != std::string::npos);
    std::vector<OStep> steps;
    REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274(), text));
    int taps = 0;
    for (const OStep& s : steps)
        if (s.kind == OStep::Kind::rigid_tap) {
            ++taps;
            CHECK(s.to.x == 0.0);
            CHECK(s.to.z == -17.0);
        }
    CHECK(taps == 1);
}

// Issue 24: turn-profiles that read_job refuses. Each is built as a struct (as a library user
// can, and as read_job let through before), posted for linuxcnc-lathe and run through rs274 to
// show what the control would cut; then the same job as JSON is refused at its JSON path.
namespace {

// A profile point from a diameter and a Z: (u, v) = (Z, radius).
Vec2 dz(double diameter, double z) { return {z, diameter / 2}; }

ProfileSegment line_to(double diameter, double z) { return ProfileSegment{dz(diameter, z), std::nullopt, ArcDirection::ccw}; }

TurnProfileOp turned(std::size_t index, Vec2 start, std::vector<ProfileSegment> segments, double retract_diameter) {
    TurnProfileOp op;
    op.path = "/operations/" + std::to_string(index);
    op.tool = 1;
    op.feed = 100;
    op.profile.plane = ProfilePlane::xz;
    op.profile.start = start;
    op.profile.segments = std::move(segments);
    op.retract_x = retract_diameter / 2;
    return op;
}

// The linuxcnc-lathe program of turn-profiles on a 0.8 mm turning tool.
std::string post_turned(const std::vector<TurnProfileOp>& ops, double clearance) {
    Job job;
    job.name = "oracle";
    job.clearance = clearance;
    Tool tool;
    tool.number = 1;
    tool.type = ToolType::turning_tool;
    tool.diameter = 0.8;
    tool.rpm = 1000;
    job.tools[1] = tool;
    for (const TurnProfileOp& op : ops) job.operations.push_back(op);
    const Machine m = load_machine("linuxcnc-lathe");
    std::ostringstream out;
    auto p = make_post(m, out, PostOptions{});
    p->open();
    expand_job(job, *p);
    p->close();
    return out.str();
}

// The same job as JSON, X as diameters: `ops` are the operations' keys after type, tool, feed.
std::string turned_json(const std::vector<std::string>& ops, double clearance) {
    std::string list;
    for (const std::string& op : ops)
        list += (list.empty() ? "" : ", ") + std::string(R"({"type": "turn-profile", "tool": 1, "feed": 100, )") + op + "}";
    return fmt::format(R"({{"clearance": {}, "tools": [{{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}}],
  "operations": [{}]}})",
                       clearance, list);
}

// The error read_job gives for `text` ("" when none).
std::string refusal(const std::string& text) {
    try {
        (void)read_job(text, "oracle.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// The lowest X (radius) the control reaches along the arcs in XZ of rs274's canonical output,
// sampled every 0.1 degree from where the previous move ended. Under G18 ARC_FEED gives
// (Z end, X end, Z centre, X centre, rotation), rotation > 0 counter-clockwise in (Z, X).
double lowest_arc_x(const std::string& canon) {
    double lowest = 1e9;
    Vec3 at{0, 0, 0};
    std::istringstream lines(canon);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t open = line.find('('), close = line.rfind(')');
        if (open == std::string::npos || close == std::string::npos) continue;
        std::vector<double> a;
        std::istringstream args(line.substr(open + 1, close - open - 1));
        for (std::string part; std::getline(args, part, ',');) a.push_back(std::strtod(part.c_str(), nullptr));
        if (line.find("STRAIGHT_") != std::string::npos && a.size() >= 3) at = {a[0], a[1], a[2]};
        if (line.find("ARC_FEED") == std::string::npos || a.size() < 5) continue;
        const double zc = a[2], xc = a[3], r = std::hypot(at.z - zc, at.x - xc);
        const double from = std::atan2(at.x - xc, at.z - zc), to = std::atan2(a[1] - xc, a[0] - zc);
        double sweep = a[4] > 0 ? to - from : from - to;
        while (sweep <= 1e-9) sweep += 2 * M_PI;
        for (int k = 0; k <= static_cast<int>(sweep / (M_PI / 1800)); ++k) {
            const double angle = from + (a[4] > 0 ? 1 : -1) * k * (M_PI / 1800);
            lowest = std::min(lowest, xc + r * std::sin(angle));
        }
        at = {a[1], 0, a[0]};
    }
    return lowest;
}

// Whether the segments (Z, X) p1-p2 and q1-q2 cross.
bool cross(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2) {
    auto side = [](Vec2 a, Vec2 b, Vec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); };
    return side(p1, p2, q1) * side(p1, p2, q2) < 0 && side(q1, q2, p1) * side(q1, q2, p2) < 0;
}

// The shaft of samples/shaft.json (diameters 28 to 40 from Z0 to Z-40) as segments.
std::vector<ProfileSegment> shaft() {
    return {line_to(28, 0), line_to(30, -1), line_to(30, -20), ProfileSegment{dz(40, -25), dz(40, -20), ArcDirection::cw},
            line_to(40, -40)};
}
const char* shaft_json = R"("start": [24, 0], "path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]},
  {"arc": {"end": [40, -25], "centre": [40, -20], "direction": "cw"}}, {"line": [40, -40]}])";

}  // namespace

TEST_CASE("linuxcnc-lathe (issue 24): an arc whose sweep passes X -8.4 runs in rs274; read_job refuses it") {
    // Ends (diameter 12.4 at Z-5, 2 at Z0.2) and centre (2, Z-5) above the axis; counter-clockwise
    // three quarters of a turn of radius 5.2 through radius -4.2.
    const std::string text =
        post_turned({turned(0, dz(12.4, -5), {ProfileSegment{dz(2, 0.2), dz(2, -5), ArcDirection::ccw}}, 20)}, 5);
    INFO(text);
    REQUIRE(text.find("G3 X2 Z0.2 I-5.2 K0") != std::string::npos);
    std::string canon;
    REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(rs274(), text));
    // The control cuts through the spindle axis, to a diameter of -8.4.
    CHECK(lowest_arc_x(canon) == doctest::Approx(-4.2).epsilon(1e-4));
    CHECK(refusal(turned_json({R"("start": [12.4, -5], "retractX": 20, "path": [{"arc": {"end": [2, 0.2], "centre": [2, -5], "direction": "ccw"}}])"}, 5))
              .find("/operations/0/path/0/arc: the arc sweeps through the spindle axis: it reaches X -8.400 mm (diameter) "
                    "at Z -5.000 mm") != std::string::npos);
}

TEST_CASE("linuxcnc-lathe (issue 24): a profile whose segments cross runs in rs274; read_job refuses it") {
    const std::string text = post_turned({turned(0, dz(40, 0), {line_to(20, -10), line_to(40, -10), line_to(20, 0)}, 44)}, 20);
    std::vector<OStep> steps;
    REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274(), text));
    std::vector<Vec2> feeds;  // (Z, X) of the feed moves' ends, from the start
    for (const OStep& s : steps)
        if (s.kind == OStep::Kind::feed) feeds.push_back({s.to.z, s.to.x});
    REQUIRE(feeds.size() >= 4);
    // The third element crosses the first: the tip cuts back through what it has just finished.
    CHECK(cross(feeds[0], feeds[1], feeds[2], feeds[3]));
    CHECK(refusal(turned_json({R"("start": [40, 0], "retractX": 44, "path": [{"line": [20, -10]}, {"line": [40, -10]}, {"line": [20, 0]}])"}, 20))
              .find("/operations/0/path/2: this element crosses or touches the profile before it") != std::string::npos);
}

TEST_CASE("linuxcnc-lathe (issue 24): a retractX inside the part rapids through it in rs274; read_job refuses it") {
    const std::string text = post_turned({turned(0, dz(24, 0), shaft(), 10)}, 20);
    std::vector<OStep> steps;
    REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274(), text));
    // After the lift off the end (to Z-39.646) the tool rapids in to radius 5 and along Z at
    // radius 5 to the clearance: through the diameters 28 to 40 between Z-40 and Z0.
    bool through = false;
    for (std::size_t i = 1; i < steps.size(); ++i)
        if (steps[i].kind == OStep::Kind::traverse && steps[i - 1].kind == OStep::Kind::traverse &&
            std::abs(steps[i - 1].to.x - 5) < 1e-4 && std::abs(steps[i - 1].to.z + 39.6464) < 1e-3 &&
            std::abs(steps[i].to.x - 5) < 1e-4 && std::abs(steps[i].to.z - 20) < 1e-4)
            through = true;
    CHECK(through);
    CHECK(refusal(turned_json({std::string(shaft_json) + R"(, "retractX": 10)"}, 20))
              .find("/operations/0/retractX: retractX 10.000 mm is inside the part") != std::string::npos);
}

TEST_CASE("linuxcnc-lathe (issue 24): a profile above the clearance: rs274 rapids into the part and feeds up; read_job refuses it") {
    // The part's face at Z30, the clearance at Z10.
    const std::string text = post_turned({turned(0, dz(40, 30), {line_to(40, 0)}, 44)}, 10);
    std::vector<OStep> steps;
    REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274(), text));
    bool feeds_up = false;
    for (std::size_t i = 1; i < steps.size(); ++i)
        if (steps[i - 1].kind == OStep::Kind::traverse && std::abs(steps[i - 1].to.x - 20) < 1e-4 &&
            std::abs(steps[i - 1].to.z - 10) < 1e-4 && steps[i].kind == OStep::Kind::feed &&
            std::abs(steps[i].to.z - 30) < 1e-4)
            feeds_up = true;
    CHECK(feeds_up);
    CHECK(refusal(turned_json({R"("start": [40, 30], "retractX": 44, "path": [{"line": [40, 0]}])"}, 10))
              .find("/operations/0/start/1: the start is at Z 30.000 mm, at or above the clearance (Z 10.000 mm)") !=
          std::string::npos);
}

TEST_CASE("linuxcnc-lathe (issue 24): a second profile's approach feeds through the first one's diameter in rs274; read_job refuses it") {
    // After the shaft, a groove at diameter 34 from Z-30: its approach rapids along Z at radius
    // 17 from the clearance to Z-29 (1 mm before its start) through the diameter 40 left from
    // the fillet (Z-24) on.
    const std::string text =
        post_turned({turned(0, dz(24, 0), shaft(), 44), turned(1, dz(34, -30), {line_to(34, -35)}, 44)}, 20);
    std::vector<OStep> steps;
    REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274(), text));
    bool through = false;
    for (std::size_t i = 1; i < steps.size(); ++i)
        if (steps[i - 1].kind == OStep::Kind::traverse && std::abs(steps[i - 1].to.x - 17) < 1e-4 &&
            std::abs(steps[i - 1].to.z - 20) < 1e-4 && steps[i].kind == OStep::Kind::traverse &&
            std::abs(steps[i].to.x - 17) < 1e-4 && std::abs(steps[i].to.z + 29) < 1e-4)
            through = true;
    CHECK(through);
    CHECK(refusal(turned_json({std::string(shaft_json) + R"(, "retractX": 44)",
                               R"("start": [34, -30], "retractX": 44, "path": [{"line": [34, -35]}])"},
                              20))
              .find("/operations/1/start: the approach runs along Z at X 34.000 mm") != std::string::npos);
}

}  // namespace test_lathe_oracle
