// A machine file cannot break motion (issue 24): settings its dialect would write as wrong
// motion, or that camgen could not read back, are refused when the file is read, naming the
// file, the line and the JSON path of the setting. One case per finding of the issue, each an
// "extends" of a built-in machine with one setting changed, as a user would write it.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_machine_checks {

using namespace camgen;
using namespace camgen::test;

namespace {

namespace fs = std::filesystem;

struct Refused {
    int code = 0;
    std::string err;
    bool wrote = false;
    std::string file;
};

// Posts samples/<sample>.json for the machine file `text` (written as <name>.json) into a file.
Refused post_with(const std::string& name, const std::string& text, const std::string& sample) {
    const fs::path dir = scratch("machine-check-" + name);
    const fs::path file = dir / (name + ".json");
    std::ofstream(file) << text;
    const fs::path out = dir / "out.nc";
    const Run r = run({std::string(CAMGEN_SOURCE_DIR) + "/samples/" + sample + ".json", "--machine", file.string(), "-o",
                       out.string()});
    return {r.code, r.err, fs::exists(out), file.string()};
}

// The file's refusal names the file, the line and the JSON path, and says `why`.
void check_refused(const Refused& r, int line, const std::string& path, const std::string& why) {
    CAPTURE(r.err);
    CHECK(r.code == 1);
    CHECK(!r.wrote);
    CHECK(r.err.find(fmt::format("{}:{}: {}: ", r.file, line, path)) != std::string::npos);
    CHECK(r.err.find(why) != std::string::npos);
}

}  // namespace

TEST_CASE("a lathe that turns off xDiameterProg under linuxcnc-lathe's G7 is refused: X would be cut at half its radius") {
    const Refused r = post_with("g7-radius", "{\n  \"extends\": \"linuxcnc-lathe\",\n  \"globals\": {\"xDiameterProg\": false}\n}\n",
                                "shaft");
    check_refused(r, 3, "/globals/xDiameterProg", "the start block's G7");
    CHECK(r.err.find("half its radius") != std::string::npos);
    // Taking G7 out with it (the control in its radius mode) is a consistent lathe.
    const Refused ok = post_with("g7-out", R"({"extends": "linuxcnc-lathe", "globals": {"xDiameterProg": false},
        "frame": {"startBlock": ["G18", "G8", "G40", "G80", "G90", "G94"]}})", "shaft");
    CHECK_MESSAGE(ok.code == 0, ok.err);
    // The other way round: G8 (radius) with X written as a diameter, named at the word the file gives.
    const Refused g8 = post_with("g8-diameter", "{\"extends\": \"linuxcnc-lathe\",\n"
                                                "  \"frame\": {\"startBlock\": [\"G18\", \"G8\", \"G40\", \"G80\", \"G90\", \"G94\"]}}\n",
                                 "shaft");
    check_refused(g8, 2, "/frame/startBlock/1", "twice its radius");
}

TEST_CASE("a lathe that turns off xDiameterProg under sinumerik-lathe's DIAMON is refused") {
    const Refused r = post_with("diamon-radius", "{\n  \"extends\": \"sinumerik-lathe\",\n  \"globals\": {\"xDiameterProg\": false}\n}\n",
                                "shaft");
    check_refused(r, 3, "/globals/xDiameterProg", "the start block's DIAMON");
}

TEST_CASE("G7 with iDiameterProg is refused: LinuxCNC reads I as a radius under G7") {
    const Refused r = post_with("g7-i-diameter", "{\n  \"extends\": \"linuxcnc-lathe\",\n  \"globals\": {\"iDiameterProg\": true}\n}\n",
                                "shaft");
    check_refused(r, 3, "/globals/iDiameterProg", "I and K as radii");
}

TEST_CASE("a code format with a scale is refused: scale 2 writes G21 as G42 and M3 as M6") {
    const Refused r = post_with("code-scale", "{\n  \"extends\": \"linuxcnc\",\n  \"formats\": {\n    \"code\": {\"scale\": 2}\n  }\n}\n",
                                "plate");
    check_refused(r, 4, "/formats/code/scale", "G21 as G42 and M3 as M6");
}

TEST_CASE("code decimals 0 on a machine that taps with G33.1 is refused: G33.1 would be written as G33") {
    const Refused r = post_with("code-decimals", "{\n  \"extends\": \"linuxcnc\",\n  \"formats\": {\"code\": {\"decimals\": 0}}\n}\n",
                                "tapping-rigid");
    check_refused(r, 3, "/formats/code/decimals", "G33.1 as G33");
    // Without a G33.1 cycle no code has a fraction: whole codes are written as before.
    const Refused fanuc = post_with("code-decimals-fanuc", R"({"extends": "fanuc", "formats": {"code": {"decimals": 0}}})", "plate");
    CHECK_MESSAGE(fanuc.code == 0, fanuc.err);
}

TEST_CASE("a decimal comma on sinumerik is refused: the comma separates cycle parameters") {
    const Refused r = post_with("sinumerik-comma", "{\n  \"extends\": \"sinumerik\",\n  \"globals\": {\"decimalMark\": \",\"}\n}\n",
                                "drilling");
    check_refused(r, 3, "/globals/decimalMark", "CYCLE82(5,000, 0,000, ...)");
    // ISO controls read a point only (rs274 refuses the comma; Fanuc's ,C ,R are words of their own).
    const Refused iso = post_with("linuxcnc-comma", "{\n  \"extends\": \"linuxcnc\",\n  \"globals\": {\"decimalMark\": \",\"}\n}\n",
                                  "plate");
    check_refused(iso, 3, "/globals/decimalMark", "decimal point only");
}

TEST_CASE("heidenhain with XZ arcs is refused: its arc blocks are XY arcs") {
    const Refused r = post_with("heidenhain-xz", "{\n  \"extends\": \"heidenhain\",\n  \"arcs\": {\"planes\": [\"xy\", \"xz\"]}\n}\n",
                                "arcs");
    check_refused(r, 3, "/arcs/planes/1", "XY plane only");
    const Refused kosy = post_with("kosy-yz", R"({"extends": "kosy", "arcs": {"planes": ["yz"]}})", "arcs");
    check_refused(kosy, 1, "/arcs/planes/0", "XY plane only");
}

TEST_CASE("a single arc plane other than the start block's is refused: no plane word would be written") {
    const Refused r = post_with("linuxcnc-xz", "{\n  \"extends\": \"linuxcnc\",\n  \"arcs\": {\"planes\": [\"xz\"]}\n}\n", "arcs");
    check_refused(r, 3, "/arcs/planes", "the start block selects G17 (XY)");
    // Selecting the plane in the start block instead is named at that word when the file gives it.
    const Refused lathe = post_with("lathe-g17", "{\"extends\": \"linuxcnc-lathe\",\n"
                                                 "  \"frame\": {\"startBlock\": [\"G17\", \"G7\", \"G40\", \"G80\", \"G90\", \"G94\"]}}\n",
                                    "shaft");
    check_refused(lathe, 2, "/frame/startBlock/0", "arcs.planes is [\"xz\"] alone");
    // A start block without a plane word leaves LinuxCNC in G17.
    const Refused none = post_with("lathe-no-plane", R"({"extends": "linuxcnc-lathe",
        "frame": {"startBlock": ["G7", "G40", "G80", "G90", "G94"]}})", "shaft");
    check_refused(none, 2, "/frame/startBlock", "the control starts in G17 (XY)");
}

TEST_CASE("a width without zeropad is refused: the number would be padded with spaces") {
    const Refused r = post_with("width-spaces", "{\n  \"extends\": \"linuxcnc\",\n  \"formats\": {\"xyz\": {\"width\": 8}}\n}\n",
                                "plate");
    check_refused(r, 3, "/formats/xyz/width", "pads the number with spaces");
    const Refused padded = post_with("width-zeros", R"({"extends": "linuxcnc", "formats": {"xyz": {"width": 3, "zeropad": true}}})",
                                     "plate");
    CHECK_MESSAGE(padded.code == 0, padded.err);
}

TEST_CASE("a machine file without extends is refused at its own line, and --describe-machine refuses it too") {
    const fs::path dir = scratch("machine-check-own");
    std::string text = read_file(CAMGEN_SOURCE_DIR "/machines/linuxcnc-lathe.json");
    const auto at = text.find("\"xDiameterProg\": true");
    REQUIRE(at != std::string::npos);
    text.replace(at, 21, "\"xDiameterProg\": false");
    const int line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n')) + 1;
    const fs::path file = dir / "mylathe.json";
    std::ofstream(file) << text;
    const Run r = run({"--describe-machine", file.string()});
    CHECK(r.code == 1);
    CHECK(r.err.find(fmt::format("{}:{}: /globals/xDiameterProg: ", file.string(), line)) != std::string::npos);
}

TEST_CASE("an nccad machine that says it taps is refused: its spindle cannot reverse") {
    const Refused r = post_with("wabeco-taps", "{\"extends\": \"wabeco\",\n  \"drilling\": {\"tapping\": \"floating\"}}\n",
                                "drilling");
    check_refused(r, 2, "/drilling/tapping", "nccad's spindle runs clockwise only");
    CHECK(r.err.find("set tapping to none") != std::string::npos);
}

TEST_CASE("every built-in machine passes its checks") {
    for (const auto& [name, description] : list_machines()) {
        CAPTURE(name);
        CHECK(!machine_problem(load_machine(name)));
    }
}

TEST_CASE("found by the variants of tests/machines: coordinate scales, axis decimals, start-block words, block numbers, arc forms") {
    // A scale on coordinates makes the part that many times bigger, and arcs with centres
    // scaled otherwise run off their circles (rs274: "radius to end of arc differs").
    check_refused(post_with("xyz-scale", "{\"extends\": \"linuxcnc\",\n \"formats\": {\"xyz\": {\"scale\": 10}}}", "arcs"), 2,
                  "/formats/xyz/scale", "10 times what the job says");
    // Z coarser than xyz: depths and pecks are rounded at xyz's resolution.
    check_refused(post_with("z-decimals", "{\"extends\": \"linuxcnc\",\n \"formats\": {\"z\": {\"decimals\": 1}}}", "drilling"), 2,
                  "/formats/z/decimals", "Z words with 1 decimals where the xyz format has 4");
    // The unit word comes from "units"; two planes in one block; a word the reader does not read back.
    check_refused(post_with("start-g21", "{\"extends\": \"grbl\",\n \"frame\": {\"startBlock\": [\"G40\", \"G21\"]}}", "plate"), 2,
                  "/frame/startBlock/1", "G21 is a unit word");
    check_refused(post_with("start-planes", "{\"extends\": \"fanuc\",\n \"frame\": {\"startBlock\": [\"G17\", \"G18\"]}}", "plate"), 2,
                  "/frame/startBlock/1", "two planes in one block");
    check_refused(post_with("start-diamof", "{\"extends\": \"sinumerik\",\n \"frame\": {\"startBlock\": [\"G17\", \"DIAMOF\"]}}",
                            "plate"),
                  2, "/frame/startBlock/1", "DIAMOF is not a word of a sinumerik safe start");
    check_refused(post_with("start-g91", "{\"extends\": \"linuxcnc\",\n \"frame\": {\"startBlock\": [\"G17\", \"G91\"]}}", "plate"), 2,
                  "/frame/startBlock/1", "G91 is not a word of a iso safe start");
    // Heidenhain numbers its blocks 0, 1, 2, ...
    check_refused(post_with("tnc-step", "{\"extends\": \"heidenhain\",\n \"globals\": {\"sequenceNumberIncrement\": 100}}", "plate"), 2,
                  "/globals/sequenceNumberIncrement", "numbers every block 0, 1, 2");
    // nccad has no R and no absolute centres.
    check_refused(post_with("kosy-radius", "{\"extends\": \"kosy\",\n \"arcs\": {\"format\": \"radius\"}}", "arcs"), 2,
                  "/arcs/format", "it has no R");
    // The nccad angle form's own limits name the setting the file changed.
    check_refused(post_with("linuxcnc-angle", "{\"extends\": \"linuxcnc\",\n \"arcs\": {\"format\": \"nccad-angle\"}}", "arcs"), 2,
                  "/arcs/format", "at most 180 degrees");
    // An inch format inherits the mm format's width: named at the width the file gives.
    check_refused(post_with("width-inch", "{\"extends\": \"linuxcnc\",\n \"formats\": {\"xyz\": {\"width\": 3}}}", "plate"), 2,
                  "/formats/xyz/width", "pads the number with spaces");
}

}  // namespace test_machine_checks
