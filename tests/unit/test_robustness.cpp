// Bad numbers anywhere in a job: camgen either posts a program or raises an InputError. It
// never crashes, hangs, throws anything else, or writes NaN, an exponent or -0.
#include <filesystem>
#include <random>
#include <set>
#include <cctype>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <doctest/doctest.h>

#include "camgen/reader/reader.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_robustness {

using namespace camgen;
using namespace camgen::test;

namespace {

// Pointers to every number in a JSON value, except counts that only make a job larger.
void numbers(const nlohmann::json& j, const std::string& path, std::vector<std::string>& out) {
    if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            static const std::set<std::string> skip{"count", "countX", "countY", "turns", "number", "tool"};
            if (!skip.count(it.key())) numbers(it.value(), path + "/" + it.key(), out);
        }
    } else if (j.is_array()) {
        for (size_t i = 0; i < j.size(); ++i) numbers(j[i], path + "/" + std::to_string(i), out);
    } else if (j.is_number()) {
        out.push_back(path);
    }
}

}  // namespace

TEST_CASE("the bad-number scanner finds exponents, minus zero and NaN") {
    CHECK(bad_number("G1 X12.5 Y-0.5 F100\n").empty());
    CHECK(bad_number("G1 X1e+06\n") == "X1e+");
    CHECK(bad_number("F1.18e6\n") == "F1.18e6");
    CHECK(bad_number("G1 X-0 Y1\n") == "X-0");
    CHECK(bad_number("G1 Z-0.000\n") == "Z-0.000");
    CHECK(bad_number("Q201=-0 ;DEPTH\n") == "=-0");
    CHECK(bad_number("G1 X-0.001\n").empty());
    CHECK(bad_number("G1 Xnan\n") == "nan");
    CHECK(bad_number("; tool information\n").empty());
}

TEST_CASE("mutated samples: a program or an InputError, never anything else") {
    const double values[] = {0.0, -0.0, -1.0, 0.0004, -0.0004, 1e-9, 7.25, 359.9999, 1e6, -1e6, 1e300};
    std::vector<std::string> machines;
    for (const auto& [name, description] : list_machines()) machines.push_back(name);
    std::mt19937 rng(2026);
    int posted = 0, rejected = 0;
    for (const char* sample : {"plate", "bracket", "drilling", "arcs"}) {
        nlohmann::json original =
            nlohmann::json::parse(read_file(std::string(CAMGEN_SOURCE_DIR "/samples/") + sample + ".json"));
        std::vector<std::string> leaves;
        numbers(original, "", leaves);
        for (int round = 0; round < 60; ++round) {
            nlohmann::json job = original;
            for (int k = 0; k < 2; ++k) {
                auto pointer = nlohmann::json::json_pointer(leaves[rng() % leaves.size()]);
                job[pointer] = values[rng() % std::size(values)];
            }
            std::string text = job.dump();
            for (const std::string& machine : machines) {
                CAPTURE(sample);
                CAPTURE(machine);
                CAPTURE(text);
                try {
                    Posted p = post_job(text, machine);
                    ++posted;
                    std::string bad = bad_number(p.text);
                    CHECK_MESSAGE(bad.empty(), "bad number: " << bad);
                } catch (const InputError&) {
                    ++rejected;
                }
            }
        }
    }
    // Both outcomes really happened, so the loop exercised the posts and the checks.
    CHECK(posted > 100);
    CHECK(rejected > 100);
}

TEST_CASE("limits: JSON nested deeper than 64 levels is refused at once, naming the line and column") {
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    const test::Run r = test::run({"-", "--machine", "fanuc"}, deep);
    CHECK(r.code == 1);
    CHECK(r.err.find("<stdin>:1: line 1, column 65: arrays and objects nested deeper than 64 levels") != std::string::npos);
    // Brackets inside strings do not count.
    const std::string in_string = R"({"name": ")" + std::string(1000, '[') + R"(", "clearance": 10, "tools": [{"number": 1, "diameter": 3, "rpm": 1000}], "operations": []})";
    CHECK(test::run({"-", "--machine", "fanuc"}, in_string).code == 0);
    // Nor after an escaped quote; an escaped backslash ends before the string's own quote.
    const std::string escaped = R"({"name": "a\"b)" + std::string(1000, '[') + R"(c\\", "clearance": 10, "tools": [{"number": 1, "diameter": 3, "rpm": 1000}], "operations": []})";
    CHECK(test::run({"-", "--machine", "fanuc"}, escaped).code == 0);
    const std::string deep_after = R"({"name": "a\\", "x": )" + std::string(100, '[') + std::string(100, ']') + "}";
    CHECK(test::run({"-", "--machine", "fanuc"}, deep_after).err.find("line 1, column 85: arrays and objects nested deeper than 64 "
                                                                      "levels") != std::string::npos);
}

TEST_CASE("limits: the holes of all operations together are counted before they are made; --max-holes raises it") {
    const auto job = [](int count) {
        return R"({"clearance": 10, "tools": [{"number": 1, "diameter": 3, "rpm": 1000}], "operations": [
          {"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100, "holes": [[0, 0], [1, 0]]},
          {"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100,
           "line": {"start": [0, 5], "end": [10, 5], "count": )" + std::to_string(count) + "}}]}";
    };
    const test::Run over = test::run({"-", "--machine", "fanuc", "--max-holes", "5"}, job(4));
    CHECK(over.code == 1);
    CHECK(over.err.find("/operations/1/line/count: the job would have more than 5 holes (4 here, 2 before); raise the "
                        "limit with --max-holes") != std::string::npos);
    CHECK(test::run({"-", "--machine", "fanuc", "--max-holes", "6"}, job(4)).code == 0);
    CHECK(test::run({"-", "--machine", "fanuc"}, job(4)).code == 0);
    // 40 grids of 10 million holes: refused with a message, not std::bad_alloc.
    std::string grids = R"({"clearance": 10, "tools": [{"number": 1, "diameter": 3, "rpm": 1000}], "operations": [)";
    for (int i = 0; i < 40; ++i)
        grids += std::string(i ? "," : "") + R"({"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100,
          "grid": {"origin": [0, 0], "countX": 10000, "countY": 1000, "spacingX": 1, "spacingY": 1}})";
    grids += "]}";
    const test::Run many = test::run({"-", "--machine", "fanuc", "--max-holes", "1000"}, grids);
    CHECK(many.code == 1);
    CHECK(many.err.find("/operations/0/grid: the job would have more than 1000 holes") != std::string::npos);
}

// The memory (MiB, at most 255) that reading `job` under `limits` took at its peak, measured
// in a child process so that nothing else the tests did counts; 255 when reading did not end
// in an InputError.
int mib_to_refuse(const std::string& job, JobLimits limits) {
    const pid_t child = fork();
    if (child == 0) {
        rusage before{};
        getrusage(RUSAGE_SELF, &before);
        bool refused = false;
        try {
            read_job(job, "big.json", limits);
        } catch (const InputError&) {
            refused = true;
        } catch (...) {
        }
        rusage after{};
        getrusage(RUSAGE_SELF, &after);
        const long mib = (after.ru_maxrss - before.ru_maxrss) / 1024;  // ru_maxrss is in KiB
        _exit(refused ? static_cast<int>(std::min(mib, 254L)) : 255);
    }
    int status = 0;
    waitpid(child, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 255;
}

TEST_CASE("limits: a job over the hole limit is refused before any pattern makes its holes") {
    // Ten million holes in the first operation (160 MB as points), then one over the limit.
    const std::string job = R"({"clearance": 10, "tools": [{"number": 1, "diameter": 3, "rpm": 1000}], "operations": [
      {"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100,
       "grid": {"origin": [0, 0], "countX": 10000, "countY": 1000, "spacingX": 1, "spacingY": 1}},
      {"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100, "holes": [[0, 0]]}]})";
    JobLimits limits;
    limits.holes = 10'000'000;
    CHECK_THROWS_WITH_AS(read_job(job, "big.json", limits),
                         doctest::Contains("/operations/1/holes: the job would have more than 10000000 holes"), InputError);
    CHECK(mib_to_refuse(job, limits) < 20);
}

TEST_CASE("limits: contour path elements are counted; --max-elements raises the limit") {
    const std::string job = R"({"clearance": 10, "tools": [{"number": 1, "diameter": 3, "rpm": 1000}], "operations": [
      {"type": "path", "tool": 1, "z": -1, "feed": 100, "start": [0, 0],
       "path": [{"line": [10, 0]}, {"line": [10, 10]}, {"line": [0, 10]}]}]})";
    const test::Run over = test::run({"-", "--machine", "fanuc", "--max-elements", "2"}, job);
    CHECK(over.code == 1);
    CHECK(over.err.find("/operations/0/path: the job would have more than 2 path elements") != std::string::npos);
    CHECK(test::run({"-", "--machine", "fanuc", "--max-elements", "3"}, job).code == 0);
}

TEST_CASE("readers: huge codes and numbers are errors naming the line, never undefined behaviour") {
    struct Case {
        const char* machine;
        std::string program;
    };
    const Case cases[] = {
        {"fanuc", "%\nO1000\nN10 G444444444\n%\n"},
        {"fanuc", "%\nO1000\nN10 M99999999999999999999\n%\n"},
        {"linuxcnc", "%\nG1e300\n%\n"},
        {"grbl", "(Insert tool 99999999999999999999)\nM0\n"},
        {"wabeco", "_\n_\nG90\nM01 Insert tool 99999999999999999999\n"},
        {"heidenhain", "0 BEGIN PGM x MM\n1 CYCL DEF 200 DRILLING ~\n  Q99999999999999999999=+1 ;X\n2 END PGM x MM\n"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.machine);
        CAPTURE(c.program);
        const Machine m = load_machine(c.machine);
        CHECK_THROWS_AS(read_program(c.program, m, "p"), InputError);
    }
}

}  // namespace test_robustness
