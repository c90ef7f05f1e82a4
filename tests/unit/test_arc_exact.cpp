// An arc whose end lies off its circle by less than the 0.001 mm a job allows is made exact
// where the job is read (make_arcs_exact, geometry/profile.hpp: its centre moved along the
// bisector of its ends), so that the offsets, the part guard, the posts, verify and simulate's
// design all take one arc. Found by an exploratory tester: at a sharp corner such an arc was
// offset as the arc to its circle and a radial line on, which turned against the corner, and
// the offset loop came out open, its corner arc missing; as a pocket's island, the island was
// lost from simulate's design.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/contour/contour.hpp"
#include "camgen/operations/pocket/pocket.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"
#include "support.hpp"

namespace test_arc_exact {

using namespace camgen;
using nlohmann::json;
namespace fs = std::filesystem;

// A deterministic sequence of numbers (the same on every standard library).
struct Numbers {
    std::uint64_t state;
    double next() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 11) / 9007199254740992.0;
    }
    double in(double a, double b) { return a + (b - a) * next(); }
};

// The distance from p to segment i of a profile, the arc taken with the radius of its start
// and its given end's angle (exact for an exact arc), computed here from first principles.
double to_segment(const Profile& p, std::size_t i, Vec2 q) {
    const Vec2 a = segment_start(p, i), b = p.segments[i].end;
    if (!p.segments[i].centre) {
        const Vec2 d = b - a;
        const double l2 = dot(d, d);
        const double t = l2 > 0 ? std::clamp(dot(q - a, d) / l2, 0.0, 1.0) : 0.0;
        return distance(q, a + d * t);
    }
    const Vec2 c = *p.segments[i].centre;
    const double r = distance(a, c), sign = p.segments[i].direction == ArcDirection::ccw ? 1.0 : -1.0;
    double sweep = sign * (std::atan2(b.y - c.y, b.x - c.x) - std::atan2(a.y - c.y, a.x - c.x));
    sweep = std::fmod(sweep + 4 * pi, two_pi);
    if (sweep <= 1e-12) sweep = two_pi;
    double at = sign * (std::atan2(q.y - c.y, q.x - c.x) - std::atan2(a.y - c.y, a.x - c.x));
    at = std::fmod(at + 4 * pi, two_pi);
    const Vec2 end_on_circle = c + unit_at(std::atan2(a.y - c.y, a.x - c.x) + sign * sweep) * r;
    if (at <= sweep) return std::abs(distance(q, c) - r);
    return std::min(distance(q, a), distance(q, end_on_circle));
}
double to_profile(const Profile& p, Vec2 q) {
    double best = 1e9;
    for (std::size_t i = 0; i < p.segments.size(); ++i) best = std::min(best, to_segment(p, i, q));
    return best;
}

// Points along a profile every `step` mm or closer (each segment's ends and between).
std::vector<Vec2> samples_of(const Profile& p, double step) {
    std::vector<Vec2> out{p.start};
    for (std::size_t i = 0; i < p.segments.size(); ++i) {
        const Vec2 a = segment_start(p, i), b = p.segments[i].end;
        if (!p.segments[i].centre) {
            const int k = std::max(1, static_cast<int>(distance(a, b) / step));
            for (int j = 1; j <= k; ++j) out.push_back(a + (b - a) * (static_cast<double>(j) / k));
            continue;
        }
        const double sweep = segment_sweep(p, i);
        const Vec2 c = *p.segments[i].centre;
        const double r = distance(a, c), a0 = std::atan2(a.y - c.y, a.x - c.x);
        const double sign = p.segments[i].direction == ArcDirection::ccw ? 1.0 : -1.0;
        const int k = std::max(1, static_cast<int>(r * sweep / step));
        for (int j = 1; j < k; ++j) out.push_back(c + unit_at(a0 + sign * sweep * j / k) * r);
        out.push_back(b);
    }
    return out;
}

// How far an arc's end is off the circle through its start, mm (0 for a line).
double off_of(const Profile& p, std::size_t i) {
    if (!p.segments[i].centre) return 0.0;
    const Vec2 c = *p.segments[i].centre;
    return std::abs(distance(segment_start(p, i), c) - distance(p.segments[i].end, c));
}

// The tester's profile: a line up to (77.39, 72.46), a concave arc on to (59.51, 85.73), where
// the line down to (11.41, 55.01) turns 123 degrees (a sharp convex corner), and two lines back
// to the start; the arc's centre on the bisector of its ends (exact), its end moved by `move`.
// (As the tester gave it, the centre (73.286, 85.611) left the end 2.6e-5 mm inside its circle.)
const Vec2 tester_start{73.9, 52.32}, arc_from{77.39, 72.46}, arc_to{59.51, 85.73}, given_centre{73.286, 85.611};
Vec2 exact_centre() {
    const Vec2 u = (arc_to - arc_from) * (1 / distance(arc_from, arc_to));
    return given_centre - u * dot(given_centre - (arc_from + arc_to) * 0.5, u);
}
json tester_path(Vec2 move, Vec2 centre = exact_centre()) {
    const Vec2 end = arc_to + move;
    return json::array({{{"line", {arc_from.x, arc_from.y}}},
                        {{"arc", {{"end", {end.x, end.y}}, {"centre", {centre.x, centre.y}}, {"direction", "cw"}}}},
                        {{"line", {11.41, 55.01}}},
                        {{"line", {57.89, 15.2}}},
                        {{"line", {tester_start.x, tester_start.y}}}});
}
std::string contour_job(const json& path, const char* side, double diameter, Vec2 start = tester_start) {
    const json job = {{"clearance", 10},
                      {"stock", {{"box", {{"min", {0, 5, -3}}, {"max", {90, 97, 0}}}}}},
                      {"tools", json::array({{{"number", 1}, {"type", "end-mill"}, {"diameter", diameter}, {"rpm", 8000}}})},
                      {"operations", json::array({{{"type", "contour"}, {"tool", 1}, {"endDepth", 1}, {"feed", 500}, {"side", side},
                                                   {"compensation", "computer"}, {"leadIn", {{"type", "none"}}}, {"leadOut", {{"type", "none"}}},
                                                   {"start", {start.x, start.y}}, {"path", path}}})}};
    return job.dump();
}
Profile contour_profile(const std::string& job_text) { return std::get<ContourOp>(read_job(job_text, "test.json").operations.at(0)).profile; }

// An offset loop's checks: one closed loop, every point at `distance` from `from` (within
// 1e-6) and from `near` within `slack`, and a convex corner arc of radius `distance` about
// `corner`.
struct LoopCheck {
    bool closed = false;
    bool one = false;
    double worst_exact = 0.0;  // the largest | distance to `from` - d |
    double worst_near = 0.0;   // the largest | distance to `near` - d |
    bool corner_arc = false;
};
LoopCheck check_loop(const OffsetResult& o, const Profile& from, const Profile& near, double d, Vec2 corner) {
    LoopCheck c;
    c.one = !o.empty() && o.others.empty();
    if (o.empty()) return c;
    c.closed = is_closed(o.profile);
    for (Vec2 q : samples_of(o.profile, 0.05)) {
        c.worst_exact = std::max(c.worst_exact, std::abs(to_profile(from, q) - d));
        c.worst_near = std::max(c.worst_near, std::abs(to_profile(near, q) - d));
    }
    for (std::size_t i = 0; i < o.profile.segments.size(); ++i) {
        const ProfileSegment& s = o.profile.segments[i];
        if (s.centre && distance(*s.centre, corner) < 1e-3 && std::abs(distance(segment_start(o.profile, i), *s.centre) - d) < 1e-6 &&
            segment_sweep(o.profile, i) > 60 * rad_per_deg)
            c.corner_arc = true;
    }
    return c;
}

TEST_CASE("make_arcs_exact: an arc's end a little off its circle moves its centre onto the bisector of its ends, once") {
    using namespace test_arc_exact;
    for (double angle = 0; angle < 360; angle += 45) {
        CAPTURE(angle);
        const Vec2 move = unit_at(angle * rad_per_deg) * 5e-5;
        Profile p = contour_profile(contour_job(tester_path({0, 0}), "outside", 6));
        p.segments[1].end = p.segments[1].end + move;
        p.segments[1].centre = given_centre;
        const double off = off_of(p, 1);
        Profile q = p;
        CHECK(make_arcs_exact(q, arc_radius_tolerance) == (off > 1e-9 ? 1u : 0u));
        // The ends stay; the centre is on the bisector, as near the given one as that allows.
        CHECK(q.start == p.start);
        for (std::size_t i = 0; i < p.segments.size(); ++i) CHECK(q.segments[i].end == p.segments[i].end);
        CHECK(off_of(q, 1) < 1e-12);
        const Vec2 a = segment_start(q, 1), b = q.segments[1].end, chord = (b - a) * (1 / distance(a, b));
        CHECK(std::abs(dot(*q.segments[1].centre - given_centre, left_of(chord))) < 1e-12);
        // (the shortest move onto the bisector: (r1^2 - r0^2) / (2 chord), about off x radius / chord)
        const double r = distance(a, given_centre);
        CHECK(distance(*q.segments[1].centre, given_centre) <= off * r / distance(a, b) * 1.01 + 1e-12);
        // A second call moves nothing.
        Profile again = q;
        CHECK(make_arcs_exact(again, arc_radius_tolerance) == 0);
        CHECK(*again.segments[1].centre == *q.segments[1].centre);
    }
    // An arc off by more than `within` stays as given (a drawing's wider joints), and so does
    // one nearly a full circle whose exact twin would lie further than that from it.
    Profile wide = contour_profile(contour_job(tester_path({0, 0}), "outside", 6));
    wide.segments[1].end = wide.segments[1].end + (wide.segments[1].end - *wide.segments[1].centre) * (0.002 / distance(wide.segments[1].end, *wide.segments[1].centre));
    CHECK(make_arcs_exact(wide, arc_radius_tolerance) == 0);
    Profile round;
    round.start = {10, 0};
    round.segments = {{{unit_at(350 * rad_per_deg) * 10.0009}, Vec2{0, 0}, ArcDirection::ccw}};
    CHECK(make_arcs_exact(round, arc_radius_tolerance) == 0);
    round.segments[0].end = unit_at(350 * rad_per_deg) * 10.0001;
    CHECK(make_arcs_exact(round, arc_radius_tolerance) == 1);
    CHECK(distance(*round.segments[0].centre, {0, 0}) < 0.001);
}

TEST_CASE("arc a little off its circle: the tester's contour, its arc's end 5e-5 mm off, is offset closed, with its corner arc") {
    using namespace test_arc_exact;
    const Profile exact = contour_profile(contour_job(tester_path({0, 0}), "outside", 6));
    const auto side = side_for(orientation(exact), Region::outside);
    int cases = 0;
    for (double angle = 0; angle < 360; angle += 30) {
        CAPTURE(angle);
        const Vec2 move = unit_at(angle * rad_per_deg) * 5e-5;
        const Profile p = contour_profile(contour_job(tester_path(move), "outside", 6));
        CHECK(off_of(p, 1) < 1e-12);  // made exact as it was read
        for (double d : {1.0, 3.0}) {
            CAPTURE(d);
            const OffsetResult o = offset_profile(p, d, side);
            const LoopCheck c = check_loop(o, p, exact, d, p.segments[1].end);
            CHECK(c.one);
            CHECK(c.closed);
            CHECK(c.corner_arc);
            CHECK(c.worst_exact < 1e-6);
            CHECK(c.worst_near < 2e-4);
            CHECK(o.profile.segments.size() == offset_profile(exact, d, side).profile.segments.size());
            // The posted contour: one closed loop at the tool's radius from the profile, the
            // moves of the exact profile's (within the program's 4 decimals and the move).
            const std::string program = test::post_job(contour_job(tester_path(move), "outside", 2 * d), "linuxcnc").text;
            const std::string exact_program = test::post_job(contour_job(tester_path({0, 0}), "outside", 2 * d), "linuxcnc").text;
            std::vector<test::NcMove> cut;
            for (const test::NcMove& m : test::interpret(program, ArcFormat::ijk_relative))
                if (m.g != 0 && std::abs(m.from.z + 1) < 1e-9 && std::abs(m.to.z + 1) < 1e-9 &&
                    (m.g > 1 || m.from.x != m.to.x || m.from.y != m.to.y))
                    cut.push_back(m);
            REQUIRE(cut.size() > 4);
            CHECK(distance({cut.front().from.x, cut.front().from.y}, {cut.back().to.x, cut.back().to.y}) < 1e-9);
            double worst = 0.0;
            for (const test::NcMove& m : cut)
                for (int k = 0; k <= 20; ++k) {
                    const Vec3 q = m.at(k / 20.0);
                    worst = std::max(worst, std::abs(to_profile(exact, {q.x, q.y}) - d));
                }
            CHECK(worst < 2e-4);
            CHECK(test::lines_of(program).size() == test::lines_of(exact_program).size());
            ++cases;
        }
    }
    CHECK(cases == 24);
    // The tester's job verbatim (its centre as given, the end 2.6e-5 mm inside): closed, one
    // plunge, as the exact arc's program within a unit of the last decimal.
    const std::string verbatim = test::post_job(contour_job(tester_path({0, 0}, given_centre), "outside", 2), "linuxcnc").text;
    const std::string exact_text = test::post_job(contour_job(tester_path({0, 0}), "outside", 2), "linuxcnc").text;
    const std::vector<std::string> v = test::lines_of(verbatim), e = test::lines_of(exact_text);
    REQUIRE(v.size() == e.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const auto wv = test::words_of(v[i]), we = test::words_of(e[i]);
        for (char axis : {'X', 'Y'})
            if (wv.count(axis) && we.count(axis)) largest = std::max(largest, std::abs(std::stod(wv.at(axis)) - std::stod(we.at(axis))));
    }
    CHECK(largest <= 1e-4 + 1e-9);
}

// Simulate's verdict on a program of a job: exit code, "no errors", "as designed", and the lines
// that warn or name a gouge.
std::string verdict(const fs::path& dir, const std::string& job_text, const std::string& program) {
    const std::string job = (dir / "job.json").string(), nc = (dir / "p.ngc").string();
    std::ofstream(job) << job_text;
    std::ofstream(nc) << program;
    const test::Run r = test::run({"simulate", nc, "--machine", "linuxcnc", "--job", job, "--resolution", "0.25"});
    int warnings = 0;
    for (const std::string& line : test::lines_of(r.out + r.err))
        if (line.find("warning") != std::string::npos || line.find("gouge") != std::string::npos) ++warnings;
    return fmt::format("exit {}, no errors {}, as designed {}, warnings {}", r.code, r.out.find("simulation: no errors") != std::string::npos,
                       r.out.find("the part is as designed") != std::string::npos, warnings);
}

TEST_CASE("arc a little off its circle: the tester's profile as a pocket's island, drawn either way, is kept, and a gouge into it found") {
    using namespace test_arc_exact;
    const fs::path dir = test::scratch("arc-exact-island");
    for (bool backwards : {false, true})
        for (double angle : {180.0, 0.0}) {  // (the design lost the island; the region check refused it)
            CAPTURE(backwards);
            CAPTURE(angle);
            const Vec2 move = unit_at(angle * rad_per_deg) * 5e-5, end = arc_to + move, c = exact_centre();
            json island = {{"start", {tester_start.x, tester_start.y}}, {"path", tester_path(move)}};
            if (backwards)
                island["path"] = json::array({{{"line", {57.89, 15.2}}},
                                              {{"line", {11.41, 55.01}}},
                                              {{"line", {end.x, end.y}}},
                                              {{"arc", {{"end", {arc_from.x, arc_from.y}}, {"centre", {c.x, c.y}}, {"direction", "ccw"}}}},
                                              {{"line", {tester_start.x, tester_start.y}}}});
            json job = json::parse(contour_job(tester_path(move), "outside", 2));
            job["operations"][0] = {{"type", "pocket"}, {"tool", 1}, {"endDepth", 1}, {"feed", 500}, {"start", {2, 7}},
                                    {"path", json::parse(R"([{"line":[88,7]},{"line":[88,95]},{"line":[2,95]},{"line":[2,7]}])")},
                                    {"islands", json::array({island})}};
            const Job read = read_job(job.dump(), "test.json");
            const auto& pocket = std::get<PocketOp>(read.operations.at(0));
            REQUIRE(pocket.region.islands.size() == 1);
            const Profile& kept = pocket.region.islands[0];
            for (std::size_t i = 0; i < kept.segments.size(); ++i) CHECK(off_of(kept, i) < 1e-12);
            const std::string program = test::post_program(read, load_machine("linuxcnc"));
            CHECK(verdict(dir, job.dump(), program) == "exit 0, no errors true, as designed true, warnings 0");
            // A feed into the island past its sharp corner is a gouge the design check finds.
            std::string gouged = program;
            const std::size_t at = gouged.rfind("\nG0 Z10");
            REQUIRE(at != std::string::npos);
            gouged.insert(at + 1, "G0 Z5\nG0 X59.5 Y90\nG1 Z-1\nG1 X50 Y60\nG0 Z10\n");
            const std::string g = verdict(dir, job.dump(), gouged);
            CHECK(g.find("as designed false") != std::string::npos);
        }
}

// A closed counter-clockwise star of lines and arcs about (50, 50): convex and concave corners,
// arcs bulging out and in, segment 0 a line.
Profile star(Numbers& g) {
    const int n = 4 + static_cast<int>(g.next() * 4);
    std::vector<Vec2> v;
    for (int i = 0; i < n; ++i) {
        const double a = two_pi * (i + g.in(-0.2, 0.2)) / n, r = g.in(17, 29);
        v.push_back(Vec2{50, 50} + unit_at(a) * r);
    }
    Profile s;
    s.start = v[0];
    for (int i = 0; i < n; ++i) {
        const Vec2 p = v[i], q = v[(i + 1) % n];
        ProfileSegment seg{q, std::nullopt, ArcDirection::ccw};
        if (i > 0 && g.next() < 0.7) {
            const double sweep = g.in(20, 120) * rad_per_deg, h = distance(p, q) / 2;
            const double r = h / std::sin(sweep / 2), m = r * std::cos(sweep / 2);
            const Vec2 u = (q - p) * (1 / (2 * h)), mid = (p + q) * 0.5;
            const bool out = g.next() < 0.5 || sweep > 100 * rad_per_deg;  // (a deep inward bulge would cross the next side)
            seg.centre = mid + left_of(u) * (out ? m : -m);
            seg.direction = out ? ArcDirection::ccw : ArcDirection::cw;
        }
        s.segments.push_back(seg);
    }
    return s;
}
json path_of(const Profile& s) {
    json path = json::array();
    for (const ProfileSegment& g : s.segments)
        if (g.centre)
            path.push_back({{"arc", {{"end", {g.end.x, g.end.y}}, {"centre", {g.centre->x, g.centre->y}}, {"direction", g.direction == ArcDirection::ccw ? "ccw" : "cw"}}}});
        else
            path.push_back({{"line", {g.end.x, g.end.y}}});
    return path;
}

TEST_CASE("arc a little off its circle: generated profiles with arcs' ends moved up to 0.001 mm in any direction give closed offsets at the tool's radius") {
    using namespace test_arc_exact;
    Numbers g{20261204};
    int shapes = 0, loops = 0, moved_arcs = 0, refused = 0;
    double largest_off = 0.0, worst_near_ratio = 0.0, worst_exact = 0.0;
    for (int n = 0; n < 60; ++n) {
        CAPTURE(n);
        Profile exact = star(g);
        try {
            exact = contour_profile([&] {
                json job = json::parse(contour_job(path_of(exact), "outside", 6, exact.start));
                job["stock"]["box"] = {{"min", {-10, -10, -3}}, {"max", {110, 110, 0}}};
                return job.dump();
            }());
        } catch (const InputError&) {
            ++refused;  // (a generated star that crosses itself)
            continue;
        }
        // Every arc's end but the closing one moved by up to 0.001 mm in any direction, as long as
        // it stays within 0.001 mm of its circle (the next segment starts there).
        Profile given = exact;
        double moved_most = 0.0;
        for (std::size_t i = 0; i + 1 < given.segments.size(); ++i) {
            if (!given.segments[i].centre) continue;
            for (;;) {
                const Vec2 move = unit_at(g.in(0, two_pi)) * (0.001 * g.next());
                Profile t = given;
                t.segments[i].end = exact.segments[i].end + move;
                if (off_of(t, i) > 0.001 || off_of(t, i + 1) > 0.001) continue;
                given = t;
                moved_most = std::max(moved_most, norm(move));
                break;
            }
        }
        double off = 0.0;
        for (std::size_t i = 0; i < given.segments.size(); ++i) off = std::max(off, off_of(given, i));
        largest_off = std::max(largest_off, off);
        json job = json::parse(contour_job(path_of(given), "outside", 6, given.start));
        job["stock"]["box"] = {{"min", {-10, -10, -3}}, {"max", {110, 110, 0}}};
        const Profile read = contour_profile(job.dump());
        for (std::size_t i = 0; i < read.segments.size(); ++i) {
            CHECK(off_of(read, i) < 1e-12);
            moved_arcs += off_of(given, i) > 1e-9;
        }
        ++shapes;
        for (Region region : {Region::outside, Region::inside})
            for (double d : {0.5, 1.0, 3.0}) {
                CAPTURE(d);
                CAPTURE(static_cast<int>(region));
                const OffsetResult oe = offset_profile(exact, d, side_for(orientation(exact), region));
                const OffsetResult o = offset_profile(read, d, side_for(orientation(read), region));
                if (oe.empty() || !oe.others.empty()) continue;  // (split or consumed even when exact: nothing to compare)
                ++loops;
                const LoopCheck c = check_loop(o, read, exact, d, {1e9, 1e9});
                CHECK(c.one);
                CHECK(c.closed);
                CHECK(c.worst_exact < 1e-6);
                // Near the exact profile: within about the ends' move (the exact arc through the
                // moved end leaves the unmoved one by about that), and the same loop of pieces.
                CHECK(c.worst_near <= 2 * moved_most + 1e-6);
                CHECK(o.profile.segments.size() == oe.profile.segments.size());
                worst_exact = std::max(worst_exact, c.worst_exact);
                if (moved_most > 0) worst_near_ratio = std::max(worst_near_ratio, c.worst_near / moved_most);
            }
    }
    MESSAGE(fmt::format("{} shapes ({} refused as drawn), {} arcs off, {} offset loops, largest arc end off {:.6f} mm, worst distance error {:.2g} mm, worst "
                        "distance from the unmoved profile / the ends' move {:.2f}",
                        shapes, refused, moved_arcs, loops, largest_off, worst_exact, worst_near_ratio));
    CHECK(shapes >= 50);
    CHECK(loops > 200);
    CHECK(largest_off > 8e-4);
}

TEST_CASE("arc a little off its circle: a lathe profile's arc is made exact as it is read, and turned as the exact one") {
    using namespace test_arc_exact;
    // The shaft sample's finishing profile, its R5 fillet's end moved 5e-5 mm along Z, off its
    // circle (X as a diameter).
    auto job = [](double end_z) {
        return json{{"units", "mm"},
                    {"clearance", 20},
                    {"stock", {{"bar", {{"diameter", 44}, {"length", 70}, {"faceZ", 1}}}}},
                    {"tools", json::array({{{"number", 3}, {"type", "turning-tool"}, {"diameter", 0.8}, {"surfaceSpeed", 220}, {"maxRpm", 2500}}})},
                    {"operations", json::array({{{"type", "turn-profile"}, {"tool", 3}, {"xValues", "diameter"}, {"feedMode", "per-revolution"}, {"feed", 0.1}, {"start", {24, 0}},
                                                 {"retractX", 44},
                                                 {"path", json::array({{{"line", {28, 0}}},
                                                                       {{"line", {30, -1}}},
                                                                       {{"line", {30, -20}}},
                                                                       {{"arc", {{"end", {40, end_z}}, {"centre", {40, -20}}, {"direction", "cw"}}}},
                                                                       {{"line", {40, -40}}}})}}})}}
            .dump();
    };
    for (double end_z : {-25.00005, -24.99995}) {
        CAPTURE(end_z);
        const Job read = read_job(job(end_z), "lathe.json");
        const Profile& p = std::get<TurnProfileOp>(read.operations.at(0)).profile;
        Profile again = p;
        CHECK(make_arcs_exact(again, 1.0) == 0);  // (nothing left off its circle)
        for (std::size_t i = 0; i < p.segments.size(); ++i) CHECK(off_of(p, i) < 1e-12);
        // The program is the exact fillet's within a unit of its last decimal.
        const std::string given = test::post_program(read, load_machine("linuxcnc-lathe"));
        const std::string exact = test::post_program(read_job(job(-25), "lathe.json"), load_machine("linuxcnc-lathe"));
        const std::vector<std::string> g = test::lines_of(given), e = test::lines_of(exact);
        REQUIRE(g.size() == e.size());
        for (std::size_t i = 0; i < g.size(); ++i) {
            const auto wg = test::words_of(g[i]), we = test::words_of(e[i]);
            for (char axis : {'X', 'Z', 'I', 'K'})
                if (wg.count(axis) && we.count(axis)) CHECK(std::abs(std::stod(wg.at(axis)) - std::stod(we.at(axis))) <= 2e-4 + 1e-9);
        }
    }
}

}  // namespace test_arc_exact
