// Fanuc T's type I G72 on fanuc-lathe (issue 30): turn-rough along X ("direction": "x") written
// as G72 W R / G72 P Q U0 W0 F with the finishing shape (its first block G0 Z) right after it,
// where camgen's model of the cycle (fanuc_g72, geometry/lathe_cycle.hpp) cuts camgen's passes;
// the fanuc-lathe reader expands it into the same moves. And the way out after a Fanuc roughing
// cycle (G71 and G72): a rapid from the start point A, where the control ends, in air. There is
// no Fanuc control here: these tests hold the post and the reader to the model (and the model
// to the boundary and the bar), not the model to a control.
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

namespace test_fanuc_g72 {

using namespace camgen;

namespace {

std::string fx_job(const std::string& path, double start_x, double doc, const std::string& extra = "") {
    return fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0.5}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.5}},
                 {{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": {}, "allowanceX": 0.4, "allowanceZ": 0.1,
                   "direction": "x", "start": [{}, 0], "path": {}{}}}]}})",
                       doc, start_x, path, extra);
}

// A facing profile: from diameter d0 at Z0 outwards and towards the chuck, its radius never
// falling and its Z never rising (what G72 roughs, walked backwards): faces, tapers, steps along Z
// and 90-degree fillets (G3 quarter arcs), short in Z: as JSON.
std::string fx_profile(std::mt19937& rng, double& d0) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double d = 2 + std::round(u(rng) * 100) / 10, z = 0;
    d0 = d;
    std::string out = "[";
    const int n = 2 + static_cast<int>(u(rng) * 4);
    for (int k = 0; k < n && d < 34; ++k) {
        const double rise = 1 + std::round(u(rng) * 60) / 10;
        if (d + rise > 36) break;
        const int kind = rise >= 4 ? static_cast<int>(u(rng) * 3) : static_cast<int>(u(rng) * 2);
        if (kind == 0) {
            out += fmt::format(R"({{"line": [{}, {}]}}, )", d + rise, z);
        } else if (kind == 1) {
            const double dz = std::round(u(rng) * 20) / 10 + 0.5;
            out += fmt::format(R"({{"line": [{}, {}]}}, )", d + rise, z - dz);
            z -= dz;
        } else {
            // A face out, then a 90-degree fillet of radius rr (radial) into a step along Z.
            const double rr = rise / 4;
            out += fmt::format(R"({{"line": [{}, {}]}}, )", d + rise / 2, z);
            out += fmt::format(R"({{"arc": {{"end": [{}, {}], "centre": [{}, {}], "direction": "ccw"}}}}, )", d + rise, z - rr,
                               d + rise / 2, z - rr);
            z -= rr;
        }
        d = std::round((d + rise) * 10) / 10;
        const double len = 0.5 + std::round(u(rng) * 25) / 10;
        out += fmt::format(R"({{"line": [{}, {}]}}, )", d, z - len);
        z -= len;
    }
    out += fmt::format(R"({{"line": [{}, {}]}}])", 38, z - 1);
    return out;
}

// The radius of a (Z, radius) profile that never rises in Z at z (its lowest on a face).
double fx_radius_at(const Profile& p, double z) {
    double best = -1;
    Vec2 a = p.start;
    for (const ProfileSegment& s : p.segments) {
        const Vec2 b = s.end;
        const double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
        if (z >= lo - 1e-9 && z <= hi + 1e-9) {
            double r;
            if (!s.centre) {
                r = std::abs(b.x - a.x) < 1e-12 ? std::min(a.y, b.y) : a.y + (z - a.x) / (b.x - a.x) * (b.y - a.y);
            } else {
                const double rr = distance(a, *s.centre), dz = z - s.centre->x;
                const double h = std::sqrt(std::max(0.0, rr * rr - dz * dz));
                const double r1 = s.centre->y + h, r2 = s.centre->y - h;
                r = std::abs(r1 - (a.y + b.y) / 2) < std::abs(r2 - (a.y + b.y) / 2) ? r1 : r2;
                r = std::clamp(r, std::min(a.y, b.y), std::max(a.y, b.y));
            }
            best = best < 0 ? r : std::min(best, r);
        }
        a = b;
    }
    return best;
}

// The roughing cycle a job's turn-rough emits (with its way out), if it emits one that is used.
std::optional<TurnCycle> fx_emitted(const Job& j) {
    for (const Event& e : expand_job(j))
        if (const auto* c = std::get_if<TurnCycle>(&e); c && !c->refusal) return *c;
    return std::nullopt;
}

}  // namespace

TEST_CASE("fanuc-g72: generated facing profiles: canned where the model takes them, read back as the job's moves") {
    const Machine fanuc = load_machine("fanuc-lathe");
    REQUIRE(fanuc.rough_pattern() == RoughCyclePattern::fanuc_g71);
    Machine plain = fanuc;  // a control without sequence numbers: the shape's blocks carry their own
    plain.block.sequence_numbers = false;
    std::mt19937 rng(72);
    int canned = 0, longhand = 0, checked_moves = 0, unreachable = 0, fanuc_refused = 0;
    for (int n = 0; n < 60; ++n) {
        double d0 = 0;
        const std::string path = fx_profile(rng, d0);
        const double doc = (n % 3 == 0) ? 1.5 : (n % 3 == 1 ? 1.0 : 2.2);
        CAPTURE(path);
        CAPTURE(doc);
        std::optional<Job> read_in;
        try {
            read_in = read_job(fx_job(path, d0, doc, n % 2 ? R"(, "compensation": "none")" : ""), "fx.json");
        } catch (const InputError&) {
            ++unreachable;  // the nose cannot follow this profile: not a roughing
            continue;
        }
        const Job& j = *read_in;
        const auto& op = std::get<TurnRoughOp>(j.operations.at(1));
        const TurnCycle c = turn_cycle(op);
        REQUIRE(c.along_x);
        const std::vector<LatheCycleMove> moves = turn_cycle_path(c, RoughCyclePattern::fanuc_g71);
        // (where Fanuc's model refuses what LinuxCNC's takes, the path is LinuxCNC's: longhand with a note)
        const bool fanuc_takes = !c.refusal && moves != c.moves;
        if (!c.refusal && !fanuc_takes) ++fanuc_refused;
        for (const Machine* m : {&fanuc, static_cast<const Machine*>(&plain)}) {
            const auto p = test::post_noted(j, *m);
            const bool is_canned = p.text.find("G72 W") != std::string::npos;
            if (m == &fanuc) (is_canned ? canned : longhand)++;
            if (!is_canned && m == &fanuc && p.notes.find("longhand") != std::string::npos)
                MESSAGE(p.notes.substr(p.notes.find("longhand"), 160));
            // Written where Fanuc's model of the rounded words cuts camgen's passes.
            if (!fanuc_takes) CHECK_FALSE(is_canned);
            if (is_canned) CHECK(fanuc_takes);
            // verify --job: the program read back moves as the job's events traced for the machine.
            const Trace read = trace_program(read_program(p.text, *m, "t.nc"), *m);
            const auto miss = compare_traces(trace_expected(expand_job(j), *m), read, compare_tolerance(*m));
            CHECK_MESSAGE(!miss, (miss ? miss->message : "") << "\n" << p.text);
            if (is_canned) {
                // P and Q name the blocks right after the cycle; ns is G0 Z (type I).
                const std::size_t at = p.text.find("G72 P");
                REQUIRE(at != std::string::npos);
                const long ns = std::stol(p.text.substr(at + 5));
                const std::size_t next = p.text.find('\n', at) + 1;
                CHECK(p.text.substr(next, fmt::format("N{} G0 Z", ns).size()) == fmt::format("N{} G0 Z", ns));
                // A deliberately wrong depth of cut (W too small) is found by verify.
                std::string wrong = p.text;
                const std::size_t w = wrong.find("G72 W");
                const std::size_t end = wrong.find(' ', w + 4);
                wrong.replace(w + 4, end - (w + 4), "W0.400");
                bool found = false;
                try {
                    found = compare_traces(trace_expected(expand_job(j), *m), trace_program(read_program(wrong, *m, "t.nc"), *m),
                                           compare_tolerance(*m))
                                .has_value();
                } catch (const InputError&) {
                    found = true;  // refused by the reader: a level through a corner
                }
                CHECK(found);
                // The way out: from A at rapid, no feed after the shape's last block.
                const std::size_t q = p.text.find("G72 P");
                const long nf = std::stol(p.text.substr(p.text.find('Q', q) + 1));
                const std::size_t last = p.text.find(fmt::format("N{} ", nf));
                REQUIRE(last != std::string::npos);
                const std::size_t after = p.text.find('\n', last) + 1;
                const std::string line = p.text.substr(after, p.text.find('\n', after) - after);
                CHECK_MESSAGE((line.find("G0 ") != std::string::npos && line.find("G1") == std::string::npos), line);
            }
        }
        if (!fanuc_takes) continue;
        // The model's moves: no feed below the boundary, no rapid into material.
        const Profile& b = op.tip_boundary;
        const double face = op.bar_face.value_or(0.5), stock = op.stock_radius;
        const Vec2 a = fanuc_g71_start(c);
        struct Pass {
            double z, r;  // cleared: Z at and above z, radius at and above r
        };
        std::vector<Pass> passes;
        Vec2 at = Vec2{c.start.z, c.start.x};
        // The pass along the shape: after the last rapid to its start A'.
        std::size_t contour = moves.size();
        for (std::size_t k = 0; k < moves.size(); ++k)
            if (moves[k].kind == LatheCycleMove::Kind::rapid && distance(moves[k].end, Vec2{c.profile.start.x, a.y}) < 1e-9)
                contour = k;
        REQUIRE(contour < moves.size());
        for (std::size_t k = 0; k < moves.size(); ++k) {
            const LatheCycleMove& m = moves[k];
            const bool last = k + 1 == moves.size();
            for (int s = 0; s <= 20 && m.kind != LatheCycleMove::Kind::arc; ++s) {  // (arcs: on the boundary)
                const Vec2 q = at + (m.end - at) * (s / 20.0);
                const double below = fx_radius_at(b, q.x);
                if (below >= 0 && (k <= contour || last))
                    CHECK_MESSAGE(q.y >= below - 1e-6, "move " << k << " below the boundary at Z " << q.x);
                if (m.kind != LatheCycleMove::Kind::rapid || q.x >= face - 1e-9 || q.y >= stock - 1e-9) continue;
                bool cleared = last;  // the return to A: after the pass along the shape, above it
                for (const Pass& ps : passes) cleared = cleared || (q.x >= ps.z - 1e-6 && q.y >= ps.r - 1e-6);
                CHECK_MESSAGE(cleared, "rapid " << k << " into material at Z " << q.x << " radius " << q.y);
            }
            if (m.kind == LatheCycleMove::Kind::feed && std::abs(m.end.x - at.x) < 1e-9 && m.end.y < at.y)
                passes.push_back({m.end.x, m.end.y});
            at = m.end;
            ++checked_moves;
        }
        // The control ends at A; the way out is at rapid, outside the bar or beyond its face.
        CHECK(distance(moves.back().end, a) < 1e-9);
        const std::optional<TurnCycle> emitted = fx_emitted(j);
        REQUIRE(emitted);
        for (const Event& e : turn_cycle_exit(*emitted, RoughCyclePattern::fanuc_g71)) {
            const auto* r = std::get_if<Rapid>(&e);
            REQUIRE(r);
            CHECK((r->to.x >= stock - 1e-9 || r->to.z >= face - 1e-9));
        }
    }
    MESSAGE("fanuc-g72: " << canned << " canned, " << longhand << " longhand (" << fanuc_refused
                          << " where Fanuc's model refuses LinuxCNC's levels), " << unreachable
                          << " profiles the nose cannot follow, " << checked_moves << " model moves checked");
    CHECK(canned >= 20);
}

TEST_CASE("fanuc-g72: the reader refuses what it does not model") {
    const Machine fanuc = load_machine("fanuc-lathe");
    auto refusal = [&](const std::string& body) {
        const std::string text = "%\nO1000\nG18 G40 G80 G98 G21\nT0101\nG97 S1000 M3\nG0 X42.000 Z0.500\n" + body + "M30\n%\n";
        try {
            (void)read_program(text, fanuc, "t.nc");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string shape = "N100 G0 Z-12.000\nN101 G1 X30.000\nN102 G1 X20.000 Z-4.000\nN103 G1 X10.000 Z0.000\n";
    CHECK(refusal("G72 W1.400 R0.500\nG72 P100 Q103 U0.000 W0.000 F200\n" + shape) == "");
    // The allowance is read (the shape moved by it: test_fanuc_g70.cpp); a negative one is not modelled.
    CHECK(refusal("G72 W1.400 R0.500\nG72 P100 Q103 U0.000 W0.200 F200\n" + shape) == "");
    CHECK(refusal("G72 W1.400 R0.500\nG72 P100 Q103 U-0.400 W0.000 F200\n" + shape).find("negative") != std::string::npos);
    CHECK(refusal("G72 P100 Q103 U0.000 W0.000 F200\n" + shape).find("G72 P Q without its first block G72 W R") !=
          std::string::npos);
    // G71's first block does not set G72's.
    CHECK(refusal("G71 U1.400 R0.500\nG72 P100 Q103 U0.000 W0.000 F200\n" + shape).find("without its first block") !=
          std::string::npos);
    CHECK(refusal("G72 U1.400 R0.500\n").find("G72 W(depth of cut) R(retract)") != std::string::npos);
    CHECK(refusal("G72 W1.400 R0.500\nG72 P100 Q103 U0.000 W0.000 F200\nN100 G0 X40.000 Z-12.000\nN101 G1 X30.000\n"
                  "N102 G1 X20.000 Z-4.000\nN103 G1 X10.000 Z0.000\n")
              .find("along Z only") != std::string::npos);
    CHECK(refusal("G72 W1.400 R0.500\nG72 P100 Q103 U0.000 W0.000 F200\nN100 G0 Z-12.000\nN101 G1 X30.000\n")
              .find("finishing shape") != std::string::npos);
    // A pocket: Z falls along the shape.
    CHECK(refusal("G72 W1.400 R0.500\nG72 P100 Q103 U0.000 W0.000 F200\nN100 G0 Z-12.000\nN101 G1 X30.000\n"
                  "N102 G1 X20.000 Z-8.000\nN103 G1 X10.000 Z-9.000\n")
              .find("falls in Z") != std::string::npos);
    // A shape that ends beyond A in Z.
    CHECK(refusal("G72 W1.400 R0.500\nG72 P100 Q103 U0.000 W0.000 F200\nN100 G0 Z-12.000\nN101 G1 X30.000\n"
                  "N102 G1 X20.000 Z-4.000\nN103 G1 X10.000 Z1.000\n")
              .find("ends beyond the start point in Z") != std::string::npos);
    // The cycle's moves: from A along -X at Z levels 1.4 apart, back to A.
    const std::string text = "%\nO1000\nG18 G40 G80 G98 G21\nT0101\nG97 S1000 M3\nG0 X42.000 Z0.500\nG72 W1.400 R0.500\n"
                             "G72 P100 Q103 U0.000 W0.000 F200\n" +
                             shape + "M30\n%\n";
    const Trace t = trace_program(read_program(text, fanuc, "t.nc"), fanuc);
    int along_x = 0;
    std::optional<Vec3> end;
    for (const Step& s : t.steps) {
        if (s.kind == StepKind::feed && std::abs(s.from.z - s.to.z) < 1e-9 && s.to.x < s.from.x - 1e-6) ++along_x;
        if (s.kind == StepKind::feed || s.kind == StepKind::rapid) end = s.to;
    }
    CHECK(along_x >= 8);  // levels -0.9 .. -11.1 and the shape's X moves
    REQUIRE(end);
    CHECK(end->x == doctest::Approx(21.0));  // back at A (radius)
    CHECK(end->z == doctest::Approx(0.5));
}

TEST_CASE("fanuc roughing cycles: the way out starts from A at rapid; LinuxCNC's lifts off the last pass") {
    // (the shaft sample's rough on fanuc-lathe was a 44 mm feed from A in air)
    const std::string path = R"([{"line": [18, 0]}, {"line": [20, -1]}, {"line": [20, -15]}, {"line": [26, -20]},
        {"arc": {"end": [32, -23], "centre": [26, -23], "direction": "ccw"}}, {"line": [32, -35]}])";
    const Machine fanuc = load_machine("fanuc-lathe");
    const Machine lcnc = load_machine("linuxcnc-lathe");
    for (const char* dir : {"z", "x"}) {
        CAPTURE(dir);
        const std::string text = fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0.5}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}}],
  "operations": [{{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.5}},
                 {{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": 1.5, "allowanceX": 0.4, "allowanceZ": 0.1, "direction": "{}", "start": [16, 0], "path": {}}}]}})",
                                             dir, path);
        const Job j = read_job(text, "fx.json");
        const std::optional<TurnCycle> c = fx_emitted(j);
        REQUIRE(c);
        CHECK(c->lift > 0);
        CHECK(c->out_z == 10.0);
        // Fanuc: rapids only, from A, outside the bar or beyond its face, ending at the clearance.
        const std::vector<Event> out = turn_cycle_exit(*c, RoughCyclePattern::fanuc_g71);
        REQUIRE_FALSE(out.empty());
        for (const Event& e : out) {
            const auto* r = std::get_if<Rapid>(&e);
            REQUIRE(r);
            CHECK((r->to.x >= 20.0 || r->to.z >= 0.0));
        }
        CHECK(std::get<Rapid>(out.back()).to.z == 10.0);
        // LinuxCNC: a feed off the last pass first (it ends on the boundary).
        const std::vector<Event> lout = turn_cycle_exit(*c, RoughCyclePattern::linuxcnc_g71);
        REQUIRE(lout.size() == 3);
        CHECK(std::get<Linear>(lout.front()).movement == Movement::lead_out);
        // Both programs read back as the job's moves; the Fanuc one has no feed between the
        // shape's last block and the next tool change or end.
        for (const Machine* m : {&fanuc, &lcnc}) {
            const auto p = test::post_noted(j, *m);
            CHECK_MESSAGE(p.notes.find("is written longhand") == std::string::npos, p.notes);
            const auto miss = compare_traces(trace_expected(expand_job(j), *m),
                                             trace_program(read_program(p.text, *m, "t.nc"), *m), compare_tolerance(*m));
            CHECK_MESSAGE(!miss, (miss ? miss->message : ""));
        }
        const auto p = test::post_noted(j, fanuc);
        const std::size_t q = p.text.find(std::string("G7") + (std::string(dir) == "z" ? "1" : "2") + " P");
        REQUIRE(q != std::string::npos);
        const long nf = std::stol(p.text.substr(p.text.find('Q', q) + 1));
        const std::size_t after = p.text.find('\n', p.text.find(fmt::format("N{} ", nf))) + 1;
        const std::string rest = p.text.substr(after, p.text.find("M5", after) - after);
        CHECK_MESSAGE(rest.find("G1") == std::string::npos, rest);
        CHECK_MESSAGE(rest.find("G0") != std::string::npos, rest);
    }
}

}  // namespace test_fanuc_g72
