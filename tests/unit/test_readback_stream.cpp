// The read-back as a stream: a program read from a stream gives the events of the text read
// whole; the comparison with a job reads the program only as far as it needs; the drawing of a
// large program is thinned beyond BackplotOptions::exact and says so. (That the streamed
// statistics, comparison and drawing equal the committed ones: tests/readback; that verify's
// memory does not grow with the program: tests/memory.)
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "camgen/analysis/backplot.hpp"
#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_readback_stream {

using namespace camgen;

namespace {

// A drill job of `n` holes in rows of 20, 5 mm apart, each row `row` mm above the last (a
// hundredth of a millimetre: every row is drawn on the first one's pixels).
std::string grid_job(int n, double row = 5.0) {
    std::string holes;
    for (int i = 0; i < n; ++i) holes += fmt::format("{}[{}, {}]", i ? ", " : "", i % 20 * 5, i / 20 * row);
    return fmt::format(R"({{"name": "grid", "clearance": 10, "tools": [{{"number": 1, "diameter": 3, "rpm": 2000}}],
      "operations": [{{"type": "drill", "tool": 1, "endDepth": 3, "plungingFeedrate": 100, "holes": [{}]}}]}})",
                       holes);
}

// Each event as its JSON and line, for comparing two readings.
struct Events : ReadEventSink {
    std::vector<std::string> seen;
    bool finished = false;
    void read_event(const ReadEvent& e) override { seen.push_back(fmt::format("{} {}", e.line, event_to_json(e.event))); }
    void finish() override { finished = true; }
};

std::vector<std::string> as_text(const std::vector<ReadEvent>& events) {
    std::vector<std::string> out;
    for (const ReadEvent& e : events) out.push_back(fmt::format("{} {}", e.line, event_to_json(e.event)));
    return out;
}

}  // namespace

TEST_CASE("stream read: a program read from a stream gives the events of its text read whole") {
    const Machine m = load_machine("fanuc");
    std::string program = test::post_job(grid_job(30), "fanuc").text;
    SUBCASE("as written") {}
    // A line longer than a block of the stream (64 KiB), lines ending in CR LF, no last line
    // break: none of them moves an event or a line number.
    SUBCASE("a long comment line") { program = test::replace_once(program, "(T1 ", "(" + std::string(70000, 'x') + ")\n(T1 "); }
    SUBCASE("CR LF") {
        std::string crlf;
        for (char c : program) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
        program = crlf;
    }
    SUBCASE("no last line break") { program.pop_back(); }
    const std::vector<std::string> whole = as_text(read_program(program, m, "p"));
    std::istringstream in(program);
    Events streamed;
    ProgramReader reader(in, m, "p", streamed);
    int lines = 0;
    while (reader.advance()) ++lines;
    CHECK_FALSE(reader.advance());
    CHECK(streamed.finished);
    CHECK(lines == static_cast<int>(std::count(program.begin(), program.end(), '\n') + (program.back() != '\n')));
    CHECK(streamed.seen == whole);
}

TEST_CASE("stream read: an error in a streamed program names its line, as read whole") {
    const Machine m = load_machine("fanuc");
    const std::string program = test::replace_once(test::post_job(grid_job(30), "fanuc").text, " G80\n", " G80 Q7\n");
    const std::string whole = test::error_of(program, "fanuc");
    REQUIRE_FALSE(whole.empty());
    std::istringstream in(program);
    Events streamed;
    ProgramReader reader(in, m, "prog.nc", streamed);
    CHECK_THROWS_WITH(reader.read_all(), whole.c_str());
}

TEST_CASE("stream compare: the job leads and the program is read only as far as its first difference") {
    const Machine m = load_machine("grbl");
    const std::string job_json = grid_job(200);
    const std::string program = test::post_job(job_json, "grbl").text;
    const Trace expected = trace_expected(expand_job(read_job(job_json, "job.json")), m);
    // The third hole is drilled 1 mm off.
    std::string off = program;
    off.replace(off.find("\nX10\n"), 5, "\nX11\n");
    const Trace wrong = trace_program(read_program(off, m, "p"), m);
    const Trace right = trace_program(read_program(program, m, "p"), m);
    for (const Trace* actual : {&wrong, &right}) {
        std::size_t pulled = 0;
        TraceComparer* comparer = nullptr;
        TraceComparer c(compare_tolerance(m), [&] {
            if (pulled < actual->steps.size()) {
                comparer->actual().step(actual->steps[pulled++]);
                return true;
            }
            if (pulled++ == actual->steps.size()) comparer->actual().finish({});
            return false;
        });
        comparer = &c;
        std::size_t fed = 0;
        for (const Step& s : expected.steps) {
            c.expected().step(s);
            ++fed;
            // The program is never far ahead of the job: a hole's steps at most.
            CHECK(pulled <= fed + 20);
        }
        c.expected().finish({});
        REQUIRE(c.decided());
        if (actual == &wrong) {
            REQUIRE(c.mismatch());
            CHECK(c.mismatch()->message.find("X10.000 Y0.000") != std::string::npos);
            CHECK(pulled < actual->steps.size() / 10);  // decided at the third hole of 200
        } else {
            CHECK_FALSE(c.mismatch());
            CHECK(pulled == actual->steps.size() + 1);
        }
        // compare_traces, built on the same comparer, agrees.
        CHECK(compare_traces(expected, *actual, compare_tolerance(m)).has_value() == (actual == &wrong));
    }
}

TEST_CASE("stream plot: beyond `exact` elements of a kind the drawing is thinned and says so; up to it, it is not") {
    const Machine m = load_machine("fanuc");
    const Trace trace = trace_program(read_program(test::post_job(grid_job(400, 0.01), "fanuc").text, m, "p"), m);
    const ProgramStats stats = compute_stats(trace, m);
    BackplotOptions options{"p.nc", m.name, m.kind};
    options.exact = std::numeric_limits<std::size_t>::max();
    const std::string full = backplot_svg(trace, stats, options);
    options.exact = 400;  // every kind has at most 400 elements: nothing is thinned
    CHECK(backplot_svg(trace, stats, options) == full);
    options.exact = 50;
    const std::string thin = backplot_svg(trace, stats, options);
    CHECK(full.find("are left out where") == std::string::npos);
    CHECK(thin.find("are left out where they would cover drawn pixels only") != std::string::npos);
    CHECK(thin.find("349 holes after the first 50 have no number") != std::string::npos);
    CHECK(thin.size() < full.size() / 2);
    // The last hole keeps its number; the 51st has none.
    CHECK(thin.find(">400</tspan>") != std::string::npos);
    CHECK(thin.find(">51</tspan>") == std::string::npos);
    // Marked holes (besides the work zero and the key): all 400 in full, the first 50 thinned.
    auto circles = [](const std::string& svg) {
        std::size_t n = 0;
        for (auto at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++n;
        return n;
    };
    CHECK(circles(full) == 402);
    CHECK(circles(thin) == 52);
}

TEST_CASE("stream plot: a plunge at a hole's place is the hole's, one beside it in the same column is marked") {
    // Holes in columns (equal X, as a grid has them; drilled downwards, so that the lookup must
    // sort them), plunges at each of them and between them.
    Trace trace;
    auto plunge = [&](double x, double y) {
        Step down;
        down.kind = StepKind::feed;
        down.tool = 1;
        down.feed = 100;
        down.from = {x, y, 2};
        down.to = {x, y, -3};
        trace.steps.push_back(down);
    };
    for (int column = 0; column < 3; ++column)
        for (int row = 49; row >= 0; --row) trace.holes.push_back({{column * 10.0, row * 2.0}, -3, 1, 0});
    for (const Hole& h : trace.holes) plunge(h.at.x, h.at.y);
    plunge(10, 2.0000004);  // a hole's place within 1e-6 mm
    plunge(10, 3);          // between two holes of a column
    plunge(10, 200);        // beyond the column's last
    plunge(10.5, 40);       // between the columns
    trace.tools.push_back({1, 3, "drill"});
    const Machine m = load_machine("fanuc");
    const std::string svg = backplot_svg(trace, compute_stats(trace, m), BackplotOptions{"p.nc", m.name, m.kind});
    std::size_t marks = 0;
    for (auto at = svg.find("l8,8M"); at != std::string::npos; at = svg.find("l8,8M", at + 1)) ++marks;
    CHECK(marks == 3 + 1);  // and the key's
}

TEST_CASE("stream verify: a program from standard input is read twice for --job and --plot, as a file is") {
    const std::string job_json = grid_job(40);
    const auto dir = std::filesystem::temp_directory_path() / "camgen-stream-verify";
    std::filesystem::create_directories(dir);
    const std::string job = (dir / "job.json").string(), file = (dir / "p.nc").string();
    std::ofstream(job) << job_json;
    const std::string program = test::post_job(job_json, "grbl").text;
    std::ofstream(file) << program;
    const test::Run from_file = test::run({"verify", file, "--machine", "grbl", "--job", job, "--plot", (dir / "f.svg").string()});
    const test::Run from_stdin =
        test::run({"verify", "-", "--machine", "grbl", "--job", job, "--plot", (dir / "s.svg").string()}, program);
    CHECK(from_file.code == 0);
    CHECK(from_stdin.code == 0);
    CHECK(from_stdin.out.find("matches job") != std::string::npos);
    // The same drawing under another title.
    const std::string f = test::read_file((dir / "f.svg").string()), s = test::read_file((dir / "s.svg").string());
    CHECK(f.substr(f.find("<g stroke")) == s.substr(s.find("<g stroke")));
    std::filesystem::remove_all(dir);
}

}  // namespace test_readback_stream
