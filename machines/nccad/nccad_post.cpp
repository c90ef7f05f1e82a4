// The nccad dialect (MAX computer nccad: Wabeco, KOSY): "_" lines, G90, M01 <message> for
// what the operator must do (no tool changer, no programmable speed), M10 O6.1/O6.0 spindle,
// M30 P<n> dwell in 1/18 s, G81 .. B + G79 drilling, G77 home, G99 end of program.
#include "machines/nccad/nccad_post.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/post/machine_checks.hpp"

namespace camgen {

NccadPost::NccadPost(const Machine& machine, std::ostream& out, PostOptions options)
    : Post(machine, out, std::move(options)), settings_(settings_of<nccad::Settings>(this->machine())) {
    // nccad has no unit word and reads every length as mm, every feed in its feed unit.
    if (machine.units != Units::mm)
        throw InputError("/units", fmt::format("machine {}: nccad has no inch mode; its programs are in mm", machine.name),
                         0, machine.source);
}

void NccadPost::on_open() {
    for (int i = 0; i < settings_.underscore_lines; ++i) writer().raw("_");
    if (!options().program_name.empty()) writer().comment(options().program_name);
    write_start_block("");
    if (settings_.reference_run) writer().add(g(76)).end();
}

void NccadPost::on_close() {
    if (spindle_on_) writer().add(m(10)).add("O6.0").end();
    if (settings_.home_at_end) writer().add(g(77)).end();
    if (settings_.end_of_program) writer().add(g(99)).end();
}

void NccadPost::on_tool_change(const ToolChange& tool) {
    // nccad cannot change tools or set a speed: stop and show the operator what to do.
    pending_tool_ = tool;
}

std::optional<std::string> NccadPost::control_compensation_refusal() const {
    if (auto why = Post::control_compensation_refusal()) return why;
    return fmt::format("machine {} has no cutter radius compensation (nccad has no G41/G42): use compensation computer",
                       machine().name);
}

std::optional<std::string> NccadPost::ccw_spindle_refusal() const {
    return fmt::format("machine {} cannot run the spindle counter-clockwise", machine().name);
}

std::optional<std::string> NccadPost::tapping_impossible(CycleKind kind) const {
    if (kind == CycleKind::tap_left)
        return "its spindle cannot run counter-clockwise, and a left-hand tap cuts only counter-clockwise";
    return "its spindle cannot run counter-clockwise, so a right-hand tap cannot be backed out of the hole";
}

void NccadPost::on_spindle(const Spindle& s) {
    if (s.state == SpindleState::ccw)
        if (auto why = ccw_spindle_refusal()) fail("", fmt::format("{} (tool {})", *why, current_tool()));
    if (s.state == SpindleState::off) {
        if (pending_tool_) flush_tool_message(std::nullopt);
        writer().add(m(10)).add("O6.0").end();
        spindle_on_ = false;
        return;
    }
    if (pending_tool_) {
        flush_tool_message(s.rpm);
    } else if (s.rpm != speed_) {
        writer().add(m(1)).add(writer().clean_comment(fmt::format("Set spindle speed to {} rpm", speed_text(s.rpm)))).end();
    }
    speed_ = s.rpm;
    writer().add(m(10)).add("O6.1").end();
    spindle_on_ = true;
}

void NccadPost::flush_tool_message(std::optional<double> rpm) {
    const ToolChange& t = *pending_tool_;
    std::string msg = fmt::format("Insert tool {}", t.number);
    if (!t.description.empty()) msg += " " + t.description;
    const std::string tail = rpm ? fmt::format(", spindle {} rpm", speed_text(*rpm)) : "";
    std::string cleaned = writer().clean_comment(msg + tail);
    if (!tail.empty() && !cleaned.ends_with(tail)) {
        // A long description (a library tool's computed values) is cut, never the spindle speed
        // the operator sets and the reader reads.
        std::string head = writer().clean_comment(msg);
        head.resize(std::min(head.size(), cleaned.size() > tail.size() ? cleaned.size() - tail.size() : 0));
        while (!head.empty() && head.back() == ' ') head.pop_back();
        cleaned = head + tail;
    }
    // ';' starts a comment in nccad: it must not appear in the message.
    for (char& c : cleaned)
        if (c == ';') c = ',';
    writer().add(m(1)).add(cleaned).end();
    pending_tool_.reset();
}

void NccadPost::on_stop(const Stop& stop) {
    if (pending_tool_) flush_tool_message(std::nullopt);
    if (stop.kind == StopKind::optional)
        note(fmt::format("{}: machine {} has no optional stop: the optional stop is written as M01 <message>, which "
                         "always waits",
                         operation_path(), machine().name));
    std::string msg = writer().clean_comment(stop.message);
    // ';' starts a comment in nccad: it must not appear in the message.
    for (char& c : msg)
        if (c == ';') c = ',';
    writer().add(m(1)).add(msg).end();
}

void NccadPost::on_dwell(double seconds) {
    // M30 P<n>: n in 1/18 s, rounded up so the dwell is never shorter than asked.
    long n = static_cast<long>(std::ceil(seconds * 18.0 - 1e-9));
    if (n < 1) n = 1;
    writer().add(m(30)).add(fmt::format("P{}", n)).end();
}

// Control compensation never comes on (control_compensation_refusal), so there is no G40 to write.
void NccadPost::on_compensation(const Compensation&) {}

void NccadPost::on_drilling_header(const DrillCycle&, const DrillingCycleSpec&) {}

void NccadPost::on_drilling_point(const DrillCycle& c, const DrillingCycleSpec&, Vec2 at, bool first) {
    const AxisWords w = force_xy(at);
    if (first) {
        // G81 X Y Z<bottom> B<retract plane> F: the feed runs from B to Z, then back to B.
        writer().add(g(81)).add(w.x).add(w.y).add(force_z(c.bottom_z)).add(xyz_format().word("B", c.retract_z))
            .add((forget_feed(), feed_word(c.feed))).end();
    } else {
        writer().add(g(79)).add(w.x).add(w.y).end();
    }
}

void NccadPost::on_drilling_footer(const DrillCycle&, const DrillingCycleSpec&) {}

std::optional<MachineProblem> check_nccad_machine(const Machine& machine) {
    if (machine.arcs.format != ArcFormat::ijk_relative && machine.arcs.format != ArcFormat::nccad_angle)
        return MachineProblem{{"/arcs/format"},
                              "nccad writes arcs as G02/G03 X Y I J with I and J relative to the start, or as "
                              "G02 D I J (nccad-angle): it has no R and no absolute centre; use ijk-relative or "
                              "nccad-angle"};
    if (machine.block.comment_max_length > 0 &&
        machine.block.comment_max_length < static_cast<int>(nc::default_comment_limit))
        return MachineProblem{{"/commentMaxLength"},
                              fmt::format("nccad's M01 messages tell the operator the tool to insert and the spindle "
                                          "speed to set by hand: a limit below {} characters would cut the speed off; "
                                          "leave commentMaxLength out",
                                          nc::default_comment_limit)};
    if (machine.arcs.format == ArcFormat::ijk_relative && !machine.arcs.force_xy)
        return MachineProblem{{"/arcs/forceXY", "/arcs/format"},
                              "nccad's G02/G03 X Y I J needs both X and Y on every arc block: keep forceXY true"};
    if (const auto rpm = machine.formats.find("rpm"); rpm != machine.formats.end() && rpm->second.scale != 1.0)
        return MachineProblem{{"/formats/rpm/scale"},
                              "nccad's M01 message tells the operator the spindle speed to set by hand, in rpm: "
                              "leave scale out of the rpm format"};
    // on_drilling_point writes every canned cycle as G81 X Y Z B F (G79 at the next holes): a
    // plain drill fed from B. A cycle of another kind, or one carrying more, would be written
    // as that plain drill (and described as what it is not).
    for (std::size_t i = 0; i < machine.drilling.size(); ++i) {
        const DrillingCycleSpec& c = machine.drilling[i];
        const bool g81 = c.kind == CycleKind::drill && c.name == "G81" && c.style == CannedStyle::standard &&
                         std::all_of(c.fields.begin(), c.fields.end(),
                                     [](DrillField f) { return f == DrillField::plunging_feedrate; });
        if (c.canned && !g81)
            return MachineProblem{{fmt::format("/drilling/cycles/{}", i)},
                                  "nccad's one canned cycle is G81 X Y Z B F, a plain drill: {\"name\": \"G81\", "
                                  "\"kind\": \"drill\", \"fields\": [\"plungingFeedrate\"]}; camgen writes every other "
                                  "cycle longhand: remove this one"};
    }
    // Every tap is refused on nccad (tapping_impossible): a machine file that says otherwise
    // would tell --describe-machine and the stops that replace taps (impossible_cycle) a lie.
    if (machine.tapping != TappingMode::none)
        return MachineProblem{{"/drilling/tapping"},
                              "nccad's spindle runs clockwise only: a right-hand tap cannot be backed out of the hole "
                              "and a left-hand one cannot cut; set tapping to none"};
    static constexpr std::string_view no_unit_words[] = {"G70", "G71"};
    static constexpr std::string_view start_words[] = {"G90"};
    if (auto p = start_block_problem(machine, no_unit_words, start_words)) return p;
    return xy_arcs_only_problem(machine, "G02/G03 X Y I J");
}

}  // namespace camgen
