// LinuxCNC oracle for turn-groove and turn-part (issue 30): their programs, longhand G0/G1/G4 on
// every lathe, run through rs274 in lathe mode to their end, and rs274's moves are camgen's
// reading of the program (oracle::check_read_as_run): linuxcnc-lathe's as written, and
// fanuc-lathe's with the words only a Fanuc has put in LinuxCNC's (diameter mode G7 for its
// diameter X, T0101 as T1 M6, G98/G99 as G94/G95, no O number, sequence numbers or G50 S
// block) and its motion words untouched. The sample shaft and many random grooves and partings;
// random internal grooves (in a bore, along +X) and face grooves (along -Z) alike.
#include <doctest/doctest.h>

#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

namespace test_turn_groove_oracle {

using namespace camgen;

namespace {

std::string rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A fanuc-lathe program in LinuxCNC's words, its motion untouched.
std::string fanuc_as_linuxcnc(const std::string& program) {
    std::istringstream in(program);
    std::string out = "G7\n";
    const std::regex seq(R"(^N[0-9]+ )"), tool(R"(\bT0*([0-9]+?)([0-9]{2})\b)");
    for (std::string line; std::getline(in, line);) {
        if (line == "%" || line.rfind("O", 0) == 0) continue;
        line = std::regex_replace(line, seq, "");
        if (line.rfind("G50 S", 0) == 0) continue;
        line = std::regex_replace(line, tool, "T$1 M6");
        line = std::regex_replace(line, std::regex(R"(\bG98\b)"), "G94");
        line = std::regex_replace(line, std::regex(R"(\bG99\b)"), "G95");
        out += line + "\n";
    }
    return out;
}

void run_on(const Job& job, const std::string& machine, double tolerance = 1e-6) {
    const Machine m = load_machine(machine);
    const std::string program = oracle::posted_program(job, m);
    const std::string text = machine == "fanuc-lathe" ? fanuc_as_linuxcnc(program) : program;
    INFO(machine << ":\n" << text);
    std::vector<oracle::Step> theirs;
    REQUIRE_NOTHROW(theirs = oracle::run_rs274(rs274(), text));
    oracle::check_read_as_run(theirs, program, m, tolerance);
}

}  // namespace

TEST_CASE("linuxcnc-lathe and fanuc-lathe: the sample shaft's groove and parting run in rs274 as camgen reads them") {
    std::ifstream f(CAMGEN_SOURCE_DIR "/samples/shaft.json");
    std::stringstream text;
    text << f.rdbuf();
    // Its groove and parting alone: the drilling and turning before them are compared move for
    // move by test_turn_rough_oracle.cpp (the steps of rs274's canned cycles and arcs are not
    // check_read_as_run's).
    nlohmann::json doc = nlohmann::json::parse(text.str());
    auto& ops = doc["operations"];
    ops.erase(ops.begin(), ops.begin() + 5);
    // (the thread between them is test_turn_thread_oracle.cpp's)
    for (auto it = ops.begin(); it != ops.end();) it = (*it)["type"] == "turn-thread" ? ops.erase(it) : it + 1;
    // The bar as the turning left it where they cut (D30): on the D44 the groove's startX 30 is in
    // the bar nothing turned (check_blade_material).
    doc["stock"]["bar"]["diameter"] = 30;
    const Job job = read_job(doc.dump(), "shaft.json");
    bool groove = false, part = false;
    for (const Operation& op : job.operations) groove |= std::holds_alternative<TurnGrooveOp>(op), part |= std::holds_alternative<TurnPartOp>(op);
    CHECK(groove);
    CHECK(part);
    run_on(job, "linuxcnc-lathe");
    run_on(job, "fanuc-lathe");
}

TEST_CASE("linuxcnc-lathe and fanuc-lathe: random grooves and partings run in rs274 as camgen reads them") {
    std::mt19937 rng(3033);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n = 0; n < 16; ++n) {
        const double w = 1.5 + 3.0 * u(rng);
        const double width = u(rng) < 0.3 ? w : w + 8.0 * u(rng);
        const double depth = 0.5 + 5.0 * u(rng);
        const double c = u(rng) < 0.5 ? 0.0 : std::min(depth * 0.9, 0.2 + 1.2 * u(rng));
        std::string pecks;
        if (u(rng) < 0.6) pecks += fmt::format(R"(, "peckDepth": {:.3f})", 0.4 + 2.0 * u(rng));
        if (!pecks.empty() && u(rng) < 0.5) pecks += R"(, "fullRetract": true)";
        const std::string text = fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 36, "length": 80, "faceZ": 0}}}},
  "tools": [{{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 700{}}},
            {{"number": 2, "type": "parting-tool", "width": 3, "rpm": 500}}],
  "operations": [{{"type": "turn-groove", "tool": 1, "feedMode": "per-revolution", "feed": 0.05, "z": {:.3f}, "width": {:.3f},
                   "depth": {:.3f}, "chamfer": {:.3f}, "dwell": {}{}}},
                 {{"type": "turn-part", "tool": 2, "feedMode": "per-revolution", "feed": 0.06, "z": -40, "chamfer": {:.3f}{}}}]}})",
            w, u(rng) < 0.5 ? R"(, "orientation": 1)" : "", -5.0 - 15.0 * u(rng), width, depth, c, u(rng) < 0.5 ? 0 : 0.3,
            pecks, c, pecks);
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "groove.json"));
        run_on(job, "linuxcnc-lathe");
        run_on(job, "fanuc-lathe");
    }
}

TEST_CASE("linuxcnc-lathe and fanuc-lathe: random internal and face grooves run in rs274 as camgen reads them") {
    std::mt19937 rng(3134);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n = 0; n < 16; ++n) {
        const bool face = n % 2 == 1;
        auto mm = [](double v) { return std::round(v * 1000) / 1000; };
        const double w = mm(1.5 + 2.0 * u(rng));
        const double width = u(rng) < 0.3 ? w : mm(w + 4.0 * u(rng));
        const double depth = 0.5 + 3.0 * u(rng);
        const double c = u(rng) < 0.5 ? 0.0 : std::min(depth * 0.9, 0.2 + 0.8 * u(rng));
        std::string keys;
        if (u(rng) < 0.6) keys += fmt::format(R"(, "peckDepth": {:.3f})", 0.4 + 1.5 * u(rng));
        if (!keys.empty() && u(rng) < 0.5) keys += R"(, "fullRetract": true)";
        const double inner = mm(10.5 + 2.0 * u(rng));
        std::string side = face ? fmt::format(R"("side": "face", "z": 0, "innerX": {:.3f}, "outerX": {:.3f})", 2 * inner,
                                              2 * (inner + width))
                                : fmt::format(R"("side": "internal", "z": {:.3f}, "width": {:.3f})", -4.0 - 20.0 * u(rng), width);
        const std::string text = fmt::format(
            R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0, "boreDiameter": 16}}}},
  "tools": [{{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 700, "orientation": {}}}],
  "operations": [{{"type": "turn-groove", "tool": 1, "feedMode": "per-revolution", "feed": 0.05, {},
                   "depth": {:.3f}, "chamfer": {:.3f}, "dwell": {}, "output": "longhand"{}}}]}})",
            w, face ? 7 : (u(rng) < 0.5 ? 3 : 4), side, depth, c, u(rng) < 0.5 ? 0 : 0.3, keys);
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "groove.json"));
        // (a face groove's plunges and chamfers fall on X of odd thousandths: their radii end
        // in 5 at the fourth decimal, which rs274 prints rounded)
        run_on(job, "linuxcnc-lathe", 1e-4);
        run_on(job, "fanuc-lathe", 1e-4);
    }
}

}  // namespace test_turn_groove_oracle
