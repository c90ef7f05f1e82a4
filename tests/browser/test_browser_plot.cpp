// The HTML backplot in a real browser: Debian's chromium loads the page written by
// `camgen verify PROGRAM --plot page.html` headless, with #block=1,2,...&check: the page's
// script steps its slider to every block by input events, as a user would, records what it
// shows (the block's line and text, the tool's X Y Z, the tool, the marker), then switches each
// layer off and on. The dumped DOM is compared with camgen's own read-back of the same program.
// Machines: a mill on ISO (fanuc), a mill on nccad (wabeco), a lathe (fanuc-lathe).
// The simulation's page (`camgen simulate --plot`): it draws, its slider shows the part cut up
// to a block (less early), its WebGL view draws (SwiftShader); screenshots are saved under
// build/simulate-screenshots/.
// Exits 77 (ctest: skipped) with a message when chromium is not installed.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/analysis/backplot.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/simulation/pictures.hpp"
#include "tests/unit/html_plot_support.hpp"
#include "tests/unit/support.hpp"

using namespace camgen;

namespace {

// Runs a shell command and returns its standard output and exit status.
std::pair<std::string, int> output_of(const std::string& command) {
    std::string out;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::array<char, 65536> buffer{};
    for (size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) out.append(buffer.data(), n);
    return {out, pclose(pipe)};
}

// Text of an HTML text node as the DOM serializer writes it, back to characters.
std::string unescape(std::string s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        bool replaced = false;
        for (auto [ref, c] : {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&amp;", "&"}, {"&quot;", "\""}, {"&nbsp;", "\xc2\xa0"}}) {
            const std::string r = ref;
            if (s.compare(i, r.size(), r) == 0) {
                out += c;
                i += r.size() - 1;
                replaced = true;
                break;
            }
        }
        if (!replaced) out += s[i];
    }
    return out;
}

// Loads `page` in headless chromium at `hash` and returns the lines the page's check wrote.
std::vector<nlohmann::json> browse(const std::filesystem::path& page, const std::string& hash) {
    // As root (CI) chromium needs --no-sandbox; containers often have a small /dev/shm.
    const std::filesystem::path profile = page.parent_path() / "chromium-profile", log = page.parent_path() / "chromium.err";
    const auto [dom, status] = output_of(fmt::format("timeout 60 chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage "
                                                     "--no-first-run --user-data-dir='{}' --dump-dom 'file://{}{}' 2>'{}'",
                                                     profile.string(), page.string(), hash, log.string()));
    const std::string open = "<pre id=\"steps\" hidden=\"\">";
    const auto from = dom.find(open);
    REQUIRE_MESSAGE((status == 0 && from != std::string::npos), "chromium exit status " << status << ", no check output in:\n"
                                                                   << dom.substr(0, 400) << "\nchromium's errors:\n"
                                                                   << test::read_file(log.string()));
    const auto to = dom.find("</pre>", from);
    std::vector<nlohmann::json> lines;
    for (const std::string& line : test::lines_of(unescape(dom.substr(from + open.size(), to - from - open.size()))))
        lines.push_back(nlohmann::json::parse(line));
    return lines;
}

double number(const nlohmann::json& text) { return std::stod(text.get<std::string>()); }

// Posts `job` for `machine`, writes the page with camgen verify, and checks every block and
// every layer in the browser. `drawn`: layer classes that must have elements on this page.
void check_in_browser(const std::string& name, const std::string& job, const std::string& machine_name,
                      const std::set<std::string>& drawn) {
    CAPTURE(machine_name);
    const Machine m = load_machine(machine_name);
    const std::filesystem::path dir = test::scratch("browser-" + name);
    const std::string program = test::post_job(job, machine_name).text;
    const std::filesystem::path nc = dir / (name + "." + m.extension), page = dir / (name + ".html");
    std::ofstream(nc) << program;
    const test::Run r = test::run({"verify", nc.string(), "--machine", machine_name, "--plot", page.string()});
    REQUIRE_MESSAGE(r.code == 0, r.err);

    // camgen's read-back of the same program, and where its drawing puts a position.
    const Trace trace = trace_program(read_program(program, m, nc.string()), m);
    const BackplotFrame f = backplot_drawing(trace, compute_stats(trace, m), {name, m.name, m.kind}).frame;
    const bool lathe = m.kind == MachineKind::lathe;
    const std::vector<std::string> lines = test::lines_of(program);

    std::string hash = "#block=";
    for (size_t n = 1; n <= lines.size(); ++n) hash += fmt::format("{}{}", n > 1 ? "," : "", n);
    const std::vector<nlohmann::json> shown = browse(page, hash + "&check");

    size_t blocks = 0;
    std::set<std::string> layers;
    for (const nlohmann::json& s : shown) {
        if (s.contains("layer")) {
            CAPTURE(s.dump());
            const int elements = s["elements"].get<int>();
            CHECK(s["before"].get<int>() == elements);  // all shown at first
            CHECK(s["hidden"].get<int>() == 0);         // none once its box is unchecked
            CHECK(s["after"].get<int>() == elements);   // all again when checked
            if (elements > 0) layers.insert(s["layer"].get<std::string>());
            continue;
        }
        const int n = s["block"].get<int>();
        CAPTURE(n);
        ++blocks;
        REQUIRE(n == static_cast<int>(blocks));
        CHECK(s["line"].get<int>() == n);
        CHECK(s["nc"].get<std::string>() == lines[static_cast<size_t>(n - 1)]);
        const test::BlockState expected = test::block_state(trace, n);
        CHECK(s["tool"].get<std::string>() == (expected.tool < 0 ? "-" : fmt::format("T{}", expected.tool)));
        if (!expected.known) {
            CHECK(s["x"] == "?");
            CHECK(s["z"] == "?");
            CHECK(s["marker"].is_null());
            continue;
        }
        // Three decimals shown: within half a unit of the last one.
        CHECK(std::abs(number(s["x"]) - expected.at.x) < 0.00051);
        CHECK(std::abs(number(s["y"]) - expected.at.y) < 0.00051);
        CHECK(std::abs(number(s["z"]) - expected.at.z) < 0.00051);
        REQUIRE(s["marker"].is_string());
        double mx = 0, my = 0;
        REQUIRE(std::sscanf(s["marker"].get<std::string>().c_str(), "translate(%lf,%lf)", &mx, &my) == 2);
        const double u = lathe ? expected.at.z : expected.at.x, v = lathe ? expected.at.x : expected.at.y;
        CHECK(std::abs(mx - (f.left + (u - f.min_u) * f.scale)) < 0.01);
        CHECK(std::abs(my - (f.top + (f.max_v - v) * f.scale)) < 0.01);
    }
    CHECK(blocks == lines.size());
    for (const std::string& layer : drawn) CHECK_MESSAGE(layers.count(layer), layer);
}

}  // namespace

TEST_CASE("browser: every block of a fanuc mill program, a comment </script> in it; layers switch") {
    // The tool's comment reaches the program as (T1 5 mm drill - </script><!-- ... -->).
    const std::string job = R"({"name": "n</title><b>", "clearance": 10,
  "tools": [{"number": 1, "diameter": 5, "rpm": 1000, "comment": "</script><!-- a & \"b\" 'c' -->"},
            {"number": 2, "type": "end-mill", "diameter": 6, "rpm": 3000}],
  "operations": [{"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100, "holes": [[0, 0], [10, 5], [20, 0]]},
                 {"type": "path", "tool": 2, "z": -1, "feed": 400, "plungeFeed": 100, "start": [0, 20],
                  "path": [{"line": [30, 20]}, {"arc": {"end": [40, 30], "centre": [30, 30], "direction": "ccw"}}]}]})";
    check_in_browser("fanuc", job, "fanuc", {"t1", "t2", "k-rapid", "k-feed", "k-plunge", "k-hole", "k-width"});
}

TEST_CASE("browser: every block of a wabeco (nccad) program with ramps and a helix") {
    check_in_browser("wabeco", test::read_file(CAMGEN_SOURCE_DIR "/samples/pocket-wall.json"), "wabeco",
                     {"t2", "k-feed", "k-ramp", "k-width", "k-plunge"});
}

TEST_CASE("browser: every block of a lathe program, the half-section's marker at (Z, X)") {
    check_in_browser("lathe", test::read_file(CAMGEN_SOURCE_DIR "/samples/shaft.json"), "fanuc-lathe",
                     {"t1", "t2", "t3", "k-rapid", "k-feed", "k-width"});
}

namespace {

// The simulation's page (camgen simulate --plot): chromium with SwiftShader's software WebGL.
// `hash` steps the slider; returns the page's check lines.
std::vector<nlohmann::json> browse_simulation(const std::filesystem::path& page, const std::string& hash) {
    const std::filesystem::path profile = page.parent_path() / "chromium-profile", log = page.parent_path() / "chromium.err";
    const auto [dom, status] = output_of(fmt::format("timeout 90 chromium --headless --no-sandbox --use-gl=swiftshader "
                                                     "--enable-unsafe-swiftshader --disable-dev-shm-usage --no-first-run "
                                                     "--user-data-dir='{}' --dump-dom 'file://{}{}' 2>'{}'",
                                                     profile.string(), page.string(), hash, log.string()));
    const std::string open = "<pre id=\"steps\" hidden=\"\">";
    const auto from = dom.find(open);
    REQUIRE_MESSAGE((status == 0 && from != std::string::npos), "chromium exit status " << status << ", no check output in:\n"
                                                                   << dom.substr(0, 400) << "\nchromium's errors:\n"
                                                                   << test::read_file(log.string()));
    const auto to = dom.find("</pre>", from);
    std::vector<nlohmann::json> lines;
    for (const std::string& line : test::lines_of(unescape(dom.substr(from + open.size(), to - from - open.size()))))
        lines.push_back(nlohmann::json::parse(line));
    return lines;
}

void screenshot(const std::filesystem::path& page, const std::string& hash, const std::filesystem::path& png) {
    const std::filesystem::path profile = page.parent_path() / "chromium-profile";
    std::filesystem::create_directories(png.parent_path());
    std::filesystem::remove(png);
    const auto [out, status] = output_of(fmt::format("timeout 90 chromium --headless --no-sandbox --use-gl=swiftshader "
                                                     "--enable-unsafe-swiftshader --disable-dev-shm-usage --no-first-run "
                                                     "--user-data-dir='{}' --window-size=1280,1400 --screenshot='{}' "
                                                     "'file://{}{}' 2>/dev/null",
                                                     profile.string(), png.string(), page.string(), hash));
    CHECK(status == 0);
    CHECK(std::filesystem::exists(png));
}

}  // namespace

TEST_CASE("browser: the simulation page draws, its slider shows less cut early, its WebGL view draws") {
    const std::filesystem::path dir = test::scratch("browser-simulate");
    const std::string job = CAMGEN_SOURCE_DIR "/samples/pocket.json";
    const std::filesystem::path nc = dir / "pocket.ngc", page = dir / "pocket.html";
    std::ofstream(nc) << test::post_job(test::read_file(job), "linuxcnc").text;
    const test::Run r = test::run({"simulate", nc.string(), "--machine", "linuxcnc", "--job", job, "--stock-box",
                                   "-10,-10,-12,110,80,0", "--section", "-10,30,110,30", "--plot", page.string()});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const std::size_t lines = test::lines_of(test::read_file(nc.string())).size();
    const std::vector<nlohmann::json> shown = browse_simulation(page, fmt::format("#block=40,300,{}&check", lines));
    REQUIRE(shown.size() == 3);
    for (const nlohmann::json& s : shown) {
        CAPTURE(s.dump());
        CHECK(s["top"].get<int>() > 100000);    // the top view is drawn (not blank)
        CHECK(s["section"].get<int>() > 1000);  // and the section
    }
    const nlohmann::json &early = shown[0], &middle = shown[1], &late = shown[2];
    CHECK(early["line"] == 40);
    CHECK(late["line"].get<std::size_t>() == lines);
    // The slider moves the cut: fewer cells cut at block 40 than at the end, and other pictures.
    CHECK(early["cut"].get<int>() > 0);
    CHECK(early["cut"].get<int>() < middle["cut"].get<int>());
    CHECK(middle["cut"].get<int>() < late["cut"].get<int>());
    CHECK(early["topSum"] != late["topSum"]);
    CHECK(early["sectionSum"] != late["sectionSum"]);
    // SwiftShader gives headless chromium WebGL: the 3D view draws, and changes with the slider.
    REQUIRE_MESSAGE(early["webgl"].get<bool>(), "chromium has no WebGL even with SwiftShader");
    CHECK(early["gl"].get<int>() > 10000);
    CHECK(early["glSum"] != late["glSum"]);
    // Screenshots for a person to look at.
    const std::filesystem::path shots = CAMGEN_BUILD_DIR "/simulate-screenshots";
    screenshot(page, "#block=40", shots / "pocket-block-40.png");
    screenshot(page, fmt::format("#block={}", lines), shots / "pocket-last-block.png");
    // A lathe's page: the half-section, no 3D view.
    const std::string shaft = CAMGEN_SOURCE_DIR "/samples/shaft.json";
    const std::filesystem::path lnc = dir / "shaft.nc", lpage = dir / "shaft.html";
    std::ofstream(lnc) << test::post_job(test::read_file(shaft), "fanuc-lathe").text;
    const test::Run lr = test::run({"simulate", lnc.string(), "--machine", "fanuc-lathe", "--job", shaft, "--bar", "40,80,0",
                                    "--plot", lpage.string()});
    REQUIRE_MESSAGE(lr.code == 0, lr.err);
    const std::vector<nlohmann::json> lathe = browse_simulation(lpage, "#block=20,1000&check");
    REQUIRE(lathe.size() == 2);
    CHECK(lathe[0]["top"].get<int>() > 10000);
    CHECK(lathe[0]["cut"].get<int>() < lathe[1]["cut"].get<int>());
    CHECK(lathe[0]["gl"].is_null());
    screenshot(lpage, "#block=1000", shots / "shaft-last-block.png");
}

int main(int argc, char** argv) {
    if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
        std::cout << "SKIPPED: chromium is not installed (scripts/install-deps --tests installs Debian's chromium), so the HTML "
                     "backplot was not tried in a browser\n";
        return 77;
    }
    doctest::Context context(argc, argv);
    return context.run();
}
