// camgen simulate checks a lathe's turned part against the job's design (issue 27): the design
// of turn-profile and turn-drill (operations/design_lathe), every lathe sample on every lathe
// simulates as designed, and hand-edited programs' gouges (into a finished diameter, a drill too
// deep, into a shoulder between two Z samples) and material left (a finishing pass removed) are
// found, the gouges at the line that cut them, each naming its operation.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/operations/design.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/simulation/design_check_lathe.hpp"
#include "support.hpp"

namespace test_simulation_lathe_design {

namespace fs = std::filesystem;
using namespace camgen;

namespace {

const std::string samples = CAMGEN_SOURCE_DIR "/samples/";
const double pi_ = std::acos(-1.0);

// The program with `line` (the first line equal to it after `after`) replaced by `with`; the
// 1-based number of the replaced line.
std::pair<std::string, std::size_t> replace_line(const std::string& text, const std::string& after, const std::string& line,
                                                 const std::string& with) {
    const std::vector<std::string> lines = test::lines_of(text);
    std::size_t from = 0;
    while (from < lines.size() && lines[from].find(after) == std::string::npos) ++from;
    REQUIRE_MESSAGE(from < lines.size(), after);
    std::size_t at = from;
    while (at < lines.size() && lines[at] != line) ++at;
    REQUIRE_MESSAGE(at < lines.size(), line);
    std::string out;
    for (std::size_t i = 0; i < lines.size(); ++i) out += (i == at ? with : lines[i]) + "\n";
    return {out, at + 1};
}

struct Simulated {
    test::Run run;
    std::string program;
};

// `job` posted for `machine`, edited, and simulated in `bar` (the shaft's: D44 x 70, face Z1).
Simulated simulate(const std::string& job, const std::string& machine, const std::string& name,
                   const std::function<std::string(const std::string&)>& edit, const std::string& resolution = "",
                   const std::string& bar = "44,70,1") {
    const fs::path dir = test::scratch("simulate-lathe-design");
    const std::string posted = (dir / (name + ".posted")).string(), program = (dir / name).string();
    REQUIRE(test::run({job, "--machine", machine, "-q", "-o", posted}).code == 0);
    const std::string text = edit(test::read_file(posted));
    std::ofstream(program) << text;
    std::vector<std::string> args{"simulate", program, "--machine", machine, "--job", job, "--bar", bar};
    if (!resolution.empty()) args.insert(args.end(), {"--resolution", resolution});
    return {test::run(args), text};
}

bool has(const test::Run& r, const std::string& s) { return r.out.find(s) != std::string::npos; }

}  // namespace

TEST_CASE("lathe design: a turn-profile keeps its profile and is judged by what its nosed tip leaves; a turn-drill bores its drill") {
    const Job job = read_job(test::read_file(samples + "shaft.json"), "shaft.json");
    const PartDesign design = part_design(job);
    CHECK(design.unchecked.empty());
    CHECK(design.cuts.empty());
    // The face, the rough (designed in design_turn_face, design_turn_rough), the finish, the
    // groove, the thread (design_turn_thread) and the parting (test_turn_groove.cpp).
    REQUIRE(design.lathe.profiles.size() == 6);
    REQUIRE(design.lathe.holes.size() == 2);
    CHECK(design.lathe.profiles[0].path == "/operations/0");
    CHECK(design.lathe.profiles[1].path == "/operations/3");
    CHECK(design.lathe.profiles[1].z_hi == doctest::Approx(0.1));   // the boundary: allowanceZ 0.1
    CHECK(design.lathe.profiles[1].z_lo == doctest::Approx(-39.9));
    const LatheTurnDesign& p = design.lathe.profiles[2];
    CHECK(p.path == "/operations/4");
    CHECK(p.nose == doctest::Approx(0.4));
    CHECK(p.z_lo == doctest::Approx(-40));
    CHECK(p.z_hi == doctest::Approx(20));  // the approach from the clearance
    // The D30 cylinder, the face at Z0 (radius 12 to 14, and the approach's 12 above it), the R5
    // fillet exactly (radius 20 - sqrt(25 - 2.5^2) at Z-22.5) and over a window across its end.
    auto range = [&](double a, double b) {
        const auto r = p.radius_range(a, b);
        REQUIRE(r);
        return *r;
    };
    CHECK(range(-10, -10).first == doctest::Approx(15));
    CHECK(range(-10, -10).second == doctest::Approx(15));
    CHECK(range(-0.001, 0.001).first == doctest::Approx(12));
    CHECK(range(-0.001, 0.001).second == doctest::Approx(14.001));
    CHECK(range(-22.5, -22.5).first == doctest::Approx(20 - std::sqrt(25 - 6.25)).epsilon(1e-12));
    CHECK(range(-25.5, -24.5).first == doctest::Approx(20 - std::sqrt(25 - 4.5 * 4.5)).epsilon(1e-12));
    CHECK(range(-25.5, -24.5).second == doctest::Approx(20));
    // The thread M30x2 from Z0 to Z-11: its minor diameter d3 = 30 - 1.226869 x 2 over its length.
    const LatheTurnDesign& t = design.lathe.profiles[4];
    CHECK(t.path == "/operations/6");
    CHECK(t.z_lo == doctest::Approx(-11));
    CHECK(t.z_hi == doctest::Approx(0));
    const auto thread = t.radius_range(-10, -10);
    REQUIRE(thread);
    CHECK(thread->first == doctest::Approx((30 - 1.226869 * 2) / 2).epsilon(1e-6));
    CHECK_FALSE(p.radius_range(-45, -41));
    // What the R0.4 nose leaves, its path compensated (the sample's default): the profile itself,
    // on the cylinder, on the 45 degree chamfer and in the fillet (within the chords of the tip
    // path's arcs, 0.0001 mm).
    CHECK(p.left_radius(-10) == doctest::Approx(15).epsilon(1e-12));
    CHECK(std::abs(p.left_radius(-0.5) - 14.5) <= 1e-4);
    const double z = -22.5, fillet = 20 - std::sqrt(25 - (z + 20) * (z + 20));
    CHECK(std::abs(p.left_radius(z) - fillet) <= 1e-4);
    // The centre drill: D4, 60 degrees, to Z-4; the drill: D10, 118 degrees, its tip below Z-30.
    const LatheHoleDesign& centre = design.lathe.holes[0];
    CHECK(centre.bottom_z == doctest::Approx(-4));
    CHECK(centre.radius_at(-3) == doctest::Approx(std::tan(pi_ / 6)));
    CHECK(centre.radius_at(-4.01) == 0);
    CHECK(centre.radius_at(10) == doctest::Approx(2));
    const LatheHoleDesign& drill = design.lathe.holes[1];
    CHECK(drill.bottom_z == doctest::Approx(-30 - 5 / std::tan(59 * pi_ / 180)));
    CHECK(drill.radius_at(-20) == doctest::Approx(5));
}

TEST_CASE("lathe design check: where no operation designs the bar, a cut into it is named after the operation of its line") {
    // A bar D40 x 10 at Z0..-10 with nothing designed; the simulated outside cut to 19 at Z-5 by
    // line 12, of the operation that starts at line 10.
    SimStock bar;
    bar.kind = SimStock::Kind::bar;
    bar.bar_diameter = 40;
    bar.bar_length = 10;
    LatheProfile part;
    part.z0 = -10, part.dz = 0.1, part.nz = 100;
    part.outside.assign(100, 20.0);
    part.bore.assign(100, 0.0);
    part.outside_lines.assign(100, 0);
    part.bore_lines.assign(100, 0);
    part.outside[50] = 19, part.outside_lines[50] = 12;
    const LatheCheck c = check_lathe_design({}, bar, part, {}, 0.01, {{1, "/operations/0"}, {10, "/operations/1"}});
    CHECK(c.samples == 100);
    REQUIRE(c.findings.size() == 1);
    CHECK(c.findings[0].message() ==
          "/operations/1 (the bar, which no operation turns there): material removed 1 mm inside the designed radius 20 at "
          "Z-4.95 (radius 19), by line 12 (cut at 1 sample)");
}

TEST_CASE("camgen simulate: every lathe sample on every lathe makes the part its job designs") {
    int simulated = 0;
    for (const std::string machine : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"})
        for (const char* file : {"shaft.json", "shaft-stops.json", "shaft-control.json"}) {
            CAPTURE(machine);
            CAPTURE(file);
            // shaft-control's bar starts at its profile's face (no turn-face): faceZ 0, as its stock says.
            const std::string bar = std::string(file) == "shaft-control.json" ? "44,70,0" : "44,70,1";
            const Simulated s =
                simulate(samples + file, machine, "sample.nc", [](const std::string& t) { return t; }, "", bar);
            CHECK_MESSAGE(s.run.code == 0, std::string(s.run.out + s.run.err));
            CHECK(has(s.run, "simulation: no errors\n"));
            CHECK(has(s.run, "design check   lathe: "));
            CHECK_MESSAGE(has(s.run, "  the part is as designed\n"), s.run.out);
            ++simulated;
        }
    CHECK(simulated == 9);
    // Where the machine cannot tap, the tap is the operator's: not checked (its bore is not cut).
    const Simulated stops = simulate(samples + "shaft-stops.json", "fanuc-lathe", "stops.nc", [](const std::string& t) { return t; });
    CHECK(has(stops.run, "  not checked: /operations/5: the program leaves its cycle to the operator at a stop (machine "
                         "fanuc-lathe cannot tap)\n"));
    // The shaft's nose leaves material on the chamfer and in the fillet, which is said.
    const Simulated shaft = simulate(samples + "shaft.json", "linuxcnc-lathe", "shaft.nc", [](const std::string& t) { return t; });
    CHECK(has(shaft.run, "design check   lathe: 6 profiles, 2 holes, within 0.008 mm in radius and in Z, 70000 samples and 40 "
                         "sections 0.0088 mm beside the designed corners\n"));
    CHECK(has(shaft.run, "  note: /operations/4: the nose of tool 3 (radius 0.4 mm) leaves up to "));
}

TEST_CASE("camgen simulate: control compensation on the wrong side (G41 for G42) gouges the part; none leaves material") {
    // The simulation sees the nose where the control puts it: G41 offsets it into the part.
    for (const std::string machine : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        const Simulated wrong = simulate(
            samples + "shaft-control.json", machine, "g41.nc",
            [](std::string t) { return t.replace(t.find("G42 G1"), 3, "G41"); }, "", "44,70,0");
        CHECK(wrong.run.code == 1);
        CHECK(wrong.run.out.find("error: gouge: /operations/0 (the part inside the profile): material removed") !=
              std::string::npos);
    }
}

TEST_CASE("camgen simulate: a tool 0.05 mm into the shaft's finished D30 is a gouge at its line, on every lathe") {
    for (const std::string machine : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        // The finishing pass along D30 (to Z-20.4, the tip of the compensated nose) stops at Z-19
        // (beyond the thread, which ends at Z-11, and the groove at Z-12 to Z-16), feeds in to X29.9
        // and out again (with decimal points: a Fanuc reads X30 as 0.03 mm).
        std::size_t dig = 0;
        const Simulated s = simulate(samples + "shaft.json", machine, "gouge.nc", [&](const std::string& t) {
            const std::vector<std::string> lines = test::lines_of(t);
            std::string pass;
            for (const std::string& l : lines)
                if (std::regex_search(l, std::regex(R"((^|\s)Z-20\.40*$)"))) pass = l;
            REQUIRE(!pass.empty());
            auto [text, at] = replace_line(t, "finish the outside", pass, "G1 Z-19.0\nX29.9\nX30.0\n" + pass);
            dig = at + 1;
            return text;
        });
        CHECK(s.run.code == 1);
        CHECK_MESSAGE(has(s.run, "error: gouge: /operations/4 (the part inside the profile): material removed 0.05 mm inside the "
                                 "designed radius 15 at Z-"),
                      s.run.out);
        CHECK_MESSAGE(has(s.run, fmt::format("(radius 14.95), by line {} (cut at ", dig)), s.run.out);
        CHECK_FALSE(has(s.run, "the part is as designed"));
    }
}

TEST_CASE("camgen simulate: a lathe's drill 0.5 mm too deep is a gouge below its point at its line") {
    // linuxcnc-lathe pecks with G1 (the last to Z-33.0043), fanuc-lathe drills with G74.
    const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
        {"linuxcnc-lathe", "G1 Z-33.0043", "G1 Z-33.5043"}, {"fanuc-lathe", "Z-33.004 Q6000", "Z-33.504 Q6000"}};
    for (const auto& [machine, from, to] : cases) {
        CAPTURE(machine);
        std::size_t line = 0;
        const Simulated s = simulate(samples + "shaft.json", machine, "deep.nc", [&](const std::string& t) {
            const std::vector<std::string> lines = test::lines_of(t);
            for (std::size_t i = 0; i < lines.size(); ++i)
                if (lines[i].find(from) != std::string::npos) line = i + 1;
            REQUIRE(line > 0);
            std::string out = t;
            out.replace(out.find(from), from.size(), to);
            return out;
        });
        CHECK(s.run.code == 1);
        // The hole's cone 0.5 mm lower: below the point, and wider than designed on the cone.
        CHECK_MESSAGE(has(s.run, "error: gouge: /operations/2 (the part below the hole's point): material removed "), s.run.out);
        CHECK_MESSAGE(has(s.run, fmt::format("beyond the designed bore radius 0 at Z-33.")), s.run.out);
        CHECK_MESSAGE(has(s.run, fmt::format("), by line {} (cut at ", line)), s.run.out);
        CHECK(has(s.run, "error: gouge: /operations/2 (the part around the hole): material removed "));
    }
}

TEST_CASE("camgen simulate: the shaft's finishing pass removed leaves material, a warning with where and how much") {
    // Everything of the pass between its feed down to Z0 and its lift off D40 at Z-40.
    const Simulated s = simulate(samples + "shaft.json", "linuxcnc-lathe", "left.nc", [](const std::string& t) {
        const std::string lift = "X40.7071 Z-39.6464\n";
        const std::size_t a = t.find("G1 Z0 F0.1\n") + std::string("G1 Z0 F0.1\n").size(), b = t.find(lift);
        REQUIRE(a < b);
        return t.substr(0, a) + t.substr(b + lift.size());
    });
    CHECK(s.run.code == 0);  // a warning
    // The bar's radius 22 where the roughing's face (at Z-39.9, allowanceZ 0.1) stops and the
    // finishing pass should have turned D40 on to Z-40.
    CHECK_MESSAGE(has(s.run, "warning: /operations/4 (the turned profile): material left 1.855 mm above the radius its tool "
                             "leaves (20.145) at Z-39.901: radius 22 (at "),
                  s.run.out);
    CHECK_FALSE(has(s.run, "error: gouge"));
    CHECK_FALSE(has(s.run, "the part is as designed"));
}

TEST_CASE("camgen simulate: a roughing pass 0.1 mm into its allowance is a gouge of the turn-rough at its line") {
    // The shaft's facing and roughing alone: the rough leaves the profile 0.2 mm out (radius)
    // and 0.1 mm towards +Z, which its design keeps.
    const fs::path dir = test::scratch("simulate-lathe-rough");
    nlohmann::json job = nlohmann::json::parse(test::read_file(samples + "shaft.json"));
    job["operations"] = nlohmann::json::array({job["operations"][0], job["operations"][3]});
    // As linuxcnc-lathe's G71 (the default output) it is made as designed too.
    const std::string canned = (dir / "canned.json").string();
    std::ofstream(canned) << job.dump(1);
    const Simulated g71 = simulate(canned, "linuxcnc-lathe", "canned.ngc", [](const std::string& t) { return t; });
    CHECK(g71.program.find("G71 Q100") != std::string::npos);
    CHECK_MESSAGE(has(g71.run, "  the part is as designed\n"), g71.run.out);
    // Longhand, whose last pass has a line of its own to edit.
    job["operations"][1]["output"] = "longhand";
    const std::string file = (dir / "rough.json").string();
    std::ofstream(file) << job.dump(1);
    const Simulated clean = simulate(file, "linuxcnc-lathe", "rough.ngc", [](const std::string& t) { return t; });
    CHECK_MESSAGE(has(clean.run, "  the part is as designed\n"), clean.run.out);
    // Its last pass along D30.4 (radius 15.2) run at D30.2 instead.
    std::size_t line = 0;
    const Simulated s = simulate(file, "linuxcnc-lathe", "gouge.ngc", [&](const std::string& t) {
        auto [text, at] = replace_line(t, "rough the outside", "G1 Z-20.7", "G1 X30.2\nZ-20.7\nX30.4");
        line = at + 1;
        return text;
    });
    CHECK(s.run.code == 1);
    CHECK_MESSAGE(has(s.run, fmt::format("error: gouge: /operations/1 (the part inside the profile): material removed 0.1 mm "
                                         "inside the designed radius 15.2 at Z-")),
                  s.run.out);
    CHECK_MESSAGE(has(s.run, fmt::format("(radius 15.1), by line {} (cut at ", line)), s.run.out);
}

TEST_CASE("camgen simulate: a lathe tool 0.012 mm into a shoulder between two Z samples 0.01 mm apart is found by the sections beside it") {
    // The face at Z0 from D24 to D28 (the tool feeds out along it): the added moves go in to Z-0.012
    // at D26 and back. The samples at Z-0.005 (the face within the 0.008 mm tolerance: either side
    // of it) and Z-0.015 (below the cut) cannot see it; the section 0.0088 mm below the face does.
    std::size_t line = 0;
    const Simulated s = simulate(
        samples + "shaft.json", "linuxcnc-lathe", "shoulder.nc",
        [&](const std::string& t) {
            auto [text, at] = replace_line(t, "finish the outside", "X27.2", "X26.0\nZ-0.012\nZ0.0\nX27.2");
            line = at + 1;
            return text;
        },
        "0.01");
    CHECK(s.run.code == 1);
    // (the thread M30x2 from Z0 designs its minor radius 13.773 there: the deepest design at that Z)
    CHECK_MESSAGE(has(s.run, fmt::format("error: gouge: /operations/6 (the part inside the profile): material removed ")), s.run.out);
    CHECK_MESSAGE(has(s.run, fmt::format("at Z-0.0088 (radius 13.35), by line {} (cut at 0 samples and 1 section beside corners)", line)),
                  s.run.out);
}

TEST_CASE("camgen simulate: the shaft's roughing along X leaves the part as designed on the three lathes") {
    // The facing and the roughing with "direction": "x": the same boundary, roughed in passes
    // along -X; simulated as each lathe's program reads back, the part is as designed.
    const fs::path dir = test::scratch("simulate-lathe-rough-x");
    nlohmann::json job = nlohmann::json::parse(test::read_file(samples + "shaft.json"));
    job["operations"][3]["direction"] = "x";
    job["operations"] = nlohmann::json::array({job["operations"][0], job["operations"][3]});
    const std::string file = (dir / "rough-x.json").string();
    std::ofstream(file) << job.dump(1);
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        const Simulated s = simulate(file, machine, "rough-x-" + machine + ".nc", [](const std::string& t) { return t; });
        const std::string said = machine + "\n" + s.run.out;
        CHECK_MESSAGE(s.run.code == 0, said);
        CHECK_MESSAGE(has(s.run, "  the part is as designed\n"), said);
    }
}

TEST_CASE("camgen simulate: an internal thread opens the bore to its major diameter, as designed; deeper is a gouge, shallower material left") {
    // A D20.4 bore drilled 25 deep, threaded M22x1.5 inside down to Z-15: the threading tool
    // (none, or an orientation whose tip points to +X) is swept as a boring tool, which opens the
    // bore and leaves the outside alone; its nose rounds the thread's end.
    const fs::path dir = test::scratch("simulate-internal-thread");
    for (const std::string orientation : {"", ", \"orientation\": 3", ", \"orientation\": 8", ", \"orientation\": 4"}) {
        CAPTURE(orientation);
        const std::string job = (dir / "inside.json").string();
        std::ofstream(job) << R"({"clearance": 20, "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 0}}, "tools": [
 {"number": 2, "type": "drill", "diameter": 20.4, "tipAngle": 118, "rpm": 500},
 {"number": 8, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 400)" + orientation + R"(}],
 "operations": [
  {"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -25, "safeDistance": 2, "retractDistance": 5,
   "feedMode": "per-revolution", "plungingFeedrate": 0.1},
  {"type": "turn-thread", "tool": 8, "thread": "M22x1.5", "side": "internal", "startZ": 0, "endZ": -15, "firstDepth": 0.2}]})";
        const Job parsed = read_job(test::read_file(job), "inside.json");
        const PartDesign design = part_design(parsed);
        CHECK(design.unchecked.empty());
        REQUIRE(design.lathe.holes.size() == 2);
        const LatheHoleDesign& h = design.lathe.holes[1];
        CHECK(h.path == "/operations/1");
        CHECK(h.radius_at(-10) == doctest::Approx(11));
        CHECK(h.radius_at(-15 + h.nose_above + 1e-9) == doctest::Approx(11));
        CHECK(h.radius_at(-15 + h.nose_above - 0.1 - 1e-6) == 0.0);
        CHECK(h.radius_at(-15 + h.nose_above - 0.05) == doctest::Approx(10.9 + std::sqrt(0.01 - 0.0025)));
        for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
            CAPTURE(machine);
            const Simulated s = simulate(job, machine, "inside.nc", [](const std::string& t) { return t; }, "", "40,50,0");
            CHECK_MESSAGE(s.run.code == 0, s.run.out << s.run.err);
            CHECK_MESSAGE(has(s.run, "the part is as designed"), s.run.out);
            CHECK_MESSAGE(has(s.run, "simulation: no errors"), s.run.out);
            // The thread removes the ring from the minor bore of the drill (D20.4) to D22 over 15
            // mm (and a little more at the thread's start, beyond the drill's): the outside stays.
            const std::regex removed(R"(tool T8: removed ([0-9.]+) mm\^3)");
            std::smatch m;
            REQUIRE(std::regex_search(s.run.out, m, removed));
            const double ring = pi_ * (11.0 * 11.0 - 10.2 * 10.2) * 15.0;
            CHECK(std::stod(m[1]) == doctest::Approx(ring).epsilon(0.02));
        }
    }
    // Written longhand on linuxcnc-lathe (not its G76): the passes' X is the tip's diameter; the
    // last passes at X22 (D22).
    const std::string job = (dir / "inside-longhand.json").string();
    {
        std::string text = test::read_file((dir / "inside.json").string());
        const std::string key = R"("side": "internal",)";
        REQUIRE(text.find(key) != std::string::npos);
        text.replace(text.find(key), key.size(), key + R"( "output": "longhand",)");
        std::ofstream(job) << text;
    }
    auto edit_last = [](const std::string& to) {
        return [to](const std::string& t) { return std::regex_replace(t, std::regex("\nX22\n"), "\n" + to + "\n"); };
    };
    const Simulated deeper = simulate(job, "linuxcnc-lathe", "deeper.nc", edit_last("X22.4"), "", "40,50,0");
    CHECK(deeper.run.code == 1);
    CHECK_MESSAGE(has(deeper.run, "error: gouge: /operations/1 (the part around the hole): material removed 0.2 mm beyond the designed "
                                  "bore radius 11"),
                  deeper.run.out);
    const Simulated shallower = simulate(job, "linuxcnc-lathe", "shallower.nc", edit_last("X21.8"), "", "40,50,0");
    CHECK_MESSAGE(has(shallower.run, "warning: /operations/1 (the hole): material left 0.012 mm inside the radius its tool cuts (11)"),
                  shallower.run.out);
}

TEST_CASE("camgen simulate: a turning tool's tip past the axis has its nose centred there (a profile that faces from the centre)") {
    // The tip at X-0.8 (diameter) of an R0.4 nose of orientation 2: the nose's centre is on the
    // axis. Swept with the centre mirrored from the tip's |X|, it read 0.718 mm of material
    // left at the face's centre.
    const fs::path dir = test::scratch("simulate-past-axis");
    const std::string job = (dir / "stub.json").string();
    std::ofstream(job) << R"({"clearance": 20, "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 1}},
 "tools": [{"number": 3, "type": "turning-tool", "noseRadius": 0.4, "rpm": 800}],
 "operations": [{"type": "turn-profile", "tool": 3, "xValues": "diameter", "feedMode": "per-revolution", "feed": 0.1,
   "start": [0, 0], "retractX": 44, "path": [{"line": [30, 0]}, {"line": [30, -10]}, {"line": [40, -10]}]}]})";
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        const Simulated s = simulate(job, machine, "stub.nc", [](const std::string& t) { return t; }, "", "40,50,1");
        CHECK_MESSAGE(s.run.code == 0, s.run.out << s.run.err);
        CHECK_MESSAGE(has(s.run, "the part is as designed"), s.run.out);
        CHECK_MESSAGE(!has(s.run, "warning:"), s.run.out);
    }
}

}  // namespace test_simulation_lathe_design
