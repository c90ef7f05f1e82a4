#pragma once
// Writes NC blocks: sequence numbers, word separator, line break, comments. Buffers the text
// and hands it to the stream in large pieces.
#include <cstddef>
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

    // Adds a word to the block being built; empty words (modal words not written) are skipped
    // here, inline, before any call.
    BlockWriter& add(std::string_view word) {
        if (!word.empty()) add_word(word);
        return *this;
    }
    // Ends the block: writes it with its sequence number, unless it is empty.
    void end();
    // Writes a comment on a line of its own (no sequence number); a block being built comes
    // after it.
    void comment(std::string_view text);
    // Writes a line as it is (no sequence number): "%", "_", program frames; a block being
    // built comes after it.
    void raw(std::string_view line);
    // Hands the finished blocks to the stream (a block not ended yet stays, and is dropped if
    // it never ends). Throws IoError when the stream failed.
    void flush();
    const BlockStyle& style() const { return style_; }
    // The sequence number the next block gets (with sequence_numbers; a block being built has
    // its number already).
    long next_sequence() const { return sequence_; }
    // Comment text made safe for the style, the one place every post's text goes through:
    // printable ASCII only (control bytes become spaces, common letters such as umlauts and
    // the diameter sign are spelt out, any other non-ASCII character is '?'), no nested
    // delimiters, no '%' (a Fanuc end of record: written "pct"), at most the machine's
    // commentMaxLength characters (default_comment_limit when it sets none).
    std::string clean_comment(std::string_view text) const;

private:
    static constexpr std::size_t no_block = static_cast<std::size_t>(-1);
    void maybe_flush();
    // Adds a word that is not empty.
    void add_word(std::string_view word);
    // Starts the block being built at the end of the buffer: its sequence number first.
    void open_block();
    // The text of the block being built, taken out of the buffer ("" when none is open).
    std::string take_open_block();
    // Puts back a block taken out of the buffer, to be built on.
    void restore_open_block(const std::string& text);
    BlockStyle style_;
    std::ostream& out_;
    // The finished blocks, then the block being built: each word is written here once.
    std::string buffer_;
    std::size_t block_start_ = no_block;  // where the block being built begins in buffer_
    long sequence_;
};

}  // namespace camgen::nc
