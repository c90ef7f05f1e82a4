// Custom blocks: the control's own lines, written only where the machine's reader reads them
// back as comments and dwells that leave the program's state as it was; refused otherwise,
// naming the line and what it would do.
#include <doctest/doctest.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include <fmt/format.h>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_custom_block {

using namespace camgen;
using namespace camgen::test;

namespace {

// A job that drills one hole, runs the custom block `text` (a JSON object) and drills another.
std::string custom_job(const std::string& text, const std::string& work_offset = "") {
    return R"({"name": "t", "units": "mm", "clearance": 20, )" +
           (work_offset.empty() ? std::string() : R"("workOffset": ")" + work_offset + R"(", )") + R"("tools": [
  {"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}],
"operations": [
  {"type": "drill", "tool": 1, "retractPlane": 5, "endDepth": 5, "plungingFeedrate": 100, "holes": [[10, 10]]},
  {"type": "custom", "comment": "mine", "text": )" +
           text + R"(},
  {"type": "drill", "tool": 1, "retractPlane": 5, "endDepth": 5, "plungingFeedrate": 100, "holes": [[30, 10]]}]})";
}

// The message of posting the job for the machine, or "" when it posts.
std::string refusal(const std::string& job, const std::string& machine) {
    try {
        (void)post_job(job, machine);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::optional<Mismatch> verify(const std::string& job_json, const std::string& machine_name) {
    const Machine machine = load_machine(machine_name);
    const Job job = read_job(job_json, "t.json");
    const std::string text = post_program(job, machine);
    return compare_traces(trace_expected(expand_job(job), machine, job.work_offset), trace_program(read_program(text, machine), machine),
                          compare_tolerance(machine));
}

}  // namespace

TEST_CASE("custom: comments and dwells are written as they are, where the machine's reader reads them back") {
    const std::string job = custom_job(R"~({"linuxcnc": ["(MSG, blow the chips off)", "G4 P1.5"], "fanuc": "G4 P1500",
        "iso": "(nothing to do here)", "nccad": ["; chips", "M30 P18"], "sinumerik": ["G4 F1.5"],
        "heidenhain": ["CYCL DEF 9.0 DWELL TIME", "CYCL DEF 9.1 DWELL 1.5"]})~");
    struct Expect {
        const char* machine;
        const char* text;
    } const expected[] = {
        {"linuxcnc", "(mine)\n(MSG, blow the chips off)\nG4 P1.5\n(drill 1 hole)\n"},
        // The machine's name comes before its dialect's; a block gets its sequence number.
        {"fanuc", "(mine)\nN55 G4 P1500\n(drill 1 hole)\n"},
        {"grbl", "(mine)\n(nothing to do here)\n(drill 1 hole)\n"},
        {"wabeco", "; mine\n; chips\nM30 P18\n; drill 1 hole\n"},
        {"sinumerik", "; mine\nN130 G4 F1.5\n; drill 1 hole\n"},
        {"heidenhain", "; mine\n12 CYCL DEF 9.0 DWELL TIME\n13 CYCL DEF 9.1 DWELL 1.5\n14 ; drill 1 hole\n"},
    };
    for (const Expect& e : expected) {
        INFO(e.machine);
        const std::string text = post_job(job, e.machine).text;
        CAPTURE(text);
        CHECK(text.find(e.text) != std::string::npos);
        CHECK_FALSE(verify(job, e.machine));
    }
    // The dwell is in the job's expected motion: a program that dwells otherwise does not match.
    const Machine machine = load_machine("linuxcnc");
    const Job j = read_job(job, "t.json");
    std::string text = post_program(j, machine);
    text.replace(text.find("G4 P1.5\n"), 8, "G4 P2.5\n");
    const auto m = compare_traces(trace_expected(expand_job(j), machine), trace_program(read_program(text, machine), machine),
                                  compare_tolerance(machine));
    REQUIRE(m);
    CAPTURE(m->message);
    CHECK(m->message == "the program has a dwell of 2.500 s, the job a dwell of 1.500 s");
}

TEST_CASE("custom: \"\" writes nothing; a machine with no text (nor its dialect) is refused, naming the texts there are") {
    const std::string job = custom_job(R"({"linuxcnc": "", "fanuc": [], "sinumerik": "G4 F1"})");
    CHECK(post_job(job, "linuxcnc").text.find("(mine)\n(drill 1 hole)\n") != std::string::npos);
    CHECK(post_job(job, "fanuc").text.find("(mine)\n(drill 1 hole)\n") != std::string::npos);
    CHECK(refusal(job, "grbl") == "/operations/1/text: the custom block has no text for machine grbl or its dialect iso (it "
                                  "has text for: fanuc, linuxcnc, sinumerik); give one, or \"\" to write nothing there");
    // A name a letter off the machine's or its dialect's is named.
    CHECK(refusal(custom_job(R"({"isso": "G4 P1"})"), "grbl") ==
          "/operations/1/text: the custom block has no text for machine grbl or its dialect iso (it has text for: isso) "
          "(did you mean \"iso\" for \"isso\"?); give one, or \"\" to write nothing there");
}

TEST_CASE("custom: what the reader cannot read is refused with the line") {
    const std::string job = custom_job(R"~({"linuxcnc": ["(fine)", "G64 P0.01"]})~");
    CHECK(refusal(job, "linuxcnc") ==
          "/operations/1/text/linuxcnc: machine linuxcnc's reader cannot read custom line 2 \"G64 P0.01\": unknown code G64; "
          "camgen writes only what it can read back (camgen verify)");
    CHECK(refusal(custom_job(R"({"heidenhain": "FN 0: Q1 = 5"})"), "heidenhain")
              .find("machine heidenhain's reader cannot read custom line 1 \"FN 0: Q1 = 5\"") != std::string::npos);
    CHECK(refusal(custom_job(R"~({"sinumerik": "MSG(\"a\"b\")"})~"), "sinumerik")
              .find("the message is one string in double quotes") != std::string::npos);
}

TEST_CASE("custom: motion, tools, spindle, coolant, stops and the program end are refused, naming what they would do") {
    struct Case {
        const char* machine;
        const char* text;
        const char* says;
    } const cases[] = {
        {"linuxcnc", R"~(["(ok)", "G0 X50"])~", "custom line 2 \"G0 X50\" would move the tool (a rapid)"},
        {"linuxcnc", R"("G1 Z-30 F100")", "would move the tool (a feed move)"},
        {"linuxcnc", R"("G2 X20 Y10 I5 J0 F100")", "would move the tool (an arc)"},
        {"fanuc", R"("T2 M6")", "would change to tool 2"},
        {"linuxcnc", R"("M5")", "would stop the spindle"},
        {"linuxcnc", R"("S2000 M3")", "would start the spindle"},
        {"linuxcnc", R"("M8")", "would switch the coolant"},
        {"linuxcnc", R"("G41 D1")", "would switch cutter radius compensation"},
        {"linuxcnc", R"("M0")", "would stop the program with the spindle as it is (a stop operation stops the spindle"},
        {"linuxcnc", R"("G81 X40 Y40 Z-5 R2 F100")", "would drill"},
        {"wabeco", R"("M01 take a break")", "would stop the program"},
        {"wabeco", R"("G00 X40")", "would move the tool"},
        {"heidenhain", R"("L X+40 R0 FMAX")", "would move the tool (a rapid)"},
        {"heidenhain", R"("STOP")", "would stop the program"},
        {"sinumerik", R"("G0 X40.")", "would move the tool"},
    };
    for (const Case& c : cases) {
        INFO(c.machine << " " << c.text);
        const std::string msg = refusal(custom_job(fmt::format(R"({{"{}": {}}})", c.machine, c.text)), c.machine);
        CHECK(msg.find(c.says) != std::string::npos);
        CHECK(msg.find("a custom block may only comment and dwell") != std::string::npos);
    }
}

TEST_CASE("custom: a block that changes the state the program goes on with is refused, naming the change") {
    struct Case {
        const char* machine;
        const char* text;
        const char* says;
    } const cases[] = {
        {"linuxcnc", R"("G20")", "changes the units from mm to inch"},
        {"linuxcnc", R"("G55")", "changes the work offset from G54 to G55"},
        {"linuxcnc", R"("G43 H7")", "changes the tool length offset from G43 H1 to G43 H7"},
        {"linuxcnc", R"("G18")", "changes the plane from G17 to G18"},
        {"linuxcnc", R"("M2")", "changes the program end from not read to read"},
        {"fanuc", R"("M30")", "changes the program end from not read to read"},
        {"fanuc", R"("O1234")", "changes the program numbers from 1 to 2"},
        {"grbl", R"~("(Insert tool 2: a drill)")~", "changes the tool change announced from none to Insert tool 2"},
        {"sinumerik", R"~(["F100", "MCALL CYCLE81(5, 0, 2, -5)"])~", "changes the modal cycle call from none to CYCLE81"},
        {"sinumerik", R"("G700")", "changes the units from mm to inch"},
        {"heidenhain", R"("CYCL DEF 9.0 DWELL TIME")", "changes the cycle definition from none to CYCL DEF 9.0 (without its 9.1)"},
        {"heidenhain", R"("M30")", "changes the program end from not read to M30 read"},
        {"wabeco", R"("G99")", "changes the program end from not read to read"},
        {"wabeco", R"("G77")", "changes the axes whose position is known from XYZ to none"},
    };
    for (const Case& c : cases) {
        INFO(c.machine << " " << c.text);
        const std::string msg = refusal(custom_job(fmt::format(R"({{"{}": {}}})", c.machine, c.text),
                                                   std::string(c.machine) == "wabeco" || std::string(c.machine) == "heidenhain" ? "" : "G54"),
                                        c.machine);
        CAPTURE(msg);
        CHECK(msg.find(c.says) != std::string::npos);
    }
    // What restates the state is written (and the post writes its modal words again after it).
    const std::string restated = custom_job(R"({"linuxcnc": ["G17 G21 G90 G94", "G54", "G1"]})", "G54");
    const std::string text = post_job(restated, "linuxcnc").text;
    CAPTURE(text);
    CHECK(text.find("(mine)\nG17 G21 G90 G94\nG54\nG1\n(drill 1 hole)\nG0 X30 Y10 Z20\n") != std::string::npos);
    CHECK_FALSE(verify(restated, "linuxcnc"));
}

TEST_CASE("custom: lines a reader takes as the program's frame are refused") {
    CHECK(refusal(custom_job(R"({"wabeco": "_"})"), "wabeco")
              .find("custom line 1 \"_\" is a line of the program's frame for machine wabeco's reader, not a block") !=
          std::string::npos);
}

TEST_CASE("custom: the text is checked against the rules of comments and blocks when the job is read") {
    auto error = [](const std::string& text) {
        try {
            (void)read_job(custom_job(text), "t.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(error(R"("G4 P1")").find("/operations/1/text: text is an object") != std::string::npos);
    CHECK(error(R"({})").find("text names no machine or dialect") != std::string::npos);
    CHECK(error(R"({"iso": 5})").find("/operations/1/text/iso: the lines for iso are a string or an array of strings") !=
          std::string::npos);
    CHECK(error(R"({"iso": ["G4 P1", 5]})").find("/operations/1/text/iso/1: a line is a string") != std::string::npos);
    CHECK(error(R"({"iso": "G4 P1\nM30"})").find("a control character") != std::string::npos);
    CHECK(error(R"({"iso": "G4 P1 %"})").find("'%'") != std::string::npos);
    CHECK(error(R"~({"iso": "(Mass)\u00df"})~").find("outside ASCII") != std::string::npos);
    CHECK(error(R"({"iso": ["G4 P1", " "]})").find("/operations/1/text/iso/1: custom text: an empty line") != std::string::npos);
    CHECK(error(R"({"iso": ")" + std::string(201, 'x') + "\"}").find("a line of 201 characters, more than 200") != std::string::npos);
    CHECK(error(R"({"iso": ")" + std::string(200, 'x') + "\"}") == "no error");
    std::string many = "[";
    for (int i = 0; i < 1001; ++i) many += std::string(i ? "," : "") + "\"(x)\"";
    CHECK(error(R"({"iso": )" + many + "]}").find("1001 lines, more than 1000") != std::string::npos);
    CHECK(error(R"({"iso": "G4 P1"}, "tool": 1)").find("unknown key \"tool\"") != std::string::npos);
}

TEST_CASE("custom: the check reads the lines where they stand, with the spindle and tool of the program") {
    // With the spindle running, S changes its speed (a Spindle event); a dwell is fine.
    const std::string job = custom_job(R"({"linuxcnc": "S3000"})");
    CHECK(refusal(job, "linuxcnc").find("would start the spindle") != std::string::npos);
    // Before any tool, the spindle stands: S sets the speed the next start takes, which the
    // reader keeps, so it is refused as a change of state.
    const std::string first = R"({"name": "t", "units": "mm", "clearance": 20, "tools": [
  {"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}],
"operations": [{"type": "custom", "text": {"heidenhain": "TOOL CALL Z S500"}},
  {"type": "drill", "tool": 1, "retractPlane": 5, "endDepth": 5, "plungingFeedrate": 100, "holes": [[30, 10]]}]})";
    CHECK(refusal(first, "heidenhain").find("changes the spindle speed from 0 rpm to 500 rpm") != std::string::npos);
}

TEST_CASE("custom: the read-back finds the block's lines whatever the machine's comment length (found by machines/variants)") {
    // With commentMaxLength 12 comments are cut short: the check must not rely on comments to
    // find the block in the program it reads back.
    const std::string machine = file_with("short-comments", R"({"extends": "linuxcnc", "commentMaxLength": 12})");
    const std::string job = file_with("short", custom_job(R"~({"iso": ["(a long comment here)", "G4 P1"]})~"));
    const std::filesystem::path out = scratch("short-comments-out") / "p.ngc";
    Run r = run({job, "--machine", machine, "-o", out.string()});
    CHECK_MESSAGE(r.code == 0, r.err);
    CHECK(read_file(out.string()).find("(a long comment here)\nG4 P1\n") != std::string::npos);
    Run v = run({"verify", out.string(), "--machine", machine, "--job", job});
    CHECK_MESSAGE(v.code == 0, std::string(v.out + v.err));
    // A refusal still names the line.
    Run bad = run({file_with("short-bad", custom_job(R"~({"iso": ["(ok)", "G0 X1"]})~")), "--machine", machine});
    CHECK(bad.code == 1);
    CHECK(bad.err.find("custom line 2 \"G0 X1\" would move the tool (a rapid)") != std::string::npos);
}

}  // namespace test_custom_block
