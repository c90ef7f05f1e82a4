// The interactive backplot page (--plot F.html): self-contained, everything from the program
// escaped, the drawing's layers marked, every block's text and position in its data. (The page
// in a real browser: tests/browser.)
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include "camgen/analysis/backplot_html.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/reader/reader.hpp"
#include "html_plot_support.hpp"
#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_backplot_html {

using namespace camgen;

namespace {

// A job whose names and comments hold everything that could break a page.
const std::string nasty_job = R"({"name": "n</title><b>", "clearance": 10,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000, "comment": "</script><!-- a & \"b\" 'c' -->"},
            {"number": 2, "type": "end-mill", "diameter": 6, "rpm": 3000}],
  "operations": [{"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100, "holes": [[0, 0], [10, 5]]},
                 {"type": "path", "tool": 2, "z": -1, "feed": 400, "plungeFeed": 100, "start": [0, 20],
                  "path": [{"line": [30, 20]}, {"line": [30, 30]}]}]})";

struct Plotted {
    std::string program;
    Trace trace;
    std::string page;
};

Plotted plot(const std::string& job, const std::string& machine_name, const HtmlPlotLimits& limits = {}) {
    const Machine m = load_machine(machine_name);
    Plotted p;
    p.program = test::post_job(job, machine_name).text;
    p.trace = trace_program(read_program(p.program, m, "p"), m);
    p.page = backplot_html(p.program, p.trace, compute_stats(p.trace, m), {"p</b>.nc", m.name, m.kind}, limits);
    return p;
}

std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("html plot: text from the program and the job is escaped; a comment </script> does not end the script") {
    for (const std::string machine : {"fanuc", "wabeco"}) {
        CAPTURE(machine);
        const Plotted p = plot(nasty_job, machine);
        REQUIRE(p.program.find("</script><!-- a & \"b\" 'c' -->") != std::string::npos);
        // Two scripts (the data and the code), each closed once; no comment opened anywhere.
        CHECK(occurrences(p.page, "<script") == 2);
        CHECK(occurrences(p.page, "</script") == 2);
        CHECK(occurrences(p.page, "<!--") == 0);
        CHECK(occurrences(p.page, "</title") == 1);
        CHECK(p.page.find("<title>p&lt;/b&gt;.nc - camgen backplot</title>") != std::string::npos);
        // The tool's comment in the layer switches and the statistics, as text.
        CHECK(p.page.find("&lt;/script&gt;&lt;!-- a &amp; &quot;b&quot; &#39;c&#39; --&gt;") != std::string::npos);
        // The data gives back every line exactly.
        const auto data = test::page_data(p.page);
        const std::vector<std::string> lines = test::lines_of(p.program);
        std::string joined;
        for (std::size_t i = 0; i < lines.size(); ++i) joined += (i ? "\n" : "") + lines[i];
        CHECK(data["nc"].get<std::string>() == joined);
    }
}

TEST_CASE("html plot: bytes that are no UTF-8 and control characters cannot break the data") {
    const Machine m = load_machine("fanuc");
    std::string program = test::post_job(nasty_job, "fanuc").text;
    program = test::replace_once(program, "(drill 2 holes)", "(drill \xff\xfe 2 holes \xe2\x80\xa8 \x01)");
    const Trace t = trace_program(read_program(program, m, "p"), m);
    const std::string page = backplot_html(program, t, compute_stats(t, m), {"p", m.name, m.kind});
    const auto data = test::page_data(page);
    CHECK(data["nc"].get<std::string>().find("(drill \xef\xbf\xbd\xef\xbf\xbd 2 holes \xe2\x80\xa8 \x01)") != std::string::npos);
    for (char c : page.substr(page.find("id=\"camgen-data\"")))
        CHECK_MESSAGE((c == '\n' || (c >= 0x20 && c < 0x7f)), "byte " << int(static_cast<unsigned char>(c)));
}

TEST_CASE("html plot: self-contained: no address the browser would fetch") {
    const std::string page = plot(nasty_job, "fanuc").page;
    CHECK(page.rfind("<!DOCTYPE html>", 0) == 0);
    for (const char* fetch : {"src=", "href=", "@import", "url(", "https:", "//cdn", "<link", "<iframe", "<img"})
        CHECK_MESSAGE(page.find(fetch) == std::string::npos, fetch);
    // http: only as the SVG namespace name, which is never fetched.
    CHECK(occurrences(page, "http") == occurrences(page, "http://www.w3.org/2000/svg"));
}

TEST_CASE("html plot: a layer class for each tool and kind of move in the program, and a switch for each") {
    const Plotted p = plot(nasty_job, "fanuc");
    for (const char* cls : {"t1 k-rapid", "t2 k-feed", "t2 k-width", "t1 k-hole", "t2 k-plunge"})
        CHECK_MESSAGE(p.page.find(fmt::format("class=\"{}\"", cls)) != std::string::npos, cls);
    for (const char* sw : {"t1", "t2", "k-rapid", "k-feed", "k-plunge", "k-width", "k-hole"})
        CHECK_MESSAGE(p.page.find(fmt::format("checked data-class=\"{}\"", sw)) != std::string::npos, sw);
    // The read-back has no ramps or leads here: their switches are there but off.
    for (const char* sw : {"k-ramp", "k-lead"}) CHECK(p.page.find(fmt::format("disabled data-class=\"{}\"", sw)) != std::string::npos);
    // The statistics are the --stats text.
    const Machine m = load_machine("fanuc");
    std::string stats = format_stats(compute_stats(p.trace, m));
    stats = std::regex_replace(stats, std::regex("&"), "&amp;");
    stats = std::regex_replace(stats, std::regex("<"), "&lt;");
    stats = std::regex_replace(stats, std::regex(">"), "&gt;");
    stats = std::regex_replace(stats, std::regex("\""), "&quot;");
    stats = std::regex_replace(stats, std::regex("'"), "&#39;");
    CHECK(p.page.find("<pre>" + stats + "</pre>") != std::string::npos);
    // A plain SVG carries no classes.
    CHECK(backplot_svg(p.trace, compute_stats(p.trace, m), {"p", "fanuc"}).find("class=") == std::string::npos);
}

TEST_CASE("html plot: the data has every block, and decoded it gives the read-back's position after each") {
    for (const char* machine : {"fanuc", "wabeco"}) {
        CAPTURE(machine);
        const Plotted p = plot(nasty_job, machine);
        const auto data = test::page_data(p.page);
        const std::vector<std::string> lines = test::lines_of(p.program);
        // One record per line that moves the tool or changes it, five numbers each.
        std::set<int> moving;
        for (const Step& s : p.trace.steps)
            if (s.kind == StepKind::rapid || s.kind == StepKind::feed || s.kind == StepKind::tool_change) moving.insert(s.line);
        const auto& moves = data["moves"];
        REQUIRE(moves.size() == 5 * moving.size());
        CHECK(data["tools"].size() == 4);  // two tool changes: (line step, tool)
        // The same decoding as the page's script.
        std::map<int, std::pair<int, Vec3>> records;  // line -> kind, position
        long long l = 0, x = 0, y = 0, z = 0;
        for (std::size_t i = 0; i < moves.size(); i += 5) {
            l += moves[i].get<long long>(), x += moves[i + 2].get<long long>(), y += moves[i + 3].get<long long>();
            z += moves[i + 4].get<long long>();
            records[static_cast<int>(l)] = {moves[i + 1].get<int>(), Vec3{x * 1e-4, y * 1e-4, z * 1e-4}};
        }
        for (int line = 1; line <= static_cast<int>(lines.size()); ++line) {
            CAPTURE(line);
            const test::BlockState expected = test::block_state(p.trace, line);
            auto it = records.upper_bound(line);
            const bool known = it != records.begin() && std::prev(it)->second.first >= 0;
            REQUIRE(known == expected.known);
            if (!known) continue;
            const Vec3 at = std::prev(it)->second.second;
            CHECK(std::abs(at.x - expected.at.x) < 1e-4);
            CHECK(std::abs(at.y - expected.at.y) < 1e-4);
            CHECK(std::abs(at.z - expected.at.z) < 1e-4);
        }
    }
}

TEST_CASE("html plot: above the move limit the drawing is thinned, saying so; the block data is not") {
    // A straight line in 2000 pieces, then a corner: drawn as two lines; every block kept.
    std::string path = R"({"line": [0.05, 0]})";
    for (int i = 2; i <= 2000; ++i) path += fmt::format(R"(, {{"line": [{}, 0]}})", i * 0.05);
    path += R"(, {"line": [100, 40]})";
    const std::string job = R"({"clearance": 10, "tools": [{"number": 3, "type": "end-mill", "diameter": 6, "rpm": 3000}],
  "operations": [{"type": "path", "tool": 3, "z": -1, "feed": 400, "plungeFeed": 100, "start": [0, 0], "path": [)" + path + "]}]}";
    const Plotted full = plot(job, "fanuc");
    const Plotted thin = plot(job, "fanuc", {100});
    CHECK(full.page.find("Drawing thinned") == std::string::npos);
    CHECK(thin.page.find("id=\"thinned\"") != std::string::npos);
    CHECK(test::page_data(thin.page)["moves"] == test::page_data(full.page)["moves"]);
    CHECK(test::page_data(thin.page)["nc"] == test::page_data(full.page)["nc"]);
    // The feed path: 2001 line commands as the program has them, 2 when thinned; the corner
    // (100, 0) is kept.
    auto feed_path = [](const std::string& page) {
        const std::string open = "<path class=\"t3 k-feed\" d=\"";
        const auto from = page.find(open);
        REQUIRE(from != std::string::npos);
        return page.substr(from + open.size(), page.find('"', from + open.size()) - from - open.size());
    };
    CHECK(occurrences(feed_path(full.page), "L") == 2001);
    CHECK(occurrences(feed_path(thin.page), "L") == 2);
    const std::string full_path = feed_path(full.page);
    const auto last = full_path.rfind('L'), before = full_path.rfind('L', last - 1);
    const std::string corner = full_path.substr(before + 1, last - before - 1);
    CHECK(feed_path(thin.page).find("L" + corner + "L") != std::string::npos);
}

TEST_CASE("html plot: --plot F.html writes the page, F.svg the drawing, on the main command and on verify") {
    CHECK(is_html_plot("a.html"));
    CHECK(is_html_plot("dir.svg/A.HTM"));
    CHECK_FALSE(is_html_plot("a.svg"));
    CHECK_FALSE(is_html_plot("html"));
    const std::filesystem::path dir = test::scratch("html-plot");
    const std::string job = test::file_with("nasty", nasty_job), program = (dir / "p.nc").string();
    const std::string html = (dir / "p.html").string(), svg = (dir / "p.svg").string(), again = (dir / "v.HTML").string();
    REQUIRE(test::run({job, "--machine", "fanuc", "-o", program, "--plot", html}).code == 0);
    REQUIRE(test::run({job, "--machine", "fanuc", "--plot", svg}).code == 0);
    REQUIRE(test::run({"verify", program, "--machine", "fanuc", "--plot", again}).code == 0);
    CHECK(test::read_file(html).rfind("<!DOCTYPE html>", 0) == 0);
    CHECK(test::read_file(svg).rfind("<svg", 0) == 0);
    // verify reads the same program (named p.nc both times): the same page.
    CHECK(test::read_file(again) == test::read_file(html));
}

TEST_CASE("html plot: verify copies the text from the file or standard input, line by line, as the page of the text in memory") {
    const Machine m = load_machine("fanuc");
    // CR LF line ends, a blank line, bytes that are no UTF-8 in a comment, no final newline.
    std::string text;
    for (const std::string& line : test::lines_of(test::post_job(nasty_job, "fanuc").text)) {
        text += line + "\r\n";
        if (text.size() < 80 && line.find('(') != std::string::npos) text += "\r\n(\xff\xfe </pre> \xc3\xa9)\r\n";
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    REQUIRE(text.find("\xff\xfe") != std::string::npos);
    const std::filesystem::path dir = test::scratch("html-plot-stream");
    const std::string file = (dir / "p.nc").string(), from_file = (dir / "f.html").string(), from_stdin = (dir / "s.html").string();
    std::ofstream(file, std::ios::binary) << text;
    REQUIRE(test::run({"verify", file, "--machine", "fanuc", "--plot", from_file}).code == 0);
    REQUIRE(test::run({"verify", "-", "--machine", "fanuc", "--plot", from_stdin}, text).code == 0);
    const Trace trace = trace_program(read_program(text, m, "p.nc"), m);
    const ProgramStats stats = compute_stats(trace, m);
    const std::string page = test::read_file(from_file);
    CHECK(page == backplot_html(text, trace, stats, {"p.nc", m.name, m.kind}));
    CHECK(test::read_file(from_stdin) == backplot_html(text, trace, stats, {"<stdin>", m.name, m.kind}));
    // The text as the reader counts its lines: '\r' dropped, joined by '\n', the slider over all.
    const std::vector<std::string> lines = test::lines_of(text);
    std::string joined;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (i > 0) joined += '\n';
        std::string_view line = lines[i];
        if (line.ends_with('\r')) line.remove_suffix(1);
        joined += line;
    }
    for (auto at = joined.find("\xff\xfe"); at != std::string::npos; at = joined.find("\xff\xfe"))
        joined.replace(at, 2, "\xef\xbf\xbd\xef\xbf\xbd");  // each byte that is no UTF-8 shown as U+FFFD
    CHECK(test::page_data(page)["nc"].get<std::string>() == joined);
    CHECK(page.find(fmt::format("max=\"{}\"", lines.size())) != std::string::npos);
}

TEST_CASE("html plot: above the hole limit further holes are plain circles, one path per tool, saying so") {
    const Plotted full = plot(nasty_job, "fanuc");
    const Plotted plain = plot(nasty_job, "fanuc", {20000, 1});
    CHECK(full.page.find("id=\"plain-holes\"") == std::string::npos);
    CHECK(plain.page.find("id=\"plain-holes\"") != std::string::npos);
    CHECK(occurrences(full.page, "<circle class=\"t1 k-hole\"") == 2);
    CHECK(occurrences(plain.page, "<circle class=\"t1 k-hole\"") == 1);
    // The second hole: a ring of two half circles ("a5,5 0 1 0 10,0a5,5 0 1 0 -10,0").
    CHECK(occurrences(full.page, " 0 1 0 ") == 0);
    CHECK(occurrences(plain.page, " 0 1 0 ") == 2);
    // Both holes keep their numbers.
    CHECK(plain.page.find(">1</tspan>") != std::string::npos);
    CHECK(plain.page.find(">2</tspan>") != std::string::npos);
}

}  // namespace test_backplot_html
