// `camgen verify`, `--stats` and `--plot`: the statistics of every sample on every machine
// checked against numbers worked out by hand, mismatches with exit 1, the SVG backplot.
#include <filesystem>
#include <fstream>
#include <regex>

#include <doctest/doctest.h>

#include "camgen/analysis/backplot.hpp"
#include "camgen/cli/cli.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/analysis/stats.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_cli_verify {

namespace fs = std::filesystem;
using namespace camgen;
using test::Run;
using test::run;

namespace {

const std::string samples = CAMGEN_SOURCE_DIR "/samples/";

bool has_line(const std::string& text, const std::string& line) { return ("\n" + text).find("\n" + line + "\n") != std::string::npos; }

}  // namespace

TEST_CASE("verify prints the statistics of each sample on each machine, worked out by hand") {
    // plate: spot 6 holes from R2 to -1.5 (3.5 mm each = 21 mm at 80 mm/min), drill 6 holes
    // from R1 to -9.803 (8 mm + tip 3/tan 59 deg = 1.803; 10.803 mm each = 64.818 mm at 120).
    // Feed path 85.818 mm. Rapids: tool 1: Z10->2 (8), 6 x up 3.5 (21), across 40+40+30+40+40
    // (190), Z2->10 (8) = 227; tool 2: Z10->5 (5), 6 x (down 5->1 = 4, up -9.803->5 = 14.803)
    // = 112.818, across 190, Z5->10 (5) = 312.818; together 539.818 mm. The first rapid of
    // each tool comes from the tool-change position and is not measured.
    // fanuc: 21/80 + 64.818/120 min = 48.159 s, rapids 539.818/15000 min = 2.159 s: 50.3 s.
    // wabeco: F13.3 x 6 = 79.8 mm/min: 21/79.8 min = 15.789 s, + 32.409 s; rapids at 6000 mm/min
    // 5.398 s: 53.6 s.
    // bracket: plunges 2 x 13 mm at 100; cuts 60 + 10*pi/2 + 30 + 10*3pi/2 + 60 + 50 + 8*2pi =
    // 200 + 36 pi = 313.097 mm at 400; feed path 339.097 mm; rapids 13 + hypot(38, 25) + 13 =
    // 71.486 mm. fanuc: 15.6 + 46.965 + 0.286 = 62.851 s. wabeco: F16.7 and F66.7 are 100.2 and
    // 400.2 mm/min: 15.569 + 46.941 + 0.715 = 63.225 s.
    // plate on sinumerik and heidenhain (canned cycles read back, rapids at 30000 mm/min):
    // 48.159 + 539.818/30000 min (1.080 s) = 49.2 s; on grbl (all longhand, rapids at 5000):
    // 48.159 + 6.478 = 54.6 s.
    struct Case {
        const char* sample;
        const char* machine;
        const char* ext;
        std::vector<std::string> lines;
    };
    std::vector<Case> cases = {
        {"plate", "fanuc", "nc",
         {"holes          12", "feed path      85.818 mm",
          "rapid path     539.818 mm (+ 2 rapids from the tool-change position, not measured)", "lowest Z       -9.803 mm",
          "time           50.3 s (feed 48.2 s, rapid 2.2 s at 15000 mm/min, dwell 0.0 s)",
          "               6 holes, feed 21.000 mm, rapid 227.000 mm, 16.7 s",
          "               X 10.000 .. 90.000  Y 10.000 .. 40.000  Z -9.803 .. 10.000"}},
        {"plate", "wabeco", "knc",
         {"holes          12", "feed path      85.818 mm",
          "rapid path     539.818 mm (+ 2 rapids from the tool-change position, not measured)", "lowest Z       -9.803 mm",
          "time           53.6 s (feed 48.2 s, rapid 5.4 s at 6000 mm/min, dwell 0.0 s)"}},
        {"plate", "sinumerik", "mpf",
         {"holes          12", "feed path      85.818 mm",
          "rapid path     539.818 mm (+ 2 rapids from the tool-change position, not measured)", "lowest Z       -9.803 mm",
          "time           49.2 s (feed 48.2 s, rapid 1.1 s at 30000 mm/min, dwell 0.0 s)"}},
        {"plate", "heidenhain", "h",
         {"holes          12", "feed path      85.818 mm",
          "rapid path     539.818 mm (+ 2 rapids from the tool-change position, not measured)", "lowest Z       -9.803 mm",
          "time           49.2 s (feed 48.2 s, rapid 1.1 s at 30000 mm/min, dwell 0.0 s)"}},
        {"plate", "grbl", "nc",
         {"holes          12", "feed path      85.818 mm",
          "rapid path     539.818 mm (+ 2 rapids from the tool-change position, not measured)", "lowest Z       -9.803 mm",
          "time           54.6 s (feed 48.2 s, rapid 6.5 s at 5000 mm/min, dwell 0.0 s)"}},
        {"bracket", "fanuc", "nc",
         {"holes          0", "feed path      339.097 mm", "rapid path     71.486 mm (+ 1 rapid from the tool-change position, not measured)",
          "lowest Z       -3.000 mm", "time           1 min 02.9 s (feed 1 min 02.6 s, rapid 0.3 s at 15000 mm/min, dwell 0.0 s)",
          "               X 0.000 .. 80.000  Y 0.000 .. 60.000  Z -3.000 .. 10.000"}},
        {"bracket", "wabeco", "knc",
         {"holes          0", "feed path      339.097 mm", "lowest Z       -3.000 mm",
          "time           1 min 03.2 s (feed 1 min 02.5 s, rapid 0.7 s at 6000 mm/min, dwell 0.0 s)"}},
    };
    fs::path dir = test::scratch("verify-stats");
    for (const Case& c : cases) {
        CAPTURE(c.sample);
        CAPTURE(c.machine);
        std::string job = samples + c.sample + ".json";
        std::string program = (dir / (std::string(c.sample) + "." + c.ext)).string();
        REQUIRE(run({job, "--machine", c.machine, "-o", program}).code == 0);
        Run v = run({"verify", program, "--machine", c.machine, "--job", job});
        CHECK(v.code == 0);
        CHECK(v.out.rfind(program + " on machine " + c.machine + "\n", 0) == 0);
        for (const std::string& l : c.lines) CHECK_MESSAGE(has_line(v.out, l), l << "\n--- in ---\n" << v.out);
        CHECK(v.out.find("matches job " + job) != std::string::npos);
        CHECK(v.err == "");
    }
}

TEST_CASE("verify exits 1 and prints the first mismatch; reading errors name the line") {
    fs::path dir = test::scratch("verify-mismatch");
    std::string job = samples + "plate.json";
    std::string text = run({job, "--machine", "fanuc"}).out;
    std::string broken = text;
    broken.replace(broken.find("N55 X90.000 Y40.000"), 19, "N55 X90.000");
    fs::path program = dir / "plate.nc";
    std::ofstream(program) << broken;
    Run v = run({"verify", program.string(), "--machine", "fanuc", "--job", job});
    CHECK(v.code == 1);
    CHECK(v.out.find("MISMATCH " + program.string() + ":14: the job's rapid move from X90.000 Y10.000 Z2.000 to X90.000 Y40.000") !=
          std::string::npos);
    // Without --job: only the statistics, exit 0; the 4th hole drills the 3rd again, so the
    // program makes 11 holes, not 12.
    Run s = run({"verify", program.string(), "--machine", "fanuc"});
    CHECK(s.code == 0);
    CHECK(has_line(s.out, "holes          11"));
    // A word the dialect does not write.
    std::ofstream(program) << "%\nO1000\nN10 G17 G21 G90 G94\nN15 T1 M6 E5\n%\n";
    Run e = run({"verify", program.string(), "--machine", "fanuc"});
    CHECK(e.code == 1);
    CHECK(e.err == "camgen: " + program.string() + ":4: unknown word E5\n");
    // Standard input, and usage errors.
    CHECK(run({"verify", "-", "--machine", "fanuc", "--job", job}, text).code == 0);
    CHECK(run({"verify", "-", "--machine", "fanuc", "--job", "-"}, text).code == 2);
    CHECK(run({"verify", program.string()}).code == 2);
    CHECK(run({"verify", program.string(), "--machine", "nosuch"}).code == 2);
    CHECK(run({"verify", "/nonexistent.nc", "--machine", "fanuc"}).code == 3);
}

TEST_CASE("--stats prints the statistics to stderr; the program is unchanged") {
    std::string job = samples + "plate.json";
    Run plain = run({job, "--machine", "wabeco"});
    Run st = run({job, "--machine", "wabeco", "--stats"});
    CHECK(st.code == 0);
    CHECK(st.out == plain.out);
    CHECK(has_line(st.err, "rapid path     539.818 mm (+ 2 rapids from the tool-change position, not measured)"));
    CHECK(has_line(st.err, "holes          12"));
    fs::path dir = test::scratch("verify-stats-file");
    Run f = run({job, "--machine", "fanuc", "--stats", "-o", (dir / "p.nc").string()});
    CHECK(f.code == 0);
    CHECK(test::read_file((dir / "p.nc").string()) == run({job, "--machine", "fanuc"}).out);
    CHECK(run({job, "--events", "--stats"}).code == 2);
}

TEST_CASE("--stats, --plot and verify read every machine's programs; an unknown dialect is refused") {
    fs::path dir = test::scratch("verify-every-machine");
    for (const auto& listed : list_machines()) {
        const std::string& name = listed.first;
        CAPTURE(name);
        Machine m = load_machine(name);
        CHECK(has_reader(m.dialect));
        // A mill drills the drilling sample's 25 holes, a lathe the shaft's two centre holes.
        const bool lathe = m.kind == MachineKind::lathe;
        std::string job = samples + (lathe ? "shaft.json" : "drilling.json");
        fs::path program = dir / ("drilling." + m.extension), svg = dir / (name + ".svg");
        Run r = run({job, "--machine", name, "-o", program.string(), "--stats", "--plot", svg.string()});
        CHECK(r.code == 0);
        CHECK(has_line(r.err, lathe ? "holes          2" : "holes          25"));
        CHECK(test::read_file(svg.string()).ends_with("</svg>\n"));
        Run v = run({"verify", program.string(), "--machine", name, "--job", job});
        CHECK(v.code == 0);
        CHECK(v.out.find("matches job " + job) != std::string::npos);
    }
    // A machine file naming a dialect camgen has no reader (nor post) for.
    std::string text = test::read_file(CAMGEN_SOURCE_DIR "/machines/fanuc.json");
    const std::string iso = "\"dialect\": \"iso\"";
    text.replace(text.find(iso), iso.size(), "\"dialect\": \"acme\"");
    fs::path acme = dir / "acme.json";
    std::ofstream(acme) << text;
    Run r = run({samples + "plate.json", "--machine", acme.string(), "--plot", (dir / "a.svg").string()});
    CHECK(r.code == 2);
    CHECK(r.err == "camgen: --plot and --stats read the program back, and camgen cannot read the acme dialect of machine acme yet\n");
    fs::path prog = dir / "p.nc";
    std::ofstream(prog) << "%\n%\n";
    Run v = run({"verify", prog.string(), "--machine", acme.string()});
    CHECK(v.code == 1);
    CHECK(v.err.find("camgen cannot read programs of dialect \"acme\" (machine acme) yet; it reads: iso, iso-lathe, nccad, sinumerik, sinumerik-lathe, heidenhain") !=
          std::string::npos);
}

TEST_CASE("--plot writes a deterministic SVG backplot, on the main command and on verify") {
    fs::path dir = test::scratch("verify-plot");
    std::string job = samples + "plate.json";
    fs::path a = dir / "a.svg", b = dir / "b.svg";
    Run r = run({job, "--machine", "wabeco", "--plot", a.string()});
    CHECK(r.code == 0);
    std::string svg = test::read_file(a.string());
    CHECK(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0) == 0);
    CHECK(svg.ends_with("</svg>\n"));
    // Twelve holes numbered in drilling order: the spot and the drill at the same place share
    // a label ("1, 7"), each number in its tool's colour.
    CHECK(svg.find("<tspan fill=\"#1f5fbf\">1</tspan><tspan fill=\"#555\">, </tspan><tspan fill=\"#d62728\">7</tspan>") !=
          std::string::npos);
    CHECK(std::regex_search(svg, std::regex("stroke-dasharray")));  // rapids dashed
    CHECK(svg.find("No stock outline") != std::string::npos);
    CHECK(svg.find("e+") == std::string::npos);
    CHECK(svg.find("-0 ") == std::string::npos);
    // verify on the posted program draws the same picture, but for its title.
    std::string program = (dir / "plate.knc").string();
    REQUIRE(run({job, "--machine", "wabeco", "-o", program}).code == 0);
    CHECK(run({"verify", program, "--machine", "wabeco", "--plot", b.string()}).code == 0);
    CHECK(test::read_file(b.string()) == svg);
    // Deterministic.
    CHECK(run({job, "--machine", "wabeco", "--plot", b.string()}).code == 0);
    CHECK(test::read_file(b.string()) == svg);
    CHECK(run({job, "--events", "--plot", b.string()}).code == 2);
}

TEST_CASE("backplot arcs turn the right way: a ccw arc is SVG sweep flag 0 (y points down)") {
    Machine m = load_machine("fanuc");
    std::vector<Event> ev{ToolChange{1, 6, "6 mm end mill"}, Rapid{{10, 0, 5}}, Linear{{10, 0, -1}, 100},
                          Arc{{0, 10, -1}, {0, 0, -1}, ArcDirection::ccw, Plane::xy, 100, 0}};
    Trace t = trace_events(ev, m);
    std::string svg = backplot_svg(t, compute_stats(t, m), {"arc", "fanuc"});
    std::smatch match;
    REQUIRE(std::regex_search(svg, match, std::regex("A([0-9.]+),([0-9.]+) 0 0 ([01]) ")));
    CHECK(match[3] == "0");
    ev.back() = Arc{{0, -10, -1}, {0, 0, -1}, ArcDirection::cw, Plane::xy, 100, 0};
    t = trace_events(ev, m);
    svg = backplot_svg(t, compute_stats(t, m), {"arc", "fanuc"});
    REQUIRE(std::regex_search(svg, match, std::regex("A([0-9.]+),([0-9.]+) 0 0 ([01]) ")));
    CHECK(match[3] == "1");
}

TEST_CASE("the backplots committed under samples/ are up to date") {
    // samples/<name>.svg is the wabeco backplot of samples/<name>.json, or the fanuc one where
    // wabeco cannot run the job (tests/golden/wabeco/<name>.err), or the linuxcnc-lathe one
    // for a lathe job (tests/golden/fanuc/<name>.err too); scripts/update-golden rewrites them.
    // Every sample has one.
    fs::path dir = test::scratch("verify-samples-svg");
    int plots = 0;
    for (const auto& f : fs::directory_iterator(CAMGEN_SOURCE_DIR "/samples")) {
        if (f.path().extension() != ".json") continue;
        fs::path svg = f.path();
        svg.replace_extension(".svg");
        CAPTURE(svg.string());
        REQUIRE_MESSAGE(fs::exists(svg), "no backplot: run scripts/update-golden");
        std::string sample = f.path().stem().string();
        bool wabeco = !fs::exists(fs::path(CAMGEN_SOURCE_DIR "/tests/golden/wabeco") / (sample + ".err"));
        bool fanuc = !fs::exists(fs::path(CAMGEN_SOURCE_DIR "/tests/golden/fanuc") / (sample + ".err"));
        const std::string machine = wabeco ? "wabeco" : fanuc ? "fanuc" : "linuxcnc-lathe";
        fs::path fresh = dir / svg.filename();
        REQUIRE(run({f.path().string(), "--machine", machine, "--plot", fresh.string()}).code == 0);
        ++plots;
        CHECK(test::read_file(fresh.string()) == test::read_file(svg.string()));
    }
    CHECK(plots >= 5);
}

}  // namespace test_cli_verify
