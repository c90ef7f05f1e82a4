#pragma once
// Reading an input (a job, a machine file, a program, a tool table) with bounds: a size limit for
// every input and a line-length limit for programs, so that a file without an end (/dev/zero, a
// pipe that never closes) is refused with the limit, never read until memory runs out. Each
// regular file read keeps its identity (device and inode) for the check that no output replaces
// an input.
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

namespace camgen {

// The size limit of an input unless CAMGEN_MAX_INPUT_SIZE says otherwise: 1 GiB.
inline constexpr std::uint64_t default_max_input_size = std::uint64_t{1} << 30;
// The longest line of a program camgen reads: 1 MiB (a block of a control is a few dozen bytes).
inline constexpr std::size_t max_program_line = std::size_t{1} << 20;

// The size limit of every input: CAMGEN_MAX_INPUT_SIZE (bytes, or with a suffix K, M, G for
// KiB, MiB, GiB) where it is set and valid, else default_max_input_size. UsageError for a value
// that is not a size.
std::uint64_t max_input_size();

// A size for a message: "1 GiB", "64 KiB", "1000 bytes".
std::string size_text(std::uint64_t bytes);

// Which file a path names, links followed.
struct FileId {
    std::uint64_t device = 0;
    std::uint64_t inode = 0;
    friend bool operator==(const FileId&, const FileId&) = default;
};

// The identity of the regular file `path` names (links followed); none for a file that does not
// exist or is not a regular file (a FIFO, a device, a folder).
std::optional<FileId> regular_file_id(const std::string& path);

// The identity of the process's standard input where it is a regular file (`camgen - < job.json`).
std::optional<FileId> standard_input_id();
// The same of standard output (`camgen job.json >> job.json`).
std::optional<FileId> standard_output_id();

// How an input is read.
struct InputRules {
    std::string what = {};         // "machine file", ... for messages ("cannot read machine file F"); "" : the file alone
    std::string named_by = {};     // "the extends of m.json": said where the file is refused by its type
    bool regular_only = false;     // a FIFO, a device or a socket is refused by its type, never opened to wait
    std::size_t max_line = 0;      // refuse a line longer than this (a program); 0: no line limit
    bool json = false;             // JSON text, which never holds a NUL byte: from the first one on the
                                   // rest is counted, not kept (it is not JSON; the first 64 KiB stay
                                   // to say what it is)
};

// An input as read.
struct InputText {
    std::string text;
    std::optional<FileId> id;  // a regular file's identity
    bool cut = false;          // JSON rules: a NUL byte was found and the text after 64 KiB dropped
};

// Reads `file` whole ("-": `standard_input`) within the size limit (max_input_size()) and the
// rules. IoError naming the file for a file that cannot be read, a folder, a file the rules
// refuse by its type, more bytes than the limit (a regular file's size is checked before it is
// read; a pipe's or a device's bytes are counted as they come) and a line above max_line.
InputText read_input(const std::string& file, const InputRules& rules, std::istream& standard_input);

// Counts what a program reader reads from a stream and refuses it past the size limit or a line
// above max_program_line (IoError naming `source`).
class InputBounds {
public:
    explicit InputBounds(std::string source);
    // `bytes` more read.
    void add(std::size_t bytes);
    // A line of `length` bytes (so far, for a line not yet ended) at 1-based `line`.
    void line(std::size_t length, long line) const;

private:
    std::string source_;
    std::uint64_t limit_;
    std::uint64_t read_ = 0;
};

}  // namespace camgen
