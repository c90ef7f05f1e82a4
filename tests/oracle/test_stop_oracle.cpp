// Stops for the operator as LinuxCNC's rs274 runs them: the programs of samples/stops.json
// (linuxcnc, grbl, fanuc) stop the spindle before every stop, show LinuxCNC's message, stop
// (PROGRAM_STOP, or OPTIONAL_PROGRAM_STOP where the control has M1), start the spindle again and
// wait before the next move, and run on to PROGRAM_END.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "camgen/operations/registry.hpp"
#include "camgen/post/post.hpp"
#include "../unit/support.hpp"
#include "rs274.hpp"

using namespace camgen;

namespace {

// The names of rs274's canonical calls, in order ("STRAIGHT_TRAVERSE", "PROGRAM_STOP", ...),
// with the argument text of MESSAGE, COMMENT and DWELL kept ("MESSAGE( Check ...)").
std::vector<std::string> calls_of(const std::string& canon) {
    std::vector<std::string> out;
    std::istringstream in(canon);
    for (std::string line; std::getline(in, line);) {
        // "   47 N65    COMMENT(...)" ("N....." where the program has no block numbers).
        std::smatch m;
        if (!std::regex_match(line, m, std::regex(R"(\s*[0-9]+\s+N\S*\s+(.*))"))) continue;
        std::string call = m[1];
        if (call.rfind("MESSAGE", 0) != 0 && call.rfind("COMMENT", 0) != 0 && call.rfind("DWELL", 0) != 0)
            call = call.substr(0, call.find('('));
        out.push_back(call);
    }
    return out;
}

// The index of the first call at or after `from` that starts with `prefix`, else -1.
long find_call(const std::vector<std::string>& calls, const std::string& prefix, std::size_t from = 0) {
    for (std::size_t i = from; i < calls.size(); ++i)
        if (calls[i].rfind(prefix, 0) == 0) return static_cast<long>(i);
    return -1;
}

}  // namespace

TEST_CASE("rs274 runs the stops of samples/stops.json: spindle off, the stop, spindle on and a wait, to PROGRAM_END") {
    const std::optional<std::string> rs274 = oracle::find_rs274();
    REQUIRE_MESSAGE(rs274, "rs274 (linuxcnc-uspace) is not installed");
    std::ifstream f(CAMGEN_SOURCE_DIR "/samples/stops.json");
    std::stringstream text;
    text << f.rdbuf();
    const Job job = read_job(text.str(), "samples/stops.json");
    for (const std::string name : {"linuxcnc", "grbl", "fanuc"}) {
        INFO(name);
        const std::string program = test::post_program(job, load_machine(name));
        std::string canon;
        REQUIRE_NOTHROW(canon = oracle::run_rs274_canon(*rs274, program, test::tool_diameters(job)));
        const std::vector<std::string> calls = calls_of(canon);
        CAPTURE(canon);
        // The optional stop after the first row, its message a MESSAGE (LinuxCNC's MSG) or a
        // COMMENT before the stop: M1 where the control has it, M0 on GRBL.
        const long message = find_call(calls, name == "linuxcnc" ? "MESSAGE(\" Check the depth" : "COMMENT(\"Check the depth");
        REQUIRE(message > 0);
        REQUIRE(static_cast<std::size_t>(message) + 1 < calls.size());
        CHECK(calls[static_cast<std::size_t>(message) + 1] == (name == "grbl" ? "PROGRAM_STOP" : "OPTIONAL_PROGRAM_STOP"));
        // The spindle stops right before it.
        CHECK(calls[static_cast<std::size_t>(message) - 1] == "STOP_SPINDLE_TURNING");
        // After it, before any move: the custom block's comment and dwell, the spindle on again
        // and the 2 s wait (Fanuc's P is in ms, which rs274 reads as seconds).
        const long on = find_call(calls, "START_SPINDLE_CLOCKWISE", static_cast<std::size_t>(message));
        const long move = find_call(calls, "STRAIGHT_", static_cast<std::size_t>(message));
        REQUIRE(on > message);
        CHECK(on < move);
        CHECK(calls[static_cast<std::size_t>(on) + 1] == (name == "fanuc" ? "DWELL(2000.0000)" : "DWELL(2.0000)"));
        // The taps: G33.1 on LinuxCNC, G84 on Fanuc; GRBL cannot tap and stops for them.
        const long taps = find_call(calls, "RIGID_TAP");
        if (name == "linuxcnc") CHECK(taps > 0);
        if (name == "grbl") CHECK(taps < 0);
        // Every stop a program stop; the last call before the end is the program's.
        long stops = 0;
        for (const std::string& c : calls) stops += c == "PROGRAM_STOP" || c == "OPTIONAL_PROGRAM_STOP";
        CHECK(stops == (name == "grbl" ? 6 : 2));  // grbl: its 3 tool changes are pauses too
        CHECK(find_call(calls, "PROGRAM_END") > 0);
    }
}
