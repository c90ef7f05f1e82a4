// Number formatting (CNC-Calc createFormat / createVariable) at its edges.
#include <clocale>
#include <limits>
#include <sstream>
#include <locale>

#include <doctest/doctest.h>

#include "camgen/nc/block_writer.hpp"
#include "camgen/nc/format.hpp"

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
    // scripts/install-deps generates de_DE.UTF-8; without it this test cannot show anything.
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
        camgen::nc::BlockStyle style;
        style.sequence_numbers = true;
        style.sequence_start = 10;
        style.sequence_increment = 5;
        style.line_break = "\r\n";
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
