// Fanuc T's G74 face grooving for turn-groove "side": "face" (issue 30): fanuc-lathe writes
// G74 R(e) / G74 X Z P(X step) Q(peck) F for many random plain face grooves (widths, pecks, with
// and without a bore, inner and outer walls) under "canned"; the program reads back as the job's
// moves (the G74 block's moves within 0.001 mm of groove_cycle_moves, the whole program as
// verify --job compares it), every move along X in air at z + approachDistance, every feed along
// -Z, no rapid below what was cut; a changed word is found; the words worked out by hand; what G74
// cannot carry is longhand with a note (refused under canned); the reader refuses G74 blocks it
// cannot read and still reads the drilling G74; machine files' face-groove cycles are checked.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
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

namespace test_fanuc_g74_groove {

using namespace camgen;

namespace {

std::optional<Vec3> g74_end_of(const Event& e) {
    if (const auto* r = std::get_if<Rapid>(&e)) return r->to;
    if (const auto* l = std::get_if<Linear>(&e)) return l->to;
    return std::nullopt;
}

// A bar of D40, 60 long, its face at Z0, with a bore of D16 or without one.
std::string g74_job(bool bore, const std::string& tool, const std::string& op) {
    return fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0{}}}}},
  "tools": [{}], "operations": [{}]}})",
                       bore ? R"(, "boreDiameter": 16)" : "", tool, op);
}

struct FaceGroove {
    std::string text;
    double inner = 0, outer = 0, depth = 0, approach = 0;  // radii, mm
};

// A random plain face groove (no chamfer, dwell, full retract; finishAllowance 0).
FaceGroove random_plain_face(std::mt19937& rng, const std::string& output) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    FaceGroove g;
    const bool bore = u(rng) < 0.5;
    const double w = std::round((1.5 + 2.0 * u(rng)) * 1000) / 1000;
    const double width = u(rng) < 0.3 ? w : std::round((w + 6.0 * u(rng)) * 1000) / 1000;
    g.inner = std::round(((bore ? 9.0 : 0.5) + (bore ? 2.0 : 8.0) * u(rng)) * 1000) / 1000;
    g.outer = g.inner + width;
    g.depth = std::round((0.5 + 8.0 * u(rng)) * 1000) / 1000;
    g.approach = std::round((0.3 + 1.5 * u(rng)) * 1000) / 1000;
    std::string extra = fmt::format(R"(, "output": "{}", "finishAllowance": 0)", output);
    if (u(rng) < 0.7) {
        extra += fmt::format(R"(, "peckDepth": {:.3f})", 0.4 + 2.0 * u(rng));
        if (u(rng) < 0.5) extra += fmt::format(R"(, "peckRetract": {:.3f})", 0.1 + 0.25 * u(rng));
    }
    if (width > w && u(rng) < 0.6) extra += fmt::format(R"(, "stepover": {:.3f})", w * (0.3 + 0.7 * u(rng)));
    g.text = g74_job(bore, fmt::format(R"({{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 600, "orientation": 7}})", w),
                     fmt::format(R"({{"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": {:.3f},
                         "outerX": {:.3f}, "depth": {:.3f}, "approachDistance": {:.3f}{}}})",
                                 2 * g.inner, 2 * g.outer, g.depth, g.approach, extra));
    return g;
}

test::Posted g74_posted(const std::string& text, const Machine& m) { return test::post_noted(text, m, "g.json"); }

// The line (1-based) of the first occurrence of `what` in `text`.
int g74_line_of(const std::string& text, std::size_t at) {
    return static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n')) + 1;
}

}  // namespace

TEST_CASE("fanuc G74 face groove: random plain face grooves are written as G74, read back as the job's moves, in air") {
    const Machine fanuc = load_machine("fanuc-lathe");
    std::mt19937 rng(7474);
    int canned = 0, stepped = 0, single = 0, pecked = 0, verified = 0;
    for (int n = 0; n < 60; ++n) {
        const FaceGroove g = random_plain_face(rng, "canned");
        INFO(g.text);
        const Job job = read_job(g.text, "g.json");
        const GrooveCycle c = groove_cycle(std::get<TurnGrooveOp>(job.operations.front()));
        REQUIRE(c.plain());
        const test::Posted p = g74_posted(g.text, fanuc);
        INFO(p.text);
        const std::size_t first = p.text.find("G74 R");
        REQUIRE(first != std::string::npos);
        const std::size_t second = p.text.find("G74 X", first);
        REQUIRE(second != std::string::npos);
        ++canned;
        CHECK(p.text.find("G1 ") == std::string::npos);
        CHECK(p.text.find("G80") == p.text.rfind("G80"));  // (the start block's alone: G74 grooving needs none)
        const std::string block = p.text.substr(second, p.text.find('\n', second) - second);
        if (block.find(" P") != std::string::npos) ++stepped;
        else ++single;
        if (c.peck > 0) ++pecked;
        // X the inner wall (a diameter), Z the bottom.
        std::smatch m;
        REQUIRE(std::regex_search(block, m, std::regex(R"(^G74 X([0-9.]+) Z(-?[0-9.]+) (P[0-9]+ )?Q[0-9]+ F)")));
        CHECK(std::abs(std::stod(m[1]) - 2 * g.inner) < 0.0015);
        CHECK(std::abs(std::stod(m[2]) + g.depth) < 0.0006);
        // The G74 block's moves are the cycle's.
        const std::vector<ReadEvent> read = read_program(p.text, fanuc, "g.nc");
        const int line = g74_line_of(p.text, second);
        std::vector<std::pair<Vec3, bool>> got;  // (to, rapid)
        std::optional<Vec3> before;
        for (const ReadEvent& e : read) {
            const auto to = g74_end_of(e.event);
            if (!to) continue;
            if (static_cast<int>(e.line) == line) got.emplace_back(*to, std::holds_alternative<Rapid>(e.event));
            else if (got.empty()) before = to;
        }
        const std::vector<Event> want = groove_cycle_moves(c);
        REQUIRE(got.size() == want.size());
        for (std::size_t k = 0; k < got.size(); ++k) {
            CAPTURE(k);
            const Vec3 w = *g74_end_of(want[k]);
            CHECK(std::hypot(got[k].first.x - w.x, got[k].first.z - w.z) <= 0.001);
            CHECK(got[k].second == std::holds_alternative<Rapid>(want[k]));
        }
        // In air: every move along X at the approach level; every feed straight along -Z; no
        // rapid below the deepest cut at its X (a back-off's return stops above it).
        REQUIRE(before);
        CHECK(before->z == doctest::Approx(g.approach).epsilon(1e-6));
        Vec3 at = *before;
        std::map<long, double> cut;  // deepest Z fed at each X (µm)
        for (const auto& [to, rapid] : got) {
            if (std::abs(to.x - at.x) > 1e-9) {
                CHECK(rapid);
                CHECK(std::abs(at.z - g.approach) < 0.0006);
                CHECK(std::abs(to.z - g.approach) < 0.0006);
            }
            const long key = std::lround(to.x * 1000);
            if (!rapid) {
                CHECK(std::abs(to.x - at.x) < 1e-9);
                CHECK(to.z < at.z);
                CHECK(to.z >= -g.depth - 0.0006);
                cut[key] = std::min(cut.count(key) ? cut[key] : 0.0, to.z);
            } else if (to.z < at.z - 1e-9) {
                CHECK(to.z >= (cut.count(key) ? cut[key] : 0.0) - 1e-9);
            }
            at = to;
        }
        CHECK(std::abs(at.x - before->x) < 1e-9);
        CHECK(std::abs(at.z - before->z) < 1e-9);
        // The whole program against the job (verify --job's comparison).
        const Trace trace = trace_program(read, fanuc);
        const auto mismatch = compare_traces(trace_expected(expand_job(job), fanuc), trace, compare_tolerance(fanuc, 0.0));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        // A changed word is another cut: Z 0.2 deeper, or (several plunges) a shorter X step.
        std::string wrong = p.text;
        const std::size_t zat = wrong.find(" Z", second) + 2, zend = wrong.find(' ', zat);
        wrong.replace(zat, zend - zat, fmt::format("{:.3f}", std::stod(wrong.substr(zat, zend - zat)) - 0.2));
        CHECK(compare_traces(trace_expected(expand_job(job), fanuc), trace_program(read_program(wrong, fanuc, "g.nc"), fanuc),
                             compare_tolerance(fanuc, 0.0)));
        if (block.find(" P") != std::string::npos) {
            std::string step = p.text;
            const std::size_t pat = step.find(" P", second) + 2, pend = step.find(' ', pat);
            step.replace(pat, pend - pat, std::to_string(std::stol(step.substr(pat, pend - pat)) - 150));
            CHECK(compare_traces(trace_expected(expand_job(job), fanuc), trace_program(read_program(step, fanuc, "g.nc"), fanuc),
                                 compare_tolerance(fanuc, 0.0)));
        }
        // camgen verify --job on some of them.
        if (n % 6 == 0) {
            const std::filesystem::path dir = test::scratch("fanuc-g74-groove");
            const std::string jf = (dir / "g.json").string(), nc = (dir / "g.nc").string();
            std::ofstream(jf) << g.text;
            std::ofstream(nc) << p.text;
            const test::Run v = test::run({"verify", nc, "--machine", "fanuc-lathe", "--job", jf});
            CHECK_MESSAGE(v.code == 0, std::string(v.out + v.err));
            ++verified;
        }
    }
    CHECK(canned == 60);
    CHECK(stepped > 10);
    CHECK(single > 3);
    CHECK(pecked > 10);
    CHECK(verified == 10);
}

TEST_CASE("fanuc G74 face groove: the words worked out by hand") {
    // A 2 mm blade from D28 to D36, 3 deep in the face at Z0, stepover 1.5, pecks of 1.5 (back-off
    // 0.3): the inner corner from radius 16 to 14 in 2 steps of 1; the start X32 Z1.
    const std::string text = g74_job(false, R"({"number": 1, "type": "grooving-tool", "width": 2, "rpm": 600, "orientation": 7})",
                                     R"({"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": 28,
                                         "outerX": 36, "depth": 3, "stepover": 1.5, "peckDepth": 1.5, "finishAllowance": 0})");
    const test::Posted p = g74_posted(text, load_machine("fanuc-lathe"));
    CHECK_MESSAGE(p.text.find("X32.000\nN40 Z1.000\nN45 G74 R0.300\n") != std::string::npos, p.text);
    CHECK_MESSAGE(p.text.find("G74 X28.000 Z-3.000 P1000 Q1500 F30\n") != std::string::npos, p.text);
    CHECK(p.notes.find("longhand") == std::string::npos);
    // Pecks from Z1: -0.5, back to -0.2, -2, back to -1.7, the bottom -3, out to Z1: 6 moves a
    // plunge, 3 plunges, 2 steps along X, back to the start.
    const Job job = read_job(text, "g.json");
    const GrooveCycle c = groove_cycle(std::get<TurnGrooveOp>(job.operations.front()));
    const std::vector<Event> moves = groove_cycle_moves(c);
    REQUIRE(moves.size() == 3 * 6 + 2 + 1);
    CHECK(std::get<Linear>(moves[0]).to.z == doctest::Approx(-0.5));
    CHECK(std::get<Rapid>(moves[1]).to.z == doctest::Approx(-0.2));
    CHECK(std::get<Linear>(moves[4]).to.z == doctest::Approx(-3));
    CHECK(std::get<Rapid>(moves[5]).to == Vec3{16, 0, 1});
    CHECK(std::get<Rapid>(moves[6]).to == Vec3{15, 0, 1});
    CHECK(std::get<Rapid>(moves.back()).to == c.start());
    // The model from the words makes them.
    iso::FanucGroove g;
    g.along_z = true, g.start_x = 16, g.start_z = 1, g.x = 14, g.z = -3, g.peck = 1.5, g.step = 1, g.e = 0.3, g.feed = 30;
    const std::vector<Event> control = iso::fanuc_groove_moves(g);
    REQUIRE(control.size() == moves.size());
    for (std::size_t k = 0; k < moves.size(); ++k) {
        CHECK(control[k].index() == moves[k].index());
        CHECK(*g74_end_of(control[k]) == *g74_end_of(moves[k]));
    }
    // One plunge (the groove as wide as the blade), no pecks: X the start point's, no P, Q the
    // whole plunge.
    const std::string one = g74_job(false, R"({"number": 1, "type": "grooving-tool", "width": 2, "rpm": 600, "orientation": 7})",
                                    R"({"type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": 28,
                                        "outerX": 32, "depth": 3})");
    CHECK_MESSAGE(g74_posted(one, load_machine("fanuc-lathe")).text.find("G74 X28.000 Z-3.000 Q4000 F30\n") != std::string::npos,
                  g74_posted(one, load_machine("fanuc-lathe")).text);
}

TEST_CASE("fanuc G74 face groove: what G74 cannot carry is longhand with a note, refused under canned") {
    const Machine fanuc = load_machine("fanuc-lathe");
    const std::string tool = R"({"number": 1, "type": "grooving-tool", "width": 2, "rpm": 600, "orientation": 7})";
    const std::string chamfered =
        R"("type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": 28, "outerX": 36, "depth": 3, "chamfer": 0.3)";
    {
        const test::Posted p = g74_posted(g74_job(true, tool, "{" + chamfered + "}"), fanuc);
        CHECK(p.text.find("G74 X") == std::string::npos);
        CHECK_MESSAGE(p.notes.find("/operations/0 (turn groove): the groove is written longhand because machine fanuc-lathe's G74 "
                                   "cannot carry finishPass, chamfer") != std::string::npos,
                      p.notes);
        try {
            (void)g74_posted(g74_job(true, tool, "{" + chamfered + R"(, "output": "canned"})"), fanuc);
            FAIL("a canned face groove G74 cannot carry was not refused");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find("/operations/0/output: machine fanuc-lathe's G74 cannot carry finishPass, chamfer") !=
                  std::string::npos);
        }
    }
    // A back-off longer than the peck: the control would refuse it.
    const std::string pecked =
        R"("type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": 28, "outerX": 32, "depth": 3, "peckDepth": 0.4, "peckRetract": 0.5)";
    CHECK_MESSAGE(g74_posted(g74_job(false, tool, "{" + pecked + "}"), fanuc)
                          .notes.find("cannot carry this groove: its back-off R 0.5 is longer than its peck 0.4") != std::string::npos,
                  g74_posted(g74_job(false, tool, "{" + pecked + "}"), fanuc).notes);
    // longhand: no G74, no note.
    const test::Posted l = g74_posted(g74_job(false, tool, "{" + pecked + R"(, "output": "longhand"})"), fanuc);
    CHECK(l.text.find("G74") == std::string::npos);
    CHECK(l.notes.find("longhand") == std::string::npos);
    // A machine whose only grooving cycle is G75: a face groove is longhand, named so.
    Machine only_g75 = fanuc;
    only_g75.grooving.erase(std::remove_if(only_g75.grooving.begin(), only_g75.grooving.end(),
                                           [](const GroovingCycleSpec& s) { return s.face; }),
                            only_g75.grooving.end());
    REQUIRE(only_g75.grooving.size() == 1);
    CHECK(g74_posted(g74_job(false, tool, "{" + chamfered + "}"), only_g75)
              .notes.find("machine fanuc-lathe's G75 plunges along X; a face groove plunges along Z") != std::string::npos);
    // linuxcnc-lathe has no grooving cycle: a plain face groove is longhand without a note under
    // auto, refused under canned.
    const std::string plain =
        R"("type": "turn-groove", "side": "face", "tool": 1, "feed": 30, "z": 0, "innerX": 28, "outerX": 32, "depth": 3)";
    const test::Posted lc = g74_posted(g74_job(false, tool, "{" + plain + "}"), load_machine("linuxcnc-lathe"));
    CHECK(lc.text.find("G74") == std::string::npos);
    CHECK(lc.notes.find("longhand") == std::string::npos);
    CHECK_THROWS_WITH_AS((void)g74_posted(g74_job(false, tool, "{" + plain + R"(, "output": "canned"})"), load_machine("linuxcnc-lathe")),
                         doctest::Contains("/operations/0/output: machine linuxcnc-lathe has no canned grooving cycle"), InputError);
    CHECK(g74_posted(g74_job(false, tool, "{" + plain + "}"), fanuc).text.find("G74 X28.000 Z-3.000 Q4000 F30") != std::string::npos);
    // The bushing sample's face groove (chamfered, three plunges with a finishing pass) stays longhand.
    std::ifstream f(CAMGEN_SOURCE_DIR "/samples/bushing.json");
    std::stringstream text;
    text << f.rdbuf();
    const test::Posted b = g74_posted(text.str(), fanuc);
    CHECK(b.text.find("G74 X") == std::string::npos);
    CHECK(b.notes.find("G74 cannot carry finishPass, chamfer") != std::string::npos);
}

TEST_CASE("fanuc G74 face groove: the reader refuses a G74 it cannot read and still reads the drilling G74") {
    const Machine fanuc = load_machine("fanuc-lathe");
    auto read = [&](const std::string& g74) {
        const std::string program =
            "%\nO1000\nG18 G40 G80 G98\nT0101\nG97 S600 M3\nG0 X32.000 Z1.000\n" + g74 + "\nG0 Z10.000\nM5\nM30\n%\n";
        return read_program(program, fanuc, "g.nc");
    };
    auto refusal_of = [&](const std::string& g74) {
        try {
            (void)read(g74);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 P1000 Q1500 F30") == "");
    CHECK(refusal_of("G74 X28.000 Z-3.000 P1000 Q1500 F30").find("without the first block G74 R(e)") != std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 P1.0 Q1500 F30").find("P1.0: P and Q are in least input increments") !=
          std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 P1000 Q1500 R0.1 F30").find("R0.1 in the second G74 block") !=
          std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z3.000 P1000 Q1500 F30").find("towards the chuck") != std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z1.000 P1000 Q1500 F30").find("must lie off the start point's Z") != std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 Q1500 F30").find("needs its step P > 0") != std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 P1000 F30").find("needs X, Z and the peck Q") != std::string::npos);
    // What the control refuses: a peck longer than the plunge, a step longer than the travel, a
    // back-off longer than the peck.
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 P1000 Q4500 F30").find("Q4500: the peck is longer than the plunge") !=
          std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 P2500 Q1500 F30").find("P2500: the step is longer than the travel") !=
          std::string::npos);
    CHECK(refusal_of("G74 R0.3\nG74 X28.000 Z-3.000 P1000 Q200 F30").find("Q200: the back-off R(e) is longer than the peck") !=
          std::string::npos);
    // Each bound alone holds (10000 pecks a plunge, 10000 plunges), both at once would be 10^8
    // pecks from one block: the cycle's pecks are bounded too.
    CHECK(refusal_of("G74 R0.001\nG74 X12.000 Z-9.000 P1 Q1 F30").find("more than 100000 pecks in one cycle") !=
          std::string::npos);
    // X the start point's and no P: one plunge.
    {
        const std::vector<ReadEvent> r = read("G74 R0.3\nG74 X32.000 Z-3.000 Q1500 F30");
        int feeds = 0;
        for (const ReadEvent& e : r)
            if (std::holds_alternative<Linear>(e.event)) ++feeds;
        CHECK(feeds == 3);  // Z-0.5, -2, -3
    }
    // The drilling G74 (no X, no P) is still a drilling cycle.
    {
        const std::vector<ReadEvent> r = read("G74 R1.0\nG74 Z-20.000 Q5000 F30");
        CHECK(std::any_of(r.begin(), r.end(), [](const ReadEvent& e) { return std::holds_alternative<DrillCycle>(e.event); }));
    }
}

TEST_CASE("fanuc G74 face groove: machine files' face-groove cycles are checked with their paths") {
    std::ifstream f(CAMGEN_SOURCE_DIR "/machines/fanuc-lathe.json");
    std::stringstream buf;
    buf << f.rdbuf();
    const std::string file = buf.str();
    const std::string cycle = R"({"name": "G74", "kind": "face-groove", "style": "fanuc-g74", "fields": ["pecks"]})";
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
    CHECK(refused(R"({"name": "G74", "kind": "groove", "style": "fanuc-g74"})").find("/groovingCycles/1/style: style fanuc-g74 "
                                                                                    "cuts face grooves") != std::string::npos);
    CHECK(refused(R"({"name": "G74", "kind": "face-groove", "style": "fanuc-g75"})").find("/groovingCycles/1/style") !=
          std::string::npos);
    CHECK(refused(R"({"name": "G76", "kind": "groove", "style": "fanuc-g75"})").find("/groovingCycles/1/kind: a second grooving "
                                                                                    "cycle of kind groove") != std::string::npos);
    CHECK(describe_machine(load_machine("fanuc-lathe")).find("G74 (fanuc-g74): pecks") != std::string::npos);
    // G74 grooving beside a G74 drilling cycle of another style (LinuxCNC's left-hand tapping).
    const std::string drill = R"({"name": "G74", "kind": "chip-break", "style": "fanuc-g74",)";
    REQUIRE(file.find(drill) != std::string::npos);
    std::string tapping = file;
    tapping.replace(tapping.find(drill), drill.size(), R"({"name": "G74", "kind": "chip-break", "style": "standard",)");
    try {
        (void)parse_machine(tapping, "m", "m.json");
        FAIL("G74 grooving beside another G74 was not refused");
    } catch (const InputError& e) {
        CHECK_MESSAGE(std::string(e.what()).find("/groovingCycles/1/name: G74 is also a drilling cycle") != std::string::npos,
                      e.what());
    }
}

}  // namespace test_fanuc_g74_groove
