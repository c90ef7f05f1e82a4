#pragma once
// The fuzz targets' logic, shared by the libFuzzer binaries (CAMGEN_FUZZ=ON, clang) and the
// regression test that runs the committed corpus and every input that once failed through
// them in every build. Each returns what went wrong, or nothing: an input camgen refuses with
// a clear error is fine; a crash, an unexpected exception or a program that does not read
// back as its job is a finding.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace camgen::fuzz {

// Bytes as a job: read, expanded and posted for every built-in machine.
std::optional<std::string> job_input(const std::uint8_t* data, std::size_t size);

// Bytes as an NC program, read by every built-in machine's reader.
std::optional<std::string> program_input(const std::uint8_t* data, std::size_t size);

// Bytes as mutations of a sample job (which sample, which machine, which numbers change to
// what); a mutant that reads as a valid job is posted, read back and compared with the job.
std::optional<std::string> mutated_sample(const std::uint8_t* data, std::size_t size);

}  // namespace camgen::fuzz
