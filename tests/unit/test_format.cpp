// Number formatting (CNC-Calc createFormat / createVariable) at its edges.
#include <charconv>
#include <clocale>
#include <cmath>
#include <random>
#include <limits>
#include <sstream>
#include <locale>

#include <doctest/doctest.h>

#include "camgen/nc/block_writer.hpp"
#include "camgen/nc/format.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_format {

using camgen::nc::Format;
using camgen::nc::FormatSpec;
using camgen::nc::Word;

namespace {
Format fmt3(bool force = false) {
    FormatSpec s;
    s.decimals = 3;
    s.force_decimal = force;
    return Format(s);
}
}  // namespace

TEST_CASE("never -0: values that round to zero lose their sign") {
    CHECK(fmt3().format(-0.0004) == "0");
    CHECK(fmt3(true).format(-0.0004) == "0.000");
    CHECK(fmt3().format(-0.0) == "0");
    CHECK(fmt3().format(-0.0005) == "-0.001");  // half away from zero
}

TEST_CASE("never an exponent, at either end of the range") {
    CHECK(fmt3().format(1e-9) == "0");
    FormatSpec fine;
    fine.decimals = 12;
    CHECK(Format(fine).format(1e-9) == "0.000000001");
    CHECK(fmt3().format(1e12) == "1000000000000");
    CHECK(fmt3().format(-1e15) == "-1000000000000000");
    CHECK(fmt3().format(1.18e6) == "1180000");
}

TEST_CASE("rounding is half away from zero on the decimal value as written") {
    // 2.0005 is 2.000499999... in binary; camgen rounds the number as a person wrote it.
    CHECK(fmt3().format(2.0005) == "2.001");
    CHECK(fmt3().format(-2.0005) == "-2.001");
    CHECK(fmt3().format(2.0004999) == "2");
    CHECK(fmt3().format(9.9996) == "10");
    CHECK(fmt3(true).format(9.9996) == "10.000");
    CHECK(fmt3().format(0.1 + 0.2) == "0.3");
    CHECK(fmt3().rounded(2.0005) == doctest::Approx(2.001).epsilon(1e-12));
}

TEST_CASE("createFormat fields: forceDecimal, decimal comma, zero padding, sign, scale, prefix") {
    CHECK(fmt3(true).format(3) == "3.000");
    CHECK(fmt3().format(3) == "3");
    CHECK(fmt3().format(12.5) == "12.5");
    FormatSpec comma;
    comma.decimals = 2;
    comma.decimal_mark = ',';
    CHECK(Format(comma).format(12.53) == "12,53");
    FormatSpec pad;
    pad.width = 4;
    pad.zeropad = true;
    CHECK(Format(pad).format(1) == "0001");
    CHECK(Format(pad).format(-12) == "-0012");
    pad.zeropad = false;
    CHECK(Format(pad).format(7) == "   7");
    FormatSpec sign;
    sign.decimals = 2;
    sign.force_sign = true;
    CHECK(Format(sign).format(4.25) == "+4.25");
    CHECK(Format(sign).format(-4.25) == "-4.25");
    CHECK(Format(sign).format(-0.001) == "+0");
    FormatSpec feed;
    feed.decimals = 1;
    feed.scale = 1.0 / 6.0;  // mm/min -> 0.1 mm/s
    CHECK(Format(feed).format(100) == "16.7");
    CHECK(Format(feed).format(6000) == "1000");
    FormatSpec g;
    g.prefix = "G";
    g.width = 2;
    g.zeropad = true;
    g.decimals = 1;
    CHECK(Format(g).format(1) == "G01");
    CHECK(Format(g).format(33.1) == "G33.1");
}

TEST_CASE("a format refuses NaN and infinity instead of writing them") {
    CHECK_THROWS_AS(fmt3().format(std::numeric_limits<double>::quiet_NaN()), std::logic_error);
    CHECK_THROWS_AS(fmt3().format(std::numeric_limits<double>::infinity()), std::logic_error);
}

TEST_CASE("the process locale does not change the output") {
    std::locale previous;
    const char* c_previous = std::setlocale(LC_ALL, nullptr);
    std::string saved = c_previous ? c_previous : "C";
    // scripts/install-deps --tests generates de_DE.UTF-8; without it this test cannot show anything.
    REQUIRE_NOTHROW(std::locale::global(std::locale("de_DE.UTF-8")));
    std::setlocale(LC_ALL, "de_DE.UTF-8");
    CHECK(fmt3().format(12.53) == "12.53");
    CHECK(fmt3(true).format(1234567.5) == "1234567.500");
    std::locale::global(previous);
    std::setlocale(LC_ALL, saved.c_str());
}

TEST_CASE("a modal word compares the formatted text, not the number") {
    Word x("X", fmt3());
    CHECK(x.format(1.0001) == "X1");
    CHECK(x.format(1.0002) == "");  // same text: modal, not written
    CHECK(x.last() == doctest::Approx(1.0002));
    CHECK(x.format(1.001) == "X1.001");
    x.reset();
    CHECK(x.format(1.001) == "X1.001");  // the control's state was unknown: written again
    x.set_last(5);
    CHECK(x.format(5) == "");            // recorded as known without being written
    CHECK(x.force(5) == "X5");
    Word f("F", fmt3(), true);
    CHECK(f.format(100) == "F100");
    CHECK(f.format(100) == "F100");      // force: always written
}

TEST_CASE("block writer: sequence numbers, separator, line break, comments") {
    std::ostringstream out;
    {
        camgen::nc::BlockStyle style{
            .line_break = "\r\n", .sequence_numbers = true, .sequence_start = 10, .sequence_increment = 5};
        camgen::nc::BlockWriter w(style, out);
        w.add("G0").add("").add("X1").end();
        w.end();  // empty block: nothing
        w.comment("drill (6 mm)");
        w.add("M30").end();
        w.raw("%");
    }
    CHECK(out.str() == "N10 G0 X1\r\n(drill [6 mm])\r\nN15 M30\r\n%\r\n");
    std::ostringstream semi;
    {
        camgen::nc::BlockStyle style;
        style.comment_style = camgen::nc::CommentStyle::semicolon;
        style.separator = "";
        camgen::nc::BlockWriter w(style, semi);
        w.add("G1").add("X2").end();
        w.comment("line one\nline two");
    }
    CHECK(semi.str() == "G1X2\n; line one line two\n");
}

TEST_CASE("block writer: a comment or raw line while a block is built comes before the block") {
    // The block is built in the output buffer itself: what interrupts it must not split it.
    std::ostringstream out;
    {
        camgen::nc::BlockStyle style{.sequence_numbers = true, .sequence_start = 10, .sequence_increment = 10};
        camgen::nc::BlockWriter w(style, out);
        w.add("G1").add("X1");
        w.comment("between");
        w.add("Y2");
        w.raw("%");
        w.add("F100").end();
        w.add("M30").end();
    }
    CHECK(out.str() == "(between)\n%\nN10 G1 X1 Y2 F100\nN20 M30\n");
}

TEST_CASE("block writer: flushing hands over finished blocks only; an unfinished block is dropped") {
    std::ostringstream out;
    {
        camgen::nc::BlockWriter w(camgen::nc::BlockStyle{}, out);
        w.add("G0").add("Z5").end();
        w.add("G1").add("Z-1");
        w.flush();
        CHECK(out.str() == "G0 Z5\n");
        w.add("F100").end();
        w.flush();
        CHECK(out.str() == "G0 Z5\nG1 Z-1 F100\n");
        w.add("X1");  // never ended: a post that failed halfway through a block
    }
    CHECK(out.str() == "G0 Z5\nG1 Z-1 F100\n");
}

TEST_CASE("a modal word's text stays valid until the word writes again, whatever its length") {
    Word x("X", fmt3()), y("Y", fmt3());
    const std::string_view a = x.format(1.5);
    const std::string_view b = y.format(2.5);
    CHECK(a == "X1.5");  // another word's text does not disturb it
    CHECK(b == "Y2.5");
    // Texts longer than a short string's own storage, through the exact path too.
    const std::string long_prefix(40, 'P');
    Word w(long_prefix, fmt3(true));
    CHECK(w.format(1e20) == long_prefix + "100000000000000000000.000");
    CHECK(w.format(1e20 + 1) == "");  // the same text: modal
    CHECK(w.format(2.0005) == long_prefix + "2.001");
    CHECK(w.format(2.0005000001) == "");
    CHECK(w.force(2.0005) == long_prefix + "2.001");
    w.reset();
    CHECK(w.format(2.0005) == long_prefix + "2.001");
    CHECK(w.last() == 2.0005);
    // The same text from the exact path (a written half) and from the fast one is unchanged.
    Word z("Z", fmt3());
    CHECK(z.format(2.0005) == "Z2.001");
    CHECK(z.format(2.001) == "");
    CHECK(z.format(-1e12) == "Z-1000000000000");
    CHECK(z.format(-1e12 - 0.0001) == "");
    CHECK(z.format(1.25) == "Z1.25");
    Word copy = z;  // a copy's texts are its own
    CHECK(z.force(3) == "Z3");
    CHECK(copy.force(1.25) == "Z1.25");
    CHECK(copy.format(3) == "Z3");
}

namespace {

// Reference rounding for the property test: round the shortest decimal text of v half away
// from zero at `decimals`, by digit arithmetic on the text; trailing zeros stripped.
std::string reference_format(double v, int decimals) {
    char buf[400];
    auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
    std::string t(buf, r.ptr);
    bool neg = t[0] == '-';
    if (neg) t.erase(0, 1);
    auto dot = t.find('.');
    std::string ip = t.substr(0, dot), fp = dot == std::string::npos ? "" : t.substr(dot + 1);
    fp.resize(std::max<size_t>(fp.size(), static_cast<size_t>(decimals) + 1), '0');
    bool up = fp[static_cast<size_t>(decimals)] >= '5';
    std::string digits = ip + fp.substr(0, static_cast<size_t>(decimals));
    if (up) {
        int i = static_cast<int>(digits.size()) - 1;
        for (; i >= 0 && digits[static_cast<size_t>(i)] == '9'; --i) digits[static_cast<size_t>(i)] = '0';
        if (i < 0) digits.insert(0, "1"); else ++digits[static_cast<size_t>(i)];
    }
    std::string ipart = digits.substr(0, digits.size() - static_cast<size_t>(decimals));
    std::string fpart = digits.substr(digits.size() - static_cast<size_t>(decimals));
    while (!fpart.empty() && fpart.back() == '0') fpart.pop_back();
    while (ipart.size() > 1 && ipart[0] == '0') ipart.erase(0, 1);
    std::string out = ipart + (fpart.empty() ? "" : "." + fpart);
    if (neg && out != "0") out = "-" + out;
    return out;
}

}  // namespace

TEST_CASE("property: the fast path rounds exactly like the decimal text of the value") {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-6, 8), decimals(0, 6), ties(0, 3);
    int mismatches = 0;
    for (int i = 0; i < 200000; ++i) {
        int dec = decimals(rng);
        double v = mantissa(rng) * std::pow(10.0, exponent(rng));
        // A quarter of the cases sit exactly on a written half (x.xxx5), the hard case.
        if (ties(rng) == 0) v = (std::round(v * std::pow(10.0, dec)) + 0.5 * (v < 0 ? -1 : 1)) / std::pow(10.0, dec);
        FormatSpec s;
        s.decimals = dec;
        std::string got = Format(s).format(v);
        std::string want = reference_format(v, dec);
        if (got != want && mismatches++ == 0) {
            CAPTURE(v);
            CAPTURE(dec);
            CHECK(got == want);
        }
    }
    CHECK(mismatches == 0);
}

TEST_CASE("property: every field of a format decorates the same rounded number") {
    // The fast path (write_backwards) writes sign, padding, decimals and mark itself: each
    // combination must give the text of the rounded number (reference_format) laid out as the
    // fields say.
    std::mt19937_64 rng(777);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-5, 7), decimals(0, 5), coin(0, 1), widths(0, 5);
    int written_backwards = 0;
    for (int i = 0; i < 50000; ++i) {
        FormatSpec s;
        s.decimals = decimals(rng);
        s.force_decimal = coin(rng) == 1;
        s.force_sign = coin(rng) == 1;
        s.zeropad = coin(rng) == 1;
        s.width = widths(rng);
        s.decimal_mark = coin(rng) == 1 ? ',' : '.';
        if (coin(rng) == 1) s.prefix.push_back('X');
        // Now and then a prefix or width longer than the fast path's buffer.
        if (i % 97 == 0) s.prefix.append(120, 'P');
        if (i % 89 == 0) s.width = 100;
        const double v = mantissa(rng) * std::pow(10.0, exponent(rng));
        std::string text = reference_format(v, s.decimals);
        const bool negative = text[0] == '-';
        if (negative) text.erase(0, 1);
        const auto point = text.find('.');
        std::string integer = text.substr(0, point), fraction = point == std::string::npos ? "" : text.substr(point + 1);
        if (s.force_decimal) fraction.resize(static_cast<std::size_t>(s.decimals), '0');
        if (static_cast<int>(integer.size()) < s.width)
            integer.insert(0, static_cast<std::size_t>(s.width) - integer.size(), s.zeropad ? '0' : ' ');
        // Appended piece by piece: gcc 12's -Wrestrict misreads a chain of + on strings.
        std::string want = s.prefix;
        if (negative) want += '-';
        else if (s.force_sign) want += '+';
        want += integer;
        if (!fraction.empty()) {
            want += s.decimal_mark;
            want += fraction;
        }
        const std::string got = Format(s).format(v);
        if (got != want) {
            CAPTURE(v);
            CAPTURE(s.decimals);
            CAPTURE(s.width);
            REQUIRE(got == want);
        }
        // write_backwards, where it writes at all, writes the same text, in any room it takes.
        char buffer[200];
        const std::size_t room = i % 3 == 0 ? sizeof buffer : static_cast<std::size_t>(30 + i % 40);
        char* const end = buffer + room;
        if (const char* begin = Format(s).write_backwards(end, room, v)) {
            ++written_backwards;
            const std::string_view text(begin, static_cast<std::size_t>(end - begin));
            if (text != want) {
                CAPTURE(v);
                CAPTURE(s.decimals);
                CAPTURE(room);
                REQUIRE(text == want);
            }
        }
    }
    // Nearly every case is in its range: the comparison is not vacuous.
    CHECK(written_backwards > 40000);
}

}  // namespace test_format
