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
    // How messages name a point (compare_tolerance copies them): a lathe's as X and Z, X as a
    // diameter where the machine programs it so, as the program writes it.
    bool lathe = false;
    bool x_diameter = false;
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

// What differs between the offsets a job's post selects and those a program has in force at a
// move of `tool` (SelectedOffsets: the tool length offset, then the work offset), in words
// that name where the program selected them; nullopt when they are the same.
std::optional<std::string> offsets_difference(const SelectedOffsets& job, const SelectedOffsets& program, int tool);

// Compares the motion: the same tool changes, spindle states, dwells, and the same path in
// the same order, rapid where rapid and at the same feed where feeding, under the same
// offsets (Step::offsets: the tool length offset the post selects for each tool and the job's
// work offset, at every move). Paths are compared
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
// The offsets alone, for a program whose moves are not compared with a job's (simulate --job):
// each move of the program (its steps, as a sink) against the tool length offset `machine`'s post
// selects for the tool in the spindle and the job's `work_offset` ("": none). `found` is told of
// the first move of each run of moves under other offsets, with what differs, at its line.
class OffsetCheck : public TraceSink {
public:
    OffsetCheck(const Machine& machine, std::string work_offset, std::function<void(const Mismatch&, const Step&)> found);
    void step(const Step& step) override;
    void hole(const Hole&) override {}
    void finish(const TraceSummary&) override {}

private:
    const Machine& machine_;
    std::function<void(const Mismatch&, const Step&)> found_;
    SelectedOffsets expected_;
    std::optional<SelectedOffsets> reported_;  // the wrong offsets of the run told of last
};

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
