// The ISO (Fanuc-style) dialect: %, O-number, G-code program frame, T.. M6, S.. M3, G43 H,
// canned cycles G73/G74/G81-G89 with G98/G99 and G80, LinuxCNC G33.1 rigid tapping.
#include "machines/iso/iso_post.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "camgen/post/machine_checks.hpp"

namespace camgen {

namespace {
// Whether the canned cycle carries `field`.
bool carries(const std::vector<DrillField>& fields, DrillField field) {
    return std::find(fields.begin(), fields.end(), field) != fields.end();
}
}  // namespace

IsoPost::IsoPost(const Machine& machine, std::ostream& out, PostOptions options)
    : Post(machine, out, std::move(options)), settings_(settings_of<iso::Settings>(this->machine())) {}

void IsoPost::on_open() {
    if (settings_.percent) writer().raw("%");
    if (settings_.program_number > 0) {
        std::string line = fmt::format("O{:04}", options().program_number.value_or(settings_.program_number));
        if (!options().program_name.empty())
            line += " (" + writer().clean_comment(options().program_name) + ")";
        writer().raw(line);
    } else if (!options().program_name.empty()) {
        writer().comment(options().program_name);
    }
    write_start_block(g(machine().units == Units::inch ? 20 : 21));
    if (starts_in_xy(machine())) assume_plane(17);
}

void IsoPost::on_close() {
    writer().add(settings_.end_code).end();
    if (settings_.percent) writer().raw("%");
}

void IsoPost::on_tool_change(const ToolChange& tool) {
    switch (settings_.tool_change) {
        case iso::ToolChangeStyle::m6:
            if (!tool.description.empty()) writer().comment(fmt::format("T{} {}", tool.number, tool.description));
            writer().add(fmt::format("T{}", tool.number)).add(m(6)).end();
            break;
        case iso::ToolChangeStyle::pause:
            // No tool changer (GRBL has no M6): the spindle is off; stop and tell the operator.
            writer().comment(fmt::format("Insert tool {}{}", tool.number,
                                         tool.description.empty() ? "" : ": " + tool.description));
            writer().add(m(0)).end();
            break;
        case iso::ToolChangeStyle::none:
            if (!tool.description.empty()) writer().comment(fmt::format("T{} {}", tool.number, tool.description));
            break;
    }
    length_offset_pending_ = settings_.length_offset;
}

void IsoPost::on_stop(const Stop& stop) {
    const bool optional = stop.kind == StopKind::optional;
    if (optional && !settings_.stop.optional_stop)
        note(fmt::format("{}: machine {} ignores M1 (it has no optional stop): the optional stop is written as M0, "
                         "which always stops",
                         operation_path(), machine().name));
    std::string text = stop.message;
    if (settings_.stop.msg && !text.empty()) text = fmt::format("{} {}", iso::msg_prefix, text);
    writer().add(m(optional && settings_.stop.optional_stop ? 1 : 0)).add(text.empty() ? "" : inline_comment(text)).end();
}

void IsoPost::on_dwell(double seconds) { writer().add(g(4)).add(dwell_format().word("P", seconds)).end(); }

void IsoPost::rapid_z_from_unknown(double z) {
    if (!length_offset_pending_) {
        Post::rapid_z_from_unknown(z);
        return;
    }
    // The first Z move after a tool change carries the tool length offset, before any X or Y.
    writer().add(motion_word(0)).add(g(43)).add(force_z(z)).add(fmt::format("H{}", current_tool())).end();
    length_offset_pending_ = false;
}

std::optional<SpindleState> IsoPost::tapping_direction(const DrillCycle& c) {
    if (c.kind == CycleKind::tap_left && c.spindle_direction != SpindleDirection::ccw) return SpindleState::ccw;
    if (c.kind == CycleKind::tap && c.spindle_direction != SpindleDirection::cw) return SpindleState::cw;
    return std::nullopt;
}

void IsoPost::on_drilling_header(const DrillCycle& c, const DrillingCycleSpec&) {
    // G84/G74 and G33.1 tap in the direction the spindle runs when they start.
    if (auto dir = tapping_direction(c)) on_spindle(Spindle{*dir, c.spindle_rpm});
    // G98 returns to the Z the tool had before the cycle: make sure that is the retract plane.
    if (const Vec3 at = position(); c.retract_z > c.safe_z && at.z != c.retract_z) {
        on_rapid({at.x, at.y, c.retract_z});
        set_position({at.x, at.y, c.retract_z});
    }
}

void IsoPost::on_drilling_point(const DrillCycle& c, const DrillingCycleSpec& spec, Vec2 at, bool first) {
    if (spec.style == CannedStyle::rigid_g33_1) {
        // LinuxCNC rigid tapping: from R, synchronised down to Z, spindle reversal and back to
        // R in one move; the control restores the spindle direction.
        on_rapid({at.x, at.y, position().z});
        on_rapid({at.x, at.y, c.safe_z});
        // K times the speed is the feed: as many decimals as the pitch needs (1/32 in).
        const double pitch = *c.values.get(DrillField::pitch);
        writer().add(g(iso::rigid_tap_code)).add(force_z(c.bottom_z))
            .add(nc::exact_format(xyz_format().spec(), pitch, 6).word("K", pitch)).end();
        forget_motion();
        assume_z(c.safe_z);
        on_rapid({at.x, at.y, c.retract_z});
        return;
    }
    const AxisWords w = force_xy(at);
    if (!first) {
        writer().add(w.x).add(w.y).end();
        return;
    }
    const DrillValues& p = c.values;
    // G98 returns to the Z the tool had before the cycle: the retract plane, where the
    // operation put it. G99 returns to R.
    if (writes_return_level()) writer().add(g(c.retract_z > c.safe_z ? 98 : 99));
    writer().add(motion_word(iso::cycle_code(c.kind))).add(w.x).add(w.y);
    writer().add(force_z(c.bottom_z)).add(xyz_format().word("R", c.safe_z));
    if ((c.kind == CycleKind::deep || c.kind == CycleKind::chip_break) && p.get(DrillField::first_depth))
        writer().add(xyz_format().word("Q", *p.get(DrillField::first_depth)));
    // G82, G86 and G89 need their P (LinuxCNC: "Dwell time p word missing"), P0 when no dwell.
    const bool dwell_cycle = c.kind == CycleKind::dwell || c.kind == CycleKind::bore_stop || c.kind == CycleKind::bore_dwell;
    const double dwell = p.get(DrillField::bottom_dwell).value_or(0.0);
    if (dwell > 0 || (dwell_cycle && carries(spec.fields, DrillField::bottom_dwell)))
        writer().add(dwell_format().word("P", dwell));
    writer().add(feed_word(c.feed)).end();
}

void IsoPost::on_drilling_footer(const DrillCycle& c, const DrillingCycleSpec& spec) {
    if (spec.style != CannedStyle::rigid_g33_1) writer().add(g(80)).end();
    if (tapping_direction(c)) on_spindle(Spindle{c.spindle_direction == SpindleDirection::cw ? SpindleState::cw : SpindleState::ccw,
                                                 c.spindle_rpm});
}

std::string iso_length_offset(const Machine& machine, int tool) {
    return tool > 0 && settings_of<iso::Settings>(machine).length_offset ? fmt::format("G43 H{}", tool) : std::string();
}

std::optional<MachineProblem> check_iso_machine(const Machine& machine) {
    if (auto p = decimal_point_only_problem(machine, "Fanuc and LinuxCNC read \"1,5\" as 1 and a stray comma "
                                                     "(rs274 refuses the block)"))
        return p;
    const auto& b = machine.frame.start_block;
    if (auto p = diameter_mode_problem(machine, "G7", true, "LinuxCNC's lathe diameter mode")) return p;
    if (auto p = diameter_mode_problem(machine, "G8", false, "LinuxCNC's lathe radius mode")) return p;
    if (machine.x_diameter && machine.i_diameter && std::find(b.begin(), b.end(), "G7") != b.end())
        return MachineProblem{{"/globals/iDiameterProg"},
                              "LinuxCNC's G7 reads X as a diameter but I and K as radii: iDiameterProg true would "
                              "write I at twice the arc centre's distance; set iDiameterProg to false"};
    static constexpr std::string_view unit_words[] = {"G20", "G21", "G70", "G71"};
    // G98/G99: the return level on a mill, the feed mode on Fanuc T (frame.feedModes).
    static constexpr std::string_view start_words[] = {"G17", "G18", "G19", "G40", "G49", "G80",
                                                       "G90", "G94", "G98", "G99", "G7",  "G8"};
    if (auto p = start_block_problem(machine, unit_words, start_words)) return p;
    // Fanuc T (feed modes G98/G99, G code system A): G90 and G94 are turning and facing cycles.
    bool fanuc_t = false;
    for (const auto& [mode, code] : machine.frame.feed_modes) fanuc_t = fanuc_t || code == "G98" || code == "G99";
    for (size_t i = 0; fanuc_t && i < b.size(); ++i)
        if (b[i] == "G90" || b[i] == "G94")
            return MachineProblem{{fmt::format("/frame/startBlock/{}", i), "/frame/feedModes"},
                                  fmt::format("with feed modes G98/G99 (Fanuc T, G code system A) {} is a turning "
                                              "cycle, not a mode: take it out of the start block",
                                              b[i])};
    // GRBL's tool change is a comment and M0: the reader needs the whole "Insert tool" comment.
    const iso::Settings& settings = settings_of<iso::Settings>(machine);
    if (settings.tool_change == iso::ToolChangeStyle::pause && machine.block.comment_max_length > 0 &&
        machine.block.comment_max_length < static_cast<int>(nc::default_comment_limit))
        return MachineProblem{{"/commentMaxLength", "/settings/toolChange"},
                              fmt::format("a tool change that pauses (M0) tells the operator the tool in a comment: "
                                          "a limit below {} characters would cut it off; leave commentMaxLength out",
                                          nc::default_comment_limit)};
    if (machine.arcs.format == ArcFormat::ijk_absolute)
        return MachineProblem{{"/arcs/format"},
                              "Fanuc, GRBL and LinuxCNC read I, J and K relative to the arc's start (LinuxCNC's "
                              "absolute mode G90.1 is not written): ijk-absolute would put every centre elsewhere; use "
                              "ijk-relative or radius"};
    // The O line carries the program name in parentheses, whatever the comment style.
    if (settings.program_number > 0 && machine.block.comment_style == nc::CommentStyle::semicolon)
        return MachineProblem{{"/comments", "/settings/programNumber"},
                              "a program number writes the program's name as \"O1000 (name)\", and Fanuc reads "
                              "comments in parentheses only: use \"comments\": \"parentheses\" (or programNumber 0, "
                              "as LinuxCNC)"};
    return single_arc_plane_problem(machine, Plane::xy);
}

}  // namespace camgen
