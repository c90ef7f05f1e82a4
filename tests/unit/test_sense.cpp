// Values a machinist can type that a control would run differently from what the job says:
// speeds, pecks and dwells below the machine's resolution, canned feeds above the limit
// (clamped the same way on every machine). Pecks beyond count and tap feeds above the limit
// are field failures (test_field_failures.cpp).
#include <doctest/doctest.h>

#include <string>

#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_sense {

using namespace camgen;

namespace {

// One drill operation on tool 1 (a drill at `rpm`) or tool 2 (a tap at `rpm`).
std::string job_with(const std::string& op, double rpm = 1000) {
    return R"({"clearance": 20, "tools": [{"number": 1, "diameter": 5, "rpm": )" + std::to_string(rpm) +
           R"(}, {"number": 2, "type": "tap", "diameter": 12, "rpm": )" + std::to_string(rpm) +
           R"(}], "operations": [{"type": "drill", "retractPlane": 5, "safeDistance": 2, )" + op +
           R"(, "holes": [[10, 10]]}]})";
}

// The message posting `job` on `machine` fails with ("" when it succeeds).
std::string refusal(const std::string& job, const std::string& machine) {
    try {
        (void)test::post_job(job, machine);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("sense: speeds, pecks and dwells that a machine would write as 0 are refused") {
    CHECK(has(refusal(job_with(R"("tool": 1, "endDepth": 5, "plungingFeedrate": 100)", 0.4), "fanuc"),
              "spindle speed 0.4 rpm would be written as S0 on machine fanuc"));
    // nccad has no S word: the speed is a message to the operator, which must not say 0 rpm.
    CHECK(has(refusal(job_with(R"("tool": 1, "endDepth": 5, "plungingFeedrate": 100)", 0.4), "wabeco"),
              "spindle speed 0.4 rpm would be written as S0 on machine wabeco"));
    CHECK(has(refusal(job_with(R"("tool": 2, "cycle": "tap", "endDepth": 10, "pitch": 1, "tappingSpeed": 0.3)"), "sinumerik"),
              "/operations/0/tappingSpeed: tappingSpeed 0.3 rpm would be written as 0 on machine sinumerik"));
    CHECK(has(refusal(job_with(R"("tool": 1, "cycle": "deep", "endDepth": 5, "firstDepth": 0.0001, "plungingFeedrate": 100)"),
                      "fanuc"),
              "/operations/0/firstDepth: firstDepth 0.0001 mm is below the resolution of machine fanuc"));
    CHECK(has(refusal(job_with(R"("tool": 1, "cycle": "dwell", "endDepth": 5, "bottomDwell": 1e-9, "plungingFeedrate": 100)"),
                      "linuxcnc"),
              "/operations/0/bottomDwell: bottomDwell 0.000000001 s is below the resolution of machine linuxcnc"));
}

TEST_CASE("sense: a hole written 0 deep, or not below its feed start, is refused on every machine (fuzz finding 11)") {
    // heidenhain wrote CYCL DEF 203 with Q201=+0 (the control skips the cycle), which its own
    // read-back refused; the others wrote a feed from Z0 to Z0.
    auto mill = [](const std::string& cycle, const std::string& depth) {
        const std::string peck = cycle == "chip-break" ? R"(, "firstDepth": 2.5)" : "";
        return job_with(R"("tool": 1, "plungingFeedrate": 90, "cycle": ")" + cycle + R"(", "endDepth": )" + depth + peck);
    };
    for (const std::string machine : {"fanuc", "grbl", "heidenhain", "kosy", "linuxcnc", "sinumerik", "wabeco"})
        for (const std::string cycle : {"drill", "chip-break"}) {
            CAPTURE(machine);
            CAPTURE(cycle);
            CHECK(has(refusal(mill(cycle, "3.2398696036443e-09"), machine),
                      "/operations/0/endDepth: the hole is 0.0000000032 mm deep (Z 0 to -0.0000000032), below "
                      "the resolution of machine " + machine + ": it would be written 0 deep and not drilled"));
            CHECK(refusal(mill(cycle, "0.001"), machine) == "");  // one unit of the last decimal is a hole
        }
    // Both Zs rounding alike (R0.000 Z0.000 on fanuc, G0 Z0 and back on grbl), and a bottom
    // above the reference plane (heidenhain wrote Q201=+1, which the control refuses).
    const std::string flat = R"({"clearance": 20, "tools": [{"number": 1, "diameter": 5, "rpm": 1000}], "operations": [
        {"type": "drill", "retractPlane": 5, "safeDistance": 0, "referencePlane": 0.0004, "tool": 1, "plungingFeedrate": 90,
         "endDepth": 0.0008, "holes": [[10, 10]]}]})";
    // linuxcnc writes 4 decimals: there 0.0004 to -0.0004 is a hole, 0.00004 to -0.00004 is not.
    const std::string finer = R"({"clearance": 20, "tools": [{"number": 1, "diameter": 5, "rpm": 1000}], "operations": [
        {"type": "drill", "retractPlane": 5, "safeDistance": 0, "referencePlane": 0.00004, "tool": 1, "plungingFeedrate": 90,
         "endDepth": 0.00008, "holes": [[10, 10]]}]})";
    const std::string above = job_with(R"("tool": 1, "plungingFeedrate": 90, "endDepth": 1, "endDepthIsAbsolute": true)");
    for (const std::string machine : {"fanuc", "grbl", "heidenhain", "kosy", "linuxcnc", "sinumerik", "wabeco"}) {
        CAPTURE(machine);
        if (machine == "linuxcnc")
            CHECK(refusal(flat, machine) == "");
        else
            CHECK(has(refusal(flat, machine), "/operations/0/endDepth: the hole is 0.0008 mm deep (Z 0.0004 to -0.0004), below "
                                              "the resolution of machine " + machine));
        CHECK(has(refusal(finer, machine), "/operations/0/endDepth: the hole is 0.00008 mm deep (Z 0.00004 to -0.00004), below "
                                           "the resolution of machine " + machine));
        CHECK(has(refusal(above, machine),
                  "/operations/0/endDepth: the hole's bottom (Z 1) is not below where its feed starts (Z 0): nothing would "
                  "be drilled"));
    }
    auto lathe = [](const std::string& depth, const std::string& peck) {
        return R"({"clearance": 20, "tools": [{"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}],
          "operations": [{"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": )" + depth +
               R"(, "safeDistance": 2, "retractDistance": 5, "plungingFeedrate": 90)" + peck + "}]}";
    };
    for (const std::string machine : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"})
        for (const std::string peck : {"", R"(, "firstPeckDepth": 1)"}) {
            CAPTURE(machine);
            CAPTURE(peck);
            CHECK(has(refusal(lathe("-1e-9", peck), machine), "/operations/0/endDepth: the hole is 0.000000001 mm deep"));
            CHECK(refusal(lathe("-0.001", peck), machine) == "");
        }
    // Both Zs rounding alike on a lathe: a face at Z0.00004 and a bottom at Z-0.00004 (every
    // lathe), at Z0.0004 and Z-0.0004 (all but linuxcnc-lathe, which writes 4 decimals).
    auto lathe_from = [](const std::string& start, const std::string& end) {
        return R"({"clearance": 20, "tools": [{"number": 1, "type": "drill", "diameter": 5, "rpm": 1000}],
          "operations": [{"type": "turn-drill", "tool": 1, "startDepth": )" + start + R"(, "endDepth": )" + end +
               R"(, "safeDistance": 2, "retractDistance": 5, "plungingFeedrate": 90}]})";
    };
    for (const std::string machine : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        CHECK(has(refusal(lathe_from("0.00004", "-0.00004"), machine),
                  "/operations/0/endDepth: the hole is 0.00008 mm deep (Z 0.00004 to -0.00004), below the resolution of machine " +
                      machine));
        if (machine == "linuxcnc-lathe")
            CHECK(refusal(lathe_from("0.0004", "-0.0004"), machine) == "");
        else
            CHECK(has(refusal(lathe_from("0.0004", "-0.0004"), machine),
                      "/operations/0/endDepth: the hole is 0.0008 mm deep (Z 0.0004 to -0.0004), below the resolution of "
                      "machine " + machine));
        // A bottom above the face is refused by the operation before any machine sees it.
        CHECK(has(refusal(lathe_from("0", "1"), machine), "/operations/0/endDepth: endDepth (Z 1.000 mm) is not below startDepth"));
    }
}

TEST_CASE("sense: canned feeds above the machine's limit are clamped on every machine, with a warning") {
    const std::string job = job_with(R"("tool": 1, "cycle": "ream", "endDepth": 5, "plungingFeedrate": 50000,
        "retractFeedrate": 60000)");
    const test::Posted heidenhain = test::post_job(job, "heidenhain");
    CHECK_FALSE(has(heidenhain.text, "50000"));
    CHECK(has(heidenhain.warnings, "feed 50000 mm/min is above the limit of machine heidenhain"));
    const test::Posted sinumerik = test::post_job(job, "sinumerik");
    CHECK_FALSE(has(sinumerik.text, "50000"));
    CHECK_FALSE(has(sinumerik.text, "60000"));
    CHECK(has(sinumerik.text, "CYCLE85("));
    CHECK(has(sinumerik.warnings, "feed 60000 mm/min is above the limit of machine sinumerik"));
    CHECK(has(test::post_job(job, "fanuc").text, "F10000"));
}

TEST_CASE("sense: pecks are canned only when the control, from the rounded planes, makes as many as the job (fuzz finding 13)") {
    // endDepth 3.0000000016 at pecks of 2.5 from Z2: the job pecks to -0.5, -3 and -3.0000000016;
    // from G73 ... Z-3.000 R2.000 Q2.500 the control pecks twice. Written longhand, with a note.
    const std::string job = job_with(R"("tool": 1, "cycle": "chip-break", "endDepth": 3.000000001605697, "firstDepth": 2.5,
        "plungingFeedrate": 90)");
    for (const std::string machine : {"fanuc", "linuxcnc", "sinumerik", "heidenhain"}) {
        CAPTURE(machine);
        const test::Run r = test::run({test::file_with("pecks", job), "--machine", machine});
        REQUIRE(r.code == 0);
        CHECK(has(r.err, "the chip-break cycle is written longhand because machine " + machine));
        CHECK(has(r.err, "its depths rounded to the program's decimals make 2 pecks, not 3"));
        CHECK(test::round_trip(job, r.out, machine) == "");
    }
    // On the grid, canned.
    const std::string even = job_with(R"("tool": 1, "cycle": "chip-break", "endDepth": 3, "firstDepth": 2.5, "plungingFeedrate": 90)");
    CHECK(has(test::post_job(even, "fanuc").text, "G73"));
}

}  // namespace test_sense
