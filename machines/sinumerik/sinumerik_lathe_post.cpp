#include "machines/sinumerik/sinumerik_lathe_post.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/geometry/compensation.hpp"

namespace camgen {

SinumerikLathePost::SinumerikLathePost(const Machine& machine, std::ostream& out, PostOptions options)
    : SinumerikPost(machine, out, std::move(options)) {
    if (machine.kind != MachineKind::lathe)
        throw InputError("/dialect", "the sinumerik-lathe dialect writes for lathes: set \"kind\": \"lathe\"", 0,
                         machine.source);
}

void SinumerikLathePost::on_compensation(const Compensation& c) {
    if (c.side != CompensationSide::off)
        writer().comment(fmt::format("{} nose comp: T{} D1 radius {}, cutting edge position {}, {} (LinuxCNC numbering)",
                                     c.side == CompensationSide::left ? "G41" : "G42", current_tool(), number_text(c.radius),
                                     c.orientation, lathe_tip_words(c.orientation)));
    SinumerikPost::on_compensation(c);
}

void SinumerikLathePost::on_open() {
    SinumerikPost::on_open();
    const auto& b = machine().frame.start_block;
    if (std::find(b.begin(), b.end(), "G18") != b.end()) assume_plane(18);
}

void SinumerikLathePost::on_spindle(const Spindle& s) {
    if (s.state == SpindleState::off || (s.surface_speed == 0 && !surface_mode_)) {
        SinumerikPost::on_spindle(s);
        return;
    }
    const std::string on = m(s.state == SpindleState::cw ? 3 : 4);
    if (s.surface_speed == 0) {
        writer().add(g(97)).add(speed_word(s.rpm)).add(on).end();
        surface_mode_ = false;
        // G97 switches feed per revolution on, as G95 (SINUMERIK ONE programming manual: "G97:
        // revolutional feedrate and constant spindle speed"; the 840D manual of 2004: "G97 can be
        // programmed without G96 beforehand. The function then has the same effect as G95"): under
        // feed per minute, G94 again (it keeps the speed just written; G971 would do the same,
        // but not every Sinumerik has it), and the F is written anew.
        if (feed_mode_now() == FeedMode::per_minute) {
            const auto code = machine().frame.feed_modes.find(FeedMode::per_minute);
            writer().add(code != machine().frame.feed_modes.end() ? code->second : g(94)).end();
            forget_feed();
        }
        return;
    }
    // G96 S in m/min (ft/min under G700), the spindle held to LIMS= (SINUMERIK programming
    // manual, "Constant cutting rate"); G96 switches G95 on, which camgen's operations under
    // it use already.
    const std::string limit = speed_text(s.rpm);
    const double vc = machine().units == Units::inch ? s.surface_speed / 0.3048 : s.surface_speed;
    if (rpm_format().is_zero(vc))
        fail("", fmt::format("surface speed {} m/min would be written as S0 on machine {}", number_text(s.surface_speed),
                             machine().name));
    if (limit_written_ != s.rpm) writer().add("LIMS=" + limit).end();
    limit_written_ = s.rpm;
    writer().add(g(96)).add(rpm_format().word("S", vc)).add(on).end();
    surface_mode_ = true;
}

void SinumerikLathePost::on_thread_feed(const Vec3& from, const ThreadFeed& t) {
    if (std::abs(t.to.y - from.y) > 1e-9) fail("", "a thread-cutting move that leaves the XZ plane");
    const double dx = std::abs(t.to.x - from.x), dz = std::abs(t.to.z - from.z);
    // A taper (a chamfered runout's pull-out): G33 takes the lead of the longer axis, K along Z
    // below 45 degrees (the Programming Manual, G33 taper thread); camgen writes no steeper one.
    if (dx > 1e-9 && !(dz > 0 && dx <= dz + 0.001))
        fail("", "a thread-cutting move steeper than 45 degrees from Z: camgen writes a taper's lead along Z (K) only");
    const std::string lead = lead_word("K", t.lead);
    writer().add(g(33));
    if (dx > 1e-9) writer().add(force_xy({t.to.x, t.to.y}).x);
    writer().add(force_z(t.to.z)).add(lead).end();
    forget_motion();
}

std::optional<std::string> SinumerikLathePost::canned_limit(const DrillCycle& c, const DrillingCycleSpec& spec) const {
    if (auto v = c.values.get(DrillField::peck_clearance); v && *v != machine().peck_clearance)
        return "its _DIS1 is the machine's peck clearance, " + xyz_format().format(machine().peck_clearance) + " mm";
    return SinumerikPost::canned_limit(c, spec);
}

void SinumerikLathePost::on_drilling_header(const DrillCycle& c, const DrillingCycleSpec& spec) {
    // Under G18 the cycle would drill along Y: the axial hole is drilled under G17.
    writer().add(g(17)).end();
    SinumerikPost::on_drilling_header(c, spec);
}

void SinumerikLathePost::on_drilling_footer(const DrillCycle& c, const DrillingCycleSpec& spec) {
    SinumerikPost::on_drilling_footer(c, spec);
    writer().add(g(18)).end();
}

}  // namespace camgen
