// Nose-radius compensation (issue 30 item 3), computer side: turn-profile and turn-rough's last
// pass program the imaginary tip so that the nose circle runs along the profile. Measured here
// independently of camgen's offsets: the tip path is turned back into the nose centre's with
// this file's own table of LinuxCNC's tip codes, sampled finely, and each sample's distance to
// the designed profile's lines and arcs (computed here) must be the nose radius within 0.002 mm;
// each point of the profile must lie within the radius (plus 0.002) of a centre sample, so the
// nose's envelope is the profile. Random profiles with faces, tapers, chamfers, convex and
// concave arcs; all eight orientations on mirrored copies; whole jobs through read_job and
// expand_job; refusals at their JSON paths.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_nose_compensation {

using namespace camgen;

namespace {

constexpr double pi_ = 3.14159265358979323846;

// Where the imaginary tip lies from the nose centre, unit radius, (Z, X): LinuxCNC's lathe
// tool orientation picture (docs "Lathe User Information", tool orientations 1-9).
Vec2 tip_from_centre(int orientation) {
    switch (orientation) {
    case 1: return {1, -1};
    case 2: return {-1, -1};
    case 3: return {-1, 1};
    case 4: return {1, 1};
    case 5: return {1, 0};
    case 6: return {0, -1};
    case 7: return {-1, 0};
    case 8: return {0, 1};
    default: return {0, 0};
    }
}

// One element of a profile for measuring: a line from a to b, or an arc about c from a to b.
struct Piece {
    Vec2 a, b;
    bool arc = false;
    Vec2 c;
    bool ccw = true;
};

std::vector<Piece> pieces_of(const Profile& p) {
    std::vector<Piece> out;
    Vec2 at = p.start;
    for (const ProfileSegment& s : p.segments) {
        Piece k{at, s.end, s.centre.has_value(), s.centre.value_or(Vec2{}), s.direction == ArcDirection::ccw};
        out.push_back(k);
        at = s.end;
    }
    return out;
}

double len(Vec2 v) { return std::hypot(v.x, v.y); }

// The ccw sweep (radians, in (0, 2pi]) of an arc piece.
double sweep_of(const Piece& k) {
    const double a0 = std::atan2(k.a.y - k.c.y, k.a.x - k.c.x), a1 = std::atan2(k.b.y - k.c.y, k.b.x - k.c.x);
    double s = k.ccw ? a1 - a0 : a0 - a1;
    while (s <= 1e-12) s += 2 * pi_;
    return s;
}

// The distance from q to a piece.
double distance_to(const Piece& k, Vec2 q) {
    if (!k.arc) {
        const Vec2 d{k.b.x - k.a.x, k.b.y - k.a.y};
        const double l2 = d.x * d.x + d.y * d.y;
        double t = l2 > 0 ? ((q.x - k.a.x) * d.x + (q.y - k.a.y) * d.y) / l2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        return len({q.x - k.a.x - t * d.x, q.y - k.a.y - t * d.y});
    }
    const double r = len({k.a.x - k.c.x, k.a.y - k.c.y});
    const double a0 = std::atan2(k.a.y - k.c.y, k.a.x - k.c.x), aq = std::atan2(q.y - k.c.y, q.x - k.c.x);
    double d = k.ccw ? aq - a0 : a0 - aq;
    while (d < 0) d += 2 * pi_;
    while (d >= 2 * pi_) d -= 2 * pi_;
    if (d <= sweep_of(k)) return std::abs(len({q.x - k.c.x, q.y - k.c.y}) - r);
    return std::min(len({q.x - k.a.x, q.y - k.a.y}), len({q.x - k.b.x, q.y - k.b.y}));
}

double distance_to(const std::vector<Piece>& ps, Vec2 q) {
    double best = 1e300;
    for (const Piece& k : ps) best = std::min(best, distance_to(k, q));
    return best;
}

// Points every `step` mm along the pieces.
std::vector<Vec2> samples(const std::vector<Piece>& ps, double step) {
    std::vector<Vec2> out;
    for (const Piece& k : ps) {
        if (!k.arc) {
            const int n = std::max(1, static_cast<int>(len({k.b.x - k.a.x, k.b.y - k.a.y}) / step));
            for (int i = 0; i <= n; ++i) out.push_back({k.a.x + (k.b.x - k.a.x) * i / n, k.a.y + (k.b.y - k.a.y) * i / n});
            continue;
        }
        const double r = len({k.a.x - k.c.x, k.a.y - k.c.y}), sw = sweep_of(k);
        const double a0 = std::atan2(k.a.y - k.c.y, k.a.x - k.c.x);
        const int n = std::max(1, static_cast<int>(r * sw / step));
        for (int i = 0; i <= n; ++i) {
            const double ang = a0 + (k.ccw ? 1 : -1) * sw * i / n;
            out.push_back({k.c.x + r * std::cos(ang), k.c.y + r * std::sin(ang)});
        }
    }
    return out;
}

// The nose's envelope against the profile: every centre sample at `r` from the profile, every
// profile sample within `r` of the centre path. Returns the worst deviation, mm.
// With `short_end`, the profile's points within the radius of its end are not asked for: a
// turn-profile's nose stops with its leading point at the end.
// `concave`: sharp concave corners, where the nose leaves its radius: the profile's points
// within twice the radius of one are not asked for either.
double envelope_error(const Profile& profile, const std::vector<Piece>& centre, double r, bool short_end = false,
                      const std::vector<Vec2>& concave = {}) {
    const std::vector<Piece> designed = pieces_of(profile);
    const Vec2 end = profile.segments.back().end;
    double worst = 0.0;
    for (const Vec2& q : samples(centre, 0.01)) worst = std::max(worst, std::abs(distance_to(designed, q) - r));
    for (const Vec2& q : samples(designed, 0.01)) {
        if (short_end && len(q - end) <= r + 0.011) continue;
        if (std::any_of(concave.begin(), concave.end(), [&](Vec2 c) { return len(q - c) <= 2 * r; })) continue;
        worst = std::max(worst, distance_to(centre, q) - r);
    }
    return worst;
}

// The tip path turned back into the nose centre's, by this file's table.
std::vector<Piece> centre_of(const std::vector<Piece>& tip, int orientation, double r) {
    const Vec2 t = tip_from_centre(orientation) * r;
    std::vector<Piece> out = tip;
    for (Piece& k : out) {
        k.a = k.a - t, k.b = k.b - t;
        if (k.arc) k.c = k.c - t;
    }
    return out;
}

// A random outside profile from Z0 towards -Z, (Z, radius): a face from the start up, then
// cylinders, rising tapers and chamfers, each joined to the next by a sharp convex corner or,
// where the next rises less, a concave fillet of radius above `nose`; a convex arc now and then.
// Its material directions lie between -Z and -X (what orientations 2, 6 and 7 reach).
Profile random_profile(std::mt19937& rng, double nose) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Profile p;
    p.plane = ProfilePlane::xz;
    p.start = {0.0, 3.0 + 3.0 * u(rng)};
    // Directions of travel (radians from +Z towards +X): +X (pi/2) first, then in [pi/2, pi].
    std::vector<double> dirs{pi_ / 2};
    const int n = 3 + static_cast<int>(u(rng) * 5);
    for (int i = 0; i < n; ++i) dirs.push_back(u(rng) < 0.35 ? pi_ : pi_ / 2 + 0.05 + (pi_ / 2 - 0.05) * u(rng));
    dirs.push_back(pi_);
    Vec2 at = p.start;
    for (std::size_t i = 0; i < dirs.size(); ++i) {
        const double l = 1.0 + 4.0 * u(rng);
        const Vec2 d{std::cos(dirs[i]), std::sin(dirs[i])};
        const Vec2 end = at + d * l;
        p.segments.push_back({end, std::nullopt, ArcDirection::ccw});
        at = end;
        if (i + 1 == dirs.size()) break;
        const double next = dirs[i + 1];
        if (next > dirs[i] + 1e-3 && u(rng) < 0.5) {
            // A convex arc (ccw: the centre on the material side) turning to the next direction,
            // tangent to both.
            const double rad = 0.3 + 2.0 * u(rng);
            const Vec2 c = at + Vec2{-d.y, d.x} * rad;  // left of travel
            const Vec2 e = c + Vec2{std::sin(next), -std::cos(next)} * rad;
            p.segments.push_back({e, c, ArcDirection::ccw});
            at = e;
        } else if (next < dirs[i] - 1e-3) {
            // A concave turn: a cw fillet of radius above the nose's.
            const double rad = nose * (1.2 + 3.0 * u(rng));
            const Vec2 c = at + Vec2{d.y, -d.x} * rad;  // right of travel
            const Vec2 e = c + Vec2{-std::sin(next), std::cos(next)} * rad;
            p.segments.push_back({e, c, ArcDirection::cw});
            at = e;
        }
    }
    return p;
}

// The profile mirrored in Z and/or X (walked backwards where one mirror turns the material to
// the right), so that its material still lies to the left of travel.
Profile mirrored(const Profile& p, bool z, bool x) {
    Profile out = p;
    auto m = [&](Vec2 v) { return Vec2{z ? -v.x : v.x, x ? -v.y : v.y}; };
    out.start = m(p.start);
    for (ProfileSegment& s : out.segments) {
        s.end = m(s.end);
        if (s.centre) s.centre = m(*s.centre);
        if (z != x) s.direction = s.direction == ArcDirection::ccw ? ArcDirection::cw : ArcDirection::ccw;
    }
    return z != x ? reversed(out) : out;
}

std::string refusal(const std::string& text) {
    try {
        (void)read_job(text, "nose.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A profile as a turn-profile's "start" and "path" (X as radii).
std::string json_of(const Profile& p) {
    std::string path;
    for (std::size_t i = 0; i < p.segments.size(); ++i) {
        const ProfileSegment& s = p.segments[i];
        if (i) path += ", ";
        if (s.centre)
            path += fmt::format(R"({{"arc": {{"end": [{:.12f}, {:.12f}], "centre": [{:.12f}, {:.12f}], "direction": "{}"}}}})", s.end.y,
                                s.end.x, s.centre->y, s.centre->x, s.direction == ArcDirection::ccw ? "ccw" : "cw");
        else
            path += fmt::format(R"({{"line": [{:.12f}, {:.12f}]}})", s.end.y, s.end.x);
    }
    return fmt::format(R"("start": [{:.12f}, {:.12f}], "path": [{}])", p.start.y, p.start.x, path);
}

// The tip path of a job's finishing moves (turn-profile) or of the cutting moves from the last
// pass's lead-in on (turn-rough), (Z, radius).
std::vector<Piece> tip_path_of(const Job& job, Movement kind) {
    std::vector<Piece> out;
    Vec2 at{0, 0};
    bool on = false;
    for (const Event& e : expand_job(job)) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            at = {r->to.z, r->to.x};
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            const Vec2 to{l->to.z, l->to.x};
            if (l->movement == Movement::lead_in) on = true, out.clear();
            else if (l->movement == Movement::lead_out) on = false;
            else if (on && l->movement == kind) out.push_back({at, to});
            at = to;
        } else if (const auto* a = std::get_if<Arc>(&e)) {
            const Vec2 to{a->to.z, a->to.x};
            if (on && a->movement == kind) out.push_back({at, to, true, {a->centre.z, a->centre.x}, a->direction == ArcDirection::ccw});
            at = to;
        }
    }
    return out;
}

}  // namespace

TEST_CASE("nose compensation: the nose circle's envelope is the profile, random profiles, all eight orientations") {
    std::mt19937 rng(30301);
    int checked[10] = {};
    for (int round = 0; round < 60; ++round) {
        const double r = 0.2 + 0.6 * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const Profile base = random_profile(rng, r);
        for (int variant = 0; variant < 4; ++variant) {
            const Profile p = mirrored(base, variant & 1, (variant & 2) != 0);
            for (int o = 1; o <= 9; ++o) {
                if (first_unreachable(p, o, 1)) continue;
                const NosePath nose = nose_path(p, r, o);
                INFO("round " << round << " variant " << variant << " orientation " << o << " r " << r);
                REQUIRE(!nose.refusal);
                CHECK(nose.concave_corners.empty());
                const double e = envelope_error(p, centre_of(pieces_of(nose.tip), o, r), r);
                CHECK(e <= 0.002);
                ++checked[o];
            }
        }
    }
    // Every orientation met profiles it can cut (the mirrors give each its own).
    for (int o = 1; o <= 9; ++o) CHECK(checked[o] >= 60);
}

TEST_CASE("nose compensation: which orientations reach an outside profile") {
    Profile p;
    p.plane = ProfilePlane::xz;
    p.start = {0, 5};
    p.segments = {{{0, 8}, std::nullopt, ArcDirection::ccw}, {{-10, 8}, std::nullopt, ArcDirection::ccw}};
    // The face (material towards -Z) and the cylinder (towards -X): 2, 6 and 7 reach both.
    for (int o : {2, 6, 7, 9}) CHECK(!first_unreachable(p, o, 1));
    for (int o : {1, 3, 4, 5, 8}) CHECK(first_unreachable(p, o, 1));
    const auto bad = first_unreachable(p, 3, 4);
    REQUIRE(bad);
    CHECK(bad->index == 1);
    CHECK(bad->why.find("tool 4 of orientation 3") != std::string::npos);
}

TEST_CASE("turn-profile: computer compensation by default with a nose radius, random jobs, orientations 2, 6, 7 and 9") {
    std::mt19937 rng(30302);
    for (int round = 0; round < 40; ++round) {
        const Profile p = random_profile(rng, 0.8);
        for (int o : {2, 6, 7, 9}) {
            const double r = 0.4;
            const std::string text = fmt::format(
                R"({{"clearance": 20, "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": {}, "orientation": {}, "rpm": 1000}}],
  "operations": [{{"type": "turn-profile", "tool": 1, "feed": 100, "xValues": "radius", "retractX": 200, {}}}]}})",
                r, o, json_of(p));
            INFO(text);
            const Job job = read_job(text, "nose.json");
            const std::vector<Piece> tip = tip_path_of(job, Movement::finishing);
            REQUIRE(!tip.empty());
            CHECK(envelope_error(p, centre_of(tip, o, r), r, true) <= 0.002);
            // The nose stops with its leading point at the end: its centre a radius short of it
            // along the last element (a cylinder along -Z).
            const Vec2 last = centre_of(tip, o, r).back().b, end = p.segments.back().end;
            CHECK(last.x == doctest::Approx(end.x + r));
            CHECK(last.y == doctest::Approx(end.y + r));
            // "none": the profile itself is the tip's path.
            std::string none = text;
            none.insert(none.find("\"retractX\""), R"("compensation": "none", )");
            const std::vector<Piece> plain = tip_path_of(read_job(none, "nose.json"), Movement::finishing);
            REQUIRE(plain.size() == p.segments.size());
            CHECK(std::abs(plain.back().b.x - p.segments.back().end.x) < 1e-9);
            CHECK(std::abs(plain.back().b.y - p.segments.back().end.y) < 1e-9);
        }
    }
}

TEST_CASE("turn-profile: the shaft's finishing pass with a 0.4 mm nose, words by hand") {
    // The sample's profile (diameters): a face at Z0 from D24 to D28, a 1 mm chamfer to D30,
    // D30 to Z-20, an R5 fillet up to D40 at Z-25, D40 to Z-40; orientation 2, r 0.4.
    const Job job = read_job(R"({"clearance": 20, "tools": [{"number": 3, "type": "turning-tool", "diameter": 0.8, "rpm": 1200}],
  "operations": [{"type": "turn-profile", "tool": 3, "feed": 120, "start": [24, 0], "retractX": 44,
     "path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]},
              {"arc": {"end": [40, -25], "centre": [40, -20], "direction": "cw"}}, {"line": [40, -40]}]}]})",
                             "shaft.json");
    const std::vector<Piece> tip = tip_path_of(job, Movement::finishing);
    // Face: the nose centre 0.4 beyond Z0, from radius 12 to 14 less the corner's own
    // (the chamfer's normal is (1, 1)/sqrt 2: the centre ends at 14 - 0.4 tan 22.5 degrees).
    const double r = 0.4, t = r * std::tan(pi_ / 8);
    REQUIRE(tip.size() >= 6);
    // The face, with the tip 0.4 below the centre in X and Z: Z 0, X from 12 - 0.4.
    CHECK(tip[0].a.x == doctest::Approx(0.0));
    CHECK(tip[0].a.y == doctest::Approx(12 - r));
    CHECK(tip[0].b.x == doctest::Approx(0.0));
    CHECK(tip[0].b.y == doctest::Approx(14 - r).epsilon(1e-12));
    // An arc about the corner (14, 0) of radius 0.4 (moved by the tip offset), then the chamfer
    // 0.4 out along its normal.
    CHECK(tip[1].arc);
    CHECK(tip[1].c.x == doctest::Approx(0.0 - r));
    CHECK(tip[1].c.y == doctest::Approx(14.0 - r));
    CHECK(!tip[2].arc);
    CHECK(tip[2].a.x == doctest::Approx(0 + r / std::sqrt(2.0) - r));
    CHECK(tip[2].a.y == doctest::Approx(14 + r / std::sqrt(2.0) - r));
    // The D30 cylinder: the tip at radius 15, the nose centre at 15.4; it ends where the
    // fillet's offset (radius 5 - 0.4) begins, at Z -20.
    const Piece& cyl = tip[4];
    CHECK(cyl.a.y == doctest::Approx(15.0));
    CHECK(cyl.b.y == doctest::Approx(15.0));
    CHECK(cyl.b.x == doctest::Approx(-20 - r));
    // The fillet: about (Z-20, 20) less the tip offset, radius 4.6.
    const Piece& fillet = tip[5];
    CHECK(fillet.arc);
    CHECK(!fillet.ccw);
    CHECK(fillet.c.x == doctest::Approx(-20 - r));
    CHECK(fillet.c.y == doctest::Approx(20 - r));
    CHECK(len(fillet.a - fillet.c) == doctest::Approx(5 - r));
    (void)t;
}

TEST_CASE("turn-rough: with a nose radius the last pass runs the nose along the boundary and no pass gouges it") {
    std::mt19937 rng(30303);
    for (int round = 0; round < 25; ++round) {
        const double r = 0.8, ax = 0.2, az = 0.1;
        const Profile p = random_profile(rng, r);
        double top = 0;
        for (const Vec2& q : samples(pieces_of(p), 0.05)) top = std::max(top, q.y);
        const double bar = top + ax + 2.0;
        const std::string text = fmt::format(
            R"({{"clearance": 20, "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": {}, "rpm": 1000}}],
  "operations": [{{"type": "turn-rough", "output": "longhand", "tool": 1, "feed": 200, "xValues": "radius", "startX": {}, "allowanceX": {},
                  "allowanceZ": {}, "depthOfCut": 1.5, {}}}]}})",
            r, bar, ax, az, json_of(p));
        INFO(text);
        const Job job = read_job(text, "rough.json");
        // The boundary, worked out here: the profile moved by the allowances, closed by the face
        // at its end up to the bar.
        Profile boundary = p;
        const Vec2 shift{az, ax};
        boundary.start = boundary.start + shift;
        for (ProfileSegment& s : boundary.segments) {
            s.end = s.end + shift;
            if (s.centre) s.centre = *s.centre + shift;
        }
        boundary.segments.push_back({Vec2{boundary.segments.back().end.x, bar}, std::nullopt, ArcDirection::ccw});
        const std::vector<Piece> closed = pieces_of(boundary);
        // Every feed of the nose stays a nose radius off the boundary.
        Vec2 at{0, 0};
        bool started = false;  // the first move starts from nowhere known
        double worst = 0.0;
        for (const Event& e : expand_job(job)) {
            std::vector<Piece> moved;
            if (const auto* q = std::get_if<Rapid>(&e)) moved.push_back({at, {q->to.z, q->to.x}});
            else if (const auto* l = std::get_if<Linear>(&e)) moved.push_back({at, {l->to.z, l->to.x}});
            else if (const auto* a = std::get_if<Arc>(&e))
                moved.push_back({at, {a->to.z, a->to.x}, true, {a->centre.z, a->centre.x}, a->direction == ArcDirection::ccw});
            else continue;
            at = moved[0].b;
            if (!std::exchange(started, true)) continue;
            for (const Vec2& c : samples(centre_of(moved, 2, r), 0.02)) worst = std::max(worst, r - distance_to(closed, c));
        }
        CHECK(worst <= 0.002);
        // The last pass: from its lead-in to the face's top (the tip at the bar less the nose,
        // before the move up out of the bar), the nose's envelope is the boundary.
        std::vector<Piece> last = tip_path_of(job, Movement::cutting);
        REQUIRE(!last.empty());
        if (std::abs(last.back().b.y - bar) < 1e-9) last.pop_back();
        CHECK(std::abs(last.back().b.y - (bar - r)) < 1e-9);
        // The corner where the boundary meets the end face is concave: the nose leaves its radius.
        CHECK(envelope_error(boundary, centre_of(last, 2, r), r, false, {segment_start(boundary, boundary.segments.size() - 1)}) <=
              0.002);
    }
}

TEST_CASE("turn-rough along X: with a nose radius no feed's nose enters the boundary and the last pass's nose envelopes it") {
    // Random profiles (a face up from Z0 then cylinders, tapers, chamfers, convex arcs and
    // concave fillets), half of them without the face (the boundary starts at a corner, round
    // which the nose rolls), noses 0.4, 0.8 and 1.2, roughed in passes along -X.
    std::mt19937 rng(30307);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int jobs = 0, feeds = 0;
    double worst_gouge = 0.0, worst_envelope = 0.0;
    for (int round = 0; round < 60; ++round) {
        const double r = std::array<double, 3>{0.4, 0.8, 1.2}[round % 3];
        const double ax = 0.3 * u(rng), az = 0.3 * u(rng);
        Profile p = random_profile(rng, r);
        if (round % 2) {
            p.start = p.segments.front().end;
            p.segments.erase(p.segments.begin());
        }
        double top = 0;
        for (const Vec2& q : samples(pieces_of(p), 0.05)) top = std::max(top, q.y);
        const double bar = top + ax + 2.0 + u(rng);
        const double doc = 0.6 + 1.5 * u(rng);
        const std::string text = fmt::format(
            R"({{"clearance": 20, "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": {}, "rpm": 1000}}],
  "operations": [{{"type": "turn-rough", "direction": "x", "tool": 1, "feed": 200, "xValues": "radius", "startX": {}, "allowanceX": {},
                  "allowanceZ": {}, "depthOfCut": {}, {}}}]}})",
            r, bar, ax, az, doc, json_of(p));
        INFO(text);
        // camgen's passes, and the cycle's moves (G72: "auto" without a machine gives the cycle).
        for (const char* output : {"longhand", "auto"}) {
        CAPTURE(output);
        const Job job = read_job(text.substr(0, text.size() - 3) + R"(, "output": ")" + output + R"("}]})", "roughx.json");
        // The boundary, worked out here: the profile moved by the allowances, closed by the face
        // at its end up to the bar.
        Profile boundary = p;
        const Vec2 shift{az, ax};
        boundary.start = boundary.start + shift;
        for (ProfileSegment& s : boundary.segments) {
            s.end = s.end + shift;
            if (s.centre) s.centre = *s.centre + shift;
        }
        boundary.segments.push_back({Vec2{boundary.segments.back().end.x, bar}, std::nullopt, ArcDirection::ccw});
        const std::vector<Piece> closed = pieces_of(boundary);
        // Every feed's nose stays outside the boundary; the last pass is the cutting feeds after
        // the last rapid before the final lift off.
        Vec2 at{0, 0};
        bool started = false;
        std::vector<Piece> pass, last;
        std::vector<Event> events;
        for (const Event& e : expand_job(job)) {
            if (const auto* c = std::get_if<TurnCycle>(&e)) {
                for (const Event& m : turn_cycle_moves(*c)) events.push_back(m);
            } else {
                events.push_back(e);
            }
        }
        for (const Event& e : events) {
            Piece moved;
            Movement kind = Movement::cutting;
            bool feed = true;
            if (const auto* q = std::get_if<Rapid>(&e)) moved = {at, {q->to.z, q->to.x}}, feed = false;
            else if (const auto* l = std::get_if<Linear>(&e)) moved = {at, {l->to.z, l->to.x}}, kind = l->movement;
            else if (const auto* a = std::get_if<Arc>(&e))
                moved = {at, {a->to.z, a->to.x}, true, {a->centre.z, a->centre.x}, a->direction == ArcDirection::ccw},
                kind = a->movement;
            else continue;
            at = moved.b;
            if (!std::exchange(started, true)) continue;
            if (!feed) {
                pass.clear();
                continue;
            }
            ++feeds;
            for (const Vec2& c : samples(centre_of({moved}, 2, r), 0.02))
                worst_gouge = std::max(worst_gouge, r - distance_to(closed, c));
            if (kind == Movement::cutting) pass.push_back(moved);
            else if (kind == Movement::lead_out && !pass.empty()) last = pass;
        }
        // The last pass: its first feed comes down the end face's line from outside the bar; from
        // where the nose touches the bar's corner (the tip a nose radius below the bar) the nose
        // runs down the face and along the boundary to its start.
        REQUIRE(last.size() >= 2);
        CHECK(!last.front().arc);
        CHECK(std::abs(last.front().a.x - last.front().b.x) < 1e-9);
        CHECK(last.front().a.y >= bar - r - 1e-9);
        last.front().a.y = bar - r;
        const double e = envelope_error(boundary, centre_of(last, 2, r), r, false,
                                        {segment_start(boundary, boundary.segments.size() - 1)});
        worst_envelope = std::max(worst_envelope, e);
        CHECK(e <= 0.002);
        ++jobs;
        }
    }
    CHECK(worst_gouge <= 0.002);
    MESSAGE("turn-rough along X with a nose: " << jobs << " random jobs, " << feeds << " feeds; the nose enters the boundary by at most "
                                               << worst_gouge << " mm, the last pass's envelope is off it by at most " << worst_envelope
                                               << " mm");
}

TEST_CASE("nose compensation: refusals and notes at their JSON paths") {
    auto job = [](const std::string& tool, const std::string& path, const std::string& extra = "") {
        return R"({"clearance": 20, "tools": [)" + tool + R"(], "operations": [{"type": "turn-profile", "tool": 1, "feed": 100, )" +
               extra + R"("xValues": "radius", "retractX": 30, "start": [5, 0], "path": [)" + path + "]}]}";
    };
    const std::string nose = R"({"number": 1, "type": "turning-tool", "noseRadius": 0.8, "rpm": 1000})";
    // A concave fillet of 0.5 under a 0.8 nose.
    const std::string tight = R"({"line": [10, 0]}, {"line": [10, -5]}, {"arc": {"end": [10.5, -5.5], "centre": [10.5, -5], "direction": "cw"}}, {"line": [10.5, -9]}, {"line": [12, -9]})";
    CHECK(refusal(job(nose, tight)).find("/operations/0/path/2: a concave arc tighter than the nose radius 0.800 mm") != std::string::npos);
    // Without compensation the same is the tip's path.
    CHECK(refusal(job(nose, tight, R"("compensation": "none", )")) == "");
    // A groove narrower than the nose: its bottom is out of reach.
    const std::string groove = R"({"line": [10, 0]}, {"line": [10, -5]}, {"line": [8, -5]}, {"line": [8, -6]}, {"line": [10, -6]}, {"line": [10, -9]})";
    const std::string g = refusal(job(nose, groove));
    CHECK(g.find("/operations/0/path/") != std::string::npos);
    CHECK(g.find("nose") != std::string::npos);
    // An outside profile with a tool of orientation 3 (the tip towards +X: a boring tool).
    const std::string cyl = R"({"line": [10, 0]}, {"line": [10, -9]})";
    CHECK(refusal(job(R"({"number": 1, "type": "turning-tool", "noseRadius": 0.4, "orientation": 3, "rpm": 1000})", cyl))
              .find("/operations/0/path/1: the nose touches this element's surface from") != std::string::npos);
    CHECK(refusal(job(R"({"number": 1, "type": "turning-tool", "noseRadius": 0.4, "orientation": 3, "rpm": 1000})", cyl))
              .find("tool 1 of orientation 3 (its tip towards -Z and +X) cuts only between 45 and 225 degrees") != std::string::npos);
    // Without compensation the tip follows the profile, but the boring tool's lift (towards +Z
    // and -X) would dive into the diameter it has just cut: refused at lift.
    CHECK(refusal(job(R"({"number": 1, "type": "turning-tool", "noseRadius": 0.4, "orientation": 3, "rpm": 1000})", cyl,
                      R"("compensation": "none", )"))
              .find("/operations/0/lift: the lift off the profile's end (0.500 mm towards +Z and -X") != std::string::npos);
    CHECK(refusal(job(nose, cyl, R"("compensation": "left", )")).find("/operations/0/compensation") != std::string::npos);
    // A sharp concave corner is cut with the nose's radius left in it, and says so.
    const Job shoulder = read_job(job(nose, R"({"line": [10, 0]}, {"line": [10, -5]}, {"line": [12, -5]}, {"line": [12, -9]})"), "n.json");
    const auto& op = std::get<TurnProfileOp>(shoulder.operations[0]);
    REQUIRE(op.notes.size() >= 1);
    CHECK(op.notes[0].find("/operations/0/path/2: the sharp concave corner before this element keeps the nose's radius") !=
          std::string::npos);
}

}  // namespace test_nose_compensation
