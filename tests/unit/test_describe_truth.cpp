// Issue 25 item 6: --describe-machine tells the truth. For every built-in machine its
// capabilities (`--describe-machine M --json`, "capabilities") are held against what posting
// probe jobs does: what it says is supported posts (canned or longhand as it says), what it
// says is refused is refused with the message it quotes. The text description says the same,
// and a machine file's one-line description names no canned cycle camgen does not write.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/reader/reader.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_describe_truth {

using namespace camgen;
using test::Run;
using test::run;
using Json = nlohmann::json;

namespace {

// The capabilities --describe-machine --json prints for a machine.
Json capabilities_of(const std::string& machine) {
    const Run r = run({"--describe-machine", machine, "--json"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const Json doc = Json::parse(r.out);
    REQUIRE(doc.contains("machine"));
    REQUIRE(doc.contains("capabilities"));
    return doc["capabilities"];
}

// A job of these tools and operations (JSON text of the arrays' members), clearance 20.
std::string job_of(const std::string& tools, const std::string& operations, const std::string& extra = "") {
    return R"({"name": "probe", "units": "mm", "clearance": 20)" + extra + R"(, "tools": [)" + tools +
           R"(], "operations": [)" + operations + "]}";
}

// Posts a job text for a machine into a file; the run (quiet unless `stats`).
struct Posted {
    Run run;
    std::string program;  // its path
};
Posted post(const std::string& name, const std::string& machine, const std::string& job, bool stats = false) {
    const std::filesystem::path dir = test::scratch("truth-" + machine + "-" + name);
    const std::string file = (dir / "job.json").string();
    std::ofstream(file) << job;
    const std::string program = (dir / "program.nc").string();
    std::vector<std::string> args{file, "--machine", machine, "-o", program};
    args.push_back(stats ? "--stats" : "--quiet");
    return {run(args), program};
}

// Checks a refused run: exit 1, the capability's message, nothing written.
void check_refused(const Posted& p, const std::string& message) {
    CHECK(p.run.code == 1);
    CHECK_MESSAGE(p.run.err.find(message) != std::string::npos, p.run.err);
    CHECK_FALSE(std::filesystem::exists(p.program));
}

// The Arc events of a posted program, read back with the machine.
std::vector<Arc> arcs_read_back(const Posted& p, const std::string& machine) {
    std::vector<Arc> arcs;
    for (const ReadEvent& e : read_program(test::read_file(p.program), load_machine(machine), p.program))
        if (const auto* a = std::get_if<Arc>(&e.event)) arcs.push_back(*a);
    return arcs;
}

const std::string mill_tools = R"({"number": 1, "type": "drill", "diameter": 5, "rpm": 1000},
  {"number": 2, "type": "tap", "diameter": 8, "rpm": 300},
  {"number": 3, "type": "end-mill", "diameter": 6, "rpm": 3000},
  {"number": 4, "type": "drill", "diameter": 5, "rpm": 1000, "direction": "ccw"})";

const std::string lathe_tools = R"({"number": 1, "type": "drill", "diameter": 5, "rpm": 1000},
  {"number": 2, "type": "tap", "diameter": 8, "rpm": 300},
  {"number": 3, "type": "tap", "diameter": 8, "rpm": 300, "direction": "ccw"},
  {"number": 4, "type": "turning-tool", "diameter": 0.8, "rpm": 1200},
  {"number": 5, "type": "drill", "diameter": 5, "rpm": 1000, "direction": "ccw"})";

// A mill's drill operation (two holes) of cycle kind `kind`, with the fields the kind needs.
std::string mill_cycle(const std::string& kind, const std::string& output) {
    std::string fields = R"("tool": 1, "retractPlane": 5, "endDepth": 6, "plungingFeedrate": 100)";
    if (kind == "dwell" || kind == "bore-dwell") fields += R"(, "bottomDwell": 0.5)";
    if (kind == "deep" || kind == "chip-break") fields += R"(, "firstDepth": 2)";
    if (kind == "tap" || kind == "tap-left") fields = R"("tool": 2, "retractPlane": 5, "endDepth": 12, "pitch": 1.25)";
    return fmt::format(R"({{"type": "drill", "cycle": "{}", {}, "output": "{}", "holes": [[10, 10], [30, 10]]}})", kind,
                       fields, output);
}

// A lathe's turn-drill (one hole on the axis) whose fields ask for cycle kind `kind`.
std::string lathe_cycle(const std::string& kind, const std::string& output, double peck_clearance) {
    std::string fields = R"("tool": 1, "plungingFeedrate": 100)";
    if (kind == "dwell") fields += R"(, "lowerDwell": 0.5)";
    if (kind == "deep") fields += R"(, "firstPeckDepth": 3)";
    if (kind == "chip-break") fields += fmt::format(R"(, "firstPeckDepth": 3, "peckRetract": {})", peck_clearance);
    if (kind == "tap") fields = R"("tool": 2, "pitch": 1.25)";
    if (kind == "tap-left") fields = R"("tool": 3, "pitch": 1.25)";
    return fmt::format(R"({{"type": "turn-drill", {}, "startDepth": 0, "endDepth": -10, "safeDistance": 2, "output": "{}"}})",
                       fields, output);
}

// "hole cycles    C canned, L longhand" as --stats prints it.
std::string hole_counts(int canned, int longhand) {
    return fmt::format("hole cycles    {} canned, {} longhand\n", canned, longhand);
}

}  // namespace

TEST_CASE("describe: every drilling kind posts canned, longhand or is refused as --describe-machine --json says") {
    for (const auto& [machine, description] : list_machines()) {
        const Json caps = capabilities_of(machine);
        const Machine m = load_machine(machine);
        const bool lathe = m.kind == MachineKind::lathe;
        const int holes = lathe ? 1 : 2;
        REQUIRE(caps.contains("drilling"));
        // Every kind a job of the machine's kind can ask for is described.
        CHECK(caps["drilling"].size() == (lathe ? 6u : 9u));
        for (const auto& [kind, cycle] : caps["drilling"].items()) {
            for (const std::string output : {"auto", "canned", "longhand"}) {
                INFO(machine << " " << kind << " output " << output << ": " << cycle.dump());
                const std::string op = lathe ? lathe_cycle(kind, output, m.peck_clearance) : mill_cycle(kind, output);
                const Posted p = post(kind + "-" + output, machine, job_of(lathe ? lathe_tools : mill_tools, op), true);
                if (!cycle["supported"].get<bool>()) {
                    CHECK(cycle["canned"].is_null());
                    CHECK_FALSE(cycle["longhand"].get<bool>());
                    check_refused(p, cycle["refused"].get<std::string>());
                    continue;
                }
                const bool canned = !cycle["canned"].is_null(), longhand = cycle["longhand"].get<bool>();
                const bool posts = output == "auto" || (output == "canned" ? canned : longhand);
                if (!posts) {
                    CHECK(p.run.code == 1);
                    CHECK_FALSE(std::filesystem::exists(p.program));
                    continue;
                }
                REQUIRE_MESSAGE(p.run.code == 0, p.run.err);
                const bool as_canned = output == "canned" || (output == "auto" && canned);
                CHECK_MESSAGE(p.run.err.find(as_canned ? hole_counts(holes, 0) : hole_counts(0, holes)) != std::string::npos,
                              p.run.err);
                if (as_canned) CHECK(test::read_file(p.program).find(cycle["canned"].get<std::string>()) != std::string::npos);
            }
        }
    }
}

TEST_CASE("describe: control compensation, arcs per plane and helices post as --describe-machine --json says") {
    const std::string plate_control = test::read_file(CAMGEN_SOURCE_DIR "/samples/plate-outline-control.json");
    for (const auto& [machine, description] : list_machines()) {
        INFO(machine);
        const Json caps = capabilities_of(machine);
        const bool lathe = load_machine(machine).kind == MachineKind::lathe;
        if (lathe) {
            // No lathe operation asks for control compensation or a helix: neither is described.
            CHECK_FALSE(caps.contains("controlCompensation"));
            CHECK_FALSE(caps.contains("helices"));
            REQUIRE(caps["arcs"].size() == 1);
            const std::string op = R"({"type": "turn-profile", "tool": 4, "feed": 100, "start": [24, 0], "retractX": 44,
              "path": [{"line": [30, 0]}, {"arc": {"end": [40, -5], "centre": [40, 0], "direction": "cw"}}]})";
            const Posted p = post("arc-xz", machine, job_of(lathe_tools, op));
            REQUIRE_MESSAGE(p.run.code == 0, p.run.err);
            const std::vector<Arc> arcs = arcs_read_back(p, machine);
            CHECK(caps["arcs"]["xz"] == (arcs.empty() ? "lines" : "arcs"));
            for (const Arc& a : arcs) CHECK(a.plane == Plane::xz);
            continue;
        }
        // A contour with the control compensating: the sample.
        const Json& comp = caps["controlCompensation"];
        const Posted c = post("control", machine, plate_control);
        if (comp["supported"].get<bool>()) {
            CHECK_MESSAGE(c.run.code == 0, c.run.err);
        } else {
            check_refused(c, comp["refused"].get<std::string>());
        }
        // One arc in each plane (a half circle of radius 5 dipping from Z-1), and a helix.
        const std::map<std::string, std::string> arc_paths = {
            {"xy", R"({"arc": {"end": [10, 0], "centre": [5, 0], "direction": "ccw"}})"},
            {"xz", R"({"arc": {"plane": "xz", "end": [10, 0, -1], "centre": [5, 0, -1], "direction": "cw"}})"},
            {"yz", R"({"arc": {"plane": "yz", "end": [0, 10, -1], "centre": [0, 5, -1], "direction": "ccw"}})"},
        };
        for (const auto& [plane, element] : arc_paths) {
            INFO("arcs in " << plane);
            const std::string op = R"({"type": "path", "tool": 3, "z": -1, "feed": 300, "start": [0, 0], "path": [)" + element + "]}";
            const Posted p = post("arc-" + plane, machine, job_of(mill_tools, op));
            REQUIRE_MESSAGE(p.run.code == 0, p.run.err);
            const std::vector<Arc> arcs = arcs_read_back(p, machine);
            CHECK(caps["arcs"][plane] == (arcs.empty() ? "lines" : "arcs"));
            for (const Arc& a : arcs) CHECK(name_of(plane_names, a.plane) == plane);
        }
        const std::string helix = R"({"type": "path", "tool": 3, "z": -1, "feed": 300, "start": [0, 0],
          "path": [{"helix": {"centre": [5, 0], "direction": "ccw", "z": -5, "turns": 2}}]})";
        const Posted h = post("helix", machine, job_of(mill_tools, helix));
        REQUIRE_MESSAGE(h.run.code == 0, h.run.err);
        const std::vector<Arc> arcs = arcs_read_back(h, machine);
        CHECK(caps["helices"] == (arcs.empty() ? "lines" : "arcs"));
        for (const Arc& a : arcs) CHECK(a.to.z < -1);
    }
}

TEST_CASE("describe: a counter-clockwise spindle and a program number post as --describe-machine --json says") {
    for (const auto& [machine, description] : list_machines()) {
        INFO(machine);
        const Json caps = capabilities_of(machine);
        const bool lathe = load_machine(machine).kind == MachineKind::lathe;
        const std::string ccw_op = lathe ? R"({"type": "turn-drill", "tool": 5, "startDepth": 0, "endDepth": -10,
                                               "safeDistance": 2, "plungingFeedrate": 100})"
                                         : R"({"type": "drill", "tool": 4, "retractPlane": 5, "endDepth": 6,
                                               "plungingFeedrate": 100, "holes": [[10, 10]]})";
        const std::string tools = lathe ? lathe_tools : mill_tools;
        const Posted ccw = post("ccw", machine, job_of(tools, ccw_op));
        if (caps["counterClockwiseSpindle"]["supported"].get<bool>()) {
            CHECK_MESSAGE(ccw.run.code == 0, ccw.run.err);
        } else {
            check_refused(ccw, caps["counterClockwiseSpindle"]["refused"].get<std::string>());
        }
        // The same hole with a clockwise spindle and a program number.
        std::string cw_op = ccw_op;
        cw_op.replace(cw_op.find(lathe ? "\"tool\": 5" : "\"tool\": 4"), 9, "\"tool\": 1");
        const Posted number = post("number", machine, job_of(tools, cw_op, R"(, "programNumber": 7)"));
        if (caps["programNumber"]["supported"].get<bool>()) {
            CHECK_MESSAGE(number.run.code == 0, number.run.err);
            CHECK(test::read_file(number.program).find("O0007") != std::string::npos);
        } else {
            check_refused(number, caps["programNumber"]["refused"].get<std::string>());
        }
        CHECK(post("plain", machine, job_of(tools, cw_op)).run.code == 0);
    }
}

TEST_CASE("describe: a constant surface speed posts as --describe-machine --json says") {
    for (const auto& [machine, description] : list_machines()) {
        INFO(machine);
        const Json caps = capabilities_of(machine);
        const Machine m = load_machine(machine);
        // A lathe job's turning tool at 200 m/min (a mill refuses it before its tools could be
        // read for it, at the post: the same Spindle event).
        const std::vector<Event> events{ToolChange{1, 0.8, ""}, Spindle{SpindleState::cw, 2500, 200}};
        if (caps["constantSurfaceSpeed"]["supported"].get<bool>()) {
            CHECK(m.kind == MachineKind::lathe);
            const std::string op = R"({"type": "turn-face", "tool": 6, "z": 0, "stepdown": 1, "outerX": 40, "startZ": 1,
                                       "feedMode": "per-revolution", "feed": 0.2})";
            const std::string tools = lathe_tools + R"(, {"number": 6, "type": "turning-tool", "diameter": 0.8,
                                                         "surfaceSpeed": 200, "maxRpm": 2500})";
            const Posted p = post("g96", machine, job_of(tools, op));
            REQUIRE_MESSAGE(p.run.code == 0, p.run.err);
            CHECK(test::read_file(p.program).find("G96") != std::string::npos);
            CHECK(test::post_events(m, events).find("G96") != std::string::npos);
        } else {
            const std::string refused = caps["constantSurfaceSpeed"]["refused"].get<std::string>();
            CHECK_THROWS_WITH_AS(test::post_events(m, events), doctest::Contains(refused.c_str()), InputError);
        }
    }
}

TEST_CASE("describe: the text description says what the --json capabilities say") {
    for (const auto& [machine, description] : list_machines()) {
        INFO(machine);
        const Json caps = capabilities_of(machine);
        const Run r = run({"--describe-machine", machine});
        REQUIRE(r.code == 0);
        auto has_line = [&](const std::string& label, const std::string& value) {
            const std::string line = fmt::format("  {:<24}{}\n", label, value);
            INFO(line);
            CHECK(r.out.find(line) != std::string::npos);
        };
        auto verdict = [](const Json& c, const std::string& yes) {
            return c["supported"].get<bool>() ? yes : "refused: " + c["refused"].get<std::string>();
        };
        if (caps.contains("controlCompensation"))
            has_line("control compensation", verdict(caps["controlCompensation"], "yes: G41/G42 for \"compensation\": \"control\""));
        for (const auto& [plane, how] : caps["arcs"].items())
            has_line("arcs in " + plane, how == "arcs" ? "arc blocks" : "straight moves");
        if (caps.contains("helices")) has_line("helices", caps["helices"] == "arcs" ? "helical arc blocks" : "straight moves");
        has_line("spindle ccw", verdict(caps["counterClockwiseSpindle"], "yes"));
        has_line("programNumber", verdict(caps["programNumber"], "yes"));
        has_line("surface speed",
                 verdict(caps["constantSurfaceSpeed"], "yes: G96 for a tool's surfaceSpeed, within its maxRpm (else maxRpm above)"));
        for (const auto& [kind, cycle] : caps["drilling"].items()) {
            std::string text = "longhand";
            if (!cycle["supported"].get<bool>()) text = "refused: " + cycle["refused"].get<std::string>();
            else if (!cycle["canned"].is_null())
                text = fmt::format("canned {}; fields: {}{}", cycle["canned"].get<std::string>(),
                                   cycle["fields"].empty() ? "-" : fmt::format("{}", fmt::join(cycle["fields"].get<std::vector<std::string>>(), ", ")),
                                   cycle["longhand"].get<bool>() ? "" : "; never longhand (rigid tapping)");
            has_line(kind, text);
        }
        // The machine file's own flag is not what the description reports.
        CHECK(r.out.find("cutterCompensation") == std::string::npos);
    }
    // The cases of issue 25: wabeco has no control compensation and cannot tap.
    const Run w = run({"--describe-machine", "wabeco"});
    CHECK(w.out.find("  control compensation    refused: machine wabeco has no cutter radius compensation") != std::string::npos);
    CHECK(w.out.find("  tap                     refused: machine wabeco cannot tap: ") != std::string::npos);
    CHECK(w.out.find("  tap-left                refused: machine wabeco cannot tap: ") != std::string::npos);
}

TEST_CASE("describe: a machine's one-line description names only canned cycles it writes") {
    // G73-G89, CYCLE81-89 and CYCL DEF 2xx, with ranges ("G81-G89", "CYCLE81-84") spelt out.
    const std::regex code(R"((G|CYCLE|CYCL DEF )(\d+)(?:-G?(\d+))?)");
    for (const auto& [machine, description] : list_machines()) {
        INFO(machine << ": " << description);
        const Machine m = load_machine(machine);
        std::set<std::string> written;
        for (const DrillingCycleSpec& c : m.drilling) written.insert(c.name);
        for (auto it = std::sregex_iterator(description.begin(), description.end(), code); it != std::sregex_iterator(); ++it) {
            const std::string prefix = (*it)[1];
            const int first = std::stoi((*it)[2]);
            const int last = (*it)[3].matched ? std::stoi((*it)[3]) : first;
            for (int n = first; n <= last; ++n) {
                // G80 cancels a cycle, nccad's G79 repeats its G81 at the next hole; below G73 no
                // G code is a drilling cycle.
                const bool cycle =
                    prefix == "G" ? n >= 73 && n <= 89 && n != 80 && !(n == 79 && m.dialect == "nccad") : true;
                if (!cycle) continue;
                const std::string name = prefix + std::to_string(n);
                CHECK_MESSAGE(written.count(name), name << " is named but machine " << machine << " has no such canned cycle");
            }
        }
    }
}

TEST_CASE("describe: an nccad machine file cannot claim a canned cycle nccad does not write") {
    // nccad writes every canned cycle as G81 X Y Z B F: a "deep" G83 would have been described
    // as canned G83 and drilled without a single peck.
    const std::filesystem::path dir = test::scratch("truth-nccad-cycles");
    const std::string machine = (dir / "pecking-wabeco.json").string();
    std::ofstream(machine) << R"({"extends": "wabeco", "drilling": {"cycles": [
  {"name": "G81", "kind": "drill", "fields": ["plungingFeedrate"]},
  {"name": "G83", "kind": "deep", "fields": ["plungingFeedrate", "firstDepth"]}]}})";
    const Run d = run({"--describe-machine", machine});
    CHECK(d.code == 1);
    CHECK(d.out == "");
    CHECK_MESSAGE(d.err.find(machine + ":3: /drilling/cycles/1: nccad's one canned cycle is G81 X Y Z B F") != std::string::npos,
                  d.err);
    const std::string job = (dir / "deep.json").string();
    std::ofstream(job) << job_of(mill_tools, mill_cycle("deep", "auto"));
    CHECK(run({job, "--machine", machine}).code == 1);
    // A safe distance G81 does not carry either.
    std::ofstream(machine) << R"({"extends": "wabeco", "drilling": {"cycles": [
  {"name": "G81", "kind": "drill", "fields": ["safeDistance", "plungingFeedrate"]}]}})";
    CHECK(run({"--describe-machine", machine}).code == 1);
    // The built-in cycle is what nccad writes.
    std::ofstream(machine) << R"({"extends": "wabeco", "drilling": {"cycles": [
  {"name": "G81", "kind": "drill", "fields": ["plungingFeedrate"]}]}})";
    CHECK(run({"--describe-machine", machine}).code == 0);
}

}  // namespace test_describe_truth
