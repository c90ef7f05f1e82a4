#include "src/geometry/curve.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "camgen/geometry/arc.hpp"

// The offset is built the classical way: every segment offset on its own (a line moved along
// its normal, an arc about its centre with the radius +- distance), an arc of the distance
// around every corner (turning with the tangent, so that at a concave corner it makes a small
// loop), then every piece split wherever it crosses another piece, the other side's offsets or
// a circle of the distance around a vertex. Between two such crossings a piece is either wholly
// at the distance from the profile or wholly closer, so a piece is kept when its midpoint is no
// closer than the distance; the kept pieces are chained end to start. That is the boundary of
// the region within the distance of the profile, on the chosen side: no gouge, loops gone.

namespace camgen::curves {

Curve line_curve(Vec2 a, Vec2 b) { return Curve{a, b, false, {}, 0.0, 0.0, 0.0}; }

Curve arc_curve(Vec2 c, double r, double a0, double sweep) {
    Curve k{{}, {}, true, c, r, a0, sweep};
    k.a = k.at(0.0);
    k.b = k.at(1.0);
    return k;
}

Curve part(const Curve& k, double t0, double t1) {
    if (k.arc) return arc_curve(k.c, k.r, k.a0 + k.sweep * t0, k.sweep * (t1 - t0));
    return line_curve(k.at(t0), k.at(t1));
}

Curve curve_of(const Profile& p, std::size_t index) {
    const ProfileSegment& s = p.segments[index];
    const Vec2 from = segment_start(p, index);
    if (!s.centre) return line_curve(from, s.end);
    const ArcGeometry g = resolve_arc({from.x, from.y, 0.0},
                                      ArcSpec{{s.end.x, s.end.y, 0.0}, {s.centre->x, s.centre->y, 0.0}, s.direction, Plane::xy, 0});
    Curve k = arc_curve(*s.centre, g.radius, g.start_angle, s.direction == ArcDirection::ccw ? g.sweep : -g.sweep);
    k.a = from;  // exactly where the profile is
    if (g.sweep < two_pi) k.b = s.end;
    return k;
}

std::vector<Curve> curves_of(const Profile& p, std::size_t index) {
    Curve k = curve_of(p, index);
    if (!k.arc || distance(k.at(1.0), k.b) <= same_length) return {k};
    const Vec2 given = k.b;
    k.b = k.at(1.0);
    return {k, line_curve(k.b, given)};
}

double parameter_of(const Curve& k, Vec2 p) {
    if (!k.arc) {
        const Vec2 d = k.b - k.a;
        return dot(p - k.a, d) / dot(d, d);
    }
    double delta = std::atan2(p.y - k.c.y, p.x - k.c.x) - k.a0;
    if (k.sweep < 0) delta = -delta;
    delta = std::fmod(delta, two_pi);
    if (delta < 0) delta += two_pi;
    const double s = std::abs(k.sweep);
    const double t = delta / s, before = (delta - two_pi) / s;
    return (t - 1.0 > -before) ? before : t;
}

TwoPoints support_crossings(const Curve& x, const Curve& y) {
    if (!x.arc && !y.arc) {
        const Vec2 dx = x.b - x.a, dy = y.b - y.a;
        const double den = cross(dx, dy);
        if (std::abs(den) <= 1e-12 * norm(dx) * norm(dy)) return {};
        return {{x.a + dx * (cross(y.a - x.a, dy) / den), {}}, 1};
    }
    if (x.arc != y.arc) {
        const Curve& line = x.arc ? y : x;
        const Curve& circle = x.arc ? x : y;
        const Vec2 d = line.b - line.a, f = line.a - circle.c;
        const double qa = dot(d, d), qb = 2.0 * dot(f, d), qc = dot(f, f) - circle.r * circle.r;
        double disc = qb * qb - 4.0 * qa * qc;
        if (disc < -1e-12 * qb * qb - 1e-18) return {};
        disc = std::sqrt(std::max(0.0, disc));
        return {{line.a + d * ((-qb - disc) / (2.0 * qa)), line.a + d * ((-qb + disc) / (2.0 * qa))}, 2};
    }
    const Vec2 between = y.c - x.c;
    const double dd = norm(between);
    if (dd < same_length) return {};  // concentric: they meet nowhere, or everywhere (the same circle)
    const double along = (dd * dd + x.r * x.r - y.r * y.r) / (2.0 * dd);
    double h2 = x.r * x.r - along * along;
    if (h2 < -1e-9 * x.r * x.r) return {};
    const double h = std::sqrt(std::max(0.0, h2));
    const Vec2 u = between * (1.0 / dd), foot = x.c + u * along;
    return {{foot + left_of(u) * h, foot - left_of(u) * h}, 2};
}

bool within(const Curve& k, double t) {
    const double slack = same_length / std::max(k.length(), same_length);
    return t >= -slack && t <= 1.0 + slack;
}

Rect box_of(const Curve& k) {
    Rect b{std::min(k.a.x, k.b.x), std::min(k.a.y, k.b.y), std::max(k.a.x, k.b.x), std::max(k.a.y, k.b.y)};
    if (!k.arc) return b;
    for (int quarter = 0; quarter < 4; ++quarter) {  // the extreme points the arc passes
        const Vec2 p = k.c + unit_at(quarter * pi / 2) * k.r;
        const double t = parameter_of(k, p);
        if (t < 0.0 || t > 1.0) continue;
        b = {std::min(b.x0, p.x), std::min(b.y0, p.y), std::max(b.x1, p.x), std::max(b.y1, p.y)};
    }
    return b;
}

bool apart(const Rect& a, const Rect& b) {
    constexpr double slack = 1e-6;
    return a.x1 + slack < b.x0 || b.x1 + slack < a.x0 || a.y1 + slack < b.y0 || b.y1 + slack < a.y0;
}

double box_distance(const Rect& b, Vec2 p) {
    return std::hypot(std::max({b.x0 - p.x, 0.0, p.x - b.x1}), std::max({b.y0 - p.y, 0.0, p.y - b.y1}));
}

BoxGrid::BoxGrid(std::vector<Rect> boxes) : boxes_(std::move(boxes)) {
    if (boxes_.empty()) return;
    extent_ = boxes_.front();
    for (const Rect& b : boxes_)
        extent_ = {std::min(extent_.x0, b.x0), std::min(extent_.y0, b.y0), std::max(extent_.x1, b.x1), std::max(extent_.y1, b.y1)};
    const double w = extent_.x1 - extent_.x0, h = extent_.y1 - extent_.y0;
    cell_ = std::max({std::sqrt(w * h / static_cast<double>(boxes_.size())), w / 512, h / 512, 1e-3});
    nx_ = static_cast<int>(w / cell_) + 1;
    ny_ = static_cast<int>(h / cell_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    seen_.assign(boxes_.size(), 0u);
    for (std::size_t i = 0; i < boxes_.size(); ++i) visit(boxes_[i], [&](std::size_t cell) { cells_[cell].push_back(i); });
}

std::vector<std::size_t> BoxGrid::near(const Rect& query) const {
    std::vector<std::size_t> out;
    if (boxes_.empty() || apart(query, extent_)) return out;
    // Each box once (a box spans several cells): a stamp per query rather than sorting the
    // duplicates away.
    if (++stamp_ == 0) {
        std::fill(seen_.begin(), seen_.end(), 0u);
        stamp_ = 1;
    }
    visit(query, [&](std::size_t cell) {
        for (std::size_t i : cells_[cell]) {
            if (seen_[i] == stamp_) continue;
            seen_[i] = stamp_;
            if (!apart(boxes_[i], query)) out.push_back(i);
        }
    });
    std::sort(out.begin(), out.end());
    return out;
}

template <class F>
void BoxGrid::visit(const Rect& b, F f) const {
    auto index = [&](double v, double origin, int n) { return std::clamp(static_cast<int>((v - origin) / cell_), 0, n - 1); };
    const int i0 = index(b.x0 - 1e-6, extent_.x0, nx_), i1 = index(b.x1 + 1e-6, extent_.x0, nx_);
    const int j0 = index(b.y0 - 1e-6, extent_.y0, ny_), j1 = index(b.y1 + 1e-6, extent_.y0, ny_);
    for (int i = i0; i <= i1; ++i)
        for (int j = j0; j <= j1; ++j) f(static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i));
}

bool opposed_lines(const Curve& x, const Curve& y) {
    if (x.arc || y.arc) return false;
    const Vec2 dx = x.b - x.a, dy = y.b - y.a;
    const double lx = norm(dx);
    return dot(dx, dy) < 0 && std::abs(cross(dx, y.a - x.a)) / lx <= min_piece && std::abs(cross(dx, y.b - x.a)) / lx <= min_piece;
}

TwoParameters crossings(const Curve& x, const Curve& y) {
    TwoParameters out;
    for (Vec2 p : support_crossings(x, y)) {
        const double tx = parameter_of(x, p), ty = parameter_of(y, p);
        if (within(x, tx) && within(y, ty)) out.t[out.n++] = tx;
    }
    return out;
}

double distance_to_curve(const Curve& k, Vec2 p) {
    const double t = parameter_of(k, p);
    if (t >= 0.0 && t <= 1.0) return k.arc ? std::abs(distance(p, k.c) - k.r) : distance(p, k.at(t));
    return std::min(distance(p, k.a), distance(p, k.b));
}

std::vector<Element> elements_of(const Profile& p, std::size_t loop) {
    std::vector<Element> out;
    for (std::size_t i = 0; i < p.segments.size(); ++i)
        for (const Curve& k : curves_of(p, i))
            if (k.length() > same_length) out.push_back({k, i, box_of(k), loop});
    return out;
}

bool closer_than(const std::vector<Element>& elements, const BoxGrid& grid, Vec2 p, double limit) {
    auto any_within = [&](double reach) {
        for (std::size_t i : grid.near({p.x - reach, p.y - reach, p.x + reach, p.y + reach}))
            if (box_distance(elements[i].box, p) < limit && distance_to_curve(elements[i].curve, p) < limit) return true;
        return false;
    };
    // The elements nearest p first (where a piece is closer, it mostly is to something near):
    // a large distance's box holds most of the elements.
    const double first = std::min(limit, grid.cell_size());
    return (first < limit && any_within(first)) || any_within(limit);
}

std::optional<Curve> offset_curve(const Curve& k, double d, double s) {
    if (!k.arc) {
        const Vec2 n = left_of(k.tangent(0.0)) * (s * d);
        return line_curve(k.a + n, k.b + n);
    }
    const double r = k.r - d * s * (k.sweep > 0 ? 1.0 : -1.0);
    if (std::abs(r) <= same_length) return std::nullopt;
    return arc_curve(k.c, std::abs(r), r < 0 ? k.a0 + pi : k.a0, k.sweep);
}

std::optional<Curve> corner_curve(const Curve& in, const Curve& out, double d, double s) {
    const Vec2 t1 = in.tangent(1.0), t2 = out.tangent(0.0);
    double turn = std::atan2(cross(t1, t2), dot(t1, t2));
    if (std::abs(turn) * d <= same_length) return std::nullopt;
    if (pi - std::abs(turn) <= 1e-9) turn = -s * pi;
    const Vec2 n1 = left_of(t1) * s;
    return arc_curve(in.b, d, std::atan2(n1.y, n1.x), turn);
}

OffsetPieces offset_pieces(const std::vector<Element>& elements, const std::vector<LoopSpan>& loops, double d, double s) {
    OffsetPieces out;
    std::vector<RawPiece>& raw = out.raw;
    // The raw offset: each element's offset, and a corner arc after it.
    for (const LoopSpan& loop : loops)
        for (std::size_t i = loop.begin; i < loop.end; ++i) {
            const Curve& k = elements[i].curve;
            if (auto o = offset_curve(k, d, s)) raw.push_back({*o, i});
            if (i + 1 < loop.end || loop.closed)
                if (auto c = corner_curve(k, elements[i + 1 < loop.end ? i + 1 : loop.begin].curve, d, s)) raw.push_back({*c, std::nullopt});
        }

    // What may cut a raw piece besides the other raw pieces: the other side's offsets and a
    // circle of radius d around every vertex (at an open profile's ends, its end caps).
    std::vector<Curve> cutters;
    for (const Element& e : elements) {
        if (auto o = offset_curve(e.curve, d, -s)) cutters.push_back(*o);
        cutters.push_back(arc_curve(e.curve.a, d, 0.0, two_pi));
    }
    for (const LoopSpan& loop : loops)
        if (loop.end > loop.begin && !loop.closed) cutters.push_back(arc_curve(elements[loop.end - 1].curve.b, d, 0.0, two_pi));
    // Raw pieces and cutters in one grid: indices below raw.size() are raw pieces.
    std::vector<Rect> boxes;
    for (const RawPiece& r : raw) boxes.push_back(box_of(r.curve));
    for (const Curve& c : cutters) boxes.push_back(box_of(c));
    const BoxGrid curves(boxes);
    std::vector<Rect> element_boxes;
    for (const Element& e : elements) element_boxes.push_back(e.box);
    const BoxGrid element_grid(element_boxes);

    for (std::size_t i = 0; i < raw.size(); ++i) {
        const Curve& k = raw[i].curve;
        std::vector<double> ts{0.0, 1.0};
        auto add = [&](const Curve& other) {
            if (k.arc && other.arc && distance(k.c, other.c) < same_length && std::abs(k.r - other.r) < same_length) return;
            for (double t : crossings(k, other)) ts.push_back(std::clamp(t, 0.0, 1.0));
        };
        // Where another raw line runs back along this one, this one is cut at its ends.
        std::vector<const Curve*> opposed;
        for (std::size_t j : curves.near(boxes[i])) {
            if (j == i) continue;
            if (j >= raw.size()) {
                add(cutters[j - raw.size()]);
                continue;
            }
            add(raw[j].curve);
            if (!opposed_lines(k, raw[j].curve)) continue;
            opposed.push_back(&raw[j].curve);
            for (Vec2 end : {raw[j].curve.a, raw[j].curve.b}) ts.push_back(std::clamp(parameter_of(k, end), 0.0, 1.0));
        }
        std::sort(ts.begin(), ts.end());
        const double step = same_length / std::max(k.length(), same_length);
        std::vector<double> cuts{0.0};
        for (double t : ts)
            if (t - cuts.back() > step) cuts.push_back(t);
        if (1.0 - cuts.back() <= step) cuts.back() = 1.0;
        else cuts.push_back(1.0);
        for (std::size_t j = 0; j + 1 < cuts.size(); ++j) {
            const Curve piece = part(k, cuts[j], cuts[j + 1]);
            const Vec2 mid = piece.at(0.5);
            // (the margin is far below what a near-tangent joint's pieces come closer: a turn
            // of 1e-4 rad brings them d 1e-9 closer; rounding is some 1e-13 mm)
            if (closer_than(elements, element_grid, mid, d - 1e-11)) continue;
            // Two walls exactly the tool's width apart: their offsets coincide, walked opposite
            // ways; the zero-width strip between them is no path.
            if (std::any_of(opposed.begin(), opposed.end(), [&](const Curve* o) {
                    const double t = parameter_of(*o, mid);
                    return t > 0.0 && t < 1.0;
                }))
                continue;
            out.kept.push_back({i, cuts[j], cuts[j + 1], piece});
        }
    }
    return out;
}

std::string mm_text(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, std::round(v * 1000.0) / 1000.0);
    return std::string(buf, r.ptr);
}

std::vector<std::vector<std::size_t>> chain(const std::vector<KeptPiece>& kept) {
    std::vector<bool> used(kept.size(), false);
    std::vector<std::vector<std::size_t>> chains;
    for (std::size_t first = 0; first < kept.size(); ++first) {
        if (used[first]) continue;
        std::vector<std::size_t> c{first};
        used[first] = true;
        for (;;) {
            const Vec2 end = kept[c.back()].curve.b;
            const std::size_t next = c.back() + 1;
            if (next < kept.size() && !used[next] && distance(kept[next].curve.a, end) <= chain_gap) {
                c.push_back(next);
                used[next] = true;
                continue;
            }
            if (distance(kept[c.front()].curve.a, end) <= chain_gap) break;
            std::optional<std::size_t> best;
            for (std::size_t j = 0; j < kept.size(); ++j)
                if (!used[j] && distance(kept[j].curve.a, end) <= chain_gap &&
                    (!best || distance(kept[j].curve.a, end) < distance(kept[*best].curve.a, end)))
                    best = j;
            if (!best) break;
            c.push_back(*best);
            used[*best] = true;
        }
        chains.push_back(std::move(c));
    }
    // Open chains that continue one another are one chain.
    for (bool joined = true; joined;) {
        joined = false;
        for (std::size_t i = 0; i < chains.size() && !joined; ++i)
            for (std::size_t j = 0; j < chains.size() && !joined; ++j) {
                if (i == j) continue;
                const Vec2 end = kept[chains[i].back()].curve.b;
                if (distance(kept[chains[i].front()].curve.a, end) <= chain_gap) continue;  // closed
                if (distance(kept[chains[j].front()].curve.a, end) > chain_gap) continue;
                chains[i].insert(chains[i].end(), chains[j].begin(), chains[j].end());
                chains.erase(chains.begin() + static_cast<std::ptrdiff_t>(j));
                joined = true;
            }
    }
    return chains;
}

OffsetPath path_of(const std::vector<std::size_t>& c, const std::vector<KeptPiece>& kept, const std::vector<RawPiece>& raw,
                   const std::vector<Element>& elements, ProfilePlane plane, bool closed) {
    std::vector<KeptPiece> merged;
    for (std::size_t i : c) {
        const KeptPiece& k = kept[i];
        if (!merged.empty() && merged.back().raw == k.raw && std::abs(merged.back().t1 - k.t0) < 1e-12) {
            merged.back().t1 = k.t1;
            merged.back().curve = part(raw[k.raw].curve, merged.back().t0, k.t1);
        } else {
            merged.push_back(k);
        }
    }
    OffsetPath path{Profile{plane, merged.front().curve.a, {}}, {}, 0.0};
    for (const KeptPiece& k : merged) {
        if (k.curve.length() < min_piece) continue;
        ProfileSegment s{k.curve.b, std::nullopt, ArcDirection::ccw};
        if (k.curve.arc) {
            s.centre = k.curve.c;
            s.direction = k.curve.sweep > 0 ? ArcDirection::ccw : ArcDirection::cw;
        }
        const auto& e = raw[k.raw].element;
        path.profile.segments.push_back(s);
        path.source.push_back(e ? std::optional<std::size_t>(elements[*e].segment) : std::nullopt);
    }
    if (closed && !path.profile.segments.empty()) path.profile.segments.back().end = path.profile.start;
    path.length = profile_length(path.profile);
    return path;
}

}  // namespace camgen::curves
