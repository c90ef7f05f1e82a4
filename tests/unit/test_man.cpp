// The man page (camgen --man, installed as camgen.1) lists exactly the options and subcommands
// --help lists, with the same names, arguments and descriptions.
#include <doctest/doctest.h>

#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "tests/unit/support.hpp"

namespace camgen {
namespace test_man {  // named: a unity build compiles several test files as one

using test::lines_of;
using test::run;

// One entry of a help text: "-m,--machine TEXT" and its description.
using Entry = std::pair<std::string, std::string>;

// The entries of the Positionals and Options sections of `--help` output. CLI11 writes each
// as "  NAMES ARGS  DESCRIPTION", the description on the next line when NAMES ARGS is long.
std::vector<Entry> help_entries(const std::string& help) {
    std::vector<Entry> entries;
    bool in_section = false;
    for (const std::string& line : lines_of(help)) {
        if (line == "Positionals:" || line == "Options:") in_section = true;
        else if (!line.empty() && line[0] != ' ') in_section = false;
        if (!in_section || line.size() < 3 || line[0] != ' ') continue;
        const auto start = line.find_first_not_of(' ');
        const auto gap = line.find("  ", start);
        if (start > 2 && !entries.empty() && entries.back().second.empty()) {
            entries.back().second = line.substr(start);  // a description on its own line
            continue;
        }
        std::string names = line.substr(start, gap == std::string::npos ? std::string::npos : gap - start);
        std::string description;
        if (gap != std::string::npos) description = line.substr(line.find_first_not_of(' ', gap));
        entries.emplace_back(names, description);
    }
    return entries;
}

// The man page as text: roff's escapes and font changes undone.
std::string unroff(std::string text) {
    text = std::regex_replace(text, std::regex(R"(\\f[BIR])"), "");
    text = std::regex_replace(text, std::regex(R"(\\&)"), "");
    text = std::regex_replace(text, std::regex(R"(\\-)"), "-");
    return std::regex_replace(text, std::regex(R"(\\e)"), "\\");
}

// The tagged paragraphs (.TP: tag line, text line) of one section or subsection of the page,
// from the heading that starts with `heading` to the next heading.
std::vector<Entry> man_entries(const std::string& page, const std::string& heading) {
    std::vector<Entry> entries;
    const std::vector<std::string> lines = lines_of(page);
    bool in_section = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].starts_with(".SH") || lines[i].starts_with(".SS")) in_section = lines[i].starts_with(heading);
        if (in_section && lines[i] == ".TP" && i + 2 < lines.size()) entries.emplace_back(lines[i + 1], lines[i + 2]);
    }
    return entries;
}

TEST_CASE("man: the page lists every option of --help, and only those, as --help names and describes them") {
    const test::Run man = run({"--man"});
    REQUIRE(man.code == 0);
    const std::string page = unroff(man.out);
    CHECK(page.starts_with(".TH CAMGEN 1"));
    const std::vector<std::pair<std::vector<std::string>, std::string>> commands = {
        {{"--help"}, ".SH OPTIONS"}, {{"verify", "--help"}, ".SS \"camgen verify\""}, {{"schema", "--help"}, ".SS \"camgen schema\""}};
    for (const auto& [args, heading] : commands) {
        CAPTURE(heading);
        const test::Run help = run(args);
        REQUIRE(help.code == 0);
        const std::vector<Entry> expected = help_entries(help.out);
        REQUIRE(expected.size() >= 2);
        CHECK(man_entries(page, heading) == expected);
    }
    // The subcommands --help lists, each with its description.
    const test::Run help = run({"--help"});
    for (const std::string sub : {"verify", "schema"}) CHECK(page.find(".SS \"camgen " + sub + "\"") != std::string::npos);
    CHECK(help_entries(help.out).front().first == "job TEXT");
    // The hidden --man itself is not documented, as --help does not show it.
    CHECK(help.out.find("--man") == std::string::npos);
    CHECK(page.find("--man") == std::string::npos);
}

TEST_CASE("man: option text that roff would read as requests or escapes is written literally") {
    const std::string page = run({"--man"}).out;
    for (const std::string& line : lines_of(page)) {
        CAPTURE(line);
        // Only the page's own requests start with '.'; text never starts with ' (a request too).
        if (line.starts_with(".")) CHECK(std::regex_match(line, std::regex(R"(\.(TH|SH|SS|TP|PP|br|nf|fi)( .*)?)")));
        CHECK_FALSE(line.starts_with("'"));
        // Every backslash starts one of the escapes the page uses.
        CHECK(std::regex_match(line, std::regex(R"(([^\\]|\\[-e&]|\\f[BIR])*)")));
    }
}

}  // namespace test_man
}  // namespace camgen
