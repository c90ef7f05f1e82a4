// Events -> motion steps: canned cycles expanded with the posts' longhand semantics, holes
// found in the motion itself so that canned and longhand drilling count alike.
#include <algorithm>
#include <cmath>

#include "camgen/common/error.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/post/longhand.hpp"
#include "camgen/analysis/trace.hpp"

namespace camgen {

namespace {

constexpr double same_xy = 1e-6;  // mm

bool xy_moves(const Step& s) {
    return s.arc || std::hypot(s.to.x - s.from.x, s.to.y - s.from.y) > same_xy;
}

// A hole is a run of moves at one XY position that feeds down and then leaves upwards; it is
// known once the tool moves on in XY, changes or the trace ends.
class HoleFinder {
public:
    // The step that comes next; a hole it ends goes to the sink first.
    void step(const Step& s, TraceSink& sink) {
        if (s.kind == StepKind::tool_change) {
            close(sink);
            return;
        }
        if (s.kind != StepKind::rapid && s.kind != StepKind::feed) return;
        if (!s.from_known || xy_moves(s)) {
            close(sink);
            active_ = true;
            hole_ = Hole{{s.to.x, s.to.y}, s.to.z, s.tool, s.line};
            return;
        }
        if (s.kind == StepKind::feed && s.to.z < s.from.z) {
            if (!down_ || s.to.z < hole_.bottom_z) {
                hole_.bottom_z = s.to.z;
                hole_.line = s.line;
            }
            down_ = true;
            up_after_ = false;
        } else if (s.to.z > s.from.z && down_) {
            up_after_ = true;
        }
    }
    void close(TraceSink& sink) {
        if (active_ && down_ && up_after_) sink.hole(hole_);
        active_ = down_ = up_after_ = false;
    }

private:
    bool active_ = false, down_ = false, up_after_ = false;
    Hole hole_;
};

}  // namespace

class TraceBuilder::Impl {
public:
    Impl(const Machine& machine, TraceSink& sink)
        : options_(machine.longhand()), lathe_(machine.kind == MachineKind::lathe), sink_(sink) {}

    void add(const ReadEvent& e) {
        line_ = e.line;
        uncertainty_ = e.uncertainty;
        visit_exhaustive(overloaded{
                       [&](const OperationStart&) {},
                       [&](const OperationEnd&) {},
                       [&](const Comment&) {},
                       // No motion of its own: with compensation on, the steps are the programmed
                       // path (the profile), which is what a job with control compensation expects
                       // too. The control's offset path is LinuxCNC's to show (the rs274 oracle).
                       [&](const Compensation&) {},
                       [&](const ToolChange& t) {
                           tool_ = t.number;
                           emit(base(StepKind::tool_change));
                           known_ = false;
                           auto it = std::find_if(summary_.tools.begin(), summary_.tools.end(),
                                                  [&](const ToolInfo& i) { return i.number == t.number; });
                           if (it == summary_.tools.end())
                               summary_.tools.push_back({t.number, t.diameter, t.description});
                           else if (it->diameter == 0.0)
                               *it = {t.number, t.diameter, t.description};
                       },
                       [&](const Coolant&) {},  // no motion; verify does not compare coolant yet
                       [&](const Spindle& sp) {
                           Step s = base(StepKind::spindle);
                           s.spindle = sp.state;
                           s.rpm = sp.rpm;
                           emit(s);
                       },
                       [&](const Rapid& r) {
                           if (auto s = move(StepKind::rapid, r.to, 0.0, e.from_unknown)) emit(*s);
                       },
                       [&](const Linear& l) {
                           if (auto s = move(StepKind::feed, l.to, l.feed, false)) {
                               s->movement = l.movement;
                               if (e.per_revolution > 0) s->pitch = e.per_revolution;
                               emit(*s);
                           }
                       },
                       [&](const Arc& a) {
                           if (!known_) throw std::logic_error("arc from an unknown position");
                           Step s = base(StepKind::feed);
                           s.from = pos_;
                           s.to = a.to;
                           s.feed = a.feed;
                           s.arc = resolve_arc(pos_, a);
                           s.movement = a.movement;
                           s.pitch = e.per_revolution;
                           pos_ = a.to;
                           emit(s);
                       },
                       [&](const Dwell& d) {
                           Step s = base(StepKind::dwell);
                           s.seconds = d.seconds;
                           emit(s);
                       },
                       [&](const DrillCycle& c) { cycle_ = c; },
                       [&](const DrillPoint& p) {
                           if (!cycle_) throw std::logic_error("drill point outside a cycle");
                           if (!known_) throw std::logic_error("drilling from an unknown position");
                           ++summary_.canned_holes;
                           // A tap's feed follows the spindle: its moves carry the pitch, so that a
                           // comparison allows for the speed the program could write.
                           pitch_ = is_tapping(cycle_->kind) ? cycle_->values.value_or(DrillField::pitch, 0.0) : 0.0;
                           for (const LonghandMove& m : longhand_moves(*cycle_, pos_, p.at, options_, longhand_buffers_))
                               add(ReadEvent{.event = to_event(m), .line = e.line, .uncertainty = e.uncertainty,
                                             .per_revolution = e.per_revolution});
                           pitch_ = 0.0;
                       },
                       [&](const DrillEnd&) { cycle_.reset(); },
                   },
                   e.event);
    }

    void finish() {
        holes_.close(sink_);
        sink_.finish(summary_);
    }

private:
    Step base(StepKind kind) const {
        Step s;
        s.kind = kind;
        s.tool = tool_;
        s.line = line_;
        s.uncertainty = uncertainty_;
        return s;
    }

    // A step to the sink, its holes found first. A program does not say what kind a feed move
    // is; its motion does where it goes down. On a lathe Z is the spindle's axis: a feed towards
    // the chuck turns the work, except on the axis, where a drill plunges.
    void emit(Step s) {
        if (s.kind == StepKind::feed && s.movement == Movement::cutting && s.to.z < s.from.z) {
            const bool straight_down = !s.arc && s.to.x == s.from.x && s.to.y == s.from.y;
            if (!lathe_) s.movement = straight_down ? Movement::plunge : Movement::ramp;
            else if (straight_down && s.to.x == 0.0 && s.to.y == 0.0) s.movement = Movement::plunge;
        }
        holes_.step(s, sink_);
        sink_.step(s);
    }

    // The step of a straight move, or none where it goes nowhere from a known position.
    std::optional<Step> move(StepKind kind, const Vec3& to, double feed, bool from_unknown) {
        bool from_known = known_ && !from_unknown;
        if (kind == StepKind::feed && !from_known) throw std::logic_error("feed move from an unknown position");
        if (from_known && to == pos_) return std::nullopt;
        Step s = base(kind);
        s.from = from_known ? pos_ : to;
        s.to = to;
        s.from_known = from_known;
        s.feed = feed;
        if (kind == StepKind::feed) s.pitch = pitch_;
        pos_ = to;
        known_ = true;
        return s;
    }

    LonghandOptions options_;
    bool lathe_;  // Z is the spindle axis
    LonghandBuffers longhand_buffers_;  // reused by every canned hole's moves
    TraceSink& sink_;
    HoleFinder holes_;
    TraceSummary summary_;
    Vec3 pos_;
    bool known_ = false;
    int tool_ = 0;
    int line_ = 0;
    double uncertainty_ = 0.0;
    double pitch_ = 0.0;  // while a tap is expanded
    std::optional<DrillCycle> cycle_;
};

TraceBuilder::TraceBuilder(const Machine& machine, TraceSink& sink) : impl_(std::make_unique<Impl>(machine, sink)) {}

TraceBuilder::~TraceBuilder() = default;

void TraceBuilder::read_event(const ReadEvent& event) { impl_->add(event); }

void TraceBuilder::add_job_event(const Event& e) {
    ReadEvent r{e};
    if (std::holds_alternative<ToolChange>(e)) known_ = false;
    if (std::holds_alternative<Rapid>(e)) {
        r.from_unknown = !known_;
        known_ = true;
    }
    impl_->add(r);
}

void TraceBuilder::finish() { impl_->finish(); }

void TraceFanOut::step(const Step& step) {
    for (TraceSink* s : sinks_) s->step(step);
}

void TraceFanOut::hole(const Hole& hole) {
    for (TraceSink* s : sinks_) s->hole(hole);
}

void TraceFanOut::finish(const TraceSummary& summary) {
    for (TraceSink* s : sinks_) s->finish(summary);
}

void TraceCollector::finish(const TraceSummary& summary) {
    trace_.canned_holes = summary.canned_holes;
    trace_.tools = summary.tools;
}

void FeedClamp::step(const Step& step) {
    if (step.kind != StepKind::feed) return next_.step(step);
    Step s = step;
    s.feed = std::clamp(s.feed, min_, max_);
    next_.step(s);
}

Trace trace_program(const std::vector<ReadEvent>& events, const Machine& machine) {
    TraceCollector trace;
    TraceBuilder t(machine, trace);
    for (const ReadEvent& e : events) t.read_event(e);
    t.finish();
    return trace.take();
}

Trace trace_events(const std::vector<Event>& events, const Machine& machine) {
    TraceCollector trace;
    TraceBuilder t(machine, trace);
    for (const Event& e : events) t.add_job_event(e);
    t.finish();
    return trace.take();
}

Trace trace_expected(const std::vector<Event>& job_events, const Machine& machine) {
    TraceCollector trace;
    FeedClamp clamp(machine, trace);
    TraceBuilder t(machine, clamp);
    for (const Event& e : job_events) t.add_job_event(e);
    t.finish();
    return trace.take();
}

}  // namespace camgen
