#pragma once
// The motion a program makes, as a flat list of steps: canned drilling cycles expanded with
// the posts' longhand semantics (longhand.hpp), arcs kept as arcs. Built from a program read
// back (reader.hpp) or from a job's events, so the two can be compared (compare.hpp), measured
// (stats.hpp) and drawn (backplot.hpp).
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/arc.hpp"
#include "camgen/events/events.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"

namespace camgen {

enum class StepKind { rapid, feed, dwell, tool_change, spindle };

// One step of motion or machine state.
struct Step {
    StepKind kind = StepKind::rapid;
    Vec3 from;                       // rapid, feed: start (meaningless when !from_known)
    Vec3 to;                         // rapid, feed: end
    bool from_known = true;          // false: from the tool-change position, path unknown
    double feed = 0.0;               // feed: mm/min as programmed
    double pitch = 0.0;              // feed: mm per spindle turn when the move follows the spindle (tapping, or a
                                     // per-revolution feed, G95), else 0
    Movement movement = Movement::cutting;  // feed: as the job's events say; read back: plunge or ramp
                                            // where the motion shows it (straight down, down along XY)
    std::optional<ArcGeometry> arc;  // feed: set for a circular move
    double seconds = 0.0;            // dwell
    int tool = 0;                    // the tool in the spindle (tool_change: the new one)
    SpindleState spindle = SpindleState::off;  // spindle
    double rpm = 0.0;                // spindle
    int line = 0;                    // program line (0: from a job)
    double uncertainty = 0.0;        // mm, see ReadEvent::uncertainty
};

// A hole: a feed move down at one XY position that the tool leaves upwards again before it
// moves in XY (canned or longhand drilling alike; a contour's plunge is no hole).
struct Hole {
    Vec2 at;
    double bottom_z = 0.0;
    int tool = 0;
    int line = 0;  // the line of the deepest feed move
};

// A tool as far as the program or job says (diameter 0: unknown).
struct ToolInfo {
    int number = 0;
    double diameter = 0.0;  // mm
    std::string description;
};

// The motion of a whole program or job.
struct Trace {
    std::vector<Step> steps;
    std::vector<Hole> holes;      // in drilling order
    int canned_holes = 0;         // holes drilled by a canned cycle (the others are longhand)
    std::vector<ToolInfo> tools;  // in order of first use
};

// The motion of a program read back. `machine` gives the peck clearance of longhand cycles.
Trace trace_program(const std::vector<ReadEvent>& events, const Machine& machine);

// The motion of a job's events (the position is unknown at the start and after every tool
// change, as in the posts).
Trace trace_events(const std::vector<Event>& events, const Machine& machine);

// The motion a job's events (expand_job) should make on `machine`: feeds clamped to the
// machine's limits, as every post writes them.
Trace trace_expected(const std::vector<Event>& job_events, const Machine& machine);

}  // namespace camgen
