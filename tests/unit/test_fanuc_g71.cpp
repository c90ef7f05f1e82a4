// Fanuc T's type I G71 on fanuc-lathe (issue 30): turn-rough along Z written as G71 U R / G71 P Q
// U0 W0 F with the finishing shape right after it, where camgen's model of the cycle
// (fanuc_g71, geometry/lathe_cycle.hpp) cuts camgen's passes; the fanuc-lathe reader expands it
// into the same moves. There is no Fanuc control here: these tests hold the post and the reader to
// the model (and the model to the boundary and the bar), not the model to a control.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/turn_rough/turn_rough.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "support.hpp"
#include "lathe_profiles.hpp"

namespace test_fanuc_g71 {

using namespace camgen;

namespace {

std::string fg_job(const std::string& path, double start_x, double doc, const std::string& extra = "") {
    return fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0.5}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.5}},
                 {{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": {}, "allowanceX": 0.4, "allowanceZ": 0.1,
                   "start": [{}, 0], "path": {}{}}}]}})",
                       doc, start_x, path, extra);
}

test::Posted fg_posted(const Job& j, const Machine& m) { return test::post_noted(j, m); }

}  // namespace

TEST_CASE("fanuc-g71: generated profiles: canned where the model takes them, read back as the job's moves") {
    const Machine fanuc = load_machine("fanuc-lathe");
    REQUIRE(fanuc.rough_pattern() == RoughCyclePattern::fanuc_g71);
    Machine plain = fanuc;  // a control without sequence numbers: the shape's blocks carry their own
    plain.block.sequence_numbers = false;
    std::mt19937 rng(71);
    int canned = 0, longhand = 0, checked_moves = 0, unreachable = 0;
    for (int n = 0; n < 60; ++n) {
        double d0 = 0;
        const std::string path = test::stepped_shaft_profile(rng, d0);
        const double doc = (n % 3 == 0) ? 1.5 : (n % 3 == 1 ? 1.0 : 2.2);
        CAPTURE(path);
        CAPTURE(doc);
        std::optional<Job> read_in;
        try {
            read_in = read_job(fg_job(path, d0, doc, n % 2 ? R"(, "compensation": "none")" : ""), "fg.json");
        } catch (const InputError&) {
            ++unreachable;  // the nose cannot follow this profile: not a roughing
            continue;
        }
        const Job& j = *read_in;
        const auto& op = std::get<TurnRoughOp>(j.operations.at(1));
        const TurnCycle c = turn_cycle(op);
        for (const Machine* m : {&fanuc, static_cast<const Machine*>(&plain)}) {
            const auto p = fg_posted(j, *m);
            const bool is_canned = p.text.find("G71 U") != std::string::npos;
            if (m == &fanuc) (is_canned ? canned : longhand)++;
            if (!is_canned && m == &fanuc && p.notes.find("longhand") != std::string::npos)
                MESSAGE(p.notes.substr(p.notes.find("longhand"), 160));
            // Where LinuxCNC's model takes the boundary, so does Fanuc's (these profiles): canned.
            CHECK_MESSAGE(is_canned == !c.refusal, p.notes);
            // verify --job: the program read back moves as the job's events traced for the machine.
            const Trace read = trace_program(read_program(p.text, *m, "t.nc"), *m);
            const auto miss = compare_traces(trace_expected(expand_job(j), *m), read, compare_tolerance(*m));
            CHECK_MESSAGE(!miss, (miss ? miss->message : "") << "\n" << p.text);
            if (is_canned) {
                // P and Q name the blocks right after the cycle.
                const std::size_t at = p.text.find("G71 P");
                REQUIRE(at != std::string::npos);
                const long ns = std::stol(p.text.substr(at + 5));
                const std::size_t next = p.text.find('\n', at) + 1;
                CHECK(p.text.substr(next, fmt::format("N{} G0 X", ns).size()) == fmt::format("N{} G0 X", ns));
                // A deliberately wrong depth of cut (U too small) is found by verify.
                std::string wrong = p.text;
                const std::size_t u = wrong.find("G71 U");
                const std::size_t end = wrong.find(' ', u + 4);
                wrong.replace(u + 4, end - (u + 4), "U0.400");
                // (found as other moves, or refused by the reader: a level through a corner)
                bool found = false;
                try {
                    found = compare_traces(trace_expected(expand_job(j), *m), trace_program(read_program(wrong, *m, "t.nc"), *m),
                                           compare_tolerance(*m))
                                .has_value();
                } catch (const InputError&) {
                    found = true;
                }
                CHECK(found);
            }
        }
        if (c.refusal) continue;
        // The model's moves: no feed below the boundary, no rapid into material.
        const std::vector<LatheCycleMove> moves = turn_cycle_path(c, RoughCyclePattern::fanuc_g71);
        const Profile& b = op.tip_boundary;
        const double face = op.bar_face.value_or(0.5), stock = op.stock_radius;
        struct Pass {
            double z_lo, z_hi, r;
        };
        std::vector<Pass> passes;
        Vec2 at{c.start.z, c.start.x};
        // The pass along the boundary: after the last rapid to its start (A').
        std::size_t contour = moves.size();
        for (std::size_t k = 0; k < moves.size(); ++k)
            if (moves[k].kind == LatheCycleMove::Kind::rapid &&
                distance(moves[k].end, Vec2{c.start.z, c.profile.start.y}) < 1e-9)
                contour = k;
        for (std::size_t k = 0; k < moves.size(); ++k) {
            const LatheCycleMove& m = moves[k];
            const bool last = k + 1 == moves.size();
            for (int s = 0; s <= 20; ++s) {
                const Vec2 q = at + (m.end - at) * (s / 20.0);
                if (m.kind == LatheCycleMove::Kind::arc) break;  // on the boundary: its ends are checked
                const double below = test::stepped_profile_radius_at(b, q.x, false);
                if (below >= 0 && (k <= contour || last)) CHECK_MESSAGE(q.y >= below - 1e-6, "move " << k << " below the boundary at Z " << q.x);
                if (m.kind != LatheCycleMove::Kind::rapid || q.x >= face - 1e-9 || q.y >= stock - 1e-9) continue;
                bool cleared = last;  // the return to A: after the pass along the boundary, above it
                for (const Pass& ps : passes)
                    cleared = cleared || (q.x >= ps.z_lo - 1e-6 && q.x <= ps.z_hi + 1e-6 && ps.r <= q.y + 1e-6);
                CHECK_MESSAGE(cleared, "rapid " << k << " into material at Z " << q.x << " radius " << q.y);
            }
            if (m.kind == LatheCycleMove::Kind::feed && std::abs(m.end.y - at.y) < 1e-9 && m.end.x < at.x)
                passes.push_back({m.end.x, at.x, at.y});
            at = m.end;
            ++checked_moves;
        }
        // The control ends at A.
        CHECK(distance(moves.back().end, fanuc_g71_start(c)) < 1e-9);
    }
    MESSAGE("fanuc-g71: " << canned << " canned, " << longhand << " longhand, " << unreachable << " profiles the nose cannot follow, "
                          << checked_moves << " model moves checked");
    CHECK(canned >= 20);
}

TEST_CASE("fanuc-g71: the reader refuses what it does not model") {
    const Machine fanuc = load_machine("fanuc-lathe");
    auto refusal = [&](const std::string& body) {
        const std::string text = "%\nO1000\nG18 G40 G80 G98 G21\nT0101\nG97 S1000 M3\nG0 X44.000 Z2.000\n" + body + "M30\n%\n";
        try {
            (void)read_program(text, fanuc, "t.nc");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string shape = "N100 G0 X20.000\nN101 G1 Z-10.000\nN102 G1 X40.000 Z-12.000\n";
    CHECK(refusal("G71 U1.400 R0.500\nG71 P100 Q102 U0.000 W0.000 F200\n" + shape) == "");
    // U and W (the finishing allowance) are read (test_fanuc_g70.cpp); a negative one is not modelled.
    CHECK(refusal("G71 U1.400 R0.500\nG71 P100 Q102 U0.400 W0.000 F200\n" + shape) == "");
    CHECK(refusal("G71 U1.400 R0.500\nG71 P100 Q102 U0.000 W-0.100 F200\n" + shape).find("negative") != std::string::npos);
    CHECK(refusal("G71 P100 Q102 U0.000 W0.000 F200\n" + shape).find("without its first block") != std::string::npos);
    CHECK(refusal("G71 U1.400 R0.500\nG71 P100 Q102 U0.000 W0.000 F200\nN100 G0 X20.000 Z1.000\nN101 G1 Z-10.000\nN102 G1 X40.000 Z-12.000\n")
              .find("along X only") != std::string::npos);
    CHECK(refusal("G71 U1.400 R0.500\nG71 P100 Q102 U0.000 W0.000 F200\nN100 G0 X20.000\nN101 G1 Z-10.000\n")
              .find("finishing shape") != std::string::npos);
    CHECK(refusal("G71 U1.400 R0.500\nG71 P100 Q102 U0.000 W0.000 F200\nN100 G0 X20.000\nN101 G1 X16.000 Z-10.000\nN102 G1 X40.000 Z-12.000\n")
              .find("falls in radius") != std::string::npos);
    // 12,000 levels over a shape of 6,000 elements: bounded (each level looks for its element),
    // refused at once instead of running for minutes. (A at radius 22.0005, the corners' radii
    // on whole thousandths: no level runs through a corner, which is refused before.)
    {
        std::string many = "N100 G0 X20.000\n";
        for (int k = 1; k <= 6000; ++k) many += fmt::format("N{} G1 X{:.3f} Z{:.3f}\n", 100 + k, 20.0 + k * 0.004, -k * 0.01);
        CHECK(refusal(fmt::format("G0 X44.001\nG71 U0.001 R0.0005\nG71 P100 Q{} U0.000 W0.000 F200\n", 6100) + many)
                  .find("more than camgen models") != std::string::npos);
    }
    CHECK(refusal("G0 X30.000\nG71 U1.400 R0.500\n") == "");
    CHECK(refusal("G1 X30.000 U2.000 F100\n") != "");
}

}  // namespace test_fanuc_g71
