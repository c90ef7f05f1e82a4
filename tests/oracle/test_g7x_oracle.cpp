// What LinuxCNC 2.9's G71 and G72 roughing cycles do with their words, as its interpreter runs
// them (issue 30 item 2: canned roughing on linuxcnc-lathe). camgen does not write them yet;
// these are the facts a canned turn-rough and its read-back must follow, held to rs274 here so
// that a change of the interpreter shows:
// - G71 Q<sub> D<d> I<i> R<r>: passes along -Z at radial levels i apart from the start point's
//   X down; D is the finishing allowance as a normal offset of the whole profile (convex corners
//   rounded with radius d), not Fanuc's separate U/W: a pass ends where it meets the offset
//   profile; after each pass the tool retracts r at 45 degrees (+X, +Z); a last pass follows
//   the offset profile. So camgen's allowances (the profile moved by allowanceX and allowanceZ)
//   are what G71 leaves only where both are 0.
// - G72 alike along -X, at Z levels i apart from the start point's Z down.
// (The reference run R_g71_rough_sub, without I, stepped 1 mm.)
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_g7x_oracle {

using namespace camgen;

namespace {

std::string g7x_rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// One move rs274 made in XZ: its end (X as a radius), a rapid or a feed, an arc (centre).
using G7xMove = oracle::XzMove;

std::vector<G7xMove> g7x_moves(const std::string& canon) { return oracle::xz_moves(canon); }

const std::string g7x_head = "G18 G7 G21 G90\nT1 M6\nS1000 M3\nG95\n";

}  // namespace

TEST_CASE("rs274: G71's I is the depth of cut, D a normal offset of the profile with rounded corners, R the 45-degree retract") {
    // D30 to Z-20, a shoulder to D30 (radius 15) to Z-30, a shoulder to D40; start X40 Z2.
    const std::string program = g7x_head + R"(G0 X40 Z2
O100 sub
G1 X20 Z0
G1 Z-20
G1 X30
G1 Z-30
G1 X40
O100 endsub
G71 Q100 D2 I0.4 R1 F0.2
G0 X50 Z5
M2
)";
    const std::vector<G7xMove> moves = g7x_moves(oracle::run_rs274_canon(g7x_rs274(), program));
    // The profile offset by 2, worked out here: r12 to Z-18 (the face at Z-20 moved up 2), the
    // convex corner (Z-20, r15) as a quarter circle of radius 2, r17 to Z-28, then r20.
    auto offset_end = [](double r) {
        if (r <= 15.0) return -18.0;
        if (r < 17.0) return -20.0 + std::sqrt(4.0 - (r - 15.0) * (r - 15.0));
        return -28.0;
    };
    std::vector<double> levels;
    for (std::size_t i = 0; i + 1 < moves.size(); ++i) {
        const G7xMove& m = moves[i];
        if (m.rapid || m.arc || i == 0 || std::abs(moves[i - 1].x - m.x) > 1e-9 || m.z > moves[i - 1].z) continue;
        // A pass along -Z: it ends on the offset profile, then retracts R1 at 45 degrees.
        if (!moves[i + 1].rapid) break;  // the last pass runs on along the offset profile
        levels.push_back(m.x);
        CHECK(m.z == doctest::Approx(offset_end(m.x)).epsilon(1e-4));
        CHECK(moves[i + 1].x == doctest::Approx(m.x + 1.0));
        CHECK(moves[i + 1].z == doctest::Approx(m.z + 1.0));
    }
    REQUIRE(levels.size() == 20);  // from r20 down by 0.4 to r12.4
    for (std::size_t k = 0; k < levels.size(); ++k) CHECK(levels[k] == doctest::Approx(20.0 - 0.4 * k));
    // The last pass: along r12 to Z-18, out to r15, the rounded corner about (Z-20, r15), r17 to
    // Z-28, out to r20.
    const std::size_t n = moves.size();
    REQUIRE(n >= 6);
    CHECK(moves[n - 6].x == doctest::Approx(12.0));
    CHECK(moves[n - 6].z == doctest::Approx(-18.0));
    CHECK(moves[n - 5].x == doctest::Approx(15.0));
    CHECK(moves[n - 4].arc);
    CHECK(moves[n - 4].cx == doctest::Approx(15.0));
    CHECK(moves[n - 4].cz == doctest::Approx(-20.0));
    CHECK(moves[n - 4].x == doctest::Approx(17.0));
    CHECK(moves[n - 3].z == doctest::Approx(-28.0));
    CHECK(moves[n - 2].x == doctest::Approx(20.0));
}

TEST_CASE("rs274: G72 roughs along -X at Z levels I apart, retracting R at 45 degrees") {
    // A facing profile from the outside in: D44 at Z-10 in to D30, up to Z-6, in to D20, up to Z0.
    const std::string program = g7x_head + R"(G0 X46 Z1
O100 sub
G1 X44 Z-10
G1 X30
G1 Z-6
G1 X20
G1 Z0
O100 endsub
G72 Q100 D0 I1 R0.5 F0.2
G0 X50 Z5
M2
)";
    const std::vector<G7xMove> moves = g7x_moves(oracle::run_rs274_canon(g7x_rs274(), program));
    std::vector<double> levels;
    for (std::size_t i = 1; i + 1 < moves.size(); ++i) {
        const G7xMove& m = moves[i];
        if (m.rapid || m.arc || std::abs(moves[i - 1].z - m.z) > 1e-9 || m.x > moves[i - 1].x) continue;
        if (!moves[i + 1].rapid) break;
        levels.push_back(m.z);
        // In to the profile: r10 above Z-6, r15 down to Z-10.
        CHECK(m.x == doctest::Approx(m.z > -6.0 + 1e-9 ? 10.0 : 15.0));
        CHECK(moves[i + 1].x == doctest::Approx(m.x + 0.5));
        CHECK(moves[i + 1].z == doctest::Approx(m.z + 0.5));
    }
    REQUIRE(levels.size() >= 5);
    for (std::size_t k = 0; k < levels.size(); ++k) CHECK(levels[k] == doctest::Approx(1.0 - 1.0 * k));
}

}  // namespace test_g7x_oracle
