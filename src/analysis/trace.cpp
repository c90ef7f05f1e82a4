// Events -> motion steps: canned cycles expanded with the posts' longhand semantics, holes
// found in the motion itself so that canned and longhand drilling count alike.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <deque>
#include <set>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/post/arc_output.hpp"
#include "camgen/post/longhand.hpp"
#include "camgen/post/post.hpp"
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
    Impl(const Machine& machine, TraceSink& sink, TraceOptions options)
        : options_(machine.longhand()), lathe_(machine.kind == MachineKind::lathe), arcs_(machine.arcs),
          thread_pattern_(machine.thread_pattern()), rough_pattern_(machine.rough_pattern()), sink_(sink), trace_options_(std::move(options)) {}

    // `job`: an event of a job (its Compensation carries the radius), not of a program.
    void add(const ReadEvent& e, bool job) {
        line_ = e.line;
        uncertainty_ = e.uncertainty;
        offsets_ = e.offsets;
        visit_exhaustive(overloaded{
                       [&](const OperationStart& o) {
                           operation_path_ = o.path;
                           op_tolerance_ = o.tolerance;
                       },
                       [&](const OperationEnd&) {},
                       [&](const Comment& c) { comment_orientation(c.text); },
                       // No motion of its own: the moves after it are offset as the control
                       // offsets them (comp_move), so the steps are the tool centre's path.
                       [&](const Compensation& c) { compensation(c, job); },
                       [&](const ToolChange& t) {
                           if (comp_ && comp_->active())
                               refuse(CompError{"Cannot change tools with cutter radius compensation on", 0});
                           end_compensation();
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
                           s.surface_speed = sp.state == SpindleState::off ? 0.0 : sp.surface_speed;
                           thread_rpm_ = sp.state == SpindleState::off ? 0.0 : sp.rpm;
                           emit_in_order(s);
                       },
                       [&](const Rapid& r) {
                           Programmed p = programmed(StepKind::rapid, 0.0, Movement::cutting, 0.0, e.from_unknown);
                           if (comp_) return comp_move(comp_straight(CompMove::Kind::rapid, to_plane(r.to)), p);
                           straight(r.to, p);
                       },
                       [&](const Linear& l) {
                           Programmed p = programmed(StepKind::feed, l.feed, l.movement,
                                                     e.per_revolution > 0 ? e.per_revolution : pitch_, false);
                           if (comp_) return comp_move(comp_straight(CompMove::Kind::feed, to_plane(l.to)), p);
                           straight(l.to, p);
                       },
                       [&](const Arc& a) {
                           Programmed p = programmed(StepKind::feed, a.feed, a.movement, e.per_revolution, false);
                           p.centre_z = a.centre.z;
                           if (comp_ && a.plane == comp_plane()) {
                               if (job && as_written_lines(a, p)) return;
                               CompMove m;
                               m.kind = CompMove::Kind::arc;
                               m.end = to_plane(a.to);
                               const Vec3 c = to_plane(a.centre);
                               m.centre = {c.x, c.y};
                               m.direction = a.direction;
                               m.turns = a.turns;
                               return comp_move(m, p);
                           }
                           if (comp_ && comp_->radius() > 0)
                               refuse(CompError{lathe_ ? "an arc outside the XZ plane under nose radius compensation (camgen "
                                                         "interprets a lathe's G41/G42 in G18 only)"
                                                       : "an arc outside the XY plane under cutter radius compensation (camgen "
                                                         "interprets G41/G42 in the XY plane only)",
                                                0, true});
                           end_compensation();
                           if (!known_) throw std::logic_error("arc from an unknown position");
                           arc(resolve_arc(pos_, a), a.to, p);
                       },
                       [&](const Dwell& d) {
                           Step s = base(StepKind::dwell);
                           s.seconds = d.seconds;
                           emit_in_order(s);
                       },
                       [&](const DrillCycle& c) {
                           if (comp_ && comp_->active())
                               refuse(CompError{"Cannot use canned cycles with cutter compensation on", 0});
                           end_compensation();
                           cycle_ = c;
                       },
                       [&](const DrillPoint& p) {
                           if (!cycle_) throw std::logic_error("drill point outside a cycle");
                           if (!known_) throw std::logic_error("drilling from an unknown position");
                           ++summary_.canned_holes;
                           // A tap's feed follows the spindle: its moves carry the pitch, so that a
                           // comparison allows for the speed the program could write.
                           pitch_ = is_tapping(cycle_->kind) ? cycle_->values.value_or(DrillField::pitch, 0.0) : 0.0;
                           for (const LonghandMove& m : longhand_moves(*cycle_, pos_, p.at, options_, longhand_buffers_))
                               add(ReadEvent{.event = to_event(m), .line = e.line, .uncertainty = e.uncertainty,
                                             .per_revolution = e.per_revolution, .offsets = e.offsets},
                                   job);
                           pitch_ = 0.0;
                       },
                       [&](const DrillEnd&) { cycle_.reset(); },
                       [&](const ThreadCycle& c) {
                           // As the machine's cycle moves (canned) and its post writes it (longhand).
                           for (const Event& m : thread_cycle_moves(c, thread_pattern_))
                               add(ReadEvent{.event = m, .line = e.line, .uncertainty = e.uncertainty,
                                             .per_revolution = e.per_revolution, .offsets = e.offsets},
                                   job);
                       },
                       [&](const TurnCycle& c) {
                           for (const Event& m : turn_cycle_moves(c, rough_pattern_))
                               add(ReadEvent{.event = m, .line = e.line, .uncertainty = e.uncertainty,
                                             .per_revolution = e.per_revolution, .offsets = e.offsets},
                                   job);
                       },
                       [&](const FinishCycle& c) {
                           for (const Event& m : finish_cycle_moves(c, rough_pattern_))
                               add(ReadEvent{.event = m, .line = e.line, .uncertainty = e.uncertainty,
                                             .per_revolution = e.per_revolution, .offsets = e.offsets},
                                   job);
                       },
                       [&](const GrooveCycle& c) {
                           for (const Event& m : groove_cycle_moves(c))
                               add(ReadEvent{.event = m, .line = e.line, .uncertainty = e.uncertainty,
                                             .per_revolution = e.per_revolution, .offsets = e.offsets},
                                   job);
                       },
                       [&](const Stop& st) {
                           Step s = base(StepKind::stop);
                           s.stop = st.kind;
                           emit_in_order(s);
                           // The operator may move the axes: the next move is from where they are.
                           known_ = false;
                           if (summary_.stops.size() < max_stop_notes) summary_.stops.push_back({line_, st.kind, st.message});
                           ++summary_.stop_count;
                       },
                       [&](const CustomBlock&) {},  // comments and dwells only, which the program reads back as such
                       [&](const ThreadFeed& t) {
                           // A feed of lead x rpm; like a tap's it carries the lead, so that a
                           // comparison allows for the speed the program could write.
                           Programmed p = programmed(StepKind::feed, t.lead * thread_rpm_, Movement::cutting, t.lead, false);
                           if (comp_) return comp_move(comp_straight(CompMove::Kind::feed, to_plane(t.to)), p);
                           straight(t.to, p);
                       },
                   },
                   e.event);
    }

    void finish() {
        end_compensation();
        holes_.close(sink_);
        summary_.notes = notes_;
        sink_.finish(summary_);
    }

    const std::vector<std::string>& notes() const { return notes_; }

private:
    // What a programmed move carries to the steps made of it (under compensation: to the tool
    // centre's moves, which the control makes later, once the next move decides the corner).
    struct Programmed {
        std::size_t source = 0;  // its tag in CutterCompensation
        StepKind kind = StepKind::feed;
        double feed = 0.0;
        Movement movement = Movement::cutting;
        double pitch = 0.0;
        bool from_unknown = false;
        int line = 0;
        double uncertainty = 0.0;
        std::optional<double> centre_z;  // an arc's centre Z as programmed
        // A lathe's move under nose-radius compensation: the controlled point is the imaginary
        // tip, this far from the nose centre the control offsets (Z, radius), mm.
        std::optional<Vec2> tip;
        SelectedOffsets offsets;  // in force where it was programmed
    };

    Programmed programmed(StepKind kind, double feed, Movement movement, double pitch, bool from_unknown) const {
        return Programmed{0, kind, feed, movement, pitch, from_unknown, line_, uncertainty_, std::nullopt, std::nullopt, offsets_};
    }

    Step base(StepKind kind) const {
        Step s;
        s.kind = kind;
        s.tool = tool_;
        s.line = line_;
        s.uncertainty = uncertainty_;
        s.offsets = offsets_;
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

    // A step without motion (dwell, spindle): under compensation it waits behind the moves
    // programmed before it that the control still holds, as the control's queue keeps it.
    void emit_in_order(const Step& s) {
        if (comp_) held_.push_back({next_source_ - 1, s});
        else emit(s);
    }

    // The step of a straight move, unless it goes nowhere from a known position.
    void straight(const Vec3& to, const Programmed& p) {
        const bool from_known = known_ && !p.from_unknown;
        if (p.kind == StepKind::feed && !from_known) throw std::logic_error("feed move from an unknown position");
        if (from_known && to == pos_) return;
        Step s = base(p.kind);
        s.line = p.line;
        s.uncertainty = p.uncertainty;
        s.offsets = p.offsets;
        s.from = from_known ? pos_ : to;
        s.to = to;
        s.from_known = from_known;
        if (p.kind == StepKind::feed) {
            s.feed = p.feed;
            s.pitch = p.pitch;
            s.movement = p.movement;
        }
        pos_ = to;
        known_ = true;
        emit(s);
    }

    void arc(const ArcGeometry& geometry, const Vec3& to, const Programmed& p) {
        Step s = base(StepKind::feed);
        s.line = p.line;
        s.uncertainty = p.uncertainty;
        s.offsets = p.offsets;
        s.from = pos_;
        s.to = to;
        s.feed = p.feed;
        s.arc = geometry;
        s.movement = p.movement;
        s.pitch = p.pitch;
        pos_ = to;
        emit(s);
    }

    // ---- cutter compensation (G41/G42 ... G40) ----
    // From G41/G42 to the move after G40 the moves go through CutterCompensation (comp_); the
    // tool centre's moves come back to tool_move as the control makes them.

    void compensation(const Compensation& c, bool job) {
        if (c.side == CompensationSide::off) {
            if (comp_)
                if (auto err = comp_->off(0)) refuse(*err);
            return;
        }
        const double radius = job ? c.radius : radius_of(c);
        // A lathe (G18): the nose centre offset by the radius from the programmed path, the
        // point the control moves the imaginary tip of the tool's orientation (LinuxCNC's lathe
        // compensation, interp_queue.cc latheorigin_x/z).
        tip_ = lathe_ ? lathe_tip_offset(job ? c.orientation : orientation_of(c, radius), radius) : Vec2{0, 0};
        if (!comp_) {
            comp_.emplace([this](const CompMove& m) { tool_move(m); });
            if (known_) comp_->set_position(to_plane(pos_));
        }
        if (auto err = comp_->on(c.side == CompensationSide::left ? CompSide::left : CompSide::right, radius, 0))
            refuse(*err);
    }

    // The radius the control offsets by for a program's G41/G42 (0 where unknown, with a note).
    double radius_of(const Compensation& c) {
        if (c.radius > 0) return c.radius;
        const int reg = c.d_register != 0 ? c.d_register : tool_;
        if (auto it = trace_options_.compensation_radii.find(reg); it != trace_options_.compensation_radii.end())
            return it->second;
        for (const ToolInfo& t : summary_.tools)
            if (t.number == reg && t.diameter > 0) return t.diameter / 2;
        note_once(reg, fmt::format("line {}: cutter radius compensation with offset register D{}, whose radius camgen "
                                   "does not know (verify --tool-table gives it): its moves are taken as programmed, "
                                   "not as the control offsets them",
                                   line_, reg));
        return 0.0;
    }

    // The tip orientation of a lathe program's G41/G42 (0 where unknown, with a note: the
    // programmed point taken as the nose centre).
    int orientation_of(const Compensation& c, double radius) {
        if (c.orientation != 0) return c.orientation;
        const int reg = c.d_register != 0 ? c.d_register : tool_;
        if (auto it = trace_options_.compensation_orientations.find(reg); it != trace_options_.compensation_orientations.end())
            return it->second;
        if (comment_orientation_ && comment_orientation_->first == tool_) return comment_orientation_->second;
        if (radius > 0)
            note_once(-1 - reg, fmt::format("line {}: nose radius compensation with tool {}, whose tip orientation camgen does "
                                            "not know: the programmed point is taken as the nose centre",
                                            line_, reg));
        return 0;
    }

    // camgen's comment before a lathe's G41/G42 names the orientation the control's table must
    // hold (the lathe posts' on_compensation): "... Q2 tip ..." (LinuxCNC), "... Fanuc tip T3: tip
    // ..." (Fanuc T, in Fanuc's numbering; camgen before it wrote "... T2 tip ... [LinuxCNC
    // numbering]"), "... cutting edge position 2, tip ..." (Sinumerik, LinuxCNC's numbering). A
    // program read without a job takes it from there, in LinuxCNC's numbering.
    void comment_orientation(const std::string& text) {
        if (!lathe_ || text.find("nose comp: ") == std::string::npos) return;
        for (const char* key : {", Q", "Fanuc tip T", ", T", "cutting edge position "}) {
            const std::size_t at = text.find(key);
            if (at == std::string::npos) continue;
            const std::size_t d = at + std::string_view(key).size();
            if (d < text.size() && text[d] >= '1' && text[d] <= '9') {
                const int number = text[d] - '0';
                comment_orientation_ = std::pair{tool_, key[0] == 'F' ? fanuc_tip_number(number) : number};
            }
            return;
        }
    }

    // The plane the control compensates in, and a point's coordinates in it as CutterCompensation
    // takes them ((Z, X, Y) in G18: ARC_FEED's first and second axes) and back.
    Plane comp_plane() const { return lathe_ ? Plane::xz : Plane::xy; }
    Vec3 to_plane(const Vec3& p) const { return lathe_ ? Vec3{p.z, p.x, p.y} : p; }
    Vec3 from_plane(const Vec3& q) const { return lathe_ ? Vec3{q.y, q.z, q.x} : q; }

    void note_once(int key, std::string text) {
        if (noted_.insert(key).second) notes_.push_back(std::move(text));
    }

    // A job's arc under compensation that the machine writes as straight moves (arcs.maxRadius,
    // a plane without arcs, ...): the control offsets those moves, not the arc, and they meet
    // the moves around them otherwise (the end of chords offset square to the last chord lies
    // up to radius x its half angle along the path from the arc's: a G40 move from there runs
    // 0.05 mm beside the one from the arc's end). So the job's arc goes through the control as
    // the chords the post writes (post.cpp write_lines: the same plan, the same points).
    bool as_written_lines(const Arc& a, const Programmed& p) {
        const std::optional<Vec3> start = comp_->programmed_position();
        if (!start) return false;
        const ArcGeometry geo = resolve_arc(from_plane(*start), a);
        const ArcPlan plan = plan_arc(geo, arcs_, effective_chord_tolerance(arcs_, op_tolerance_));
        if (plan.treatment == ArcTreatment::arcs || plan.count > max_arc_chords) return false;
        const std::int64_t n = plan.treatment == ArcTreatment::one_line ? 1 : std::max<std::int64_t>(plan.count, 1);
        for (std::int64_t k = 1; k <= n; ++k)
            comp_move(comp_straight(CompMove::Kind::feed, to_plane(k < n ? point_on_arc(geo, double(k) / double(n)) : a.to)), p);
        return true;
    }

    // A straight move to `to` (the plane's coordinates: to_plane).
    static CompMove comp_straight(CompMove::Kind kind, const Vec3& to) {
        CompMove m;
        m.kind = kind;
        m.end = to;
        return m;
    }

    void comp_move(CompMove m, Programmed p) {
        m.source = p.source = next_source_++;
        if (const double unit = 2.0 * trace_options_.rounding; unit > 0) {
            m.end.x = std::round(m.end.x / unit) * unit;
            m.end.y = std::round(m.end.y / unit) * unit;
        }
        if (lathe_ && comp_->active() && comp_->radius() > 0) p.tip = tip_;
        programmed_.push_back(p);
        if (auto err = comp_->move(m)) refuse(*err);
        // The move after G40 was the last the control offsets: the rest is as programmed.
        if (!comp_->active()) end_compensation();
    }

    // A tool-centre move, made of the programmed move tagged m.source.
    void tool_move(const CompMove& m) {
        while (!programmed_.empty() && programmed_.front().source < m.source) programmed_.pop_front();
        release_held(m.source);
        if (programmed_.empty() || programmed_.front().source != m.source)
            throw std::logic_error("a tool-centre move of no programmed move");
        const Programmed& p = programmed_.front();
        // The point the control moves: the tool centre's, or a lathe's imaginary tip beside it.
        const Vec2 tip = p.tip.value_or(Vec2{0, 0});
        const auto moved = [&](Vec2 q, double normal) {
            return from_plane({q.x + tip.x, q.y + tip.y, normal});
        };
        const Vec3 end = moved({m.end.x, m.end.y}, m.end.z);
        if (m.kind != CompMove::Kind::arc) {
            Programmed q = p;
            q.kind = m.kind == CompMove::Kind::rapid ? StepKind::rapid : StepKind::feed;
            return straight(end, q);
        }
        if (!known_) throw std::logic_error("arc from an unknown position");
        // A corner the control adds turns at the height of the move before it.
        const Vec3 centre = lathe_ ? moved(m.centre, pos_.y) : Vec3{m.centre.x, m.centre.y, p.centre_z.value_or(pos_.z)};
        const ArcSpec spec{end, centre, m.direction, comp_plane(), m.turns};
        arc(resolve_arc(pos_, spec), end, p);
    }

    // The steps without motion that wait for the moves programmed before them.
    void release_held(std::size_t before) {
        std::size_t n = 0;
        while (n < held_.size() && held_[n].first < before) emit(held_[n++].second);
        held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(n));
    }

    // The control hands on what it holds (before a tool change, a canned cycle, the end).
    void end_compensation() {
        if (!comp_) return;
        comp_->flush();
        release_held(next_source_);
        comp_.reset();
        programmed_.clear();
    }

    [[noreturn]] void refuse(const CompError& err) const {
        int line = line_;
        for (const Programmed& p : programmed_)
            if (p.source == err.source && err.source != 0) line = p.line;
        const std::string detail = (err.unmodelled ? "camgen cannot model this: " : "the control refuses this: ") + err.message;
        if (line == 0) throw ControlRefusal(operation_path_, detail);
        throw ControlRefusal("", detail, line);
    }

    LonghandOptions options_;
    bool lathe_;  // Z is the spindle axis
    ArcSettings arcs_;  // the machine's: which of a job's arcs it writes as straight moves
    ThreadCyclePattern thread_pattern_;  // how the machine's threading cycles move in air
    RoughCyclePattern rough_pattern_;    // how its roughing cycles move
    std::optional<double> op_tolerance_;  // the operation's chord tolerance (OperationStart)
    LonghandBuffers longhand_buffers_;  // reused by every canned hole's moves
    TraceSink& sink_;
    TraceOptions trace_options_;
    HoleFinder holes_;
    TraceSummary summary_;
    Vec3 pos_;  // where the tool centre is (after the steps emitted)
    bool known_ = false;
    int tool_ = 0;
    int line_ = 0;
    double uncertainty_ = 0.0;
    SelectedOffsets offsets_;  // of the event being added
    double pitch_ = 0.0;  // while a tap is expanded
    double thread_rpm_ = 0.0;  // the spindle speed a thread-cutting move feeds by (lead x rpm)
    std::optional<DrillCycle> cycle_;
    std::string operation_path_;  // of a job's events: the operation's JSON path, for a refusal
    std::optional<CutterCompensation> comp_;  // from G41/G42 to the move after G40
    std::optional<std::pair<int, int>> comment_orientation_;  // tool, orientation: from camgen's comment
    Vec2 tip_;  // a lathe's: the imaginary tip from the nose centre under the G41/G42 in force (Z, radius)
    std::deque<Programmed> programmed_;       // the moves comp_ may still make steps of
    std::vector<std::pair<std::size_t, Step>> held_;  // steps without motion, after the programmed move tagged first
    std::size_t next_source_ = 1;
    std::vector<std::string> notes_;
    std::set<int> noted_;  // the registers (and -1 - tool: a lathe tool's orientation) noted
};

TraceBuilder::TraceBuilder(const Machine& machine, TraceSink& sink, TraceOptions options)
    : machine_(machine),
      job_offsets_{.length = {}, .work = OffsetWord(options.work_offset)},
      impl_(std::make_unique<Impl>(machine, sink, std::move(options))),
      stops_(std::make_unique<OperatorStops>(machine, job_events_)) {}

TraceBuilder::~TraceBuilder() = default;

void TraceBuilder::read_event(const ReadEvent& event) { impl_->add(event, false); }

void TraceBuilder::add_job_event(const Event& e) { stops_->emit(e); }

void TraceBuilder::add_stopped_event(const Event& e) {
    if (const auto* c = std::get_if<CustomBlock>(&e)) {
        // What the program's reader reads of the block's lines: its comments and dwells (the
        // post checked the rest where it wrote them, in a program it knew the frame of).
        const CustomText& text = Post::custom_text(machine_, *c);
        for (const Event& x : Post::custom_block_events(machine_, {}, *c, text, {}, Post::StateCheck::unchecked))
            add_stopped_event(x);
        return;
    }
    ReadEvent r{e};
    if (std::holds_alternative<ToolChange>(e) || std::holds_alternative<Stop>(e)) known_ = false;
    // The offsets the post selects: the tool's length offset from its change on, the job's
    // work offset from the start.
    if (const auto* t = std::get_if<ToolChange>(&e)) job_offsets_.length = OffsetWord(post_length_offset(machine_, t->number));
    r.offsets = job_offsets_;
    if (std::holds_alternative<Rapid>(e)) {
        r.from_unknown = !known_;
        known_ = true;
    }
    impl_->add(r, true);
}

void TraceBuilder::finish() { impl_->finish(); }

const std::vector<std::string>& TraceBuilder::notes() const { return impl_->notes(); }

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
    trace_.notes = summary.notes;
    trace_.stops = summary.stops;
    trace_.stop_count = summary.stop_count;
}

void FeedClamp::step(const Step& step) {
    if (step.kind != StepKind::feed) return next_.step(step);
    Step s = step;
    s.feed = std::clamp(s.feed, min_, max_);
    next_.step(s);
}

Trace trace_program(const std::vector<ReadEvent>& events, const Machine& machine, const TraceOptions& options) {
    TraceCollector trace;
    TraceBuilder t(machine, trace, options);
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

Trace trace_expected(const std::vector<Event>& job_events, const Machine& machine, const std::string& work_offset) {
    TraceCollector trace;
    FeedClamp clamp(machine, trace);
    TraceOptions options;
    options.work_offset = work_offset;
    TraceBuilder t(machine, clamp, options);
    for (const Event& e : job_events) t.add_job_event(e);
    t.finish();
    return trace.take();
}

}  // namespace camgen
