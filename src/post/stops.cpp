#include "camgen/post/stops.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "camgen/events/visit.hpp"

namespace camgen {

namespace {

// The holes a stop's message may show (more are counted).
constexpr std::size_t most_shown = 8;

// What the operator does at a hole of a cycle of this kind.
std::string verb_of(CycleKind kind) {
    switch (kind) {
        case CycleKind::tap: return "Tap";
        case CycleKind::tap_left: return "Tap left-hand";
        default: return fmt::format("Make the {} hole", name_of(cycle_kinds, kind));
    }
}

}  // namespace

namespace {
// The machine's format `key` as a person reads it: no forced decimals, sign, prefix or width.
nc::Format plain_format(const Machine& machine, const std::string& key) {
    nc::FormatSpec spec = machine.format(key).spec();
    spec.force_decimal = false;
    spec.force_sign = false;
    spec.prefix.clear();
    spec.width = 0;
    return nc::Format(spec);
}

}  // namespace

std::optional<std::string> impossible_cycle(const Machine& machine, const DrillCycle& cycle) {
    if (!is_tapping(cycle.kind)) return std::nullopt;
    if (machine.tapping == TappingMode::none) return fmt::format("machine {} cannot tap", machine.name);
    if (machine.tapping == TappingMode::rigid && !machine.canned_cycle(cycle.kind))
        return fmt::format("machine {} taps only rigidly and has no canned cycle for \"{}\"", machine.name,
                           name_of(cycle_kinds, cycle.kind));
    return std::nullopt;
}

OperatorStops::OperatorStops(const Machine& machine, EventSink& next) : machine_(machine), next_(next) {}

std::string OperatorStops::position(Vec2 at) const {
    // A lathe drills on its axis (X as the machine writes it, a diameter or a radius).
    if (machine_.kind == MachineKind::lathe) return "X" + plain_format(machine_, "x").format(at.x);
    const nc::Format f = plain_format(machine_, "xyz");
    return fmt::format("X{} Y{}", f.format(at.x), f.format(at.y));
}

void OperatorStops::stop(const Stop& s) {
    Resume r = resume_.value_or(Resume{});
    if (coolant_.mode != CoolantMode::off) {
        r.coolant = coolant_;
        next_.emit(Coolant{CoolantMode::off, coolant_.path});
        coolant_ = Coolant{CoolantMode::off, ""};
    }
    if (spindle_ != SpindleState::off) {
        r.spindle = Spindle{spindle_, rpm_, surface_speed_};
        next_.emit(Spindle{SpindleState::off, 0.0});
        spindle_ = SpindleState::off;
    }
    r.spin_up = std::max(r.spin_up, s.spin_up);
    next_.emit(s);
    // The operator may have moved the axes.
    pos_.reset();
    if (r.spindle || r.coolant) resume_ = r;
}

void OperatorStops::resume() {
    if (!resume_) return;
    const Resume r = *resume_;
    resume_.reset();
    if (r.spindle) {
        spindle_ = r.spindle->state;
        rpm_ = r.spindle->rpm;
        surface_speed_ = r.spindle->surface_speed;
        next_.emit(*r.spindle);
        if (r.spin_up > 0) next_.emit(Dwell{r.spin_up});
    }
    if (r.coolant) {
        coolant_ = *r.coolant;
        next_.emit(*r.coolant);
    }
}

void OperatorStops::left_out(const DrillCycle& c, const std::string& why) {
    leaving_ = LeftOut{c, tool_, {}, 0};
    const std::string& op = op_name_.empty() ? op_path_ : op_name_;
    next_.emit(Comment{fmt::format("{}: {}; made by hand at the stop after this operation", op, why)});
    const nc::Format len = plain_format(machine_, "xyz");
    const std::string unit(name_of(unit_names, machine_.units));
    std::string what = fmt::format("{} with tool {}", verb_of(c.kind), tool_);
    if (!tool_description_.empty()) what += ", " + tool_description_;
    if (is_tapping(c.kind))
        what += fmt::format(", pitch {} {}",
                            nc::exact_format(len.spec(), c.values.value_or(DrillField::pitch, 0.0), 6)
                                .format(c.values.value_or(DrillField::pitch, 0.0)),
                            unit);
    what += fmt::format(", from Z{} to Z{}", len.format(std::min(c.reference_z, c.safe_z)), len.format(c.bottom_z));
    next_.emit(Comment{what});
}

Stop OperatorStops::stop_for(const LeftOut& l) const {
    const std::string head = fmt::format("{} by hand with tool {} at ", verb_of(l.cycle.kind), l.tool);
    const std::string all = fmt::format(", {} hole{}", l.count, l.count == 1 ? "" : "s");
    std::string shown;
    std::size_t n = 0;
    for (; n < l.shown.size(); ++n) {
        const std::string next = (n ? shown + ", " : shown) + position(l.shown[n]);
        const std::size_t rest = l.count - (n + 1);
        const std::string tail = rest == 0 ? all : fmt::format(" and {} more, {} holes listed above", rest, l.count);
        if (n > 0 && head.size() + next.size() + tail.size() > max_stop_message) break;
        shown = next;
    }
    const std::size_t rest = l.count - n;
    const std::string tail = rest == 0 ? all : fmt::format(" and {} more, {} holes listed above", rest, l.count);
    std::string message = head + shown + tail;
    if (message.size() > max_stop_message) message.resize(max_stop_message);
    return Stop{StopKind::mandatory, message, unsupported_spin_up};
}

void OperatorStops::emit(const Event& event) {
    visit_exhaustive(overloaded{
                         [&](const OperationStart& o) {
                             op_path_ = o.path;
                             op_name_ = o.name;
                             op_top_.reset();
                             next_.emit(event);
                         },
                         [&](const OperationEnd&) {
                             // The tool is at the clearance: the operator's turn.
                             for (const LeftOut& l : left_) stop(stop_for(l));
                             left_.clear();
                             next_.emit(event);
                         },
                         [&](const ToolChange& t) {
                             // The new tool's own spindle start takes the place of a restart.
                             resume_.reset();
                             tool_ = t.number;
                             tool_description_ = t.description;
                             pos_.reset();
                             next_.emit(event);
                         },
                         [&](const Spindle& s) {
                             if (resume_ && resume_->spindle) {
                                 resume_->spindle.reset();
                                 if (!resume_->coolant) resume_.reset();
                                 // Stopped already: not again.
                                 if (s.state == SpindleState::off && spindle_ == SpindleState::off) return;
                             }
                             spindle_ = s.state;
                             rpm_ = s.state == SpindleState::off ? 0.0 : s.rpm;
                             surface_speed_ = s.state == SpindleState::off ? 0.0 : s.surface_speed;
                             next_.emit(event);
                         },
                         [&](const Coolant& c) {
                             if (resume_ && resume_->coolant) {
                                 resume_->coolant.reset();
                                 if (!resume_->spindle) resume_.reset();
                                 if (c.mode == CoolantMode::off && coolant_.mode == CoolantMode::off) return;
                             }
                             coolant_ = c;
                             next_.emit(event);
                         },
                         [&](const Rapid& r) {
                             resume();
                             pos_ = r.to;
                             op_top_ = std::max(op_top_.value_or(r.to.z), r.to.z);
                             next_.emit(event);
                         },
                         [&](const Linear& l) {
                             resume();
                             pos_ = l.to;
                             next_.emit(event);
                         },
                         [&](const Arc& a) {
                             resume();
                             pos_ = a.to;
                             next_.emit(event);
                         },
                         [&](const ThreadFeed& t) {
                             resume();
                             pos_ = t.to;
                             next_.emit(event);
                         },
                         [&](const ThreadCycle& c) {
                             resume();
                             pos_ = thread_cycle_end(c, machine_.thread_pattern());
                             next_.emit(event);
                         },
                         [&](const TurnCycle& c) {
                             resume();
                             if (!c.moves.empty()) pos_ = turn_cycle_end(c, machine_.rough_pattern());
                             next_.emit(event);
                         },
                         [&](const FinishCycle& c) {
                             resume();
                             pos_ = finish_cycle_end(c, machine_.rough_pattern());
                             next_.emit(event);
                         },
                         [&](const GrooveCycle& c) {
                             resume();
                             pos_ = groove_cycle_end(c);
                             next_.emit(event);
                         },
                         [&](const Dwell&) {
                             resume();
                             next_.emit(event);
                         },
                         [&](const Compensation&) {
                             resume();
                             next_.emit(event);
                         },
                         [&](const DrillCycle& c) {
                             if (c.unsupported == UnsupportedCycle::stop)
                                 if (auto why = impossible_cycle(machine_, c)) return left_out(c, *why);
                             resume();
                             next_.emit(event);
                         },
                         [&](const DrillPoint& p) {
                             if (!leaving_) return next_.emit(event);
                             LeftOut& l = *leaving_;
                             if (l.shown.size() < most_shown) l.shown.push_back(p.at);
                             ++l.count;
                             next_.emit(Comment{fmt::format("hole {}: {}", l.count, position(p.at))});
                         },
                         [&](const DrillEnd&) {
                             if (!leaving_) return next_.emit(event);
                             left_.push_back(std::move(*leaving_));
                             leaving_.reset();
                             // Straight up to where the operation came from (the clearance): the
                             // next rapid of the operation goes across at that height.
                             if (pos_ && op_top_ && *op_top_ > pos_->z) {
                                 pos_->z = *op_top_;
                                 next_.emit(Rapid{*pos_});
                             }
                         },
                         [&](const Comment&) { next_.emit(event); },
                         [&](const Stop& s) { stop(s); },
                         [&](const CustomBlock&) { next_.emit(event); },
                     },
                     event);
}

}  // namespace camgen
