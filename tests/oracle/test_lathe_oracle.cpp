// LinuxCNC oracle for the linuxcnc-lathe machine (issue 12): every turn-drill cycle the machine
// writes canned (G17, G98 G81/G82/G83/G73 X0 Z R, G80, G18) moves through rs274 exactly as
// camgen's longhand of the same cycle, with every TurnDrillingFields combination it carries,
// feeds per minute and per revolution; and X written in G7 reads back in rs274 as the job's
// radius, I staying a radius.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "camgen/operations/registry.hpp"
#include "rs274.hpp"

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
        std::vector<OStep> steps;
        REQUIRE_NOTHROW(steps = oracle::run_rs274(rs274(), text.str()));
        // Nothing leaves the XZ plane, and no move goes below the spindle axis.
        for (const OStep& s : steps) {
            CHECK(s.to.y == 0.0);
            CHECK(s.to.x >= 0.0);
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
