#pragma once
// A simulated turned part against the job's lathe design (operations/design_lathe.hpp): where
// the program removed material the design keeps (a gouge: an error, at the line that cut it) and
// where it left material an operation should have removed (a warning, with where and how much).
//
// The turned part is one radius per Z (the outside, and the bore), so every Z sample of the
// simulation is judged, exactly: the simulated radii there are exact and so is the design
// (lines and arcs). A position may be `tolerance` off in Z as well as in radius: at Z z the
// design is taken over [z - tolerance, z + tolerance] (the least of it where material must stay,
// the most where it must be gone), so a sample beside a shoulder may be either side of it. The
// samples miss what lies between them: a tool that strays into a shoulder's face by less than a
// Z step; so the simulation also sweeps sections (LatheSections) `tolerance` x 1.1 beside every
// corner of the designed profiles and every hole's point, judged as the samples are. Between
// samples on a slope a gouge reads up to its slope x the Z step less deep than it is.
#include <cstddef>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "camgen/operations/design.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/simulation/simulation.hpp"

namespace camgen {

struct Job;

struct LatheFinding {
    enum class Kind { gouge, left };
    // ring: a face groove's walls (designed..designed_hi: the ring's radii); ring_bottom: below
    // its bottom (designed: the bottom's Z; amount: mm in Z below it).
    enum class Surface { outside, bore, ring, ring_bottom };
    Kind kind = Kind::gouge;
    Surface surface = Surface::outside;
    std::string path;        // the operation whose design it breaks (for the bar no operation turns: the one that cut it)
    std::string what;        // "the part inside the profile", "the part below the hole's point", ...
    double z = 0.0;          // the worst position's Z, mm
    double radius = 0.0;     // the simulated radius there (outside or bore), mm
    double designed = 0.0;   // the designed radius there: the least kept (gouge), the most left (left)
    double amount = 0.0;     // mm in radius beyond it
    double designed_hi = 0.0;  // ring: the ring's outer radius (designed: its inner)
    std::size_t samples = 0; // Z samples of this finding
    std::size_t sections = 0;  // sections beside corners of this finding
    int line = 0;            // the program line that last turned the worst position (gouge)
    std::string message() const;
};

struct LatheCheck {
    std::vector<LatheFinding> findings;  // gouges first, then material left, each in the design's order
    std::vector<std::string> notes;      // what the tools' noses leave beyond the profiles
    std::size_t samples = 0;             // samples and sections judged (in the bar)
    std::size_t sections = 0;
};

// The Z of the sections the check needs: `offset` either side of every corner of the designed
// profiles and of every hole's point and the top of its cone, within the bar, sorted, once each.
std::vector<double> lathe_check_sections(const LatheDesign& design, const SimStock& bar, double offset);

// The simulated bar (`part`, and `sections` at the Z lathe_check_sections gave) against the design
// of the bar `bar`. `tolerance`: mm the part may differ in radius and in Z; `operations`: the
// program's lines by operation, to name the operation that cut the bar where none designs it.
LatheCheck check_lathe_design(const LatheDesign& design, const SimStock& bar, const LatheProfile& part,
                              const LatheSections& sections, double tolerance,
                              const std::vector<OperationSpan>& operations = {});

// The shapes of a job's tools (tool_shapes), a threading tool given no orientation swept as
// its turn-thread programs it: orientation 2 on the outside, 3 for an internal thread (its tip
// +X of its nose, at the bore's wall).
std::map<int, ToolShape> job_tool_shapes(const Job& job);

// `camgen simulate`'s lathe design check: made before the sweep (it gives the simulator its
// sections), reported after it.
struct LatheDesignCheck {
    PartDesign design;
    SimStock bar;
    double tolerance = 0.0;
    double offset = 0.0;  // the sections' distance from the corners, mm
};
// The job's design (part_design; a turn-drill whose cycle the machine cannot make is left to the
// operator, not checked) within compare_tolerance(machine).path, as the mill's check.
LatheDesignCheck prepare_lathe_design_check(const Job& job, const Machine& machine, const SimStock& bar, Simulator& sim);
// Writes "design check ..." and a line for each operation not checked, each note and each finding
// ("error: gouge: ...", "warning: ..."), or "  the part is as designed"; returns the gouges' count.
std::size_t report_lathe_design_check(const LatheDesignCheck& check, const SimResult& result,
                                      const std::vector<OperationSpan>& operations, std::ostream& out);

}  // namespace camgen
