// Issue 9 parts 4 and 6: tapping as a machine capability, notes for cycles written longhand
// (--quiet hides them), holes counted canned and longhand by --stats and verify.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_capabilities {

using namespace camgen;
using test::post_job;
using test::Run;
using test::run;
using test::drill_job;
using test::file_with;

namespace {


// The text of a built-in machine file.
std::string machine_text(const std::string& name) {
    return std::find_if(embedded_machines().begin(), embedded_machines().end(),
                        [&](const auto& e) { return e.name == name; })
        ->text;
}

const std::string tap_right = R"("tool": 2, "cycle": "tap", "retractPlane": 5, "safeDistance": 3, "endDepth": 12, "pitch": 1.25)";

}  // namespace

TEST_CASE("a tap on a machine that cannot tap is refused with the true reason") {
    const std::string job = file_with("tap", drill_job(tap_right));
    // grbl writes G1 moves with a spindle reversal, which breaks a tap in a rigid holder.
    Run g = run({job, "--machine", "grbl"});
    CHECK(g.code == 1);
    CHECK(g.out == "");
    CHECK(g.err.find("/operations/0/cycle: machine grbl cannot synchronise the spindle to the feed; tapping needs a "
                     "floating tap holder: set tapping to floating in a copy of the machine file") != std::string::npos);
    // nccad's spindle cannot reverse: the tap could not be backed out.
    for (const char* m : {"wabeco", "kosy"}) {
        Run w = run({job, "--machine", m});
        CHECK(w.code == 1);
        CHECK(w.err.find(std::string("machine ") + m +
                         " cannot tap: its spindle cannot run counter-clockwise, so a right-hand tap cannot be backed "
                         "out of the hole") != std::string::npos);
    }
}

TEST_CASE("grbl with tapping floating in a copy of its machine file writes the longhand tap") {
    std::string text = machine_text("grbl");
    const auto at = text.find("\"tapping\": \"none\"");
    REQUIRE(at != std::string::npos);
    text.replace(at, 17, "\"tapping\": \"floating\"");
    const std::string machine = file_with("grbl-floating", text);
    Run r = run({file_with("tap2", drill_job(tap_right)), "--machine", machine});
    CHECK(r.code == 0);
    CHECK(r.out.find("M4") != std::string::npos);
}

TEST_CASE("a rigid-tapping machine never writes a longhand tap") {
    // linuxcnc's G33.1 carries no separate tapping speed: longhand G1 moves would break a rigid tap.
    const std::string op = R"("tool": 2, "cycle": "tap", "retractPlane": 5, "endDepth": 12, "pitch": 1.25, "tappingSpeed": 200)";
    Run r = run({file_with("rigid", drill_job(op)), "--machine", "linuxcnc"});
    CHECK(r.code == 1);
    CHECK(r.err.find("/operations/0/output: machine linuxcnc taps rigidly and its G33.1 cannot carry tappingSpeed; a "
                     "longhand tap (feed moves with a spindle reversal) is not synchronised to the spindle and breaks a "
                     "tap in a rigid holder: leave out tappingSpeed, or if the tap sits in a floating holder, set "
                     "tapping to floating in a copy of the machine file") != std::string::npos);
    CHECK(r.out == "");
    // Asked for longhand: refused too.
    Run l = run({file_with("rigid-lh", drill_job(tap_right + R"(, "output": "longhand")")), "--machine", "heidenhain"});
    CHECK(l.code == 1);
    CHECK(l.err.find("machine heidenhain taps rigidly and the job asks for output \"longhand\"") != std::string::npos);
    // The canned rigid tap is fine.
    CHECK(run({file_with("rigid-ok", drill_job(tap_right)), "--machine", "linuxcnc"}).code == 0);
}

TEST_CASE("--describe-machine shows the tapping capability; a G33.1 cycle needs tapping rigid") {
    CHECK(run({"--describe-machine", "fanuc"}).out.find("tapping                 floating: ") != std::string::npos);
    CHECK(run({"--describe-machine", "grbl"}).out.find("tapping                 none: ") != std::string::npos);
    std::string text = machine_text("linuxcnc");
    text.replace(text.find("\"tapping\": \"rigid\""), 18, "\"tapping\": \"floating\"");
    CHECK_THROWS_WITH_AS(parse_machine(text, "x", "x.json"), doctest::Contains("style rigid-g33.1 taps rigidly"), InputError);
}

TEST_CASE("auto writing longhand where the machine has the cycle canned says so; --quiet hides it") {
    const std::string op = R"("tool": 1, "retractPlane": 5, "safeDistance": 2, "endDepth": 6, "plungingFeedrate": 100)";
    const std::string job = file_with("note", drill_job(op));
    Run r = run({job, "--machine", "wabeco"});
    CHECK(r.code == 0);
    CHECK(r.err == "camgen: note: /operations/0 (drill 2 holes): the drill cycle is written longhand because machine wabeco's G81 "
                   "cannot carry safeDistance\n");
    Run q = run({job, "--machine", "wabeco", "--quiet"});
    CHECK(q.code == 0);
    CHECK(q.err == "");
    CHECK(q.out == r.out);
    // Canned: no note.
    CHECK(run({job, "--machine", "fanuc"}).err == "");
    // grbl has no canned cycles at all: longhand is no surprise there.
    CHECK(run({job, "--machine", "grbl"}).err == "");
}

TEST_CASE("--stats and verify count the holes written canned and longhand") {
    const std::string canned = file_with("count-a", drill_job(R"("tool": 1, "retractPlane": 5, "endDepth": 6, "plungingFeedrate": 100)"));
    Run a = run({canned, "--machine", "wabeco", "--stats"});
    CHECK(a.code == 0);
    CHECK(a.err.find("hole cycles    2 canned, 0 longhand\n") != std::string::npos);
    const std::string longhand =
        file_with("count-b", drill_job(R"("tool": 1, "retractPlane": 5, "safeDistance": 2, "endDepth": 6, "plungingFeedrate": 100)"));
    Run b = run({longhand, "--machine", "wabeco", "--stats", "--quiet"});
    CHECK(b.code == 0);
    CHECK(b.err.find("hole cycles    0 canned, 2 longhand\n") != std::string::npos);
    const std::filesystem::path program = test::scratch("safety-count") / "p.knc";
    REQUIRE(run({longhand, "--machine", "wabeco", "-q", "-o", program.string()}).code == 0);
    CHECK(run({"verify", program.string(), "--machine", "wabeco"}).out.find("hole cycles    0 canned, 2 longhand\n") !=
          std::string::npos);
}

}  // namespace test_capabilities
