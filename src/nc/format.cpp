#include "camgen/nc/format.hpp"

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

// Digits of |v| in fixed notation, rounded half away from zero to `decimals` places.
// Returns integer digits and fraction digits (fraction has exactly `decimals` digits).
struct Decimal {
    std::string integer;
    std::string fraction;
    bool negative = false;
};

Decimal round_decimal(double v, int decimals) {
    // Shortest round-trip representation in fixed notation: never an exponent.
    char buf[400];
    auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
    if (res.ec != std::errc()) throw std::logic_error("number too large to format");
    std::string_view text(buf, static_cast<size_t>(res.ptr - buf));
    Decimal d;
    if (!text.empty() && text.front() == '-') {
        d.negative = true;
        text.remove_prefix(1);
    }
    auto point = text.find('.');
    d.integer = std::string(text.substr(0, point));
    std::string frac = point == std::string_view::npos ? std::string() : std::string(text.substr(point + 1));
    bool round_up = frac.size() > static_cast<size_t>(decimals) && frac[static_cast<size_t>(decimals)] >= '5';
    frac.resize(static_cast<size_t>(decimals), '0');
    if (round_up) {
        std::string digits = d.integer + frac;
        int i = static_cast<int>(digits.size()) - 1;
        while (i >= 0 && digits[static_cast<size_t>(i)] == '9') digits[static_cast<size_t>(i--)] = '0';
        if (i < 0)
            digits.insert(digits.begin(), '1');
        else
            ++digits[static_cast<size_t>(i)];
        d.integer = digits.substr(0, digits.size() - static_cast<size_t>(decimals));
        frac = digits.substr(digits.size() - static_cast<size_t>(decimals));
    }
    d.fraction = std::move(frac);
    if (d.integer.empty()) d.integer = "0";
    return d;
}

bool all_zero(const Decimal& d) {
    for (char c : d.integer)
        if (c != '0') return false;
    for (char c : d.fraction)
        if (c != '0') return false;
    return true;
}

}  // namespace

void Format::append(std::string& out, double value) const {
    if (!std::isfinite(value)) throw std::logic_error("refusing to write a number that is not finite");
    double v = value * spec_.scale;
    if (!std::isfinite(v)) throw std::logic_error("refusing to write a number that is not finite");
    Decimal d = round_decimal(v, spec_.decimals);
    bool zero = all_zero(d);
    out += spec_.prefix;
    if (d.negative && !zero)
        out += '-';
    else if (spec_.force_sign)
        out += '+';
    if (static_cast<int>(d.integer.size()) < spec_.width)
        out.append(static_cast<size_t>(spec_.width) - d.integer.size(), spec_.zeropad ? '0' : ' ');
    out += d.integer;
    std::string& frac = d.fraction;
    if (!spec_.force_decimal) {
        while (!frac.empty() && frac.back() == '0') frac.pop_back();
    }
    if (!frac.empty()) {
        out += spec_.decimal_mark;
        out += frac;
    }
}

std::string Format::format(double value) const {
    std::string s;
    append(s, value);
    return s;
}

double Format::rounded(double value) const {
    Decimal d = round_decimal(value * spec_.scale, spec_.decimals);
    std::string text = d.integer + "." + d.fraction;
    double r = 0.0;
    std::from_chars(text.data(), text.data() + text.size(), r);
    if (d.negative) r = -r;
    if (r == 0.0) r = 0.0;  // no -0
    return r / spec_.scale;
}

bool Format::is_zero(double value) const {
    return all_zero(round_decimal(value * spec_.scale, spec_.decimals));
}

Word::Word(std::string prefix, Format format, bool force)
    : prefix_(std::move(prefix)), format_(std::move(format)), force_(force) {}

std::string Word::format(double value) {
    std::string text = prefix_;
    format_.append(text, value);
    last_value_ = value;
    if (!force_ && text == last_text_) return {};
    last_text_ = text;
    return text;
}

std::string Word::force(double value) {
    std::string text = prefix_;
    format_.append(text, value);
    last_value_ = value;
    last_text_ = text;
    return text;
}

void Word::reset() {
    last_text_.clear();
    last_value_.reset();
}

void Word::set_last(double value) {
    last_text_ = prefix_;
    format_.append(last_text_, value);
    last_value_ = value;
}

}  // namespace camgen::nc
