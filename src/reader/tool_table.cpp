#include "camgen/reader/tool_table.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {

// The letters of LinuxCNC's tool table: tool, pocket, the offsets of each axis, diameter, and a
// lathe tool's front and back angles and orientation.
constexpr std::string_view table_letters = "TPXYZABCUVWDIJQ";

bool table_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

}  // namespace

std::map<int, double> read_tool_table(std::string_view text, const std::string& source, Units units) {
    std::map<int, double> tools;
    std::map<int, int> line_of;  // where each tool was given
    int line = 0;
    const auto fail = [&](const std::string& detail) { throw InputError("", detail, line, source); };
    while (!text.empty()) {
        ++line;
        const std::size_t nl = text.find('\n');
        std::string_view l = text.substr(0, nl);
        text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
        if (const std::size_t c = l.find(';'); c != std::string_view::npos) l = l.substr(0, c);
        std::optional<int> tool;
        double diameter = 0.0;
        bool has_diameter = false;
        std::string seen;
        std::size_t i = 0;
        while (i < l.size()) {
            if (table_blank(l[i])) {
                ++i;
                continue;
            }
            std::size_t end = i;
            while (end < l.size() && !table_blank(l[end])) ++end;
            const std::string_view word = l.substr(i, end - i);
            i = end;
            const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(word[0])));
            if (table_letters.find(letter) == std::string_view::npos)
                fail(fmt::format("\"{}\" is not a word of a tool table (T P X Y Z A B C U V W D I J Q)", word));
            if (seen.find(letter) != std::string::npos) fail(fmt::format("two {} words in one tool", letter));
            seen += letter;
            std::string_view number = word.substr(1);
            if (!number.empty() && number[0] == '+') number.remove_prefix(1);
            double v = 0.0;
            const auto [p, ec] = std::from_chars(number.data(), number.data() + number.size(), v,
                                                 std::chars_format::fixed);
            if (number.empty() || ec != std::errc() || p != number.data() + number.size() || !std::isfinite(v))
                fail(fmt::format("{}: \"{}\" is not a number", letter, word.substr(1)));
            if (letter == 'T') {
                if (v < 0 || v != std::floor(v) || v > 1e9) fail(fmt::format("{}: a tool number is a whole number, 0 or more", word));
                tool = static_cast<int>(v);
            } else if (letter == 'D') {
                if (v < 0) fail(fmt::format("{}: a diameter below 0", word));
                diameter = v * (units == Units::inch ? mm_per_inch : 1.0);
                has_diameter = true;
            }
        }
        if (seen.empty()) continue;  // a blank line or a comment
        if (!tool) fail("a tool without its number T");
        if (auto [it, fresh] = line_of.emplace(*tool, line); !fresh)
            fail(fmt::format("tool {} again (it is on line {})", *tool, it->second));
        tools[*tool] = has_diameter ? diameter : 0.0;
    }
    return tools;
}

}  // namespace camgen
