#pragma once
// Material simulation: the motion a program makes (the steps of a TraceBuilder: tool-centre
// moves with cutter compensation applied, lines and arcs, tool changes) swept through a stock.
// A mill's stock is a height field (Z-map) over its XY extent; a lathe's bar is its turned
// profile r(z) (and bore, and the rings of air a face blade cuts inside the material: LatheGap)
// sampled along Z. Each move lowers the material it passes through to the tool's lowest surface
// and is then dropped: memory is the field plus a constant (a lathe's rings: a list a sample,
// made at the first ring, 24 bytes a sample and 24 a ring).
//
// Exactness (mill, heights at each cell's centre):
// - a straight move: exact for every tool shape where the move is horizontal or vertical; a
//   flat (or cylindrical) tool on any straight 3D move is exact (the covered interval of the
//   move by a quadratic, the lowest point at its lower end); a ball on any straight move is
//   exact (the swept capsule met by the column: a quadratic and the two end spheres); a
//   bull-nose or cone tip on a sloping move is found by golden-section search of the lowest
//   surface over the covered interval (convex in the move's parameter: a convex, radially
//   non-decreasing tool profile over the convex distance of a column from a line), to 1e-10 of
//   the move: the height error is below 1e-6 mm for a cone and below sqrt(2 x corner radius x
//   1e-10 x move length) for a bull-nose;
// - an arc in XY at one height: exact for every tool (the column's nearest point on the arc);
// - a helix, or an arc in XZ or YZ: chords whose sagitta (the largest distance of the tool
//   centre from the arc) is at most `arc_chord_fraction` x the cell (1/8) and 0.0005 mm (below
//   the design check's least tolerance: its wall points lie that far into a wall), each exact
//   as above.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <optional>
#include <string>
#include <vector>

#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// The shape of a tool's cutting end.
enum class ToolForm {
    flat,       // flat end mill (and a face mill)
    ball,       // ball end mill: a hemisphere of the tool's radius
    bull_nose,  // flat bottom with a corner radius
    cone,       // a point: drill and spot drill (tip angle), chamfer mill and V-bit (tip angle and
                // tip diameter, the flat at the point)
    cylinder,   // tap, reamer: its diameter, flat at the end
    turning,    // a lathe's tool: its tip point, or a circle of its nose radius
    blade,      // a grooving or parting tool: a flat edge `diameter` wide (its width) along Z, its body
                // straight out in +X; its programmed point at the edge's Z + blade_lo. Orientation 3
                // or 4 (an internal grooving tool): the edge faces +X, its body towards the axis (it
                // opens the bore). Orientation 7 (a face grooving tool): the edge faces -Z, `diameter`
                // wide along X from the programmed point (its inner corner) out, its body along +Z
};

// A tool as the simulation sweeps it, mm and degrees.
struct ToolShape {
    ToolForm form = ToolForm::flat;
    double diameter = 0.0;                // mm (turning: unused)
    double corner_radius = 0.0;           // bull_nose: mm, at most the radius
    double tip_angle = 118.0;             // cone: included angle, degrees (0 < angle < 180)
    double tip_diameter = 0.0;            // cone: the flat at the point, mm (0: a sharp point)
    double nose_radius = 0.0;             // turning: mm (0: the tip point); the program's point is the
                                          // imaginary tip of `orientation`
    int orientation = 2;                  // turning: LinuxCNC's tip code (1-9): the nose centre is the
                                          // program's point less lathe_tip_offset (2: a radius above in X and Z);
                                          // blade: which way its edge faces (see ToolForm::blade)
    // turning: the insert beyond its nose, drawn as an outside tool cutting towards the chuck's
    // (orientation 2): its two flanks leave the nose circle (tangent to it) in the directions
    // flank_lo and flank_hi, degrees from +Z towards +X, and the insert and its holder fill the
    // angle between them (0 <= flank_lo <= flank_hi <= 180, less than 180 apart), without end.
    // The end edge is flank_lo (180 - approachAngle - insertAngle), the main edge flank_hi
    // (180 - approachAngle). Mirrored in Z for an outside tool whose tip lies on the nose's +Z
    // side (orientations 1 and 5: cutting towards the tailstock) and in X where the tip lies on
    // its +X side (3, 4, 8: a boring tool, not mirrored in Z: its bar runs out of the bore
    // towards +Z). The default, 0 and 90: an end edge along Z and a main edge
    // along X, an insert that cuts no undercut (a tool whose angles are not given).
    double flank_lo = 0.0;
    double flank_hi = 90.0;
    double blade_lo = 0.0;                // blade: the edge's -Z end from the programmed point, mm (0: the
                                          // left corner is programmed; -diameter: the right one)
    std::optional<double> flute_length;   // mm; a feed cutting deeper than this is an error
    bool thread_mill = false;             // a thread mill: made to cut a thread's depth, not stock (a note
                                          // above thread_mill_engagement)
    bool threading = false;               // a lathe's threading tool: a pass deeper than thread_pass_depth
                                          // of its lead is an error (an overloaded insert)
};

// The radial engagement (of the diameter) above which a thread mill's cut gets a note: a metric
// thread's depth is 0.61 x its pitch, at most a few tenths of the tool's diameter.
inline constexpr double thread_mill_engagement = 0.5;

// The deepest a threading tool's pass following the spindle may cut in one go, radial, per mm of
// its lead: the height of a sharp 60-degree V of that lead (sqrt(3)/2), deeper than the whole of
// an ISO or unified thread (0.613 x the pitch). A pass deeper than that cuts into a diameter
// larger than the thread's major (a bore less than its minor): the insert is overloaded, as good
// as a crash.
inline constexpr double thread_pass_depth = 0.8660254037844386;

// The stock before the program runs.
struct SimStock {
    enum class Kind { box, profile, bar };
    Kind kind = Kind::box;
    // box: its corners, mm
    Vec3 min, max;
    // profile: a closed profile in XY, the material between bottom and top (mm)
    Profile profile;
    double top = 0.0, bottom = 0.0;
    // bar (lathe, Z along the spindle, radius along X): from face_z down to face_z - length
    double bar_diameter = 0.0;
    double bar_length = 0.0;
    double face_z = 0.0;
    std::optional<double> bore_diameter;  // a tube: its inside diameter
};

// A program line from which on the steps belong to an operation (its JSON path).
struct OperationSpan {
    int first_line = 0;
    std::string path;
};

// Told of every change of the stock as it happens (the page's history of the part, pictures.hpp).
class SimObserver {
public:
    virtual ~SimObserver() = default;
    // Mill: the field's cell `cell` (row after row) was lowered to `height` by program line `line`.
    virtual void lowered(std::size_t cell, float height, int line) = 0;
    // Lathe: Z sample `sample` was turned to this outside radius and bore by line `line`.
    virtual void turned(int sample, double outside, double bore, int line) = 0;
};

// How to simulate.
struct SimOptions {
    double resolution = 0.0;               // mm per cell (mill) or Z sample (lathe); 0: from the budget
    std::size_t cell_budget = 4'000'000;   // mill: the most cells when no resolution is given
    std::size_t lathe_budget = 100'000;    // lathe: the most Z samples when no resolution is given
    double crash_depth = 0.002;            // mm: a rapid that removes more than this in a column is a crash
    std::vector<OperationSpan> operations; // sorted by first_line; steps before the first: no operation
    // mill: points whose heights are swept exactly as cells' centres are (the design check's
    // points on the part's walls, which the cells' centres miss); at most 2^32.
    std::vector<Vec2> probes;
    // lathe: Z positions swept exactly as the samples are (the design check's sections beside
    // a designed profile's corners, which the samples may miss); any order, at most 2^31.
    std::vector<double> lathe_sections;
    SimObserver* observer = nullptr;       // told of each change (none: nothing costs)
};

// The chords of a helix (or of an arc out of XY) keep the tool centre within this fraction
// of a cell of the arc.
inline constexpr double arc_chord_fraction = 0.125;

// The height field of a mill's stock: the material's top at each cell's centre, row after row
// (x fastest). A column with no material holds `bottom`.
struct HeightField {
    double x0 = 0.0, y0 = 0.0;   // the corner of cell (0, 0), mm
    double cell = 0.0;           // mm
    int nx = 0, ny = 0;
    double bottom = 0.0;         // the stock's bottom, mm
    double top = 0.0;            // the stock's top as it was, mm
    std::vector<float> heights;  // nx * ny
    std::vector<std::int32_t> lines;  // nx * ny: the program line of the move that last lowered the cell (0: none)
    double at(int i, int j) const { return heights[static_cast<std::size_t>(j) * nx + i]; }
    // The centre of cell (i, j).
    double x(int i) const { return x0 + (i + 0.5) * cell; }
    double y(int j) const { return y0 + (j + 0.5) * cell; }
};

// A ring of air inside a lathe's material at one Z (a face groove's): radii lo < hi, strictly
// between the bore and the outside, and the program line that last widened it.
struct LatheGap {
    double lo = 0.0, hi = 0.0;  // mm, radius
    std::int32_t line = 0;
};

// The material at one Z: from the bore to the outside less the gaps (sorted, apart, strictly
// inside); radial length of it within [lo, hi], its largest piece there, its area (mm^2).
double lathe_material_within(double outside, double bore, const std::vector<LatheGap>* gaps, double lo, double hi,
                             bool largest_piece = false);
double lathe_material_area(double outside, double bore, const std::vector<LatheGap>* gaps);

// A lathe's bar: at each Z sample the outside radius and the bore's radius (0: none), less the
// rings of air a face blade cut inside the material (`gaps`); no material where the outside is
// not above the bore.
struct LatheProfile {
    double z0 = 0.0;    // the bottom of sample 0, mm (face_z - length)
    double dz = 0.0;    // mm
    int nz = 0;
    std::vector<double> outside;  // mm, radius
    std::vector<double> bore;     // mm, radius
    // The program line of the move that last turned each sample's outside, and its bore (0: none).
    std::vector<std::int32_t> outside_lines, bore_lines;
    // Each sample's gaps, sorted by radius: empty until a face blade cuts a ring inside the
    // material (then nz lists, most of them empty).
    std::vector<std::vector<LatheGap>> gaps;
    double z(int k) const { return z0 + (k + 0.5) * dz; }
    // Sample k's gaps, or null where it has none.
    const std::vector<LatheGap>* gaps_at(int k) const {
        return gaps.empty() || gaps[static_cast<std::size_t>(k)].empty() ? nullptr : &gaps[static_cast<std::size_t>(k)];
    }
};

// A lathe's bar at given Z positions (SimOptions::lathe_sections), swept exactly as the samples
// are: the outside radius and the bore there (no material where the outside is not above the
// bore: beyond the bar's ends), the lines that last turned them (0: none) and the gaps, as
// LatheProfile's.
struct LatheSections {
    std::vector<double> z, outside, bore;  // mm
    std::vector<std::int32_t> outside_lines, bore_lines;
    std::vector<std::vector<LatheGap>> gaps;
    const std::vector<LatheGap>* gaps_at(std::size_t i) const {
        return gaps.empty() || gaps[i].empty() ? nullptr : &gaps[i];
    }
};

// An error the simulation found, at a program line (0: a job's event) and operation.
struct SimReport {
    int line = 0;
    std::string operation;  // the operation's JSON path, empty when unknown
    int tool = 0;
    std::string message;
};

// Material removed and the largest radial engagement, per tool or per operation.
struct SimFigure {
    std::string name;           // "T3" or the operation's path
    int tool = 0;
    double volume = 0.0;        // mm^3
    double max_engagement = 0.0;  // the largest fraction of the diameter in material (see below)
    int engagement_line = 0;    // the line of that move
};

// Radial engagement of a feed move with XY motion: at sample points along the move (one a cell,
// at most 256), the width across the direction of travel, within the tool's radius, of the
// columns that held material above the tool's lowest surface there before the move, as a
// fraction of the diameter. A slot is 1, a side cut of a quarter of the diameter 0.25.
// Plunges (no XY motion) and lathe moves have none.

// What a simulation found.
struct SimResult {
    MachineKind kind = MachineKind::mill;
    double resolution = 0.0;     // mm, as chosen
    std::size_t cells = 0;       // cells (mill) or Z samples (lathe)
    HeightField field;           // mill
    LatheProfile lathe;          // lathe
    double initial_volume = 0.0; // mm^3
    double removed_volume = 0.0; // mm^3
    std::vector<SimFigure> tools;       // in order of first cut
    std::vector<SimFigure> operations;  // in order of first cut (empty without OperationSpans)
    std::vector<SimReport> errors;      // in program order
    ProgramStats stats;          // machining time and lengths, as verify --stats
    std::size_t cell_updates = 0;  // columns (or samples) visited by moves, for the rate
    std::vector<std::string> notes;  // what was not swept, and why
    // mill, SimOptions::probes: the material's top at each probe (NaN outside the stock) and the
    // program line of the move that last lowered it (0: none).
    std::vector<double> probe_heights;
    std::vector<std::int32_t> probe_lines;
    LatheSections lathe_sections;  // lathe, SimOptions::lathe_sections: in their order
};

// Refused simulation input (a stock or a tool that cannot be swept), with its reason.
class SimInputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Sweeps steps as they come (a TraceSink): hand it to a TraceBuilder, or to a TraceFanOut
// beside other sinks. Tools missing from `tools` are refused at their first move.
class Simulator : public TraceSink {
public:
    Simulator(const Machine& machine, SimStock stock, std::map<int, ToolShape> tools, SimOptions options = {});
    ~Simulator() override;
    void step(const Step& step) override;
    void hole(const Hole& hole) override;
    void finish(const TraceSummary& summary) override;
    // The steps that follow belong to this operation (a job's OperationStart; read-back
    // programs use SimOptions::operations).
    void begin_operation(std::string path);
    // Sets SimOptions::probes (before the first step): a mill's field is laid out by then
    // (result().field), so that probes can be placed on it.
    void set_probes(std::vector<Vec2> points);
    // Sets SimOptions::lathe_sections (before the first step; a lathe's).
    void set_lathe_sections(std::vector<double> z);
    // An error found beside the sweep at a program line (a move under offsets the job's post does
    // not select: OffsetCheck), among the errors in program order (told before the line's step).
    void report_error(int line, int tool, std::string message);
    // From now on tell `observer` of each change (nullptr: none).
    void observe(SimObserver* observer);
    // The result, complete after finish.
    const SimResult& result() const;
    SimResult take();

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

// The shape of a job's tool: end mill flat, ball mill ball, drill, centre and spot drill a cone
// of their tip angle (118 and 90 degrees where none is given), tap, reamer and boring bar a
// cylinder, a turning tool its nose (its diameter is the nose's); fluteLength as given.
ToolShape tool_shape(const Tool& tool);
std::map<int, ToolShape> tool_shapes(const std::map<int, Tool>& tools);

// Sweeps a whole trace's steps.
SimResult simulate(const std::vector<Step>& steps, const Machine& machine, const SimStock& stock,
                   const std::map<int, ToolShape>& tools, const SimOptions& options = {});

// The result as text: resolution, cells, volumes per tool and operation, engagement, time and
// the errors, each at its line.
std::string format_simulation(const SimResult& result);

}  // namespace camgen
