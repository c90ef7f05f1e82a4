// Stops for the operator (the stop operation, "unsupported": "stop" on a drilling cycle the
// machine cannot make): what each machine writes, that the spindle and coolant are stopped
// before a stop and restored after it, that the program reads back to the same events (verify
// --job matches), and what is refused.
#include <algorithm>
#include <regex>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/post/safety.hpp"
#include "camgen/post/stops.hpp"
#include "camgen/reader/reader.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_stops {

using namespace camgen;
using namespace camgen::test;

namespace {

// A job on a 5 mm drill (tool 1, flood coolant where `coolant`), an 8 mm tap (tool 2) and
// the operations given.
std::string job_with(const std::string& operations, bool coolant = false) {
    return std::string(R"({"name": "t", "units": "mm", "clearance": 20, "tools": [
  {"number": 1, "type": "drill", "diameter": 5, "rpm": 1000)") +
           (coolant ? R"(, "coolant": "flood")" : "") + R"(},
  {"number": 2, "type": "tap", "diameter": 8, "rpm": 300, "comment": "M8 tap"}],
"operations": [)" + operations + "]}";
}

// A drill operation of tool 1 at `holes`.
std::string drill_at(const std::string& holes) {
    return R"({"type": "drill", "tool": 1, "retractPlane": 5, "endDepth": 5, "plungingFeedrate": 100, "holes": )" + holes +
           "}";
}

const std::string two_rows = drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "Check the hole"}, )" +
                             drill_at("[[30, 10]]");

// The index of the first line of `lines` at or after `from` that is `line`, else npos.
std::size_t find_line(const std::vector<std::string>& lines, const std::string& line, std::size_t from = 0) {
    for (std::size_t i = from; i < lines.size(); ++i)
        if (lines[i] == line) return i;
    return std::string::npos;
}

// The program for a machine, what its reader reads of it, and whether camgen verify matches it
// with its job.
struct Checked {
    std::string text;
    std::optional<Mismatch> mismatch;
    std::vector<ReadEvent> events;
};

Checked post_and_verify(const std::string& job_json, const std::string& machine_name) {
    const Machine machine = load_machine(machine_name);
    const Job job = read_job(job_json, "test.json");
    Checked c;
    c.text = post_program(job, machine);
    c.events = read_program(c.text, machine, "test.nc");
    c.mismatch = compare_traces(trace_expected(expand_job(job), machine), trace_program(c.events, machine),
                                compare_tolerance(machine));
    return c;
}

std::vector<Stop> stops_of(const std::vector<ReadEvent>& events) {
    std::vector<Stop> out;
    for (const ReadEvent& e : events)
        if (const auto* s = std::get_if<Stop>(&e.event)) out.push_back(*s);
    return out;
}

const char* const mills[] = {"fanuc", "linuxcnc", "grbl", "wabeco", "kosy", "sinumerik", "heidenhain"};
const char* const lathes[] = {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"};

}  // namespace

TEST_CASE("stop: each control writes the stop and its message as it shows one") {
    const std::string job = job_with(drill_at("[[10, 10]]") +
                                     R"(, {"type": "stop", "message": "Check the hole (a); really", "optional": true}, )" +
                                     R"({"type": "stop", "message": "Turn the part over"})");
    struct Expect {
        const char* machine;
        std::vector<std::string> lines;  // in this order
    } const expected[] = {
        {"fanuc", {"M5", "M1 (Check the hole [a]; really)", "M0 (Turn the part over)"}},
        {"linuxcnc", {"M5", "M1 (MSG, Check the hole [a]; really)", "M0 (MSG, Turn the part over)"}},
        // GRBL ignores M1: the optional stop always stops.
        {"grbl", {"M5", "M0 (Check the hole [a]; really)", "M0 (Turn the part over)"}},
        // nccad has no optional stop either; ';' would start a comment.
        {"wabeco", {"M10 O6.0", "M01 Check the hole (a), really", "M01 Turn the part over"}},
        {"sinumerik",
         {"M5", "MSG(\"Check the hole (a), really\")", "M1", "MSG()", "MSG(\"Turn the part over\")", "M0", "MSG()"}},
        {"heidenhain", {"M5", "M1 ; Check the hole (a); really", "STOP ; Turn the part over"}},
    };
    for (const Expect& e : expected) {
        INFO(e.machine);
        const Checked c = post_and_verify(job, e.machine);
        std::vector<std::string> lines = lines_of(c.text);
        // Without block numbers.
        for (std::string& l : lines) l = std::regex_replace(l, std::regex("^(N[0-9]+|[0-9]+) "), "");
        std::size_t at = 0;
        for (const std::string& l : e.lines) {
            at = find_line(lines, l, at);
            CHECK_MESSAGE(at != std::string::npos, l);
            if (at == std::string::npos) break;
        }
        CHECK_FALSE(c.mismatch);
        const std::vector<Stop> stops = stops_of(c.events);
        REQUIRE(stops.size() == 2);
        const bool has_optional = std::string(e.machine) != "grbl" && std::string(e.machine) != "wabeco";
        CHECK(stops[0].kind == (has_optional ? StopKind::optional : StopKind::mandatory));
        CHECK(stops[1].kind == StopKind::mandatory);
        CHECK(stops[1].message == "Turn the part over");
    }
}

TEST_CASE("stop: an optional stop on a control without one is noted, and written so that it stops") {
    const std::string job = job_with(drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "look", "optional": true})");
    for (const char* m : {"grbl", "wabeco", "kosy"}) {
        INFO(m);
        Run r = run({file_with("opt", job), "--machine", m});
        CHECK(r.code == 0);
        CHECK(r.err.find("/operations/1: machine " + std::string(m) + " ") != std::string::npos);
        CHECK(r.err.find("which always") != std::string::npos);
    }
    // Where the control has M1, nothing is said.
    Run f = run({file_with("opt", job), "--machine", "fanuc"});
    CHECK(f.code == 0);
    CHECK(f.err.find("optional stop") == std::string::npos);
}

TEST_CASE("stop: the spindle and coolant stop before it, and run again before the next move") {
    const std::string job = job_with(two_rows, true);
    const std::vector<std::string> l = lines_of(post_job(job, "linuxcnc").text);
    const std::size_t stop = find_line(l, "M0 (MSG, Check the hole)");
    REQUIRE(stop != std::string::npos);
    REQUIRE(stop >= 4);
    REQUIRE(stop + 6 < l.size());
    // Coolant off, then the spindle, right before the stop; the tool at the clearance.
    CHECK(l[stop - 1] == "M5");
    CHECK(l[stop - 2] == "M9");
    CHECK(l[stop - 3] == "(stop)");
    CHECK(l[stop - 4] == "G0 Z20");
    // After it: the spindle at its speed, 2 s for it to come up to speed, the coolant; then
    // the first move, Z first (the operator may have moved the axes).
    CHECK(l[stop + 1] == "(drill 1 hole)");
    CHECK(l[stop + 2] == "S1000 M3");
    CHECK(l[stop + 3] == "G4 P2");
    CHECK(l[stop + 4] == "M8");
    CHECK(l[stop + 5] == "G0 Z20");
    CHECK(l[stop + 6] == "X30 Y10");
    // Every control with flood coolant reads the same events back; those without it, the job
    // without coolant.
    for (const char* m : {"fanuc", "linuxcnc", "sinumerik", "heidenhain"}) {
        INFO(m);
        CHECK_FALSE(post_and_verify(job, m).mismatch);
    }
    for (const char* m : {"wabeco", "kosy", "grbl"}) {
        INFO(m);
        CHECK_FALSE(post_and_verify(job_with(two_rows), m).mismatch);
    }
}

TEST_CASE("stop: spinUp sets the wait after the restart; 0 waits not at all") {
    const std::string with = job_with(drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "m", "spinUp": 4.5}, )" +
                                      drill_at("[[30, 10]]"));
    const std::string text = post_job(with, "linuxcnc").text;
    CHECK(text.find("S1000 M3\nG4 P4.5\n") != std::string::npos);
    const std::string none = job_with(drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "m", "spinUp": 0}, )" +
                                      drill_at("[[30, 10]]"));
    const std::string t0 = post_job(none, "linuxcnc").text;
    CHECK(t0.find("M0 (MSG, m)\n(drill 1 hole)\nS1000 M3\nG0 Z20\n") != std::string::npos);
    CHECK(t0.find("G4 P") == std::string::npos);
    CHECK_FALSE(post_and_verify(with, "linuxcnc").mismatch);
    CHECK_FALSE(post_and_verify(none, "linuxcnc").mismatch);
}

TEST_CASE("stop: a tool change after it, or the end of the program, takes the place of the restart") {
    const std::string job = job_with(drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "Change"}, )" +
                                     R"({"type": "drill", "tool": 2, "cycle": "tap", "retractPlane": 5, "endDepth": 5, )" +
                                     R"("pitch": 1.25, "holes": [[30, 10]]}, {"type": "stop", "message": "Done"})");
    const std::string text = post_job(job, "linuxcnc").text;
    // No restart of tool 1 before tool 2 comes in, no M5 twice.
    CHECK(text.find("M0 (MSG, Change)\n(drill 1 hole)\n(T2 8 mm tap - M8 tap)\nT2 M6\nS300 M3\n") != std::string::npos);
    CHECK(text.find("M5\nM5") == std::string::npos);
    // The last stop ends the program: nothing restarts.
    CHECK(text.find("M0 (MSG, Done)\nM2\n") != std::string::npos);
    CHECK_FALSE(post_and_verify(job, "linuxcnc").mismatch);
}

TEST_CASE("stop: a stop before any tool stops nothing; the stop operation needs no tool on a mill or a lathe") {
    const std::string job = job_with(R"({"type": "stop", "message": "Clamp the part"}, )" + drill_at("[[10, 10]]"));
    const std::string text = post_job(job, "fanuc").text;
    CHECK(text.find("(stop)\nN15 M0 (Clamp the part)\n") != std::string::npos);
    CHECK_FALSE(post_and_verify(job, "fanuc").mismatch);
    const std::string lathe = R"({"name": "t", "units": "mm", "clearance": 20, "tools": [
  {"number": 1, "type": "centre-drill", "diameter": 4, "tipAngle": 60, "rpm": 1500}],
"operations": [{"type": "stop", "message": "Chuck the bar"},
  {"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": -4, "safeDistance": 2, "plungingFeedrate": 60},
  {"type": "stop", "message": "Check the centre", "optional": true}]})";
    for (const char* m : lathes) {
        INFO(m);
        const Checked c = post_and_verify(lathe, m);
        CHECK_FALSE(c.mismatch);
        CHECK(stops_of(c.events).size() == 2);
    }
}

TEST_CASE("stop: the program takes the position as unknown after a stop, as after a tool change") {
    // The stop, then a drill at the same place: Z first, then X and Y, though they did not change.
    const std::string job = job_with(drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "m", "spinUp": 0}, )" +
                                     drill_at("[[10, 10]]"));
    const std::string text = post_job(job, "linuxcnc").text;
    CHECK(text.find("M0 (MSG, m)\n(drill 1 hole)\nS1000 M3\nG0 Z20\nX10 Y10\nZ5\n") != std::string::npos);
    // The reader takes it so too: the first rapid after the stop is from an unknown position.
    const std::vector<ReadEvent> events = read_program(text, load_machine("linuxcnc"));
    bool after_stop = false, checked = false;
    for (const ReadEvent& e : events) {
        if (std::holds_alternative<Stop>(e.event)) after_stop = true;
        if (after_stop && std::holds_alternative<Rapid>(e.event)) {
            CHECK(e.from_unknown);
            checked = true;
            break;
        }
    }
    CHECK(checked);
}

TEST_CASE("stop: verify tells a missing, an extra and a weaker stop from the job's") {
    const Machine machine = load_machine("linuxcnc");
    const Job with = read_job(job_with(two_rows), "with.json");
    const Job without = read_job(job_with(drill_at("[[10, 10]]") + ", " + drill_at("[[30, 10]]")), "without.json");
    const std::string program = post_program(with, machine);
    const CompareTolerance tol = compare_tolerance(machine);
    const Trace prog = trace_program(read_program(program, machine), machine);
    // The job has no stop where the program stops: the program's path breaks off where the
    // job's goes on (after a stop the next move starts from where the operator left the axes).
    const auto extra = compare_traces(trace_expected(expand_job(without), machine), prog, tol);
    REQUIRE(extra);
    CHECK(extra->message ==
          "the job's rapid move from X10.000 Y10.000 Z20.000 to X30.000 Y10.000 Z20.000 is not in the program (there the "
          "program has a rapid move from X30.000 Y10.000 Z20.000 to X30.000 Y10.000 Z5.000)");
    // The job stops where the program does not.
    const auto missing = compare_traces(trace_expected(expand_job(with), machine),
                                        trace_program(read_program(post_program(without, machine), machine), machine), tol);
    REQUIRE(missing);
    CHECK(missing->message.find("is not in the job") != std::string::npos);
    // A stop at the end, where nothing moves after it, is named.
    const Job ends = read_job(job_with(drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "Done"})"), "e.json");
    const Job plain = read_job(job_with(drill_at("[[10, 10]]")), "p.json");
    const auto at_end = compare_traces(trace_expected(expand_job(ends), machine),
                                       trace_program(read_program(post_program(plain, machine), machine), machine), tol);
    REQUIRE(at_end);
    CHECK(at_end->message == "the program ends where the job still has a stop");
    const auto extra_end = compare_traces(trace_expected(expand_job(plain), machine),
                                          trace_program(read_program(post_program(ends, machine), machine), machine), tol);
    REQUIRE(extra_end);
    CHECK(extra_end->message == "the program has a stop after the end of the job's motion");
    // An optional stop (M1) where the job stops always is a difference; the other way round not
    // (a control without M1 writes an optional stop as M0).
    std::string weaker = program;
    weaker.replace(weaker.find("M0 (MSG"), 2, "M1");
    const auto m = compare_traces(trace_expected(expand_job(with), machine), trace_program(read_program(weaker, machine), machine), tol);
    REQUIRE(m);
    CHECK(m->message == "the program has an optional stop where the job stops always");
    const Job optional = read_job(job_with(drill_at("[[10, 10]]") + R"(, {"type": "stop", "message": "Check the hole", "optional": true}, )" +
                                           drill_at("[[30, 10]]")),
                                  "o.json");
    CHECK_FALSE(compare_traces(trace_expected(expand_job(optional), machine), prog, tol));
}

TEST_CASE("stop: verify lists the stops with their lines and messages") {
    const std::string job = file_with("stops", job_with(two_rows));
    const std::filesystem::path program = scratch("stops-verify") / "p.ngc";
    REQUIRE(run({job, "--machine", "linuxcnc", "-o", program.string()}).code == 0);
    Run v = run({"verify", program.string(), "--machine", "linuxcnc", "--job", job});
    CHECK(v.code == 0);
    CAPTURE(v.out);
    CHECK(v.out.find("stops          1\n               line 15: Check the hole\n") != std::string::npos);
    // The HTML backplot lists them in its statistics.
    const std::filesystem::path page = program.parent_path() / "p.html";
    REQUIRE(run({"verify", program.string(), "--machine", "linuxcnc", "--plot", page.string()}).code == 0);
    CHECK(read_file(page.string()).find("stops          1\n               line 15: Check the hole\n") != std::string::npos);
    // The SVG's legend counts them.
    const std::filesystem::path svg = program.parent_path() / "p.svg";
    REQUIRE(run({"verify", program.string(), "--machine", "linuxcnc", "--plot", svg.string()}).code == 0);
    const std::string drawing = read_file(svg.string());
    const auto row = drawing.find(">stops</text>");
    REQUIRE(row != std::string::npos);
    CHECK(drawing.find(">1</text>", row) != std::string::npos);
    const std::string plain = file_with("plain", job_with(drill_at("[[10, 10]]")));
    REQUIRE(run({plain, "--machine", "linuxcnc", "-o", program.string()}).code == 0);
    REQUIRE(run({"verify", program.string(), "--machine", "linuxcnc", "--plot", svg.string()}).code == 0);
    CHECK(read_file(svg.string()).find(">stops</text>") == std::string::npos);
}

TEST_CASE("stop: the message and the keys are checked when the job is read") {
    auto error = [](const std::string& stop) {
        try {
            (void)read_job(job_with(drill_at("[[10, 10]]") + ", " + stop), "t.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(error(R"({"type": "stop"})").find("/operations/1/message") != std::string::npos);
    CHECK(error(R"({"type": "stop", "message": "  "})").find("/operations/1/message: the message is empty") != std::string::npos);
    CHECK(error(R"({"type": "stop", "message": "a\nb"})").find("a control character") != std::string::npos);
    CHECK(error(R"({"type": "stop", "message": ")" + std::string(101, 'x') + "\"}").find("101 characters, more than the 100") !=
          std::string::npos);
    CHECK(error(R"({"type": "stop", "message": ")" + std::string(100, 'x') + "\"}") == "no error");
    CHECK(error(R"({"type": "stop", "message": "Insert tool 3 now"})").find("begins with \"Insert tool\"") != std::string::npos);
    CHECK(error(R"({"type": "stop", "message": "Set spindle speed to 500 rpm"})").find("begins with \"Set spindle speed to\"") !=
          std::string::npos);
    CHECK(error(R"({"type": "stop", "message": "m", "spinUp": -1})").find("/operations/1/spinUp") != std::string::npos);
    CHECK(error(R"({"type": "stop", "message": "m", "spinUp": 61})").find("/operations/1/spinUp") != std::string::npos);
    CHECK(error(R"({"type": "stop", "message": "m", "optional": "yes"})").find("/operations/1/optional") != std::string::npos);
    CHECK(error(R"({"type": "stop", "message": "m", "tool": 1})").find("unknown key \"tool\"") != std::string::npos);
    CHECK(error(R"({"type": "stop", "mesage": "m"})").find("did you mean \"message\"") != std::string::npos);
}

TEST_CASE("stop: --events shows the stop, the custom block and a cycle's unsupported") {
    const std::string job = file_with(
        "events", job_with(R"({"type": "drill", "tool": 2, "cycle": "tap", "retractPlane": 5, "endDepth": 5, "pitch": 1.25, )"
                           R"("unsupported": "stop", "holes": [[10, 10]]}, {"type": "stop", "message": "m", "optional": true}, )"
                           R"({"type": "custom", "text": {"iso": ["G4 P1"]}})"));
    Run r = run({job, "--events"});
    CHECK(r.code == 0);
    CHECK(r.out.find(R"("unsupported":"stop")") != std::string::npos);
    CHECK(r.out.find(R"({"event":"stop","optional":true,"message":"m","spinUp":2.0})") != std::string::npos);
    CHECK(r.out.find(R"({"event":"custom","path":"/operations/2/text","text":{"iso":["G4 P1"]}})") != std::string::npos);
}

TEST_CASE("stop: a stop below the clearance is refused by the safety check") {
    SafetyLimits limits{20.0, {}, {}};
    SafetyCheck check(limits);
    check.emit(OperationStart{"x", "/operations/3", std::nullopt, {}, OperationPlanes{5, 0, 5}});
    check.emit(ToolChange{1, 5, ""});
    check.emit(Rapid{{0, 0, 20}});
    check.emit(Rapid{{0, 0, 5}});
    CHECK_THROWS_WITH_AS(check.emit(Stop{StopKind::mandatory, "m"}),
                         "/operations/3: the program would stop with the tool at Z 5.000, below the clearance (Z 20.000)",
                         InputError);
    SafetyCheck ok(limits);
    ok.emit(ToolChange{1, 5, ""});
    ok.emit(Rapid{{0, 0, 20}});
    CHECK_NOTHROW(ok.emit(Stop{StopKind::mandatory, "m"}));
}

// ---- a drilling cycle the machine cannot make: "unsupported": "stop" ----

namespace {

std::string tap_job(const std::string& holes, const std::string& extra = R"(, "unsupported": "stop")") {
    return job_with(R"({"type": "drill", "tool": 2, "cycle": "tap", "comment": "tap M8", "retractPlane": 5, "safeDistance": 3, )"
                    R"("endDepth": 12, "pitch": 1.25, "holes": )" +
                    holes + extra + "}");
}

}  // namespace

TEST_CASE("unsupported stop: a machine that cannot tap stops for the taps by hand instead of refusing the job") {
    const std::string job = tap_job("[[10, 20], [30, 20], [50, 20]]");
    // Without the opt-in the job is refused, as before.
    CHECK_THROWS_WITH_AS(post_job(tap_job("[[10, 20]]", ""), "wabeco"), doctest::Contains("machine wabeco cannot tap"),
                         InputError);
    const std::string text = post_job(job, "wabeco").text;
    CHECK(text.find("G81") == std::string::npos);
    const std::string expected =
        "; tap M8: machine wabeco cannot tap; made by hand at the stop after this operation\n"
        "; Tap with tool 2, 8 mm tap - M8 tap, pitch 1.25 mm, from Z0 to Z-12\n"
        "; hole 1: X10 Y20\n"
        "; hole 2: X30 Y20\n"
        "; hole 3: X50 Y20\n"
        // Straight up to the clearance, across at it to the last hole: no cycle, no feed.
        "G00 Z20\n"
        "G00 X50\n"
        // The spindle off, the stop with its message.
        "M10 O6.0\n"
        "M01 Tap by hand with tool 2 at X10 Y20, X30 Y20, X50 Y20, 3 holes\n";
    CHECK(text.find(expected) != std::string::npos);
    for (const char* m : {"wabeco", "kosy", "grbl"}) {
        INFO(m);
        const Checked c = post_and_verify(job, m);
        CHECK_FALSE(c.mismatch);
        const std::vector<Stop> stops = stops_of(c.events);
        REQUIRE(stops.size() == 1);
        CHECK(stops[0].message == "Tap by hand with tool 2 at X10 Y20, X30 Y20, X50 Y20, 3 holes");
        // No hole is tapped; the tool never goes below the retract plane.
        const Trace t = trace_program(c.events, load_machine(m));
        CHECK(t.holes.empty());
        for (const Step& s : t.steps)
            if (s.kind == StepKind::rapid || s.kind == StepKind::feed) CHECK(s.to.z >= 5.0);
    }
    // A machine that can tap taps.
    for (const char* m : {"fanuc", "linuxcnc", "sinumerik", "heidenhain"}) {
        INFO(m);
        const Checked c = post_and_verify(job, m);
        CHECK_FALSE(c.mismatch);
        CHECK(stops_of(c.events).empty());
        CHECK(trace_program(c.events, load_machine(m)).holes.size() == 3);
    }
}

TEST_CASE("unsupported stop: the stop comes at the clearance, with the spindle and coolant off, and they restart after it") {
    const std::string job = job_with(R"({"type": "drill", "tool": 2, "cycle": "tap", "retractPlane": 5, "endDepth": 12, )"
                                     R"("pitch": 1.25, "unsupported": "stop", "holes": [[10, 20], [30, 20]]}, )" +
                                     std::string(R"({"type": "drill", "tool": 2, "cycle": "tap", "retractPlane": 5, "endDepth": 12, )"
                                                 R"("pitch": 1.25, "unsupported": "stop", "holes": [[70, 20]]})"));
    const std::vector<std::string> l = lines_of(post_job(job, "grbl").text);
    const std::size_t stop = find_line(l, "M0 (Tap by hand with tool 2 at X10 Y20, X30 Y20, 2 holes)");
    REQUIRE(stop != std::string::npos);
    CHECK(l[stop - 1] == "M5");
    CHECK(l[stop - 2] == "X30");
    CHECK(l[stop - 3] == "Z20");
    // The next operation of the same tool: the spindle back on and 2 s to come up to speed.
    CHECK(l[stop + 1] == "(drill 1 hole)");
    CHECK(l[stop + 2] == "S300 M3");
    CHECK(l[stop + 3] == "G4 P2");
    CHECK(find_line(l, "M0 (Tap by hand with tool 2 at X70 Y20, 1 hole)") != std::string::npos);
    CHECK_FALSE(post_and_verify(job, "grbl").mismatch);
}

TEST_CASE("unsupported stop: with many holes the message shows the first and counts them; the comments list every one") {
    std::string holes = "[";
    for (int i = 0; i < 40; ++i) holes += fmt::format("{}[{}, {}.125]", i ? ", " : "", 100 + 10 * i, 200 + i);
    holes += "]";
    const Checked c = post_and_verify(tap_job(holes), "wabeco");
    CHECK_FALSE(c.mismatch);
    const std::vector<Stop> stops = stops_of(c.events);
    REQUIRE(stops.size() == 1);
    CHECK(stops[0].message.size() <= max_stop_message);
    CHECK(stops[0].message == "Tap by hand with tool 2 at X100 Y200.125, X110 Y201.125 and 38 more, 40 holes listed above");
    for (int i = 0; i < 40; ++i)
        CHECK(c.text.find(fmt::format("; hole {}: X{} Y{}.125\n", i + 1, 100 + 10 * i, 200 + i)) != std::string::npos);
}

TEST_CASE("unsupported stop: which cycles a machine cannot make") {
    DrillCycle tap;
    tap.kind = CycleKind::tap;
    DrillCycle left = tap;
    left.kind = CycleKind::tap_left;
    DrillCycle drill = tap;
    drill.kind = CycleKind::drill;
    CHECK(impossible_cycle(load_machine("wabeco"), tap) == "machine wabeco cannot tap");
    CHECK(impossible_cycle(load_machine("grbl"), left) == "machine grbl cannot tap");
    CHECK(impossible_cycle(load_machine("fanuc-lathe"), tap) == "machine fanuc-lathe cannot tap");
    CHECK_FALSE(impossible_cycle(load_machine("wabeco"), drill));
    CHECK_FALSE(impossible_cycle(load_machine("fanuc"), tap));
    CHECK_FALSE(impossible_cycle(load_machine("linuxcnc"), left));
    // A machine that taps only rigidly and has no canned cycle for a kind cannot make it.
    Machine rigid = load_machine("linuxcnc");
    std::erase_if(rigid.drilling, [](const DrillingCycleSpec& s) { return s.kind == CycleKind::tap_left; });
    CHECK(impossible_cycle(rigid, left) == "machine linuxcnc taps only rigidly and has no canned cycle for \"tap-left\"");
    CHECK_FALSE(impossible_cycle(rigid, tap));
}

TEST_CASE("unsupported stop: a rigid-tapping machine without the canned cycle stops for the left-hand taps") {
    std::string text = read_file(CAMGEN_SOURCE_DIR "/machines/linuxcnc.json");
    const std::string line = R"(      {"name": "G33.1", "kind": "tap-left", "style": "rigid-g33.1", "fields": ["safeDistance", "pitch"]},)";
    const auto at = text.find(line);
    REQUIRE(at != std::string::npos);
    text.erase(at, line.size() + 1);
    const std::string machine = file_with("no-left", text);
    const std::string job = job_with(R"({"type": "drill", "tool": 3, "cycle": "tap-left", "retractPlane": 5, "endDepth": 12, )"
                                     R"("pitch": 1, "holes": [[10, 10]]})");
    std::string left_tool = job;
    left_tool.replace(left_tool.find("{\"number\": 2"), 0,
                      R"({"number": 3, "type": "tap", "diameter": 6, "rpm": 200}, )");
    Run refused = run({file_with("left", left_tool), "--machine", machine});
    CHECK(refused.code == 1);
    CHECK(refused.err.find("taps rigidly and has no canned cycle for \"tap-left\"") != std::string::npos);
    std::string opted = left_tool;
    opted.replace(opted.find("\"holes\""), 0, R"("unsupported": "stop", )");
    Run r = run({file_with("left2", opted), "--machine", machine});
    CHECK(r.code == 0);
    CHECK(r.out.find("M0 (MSG, Tap left-hand by hand with tool 3 at X10 Y10, 1 hole)") != std::string::npos);
    CHECK(r.out.find("G33.1") == std::string::npos);
}

TEST_CASE("unsupported stop: a lathe that cannot tap stops for the tap on its axis") {
    const std::string job = R"({"name": "t", "units": "mm", "clearance": 20, "tools": [
  {"number": 4, "type": "tap", "diameter": 8, "rpm": 200}],
"operations": [{"type": "turn-drill", "tool": 4, "startDepth": 0, "endDepth": -15, "safeDistance": 3,
  "retractDistance": 5, "pitch": 1.25, "unsupported": "stop"}]})";
    const Checked c = post_and_verify(job, "fanuc-lathe");
    CHECK_FALSE(c.mismatch);
    REQUIRE(stops_of(c.events).size() == 1);
    CHECK(stops_of(c.events)[0].message == "Tap by hand with tool 4 at X0, 1 hole");
    for (const char* m : {"linuxcnc-lathe", "sinumerik-lathe"}) {
        INFO(m);
        const Checked t = post_and_verify(job, m);
        CHECK_FALSE(t.mismatch);
        CHECK(stops_of(t.events).empty());
    }
}

TEST_CASE("unsupported: the key takes refuse or stop") {
    CHECK_THROWS_WITH_AS(read_job(tap_job("[[1, 1]]", R"(, "unsupported": "skip")"), "t.json"),
                         doctest::Contains("/operations/0/unsupported"), InputError);
    CHECK_NOTHROW(read_job(tap_job("[[1, 1]]", R"(, "unsupported": "refuse")"), "t.json"));
}

}  // namespace test_stops
