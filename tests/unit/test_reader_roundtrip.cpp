// Round trip: every golden file of every machine (tests/golden/<machine>/<sample>.<ext>), read
// back with the machine's reader, makes the motion of the job that produced it, within half a
// unit of the last decimal written. Data-driven: a new machine's or sample's golden files are
// picked up without a change here. Every machine's dialect has a reader: none is skipped.
// A <sample>.err golden file is camgen's message for a job the machine cannot run: not a
// program, so not read, but it must not stand beside a program of the same sample.
#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include <doctest/doctest.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_reader_roundtrip {

namespace fs = std::filesystem;
using namespace camgen;

TEST_CASE("every golden file reads back to the motion of its job") {
    int checked = 0;
    std::vector<fs::path> files;
    for (const auto& dir : fs::directory_iterator(CAMGEN_SOURCE_DIR "/tests/golden"))
        if (dir.is_directory())
            for (const auto& f : fs::directory_iterator(dir.path())) files.push_back(f.path());
    std::sort(files.begin(), files.end());
    int errors = 0;
    for (const fs::path& golden : files) {
        std::string machine_name = golden.parent_path().filename().string();
        std::string sample = golden.stem().string();
        CAPTURE(golden.string());
        fs::path job_file = fs::path(CAMGEN_SOURCE_DIR "/samples") / (sample + ".json");
        REQUIRE_MESSAGE(fs::exists(job_file), "a golden file without its sample job");
        Machine machine = load_machine(machine_name);
        if (golden.extension() == ".err") {
            fs::path program = golden;
            program.replace_extension("." + machine.extension);
            CHECK_MESSAGE(!fs::exists(program), "both an error and a program for one sample: " << program.string());
            ++errors;
            continue;
        }
        REQUIRE(golden.extension() == "." + machine.extension);
        REQUIRE_MESSAGE(has_reader(machine.dialect), "no reader for dialect " << machine.dialect);
        Job job = read_job(test::read_file(job_file.string()), job_file.string());
        std::vector<ReadEvent> events;
        REQUIRE_NOTHROW(events = read_program(test::read_file(golden.string()), machine, golden.string()));
        Trace actual = trace_program(events, machine);
        Trace expected = trace_expected(expand_job(job), machine);
        auto mismatch = compare_traces(expected, actual, compare_tolerance(machine, 0.0));
        CHECK_MESSAGE(!mismatch, (mismatch ? fmt::format("line {}: {}", mismatch->line, mismatch->message) : ""));
        CHECK(actual.holes.size() == expected.holes.size());
        ++checked;
    }
    // 7 machines x 5 samples; kosy and wabeco cannot tap.
    CHECK(checked >= 33);
    CHECK(errors >= 2);
}

TEST_CASE("every sample posted in inch for every machine with an inch mode reads back to the motion of its job") {
    // Inch programs state lengths in inches and feeds in in/min, canned-cycle parameters too
    // (Sinumerik CYCLE8x, Heidenhain Q parameters): all read back through the machine's inch
    // formats, within half a unit of the last decimal (and what rounded cycle parameters add
    // up to over the pecks).
    int checked = 0;
    for (const auto& listed : list_machines()) {
        const std::string& name = listed.first;
        Machine machine = load_machine(name);
        if (!machine.accepts(Units::inch)) continue;  // nccad: refused (test_cli.cpp)
        machine.units = Units::inch;
        for (const auto& f : fs::directory_iterator(CAMGEN_SOURCE_DIR "/samples")) {
            if (f.path().extension() != ".json") continue;
            if (fs::exists(fs::path(CAMGEN_SOURCE_DIR "/tests/golden") / name / (f.path().stem().string() + ".err"))) continue;
            CAPTURE(name);
            CAPTURE(f.path().string());
            Job job = read_job(test::read_file(f.path().string()), f.path().string());
            const std::string program = test::post_program(job, machine);
            ReadResolution res;
            std::vector<ReadEvent> events;
            REQUIRE_NOTHROW(events = read_program(program, machine, "inch", &res));
            CHECK(res.position > read_resolution(load_machine(name)).position);  // read in inches
            auto mismatch = compare_traces(trace_expected(expand_job(job), machine), trace_program(events, machine), compare_tolerance(machine, res, 0.0));
            CHECK_MESSAGE(!mismatch, (mismatch ? fmt::format("line {}: {}", mismatch->line, mismatch->message) : ""));
            ++checked;
        }
    }
    // fanuc, grbl, heidenhain, linuxcnc, sinumerik x 5 samples.
    CHECK(checked >= 25);
}

TEST_CASE("the reader tells an XY-first approach from a Z-first one") {
    const Machine m = load_machine("linuxcnc");
    auto first_approach = [&](const std::string& program) {
        for (const ReadEvent& e : read_program(program, m, "prog"))
            if (e.from_unknown) return e.approach;
        FAIL("no rapid from an unknown position");
        return Approach::z_first;
    };
    CHECK(first_approach("G0 Z10\nG0 X1 Y2\nM2\n") == Approach::z_first);
    CHECK(first_approach("G0 X1 Y2\nG0 Z10\nM2\n") == Approach::xy_first);
    CHECK(first_approach("G0 X1 Y2 Z10\nM2\n") == Approach::xy_first);
    CHECK(first_approach("T1 M6\nG0 G43 Z10 H1\nX1 Y2\nM2\n") == Approach::z_first);
}

}  // namespace test_reader_roundtrip
