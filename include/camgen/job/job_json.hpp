#pragma once
// Reading a job file (format: README "Job file").
#include <string>
#include <string_view>

#include "camgen/job/job.hpp"

namespace camgen {

// Parses and validates a job. `source_name` names the file in messages.
// Throws InputError (JSON path + line) on any problem. Inch input is converted to mm here.
Job read_job(std::string_view text, const std::string& source_name);

// Reads a job from a file ("-" = standard input). Throws IoError when it cannot be read.
Job read_job_file(const std::string& filename);

}  // namespace camgen
