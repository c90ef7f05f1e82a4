#pragma once
// How close a tool-centre move comes to a profile: exact distances between lines and arcs (no
// sampling), over a grid of the profile's segments so that a move looks only at the segments
// near it, and which side of a closed profile a point is on (by counting crossings, lines and
// arcs exact). The part-aware safety check of the milling operations asks these questions of
// every move it adds. Machine-free. Lengths mm.
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "camgen/geometry/profile.hpp"

namespace camgen {

// A line or an arc from `start`: one move of a tool centre in XY, or one segment of a profile.
struct PathPiece {
    Vec2 start;
    ProfileSegment segment;
};

// The closest approach of two pieces: the distance and the point on the first piece where it is.
struct ClosestApproach {
    double distance = 0.0;
    Vec2 at;
};

// The shortest distance between a point and a piece.
ClosestApproach point_piece_distance(Vec2 p, const PathPiece& piece);
// The shortest distance between two pieces (0 where they touch or cross); `at` lies on `a`.
ClosestApproach piece_distance(const PathPiece& a, const PathPiece& b);

class ProfileClearance {
public:
    // `reach`: distances beyond it need not be exact (the answer is then at least `reach`).
    ProfileClearance(const Profile& profile, double reach);

    // The closest approach of a move (a point: a segment with no length) to the profile.
    ClosestApproach nearest(const PathPiece& move) const;
    ClosestApproach nearest(Vec2 point) const;
    // `p` inside the closed profile (on it counts as neither: call with a point off it).
    bool inside(Vec2 p) const;

private:
    std::vector<std::size_t> cells_of(double x0, double y0, double x1, double y1) const;
    std::vector<PathPiece> pieces_;
    std::vector<std::array<double, 4>> boxes_;  // each piece's bounding box: x0, y0, x1, y1
    double reach_;
    double x0_ = 0, y0_ = 0, cell_ = 1;
    std::size_t nx_ = 1, ny_ = 1;
    std::vector<std::vector<std::size_t>> grid_;
    // Which pieces one query has looked at already (a stamp per query, not a set).
    mutable std::vector<unsigned> seen_;
    mutable unsigned stamp_ = 0;
};

}  // namespace camgen
