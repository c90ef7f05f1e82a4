#include "camgen/geometry/region.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/clearance.hpp"
#include "src/geometry/curve.hpp"

// A region offset is the profile offset's algorithm (src/geometry/curve.hpp) over all its
// loops at once, each walked with the region on its left: the raw offsets of every loop to the
// left (shrinking) or right (growing), split at their crossings with one another and with what
// is at the distance from any loop, kept where no closer than the distance to any loop (and,
// a safety net, on the region's side by an inside test), chained into closed loops (a chain that
// a crumb of pieces at a joint leads past its start gives the loop it holds; a spike a hair long
// is cut off). A loop of the result turning counter-clockwise bounds a region from outside, one
// turning clockwise a hole; each hole belongs to the smallest loop around it (the nesting, by an
// exact inside test: a ray's crossings with lines and arcs, counted half-open).

namespace camgen::region_impl {

using curves::Curve;
using curves::Element;
using curves::KeptPiece;
using curves::LoopSpan;
using curves::mm_text;
using curves::Rect;

// Segments with less than this between them along their loop meet at a joint (they may come
// closer than region_touch there, and do not touch for that), mm.
constexpr double joint_slack = 2.5 * arc_radius_tolerance;

// The name of loop `loop` of a region (0 the outline, 1 + i island i) in a message.
std::string loop_name(std::size_t loop) { return loop == 0 ? "the outline" : "island " + std::to_string(loop - 1); }

std::vector<const Profile*> loops_of(const PlaneRegion& region) {
    std::vector<const Profile*> loops{&region.outer};
    for (const Profile& island : region.islands) loops.push_back(&island);
    return loops;
}

// The loop's curves (zero-length segments left out) joined end to start exactly, so that a
// ray's crossings at the joints are counted consistently.
std::vector<Curve> closed_curves(const Profile& p) {
    std::vector<Curve> out;
    for (std::size_t i = 0; i < p.segments.size(); ++i)
        for (const Curve& k : curves::curves_of(p, i))
            if (k.length() > curves::same_length) out.push_back(k);
    for (std::size_t i = 0; i < out.size(); ++i) out[i].a = out[i == 0 ? out.size() - 1 : i - 1].b;
    return out;
}

// The signed area a closed chain of curves encloses (counter-clockwise positive),
// by Green's theorem: a line adds cross(a, b) / 2, an arc about c of radius r and signed sweep
// w adds (cross(c, b - a) + r^2 w) / 2.
double signed_area(const std::vector<Curve>& curves) {
    double twice = 0.0;
    for (const Curve& k : curves) twice += k.arc ? cross(k.c, k.b - k.a) + k.r * k.r * k.sweep : cross(k.a, k.b);
    return twice / 2.0;
}

// A piece of a loop monotone in y: a line, or a part of an arc within a half circle (its
// points at x = c.x + side sqrt(r^2 - (y - c.y)^2)).
struct YPiece {
    Vec2 s, e;
    bool arc = false;
    Vec2 c;
    double r = 0.0, side = 1.0;
};

void add_y_pieces(const Curve& k, std::vector<YPiece>& out) {
    if (!k.arc) {
        out.push_back({k.a, k.b, false, {}, 0.0, 1.0});
        return;
    }
    // Cut at the top and bottom of the circle (angles pi/2 + m pi) that the arc passes.
    std::vector<double> ts{0.0};
    const double dir = k.sweep > 0 ? 1.0 : -1.0;
    const double first = dir > 0 ? pi / 2 + pi * std::floor((k.a0 - pi / 2) / pi + 1.0) : pi / 2 + pi * std::ceil((k.a0 - pi / 2) / pi - 1.0);
    for (double angle = first;; angle += dir * pi) {
        const double t = (angle - k.a0) / k.sweep;
        if (t >= 1.0) break;
        if (t > 1e-12) ts.push_back(t);
    }
    ts.push_back(1.0);
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
        const double mid = k.a0 + k.sweep * (ts[i] + ts[i + 1]) / 2;
        out.push_back({ts[i] == 0.0 ? k.a : k.at(ts[i]), ts[i + 1] == 1.0 ? k.b : k.at(ts[i + 1]), true, k.c, k.r,
                       std::cos(mid) >= 0 ? 1.0 : -1.0});
    }
}

// True when the piece crosses the line at height y, counted half-open (an end exactly at y
// counts as below it), so that a closed loop crosses any line an even number of times.
bool crosses_row(const YPiece& p, double y) { return (p.s.y > y) != (p.e.y > y); }

// Where a piece that crosses the line at height y does.
double x_at(const YPiece& p, double y) {
    if (!p.arc) return std::clamp(p.s.x + (y - p.s.y) * (p.e.x - p.s.x) / (p.e.y - p.s.y), std::min(p.s.x, p.e.x), std::max(p.s.x, p.e.x));
    const double dy = y - p.c.y;
    return p.c.x + p.side * std::sqrt(std::max(0.0, p.r * p.r - dy * dy));
}

std::vector<YPiece> y_pieces(const std::vector<Curve>& curves) {
    std::vector<YPiece> out;
    for (const Curve& k : curves) add_y_pieces(k, out);
    return out;
}

// p inside the closed loop of these pieces (even-odd; a point on it may go either way).
bool inside_pieces(const std::vector<YPiece>& pieces, Vec2 p) {
    bool in = false;
    for (const YPiece& piece : pieces)
        if (crosses_row(piece, p.y) && x_at(piece, p.y) > p.x) in = !in;
    return in;
}

Rect box_of_curves(const std::vector<Curve>& curves) {
    Rect b{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity()};
    for (const Curve& k : curves) {
        const Rect r = curves::box_of(k);
        b = {std::min(b.x0, r.x0), std::min(b.y0, r.y0), std::max(b.x1, r.x1), std::max(b.y1, r.y1)};
    }
    return b;
}

bool box_within(const Rect& inner, const Rect& outer) {
    constexpr double slack = 1e-9;
    return inner.x0 >= outer.x0 - slack && inner.y0 >= outer.y0 - slack && inner.x1 <= outer.x1 + slack && inner.y1 <= outer.y1 + slack;
}

// The loop's lowest point, the leftmost of equals: the order of results.
Vec2 lowest_point(const std::vector<Curve>& curves) {
    Vec2 best{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    auto consider = [&](Vec2 p) {
        if (p.y < best.y || (p.y == best.y && p.x < best.x)) best = p;
    };
    for (const Curve& k : curves) {
        consider(k.a);
        consider(k.b);
        if (!k.arc) continue;
        const Vec2 bottom{k.c.x, k.c.y - k.r};
        const double t = curves::parameter_of(k, bottom);
        if (t > 0.0 && t < 1.0) consider(bottom);
    }
    return best;
}

// A point on the loop away from its joints: the middle of its longest curve.
Vec2 probe_of(const std::vector<Curve>& curves) {
    const auto longest = std::max_element(curves.begin(), curves.end(), [](const Curve& a, const Curve& b) { return a.length() < b.length(); });
    return longest->at(0.5);
}

// A curve as clearance.hpp's piece, for its exact distances.
PathPiece piece_of(const Curve& k) {
    ProfileSegment s{k.b, std::nullopt, ArcDirection::ccw};
    if (k.arc) {
        s.centre = k.c;
        s.direction = k.sweep > 0 ? ArcDirection::ccw : ArcDirection::cw;
    }
    return {k.a, s};
}

std::string point_text(Vec2 p) { return "(" + mm_text(p.x) + ", " + mm_text(p.y) + ")"; }

// One loop walked with the region on its left (an outline counter-clockwise, an island
// clockwise).
Profile normal_loop(const Profile& p, bool outer) { return (signed_area(closed_curves(p)) >= 0.0) == outer ? p : reversed(p); }

// The curve walked the other way.
Curve reversed_curve(const Curve& k) {
    Curve r = k;
    std::swap(r.a, r.b);
    if (k.arc) {
        r.a0 = k.a0 + k.sweep;
        r.sweep = -k.sweep;
    }
    return r;
}

// The even-odd inside test of inside_pieces over many pieces, for many points: the pieces
// bucketed in horizontal bands, so that a point looks at those of its band only.
class InsideTest {
public:
    explicit InsideTest(std::vector<YPiece> pieces) : pieces_(std::move(pieces)) {
        if (pieces_.empty()) return;
        y0_ = std::numeric_limits<double>::infinity();
        double y1 = -y0_;
        for (const YPiece& p : pieces_) y0_ = std::min({y0_, p.s.y, p.e.y}), y1 = std::max({y1, p.s.y, p.e.y});
        // About four pieces a band, but no more bands than keep the entries (a piece in each
        // band it spans) below eight a piece.
        double spans = 0.0;
        for (const YPiece& p : pieces_) spans += std::abs(p.e.y - p.s.y) / std::max(y1 - y0_, 1e-9);
        const double most = 7.0 * static_cast<double>(pieces_.size()) / std::max(spans, 1e-9);
        bands_.resize(static_cast<std::size_t>(std::clamp(std::min(most, static_cast<double>(pieces_.size() / 4)), 1.0, 1e6)));
        height_ = std::max((y1 - y0_) / static_cast<double>(bands_.size()), 1e-9);
        for (std::size_t i = 0; i < pieces_.size(); ++i) {
            const YPiece& p = pieces_[i];
            for (std::size_t b = band(std::min(p.s.y, p.e.y)); b <= band(std::max(p.s.y, p.e.y)); ++b) bands_[b].push_back(i);
        }
    }
    bool operator()(Vec2 p) const {
        if (pieces_.empty()) return false;
        bool in = false;
        for (std::size_t i : bands_[band(p.y)])
            if (crosses_row(pieces_[i], p.y) && x_at(pieces_[i], p.y) > p.x) in = !in;
        return in;
    }

private:
    std::size_t band(double y) const {
        const double b = std::floor((y - y0_) / height_);
        return static_cast<std::size_t>(std::clamp(b, 0.0, static_cast<double>(bands_.size() - 1)));
    }
    std::vector<YPiece> pieces_;
    std::vector<std::vector<std::size_t>> bands_;
    double y0_ = 0.0, height_ = 1.0;
};

// An offset region loop with what the nesting asks of it.
struct OutLoop {
    Profile profile;
    std::vector<Curve> curves;
    std::vector<YPiece> pieces;
    double area = 0.0;  // signed
    Rect box{};
    Vec2 probe, lowest;
};

bool lower_first(Vec2 a, Vec2 b) { return a.y < b.y || (a.y == b.y && a.x < b.x); }

bool full_circle(const Curve& k) { return k.arc && std::abs(k.sweep) >= two_pi; }

// True when kept piece `next` continues `prev` along the same raw piece (cut between them where
// nothing changed, or across the start of a raw full circle).
bool continues(const KeptPiece& prev, const KeptPiece& next, const std::vector<curves::RawPiece>& raw) {
    if (prev.raw != next.raw) return false;
    return std::abs(prev.t1 - next.t0) < 1e-12 || (full_circle(raw[prev.raw].curve) && prev.t1 == 1.0 && next.t0 == 0.0);
}

// Spikes no longer than this are cut off a loop, mm.
constexpr double spike_length = 1e-5;

// `k` with its start (or end) moved to p, a point on or within a hair of its support (an arc
// keeps its centre and radius, its sweep following).
Curve moved_end(const Curve& k, Vec2 p, bool start) {
    Curve m = k;
    if (k.arc) {
        double delta = std::atan2(p.y - k.c.y, p.x - k.c.x) - (start ? k.a0 : k.a0 + k.sweep);
        delta = std::remainder(delta, two_pi);
        if (start) {
            m.a0 = k.a0 + delta;
            m.sweep = k.sweep - delta;
        } else {
            m.sweep = k.sweep + delta;
        }
    }
    (start ? m.a : m.b) = p;
    return m;
}

// Cuts off a closed loop's spikes: where the loop turns straight back at a joint and one of
// the two curves there is shorter than spike_length, it lies along the other (crumbs of pieces
// at the distance about a joint a drawing leaves a little off); it goes, and the other stops
// where it began.
void remove_spikes(std::vector<Curve>& cs) {
    for (bool changed = true; changed && cs.size() > 2;) {
        changed = false;
        for (std::size_t i = 0; i < cs.size() && !changed; ++i) {
            const std::size_t j = (i + 1) % cs.size();
            if (dot(cs[i].tangent(1.0), cs[j].tangent(0.0)) > -0.99) continue;
            if (cs[i].length() <= cs[j].length() && cs[i].length() <= spike_length) {
                cs[j] = moved_end(cs[j], cs[i].a, true);
                cs.erase(cs.begin() + static_cast<std::ptrdiff_t>(i));
                changed = true;
            } else if (cs[j].length() < cs[i].length() && cs[j].length() <= spike_length) {
                cs[i] = moved_end(cs[i], cs[j].b, false);
                cs.erase(cs.begin() + static_cast<std::ptrdiff_t>(j));
                changed = true;
            }
        }
    }
}

// A closed chain as a loop: started where two raw pieces meet (not in the middle of one), the
// parts of one raw piece merged back into one segment (across a full circle's start too), tiny
// parts dropped, spikes cut off, the end put exactly on the start.
Profile loop_of(std::vector<std::size_t> c, const std::vector<KeptPiece>& kept, const std::vector<curves::RawPiece>& raw) {
    for (std::size_t p = 0; p < c.size(); ++p)
        if (!continues(kept[c[(p + c.size() - 1) % c.size()]], kept[c[p]], raw)) {
            std::rotate(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(p), c.end());
            break;
        }
    // Runs of pieces: `t1` the raw parameter where a run ends, `span` how far it runs (across
    // a full circle's start the run's parameter goes on past 1).
    std::vector<KeptPiece> merged;
    std::vector<double> span;
    for (std::size_t i : c) {
        const KeptPiece& k = kept[i];
        if (!merged.empty() && continues(merged.back(), k, raw)) {
            span.back() += k.t1 - k.t0;
            merged.back().t1 = k.t1;
            merged.back().curve = curves::part(raw[k.raw].curve, merged.back().t0, merged.back().t0 + span.back());
        } else {
            merged.push_back(k);
            span.push_back(k.t1 - k.t0);
        }
    }
    std::vector<Curve> cs;
    for (const KeptPiece& k : merged)
        if (k.curve.length() >= curves::min_piece) cs.push_back(k.curve);
    remove_spikes(cs);
    Profile out{ProfilePlane::xy, cs.empty() ? Vec2{} : cs.front().a, {}};
    for (const Curve& k : cs) {
        ProfileSegment s{k.b, std::nullopt, ArcDirection::ccw};
        if (k.arc) {
            s.centre = k.c;
            s.direction = k.sweep > 0 ? ArcDirection::ccw : ArcDirection::cw;
        }
        out.segments.push_back(s);
    }
    if (!out.segments.empty()) out.segments.back().end = out.start;
    return out;
}

RegionOffset offset_loops(const PlaneRegion& input, double d, bool grow) {
    if (!(d > 0.0)) return {{normalised(input)}, {}};
    const double s = grow ? -1.0 : 1.0;
    // Each loop's elements as drawn (segment indices the input's), walked backwards where the
    // loop turns the wrong way: the same curves, not profile.hpp's reversed (which takes an arc's
    // radius from its other end).
    const std::vector<const Profile*> loops = loops_of(input);
    auto segment_name = [&](std::size_t l, std::size_t j) { return loop_name(l) + " segment " + std::to_string(j); };
    std::vector<Element> elements;
    std::vector<LoopSpan> spans;
    for (std::size_t l = 0; l < loops.size(); ++l) {
        std::vector<Element> e = curves::elements_of(*loops[l], l);
        if ((signed_area(closed_curves(*loops[l])) >= 0.0) != (l == 0)) {
            std::reverse(e.begin(), e.end());
            for (Element& x : e) x.curve = reversed_curve(x.curve);
        }
        spans.push_back({elements.size(), elements.size() + e.size(), true});
        elements.insert(elements.end(), e.begin(), e.end());
    }
    RegionOffset result;
    auto note = [&](OffsetNoteKind kind, std::size_t l, std::optional<std::size_t> j, std::string message) {
        result.notes.push_back({kind, l == 0 ? std::nullopt : std::optional<std::size_t>(l - 1),
                                j, std::move(message)});
    };
    const std::string by = mm_text(d) + " mm";
    for (const Element& e : elements) {
        const Curve& k = e.curve;
        if (k.arc && k.r < d - curves::same_length && (k.sweep > 0) == (s > 0))
            note(OffsetNoteKind::arc_too_tight, e.loop, e.segment,
                 segment_name(e.loop, e.segment) + ": a concave arc of radius " + mm_text(k.r) + " mm is tighter than the offset " + by +
                     (grow ? "; the grown region fills it" : "; the tool cannot reach into it"));
    }

    const curves::OffsetPieces pieces = curves::offset_pieces(elements, spans, d, s);
    // The containment test: a kept piece lies inside the region when it shrinks, outside when it
    // grows. (Where the loops are simple it always does: a safety net.)
    std::vector<Curve> all_curves;
    for (const Profile* p : loops) {
        const std::vector<Curve> c = closed_curves(*p);
        all_curves.insert(all_curves.end(), c.begin(), c.end());
    }
    const InsideTest inside(y_pieces(all_curves));
    std::vector<KeptPiece> kept;
    for (const KeptPiece& k : pieces.kept)
        if (inside(k.curve.at(0.5)) != grow) kept.push_back(k);
    std::vector<std::vector<bool>> segment_kept(loops.size());
    std::vector<bool> loop_kept(loops.size(), false);
    for (std::size_t l = 0; l < loops.size(); ++l) segment_kept[l].assign(loops[l]->segments.size(), false);
    std::vector<std::vector<bool>> segment_raw = segment_kept;
    for (const curves::RawPiece& r : pieces.raw)
        if (r.element) segment_raw[elements[*r.element].loop][elements[*r.element].segment] = true;
    for (const KeptPiece& k : kept) {
        const auto& e = pieces.raw[k.raw].element;
        if (!e || k.curve.length() < curves::min_piece) continue;
        segment_kept[elements[*e].loop][elements[*e].segment] = true;
        loop_kept[elements[*e].loop] = true;
    }

    // The closed loops of the result. A chain that does not come round to its start (where
    // pieces meet within the chaining gap a crumb of pieces at the distance may lead it past its
    // start: a joint a drawing leaves a little off) gives the longest loop it holds, and its
    // other pieces are chained again.
    std::vector<std::vector<std::size_t>> loops_found;
    std::vector<std::vector<std::size_t>> pending = curves::chain(kept);
    while (!pending.empty()) {
        std::vector<std::size_t> c = std::move(pending.back());
        pending.pop_back();
        auto meets = [&](std::size_t j, std::size_t i) { return distance(kept[c[j]].curve.b, kept[c[i]].curve.a) <= curves::chain_gap; };
        if (meets(c.size() - 1, 0)) {
            loops_found.push_back(std::move(c));
            continue;
        }
        std::optional<std::pair<std::size_t, std::size_t>> best;
        for (std::size_t i = 0; i < c.size(); ++i)
            for (std::size_t j = c.size(); j-- > i;)
                if (meets(j, i) && (!best || j - i > best->second - best->first)) {
                    best = std::pair(i, j);
                    break;
                }
        if (!best) continue;  // no loop in it
        loops_found.emplace_back(c.begin() + static_cast<std::ptrdiff_t>(best->first), c.begin() + static_cast<std::ptrdiff_t>(best->second) + 1);
        std::vector<std::size_t> rest(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(best->first));
        rest.insert(rest.end(), c.begin() + static_cast<std::ptrdiff_t>(best->second) + 1, c.end());
        if (!rest.empty()) pending.push_back(std::move(rest));
    }
    std::vector<OutLoop> out;
    for (const auto& c : loops_found) {
        double length = 0.0;
        for (std::size_t i : c) length += kept[i].curve.length();
        if (length < curves::chain_gap) continue;  // a crumb where pieces cross
        Profile profile = loop_of(c, kept, pieces.raw);
        if (profile.segments.empty()) continue;
        OutLoop loop{std::move(profile), {}, {}, 0.0, {}, {}, {}};
        loop.curves = closed_curves(loop.profile);
        if (loop.curves.empty()) continue;
        loop.area = signed_area(loop.curves);
        // A loop enclosing nothing is a slit where the tool exactly fits between two walls.
        if (std::abs(loop.area) < curves::chain_gap * length) continue;
        loop.pieces = y_pieces(loop.curves);
        loop.box = box_of_curves(loop.curves);
        loop.probe = probe_of(loop.curves);
        loop.lowest = lowest_point(loop.curves);
        out.push_back(std::move(loop));
    }

    // Nesting: each loop's parent is the smallest loop around it; a counter-clockwise loop is a
    // region's outline, a clockwise one an island of its parent.
    std::vector<std::size_t> by_size(out.size());
    for (std::size_t i = 0; i < out.size(); ++i) by_size[i] = i;
    std::stable_sort(by_size.begin(), by_size.end(), [&](std::size_t a, std::size_t b) { return std::abs(out[a].area) < std::abs(out[b].area); });
    std::vector<std::optional<std::size_t>> parent(out.size());
    for (std::size_t x = 0; x < by_size.size(); ++x) {
        const OutLoop& inner = out[by_size[x]];
        for (std::size_t y = x + 1; y < by_size.size(); ++y) {
            const OutLoop& outer = out[by_size[y]];
            if (!box_within(inner.box, outer.box) || !inside_pieces(outer.pieces, inner.probe)) continue;
            parent[by_size[x]] = by_size[y];
            break;
        }
    }
    std::vector<std::size_t> outlines;
    for (std::size_t i = 0; i < out.size(); ++i)
        if (out[i].area > 0) outlines.push_back(i);
    std::sort(outlines.begin(), outlines.end(), [&](std::size_t a, std::size_t b) { return lower_first(out[a].lowest, out[b].lowest); });
    for (std::size_t o : outlines) {
        std::vector<std::size_t> holes;
        for (std::size_t i = 0; i < out.size(); ++i)
            if (out[i].area < 0 && parent[i] == o) holes.push_back(i);
        std::sort(holes.begin(), holes.end(), [&](std::size_t a, std::size_t b) { return lower_first(out[a].lowest, out[b].lowest); });
        PlaneRegion r{std::move(out[o].profile), {}};
        for (std::size_t h : holes) r.islands.push_back(std::move(out[h].profile));
        result.regions.push_back(std::move(r));
    }

    if (result.regions.empty()) {
        // What vanished on the way is no news then.
        result.notes.clear();
        note(OffsetNoteKind::consumed, 0, std::nullopt,
             "nothing remains of the region " + std::string(grow ? "grown" : "shrunk") + " by " + by + ": it is nowhere wider than " +
                 mm_text(2 * d) + " mm");
        return result;
    }
    for (std::size_t l = 0; l < loops.size(); ++l) {
        if (!loop_kept[l] && l > 0) {
            // A whole island gone: one note for it, instead of its segments'.
            std::erase_if(result.notes, [&](const RegionNote& n) { return n.island == std::optional<std::size_t>(l - 1); });
            note(OffsetNoteKind::element_removed, l, std::nullopt,
                 loop_name(l) + (grow ? ": it vanishes, nowhere wider than " + mm_text(2 * d) + " mm"
                                      : ": its offset vanishes entirely, cut away by the outline's or other islands' offsets"));
            continue;
        }
        for (std::size_t j = 0; j < loops[l]->segments.size(); ++j) {
            if (segment_kept[l][j]) continue;
            // Only segments that had an offset (zero-length ones are passed over, an arc of
            // radius exactly the distance shrinks to its centre: the tool just fits).
            if (!segment_raw[l][j]) continue;
            const std::optional<std::size_t> isl = l == 0 ? std::nullopt : std::optional<std::size_t>(l - 1);
            const bool noted = std::any_of(result.notes.begin(), result.notes.end(), [&](const RegionNote& n) {
                return n.island == isl && n.segment == std::optional<std::size_t>(j);
            });
            if (!noted)
                note(OffsetNoteKind::element_removed, l, j,
                     segment_name(l, j) + ": its offset vanishes, cut away by " + (loops.size() > 1 ? "its neighbours or another loop" : "its neighbours") +
                         (grow ? "" : "; the tool cannot follow it"));
        }
    }
    // By loop (the outline first) and segment, as the input has them.
    auto order = [](const RegionNote& n) {
        return std::pair(n.island ? *n.island + 1 : 0, n.segment ? *n.segment + 1 : 0);
    };
    std::stable_sort(result.notes.begin(), result.notes.end(), [&](const RegionNote& a, const RegionNote& b) { return order(a) < order(b); });
    if (result.regions.size() > 1)
        note(OffsetNoteKind::split, 0, std::nullopt,
             "the region " + std::string(grow ? "grown" : "shrunk") + " by " + by + " falls apart into " + std::to_string(result.regions.size()) +
                 " regions: it has a neck narrower than " + mm_text(2 * d) + " mm");
    return result;
}

// The first problem of a region as input (region_problem), loop by loop.
std::optional<RegionProblem> first_problem(const PlaneRegion& region) {
    const std::vector<const Profile*> loops = loops_of(region);
    auto problem = [](std::size_t l, std::string message) {
        return RegionProblem{l == 0 ? std::nullopt : std::optional<std::size_t>(l - 1), std::move(message)};
    };
    auto finite = [](Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); };
    // Each loop on its own: in XY, finite, closed, of some length, arcs' ends on their circles.
    std::vector<std::vector<Curve>> curves(loops.size());
    std::vector<std::vector<std::size_t>> segment_of(loops.size());  // each curve's segment
    for (std::size_t l = 0; l < loops.size(); ++l) {
        const Profile& p = *loops[l];
        const std::string name = loop_name(l);
        if (p.plane != ProfilePlane::xy) return problem(l, name + " is not in the XY plane");
        bool all_finite = finite(p.start);
        for (const ProfileSegment& seg : p.segments) all_finite = all_finite && finite(seg.end) && (!seg.centre || finite(*seg.centre));
        if (!all_finite) return problem(l, name + " has a coordinate that is not a finite number");
        if (p.segments.empty()) return problem(l, name + " has no segments");
        if (!is_closed(p))
            return problem(l, name + " is not closed: it ends at " + point_text(p.segments.back().end) + ", " +
                                  mm_text(distance(p.segments.back().end, p.start)) + " mm from its start " + point_text(p.start));
        for (std::size_t j = 0; j < p.segments.size(); ++j) {
            const ProfileSegment& seg = p.segments[j];
            if (!seg.centre) continue;
            const Vec2 from = segment_start(p, j);
            const double off = std::abs(distance(seg.end, *seg.centre) - distance(from, *seg.centre));
            if (off > arc_radius_tolerance)
                return problem(l, name + " segment " + std::to_string(j) + ": the arc's end is " + mm_text(off) +
                                      " mm off the circle through its start about its centre");
        }
        // One curve a segment, an arc to the angle of its given end.
        for (std::size_t j = 0; j < p.segments.size(); ++j) {
            const Curve k = curves::curve_of(p, j);
            if (k.length() <= curves::same_length) continue;
            curves[l].push_back(k);
            segment_of[l].push_back(j);
        }
        if (curves[l].empty()) return problem(l, name + " has no length");
    }
    // Every curve of every loop in one grid; pairs of curves closer than region_touch.
    struct Item {
        std::size_t loop, index;
    };
    std::vector<Item> items;
    std::vector<Rect> boxes;
    for (std::size_t l = 0; l < loops.size(); ++l)
        for (std::size_t i = 0; i < curves[l].size(); ++i) {
            items.push_back({l, i});
            const Rect b = curves::box_of(curves[l][i]);
            boxes.push_back({b.x0 - region_touch, b.y0 - region_touch, b.x1 + region_touch, b.y1 + region_touch});
        }
    const curves::BoxGrid grid(boxes);
    // Per loop, the length along it to the start of each curve (and to its end, last).
    std::vector<std::vector<double>> along(loops.size());
    for (std::size_t l = 0; l < loops.size(); ++l) {
        along[l].push_back(0.0);
        for (const Curve& k : curves[l]) along[l].push_back(along[l].back() + k.length());
    }
    // The problems found, the first (by the later loop, then the earlier) reported.
    struct Found {
        std::size_t later, earlier;
        std::string message;
    };
    std::optional<Found> found;
    auto consider = [&](std::size_t later, std::size_t earlier, std::string message) {
        if (!found || std::pair(later, earlier) < std::pair(found->later, found->earlier)) found = Found{later, earlier, std::move(message)};
    };
    for (std::size_t x = 0; x < items.size(); ++x)
        for (std::size_t y : grid.near(boxes[x])) {
            if (y <= x) continue;
            const Item a = items[x], b = items[y];
            const Curve& ka = curves[a.loop][a.index];
            const Curve& kb = curves[b.loop][b.index];
            if (a.loop == b.loop) {
                // Neighbours, or segments with less than joint_slack between them (a drawing's
                // tiny segments), meet at their joint (both joints for a loop of two): anywhere
                // else, or turning straight back there, the loop is not simple.
                const std::vector<double>& at = along[a.loop];
                const double between = at[b.index] - at[a.index + 1], around = at.back() - at[b.index + 1] + at[a.index];
                const bool a_then_b = between <= joint_slack, b_then_a = around <= joint_slack;
                if (a_then_b || b_then_a) {
                    std::vector<Vec2> joints;
                    auto joint = [&](const Curve& in, const Curve& next) {
                        joints.push_back(in.b);
                        joints.push_back(next.a);
                        const Vec2 t1 = in.tangent(1.0), t2 = next.tangent(0.0);
                        if (dot(t1, t2) < 0 && std::abs(cross(t1, t2)) < 1e-9)
                            consider(a.loop, a.loop, loop_name(a.loop) + " turns back on itself at " + point_text(in.b));
                    };
                    if (a_then_b) joint(ka, kb);
                    if (b_then_a) joint(kb, ka);
                    // A crossing but at the joint, where the two do cross (not merely graze in a
                    // tangent joint's rounding): a segment that runs back over the one before
                    // it, if only by a hair (a sharp corner whose joint is a little off).
                    for (double t : curves::crossings(ka, kb)) {
                        const Vec2 q = ka.at(std::clamp(t, 0.0, 1.0));
                        const Vec2 ta = ka.tangent(std::clamp(t, 0.0, 1.0)), tb = kb.tangent(std::clamp(curves::parameter_of(kb, q), 0.0, 1.0));
                        const bool crosses = std::abs(cross(ta, tb)) > 1e-6 || dot(ta, tb) < 0;
                        if (crosses && std::all_of(joints.begin(), joints.end(), [&](Vec2 j) { return distance(q, j) > 1e-9; })) {
                            const std::size_t first = a_then_b ? a.index : b.index, second = a_then_b ? b.index : a.index;
                            consider(a.loop, a.loop,
                                     loop_name(a.loop) + " crosses itself at " + point_text(q) + ", where segment " + std::to_string(segment_of[a.loop][first]) +
                                         " meets segment " + std::to_string(segment_of[a.loop][second]) +
                                         ": they cross by a hair at their joint (an arc's end a little off its circle at a sharp corner)");
                        }
                    }
                    continue;
                }
            }
            const ClosestApproach gap = piece_distance(piece_of(ka), piece_of(kb));
            if (gap.distance > region_touch) continue;
            if (a.loop == b.loop) consider(a.loop, a.loop, loop_name(a.loop) + " crosses or touches itself at " + point_text(gap.at));
            else consider(b.loop, a.loop, loop_name(b.loop) + " crosses or touches " + loop_name(a.loop) + " at " + point_text(gap.at));
        }
    if (found) return problem(found->later, found->message);
    // The loops apart: each island inside the outline and outside the other islands.
    std::vector<std::vector<YPiece>> pieces(loops.size());
    std::vector<Rect> loop_boxes(loops.size());
    for (std::size_t l = 0; l < loops.size(); ++l) {
        pieces[l] = y_pieces(closed_curves(*loops[l]));
        loop_boxes[l] = box_of_curves(curves[l]);
    }
    for (std::size_t l = 1; l < loops.size(); ++l) {
        const Vec2 probe = probe_of(curves[l]);
        if (!inside_pieces(pieces[0], probe)) return problem(l, loop_name(l) + " lies outside the outline");
        for (std::size_t m = 1; m < loops.size(); ++m) {
            if (m == l || !box_within(loop_boxes[l], loop_boxes[m]) || !inside_pieces(pieces[m], probe)) continue;
            return problem(l, loop_name(l) + " lies inside " + loop_name(m) + ": islands may not nest");
        }
    }
    return std::nullopt;
}

// Every loop's curves (for distances) and y-monotone pieces (for inside tests).
struct RegionShape {
    std::vector<Curve> curves;
    std::vector<YPiece> pieces;
};

RegionShape shape_of(const PlaneRegion& region) {
    RegionShape out;
    for (const Profile* p : loops_of(region)) {
        const std::vector<Curve> c = closed_curves(*p);
        const std::vector<YPiece> y = y_pieces(c);
        out.curves.insert(out.curves.end(), c.begin(), c.end());
        out.pieces.insert(out.pieces.end(), y.begin(), y.end());
    }
    return out;
}

double boundary_distance(const std::vector<Curve>& curves, Vec2 p) {
    double best = std::numeric_limits<double>::infinity();
    for (const Curve& k : curves) best = std::min(best, curves::distance_to_curve(k, p));
    return best;
}

// A curve seen in the frame whose x runs along u and y along left_of(u).
Curve in_frame(const Curve& k, Vec2 u, double angle) {
    const Vec2 n = left_of(u);
    auto map = [&](Vec2 v) { return Vec2{dot(v, u), dot(v, n)}; };
    Curve out = k;
    out.a = map(k.a);
    out.b = map(k.b);
    if (k.arc) {
        out.c = map(k.c);
        out.a0 = k.a0 - angle;
    }
    return out;
}

}  // namespace camgen::region_impl

namespace camgen {

PlaneRegion normalised(const PlaneRegion& region) {
    PlaneRegion out{region_impl::normal_loop(region.outer, true), {}};
    for (const Profile& island : region.islands) out.islands.push_back(region_impl::normal_loop(island, false));
    return out;
}

RegionOffset offset_region(const PlaneRegion& region, double distance) { return region_impl::offset_loops(region, distance, false); }

RegionOffset grow_region(const PlaneRegion& region, double distance) { return region_impl::offset_loops(region, distance, true); }

}  // namespace camgen

namespace camgen {

std::optional<RegionProblem> region_problem(const PlaneRegion& region) { return region_impl::first_problem(region); }

bool region_contains(const PlaneRegion& region, Vec2 p) {
    const region_impl::RegionShape shape = region_impl::shape_of(region);
    return region_impl::inside_pieces(shape.pieces, p) && region_impl::boundary_distance(shape.curves, p) > region_boundary_tolerance;
}

double region_boundary_distance(const PlaneRegion& region, Vec2 p) {
    return region_impl::boundary_distance(region_impl::shape_of(region).curves, p);
}

double region_area(const PlaneRegion& region) {
    double area = std::abs(region_impl::signed_area(region_impl::closed_curves(region.outer)));
    for (const Profile& island : region.islands) area -= std::abs(region_impl::signed_area(region_impl::closed_curves(island)));
    return area;
}

std::vector<HatchRow> hatch_region(const PlaneRegion& region, double angle_deg, double max_spacing) {
    using region_impl::YPiece;
    if (!(max_spacing > 0.0) || !std::isfinite(angle_deg)) return {};
    const double angle = angle_deg * rad_per_deg;
    const Vec2 u = unit_at(angle), n = left_of(u);
    // The region in the rows' frame: rows are lines of constant y there.
    std::vector<YPiece> pieces;
    double y0 = std::numeric_limits<double>::infinity(), y1 = -y0;
    for (const Profile* p : region_impl::loops_of(region))
        for (const curves::Curve& k : region_impl::closed_curves(*p)) {
            const curves::Curve f = region_impl::in_frame(k, u, angle);
            const curves::Rect b = curves::box_of(f);
            y0 = std::min(y0, b.y0);
            y1 = std::max(y1, b.y1);
            region_impl::add_y_pieces(f, pieces);
        }
    const double width = y1 - y0;
    if (!(width > 0.0) || !std::isfinite(width)) return {};
    const std::size_t count = static_cast<std::size_t>(std::max(1.0, std::ceil(width / max_spacing - 1e-9)));
    const double step = width / static_cast<double>(count);
    std::vector<HatchRow> rows(count);
    std::vector<std::vector<double>> xs(count);
    for (std::size_t i = 0; i < count; ++i) rows[i].offset = y0 + (static_cast<double>(i) + 0.5) * step;
    for (const YPiece& piece : pieces) {
        const double lo = std::min(piece.s.y, piece.e.y), hi = std::max(piece.s.y, piece.e.y);
        const double first = std::max(0.0, std::floor((lo - y0) / step - 0.5));
        const double last = std::min(static_cast<double>(count - 1), std::ceil((hi - y0) / step - 0.5));
        for (double i = first; i <= last; ++i) {
            const std::size_t row = static_cast<std::size_t>(i);
            if (region_impl::crosses_row(piece, rows[row].offset)) xs[row].push_back(region_impl::x_at(piece, rows[row].offset));
        }
    }
    constexpr double shortest = 1e-6;
    for (std::size_t i = 0; i < count; ++i) {
        std::vector<double>& x = xs[i];
        std::sort(x.begin(), x.end());
        std::vector<std::pair<double, double>> spans;
        for (std::size_t k = 0; k + 1 < x.size(); k += 2) {
            if (!spans.empty() && x[k] - spans.back().second < shortest) spans.back().second = x[k + 1];  // a gap of nothing
            else spans.emplace_back(x[k], x[k + 1]);
        }
        const double o = rows[i].offset;
        for (const auto& [from, to] : spans)
            if (to - from >= shortest) rows[i].pieces.emplace_back(u * from + n * o, u * to + n * o);
    }
    return rows;
}

}  // namespace camgen

namespace camgen {

struct RegionRows::Impl {
    std::vector<region_impl::YPiece> pieces;  // sorted by their lowest y
    std::array<double, 4> box{0.0, 0.0, 0.0, 0.0};
};

RegionRows::RegionRows(const PlaneRegion& region) : impl_(std::make_unique<Impl>()) {
    using region_impl::YPiece;
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const Profile* p : region_impl::loops_of(region))
        for (const curves::Curve& k : region_impl::closed_curves(*p)) {
            const curves::Rect b = curves::box_of(k);
            x0 = std::min(x0, b.x0), y0 = std::min(y0, b.y0), x1 = std::max(x1, b.x1), y1 = std::max(y1, b.y1);
            region_impl::add_y_pieces(k, impl_->pieces);
        }
    if (impl_->pieces.empty()) return;
    impl_->box = {x0, y0, x1, y1};
    auto low = [](const YPiece& p) { return std::min(p.s.y, p.e.y); };
    std::sort(impl_->pieces.begin(), impl_->pieces.end(), [&](const YPiece& a, const YPiece& b) { return low(a) < low(b); });
}

RegionRows::~RegionRows() = default;
RegionRows::RegionRows(RegionRows&&) noexcept = default;
RegionRows& RegionRows::operator=(RegionRows&&) noexcept = default;

std::vector<std::pair<double, double>> RegionRows::spans(double y) const {
    std::vector<double> xs;
    for (const region_impl::YPiece& p : impl_->pieces) {
        if (std::min(p.s.y, p.e.y) > y) break;  // sorted by their lowest y: none after reaches down to y
        if (region_impl::crosses_row(p, y)) xs.push_back(region_impl::x_at(p, y));
    }
    std::sort(xs.begin(), xs.end());
    std::vector<std::pair<double, double>> out;
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2)
        if (xs[i + 1] > xs[i]) out.emplace_back(xs[i], xs[i + 1]);
    return out;
}

std::array<double, 4> RegionRows::bounds() const { return impl_->box; }

}  // namespace camgen
