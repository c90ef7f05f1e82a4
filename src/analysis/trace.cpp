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

// A hole is a run of moves at one XY position that feeds down and then leaves upwards.
std::vector<Hole> find_holes(const std::vector<Step>& steps) {
    std::vector<Hole> holes;
    bool active = false, down = false, up_after = false;
    Hole hole;
    auto close = [&] {
        if (active && down && up_after) holes.push_back(hole);
        active = down = up_after = false;
    };
    for (const Step& s : steps) {
        if (s.kind == StepKind::tool_change) {
            close();
            continue;
        }
        if (s.kind != StepKind::rapid && s.kind != StepKind::feed) continue;
        if (!s.from_known || xy_moves(s)) {
            close();
            active = true;
            hole = Hole{{s.to.x, s.to.y}, s.to.z, s.tool, s.line};
            continue;
        }
        if (s.kind == StepKind::feed && s.to.z < s.from.z) {
            if (!down || s.to.z < hole.bottom_z) {
                hole.bottom_z = s.to.z;
                hole.line = s.line;
            }
            down = true;
            up_after = false;
        } else if (s.to.z > s.from.z && down) {
            up_after = true;
        }
    }
    close();
    return holes;
}

class Tracer {
public:
    explicit Tracer(const Machine& machine) : options_(machine.longhand()) {}

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
                           Step s = base(StepKind::tool_change);
                           trace_.steps.push_back(s);
                           known_ = false;
                           auto it = std::find_if(trace_.tools.begin(), trace_.tools.end(),
                                                  [&](const ToolInfo& i) { return i.number == t.number; });
                           if (it == trace_.tools.end())
                               trace_.tools.push_back({t.number, t.diameter, t.description});
                           else if (it->diameter == 0.0)
                               *it = {t.number, t.diameter, t.description};
                       },
                       [&](const Coolant&) {},  // no motion; verify does not compare coolant yet
                       [&](const Spindle& sp) {
                           Step s = base(StepKind::spindle);
                           s.spindle = sp.state;
                           s.rpm = sp.rpm;
                           trace_.steps.push_back(s);
                       },
                       [&](const Rapid& r) { move(StepKind::rapid, r.to, 0.0, e.from_unknown); },
                       [&](const Linear& l) {
                           move(StepKind::feed, l.to, l.feed, false);
                           if (!trace_.steps.empty() && trace_.steps.back().kind == StepKind::feed) {
                               trace_.steps.back().movement = l.movement;
                               if (e.per_revolution > 0) trace_.steps.back().pitch = e.per_revolution;
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
                           trace_.steps.push_back(s);
                           pos_ = a.to;
                       },
                       [&](const Dwell& d) {
                           Step s = base(StepKind::dwell);
                           s.seconds = d.seconds;
                           trace_.steps.push_back(s);
                       },
                       [&](const DrillCycle& c) { cycle_ = c; },
                       [&](const DrillPoint& p) {
                           if (!cycle_) throw std::logic_error("drill point outside a cycle");
                           if (!known_) throw std::logic_error("drilling from an unknown position");
                           ++trace_.canned_holes;
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

    Trace finish() {
        // A program does not say what kind a feed move is; its motion does where it goes down.
        for (Step& s : trace_.steps) {
            if (s.kind != StepKind::feed || s.movement != Movement::cutting || !(s.to.z < s.from.z)) continue;
            const bool straight_down = !s.arc && s.to.x == s.from.x && s.to.y == s.from.y;
            s.movement = straight_down ? Movement::plunge : Movement::ramp;
        }
        trace_.holes = find_holes(trace_.steps);
        return std::move(trace_);
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

    void move(StepKind kind, const Vec3& to, double feed, bool from_unknown) {
        bool from_known = known_ && !from_unknown;
        if (kind == StepKind::feed && !from_known) throw std::logic_error("feed move from an unknown position");
        if (from_known && to == pos_) return;
        Step s = base(kind);
        s.from = from_known ? pos_ : to;
        s.to = to;
        s.from_known = from_known;
        s.feed = feed;
        if (kind == StepKind::feed) s.pitch = pitch_;
        trace_.steps.push_back(s);
        pos_ = to;
        known_ = true;
    }

    LonghandOptions options_;
    LonghandBuffers longhand_buffers_;  // reused by every canned hole's moves
    Trace trace_;
    Vec3 pos_;
    bool known_ = false;
    int tool_ = 0;
    int line_ = 0;
    double uncertainty_ = 0.0;
    double pitch_ = 0.0;  // while a tap is expanded
    std::optional<DrillCycle> cycle_;
};

}  // namespace

Trace trace_program(const std::vector<ReadEvent>& events, const Machine& machine) {
    Tracer t(machine);
    for (const ReadEvent& e : events) t.add(e);
    return t.finish();
}

Trace trace_events(const std::vector<Event>& events, const Machine& machine) {
    Tracer t(machine);
    bool known = false;
    for (const Event& e : events) {
        ReadEvent r{e};
        if (std::holds_alternative<ToolChange>(e)) known = false;
        if (std::holds_alternative<Rapid>(e)) {
            r.from_unknown = !known;
            known = true;
        }
        t.add(r);
    }
    return t.finish();
}

Trace trace_expected(const std::vector<Event>& job_events, const Machine& machine) {
    Trace t = trace_events(job_events, machine);
    // The posts clamp every feed to the machine's limits (with a warning).
    for (Step& s : t.steps)
        if (s.kind == StepKind::feed) s.feed = std::clamp(s.feed, machine.limits.min_feed, machine.limits.max_feed);
    return t;
}

}  // namespace camgen
