// G41/G42 as the control cuts it (issue 24): camgen's CutterCompensation against LinuxCNC's own
// interpreter. Random closed profiles of lines and arcs (convex and concave corners, tangent and
// non-tangent joints, arcs bulging out and in), random tool radii, sides, starts and entry and
// exit moves; each program runs through `rs274 -g` with the tool in its table and through
// CutterCompensation. Where rs274 refuses the program camgen must refuse it too; where it cuts,
// the tool-centre moves must agree within 0.001 mm (kind, end point, arc centre and turning).
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/geometry/compensation.hpp"
#include "camgen/post/machine.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_compensation_oracle {

using namespace camgen;
using namespace camgen::oracle;
using camgen::oracle::Step;  // not camgen::Step (analysis/trace.hpp), which a unity build may see too

namespace {

double r3(double v) { return std::round(v * 1000.0) / 1000.0; }

struct Programmed {
    std::string text;
    std::vector<std::pair<int, CompMove>> moves;  // 0 move, 1 G41, 2 G42, 3 G40 (then the move is unused)
};

// A random closed profile around the origin: n vertices at random radii and sorted angles, some
// edges arcs through a centre on the edge's bisector (bulging out or in).
Programmed random_program(std::mt19937& rng, double tool_r, bool left, bool& has_arcs) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 3 + static_cast<int>(u(rng) * 6);
    std::vector<double> angles;
    for (int k = 0; k < n; ++k) angles.push_back(u(rng) * 2 * M_PI);
    std::sort(angles.begin(), angles.end());
    std::vector<Vec2> v;
    for (double a : angles) {
        const double rad = 20 + 30 * u(rng);
        v.push_back({r3(rad * std::cos(a)), r3(rad * std::sin(a))});
    }
    if (u(rng) < 0.5) std::reverse(v.begin(), v.end());
    Programmed p;
    std::ostringstream s;
    s << "G21 G17 G90 G40 G49 G80 G94\nT1 M6 G43\nM3 S1000\n";
    const Vec2 first = v[0];
    // Entry: from a point away from the first vertex, longer than the radius.
    const double ea = u(rng) * 2 * M_PI, el = tool_r * (1.2 + 3 * u(rng)) + 1;
    const Vec2 start{r3(first.x + el * std::cos(ea)), r3(first.y + el * std::sin(ea))};
    s << fmt::format("G0 X{:.3f} Y{:.3f} Z5\nG1 Z-1 F100\n", start.x, start.y);
    p.moves.push_back({0, CompMove{CompMove::Kind::rapid, {start.x, start.y, 5}, {}}});
    p.moves.push_back({0, CompMove{CompMove::Kind::feed, {start.x, start.y, -1}, {}}});
    s << (left ? "G41\n" : "G42\n");
    p.moves.push_back({left ? 1 : 2, {}});
    s << fmt::format("G1 X{:.3f} Y{:.3f}\n", first.x, first.y);
    p.moves.push_back({0, CompMove{CompMove::Kind::feed, {first.x, first.y, -1}, {}}});
    Vec2 at = first;
    for (int k = 1; k <= n; ++k) {
        const Vec2 to = v[k % n];
        const double dx = to.x - at.x, dy = to.y - at.y, len = std::hypot(dx, dy);
        if (len < 0.5) continue;
        if (u(rng) < 0.4) {
            has_arcs = true;
            // Centre on the bisector, offset h (signed); direction either way.
            const double h = (u(rng) - 0.5) * 3 * len;
            Vec2 c{r3((at.x + to.x) / 2 - dy / len * h), r3((at.y + to.y) / 2 + dx / len * h)};
            const bool ccw = u(rng) < 0.5;
            // The end on the circle through `at` about c (rounded; rs274 tolerates the rest).
            const double rad = std::hypot(at.x - c.x, at.y - c.y);
            const double ta = std::atan2(to.y - c.y, to.x - c.x);
            const Vec2 e{r3(c.x + rad * std::cos(ta)), r3(c.y + rad * std::sin(ta))};
            s << fmt::format("{} X{:.3f} Y{:.3f} I{:.3f} J{:.3f}\n", ccw ? "G3" : "G2", e.x, e.y, c.x - at.x, c.y - at.y);
            CompMove m{CompMove::Kind::arc, {e.x, e.y, -1}, c, ccw ? ArcDirection::ccw : ArcDirection::cw};
            p.moves.push_back({0, m});
            at = e;
        } else {
            s << fmt::format("G1 X{:.3f} Y{:.3f}\n", to.x, to.y);
            p.moves.push_back({0, CompMove{CompMove::Kind::feed, {to.x, to.y, -1}, {}}});
            at = to;
        }
    }
    // Exit: a straight move on with compensation, then off and away.
    const double xa = u(rng) * 2 * M_PI, xl = tool_r * (1.2 + 3 * u(rng)) + 1;
    const Vec2 out{r3(at.x + xl * std::cos(xa)), r3(at.y + xl * std::sin(xa))};
    s << fmt::format("G1 X{:.3f} Y{:.3f}\nG40\n", out.x, out.y);
    p.moves.push_back({0, CompMove{CompMove::Kind::feed, {out.x, out.y, -1}, {}}});
    p.moves.push_back({3, {}});
    const Vec2 away{r3(out.x + 2 * std::cos(xa)), r3(out.y + 2 * std::sin(xa))};
    s << fmt::format("G1 X{:.3f} Y{:.3f}\nG0 Z5\nM5\nM2\n", away.x, away.y);
    p.moves.push_back({0, CompMove{CompMove::Kind::feed, {away.x, away.y, -1}, {}}});
    p.moves.push_back({0, CompMove{CompMove::Kind::rapid, {away.x, away.y, 5}, {}}});
    p.text = s.str();
    return p;
}

struct Outcome {
    std::vector<Step> steps;
    std::optional<std::string> error;
};

Outcome camgen_cut(const Programmed& p, double tool_r) {
    Outcome o;
    Vec3 pos{0, 0, 0};
    CutterCompensation comp([&](const CompMove& m) {
        Step s;
        s.to = m.end;
        if (m.kind == CompMove::Kind::arc) {
            s.kind = Step::Kind::arc;
            s.centre = m.centre;
            s.rotation = m.direction == ArcDirection::ccw ? 1 + m.turns : -1 - m.turns;
        } else {
            s.kind = m.kind == CompMove::Kind::rapid ? Step::Kind::traverse : Step::Kind::feed;
        }
        o.steps.push_back(s);
    });
    comp.set_position({0, 0, 0});
    (void)pos;
    for (const auto& [what, m] : p.moves) {
        std::optional<CompError> e;
        if (what == 0) e = comp.move(m);
        else if (what == 3) e = comp.off(0);
        else e = comp.on(what == 1 ? CompSide::left : CompSide::right, tool_r, 0);
        if (e) {
            o.error = e->message;
            return o;
        }
    }
    comp.flush();
    return o;
}

// Drops moves that go nowhere (rs274 prints some, camgen's reader drops them).
std::vector<Step> moving(const std::vector<Step>& steps) {
    std::vector<Step> out;
    Vec3 at{0, 0, 0};
    for (const Step& s : steps) {
        if (s.kind == Step::Kind::spindle || s.kind == Step::Kind::dwell) continue;
        if (std::hypot(s.to.x - at.x, s.to.y - at.y, s.to.z - at.z) < 0.0005) continue;
        out.push_back(s);
        at = s.to;
    }
    return out;
}

}  // namespace

TEST_CASE("compensation: camgen's G41/G42 interpretation cuts what rs274 cuts, and refuses what it refuses") {
    const auto rs274 = find_rs274();
    REQUIRE_MESSAGE(rs274, "rs274 (linuxcnc-uspace) is needed for the compensation oracle");
    const unsigned seed = std::getenv("CAMGEN_COMP_SEED") ? static_cast<unsigned>(std::atoi(std::getenv("CAMGEN_COMP_SEED"))) : 2412u;
    const int count = std::getenv("CAMGEN_COMP_CASES") ? std::atoi(std::getenv("CAMGEN_COMP_CASES")) : 200;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int accepted = 0, refused = 0, with_arcs = 0;
    for (int k = 0; k < count; ++k) {
        const double tool_r = r3(0.5 + 6 * u(rng));
        const bool left = u(rng) < 0.5;
        bool has_arcs = false;
        const Programmed p = random_program(rng, tool_r, left, has_arcs);
        with_arcs += has_arcs;
        Outcome theirs;
        try {
            theirs.steps = moving(run_rs274(*rs274, p.text, {{1, 2 * tool_r}}));
        } catch (const std::exception& e) {
            theirs.error = e.what();
        }
        const Outcome ours = camgen_cut(p, tool_r);
        INFO("seed ", seed, " case ", k, " tool radius ", tool_r, "\n", p.text);
        if (theirs.error) {
            ++refused;
            CHECK_MESSAGE(ours.error.has_value(), "rs274 refused: ", *theirs.error);
            if (ours.error) CHECK_MESSAGE(theirs.error->find(*ours.error) != std::string::npos, "rs274: ", *theirs.error, " camgen: ", *ours.error);
            continue;
        }
        ++accepted;
        REQUIRE_MESSAGE(!ours.error, "camgen refused: ", ours.error.value_or(""));
        const std::vector<Step> mine = moving(ours.steps);
        REQUIRE(mine.size() == theirs.steps.size());
        for (std::size_t i = 0; i < mine.size(); ++i) {
            INFO("move ", i, ": rs274 ", describe(theirs.steps[i]), ", camgen ", describe(mine[i]));
            CHECK(mine[i].kind == theirs.steps[i].kind);
            CHECK(std::hypot(mine[i].to.x - theirs.steps[i].to.x, mine[i].to.y - theirs.steps[i].to.y, mine[i].to.z - theirs.steps[i].to.z) < 0.001);
            if (mine[i].kind == Step::Kind::arc) {
                CHECK(std::hypot(mine[i].centre.x - theirs.steps[i].centre.x, mine[i].centre.y - theirs.steps[i].centre.y) < 0.001);
                CHECK(mine[i].rotation == theirs.steps[i].rotation);
            }
        }
    }
    MESSAGE(fmt::format("compensation oracle: seed {}, {} programs ({} with arcs): {} cut alike, {} refused by both", seed, count,
                        with_arcs, accepted, refused));
    CHECK(accepted > count / 4);
    CHECK(refused > 0);
}

// The same random programs read back by camgen (the linuxcnc reader and the TraceBuilder, which
// applies CutterCompensation in the read-back): the trace is rs274's motion, move for move, or
// both refuse, camgen at the line rs274 stops at.
TEST_CASE("compensation: camgen's read-back of a G41/G42 program traces what rs274 cuts, and refuses at rs274's line") {
    const auto rs274 = find_rs274();
    REQUIRE_MESSAGE(rs274, "rs274 (linuxcnc-uspace) is needed for the compensation oracle");
    const Machine machine = load_machine("linuxcnc");
    const unsigned seed = std::getenv("CAMGEN_COMP_SEED") ? static_cast<unsigned>(std::atoi(std::getenv("CAMGEN_COMP_SEED"))) : 2413u;
    const int count = std::getenv("CAMGEN_COMP_CASES") ? std::atoi(std::getenv("CAMGEN_COMP_CASES")) : 100;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int accepted = 0, refused = 0;
    const auto with = [](std::string text, const std::string& from, const std::string& to) {
        const std::size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        return text.replace(at, from.size(), to);
    };
    for (int k = 0; k < count; ++k) {
        const double tool_r = r3(0.5 + 6 * u(rng));
        const bool left = u(rng) < 0.5;
        bool has_arcs = false;
        const Programmed p = random_program(rng, tool_r, left, has_arcs);
        // As the linuxcnc machine writes it: H and D words, a spindle speed before M3.
        std::string text = with(with(p.text, "G43\n", "G43 H1\n"), left ? "G41\n" : "G42\n", left ? "G41 D1\n" : "G42 D1\n");
        text = with(text, "M3 S1000\n", "S1000 M3\n");
        INFO("seed ", seed, " case ", k, " tool radius ", tool_r, "\n", text);
        std::optional<std::string> theirs_error;
        std::vector<Step> theirs;
        try {
            theirs = moving(run_rs274(*rs274, text, {{1, 2 * tool_r}}));
        } catch (const std::exception& e) {
            theirs_error = e.what();
        }
        const CompensatedRead ours = read_with_camgen(text, machine, {{1, tool_r}});
        if (ours.refused_line == 0) {
            const std::vector<Step> mine = moving(ours.steps);
            REQUIRE_MESSAGE(!theirs_error, "rs274 refused: ", theirs_error.value_or(""));
            ++accepted;
            REQUIRE(mine.size() == theirs.size());
            for (std::size_t i = 0; i < mine.size(); ++i) {
                INFO("move ", i, ": rs274 ", describe(theirs[i]), ", camgen ", describe(mine[i]));
                CHECK(mine[i].kind == theirs[i].kind);
                CHECK(std::hypot(mine[i].to.x - theirs[i].to.x, mine[i].to.y - theirs[i].to.y, mine[i].to.z - theirs[i].to.z) < 0.001);
                if (mine[i].kind == Step::Kind::arc) {
                    CHECK(std::hypot(mine[i].centre.x - theirs[i].centre.x, mine[i].centre.y - theirs[i].centre.y) < 0.001);
                    CHECK(mine[i].rotation == theirs[i].rotation);
                }
            }
        } else {
            REQUIRE_MESSAGE(theirs_error, "camgen refused at line ", ours.refused_line, ": ", ours.refusal);
            ++refused;
            // rs274 prints its message and then the block it stopped at.
            const std::vector<std::string> lines = [&] {
                std::vector<std::string> out;
                std::istringstream in(text);
                for (std::string l; std::getline(in, l);) out.push_back(l);
                return out;
            }();
            REQUIRE(ours.refused_line <= static_cast<int>(lines.size()));
            CHECK_MESSAGE(theirs_error->find(ours.refusal + "\n" + lines[static_cast<std::size_t>(ours.refused_line - 1)]) !=
                              std::string::npos,
                          "rs274: ", *theirs_error, " camgen: line ", ours.refused_line, ": ", ours.refusal);
        }
    }
    MESSAGE(fmt::format("compensation read-back oracle: seed {}, {} programs: {} traced alike, {} refused by both at one line",
                        seed, count, accepted, refused));
    CHECK(accepted > count / 4);
    CHECK(refused > 0);
}

}  // namespace test_compensation_oracle
