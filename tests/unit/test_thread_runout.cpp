// turn-thread's chamfered runout (issue 30): each pass ends with a taper synchronised with the
// spindle, pulling out by the thread's depth over runoutLength (LinuxCNC G76 E L2). The
// geometry of the passes worked out here on its own; the three lathes' words (LinuxCNC G33 X Z K
// with K along the path, Fanuc G32 X Z F and Sinumerik G33 X Z K along Z; LinuxCNC's G76 E L2)
// read back to the job's moves; Fanuc's G76 does not carry it (a note, or refused under
// canned); refusals with their JSON paths; camgen simulate finds the runout as designed and one
// cut 0.2 mm too deep.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/operations/design.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/vocabulary/threads.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_thread_runout {

using namespace camgen;

namespace {

namespace fs = std::filesystem;

std::string runout_refusal(const std::string& text) {
    try {
        (void)read_job(text, "thread.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// The thread alone: no stock (a thread is cut on a diameter turned to its major, which a bar
// nothing turned is not: check_blade_material).
std::string runout_job(const std::string& op) {
    return fmt::format(R"({{"clearance": 20, "tools": [
 {{"number": 5, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 500}}],
 "operations": [{{"type": "turn-thread", "tool": 5, {}}}]}})",
                       op);
}

struct RunoutPosted {
    std::string text, notes;
};

RunoutPosted runout_post(const std::string& job_text, const std::string& machine) {
    const Machine m = load_machine(machine);  // (the post keeps a reference to it)
    test::Posted p = test::post_noted(job_text, m, "t.json");
    return {std::move(p.text), std::move(p.notes)};
}

// The job read back from its program matches the job's own moves.
void check_read_back(const std::string& job_text, const std::string& program, const std::string& machine) {
    const Job j = read_job(job_text, "t.json");
    const Machine m = load_machine(machine);
    const Trace read = trace_program(read_program(program, m, "t.nc"), m);
    const auto mismatch = compare_traces(trace_expected(expand_job(j), m), read, compare_tolerance(m, 0.0));
    CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : "") << "\n" << program);
}

// The synchronised blocks of a program that move X (the tapers): their X (diameter), Z and lead
// word, with the X and Z they started from (the blocks before them, modal).
struct TaperBlock {
    double x0 = 0, z0 = 0, x = 0, z = 0, lead = 0;
};
std::vector<TaperBlock> taper_blocks(const std::string& program, const std::string& code, char lead_letter) {
    std::vector<TaperBlock> out;
    double x = 0, z = 0;
    const std::regex word(R"(([XZ])(-?[0-9.]+))");
    for (std::string line : test::lines_of(program)) {
        // (Sinumerik's block numbers left out)
        if (line.size() > 1 && line[0] == 'N' && std::isdigit(static_cast<unsigned char>(line[1])))
            line = line.substr(std::min(line.size(), line.find(' ') + 1));
        const double x0 = x, z0 = z;
        for (auto it = std::sregex_iterator(line.begin(), line.end(), word); it != std::sregex_iterator(); ++it) {
            const std::size_t at = static_cast<std::size_t>(it->position(0));
            if (at > 0 && std::isalnum(static_cast<unsigned char>(line[at - 1]))) continue;  // (not in a name)
            ((*it)[1] == "X" ? x : z) = std::stod((*it)[2]);
        }
        if (line.rfind(code + " X", 0) == 0) {
            const auto words = test::words_of(line);
            out.push_back({x0, z0, x, z, std::stod(words.at(lead_letter))});
        }
    }
    return out;
}

}  // namespace

TEST_CASE("turn-thread runout: each pass cuts to endZ + runoutLength, then a synchronised taper out by the thread's depth") {
    for (const bool internal : {false, true}) {
        for (const double length : {0.0, 3.0}) {
            CAPTURE(internal);
            CAPTURE(length);
            const std::string extra = length > 0 ? fmt::format(R"(, "runoutLength": {})", length) : "";
            const std::string text = runout_job(
                fmt::format(R"("thread": "M20x2.5", "side": "{}", "startZ": -2, "endZ": -22, "firstDepth": 0.35,
                               "runout": "chamfered", "output": "longhand"{})",
                            internal ? "internal" : "external", extra));
            const Job j = read_job(text, "t.json");
            const auto& op = std::get<TurnThreadOp>(j.operations.front());
            const double L = length > 0 ? length : 2.5;  // (default: one lead)
            CHECK(op.runout_length == doctest::Approx(L));
            const double major = 10, minor = (internal ? internal_minor_diameter(20, 2.5) : external_minor_diameter(20, 2.5)) / 2;
            const double surface = internal ? minor : major, total = major - minor, out = internal ? -1.0 : 1.0;
            const double away = surface + out * 1.0;  // retract 1
            Vec3 at{};
            std::size_t pass = 0;
            std::vector<Event> events = expand_job(j);
            for (std::size_t n = 0; n < events.size(); ++n) {
                const auto* t = std::get_if<ThreadFeed>(&events[n]);
                if (!t) {
                    if (const auto* r = std::get_if<Rapid>(&events[n])) at = r->to;
                    continue;
                }
                // The straight part at the pass's depth to endZ + L, then the taper.
                REQUIRE(n + 2 < events.size());
                const auto* taper = std::get_if<ThreadFeed>(&events[n + 1]);
                REQUIRE(taper);
                const double d = op.depths[pass % op.depths.size()];
                CHECK(t->to.x == doctest::Approx(surface - out * d));
                CHECK(t->to.x == doctest::Approx(at.x));
                CHECK(t->to.z == doctest::Approx(-22 + L));
                CHECK(t->lead == doctest::Approx(2.5));
                CHECK(taper->to.z == doctest::Approx(-22));
                CHECK(taper->to.x == doctest::Approx(surface - out * d + out * total));
                CHECK(taper->lead == doctest::Approx(2.5));  // along Z
                // Out: retract beyond the taper's end, as G76 returns.
                const auto* back = std::get_if<Rapid>(&events[n + 2]);
                REQUIRE(back);
                CHECK(back->to.x == doctest::Approx(away + out * (total - d)));
                CHECK(back->to.z == doctest::Approx(-22));
                at = back->to;
                n += 2;
                ++pass;
            }
            CHECK(pass == op.depths.size());
            // The last pass's taper runs from the root to the crest.
            CHECK(op.depths.back() == doctest::Approx(total));
        }
    }
}

TEST_CASE("turn-thread runout: the three lathes' tapered synchronised moves carry the lead each control measures, and read back") {
    const std::string text = runout_job(R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "springPasses": 1,
                                           "infeedAngle": 29.5, "runout": "chamfered", "runoutLength": 3, "output": "longhand")");
    const double total = 0.613435 * 2.5;  // (the table's depth, mm radial)
    struct Lathe {
        std::string name, code;
        char lead;
        bool along_path;
    };
    for (const Lathe& l : {Lathe{"linuxcnc-lathe", "G33", 'K', true}, Lathe{"fanuc-lathe", "G32", 'F', false},
                           Lathe{"sinumerik-lathe", "G33", 'K', false}}) {
        CAPTURE(l.name);
        const RunoutPosted p = runout_post(text, l.name);
        const std::vector<TaperBlock> tapers = taper_blocks(p.text, l.code, l.lead);
        REQUIRE_MESSAGE(!tapers.empty(), p.text);
        const Job j = read_job(text, "t.json");
        CHECK(tapers.size() == std::get<TurnThreadOp>(j.operations.front()).depths.size());
        for (const TaperBlock& b : tapers) {
            const double dx = (b.x - b.x0) / 2, dz = b.z0 - b.z;  // radial, along -Z
            CHECK(dz == doctest::Approx(3).epsilon(1e-6));
            CHECK(dx == doctest::Approx(total).epsilon(1e-3));
            const double want = l.along_path ? 2.5 * std::hypot(dx, dz) / dz : 2.5;
            CHECK_MESSAGE(std::abs(b.lead - want) <= 0.0002, b.lead << " " << want);  // (X and Z as written, rounded)
        }
        // The last pass's taper ends at the major diameter at endZ.
        CHECK(tapers.back().x == doctest::Approx(20));
        CHECK(tapers.back().z == doctest::Approx(-20));
        check_read_back(text, p.text, l.name);
        // A lead off by 0.01 in one taper is a mismatch.
        const Machine m = load_machine(l.name);
        const std::regex last_taper(l.code + " X20(\\.0+)? Z-20(\\.0+)? " + l.lead + "([0-9.]+)");
        std::smatch found;
        REQUIRE(std::regex_search(p.text, found, last_taper));
        std::string wrong = p.text;
        const std::string lead_text = found[3];
        const std::string broken = found.str(0).substr(0, found.str(0).size() - lead_text.size()) +
                                   fmt::format("{:.4f}", std::stod(lead_text) + 0.01);
        wrong.replace(static_cast<std::size_t>(found.position(0)), found.str(0).size(), broken);
        const Trace bad = trace_program(read_program(wrong, m, "t.nc"), m);
        CHECK(compare_traces(trace_expected(expand_job(j), m), bad, compare_tolerance(m, 0.0)));
    }
}

TEST_CASE("turn-thread runout: LinuxCNC's G76 carries it as E and L2; Fanuc's G76 does not (longhand with a note, canned refused)") {
    const std::string op = R"("thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.4, "springPasses": 2,
                              "infeedAngle": 29.5, "approachDistance": 6, "runout": "chamfered", "runoutLength": 2)";
    {
        const std::string text = runout_job(op);
        const RunoutPosted p = runout_post(text, "linuxcnc-lathe");
        CHECK_MESSAGE(p.text.find("G76 P2.5 Z-20 I-2 J0.8 K3.0672 R2 Q29.5 H2 E2 L2\n") != std::string::npos, p.text);
        CHECK(p.text.find("G33") == std::string::npos);
        check_read_back(text, p.text, "linuxcnc-lathe");
        // The reader's G76 passes: five moves each, the fourth the taper out by K to the pass's end.
        const Machine m = load_machine("linuxcnc-lathe");
        int tapers = 0;
        Vec3 at{};
        for (const ReadEvent& e : read_program(p.text, m, "t.nc")) {
            if (const auto* t = std::get_if<ThreadFeed>(&e.event)) {
                if (std::abs(t->to.x - at.x) > 1e-9) {
                    ++tapers;
                    CHECK(at.z - t->to.z == doctest::Approx(2));
                    CHECK(t->to.x - at.x == doctest::Approx(3.0672 / 2));
                    CHECK(t->lead == doctest::Approx(2.5));
                }
                at = t->to;
            } else if (const auto* r = std::get_if<Rapid>(&e.event)) {
                at = r->to;
            }
        }
        const Job j = read_job(text, "t.json");
        CHECK(tapers == static_cast<int>(std::get<TurnThreadOp>(j.operations.front()).depths.size()));  // (17)
    }
    {
        const RunoutPosted p = runout_post(runout_job(op), "fanuc-lathe");
        CHECK(p.text.find("G76") == std::string::npos);
        CHECK(p.text.find("G32 X20.000 Z-20.000 F2.5000") != std::string::npos);
        CHECK_MESSAGE(p.notes.find("cannot carry runout") != std::string::npos, p.notes);
        check_read_back(runout_job(op), p.text, "fanuc-lathe");
        CHECK_THROWS_WITH_AS(runout_post(runout_job(op + R"(, "output": "canned")"), "fanuc-lathe"),
                             doctest::Contains("cannot carry runout"), InputError);
    }
    // A G76 with an entry taper, or steeper than 45 degrees, is refused by the reader, naming the word.
    const Machine m = load_machine("linuxcnc-lathe");
    const std::string program = runout_post(runout_job(op), "linuxcnc-lathe").text;
    auto read_refusal = [&](const std::string& from, const std::string& to) {
        std::string text = program;
        const std::size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
        try {
            (void)read_program(text, m, "t.nc");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(read_refusal(" E2 L2", " E2 L1").find("L1 on G76: camgen reads an exit taper") != std::string::npos);
    CHECK(read_refusal(" E2 L2", " E1 L2").find("E1 on G76: an exit taper steeper than 45 degrees") != std::string::npos);
    // Shorter than the thread (Z6 to Z-20), but not than the thread less the last pass's shift
    // by Q29.5 (K3.0672 on the diameter: 1.5336 tan 29.5 = 0.868): its straight part would run
    // towards +Z.
    CHECK(read_refusal(" E2 L2", " E25.5 L2").find("E25.5 on G76: the exit taper is not shorter than the thread (less the "
                                                   "last pass's shift") != std::string::npos);
    CHECK(read_refusal(" E2 L2", " E25 L2") == "");
}

TEST_CASE("turn-thread runout: refusals name their key") {
    const std::string base = R"("thread": "M20x2.5", "startZ": 0, "endZ": -10, "firstDepth": 0.3)";
    CHECK(runout_refusal(runout_job(base + R"(, "runoutLength": 3)"))
              .find("/operations/0/runoutLength: runoutLength is the length of a chamfered runout") != std::string::npos);
    CHECK(runout_refusal(runout_job(base + R"(, "runout": "chamfered", "runoutLength": 1.2)"))
              .find("/operations/0/runoutLength: a chamfered runout of length 1.200 mm is steeper than 45 degrees") !=
          std::string::npos);
    CHECK(runout_refusal(runout_job(base + R"(, "runout": "chamfered", "runoutLength": 10)"))
              .find("/operations/0/runoutLength: a chamfered runout of length 10.000 mm is not shorter than the thread") !=
          std::string::npos);
    CHECK(runout_refusal(runout_job(base + R"(, "runout": "chamfered", "runoutLength": 0)")).find("/operations/0/runoutLength") !=
          std::string::npos);
    // The default, one lead, of a thread shorter than a lead.
    CHECK(runout_refusal(runout_job(R"("thread": "M20x2.5", "startZ": 0, "endZ": -2, "firstDepth": 0.3, "runout": "chamfered")"))
              .find("/operations/0/runout: a chamfered runout of length 2.500 mm is not shorter than the thread") != std::string::npos);
}

TEST_CASE("camgen simulate: a chamfered runout is cut as designed on the three lathes; one 0.2 mm too deep is a gouge") {
    const fs::path dir = test::scratch("simulate-thread-runout");
    // An M20x2.5 thread on a D20 bar ending at Z-20 without a relief groove: the bar beyond stays D20.
    const std::string job = (dir / "runout.json").string();
    const std::string text = R"({"clearance": 20, "stock": {"bar": {"diameter": 20, "length": 40, "faceZ": 0}}, "tools": [
 {"number": 5, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 500}],
 "operations": [{"type": "turn-thread", "tool": 5, "thread": "M20x2.5", "startZ": 0, "endZ": -20, "firstDepth": 0.35,
                 "runout": "chamfered", "runoutLength": 3, "output": "longhand"}]})";
    std::ofstream(job) << text;
    const PartDesign design = part_design(read_job(text, "runout.json"));
    CHECK(design.unchecked.empty());
    auto simulate = [&](const std::string& machine, const std::string& name, const std::string& program_text) {
        const std::string program = (dir / name).string();
        std::ofstream(program) << program_text;
        return test::run({"simulate", program, "--machine", machine, "--job", job, "--bar", "20,40,0"});
    };
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        const RunoutPosted p = runout_post(text, machine);
        const test::Run s = simulate(machine, "runout.nc", p.text);
        CHECK_MESSAGE(s.code == 0, s.out << s.err);
        CHECK_MESSAGE(s.out.find("the part is as designed") != std::string::npos, s.out);
        CHECK_MESSAGE(s.out.find("simulation: no errors") != std::string::npos, s.out);
        // The last pass's taper ending 0.2 mm (radial) deeper at endZ: into the bar beyond the design.
        const std::regex last_taper("(G3[23]) X20(\\.0+)? Z-20(\\.0+)? ");
        std::smatch found;
        REQUIRE(std::regex_search(p.text, found, last_taper));
        std::string deeper = p.text;
        const std::string x = machine == "linuxcnc-lathe" ? "X19.6" : "X19.600";
        std::string with = found.str(0);
        with.replace(with.find("X20"), found.str(0).find(" Z") - with.find("X20"), x);
        deeper.replace(static_cast<std::size_t>(found.position(0)), found.str(0).size(), with);
        REQUIRE(deeper != p.text);
        const test::Run bad = simulate(machine, "deeper.nc", deeper);
        CHECK(bad.code == 1);
        CHECK_MESSAGE(bad.out.find("error: gouge: /operations/0") != std::string::npos, bad.out);
    }
    // Canned on linuxcnc-lathe (G76 E L2): as designed too.
    {
        std::string canned = text;
        canned.replace(canned.find("\"longhand\""), 10, "\"canned\"");
        std::ofstream(job) << canned;
        const RunoutPosted p = runout_post(canned, "linuxcnc-lathe");
        REQUIRE(p.text.find(" E3 L2") != std::string::npos);
        const test::Run s = simulate("linuxcnc-lathe", "canned.nc", p.text);
        CHECK_MESSAGE(s.out.find("the part is as designed") != std::string::npos, s.out);
    }
}

TEST_CASE("camgen simulate: an internal thread's chamfered runout narrows the bore to its minor diameter, as designed") {
    const fs::path dir = test::scratch("simulate-internal-runout");
    const std::string job = (dir / "inside.json").string();
    const std::string text = R"({"clearance": 20, "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 0}}, "tools": [
 {"number": 2, "type": "drill", "diameter": 20.4, "tipAngle": 118, "rpm": 500},
 {"number": 8, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 400, "orientation": 3}],
 "operations": [
  {"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -25, "safeDistance": 2, "retractDistance": 5,
   "feedMode": "per-revolution", "plungingFeedrate": 0.1},
  {"type": "turn-thread", "tool": 8, "thread": "M22x1.5", "side": "internal", "startZ": 0, "endZ": -15, "firstDepth": 0.2,
   "runout": "chamfered", "runoutLength": 2}]})";
    std::ofstream(job) << text;
    const PartDesign design = part_design(read_job(text, "inside.json"));
    REQUIRE(design.lathe.holes.size() == 2);
    const LatheHoleDesign& h = design.lathe.holes[1];
    const double minor = internal_minor_diameter(22, 1.5) / 2;
    // The tip's cone from D22 at Z-13 to D1 at Z-15, as the R0.1 nose leaves it (within its radius).
    CHECK(h.radius_at(-10) == doctest::Approx(11));
    CHECK(std::abs(h.radius_at(-13) - 11) <= 0.1);
    CHECK(std::abs(h.radius_at(-14) - (minor + (11 - minor) / 2)) <= 0.1);
    CHECK(std::abs(h.radius_at(-15) - minor) <= 0.1);
    CHECK(h.radius_at(-14.5) < h.radius_at(-14));
    CHECK(h.radius_at(-16) == 0.0);
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        const RunoutPosted p = runout_post(text, machine);
        const std::string program = (dir / "inside.nc").string();
        std::ofstream(program) << p.text;
        const test::Run s = test::run({"simulate", program, "--machine", machine, "--job", job, "--bar", "40,50,0"});
        CHECK_MESSAGE(s.code == 0, s.out << s.err);
        CHECK_MESSAGE(s.out.find("the part is as designed") != std::string::npos, s.out);
    }
}

}  // namespace test_thread_runout
