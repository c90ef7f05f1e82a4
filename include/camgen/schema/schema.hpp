#pragma once
// JSON Schemas (draft 2020-12) of job and machine files, generated from the key tables that
// the readers use (ObjectSpec: job header and tools in src/job/, each operation type in
// operations/<type>/, machine files in src/post/machine.cpp), so that an editor or any JSON
// Schema validator checks a file with the same keys, types, bounds and choices as camgen.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace camgen {

// The schema of a job file.
nlohmann::ordered_json job_schema();

// The schema of a machine file.
nlohmann::ordered_json machine_schema();

// The schema of a tool library file.
nlohmann::ordered_json tools_schema();

// The names `camgen schema` takes, in order: "job", "machine", "tools".
std::vector<std::string> schema_names();

// The keys of the job-file object named `name` (an operation type such as "contour", or one
// of its objects such as "contourLead") as a Markdown table for docs/job-format.md: key, value,
// default, meaning; or of a machine-file object (a dialect's settings, "settings-iso", for
// docs/reference.md) where no job object has the name. nullopt for an unknown name.
std::optional<std::string> keys_markdown(std::string_view name);

// The schema named `name` as text (2-space indent, trailing newline); nullopt for an unknown name.
std::optional<std::string> schema_text(std::string_view name);

}  // namespace camgen
