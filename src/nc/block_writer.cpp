#include "camgen/nc/block_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cerrno>

#include <utility>

#include "camgen/common/error.hpp"

namespace camgen::nc {

namespace {
constexpr size_t flush_threshold = 1 << 20;

// Appends a separator or line break: most are one character, which needs no copy of a string.
void append_text(std::string& to, const std::string& text) {
    if (text.size() == 1) to.push_back(text[0]);
    else to += text;
}
}  // namespace

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

void BlockWriter::add_word(std::string_view word) {
    if (block_start_ == no_block) open_block();
    else append_text(buffer_, style_.separator);
    buffer_ += word;
}

void BlockWriter::open_block() {
    block_start_ = buffer_.size();
    if (!style_.sequence_numbers) return;
    buffer_ += style_.sequence_prefix;
    char digits[24];
    const auto written = std::to_chars(digits, digits + sizeof digits, sequence_);
    buffer_.append(digits, written.ptr);
    append_text(buffer_, style_.separator);
}

void BlockWriter::end() {
    if (block_start_ == no_block) return;
    append_text(buffer_, style_.line_break);
    block_start_ = no_block;
    if (style_.sequence_numbers) sequence_ += style_.sequence_increment;
    maybe_flush();
}

std::string BlockWriter::take_open_block() {
    if (block_start_ == no_block) return {};
    std::string text = buffer_.substr(block_start_);
    buffer_.resize(block_start_);
    block_start_ = no_block;
    return text;
}

void BlockWriter::restore_open_block(const std::string& text) {
    if (text.empty()) return;
    block_start_ = buffer_.size();
    buffer_ += text;
}

namespace {

// Letters a machinist's comment often holds, spelt in ASCII (a control may show nothing else).
constexpr std::pair<std::string_view, std::string_view> ascii_spellings[] = {
    {"\u00e4", "ae"}, {"\u00f6", "oe"}, {"\u00fc", "ue"}, {"\u00c4", "Ae"}, {"\u00d6", "Oe"}, {"\u00dc", "Ue"},
    {"\u00df", "ss"}, {"\u00b0", " deg"}, {"\u00d8", "D"}, {"\u00f8", "D"}, {"\u2300", "D"}, {"\u00b1", "+-"},
    {"\u00e9", "e"}, {"\u00e8", "e"}, {"\u00e0", "a"}, {"\u00e7", "c"}, {"\u00b5", "u"}, {"\u00d7", "x"},
};

// The length of the UTF-8 sequence that starts with byte `c` (1 for a stray byte).
std::size_t utf8_length(unsigned char c) {
    if (c >= 0xF0 && c < 0xF8) return 4;
    if (c >= 0xE0) return 3;
    if (c >= 0xC0) return 2;
    return 1;
}

}  // namespace

std::string BlockWriter::clean_comment(std::string_view text) const {
    std::string s;
    s.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c >= 0x80) {
            // Outside ASCII: a known letter spelt out, anything else one '?'.
            const std::size_t n = std::min(utf8_length(c), text.size() - i);
            const std::string_view seq = text.substr(i, n);
            std::string_view spelt = "?";
            for (const auto& [utf8, ascii] : ascii_spellings)
                if (seq == utf8) spelt = ascii;
            s += spelt;
            i += n;
            continue;
        }
        ++i;
        char ch = static_cast<char>(c);
        // Control bytes (NUL, tab, line breaks, VT, FF, DEL ...) could end or split the block.
        if (c < 0x20 || c == 0x7F) ch = ' ';
        // '%' ends the record when a Fanuc-style control loads a program.
        if (ch == '%') {
            s += "pct";
            continue;
        }
        if (style_.comment_style == CommentStyle::parentheses) {
            if (ch == '(') ch = '[';
            if (ch == ')') ch = ']';
        }
        s += ch;
    }
    while (!s.empty() && s.back() == ' ') s.pop_back();
    const std::size_t limit = style_.comment_max_length > 0 ? static_cast<std::size_t>(style_.comment_max_length)
                                                            : default_comment_limit;
    if (s.size() > limit) s.resize(limit);
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

void BlockWriter::comment(std::string_view text) {
    const std::string open = take_open_block();
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
    restore_open_block(open);
}

void BlockWriter::raw(std::string_view line) {
    const std::string open = take_open_block();
    buffer_ += line;
    buffer_ += style_.line_break;
    maybe_flush();
    restore_open_block(open);
}

void BlockWriter::maybe_flush() {
    if (buffer_.size() >= flush_threshold) flush();
}

void BlockWriter::flush() {
    errno = 0;
    const std::size_t finished = block_start_ == no_block ? buffer_.size() : block_start_;
    if (finished > 0) {
        out_.write(buffer_.data(), static_cast<std::streamsize>(finished));
        buffer_.erase(0, finished);
        if (block_start_ != no_block) block_start_ = 0;
    }
    out_.flush();
    if (!out_) throw IoError("writing the NC program failed", errno);
}

}  // namespace camgen::nc
