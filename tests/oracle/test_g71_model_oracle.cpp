// camgen's model of LinuxCNC's G71 (geometry/lathe_cycle.hpp: what the linuxcnc-lathe reader
// expands a G71 into, and the longhand a canned turn-rough carries) against rs274 running the
// same cycle: many generated profiles (shafts with steps, tapers, chamfers, convex rounds and
// concave fillets, quarter and partial arcs; start points above and beside the bar's end, on
// and off the profile's start Z; depths and retracts that land on the profile's radii and not),
// every move equal within 0.001 mm.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/geometry/lathe_cycle.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/geometry/vec.hpp"
#include "rs274.hpp"

namespace test_g71_model_oracle {

using namespace camgen;

namespace {

std::string g71m_rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A move rs274 printed (or the model made), in (Z, radius).
struct G71mMove {
    char kind = 'r';  // r rapid, f feed, a arc
    double z = 0, x = 0, cz = 0, cx = 0;
    int rot = 0;
};

std::vector<G71mMove> g71m_normalise(const std::vector<G71mMove>& in) {
    std::vector<G71mMove> out;
    for (const G71mMove& m : in) {
        if (!out.empty() && std::abs(out.back().x - m.x) < 1e-4 && std::abs(out.back().z - m.z) < 1e-4) continue;
        out.push_back(m);
    }
    return out;
}

std::vector<G71mMove> g71m_canon(const std::string& canon) {
    std::vector<G71mMove> out;
    std::istringstream lines(canon);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t open = line.find('('), close = line.rfind(')');
        if (open == std::string::npos || close == std::string::npos) continue;
        std::vector<double> a;
        std::istringstream args(line.substr(open + 1, close - open - 1));
        for (std::string part; std::getline(args, part, ',');) a.push_back(std::strtod(part.c_str(), nullptr));
        G71mMove m;
        if (line.find("STRAIGHT_TRAVERSE") != std::string::npos || line.find("STRAIGHT_FEED") != std::string::npos) {
            m.kind = line.find("STRAIGHT_TRAVERSE") != std::string::npos ? 'r' : 'f';
            m.x = a.at(0), m.z = a.at(2);
        } else if (line.find("ARC_FEED") != std::string::npos) {
            m.kind = 'a';
            m.z = a.at(0), m.x = a.at(1), m.cz = a.at(2), m.cx = a.at(3), m.rot = static_cast<int>(a.at(4));
        } else {
            continue;
        }
        out.push_back(m);
    }
    return g71m_normalise(out);
}

std::vector<G71mMove> g71m_model(const LatheCycleModel& model) {
    std::vector<G71mMove> out;
    for (const LatheCycleMove& m : model.moves) {
        G71mMove g;
        g.kind = m.kind == LatheCycleMove::Kind::rapid ? 'r' : m.kind == LatheCycleMove::Kind::feed ? 'f' : 'a';
        g.z = m.end.x, g.x = m.end.y;
        if (g.kind == 'a') g.cz = m.centre.x, g.cx = m.centre.y, g.rot = m.direction == ArcDirection::ccw ? 1 : -1;
        out.push_back(g);
    }
    return g71m_normalise(out);
}

std::string g71m_num(double v) {
    std::string s = fmt::format("{:.4f}", v);
    if (s == "-0.0000") s = "0.0000";
    return s;
}

// One generated case: the profile and the program that runs G71 on it.
struct G71mCase {
    Profile profile;
    Vec2 start;
    double depth = 1, retract = 0.5;
    std::string sub;
};

G71mCase g71m_generate(std::mt19937& rng) {
    auto pick = [&](int lo, int hi) { return lo + static_cast<int>(rng() % static_cast<unsigned>(hi - lo + 1)); };
    G71mCase c;
    c.profile.plane = ProfilePlane::xz;
    Vec2 at{0.0, pick(4, 16) * 0.5};
    c.profile.start = at;
    std::ostringstream sub;
    sub << "G1 X" << g71m_num(2 * at.y) << " Z" << g71m_num(at.x) << "\n";
    const int n = pick(1, 6);
    auto line_to = [&](Vec2 to) {
        c.profile.segments.push_back({to, std::nullopt, ArcDirection::ccw});
        sub << "G1 X" << g71m_num(2 * to.y) << " Z" << g71m_num(to.x) << "\n";
        at = to;
    };
    auto arc_to = [&](Vec2 to, Vec2 centre, bool ccw) {
        c.profile.segments.push_back({to, centre, ccw ? ArcDirection::ccw : ArcDirection::cw});
        sub << (ccw ? "G3" : "G2") << " X" << g71m_num(2 * to.y) << " Z" << g71m_num(to.x) << " I"
            << g71m_num(centre.y - at.y) << " K" << g71m_num(centre.x - at.x) << "\n";
        at = to;
    };
    for (int i = 0; i < n; ++i) {
        switch (pick(0, 7)) {
            case 0: line_to(at + Vec2{-pick(2, 20) * 0.5, 0.0}); break;                      // along -Z
            case 1: line_to(at + Vec2{-pick(2, 12) * 0.5, pick(1, 6) * 0.5}); break;         // a taper
            case 2: line_to(at + Vec2{0.0, pick(1, 6) * 0.5}); break;                        // a shoulder
            case 3: {  // a 45-degree chamfer
                const double k = pick(1, 8) * 0.25;
                line_to(at + Vec2{-k, k});
            } break;
            case 4: {  // a convex quarter round, face to cylinder
                const double r = pick(1, 8) * 0.25;
                arc_to(at + Vec2{-r, r}, at + Vec2{-r, 0.0}, true);
            } break;
            case 5: {  // a concave quarter fillet, cylinder to face
                const double r = pick(1, 8) * 0.25;
                arc_to(at + Vec2{-r, r}, at + Vec2{0.0, r}, false);
            } break;
            case 6: {  // part of a convex arc: from (4,3) to (3,4) of a 3-4-5 triangle
                const double k = pick(1, 6) * 0.25;
                const Vec2 centre = at + Vec2{-4 * k, -3 * k};
                arc_to(centre + Vec2{3 * k, 4 * k}, centre, true);
            } break;
            default: {  // part of a concave arc: from (-3,-4) to (-4,-3)
                const double k = pick(1, 6) * 0.25;
                const Vec2 centre = at + Vec2{3 * k, 4 * k};
                arc_to(centre + Vec2{-4 * k, -3 * k}, centre, false);
            } break;
        }
    }
    if (c.profile.segments.back().end.x > -0.5) line_to(at + Vec2{-2.0, 0.0});
    const double end_r = at.y;
    // Off the profile's grid of 0.25 (mostly): levels through its corners are not modelled.
    const double offsets[] = {0.0, 0.037, 0.1, 0.113, 0.2};
    c.start = Vec2{pick(1, 6) * 0.5, std::max(c.profile.start.y + 0.5, end_r + pick(-4, 6) * 0.5) + offsets[pick(0, 4)]};
    const double depths[] = {0.3, 0.5, 0.7, 1.0, 1.25, 2.0, 2.5};
    const double retracts[] = {0.2, 0.5, 1.0, 1.5};
    c.depth = depths[pick(0, 6)];
    c.retract = retracts[pick(0, 3)];
    c.sub = sub.str();
    return c;
}

std::string g71m_program(const G71mCase& c) {
    return "G18 G7 G21 G90\nT1 M6\nS1000 M3\nG95\nG0 X" + g71m_num(2 * c.start.y) + " Z" + g71m_num(c.start.x) +
           "\nO100 sub\n" + c.sub + "O100 endsub\nG71 Q100 D0 I" + g71m_num(c.depth) + " R" + g71m_num(c.retract) +
           " F0.2\nM2\n";
}

void g71m_compare(const G71mCase& c, const std::string& rs274, LatheCycleAxis axis = LatheCycleAxis::z) {
    const LatheCycleModel model = linuxcnc_g7x(axis, c.start, c.profile, c.depth, c.retract);
    std::string program = g71m_program(c);
    if (axis == LatheCycleAxis::x) program.replace(program.find("G71 Q100"), 3, "G72");
    INFO(program);
    REQUIRE_FALSE(model.refusal);
    const std::vector<G71mMove> want = g71m_canon(oracle::run_rs274_canon(rs274, program));
    const std::vector<G71mMove> got = g71m_model(model);
    std::string diff;
    const std::size_t n = std::max(want.size(), got.size());
    for (std::size_t i = 0; i < n && diff.empty(); ++i) {
        if (i >= want.size() || i >= got.size()) {
            diff = fmt::format("move {}: rs274 made {} moves, the model {}", i, want.size(), got.size());
            break;
        }
        const G71mMove& w = want[i];
        const G71mMove& g = got[i];
        bool same = w.kind == g.kind && std::abs(w.z - g.z) < 1e-3 && std::abs(w.x - g.x) < 1e-3;
        if (same && w.kind == 'a') same = std::abs(w.cz - g.cz) < 1e-3 && std::abs(w.cx - g.cx) < 1e-3 && w.rot == g.rot;
        if (!same)
            diff = fmt::format("move {}: rs274 {} Z{:.4f} X{:.4f} (centre {:.4f} {:.4f} {}), the model {} Z{:.4f} X{:.4f} (centre "
                               "{:.4f} {:.4f} {})",
                               i, w.kind, w.z, w.x, w.cz, w.cx, w.rot, g.kind, g.z, g.x, g.cz, g.cx, g.rot);
    }
    CHECK_MESSAGE(diff.empty(), diff);
}

// The moves from the one ending at `start` on (the cycle's own), dropping what comes before.
std::vector<G71mMove> g71m_from(const std::vector<G71mMove>& all, Vec2 start) {
    for (std::size_t i = 0; i < all.size(); ++i)
        if (std::abs(all[i].z - start.x) < 1e-4 && std::abs(all[i].x - start.y) < 1e-4)
            return {all.begin() + static_cast<std::ptrdiff_t>(i), all.end()};
    return {};
}

// camgen's linuxcnc-lathe reader on the same program: its Rapid, Linear and Arc events.
std::vector<G71mMove> g71m_read(const std::string& program) {
    const Machine machine = load_machine("linuxcnc-lathe");
    std::vector<G71mMove> out;
    for (const ReadEvent& e : read_program(program, machine, "g71.ngc")) {
        G71mMove m;
        if (const auto* r = std::get_if<Rapid>(&e.event)) {
            m.kind = 'r', m.x = r->to.x, m.z = r->to.z;
        } else if (const auto* l = std::get_if<Linear>(&e.event)) {
            m.kind = 'f', m.x = l->to.x, m.z = l->to.z;
        } else if (const auto* a = std::get_if<Arc>(&e.event)) {
            m.kind = 'a', m.x = a->to.x, m.z = a->to.z, m.cx = a->centre.x, m.cz = a->centre.z;
            m.rot = a->direction == ArcDirection::ccw ? 1 : -1;
        } else {
            continue;
        }
        out.push_back(m);
    }
    return g71m_normalise(out);
}

std::string g71m_diff(const std::vector<G71mMove>& want, const std::vector<G71mMove>& got) {
    if (want.size() != got.size()) return fmt::format("rs274 made {} moves, camgen {}", want.size(), got.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
        const G71mMove& w = want[i];
        const G71mMove& g = got[i];
        bool same = w.kind == g.kind && std::abs(w.z - g.z) < 1e-3 && std::abs(w.x - g.x) < 1e-3;
        if (same && w.kind == 'a') same = std::abs(w.cz - g.cz) < 1e-3 && std::abs(w.cx - g.cx) < 1e-3 && w.rot == g.rot;
        if (!same)
            return fmt::format("move {}: rs274 {} Z{:.4f} X{:.4f}, camgen {} Z{:.4f} X{:.4f}", i, w.kind, w.z, w.x, g.kind, g.z, g.x);
    }
    return {};
}

// A linuxcnc-lathe program as camgen's reader takes it, running G71 on the case's profile.
std::string g71m_lathe_program(const G71mCase& c) {
    return "G18 G7 G40 G80 G90 G94 G21\nT1 M6\nS1000 M3\nG0 G43 Z20 H1\nX" + g71m_num(2 * c.start.y) + " Z" +
           g71m_num(c.start.x) + "\nO100 sub\n" + c.sub + "O100 endsub\nG71 Q100 D0 I" + g71m_num(c.depth) + " R" +
           g71m_num(c.retract) + " F100\nG0 Z20\nM5\nM2\n";
}

// A G71 case turned into a G72 one: each point (Z, radius) to (radius - 20, Z + 70) (Z and X
// swapped, moved so that the radii stay above 0; arcs turn the other way), the subroutine
// written anew. G72 on it is, by LinuxCNC's source, G71 on the original: rs274 decides.
G71mCase g72m_of(const G71mCase& g) {
    auto map = [](Vec2 p) { return Vec2{p.y - 20.0, p.x + 70.0}; };
    G71mCase c;
    c.profile.plane = ProfilePlane::xz;
    c.profile.start = map(g.profile.start);
    std::ostringstream sub;
    sub << "G1 X" << g71m_num(2 * c.profile.start.y) << " Z" << g71m_num(c.profile.start.x) << "\n";
    Vec2 at = c.profile.start;
    for (const ProfileSegment& s : g.profile.segments) {
        const Vec2 to = map(s.end);
        if (!s.centre) {
            c.profile.segments.push_back({to, std::nullopt, ArcDirection::ccw});
            sub << "G1 X" << g71m_num(2 * to.y) << " Z" << g71m_num(to.x) << "\n";
        } else {
            const Vec2 centre = map(*s.centre);
            const bool ccw = s.direction != ArcDirection::ccw;
            c.profile.segments.push_back({to, centre, ccw ? ArcDirection::ccw : ArcDirection::cw});
            sub << (ccw ? "G3" : "G2") << " X" << g71m_num(2 * to.y) << " Z" << g71m_num(to.x) << " I" << g71m_num(centre.y - at.y)
                << " K" << g71m_num(centre.x - at.x) << "\n";
        }
        at = to;
    }
    c.start = map(g.start);
    c.depth = g.depth;
    c.retract = g.retract;
    c.sub = sub.str();
    return c;
}

std::string g72m_lathe_program(const G71mCase& c) {
    std::string p = g71m_lathe_program(c);
    p.replace(p.find("G71 Q100"), 3, "G72");
    return p;
}

}  // namespace

TEST_CASE("linuxcnc-lathe reader: G71 with its profile subroutine is read as the moves rs274 makes") {
    const std::string rs274 = g71m_rs274();
    std::mt19937 rng(7);
    int compared = 0;
    const int stride = oracle::oracle_stride();
    for (int k = 0; k < 60; ++k) {
        const G71mCase c = g71m_generate(rng);
        if (!oracle::oracle_case(k)) continue;
        if (linuxcnc_g71(c.start, c.profile, c.depth, c.retract).refusal) continue;
        const std::string program = g71m_lathe_program(c);
        CAPTURE(k);
        INFO(program);
        const std::vector<G71mMove> want = g71m_from(g71m_canon(oracle::run_rs274_canon(rs274, program)), c.start);
        const std::vector<G71mMove> got = g71m_from(g71m_read(program), c.start);
        REQUIRE(want.size() > 3);
        const std::string diff = g71m_diff(want, got);
        CHECK_MESSAGE(diff.empty(), diff);
        ++compared;
    }
    CHECK(compared * stride >= 40);
}

TEST_CASE("linuxcnc-lathe reader: what it refuses of G71 and its subroutine") {
    const Machine machine = load_machine("linuxcnc-lathe");
    const std::string head = "G18 G7 G40 G80 G90 G94 G21\nT1 M6\nS1000 M3\nG0 G43 Z20 H1\nX41 Z2\n";
    const std::string sub = "O100 sub\nG1 X20 Z0\nG1 Z-20\nG1 X30.5\nO100 endsub\n";
    auto refusal = [&](const std::string& body) -> std::string {
        try {
            (void)read_program(head + body + "M5\nM2\n", machine, "g71.ngc");
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    CHECK(refusal(sub + "G71 Q100 D0 I1 R0.5 F100\n").empty());
    CHECK(refusal(sub + "G71 Q100 D1 I1 R0.5 F100\n").find("D0 only") != std::string::npos);
    CHECK(refusal(sub + "G71 Q200 D0 I1 F100\n").find("no subroutine o200") != std::string::npos);
    CHECK(refusal(sub + "G71 Q100 X40 Z2 I1 F100\n").find("from where the tool stands") != std::string::npos);
    CHECK(refusal("O100 sub\nG1 X20 Z0\nG1 Z-20\nG1 X18 Z-25\nG1 X30 Z-30\nO100 endsub\nG71 Q100 I1 F100\n")
              .find("element 1 falls in radius (a pocket)") != std::string::npos);
    CHECK(refusal(sub + "G0 X40 Z2\nG71 Q100 D0 I1 F100\n").find("runs through a corner of the profile") != std::string::npos);
    CHECK(refusal("O100 sub\nG1 X20 Z0\nM3\nO100 endsub\n").find("G0/G1/G2/G3 X Z I K only") != std::string::npos);
    // The program's end read into a subroutine left open.
    CHECK(refusal("O100 sub\nG1 X20 Z0\nG1 Z-20\n").find("M5 in subroutine o100") != std::string::npos);
    try {
        (void)read_program(head + "O100 sub\nG1 X20 Z0\nG1 Z-20\n", machine, "g71.ngc");
        FAIL("a subroutine without its end was read");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("has no o100 endsub") != std::string::npos);
    }
    CHECK(refusal("O100 endsub\n").find("without o100 sub") != std::string::npos);
    // fanuc-lathe has no such cycle: its reader does not take G71.
    const Machine fanuc = load_machine("fanuc-lathe");
    CHECK_THROWS(read_program("G71 Q100 I1\nM30\n", fanuc, "g71.nc"));
}

TEST_CASE("G71 model: the reference run R_g71_rough_sub's profile with D0 moves as rs274 moves") {
    G71mCase c;
    c.profile.plane = ProfilePlane::xz;
    c.profile.start = {0, 10};
    c.profile.segments = {{{-20, 10}, std::nullopt, ArcDirection::ccw},
                          {{-25, 15}, std::nullopt, ArcDirection::ccw},
                          {{-40, 15}, std::nullopt, ArcDirection::ccw},
                          {{-40, 20}, std::nullopt, ArcDirection::ccw}};
    c.sub = "G1 X20 Z0\nG1 Z-20\nG1 X30 Z-25\nG1 Z-40\nG1 X40\n";
    c.start = {2, 20.5};  // (X41: no level through a corner)
    c.depth = 1;
    c.retract = 0.5;
    g71m_compare(c, g71m_rs274());
}

TEST_CASE("G71 model: 300 generated monotone profiles move as rs274 moves, within 0.001 mm") {
    const std::string rs274 = g71m_rs274();
    std::mt19937 rng(20261203);
    int compared = 0;
    const int stride = oracle::oracle_stride();
    for (int k = 0; k < 300; ++k) {
        const G71mCase c = g71m_generate(rng);
        if (!oracle::oracle_case(k)) continue;
        CAPTURE(k);
        // What the model refuses (a level through a corner, a start at the profile's Z) is not
        // compared: camgen neither writes nor reads it as a G71.
        if (linuxcnc_g71(c.start, c.profile, c.depth, c.retract).refusal) continue;
        g71m_compare(c, rs274);
        ++compared;
    }
    CHECK(compared * stride >= 200);
    MESSAGE(compared << " of 300 generated profiles compared (one in " << stride << " checked)");
}

TEST_CASE("G71 model: what it does not cover is refused with a reason") {
    Profile p;
    p.plane = ProfilePlane::xz;
    p.start = {0, 10};
    p.segments = {{{-10, 10}, std::nullopt, ArcDirection::ccw}, {{-15, 8}, std::nullopt, ArcDirection::ccw},
                  {{-20, 12}, std::nullopt, ArcDirection::ccw}};
    auto pocket = linuxcnc_g71({2, 14}, p, 1, 0.5);
    REQUIRE(pocket.refusal);
    CHECK(pocket.moves.empty());
    CHECK(pocket.refusal->find("element 1 falls in radius") != std::string::npos);
    p.segments = {{{-10, 12}, std::nullopt, ArcDirection::ccw}};
    CHECK(linuxcnc_g71({2, 9}, p, 1, 0.5).refusal);       // the start below the profile's start
    CHECK(linuxcnc_g71({-1, 14}, p, 1, 0.5).refusal);     // the start beyond the profile's start in Z
    CHECK(linuxcnc_g71({2, 14}, p, 0, 0.5).refusal);      // no depth
    p.segments = {{{-10, 12}, std::nullopt, ArcDirection::ccw}, {{-8, 13}, std::nullopt, ArcDirection::ccw}};
    CHECK(linuxcnc_g71({2, 14}, p, 1, 0.5).refusal);      // back towards +Z
    CHECK_FALSE(linuxcnc_g71({2, 14.5}, Profile{ProfilePlane::xz, {0, 10}, {{{-10, 12}, std::nullopt, ArcDirection::ccw}}}, 1, 0.5).refusal);
    // A level through a corner: rs274 runs this one (a G2 from the profile's start, levels
    // 0.3 apart from r5 meeting its start r2) without end.
    Profile hang{ProfilePlane::xz, {0, 2}, {{{-2, 4}, Vec2{0, 4}, ArcDirection::cw}, {{-2, 5}, std::nullopt, ArcDirection::ccw}}};
    const auto refused = linuxcnc_g71({1, 5}, hang, 0.3, 1.0);
    REQUIRE(refused.refusal);
    CHECK(refused.refusal->find("runs through a corner") != std::string::npos);
    // The start at the profile's start Z (a line down along X): not modelled.
    CHECK(linuxcnc_g71({0, 14.5}, Profile{ProfilePlane::xz, {0, 10}, {{{-10, 12}, std::nullopt, ArcDirection::ccw}}}, 1, 0.5).refusal);
}


TEST_CASE("G72 model: 300 generated profiles along X move as rs274 moves, within 0.001 mm") {
    const std::string rs274 = g71m_rs274();
    std::mt19937 rng(20261204);
    int compared = 0;
    const int stride = oracle::oracle_stride();
    for (int k = 0; k < 300; ++k) {
        const G71mCase c = g72m_of(g71m_generate(rng));
        if (!oracle::oracle_case(k)) continue;
        CAPTURE(k);
        if (linuxcnc_g72(c.start, c.profile, c.depth, c.retract).refusal) continue;
        g71m_compare(c, rs274, LatheCycleAxis::x);
        ++compared;
    }
    CHECK(compared * stride >= 200);
    MESSAGE(compared << " of 300 generated G72 profiles compared (one in " << stride << " checked)");
}

TEST_CASE("linuxcnc-lathe reader: G72 with its profile subroutine is read as the moves rs274 makes") {
    const std::string rs274 = g71m_rs274();
    std::mt19937 rng(72);
    int compared = 0;
    const int stride = oracle::oracle_stride();
    for (int k = 0; k < 60; ++k) {
        const G71mCase c = g72m_of(g71m_generate(rng));
        if (!oracle::oracle_case(k)) continue;
        if (linuxcnc_g72(c.start, c.profile, c.depth, c.retract).refusal) continue;
        const std::string program = g72m_lathe_program(c);
        CAPTURE(k);
        INFO(program);
        const std::vector<G71mMove> want = g71m_from(g71m_canon(oracle::run_rs274_canon(rs274, program)), c.start);
        const std::vector<G71mMove> got = g71m_from(g71m_read(program), c.start);
        REQUIRE(want.size() > 3);
        const std::string diff = g71m_diff(want, got);
        CHECK_MESSAGE(diff.empty(), diff);
        ++compared;
    }
    CHECK(compared * stride >= 40);
}

TEST_CASE("G72 model: what it does not cover is refused in G72's terms") {
    // Along X from the end face's top back to the start: X must not rise, Z must not fall.
    Profile p{ProfilePlane::xz, {-20, 20}, {{{-20, 10}, std::nullopt, ArcDirection::ccw}, {{-10, 10}, std::nullopt, ArcDirection::ccw},
                                            {{-5, 12}, std::nullopt, ArcDirection::ccw}, {{0, 5}, std::nullopt, ArcDirection::ccw}}};
    const auto up = linuxcnc_g72({2, 21}, p, 1, 0.5);
    REQUIRE(up.refusal);
    CHECK(up.refusal->find("element 2 turns back towards +X") != std::string::npos);
    p.segments[2].end = {-12, 8};
    const auto back = linuxcnc_g72({2, 21}, p, 1, 0.5);
    REQUIRE(back.refusal);
    CHECK(back.refusal->find("element 2 falls in Z (a pocket)") != std::string::npos);
    p.segments[2].end = {-5, 8};
    CHECK_FALSE(linuxcnc_g72({2.3, 21}, p, 1, 0.5).refusal);
    CHECK(linuxcnc_g72({2.3, 20}, p, 1, 0.5).refusal->find("not outside the profile's start in X") != std::string::npos);
    CHECK(linuxcnc_g72({-25, 21}, p, 1, 0.5).refusal->find("not beyond the profile's start in Z") != std::string::npos);
    // A profile along X alone: rs274 turns it the other way.
    CHECK(linuxcnc_g72({2.3, 21}, Profile{ProfilePlane::xz, {-20, 20}, {{{-20, 10}, std::nullopt, ArcDirection::ccw}}}, 1, 0.5)
              .refusal->find("ends at the Z it starts at") != std::string::npos);
    // A level on a corner's Z.
    const auto corner = linuxcnc_g72({2, 21}, p, 1, 0.5);
    REQUIRE(corner.refusal);
    CHECK(corner.refusal->find("a level of the cycle (Z 0) runs through a corner") != std::string::npos);
}

}  // namespace test_g71_model_oracle
