#include "camgen/common/input_file.hpp"
#include "camgen/common/large_buffer.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {

// Bytes read at a time from a pipe or a device, and what a binary JSON input keeps.
constexpr std::size_t chunk = std::size_t{1} << 16;

std::string named(const std::string& what, const std::string& file) { return what.empty() ? file : what + " " + file; }

[[noreturn]] void cannot_read(const InputRules& rules, const std::string& file, const std::string& why) {
    throw IoError(fmt::format("cannot read {}: {}", named(rules.what, file), why));
}

[[noreturn]] void too_large(const InputRules& rules, const std::string& file, std::uint64_t limit,
                            std::optional<std::uint64_t> size) {
    cannot_read(rules, file,
                fmt::format("{} than {}, the limit for an input (CAMGEN_MAX_INPUT_SIZE changes it)",
                            size ? fmt::format("it is {}, larger", size_text(*size)) : std::string("it goes on longer"),
                            size_text(limit)));
}

[[noreturn]] void line_too_long(const std::string& source, long line) {
    throw IoError(fmt::format("cannot read {}: line {} is longer than {}, the limit for a line of a program", source,
                              line, size_text(max_program_line)));
}

std::string type_name(mode_t mode) {
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISDIR(mode)) return "a folder";
    return "not a regular file";
}

[[noreturn]] void refused_type(const InputRules& rules, const std::string& file, mode_t mode) {
    cannot_read(rules, file,
                fmt::format("it is {}, not a regular file{}", type_name(mode),
                            rules.named_by.empty() ? std::string() : fmt::format(" ({} names a file)", rules.named_by)));
}

FileId id_of(const struct stat& st) {
    return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)};
}

// Collects what is read: keeps it (within the limit), checks line lengths, and under JSON rules
// stops keeping at the first NUL byte.
class Collector {
public:
    Collector(const std::string& file, const InputRules& rules, std::uint64_t limit)
        : file_(file), rules_(rules), limit_(limit) {}

    // Space for up to `n` more bytes (less once the text is cut: only counted); then
    // taken(count) says how many came.
    std::pair<char*, std::size_t> space(std::size_t n) {
        if (cut_) {
            scratch_.resize(chunk);
            return {scratch_.data(), std::min(n, chunk)};
        }
        kept_ = text_.size();
        if (text_.capacity() < kept_ + n) text_.reserve(std::max(kept_ + n, text_.capacity() * 2));
        text_.resize(kept_ + n);
        return {text_.data() + kept_, n};
    }
    void taken(std::size_t count) {
        total_ += count;
        if (total_ > limit_) too_large(rules_, file_, limit_, std::nullopt);
        if (cut_) return;
        text_.resize(kept_ + count);
        const std::string_view got(text_.data() + kept_, count);
        if (rules_.max_line > 0) check_lines(got);
        if (rules_.json && got.find('\0') != std::string_view::npos) {
            // Not JSON: what it is shows in its first bytes; the rest is only counted.
            cut_ = true;
            if (text_.size() > chunk) text_.resize(chunk);
            text_.shrink_to_fit();
        }
    }
    void reserve(std::size_t n) {
        text_.reserve(n);
        advise_huge_pages(text_.data(), text_.capacity());
    }
    std::size_t size() const { return text_.size(); }
    InputText finish(std::optional<FileId> id) { return {std::move(text_), id, cut_}; }

private:
    void check_lines(std::string_view got) {
        std::size_t at = 0;
        while (true) {
            const std::size_t nl = got.find('\n', at);
            const std::size_t length = (nl == std::string_view::npos ? got.size() : nl) - at;
            if (line_length_ + length > rules_.max_line) line_too_long(file_, line_);
            if (nl == std::string_view::npos) {
                line_length_ += length;
                return;
            }
            line_length_ = 0;
            ++line_;
            at = nl + 1;
        }
    }

    const std::string& file_;
    const InputRules& rules_;
    std::uint64_t limit_;
    std::uint64_t total_ = 0;
    std::string text_;
    std::size_t kept_ = 0;
    std::string scratch_;
    bool cut_ = false;
    std::size_t line_length_ = 0;
    long line_ = 1;
};

}  // namespace

std::uint64_t max_input_size() {
    const char* env = std::getenv("CAMGEN_MAX_INPUT_SIZE");
    if (!env || !*env) return default_max_input_size;
    const std::string_view text = env;
    std::uint64_t value = 0;
    std::size_t i = 0;
    for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
        if (value > (std::uint64_t{1} << 50)) break;
        value = value * 10 + static_cast<std::uint64_t>(text[i] - '0');
    }
    int shift = -1;
    if (i > 0 && i == text.size()) shift = 0;
    else if (i > 0 && i + 1 == text.size()) {
        const char unit = text[i];
        shift = unit == 'K' || unit == 'k' ? 10 : unit == 'M' || unit == 'm' ? 20 : unit == 'G' || unit == 'g' ? 30 : -1;
    }
    if (shift < 0 || value == 0 || value > (std::uint64_t{1} << 40))
        throw UsageError(fmt::format("CAMGEN_MAX_INPUT_SIZE={}: not a size (a number of bytes > 0, or with K, M or G "
                                     "for KiB, MiB or GiB)",
                                     text));
    return value << shift;
}

std::string size_text(std::uint64_t bytes) {
    for (const auto& [shift, unit] : {std::pair{30, "GiB"}, std::pair{20, "MiB"}, std::pair{10, "KiB"}}) {
        const std::uint64_t one = std::uint64_t{1} << shift;
        if (bytes < one) continue;
        if (bytes % one == 0) return fmt::format("{} {}", bytes >> shift, unit);
        return fmt::format("{:.1f} {}", static_cast<double>(bytes) / static_cast<double>(one), unit);
    }
    return fmt::format("{} bytes", bytes);
}

std::optional<FileId> regular_file_id(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
    return id_of(st);
}

std::optional<FileId> standard_input_id() {
    struct stat st {};
    if (::fstat(0, &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
    return id_of(st);
}

std::optional<FileId> standard_output_id() {
    struct stat st {};
    if (::fstat(1, &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
    return id_of(st);
}

InputText read_input(const std::string& file, const InputRules& rules, std::istream& standard_input) {
    const std::uint64_t limit = max_input_size();
    const std::string name = file == "-" ? "<stdin>" : file;  // for messages
    Collector collect(name, rules, limit);
    if (file == "-") {
        while (standard_input) {
            const auto [at, n] = collect.space(chunk);
            standard_input.read(at, static_cast<std::streamsize>(n));
            collect.taken(static_cast<std::size_t>(standard_input.gcount()));
        }
        if (standard_input.bad()) cannot_read(rules, name, std::strerror(errno ? errno : EIO));
        return collect.finish(std::nullopt);
    }
    struct stat st {};
    if (rules.regular_only) {
        // Refused before it is opened: opening a FIFO waits for a writer.
        if (::stat(file.c_str(), &st) != 0) cannot_read(rules, file, std::strerror(errno));
        if (S_ISDIR(st.st_mode)) cannot_read(rules, file, std::strerror(EISDIR));
        if (!S_ISREG(st.st_mode)) refused_type(rules, file, st.st_mode);
    }
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | (rules.regular_only ? O_NONBLOCK : 0));
    if (fd < 0) cannot_read(rules, file, std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    if (::fstat(fd, &st) != 0) cannot_read(rules, file, std::strerror(errno));
    if (S_ISDIR(st.st_mode)) cannot_read(rules, file, std::strerror(EISDIR));
    const bool regular = S_ISREG(st.st_mode);
    if (rules.regular_only) {
        if (!regular) refused_type(rules, file, st.st_mode);  // swapped since the stat
        ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    }
    // A regular file's size is known before it is read (a file in /proc says 0 and is counted).
    if (regular && static_cast<std::uint64_t>(st.st_size) > limit)
        too_large(rules, file, limit, static_cast<std::uint64_t>(st.st_size));
    if (regular && st.st_size > 0) collect.reserve(static_cast<std::size_t>(st.st_size) + 1);
    // A regular file is read into a string of its size (one more byte shows the end), without
    // growing it; a pipe or a device a chunk at a time.
    const std::size_t expected = regular && st.st_size > 0 ? static_cast<std::size_t>(st.st_size) + 1 : 0;
    while (true) {
        const std::size_t step = collect.size() < expected ? expected - collect.size() : chunk;
        const auto [at, n] = collect.space(step);
        const ssize_t got = ::read(fd, at, n);
        if (got < 0) {
            if (errno == EINTR) {
                collect.taken(0);
                continue;
            }
            const int error = errno;
            collect.taken(0);
            cannot_read(rules, file, std::strerror(error));
        }
        collect.taken(static_cast<std::size_t>(got));
        if (got == 0) break;
    }
    return collect.finish(regular ? std::optional<FileId>(id_of(st)) : std::nullopt);
}

InputBounds::InputBounds(std::string source) : source_(std::move(source)), limit_(max_input_size()) {}

void InputBounds::add(std::size_t bytes) {
    read_ += bytes;
    if (read_ > limit_)
        throw IoError(fmt::format("cannot read {}: it goes on longer than {}, the limit for an input "
                                  "(CAMGEN_MAX_INPUT_SIZE changes it)",
                                  source_, size_text(limit_)));
}

void InputBounds::line(std::size_t length, long line) const {
    if (length > max_program_line) line_too_long(source_, line);
}

}  // namespace camgen
