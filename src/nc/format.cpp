#include "camgen/nc/format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace camgen::nc {

Format::Format(FormatSpec spec) : spec_(std::move(spec)) {
    if (spec_.decimals < 0 || spec_.decimals > 12)
        throw std::invalid_argument("format decimals must be between 0 and 12");
}

namespace {

constexpr unsigned long long pow10[] = {1ULL, 10ULL, 100ULL, 1000ULL, 10000ULL, 100000ULL, 1000000ULL,
                                        10000000ULL, 100000000ULL, 1000000000ULL, 10000000000ULL,
                                        100000000000ULL, 1000000000000ULL};

// |v| rounded to `decimals` places: the integer digits, then exactly `decimals` fraction
// digits, in one buffer.
struct Decimal {
    char digits[400];
    int integer_length = 0;
    int fraction_length = 0;
    bool negative = false;

    bool zero() const {
        for (int i = 0; i < integer_length + fraction_length; ++i)
            if (digits[i] != '0') return false;
        return true;
    }
};

// Exact path: round the shortest decimal text of v (std::to_chars, fixed notation: never an
// exponent) half away from zero, digit by digit.
void round_text(double v, int decimals, Decimal& d) {
    char text[400];
    auto res = std::to_chars(text, text + sizeof text, v, std::chars_format::fixed);
    if (res.ec != std::errc()) throw std::logic_error("number too large to format");
    const char* p = text;
    const char* end = res.ptr;
    d.negative = *p == '-';
    if (d.negative) ++p;
    int n = 0;
    while (p < end && *p != '.') d.digits[n++] = *p++;
    d.integer_length = n;
    if (p < end) ++p;  // the point
    int kept = 0;
    while (p < end && kept < decimals) d.digits[n++] = *p++, ++kept;
    bool round_up = p < end && *p >= '5';
    for (; kept < decimals; ++kept) d.digits[n++] = '0';
    d.fraction_length = decimals;
    if (round_up) {
        int i = n - 1;
        while (i >= 0 && d.digits[i] == '9') d.digits[i--] = '0';
        if (i >= 0) {
            ++d.digits[i];
        } else {  // 9.99 -> 10.00: one more integer digit
            for (int k = n; k > 0; --k) d.digits[k] = d.digits[k - 1];
            d.digits[0] = '1';
            ++d.integer_length;
        }
    }
}

// value x scale, checked to be finite.
double scaled_value(const FormatSpec& spec, double value) {
    const double v = value * spec.scale;
    if (!std::isfinite(value) || !std::isfinite(v))
        throw std::logic_error("refusing to write a number that is not finite");
    return v;
}

// Fast path: |v| in units of the last decimal, rounded, when the scaled value is small enough
// for double arithmetic to be exact to far below half a unit and not close to a rounding
// boundary: then rounding the binary value gives the same digits as rounding its decimal
// text. nullopt where the exact path (round_text) must decide.
std::optional<unsigned long long> rounded_units(double v, int decimals) {
    const double scaled = std::abs(v) * static_cast<double>(pow10[decimals]);
    if (!(scaled < 1e9)) return std::nullopt;
    // scaled is >= 0: truncation is floor (and needs no call into libm).
    const auto whole = static_cast<unsigned long long>(scaled);
    const double frac = scaled - static_cast<double>(whole);
    if (std::abs(frac - 0.5) < 1e-6) return std::nullopt;
    return whole + (frac > 0.5 ? 1 : 0);
}

// The digits of value x scale.
Decimal digits_of(const FormatSpec& spec, double value) {
    const double v = scaled_value(spec, value);
    Decimal d;
    const std::optional<unsigned long long> units = rounded_units(v, spec.decimals);
    if (!units) {
        round_text(v, spec.decimals, d);
        return d;
    }
    unsigned long long n = *units;
    d.negative = v < 0;
    unsigned long long integer = n / pow10[spec.decimals];
    unsigned long long fraction = n % pow10[spec.decimals];
    char tmp[24];
    int i = 24;
    do {
        tmp[--i] = static_cast<char>('0' + integer % 10);
        integer /= 10;
    } while (integer);
    d.integer_length = 24 - i;
    for (int k = 0; k < d.integer_length; ++k) d.digits[k] = tmp[i + k];
    d.fraction_length = spec.decimals;
    for (int k = spec.decimals - 1; k >= 0; --k) {
        d.digits[d.integer_length + k] = static_cast<char>('0' + fraction % 10);
        fraction /= 10;
    }
    return d;
}

// "00" .. "99": two digits at a time.
constexpr char digit_pairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Writes the decimal digits of `n`, at least `min_digits` of them (leading zeros), so that
// they end just before `end`; returns where they begin.
char* write_digits(char* end, unsigned long long n, int min_digits) {
    char* p = end;
    while (n >= 100) {
        const auto pair = static_cast<unsigned>(n % 100) * 2;
        n /= 100;
        *--p = digit_pairs[pair + 1];
        *--p = digit_pairs[pair];
    }
    if (n >= 10) {
        const auto pair = static_cast<unsigned>(n) * 2;
        *--p = digit_pairs[pair + 1];
        *--p = digit_pairs[pair];
    } else {
        *--p = static_cast<char>('0' + n);
    }
    while (end - p < min_digits) *--p = '0';
    return p;
}

}  // namespace

// Digits the fast path writes besides prefix and padding: a sign, 10 digits (it takes fewer
// than 1e9 units), the decimal mark and 12 decimals, with room to spare.
constexpr std::size_t fast_digits = 26;

char* Format::write_backwards(char* end, std::size_t room, double value) const {
    const double v = scaled_value(spec_, value);
    const std::optional<unsigned long long> units = rounded_units(v, spec_.decimals);
    if (!units || room < spec_.prefix.size() + static_cast<std::size_t>(std::max(spec_.width, 0)) + fast_digits)
        return nullptr;
    // Trailing zeros of the fraction go first (unless forced), then the digits are written
    // backwards one by one: every division is by the constant 10.
    unsigned long long n = *units;
    int fraction_digits = spec_.decimals;
    if (!spec_.force_decimal)
        for (; fraction_digits > 0 && n % 10 == 0; --fraction_digits) n /= 10;
    char* p = end;
    if (fraction_digits > 0) {
        for (int k = 0; k < fraction_digits; ++k, n /= 10) *--p = static_cast<char>('0' + n % 10);
        *--p = spec_.decimal_mark;
    }
    char* const integer_end = p;
    p = write_digits(p, n, 1);
    for (int padding = spec_.width - static_cast<int>(integer_end - p); padding > 0; --padding)
        *--p = spec_.zeropad ? '0' : ' ';
    if (v < 0 && *units != 0) *--p = '-';
    else if (spec_.force_sign) *--p = '+';
    p -= spec_.prefix.size();
    std::copy(spec_.prefix.begin(), spec_.prefix.end(), p);
    return p;
}

void Format::append(std::string& out, double value) const {
    // The common case of every program line: written backwards into a buffer, appended at once.
    char buffer[64];
    char* const end = buffer + sizeof buffer;
    if (const char* begin = write_backwards(end, sizeof buffer, value)) {
        out.append(begin, static_cast<std::size_t>(end - begin));
        return;
    }
    append_exact(out, scaled_value(spec_, value));
}

void Format::append_exact(std::string& out, double v) const {
    Decimal d;
    round_text(v, spec_.decimals, d);
    out += spec_.prefix;
    if (d.negative && !d.zero())
        out += '-';
    else if (spec_.force_sign)
        out += '+';
    if (d.integer_length < spec_.width)
        out.append(static_cast<size_t>(spec_.width - d.integer_length), spec_.zeropad ? '0' : ' ');
    out.append(d.digits, static_cast<size_t>(d.integer_length));
    int frac = d.fraction_length;
    if (!spec_.force_decimal)
        while (frac > 0 && d.digits[d.integer_length + frac - 1] == '0') --frac;
    if (frac > 0) {
        out += spec_.decimal_mark;
        out.append(d.digits + d.integer_length, static_cast<size_t>(frac));
    }
}

std::string Format::format(double value) const {
    std::string s;
    append(s, value);
    return s;
}

std::string Format::word(std::string_view letter, double value) const {
    std::string s(letter);
    append(s, value);
    return s;
}

double Format::rounded(double value) const {
    Decimal d = digits_of(spec_, value);
    double r = 0.0;
    std::string text(d.digits, static_cast<size_t>(d.integer_length));
    text += '.';
    text.append(d.digits + d.integer_length, static_cast<size_t>(d.fraction_length));
    std::from_chars(text.data(), text.data() + text.size(), r);
    if (d.negative) r = -r;
    if (r == 0.0) r = 0.0;  // no -0
    return r / spec_.scale;
}

Format exact_format(FormatSpec spec, double value, int max_decimals) {
    for (; spec.decimals < max_decimals; ++spec.decimals) {
        const Format f(spec);
        if (std::abs(f.rounded(value) - value) <= 1e-9 * std::max(1.0, std::abs(value))) return f;
    }
    return Format(spec);
}

bool Format::is_zero(double value) const {
    // Every feed is checked: the fast path answers without the digits.
    if (const auto units = rounded_units(scaled_value(spec_, value), spec_.decimals)) return *units == 0;
    return digits_of(spec_, value).zero();
}

Word::Word(std::string prefix, Format format, bool force)
    : prefix_(std::move(prefix)), format_(std::move(format)), force_(force) {}

std::string_view Word::compose(double value) {
    Text& spare = texts_[1 - last_];
    constexpr std::size_t size = sizeof spare.chars;
    char* const end = spare.chars + size;
    char* begin = prefix_.size() < size ? format_.write_backwards(end, size - prefix_.size(), value) : nullptr;
    spare.spilled = begin == nullptr;
    if (spare.spilled) {
        spare.spill = prefix_;
        format_.append(spare.spill, value);
        return spare.spill;
    }
    // The prefix is a letter or two: copied by hand, a call to memmove costs more.
    for (auto c = prefix_.rbegin(); c != prefix_.rend(); ++c) *--begin = *c;
    spare.begin = static_cast<unsigned char>(begin - spare.chars);
    return {begin, static_cast<std::size_t>(end - begin)};
}

std::string_view Word::take_spare() {
    last_ = 1 - last_;
    return texts_[last_].view();
}

std::string_view Word::format(double value) {
    // The same number gives the same text: no need to format it again.
    if (last_value_ && *last_value_ == value) return force_ ? texts_[last_].view() : std::string_view();
    const std::string_view text = compose(value);
    const bool unchanged = last_value_ && text == texts_[last_].view();
    last_value_ = value;
    if (unchanged && !force_) return {};
    return take_spare();
}

std::string_view Word::force(double value) {
    compose(value);
    last_value_ = value;
    return take_spare();
}

void Word::reset() { last_value_.reset(); }

void Word::set_last(double value) {
    compose(value);
    last_value_ = value;
    take_spare();
}

}  // namespace camgen::nc
