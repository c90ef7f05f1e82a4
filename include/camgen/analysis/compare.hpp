#pragma once
// Comparing two traces (verify --job): does a program make the motion its job asks for?
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "camgen/analysis/trace.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"

namespace camgen {

// How close two traces must be.
struct CompareTolerance {
    double position = 0.001;  // mm, block end points (plus each step's uncertainty)
    double path = 0.001;      // mm, points inside arcs (an arc may be written as chords)
    double feed = 0.5;        // mm/min
    double dwell = 0.0005;    // s
    double rpm = 0.5;         // rev/min
    // The machine's arc rules (compare_tolerance copies them; none by default): a job's arc
    // that the post writes as one straight move (written_as_one_line: below minRadius or
    // minLength) is compared as that move, allowed to lie as far off as the arc strays from it.
    ArcSettings arcs;
};

// Tolerances for comparing a job with a program for `machine`: `position` mm for end points
// (raised to the distance that half a unit of the last decimal on each axis makes, where the
// machine writes fewer decimals; position 0 asks for exactly that), and for points
// inside arcs that plus the machine's arc tolerance and chord tolerance (arcs that become
// lines, arcs whose centres are rounded).
CompareTolerance compare_tolerance(const Machine& machine, double position = 0.001);
// The same for a program read with this resolution (read_program's coarsest resolution).
CompareTolerance compare_tolerance(const Machine& machine, const ReadResolution& resolution, double position = 0.001);

// The first difference between two traces.
struct Mismatch {
    int line = 0;         // the actual program's line, where known
    std::string message;  // what was expected and what the program does
};

// Compares the motion: the same tool changes, spindle states, dwells, and the same path in
// the same order, rapid where rapid and at the same feed where feeding. Paths are compared
// as positions visited, not as blocks: an arc written as two half arcs or as chords matches
// the arc it stands for; every end point of each side must lie on the other's path, in
// order, and points sampled along arcs too. Moves from an unknown position compare only by
// their end.
std::optional<Mismatch> compare_traces(const Trace& expected, const Trace& actual, const CompareTolerance& tolerance);

// The same comparison as two traces are made (the streaming core of compare_traces): the
// expected trace (a job's) and the actual one (a program's) are handed in step by step, each
// to its sink, and the comparer keeps only the paths it has not compared yet (a run of rapid or
// feed moves and the one after it), so that a million-hole program is compared in constant
// memory. The expected side may lead: when the comparer needs more of the actual trace it calls
// `more_actual`, which hands on the next part of it (false: there is no more, the actual
// sink has finished). Without it the actual side must lead.
class TraceComparer {
public:
    TraceComparer(const CompareTolerance& tolerance, std::function<bool()> more_actual = {});
    ~TraceComparer();
    TraceComparer(const TraceComparer&) = delete;
    TraceComparer& operator=(const TraceComparer&) = delete;
    TraceSink& expected();
    TraceSink& actual();
    // True once the result is known (the first difference, or both traces finished).
    bool decided() const;
    // The first difference; nullopt when both traces finished and match. Only once decided.
    const std::optional<Mismatch>& mismatch() const;

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace camgen
