#pragma once
// Internal to src/post: reading a machine file's JSON once its "extends" chain is applied.
#include <string>

#include <nlohmann/json.hpp>

#include "camgen/common/json_util.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// Reads a machine from its (resolved) JSON document; errors name `source` and its lines.
Machine parse_machine_json(const nlohmann::json& root, const std::string& name, const json::Source& source);

}  // namespace camgen
