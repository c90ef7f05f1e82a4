#pragma once
// Pictures of a simulated part (`camgen simulate --png/--section/--plot/--stl`):
// - PNG (cairo): a mill's top view shaded and coloured by depth, with a depth scale and a mm
//   scale bar, and optionally a section along a segment drawn to scale; a lathe's half-section
//   (the turned profile r(z), the bore, the bar as it was);
// - binary STL: a mill's height field as a closed surface of cell columns, a lathe's profile
//   revolved;
// - the HTML page: the same views drawn by the page's script from a coarse copy of the part and
//   its history (`SimHistory`), a block slider that shows the part cut up to that block, and a
//   WebGL view of the height field.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "camgen/geometry/vec.hpp"
#include "camgen/simulation/simulation.hpp"

namespace camgen {

// A section's segment in XY, mm.
struct SectionLine {
    Vec2 a, b;
};

// One sample of a section: its distance from the segment's start and the field's height there
// (the cell under the point), mm; `inside` false where the point is off the field.
struct SectionSample {
    double distance = 0.0;
    double height = 0.0;
    bool inside = false;
    bool stock = false;  // the stock held material there before the program (for its outline)
};

// The field along a segment: a sample at every crossing of a cell's edge and in each cell
// crossed (the profile is a step function of the cells the segment passes, each at its centre).
std::vector<SectionSample> field_section(const HeightField& field, const SectionLine& line);

// Whether a cell held material before the program: it holds some now, or a move lowered it.
inline bool had_stock(const HeightField& f, std::size_t index) {
    return f.heights[index] > f.bottom || f.lines[index] != 0;
}

// An RGB colour, 0 to 255 a channel.
struct Rgb {
    int r = 0, g = 0, b = 0;
    bool operator==(const Rgb&) const = default;
};

// The colour of a depth below the stock's top, as a fraction of the stock's height (0: the
// uncut top, 1: the bottom). A flat area of the top view is drawn in exactly this colour.
Rgb depth_colour(double fraction);
// The colour of a column with no material (a through cut, or outside the stock).
inline constexpr Rgb no_material_colour{255, 255, 255};

// What the picture's title says.
struct PictureLabels {
    std::string program;
    std::string machine;
};

// Where the top view lies in the PNG: a point (x, y) of the field is at pixel
// (left + (x - x0) * scale, top + (y1 - y) * scale). A lathe's half-section: the point (z, r)
// at (left + (z - x0) * scale, top + (y1 - r) * scale), y1 the bar's radius.
struct TopViewFrame {
    double left = 0.0, top = 0.0;  // px
    double scale = 0.0;            // px per mm
    double x0 = 0.0, y1 = 0.0;     // mm: the field's left and far edges
    int width = 0, height = 0;     // px, of the whole image
    // The section (mill, when drawn): the point at distance d along it and height z is at
    // (section_left + d * section_scale, section_base - (z - bottom) * section_z_scale).
    double section_left = 0.0, section_base = 0.0, section_scale = 0.0, section_z_scale = 0.0;
};

// The PNG of a simulated part: a mill's top view (and the section, when given), a lathe's
// half-section (a section is refused: SimInputError). Writes the PNG's bytes to `out`; returns
// where the top view lies (mill), for tests and the page.
TopViewFrame write_simulation_png(const SimResult& result, const std::optional<SectionLine>& section,
                                  const PictureLabels& labels, std::ostream& out);

// How the STL is made.
struct StlOptions {
    std::size_t mill_cells = 250'000;  // a larger field is merged into blocks of k x k cells (the
                                       // blocks' mean heights: the volume kept)
    int lathe_segments = 128;          // around the axis
    std::size_t lathe_bands = 4'000;   // a profile of more Z samples is merged into bands (the
                                       // bands' mean ring areas: the volume kept)
};

// What the STL holds, for the report and tests.
struct StlSummary {
    std::size_t triangles = 0;
    int block = 1;  // mill: cells merged into a block on a side; lathe: samples merged into a band
};

// The simulated part as a binary STL in mm (deterministic). Mill: every column of material a
// box from the stock's bottom to its height (cells of the same height side by side share their
// top), the walls between columns of different heights split where the neighbouring columns'
// heights meet them, so that every edge of the closed surface is one of two triangles (four at
// a saddle corner, where two columns meet only diagonally above the other two). Lathe: the
// profile r(z) revolved as a polygon of `lathe_segments` sides (vertices on the circle).
StlSummary write_simulation_stl(const SimResult& result, const StlOptions& options, std::ostream& out);

// The history the page's block slider replays, kept as the simulation runs (a SimObserver):
// a coarse copy of the part (mill: at most `coarse_side` x `coarse_side` cells, each the lowest
// of the field's cells in it; lathe: at most `coarse_side` x 4 bands of Z, each the smallest
// outside radius and the largest bore of its samples) and a log of its changes in program
// order, each (coarse cell, program line, new value). A change is logged when a coarse cell
// falls at least `quantum` below its last logged value; whenever the log would exceed
// `event_budget`, the quantum is doubled and the log thinned to it; at the end each cell's
// exact final value is logged where it differs from its last. Memory: the coarse copy and the
// budget, whatever the program.
class SimHistory : public SimObserver {
public:
    static constexpr int coarse_side = 256;
    static constexpr std::size_t default_event_budget = 400'000;
    // `initial`: the result before the first move (Simulator::result() after construction).
    explicit SimHistory(const SimResult& initial, std::size_t event_budget = default_event_budget);
    void lowered(std::size_t cell, float height, int line) override;
    void turned(int sample, double outside, double bore, int line) override;
    // Logs the final values; call once the simulation has finished.
    void finish(const SimResult& final_result);

    struct Event {
        std::int32_t cell = 0;
        std::int32_t line = 0;
        float value = 0.0f;   // mill: the height; lathe: the outside radius
        float value2 = 0.0f;  // lathe: the bore's radius
    };
    MachineKind kind = MachineKind::mill;
    int factor = 1;       // field cells (or samples) merged into one coarse cell a side
    int nx = 0, ny = 0;   // coarse cells (lathe: ny 1, nx bands)
    double x0 = 0, y0 = 0, cell = 0;  // mill: the coarse grid, mm; lathe: z0 and the band length in x0, cell
    double top = 0, bottom = 0;       // mill: the stock's top and bottom; lathe: the bar's radius and 0
    std::vector<float> initial;       // coarse values before the program (lathe: outside, then bore)
    std::vector<float> final;         // after it
    std::vector<Event> events;        // in program order
    double quantum = 0;               // mm, as thinned
    std::size_t budget = 0;
    std::size_t thinned = 0;          // changes left out of the log

private:
    void log(std::size_t coarse, int line, float value, float value2);
    void thin();
    std::vector<float> current_;      // the coarse part now (lathe: outside, then bore)
    std::vector<float> logged_;       // the last logged value of each coarse cell (lathe: both)
    std::vector<std::int32_t> current_line_;
    int field_nx_ = 0;
};

// The page: title, the top view (or the lathe's half-section) and the section drawn by its
// script from the history, the block slider with the program's text (as the backplot page:
// #block=N shows the part cut up to block N), and a WebGL view of the height field. `text`
// opens the program, which is read once and copied in a line at a time.
void write_simulation_html(std::ostream& out, const SimResult& result, const SimHistory& history,
                           const std::optional<SectionLine>& section, const PictureLabels& labels,
                           const std::function<std::istream&()>& text);

}  // namespace camgen
