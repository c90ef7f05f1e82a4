// The geometry layer's profile offset (issue 11), tested as a geometry library: for many
// profiles, every point of the offset is at exactly the distance from the profile (never
// closer), the offset is simple and closed when the profile is, arcs stay arcs, and the region
// it encloses is exactly the region within (or beyond) the distance. Then hand-worked cases and
// the helpers a contour operation uses (point and tangent at a length, sub-profiles, distance).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "camgen/geometry/offset.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_offset {

using namespace camgen;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double exact = 1e-6;  // mm: "at the distance" and "never closer" within this

struct Builder {
    Profile p;
    explicit Builder(Vec2 start) : p{ProfilePlane::xy, start, {}} {}
    Builder& line(Vec2 end) {
        p.segments.push_back({end, std::nullopt, ArcDirection::ccw});
        return *this;
    }
    Builder& arc(Vec2 end, Vec2 centre, ArcDirection d) {
        p.segments.push_back({end, centre, d});
        return *this;
    }
};

Profile polygon(const std::vector<Vec2>& v) {
    Builder b(v.front());
    for (std::size_t i = 1; i < v.size(); ++i) b.line(v[i]);
    b.line(v.front());
    return b.p;
}

// A w x h rectangle at the origin with corner radius r (0: sharp), counter-clockwise.
Profile rectangle(double w, double h, double r) {
    if (r == 0.0) return polygon({{0, 0}, {w, 0}, {w, h}, {0, h}});
    const auto ccw = ArcDirection::ccw;
    Builder b({r, 0});
    b.line({w - r, 0}).arc({w, r}, {w - r, r}, ccw).line({w, h - r}).arc({w - r, h}, {w - r, h - r}, ccw);
    b.line({r, h}).arc({0, h - r}, {r, h - r}, ccw).line({0, r}).arc({r, 0}, {r, r}, ccw);
    return b.p;
}

Profile circle(Vec2 c, double r) {
    Builder b({c.x + r, c.y});
    b.arc({c.x + r, c.y}, c, ArcDirection::ccw);
    return b.p;
}

// A slot (obround): two semicircles of radius r joined by lines of length l, ccw.
Profile slot(double l, double r) {
    Builder b({0, -r});
    b.line({l, -r}).arc({l, r}, {l, 0}, ArcDirection::ccw).line({0, r}).arc({0, -r}, {0, 0}, ArcDirection::ccw);
    return b.p;
}

// An L: 60 x 60 less the 30 x 30 top right square, so a concave corner at (30, 30).
Profile ell() { return polygon({{0, 0}, {60, 0}, {60, 30}, {30, 30}, {30, 60}, {0, 60}}); }

// A 60 x 40 block with a semicircular bite of radius `r` out of its top side (a concave arc).
Profile bitten(double r) {
    Builder b({0, 0});
    b.line({60, 0}).line({60, 40}).line({30 + r, 40}).arc({30 - r, 40}, {30, 40}, ArcDirection::cw).line({0, 40}).line({0, 0});
    return b.p;
}

// A 60 x 40 block with a rectangular notch `w` wide and 10 deep in its top side.
Profile notched(double w) {
    return polygon({{0, 0}, {60, 0}, {60, 40}, {30 + w / 2, 40}, {30 + w / 2, 30}, {30 - w / 2, 30}, {30 - w / 2, 40}, {0, 40}});
}

Profile star(int points, double outer, double inner) {
    std::vector<Vec2> v;
    for (int i = 0; i < 2 * points; ++i) {
        const double a = pi * i / points, r = i % 2 ? inner : outer;
        v.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return polygon(v);
}

// A star-shaped polygon (so simple) with radii drawn from a fixed linear congruential sequence.
Profile random_polygon(std::uint32_t seed, int n) {
    std::vector<Vec2> v;
    for (int i = 0; i < n; ++i) {
        seed = seed * 1664525u + 1013904223u;
        const double r = 20.0 + 30.0 * (seed >> 8) / double(1u << 24);
        const double a = 2 * pi * i / n;
        v.push_back({r * std::cos(a), r * std::sin(a)});
    }
    return polygon(v);
}

// The star-shaped polygon of random_polygon with some edges made arcs bulging out or in by up
// to a fifth of their chord (seeded as well).
Profile random_profile(std::uint32_t seed, int n) {
    const Profile poly = random_polygon(seed, n);
    Builder b(poly.start);
    Vec2 from = poly.start;
    for (const ProfileSegment& edge : poly.segments) {
        seed = seed * 1664525u + 1013904223u;
        const double u = (seed >> 8) / double(1u << 24);  // [0, 1)
        const Vec2 to = edge.end, mid{(from.x + to.x) / 2, (from.y + to.y) / 2};
        const double chord = std::hypot(to.x - from.x, to.y - from.y);
        const Vec2 left{-(to.y - from.y) / chord, (to.x - from.x) / chord};
        const double sagitta = (u - 0.5) * 0.4 * chord;  // + bulges left (in), - right (out)
        if (std::abs(sagitta) < 0.05 * chord) {
            b.line(to);
        } else {
            const double radius = (chord * chord / 4 + sagitta * sagitta) / (2 * std::abs(sagitta));
            const double toward = sagitta > 0 ? -(radius - sagitta) : (radius + sagitta);  // centre from mid, along left
            b.arc(to, {mid.x + left.x * toward, mid.y + left.y * toward}, sagitta > 0 ? ArcDirection::cw : ArcDirection::ccw);
        }
        from = to;
    }
    return b.p;
}

// The profile with every joint (the start, which is also the end, and each segment's end)
// moved by 0.001 to 0.01 mm in a direction drawn from a fixed sequence, arc centres kept: the
// joints of a drawing slightly off tangent, arcs whose end is a little off their circle (their
// radius is the start's).
Profile nudged(const Profile& p, std::uint32_t seed) {
    auto next = [&seed] {
        seed = seed * 1664525u + 1013904223u;
        return (seed >> 8) / double(1u << 24);  // [0, 1)
    };
    auto nudge = [&](Vec2 v) {
        const double by = 0.001 + 0.009 * next(), a = 2 * pi * next();
        return Vec2{v.x + by * std::cos(a), v.y + by * std::sin(a)};
    };
    Profile q = p;
    q.start = nudge(p.start);
    for (std::size_t i = 0; i + 1 < q.segments.size(); ++i) q.segments[i].end = nudge(q.segments[i].end);
    q.segments.back().end = q.start;
    return q;
}

// A comb: a base 10 high with `teeth` teeth `w` wide and 20 high, `gap` apart, ccw.
Profile comb(int teeth, double w, double gap) {
    std::vector<Vec2> v{{0, 0}, {teeth * w + (teeth - 1) * gap, 0}};
    for (int i = teeth - 1; i >= 0; --i) {
        const double x0 = i * (w + gap), x1 = x0 + w;
        v.push_back({x1, 30});
        v.push_back({x0, 30});
        if (i > 0) v.push_back({x0, 10}), v.push_back({x0 - gap, 10});
    }
    return polygon(v);
}

// Two 30 x 30 squares joined by a 40 long bar `neck` wide: inside offsets wider than half the
// neck fall apart in two.
Profile dumbbell(double neck) {
    const double y0 = 15 - neck / 2, y1 = 15 + neck / 2;
    return polygon({{0, 0}, {30, 0}, {30, y0}, {70, y0}, {70, 0}, {100, 0}, {100, 30}, {70, 30}, {70, y1}, {30, y1}, {30, 30}, {0, 30}});
}

std::size_t arcs_in(const Profile& p) {
    return static_cast<std::size_t>(std::count_if(p.segments.begin(), p.segments.end(), [](const ProfileSegment& s) { return s.centre.has_value(); }));
}

std::vector<Profile> paths_of(const OffsetResult& r) {
    std::vector<Profile> all{r.profile};
    all.insert(all.end(), r.others.begin(), r.others.end());
    return all;
}

// Every path of the offset sampled densely (every segment at least every 0.05 mm and 20
// times, ends included) lies at exactly `d` from the profile: never closer, nowhere farther.
void check_at_distance(const Profile& profile, const OffsetResult& r, double d) {
    for (const Profile& path : paths_of(r)) {
        double worst_low = 0.0, worst_high = 0.0;
        for (std::size_t i = 0; i < path.segments.size(); ++i) {
            const Profile one{path.plane, i == 0 ? path.start : path.segments[i - 1].end, {path.segments[i]}};
            const double length = profile_length(one);
            const int n = std::max(20, static_cast<int>(length / 0.05));
            for (int j = 0; j <= n; ++j) {
                const double e = distance_to(profile, point_at(one, length * j / n).point) - d;
                worst_low = std::min(worst_low, e);
                worst_high = std::max(worst_high, e);
            }
        }
        CHECK(worst_low >= -exact);   // never gouges
        CHECK(worst_high <= exact);   // follows at the distance
    }
}

// Even-odd point in polygon on a sampling (Boost's contains rebuilds its ring on every call,
// too slow for a grid of points).
bool inside_sampled(const std::vector<Vec2>& ring, Vec2 q) {
    bool in = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
        if ((ring[i].y > q.y) != (ring[j].y > q.y) &&
            q.x < ring[j].x + (ring[i].x - ring[j].x) * (q.y - ring[j].y) / (ring[i].y - ring[j].y))
            in = !in;
    return in;
}

// The region the offset encloses is exactly the profile's region grown (outside) or shrunk
// (inside) by d, tested on a grid of points not within 0.01 mm of either boundary (the
// samplings are within 0.001 mm of the arcs).
void check_region(const Profile& profile, const OffsetResult& r, double d, Region region) {
    const auto ring = sample_profile(profile, 0.001);
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (Vec2 p : ring) x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    x0 -= d + 2, y0 -= d + 2, x1 += d + 2, y1 += d + 2;
    std::vector<std::vector<Vec2>> offset_rings;
    if (!r.empty())
        for (const Profile& p : paths_of(r)) offset_rings.push_back(sample_profile(p, 0.001));
    int checked = 0, wrong = 0;
    for (int i = 0; i <= 30; ++i)
        for (int j = 0; j <= 30; ++j) {
            const Vec2 q{x0 + (x1 - x0) * (i + 0.37) / 31, y0 + (y1 - y0) * (j + 0.61) / 31};
            const double dist = distance_to(profile, q);
            if (std::abs(dist - d) < 0.01 || dist < 0.01) continue;
            const bool in_profile = inside_sampled(ring, q);
            const bool expected = region == Region::outside ? (in_profile || dist < d) : (in_profile && dist > d);
            const bool got = std::any_of(offset_rings.begin(), offset_rings.end(), [&](const auto& o) { return inside_sampled(o, q); });
            ++checked;
            if (got != expected) ++wrong;
        }
    CHECK(checked > 500);
    CHECK(wrong == 0);
}

// All the properties of the offset of a closed profile to `region` by d.
OffsetResult check_closed(const Profile& profile, double d, Region region) {
    INFO("offset by " << d << std::string(region == Region::inside ? " inside" : " outside"));
    const OffsetResult r = offset_profile(profile, d, side_for(orientation(profile), region));
    check_at_distance(profile, r, d);
    for (const Profile& path : paths_of(r)) {
        if (r.empty()) break;
        CHECK(is_closed(path));
        CHECK(is_simple(path));
        CHECK(orientation(path) == orientation(profile));  // walked the same way round
    }
    CHECK(r.source.size() == r.profile.segments.size());
    check_region(profile, r, d, region);
    return r;
}

bool has_note(const OffsetResult& r, OffsetNoteKind kind, std::optional<std::size_t> segment) {
    return std::any_of(r.notes.begin(), r.notes.end(), [&](const OffsetNote& n) { return n.kind == kind && n.segment == segment; });
}

bool near(Vec2 a, Vec2 b, double tol = 1e-9) { return std::hypot(a.x - b.x, a.y - b.y) <= tol; }

}  // namespace

TEST_CASE("offset: closed profiles of every kind, both sides, both orientations: at the distance, simple, the true region") {
    const std::vector<std::pair<std::string, Profile>> profiles{
        {"rectangle", rectangle(100, 60, 0)},    {"rounded rectangle", rectangle(200, 120, 10)},
        {"L", ell()},                            {"slot", slot(50, 10)},
        {"circle", circle({5, -3}, 20)},         {"tight concave arc", bitten(3)},
        {"concave arc", bitten(8)},              {"narrow notch", notched(4)},
        {"wide notch", notched(16)},             {"notch a 10 mm tool just fits", notched(10)},             {"star", star(5, 50, 20)},
        {"dumbbell", dumbbell(8)},
    };
    for (const auto& [name, p] : profiles)
        for (const Profile& q : {p, reversed(p)})
            for (double d : {1.0, 3.0, 5.0, 9.0})
                for (Region region : {Region::outside, Region::inside}) {
                    INFO(name << std::string(orientation(q) == Orientation::ccw ? " ccw" : " cw"));
                    check_closed(q, d, region);
                }
}

TEST_CASE("offset: deterministic random polygons, both sides") {
    for (std::uint32_t seed = 1; seed <= 12; ++seed)
        for (double d : {0.5, 2.0, 6.0})
            for (Region region : {Region::outside, Region::inside}) {
                INFO("seed " << seed);
                check_closed(random_polygon(seed, 7 + static_cast<int>(seed % 9)), d, region);
            }
}

TEST_CASE("offset: a jagged polygon of 300 vertices (a crossing every few hundredths of a mm)") {
    for (Region region : {Region::outside, Region::inside}) check_closed(random_polygon(77, 300), 1.0, region);
}

TEST_CASE("offset: deterministic random profiles of lines and arcs bulging out and in, both sides") {
    int tested = 0;
    for (std::uint32_t seed = 100; seed < 116; ++seed) {
        const Profile p = random_profile(seed, 5 + static_cast<int>(seed % 7));
        if (!is_simple(p)) continue;
        ++tested;
        std::size_t arcs = arcs_in(p);
        for (double d : {0.5, 2.0, 7.0})
            for (Region region : {Region::outside, Region::inside}) {
                INFO("seed " << seed);
                check_closed(p, d, region);
            }
        CHECK(arcs > 0);
    }
    CHECK(tested >= 12);
}

TEST_CASE("offset: combs whose gaps and teeth the tool just fits, fits easily or does not") {
    for (double w : {4.0, 6.0, 10.0})
        for (double gap : {4.0, 6.0, 10.0})
            for (double d : {1.0, 2.0, 3.0, 5.0})
                for (Region region : {Region::outside, Region::inside}) {
                    INFO("teeth " << w << " gaps " << gap);
                    const OffsetResult r = check_closed(comb(4, w, gap), d, region);
                    CHECK(r.profile.segments.size() == r.source.size());
                }
    // A base exactly the tool's width high (10, d = 5): along it the offsets of its bottom and
    // top coincide and are no path; under the two middle teeth the tool rises a little between
    // the arcs about the gaps' corners: a lens 4 wide, of area
    // 2 int_0^2 (5 - sqrt(25 - u^2)) du = 2 (10 - (sqrt 21 + 12.5 asin 0.4)) = 0.5468 mm^2.
    const OffsetResult lenses = check_closed(comb(4, 4, 4), 5, Region::inside);
    REQUIRE(lenses.others.size() == 1);
    const double lens = 2 * (10 - (std::sqrt(21.0) + 12.5 * std::asin(0.4)));
    // (the sampling's chords cut across the concave arcs: a few 1e-6 mm^2 too much)
    CHECK(std::abs(enclosed_area(lenses.profile, 1e-6) - lens) < 1e-5);
    CHECK(std::abs(enclosed_area(lenses.others[0], 1e-6) - lens) < 1e-5);
    CHECK(is_simple(lenses.profile));
}

TEST_CASE("offset: a 200 x 120 plate with R10 corners, by hand") {
    const Profile plate = rectangle(200, 120, 10);
    const Vec2 centres[4] = {{190, 10}, {190, 110}, {10, 110}, {10, 10}};

    SUBCASE("outside by 5: R15 corners about the same centres, sides 5 mm out, nothing more") {
        const OffsetResult r = check_closed(plate, 5, Region::outside);
        CHECK(r.notes.empty());
        REQUIRE(r.profile.segments.size() == 8);
        CHECK(arcs_in(r.profile) == 4);
        CHECK(near(r.profile.start, {10, -5}));
        CHECK(near(r.profile.segments[0].end, {190, -5}));
        for (int k = 0; k < 4; ++k) {
            const ProfileSegment& a = r.profile.segments[2 * k + 1];
            REQUIRE(a.centre.has_value());
            CHECK(near(*a.centre, centres[k]));
            CHECK(a.direction == ArcDirection::ccw);
            CHECK(std::hypot(a.end.x - a.centre->x, a.end.y - a.centre->y) == doctest::Approx(15));
            CHECK(r.source[2 * k + 1] == std::optional<std::size_t>(2 * k + 1));
        }
        CHECK(near(r.profile.segments[2].end, {205, 110}));
        CHECK(near(r.profile.segments[4].end, {10, 125}));
    }
    SUBCASE("inside by 5: R5 corners about the same centres") {
        const OffsetResult r = check_closed(plate, 5, Region::inside);
        CHECK(r.notes.empty());
        REQUIRE(r.profile.segments.size() == 8);
        CHECK(arcs_in(r.profile) == 4);
        for (int k = 0; k < 4; ++k) {
            const ProfileSegment& a = r.profile.segments[2 * k + 1];
            REQUIRE(a.centre.has_value());
            CHECK(near(*a.centre, centres[k]));
            CHECK(std::hypot(a.end.x - a.centre->x, a.end.y - a.centre->y) == doctest::Approx(5));
        }
        CHECK(near(r.profile.segments[0].end, {190, 5}));
    }
    SUBCASE("inside by 12: the R10 corners are tighter than the tool, the sides meet in sharp corners") {
        // The bottom side offset is y = 12, the right side x = 188: they meet at (188, 12). The
        // corner arc (centre (190, 10), R10) would need the radius 10 - 12 = -2: the tool cannot
        // reach into it. At (188, 12) the tool touches both sides, (188, 0) and (200, 12), both on
        // the straight parts; its distance to the arc is sqrt(148) = 12.17 > 12 (the arc's
        // nearest points are its ends (190, 0) and (200, 10): sqrt(2^2 + 12^2)), so the corner is
        // left as an R12 round, and the offset is the 176 x 96 rectangle from (12, 12).
        const OffsetResult r = check_closed(plate, 12, Region::inside);
        REQUIRE(r.profile.segments.size() == 4);
        CHECK(arcs_in(r.profile) == 0);
        const Vec2 corners[4] = {{188, 12}, {188, 108}, {12, 108}, {12, 12}};
        for (int k = 0; k < 4; ++k) {
            CHECK(near(r.profile.segments[k].end, corners[k], 1e-7));
            CHECK(has_note(r, OffsetNoteKind::arc_too_tight, 2 * k + 1));
            CHECK(r.source[k] == std::optional<std::size_t>(2 * k));
        }
        CHECK(enclosed_area(r.profile) == doctest::Approx(176.0 * 96.0));
        CHECK(distance_to(plate, {188, 12}) == doctest::Approx(12));
    }
    SUBCASE("inside by 10: the corners shrink to points, no note (the tool just fits)") {
        const OffsetResult r = check_closed(plate, 10, Region::inside);
        CHECK(r.notes.empty());
        CHECK(arcs_in(r.profile) == 0);
        CHECK(r.profile.segments.size() == 4);
    }
    SUBCASE("inside by 60: consumed, a note, no crash") {
        const OffsetResult r = offset_profile(plate, 60, OffsetSide::left);
        CHECK(r.empty());
        CHECK(r.others.empty());
        CHECK(has_note(r, OffsetNoteKind::consumed, std::nullopt));
    }
}

TEST_CASE("offset: arcs stay arcs, convex corners get an arc of the distance") {
    // Outside offsets keep every arc of a rounded rectangle and of a slot.
    CHECK(arcs_in(offset_profile(rectangle(80, 50, 6), 4, OffsetSide::right).profile) == 4);
    CHECK(arcs_in(offset_profile(slot(30, 5), 2, OffsetSide::right).profile) == 2);
    CHECK(arcs_in(offset_profile(slot(30, 5), 2, OffsetSide::left).profile) == 2);
    // A sharp rectangle gains four corner arcs of radius 3 around its corners outside.
    const OffsetResult r = offset_profile(rectangle(100, 60, 0), 3, OffsetSide::right);
    REQUIRE(arcs_in(r.profile) == 4);
    for (std::size_t i = 0; i < r.profile.segments.size(); ++i) {
        const ProfileSegment& s = r.profile.segments[i];
        if (!s.centre) continue;
        CHECK(!r.source[i].has_value());
        CHECK(std::hypot(s.end.x - s.centre->x, s.end.y - s.centre->y) == doctest::Approx(3));
    }
    // A circle outside by 4 and inside by 4: one full circle of radius 24 and 16.
    for (auto [side, radius] : {std::pair{OffsetSide::right, 24.0}, std::pair{OffsetSide::left, 16.0}}) {
        const OffsetResult c = offset_profile(circle({0, 0}, 20), 4, side);
        REQUIRE(c.profile.segments.size() == 1);
        CHECK(profile_length(c.profile) == doctest::Approx(2 * pi * radius));
    }
}

TEST_CASE("offset: what the tool cannot follow is noted by segment, and trimmed") {
    SUBCASE("a concave arc tighter than the tool") {
        const OffsetResult r = check_closed(bitten(3), 5, Region::outside);
        CHECK(has_note(r, OffsetNoteKind::arc_too_tight, 3));
        CHECK(r.notes.size() == 1);
        CHECK(r.notes[0].message.find("segment 3") != std::string::npos);
        CHECK(std::find(r.source.begin(), r.source.end(), std::optional<std::size_t>(3)) == r.source.end());
    }
    SUBCASE("a concave arc the tool fits: followed at R - d, no note") {
        const OffsetResult r = check_closed(bitten(8), 5, Region::outside);
        CHECK(r.notes.empty());
        const auto at = std::find(r.source.begin(), r.source.end(), std::optional<std::size_t>(3));
        REQUIRE(at != r.source.end());
        const ProfileSegment& a = r.profile.segments[static_cast<std::size_t>(at - r.source.begin())];
        REQUIRE(a.centre.has_value());
        CHECK(std::hypot(a.end.x - a.centre->x, a.end.y - a.centre->y) == doctest::Approx(3));
    }
    SUBCASE("a notch narrower than the tool is bridged: its three sides vanish") {
        const OffsetResult r = check_closed(notched(4), 5, Region::outside);
        for (std::size_t s : {3u, 4u, 5u}) CHECK(has_note(r, OffsetNoteKind::element_removed, s));
        CHECK(r.notes.size() == 3);
        CHECK(r.others.empty());
    }
    SUBCASE("a neck narrower than the tool splits the inside offset in two") {
        const OffsetResult r = check_closed(dumbbell(8), 5, Region::inside);
        CHECK(r.others.size() == 1);
        CHECK(has_note(r, OffsetNoteKind::split, std::nullopt));
        // Each half is the 20 x 20 square 5 in from the walls, plus where it reaches into the
        // neck: between the neck's corners (30, 11) and (30, 19) out to x = 30 - sqrt(25 - (y - 11)^2)
        // for y in [11, 15] and mirrored, 2 (5 * 4 - int_0^4 sqrt(25 - s^2) ds)
        // = 2 (20 - (6 + 12.5 asin 0.8)) = 4.81762 mm^2.
        const double half = 400.0 + 2.0 * (20.0 - (6.0 + 12.5 * std::asin(0.8)));
        CHECK(enclosed_area(r.profile, 1e-6) == doctest::Approx(half).epsilon(1e-7));
        CHECK(enclosed_area(r.others[0], 1e-6) == doctest::Approx(half).epsilon(1e-7));
    }
    SUBCASE("a notch the tool exactly fits: no spike into it and back") {
        const OffsetResult r = check_closed(notched(10), 5, Region::outside);
        CHECK(is_simple(r.profile));
        for (const ProfileSegment& s : r.profile.segments) CHECK_FALSE((s.end.x > 25.001 && s.end.x < 34.999 && s.end.y < 39.999));
    }
    SUBCASE("a slot as wide as the tool is consumed: the offsets of its sides coincide") {
        const OffsetResult r = offset_profile(slot(50, 5), 5, OffsetSide::left);
        CHECK(r.empty());
        CHECK(has_note(r, OffsetNoteKind::consumed, std::nullopt));
    }
    SUBCASE("a slot narrower than the tool is consumed") {
        const OffsetResult r = offset_profile(slot(50, 5), 6, OffsetSide::left);
        CHECK(r.empty());
        CHECK(has_note(r, OffsetNoteKind::consumed, std::nullopt));
    }
    SUBCASE("zero-length segments are passed over, an empty profile is consumed, no distance is no offset") {
        Profile with_zero = rectangle(200, 120, 10);
        with_zero.segments.insert(with_zero.segments.begin() + 1, {Vec2{190, 0}, std::nullopt, ArcDirection::ccw});
        const OffsetResult a = offset_profile(with_zero, 5, OffsetSide::right), b = offset_profile(rectangle(200, 120, 10), 5, OffsetSide::right);
        CHECK(a.profile.segments == b.profile.segments);
        CHECK(a.source[1] == std::optional<std::size_t>(2));  // the R10 arc, after the zero-length line
        CHECK(offset_profile(Profile{ProfilePlane::xy, {1, 2}, {}}, 5, OffsetSide::left).empty());
        const OffsetResult none = offset_profile(ell(), 0.0, OffsetSide::left);
        CHECK(none.profile.segments == ell().segments);
        CHECK(none.source.size() == ell().segments.size());
    }
    SUBCASE("a circle smaller than the tool is consumed, also at exactly its radius") {
        CHECK(offset_profile(circle({0, 0}, 5), 6, OffsetSide::left).empty());
        CHECK(offset_profile(circle({0, 0}, 5), 5, OffsetSide::left).empty());
    }
}

TEST_CASE("offset: deterministic random open chains of lines and arcs, both sides") {
    for (std::uint32_t seed = 200; seed < 220; ++seed) {
        Profile p = random_profile(seed, 6 + static_cast<int>(seed % 5));
        p.segments.pop_back();  // open
        for (double d : {0.5, 3.0, 9.0})
            for (OffsetSide side : {OffsetSide::left, OffsetSide::right}) {
                INFO("seed " << seed << " by " << d);
                const OffsetResult r = offset_profile(p, d, side);
                REQUIRE_FALSE(r.empty());
                check_at_distance(p, r, d);
                CHECK_FALSE(is_closed(r.profile));
                CHECK(is_simple(r.profile));
                // Where the start's offset is no closer to the rest, the path starts there.
                const ProfilePoint first = point_at(p, 0.0);
                const double sign = side == OffsetSide::left ? 1.0 : -1.0;
                const Vec2 start{first.point.x - sign * d * first.tangent.y, first.point.y + sign * d * first.tangent.x};
                if (distance_to(p, start) > d - 1e-9 && r.others.empty()) CHECK(near(r.profile.start, start, 1e-6));
            }
    }
}

TEST_CASE("offset: open chains, one-sided, from the start's offset to the end's") {
    const auto ccw = ArcDirection::ccw, cw = ArcDirection::cw;
    std::vector<Profile> chains;
    chains.push_back(Builder({0, 0}).line({50, 0}).p);
    chains.push_back(Builder({0, 0}).line({20, 10}).line({40, -5}).line({60, 12}).line({80, 0}).p);  // zigzag
    chains.push_back(Builder({0, 0}).line({30, 0}).arc({40, 10}, {30, 10}, ccw).line({40, 40}).arc({50, 50}, {50, 40}, cw).p);
    chains.push_back(Builder({0, 0}).line({40, 0}).line({40, 3}).line({0, 3}).p);  // a hairpin narrower than the tool
    chains.push_back(Builder({0, 0}).arc({20, 0}, {10, 0}, cw).arc({40, 0}, {30, 0}, ccw).p);
    for (const Profile& p : chains)
        for (double d : {1.0, 4.0})
            for (OffsetSide side : {OffsetSide::left, OffsetSide::right}) {
                INFO("chain of " << p.segments.size() << " by " << d << std::string(side == OffsetSide::left ? " left" : " right"));
                const OffsetResult r = offset_profile(p, d, side);
                if (&p == &chains[3] && d > 1.5 && side == OffsetSide::left) continue;  // consumed, below
                REQUIRE_FALSE(r.empty());
                check_at_distance(p, r, d);
                CHECK_FALSE(is_closed(r.profile));
                CHECK(is_simple(r.profile));
            }
    // A straight line: the offset is the line moved 4 to the left, as long.
    const OffsetResult line = offset_profile(chains[0], 4, OffsetSide::left);
    REQUIRE(line.profile.segments.size() == 1);
    CHECK(near(line.profile.start, {0, 4}));
    CHECK(near(line.profile.segments[0].end, {50, 4}));
    // The zigzag's right offset starts and ends at its ends' offsets, corner arcs between.
    const OffsetResult zig = offset_profile(chains[1], 1, OffsetSide::right);
    const ProfilePoint first = point_at(chains[1], 0.0);
    CHECK(near(zig.profile.start, {first.point.x + first.tangent.y, first.point.y - first.tangent.x}));
    CHECK(arcs_in(zig.profile) == 1);  // its one left turn is convex on the right
    // The hairpin: its left side is the inside, 3 mm wide: an 8 mm tool cannot enter it at all.
    const OffsetResult pin = offset_profile(chains[3], 4, OffsetSide::left);
    CHECK(pin.empty());
    REQUIRE(pin.notes.size() == 1);  // only that: which segments vanished on the way is no news
    CHECK(has_note(pin, OffsetNoteKind::consumed, std::nullopt));
    // A 2 mm tool fits in it: 1 mm from both sides, a line 1 mm short of the bend.
    const OffsetResult fits = offset_profile(chains[3], 1, OffsetSide::left);
    REQUIRE(fits.profile.segments.size() == 3);
    CHECK(near(fits.profile.segments[0].end, {39, 1}));
    CHECK(near(fits.profile.segments[1].end, {39, 2}));
}

TEST_CASE("profile helpers: point and tangent at a length, sub-profiles split exactly, distance, sides") {
    const Profile plate = rectangle(200, 120, 10);
    const double arc = pi * 10 / 2;  // a corner's length

    const ProfilePoint a = point_at(plate, 90);
    CHECK(near(a.point, {100, 0}));
    CHECK(near(a.tangent, {1, 0}));
    CHECK(a.segment == 0);
    const ProfilePoint b = point_at(plate, 180 + arc / 2);  // halfway round the first corner
    CHECK(near(b.point, {190 + 10 * std::cos(-pi / 4), 10 + 10 * std::sin(-pi / 4)}, 1e-9));
    CHECK(near(b.tangent, {std::cos(pi / 4), std::sin(pi / 4)}, 1e-9));
    CHECK(b.segment == 1);
    CHECK(near(point_at(plate, -5).point, {10, 0}));
    CHECK(near(point_at(plate, 1e6).point, {10, 0}));

    // A piece across the first corner: a line part, the whole arc, a line part; exact ends.
    const Profile piece = sub_profile(plate, 100, 180 + arc + 20);
    CHECK(near(point_at(plate, 100).point, {110, 0}));
    REQUIRE(piece.segments.size() == 3);
    CHECK(near(piece.start, {110, 0}));  // the plate starts at (10, 0)
    CHECK(piece.segments[1].centre == std::optional<Vec2>(Vec2{190, 10}));
    CHECK(piece.segments[1].end == Vec2{200, 10});
    CHECK(near(piece.segments[2].end, {200, 30}));
    CHECK(profile_length(piece) == doctest::Approx(80 + arc + 20));
    // Half an arc: same centre and direction, the end on the circle.
    const Profile half = sub_profile(plate, 180 + arc / 4, 180 + 3 * arc / 4);
    REQUIRE(half.segments.size() == 1);
    CHECK(half.segments[0].centre == std::optional<Vec2>(Vec2{190, 10}));
    CHECK(segment_sweep(half, 0) == doctest::Approx(pi / 4));
    // Wrapping past the start of a closed profile.
    const double total = profile_length(plate);
    const Profile wrap = sub_profile(plate, total - 30, 40);
    CHECK(profile_length(wrap) == doctest::Approx(70));
    CHECK(near(wrap.segments.back().end, {50, 0}));
    CHECK(near(wrap.start, point_at(plate, total - 30).point));

    CHECK(distance_to(plate, {100, 60}) == doctest::Approx(60));
    CHECK(distance_to(plate, {100, -7}) == doctest::Approx(7));
    CHECK(distance_to(plate, {0, 0}) == doctest::Approx(10 * std::sqrt(2.0) - 10));
    CHECK(distance_to(plate, {190, 10}) == doctest::Approx(10));

    CHECK(side_for(Orientation::ccw, Region::outside) == OffsetSide::right);
    CHECK(side_for(Orientation::ccw, Region::inside) == OffsetSide::left);
    CHECK(side_for(Orientation::cw, Region::outside) == OffsetSide::left);
    CHECK(side_for(Orientation::cw, Region::inside) == OffsetSide::right);
}

TEST_CASE("offset: a fuzzed pocket wall with slightly non-tangent joints (fuzz: an arc off its circle, a side missing)") {
    const auto ccw = ArcDirection::ccw;
    Builder b({78, 40});
    b.line({121.92, 40}).arc({130, 48}, {122, 48}, ccw).line({130, 72}).arc({122, 80}, {122, 72}, ccw);
    b.line({78, 80}).arc({70, 72}, {78, 72}, ccw).line({70, 48.006}).arc({78, 40}, {78, 48}, ccw);
    check_closed(b.p, 3.0, Region::inside);
}

TEST_CASE("offset: rounded rectangles and slots with joints nudged off tangent by 0.001 to 0.01 mm, both sides") {
    struct Shape {
        std::string name;
        Profile profile;
        double radius;  // its arcs'
    };
    const std::vector<Shape> shapes{
        {"pocket R8", rectangle(60, 40, 8), 8}, {"plate R10", rectangle(200, 120, 10), 10}, {"R3 corners", rectangle(50, 30, 3), 3}, {"slot", slot(30, 6), 6}};
    int arcs_off = 0;
    for (const auto& [name, shape, radius] : shapes)
        for (std::uint32_t seed = 1; seed <= 6; ++seed) {
            const Profile p = nudged(seed % 2 ? shape : reversed(shape), seed * 7919u);
            for (std::size_t i = 0; i < p.segments.size(); ++i) {
                const ProfileSegment& s = p.segments[i];
                const Vec2 from = i == 0 ? p.start : p.segments[i - 1].end;
                if (s.centre && std::abs(std::hypot(s.end.x - s.centre->x, s.end.y - s.centre->y) -
                                         std::hypot(from.x - s.centre->x, from.y - s.centre->y)) > 1e-4)
                    ++arcs_off;
            }
            for (double d : {1.0, 3.0, 6.0})
                for (Region region : {Region::outside, Region::inside}) {
                    INFO(name << " seed " << seed);
                    const OffsetResult r = check_closed(p, d, region);
                    CHECK(r.others.empty());  // nothing here is narrower than the tool
                    // An arc off its circle is two pieces, not two segments that vanish (inside,
                    // arcs tighter than the tool do vanish).
                    if (region == Region::outside || d < radius - 0.1)
                        CHECK_FALSE(std::any_of(r.notes.begin(), r.notes.end(), [](const OffsetNote& n) { return n.kind == OffsetNoteKind::element_removed; }));
                }
        }
    CHECK(arcs_off > 40);  // the family has what it is for: arcs whose ends are off their circles
}

}  // namespace test_offset
