// Tool libraries (issue 29 item 5): library files found as machine files are (--tools,
// CAMGEN_TOOLS, $XDG_CONFIG_HOME/camgen/tools), a job's tool naming one by "library", its keys
// overriding the library's, rpm and feeds computed from the cutting data for the job's material
// (with the radial chip-thinning correction and the machine's limits), and the errors of bad
// libraries.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "camgen/job/tool_library.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

namespace test_tool_library {

using namespace camgen;
using namespace camgen::test;

namespace fs = std::filesystem;

const std::string sample_dir = std::string(CAMGEN_SOURCE_DIR) + "/samples/library";
const std::string sample_tools = sample_dir + "/tools.json";
const std::string sample_job = sample_dir + "/plate-library.json";

// Sets an environment variable (or unsets it: nullopt) for one test and puts the old value back.
class ToolEnvGuard {
public:
    ToolEnvGuard(const char* name, const std::optional<std::string>& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value) setenv(name, value->c_str(), 1);
        else unsetenv(name);
    }
    ~ToolEnvGuard() {
        if (old_) setenv(name_, old_->c_str(), 1);
        else unsetenv(name_);
    }
    ToolEnvGuard(const ToolEnvGuard&) = delete;
    ToolEnvGuard& operator=(const ToolEnvGuard&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

// Writes `text` to `dir`/`file` and returns the path.
std::string write_to(const fs::path& dir, const std::string& file, const std::string& text) {
    fs::create_directories(dir);
    const fs::path p = dir / file;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

// The operation at `index` of a job as its type.
template <class Op>
const Op& op_at(const Job& job, std::size_t index) {
    REQUIRE(index < job.operations.size());
    const Op* op = std::get_if<Op>(&job.operations[index]);
    REQUIRE(op != nullptr);
    return *op;
}

// A library of plain tools (geometry and rpm, no cutting data).
const std::string plain_library = R"({"tools": [
  {"name": "spot", "type": "spot-drill", "diameter": 10, "tipAngle": 90, "rpm": 1500, "comment": "spot drill 90 deg"},
  {"name": "jobber-6", "type": "drill", "diameter": 6, "tipAngle": 118, "rpm": 1200, "comment": "HSS jobber", "fluteLength": 57}
]})";

}  // namespace test_tool_library

using namespace test_tool_library;

TEST_CASE("a job naming library tools posts byte for byte the program of the job with the tools written out") {
    const std::string tools = write_to(scratch("toollib-plain"), "tools.json", plain_library);
    const std::string ops = R"("operations": [
      {"type": "drill", "tool": 1, "retractPlane": 2, "endDepth": 1.5, "plungingFeedrate": 80, "holes": [[10, 10], [50, 10]]},
      {"type": "drill", "tool": 2, "retractPlane": 5, "endDepth": 8, "drillTip": true, "plungingFeedrate": 120, "holes": [[10, 10], [50, 10]]}]})";
    const std::string by_name = R"({"name": "p", "clearance": 10, "tools": [
      {"number": 1, "library": "spot"}, {"number": 2, "library": "jobber-6"}], )" + ops;
    const std::string written = R"({"name": "p", "clearance": 10, "tools": [
      {"number": 1, "type": "spot-drill", "diameter": 10, "tipAngle": 90, "rpm": 1500, "comment": "spot drill 90 deg"},
      {"number": 2, "type": "drill", "diameter": 6, "tipAngle": 118, "rpm": 1200, "comment": "HSS jobber", "fluteLength": 57}], )" + ops;
    for (const char* machine : {"wabeco", "fanuc", "linuxcnc", "heidenhain"}) {
        CAPTURE(machine);
        const Run a = run({"-", "--machine", machine, "--tools", tools}, by_name);
        const Run b = run({"-", "--machine", machine}, written);
        REQUIRE_MESSAGE(a.code == 0, a.err);
        REQUIRE_MESSAGE(b.code == 0, b.err);
        CHECK(a.out == b.out);
        CHECK(a.out.find("HSS jobber") != std::string::npos);
    }
}

TEST_CASE("the sample library job posts the program of the job with the computed values written out") {
    // Written out by hand from the cutting data (samples/library/tools.json, aluminium):
    //   T5 20 mm, vc 250: 250000 / (pi 20) = 3978.87 -> 3978 rpm; the face's stepover 6 < 10:
    //      fz 0.05 x 20 / (2 sqrt(6 x 14)) = 0.054554 x 4 flutes x 3978 = 868.07 -> 868 mm/min
    //   T1 10 mm spot, vc 50: 1591.55 -> 1591 rpm; 0.05 mm/rev x 1591 = 79.55 -> 79 mm/min
    //   T2 6 mm drill, vc 40: 2122.07 -> 2122 rpm; 0.12 mm/rev x 2122 = 254.64 -> 254 mm/min
    //   T3 6 mm end mill, rpm 6000 given: 0.03 x 3 x 6000 = 540 mm/min (a contour: no thinning)
    nlohmann::ordered_json job = nlohmann::ordered_json::parse(read_file(sample_job));
    job["tools"] = nlohmann::ordered_json::parse(R"([
      {"number": 5, "type": "end-mill", "diameter": 20, "flutes": 4, "fluteLength": 38, "rpm": 3978,
       "comment": "20 mm face mill - library 20mm-carbide-4f: 3978 rpm from vc 250 m/min for aluminium computed"},
      {"number": 1, "type": "spot-drill", "diameter": 10, "tipAngle": 90, "flutes": 2, "rpm": 1591,
       "comment": "spot drill 90 deg - library 10mm-spot-90: 1591 rpm from vc 50 m/min for aluminium computed"},
      {"number": 2, "type": "drill", "diameter": 6, "tipAngle": 118, "flutes": 2, "fluteLength": 57, "rpm": 2122,
       "comment": "HSS jobber, new - library 6mm-hss-jobber: 2122 rpm from vc 40 m/min for aluminium computed"},
      {"number": 3, "type": "end-mill", "diameter": 6, "flutes": 3, "fluteLength": 18, "rpm": 6000, "comment": "6 mm end mill"}])");
    job["operations"][0]["feed"] = 868;
    job["operations"][1]["plungingFeedrate"] = 79;
    job["operations"][2]["plungingFeedrate"] = 254;
    job["operations"][3]["feed"] = 540;
    job.erase("material");
    for (const char* machine : {"wabeco", "fanuc", "linuxcnc"}) {
        CAPTURE(machine);
        const Run a = run({sample_job, "--machine", machine, "--tools", sample_tools});
        const Run b = run({"-", "--machine", machine}, job.dump(2));
        REQUIRE_MESSAGE(a.code == 0, a.err);
        REQUIRE_MESSAGE(b.code == 0, b.err);
        CHECK(a.out == b.out);
        // What camgen computed is said on standard error.
        CHECK(a.err.find("T5 (library tool \"20mm-carbide-4f\"): 3978 rpm from vc 250 m/min for aluminium computed") !=
              std::string::npos);
        CHECK(a.err.find("feed 868 mm/min computed for T5 (library tool \"20mm-carbide-4f\", aluminium: fz 0.05 mm raised "
                         "to 0.0546 mm for the chip thinning of a 6 mm stepover, x 4 flutes x 3978 rpm)") != std::string::npos);
        CHECK(a.err.find("feed 540 mm/min computed for T3") != std::string::npos);
        CHECK(b.err.find("computed") == std::string::npos);
    }
}

TEST_CASE("rpm and feeds computed from cutting data equal the hand calculation") {
    ToolLibraryOptions options;
    options.file = sample_tools;
    const Job job = read_job(read_file(sample_job), sample_job, JobLimits{}, options);
    CHECK(job.material == "aluminium");
    CHECK(job.tools.at(5).rpm == 3978);  // floor(250 x 1000 / (pi x 20)) = floor(3978.87)
    CHECK(job.tools.at(1).rpm == 1591);  // floor(50 x 1000 / (pi x 10))
    CHECK(job.tools.at(2).rpm == 2122);  // floor(40 x 1000 / (pi x 6))
    CHECK(job.tools.at(3).rpm == 6000);  // the job's own
    CHECK(job.tools.at(3).computed.empty());
    CHECK(job.tools.at(2).comment == "HSS jobber, new");  // the job's key over the library's
    CHECK(job.tools.at(2).flute_length == 57);
    CHECK(job.tools.at(5).flutes == 4);
    // Face: 0.05 x 20 / (2 sqrt(6 x 14)) x 4 x 3978 = 868.07; plungeFeed given.
    CHECK(op_at<FaceOp>(job, 0).feeds.cutting == 868);
    CHECK(op_at<FaceOp>(job, 0).feeds.plunge == 300);
    CHECK(op_at<FaceOp>(job, 0).feeds.finishing == 868);
    CHECK(op_at<DrillOp>(job, 1).params.values.get(DrillField::plunging_feedrate) == 79);   // 0.05 x 1591
    CHECK(op_at<DrillOp>(job, 2).params.values.get(DrillField::plunging_feedrate) == 254);  // 0.12 x 2122
    CHECK(op_at<ContourOp>(job, 3).feeds.cutting == 540);  // 0.03 x 3 x 6000

    // The formulas themselves.
    CHECK(rpm_for_surface_speed(250, 20) == 3978);
    CHECK(rpm_for_surface_speed(1, 1000) == 1);  // at least 1
    CHECK(thinned_feed_per_tooth(0.05, 20, 6) == doctest::Approx(0.05 * 20 / (2 * std::sqrt(84.0))).epsilon(1e-12));
    CHECK(thinned_feed_per_tooth(0.05, 20, 2) == doctest::Approx(0.0833333333).epsilon(1e-9));  // 1 / (2 sqrt 36) ... x 0.05 x 20
    CHECK(thinned_feed_per_tooth(0.05, 20, 10) == 0.05);  // half the diameter: no thinning
    CHECK(thinned_feed_per_tooth(0.05, 20, 15) == 0.05);
    CHECK(thinned_feed_per_tooth(0.05, 20, 0) == 0.05);  // not known
}

TEST_CASE("speeds and feeds computed from a library are bounded by the machine's limits, with a note") {
    ToolLibraryOptions options;
    options.file = sample_tools;
    options.max_rpm = 2000;
    options.max_feed = 400;
    options.machine = "slow";
    const Job job = read_job(read_file(sample_job), sample_job, JobLimits{}, options);
    CHECK(job.tools.at(5).rpm == 2000);  // 3978 wanted
    REQUIRE(job.tools.at(5).computed.size() == 1);
    CHECK(job.tools.at(5).computed[0] == "2000 rpm, the limit of machine slow (vc 250 m/min for aluminium wants 3978 rpm)");
    CHECK(job.tools.at(2).rpm == 2000);  // 2122 wanted
    CHECK(job.tools.at(1).rpm == 1591);  // within
    // The feed from the clamped speed: 0.054554 x 4 x 2000 = 436.4, above maxFeed 400.
    const FaceOp& face = op_at<FaceOp>(job, 0);
    CHECK(face.feeds.cutting == 400);
    bool noted = false;
    for (const std::string& n : face.notes) noted = noted || n.find("feed 436 mm/min computed for T5") == 0;
    CHECK(noted);
    CHECK(op_at<ContourOp>(job, 3).feeds.cutting == 400);  // 540 from the job's 6000 rpm
    // On a real machine: wabeco's limits through the command line.
    const Run r = run({sample_job, "--machine", "wabeco", "--tools", sample_tools});
    CHECK_MESSAGE(r.code == 0, r.err);
}

TEST_CASE("--events shows the computed values: the tool change's description and the operation's notes") {
    const Run r = run({sample_job, "--events", "--tools", sample_tools});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    bool tool_change = false, notes = false;
    for (const std::string& line : lines_of(r.out)) {
        const auto e = nlohmann::json::parse(line);
        if (e["event"] == "tool-change" && e["tool"] == 5) {
            CHECK(e["description"] == "20 mm end mill - 20 mm face mill - library 20mm-carbide-4f: 3978 rpm from vc 250 "
                                      "m/min for aluminium computed");
            tool_change = true;
        }
        if (e["event"] == "operation-start" && e["path"] == "/operations/0") {
            REQUIRE(e.contains("notes"));
            CHECK(e["notes"][0] == "T5 (library tool \"20mm-carbide-4f\"): 3978 rpm from vc 250 m/min for aluminium computed");
            CHECK(e["notes"][1].get<std::string>().starts_with("feed 868 mm/min computed for T5"));
            notes = true;
        }
        if (e["event"] == "spindle" && e["state"] == "cw") CHECK(e["rpm"].get<double>() >= 1591);
    }
    CHECK(tool_change);
    CHECK(notes);
}

TEST_CASE("a library is found in CAMGEN_TOOLS (a file or a folder) and in $XDG_CONFIG_HOME/camgen/tools") {
    const fs::path root = scratch("toollib-search");
    const std::string job = R"({"clearance": 10, "tools": [{"number": 1, "library": "jobber-6"}],
      "operations": [{"type": "drill", "tool": 1, "retractPlane": 5, "endDepth": 8, "plungingFeedrate": 120, "holes": [[0, 0]]}]})";
    {
        // XDG: the folder's *.json.
        write_to(root / "xdg" / "camgen" / "tools", "shop.json", plain_library);
        ToolEnvGuard xdg("XDG_CONFIG_HOME", (root / "xdg").string());
        ToolEnvGuard env("CAMGEN_TOOLS", std::nullopt);
        const Run r = run({"-", "--machine", "fanuc"}, job);
        CHECK_MESSAGE(r.code == 0, r.err);
        CHECK(r.out.find("S1200") != std::string::npos);
        // CAMGEN_TOOLS before it: a file whose jobber-6 runs at 900 rpm.
        const std::string file = write_to(root / "env", "mine.json",
                                          R"({"tools": [{"name": "jobber-6", "type": "drill", "diameter": 6, "rpm": 900}]})");
        ToolEnvGuard env2("CAMGEN_TOOLS", file);
        const Run r2 = run({"-", "--machine", "fanuc"}, job);
        CHECK_MESSAGE(r2.code == 0, r2.err);
        CHECK(r2.out.find("S900") != std::string::npos);
        // A folder in CAMGEN_TOOLS.
        ToolEnvGuard env3("CAMGEN_TOOLS", (root / "env").string());
        CHECK(run({"-", "--machine", "fanuc"}, job).out.find("S900") != std::string::npos);
        // --tools alone: the search is not made.
        const std::string other = write_to(root / "other", "t.json",
                                           R"({"tools": [{"name": "jobber-6", "type": "drill", "diameter": 6, "rpm": 700}]})");
        CHECK(run({"-", "--machine", "fanuc", "--tools", other}, job).out.find("S700") != std::string::npos);
    }
    {
        // Found nowhere: the message says where camgen looked.
        ToolEnvGuard xdg("XDG_CONFIG_HOME", (root / "empty").string());
        ToolEnvGuard env("CAMGEN_TOOLS", std::nullopt);
        const Run r = run({"-", "--machine", "fanuc"}, job);
        CHECK(r.code == 1);
        CHECK(r.err == fmt::format("camgen: <stdin>:1: /tools/0/library: no tool library found for tool \"jobber-6\": looked "
                                   "in {}/empty/camgen/tools (give one with --tools, or set CAMGEN_TOOLS)\n",
                                   root.string()));
        CHECK(r.out.empty());
    }
    // A --tools that does not exist.
    const Run r = run({"-", "--machine", "fanuc", "--tools", (root / "nope.json").string()}, job);
    CHECK(r.code == 1);
    CHECK(r.err.find("cannot read the tool library " + (root / "nope.json").string() + " (--tools)") != std::string::npos);
}

TEST_CASE("errors of library tools and of library files name the file, the JSON path and the line") {
    const fs::path dir = scratch("toollib-errors");
    const std::string job = R"({"clearance": 10, "material": "aluminum",
  "tools": [{"number": 1, "library": "jobber6"}],
  "operations": []})";
    const std::string tools = write_to(dir, "tools.json", read_file(sample_tools));
    // An unknown name: the close one and the library's names.
    Run r = run({"-", "--machine", "fanuc", "--tools", tools}, job);
    CHECK(r.code == 1);
    CHECK(r.err.find("camgen: <stdin>:2: /tools/0/library: no tool \"jobber6\" in the tool library") == 0);
    CHECK(r.err.find("its tools: 20mm-carbide-4f, 6mm-carbide-3f, 10mm-spot-90, 6mm-hss-jobber, 8mm-tap-m8") != std::string::npos);
    // A material the tool has no data for: the close one.
    std::string j2 = job;
    j2.replace(j2.find("jobber6"), 7, "6mm-hss-jobber");
    r = run({"-", "--machine", "fanuc", "--tools", tools}, j2);
    CHECK(r.code == 1);
    CHECK(r.err == fmt::format("camgen: <stdin>:2: /tools/0/library: library tool \"6mm-hss-jobber\" ({} /tools/3) has no "
                               "cutting data for material \"aluminum\" (did you mean \"aluminium\"?); it has aluminium, "
                               "steel\n",
                               tools));
    // No material: said, with the materials it has.
    std::string j3 = j2;
    j3.replace(j3.find(R"("material": "aluminum",)"), 23, "");
    r = run({"-", "--machine", "fanuc", "--tools", tools}, j3);
    CHECK(r.code == 1);
    CHECK(r.err.find("has cutting data for aluminium, steel: give the job's material") != std::string::npos);
    // Material in any case.
    std::string j4 = j2;
    j4.replace(j4.find("aluminum"), 8, "Aluminium");
    CHECK(run({"-", "--events", "--tools", tools}, j4).code == 0);

    // Bad library files.
    const std::string good_job = R"({"clearance": 10, "tools": [{"number": 1, "library": "a"}], "operations": []})";
    const auto error_of = [&](const std::string& text) {
        const std::string file = write_to(dir, "bad.json", text);
        const Run bad = run({"-", "--machine", "fanuc", "--tools", file}, good_job);
        CHECK(bad.code == 1);
        CHECK(bad.out.empty());
        return bad.err;
    };
    const std::string bad = (dir / "bad.json").string();
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\", \"diameter\": 6,,}]}") ==
          "camgen: " + bad + ":2: line 2, column 29: syntax error while parsing object key - unexpected ','; expected string literal\n");
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\",\n \"diameter\": 6, \"rpm\": 100, \"fluteLenght\": 3}]}") ==
          "camgen: " + bad + ":3: /tools/0/fluteLenght: unknown key \"fluteLenght\" (did you mean \"fluteLength\"?)\n");
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\",\n \"diameter\": \"6\", \"rpm\": 100}]}") ==
          "camgen: " + bad + ":3: /tools/0/diameter: expected a number, got a string \"6\"\n");
    CHECK(error_of("{\"tools\": [\n{\"type\": \"drill\",\n \"diameter\": 6, \"rpm\": 100}]}") ==
          "camgen: " + bad + ":2: /tools/0/name: required key \"name\" is missing\n");
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\", \"libraryNumber\": 3,\n \"diameter\": 6, \"rpm\": 100}]}") ==
          "camgen: " + bad + ":2: /tools/0/libraryNumber: libraryNumber is a key of a job's tool, not of a library tool\n");
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\", \"number\": 3, \"diameter\": 6, \"rpm\": 100},\n{\"name\": \"b\", \"number\": 3, "
                   "\"diameter\": 8, \"rpm\": 100}]}") ==
          "camgen: " + bad + ":3: /tools/1/number: tool number 3 is already used by /tools/0\n");
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\", \"number\": 0, \"diameter\": 6, \"rpm\": 100}]}").find(
              "/tools/0/number: ") != std::string::npos);
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\", \"diameter\": 6, \"rpm\": 100},\n{\"name\": \"a\", \"diameter\": 8, \"rpm\": 100}]}") ==
          "camgen: " + bad + ":3: /tools/1/name: tool name \"a\" is already used by /tools/0\n");
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\", \"diameter\": 6,\n \"cuttingData\": [{\"material\": \"steel\", \"surfaceSpeed\": 80,\n "
                   "\"feedPerTooth\": 0.02}]}]}") ==
          "camgen: " + bad + ":4: /tools/0/cuttingData/0/feedPerTooth: a feedPerTooth needs the tool's flutes (the feed is fz "
                             "x flutes x rpm)\n");
    CHECK(error_of("{\"tools\": [\n{\"name\": \"a\", \"diameter\": 6}]}") ==
          "camgen: <stdin>:1: /tools/0/library: library tool \"a\" (" + bad +
              " /tools/0) gives no rpm and no cutting data: give this tool's rpm\n");
    // A library that is not JSON.
    CHECK(error_of("G0 X0 Y0\nM30\n").find(bad) != std::string::npos);
}

TEST_CASE("a library tool's keys are overridden by the job's, and a feed given in the job is kept") {
    const std::string job = R"({"clearance": 10, "material": "steel", "tools": [
      {"number": 3, "library": "6mm-carbide-3f", "flutes": 2, "coolant": "mist"}],
      "operations": [{"type": "contour", "tool": 3, "referencePlane": 0, "retractPlane": 5, "endDepth": 1, "side": "on",
        "start": [0, 0], "path": [{"line": [50, 0]}], "feed": 250}]})";
    ToolLibraryOptions options;
    options.file = sample_tools;
    const Job j = read_job(job, "job.json", JobLimits{}, options);
    const Tool& t = j.tools.at(3);
    CHECK(t.flutes == 2);
    CHECK(t.coolant == CoolantMode::mist);
    CHECK(t.diameter == 6);
    CHECK(t.rpm == 3183);  // floor(60 x 1000 / (pi x 6)) = floor(3183.1)
    CHECK(op_at<ContourOp>(j, 0).feeds.cutting == 250);  // given
    // Without a feed: 0.02 x 2 flutes x 3183 = 127.32 -> 127.
    std::string no_feed = job;
    no_feed.replace(no_feed.find(R"(, "feed": 250)"), 13, "");
    CHECK(op_at<ContourOp>(read_job(no_feed, "job.json", JobLimits{}, options), 0).feeds.cutting == 127);
    // A job without library tools still needs its feed, as before.
    const std::string plain = R"({"clearance": 10, "tools": [{"number": 3, "type": "end-mill", "diameter": 6, "rpm": 5000}],
      "operations": [{"type": "contour", "tool": 3, "referencePlane": 0, "retractPlane": 5, "endDepth": 1, "side": "on",
        "start": [0, 0], "path": [{"line": [50, 0]}]}]})";
    CHECK_THROWS_WITH_AS(read_job(plain, "job.json"), doctest::Contains("/operations/0/feed: required key \"feed\" is missing"),
                         InputError);
}

TEST_CASE("an inch library gives its lengths in inch and its surface speed in ft/min") {
    const std::string tools = write_to(scratch("toollib-inch"), "inch.json", R"({"units": "inch", "tools": [
      {"name": "half-inch", "type": "end-mill", "diameter": 0.5, "flutes": 2,
       "cuttingData": [{"material": "brass", "surfaceSpeed": 300, "feedPerTooth": 0.002}]}]})");
    const std::string job = R"({"clearance": 10, "material": "brass", "tools": [{"number": 1, "library": "half-inch"}],
      "operations": [{"type": "contour", "tool": 1, "referencePlane": 0, "retractPlane": 5, "endDepth": 1, "side": "on",
        "start": [0, 0], "path": [{"line": [50, 0]}]}]})";
    ToolLibraryOptions options;
    options.file = tools;
    const Job j = read_job(job, "job.json", JobLimits{}, options);
    CHECK(j.tools.at(1).diameter == doctest::Approx(12.7));
    // 300 SFM on 0.5 in: 12 x 300 / (pi x 0.5) = 2291.8 -> 2291 rpm; 0.002 in x 2 x 2291 = 9.164 in/min = 232.77 mm/min.
    CHECK(j.tools.at(1).rpm == 2291);
    CHECK(op_at<ContourOp>(j, 0).feeds.cutting == 232);
}

TEST_CASE("a program from library tools reads back as its job on every mill, the spindle speed kept in nccad's long tool message") {
    const fs::path dir = scratch("toollib-verify");
    for (const char* machine : {"wabeco", "kosy", "fanuc", "linuxcnc", "grbl", "sinumerik", "heidenhain"}) {
        CAPTURE(machine);
        const std::string program = (dir / (std::string(machine) + ".nc")).string();
        const Run post = run({sample_job, "--machine", machine, "--tools", sample_tools, "-q", "-o", program});
        REQUIRE_MESSAGE(post.code == 0, post.err);
        const Run v = run({"verify", program, "--machine", machine, "--job", sample_job, "--tools", sample_tools});
        CHECK_MESSAGE(v.code == 0, v.err);
        CHECK(v.out.find("matches job") != std::string::npos);
    }
    // nccad: the description is cut before the spindle speed, never the speed.
    const std::string text = read_file((dir / "wabeco.nc").string());
    CHECK(text.find(", spindle 3978 rpm\n") != std::string::npos);
}

TEST_CASE("the output never replaces the tool library") {
    const fs::path dir = scratch("toollib-output");
    const std::string tools = write_to(dir, "tools.json", read_file(sample_tools));
    const Run r = run({sample_job, "--machine", "fanuc", "--tools", tools, "-o", tools});
    CHECK(r.code == 2);
    CHECK(r.err.find("would replace the tool library " + tools) != std::string::npos);
    CHECK(read_file(tools) == read_file(sample_tools));
}

TEST_CASE("a job's tool takes a library tool by its library number as by its name") {
    const fs::path dir = scratch("toollib-number");
    const std::string tools = write_to(dir, "tools.json", R"({"tools": [
  {"name": "spot", "number": 12, "type": "spot-drill", "diameter": 10, "tipAngle": 90, "rpm": 1500},
  {"name": "jobber-6", "number": 31, "type": "drill", "diameter": 6, "tipAngle": 118, "rpm": 1200, "fluteLength": 57}
]})");
    // A second file of the folder: its tool numbered 12 too keeps its name, not the number.
    write_to(dir, "zz-more.json", R"({"tools": [{"name": "other", "number": 12, "diameter": 3, "rpm": 3000}]})");
    const std::string ops = R"("operations": [
      {"type": "drill", "tool": 7, "retractPlane": 2, "endDepth": 1, "plungingFeedrate": 80, "holes": [[10, 10]]},
      {"type": "drill", "tool": 2, "retractPlane": 2, "endDepth": 5, "plungingFeedrate": 120, "holes": [[10, 10]]}]})";
    const std::string by_number = R"({"clearance": 10, "tools": [{"number": 7, "libraryNumber": 12},
      {"number": 2, "libraryNumber": 31, "comment": "HSS"}], )" + ops;
    const std::string by_name = R"({"clearance": 10, "tools": [{"number": 7, "library": "spot"},
      {"number": 2, "library": "jobber-6", "comment": "HSS"}], )" + ops;
    const std::string written = R"({"clearance": 10, "tools": [
      {"number": 7, "type": "spot-drill", "diameter": 10, "tipAngle": 90, "rpm": 1500},
      {"number": 2, "type": "drill", "diameter": 6, "tipAngle": 118, "rpm": 1200, "fluteLength": 57, "comment": "HSS"}], )" + ops;
    const Run a = run({"-", "--machine", "linuxcnc", "--tools", dir.string()}, by_number);
    REQUIRE_MESSAGE(a.code == 0, a.err);
    const Run b = run({"-", "--machine", "linuxcnc", "--tools", dir.string()}, by_name);
    const Run c = run({"-", "--machine", "linuxcnc"}, written);
    REQUIRE_MESSAGE(b.code == 0, b.err);
    REQUIRE_MESSAGE(c.code == 0, c.err);
    CHECK(a.out == b.out);
    CHECK(a.out == c.out);
    CHECK(a.out.find("T7 M6") != std::string::npos);
    // Errors: an unknown number lists the numbered tools; both keys refused; a number below 1.
    Run bad = run({"-", "--machine", "linuxcnc", "--tools", dir.string()},
                  R"({"clearance": 10, "tools": [{"number": 7,
  "libraryNumber": 13}], "operations": []})");
    CHECK(bad.code == 1);
    CHECK(bad.out.empty());
    CHECK(bad.err.find("camgen: <stdin>:2: /tools/0/libraryNumber: no tool number 13 in the tool library") == 0);
    CHECK(bad.err.find("its numbered tools: 12 (spot), 31 (jobber-6)") != std::string::npos);
    bad = run({"-", "--machine", "linuxcnc", "--tools", dir.string()},
              R"({"clearance": 10, "tools": [{"number": 7, "library": "spot", "libraryNumber": 12}], "operations": []})");
    CHECK(bad.code == 1);
    CHECK(bad.err.find("/tools/0") != std::string::npos);
    CHECK(bad.err.find("not both") != std::string::npos);
    bad = run({"-", "--machine", "linuxcnc", "--tools", dir.string()},
              R"({"clearance": 10, "tools": [{"number": 7, "libraryNumber": 0}], "operations": []})");
    CHECK(bad.code == 1);
    CHECK(bad.err.find("/tools/0/libraryNumber") != std::string::npos);
}

TEST_CASE("path, bore-mill and thread-mill feeds are computed from the library, the circles' for the tool centre") {
    const fs::path dir = scratch("toollib-feeds");
    const std::string tools = write_to(dir, "tools.json", R"({"tools": [
  {"name": "em6", "type": "end-mill", "diameter": 6, "flutes": 3, "centreCutting": true,
   "cuttingData": [{"material": "aluminium", "surfaceSpeed": 120, "feedPerTooth": 0.03}]},
  {"name": "tm7", "type": "thread-mill", "diameter": 7, "minPitch": 0.75, "maxPitch": 2, "flutes": 3,
   "cuttingData": [{"material": "aluminium", "surfaceSpeed": 110, "feedPerTooth": 0.045}]}
]})");
    const std::string job = R"({"clearance": 10, "material": "aluminium",
  "tools": [{"number": 1, "library": "em6"}, {"number": 2, "library": "tm7"}],
  "operations": [
    {"type": "path", "tool": 1, "z": -1, "start": [0, 0], "path": [{"line": [30, 0]}]},
    {"type": "bore-mill", "tool": 1, "diameter": 20, "retractPlane": 5, "endDepth": 6, "pitch": 1, "holes": [[50, 50]]},
    {"type": "thread-mill", "tool": 2, "thread": "M10", "retractPlane": 5, "endDepth": 6, "holes": [[80, 50]]}
  ]})";
    ToolLibraryOptions options;
    options.file = tools;
    const Job j = read_job(job, "feeds.json", JobLimits{}, options);
    CHECK(j.tools.at(1).rpm == 6366);  // floor(120 x 1000 / (pi x 6))
    CHECK(j.tools.at(2).rpm == 5002);  // floor(110 x 1000 / (pi x 7))
    // Path: floor(0.03 x 3 x 6366) = floor(572.94).
    CHECK(op_at<PathOp>(j, 0).feed == 572);
    // Bore 20 with a 6 mm tool: the centre at radius 7 of the wall's 10: floor(572 x 0.7) = 400.
    const BoreMillOp& bore = op_at<BoreMillOp>(j, 1);
    CHECK(bore.feed == 400);
    CHECK(bore.ramp_feed == 400);
    bool noted = false;
    for (const std::string& n : bore.notes) noted = noted || n.find("the tool centre's feed is 400 mm/min: the computed 572 mm/min") == 0;
    CHECK(noted);
    // M10 internal with a 7 mm thread mill: edge floor(0.045 x 3 x 5002) = floor(675.27) = 675 at the major
    // radius 5; the centre at 5 - 3.5 = 1.5: floor(675 x 0.3) = floor(202.5) = 202.
    const ThreadMillOp& thread = op_at<ThreadMillOp>(j, 2);
    CHECK(thread.feed == 202);
    noted = false;
    for (const std::string& n : thread.notes) noted = noted || n.find("the tool centre's feed is 202 mm/min: the computed 675") == 0;
    CHECK(noted);
    // The program writes them.
    const Run r = run({"-", "--machine", "linuxcnc", "--tools", tools}, job);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK(r.out.find("F572") != std::string::npos);
    CHECK(r.out.find("F400") != std::string::npos);
    CHECK(r.out.find("F202") != std::string::npos);
    // Without cutting data for the material the feed is still required, at its path.
    std::string steel = job;
    steel.replace(steel.find("\"aluminium\""), 11, "\"steel\"");
    const Run bad = run({"-", "--machine", "linuxcnc", "--tools", tools}, steel);
    CHECK(bad.code == 1);
    CHECK(bad.err.find("/tools/0/library") != std::string::npos);
    const std::string plain = R"({"clearance": 10, "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 1000}],
  "operations": [{"type": "path", "tool": 1, "z": -1, "start": [0, 0], "path": [{"line": [30, 0]}]}]})";
    const Run missing = run({"-", "--machine", "linuxcnc"}, plain);
    CHECK(missing.code == 1);
    CHECK(missing.err.find("/operations/0/feed: required key \"feed\" is missing") != std::string::npos);
}

TEST_CASE("a library turning tool's surface speed is a constant surface speed (G96), not an rpm of its own diameter") {
    const fs::path dir = scratch("toollib-turning");
    const std::string tools = write_to(dir, "tools.json", R"({"tools": [
  {"name": "cnmg", "type": "turning-tool", "diameter": 12,
   "cuttingData": [{"material": "steel", "surfaceSpeed": 200, "feedPerRev": 0.2}]}]})");
    const std::string job = R"({"clearance": 10, "material": "steel", "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 1}},
  "tools": [{"number": 1, "library": "cnmg"}],
  "operations": [{"type": "turn-face", "tool": 1, "z": 0, "stepdown": 1, "feedMode": "per-revolution", "feed": 0.2}]})";
    const Run r = run({"-", "--machine", "fanuc-lathe", "--tools", tools}, job);
    CHECK(r.code == 0);
    // Within the machine's limit, 3000 rpm.
    CHECK(r.out.find(" G50 S3000\n") != std::string::npos);
    CHECK(r.out.find(" G96 S200 M3\n") != std::string::npos);
    CHECK(r.err.find("constant surface speed 200 m/min for steel (G96), at most 3000 rpm computed") != std::string::npos);
    // With the job's rpm it is used.
    std::string with_rpm = job;
    with_rpm.replace(with_rpm.find("\"library\": \"cnmg\""), 17, "\"library\": \"cnmg\", \"rpm\": 900");
    const Run at_rpm = run({"-", "--machine", "fanuc-lathe", "--tools", tools}, with_rpm);
    CHECK(at_rpm.code == 0);
    CHECK(at_rpm.out.find(" G97 S900 M3\n") != std::string::npos);
}
