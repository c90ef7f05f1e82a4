#pragma once
// Writes NC blocks: sequence numbers, word separator, line break, comments. Buffers the text
// and hands it to the stream in large pieces.
#include <ostream>
#include <string>
#include <string_view>

#include "camgen/nc/format.hpp"

namespace camgen::nc {

enum class CommentStyle { parentheses, semicolon };

// How blocks look (CNC-Calc globals: linebreak, variableDelimeter, showSequenceNumbers, ...).
// The longest comment text written when the machine file sets no commentMaxLength.
inline constexpr std::size_t default_comment_limit = 120;

struct BlockStyle {
    std::string line_break = "\n";
    std::string separator = " ";
    bool sequence_numbers = false;
    long sequence_start = 10;
    long sequence_increment = 5;
    std::string sequence_prefix = "N";
    CommentStyle comment_style = CommentStyle::parentheses;
    int comment_max_length = 0;  // 0: default_comment_limit
};

class BlockWriter {
public:
    BlockWriter(BlockStyle style, std::ostream& out);
    ~BlockWriter();
    BlockWriter(const BlockWriter&) = delete;
    BlockWriter& operator=(const BlockWriter&) = delete;

    // Adds a word to the block being built; empty words are skipped.
    BlockWriter& add(std::string_view word);
    // Ends the block: writes it with its sequence number, unless it is empty.
    void end();
    // Writes a comment on a line of its own (no sequence number).
    void comment(std::string_view text);
    // Writes a line as it is (no sequence number): "%", "_", program frames.
    void raw(std::string_view line);
    // Hands buffered text to the stream. Throws IoError when the stream failed.
    void flush();
    const BlockStyle& style() const { return style_; }
    // Comment text made safe for the style, the one place every post's text goes through:
    // printable ASCII only (control bytes become spaces, common letters such as umlauts and
    // the diameter sign are spelt out, any other non-ASCII character is '?'), no nested
    // delimiters, no '%' (a Fanuc end of record: written "pct"), at most the machine's
    // commentMaxLength characters (default_comment_limit when it sets none).
    std::string clean_comment(std::string_view text) const;

private:
    void maybe_flush();
    BlockStyle style_;
    std::ostream& out_;
    std::string buffer_;
    std::string block_;
    long sequence_;
};

}  // namespace camgen::nc
