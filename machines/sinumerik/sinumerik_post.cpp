// The Sinumerik 840D dialect. REFERENCE.md §4; parameter orders of the standard cycles:
// CYCLE81(RTP, RFP, SDIS, DP, DPR), CYCLE82(..., DTB), CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP,
// FDPR, DAM, DTB, DTS, FRF, VARI, _AXN, _MDEP, _VRT, _DTD, _DIS1), CYCLE84(RTP, RFP, SDIS, DP,
// DPR, DTB, SDAC, MPIT, PIT, POSS, SST, SST1), CYCLE85(RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF),
// CYCLE86(RTP, RFP, SDIS, DP, DPR, DTB, SDIR, RPA, RPO, RPAP, POSS), CYCLE89(..., DTB).
#include "machines/sinumerik/sinumerik_post.hpp"

#include <numbers>

#include <fmt/format.h>

#include "camgen/common/json_util.hpp"

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
    // FRF is a factor: three decimals whatever the units.
    nc::FormatSpec factor_spec = machine.format("xyz").spec();
    factor_spec.scale = 1.0;
    factor_spec.decimals = 3;
    const nc::Format factor(factor_spec);
    const DrillValues& p = c.values;
    // SDIS is unsigned: when the feed starts below the surface, the feed-start plane becomes
    // the reference plane (DP and FDEP are absolute, so nothing else changes).
    const double rfp = std::min(c.reference_z, c.safe_z);
    std::vector<std::string> v = {len.format(c.retract_z), len.format(rfp), len.format(c.safe_z - rfp),
                                  len.format(c.bottom_z), ""};
    auto dwell = [&](const std::optional<double>& s) { return s && *s > 0 ? sec.format(*s) : std::string(); };
    const std::string spindle_dir = c.spindle_direction == SpindleDirection::cw ? "3" : "4";
    switch (c.kind) {
        case CycleKind::drill:
            return "CYCLE81(" + join_parameters(v) + ")";
        case CycleKind::dwell:
            v.push_back(dwell(p.get(DrillField::bottom_dwell)));
            return "CYCLE82(" + join_parameters(v) + ")";
        case CycleKind::deep:
        case CycleKind::chip_break: {
            const bool full = c.kind == CycleKind::deep;
            v.push_back(len.format(c.safe_z - p.get(DrillField::first_depth).value_or(c.safe_z - c.bottom_z)));  // FDEP
            v.push_back("");                                                                    // FDPR
            v.push_back(p.degression_type() == DegressionType::value ? len.format(*p.get(DrillField::degression)) : "");  // DAM
            v.push_back("");                                          // DTB: would dwell at every peck
            v.push_back(full ? dwell(p.get(DrillField::top_dwell)) : "");              // DTS
            v.push_back(factor.format(p.get(DrillField::first_feedrate_factor).value_or(1.0)));  // FRF
            v.push_back(full ? "1" : "0");                            // VARI
            v.push_back("");                                          // _AXN: tool axis
            v.push_back(p.get(DrillField::minimum_depth) ? len.format(*p.get(DrillField::minimum_depth)) : "");  // _MDEP
            v.push_back(full ? "" : len.format(p.get(DrillField::pecking_retract).value_or(machine.peck_clearance)));  // _VRT
            v.push_back(dwell(p.get(DrillField::bottom_dwell)));                       // _DTD
            v.push_back(full ? len.format(machine.peck_clearance) : "");  // _DIS1
            return "CYCLE83(" + join_parameters(v) + ")";
        }
        case CycleKind::tap:
        case CycleKind::tap_left: {
            const double pitch = p.get(DrillField::pitch).value_or(0.0) * (c.kind == CycleKind::tap_left ? -1.0 : 1.0);
            const double sst = p.get(DrillField::tapping_speed).value_or(c.spindle_rpm);
            v.push_back(dwell(p.get(DrillField::bottom_dwell)));         // DTB
            v.push_back(spindle_dir);                   // SDAC: direction after the cycle
            v.push_back("");                            // MPIT
            v.push_back(len.format(pitch));             // PIT, negative: left-hand
            v.push_back("0");                           // POSS
            v.push_back(rpm.format(sst));               // SST
            v.push_back(rpm.format(p.get(DrillField::retract_speed).value_or(sst)));  // SST1
            return "CYCLE84(" + join_parameters(v) + ")";
        }
        case CycleKind::ream:
            v.push_back(dwell(p.get(DrillField::bottom_dwell)));
            v.push_back(feed.format(c.feed));                                  // FFR
            v.push_back(feed.format(p.get(DrillField::retract_feedrate).value_or(c.feed)));     // RFF
            return "CYCLE85(" + join_parameters(v) + ")";
        case CycleKind::bore_stop:
            v.push_back(dwell(p.get(DrillField::bottom_dwell)));
            // SDIR, then no lift-off (RPA, RPO, RPAP) and POSS 0: out along the hole axis.
            for (const char* s : {spindle_dir.c_str(), "0", "0", "0", "0"}) v.emplace_back(s);
            return "CYCLE86(" + join_parameters(v) + ")";
        case CycleKind::bore_dwell:
            v.push_back(dwell(p.get(DrillField::bottom_dwell)));
            return "CYCLE89(" + join_parameters(v) + ")";
    }
    return "";
}

SinumerikPost::SinumerikPost(const Machine& machine, std::ostream& out, PostOptions options)
    : Post(machine, out, std::move(options)) {
    json::Source source{machine.source, json::LineMap{}};
    json::Fields f(machine.dialect_settings, "/settings", source);
    f.finish();
}

void SinumerikPost::on_open() {
    if (!options_.program_name.empty()) out_.comment(options_.program_name);
    out_.add(g(17)).add(g(machine_.units == Units::inch ? 70 : 71)).add(g(90)).add(g(94)).end();
    plane_.set_last(17);
}

void SinumerikPost::on_close() { out_.add(m(30)).end(); }

void SinumerikPost::on_tool_change(const ToolChange& tool) {
    if (!tool.description.empty()) out_.comment(fmt::format("T{} {}", tool.number, tool.description));
    // D1: the tool's first cutting edge carries its length and radius.
    out_.add(fmt::format("T{}", tool.number)).add("D1").end();
    out_.add(m(6)).end();
}

// G4 F: dwell in seconds (G4 S would be spindle revolutions).
void SinumerikPost::on_dwell(double seconds) { out_.add(g(4)).add(dwell_fmt_.word("F", seconds)).end(); }

// G41/G42 take no D word here: D1 (the cutting edge) was selected with the tool.
std::string SinumerikPost::compensation_words(CompensationSide side) const {
    return g(side == CompensationSide::off ? 40 : side == CompensationSide::left ? 41 : 42);
}

void SinumerikPost::on_circular(const ArcGeometry& arc, double feed) {
    if (machine_.arcs.format != ArcFormat::radius) {
        Post::on_circular(arc, feed);
        return;
    }
    // CR=: the radius, negative for a sweep over 180 degrees.
    std::string plane;
    if (machine_.arcs.planes.size() > 1)
        plane = plane_.format(arc.plane == Plane::xy ? 17 : arc.plane == Plane::xz ? 18 : 19);
    std::string motion = motion_word(arc.direction == ArcDirection::cw ? 2 : 3);
    std::string fs = feed_word(feed);
    std::string xs = arc.plane != Plane::yz ? x_.force(arc.end.x) : x_.format(arc.end.x);
    std::string ys = arc.plane != Plane::xz ? y_.force(arc.end.y) : y_.format(arc.end.y);
    std::string zs = arc.plane != Plane::xy ? z_.force(arc.end.z) : z_.format(arc.end.z);
    double r = arc.sweep > std::numbers::pi ? -arc.radius : arc.radius;
    out_.add(plane).add(motion).add(xs).add(ys).add(zs).add(xyz_fmt_.word("CR=", r)).add(fs).end();
}

std::optional<std::string> SinumerikPost::canned_limit(const DrillCycle& c, const DrillingCycleSpec&) const {
    if (c.values.degression_type() == DegressionType::factor)
        return "its DAM takes a degression value, not a factor";
    return std::nullopt;
}

void SinumerikPost::on_drilling_header(const DrillCycle& c, const DrillingCycleSpec&) {
    // CYCLE81/82/83/86/89 drill at the active feed; CYCLE84 and CYCLE85 carry their own.
    if (c.kind != CycleKind::tap && c.kind != CycleKind::tap_left && c.kind != CycleKind::ream)
        out_.add(feed_word(c.feed)).end();
    out_.add("MCALL " + sinumerik_cycle_call(c, machine_)).end();
}

void SinumerikPost::on_drilling_point(const DrillCycle&, const DrillingCycleSpec&, Vec2 at, bool first) {
    // Every positioning block calls the cycle: both coordinates on each, so no hole is lost.
    std::string xs = x_.force(at.x), ys = y_.force(at.y);
    out_.add(first ? g(0) : "").add(xs).add(ys).end();
    motion_.set_last(0);
}

void SinumerikPost::on_drilling_footer(const DrillCycle&, const DrillingCycleSpec&) { out_.add("MCALL").end(); }

}  // namespace camgen
