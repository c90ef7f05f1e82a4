#pragma once
// The internals of the geometry layer's offsets (offset.cpp: one profile; region.cpp: an outline
// with islands), private to src/geometry: lines and arcs as parametrised curves, their exact
// crossings and distances, a grid of boxes, and the classical offset (raw offsets and corner
// arcs split at every crossing, kept where no closer than the distance, chained). Lengths mm.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/profile.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen::curves {

// Pieces and split points closer than this are the same, mm.
inline constexpr double same_length = 1e-9;
// Pieces shorter than this are left out of an output profile (their neighbours join), mm.
inline constexpr double min_piece = 1e-7;
// KeptPiece pieces whose ends are this close are chained, mm.
inline constexpr double chain_gap = 1e-6;

// A line or an arc, walked from t = 0 to t = 1. An arc has a centre, a radius, a start angle
// and a signed sweep (counter-clockwise positive).
struct Curve {
    Vec2 a, b;  // the ends
    bool arc = false;
    Vec2 c;
    double r = 0.0, a0 = 0.0, sweep = 0.0;

    Vec2 at(double t) const { return arc ? c + unit_at(a0 + sweep * t) * r : a + (b - a) * t; }
    double length() const { return arc ? r * std::abs(sweep) : distance(a, b); }
    Vec2 tangent(double t) const {
        if (!arc) return (b - a) * (1.0 / distance(a, b));
        const Vec2 radial = unit_at(a0 + sweep * t);
        return sweep > 0 ? left_of(radial) : left_of(radial) * -1.0;
    }
};

Curve line_curve(Vec2 a, Vec2 b);
Curve arc_curve(Vec2 c, double r, double a0, double sweep);
// The part of `k` between t0 and t1.
Curve part(const Curve& k, double t0, double t1);

// Segment `index` of the profile as a curve (an arc's radius from its start, as resolve_arc).
Curve curve_of(const Profile& p, std::size_t index);
// Segment `index` as the curves a tool follows: its curve_of, and where an arc's given end is
// off its circle (the radius is the start's; a drawing's joints are often a little off) the
// arc ending on its circle and the short radial line from there to the given end, so that the
// next segment starts where the pieces end and the offsets of neighbours meet.
std::vector<Curve> curves_of(const Profile& p, std::size_t index);

// The parameter of a point on k's support (the line or the whole circle): outside [0, 1] when
// it is beyond the ends. An arc's angle is taken on the side of [0, 1] it is closer to.
double parameter_of(const Curve& k, Vec2 p);
// At most two points (no allocation: pairs of curves are met by the thousand).
struct TwoPoints {
    Vec2 p[2];
    int n = 0;
    const Vec2* begin() const { return p; }
    const Vec2* end() const { return p + n; }
};
// Where the supports of x and y meet (the lines, the whole circles).
TwoPoints support_crossings(const Curve& x, const Curve& y);
// True when t lies on k within a length tolerance.
bool within(const Curve& k, double t);
// The parameters on x where it meets y (at most two).
struct TwoParameters {
    double t[2];
    int n = 0;
    const double* begin() const { return t; }
    const double* end() const { return t + n; }
};
TwoParameters crossings(const Curve& x, const Curve& y);
// True when the lines x and y lie on one line (within min_piece), walked opposite ways.
bool opposed_lines(const Curve& x, const Curve& y);
// The shortest distance from p to k.
double distance_to_curve(const Curve& k, Vec2 p);

// An axis-aligned box around a curve, mm: pairs of curves whose boxes are apart cannot meet,
// and a curve whose box is farther from a point than another curve is not the nearest.
struct Rect {
    double x0, y0, x1, y1;
};
Rect box_of(const Curve& k);
bool apart(const Rect& a, const Rect& b);
double box_distance(const Rect& b, Vec2 p);

// Boxes bucketed in a uniform grid of about one cell per box, so that the boxes near a query are
// found without looking at all of them (a profile of a thousand short segments).
class BoxGrid {
public:
    explicit BoxGrid(std::vector<Rect> boxes);
    // The indices of the boxes not apart from `query`, ascending.
    std::vector<std::size_t> near(const Rect& query) const;
    // The side of a cell, mm.
    double cell_size() const { return cell_; }

private:
    // Calls f with the index of every cell that box b meets.
    template <class F>
    void visit(const Rect& b, F f) const;

    std::vector<Rect> boxes_;
    Rect extent_{};
    double cell_ = 1.0;
    int nx_ = 0, ny_ = 0;
    std::vector<std::vector<std::size_t>> cells_;
    // Which boxes one query has met already (a stamp per query; a grid serves one thread).
    mutable std::vector<unsigned> seen_;
    mutable unsigned stamp_ = 0;
};

// A profile's segments as curves, with their indices (and the loop they belong to, for an
// offset of several loops at once), zero-length segments left out.
struct Element {
    Curve curve;
    std::size_t segment = 0;
    Rect box;
    std::size_t loop = 0;
};
std::vector<Element> elements_of(const Profile& p, std::size_t loop = 0);

// True when some element is closer to p than `limit` (grid: the elements' boxes).
bool closer_than(const std::vector<Element>& elements, const BoxGrid& grid, Vec2 p, double limit);

// The offset of one curve by `d` to the side whose left-normal sign is `s` (+1 left, -1 right):
// nullopt when it shrinks to a point. An arc whose centre is on that side and whose radius is
// below d turns inside out: the points at d from it lie beyond the centre.
std::optional<Curve> offset_curve(const Curve& k, double d, double s);
// The arc of radius d around the vertex between `in` and `out` on side s, turning as the
// tangent turns; nullopt at a tangent joint. A reversal (a spike) turns round the outside.
std::optional<Curve> corner_curve(const Curve& in, const Curve& out, double d, double s);

// A piece of the raw offset: the curve, and the element it offsets (nullopt: a corner arc).
struct RawPiece {
    Curve curve;
    std::optional<std::size_t> element;
};

// A kept part of raw piece `raw` between t0 and t1.
struct KeptPiece {
    std::size_t raw = 0;
    double t0 = 0.0, t1 = 1.0;
    Curve curve;
};

// The elements [begin, end) of one loop of an offset; a closed loop has a corner between its
// last element and its first, an open one a circle of the distance around its end.
struct LoopSpan {
    std::size_t begin = 0, end = 0;
    bool closed = true;
};

struct OffsetPieces {
    std::vector<RawPiece> raw;    // each element's offset and the corner arc after it, in order
    std::vector<KeptPiece> kept;  // the parts of them at exactly d from every element, in order
};

// The classical offset of the loops by d to side s (+1 left, -1 right of each loop's travel):
// the raw pieces of every loop split wherever they cross one another, the other side's offsets
// or a circle of radius d around a vertex, and the parts kept whose midpoints are no closer than
// d to any element of any loop. Chain the kept pieces (`chain`) to get the offset's paths.
OffsetPieces offset_pieces(const std::vector<Element>& elements, const std::vector<LoopSpan>& loops, double d, double s);

// A length for a message: rounded to 0.001 mm, no exponent.
std::string mm_text(double v);

// The kept pieces chained end to start, preferring the raw successor, into paths.
std::vector<std::vector<std::size_t>> chain(const std::vector<KeptPiece>& kept);

struct OffsetPath {
    Profile profile;
    std::vector<std::optional<std::size_t>> source;
    double length = 0.0;
};

// A chain as a profile: contiguous parts of one raw piece merged back, tiny parts dropped, a
// closed chain's end put exactly on its start.
OffsetPath path_of(const std::vector<std::size_t>& c, const std::vector<KeptPiece>& kept, const std::vector<RawPiece>& raw,
                   const std::vector<Element>& elements, ProfilePlane plane, bool closed);

}  // namespace camgen::curves
