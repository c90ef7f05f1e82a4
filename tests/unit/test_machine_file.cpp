// Machine files are checked like jobs (issue 10 part 2): a value that would break every
// program the machine writes is refused with an InputError naming the machine file's JSON
// path and line. Each test takes a built-in machine file and changes one value.
#include <doctest/doctest.h>

#include <fstream>

#include <algorithm>
#include <string>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_machine_file {

using namespace camgen;

namespace {

// The text of the built-in machine `name`.
std::string builtin_text(const std::string& name) {
    for (const auto& e : embedded_machines())
        if (name == e.name) return e.text;
    FAIL("no built-in machine " << name);
    return {};
}

// A refusal: the path, the 1-based line in the machine file and the message.
struct Refusal {
    std::string path;
    int line = 0;
    std::string detail;
};

// Parses machine `name` with the one occurrence of `from` replaced by `to`; the refusal, or an
// empty one when the file was accepted. `line` is where `to` stands in the changed file.
Refusal refusal(const std::string& name, const std::string& from, const std::string& to, int& line) {
    std::string text = builtin_text(name);
    const size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(text.find(from, at + 1) == std::string::npos);
    text.replace(at, from.size(), to);
    line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    try {
        parse_machine(text, name, "machines/" + name + ".json");
    } catch (const InputError& e) {
        CHECK(e.source() == "machines/" + name + ".json");
        return {e.path(), e.line(), e.detail()};
    }
    return {};
}

// Checks that changing `from` to `to` in machine `name` is refused at `path`, on the line of
// the change, with a message containing `message`.
void check_refused(const std::string& name, const std::string& from, const std::string& to, const std::string& path,
                   const std::string& message) {
    CAPTURE(name);
    CAPTURE(to);
    int line = 0;
    const Refusal r = refusal(name, from, to, line);
    CHECK(r.path == path);
    CHECK(r.line == line);
    CHECK_MESSAGE(r.detail.find(message) != std::string::npos, r.detail);
}

// Checks that changing `from` to `to` in machine `name` is accepted.
void check_accepted(const std::string& name, const std::string& from, const std::string& to) {
    CAPTURE(to);
    int line = 0;
    CHECK(refusal(name, from, to, line).path.empty());
}

}  // namespace

TEST_CASE("machine file: every built-in machine loads") {
    CHECK(embedded_machines().size() == 10);
    for (const auto& e : embedded_machines()) {
        CAPTURE(e.name);
        CHECK_NOTHROW(load_machine(e.name));
    }
}

TEST_CASE("machine file: a format's scale writes one unit as at least one in the last digit") {
    const std::string dwell = R"("dwell": {"decimals": 0, "scale": 1000})";
    check_refused("fanuc", dwell, R"("dwell": {"decimals": 0, "scale": 1e-9})", "/formats/dwell/scale",
                  "scale must be between 0.001 and 1000000");
    check_refused("fanuc", dwell, R"("dwell": {"decimals": 0, "scale": 1e7})", "/formats/dwell/scale",
                  "scale must be between 0.001 and 1000000");
    check_refused("fanuc", dwell, R"("dwell": {"decimals": 0, "scale": 0.01})", "/formats/dwell/scale",
                  "scale 0.01 with 0 decimals writes 1 as 0; the scale must be at least 1");
    check_refused("fanuc", R"("rpm": {"decimals": 0})", R"("rpm": {"decimals": 0, "scale": 0.5})", "/formats/rpm/scale",
                  "writes 1 as 0");
    check_accepted("fanuc", dwell, R"("dwell": {"decimals": 3, "scale": 0.001})");
    check_accepted("fanuc", dwell, R"("dwell": {"decimals": 0, "scale": 1000000})");
}

TEST_CASE("machine file: decimals between 0 and 12") {
    const std::string xyz = R"("xyz": {"decimals": 3, "forceDecimal": true})";
    check_refused("fanuc", xyz, R"("xyz": {"decimals": 13, "forceDecimal": true})", "/formats/xyz/decimals",
                  "decimals must be between 0 and 12");
    check_refused("fanuc", xyz, R"("xyz": {"decimals": -1, "forceDecimal": true})", "/formats/xyz/decimals",
                  "decimals must be between 0 and 12");
}

TEST_CASE("machine file: width between 0 and 20") {
    const std::string code = R"("code": {"width": 2,)";
    check_refused("wabeco", code, R"("code": {"width": 21,)", "/formats/code/width", "width must be between 0 and 20");
    check_refused("wabeco", code, R"("code": {"width": -1,)", "/formats/code/width", "width must be between 0 and 20");
    check_accepted("wabeco", code, R"("code": {"width": 20,)");
}

TEST_CASE("machine file: sequence numbers start at 0 or above and step by 1 to 1000") {
    const std::string start = R"("sequenceNumberStart": 10)";
    check_refused("fanuc", start, R"("sequenceNumberStart": -10)", "/globals/sequenceNumberStart",
                  "sequenceNumberStart must be between 0 and 99999999");
    check_refused("fanuc", start, R"("sequenceNumberStart": 100000000)", "/globals/sequenceNumberStart",
                  "sequenceNumberStart must be between 0 and 99999999");
    check_accepted("fanuc", start, R"("sequenceNumberStart": 0)");
    const std::string step = R"("sequenceNumberIncrement": 5)";
    check_refused("fanuc", step, R"("sequenceNumberIncrement": 0)", "/globals/sequenceNumberIncrement",
                  "sequenceNumberIncrement must be between 1 and 1000");
    check_refused("fanuc", step, R"("sequenceNumberIncrement": 1001)", "/globals/sequenceNumberIncrement",
                  "sequenceNumberIncrement must be between 1 and 1000");
}

TEST_CASE("machine file: limits are positive and below 1000000") {
    const std::string limits = R"("limits": {"maxFeed": 10000, "minFeed": 1, "rapidRate": 15000, "maxRpm": 12000})";
    check_refused("fanuc", limits, R"("limits": {"maxFeed": 10000, "minFeed": 1, "rapidRate": 15000, "maxRpm": -1})",
                  "/limits/maxRpm", "maxRpm must be > 0 and at most 1000000 rpm (leave it out for no limit)");
    check_refused("fanuc", limits, R"("limits": {"maxFeed": 10000, "minFeed": 1, "rapidRate": 15000, "maxRpm": 0})",
                  "/limits/maxRpm", "maxRpm must be > 0");
    check_refused("fanuc", limits, R"("limits": {"maxFeed": 2e6, "minFeed": 1, "rapidRate": 15000, "maxRpm": 12000})",
                  "/limits/maxFeed", "maxFeed must be > 0 and at most 1000000 mm/min");
    check_refused("fanuc", limits, R"("limits": {"maxFeed": 10000, "minFeed": 1, "rapidRate": 1e9, "maxRpm": 12000})",
                  "/limits/rapidRate", "rapidRate must be > 0 and at most 1000000 mm/min");
    check_refused("fanuc", limits, R"("limits": {"maxFeed": 10000, "minFeed": -1, "rapidRate": 15000, "maxRpm": 12000})",
                  "/limits/minFeed", "minFeed must be > 0");
    check_accepted("fanuc", limits, R"("limits": {"maxFeed": 10000, "minFeed": 1, "rapidRate": 15000})");
}

TEST_CASE("machine file: roughingCycles, a lathe's canned roughing cycles, checked key by key") {
    const std::string g71 =
        R"({"name": "G71", "kind": "rough-z", "style": "linuxcnc", "fields": ["depthOfCut", "retract", "allowance"]})";
    check_accepted("linuxcnc-lathe", g71, R"({"name": "G71", "kind": "rough-z", "style": "linuxcnc"})");
    check_refused("linuxcnc-lathe", g71,
                  R"({"name": "G71", "kind": "rough-z", "style": "linuxcnc", "fields": ["depthOfCut", "finish"]})",
                  "/roughingCycles/0/fields/1", "unknown roughing field \"finish\"; fields: depthOfCut, retract, allowance");
    // One cycle of each kind: a second rough-z.
    const std::string g72 =
        R"({"name": "G72", "kind": "rough-x", "style": "linuxcnc", "fields": ["depthOfCut", "retract", "allowance"]})";
    check_refused("linuxcnc-lathe", g72, R"({"name": "G72", "kind": "rough-z", "style": "linuxcnc"})",
                  "/roughingCycles/1", "a second rough-z cycle");
    check_refused("linuxcnc-lathe", g71, R"({"name": "G71", "kind": "rough-z", "style": "fanuc"})",
                  "/roughingCycles/0/style", "linuxcnc");
    check_refused("linuxcnc-lathe", g71, R"({"name": "G71", "kind": "rough-z"})", "/roughingCycles/0/style", "style");
    // Fanuc's styles: G71 along Z, G72 along X, each its own kind only.
    check_refused("linuxcnc-lathe", g72, R"({"name": "G72", "kind": "rough-x", "style": "fanuc-g71"})",
                  "/roughingCycles/1/kind", "style fanuc-g71 is a rough-z cycle (Fanuc's G71); along X: style fanuc-g72");
    check_refused("linuxcnc-lathe", g71, R"({"name": "G71", "kind": "rough-z", "style": "fanuc-g72"})",
                  "/roughingCycles/0/kind", "style fanuc-g72 is a rough-x cycle (Fanuc's G72); along Z: style fanuc-g71");
    // One pattern a machine: LinuxCNC's G71 beside Fanuc's G72 (or the other way) is refused.
    check_refused("linuxcnc-lathe", g72, R"({"name": "G72", "kind": "rough-x", "style": "fanuc-g72"})",
                  "/roughingCycles/1/style", "G71 and G72 move in different patterns (LinuxCNC's and Fanuc's)");
    check_refused("fanuc-lathe", R"("style": "fanuc-g72")", R"("style": "linuxcnc")", "/roughingCycles/1/style",
                  "a machine's roughing cycles are all LinuxCNC's or all Fanuc's");
    check_refused("linuxcnc-lathe", g71, R"({"name": "G71(", "kind": "rough-z", "style": "linuxcnc"})",
                  "/roughingCycles/0/name", "(");
    check_refused("linuxcnc", R"("frame": {)", R"("roughingCycles": [{"name": "G71", "kind": "rough-z", "style": "linuxcnc"}], "frame": {)",
                  "/roughingCycles", "roughing cycles are a lathe's");
    const Machine m = load_machine("linuxcnc-lathe");
    REQUIRE(m.roughing_cycles.size() == 2);
    CHECK(m.roughing_cycles[0].name == "G71");
    CHECK(m.roughing_cycles[0].fields.size() == 3);
    CHECK(m.roughing_cycles[1].name == "G72");
    CHECK(m.roughing_cycles[1].kind == RoughingCycleKind::rough_x);
    const Machine fanuc = load_machine("fanuc-lathe");
    REQUIRE(fanuc.roughing_cycles.size() == 2);
    CHECK(fanuc.roughing_cycles[0].style == RoughingCycleStyle::fanuc_g71);
    CHECK(fanuc.roughing_cycles[1].style == RoughingCycleStyle::fanuc_g72);
    CHECK(fanuc.roughing_cycles[1].kind == RoughingCycleKind::rough_x);
    CHECK(fanuc.rough_pattern() == RoughCyclePattern::fanuc_g71);
}

TEST_CASE("machine file: dialect settings are read with the machine, each error naming its line and key") {
    // A misspelt key, with the dialect's own keys to choose from.
    check_refused("fanuc", R"("percentLines": true)", R"("percentLine": true)", "/settings/percentLine",
                  "unknown key \"percentLine\" (did you mean \"percentLines\"?)");
    check_refused("wabeco", R"("homeAtEnd": true)", R"("homeAtEnd": true, "endOfProgramm": true)",
                  "/settings/endOfProgramm", "(did you mean \"endOfProgram\"?)");
    // A wrong type, or a value outside the key's bounds or choices.
    check_refused("fanuc", R"("toolLengthOffset": true)", R"("toolLengthOffset": "yes")", "/settings/toolLengthOffset",
                  "true or false");
    check_refused("fanuc", R"("programNumber": 1000)", R"("programNumber": "O1000")", "/settings/programNumber",
                  "integer");
    check_refused("fanuc", R"("programNumber": 1000)", R"("programNumber": -5)", "/settings/programNumber",
                  "programNumber must be between 0 (none) and 99999999");
    check_refused("grbl", R"("toolChange": "pause")", R"("toolChange": "robot")", "/settings/toolChange",
                  "\"robot\" is not one of \"m6\", \"pause\" or \"none\"");
    check_refused("linuxcnc", R"("stopMessage": "msg")", R"("stopMessage": "MSG")", "/settings/stopMessage",
                  "(did you mean \"msg\"?)");
    check_refused("wabeco", R"("underscoreLines": 2)", R"("underscoreLines": 1000000000)", "/settings/underscoreLines",
                  "underscoreLines must be between 0 and 100");
    check_refused("fanuc", R"("endCode": "M30")", R"("endCode": "")", "/settings/endCode", "must not be empty");
    // A control that takes no G43 H cannot be sent one.
    check_refused("grbl", R"("toolLengthOffset": false)", R"("toolLengthOffset": true)", "/settings/toolLengthOffset",
                  "toolLengthOffset writes G43 H, which the control does not take (lengthOffsetH is false)");
    // A setting of another dialect is named as such, not merely unknown.
    check_refused("fanuc", R"("endCode": "M30")", R"("endCode": "M30", "toolCall": "turret")", "/settings/toolCall",
                  "\"toolCall\" is a setting of dialect iso-lathe, not of this machine's dialect iso (which has "
                  "programNumber, percentLines, toolLengthOffset, toolChange, endCode, stopMessage, optionalStop, lengthOffsetH, returnLevels, arcTurns, compensationWithoutD)");
    check_refused("wabeco", R"("homeAtEnd": true)", R"("homeAtEnd": true, "percentLines": false)", "/settings/percentLines",
                  "\"percentLines\" is a setting of dialect iso and iso-lathe, not of this machine's dialect nccad");
    check_refused("sinumerik", R"("settings": {})", R"("settings": {"underscoreLines": 1})", "/settings/underscoreLines",
                  "\"underscoreLines\" is a setting of dialect nccad, not of this machine's dialect sinumerik (which "
                  "has no settings)");
    // The lathe variant's own checks, at the line of what is wrong.
    check_refused("fanuc", R"("dialect": "iso")", R"("dialect": "iso-lathe")", "/dialect",
                  "the iso-lathe dialect writes for lathes: set \"kind\": \"lathe\"");
    int line = 0;
    const Refusal limit = refusal("fanuc-lathe", R"(, "maxRpm": 3000})", "}", line);
    CHECK(limit.path == "/settings/spindleLimit");
    CHECK(limit.detail == "spindleLimit writes G50 S<maxRpm>: the machine needs limits.maxRpm");
    // The line of "spindleLimit" in the built-in machine file (found here, not counted by hand).
    {
        std::ifstream file(CAMGEN_SOURCE_DIR "/machines/fanuc-lathe.json");
        int n = 0, at = 0;
        for (std::string text; std::getline(file, text);)
            if (++n, text.find("\"spindleLimit\"") != std::string::npos) at = n;
        REQUIRE(at > 0);
        CHECK(limit.line == at);
    }
    // The lathe variant takes the ISO keys as well as its own.
    check_accepted("fanuc-lathe", R"("toolCall": "turret")", R"("toolCall": "m6", "optionalStop": false)");
}

TEST_CASE("machine file: text written into programs has no control bytes, line breaks, ( ) ; or %") {
    const std::string rule = "text written into the program must be printable ASCII without ( ) ; %";
    // A line break in the end code would end the block early; '%' would end a Fanuc tape.
    check_refused("fanuc", R"("endCode": "M30")", R"("endCode": "M30\nM0")", "/settings/endCode",
                  "a line break at character 4: " + rule);
    check_refused("fanuc", R"("endCode": "M30")", R"("endCode": "M30%")", "/settings/endCode", "'%' at character 4");
    check_refused("grbl", R"("toolChange": "pause")", R"("toolChange": "pause\r")", "/settings/toolChange",
                  "a line break");
    check_refused("fanuc", R"({"name": "G81")", R"x({"name": "G81 (drill)")x", "/drilling/cycles/0/name",
                  "'(' at character 5");
    check_refused("fanuc", R"("startBlock": ["G40")", R"("startBlock": ["G40\u0007")", "/frame/startBlock/0",
                  "the control byte 0x07 at character 4");
    check_refused("fanuc", R"("workOffsets": ["G54..G59")", R"x("workOffsets": ["G54..G59)")x", "/frame/workOffsets/0",
                  "')'");
    check_refused("fanuc", R"("flood": "M8")", R"("flood": "M8;")", "/frame/coolant/flood", "';' at character 3");
    check_refused("fanuc", R"("variableDelimeter": " ")", R"("variableDelimeter": "\t")", "/globals/variableDelimeter",
                  "the control byte 0x09");
    check_refused("heidenhain", R"("sequenceNumberPrefix": "")", R"("sequenceNumberPrefix": "N\u007f")",
                  "/globals/sequenceNumberPrefix", "the control byte 0x7F at character 2");
    check_refused("fanuc", R"("xyz": {"decimals": 3,)", R"("xyz": {"prefix": "X\u00e9", "decimals": 3,)",
                  "/formats/xyz/prefix", "the non-ASCII byte 0xC3 at character 2");
    check_refused("fanuc", R"("linebreak": "\n")", R"("linebreak": "\r")", "/globals/linebreak", "");
    check_accepted("fanuc", R"("endCode": "M30")", R"("endCode": "M2")");
}

}  // namespace test_machine_file
