#pragma once
// Helpers for the reader tests: edit a program, read it back against its job, catch the error.
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"

namespace camgen::test {

// `text` with its only occurrence of `from` replaced by `to` (the test fails if there is none,
// or more than one).
inline std::string replace_once(std::string text, const std::string& from, const std::string& to) {
    size_t at = text.find(from);
    REQUIRE_MESSAGE(at != std::string::npos, "no \"" << from << "\" in the program");
    CHECK_MESSAGE(text.find(from, at + 1) == std::string::npos, "\"" << from << "\" is not unique");
    return text.replace(at, from.size(), to);
}

// The first difference between a job and a program for a machine, as "line N: message".
inline std::string round_trip(const std::string& job_json, const std::string& program, const std::string& machine_name) {
    Machine m = load_machine(machine_name);
    Job job = read_job(job_json, "job.json");
    Trace actual = trace_program(read_program(program, m, "prog"), m);
    auto mismatch = compare_traces(trace_expected(expand_job(job), m, job.work_offset), actual, compare_tolerance(m, 0.0));
    return mismatch ? fmt::format("line {}: {}", mismatch->line, mismatch->message) : std::string();
}

// The same for a job and a machine already loaded (a machine with changed settings).
inline std::string round_trip_machine(const Job& job, const std::string& program, const Machine& m) {
    ReadResolution res;
    Trace actual = trace_program(read_program(program, m, "prog", &res), m);
    auto mismatch = compare_traces(trace_expected(expand_job(job), m, job.work_offset), actual, compare_tolerance(m, res, 0.0));
    return mismatch ? fmt::format("line {}: {}", mismatch->line, mismatch->message) : std::string();
}

// The message of the error reading `program` for a machine ("" if none).
inline std::string error_of(const std::string& program, const std::string& machine_name) {
    try {
        (void)read_program(program, load_machine(machine_name), "prog.nc");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace camgen::test
