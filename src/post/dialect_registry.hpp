#pragma once
// The dialect registry: one entry per dialect naming both of its sides, the post that writes
// its programs and the reader that reads them back. machines/registry.cpp holds the table;
// make_post (post.hpp) and the reader (src/reader/reader.cpp) look dialects up here, so
// neither includes a dialect's headers.
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>

#include "camgen/post/post.hpp"

namespace camgen {

namespace reader {
class NcReader;
}  // namespace reader

// One dialect: the name a machine file gives in "dialect", the factories of its post and
// reader (make_reader is nullptr for a dialect camgen cannot read), and the check of a
// machine's settings against what the dialect writes and reads (nullptr: none).
struct Dialect {
    std::string_view name;
    std::unique_ptr<Post> (*make_post)(const Machine& machine, std::ostream& out, PostOptions options);
    std::unique_ptr<reader::NcReader> (*make_reader)(const Machine& machine, std::string source);
    std::optional<MachineProblem> (*check_machine)(const Machine& machine) = nullptr;
};

// Every dialect, in the order of the registry table.
std::span<const Dialect> dialects();

// The dialect of this name, or nullptr.
const Dialect* find_dialect(std::string_view name);

}  // namespace camgen
