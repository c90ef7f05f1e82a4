// The Sinumerik 840D dialect: drilling as modal standard cycle calls (MCALL CYCLE81..89),
// whose parameter positions sinumerik_words.hpp names for the post and the reader.
#include "machines/sinumerik/sinumerik_post.hpp"

#include <cmath>

#include <fmt/format.h>

#include "camgen/common/json_util.hpp"
#include "camgen/post/machine_checks.hpp"
#include "machines/sinumerik/sinumerik_words.hpp"

namespace camgen {

namespace {

// Joins parameters with ", ", leaving out empty trailing ones (the cycle's defaults).
std::string join_parameters(std::vector<std::string> p) {
    while (!p.empty() && p.back().empty()) p.pop_back();
    std::string s;
    for (size_t i = 0; i < p.size(); ++i) {
        if (i) s += ", ";
        s += p[i];
    }
    return s;
}

}  // namespace

std::string sinumerik_cycle_call(const DrillCycle& c, const Machine& machine) {
    const nc::Format len = machine.format("xyz"), sec = machine.format("dwell"), feed = machine.format("feed"),
                     rpm = machine.format("rpm");
    // FRF is a factor, whatever the units: three decimals, or as many more (up to six) as the
    // job's factor needs to be read back as itself (0.7803 is not 0.780).
    const double frf = c.values.get(DrillField::first_feedrate_factor).value_or(1.0);
    nc::FormatSpec factor_spec = machine.format("xyz").spec();
    factor_spec.scale = 1.0;
    factor_spec.decimals = 3;
    const nc::Format factor = nc::exact_format(factor_spec, frf, 6);
    const DrillValues& p = c.values;
    const sinumerik::CycleForm& form = sinumerik::cycle_form(c.kind);
    // The parameters by position; empty ones are the cycle's defaults.
    std::vector<std::string> v(form.count);
    // SDIS is unsigned: when the feed starts below the surface, the feed-start plane becomes
    // the reference plane (DP and FDEP are absolute, so nothing else changes). DPR stays empty.
    const double rfp = std::min(c.reference_z, c.safe_z);
    v[sinumerik::common::rtp] = len.format(c.retract_z);
    v[sinumerik::common::rfp] = len.format(rfp);
    v[sinumerik::common::sdis] = len.format(c.safe_z - rfp);
    v[sinumerik::common::dp] = len.format(c.bottom_z);
    auto dwell = [&](const std::optional<double>& s) { return s && *s > 0 ? sec.format(*s) : std::string(); };
    const std::string spindle_dir = c.spindle_direction == SpindleDirection::cw ? "3" : "4";
    const std::string zero = "0", one = "1";
    switch (c.kind) {
        case CycleKind::drill:
            break;
        case CycleKind::dwell:
            v[sinumerik::cycle82::dtb] = dwell(p.get(DrillField::bottom_dwell));
            break;
        case CycleKind::deep:
        case CycleKind::chip_break: {
            namespace q = sinumerik::cycle83;
            const bool full = c.kind == CycleKind::deep;
            // The control pecks by the distance from RFP + SDIS to FDEP as written: taken from the
            // rounded planes, a peck keeps its size (SDIS 4.3125 written 4.313 with FDEP from the
            // exact plane made every peck 0.001 mm longer, 0.007 mm by the seventh: a fuzz finding).
            const double written_safe = len.rounded(rfp) + len.rounded(c.safe_z - rfp);
            v[q::fdep] = len.format(written_safe - p.get(DrillField::first_depth).value_or(c.safe_z - c.bottom_z));
            if (p.degression_type() == DegressionType::value) v[q::dam] = len.format(*p.get(DrillField::degression));
            // DTB stays empty: it would dwell at every peck.
            if (full) v[q::dts] = dwell(p.get(DrillField::top_dwell));
            v[q::frf] = factor.format(frf);
            v[q::vari] = full ? one : zero;
            // _AXN stays empty: the tool axis.
            if (p.get(DrillField::minimum_depth)) v[q::mdep] = len.format(*p.get(DrillField::minimum_depth));
            if (!full) v[q::vrt] = len.format(p.get(DrillField::pecking_retract).value_or(machine.peck_clearance));
            v[q::dtd] = dwell(p.get(DrillField::bottom_dwell));
            if (full) v[q::dis1] = len.format(machine.peck_clearance);
            break;
        }
        case CycleKind::tap:
        case CycleKind::tap_left: {
            namespace q = sinumerik::cycle84;
            const double pitch = p.get(DrillField::pitch).value_or(0.0) * (c.kind == CycleKind::tap_left ? -1.0 : 1.0);
            const double sst = p.get(DrillField::tapping_speed).value_or(c.spindle_rpm);
            v[q::dtb] = dwell(p.get(DrillField::bottom_dwell));
            v[q::sdac] = spindle_dir;  // the direction after the cycle; MPIT stays empty
            // PIT, SST and SST1 multiply into the feed: as many decimals as the job's values need
            // (an inch pitch of 0.79375 mm, 123.5 rpm), or the control taps at another feed.
            v[q::pit] = nc::exact_format(len.spec(), pitch, 6).format(pitch);  // negative: left-hand
            v[q::poss] = zero;
            v[q::sst] = nc::exact_format(rpm.spec(), sst, 3).format(sst);
            const double sst1 = p.get(DrillField::retract_speed).value_or(sst);
            v[q::sst1] = nc::exact_format(rpm.spec(), sst1, 3).format(sst1);
            break;
        }
        case CycleKind::ream: {
            namespace q = sinumerik::cycle85;
            v[q::dtb] = dwell(p.get(DrillField::bottom_dwell));
            v[q::ffr] = feed.format(c.feed);
            v[q::rff] = feed.format(p.get(DrillField::retract_feedrate).value_or(c.feed));
            break;
        }
        case CycleKind::bore_stop: {
            namespace q = sinumerik::cycle86;
            v[q::dtb] = dwell(p.get(DrillField::bottom_dwell));
            v[q::sdir] = spindle_dir;
            // No lift-off (RPA, RPO, RPAP) and POSS 0: out along the hole axis.
            for (std::size_t i : {q::rpa, q::rpo, q::rpap, q::poss}) v[i] = zero;
            break;
        }
        case CycleKind::bore_dwell:
            v[sinumerik::cycle89::dtb] = dwell(p.get(DrillField::bottom_dwell));
            break;
    }
    return fmt::format("{}({})", form.name, join_parameters(v));
}

SinumerikPost::SinumerikPost(const Machine& machine, std::ostream& out, PostOptions options)
    : Post(machine, out, std::move(options)) {}

void SinumerikPost::on_open() {
    if (!options().program_name.empty()) writer().comment(options().program_name);
    // G700/G710: positions and feeds in the program's units, whatever the control's base
    // system (G70/G71 would leave F in the base system's unit).
    write_start_block(g(machine().units == Units::inch ? 700 : 710));
    if (starts_in_xy(machine())) assume_plane(17);
}

void SinumerikPost::on_close() { writer().add(m(30)).end(); }

void SinumerikPost::on_tool_change(const ToolChange& tool) {
    if (!tool.description.empty()) writer().comment(fmt::format("T{} {}", tool.number, tool.description));
    // D1: the tool's first cutting edge carries its length and radius.
    writer().add(fmt::format("T{}", tool.number)).add("D1").end();
    writer().add(m(6)).end();
}

void SinumerikPost::on_stop(const Stop& stop) {
    std::string msg = writer().clean_comment(stop.message);
    // A string's quotes end it: the message keeps single ones; ';' starts a comment.
    for (char& c : msg) {
        if (c == '"') c = '\'';
        if (c == ';') c = ',';
    }
    if (!msg.empty()) writer().add(fmt::format("MSG(\"{}\")", msg)).end();
    writer().add(m(stop.kind == StopKind::optional ? 1 : 0)).end();
    if (!msg.empty()) writer().add("MSG()").end();
}

// G4 F: dwell in seconds (G4 S would be spindle revolutions).
void SinumerikPost::on_dwell(double seconds) { writer().add(g(4)).add(dwell_format().word("F", seconds)).end(); }

// G41/G42 take no D word here: D1 (the cutting edge) was selected with the tool.
std::string SinumerikPost::compensation_words(const Compensation& c) const {
    return g(c.side == CompensationSide::off ? 40 : c.side == CompensationSide::left ? 41 : 42);
}

// CR=: the radius, negative for a sweep over 180 degrees.
std::string SinumerikPost::radius_word(double radius) const { return xyz_format().word("CR=", radius); }

// A CR= arc states its end point in the plane's axes whatever forceXY says.
bool SinumerikPost::force_arc_end() const {
    return machine().arcs.format == ArcFormat::radius || Post::force_arc_end();
}

std::optional<std::string> SinumerikPost::canned_limit(const DrillCycle& c, const DrillingCycleSpec&) const {
    if (c.values.degression_type() == DegressionType::factor)
        return "its DAM takes a degression value, not a factor";
    // FRF reduces the first feed only: the control takes no factor above 1.
    if (c.values.get(DrillField::first_feedrate_factor).value_or(1.0) > 1.0)
        return "its FRF takes a factor up to 1, not above";
    // The control feeds the first peck at F x FRF, unclamped: below the machine's minimum feed
    // only longhand moves (clamped like every feed) run as the job says.
    if (c.feed * c.values.get(DrillField::first_feedrate_factor).value_or(1.0) < machine().limits.min_feed)
        return "its first feed F x FRF would be below the machine's minimum feed";
    return std::nullopt;
}

void SinumerikPost::on_drilling_header(const DrillCycle& c, const DrillingCycleSpec&) {
    // CYCLE81/82/83/86/89 drill at the active feed; CYCLE84 and CYCLE85 carry their own.
    if (c.kind != CycleKind::tap && c.kind != CycleKind::tap_left && c.kind != CycleKind::ream)
        writer().add(feed_word(c.feed)).end();
    writer().add("MCALL " + sinumerik_cycle_call(c, machine())).end();
}

void SinumerikPost::on_drilling_point(const DrillCycle&, const DrillingCycleSpec&, Vec2 at, bool first) {
    // Every positioning block calls the cycle: both coordinates on each, so no hole is lost.
    const AxisWords w = force_xy(at);
    writer().add(first ? g(0) : "").add(w.x).add(w.y).end();
    assume_motion(0);
}

void SinumerikPost::on_drilling_footer(const DrillCycle&, const DrillingCycleSpec&) { writer().add("MCALL").end(); }

std::string sinumerik_length_offset(const Machine&, int tool) { return tool > 0 ? "D1" : ""; }

std::optional<MachineProblem> check_sinumerik_machine(const Machine& machine) {
    if (auto p = decimal_point_only_problem(machine, "',' separates the parameters of a cycle call, so "
                                                     "CYCLE82(5,000, 0,000, ...) would split every number in two"))
        return p;
    if (auto p = diameter_mode_problem(machine, "DIAMON", true, "Sinumerik's diameter programming")) return p;
    if (auto p = diameter_mode_problem(machine, "DIAM90", true, "Sinumerik's diameter programming for G90")) return p;
    if (auto p = diameter_mode_problem(machine, "DIAMOF", false, "Sinumerik's radius programming")) return p;
    static constexpr std::string_view unit_words[] = {"G70", "G71", "G700", "G710"};
    static constexpr std::string_view start_words[] = {"G17", "G18", "G19", "G40", "G90", "G94", "DIAMON"};
    if (auto p = start_block_problem(machine, unit_words, start_words)) return p;
    if (machine.block.separator.empty())
        return MachineProblem{{"/globals/variableDelimeter"},
                              "Sinumerik's commands are words of letters (DIAMON, MCALL, CYCLE83(...)): without a "
                              "separator they run into the next word; give variableDelimeter a space"};
    return single_arc_plane_problem(machine, Plane::xy);
}

}  // namespace camgen
