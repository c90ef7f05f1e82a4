// camgen simulate checks the simulated part against the job's design (issue 27): every mill
// sample on every mill machine simulates as designed, and a hand-edited program's gouge and
// material left are found, the gouge at the line that cut it.
#include <filesystem>
#include <fstream>
#include <regex>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "support.hpp"

namespace test_simulate_design {

namespace fs = std::filesystem;
using namespace camgen;

namespace {

const std::string samples = CAMGEN_SOURCE_DIR "/samples/";

std::string edited(std::string text, const std::string& from, const std::string& to, bool all = false) {
    std::size_t at = text.find(from);
    REQUIRE_MESSAGE(at != std::string::npos, from);
    do {
        text.replace(at, from.size(), to);
        at = text.find(from, at + to.size());
    } while (all && at != std::string::npos);
    return text;
}

}  // namespace

TEST_CASE("camgen simulate: every mill sample on every mill machine makes the part its job designs") {
    const fs::path dir = test::scratch("simulate-design");
    // The stock each sample is cut from (stock-plate.json gives its own): its top where the
    // job's reference plane is; the plate's 8 mm, drilled through (the floor below the stock's bottom
    // is its bottom).
    const std::vector<std::pair<std::string, std::string>> jobs = {
        {"plate.json", "-20,-20,-8,120,70,0"},          {"pocket.json", "-20,-20,-20,120,90,0"},
        {"face.json", "-20,-20,-20,120,90,1"},           {"bores.json", "-20,-20,-30,130,120,0"},
        {"drilling.json", "-30,-30,-40,150,120,0"},      {"plate-outline.json", "-30,-30,-20,230,150,0"},
        {"plate-outline-control.json", "-30,-30,-20,230,150,0"}, {"pocket-wall.json", "-30,-30,-20,150,120,0"},
        {"stock-plate.json", ""},                        {"thread.json", ""},
        {"engrave.json", ""}};
    int simulated = 0;
    for (const char* machine : {"fanuc", "linuxcnc", "grbl", "sinumerik", "heidenhain", "wabeco", "kosy"})
        for (const auto& [file, box] : jobs) {
            CAPTURE(machine);
            CAPTURE(file);
            const std::string job = samples + file;
            const std::string program = (dir / "p.nc").string();
            if (test::run({job, "--machine", machine, "-q", "-o", program}).code != 0) continue;  // refused there (a golden .err)
            std::vector<std::string> args{"simulate", program, "--machine", machine, "--job", job, "--resolution", "0.2"};
            if (!box.empty()) args.insert(args.end(), {"--stock-box", box});
            const test::Run r = test::run(args);
            CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
            CHECK(r.out.find("simulation: no errors\n") != std::string::npos);
            CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
            ++simulated;
        }
    CHECK(simulated >= 69);
}

TEST_CASE("camgen simulate: a tap the machine leaves to the operator at a stop is not checked; where it taps, it is") {
    const fs::path dir = test::scratch("simulate-operator-tap");
    const std::string job = (dir / "tap.json").string();
    std::ofstream(job) << R"({"clearance": 20, "stock": {"box": {"min": [0, 0, -20], "max": [40, 40, 0]}},
      "tools": [{"number": 1, "type": "drill", "diameter": 6.8, "tipAngle": 118, "rpm": 1200},
                {"number": 7, "type": "tap", "diameter": 8, "rpm": 300}],
      "operations": [{"type": "drill", "tool": 1, "retractPlane": 5, "safeDistance": 2, "endDepth": 15,
                      "plungingFeedrate": 120, "holes": [[10, 10], [30, 30]]},
                     {"type": "drill", "tool": 7, "cycle": "tap", "unsupported": "stop", "retractPlane": 5,
                      "safeDistance": 3, "endDepth": 12, "pitch": 1.25, "holes": [[10, 10], [30, 30]]}]})";
    for (const char* machine : {"wabeco", "linuxcnc"}) {
        CAPTURE(machine);
        const std::string program = (dir / (std::string(machine) + ".nc")).string();
        REQUIRE(test::run({job, "--machine", machine, "-q", "-o", program}).code == 0);
        const test::Run r = test::run({"simulate", program, "--machine", machine, "--job", job, "--resolution", "0.2"});
        CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
        const bool stop = std::string(machine) == "wabeco";  // nccad's spindle cannot reverse
        CHECK(stop == (r.out.find("  not checked: /operations/1: the program leaves its cycle to the operator at a stop (machine "
                                  "wabeco cannot tap)\n") != std::string::npos));
        // Before, wabeco's simulation read the tap's ring from 6.8 to 8 mm as material left.
        CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
    }
}

TEST_CASE("camgen simulate: a pocket's floor cut too deep is a gouge at its line; a floor left high is material left") {
    const fs::path dir = test::scratch("simulate-gouge");
    const std::string job = samples + "pocket.json";
    const std::string program = (dir / "pocket.ngc").string();
    REQUIRE(test::run({job, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    const std::string text = test::read_file(program);
    const std::vector<std::string> args{"--machine", "linuxcnc", "--job", job, "--stock-box", "-20,-20,-20,120,90,0", "--resolution", "0.1"};
    auto simulate = [&](const std::string& name, const std::string& body) {
        const std::string file = (dir / name).string();
        std::ofstream(file) << body;
        std::vector<std::string> a{"simulate", file};
        a.insert(a.end(), args.begin(), args.end());
        return test::run(a);
    };
    // As posted: as designed.
    const test::Run ok = simulate("ok.ngc", text);
    CHECK(ok.code == 0);
    CHECK(ok.out.find("  the part is as designed\n") != std::string::npos);
    // The first move down to the floor (Z-6) goes on to Z-6.3 and back: the cells under the tool
    // there are 0.3 mm below the floor, cut by the added line.
    const std::vector<std::string> lines = test::lines_of(text);
    const std::regex at_floor(R"(Z-6(\s|$))");
    std::size_t floor = 0;
    while (floor < lines.size() && !std::regex_search(lines[floor], at_floor)) ++floor;
    REQUIRE(floor < lines.size());
    std::string deep;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        deep += lines[i] + "\n";
        if (i == floor) deep += "G1 Z-6.3\nG1 Z-6\n";
    }
    const test::Run gouge = simulate("deep.ngc", deep);
    CHECK(gouge.code == 1);
    CHECK_MESSAGE(gouge.out.find(fmt::format("error: gouge: /operations/0 (the pocket): material removed 0.3 mm below the designed -6 at ")) !=
                      std::string::npos,
                  gouge.out);
    CHECK_MESSAGE(gouge.out.find(fmt::format(", by line {} (", floor + 2)) != std::string::npos, gouge.out);
    // Every Z-6 written as Z-5.5: the pocket's floor is left 0.5 mm high (a warning: exit 0).
    const test::Run high = simulate("high.ngc", edited(text, "Z-6", "Z-5.5", true));
    CHECK(high.code == 0);
    CHECK_MESSAGE(high.out.find("warning: /operations/0 (the pocket): material left 0.5 mm above its floor and allowance -6 at ") !=
                      std::string::npos,
                  high.out);
}

TEST_CASE("camgen simulate: a drill 0.05 mm beside its hole cuts the part around the hole, found by the points on its wall") {
    // Three 5 mm holes; the second drilled 0.05 mm to the right takes 0.05 mm of its wall, which no
    // judged cell centre at 0.2 mm sees (they keep 0.149 mm from the hole's edge): the points on
    // the wall, 0.008 mm into the part around the hole, do (they were placed along the wall, not
    // into the part, where a wall is an arc: none was kept).
    const fs::path dir = test::scratch("simulate-hole-wall");
    const std::string job = (dir / "holes.json").string();
    std::ofstream(job) << R"({"name": "holes", "clearance": 10,
        "tools": [{"number": 1, "type": "drill", "diameter": 5, "tipAngle": 118, "rpm": 1500}],
        "operations": [{"type": "drill", "tool": 1, "cycle": "deep", "retractPlane": 10, "safeDistance": 2,
          "safeDistanceIsAbsolute": true, "endDepth": -6, "endDepthIsAbsolute": true, "firstDepth": 3,
          "plungingFeedrate": 100, "holes": [[10, 10], [30, 10], [30, 30]]}]})";
    const std::string program = (dir / "holes.ngc").string();
    REQUIRE(test::run({job, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    auto simulate = [&](const std::string& name, const std::string& text) {
        const std::string file = (dir / name).string();
        std::ofstream(file) << text;
        return test::run({"simulate", file, "--machine", "linuxcnc", "--job", job, "--stock-box", "0,0,-10,40,40,0",
                          "--resolution", "0.2"});
    };
    const std::string text = test::read_file(program);
    const test::Run ok = simulate("ok.ngc", text);
    CHECK_MESSAGE(ok.code == 0, ok.out);
    CHECK(ok.out.find("  the part is as designed\n") != std::string::npos);
    std::smatch m;
    REQUIRE(std::regex_search(ok.out, m, std::regex(R"(, (\d+) points on the walls 0.2 mm apart)")));
    CHECK(std::stoi(m[1]) > 100);  // on the three holes' walls
    const test::Run gouge = simulate("gouge.ngc", edited(text, "\nX30 Y10\n", "\nX30.05 Y10\n"));
    CHECK(gouge.code == 1);
    CHECK_MESSAGE(gouge.out.find("error: gouge: /operations/0 (the part around hole 1 at (30, 10)): material removed ") !=
                      std::string::npos,
                  gouge.out);
    CHECK_MESSAGE(std::regex_search(gouge.out, std::regex(R"(\(the part around hole 1 at \(30, 10\)\): material removed [0-9.]+ mm below the designed 0 at \(32\.50[0-9]*, [0-9.]+\), by line 10 \(\d+ points on its walls of the part cut\))")),
                  gouge.out);
}

TEST_CASE("camgen simulate: a thread milled wider than its job's (internal: past the major diameter; external: into the core) is a gouge") {
    // samples/thread.json's M10 internal and M16 external threads, posted with diameters a little
    // off (major 10.1 instead of 10; minor 13.4 instead of d3 = 13.546) and simulated against the
    // sample: the points on the threads' walls find both, named after the thread operations.
    const fs::path dir = test::scratch("simulate-thread");
    const std::string job = samples + "thread.json";
    std::string wide = test::read_file(job);
    wide = edited(wide, "\"thread\": \"M10\"", "\"majorDiameter\": 10.1, \"minorDiameter\": 8.376, \"pitch\": 1.5");
    wide = edited(wide, "\"thread\": \"M16\"", "\"majorDiameter\": 16, \"minorDiameter\": 13.4, \"pitch\": 2");
    const std::string wide_job = (dir / "wide.json").string();
    std::ofstream(wide_job) << wide;
    for (const char* machine : {"linuxcnc", "wabeco"}) {
        CAPTURE(machine);
        const std::string program = (dir / "wide.nc").string();
        REQUIRE(test::run({wide_job, "--machine", machine, "-q", "-o", program}).code == 0);
        const test::Run r = test::run({"simulate", program, "--machine", machine, "--job", job, "--resolution", "0.2"});
        CHECK(r.code == 1);
        CHECK_MESSAGE(std::regex_search(r.out, std::regex(R"(error: gouge: /operations/2 \(the part around thread 0 at \(25, 30\)\): material removed [0-9.]+ mm below the designed 0 at \([0-9.]+, [0-9.]+\), by line \d+)")),
                      r.out);
        CHECK_MESSAGE(std::regex_search(r.out, std::regex(R"(error: gouge: /operations/3 \(the core of thread 0 at \(70, 30\)\): material removed )")),
                      r.out);
    }
}

}  // namespace test_simulate_design

namespace test_simulate_design {

TEST_CASE("camgen simulate: a profile stock that leaves out part of the band kept around a pocket: the cells outside it are not judged") {
    const fs::path dir = test::scratch("simulate-profile-stock");
    // The pocket's outline spans 10..90 x 10..60: the band kept around it reaches 4..96 and
    // 4..66; this stock, 0..100 x 0..70 with its corners cut off 14 mm along each side, leaves
    // the band's corners out: their cells hold no material (the field's bottom), nothing to keep.
    std::string job = test::read_file(samples + "pocket.json");
    job = edited(job, "\"clearance\": 15,", R"("clearance": 15, "stock": {"profile": {"start": [14, 0], "path": [{"line": [86, 0]},
        {"line": [100, 14]}, {"line": [100, 56]}, {"line": [86, 70]}, {"line": [14, 70]}, {"line": [0, 56]}, {"line": [0, 14]},
        {"line": [14, 0]}], "top": 0, "bottom": -20}},)");
    const std::string job_file = (dir / "pocket.json").string(), program = (dir / "pocket.ngc").string();
    std::ofstream(job_file) << job;
    REQUIRE(test::run({job_file, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    const test::Run r = test::run({"simulate", program, "--machine", "linuxcnc", "--job", job_file, "--resolution", "0.1"});
    CHECK_MESSAGE(r.code == 0, r.out);
    CHECK(r.out.find("  the part is as designed\n") != std::string::npos);
}

}  // namespace test_simulate_design

namespace test_simulate_design {

TEST_CASE("camgen simulate: a tool 0.05 mm into a contour's wall is a gouge at its line, found by the points on the wall") {
    const fs::path dir = test::scratch("simulate-wall");
    // The outline's wall is at X0; the 10 mm tool finishes it at X-5 (Z-6, between the tabs at
    // Y52..68). An added move to X-4.95 and back at Y30 takes 0.05 mm of the wall: at 0.2 mm
    // cells no judged cell centre is that close to the wall (they keep 0.149 mm from it); the
    // points on the wall (0.008 mm inside it) are.
    const std::string job = samples + "plate-outline.json";
    const std::string program = (dir / "outline.ngc").string();
    REQUIRE(test::run({job, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    const std::string text = test::read_file(program);
    const std::vector<std::string> lines = test::lines_of(text);
    std::size_t along = 0;  // the finishing pass up the left wall
    while (along < lines.size() && !(lines[along] == "G1 Y52" && lines[along - 1].rfind("G2 X-5 Y10 ", 0) == 0)) ++along;
    REQUIRE(along < lines.size());
    REQUIRE(lines[along - 1].rfind("G2 X-5 Y10 ", 0) == 0);
    auto simulate = [&](const std::string& name, const std::string& into) {
        std::string body;
        for (std::size_t i = 0; i < lines.size(); ++i)
            body += i == along ? fmt::format("G1 Y30\nX{}\nX-5\nY52\n", into) : lines[i] + "\n";
        const std::string file = (dir / name).string();
        std::ofstream(file) << body;
        return test::run({"simulate", file, "--machine", "linuxcnc", "--job", job, "--stock-box", "-30,-30,-20,230,150,0",
                          "--resolution", "0.2"});
    };
    // The same detour that stays on the wall's line (X-5) is as designed.
    const test::Run ok = simulate("ok.ngc", "-5");
    CHECK_MESSAGE(ok.code == 0, ok.out);
    CHECK(ok.out.find("  the part is as designed\n") != std::string::npos);
    // The four lines put for the posted "G1 Y52" are the contour's: its volume is all there is.
    CHECK_MESSAGE(ok.out.find("note: 4 lines of the program differ from what the job posts: counted with the operation of the "
                              "line before\n") != std::string::npos,
                  ok.out);
    CHECK(ok.out.find("operation /operations/0: removed ") != std::string::npos);
    const test::Run gouge = simulate("gouge.ngc", "-4.95");
    CHECK(gouge.code == 1);
    CHECK_MESSAGE(gouge.out.find("error: gouge: /operations/0 (the part inside the contour): material removed 6 mm below the designed 0 at (0.008, ") !=
                      std::string::npos,
                  gouge.out);
    CHECK_MESSAGE(gouge.out.find(fmt::format(", by line {} (", along + 2)) != std::string::npos, gouge.out);
    CHECK_MESSAGE(gouge.out.find(" points on its walls of the part cut)") != std::string::npos, gouge.out);
}

}  // namespace test_simulate_design
