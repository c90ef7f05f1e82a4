#pragma once
// The error types camgen throws; main maps them to exit codes.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace camgen {

// Bad input (job or machine file): carries the JSON path and, where known, the line.
// Exit code 1.
class InputError : public std::runtime_error {
public:
    InputError(std::string path, std::string detail, int line = 0, std::string source = {});
    const std::string& path() const { return path_; }
    const std::string& detail() const { return detail_; }
    const std::string& source() const { return source_; }
    int line() const { return line_; }
    // A copy with the source file name and line filled in (used by the readers that know them).
    InputError located(std::string source, int line) const;

protected:
    // An error whose what() is `message` rather than its parts (InputErrors).
    InputError(const InputError& first, const std::string& message);

private:
    static std::string compose(const std::string& source, int line, const std::string& path,
                               const std::string& detail);
    std::string path_;
    std::string detail_;
    int line_ = 0;
    std::string source_;
};

// The independent errors of one job (of its header, of different tools, of different
// operations), in file order, at least one. It is an InputError: path(), detail(), line() and
// source() are the first error's, and what() lists the first `shown` errors, one a line
// ("job.json:12: /operations/2/depth: ..."), then "and N more errors" for the rest. located()
// gives the first error alone. Exit code 1.
class InputErrors : public InputError {
public:
    static constexpr std::size_t shown = 20;
    // Keeps the first `shown` of `errors` (in file order, not empty); `not_kept` more were
    // found and only counted.
    explicit InputErrors(std::vector<InputError> errors, std::size_t not_kept = 0);
    // The errors kept, the first `shown` at most.
    const std::vector<InputError>& errors() const { return errors_; }
    // Every error found, those not kept too.
    std::size_t count() const { return count_; }

private:
    static std::string list(const std::vector<InputError>& errors, std::size_t count);
    std::vector<InputError> errors_;
    std::size_t count_ = 0;
};

// A file could not be read or written. Exit code 3. `error_number` is the system's errno for
// the failure, where known (0: unknown), so that a caller that knows the file can name both.
class IoError : public std::runtime_error {
public:
    explicit IoError(const std::string& what, int error_number = 0)
        : std::runtime_error(what), error_number_(error_number) {}
    int error_number() const { return error_number_; }

private:
    int error_number_ = 0;
};

// The command line asks for something that does not exist (an unknown machine). Exit code 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The control refuses the program: cutter compensation it cannot apply without gouging, a
// canned cycle or a tool change while it is on, a tap cycle against the running spindle (the
// readers), in the control's own words ("the control
// refuses this: ..."). At the program line (line()) of a program read back; for a job's events
// at no line, with path() the operation's JSON path. Exit code 1, as any InputError.
class ControlRefusal : public InputError {
public:
    using InputError::InputError;
};

}  // namespace camgen
