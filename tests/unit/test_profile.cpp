// The geometry layer's 2D profiles: closed, simple, orientation, area, point inside (by
// Boost.Geometry on a sampling), rigid transforms (Eigen), lengths and sampling accuracy.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "camgen/geometry/profile.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_profile {

using namespace camgen;

namespace {

constexpr double pi = std::numbers::pi;

Profile line_to(Profile p, Vec2 end) {
    p.segments.push_back({end, std::nullopt, ArcDirection::ccw});
    return p;
}
Profile arc_to(Profile p, Vec2 end, Vec2 centre, ArcDirection d) {
    p.segments.push_back({end, centre, d});
    return p;
}

// The 200 x 120 plate outline with R10 corners, counter-clockwise from (10, 0).
Profile plate() {
    Profile p{ProfilePlane::xy, {10, 0}, {}};
    p = line_to(p, {190, 0});
    p = arc_to(p, {200, 10}, {190, 10}, ArcDirection::ccw);
    p = line_to(p, {200, 110});
    p = arc_to(p, {190, 120}, {190, 110}, ArcDirection::ccw);
    p = line_to(p, {10, 120});
    p = arc_to(p, {0, 110}, {10, 110}, ArcDirection::ccw);
    p = line_to(p, {0, 10});
    p = arc_to(p, {10, 0}, {10, 10}, ArcDirection::ccw);
    return p;
}

}  // namespace

TEST_CASE("profile: a closed outline with arcs is closed, simple, counter-clockwise, of its true area") {
    const Profile p = plate();
    CHECK(is_closed(p));
    CHECK(is_simple(p));
    CHECK(orientation(p) == Orientation::ccw);
    // 200 x 120 less four corners of (1 - pi/4) x 10^2 each; sampled chords lose < 0.001 mm.
    const double exact = 200.0 * 120.0 - 4.0 * (1.0 - pi / 4.0) * 100.0;
    CHECK(enclosed_area(p) == doctest::Approx(exact).epsilon(1e-5));
    CHECK(enclosed_area(p) <= exact);
    CHECK(profile_length(p) == doctest::Approx(2 * 180.0 + 2 * 100.0 + 2 * pi * 10.0));
    CHECK(contains(p, {100, 60}));
    CHECK_FALSE(contains(p, {1, 1}));  // cut off by the R10 corner
    CHECK_FALSE(contains(p, {250, 60}));
    CHECK_FALSE(first_short_segment(p).has_value());
    CHECK(segment_sweep(p, 1) == doctest::Approx(pi / 2));
    CHECK(segment_sweep(p, 0) == 0.0);
}

TEST_CASE("profile: orientation counts the arcs exactly (half discs whose chords enclose nothing)") {
    // (1, 0) to (-1, 0) by an arc about the origin and back along the X axis: the chords alone
    // enclose no area, so only the arcs' own areas decide the turning direction.
    auto half_disc = [](ArcDirection d) {
        Profile p;
        p.start = {1, 0};
        p.segments = {{{-1, 0}, Vec2{0, 0}, d}, {{1, 0}}};
        return p;
    };
    CHECK(orientation(half_disc(ArcDirection::ccw)) == Orientation::ccw);  // over the top, back below
    CHECK(orientation(half_disc(ArcDirection::cw)) == Orientation::cw);    // under the bottom, back above
    CHECK(orientation(reversed(half_disc(ArcDirection::ccw))) == Orientation::cw);
    // A circle of two half arcs, and a full circle of one arc.
    Profile circle;
    circle.start = {3, 2};
    circle.segments = {{{1, 2}, Vec2{2, 2}, ArcDirection::cw}, {{3, 2}, Vec2{2, 2}, ArcDirection::cw}};
    CHECK(orientation(circle) == Orientation::cw);
    Profile full;
    full.start = {3, 2};
    full.segments = {{{3, 2}, Vec2{2, 2}, ArcDirection::ccw}};
    CHECK(orientation(full) == Orientation::ccw);
}

TEST_CASE("profile: reversed walks the other way, same area, arcs turn the other way") {
    const Profile r = reversed(plate());
    CHECK(is_closed(r));
    CHECK(orientation(r) == Orientation::cw);
    CHECK(enclosed_area(r) == doctest::Approx(enclosed_area(plate())));
    CHECK(r.segments.front().centre.has_value());
    CHECK(r.segments.front().direction == ArcDirection::cw);
    CHECK(r.start == Vec2{10, 0});
    CHECK(r.segments.back().end == Vec2{10, 0});
}

TEST_CASE("profile: sampled points lie on the arcs within the tolerance") {
    Profile c{ProfilePlane::xy, {5, 0}, {}};
    c = arc_to(c, {5, 0}, {0, 0}, ArcDirection::ccw);  // full circle
    CHECK(is_closed(c));
    CHECK(profile_length(c) == doctest::Approx(10 * pi));
    for (double tol : {0.1, 0.01, 0.001}) {
        const auto pts = sample_profile(c, tol);
        REQUIRE(pts.size() > 4);
        for (std::size_t i = 1; i < pts.size(); ++i) {
            CHECK(std::hypot(pts[i].x, pts[i].y) == doctest::Approx(5.0));
            // the chord's midpoint is within the tolerance of the circle
            const Vec2 m{(pts[i].x + pts[i - 1].x) / 2, (pts[i].y + pts[i - 1].y) / 2};
            CHECK(5.0 - std::hypot(m.x, m.y) <= tol + 1e-12);
        }
    }
    CHECK(enclosed_area(c, 0.0001) == doctest::Approx(pi * 25).epsilon(1e-4));
}

TEST_CASE("profile: crossings, touching and zero-length segments are found") {
    // A bow tie: closed, crossing itself at (5, 5).
    Profile bow{ProfilePlane::xy, {0, 0}, {}};
    bow = line_to(bow, {10, 10});
    bow = line_to(bow, {10, 0});
    bow = line_to(bow, {0, 10});
    bow = line_to(bow, {0, 0});
    CHECK(is_closed(bow));
    CHECK_FALSE(is_simple(bow));

    // An open chain that crosses its first line.
    Profile open{ProfilePlane::xy, {0, 0}, {}};
    open = line_to(open, {10, 0});
    open = line_to(open, {10, 5});
    open = line_to(open, {5, -5});
    CHECK_FALSE(is_closed(open));
    CHECK_FALSE(is_simple(open));
    Profile ell{ProfilePlane::xy, {0, 0}, {}};
    ell = line_to(line_to(ell, {10, 0}), {10, 5});
    CHECK(is_simple(ell));
    // An open chain that touches its first line at (5, 0).
    Profile touch{ProfilePlane::xy, {0, 0}, {}};
    touch = line_to(line_to(line_to(touch, {10, 0}), {10, 5}), {5, 0});
    CHECK_FALSE(is_simple(touch));
    // An S of two tangent arcs turning opposite ways is simple, however finely sampled.
    Profile s{ProfilePlane::xy, {0, 0}, {}};
    s = arc_to(arc_to(s, {20, 0}, {10, 0}, ArcDirection::cw), {40, 0}, {30, 0}, ArcDirection::ccw);
    for (double tol : {0.1, 0.001, 0.0001}) CHECK(is_simple(s, tol));

    // An arc that bulges across the opposite side of a slot.
    Profile bulge{ProfilePlane::xy, {0, 0}, {}};
    bulge = line_to(bulge, {10, 0});
    bulge = line_to(bulge, {10, 2});
    bulge = arc_to(bulge, {0, 2}, {5, 2}, ArcDirection::cw);  // dips to y = -3, across the bottom line
    bulge = line_to(bulge, {0, 0});
    CHECK(is_closed(bulge));
    CHECK_FALSE(is_simple(bulge));

    Profile zero = plate();
    zero.segments.insert(zero.segments.begin() + 1, {Vec2{190, 0}, std::nullopt, ArcDirection::ccw});
    REQUIRE(first_short_segment(zero).has_value());
    CHECK(*first_short_segment(zero) == 1);
}

TEST_CASE("profile: rigid transforms keep arcs as arcs; a mirror turns their direction") {
    const Profile p = plate();
    Eigen::Isometry2d t = Eigen::Isometry2d::Identity();
    t.translate(Eigen::Vector2d(50, -20));
    t.rotate(Eigen::Rotation2Dd(pi / 6));
    const Profile moved = transformed(p, t);
    CHECK(is_closed(moved));
    CHECK(orientation(moved) == Orientation::ccw);
    CHECK(enclosed_area(moved) == doctest::Approx(enclosed_area(p)));
    CHECK(profile_length(moved) == doctest::Approx(profile_length(p)));
    // The corner arc's centre moved with it: its end is still 10 mm from it.
    const ProfileSegment& a = moved.segments[1];
    REQUIRE(a.centre.has_value());
    CHECK(std::hypot(a.end.x - a.centre->x, a.end.y - a.centre->y) == doctest::Approx(10.0));

    Eigen::Isometry2d mirror = Eigen::Isometry2d::Identity();
    mirror.linear() << -1, 0, 0, 1;
    const Profile m = transformed(p, mirror);
    CHECK(orientation(m) == Orientation::cw);
    CHECK(m.segments[1].direction == ArcDirection::cw);
    // Every sampled point of the mirror is the mirror of a sampled point.
    const auto a_pts = sample_profile(p, 0.01), b_pts = sample_profile(m, 0.01);
    REQUIRE(a_pts.size() == b_pts.size());
    for (std::size_t i = 0; i < a_pts.size(); ++i) {
        CHECK(b_pts[i].x == doctest::Approx(-a_pts[i].x));
        CHECK(b_pts[i].y == doctest::Approx(a_pts[i].y));
    }
}

}  // namespace test_profile
