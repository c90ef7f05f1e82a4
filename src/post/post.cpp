#include "camgen/post/post.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/post/longhand.hpp"
#include "src/post/dialect_registry.hpp"

namespace camgen {

namespace {

bool contains(const std::vector<DrillField>& v, DrillField f) {
    return std::find(v.begin(), v.end(), f) != v.end();
}

// The key a message names for a value of a drilling cycle, as the operation that made it
// spells it: a lathe's cycles come from turn-drill operations, which name the fields by
// CNC-Calc's TurnDrillingFields (firstPeckDepth, lowerDwell, ...), the planes retractDistance
// and startDepth, and tap by giving a pitch (no "cycle" key); a mill's from drill operations.
std::string cycle_key(std::string_view key, MachineKind kind) {
    if (kind != MachineKind::lathe) return std::string(key);
    if (key == "retractPlane") return "retractDistance";
    if (key == "referencePlane") return "startDepth";
    if (key == "cycle") return "pitch";
    if (const auto field = drill_field_named(key))
        if (const TurnDrillFieldInfo* t = turn_field_of(*field)) return std::string(t->key);
    return std::string(key);
}
std::string cycle_key(DrillField f, MachineKind kind) { return cycle_key(key_of(f), kind); }
}  // namespace

Post::Post(const Machine& machine, std::ostream& out, PostOptions options)
    : machine_(machine),
      options_(std::move(options)),
      out_(machine.block, out),
      xyz_fmt_(machine.format("xyz")),
      ijk_fmt_(machine.format("ijk")),
      feed_fmt_(machine.format("feed")),
      rpm_fmt_(machine.format("rpm")),
      dwell_fmt_(machine.format("dwell")),
      angle_fmt_(machine.format("angle")),
      code_fmt_(machine.format("code")),
      x_fmt_(machine.format("x")),
      z_fmt_(machine.format("z")),
      i_fmt_(machine.format("i")),
      feed_rev_fmt_(machine.format("feedPerRev")),
      x_("X", x_fmt_),
      y_("Y", xyz_fmt_),
      z_("Z", z_fmt_),
      feed_("F", feed_fmt_),
      motion_("G", code_fmt_),
      plane_("G", code_fmt_),
      feed_rev_("F", feed_rev_fmt_),
      stops_(machine_, handler_) {
    if (!machine.accepts(machine.units))
        throw InputError("/units", fmt::format("machine {} has no {} mode (its control accepts: {})", machine.name,
                                               name_of(unit_names, machine.units), machine.accepted_unit_names()),
                         0, machine.source);
}

Post::~Post() = default;

void Post::open() {
    opened_ = true;
    if (!options_.work_offset.empty() && !machine_.has_work_offset(options_.work_offset)) {
        if (machine_.frame.work_offsets.empty())
            throw InputError("/workOffset", fmt::format("machine {} has no work offsets: its control cannot select {}",
                                                        machine_.name, options_.work_offset));
        const auto& w = machine_.frame.work_offsets;
        throw InputError("/workOffset",
                         fmt::format("machine {} has no work offset \"{}\"; it has {}", machine_.name, options_.work_offset,
                                     w.size() > 12 ? fmt::format("{} .. {}", w.front(), w.back())
                                                   : fmt::format("{}", fmt::join(w, ", "))));
    }
    if (options_.program_number)
        if (auto why = program_number_refusal()) throw InputError("/programNumber", *why);
    if (!options_.snippet) on_open();
}

void Post::close() {
    if (!options_.snippet && !machine_.frame.safe_retract.empty()) write_safe_retract();
    if (!options_.snippet) on_close();
    out_.flush();
}

std::string Post::g(double code) const { return code_fmt_.word("G", code); }
std::string Post::m(double code) const { return code_fmt_.word("M", code); }

namespace {
// A note or a warning is one line on the terminal: a control character in it (a line break in
// an operation's comment, which names it) is shown as a space, as the NC text's comments do.
std::string post_one_line(std::string text) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
    return text;
}
}  // namespace

void Post::warn(const std::string& message) {
    if (options_.warnings) *options_.warnings << "camgen: warning: " << post_one_line(message) << '\n';
}

void Post::note(const std::string& message) {
    if (options_.notes) *options_.notes << "camgen: note: " << post_one_line(message) << '\n';
}

void Post::fail(const std::string& key, const std::string& detail) const {
    throw InputError(op_path_ + key, detail);
}

double Post::checked_feed(double mm_per_min, double rpm) {
    const double f = clamped_feed(mm_per_min);
    if (feed_mode_ == FeedMode::per_revolution) {
        // The control feeds F x its spindle speed: F is the job's feed per revolution.
        if (!(rpm > 0)) fail("", "a feed per revolution while the spindle stands still");
        const double per_rev = f / rpm;
        if (feed_rev_fmt_.is_zero(per_rev))
            fail("", fmt::format("feed {} mm/rev would be written as F0 on machine {}", number_text(per_rev), machine_.name));
        return per_rev;
    }
    if (feed_fmt_.is_zero(f))
        fail("", fmt::format("feed {} mm/min would be written as F0 on machine {}", number_text(f), machine_.name));
    return f;
}

std::string_view Post::feed_word(double mm_per_min) {
    const double f = checked_feed(mm_per_min, spindle_rpm_);
    return feed_mode_ == FeedMode::per_revolution ? feed_rev_.format(f) : feed_.format(f);
}

std::string Post::feed_text(double mm_per_min, double rpm) {
    const double f = checked_feed(mm_per_min, rpm);
    return feed_mode_ == FeedMode::per_revolution ? feed_rev_fmt_.word("F", f) : feed_fmt_.word("F", f);
}

void Post::on_thread_feed(const Vec3&, const ThreadFeed&) {
    fail("", fmt::format("machine {} cuts no threads: its dialect writes no move synchronised with the spindle", machine_.name));
}

std::string Post::lead_word(std::string_view letter, double lead) {
    if (!(spindle_rpm_ > 0)) fail("", "a thread-cutting move while the spindle stands still");
    if (!(lead > 0) || feed_rev_fmt_.is_zero(lead))
        fail("", fmt::format("lead {} mm would be written as 0 on machine {}", number_text(lead), machine_.name));
    const double feed = lead * spindle_rpm_;
    if (machine_.limits.max_feed > 0 && feed > machine_.limits.max_feed + 1e-9)
        fail("", fmt::format("a thread of lead {} mm at {} rpm feeds {} mm/min, beyond the maxFeed of machine {} ({} "
                             "mm/min): lower the threading tool's rpm",
                             number_text(lead), number_text(spindle_rpm_), number_text(feed), machine_.name,
                             number_text(machine_.limits.max_feed)));
    return feed_rev_fmt_.word(letter, lead);
}

double Post::clamped_feed(double mm_per_min) {
    const MachineLimits& lim = machine_.limits;
    double f = mm_per_min;
    if (!(f > 0.0) || !std::isfinite(f)) fail("", fmt::format("feed {} mm/min is not a usable feed", number_text(f)));
    // One warning per operation and feed. An operation that feeds per revolution is told in
    // its own unit, mm/rev, beside the mm/min the machine's limits are in.
    auto first = [&] { return warned_feeds_.insert({op_path_, f}).second; };
    const bool per_rev = feed_mode_ == FeedMode::per_revolution && spindle_rpm_ > 0;
    auto feed = [&](double mm_per_min) {
        return per_rev ? fmt::format("{} mm/rev ({} mm/min at {} rpm)", number_text(mm_per_min / spindle_rpm_),
                                     number_text(mm_per_min), number_text(spindle_rpm_))
                       : fmt::format("{} mm/min", number_text(mm_per_min));
    };
    auto limit = [&](double mm_per_min) {
        return per_rev ? fmt::format("{} mm/min ({} mm/rev)", number_text(mm_per_min), number_text(mm_per_min / spindle_rpm_))
                       : fmt::format("{} mm/min", number_text(mm_per_min));
    };
    if (f > lim.max_feed) {
        if (first()) warn(fmt::format("{}: feed {} is above the limit of machine {}; clamped to {}", op_path_, feed(f),
                                      machine_.name, limit(lim.max_feed)));
        f = lim.max_feed;
    } else if (f < lim.min_feed) {
        if (first()) warn(fmt::format("{}: feed {} is below the minimum of machine {}; raised to {}", op_path_, feed(f),
                                      machine_.name, limit(lim.min_feed)));
        f = lim.min_feed;
    }
    return f;
}

std::string_view Post::motion_word(double code) {
    return machine_.modal_motion ? motion_.format(code) : motion_.force(code);
}

void Post::reset_modal_axes() {
    x_.reset();
    y_.reset();
    z_.reset();
    motion_.reset();
}

Post::AxisWords Post::axis_words(const Vec3& to, ForcedAxes forced) {
    AxisWords w;
    w.x = forced.x ? x_.force(to.x) : x_.format(to.x);
    // A lathe has no Y axis: its tool stays in the XZ plane.
    if (machine_.kind != MachineKind::lathe) w.y = forced.y ? y_.force(to.y) : y_.format(to.y);
    w.z = forced.z ? z_.force(to.z) : z_.format(to.z);
    return w;
}

Post::AxisWords Post::force_xy(Vec2 at) {
    AxisWords w;
    w.x = x_.force(at.x);
    if (machine_.kind != MachineKind::lathe) w.y = y_.force(at.y);
    return w;
}

std::string_view Post::force_z(double z) { return z_.force(z); }

void Post::select_feed_mode(FeedMode mode) {
    if (mode == feed_mode_) return;
    const auto code = machine_.frame.feed_modes.find(mode);
    if (code == machine_.frame.feed_modes.end())
        fail("/feedMode", fmt::format("machine {} has no feed {} mode (no frame feedModes)", machine_.name,
                                      name_of(feed_modes, mode)));
    out_.add(code->second).end();
    feed_mode_ = mode;
    // The F word means something else now: write it again.
    feed_.reset();
    feed_rev_.reset();
}

void Post::on_operation_start(const OperationStart& op) {
    if (!op.name.empty()) on_comment(op.name);
}

void Post::on_comment(const std::string& text) { out_.comment(text); }

std::string Post::inline_comment(std::string_view text) const {
    const std::string c = out_.clean_comment(text);
    return out_.style().comment_style == nc::CommentStyle::parentheses ? "(" + c + ")" : "; " + c;
}

namespace {
// How many lines `text` has (it ends with a line break).
int lines_in(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

// What an event of a custom block would do, for the message that refuses it.
std::string what_it_does(const Event& e) {
    return visit_exhaustive(overloaded{
                                [](const OperationStart&) { return std::string("start an operation"); },
                                [](const OperationEnd&) { return std::string("end an operation"); },
                                [](const ToolChange& t) { return fmt::format("change to tool {}", t.number); },
                                [](const Spindle& s) {
                                    return std::string(s.state == SpindleState::off ? "stop the spindle" : "start the spindle");
                                },
                                [](const Coolant&) { return std::string("switch the coolant"); },
                                [](const Rapid&) { return std::string("move the tool (a rapid)"); },
                                [](const Linear&) { return std::string("move the tool (a feed move)"); },
                                [](const Arc&) { return std::string("move the tool (an arc)"); },
                                [](const Dwell&) { return std::string("dwell"); },
                                [](const Compensation&) { return std::string("switch cutter radius compensation"); },
                                [](const DrillCycle&) { return std::string("drill (a drilling cycle)"); },
                                [](const DrillPoint&) { return std::string("drill a hole"); },
                                [](const DrillEnd&) { return std::string("end a drilling cycle"); },
                                [](const Comment&) { return std::string("comment"); },
                                [](const Stop&) {
                                    return std::string("stop the program with the spindle as it is (a stop operation "
                                                       "stops the spindle and the coolant first)");
                                },
                                [](const CustomBlock&) { return std::string("custom"); },
                                [](const ThreadFeed&) { return std::string("move the tool (a thread-cutting move)"); },
                                [](const ThreadCycle&) { return std::string("cut a thread in a cycle"); },
                                [](const TurnCycle&) { return std::string("rough in a cycle"); },
                                [](const GrooveCycle&) { return std::string("cut a groove in a cycle"); },
                                [](const FinishCycle&) { return std::string("finish a profile"); },
                            },
                            e);
}
}  // namespace

const CustomText& Post::custom_text(const Machine& machine, const CustomBlock& block) {
    for (const std::string& name : {machine.name, machine.dialect})
        for (const CustomText& t : block.texts)
            if (t.name == name) return t;
    std::vector<std::string> names;
    std::string hint;
    for (const CustomText& t : block.texts) {
        names.push_back(t.name);
        if (auto near = json::did_you_mean(t.name, {machine.name, machine.dialect}); near && hint.empty())
            hint = fmt::format(" (did you mean \"{}\" for \"{}\"?)", *near, t.name);
    }
    throw InputError(block.path, fmt::format("the custom block has no text for machine {} or its dialect {} (it has text "
                                             "for: {}){}; give one, or \"\" to write nothing there",
                                             machine.name, machine.dialect, fmt::join(names, ", "), hint));
}

void Post::handle_custom(const CustomBlock& block) {
    const CustomText& text = custom_text(machine_, block);
    if (text.lines.empty()) return;
    if (!unchecked_custom_) {
        ProgramPoint point{op_path_, feed_mode_, tool_, spindle_, std::nullopt};
        if (pos_known_) point.position = pos_;
        (void)custom_block_events(machine_, options_, block, text, point);
    }
    write_custom_lines(text.lines);
}

void Post::write_custom_lines(const std::vector<std::string>& lines) {
    for (const std::string& line : lines) out_.add(line).end();
    // The check proved the control's state unchanged; the modal words this post keeps are
    // written again all the same (a custom G1 or F would otherwise stand for the post's).
    reset_modal_axes();
    forget_feed();
    feed_rev_.reset();
    plane_.reset();
    arc_actual_end_.reset();
}

std::vector<Event> Post::custom_block_events(const Machine& machine, const PostOptions& options, const CustomBlock& block,
                                             const CustomText& text, const ProgramPoint& point, StateCheck state) {
    const std::vector<std::string>& lines = text.lines;
    if (lines.empty()) return {};
    const std::string path = block.path + "/" + json::pointer_escape(text.name);
    // A program like this one up to here (its frame, feed mode, tool, spindle and position),
    // with the lines between two comments, read back with the machine's reader.
    std::ostringstream program;
    PostOptions o;
    o.program_name = options.program_name;
    o.work_offset = options.work_offset;
    o.program_number = options.program_number;
    std::unique_ptr<Post> probe = make_post(machine, program, o);
    probe->unchecked_custom_ = true;
    probe->open();
    probe->emit(OperationStart{"", point.operation_path, std::nullopt, {}, std::nullopt, point.feed_mode});
    if (point.tool > 0) probe->emit(ToolChange{point.tool, 0.0, ""});
    if (point.spindle.state != SpindleState::off) probe->emit(point.spindle);
    if (point.position) probe->emit(Rapid{*point.position});
    // The block's lines are those the probe writes for it (each one line).
    probe->out_.flush();
    const int first = lines_in(program.str()) + 1;
    probe->emit(CustomBlock{{text}, block.path});
    probe->out_.flush();
    if (lines_in(program.str()) - first + 1 != static_cast<int>(lines.size()))
        throw std::logic_error("a custom block's lines are not one line each in the program");
    probe->emit(OperationEnd{});
    probe->close();
    const LinesReadBack back = read_lines_back(machine, program.str(), first, static_cast<int>(lines.size()));
    auto line_of = [&](int k) {
        return k >= 0 && k < static_cast<int>(lines.size()) ? fmt::format("line {} \"{}\"", k + 1, lines[static_cast<std::size_t>(k)])
                                                            : std::string("the line after its last");
    };
    const std::string reader = fmt::format("machine {}'s reader", machine.name);
    if (back.error)
        throw InputError(path, fmt::format("{} cannot read custom {}: {}; camgen writes only what it can read back "
                                           "(camgen verify)",
                                           reader, line_of(back.error->first), back.error->second));
    if (!back.frame_lines.empty())
        throw InputError(path, fmt::format("custom {} is a line of the program's frame for {}, not a block",
                                           line_of(back.frame_lines.front()), reader));
    std::vector<Event> events;
    for (const auto& [k, e] : back.events) {
        if (!std::holds_alternative<Comment>(e) && !std::holds_alternative<Dwell>(e))
            throw InputError(path, fmt::format("custom {} would {}: a custom block may only comment and dwell, so that the "
                                               "tool, the spindle and the program stay where camgen has them",
                                               line_of(k), what_it_does(e)));
        events.push_back(e);
    }
    for (std::size_t i = 0; state == StateCheck::checked && i < back.state_before.size() && i < back.state_after.size(); ++i)
        if (back.state_before[i] != back.state_after[i])
            throw InputError(path, fmt::format("the custom block changes the {} from {} to {} (as {} reads it): a custom "
                                               "block must leave the control's state as it found it",
                                               back.state_before[i].first, back.state_before[i].second,
                                               back.state_after[i].second, reader));
    return events;
}

void Post::on_stop(const Stop& stop) {
    out_.add(m(stop.kind == StopKind::optional ? 1 : 0)).add(stop.message.empty() ? "" : inline_comment(stop.message)).end();
}

void Post::on_coolant(const Coolant& coolant) {
    const std::optional<std::string> code = machine_.coolant_code(coolant.mode);
    if (!code)
        throw InputError(coolant.path, fmt::format("machine {} has no {} coolant{}", machine_.name,
                                                   name_of(coolant_modes, coolant.mode),
                                                   machine_.frame.coolant.empty() ? "" : fmt::format(" (it has: {})", [&] {
                                                       std::vector<std::string> n;
                                                       for (const auto& [mode, c] : machine_.frame.coolant)
                                                           if (mode != CoolantMode::off) n.emplace_back(name_of(coolant_modes, mode));
                                                       return fmt::format("{}", fmt::join(n, ", "));
                                                   }())));
    out_.add(*code).end();
}

void Post::write_start_block(const std::string& unit_word) {
    for (const std::string& w : machine_.frame.start_block) out_.add(w);
    out_.add(unit_word).add(options_.work_offset);
    out_.end();
}

void Post::on_rapid(const Vec3& to) {
    const AxisWords w = axis_words(to);
    if (w.x.empty() && w.y.empty() && w.z.empty()) return;
    out_.add(motion_word(0)).add(w.x).add(w.y).add(w.z).end();
}

void Post::rapid_from_unknown(const Vec3& to) {
    // Where the height is unknown (the operator may have touched off on the stock), a move in
    // X or Y first could cross the part: up to the height first, then across.
    forget_z();
    x_.reset();
    y_.reset();
    if (!machine_.frame.safe_retract.empty()) {
        // The machine's own safe height (in machine coordinates) first, then across, then
        // down to where the operation wants the tool, with its length offset.
        write_safe_retract();
        const AxisWords w = force_xy({to.x, to.y});
        out_.add(motion_word(0)).add(w.x).add(w.y).end();
        rapid_z_from_unknown(to.z);
        return;
    }
    rapid_z_from_unknown(to.z);
    on_rapid(to);
}

void Post::write_safe_retract() {
    for (const std::string& w : machine_.frame.safe_retract) out_.add(w);
    out_.end();
    // The block may have set the motion mode; Z is now in machine coordinates.
    forget_motion();
    forget_z();
}

void Post::rapid_z_from_unknown(double z) { out_.add(motion_word(0)).add(force_z(z)).end(); }

void Post::on_compensation(const Compensation& compensation) { pending_compensation_ = compensation; }

std::string Post::compensation_words(const Compensation& c) const {
    const int d = c.d_register != 0 ? c.d_register : tool_;
    switch (c.side) {
        case CompensationSide::off: return g(40);
        case CompensationSide::left: return g(41) + machine_.block.separator + "D" + std::to_string(d);
        case CompensationSide::right: return g(42) + machine_.block.separator + "D" + std::to_string(d);
    }
    return {};
}

std::string Post::radius_word(double radius) const { return xyz_fmt_.word("R", radius); }

bool Post::force_arc_end() const { return machine_.arcs.force_xy; }

Post::LinearLayout Post::linear_layout() { return {motion_word(1), false}; }

std::string Post::speed_word(double rpm) const {
    // Appended rather than "S" + text: gcc 12's -Wrestrict misreads the inlined insert.
    std::string word = "S";
    word += speed_text(rpm);
    return word;
}

std::string Post::speed_text(double rpm) const {
    if (machine_.limits.max_rpm > 0 && rpm > machine_.limits.max_rpm)
        fail("", fmt::format("spindle speed {} rpm is above the limit of machine {} ({} rpm)", number_text(rpm),
                             machine_.name, number_text(machine_.limits.max_rpm)));
    if (rpm_fmt_.is_zero(rpm))
        fail("", fmt::format("spindle speed {} rpm would be written as S0 on machine {}", number_text(rpm), machine_.name));
    return rpm_fmt_.format(rpm);
}

std::optional<std::string> Post::surface_speed_refusal() const {
    return fmt::format("machine {} turns its spindle at a constant rpm only: a constant surface speed (surfaceSpeed, "
                       "G96) is for the lathe dialects",
                       machine_.name);
}

void Post::on_spindle(const Spindle& s) {
    if (s.state == SpindleState::off) {
        out_.add(m(5)).end();
        return;
    }
    out_.add(speed_word(s.rpm)).add(m(s.state == SpindleState::cw ? 3 : 4)).end();
}

void Post::on_linear(const Vec3& to, double feed) {
    std::string comp;
    if (pending_compensation_) comp = compensation_words(*pending_compensation_);
    const AxisWords w = axis_words(to);
    if (w.x.empty() && w.y.empty() && w.z.empty() && comp.empty()) return;
    const std::string_view fs = feed_word(feed);
    const LinearLayout layout = linear_layout();
    const std::string_view before = layout.compensation_after_axes ? std::string_view() : comp;
    const std::string_view after = layout.compensation_after_axes ? comp : std::string_view();
    out_.add(before).add(layout.motion).add(w.x).add(w.y).add(w.z).add(after).add(fs).end();
    pending_compensation_.reset();
}

void Post::on_circular(const ArcGeometry& arc, double feed) {
    const ArcSettings& s = machine_.arcs;
    std::string_view plane;
    if (machine_.arcs.planes.size() > 1)
        plane = plane_.format(arc.plane == Plane::xy ? 17 : arc.plane == Plane::xz ? 18 : 19);
    const std::string_view motion = motion_word(arc.direction == ArcDirection::cw ? 2 : 3);
    const std::string_view fs = feed_word(feed);
    if (s.format == ArcFormat::nccad_angle) {
        // nccad: G02 D<sweep> I J, no end point: the control computes it. Remember the end.
        nc::Word i("I", ijk_fmt_, true), j("J", ijk_fmt_, true);
        out_.add(motion).add(angle_fmt_.word("D", arc.sweep * deg_per_rad))
            .add(i.format(arc.centre.x - arc.start.x))
            .add(j.format(arc.centre.y - arc.start.y))
            .add(fs)
            .end();
        x_.set_last(arc.end.x);
        y_.set_last(arc.end.y);
        return;
    }
    // End point: the plane's two axes are written on every arc block when force_arc_end().
    const bool force = force_arc_end();
    const ForcedAxes forced{force && arc.plane != Plane::yz, force && arc.plane != Plane::xz,
                            force && arc.plane != Plane::xy};
    const AxisWords w = axis_words(arc.end, forced);
    out_.add(plane).add(motion).add(w.x).add(w.y).add(w.z);
    if (s.format == ArcFormat::radius) {
        out_.add(radius_word(arc.sweep > std::numbers::pi ? -arc.radius : arc.radius));
    } else {
        Vec3 c = arc.centre;
        if (s.format == ArcFormat::ijk_relative) c = {c.x - arc.start.x, c.y - arc.start.y, c.z - arc.start.z};
        if (arc.plane != Plane::yz) out_.add(i_fmt_.word("I", c.x));
        if (arc.plane != Plane::xz) out_.add(ijk_fmt_.word("J", c.y));
        if (arc.plane != Plane::xy) out_.add(ijk_fmt_.word("K", c.z));
    }
    out_.add(fs).end();
}

void Post::on_drilling_header(const DrillCycle&, const DrillingCycleSpec& spec) {
    throw InputError("/drilling/cycles", fmt::format("the {} dialect cannot write canned cycle {}",
                                                     machine_.dialect, spec.name), 0, machine_.source);
}
void Post::on_drilling_point(const DrillCycle&, const DrillingCycleSpec&, Vec2, bool) {}
std::optional<std::string> Post::canned_limit(const DrillCycle&, const DrillingCycleSpec&) const { return std::nullopt; }

void Post::on_thread_cycle(const ThreadCycle& c, const ThreadingCycleSpec& spec) {
    throw InputError(c.path + "/output", fmt::format("machine {}'s dialect cannot write {}", machine_.name, spec.name));
}

std::optional<std::string> Post::thread_cycle_limit(const ThreadCycle&, const ThreadingCycleSpec& spec) const {
    // A dialect that writes threading cycles overrides this; the others write the passes.
    return fmt::format("camgen writes {} only on the iso-lathe dialect", spec.name);
}

void Post::handle_thread_cycle(const ThreadCycle& c) {
    if (!pos_known_) throw std::logic_error("threading cycle from an unknown position");
    if (c.output != CycleOutput::longhand) {
        const ThreadingCycleSpec* spec = machine_.threading.empty() ? nullptr : &machine_.threading.front();
        std::string reason;
        if (!spec) {
            reason = fmt::format("machine {} has no canned threading cycle", machine_.name);
        } else {
            std::vector<std::string> missing;
            for (const std::string& f : c.fields)
                if (std::find(spec->fields.begin(), spec->fields.end(), f) == spec->fields.end()) missing.push_back(f);
            if (!missing.empty())
                reason = fmt::format("machine {}'s {} cannot carry {}", machine_.name, spec->name, fmt::join(missing, ", "));
            else if (auto limit = thread_cycle_limit(c, *spec))
                reason = fmt::format("machine {}'s {} cannot carry this thread: {}", machine_.name, spec->name, *limit);
        }
        if (reason.empty()) {
            on_thread_cycle(c, *spec);
            pos_ = thread_cycle_end(c, machine_.thread_pattern());
            return;
        }
        cycle_not_canned(c.path, c.output, spec != nullptr, "thread", reason);
    }
    // Longhand in the pattern of the machine's own cycle, so that canned or not the program
    // moves as the job's events traced for this machine (trace_expected).
    for (const Event& e : thread_cycle_moves(c, machine_.thread_pattern())) handle(e);
}
void Post::on_turn_cycle(const TurnCycle& c, const RoughingCycleSpec& spec) {
    throw InputError(c.path + "/output", fmt::format("machine {}'s dialect cannot write {}", machine_.name, spec.name));
}

std::optional<std::string> Post::turn_cycle_limit(const TurnCycle&, const RoughingCycleSpec& spec) const {
    return fmt::format("camgen writes {} only on the iso-lathe dialect", spec.name);
}

void Post::handle_turn_cycle(const TurnCycle& c) {
    if (!pos_known_) throw std::logic_error("roughing cycle from an unknown position");
    if (c.output == CycleOutput::longhand) throw std::logic_error("a roughing cycle written longhand by its operation");
    const RoughingCycleKind kind = c.along_x ? RoughingCycleKind::rough_x : RoughingCycleKind::rough_z;
    const RoughingCycleSpec* spec = nullptr;
    for (const RoughingCycleSpec& r : machine_.roughing_cycles)
        if (r.kind == kind) spec = &r;
    std::string reason;
    if (!spec) {
        reason = fmt::format("machine {} has no canned roughing cycle along {} (roughingCycles)", machine_.name,
                             c.along_x ? "X" : "Z");
    } else if (c.refusal) {
        reason = fmt::format("machine {}'s {} would not cut these passes: {}", machine_.name, spec->name, *c.refusal);
    } else {
        std::vector<std::string> missing;
        for (RoughingField f : {RoughingField::depth_of_cut, RoughingField::retract})
            if (std::find(spec->fields.begin(), spec->fields.end(), f) == spec->fields.end())
                missing.emplace_back(name_of(roughing_fields, f));
        if (!missing.empty())
            reason = fmt::format("machine {}'s {} cannot carry {}", machine_.name, spec->name, fmt::join(missing, ", "));
        else if (auto limit = turn_cycle_limit(c, *spec))
            reason = fmt::format("machine {}'s {} cannot carry these passes: {}", machine_.name, spec->name, *limit);
    }
    if (reason.empty()) {
        on_turn_cycle(c, *spec);
        // Where the control ends, then the way out, written out.
        const std::vector<LatheCycleMove> path = turn_cycle_path(c, machine_.rough_pattern());
        if (!path.empty()) pos_ = Vec3{path.back().end.y, c.start.y, path.back().end.x};
        for (const Event& e : turn_cycle_exit(c, machine_.rough_pattern())) handle(e);
        return;
    }
    cycle_not_canned(c.path, c.output, spec != nullptr, "roughing", reason);
    // Longhand in the pattern of the machine's own cycle (as trace_expected traces it).
    for (const Event& e : turn_cycle_moves(c, machine_.rough_pattern())) handle(e);
}

std::optional<std::string> Post::finish_cycle_limit(const FinishCycle&) const {
    return "camgen writes G70 only on the iso-lathe dialect";
}

void Post::on_finish_cycle(const FinishCycle& c) {
    throw InputError(c.path + "/output", fmt::format("machine {}'s dialect cannot write G70", machine_.name));
}

void Post::handle_finish_cycle(const FinishCycle& c) {
    // (It begins with rapids, which come from wherever the tool stands, as a turn-profile's do.)
    const RoughCyclePattern pattern = machine_.rough_pattern();
    const bool fanuc = pattern == RoughCyclePattern::fanuc_g71;
    if (finish_cycle_g70(c, pattern)) {
        const std::optional<std::string> limit = finish_cycle_limit(c);
        if (!limit) {
            // To A (from the clearance), G70 (which ends back at A), then the way out from A.
            for (const Event& e : finish_cycle_entry(c)) handle(e);
            on_finish_cycle(c);
            pos_ = Vec3{c.start.y, 0.0, c.start.x};
            for (const Event& e : finish_cycle_exit(c)) handle(e);
            return;
        }
        cycle_not_canned(c.path, c.output, true, "finishing", fmt::format("G70 cannot finish it: {}", *limit));
    } else {
        const std::string reason = fanuc && c.refusal ? fmt::format("G70 cannot finish it: {}", *c.refusal)
                                                      : fmt::format("machine {} has no Fanuc roughing cycle whose shape G70 finishes "
                                                           "(roughingCycles of style fanuc-g71 or fanuc-g72)",
                                                           machine_.name);
        cycle_not_canned(c.path, c.output, fanuc, "finishing", reason);
    }
    for (const Event& e : finish_cycle_moves(c, pattern)) handle(e);
}

void Post::cycle_not_canned(const std::string& path, CycleOutput output, bool has_cycle, std::string_view what,
                            const std::string& reason) {
    if (output == CycleOutput::canned) throw InputError(path + "/output", reason + "; use \"auto\" or \"longhand\"");
    if (has_cycle)
        note(fmt::format("{}{}: the {} is written longhand because {}", path, op_name_.empty() ? "" : " (" + op_name_ + ")",
                         what, reason));
}

void Post::on_groove_cycle(const GrooveCycle& c, const GroovingCycleSpec& spec) {
    throw InputError(c.path + "/output", fmt::format("machine {}'s dialect cannot write {}", machine_.name, spec.name));
}

std::optional<std::string> Post::groove_cycle_limit(const GrooveCycle&, const GroovingCycleSpec& spec) const {
    return fmt::format("camgen writes {} only on the dialect its style names", spec.name);
}

void Post::handle_groove_cycle(const GrooveCycle& c) {
    if (!pos_known_) throw std::logic_error("grooving cycle from an unknown position");
    if (c.output != CycleOutput::longhand) {
        // The machine's cycle of the groove's kind: face grooves along Z (G74), others along X (G75).
        const bool face = c.side == GrooveSide::face;
        const GroovingCycleSpec* spec = nullptr;
        for (const GroovingCycleSpec& s : machine_.grooving)
            if (s.face == face && !spec) spec = &s;
        std::string reason;
        if (machine_.grooving.empty()) {
            reason = fmt::format("machine {} has no canned grooving cycle", machine_.name);
        } else if (!spec) {
            reason = face ? fmt::format("machine {}'s {} plunges along X; a face groove plunges along Z (the machine lists "
                                        "no grooving cycle of kind \"face-groove\")",
                                        machine_.name, machine_.grooving.front().name)
                          : fmt::format("machine {}'s {} cuts face grooves; this groove plunges along X (the machine lists "
                                        "no grooving cycle of kind \"groove\")",
                                        machine_.name, machine_.grooving.front().name);
        } else {
            std::vector<std::string> missing;
            for (const std::string& f : c.fields)
                if (std::find(spec->fields.begin(), spec->fields.end(), f) == spec->fields.end()) missing.push_back(f);
            if (!missing.empty())
                reason = fmt::format("machine {}'s {} cannot carry {}", machine_.name, spec->name, fmt::join(missing, ", "));
            else if (auto limit = groove_cycle_limit(c, *spec))
                reason = fmt::format("machine {}'s {} cannot carry this groove: {}", machine_.name, spec->name, *limit);
        }
        if (reason.empty()) {
            on_groove_cycle(c, *spec);
            pos_ = groove_cycle_end(c);
            return;
        }
        cycle_not_canned(c.path, c.output, !machine_.grooving.empty(), "groove", reason);
    }
    for (const Event& e : groove_cycle_moves(c)) handle(e);
}

std::optional<std::string> Post::tapping_impossible(CycleKind) const { return std::nullopt; }
void Post::on_drilling_footer(const DrillCycle&, const DrillingCycleSpec&) {}

std::optional<std::string> Post::program_number_refusal() const {
    if (takes_program_number()) return std::nullopt;
    return fmt::format("machine {} takes no program number", machine_.name);
}

std::optional<std::string> Post::control_compensation_refusal() const {
    if (!machine_.cutter_compensation)
        return fmt::format("machine {} has no cutter radius compensation (G41/G42): use compensation computer", machine_.name);
    // A lathe compensates the nose in G18 (XZ), a mill the cutter in G17 (XY).
    const bool lathe = machine_.kind == MachineKind::lathe;
    if (!writes_arcs_in(machine_.arcs, lathe ? Plane::xz : Plane::xy))
        return fmt::format("machine {} writes arcs in {} as straight moves (its arcs.planes has no \"{}\"): with the "
                           "control compensating, every chord is a corner the control offsets on its own; use "
                           "compensation computer",
                           machine_.name, lathe ? "XZ" : "XY", lathe ? "xz" : "xy");
    return std::nullopt;
}

CycleCapability Post::cycle_capability(CycleKind kind) const {
    CycleCapability c;
    c.kind = kind;
    if (const DrillingCycleSpec* spec = machine_.canned_cycle(kind)) c.canned = *spec;
    if (!is_tapping(kind)) return c;
    auto refuse = [&](std::string why, const char* key) {
        c.canned.reset();
        c.longhand = false;
        c.refused = std::move(why);
        c.refused_key = key;
        return c;
    };
    if (auto why = tapping_impossible(kind)) return refuse(fmt::format("machine {} cannot tap: {}", machine_.name, *why), "cycle");
    if (machine_.tapping == TappingMode::none)
        return refuse(fmt::format("machine {} cannot synchronise the spindle to the feed; tapping needs a floating tap "
                                  "holder: set tapping to floating in a copy of the machine file",
                                  machine_.name),
                      "cycle");
    if (machine_.tapping == TappingMode::rigid) {
        if (!c.canned)
            return refuse(longhand_tap_refusal(fmt::format("has no canned cycle for \"{}\"", name_of(cycle_kinds, kind)),
                                               "tap on another machine"),
                          "output");
        c.longhand = false;
    }
    return c;
}

bool starts_in_xy(const Machine& machine) {
    const auto& b = machine.frame.start_block;
    return std::find(b.begin(), b.end(), "G17") != b.end();
}

std::vector<DrillField> drill_fields_used(const DrillCycle& cycle) {
    std::vector<DrillField> f;
    for (const auto& d : drill_fields) {
        // A field resolved into the planes (safeDistance) is used when the feed starts below
        // the retract plane.
        const bool used = d.in_planes ? cycle.safe_z != cycle.retract_z : cycle.values.used(d.field);
        if (used) f.push_back(d.field);
    }
    return f;
}

Post::CannedFit Post::canned_fit(const DrillCycle& cycle) const {
    CannedFit fit;
    fit.spec = machine_.canned_cycle(cycle.kind);
    if (!fit.spec) return fit;
    for (DrillField f : drill_fields_used(cycle))
        if (!contains(fit.spec->fields, f)) fit.missing.emplace_back(cycle_key(f, machine_.kind));
    if (fit.missing.empty()) fit.limit = canned_limit(cycle, *fit.spec);
    if (fit.missing.empty() && !fit.limit && is_pecking(cycle.kind)) {
        // The control counts its pecks from the rounded depths and planes: when they come to
        // another number of pecks than the job's, only longhand pecks are the job's (fuzz
        // finding 13: endDepth 4.0000000016 at pecks of 2.5 is three pecks, the last one
        // 1.6e-9 mm; from Z-4.000 the control makes two).
        DrillCycle rounded = cycle;
        for (double DrillCycle::*z : {&DrillCycle::retract_z, &DrillCycle::reference_z, &DrillCycle::safe_z, &DrillCycle::bottom_z})
            rounded.*z = xyz_fmt_.rounded(cycle.*z);
        for (DrillField f : {DrillField::first_depth, DrillField::subsequent_depth, DrillField::degression,
                             DrillField::minimum_depth})
            if (auto v = cycle.values.get(f); v && contains(fit.spec->fields, f) &&
                                              !(f == DrillField::degression && cycle.values.degression_type() != DegressionType::value))
                rounded.values.set(f, xyz_fmt_.rounded(*v));
        const size_t job_pecks = peck_depths(cycle).size(), control_pecks = peck_depths(rounded).size();
        if (job_pecks != control_pecks)
            fit.limit = fmt::format("its depths rounded to the program's decimals make {} pecks, not {}", control_pecks, job_pecks);
    }
    return fit;
}

std::string Post::longhand_tap_refusal(const std::string& why, const std::string& remedy) const {
    return fmt::format("machine {} taps rigidly and {}; a longhand tap (feed moves with a spindle reversal) is "
                       "not synchronised to the spindle and breaks a tap in a rigid holder: {}, or if the tap "
                       "sits in a floating holder, set tapping to floating in a copy of the machine file",
                       machine_.name, why, remedy);
}

void Post::refuse_longhand_tap(const DrillCycle& cycle, const std::string& why, const std::string& remedy) const {
    throw InputError(cycle.path + "/output", longhand_tap_refusal(why, remedy));
}

const DrillingCycleSpec* Post::choose_canned(const DrillCycle& cycle) {
    // A kind the machine cannot make at all was refused by handle_drill_cycle.
    const CycleCapability capability = cycle_capability(cycle.kind);
    const bool rigid = !capability.longhand;
    const std::string kind(name_of(cycle_kinds, cycle.kind));
    if (cycle.output == CycleOutput::longhand) {
        if (rigid) refuse_longhand_tap(cycle, "the job asks for output \"longhand\"", "use \"auto\" or \"canned\"");
        return nullptr;
    }
    const CannedFit fit = canned_fit(cycle);
    if (fit.fits()) return fit.spec;
    // Why the canned cycle cannot write it ("G81 cannot carry safeDistance").
    std::string reason;
    if (fit.spec && !fit.missing.empty())
        reason = fmt::format("{} cannot carry {}", fit.spec->name, fmt::join(fit.missing, ", "));
    else if (fit.spec)
        reason = fmt::format("{} cannot carry this cycle: {}", fit.spec->name, *fit.limit);
    if (cycle.output == CycleOutput::automatic) {
        if (rigid)
            refuse_longhand_tap(cycle, "its " + reason,
                                fit.missing.empty() ? std::string("change the cycle")
                                                    : fmt::format("leave out {}", fmt::join(fit.missing, ", ")));
        // Longhand where the machine has the canned cycle: say so, it is longer and slower.
        if (fit.spec)
            note(fmt::format("{}{}: the {} cycle is written longhand because machine {}'s {}", cycle.path,
                             op_name_.empty() ? "" : " (" + op_name_ + ")", kind, machine_.name, reason));
        return nullptr;
    }
    if (!fit.spec)
        throw InputError(cycle.path + "/output",
                         fmt::format("machine {} has no canned cycle for \"{}\"; use \"auto\" or \"longhand\"",
                                     machine_.name, kind));
    if (!fit.missing.empty()) {
        std::vector<std::string> offered;
        for (DrillField f : fit.spec->fields) offered.emplace_back(cycle_key(f, machine_.kind));
        throw InputError(cycle.path + "/output",
                         fmt::format("machine {}'s {} cannot carry {}; it carries: {}", machine_.name, fit.spec->name,
                                     fmt::join(fit.missing, ", "),
                                     offered.empty() ? "nothing optional" : fmt::format("{}", fmt::join(offered, ", "))));
    }
    throw InputError(cycle.path + "/output", fmt::format("machine {}'s {} cannot carry this cycle: {}", machine_.name,
                                                         fit.spec->name, *fit.limit));
}

DrillCycle Post::checked_cycle(const DrillCycle& cycle) {
    DrillCycle c = cycle;
    const DrillValues& v = cycle.values;
    auto key = [&](DrillField field) { return cycle_key(field, machine_.kind); };
    auto refuse = [&](DrillField field, const std::string& detail) { throw InputError(cycle.path + "/" + key(field), detail); };
    const std::string& m = machine_.name;
    // A hole whose bottom is not below where its feed starts, or whose depth is written as 0
    // (its depth, or its two Zs, rounding alike): no hole, and on heidenhain a CYCL DEF 200
    // with Q201=+0 (the control skips it) or a positive Q201 (the control refuses it).
    const double feed_start = std::min(c.reference_z, c.safe_z);
    const double depth = feed_start - c.bottom_z;
    if (!(depth > 0))
        throw InputError(cycle.path + "/endDepth",
                         fmt::format("the hole's bottom (Z {}) is not below where its feed starts (Z {}): nothing would be "
                                     "drilled",
                                     number_text(c.bottom_z), number_text(feed_start)));
    if (xyz_fmt_.is_zero(depth) || !(xyz_fmt_.rounded(c.bottom_z) < xyz_fmt_.rounded(feed_start)))
        throw InputError(cycle.path + "/endDepth",
                         fmt::format("the hole is {} mm deep (Z {} to {}), below the resolution of machine {}: it would be "
                                     "written 0 deep and not drilled",
                                     number_text(depth), number_text(feed_start), number_text(c.bottom_z), m));
    // Speeds that would be written as S0 (or SST=0).
    for (DrillField f : {DrillField::tapping_speed, DrillField::retract_speed})
        if (auto rpm = v.get(f); rpm && rpm_fmt_.is_zero(*rpm))
            refuse(f, fmt::format("{} {} rpm would be written as 0 on machine {}", key(f), number_text(*rpm), m));
    // A back-off the control reads as 0 would not break the chip.
    if (auto mm = v.get(DrillField::pecking_retract); mm && xyz_fmt_.is_zero(*mm))
        refuse(DrillField::pecking_retract,
               fmt::format("{} {} mm is below the resolution of machine {}: it would be written as 0",
                           key(DrillField::pecking_retract), number_text(*mm), m));
    // A peck shorter than one unit of the last decimal (or written as 0): successive depths
    // round onto each other, so pecks (and their dwells) would be written on the spot.
    const double unit = std::pow(10.0, -xyz_fmt_.spec().decimals) / xyz_fmt_.spec().scale;
    for (DrillField f : {DrillField::first_depth, DrillField::subsequent_depth, DrillField::minimum_depth})
        if (auto mm = v.get(f); mm && *mm < unit)
            refuse(f, fmt::format("{} {} mm is below the resolution of machine {} ({} mm): its pecks cannot be written",
                                  key(f), number_text(*mm), m, number_text(unit)));
    if (v.degression_type() == DegressionType::value && xyz_fmt_.is_zero(v.value_or(DrillField::degression, 0.0)))
        refuse(DrillField::degression, fmt::format("degression {} mm is below the resolution of machine {}: it would be "
                                                   "written as 0", number_text(v.value_or(DrillField::degression, 0.0)), m));
    // A dwell that was asked for but would be written as none.
    for (DrillField f : {DrillField::top_dwell, DrillField::bottom_dwell})
        if (v.used(f) && dwell_fmt_.is_zero(*v.get(f)))
            refuse(f, fmt::format("{} {} s is below the resolution of machine {}: it would be written as no dwell", key(f),
                                  number_text(*v.get(f)), m));
    // The same pecks canned and longhand: more than any control takes is refused either way
    // (at the operation's own key).
    if (is_pecking(c.kind)) {
        try {
            (void)peck_depths(c);
        } catch (const InputError& e) {
            const std::string& p = e.path();
            if (p.rfind(cycle.path + "/", 0) != 0) throw;
            throw InputError(cycle.path + "/" + cycle_key(std::string_view(p).substr(cycle.path.size() + 1), machine_.kind),
                             e.detail(), e.line(), e.source());
        }
    }
    if (is_tapping(c.kind)) {
        const double pitch = v.value_or(DrillField::pitch, 0.0);
        const double in = v.value_or(DrillField::tapping_speed, c.spindle_rpm);
        const double out = v.value_or(DrillField::retract_speed, in);
        const double fastest = std::max(in, out);
        if (pitch * fastest > machine_.limits.max_feed)
            refuse(v.has(DrillField::tapping_speed) ? DrillField::tapping_speed : DrillField::pitch,
                   fmt::format("the tap's feed {} mm/min (pitch {} mm x {} rpm) is above the limit of machine {} ({} "
                               "mm/min); a tapping feed is never clamped, it must match the pitch: tap at {} rpm or less",
                               number_text(pitch * fastest), number_text(pitch), number_text(fastest), m,
                               number_text(machine_.limits.max_feed), number_text(std::floor(machine_.limits.max_feed / pitch))));
        const double slowest = std::min(in, out);
        if (pitch * slowest < machine_.limits.min_feed)
            refuse(DrillField::pitch,
                   fmt::format("the tap's feed {} mm/min (pitch {} mm x {} rpm) is below the minimum of machine {} ({} "
                               "mm/min); a tapping feed is never clamped, it must match the pitch",
                               number_text(pitch * slowest), number_text(pitch), number_text(slowest), m,
                               number_text(machine_.limits.min_feed)));
        if (machine_.limits.max_rpm > 0 && fastest > machine_.limits.max_rpm)
            refuse(DrillField::tapping_speed, fmt::format("tapping at {} rpm is above the limit of machine {} ({} rpm)",
                                                          number_text(fastest), m, number_text(machine_.limits.max_rpm)));
        return c;
    }
    // Feeds the machine cannot run are clamped once, here, so that every dialect's canned
    // cycle and the longhand moves carry the same value.
    c.feed = clamped_feed(c.feed);
    if (auto r = v.get(DrillField::retract_feedrate)) c.values.set(DrillField::retract_feedrate, clamped_feed(*r));
    if (auto p = v.get(DrillField::plunging_feedrate)) c.values.set(DrillField::plunging_feedrate, clamped_feed(*p));
    return c;
}

void Post::handle_drill_cycle(const DrillCycle& event) {
    if (!pos_known_) throw std::logic_error("drilling cycle from an unknown position");
    // A cycle the machine cannot make at all is refused as such, before its values are checked.
    if (const CycleCapability capability = cycle_capability(event.kind); capability.refused)
        throw InputError(event.path + "/" + cycle_key(capability.refused_key, machine_.kind), *capability.refused);
    const DrillCycle cycle = checked_cycle(event);
    cycle_ = cycle;
    cycle_spec_ = choose_canned(cycle);
    first_point_ = true;
    if (cycle_spec_) on_drilling_header(cycle, *cycle_spec_);
}

void Post::handle_drill_point(Vec2 at) {
    if (!cycle_) throw std::logic_error("drilling point outside a cycle");
    if (cycle_spec_) {
        on_drilling_point(*cycle_, *cycle_spec_, at, first_point_);
        pos_ = {at.x, at.y, cycle_->retract_z};
        ++canned_holes_;
    } else {
        ++longhand_holes_;
        for (const LonghandMove& e : longhand_moves(*cycle_, pos_, at, machine_.longhand(), longhand_buffers_)) replay(e);
    }
    first_point_ = false;
}

void Post::handle_drill_end() {
    if (!cycle_) throw std::logic_error("drilling end outside a cycle");
    if (cycle_spec_) {
        on_drilling_footer(*cycle_, *cycle_spec_);
        // The control left the cycle at the retract plane; what it last read was the bottom.
        z_.reset();
        motion_.reset();
    }
    cycle_.reset();
    cycle_spec_ = nullptr;
}

void Post::handle_arc(const Arc& arc) {
    if (!pos_known_) throw std::logic_error("arc from an unknown position");
    const ArcGeometry geo = resolve_arc(pos_, arc);
    if (arc.turns > 0) {
        // A helix of whole turns whose travel a turn is below the resolution: several turns
        // would be written at one Z (or Y, X), the tool circling in place, and the read-back
        // cannot tell those turns apart (fuzz finding 12: a bore at pitch 0.00043 mm on grbl).
        const double travel = std::abs(geo.plane == Plane::xy   ? geo.end.z - geo.start.z
                                       : geo.plane == Plane::xz ? geo.end.y - geo.start.y
                                                                : geo.end.x - geo.start.x);
        const double per_turn = travel * 2 * std::numbers::pi / geo.sweep;
        const double unit = std::pow(10.0, -xyz_fmt_.spec().decimals) / xyz_fmt_.spec().scale;
        if (travel > 0 && per_turn < unit * (1 - 1e-6))  // a pitch of one unit passes
            fail("", fmt::format("a helix of {} turns moves {} mm along its axis a turn, below the resolution of machine {} ({} "
                                 "mm): turns would be written at one height, the tool circling in place (bore-mill and a "
                                 "path's helix: a larger pitch; a contour's helix ramp: a larger angle or radius)",
                                 arc.turns + 1, number_text(per_turn, 6), machine_.name, number_text(unit, 6)));
    }
    const ArcSettings& s = machine_.arcs;
    const double tolerance = effective_chord_tolerance(s, op_tolerance_);
    const ArcPlan plan = plan_arc(geo, s, tolerance);
    switch (plan.treatment) {
        case ArcTreatment::one_line: on_linear(arc.to, arc.feed); break;
        case ArcTreatment::lines: write_lines(geo, plan.count, arc.feed, tolerance, plan.reason); break;
        case ArcTreatment::arcs:
            for (const ArcGeometry& piece : split_arc(geo, plan.count)) write_arc_block(piece, arc.feed, tolerance, 0);
            break;
    }
    pos_ = arc.to;
}

void Post::write_lines(const ArcGeometry& arc, std::int64_t segments, double feed, double chord_tolerance,
                       std::string_view why) {
    if (segments > max_arc_chords) {
        // More chords than the limit would leave the tolerance (a cap on the count writes them
        // long) or write a program nobody can run: refused before the arc is written.
        ArcSettings by_tolerance = machine_.arcs;
        by_tolerance.max_segment_length.reset();
        const bool tolerance_binds = segment_count(arc, by_tolerance, chord_tolerance) > max_arc_chords;
        const double turns = arc.sweep / (2 * std::numbers::pi);
        const PlanePoint a = to_plane(arc.start, arc.plane), b = to_plane(arc.end, arc.plane);
        const std::string what = std::abs(b.w - a.w) > 1e-9
                                     ? fmt::format("a helix of {} turns of radius {} mm", number_text(turns), number_text(arc.radius))
                                     : fmt::format("an arc of {} degrees and radius {} mm",
                                                   number_text(arc.sweep * 180 / std::numbers::pi), number_text(arc.radius));
        const std::string keep = tolerance_binds
                                     ? fmt::format("within the chord tolerance of {} mm", number_text(chord_tolerance, 6))
                                     : fmt::format("each chord within maxSegmentLength {} mm",
                                                   number_text(*machine_.arcs.max_segment_length, 6));
        fail("", fmt::format("{}, which machine {} writes as straight moves ({}), needs {} of them to keep {}; at most {} "
                             "are written for one arc (fewer turns or a larger pitch, a larger tolerance up to the machine's "
                             "chordTolerance {} mm, or a machine that writes it as arcs)",
                             what, machine_.name, why, segments, keep, max_arc_chords,
                             number_text(machine_.arcs.chord_tolerance, 6)));
    }
    // One point at a time: a long helix broken into millions of chords is never held whole.
    const int n = static_cast<int>(std::max<std::int64_t>(segments, 1));
    for (int k = 1; k <= n; ++k) {
        const Vec3 p = k < n ? point_on_arc(arc, double(k) / n) : arc.end;  // the last ends exactly at the end
        on_linear(p, feed);
        pos_ = p;
    }
}

Vec3 Post::arc_control_start(const Vec3& start) const {
    Vec3 c{xyz_fmt_.rounded(start.x), xyz_fmt_.rounded(start.y), xyz_fmt_.rounded(start.z)};
    if (!arc_actual_end_) return c;
    // After an nccad angle arc the control stands where it computed the end, which is not
    // exactly the rounded end: an axis no later block has written is still there.
    auto unwritten = [&](const nc::Word& w, double believed) {
        return w.last() && xyz_fmt_.format(*w.last()) == xyz_fmt_.format(believed);
    };
    if (unwritten(x_, arc_believed_end_.x)) c.x = arc_actual_end_->x;
    if (unwritten(y_, arc_believed_end_.y)) c.y = arc_actual_end_->y;
    if (unwritten(z_, arc_believed_end_.z)) c.z = arc_actual_end_->z;
    return c;
}

void Post::write_arc_block(const ArcGeometry& piece, double feed, double chord_tolerance, int depth) {
    const ArcWordFormats formats{xyz_fmt_, ijk_fmt_, angle_fmt_, machine_.arcs.format, machine_.tolerance,
                                 machine_.arcs.max_sweep};
    const ArcFit fit = fit_arc_block(piece, arc_control_start(piece.start), formats);
    switch (fit.result) {
        case ArcFitResult::ok:
            on_circular(fit.block, feed);
            pos_ = piece.end;
            arc_actual_end_ = fit.control_end;
            arc_believed_end_ = piece.end;
            break;
        case ArcFitResult::degenerate:
            on_linear(piece.end, feed);
            pos_ = piece.end;
            break;
        case ArcFitResult::no_fit:
            // Rounding would take the control off the circle: halves have shorter chords and
            // are less sensitive; after a few halvings, straight moves.
            if (depth < 4) {
                for (const ArcGeometry& half : split_arc(piece, 2)) write_arc_block(half, feed, chord_tolerance, depth + 1);
            } else {
                write_lines(piece, segment_count(piece, machine_.arcs, chord_tolerance), feed, chord_tolerance,
                            "its rounded words leave the circle");
            }
            break;
    }
}

void Post::replay(const LonghandMove& event) {
    visit_exhaustive(overloaded{
                   [&](const Rapid& r) {
                       if (pos_known_) on_rapid(r.to); else rapid_from_unknown(r.to);
                       pos_ = r.to;
                       pos_known_ = true;
                   },
                   [&](const Linear& l) {
                       if (!pos_known_) throw std::logic_error("feed move from an unknown position");
                       on_linear(l.to, l.feed);
                       pos_ = l.to;
                   },
                   [&](const Dwell& d) { on_dwell(d.seconds); },
                   [&](const Spindle& s) {
                       spindle_rpm_ = s.state == SpindleState::off ? 0.0 : s.rpm;
                       on_spindle(s);
                   },
               },
               event);
}

void Post::emit(const Event& event) {
    if (!opened_) open();
    stops_.emit(event);
}

void Post::handle(const Event& event) {
    visit_exhaustive(overloaded{
                   [&](const OperationStart& op) {
                       op_path_ = op.path;
                       op_name_ = op.name;
                       op_tolerance_ = op.tolerance;
                       for (const std::string& n : op.notes) note(fmt::format("{} ({}): {}", op.path, op.name, n));
                       on_operation_start(op);
                       select_feed_mode(op.feed_mode);
                   },
                   [&](const OperationEnd&) { on_operation_end(); },
                   [&](const ToolChange& t) {
                       tool_ = t.number;
                       on_tool_change(t);
                       pos_known_ = false;
                       reset_modal_axes();
                   },
                   [&](const Spindle& s) {
                       if (s.state != SpindleState::off && s.surface_speed > 0)
                           if (auto why = surface_speed_refusal()) fail("", *why);
                       spindle_rpm_ = s.state == SpindleState::off ? 0.0 : s.rpm;
                       spindle_ = s;
                       on_spindle(s);
                   },
                   [&](const Coolant& c) { on_coolant(c); },
                   // A compensation change waits for the next linear feed move (CNC-Calc): never
                   // written on a rapid or an arc.
                   [&](const Rapid& r) { replay(r); },
                   [&](const Linear& l) { replay(l); },
                   [&](const Arc& a) { handle_arc(a); },
                   [&](const Dwell& d) { on_dwell(d.seconds); },
                   [&](const Compensation& c) {
                       if (c.side != CompensationSide::off)
                           if (auto why = control_compensation_refusal()) fail("/compensation", *why);
                       on_compensation(c);
                   },
                   [&](const DrillCycle& c) { handle_drill_cycle(c); },
                   [&](const DrillPoint& p) { handle_drill_point(p.at); },
                   [&](const DrillEnd&) { handle_drill_end(); },
                   [&](const Comment& c) { on_comment(c.text); },
                   [&](const Stop& s) {
                       on_stop(s);
                       // The operator may have moved the axes: the next rapid goes Z first.
                       pos_known_ = false;
                       reset_modal_axes();
                       arc_actual_end_.reset();
                   },
                   [&](const CustomBlock& c) { handle_custom(c); },
                   [&](const ThreadFeed& t) {
                       if (!pos_known_) throw std::logic_error("thread-cutting move from an unknown position");
                       on_thread_feed(pos_, t);
                       pos_ = t.to;
                   },
                   [&](const ThreadCycle& c) { handle_thread_cycle(c); },
                   [&](const TurnCycle& c) { handle_turn_cycle(c); },
                   [&](const GrooveCycle& c) { handle_groove_cycle(c); },
                   [&](const FinishCycle& c) { handle_finish_cycle(c); },
               },
               event);
}

}  // namespace camgen
