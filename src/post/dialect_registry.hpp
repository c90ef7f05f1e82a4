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
#include <utility>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/post/post.hpp"

namespace camgen {

namespace reader {
class NcReader;
}  // namespace reader

namespace json {
class Fields;
struct Source;
}  // namespace json

// One dialect: the name a machine file gives in "dialect", the factories of its post and
// reader (make_reader is nullptr for a dialect camgen cannot read), the check of a machine's
// settings against what the dialect writes and reads (nullptr: none), the tool length offset its
// post selects for a tool (post_length_offset; nullptr: none, a control without them), and its machine files'
// "settings": their keys (a variant's are its base dialect's and its own; the schema, the docs
// and the unknown-key check take them from here) and the reader of them, which parse_machine
// calls once with the settings' Fields (every error names the file, line and key) and the
// machine read so far (`source` for paths outside the settings, such as /dialect). The post and
// the reader take the struct it returns from Machine::settings (settings_of).
struct Dialect {
    std::string_view name;
    std::unique_ptr<Post> (*make_post)(const Machine& machine, std::ostream& out, PostOptions options);
    std::unique_ptr<reader::NcReader> (*make_reader)(const Machine& machine, std::string source);
    std::optional<MachineProblem> (*check_machine)(const Machine& machine) = nullptr;
    std::span<const KeySpec> settings_keys = {};
    std::shared_ptr<const DialectSettings> (*read_settings)(json::Fields& settings, const Machine& machine,
                                                            const json::Source& source) = nullptr;
    std::string (*length_offset)(const Machine& machine, int tool) = nullptr;
};

// What a machine's reader made of some lines of a program (a custom block): the events of each
// line, the lines it takes as the program's frame, and its state before and after them. Line
// numbers count from 0 at the first of them.
struct LinesReadBack {
    std::vector<std::pair<int, Event>> events;  // (line, event)
    std::vector<int> frame_lines;               // "%", "_": not blocks
    // What the reader keeps without an event (units, work offset, spindle speed, a modal
    // cycle call, the program's end, ...), by name, before and after the lines.
    std::vector<std::pair<std::string, std::string>> state_before, state_after;
    // The first line the reader could not read and why.
    std::optional<std::pair<int, std::string>> error;
};

// Reads `program` (for `machine`) with the machine's reader up to the `count` lines from line
// `first` (1-based), which are the ones it reports on. Defined with the readers
// (src/reader/reader.cpp): the post calls it to read back a custom block before it writes it,
// without including a reader. Throws std::logic_error when a line before them cannot be read
// or the program is shorter.
LinesReadBack read_lines_back(const Machine& machine, std::string_view program, int first, int count);

// Every dialect, in the order of the registry table.
std::span<const Dialect> dialects();

// The dialect of this name, or nullptr.
const Dialect* find_dialect(std::string_view name);

}  // namespace camgen
