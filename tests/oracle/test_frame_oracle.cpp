// Every sample on every ISO machine (fanuc, linuxcnc, grbl), in mm and in inch, runs through
// LinuxCNC's rs274 without an error and reaches PROGRAM_END: the program frame (start block,
// tool length offset on the first Z move, unit word, end) is one the interpreter takes.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>

#include "camgen/post/post.hpp"
#include "camgen/operations/registry.hpp"
#include "../unit/support.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_frame_oracle {

using namespace camgen;

namespace {

std::string read_text(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// True when `machine` refuses the sample: its golden file is an error message.
bool refused(const std::string& machine, const std::filesystem::path& sample) {
    return std::filesystem::exists(std::filesystem::path(CAMGEN_SOURCE_DIR "/tests/golden") / machine /
                                   (sample.stem().string() + ".err"));
}

}  // namespace

TEST_CASE("field failure: codes the control rejects (rs274): every sample on every ISO machine, in mm and inch, runs "
          "through rs274 to PROGRAM_END") {
    const std::optional<std::string> rs274 = oracle::find_rs274();
    REQUIRE_MESSAGE(rs274, "rs274 (linuxcnc-uspace) is not installed");
    namespace fs = std::filesystem;
    int programs = 0;
    for (const char* name : {"fanuc", "linuxcnc", "grbl"}) {
        for (const auto& entry : fs::directory_iterator(CAMGEN_SOURCE_DIR "/samples")) {
            if (entry.path().extension() != ".json") continue;
            // A sample the machine refuses (its golden file is the message) has no program.
            if (refused(name, entry.path())) continue;
            const Job job = read_job(read_text(entry.path()), entry.path().string());
            for (Units units : {Units::mm, Units::inch}) {
                Machine machine = load_machine(name);
                machine.units = units;
                INFO(name << " " << entry.path().filename().string() << (units == Units::inch ? " inch" : " mm"));
                const std::string program = test::post_program(job, machine);
                std::vector<oracle::Step> steps;
                REQUIRE_NOTHROW(steps = oracle::run_rs274(*rs274, program, test::tool_diameters(job)));
                CHECK_FALSE(steps.empty());
                ++programs;
            }
        }
    }
    CHECK(programs >= 30);
}

TEST_CASE("a linuxcnc machine with the safe retract G53 G0 Z0 runs every sample through rs274") {
    const std::optional<std::string> rs274 = oracle::find_rs274();
    REQUIRE(rs274);
    namespace fs = std::filesystem;
    Machine machine = load_machine("linuxcnc");
    machine.frame.safe_retract = {"G53", "G0", "Z0"};
    for (const auto& entry : fs::directory_iterator(CAMGEN_SOURCE_DIR "/samples")) {
        if (entry.path().extension() != ".json") continue;
        if (refused("linuxcnc", entry.path())) continue;
        INFO(entry.path().filename().string());
        const Job job = read_job(read_text(entry.path()), entry.path().string());
        const std::string program = test::post_program(job, machine);
        CHECK(program.find("G53 G0 Z0\n") != std::string::npos);
        CHECK_NOTHROW((void)oracle::run_rs274(*rs274, program, test::tool_diameters(job)));
    }
}

}  // namespace test_frame_oracle
