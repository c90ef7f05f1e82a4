#pragma once
// A simulated part against the job's design (operations/design.hpp): where the program removed
// material the design keeps (a gouge: an error) and where it left material a cut should have
// removed beyond its allowance (a warning). The simulated part is a height field sampled at
// cell centres; a cell is judged only where its centre lies farther than `margin` inside a
// region (a cell across a wall could go either way), so the check is exact at the centres it
// judges and says nothing within the margin of a wall.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/region.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/design.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// The simulated part as the check reads it: cells of `cell` mm from (x0, y0), their centres at
// x0 + (i + 0.5) cell; `height(i, j)` the material's top there (NaN: no stock), `line(i, j)` the
// program line of the move that last lowered it (0: none).
struct HeightGridView {
    double x0 = 0.0, y0 = 0.0, cell = 1.0;
    std::size_t nx = 0, ny = 0;
    double top = 1e300;      // the stock's top: a design above it is taken at it
    double bottom = -1e300;  // the stock's bottom: a floor below it is taken at it (a through hole)
    std::optional<PlaneRegion> stock;  // a profile stock's outline: cells outside it are not judged
    std::function<double(std::size_t, std::size_t)> height;
    std::function<int(std::size_t, std::size_t)> line;
};

struct DesignFinding {
    enum class Kind { gouge, left };
    Kind kind = Kind::gouge;
    std::string path;     // the operation whose design it breaks
    std::string what;     // its cut or keep ("the pocket", "island 0", "tab 2")
    Vec2 at;              // the worst cell's centre
    double height = 0.0;  // the simulated top there
    double designed = 0.0;  // the designed height there (gouge) or the floor plus its allowance (left)
    double amount = 0.0;  // mm below (gouge) or above (left)
    std::size_t cells = 0;  // cells of this finding
    std::size_t points = 0; // wall probes of this finding (DesignProbes)
    int line = 0;         // the program line that cut the worst cell (gouge)
    std::string message() const;
};

// Points on the part's walls, which the cells miss: the cells within the margin of a cut's edge
// are not judged, so a tool that strays a little into a wall (a lead-in arc 0.05 mm into the
// part) could leave no judged cell lower. Along every loop of every keep, a point every
// `spacing` mm, `tolerance` inside the keep (where a tool that enters the wall by more than the
// tolerance lowers it), kept where it lies within the margin of a cut's edge (elsewhere the
// cells judge) and farther than half the tolerance from every cut's edge (on an edge it could go
// either way). Its designed height is its keep's top, or the lowest floor of the cuts that
// cover it (a face over the part). The simulation sweeps them exactly (SimOptions::probes).
struct DesignProbes {
    std::vector<Vec2> points;
    std::vector<double> designed;      // mm
    std::vector<std::uint32_t> owner;  // the feature: cuts 0..C-1, then keeps
    double spacing = 0.0;              // mm, as used: the cell, or more where the budget asks
};
DesignProbes design_probes(const PartDesign& design, const HeightGridView& grid, double tolerance, double margin,
                           std::size_t budget = 1'000'000);

// The probes as swept: each point's height and the line that last lowered it.
struct ProbeHeights {
    const DesignProbes* probes = nullptr;
    const std::vector<double>* heights = nullptr;
    const std::vector<std::int32_t>* lines = nullptr;
};

// Every finding, the worst cell (or probe) of each cut or keep, gouges first, in the design's
// order. `tolerance`: mm a height may differ from the design (chords, rounding); `margin`: mm a
// judged centre keeps from a region's edge (at least half a cell's diagonal plus the tolerance).
std::vector<DesignFinding> check_design(const PartDesign& design, const HeightGridView& grid, double tolerance, double margin,
                                        const ProbeHeights& probes = {});

// A cycle the machine cannot make, left to the operator at a stop (OperatorStops: a tap where
// the machine cannot tap), makes nothing the program cuts: its cuts (a mill's drill) or bore (a
// lathe's turn-drill) leave the design, and `design.unchecked` says why.
void leave_out_operator_cycles(PartDesign& design, const Job& job, const Machine& machine);

}  // namespace camgen
