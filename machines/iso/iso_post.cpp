// The ISO (Fanuc-style) dialect: %, O-number, G-code program frame, T.. M6, S.. M3, G43 H,
// canned cycles G73/G74/G81-G89 with G98/G99 and G80, LinuxCNC G33.1 rigid tapping.
#include "machines/iso/iso_post.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "camgen/common/json_util.hpp"

namespace camgen {

namespace {
// Whether the canned cycle carries `field`.
bool contains(const std::vector<DrillField>& fields, DrillField field) {
    return std::find(fields.begin(), fields.end(), field) != fields.end();
}
}  // namespace

IsoPost::IsoPost(const Machine& machine, std::ostream& out, PostOptions options)
    : Post(machine, out, std::move(options)) {
    json::Source source{machine.source, json::LineMap{}};
    json::Fields f(machine.dialect_settings, "/settings", source);
    program_number_ = f.optional_integer("programNumber").value_or(1000);
    percent_ = f.boolean("percentLines", true);
    length_offset_ = f.boolean("toolLengthOffset", true);
    tool_change_ = iso::tool_change_setting(f);
    end_code_ = f.optional_string("endCode").value_or("M30");
    f.finish();
}

void IsoPost::on_open() {
    if (percent_) writer().raw("%");
    if (program_number_ > 0) {
        std::string line = fmt::format("O{:04}", options().program_number.value_or(program_number_));
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
    writer().add(end_code_).end();
    if (percent_) writer().raw("%");
}

void IsoPost::on_tool_change(const ToolChange& tool) {
    switch (tool_change_) {
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
    length_offset_pending_ = length_offset_;
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
    if (dwell > 0 || (dwell_cycle && contains(spec.fields, DrillField::bottom_dwell)))
        writer().add(dwell_format().word("P", dwell));
    writer().add(feed_word(c.feed)).end();
}

void IsoPost::on_drilling_footer(const DrillCycle& c, const DrillingCycleSpec& spec) {
    if (spec.style != CannedStyle::rigid_g33_1) writer().add(g(80)).end();
    if (tapping_direction(c)) on_spindle(Spindle{c.spindle_direction == SpindleDirection::cw ? SpindleState::cw : SpindleState::ccw,
                                                 c.spindle_rpm});
}

}  // namespace camgen
