#pragma once
// Internal to src/post: reading a machine file's JSON once its "extends" chain is applied.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// Reads a machine from its (resolved) JSON document; errors name `source` and its lines.
Machine parse_machine_json(const nlohmann::json& root, const std::string& name, const json::Source& source);

// A machine refused for a MachineProblem: an InputError at one of its paths, carrying them all
// so that load_machine can name the file of an "extends" chain that gives one of them.
class MachineSettingsError : public InputError {
public:
    MachineSettingsError(const MachineProblem& problem, std::string path, int line, std::string source)
        : InputError(std::move(path), problem.detail, line, std::move(source)), paths(problem.paths) {}
    std::vector<std::string> paths;
};

}  // namespace camgen
