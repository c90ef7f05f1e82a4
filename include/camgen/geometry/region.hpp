#pragma once
// Regions of the XY plane: the inside of an outline less its islands (a pocket's floor, a face),
// what is wrong with one as input, its offsets (shrunk: where a tool centre may go; grown: what a
// tool over the edge sweeps), whether a point is inside, its area, and the raster rows a zig-zag
// clearing or a facing follows. Exact for arcs throughout: lines stay lines, arcs stay arcs about
// their centres, crossings of lines and circles solved, never sampled. Machine-free. Lengths mm.
#include <cstddef>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/profile.hpp"

namespace camgen {

// A region of the plane: inside `outer` and outside every island. All closed profiles in XY,
// walked either way round (the functions below normalise them). (The name `Region` is taken by
// the inside/outside choice of offset.hpp.)
struct PlaneRegion {
    Profile outer;
    std::vector<Profile> islands;
};

// What is wrong with a region as input: the loop to blame (`island`: its index; nullopt: the
// outline) and a sentence naming it, e.g. "island 2 crosses or touches the outline at (40, 12)".
struct RegionProblem {
    std::optional<std::size_t> island;
    std::string message;
};

// Two loops (or two parts of one loop) closer than this touch, mm.
inline constexpr double region_touch = 1e-6;

// The first thing wrong with `region` as the input of the functions below, or nullopt: every
// loop in XY, of finite coordinates, closed (within profile_same_point), of some length, its
// arcs' ends within arc_radius_tolerance of their circles, simple (no part of it crosses,
// touches (within region_touch) or turns back on another, exact for lines and arcs; segments
// meet only at their joints, and a sharp corner whose arc ends a hair inside its circle, so
// that the next segment crosses back over it, is refused as crossing itself there), every
// island strictly inside the outline, and the islands apart from each other: neither crossing
// nor touching (within region_touch) nor one inside another. The outline is checked first,
// then the islands in order. Cost: about linear in the number of segments (a grid of boxes).
std::optional<RegionProblem> region_problem(const PlaneRegion& region);

// The region with its outline walked counter-clockwise and its islands clockwise (so that the
// region lies on the left of every loop), loops otherwise as given.
PlaneRegion normalised(const PlaneRegion& region);

// What an offset could not follow, naming the loop and segment where one is to blame: `island`
// the island's index (nullopt: the outline, or the region as a whole), `segment` that loop's
// segment index as given (nullopt: the whole loop, or the whole region). The kinds are the
// profile offset's: arc_too_tight (a concave arc of radius below the distance), element_removed
// (a segment whose offset vanishes, cut away by others; an island that closes up entirely when
// the region grows: segment nullopt), split (the region falls apart into several), consumed
// (nothing remains; the only note then).
struct RegionNote {
    OffsetNoteKind kind = OffsetNoteKind::element_removed;
    std::optional<std::size_t> island;
    std::optional<std::size_t> segment;
    std::string message;  // a sentence for the user, e.g. "island 2 segment 3: ..."
};

// The result of offset_region and grow_region: the regions (each normalised: outline
// counter-clockwise, islands clockwise) and the notes, in the order of the input's loops.
struct RegionOffset {
    std::vector<PlaneRegion> regions;
    std::vector<RegionNote> notes;
    bool empty() const { return regions.empty(); }
};

// The region shrunk by `distance` mm: the set of its points at least `distance` from its
// boundary (where a tool centre of radius `distance` may go), as regions. Arcs exact: an arc
// offsets to an arc about the same centre, a convex corner gets an arc of radius `distance`;
// every output segment is at exactly `distance` from the input's boundary (within 1e-6 mm),
// none closer; the loops are closed, simple and apart. The outline splits into several regions
// at a neck narrower than 2 distance; islands closer than 2 distance to each other merge into
// one island, and an island closer than 2 distance to the outline goes into the outline (its
// offset becomes part of an outer loop); a region narrower than 2 distance everywhere is
// consumed (no regions). Several regions are ordered by their outlines' lowest points (the
// leftmost of equals), each region's islands likewise; a loop starts where the offset of the
// earliest surviving input segment (outline first, then islands in order) begins to be kept,
// the same for the same input. distance <= 0: the region itself, normalised. The region must be
// valid (region_problem nullopt); otherwise the result is unspecified, but there is one.
// Cost: about the number of segments times those within 2 distance of each.
RegionOffset offset_region(const PlaneRegion& region, double distance);

// The region grown by `distance` mm: the set of points within `distance` of it (a tool of
// radius `distance` whose centre stays in the region sweeps it), as regions. The outline grows
// (a convex corner gets an arc of radius `distance`, an inlet narrower than 2 distance closes,
// possibly into an enclosed hole: a new island), each island shrinks and vanishes where it is
// narrower than 2 distance everywhere, or splits at a neck narrower than that. The same
// exactness, order and notes as offset_region; distance <= 0: the region itself, normalised.
RegionOffset grow_region(const PlaneRegion& region, double distance);

// Points whose distance from the boundary is at most this are on it, mm.
inline constexpr double region_boundary_tolerance = 1e-9;

// `p` strictly inside the region: inside the outline, outside every island, and farther than
// region_boundary_tolerance from every loop (on the boundary: false). Exact for arcs (crossings
// of a ray counted with lines and arcs solved). Cost: linear in the number of segments.
bool region_contains(const PlaneRegion& region, Vec2 p);

// The shortest distance from `p` to the region's boundary (its outline and islands), mm,
// wherever p is. Exact for arcs. Cost: linear in the number of segments.
double region_boundary_distance(const PlaneRegion& region, Vec2 p);

// The area of the region, mm^2: the outline's enclosed area less the islands', exact for arcs
// (Green's theorem over lines and circular segments), whichever way the loops are walked.
double region_area(const PlaneRegion& region);

// One raster row: the line at `offset` mm along the rows' normal (the row direction turned 90
// degrees counter-clockwise), and the pieces of it inside the region as (from, to) points, in
// the row direction.
struct HatchRow {
    double offset = 0.0;
    std::vector<std::pair<Vec2, Vec2>> pieces;
};

// Raster rows over the region (for zig-zag clearing and facing): lines at `angle_deg` degrees
// counter-clockwise from +X, as far apart as possible but at most `max_spacing` mm. The
// region's extent along the rows' normal, W, is cut into N = ceil(W / max_spacing) equal
// strips and a row runs along the middle of each: rows W / N apart, the first and the last
// W / 2N inside the extent (so a tool of diameter >= the spacing centred on the rows covers the
// whole extent, and no row merely grazes the region's extreme). Rows are ordered by offset,
// rows with no pieces kept (an island may take a whole row). Each row's pieces are where the
// line is inside the region, exactly where it crosses the lines and arcs of the boundary
// (crossings counted half-open: a row through a vertex or along a boundary line counts as
// just beyond it in the normal direction, so a tangent touch makes no piece and no gap); pieces
// shorter than 1e-6 mm are dropped and gaps shorter than that closed. max_spacing <= 0 or an
// empty region: no rows. Cost: linear in the number of segments plus the crossings.
std::vector<HatchRow> hatch_region(const PlaneRegion& region, double angle_deg, double max_spacing);

// A region's rows on a grid: where the horizontal line y = const is inside it, as [x0, x1]
// spans in ascending x, exact at line and arc crossings (counted half-open, as hatch_region), for
// filling a raster (the design a simulated part is checked against). Built once per region;
// each row costs the loops' pieces that reach its height.
class RegionRows {
public:
    explicit RegionRows(const PlaneRegion& region);
    ~RegionRows();
    RegionRows(RegionRows&&) noexcept;
    RegionRows& operator=(RegionRows&&) noexcept;
    // The spans at height y.
    std::vector<std::pair<double, double>> spans(double y) const;
    // The region's extent: {x0, y0, x1, y1}.
    std::array<double, 4> bounds() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace camgen
