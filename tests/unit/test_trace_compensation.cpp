// G41/G42 read back as the control cuts them (issue 24): the trace of a control-compensation
// program is the tool centre's path, so that verify --job, --stats and --plot see what the
// control cuts; what the control refuses is a failure at its line; the radius comes from
// --tool-table, the job or the program's tool comment, else the moves stay as programmed with
// a note.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <fmt/format.h>

#include "camgen/analysis/backplot.hpp"
#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/reader/tool_table.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_trace_compensation {

namespace fs = std::filesystem;
using namespace camgen;
using test::run;

namespace {

const std::string samples = CAMGEN_SOURCE_DIR "/samples/";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE_MESSAGE(at != std::string::npos, from);
    return text.replace(at, from.size(), to);
}

// The pocket wall sample with control compensation (it is computer-compensated as committed).
// pocket-wall with control compensation, started in the middle of its bottom side: under
// G41/G42 the entry runs along the tangent before the start, which at the sample's own start
// (where the R8 corner meets the side) would cut into the corner (the part guard refuses that).
std::string pocket_wall_control() {
    nlohmann::json job = nlohmann::json::parse(test::read_file(samples + "pocket-wall.json"));
    auto& op = job["operations"][0];
    op["compensation"] = "control";
    op["start"] = {100, 40};
    op["path"].push_back({{"line", {100, 40}}});
    return job.dump(2);
}

// The feed moves of each run between rapids after its first arc (the lead-in) and before its
// last (the lead-out): the offset profile of every pass. The leads differ by construction
// (camgen's computer lead arcs touch the offset path, the control offsets its own).
std::vector<Step> between_leads(const std::vector<Step>& steps) {
    std::vector<Step> out;
    std::size_t k = 0;
    while (k < steps.size()) {
        if (steps[k].kind != StepKind::feed) {
            ++k;
            continue;
        }
        std::size_t end = k;
        while (end < steps.size() && steps[end].kind == StepKind::feed) ++end;
        std::optional<std::size_t> first, last;
        for (std::size_t i = k; i < end; ++i)
            if (steps[i].arc) {
                if (!first) first = i;
                last = i;
            }
        if (first && *last > *first)
            for (std::size_t i = *first + 1; i < *last; ++i) out.push_back(steps[i]);
        k = end;
    }
    return out;
}

double dist(Vec3 a, Vec3 b) { return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z); }

std::string write(const fs::path& dir, const std::string& name, const std::string& text) {
    const fs::path p = dir / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
}

// A hand-written LinuxCNC program: a 4 mm slot along X, cut with G41 D1 (the slot of rs274's
// evidence K_comp_concave_gouge): a 6 mm tool cannot reach into its far corner.
const std::string slot_program = "G21 G17 G90 G94\n"  // 1
                                 "T1 M6\n"            // 2
                                 "G43 H1\n"           // 3
                                 "S1000 M3\n"         // 4
                                 "G0 X-10 Y-10 Z1\n"  // 5
                                 "G41 D1\n"           // 6
                                 "G1 X-5 Y0 F100\n"   // 7
                                 "G1 X20\n"           // 8
                                 "G1 Y4\n"            // 9
                                 "G1 X0\n"            // 10
                                 "G40\n"              // 11
                                 "G0 X-10\n"          // 12
                                 "M2\n";              // 13

}  // namespace

TEST_CASE("compensation read back: a control-compensation sample traces the tool centre, camgen's computer path between the leads") {
    for (const char* machine : {"linuxcnc", "fanuc"}) {
        CAPTURE(machine);
        const Machine m = load_machine(machine);
        const std::string control = test::read_file(samples + "plate-outline-control.json");
        const std::string computer = replaced(control, R"("compensation": "control")", R"("compensation": "computer")");
        const std::string control_nc = test::post_job(control, machine).text;
        const std::string computer_nc = test::post_job(computer, machine).text;
        REQUIRE(control_nc.find("G41 D4") != std::string::npos);
        // The program holds the profile (offset by the 0.3 mm stock only), not the tool centre.
        CHECK(control_nc.find("X-0.3") != std::string::npos);
        CHECK(control_nc.find("X-5.3") == std::string::npos);
        // The radius comes from the program's tool comment (T4 10 mm end mill).
        const Trace by_control = trace_program(read_program(control_nc, m, "control"), m);
        const Trace by_computer = trace_program(read_program(computer_nc, m, "computer"), m);
        CHECK(by_control.notes.empty());
        const std::vector<Step> a = between_leads(by_control.steps), b = between_leads(by_computer.steps);
        REQUIRE(b.size() > 10);
        REQUIRE(a.size() == b.size());
        for (std::size_t i = 0; i < a.size(); ++i) {
            CAPTURE(i);
            CAPTURE(a[i].line);
            CHECK(dist(a[i].from, b[i].from) < 0.001);
            CHECK(dist(a[i].to, b[i].to) < 0.001);
            REQUIRE(a[i].arc.has_value() == b[i].arc.has_value());
            if (a[i].arc) {
                CHECK(std::hypot(a[i].arc->centre.x - b[i].arc->centre.x, a[i].arc->centre.y - b[i].arc->centre.y) < 0.001);
                CHECK(a[i].arc->direction == b[i].arc->direction);
            }
        }
        // The job's own events, offset by the radius they carry, are the same path.
        CHECK_FALSE(compare_traces(trace_expected(expand_job(read_job(control, "c.json")), m), by_control, compare_tolerance(m)));
    }
}

TEST_CASE("compensation read back: verify --job matches camgen's control-compensation programs, as the control offsets them") {
    const fs::path dir = test::scratch("comp-verify");
    const std::string outline = samples + "plate-outline-control.json";
    const std::string pocket = write(dir, "pocket-wall-control.json", pocket_wall_control());
    for (const std::string& job : {outline, pocket})
        for (const char* machine : {"linuxcnc", "fanuc", "sinumerik", "heidenhain"}) {
            CAPTURE(job);
            CAPTURE(machine);
            const std::string text = test::post_job(test::read_file(job), machine).text;
            const std::string program = write(dir, std::string("p.") + machine, text);
            const test::Run r = run({"verify", program, "--machine", machine, "--job", job});
            CHECK(r.code == 0);
            CHECK(r.out.find("matches job") != std::string::npos);
            CHECK(r.out.find("note:") == std::string::npos);
            CHECK(r.err.empty());
        }
}

// Arcs written as chords (arcs.maxRadius) under G41/G42: the control offsets the chords, whose
// offsets meet the next move up to radius x half a chord's angle from where the arc's would
// (the G40 move after a lead-out of chords ran 0.05 mm beside the job's), and a short chord's
// rounded ends turn its offset (0.002 mm on a 0.47 mm chord written to 0.001 mm). The job's arcs
// go through the control as the chords the post writes; a chord moved into the part is still
// found.
TEST_CASE("compensation read back: arcs written as chords under G41/G42 match the job, a chord moved into the part does not") {
    const fs::path dir = test::scratch("comp-chords");
    const std::string job_text = test::read_file(samples + "plate-outline-control.json");
    nlohmann::json no_lead_in = nlohmann::json::parse(job_text);
    no_lead_in["operations"][0].erase("leadIn");
    no_lead_in["operations"][0].erase("finishing");
    const std::vector<std::pair<std::string, std::string>> jobs = {{"plate-outline-control.json", job_text},
                                                                   {"no-lead-in.json", no_lead_in.dump(2)}};
    for (const char* base : {"linuxcnc", "fanuc", "sinumerik", "heidenhain"}) {
        const std::string machine =
            write(dir, std::string(base) + "-chords.json", fmt::format(R"({{"extends": "{}", "arcs": {{"maxRadius": 4}}}})", base));
        for (const auto& [name, text] : jobs) {
            CAPTURE(base);
            CAPTURE(name);
            const std::string job = write(dir, name, text);
            const test::Run posted = run({job, "--machine", machine, "-q"});
            REQUIRE(posted.code == 0);
            // Chords, not arcs: the corner of R10 (R10.3 with the finishing stock) in straight moves.
            CHECK(posted.out.find(base == std::string("heidenhain") ? "\nCC " : "\nG2") == std::string::npos);
            const std::string program = write(dir, std::string("p.") + base, posted.out);
            const test::Run r = run({"verify", program, "--machine", machine, "--job", job});
            CHECK_MESSAGE(r.code == 0, r.out);
            CHECK(r.out.find("matches job") != std::string::npos);
        }
    }
    // A chord's end 0.05 mm into the part (the first corner, LinuxCNC): a MISMATCH at its line.
    const std::string machine = (dir / "linuxcnc-chords.json").string();
    const std::string job = (dir / "plate-outline-control.json").string();
    const std::string text = run({job, "--machine", machine, "-q"}).out;
    const std::vector<std::string> lines = test::lines_of(text);
    const auto corner = std::find(lines.begin(), lines.end(), "X8.7585 Y-0.2249");
    REQUIRE(corner != lines.end());
    const int corner_line = static_cast<int>(corner - lines.begin()) + 1;
    const test::Run r = run({"verify", write(dir, "edited.ngc", replaced(text, "\nX8.7585 Y-0.2249\n", "\nX8.7585 Y-0.1749\n")),
                             "--machine", machine, "--job", job});
    CHECK(r.code == 1);
    CHECK_MESSAGE(r.out.find(fmt::format(":{}: ", corner_line)) != std::string::npos, r.out);
}

TEST_CASE("compensation read back: a hand-edited program whose offset path gouges is a MISMATCH at the edited line") {
    const fs::path dir = test::scratch("comp-gouge");
    const std::string job = samples + "plate-outline-control.json";
    const std::string text = test::post_job(test::read_file(job), "linuxcnc").text;
    const std::vector<std::string> lines = test::lines_of(text);
    // The first wall: G1 Y110 at X-0.3 (the part's edge at X0, 0.3 mm stock). A notch in it (a
    // point 2 mm inside the part half-way up) is cut as the control offsets it: the tool centre
    // 5 mm from the notch, 2 mm into the part.
    const auto wall = std::find(lines.begin(), lines.end(), "G1 Y110");
    REQUIRE(wall != lines.end());
    const int wall_line = static_cast<int>(wall - lines.begin()) + 1;
    struct Case {
        std::string what, from, to;
        int line;
    };
    const auto entry = std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return l.rfind("G41 D4", 0) == 0; });
    REQUIRE(entry != lines.end());
    const int entry_line = static_cast<int>(entry - lines.begin()) + 1;
    for (const Case& c : {Case{"a profile point added 2 mm inside the part", "\nG1 Y110\n", "\nG1 X1.7 Y60\nG1 X-0.3 Y110\n", wall_line},
                          Case{"G41 changed to G42: the tool on the part's side", "G41 D4", "G42 D4", entry_line}}) {
        CAPTURE(c.what);
        const std::string edited = replaced(text, c.from, c.to);
        const std::string program = write(dir, "edited.ngc", edited);
        const test::Run r = run({"verify", program, "--machine", "linuxcnc", "--job", job});
        CHECK(r.code == 1);
        CHECK_MESSAGE(r.out.find(fmt::format("MISMATCH {}:{}: ", program, c.line)) != std::string::npos, r.out);
    }
    // The same program unedited matches: the difference is the edit's.
    const test::Run ok = run({"verify", write(dir, "ok.ngc", text), "--machine", "linuxcnc", "--job", job});
    CHECK(ok.code == 0);
}

TEST_CASE("compensation read back: what the control refuses is a failure naming the line and the control's message") {
    const fs::path dir = test::scratch("comp-refuse");
    const std::string table = write(dir, "tool.tbl", "T1 P1 D6 Z0 ;6 mm end mill\n");
    struct Case {
        std::string what, program;
        int line;
        std::string message;
    };
    const std::vector<Case> cases = {
        {"a concave corner the tool cannot reach", slot_program, 10,
         "Straight feed in concave corner cannot be reached by the tool without gouging"},
        {"a canned cycle under compensation",
         replaced(slot_program, "G1 Y4\n", "G81 X5 Y4 Z-1 R1\n"), 9, "Cannot use canned cycles with cutter compensation on"},
        {"a tool change under compensation", replaced(slot_program, "G1 Y4\n", "T2 M6\n"), 9,
         "Cannot change tools with cutter radius compensation on"},
        {"an entry move not longer than the radius", replaced(slot_program, "G1 X-5 Y0 F100\n", "G1 X-10 Y-7 F100\n"), 7,
         "Length of cutter compensation entry move is not greater than the tool radius"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.what);
        const std::string program = write(dir, "p.ngc", c.program);
        const test::Run r = run({"verify", program, "--machine", "linuxcnc", "--tool-table", table});
        CHECK(r.code == 1);
        CHECK(r.out.empty());
        CHECK_MESSAGE(r.err == fmt::format("camgen: {}:{}: the control refuses this: {}\n", program, c.line, c.message), r.err);
        // The library, streaming as verify does: ControlRefusal at the line (the reader would
        // refuse the feed from an unknown position after T2 M6 only on the next line).
        const Machine m = load_machine("linuxcnc");
        try {
            TraceCollector collect;
            TraceBuilder trace(m, collect, TraceOptions{{{1, 3.0}}});
            read_program(c.program, m, "p", trace);
            FAIL("not refused");
        } catch (const ControlRefusal& e) {
            CHECK(e.line() == c.line);
            CHECK(e.detail() == "the control refuses this: " + c.message);
        }
    }
    // With a job, the refusal is the comparison's verdict: a MISMATCH at that line.
    const std::string job = test::file_with("comp-refuse-job", test::read_file(samples + "plate-outline-control.json"));
    const std::string program = write(dir, "p.ngc", slot_program);
    const test::Run r = run({"verify", program, "--machine", "linuxcnc", "--tool-table", table, "--job", job});
    CHECK(r.code == 1);
    CHECK(r.out == fmt::format("{0} on machine linuxcnc\nMISMATCH {0}:10: the control refuses this: Straight feed in concave "
                               "corner cannot be reached by the tool without gouging\n",
                               program));
    // A tool small enough for the slot cuts it.
    const std::string small = write(dir, "small.tbl", "T1 P1 D3.8\n");
    CHECK(run({"verify", program, "--machine", "linuxcnc", "--tool-table", small}).code == 0);
}

TEST_CASE("compensation read back: the radius comes from --tool-table, the job, the tool comment; else a note") {
    const fs::path dir = test::scratch("comp-radius");
    // The slot 40 mm wide: every tool here fits.
    const std::string wide = replaced(slot_program, "G1 Y4\n", "G1 Y40\n");
    const std::string program = write(dir, "slot.ngc", wide);
    const auto box_x = [](const std::string& out) {
        std::smatch m;
        REQUIRE(std::regex_search(out, m, std::regex(R"(X (-?[0-9.]+) \.\. (-?[0-9.]+))")));
        return std::pair<double, double>{std::stod(m[1]), std::stod(m[2])};
    };
    // No radius known: the moves as programmed, and a note says so.
    const test::Run none = run({"verify", program, "--machine", "linuxcnc"});
    CHECK(none.code == 0);
    CHECK(none.out.find("note: line 6: cutter radius compensation with offset register D1, whose radius camgen does not know "
                        "(verify --tool-table gives it): its moves are taken as programmed, not as the control offsets them\n") !=
          std::string::npos);
    CHECK(box_x(none.out).second == doctest::Approx(20.0));
    // A 6 mm tool in mm, a 0.25 in tool in inches: the far wall's tool centre moves in by the radius.
    const test::Run mm = run({"verify", program, "--machine", "linuxcnc", "--tool-table", write(dir, "mm.tbl", "T1 P1 D6\n")});
    CHECK(mm.out.find("note:") == std::string::npos);
    CHECK(box_x(mm.out).second == doctest::Approx(17.0));
    const test::Run inch = run({"verify", program, "--machine", "linuxcnc", "--tool-table",
                                write(dir, "in.tbl", "T1 P1 D0.25 Z0 ;quarter inch\n"), "--tool-table-units", "inch"});
    CHECK(box_x(inch.out).second == doctest::Approx(20.0 - 3.175));
    // From the program's tool comment, as camgen writes it.
    const test::Run comment =
        run({"verify", write(dir, "c.ngc", replaced(wide, "T1 M6\n", "(T1 8 mm end mill)\nT1 M6\n")), "--machine", "linuxcnc"});
    CHECK(comment.out.find("note:") == std::string::npos);
    CHECK(box_x(comment.out).second == doctest::Approx(16.0));
    // With --job: the job's tool of that number (a 10 mm mill as tool 4 here: D4).
    const std::string job = samples + "plate-outline-control.json";
    const Machine m = load_machine("linuxcnc");
    const std::string d4_program = [&] {
        std::string t = replaced(test::read_file(program), "G41 D1", "G41 D4");
        return write(dir, "d4.ngc", t);
    }();
    const test::Run with_job = run({"verify", d4_program, "--machine", "linuxcnc", "--job", job});
    CHECK(with_job.out.find("note:") == std::string::npos);
    CHECK(box_x(with_job.out).second == doctest::Approx(15.0));
    // The library: the map of D register -> radius.
    const Trace t = trace_program(read_program(test::read_file(program), m, "p"), m, TraceOptions{{{1, 2.0}}});
    CHECK(t.notes.empty());
    double max_x = -1e9;
    for (const Step& s : t.steps) max_x = std::max(max_x, s.to.x);
    CHECK(max_x == doctest::Approx(18.0));
}

TEST_CASE("compensation read back: --stats and --plot show the tool centre, the extent grown by the radius") {
    const fs::path dir = test::scratch("comp-stats");
    const std::string job = samples + "plate-outline-control.json";
    const std::string program = write(dir, "p.ngc", test::post_job(test::read_file(job), "linuxcnc").text);
    // The profile is X -0.3 .. 200.3, Y -0.3 .. 120.3; the 10 mm tool's centre 5 mm outside it.
    const test::Run v = run({"verify", program, "--machine", "linuxcnc", "--plot", (dir / "p.svg").string()});
    CHECK(v.code == 0);
    CHECK(v.out.find("X -5.300 .. 205.300  Y -15.800 .. 125.300") != std::string::npos);
    const test::Run posted = run({job, "--machine", "linuxcnc", "--stats", "-o", (dir / "q.ngc").string()});
    CHECK(posted.code == 0);
    CHECK(posted.err.find("X -5.300 .. 205.300  Y -15.800 .. 125.300") != std::string::npos);
    // The drawing's frame: with the radius known it reaches 5 mm further left than the
    // programmed line, which a zero-diameter tool table leaves as it is.
    const Machine m = load_machine("linuxcnc");
    const std::string text = test::read_file(program);
    const Trace centre = trace_program(read_program(text, m, "p"), m);
    const Trace line = trace_program(read_program(text, m, "p"), m, TraceOptions{{{4, 0.0}}});
    const ProgramStats centre_stats = compute_stats(centre, m), line_stats = compute_stats(line, m);
    CHECK(centre_stats.box.min.x == doctest::Approx(line_stats.box.min.x - 5.0));
    CHECK(centre_stats.box.max.y == doctest::Approx(line_stats.box.max.y + 5.0));
    const BackplotDrawing a = backplot_drawing(centre, centre_stats, {"p.ngc", "linuxcnc", MachineKind::mill});
    const BackplotDrawing b = backplot_drawing(line, line_stats, {"p.ngc", "linuxcnc", MachineKind::mill});
    CHECK(a.frame.min_u < b.frame.min_u - 5.0);
    CHECK(test::read_file((dir / "p.svg").string()) == a.svg);
}

TEST_CASE("tool table: LinuxCNC's format, diameters by tool number in mm; a bad line is an error naming the file and line") {
    const auto t = read_tool_table("T1 P1 D6.0 Z0 ;6mm mill\n\n; a comment line\nt2 p2 d0.5 x0 z-1.5 q3\nT7 P3\n", "t.tbl", Units::mm);
    CHECK(t == std::map<int, double>{{1, 6.0}, {2, 0.5}, {7, 0.0}});
    CHECK(read_tool_table("T1 P1 D0.236220472 Z0\n", "t.tbl", Units::inch).at(1) == doctest::Approx(6.0));
    struct Bad {
        std::string text, message;
    };
    for (const Bad& b : std::vector<Bad>{
             {"T1 P1 D6\nT2 P2 R3\n", "t.tbl:2: \"R3\" is not a word of a tool table (T P X Y Z A B C U V W D I J Q)"},
             {"T1 P1 D6x\n", "t.tbl:1: D: \"6x\" is not a number"},
             {"T1 P1 D\n", "t.tbl:1: D: \"\" is not a number"},
             {"P1 D6\n", "t.tbl:1: a tool without its number T"},
             {"T1 D6\n\nT1 D3\n", "t.tbl:3: tool 1 again (it is on line 1)"},
             {"T1.5 D6\n", "t.tbl:1: T1.5: a tool number is a whole number, 0 or more"},
             {"T1 D-6\n", "t.tbl:1: D-6: a diameter below 0"},
             {"T1 D6 D7\n", "t.tbl:1: two D words in one tool"},
             {"T1 D1e3\n", "t.tbl:1: D: \"1e3\" is not a number"},
         }) {
        CAPTURE(b.text);
        try {
            (void)read_tool_table(b.text, "t.tbl", Units::mm);
            FAIL("accepted");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()) == b.message);
        }
    }
    // On the command line: exit 1, the message, nothing on standard output.
    const fs::path dir = test::scratch("comp-table");
    const std::string program = write(dir, "p.ngc", slot_program);
    const std::string bad = write(dir, "bad.tbl", "T1 P1 D6\nT2 P2 D4 K1\n");
    const test::Run r = run({"verify", program, "--machine", "linuxcnc", "--tool-table", bad});
    CHECK(r.code == 1);
    CHECK(r.out.empty());
    CHECK(r.err == fmt::format("camgen: {}:2: \"K1\" is not a word of a tool table (T P X Y Z A B C U V W D I J Q)\n", bad));
    const test::Run missing = run({"verify", program, "--machine", "linuxcnc", "--tool-table", (dir / "none.tbl").string()});
    CHECK(missing.code == 3);
    CHECK(run({"verify", program, "--machine", "linuxcnc", "--tool-table", bad, "--tool-table-units", "cm"}).code == 2);
}

}  // namespace test_trace_compensation
