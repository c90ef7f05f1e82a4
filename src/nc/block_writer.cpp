#include "camgen/nc/block_writer.hpp"

#include <cerrno>

#include <utility>

#include "camgen/common/error.hpp"

namespace camgen::nc {

namespace {
constexpr size_t flush_threshold = 1 << 20;
}

BlockWriter::BlockWriter(BlockStyle style, std::ostream& out)
    : style_(std::move(style)), out_(out), sequence_(style_.sequence_start) {
    buffer_.reserve(flush_threshold + 4096);
}

BlockWriter::~BlockWriter() {
    // Never throw from a destructor; callers flush explicitly to see errors.
    try {
        flush();
    } catch (...) {
    }
}

BlockWriter& BlockWriter::add(std::string_view word) {
    if (word.empty()) return *this;
    if (!block_.empty()) block_ += style_.separator;
    block_ += word;
    return *this;
}

void BlockWriter::end() {
    if (block_.empty()) return;
    if (style_.sequence_numbers) {
        buffer_ += style_.sequence_prefix;
        buffer_ += std::to_string(sequence_);
        buffer_ += style_.separator;
        sequence_ += style_.sequence_increment;
    }
    buffer_ += block_;
    buffer_ += style_.line_break;
    block_.clear();
    maybe_flush();
}

std::string BlockWriter::clean_comment(std::string_view text) const {
    std::string s;
    s.reserve(text.size());
    for (char c : text) {
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
        if (style_.comment_style == CommentStyle::parentheses) {
            if (c == '(') c = '[';
            if (c == ')') c = ']';
        }
        s += c;
    }
    while (!s.empty() && s.back() == ' ') s.pop_back();
    if (style_.comment_max_length > 0 && static_cast<int>(s.size()) > style_.comment_max_length)
        s.resize(static_cast<size_t>(style_.comment_max_length));
    return s;
}

void BlockWriter::comment(std::string_view text) {
    std::string c = clean_comment(text);
    if (style_.comment_style == CommentStyle::parentheses) {
        buffer_ += '(';
        buffer_ += c;
        buffer_ += ')';
    } else {
        buffer_ += "; ";
        buffer_ += c;
    }
    buffer_ += style_.line_break;
    maybe_flush();
}

void BlockWriter::raw(std::string_view line) {
    buffer_ += line;
    buffer_ += style_.line_break;
    maybe_flush();
}

void BlockWriter::maybe_flush() {
    if (buffer_.size() >= flush_threshold) flush();
}

void BlockWriter::flush() {
    errno = 0;
    if (!buffer_.empty()) {
        out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
        buffer_.clear();
    }
    out_.flush();
    if (!out_) throw IoError("writing the NC program failed", errno);
}

}  // namespace camgen::nc
