#pragma once
// A strict JSON reader for the common case of a job: well-formed text, strings without \u
// escapes. It drives the same SAX handler as nlohmann's parser and makes the same calls for
// the text it accepts; anything else (a syntax error, a \u escape, a byte-order mark, a number
// from_chars cannot read exactly, nesting deeper than the limit) makes it give up, and the
// caller reads the text again with nlohmann, whose errors are the messages users see. So it
// never decides an error, it only saves nlohmann's lexer (about half of reading a large job).
#include <charconv>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

namespace camgen::json::detail {

template <class Handler>
class FastJsonReader {
public:
    FastJsonReader(std::string_view text, Handler& handler, int max_nesting)
        : p_(text.data()), end_(text.data() + text.size()), handler_(handler), max_nesting_(max_nesting) {}

    // True when the whole text was one JSON value and every handler call returned true.
    bool run() {
        skip_ws();
        if (!value(0)) return false;
        skip_ws();
        return p_ == end_;
    }

private:
    static bool is_ws(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
    static bool is_digit(char c) { return c >= '0' && c <= '9'; }
    void skip_ws() {
        while (p_ != end_ && is_ws(*p_)) ++p_;
    }

    bool value(int depth) {
        if (p_ == end_) return false;
        switch (*p_) {
            case '{': return object(depth + 1);
            case '[': return array(depth + 1);
            case '"':
                if (!string()) return false;
                return handler_.string(buffer_);
            case 't': return literal("true") && handler_.boolean(true);
            case 'f': return literal("false") && handler_.boolean(false);
            case 'n': return literal("null") && handler_.null();
            default: return number();
        }
    }

    bool literal(std::string_view word) {
        if (static_cast<std::size_t>(end_ - p_) < word.size() || std::string_view(p_, word.size()) != word) return false;
        p_ += word.size();
        return true;
    }

    // Recursion stays shallow: deeper than the limit, or than a fixed bound whatever the
    // limit, is nlohmann's (iterative) to read.
    static constexpr int max_recursion = 256;
    bool too_deep(int depth) const { return depth > max_nesting_ || depth > max_recursion; }

    bool object(int depth) {
        if (too_deep(depth)) return false;
        ++p_;
        if (!handler_.start_object(static_cast<std::size_t>(-1))) return false;
        skip_ws();
        if (p_ != end_ && *p_ == '}') {
            ++p_;
            return handler_.end_object();
        }
        while (true) {
            if (p_ == end_ || *p_ != '"' || !string() || !handler_.key(buffer_)) return false;
            skip_ws();
            if (p_ == end_ || *p_ != ':') return false;
            ++p_;
            skip_ws();
            if (!value(depth)) return false;
            skip_ws();
            if (p_ == end_) return false;
            if (*p_ == '}') {
                ++p_;
                return handler_.end_object();
            }
            if (*p_ != ',') return false;
            ++p_;
            skip_ws();
        }
    }

    bool array(int depth) {
        if (too_deep(depth)) return false;
        ++p_;
        if (!handler_.start_array(static_cast<std::size_t>(-1))) return false;
        skip_ws();
        if (p_ != end_ && *p_ == ']') {
            ++p_;
            return handler_.end_array();
        }
        while (true) {
            if (!value(depth)) return false;
            skip_ws();
            if (p_ == end_) return false;
            if (*p_ == ']') {
                ++p_;
                return handler_.end_array();
            }
            if (*p_ != ',') return false;
            ++p_;
            skip_ws();
        }
    }

    // The string at p_ (its opening quote) into buffer_. Takes valid UTF-8 and the escapes
    // other than \u; gives up on anything else.
    bool string() {
        ++p_;
        buffer_.clear();
        const char* run = p_;
        while (true) {
            if (p_ == end_) return false;
            const auto c = static_cast<unsigned char>(*p_);
            if (c == '"') {
                buffer_.append(run, p_);
                ++p_;
                return true;
            }
            if (c < 0x20) return false;
            if (c == '\\') {
                buffer_.append(run, p_);
                if (++p_ == end_) return false;
                switch (*p_) {
                    case '"': buffer_ += '"'; break;
                    case '\\': buffer_ += '\\'; break;
                    case '/': buffer_ += '/'; break;
                    case 'b': buffer_ += '\b'; break;
                    case 'f': buffer_ += '\f'; break;
                    case 'n': buffer_ += '\n'; break;
                    case 'r': buffer_ += '\r'; break;
                    case 't': buffer_ += '\t'; break;
                    default: return false;  // \u and invalid escapes: nlohmann's
                }
                run = ++p_;
                continue;
            }
            if (c < 0x80) {
                ++p_;
                continue;
            }
            if (!utf8_sequence()) return false;
        }
    }

    // One multi-byte UTF-8 sequence at p_, as RFC 3629 allows it (no overlong forms, no
    // surrogates, nothing above U+10FFFF).
    bool utf8_sequence() {
        const auto c = static_cast<unsigned char>(*p_);
        int more = 0;
        unsigned char lo = 0x80, hi = 0xBF;  // the range of the second byte
        if (c >= 0xC2 && c <= 0xDF) more = 1;
        else if (c == 0xE0) more = 2, lo = 0xA0;
        else if (c >= 0xE1 && c <= 0xEC) more = 2;
        else if (c == 0xED) more = 2, hi = 0x9F;
        else if (c >= 0xEE && c <= 0xEF) more = 2;
        else if (c == 0xF0) more = 3, lo = 0x90;
        else if (c >= 0xF1 && c <= 0xF3) more = 3;
        else if (c == 0xF4) more = 3, hi = 0x8F;
        else return false;
        if (end_ - p_ <= more) return false;
        for (int k = 1; k <= more; ++k) {
            const auto b = static_cast<unsigned char>(p_[k]);
            if (b < (k == 1 ? lo : 0x80) || b > (k == 1 ? hi : 0xBF)) return false;
        }
        p_ += more + 1;
        return true;
    }

    // A number as RFC 8259 writes it. Like nlohmann: an integer without sign is unsigned, with
    // a minus sign signed, either as a float when it does not fit in 64 bits.
    bool number() {
        const char* start = p_;
        const bool negative = *p_ == '-';
        if (negative) ++p_;
        if (p_ == end_) return false;
        if (*p_ == '0') {
            ++p_;
        } else if (*p_ >= '1' && *p_ <= '9') {
            while (p_ != end_ && is_digit(*p_)) ++p_;
        } else {
            return false;
        }
        const char* integer_end = p_;
        bool is_float = false;
        if (p_ != end_ && *p_ == '.') {
            ++p_;
            if (p_ == end_ || !is_digit(*p_)) return false;
            while (p_ != end_ && is_digit(*p_)) ++p_;
            is_float = true;
        }
        if (p_ != end_ && (*p_ == 'e' || *p_ == 'E')) {
            ++p_;
            if (p_ != end_ && (*p_ == '+' || *p_ == '-')) ++p_;
            if (p_ == end_ || !is_digit(*p_)) return false;
            while (p_ != end_ && is_digit(*p_)) ++p_;
            is_float = true;
        }
        if (!is_float) {
            std::uint64_t magnitude = 0;
            bool fits = true;
            for (const char* d = start + (negative ? 1 : 0); d != integer_end; ++d) {
                const auto digit = static_cast<std::uint64_t>(*d - '0');
                if (magnitude > (std::numeric_limits<std::uint64_t>::max() - digit) / 10) {
                    fits = false;
                    break;
                }
                magnitude = magnitude * 10 + digit;
            }
            if (fits && !negative) return handler_.number_unsigned(magnitude);
            constexpr auto min_magnitude = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) + 1;
            if (fits && magnitude < min_magnitude) return handler_.number_integer(-static_cast<std::int64_t>(magnitude));
            if (fits && magnitude == min_magnitude) return handler_.number_integer(std::numeric_limits<std::int64_t>::min());
        }
        // A float, or an integer too large for 64 bits (which nlohmann reads as a float too).
        // from_chars rounds correctly, as strtod does; it refuses what overflows or underflows,
        // and those are nlohmann's to judge.
        double v = 0;
        const auto [end, error] = std::from_chars(start, p_, v);
        if (error != std::errc{} || end != p_) return false;
        return handler_.number_float(v, buffer_);
    }

    const char* p_;
    const char* end_;
    Handler& handler_;
    int max_nesting_;
    std::string buffer_;  // the string or key being read
};

}  // namespace camgen::json::detail
