// Constant surface speed (issue 30, item 4): a turning, grooving or parting tool's surfaceSpeed
// and maxRpm; the three lathe posts' words (fanuc-lathe G50 S / G96 S, linuxcnc-lathe G96 D S,
// sinumerik-lathe LIMS= / G96 S) and G97 S when an operation goes back to rpm; their readers'
// round trip; the statistics' time of a facing pass under G96 against the integral by hand; and
// the errors.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/events/events.hpp"
#include "camgen/job/tool_library.hpp"
#include "camgen/reader/reader.hpp"
#include "lathe_support.hpp"
#include "reader_support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_surface_speed {

using namespace camgen;

namespace {

// A bar of D40 faced to Z0 at 200 m/min within 2500 rpm, 0.2 mm/rev; then a drill on the axis at
// 1200 rpm. `tool1` replaces the turning tool's speed keys.
std::string job(const std::string& tool1 = R"("surfaceSpeed": 200, "maxRpm": 2500)",
                const std::string& face_feed = R"("feedMode": "per-revolution", "feed": 0.2)") {
    return R"({"clearance": 20, "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 1}},
  "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4, )" +
           tool1 + R"(},
            {"number": 2, "type": "drill", "diameter": 5, "tipAngle": 118, "rpm": 1200}],
  "operations": [{"type": "turn-face", "tool": 1, "z": 0, "stepdown": 1, )" +
           face_feed + R"(},
                 {"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -10, "safeDistance": 2,
                  "retractDistance": 5, "feedMode": "per-revolution", "plungingFeedrate": 0.1}]})";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string post(const std::string& machine, const std::string& text = job()) {
    return test::post_program(read_job(text, "t.json"), load_machine(machine));
}

// The Spindle events of a program read back.
std::vector<Spindle> spindles(const std::string& program, const std::string& machine) {
    std::vector<Spindle> out;
    for (const ReadEvent& e : read_program(program, load_machine(machine), "t.nc"))
        if (const auto* s = std::get_if<Spindle>(&e.event)) out.push_back(*s);
    return out;
}

// The reading of a job's tools for a machine whose limit is `max_rpm`.
Job read_for(const std::string& text, double max_rpm) {
    ToolLibraryOptions o;
    o.max_rpm = max_rpm;
    o.machine = "test-lathe";
    return read_job(text, "t.json", {}, o);
}

std::string refusal(const std::string& text, double max_rpm = 0.0) {
    try {
        (void)read_for(text, max_rpm);
    } catch (const InputError& e) {
        return e.path() + ": " + e.detail();
    }
    return "";
}

}  // namespace

TEST_CASE("surfaceSpeed: the Spindle event carries it, its rpm the limit; the drill goes back to rpm") {
    const Job j = read_job(job(), "t.json");
    CHECK(j.tools.at(1).surface_speed == 200);
    CHECK(j.tools.at(1).rpm == 2500);
    std::vector<Spindle> on;
    for (const Event& e : expand_job(j))
        if (const auto* s = std::get_if<Spindle>(&e); s && s->state != SpindleState::off) on.push_back(*s);
    REQUIRE(on.size() == 2);
    CHECK(on[0] == Spindle{SpindleState::cw, 2500, 200});
    CHECK(on[1] == Spindle{SpindleState::cw, 1200, 0});
    // --events prints it.
    CHECK(event_to_json(Event{on[0]}) == R"({"event":"spindle","state":"cw","rpm":2500.0,"surfaceSpeed":200.0})");
    CHECK(event_to_json(Event{on[1]}) == R"({"event":"spindle","state":"cw","rpm":1200.0})");
    // Without maxRpm the machine's limit is the limit.
    const Job by_machine = read_for(job(R"("surfaceSpeed": 200)"), 3000);
    CHECK(by_machine.tools.at(1).rpm == 3000);
}

TEST_CASE("fanuc-lathe: G50 S<limit> then G96 S<vc> M3; the drill's G50 S<maxRpm> and G97 S; F per revolution kept") {
    const std::string text = post("fanuc-lathe");
    INFO(text);
    CHECK(has(text, " G50 S2500\n"));
    CHECK(has(text, " G96 S200 M3\n"));
    CHECK(text.find("G50 S2500") < text.find("G96 S200"));
    // The feed per revolution the job gives, exactly.
    CHECK(has(text, " G1 X-0.800 F0.2000\n"));
    // Back to rpm: G97; 1200 rpm is within the G50 S2500 in effect, which stays.
    CHECK(has(text, " G97 S1200 M3\n"));
    CHECK(text.find("G96 S200") < text.find("G97 S1200"));
    CHECK_FALSE(has(text, "G50 S3000"));
    // A faster rpm after it has the limit raised to the machine's first.
    const std::string fast = test::replace_once(job(), R"("rpm": 1200)", R"("rpm": 2800)");
    const std::string raised = post("fanuc-lathe", fast);
    CHECK(has(raised, " G50 S3000\n"));
    CHECK(raised.find("G50 S3000") < raised.find("G97 S2800"));
    CHECK(raised.find("G50 S2500") < raised.find("G50 S3000"));
    CHECK(test::round_trip(job(), text, "fanuc-lathe").empty());
    const std::vector<Spindle> back = spindles(text, "fanuc-lathe");
    REQUIRE(back.size() >= 2);
    CHECK(back[0] == Spindle{SpindleState::cw, 2500, 200});
}

TEST_CASE("linuxcnc-lathe: G96 D<limit> S<vc> M3 and G95; G97 S before the drill's rpm") {
    const std::string text = post("linuxcnc-lathe");
    INFO(text);
    CHECK(has(text, "G96 D2500 S200 M3\n"));
    CHECK(has(text, "G95\n"));
    CHECK(has(text, "G97 S1200 M3\n"));
    CHECK(has(text, "G1 X-0.8 F0.2\n"));
    CHECK(test::round_trip(job(), text, "linuxcnc-lathe").empty());
    const std::vector<Spindle> back = spindles(text, "linuxcnc-lathe");
    REQUIRE(back.size() >= 2);
    CHECK(back[0] == Spindle{SpindleState::cw, 2500, 200});
    // A program that never used G96 writes no G97 (LinuxCNC's S is rpm until a G96).
    CHECK_FALSE(has(post("linuxcnc-lathe", job(R"("rpm": 900)", R"("feedMode": "per-revolution", "feed": 0.2)")), "G97"));
    // The reader: a G96 without D takes the machine's limit; a changed D is a changed limit.
    const std::string other = test::replace_once(text, "G96 D2500", "G96 D2000");
    CHECK(spindles(other, "linuxcnc-lathe")[0] == Spindle{SpindleState::cw, 2000, 200});
    CHECK(test::round_trip(job(), other, "linuxcnc-lathe").find("2000") != std::string::npos);
    CHECK(spindles(test::replace_once(text, "G96 D2500", "G96"), "linuxcnc-lathe")[0] == Spindle{SpindleState::cw, 3000, 200});
    // A changed surface speed is a difference.
    CHECK(test::round_trip(job(), test::replace_once(text, "S200 M3", "S180 M3"), "linuxcnc-lathe").find("180.000 m/min") !=
          std::string::npos);
}

TEST_CASE("sinumerik-lathe: LIMS=<limit>, then G96 S<vc> M3; G97 S before the drill") {
    const std::string text = post("sinumerik-lathe");
    INFO(text);
    CHECK(has(text, " LIMS=2500\n"));
    CHECK(has(text, " G96 S200 M3\n"));
    CHECK(text.find("LIMS=2500") < text.find("G96 S200"));
    CHECK(has(text, " G97 S1200 M3\n"));
    CHECK(test::round_trip(job(), text, "sinumerik-lathe").empty());
    const std::vector<Spindle> back = spindles(text, "sinumerik-lathe");
    REQUIRE(back.size() >= 2);
    CHECK(back[0] == Spindle{SpindleState::cw, 2500, 200});
}

TEST_CASE("sinumerik-lathe: G97 switches feed per revolution on (as G95): a drill fed per minute gets G94 after it") {
    // Siemens: "G97: revolutional feedrate and constant spindle speed" (SINUMERIK ONE), "the same
    // effect as G95" (840D, 2004). Without G94 after it, F100 would be 100 mm per revolution.
    std::string text = job();
    const std::string rev = R"("feedMode": "per-revolution", "plungingFeedrate": 0.1)";
    REQUIRE(has(text, rev));
    text.replace(text.find(rev), rev.size(), R"("feedMode": "per-minute", "plungingFeedrate": 100)");
    const std::string program = post("sinumerik-lathe", text);
    INFO(program);
    const auto g97 = program.find(" G97 S1200 M3\n");
    REQUIRE(g97 != std::string::npos);
    const auto next = program.find('\n', g97) + 1;
    CHECK(program.substr(next, program.find('\n', next) - next).ends_with(" G94"));
    CHECK(has(program.substr(next), " F100\n"));
    CHECK(test::round_trip(text, program, "sinumerik-lathe").empty());
    // The program without that G94 drills at 100 mm per revolution: read so, a mismatch.
    const auto line_end = program.find('\n', next);
    const std::string without = program.substr(0, next) + program.substr(line_end + 1);
    const std::string difference = test::round_trip(text, without, "sinumerik-lathe");
    CHECK_MESSAGE(has(difference, "feeds at 120000.000 mm/min where the job feeds at 100.000 mm/min"), difference);
    // Feed per revolution after G97 needs no G94: the drill of job() is per revolution.
    CHECK_FALSE(has(post("sinumerik-lathe").substr(post("sinumerik-lathe").find(" G97 ")), "G94"));
}

TEST_CASE("an inch lathe writes the surface speed in feet per minute and reads it back in m/min") {
    // 200 m/min = 656.17 ft/min; the three lathes write S as an rpm (a whole number): S656, which
    // reads back as 656 x 0.3048 = 199.949 m/min; the limit stays in rpm.
    for (const char* name : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        Machine m = load_machine(name);
        m.units = Units::inch;
        const std::string text = test::post_program(read_job(job(), "t.json"), m);
        INFO(name << "\n" << text);
        CHECK(has(text, "G96 S656 M3\n") != has(text, "G96 D2500 S656 M3\n"));
        CHECK_FALSE(has(text, "S200"));
        std::vector<Spindle> back;
        for (const ReadEvent& e : read_program(text, m, "t.nc"))
            if (const auto* s = std::get_if<Spindle>(&e.event); s && s->state != SpindleState::off) back.push_back(*s);
        REQUIRE(back.size() == 2);
        CHECK(back[0].rpm == 2500);
        CHECK(back[0].surface_speed == doctest::Approx(656 * 0.3048).epsilon(1e-12));
        CHECK(back[1] == Spindle{SpindleState::cw, 1200, 0});
    }
}

TEST_CASE("a mill refuses a constant surface speed") {
    const std::vector<Event> events{ToolChange{1, 10, ""}, Spindle{SpindleState::cw, 2500, 200}};
    for (const char* mill : {"fanuc", "linuxcnc", "sinumerik", "heidenhain"})
        CHECK_THROWS_WITH_AS(test::post_events(load_machine(mill), events), doctest::Contains("constant rpm only"),
                             InputError);
}

TEST_CASE("surfaceSpeed errors name their keys") {
    CHECK(refusal(job(R"("surfaceSpeed": 200, "rpm": 1000)")) ==
          "/tools/0/surfaceSpeed: give rpm (a constant spindle speed, G97) or surfaceSpeed (a constant surface speed, "
          "G96), not both");
    CHECK(refusal(job(R"("surfaceSpeed": 200, "maxRpm": 3500)"), 3000) ==
          "/tools/0/maxRpm: maxRpm 3500 rpm is above the limit of machine test-lathe (3000 rpm)");
    CHECK(refusal(job(R"("surfaceSpeed": 0, "maxRpm": 2000)")).find("/tools/0/surfaceSpeed: surfaceSpeed 0 must be more than 0") == 0);
    CHECK(refusal(job(R"("surfaceSpeed": -5, "maxRpm": 2000)")).find("/tools/0/surfaceSpeed:") == 0);
    CHECK(refusal(job(R"("surfaceSpeed": 200)")) ==
          "/tools/0/surfaceSpeed: a surfaceSpeed needs the spindle's limit: give maxRpm (there is no machine here whose "
          "limits.maxRpm it could be)");
    CHECK(refusal(job(R"("rpm": 1000, "maxRpm": 2000)")).find("/tools/0/maxRpm: maxRpm is the spindle's limit") == 0);
    CHECK(refusal(job(R"("surfaceSpeed": 200, "maxRpm": 2500)", R"("feed": 100)")) ==
          "/operations/0: tool 1 turns at a constant surface speed (surfaceSpeed, G96): the operation must feed per "
          "revolution (feedMode \"per-revolution\")");
    CHECK(refusal(job(R"("surfaceSpeed": 200, "maxRpm": 2500)", R"("feedMode": "per-minute", "feed": 100)"))
              .find("/operations/0/feedMode: tool 1 turns") == 0);
    // Not for a drill or a threading tool: they turn at an rpm.
    const std::string drill = R"({"clearance": 20, "tools": [{"number": 1, "diameter": 5, "surfaceSpeed": 30, "maxRpm": 2000}],
      "operations": [{"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": -10, "safeDistance": 2,
                      "retractDistance": 5, "plungingFeedrate": 50}]})";
    CHECK(refusal(drill).find("/tools/0/surfaceSpeed: surfaceSpeed is for a turning-tool, grooving-tool or parting-tool") == 0);
}

TEST_CASE("the time of a facing pass under G96 is the integral by hand; the stats print the rpm range") {
    // From radius 20 to the axis at 0.2 mm/rev, 200 m/min within 2500 rpm: above r1 = 1000 vc /
    // (2 pi 2500) the feed is 0.2 x 200000 / (2 pi r) mm/min, so dt = 2 pi r dr / 40000; below
    // it 500 mm/min.
    const double r1 = 1000.0 * 200 / (2 * std::numbers::pi * 2500);
    const double by_hand = (std::numbers::pi * (400 - r1 * r1) / 40000 + r1 / 500) * 60;
    const SurfaceSpeedFeed f{200, 2500, 0.2, 1, 5000};
    CHECK(surface_speed_feed_time(f, 20, 0, 20) == doctest::Approx(by_hand).epsilon(1e-12));
    CHECK(surface_speed_feed_time(f, 0, 20, 20) == doctest::Approx(by_hand).epsilon(1e-12));
    // Across the axis both halves count; the clamp to maxFeed (here 400 mm/min) slows the centre.
    CHECK(surface_speed_feed_time(f, 20, -20, 40) == doctest::Approx(2 * by_hand).epsilon(1e-12));
    bool clamped = false;
    const SurfaceSpeedFeed slow{200, 2500, 0.2, 1, 400};
    const double r_clamp = 1000.0 * 200 * 0.2 / (2 * std::numbers::pi * 400);  // 400 mm/min reached
    const double clamped_by_hand = (std::numbers::pi * (400 - r_clamp * r_clamp) / 40000 + r_clamp / 400) * 60;
    CHECK(surface_speed_feed_time(slow, 20, 0, 20, &clamped) == doctest::Approx(clamped_by_hand).epsilon(1e-12));
    CHECK(clamped);
    CHECK(surface_speed_rpm(200, 2500, 20) == doctest::Approx(200000 / (2 * std::numbers::pi * 20)));
    CHECK(surface_speed_rpm(200, 2500, 0) == 2500);

    // A program's facing pass, read back: its feed time is the integral, not 20 mm at 500 mm/min.
    const Machine m = load_machine("linuxcnc-lathe");
    const std::string program = "G18 G7 G40 G80 G90 G94 G21\nG95\nT1 M6\nG96 D2500 S200 M3\nG0 G43 Z20 H1\nX40\nZ0\nG1 X0 F0.2\nM5\nM2\n";
    const ProgramStats st = compute_stats(trace_program(read_program(program, m, "t.ngc"), m), m);
    CHECK(st.feed_time == doctest::Approx(by_hand).epsilon(1e-9));
    REQUIRE(st.tools.size() == 1);
    CHECK(st.tools[0].rpm_min == doctest::Approx(200000 / (2 * std::numbers::pi * 20)));
    CHECK(st.tools[0].rpm_max == 2500);
    const std::string text = format_stats(st);
    INFO(text);
    CHECK(has(text, "surface speed 200 m/min (G96), 1592 .. 2500 rpm\n"));
}

}  // namespace test_surface_speed
