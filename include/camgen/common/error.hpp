#pragma once
// The error types camgen throws; main maps them to exit codes.
#include <stdexcept>
#include <string>

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

private:
    static std::string compose(const std::string& source, int line, const std::string& path,
                               const std::string& detail);
    std::string path_;
    std::string detail_;
    int line_ = 0;
    std::string source_;
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

}  // namespace camgen
