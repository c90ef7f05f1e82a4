// Every error of a job at once (issue 25, item 4): the independent errors of a job (the header,
// each tool, each operation) are reported together, in file order, each with its file, line and
// JSON path, up to 20 and then "and N more errors"; a syntax error still stops reading; an
// operation naming a tool that failed to read is not reported again; nothing is written.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

namespace camgen::test {

namespace test_all_errors {  // named: a unity build compiles several test files as one

// A drill operation on one line, with `extra` keys.
std::string drill_op(const std::string& tool, const std::string& extra = "") {
    return R"(    {"type": "drill", "tool": )" + tool + R"(, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]])" +
           extra + "}";
}

// Three independent mistakes in three operations and one in a tool; an operation that names
// the broken tool (line 12) is not reported, since its error is the tool's.
const std::string four_mistakes = R"({
  "clearance": 10,
  "tools": [
    {"number": 1, "diameter": 5, "rpm": 1000},
    {"number": 2, "diameter": -6, "rpm": 800},
    {"number": 3, "type": "end-mill", "diameter": 6, "rpm": 12000}
  ],
  "operations": [
)" + drill_op("1", R"(, "cycle": "peck")") + ",\n" +  // line 9
                                  drill_op("1") + ",\n" +  // line 10: no mistake
                                  drill_op("1", R"(, "holez": [[1, 1]])") + ",\n" +  // line 11
                                  drill_op("2") + ",\n" +                           // line 12: tool 2 failed
                                  drill_op("7") + "\n" +                            // line 13
                                  R"(  ]
})";

// The errors read_job throws for `text`: every one of an InputErrors, else the one.
std::vector<InputError> errors_of(const std::string& text, std::size_t* count = nullptr) {
    try {
        (void)read_job(text, "job.json");
    } catch (const InputErrors& e) {
        if (count) *count = e.count();
        return e.errors();
    } catch (const InputError& e) {
        if (count) *count = 1;
        return {e};
    }
    FAIL("read_job accepted:\n" << text);
    return {};
}

}  // namespace test_all_errors

using namespace test_all_errors;

TEST_CASE("every error at once: three operations and a tool, in file order, with lines and paths") {
    std::size_t count = 0;
    const std::vector<InputError> errors = errors_of(four_mistakes, &count);
    REQUIRE(errors.size() == 4);
    CHECK(count == 4);
    CHECK(errors[0].path() == "/tools/1/diameter");
    CHECK(errors[0].line() == 5);
    CHECK(errors[1].path() == "/operations/0/cycle");
    CHECK(errors[1].line() == 9);
    CHECK(errors[2].path() == "/operations/2/holez");
    CHECK(errors[2].line() == 11);
    CHECK(errors[3].path() == "/operations/4/tool");
    CHECK(errors[3].line() == 13);
    for (const InputError& e : errors) CHECK(e.source() == "job.json");

    // A library user catches them as one InputError: the first error's parts, every error in what().
    try {
        (void)read_job(four_mistakes, "job.json");
        FAIL("accepted");
    } catch (const InputError& e) {
        CHECK(e.path() == "/tools/1/diameter");
        CHECK(e.line() == 5);
        CHECK(std::string(e.what()) ==
              "job.json:5: /tools/1/diameter: a tool diameter must be > 0\n"
              "job.json:9: /operations/0/cycle: \"peck\" is not one of \"drill\", \"dwell\", \"deep\", \"chip-break\", "
              "\"tap\", \"tap-left\", \"ream\", \"bore-stop\" or \"bore-dwell\"\n"
              "job.json:11: /operations/2/holez: unknown key \"holez\" (did you mean \"holes\"?)\n"
              "job.json:13: /operations/4/tool: tool 7 is not in /tools");
    }

    // The command line prints one error a line, the first first; exit 1; nothing written.
    const std::filesystem::path dir = scratch("all-errors");
    const std::string job = (dir / "job.json").string();
    std::ofstream(job) << four_mistakes;
    const std::string output = (dir / "part.nc").string();
    const Run r = run({job, "--machine", "fanuc", "-o", output});
    CHECK(r.code == 1);
    CHECK(r.out.empty());
    CHECK_FALSE(std::filesystem::exists(output));
    const std::vector<std::string> lines = lines_of(r.err);
    REQUIRE(lines.size() == 4);
    CHECK(lines[0] == "camgen: " + job + ":5: /tools/1/diameter: a tool diameter must be > 0");
    CHECK(lines[1].starts_with("camgen: " + job + ":9: /operations/0/cycle: \"peck\" is not one of"));
    CHECK(lines[2] == "camgen: " + job + ":11: /operations/2/holez: unknown key \"holez\" (did you mean \"holes\"?)");
    CHECK(lines[3] == "camgen: " + job + ":13: /operations/4/tool: tool 7 is not in /tools");
    // verify --job reports them the same way.
    const Run v = run({"verify", "-", "--machine", "fanuc", "--job", job}, "%\nO1\nM30\n%\n");
    CHECK(v.code == 1);
    CHECK(lines_of(v.err) == lines);
}

TEST_CASE("every error at once: 25 mistakes give the first 20 and \"and 5 more errors\"") {
    std::string text = R"({
  "clearance": 10,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": [
)";
    for (int i = 0; i < 25; ++i) text += drill_op(std::to_string(100 + i)) + (i + 1 < 25 ? ",\n" : "\n");
    text += "  ]\n}\n";
    std::size_t count = 0;
    const std::vector<InputError> errors = errors_of(text, &count);
    CHECK(count == 25);
    REQUIRE(errors.size() == 20);
    for (int i = 0; i < 20; ++i) {
        CHECK(errors[i].path() == "/operations/" + std::to_string(i) + "/tool");
        CHECK(errors[i].line() == 5 + i);
    }
    const Run r = run({"-", "--machine", "fanuc"}, text);
    CHECK(r.code == 1);
    CHECK(r.out.empty());
    const std::vector<std::string> lines = lines_of(r.err);
    REQUIRE(lines.size() == 21);
    CHECK(lines[0] == "camgen: <stdin>:5: /operations/0/tool: tool 100 is not in /tools");
    CHECK(lines[19] == "camgen: <stdin>:24: /operations/19/tool: tool 119 is not in /tools");
    CHECK(lines[20] == "camgen: and 5 more errors");
}

TEST_CASE("every error at once: a syntax error stops reading and is the only error") {
    // The same mistakes as above, and a trailing comma after the last operation.
    const std::size_t end = four_mistakes.rfind("\n  ]");
    const std::string text = four_mistakes.substr(0, end) + "," + four_mistakes.substr(end);
    const Run r = run({"-", "--machine", "fanuc"}, text);
    CHECK(r.code == 1);
    CHECK(r.out.empty());
    const std::vector<std::string> lines = lines_of(r.err);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0].starts_with("camgen: <stdin>:14: "));
    std::size_t count = 0;
    CHECK(errors_of(text, &count).size() == 1);
    CHECK(count == 1);
}

TEST_CASE("every error at once: the header's errors, and what ends reading after them") {
    // A header key after the operations: its error comes last, in file order.
    const std::string late_header = R"({
  "clearance": 10,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": [
)" + drill_op("9") + R"(
  ],
  "programNumber": 0,
  "spindle": 1
})";
    std::vector<InputError> errors = errors_of(late_header);
    REQUIRE(errors.size() == 2);
    CHECK(errors[0].path() == "/operations/0/tool");
    CHECK(errors[0].line() == 5);
    // The header's first error only: an unknown key is reported before the keys are read.
    CHECK(errors[1].path() == "/spindle");
    CHECK(errors[1].line() == 8);

    // Units and clearance measure everything after them: a mistake there is the only error.
    for (const std::string& header : {std::string(R"("clearance": "high")"), std::string(R"("clearance": 10, "units": "cm")"),
                                      std::string(R"("clearence": 10)")}) {
        CAPTURE(header);
        const std::string text = "{\n  " + header + R"(,
  "tools": [{"number": 1, "diameter": -5, "rpm": 1000}],
  "operations": [
)" + drill_op("9") + R"(
  ]
})";
        errors = errors_of(text);
        REQUIRE(errors.size() == 1);
        CHECK(errors[0].line() == 2);
    }

    // A tool table that is not a table: the operations are read, those naming a tool are not
    // reported (every tool is unknown), the others are.
    errors = errors_of(R"({
  "clearance": 10,
  "tools": {"number": 1, "diameter": 5, "rpm": 1000},
  "operations": [
)" + drill_op("1") + ",\n" + R"(    {"type": "mill"}
  ]
})");
    REQUIRE(errors.size() == 2);
    CHECK(errors[0].path() == "/tools");
    CHECK(errors[1].path() == "/operations/1/type");
    CHECK(errors[1].line() == 6);
}

TEST_CASE("every error at once: an operation naming a tool that failed to read is not reported again") {
    // Tool 2 given twice: the second is the error, and an operation naming tool 2 might mean
    // either, so it is not read on (the first tool 2 is a drill; tapping with it would be an
    // error of its own otherwise).
    const std::string text = R"({
  "clearance": 10,
  "tools": [
    {"number": 2, "diameter": 5, "rpm": 1000},
    {"number": 2, "type": "tap", "diameter": 6, "rpm": 300},
    {"diameter": 4, "rpm": 1000}
  ],
  "operations": [
)" + drill_op("2", R"(, "cycle": "tap", "pitch": 1)") +
                             ",\n" + drill_op("5") + R"(
  ]
})";
    const std::vector<InputError> errors = errors_of(text);
    // The tool without a number could be tool 5: neither operation is reported.
    REQUIRE(errors.size() == 2);
    CHECK(errors[0].path() == "/tools/1/number");
    CHECK(errors[1].path() == "/tools/2/number");
}

TEST_CASE("every error at once: InputErrors keeps the first 20 and counts the rest") {
    std::vector<InputError> many;
    for (int i = 1; i <= 22; ++i) many.emplace_back("/operations/" + std::to_string(i), "bad", i, "j.json");
    const InputErrors e(many, 3);
    CHECK(e.errors().size() == 20);
    CHECK(e.count() == 25);
    CHECK(e.path() == "/operations/1");
    CHECK(e.line() == 1);
    CHECK(e.source() == "j.json");
    const std::vector<std::string> lines = lines_of(e.what());
    REQUIRE(lines.size() == 21);
    CHECK(lines[0] == "j.json:1: /operations/1: bad");
    CHECK(lines[20] == "and 5 more errors");
}

}  // namespace camgen::test
