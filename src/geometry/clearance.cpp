#include "camgen/geometry/clearance.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace camgen {

namespace {

// Ends of an arc at most this far apart: a full circle, mm.
constexpr double full_circle_ends = 1e-12;

double wrap(double a) {
    a = std::fmod(a, two_pi);
    return a < 0 ? a + two_pi : a;
}

// An arc resolved: centre, radius, start angle and signed sweep (ccw positive).
struct ArcData {
    Vec2 c;
    double r = 0;
    double a0 = 0;
    double sweep = 0;
};

ArcData compute_arc(const PathPiece& p);

// The arc of a piece, remembering the last one asked (a move is asked against many segments).
ArcData arc_of(const PathPiece& p) {
    thread_local PathPiece last_piece;
    thread_local ArcData last;
    thread_local bool valid = false;
    if (valid && last_piece.start == p.start && last_piece.segment == p.segment) return last;
    last = compute_arc(p);
    last_piece = p;
    valid = true;
    return last;
}

ArcData compute_arc(const PathPiece& p) {
    ArcData a;
    a.c = *p.segment.centre;
    a.r = norm(p.start - a.c);
    a.a0 = std::atan2(p.start.y - a.c.y, p.start.x - a.c.x);
    const double a1 = std::atan2(p.segment.end.y - a.c.y, p.segment.end.x - a.c.x);
    // Ends that coincide make a full circle (a helix's turn); see as_piece for ends a hair apart.
    const bool full = norm(p.segment.end - p.start) <= full_circle_ends;
    a.sweep = p.segment.direction == ArcDirection::ccw ? (full ? two_pi : wrap(a1 - a.a0)) : -(full ? two_pi : wrap(a.a0 - a1));
    return a;
}

// An arc whose ends are closer than profile_same_point but not the same point (a convex corner
// of an offset that turns by almost nothing) is taken as the straight line between its ends: its
// turning is below what the numbers can tell, and read as a full circle it would sweep the whole
// circle round the corner.
PathPiece as_piece(const PathPiece& p) {
    if (!p.segment.centre) return p;
    const double d = norm(p.segment.end - p.start);
    if (d > full_circle_ends && d < profile_same_point) return {p.start, {p.segment.end, std::nullopt, p.segment.direction}};
    return p;
}

bool in_sweep(const ArcData& a, double angle) {
    if (a.sweep >= 0) return wrap(angle - a.a0) <= a.sweep + 1e-12;
    return wrap(a.a0 - angle) <= -a.sweep + 1e-12;
}

Vec2 on_circle(const ArcData& a, double angle) { return {a.c.x + a.r * std::cos(angle), a.c.y + a.r * std::sin(angle)}; }

ClosestApproach point_line(Vec2 p, Vec2 s, Vec2 e) {
    const Vec2 d = e - s;
    const double l2 = dot(d, d);
    double t = l2 > 0 ? dot((p - s), d) / l2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const Vec2 q = s + (d * t);
    return {norm(p - q), q};
}

ClosestApproach point_arc(Vec2 p, const ArcData& a, Vec2 s, Vec2 e) {
    const Vec2 v = p - a.c;
    const double d = norm(v);
    if (d < 1e-12) return {a.r, s};
    const double ang = std::atan2(v.y, v.x);
    if (in_sweep(a, ang)) return {std::abs(d - a.r), (a.c + (v * (a.r / d)))};
    const double ds = norm(p - s), de = norm(p - e);
    return ds <= de ? ClosestApproach{ds, s} : ClosestApproach{de, e};
}

// Keeps the smaller of two approaches.
void keep(ClosestApproach& best, ClosestApproach c) {
    if (c.distance < best.distance) best = c;
}

// Points where the line s-e (t in [0, 1]) meets the circle of `a` within its sweep.
int line_circle(Vec2 s, Vec2 e, const ArcData& a, std::array<Vec2, 2>& out) {
    const Vec2 d = (e - s), f = s - a.c;
    const double A = dot(d, d), B = 2 * dot(f, d), C = dot(f, f) - a.r * a.r;
    if (A <= 0) return 0;
    const double disc = B * B - 4 * A * C;
    if (disc < 0) return 0;
    const double sq = std::sqrt(disc);
    int n = 0;
    for (double t : {(-B - sq) / (2 * A), (-B + sq) / (2 * A)}) {
        if (t < 0 || t > 1) continue;
        const Vec2 q = s + (d * t);
        if (in_sweep(a, std::atan2(q.y - a.c.y, q.x - a.c.x))) out[n++] = q;
        if (sq == 0) break;
    }
    return n;
}

}  // namespace

ClosestApproach point_piece_distance(Vec2 p, const PathPiece& given) {
    const PathPiece piece = as_piece(given);
    if (!piece.segment.centre) return point_line(p, piece.start, piece.segment.end);
    return point_arc(p, arc_of(piece), piece.start, piece.segment.end);
}

ClosestApproach piece_distance(const PathPiece& given_a, const PathPiece& given_b) {
    const PathPiece a = as_piece(given_a), b = as_piece(given_b);
    const Vec2 as = a.start, ae = a.segment.end, bs = b.start, be = b.segment.end;
    ClosestApproach best{std::numeric_limits<double>::infinity(), as};
    // Ends of a against b, ends of b against a.
    keep(best, {point_piece_distance(as, b).distance, as});
    keep(best, {point_piece_distance(ae, b).distance, ae});
    {
        const ClosestApproach x = point_piece_distance(bs, a);
        keep(best, {x.distance, x.at});
        const ClosestApproach y = point_piece_distance(be, a);
        keep(best, {y.distance, y.at});
    }
    const bool a_arc = a.segment.centre.has_value(), b_arc = b.segment.centre.has_value();
    if (!a_arc && !b_arc) {
        const Vec2 r = (ae - as), s = be - bs;
        const double den = cross(r, s);
        if (den != 0) {
            const double t = cross((bs - as), s) / den, u = cross((bs - as), r) / den;
            if (t >= 0 && t <= 1 && u >= 0 && u <= 1) keep(best, {0.0, (as + (r * t))});
        }
        return best;
    }
    if (a_arc != b_arc) {
        const PathPiece& line = a_arc ? b : a;
        const PathPiece& arcp = a_arc ? a : b;
        const ArcData c = arc_of(arcp);
        std::array<Vec2, 2> hits{};
        const int n = line_circle(line.start, line.segment.end, c, hits);
        if (n > 0) return {0.0, hits[0]};
        // The arc's points square to the line from its centre.
        const ClosestApproach foot = point_line(c.c, line.start, line.segment.end);
        const Vec2 v = foot.at - c.c;
        if (foot.distance > 1e-12) {
            for (double sign : {1.0, -1.0}) {
                const double ang = std::atan2(sign * v.y, sign * v.x);
                if (!in_sweep(c, ang)) continue;
                const Vec2 q = on_circle(c, ang);
                const ClosestApproach onto_line = point_line(q, line.start, line.segment.end);
                keep(best, {onto_line.distance, a_arc ? q : onto_line.at});
            }
        }
        return best;
    }
    const ArcData ca = arc_of(a), cb = arc_of(b);
    const Vec2 cc = cb.c - ca.c;
    const double dcc = norm(cc);
    if (dcc > 1e-12) {
        // Circle-circle crossings within both sweeps.
        if (dcc <= ca.r + cb.r && dcc >= std::abs(ca.r - cb.r)) {
            const double x = (dcc * dcc + ca.r * ca.r - cb.r * cb.r) / (2 * dcc);
            const double h = std::sqrt(std::max(0.0, ca.r * ca.r - x * x));
            const Vec2 u = (cc * (1 / dcc)), n{-u.y, u.x};
            for (double sign : {1.0, -1.0}) {
                const Vec2 q = (ca.c + (u * x)) + (n * (sign * h));
                if (in_sweep(ca, std::atan2(q.y - ca.c.y, q.x - ca.c.x)) && in_sweep(cb, std::atan2(q.y - cb.c.y, q.x - cb.c.x)))
                    return {0.0, q};
            }
        }
        // The points on the line of centres.
        const double base = std::atan2(cc.y, cc.x);
        for (double pa : {base, base + pi}) {
            if (!in_sweep(ca, pa)) continue;
            const Vec2 qa = on_circle(ca, pa);
            for (double pb : {base, base + pi}) {
                if (!in_sweep(cb, pb)) continue;
                keep(best, {norm(qa - on_circle(cb, pb)), qa});
            }
        }
    }
    return best;
}

ProfileClearance::ProfileClearance(const Profile& profile, double reach) : reach_(reach) {
    Vec2 from = profile.start;
    pieces_.reserve(profile.segments.size());
    double x0 = from.x, y0 = from.y, x1 = from.x, y1 = from.y;
    auto grow = [&](Vec2 p) {
        x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    };
    std::vector<std::array<double, 4>>& boxes = boxes_;
    boxes.reserve(profile.segments.size());
    for (const ProfileSegment& s : profile.segments) {
        const PathPiece p = as_piece(PathPiece{from, s});
        double bx0 = std::min(from.x, s.end.x), by0 = std::min(from.y, s.end.y), bx1 = std::max(from.x, s.end.x),
               by1 = std::max(from.y, s.end.y);
        if (p.segment.centre) {
            const ArcData a = arc_of(p);
            for (double ang : {0.0, pi / 2, pi, 3 * pi / 2})
                if (in_sweep(a, ang)) {
                    const Vec2 q = on_circle(a, ang);
                    bx0 = std::min(bx0, q.x), by0 = std::min(by0, q.y), bx1 = std::max(bx1, q.x), by1 = std::max(by1, q.y);
                }
        }
        grow({bx0, by0});
        grow({bx1, by1});
        boxes.push_back({bx0, by0, bx1, by1});
        pieces_.push_back(p);
        from = s.end;
    }
    const double w = x1 - x0 + 2 * reach, h = y1 - y0 + 2 * reach;
    const double n = static_cast<double>(std::max<std::size_t>(pieces_.size(), 1));
    cell_ = std::max({std::sqrt(std::max(w * h, 1e-12) / (2 * n)), reach / 2, 1e-3});
    x0_ = x0 - reach;
    y0_ = y0 - reach;
    nx_ = static_cast<std::size_t>(std::min(w / cell_ + 1, 1e6));
    ny_ = static_cast<std::size_t>(std::min(h / cell_ + 1, 1e6));
    while (static_cast<double>(nx_) * static_cast<double>(ny_) > 4 * n + 64) {
        cell_ *= 1.5;
        nx_ = static_cast<std::size_t>(w / cell_ + 1);
        ny_ = static_cast<std::size_t>(h / cell_ + 1);
    }
    grid_.assign(nx_ * ny_, {});
    seen_.assign(pieces_.size(), 0u);
    for (std::size_t k = 0; k < pieces_.size(); ++k)
        for (std::size_t c : cells_of(boxes[k][0], boxes[k][1], boxes[k][2], boxes[k][3])) grid_[c].push_back(k);
}

std::vector<std::size_t> ProfileClearance::cells_of(double x0, double y0, double x1, double y1) const {
    auto ix = [&](double x) { return static_cast<std::size_t>(std::clamp((x - x0_) / cell_, 0.0, static_cast<double>(nx_ - 1))); };
    auto iy = [&](double y) { return static_cast<std::size_t>(std::clamp((y - y0_) / cell_, 0.0, static_cast<double>(ny_ - 1))); };
    std::vector<std::size_t> out;
    for (std::size_t j = iy(y0); j <= iy(y1); ++j)
        for (std::size_t i = ix(x0); i <= ix(x1); ++i) out.push_back(j * nx_ + i);
    return out;
}

ClosestApproach ProfileClearance::nearest(const PathPiece& given) const {
    const PathPiece move = as_piece(given);
    double bx0 = std::min(move.start.x, move.segment.end.x), by0 = std::min(move.start.y, move.segment.end.y),
           bx1 = std::max(move.start.x, move.segment.end.x), by1 = std::max(move.start.y, move.segment.end.y);
    if (move.segment.centre) {
        const ArcData a = arc_of(move);
        for (double ang : {0.0, pi / 2, pi, 3 * pi / 2})
            if (in_sweep(a, ang)) {
                const Vec2 q = on_circle(a, ang);
                bx0 = std::min(bx0, q.x), by0 = std::min(by0, q.y), bx1 = std::max(bx1, q.x), by1 = std::max(by1, q.y);
            }
    }
    ClosestApproach best{reach_, move.start};
    const bool point = norm(move.segment.end - move.start) == 0 && !move.segment.centre;
    ++stamp_;
    if (stamp_ == 0) {
        std::fill(seen_.begin(), seen_.end(), 0u);
        stamp_ = 1;
    }
    auto ix = [&](double x) { return static_cast<std::size_t>(std::clamp((x - x0_) / cell_, 0.0, static_cast<double>(nx_ - 1))); };
    auto iy = [&](double y) { return static_cast<std::size_t>(std::clamp((y - y0_) / cell_, 0.0, static_cast<double>(ny_ - 1))); };
    const std::size_t i0 = ix(bx0 - reach_), i1 = ix(bx1 + reach_), j0 = iy(by0 - reach_), j1 = iy(by1 + reach_);
    for (std::size_t j = j0; j <= j1; ++j)
        for (std::size_t i = i0; i <= i1; ++i)
            for (std::size_t k : grid_[j * nx_ + i]) {
                if (seen_[k] == stamp_) continue;
                seen_[k] = stamp_;
                // A segment whose box is no nearer than the best so far cannot be nearer.
                const auto& b = boxes_[k];
                const double gx = std::max({0.0, b[0] - bx1, bx0 - b[2]}), gy = std::max({0.0, b[1] - by1, by0 - b[3]});
                if (std::hypot(gx, gy) >= best.distance) continue;
                const ClosestApproach a = point ? ClosestApproach{point_piece_distance(move.start, pieces_[k]).distance, move.start}
                                         : piece_distance(move, pieces_[k]);
                keep(best, a);
            }
    return best;
}

ClosestApproach ProfileClearance::nearest(Vec2 point) const { return nearest(PathPiece{point, {point, std::nullopt, ArcDirection::ccw}}); }

bool ProfileClearance::inside(Vec2 p) const {
    bool in = false;
    // A crossing of the ray from p towards +x by a piece monotone in y, counted half-open.
    auto line_crossing = [&](Vec2 s, Vec2 e) {
        if ((s.y > p.y) != (e.y > p.y)) {
            const double x = s.x + (p.y - s.y) * (e.x - s.x) / (e.y - s.y);
            if (x > p.x) in = !in;
        }
    };
    for (const PathPiece& piece : pieces_) {
        if (!piece.segment.centre) {
            line_crossing(piece.start, piece.segment.end);
            continue;
        }
        // Split the arc at its top and bottom into pieces monotone in y.
        const ArcData a = arc_of(piece);
        std::vector<double> cuts{a.a0};
        const double step = a.sweep >= 0 ? 1.0 : -1.0;
        std::vector<double> extremes;
        for (double base : {pi / 2, 3 * pi / 2})
            for (int m = 0; m < 3; ++m) {
                const double ang = base + m * two_pi;
                const double off = step > 0 ? wrap(ang - a.a0) : wrap(a.a0 - ang);
                if (off > 1e-12 && off < std::abs(a.sweep) - 1e-12 && std::find(extremes.begin(), extremes.end(), off) == extremes.end())
                    extremes.push_back(off);
            }
        std::sort(extremes.begin(), extremes.end());
        for (double off : extremes) cuts.push_back(a.a0 + step * off);
        cuts.push_back(a.a0 + a.sweep);
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
            const Vec2 s = k == 0 ? piece.start : on_circle(a, cuts[k]);
            const Vec2 e = k + 2 == cuts.size() ? piece.segment.end : on_circle(a, cuts[k + 1]);
            if ((s.y > p.y) == (e.y > p.y)) continue;
            const double mid = (cuts[k] + cuts[k + 1]) / 2;
            const double dy = p.y - a.c.y;
            const double x = a.c.x + (std::cos(mid) >= 0 ? 1 : -1) * std::sqrt(std::max(0.0, a.r * a.r - dy * dy));
            if (x > p.x) in = !in;
        }
    }
    return in;
}

}  // namespace camgen
