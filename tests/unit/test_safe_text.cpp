// Text from the job (names, tool comments, operation comments) reaches the program only as
// safe text: printable ASCII, no control bytes that could end or split a block, no comment
// terminators, no '%' inside a Fanuc program body, and a length limit.
#include <doctest/doctest.h>

#include <string>

#include "support.hpp"

using namespace camgen;

namespace {

// A job whose every text field carries what a control could read as blocks.
// A drill operation for a mill, a turn-drill for a lathe.
std::string nasty_job(MachineKind kind) {
    const std::string nasty = R"(a\u000bG0 Z-50\u000cM30\u0000 100% (x) \u007f \u00d810 Bohrung f\u00fcr M6 \u2603;)";
    const std::string op = kind == MachineKind::mill
                               ? R"("type": "drill", "endDepth": 2, "holes": [[0, 0]], )"
                               : R"("type": "turn-drill", "startDepth": 0, "endDepth": -2, "safeDistance": 1, )";
    return R"({"name": ")" + nasty + R"(", "clearance": 10,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000, "comment": ")" + nasty + R"("}],
  "operations": [{)" + op + R"("tool": 1, "comment": ")" + nasty + R"(", "plungingFeedrate": 100}]})";
}

}  // namespace

TEST_CASE("safe text: control bytes, non-ASCII, comment terminators and % never reach a program") {
    for (const auto& listed : list_machines()) {
        const std::string& name = listed.first;
        CAPTURE(name);
        const std::string text = test::post_job(nasty_job(load_machine(name).kind), name).text;
        const bool parentheses = load_machine(name).block.comment_style == nc::CommentStyle::parentheses;
        for (char c : text) {
            const unsigned char u = static_cast<unsigned char>(c);
            CHECK_MESSAGE((u == '\n' || u == '\r' || (u >= 0x20 && u < 0x7F)), "byte " << int(u));
        }
        std::istringstream lines(text);
        for (std::string line; std::getline(lines, line);) {
            // '%' only as Fanuc's tape marks, alone on a line.
            if (line.find('%') != std::string::npos) CHECK(line == "%");
            // A parenthesised comment never holds another '(' or ')'.
            const auto open = line.find('(');
            if (parentheses && open != std::string::npos) {
                CHECK(line.find('(', open + 1) == std::string::npos);
                CHECK(line.find(')') == line.size() - 1);
            }
        }
        // The text is still readable: umlauts and the diameter sign spelt out, the rest kept.
        CHECK(text.find("D10 Bohrung fuer M6") != std::string::npos);
        CHECK(text.find("100pct") != std::string::npos);
    }
}

TEST_CASE("safe text: comments are cut at the machine's commentMaxLength, else at the default limit") {
    const std::string long_comment(500, 'x');
    const std::string job = R"({"clearance": 10, "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": [{"type": "drill", "tool": 1, "comment": ")" + long_comment + R"(", "endDepth": 2,
                  "plungingFeedrate": 100, "holes": [[0, 0]]}]})";
    const std::string text = test::post_job(job, "fanuc").text;
    CHECK(text.find("(" + std::string(nc::default_comment_limit, 'x') + ")") != std::string::npos);
    CHECK(text.find(std::string(nc::default_comment_limit + 1, 'x')) == std::string::npos);
}
