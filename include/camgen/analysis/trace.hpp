#pragma once
// The motion a program makes, as a flat list of steps: canned drilling cycles expanded with
// the posts' longhand semantics (longhand.hpp), arcs kept as arcs. Built from a program read
// back (reader.hpp) or from a job's events, so the two can be compared (compare.hpp), measured
// (stats.hpp) and drawn (backplot.hpp).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camgen/common/error.hpp"
#include "camgen/geometry/arc.hpp"
#include "camgen/events/events.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/stops.hpp"
#include "camgen/reader/reader.hpp"

namespace camgen {

enum class StepKind { rapid, feed, dwell, tool_change, spindle, stop };

// One step of motion or machine state.
struct Step {
    // The small fields first, then the doubles: Step stays at 256 bytes, up to which GCC copies a
    // struct with moves (a step is copied several times on its way to the comparison; at 272
    // bytes every copy became rep movs, 8 % of verify --job's time on 200,000 holes).
    StepKind kind = StepKind::rapid;
    Movement movement = Movement::cutting;  // feed: as the job's events say; read back: plunge or ramp
                                            // where the motion shows it (straight down, down along XY)
    SpindleState spindle = SpindleState::off;  // spindle
    StopKind stop = StopKind::mandatory;  // stop: M0 or the optional M1
    int tool = 0;                    // the tool in the spindle (tool_change: the new one)
    int line = 0;                    // program line (0: from a job)
    bool from_known = true;          // false: from the tool-change position, path unknown
    // The tool length offset and work offset in force: a program's as it selected them
    // (ReadEvent::offsets), a job's those its post selects (post_length_offset for the tool, the
    // job's workOffset: TraceOptions::work_offset).
    SelectedOffsets offsets;
    Vec3 from;                       // rapid, feed: start (meaningless when !from_known)
    Vec3 to;                         // rapid, feed: end
    double feed = 0.0;               // feed: mm/min as programmed
    double pitch = 0.0;              // feed: mm per spindle turn when the move follows the spindle (tapping, or a
                                     // per-revolution feed, G95), else 0
    std::optional<ArcGeometry> arc;  // feed: set for a circular move
    double seconds = 0.0;            // dwell
    double rpm = 0.0;                // spindle; under a constant surface speed its limit
    double surface_speed = 0.0;      // spindle: m/min under G96 (the rpm follows the radius |x|), else 0
    double uncertainty = 0.0;        // mm, see ReadEvent::uncertainty
};
static_assert(sizeof(Step) <= 256, "a Step over 256 bytes is copied with rep movs by GCC: see its comment");

// A hole: a feed move down at one XY position that the tool leaves upwards again before it
// moves in XY (canned or longhand drilling alike; a contour's plunge is no hole).
struct Hole {
    Vec2 at;
    double bottom_z = 0.0;
    int tool = 0;
    int line = 0;  // the line of the deepest feed move
};

// A stop for the operator: its line and message (stats list them).
struct StopNote {
    int line = 0;  // 0: from a job
    StopKind kind = StopKind::mandatory;
    std::string message;
};

// The most stops a trace keeps the message of (more are counted).
inline constexpr std::size_t max_stop_notes = 100;

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
    std::vector<std::string> notes;  // what the trace took as given (see TraceSummary::notes)
    std::vector<StopNote> stops;     // the first max_stop_notes stops
    int stop_count = 0;              // every stop
};

// What a trace says beyond its steps and holes, known at its end.
struct TraceSummary {
    int canned_holes = 0;         // holes drilled by a canned cycle
    std::vector<ToolInfo> tools;  // in order of first use
    std::vector<std::string> notes;  // what the steps took as given where the program did not say (a
                                     // G41/G42 whose radius is unknown: its moves as programmed)
    std::vector<StopNote> stops;     // the first max_stop_notes stops, with their messages
    int stop_count = 0;              // every stop
};

// How a program's steps are made. A program says G41/G42 and an offset register (D; none: the
// tool's number); the radius is the control's. `compensation_radii` is that register's radius in
// mm, as the control holds it (LinuxCNC: the tool of that number in its tool table); a register
// missing here takes the diameter the program gives its tool (a ToolChange), else its moves are
// taken as programmed, with a note. A job's events carry their radius and need none of this.
//
// `rounding`: for a job's events, half the unit a program writes coordinates in (0: exact).
// Under compensation the control offsets the moves as written: a short move's direction, and so
// its offset, turns with its ends' rounding by radius x rounding / length (a 0.47 mm chord
// written to 0.001 mm and offset by 5 mm lands 0.002 mm from the exact chord's offset). So
// the job's programmed XY ends under compensation are rounded to that unit, as the post writes
// them, before they are offset.
struct TraceOptions {
    std::map<int, double> compensation_radii;
    double rounding = 0.0;  // mm
    // A lathe's G41/G42 (G18): the tip orientation (LinuxCNC's codes) of the tool of that number,
    // as the control's table holds it; a tool missing here is taken as orientation 0 (the
    // programmed point the nose centre), with a note.
    std::map<int, int> compensation_orientations;
    // A job's events: the job's work offset (workOffset; "": none, the post writes none), in
    // force at every step (Step::offsets) with the length offset the post selects for the tool.
    std::string work_offset;
};

// ControlRefusal (camgen/common/error.hpp): what the control refuses, thrown by the trace and by
// the readers (a tap cycle against the running spindle).

// Receives a trace as it is made: its steps in order, each hole once the tool has left it
// (before the step that shows it has), then the end. The read-back's consumers (statistics,
// comparison, drawing) are sinks, so that no one keeps a whole program's steps.
class TraceSink {
public:
    virtual ~TraceSink() = default;
    virtual void step(const Step& step) = 0;
    virtual void hole(const Hole& hole) = 0;
    virtual void finish(const TraceSummary& summary) = 0;
};

// Hands a trace to several sinks, each step to each in the order given.
class TraceFanOut : public TraceSink {
public:
    explicit TraceFanOut(std::vector<TraceSink*> sinks) : sinks_(std::move(sinks)) {}
    void step(const Step& step) override;
    void hole(const Hole& hole) override;
    void finish(const TraceSummary& summary) override;

private:
    std::vector<TraceSink*> sinks_;
};

// Keeps a whole trace (what trace_program returns).
class TraceCollector : public TraceSink {
public:
    void step(const Step& step) override { trace_.steps.push_back(step); }
    void hole(const Hole& hole) override { trace_.holes.push_back(hole); }
    void finish(const TraceSummary& summary) override;
    Trace take() { return std::move(trace_); }

private:
    Trace trace_;
};

// Turns events into steps one at a time (the streaming core of trace_program and
// trace_events): canned cycles expanded, holes found in the motion, and cutter compensation
// (G41/G42 in the XY plane) applied as the control applies it (geometry/compensation.hpp,
// LinuxCNC's rules), so that the steps are where the tool centre goes, never the programmed
// line. Under compensation it holds at most one move in XY and the moves after it without XY
// motion (and the dwells and spindle changes among them) until the next move decides the corner.
// What the control refuses throws ControlRefusal. Read events come from a reader (it is a
// ReadEventSink); a job's events through add_job_event, which knows where the position is
// unknown as the posts do.
class TraceBuilder : public ReadEventSink {
public:
    // `machine` gives the peck clearance of longhand cycles; `options` the compensation radii.
    TraceBuilder(const Machine& machine, TraceSink& sink, TraceOptions options = {});
    ~TraceBuilder() override;
    void read_event(const ReadEvent& event) override;
    // One event of a job (expand_job): its stops as the posts make them (OperatorStops).
    void add_job_event(const Event& event);
    // The end of the events: the last hole, then sink.finish.
    void finish() override;
    // A job's events after OperatorStops (what the posts write), to add_job_event.
    struct JobEvents : EventSink {
        TraceBuilder& trace;
        explicit JobEvents(TraceBuilder& t) : trace(t) {}
        void emit(const Event& e) override { trace.add_stopped_event(e); }
    };
    // The notes so far (TraceSummary::notes), for a caller whose sinks do not keep them.
    const std::vector<std::string>& notes() const;

private:
    // One event of a job after OperatorStops.
    void add_stopped_event(const Event& event);
    const Machine& machine_;
    SelectedOffsets job_offsets_;  // job events: the offsets the post selects (Step::offsets)
    class Impl;
    std::unique_ptr<Impl> impl_;
    JobEvents job_events_{*this};
    std::unique_ptr<OperatorStops> stops_;  // a job's events go through it (add_job_event)
    bool known_ = false;  // job events: the position is known (a rapid since the last tool change or stop)
};

// Passes a trace on with every feed clamped to the machine's limits, as every post writes it
// (what a job's events should become on `machine`: trace_expected).
class FeedClamp : public TraceSink {
public:
    FeedClamp(const Machine& machine, TraceSink& next) : min_(machine.limits.min_feed), max_(machine.limits.max_feed), next_(next) {}
    void step(const Step& step) override;
    void hole(const Hole& hole) override { next_.hole(hole); }
    void finish(const TraceSummary& summary) override { next_.finish(summary); }

private:
    double min_, max_;
    TraceSink& next_;
};

// The motion of a program read back. `machine` gives the peck clearance of longhand cycles,
// `options` the compensation radii.
Trace trace_program(const std::vector<ReadEvent>& events, const Machine& machine, const TraceOptions& options = {});

// The motion of a job's events (the position is unknown at the start and after every tool
// change, as in the posts).
Trace trace_events(const std::vector<Event>& events, const Machine& machine);

// The motion a job's events (expand_job) should make on `machine`: feeds clamped to the
// machine's limits, as every post writes them; `work_offset` the job's (TraceOptions::work_offset).
Trace trace_expected(const std::vector<Event>& job_events, const Machine& machine, const std::string& work_offset = {});

}  // namespace camgen
