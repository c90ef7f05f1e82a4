#pragma once
// Number formatting for NC words, after CNC-Calc's createFormat / createVariable.
// One formatter for every number camgen writes: never an exponent, never "-0", the decimal
// mark of the machine, independent of the process locale.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace camgen::nc {

// The fields of CNC-Calc's createFormat, plus the machine's decimal mark.
struct FormatSpec {
    std::string prefix;          // written before the number
    int width = 0;               // minimum digits of the integer part
    bool zeropad = false;        // pad the integer part with '0' (else with spaces)
    int decimals = 0;            // maximum decimals (exact count when force_decimal)
    double scale = 1.0;          // the value is multiplied by this first
    bool force_decimal = false;  // always write `decimals` decimals (3 -> 3.000)
    bool force_sign = false;     // write '+' before positive values
    char decimal_mark = '.';
};

// Turns numbers into text. Rounding: half away from zero, applied to the shortest decimal
// representation of value x scale (so 2.0005 with 3 decimals is 2.001, as a person reads it).
class Format {
public:
    Format() = default;
    explicit Format(FormatSpec spec);

    const FormatSpec& spec() const { return spec_; }
    // Appends prefix and number to `out`. Throws std::logic_error for NaN or infinity.
    void append(std::string& out, double value) const;
    std::string format(double value) const;
    // append's fast path: prefix and number written backwards so that they end just before
    // `end`, within `room` chars; returns where the text begins, or nullptr where only the
    // exact path writes the value right (near a rounding tie, 1e9 units or more) or the text
    // may need more room (a long prefix or width). Throws std::logic_error as append does.
    char* write_backwards(char* end, std::size_t room, double value) const;
    // `letter` followed by the formatted value: word("R", 2) is "R2.000".
    std::string word(std::string_view letter, double value) const;
    // The value a control reads back from the text, in input units (rounded, unscaled).
    double rounded(double value) const;
    // True when the value formats as zero.
    bool is_zero(double value) const;

private:
    // append for a value (already scaled) that only its decimal text can round exactly.
    void append_exact(std::string& out, double scaled) const;
    FormatSpec spec_;
};

// `spec` with as few decimals, from its own up to `max_decimals`, as write `value` exactly (a
// factor, pitch or speed the control multiplies: 0.7803 must not become 0.780).
Format exact_format(FormatSpec spec, double value, int max_decimals);

// A modal NC word (CNC-Calc createVariable): remembers the last text it wrote and writes
// nothing when the same text would be written again, unless forced or reset. A word keeps its
// texts in storage of its own: writing one allocates nothing (unless it is longer than 47
// characters).
class Word {
public:
    Word() = default;
    Word(std::string prefix, Format format, bool force = false);

    // The word's text ("X12.5"), or "" when it is modal and unchanged. The text lives in the
    // word: it stays valid until the next call of format, force or set_last.
    std::string_view format(double value);
    // The word's text, written even when unchanged; becomes the last value. Valid as format's.
    std::string_view force(double value);
    // Forget the last value: the next format() writes (the control's state is unknown).
    void reset();
    // Record `value` as if it had been written (the control knows it by other means).
    void set_last(double value);
    // The last value written or recorded, if any.
    std::optional<double> last() const { return last_value_; }
    const Format& fmt() const { return format_; }

private:
    // One text of the word: at the end of `chars` when it fits, as nearly every word does
    // (written there by Format::write_backwards, no string made), else in `spill`. Offsets,
    // not pointers, so that a copied word's texts are its own.
    struct Text {
        char chars[48];
        unsigned char begin = sizeof chars;  // where the text starts in chars
        bool spilled = false;
        std::string spill;
        std::string_view view() const {
            return spilled ? std::string_view(spill) : std::string_view(chars + begin, sizeof chars - begin);
        }
    };
    // Formats `value` after the prefix into the spare text; returns it, not yet the last.
    std::string_view compose(double value);
    // The spare text becomes the last text written.
    std::string_view take_spare();
    std::string prefix_;
    Format format_;
    bool force_ = false;
    // The last text and a spare one for the next; swapped by index, never copied. The last
    // text means something only while last_value_ is set.
    Text texts_[2];
    int last_ = 0;
    std::optional<double> last_value_;
};

}  // namespace camgen::nc
