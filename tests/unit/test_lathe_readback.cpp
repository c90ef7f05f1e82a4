// Read-back in lathe terms (issue 30, item 5): a lathe's statistics and plots say X as the
// program writes it (a diameter where the machine programs diameters), have no Y, count the
// holes on the axis in every view, and draw the job's bar.
#include <doctest/doctest.h>

#include <algorithm>
#include <optional>
#include <regex>

#include <fmt/format.h>

#include "camgen/analysis/backplot.hpp"
#include "camgen/analysis/backplot_html.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "lathe_support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_lathe_readback {

using namespace camgen;

namespace {

const std::string shaft = CAMGEN_SOURCE_DIR "/samples/shaft.json";

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The extent of the X and Z words a program writes from the call of `tool` to the next tool
// call (its own reading of the text, not the reader's).
struct Written {
    double min_x = 1e9, max_x = -1e9, min_z = 1e9, max_z = -1e9;
};
Written written_after_tool_call(const std::string& text, int tool) {
    const std::regex call(fmt::format(R"(^(N[0-9]+ )?T(0?{0}0?{0}|{0})( |$))", tool));
    const std::regex any_call(R"(^(N[0-9]+ )?T[0-9]+( |$))");
    const std::regex word(R"((^| )([XZ])(-?[0-9]+(\.[0-9]*)?))");
    Written w;
    bool in_tool = false;
    for (const std::string& line : test::lines_of(text)) {
        if (std::regex_search(line, any_call)) in_tool = std::regex_search(line, call);
        if (!in_tool || line.empty() || line[0] == '(' || line[0] == ';') continue;
        for (auto it = std::sregex_iterator(line.begin(), line.end(), word); it != std::sregex_iterator(); ++it) {
            const double v = std::stod((*it)[3].str());
            if ((*it)[2].str() == "X") w.min_x = std::min(w.min_x, v), w.max_x = std::max(w.max_x, v);
            else w.min_z = std::min(w.min_z, v), w.max_z = std::max(w.max_z, v);
        }
    }
    return w;
}

// The job's statistics of a program read back on `machine`.
ProgramStats stats_of(const std::string& text, const Machine& machine) {
    return compute_stats(trace_program(read_program(text, machine, "t.nc"), machine), machine);
}

}  // namespace

TEST_CASE("lathe statistics: X as the program writes it (the largest diameter written), no Y, no rapid in XY") {
    for (const char* name : {"fanuc-lathe", "linuxcnc-lathe", "sinumerik-lathe"}) {
        CAPTURE(name);
        const test::Run r = test::run({shaft, "--machine", name, "-q", "--stats"});
        REQUIRE(r.code == 0);
        const std::string& text = r.out;
        const std::string& stats = r.err;
        INFO(stats);
        // The finishing tool's X words go from Ø24 (the face's start) to Ø44 (the retract); the
        // R5 fillet's quadrant ends where it is widest, so the words are the whole extent.
        const Written w = written_after_tool_call(text, 3);
        REQUIRE(w.max_x == 44.0);
        CHECK(has(stats, fmt::format("               X (diameter) {:.3f} .. {:.3f}  Z {:.3f} .. {:.3f}\n", w.min_x, w.max_x,
                                     w.min_z, w.max_z)));
        // Both drills stay on the axis: X0 written, X0 measured (their Z is in cycle words).
        CHECK(written_after_tool_call(text, 1).min_x == 0.0);
        CHECK(written_after_tool_call(text, 2).max_x == 0.0);
        std::size_t on_axis = 0;
        for (std::size_t at = stats.find("X (diameter) 0.000 .. 0.000  Z "); at != std::string::npos;
             at = stats.find("X (diameter) 0.000 .. 0.000  Z ", at + 1))
            ++on_axis;
        CHECK(on_axis == 2);
        CHECK(has(stats, "holes          2\n"));
        CHECK_FALSE(has(stats, "Y "));
        CHECK_FALSE(has(stats, "rapid in XY"));
        CHECK(has(stats, "rapid path     "));
    }
}

TEST_CASE("lathe statistics: the same text is a diameter on a diameter lathe and a radius on a radius lathe") {
    const std::string text = "G18 G90\nG0 X40.000 Z5.000\nG1 X30.000 Z0.000 F100.0\nG1 Z-12.500\nG1 X40.000\nM30\n";
    const std::string on_diameter = format_stats(stats_of(text, test::lathe(true, false)));
    INFO(on_diameter);
    CHECK(has(on_diameter, "               X (diameter) 30.000 .. 40.000  Z -12.500 .. 5.000\n"));
    const std::string on_radius = format_stats(stats_of(text, test::lathe(false, false)));
    INFO(on_radius);
    CHECK(has(on_radius, "               X (radius) 30.000 .. 40.000  Z -12.500 .. 5.000\n"));
    // The diameter lathe's motion is the radius: the feed path is that of 5 mm down the face.
    CHECK(has(on_diameter, "feed path      24.571 mm\n"));  // hypot(5, 5) + 12.5 + 5
    CHECK(has(on_radius, "feed path      33.680 mm\n"));    // hypot(10, 5) + 12.5 + 10
    // A mill's statistics keep their Y and their rapids in XY.
    const std::string mill = format_stats(stats_of("G17 G90 G21\nG0 X10.000 Y5.000 Z5.000\nG1 Z-1.000 F100.0\nM30\n",
                                                   load_machine("fanuc")));
    CHECK(has(mill, "rapid in XY"));
    CHECK(has(mill, "X 10.000 .. 10.000  Y 5.000 .. 5.000  Z -1.000 .. 5.000"));
}

TEST_CASE("lathe plot: X labelled as the program writes it, the holes on the axis counted and drawn on the page") {
    const std::string dir = test::scratch("lathe-readback-plot").string();
    const test::Run r = test::run({shaft, "--machine", "fanuc-lathe", "-q", "-o", dir + "/s.nc", "--plot", dir + "/s.svg"});
    REQUIRE(r.code == 0);
    const std::string svg = test::read_file(dir + "/s.svg");
    CHECK(has(svg, ">X mm (diameter)</text>"));
    CHECK(has(svg, "X (diameter) 23.2 .. 44, Z -40 .. 20"));  // the finishing tool: its compensated tip starts at 23.2
    CHECK_FALSE(has(svg, ", Y 0.0 .. 0.0"));
    // The grid's X labels are diameters: the Ø44 retract is inside the labelled range, so a
    // label of 40 (a radius of 20) is there; a radius label would stop at 20.
    CHECK(has(svg, "text-anchor=\"end\">40</text>"));
    // Two holes, numbered 1 and 2 at their bottoms on the axis.
    CHECK(std::regex_search(svg, std::regex(">1</tspan></text>")));
    CHECK(std::regex_search(svg, std::regex(">2</tspan></text>")));

    const test::Run v = test::run({"verify", dir + "/s.nc", "--machine", "fanuc-lathe", "--plot", dir + "/s.html"});
    REQUIRE(v.code == 0);
    const std::string page = test::read_file(dir + "/s.html");
    // The statistics count 2 holes: so does the hole layer, and both are drawn in it.
    CHECK(has(v.out, "holes          2\n"));
    CHECK(has(page, "data-class=\"k-hole\">hole <span class=\"note\">holes and their numbers, 2</span>"));
    CHECK_FALSE(has(page, "data-class=\"k-hole\">hole <span class=\"note\">holes and their numbers: none in this program"));
    CHECK(has(page, "<g class=\"t1 k-hole\""));
    CHECK(has(page, "<g class=\"t2 k-hole\""));
    // The position: X as programmed (the diameter) first, the radius beside it.
    CHECK(has(page, "<tr><th>X</th><td class=\"num\" id=\"pos-d\"></td><td>mm (diameter, as programmed)</td></tr>"));
    CHECK(has(page, "<tr><th>r</th><td class=\"num\" id=\"pos-x\"></td><td>mm (radius)</td></tr>"));
    CHECK_FALSE(has(page, "rapid in XY"));
}

TEST_CASE("lathe plot: the job's bar drawn in the half-section, where it is and as large as it is") {
    const std::string dir = test::scratch("lathe-readback-bar").string();
    std::string job = test::read_file(shaft);
    // The sample's own bar replaced by one of other sizes, with a bore.
    const std::string own = R"("stock": {"bar": {"diameter": 44, "length": 70, "faceZ": 1}},)";
    const auto at = job.find(own);
    REQUIRE(at != std::string::npos);
    job.replace(at, own.size(), R"("stock": {"bar": {"diameter": 46, "length": 60, "faceZ": 1, "boreDiameter": 6}},)");
    const std::string job_file = test::file_with(dir + "/bar.json", job);
    const test::Run r = test::run({job_file, "--machine", "fanuc-lathe", "-q", "-o", dir + "/b.nc", "--plot", dir + "/b.svg"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    const std::string svg = test::read_file(dir + "/b.svg");
    CHECK(has(svg, "Grey: the job&#39;s bar, diameter 46 mm,"));
    CHECK(has(svg, "60 mm long (bore 6 mm), its face at Z 1."));

    // The outline where the frame puts the bar: from its far end (Z -59) to its face (Z 1),
    // between the bore (radius 3) and the outside (radius 23); the drawing reaches the far end.
    const Machine m = load_machine("fanuc-lathe");
    const Trace trace = trace_program(read_program(test::read_file(dir + "/b.nc"), m, "b.nc"), m);
    const ProgramStats stats = compute_stats(trace, m);
    BackplotOptions options;
    options.kind = MachineKind::lathe;
    options.bar = BackplotBar{46.0, 60.0, 1.0, 6.0};
    const BackplotDrawing drawing = backplot_drawing(trace, stats, options);
    const BackplotFrame& f = drawing.frame;
    CHECK(f.min_u < -59.0);
    auto x = [&](double u) { return fmt::format("{:.2f}", f.left + (u + 0.0 - f.min_u) * f.scale); };
    auto y = [&](double v) { return fmt::format("{:.2f}", f.top + (f.max_v - v) * f.scale); };
    const std::string outline = fmt::format("<path id=\"bar\" d=\"M{},{}H{}V{}H{}Z\"", x(-59), y(3), x(1), y(23), x(-59));
    CHECK(has(drawing.svg, outline));
    CHECK(has(svg, outline));  // the CLI passes the job's bar

    // verify draws the bar with --job, and says that it has none without.
    const test::Run with = test::run({"verify", dir + "/b.nc", "--machine", "fanuc-lathe", "--job", job_file, "--plot", dir + "/v.svg"});
    REQUIRE(with.code == 0);
    CHECK(has(test::read_file(dir + "/v.svg"), "<path id=\"bar\""));
    const test::Run without = test::run({"verify", dir + "/b.nc", "--machine", "fanuc-lathe", "--plot", dir + "/w.svg"});
    REQUIRE(without.code == 0);
    const std::string bare = test::read_file(dir + "/w.svg");
    CHECK_FALSE(has(bare, "<path id=\"bar\""));
    CHECK(has(bare, "No bar outline: no stock bar given by a job."));
}

}  // namespace test_lathe_readback
