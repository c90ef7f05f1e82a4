#pragma once
// The backplot: an SVG drawing of a program as read back (XY view, looking down Z), what a
// machinist looks at before running a program: rapids dashed, feed moves solid with their
// direction, one colour per tool, holes marked and numbered in drilling order, a grid with
// coordinates, the work zero, a scale bar and a legend with the statistics.
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camgen/analysis/trace.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen {

// The layers of a drawing: each move, hole and band belongs to one, and to its tool.
enum class BackplotLayer { rapid, feed, plunge, ramp, lead, width, hole };
inline constexpr Named<BackplotLayer> backplot_layers[] = {
    {BackplotLayer::rapid, "rapid", "rapid moves (G0)"},
    {BackplotLayer::feed, "feed", "feed moves along the path (cutting, finishing)"},
    {BackplotLayer::plunge, "plunge", "feed moves straight down, and their marks"},
    {BackplotLayer::ramp, "ramp", "feed moves down along the path or a helix"},
    {BackplotLayer::lead, "lead", "lead-in and lead-out moves"},
    {BackplotLayer::width, "width", "the width the tool cuts"},
    {BackplotLayer::hole, "hole", "holes and their numbers"},
};

// The layer of a rapid or feed move: rapid, or its feed's movement kind.
BackplotLayer layer_of(const Step& step);

// Whether the drawing's elements say which layer they belong to.
enum class BackplotLayers {
    none,     // a plain drawing (the SVG file)
    classes,  // every element of a layer carries class="tN k-LAYER" (N: its tool), feed moves
              // drawn apart by movement kind (the HTML page switches layers with them)
};

// A lathe's bar as the job's stock gives it (mm): drawn as its outline in the half-section.
struct BackplotBar {
    double diameter = 0.0;
    double length = 0.0;                  // along Z, back from the face
    double face_z = 0.0;                  // Z of the face
    std::optional<double> bore_diameter;  // a tube's inner diameter
};

struct BackplotOptions {
    std::string title;    // the program's name ("plate.nc")
    std::string machine;  // the machine's name
    MachineKind kind = MachineKind::mill;  // a lathe's program is drawn as an XZ half-section
    BackplotLayers layers = BackplotLayers::none;
    // Holes drawn with their own circle and cross, in drilling order; the rest as plain
    // circles, one path per tool (a page with very many holes stays small).
    std::size_t hole_marks = std::numeric_limits<std::size_t>::max();
    // Moves of each kind, plunge marks, cut widths and holes drawn as they are up to this many
    // each; beyond, only those that cover a pixel of the drawing that none of their kind and
    // tool covered before, and holes as plain circles numbered only where they are a tool's
    // last: the drawing of a program of millions of lines stays within what its picture
    // shows. The legend says how many were left out.
    std::size_t exact = 10000;
    // A lathe's bar (the job's stock, where a job is given): its outline in the half-section.
    std::optional<BackplotBar> bar;
};

// Where a drawing puts a position, in SVG user units: x = left + (u - min_u) * scale and
// y = top + (max_v - v) * scale, with (u, v) = (X, Y) in a mill's XY view and (Z, X) in a
// lathe's half-section.
struct BackplotFrame {
    double min_u = 0, max_v = 0, scale = 1, left = 0, top = 0;
};

struct BackplotDrawing {
    std::string svg;
    BackplotFrame frame;
};

// What a drawing must know before its first move, from a first pass over the trace (its
// statistics come from the same pass): the extent of each tool's holes, their places (a plunge
// there is a hole's, not a plunge mark: 16 bytes a hole) and each tool's first and last hole.
class BackplotPlan : public TraceSink {
public:
    explicit BackplotPlan(MachineKind kind);
    void step(const Step& step) override {
        if (step.kind == StepKind::rapid || step.kind == StepKind::feed) ++moves;
    }
    void hole(const Hole& hole) override;
    void finish(const TraceSummary& summary) override;

    std::size_t moves = 0;                          // rapid and feed moves (the HTML page thins beyond a count)
    std::map<int, Box> hole_centres;                // tool -> the box around its holes' centres
    std::vector<Vec2> places;                       // every hole's place, by X then Y after finish
    std::map<int, std::pair<int, int>> first_last;  // tool -> its first and last hole's number
    std::size_t holes = 0;

private:
    MachineKind kind_;
};

// The drawing as the trace is read a second time (the streaming core of backplot_svg): each
// step and hole drawn as it comes, into buffers that options.exact bounds.
class BackplotDrawer : public TraceSink {
public:
    // `plan` (finished) and `stats` of the first pass; the plan must outlive the drawer.
    BackplotDrawer(const BackplotPlan& plan, const ProgramStats& stats, const BackplotOptions& options);
    ~BackplotDrawer() override;
    void step(const Step& step) override;
    void hole(const Hole& hole) override;
    void finish(const TraceSummary& summary) override;
    // The drawing, once finished.
    BackplotDrawing take() { return std::move(drawing_); }

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
    BackplotDrawing drawing_;
};

// The SVG text. Deterministic: every number goes through one fixed formatter. A lathe's
// program (options.kind) is drawn as a half-section: Z to the right, X (the radius) up, the
// spindle axis at X0 - the profile, the drilled hole's pecks along the axis, rapids dashed.
std::string backplot_svg(const Trace& trace, const ProgramStats& stats, const BackplotOptions& options);

// The same drawing and its frame, for marks laid over it (the HTML page's tool marker).
BackplotDrawing backplot_drawing(const Trace& trace, const ProgramStats& stats, const BackplotOptions& options);

}  // namespace camgen
