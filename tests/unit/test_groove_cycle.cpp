// turn-groove's grooving cycle (issue 30 item 2): the GrooveCycle's moves stay within the
// groove (never below its bottom, never beyond its walls, every move along Z in air); a plain
// groove's moves are Fanuc T's G75 as fanuc_g75.hpp models it; fanuc-lathe writes G75 R / G75 X
// Z P Q F for plain grooves and reads them back as the GrooveCycle's moves (a word changed is
// found); auto writes other grooves longhand with a note, canned refuses them at their path;
// the lathe simulation of a canned groove is as designed; machine files' groovingCycles are
// checked with their paths; the fanuc-lathe reader refuses a G75 it cannot read.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "machines/iso/fanuc_g75.hpp"
#include "support.hpp"

namespace test_groove_cycle {

using namespace camgen;

namespace {

std::string groove_job(const std::string& tool, const std::string& op) {
    return fmt::format(R"({{"clearance": 20, "stock": {{"bar": {{"diameter": 40, "length": 80, "faceZ": 0}}}},
  "tools": [{}], "operations": [{}]}})",
                       tool, op);
}

std::optional<Vec3> end_of(const Event& e) {
    if (const auto* r = std::get_if<Rapid>(&e)) return r->to;
    if (const auto* l = std::get_if<Linear>(&e)) return l->to;
    return std::nullopt;
}

// A random groove job: plain (no chamfer, dwell, full retract; finishAllowance 0) or not.
std::string random_groove(std::mt19937& rng, bool plain, const std::string& output = "auto") {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double w = std::round((1.5 + 3.0 * u(rng)) * 1000) / 1000;
    const double width = u(rng) < 0.3 ? w : w + 10.0 * u(rng);
    const double depth = 0.5 + 6.0 * u(rng);
    const double z = -5.0 - 20.0 * u(rng);
    const bool right = u(rng) < 0.5;
    const double a = 0.5 + u(rng);
    std::string extra = fmt::format(R"(, "output": "{}")", output);
    double peck = 0.0;
    if (u(rng) < 0.6) extra += fmt::format(R"(, "peckDepth": {:.3f})", peck = 0.3 + 2.0 * u(rng));
    // (a back-off at most the peck: the control refuses a longer one)
    if (extra.find("peck") != std::string::npos && u(rng) < 0.5)
        extra += fmt::format(R"(, "peckRetract": {:.3f})", std::min(0.1 + u(rng), std::floor(peck * 1000) / 1000));
    if (width > w && u(rng) < 0.5) extra += fmt::format(R"(, "stepover": {:.3f})", w * (0.3 + 0.7 * u(rng)));
    if (plain) {
        extra += R"(, "finishAllowance": 0)";
    } else {
        if (u(rng) < 0.5) extra += fmt::format(R"(, "chamfer": {:.3f})", std::min(depth * 0.9, 0.2 + 1.5 * u(rng)));
        if (u(rng) < 0.3) extra += R"(, "dwell": 0.4)";
        if (extra.find("peckD") != std::string::npos && u(rng) < 0.5) extra += R"(, "fullRetract": true)";
    }
    return groove_job(fmt::format(R"({{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 800{}}})", w,
                                  right ? R"(, "orientation": 1)" : ""),
                      fmt::format(R"({{"type": "turn-groove", "tool": 1, "feed": 30, "z": {:.3f}, "width": {:.3f}, "depth": {:.3f},
                          "approachDistance": {:.3f}{}}})",
                                  z, width, depth, a, extra));
}

test::Posted posted(const std::string& text, const Machine& m) { return test::post_noted(text, m, "g.json"); }

}  // namespace

TEST_CASE("groove cycle: the moves stay within the groove, every move along Z in air, back where they say") {
    std::mt19937 rng(3040);
    for (int n = 0; n < 120; ++n) {
        const bool plain = n % 2 == 0;
        const std::string text = random_groove(rng, plain);
        INFO(text);
        const Job job = read_job(text, "g.json");
        const auto& op = std::get<TurnGrooveOp>(job.operations.front());
        const GrooveCycle c = groove_cycle(op);
        if (plain) CHECK(c.plain());  // (another may be plain too: one plunge, no chamfer, dwell or full retract)
        CHECK(c.start() == op.blade.at(op.surface + op.approach, op.plunges.front()));
        const double off = c.right_point ? c.width : 0.0;  // programmed point from the left corner
        const double chamfer_reach = c.chamfer > 0 ? c.chamfer + (c.air - c.surface) : 0.0;
        Vec3 at = c.start();
        const std::vector<Event> moves = groove_cycle_moves(c);
        REQUIRE(!moves.empty());
        for (const Event& e : moves) {
            const auto to = end_of(e);
            if (!to) {
                CHECK(std::holds_alternative<Dwell>(e));
                CHECK(!plain);
                continue;
            }
            const double left = to->z - off;
            // Never below the bottom, never above the approach level.
            CHECK(to->x >= c.bottom - 1e-9);
            CHECK(to->x <= c.air + 1e-9);
            // The blade within the walls (the chamfers' lines start beyond them, in air).
            CHECK(left >= c.last_z - chamfer_reach - 1e-9);
            CHECK(left <= c.first_z + chamfer_reach + 1e-9);
            if (to->x < c.surface - 1e-9 && !(c.chamfer > 0 && to->x >= c.surface - c.chamfer - 1e-9)) {
                CHECK(left >= c.last_z - 1e-9);
                CHECK(left <= c.first_z + 1e-9);
            }
            if (std::holds_alternative<Rapid>(e)) {
                // A rapid along Z runs at the approach level; one in X goes out, or back down to
                // a depth already cut (a peck's back-off).
                if (std::abs(to->z - at.z) > 1e-9) {
                    CHECK(at.x == doctest::Approx(c.air));
                    CHECK(to->x == doctest::Approx(c.air));
                }
            } else if (plain) {
                // A plain groove's feeds are plunges straight in X from at most the approach level.
                CHECK(to->z == doctest::Approx(at.z));
                CHECK(to->x < at.x);
            }
            at = *to;
        }
        CHECK(at == groove_cycle_end(c));
        if (plain) {
            CHECK(at == c.start());
            // G75's model from the same values makes the same moves.
            iso::FanucGroove g;
            g.start_x = c.air, g.start_z = c.start().z, g.x = c.bottom, g.z = c.at(c.bottom, c.last_z).z;
            g.peck = c.peck > 0 ? c.peck : c.air - c.bottom + 1, g.step = c.z_step, g.e = c.retract, g.feed = c.feed;
            const std::vector<Event> control = iso::fanuc_groove_moves(g);
            REQUIRE(control.size() == moves.size());
            for (std::size_t k = 0; k < moves.size(); ++k) {
                CHECK(control[k].index() == moves[k].index());
                const Vec3 p = *end_of(control[k]), q = *end_of(moves[k]);
                CHECK(std::hypot(p.x - q.x, p.z - q.z) < 1e-9);
            }
            // The plunges: from the +Z wall to the -Z wall, at most the blade's width apart (the
            // step whole in µm), the last at the -Z wall.
            const std::vector<double> zs = c.plunges();
            CHECK(zs.size() == op.plunges.size());
            CHECK(zs.back() == doctest::Approx(op.z_left));
            for (std::size_t k = 1; k < zs.size(); ++k) CHECK(zs[k - 1] - zs[k] <= c.width + 1e-9);
            if (zs.size() > 1) CHECK(std::abs(c.z_step * 1000 - std::round(c.z_step * 1000)) < 1e-6);
        }
    }
}

TEST_CASE("groove cycle: fanuc-lathe writes G75 for plain grooves and reads it back as the GrooveCycle's moves") {
    const Machine fanuc = load_machine("fanuc-lathe");
    std::mt19937 rng(3041);
    int canned = 0;
    for (int n = 0; n < 40; ++n) {
        const std::string text = random_groove(rng, true, "canned");
        INFO(text);
        const Job job = read_job(text, "g.json");
        const GrooveCycle c = groove_cycle(std::get<TurnGrooveOp>(job.operations.front()));
        const test::Posted p = posted(text, fanuc);
        INFO(p.text);
        ++canned;
        const std::size_t first = p.text.find("G75 R");
        REQUIRE(first != std::string::npos);
        const std::size_t second = p.text.find("G75 X", first);
        REQUIRE(second != std::string::npos);
        CHECK(p.text.find("G1 ") == std::string::npos);
        CHECK(p.text.find("G01 ") == std::string::npos);
        const std::vector<ReadEvent> read = read_program(p.text, fanuc, "g.nc");
        // The G75 block's line: its moves are the cycle's.
        const int line = static_cast<int>(std::count(p.text.begin(), p.text.begin() + static_cast<long>(second), '\n')) + 1;
        std::vector<Vec3> got;
        for (const ReadEvent& e : read)
            if (static_cast<int>(e.line) == line)
                if (const auto to = end_of(e.event)) got.push_back(*to);
        std::vector<Vec3> want;
        for (const Event& e : groove_cycle_moves(c)) want.push_back(*end_of(e));
        REQUIRE(got.size() == want.size());
        for (std::size_t k = 0; k < got.size(); ++k) {
            CAPTURE(k);
            CHECK(std::hypot(got[k].x - want[k].x, got[k].z - want[k].z) <= 0.001);
        }
        // The whole program against the job.
        const Trace trace = trace_program(read, fanuc);
        const auto mismatch = compare_traces(trace_expected(expand_job(job), fanuc), trace, compare_tolerance(fanuc, 0.0));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        // Another X (0.2 mm deeper) is another cut: the comparison finds it.
        std::string wrong = p.text;
        const std::size_t xat = second + 5, xend = wrong.find(' ', xat);
        wrong.replace(xat, xend - xat, fmt::format("{:.3f}", std::stod(wrong.substr(xat, xend - xat)) - 0.4));
        REQUIRE(wrong != p.text);
        const auto bad = compare_traces(trace_expected(expand_job(job), fanuc), trace_program(read_program(wrong, fanuc, "g.nc"), fanuc),
                                        compare_tolerance(fanuc, 0.0));
        CHECK(bad);
    }
    CHECK(canned == 40);
}

TEST_CASE("groove cycle: the words of a G75, worked out by hand") {
    // A 3 mm blade in a 9 mm groove 2 deep from D40 at Z-10, stepover 2.5, pecks of 0.8 with a
    // back-off of 0.2: the left corner from Z-13 to Z-19, 3 steps of 2 mm; the start X42 Z-13.
    const std::string text =
        groove_job(R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 800})",
                   R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 9, "depth": 2, "stepover": 2.5,
                       "finishAllowance": 0, "peckDepth": 0.8, "peckRetract": 0.2})");
    const test::Posted p = posted(text, load_machine("fanuc-lathe"));
    CHECK_MESSAGE(p.text.find("G0 X42.000 Z-13.000\n") != std::string::npos, p.text);
    CHECK_MESSAGE(p.text.find("G75 R0.200\n") != std::string::npos, p.text);
    CHECK_MESSAGE(p.text.find("G75 X36.000 Z-19.000 P800 Q2000 F30\n") != std::string::npos, p.text);
    CHECK(p.notes.find("longhand") == std::string::npos);
    // Pecks from X42 (radius 21): 20.2, 19.4, 18.6, then the bottom 18 (each fed, 3 back-offs,
    // out): 8 moves a plunge, 4 plunges, 3 shifts along Z, back to the start.
    const Job job = read_job(text, "g.json");
    const GrooveCycle c = groove_cycle(std::get<TurnGrooveOp>(job.operations.front()));
    const std::vector<Event> moves = groove_cycle_moves(c);
    CHECK(moves.size() == 4 * 8 + 3 + 1);
    const auto* l = std::get_if<Linear>(&moves[0]);
    REQUIRE(l);
    CHECK(l->to.x == doctest::Approx(20.2));
    const auto* r = std::get_if<Rapid>(&moves[1]);
    REQUIRE(r);
    CHECK(r->to.x == doctest::Approx(20.4));
    CHECK(std::get<Linear>(moves[6]).to.x == doctest::Approx(18));
    CHECK(std::get<Rapid>(moves.back()).to == c.start());
}

TEST_CASE("groove cycle output: auto writes what G75 cannot carry longhand with a note, canned refuses it, longhand writes G1") {
    const Machine fanuc = load_machine("fanuc-lathe"), lcnc = load_machine("linuxcnc-lathe");
    const std::string tool = R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 800})";
    const std::string chamfered = R"("type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 4, "depth": 2, "chamfer": 0.5, "dwell": 0.2)";
    {
        const test::Posted p = posted(groove_job(tool, "{" + chamfered + "}"), fanuc);
        CHECK(p.text.find("G75") == std::string::npos);
        CHECK_MESSAGE(p.notes.find("/operations/0 (turn groove): the groove is written longhand because machine fanuc-lathe's "
                                      "G75 cannot carry dwell, finishPass, chamfer") != std::string::npos,
                      p.notes);
        try {
            (void)posted(groove_job(tool, "{" + chamfered + R"(, "output": "canned"})"), fanuc);
            FAIL("a canned groove G75 cannot carry was not refused");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find("/operations/0/output: machine fanuc-lathe's G75 cannot carry dwell, finishPass, "
                                             "chamfer; use \"auto\" or \"longhand\"") != std::string::npos);
        }
    }
    // A full retract: longhand, named.
    const std::string pecked = R"("type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3, "depth": 2, "peckDepth": 0.5)";
    CHECK(posted(groove_job(tool, "{" + pecked + R"(, "fullRetract": true})"), fanuc).notes.find("cannot carry fullRetract") !=
          std::string::npos);
    CHECK(posted(groove_job(tool, "{" + pecked + "}"), fanuc).text.find("G75 X36.000 Z-13.000 P500 F30\n") != std::string::npos);
    // longhand: no G75, no note.
    {
        const test::Posted p = posted(groove_job(tool, "{" + pecked + R"(, "output": "longhand"})"), fanuc);
        CHECK(p.text.find("G75") == std::string::npos);
        CHECK(p.text.find("G1 X") != std::string::npos);
        CHECK(p.notes.find("longhand") == std::string::npos);
    }
    // linuxcnc-lathe has no grooving cycle: auto longhand without a note, canned refused.
    {
        const test::Posted p = posted(groove_job(tool, "{" + pecked + "}"), lcnc);
        CHECK(p.text.find("G75") == std::string::npos);
        CHECK(p.notes.find("longhand") == std::string::npos);
        try {
            (void)posted(groove_job(tool, "{" + pecked + R"(, "output": "canned"})"), lcnc);
            FAIL("a canned groove on a machine without a grooving cycle was not refused");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find("/operations/0/output: machine linuxcnc-lathe has no canned grooving cycle") !=
                  std::string::npos);
        }
    }
    // The shaft's groove (chamfered, dwell, a finishing pass) stays longhand on fanuc-lathe, with the note.
    {
        std::ifstream f(CAMGEN_SOURCE_DIR "/samples/shaft.json");
        std::stringstream text;
        text << f.rdbuf();
        const test::Posted p = posted(text.str(), fanuc);
        CHECK(p.text.find("G75") == std::string::npos);
        CHECK(p.notes.find("the groove is written longhand because machine fanuc-lathe's G75 cannot carry dwell, finishPass, "
                              "chamfer") != std::string::npos);
    }
}

TEST_CASE("groove cycle: a canned groove on fanuc-lathe simulates as designed; a P that plunges too deep is a gouge") {
    const std::string job_text =
        groove_job(R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 800})",
                   R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 9, "depth": 2, "stepover": 2.5,
                       "finishAllowance": 0, "peckDepth": 0.8, "peckRetract": 0.2, "output": "canned"})");
    const std::filesystem::path dir = test::scratch("groove-cycle");
    const std::string job = (dir / "g.json").string();
    std::ofstream(job) << job_text;
    const std::string nc = (dir / "g.nc").string();
    REQUIRE(test::run({job, "--machine", "fanuc-lathe", "-q", "-o", nc}).code == 0);
    REQUIRE(test::read_file(nc).find("G75 X36.000") != std::string::npos);
    const test::Run clean = test::run({"simulate", nc, "--machine", "fanuc-lathe", "--job", job, "--bar", "40,80,0"});
    CHECK_MESSAGE(clean.code == 0, std::string(clean.out + clean.err));
    CHECK_MESSAGE(clean.out.find("  the part is as designed\n") != std::string::npos, clean.out);
    const test::Run verify = test::run({"verify", nc, "--machine", "fanuc-lathe", "--job", job});
    CHECK_MESSAGE(verify.code == 0, std::string(verify.out + verify.err));
    // X35.8: each plunge 0.1 mm too deep.
    std::string text = test::read_file(nc);
    text.replace(text.find("G75 X36.000"), 11, "G75 X35.800");
    const std::string deep = (dir / "deep.nc").string();
    std::ofstream(deep) << text;
    const test::Run r = test::run({"simulate", deep, "--machine", "fanuc-lathe", "--job", job, "--bar", "40,80,0"});
    CHECK(r.code == 1);
    CHECK_MESSAGE(r.out.find("error: gouge: /operations/0") != std::string::npos, r.out);
}

TEST_CASE("groove cycle: the fanuc-lathe reader refuses a G75 it cannot read, naming the word") {
    const Machine fanuc = load_machine("fanuc-lathe");
    auto refusal_of = [&](const std::string& g75) {
        const std::string program = "%\nO1000\nG18 G40 G80 G98\nT0101\nG97 S800 M3\nG0 X42.000 Z-13.000\n" + g75 +
                                    "\nG0 X44.000\nM5\nM30\n%\n";
        try {
            (void)read_program(program, fanuc, "g.nc");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refusal_of("G75 R0.2\nG75 X36.000 Z-19.000 P800 Q2000 F30") == "");
    CHECK(refusal_of("G75 X36.000 Z-19.000 P800 Q2000 F30").find("without the first block G75 R(e)") != std::string::npos);
    CHECK(refusal_of("G75 R0.2\nG75 X36.000 Z-19.000 P0.8 Q2000 F30").find("P0.8: P and Q are in least input increments") !=
          std::string::npos);
    CHECK(refusal_of("G75 R0.2\nG75 X36.000 Z-19.000 P800 Q2000 R0.1 F30").find("R0.1 in the second G75 block") !=
          std::string::npos);
    CHECK(refusal_of("G75 R0.2\nG75 X42.000 Z-19.000 P800 Q2000 F30").find("must lie off the start point's X") !=
          std::string::npos);
    CHECK(refusal_of("G75 R0.2\nG75 X46.000 Z-19.000 P800 Q2000 F30") == "");  // an internal groove, X rising
    CHECK(refusal_of("G75 R0.2\nG75 X36.000 Z-19.000 P800 F30").find("needs its step Q > 0") != std::string::npos);
    // A machine without the cycle does not know G75.
    CHECK_THROWS_AS((void)read_program("G18 G7 G90 G21\nT1 M6\nS800 M3\nG0 X42 Z-13\nG75 R0.2\nM2\n",
                                       load_machine("linuxcnc-lathe"), "g.ngc"),
                    InputError);
}

TEST_CASE("groove cycle: machine files' groovingCycles are checked with their paths") {
    std::ifstream f(CAMGEN_SOURCE_DIR "/machines/fanuc-lathe.json");
    std::stringstream buf;
    buf << f.rdbuf();
    const std::string file = buf.str();
    const std::string cycle = R"({"name": "G75", "kind": "groove", "style": "fanuc-g75", "fields": ["pecks"]})";
    REQUIRE(file.find(cycle) != std::string::npos);
    CHECK_NOTHROW((void)parse_machine(file, "m", "m.json"));
    auto refused = [&](const std::string& with) {
        std::string text = file;
        text.replace(text.find(cycle), cycle.size(), with);
        try {
            (void)parse_machine(text, "m", "m.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refused(R"({"name": "G75", "kind": "groove", "style": "fanuc-g75", "fields": ["peks"]})")
              .find("/groovingCycles/0/fields/0") != std::string::npos);
    CHECK(refused(R"({"name": "G75", "kind": "groove", "style": "sinumerik-cycle93"})").find("/groovingCycles/0/style") !=
          std::string::npos);
    CHECK(refused(R"({"name": "G75", "style": "fanuc-g75"})").find("/groovingCycles/0") != std::string::npos);
    // --describe-machine lists it.
    CHECK(describe_machine(load_machine("fanuc-lathe")).find("G75 (fanuc-g75): pecks") != std::string::npos);
}

}  // namespace test_groove_cycle
