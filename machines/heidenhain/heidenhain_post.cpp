// The Heidenhain TNC conversational dialect: drilling as cycle definitions 200, 203 and 207
// whose Q parameters heidenhain_words.hpp names for the post and the reader.
#include "machines/heidenhain/heidenhain_post.hpp"

#include <cctype>
#include <map>

#include <fmt/format.h>

#include "camgen/common/json_util.hpp"
#include "camgen/post/longhand.hpp"
#include "camgen/post/machine_checks.hpp"
#include "machines/heidenhain/heidenhain_words.hpp"

namespace camgen {

namespace {

bool tapping(CycleKind k) { return k == CycleKind::tap || k == CycleKind::tap_left; }
bool pecking(CycleKind k) { return k == CycleKind::deep || k == CycleKind::chip_break; }

}  // namespace

std::pair<std::string, std::vector<TncParameter>> heidenhain_cycle(const DrillCycle& c, const Machine& machine) {
    using heidenhain::Q;
    nc::FormatSpec signed_len = machine.format("xyz").spec();
    signed_len.force_sign = true;
    nc::FormatSpec signed_feed = machine.format("feed").spec();
    signed_feed.force_sign = true;
    nc::FormatSpec signed_sec = machine.format("dwell").spec();
    signed_sec.force_sign = true;
    const nc::Format len(signed_len), feed(signed_feed), sec(signed_sec);
    const DrillValues& p = c.values;
    // The set-up clearance is unsigned: when the feed starts below the surface, the
    // feed-start plane is given as the surface.
    const double surface = std::min(c.reference_z, c.safe_z);
    auto dwell = [&](DrillField f) { return sec.format(p.get(f).value_or(0.0)); };  // none: 0
    // The values by parameter; the cycle's form gives their order and comments.
    std::map<Q, std::string> v = {{Q::setup_clearance, len.format(c.safe_z - surface)},
                                  {Q::depth, len.format(c.bottom_z - surface)},
                                  {Q::surface, len.format(surface)},
                                  {Q::second_setup_clearance, len.format(c.retract_z - surface)}};
    const heidenhain::CycleForm* form = nullptr;
    if (tapping(c.kind)) {
        form = &heidenhain::rigid_tapping;
        const double pitch = p.get(DrillField::pitch).value_or(0.0) * (c.kind == CycleKind::tap_left ? -1.0 : 1.0);
        // Q239 times the speed is the feed: as many decimals as the pitch needs (1/32 in).
        v[Q::pitch] = nc::exact_format(len.spec(), pitch, 6).format(pitch);
    } else if (!pecking(c.kind)) {
        form = &heidenhain::drilling;
        v[Q::plunge_feed] = feed.format(c.feed);
        v[Q::plunging_depth] = len.format(surface - c.bottom_z);  // all in one plunge
        v[Q::top_dwell] = sec.format(0.0);
        v[Q::bottom_dwell] = dwell(DrillField::bottom_dwell);
    } else {
        form = &heidenhain::universal_drilling;
        const bool full = c.kind == CycleKind::deep;
        const double decrement = p.degression_type() == DegressionType::value ? *p.get(DrillField::degression) : 0.0;
        v[Q::plunge_feed] = feed.format(c.feed);
        v[Q::plunging_depth] = len.format(p.get(DrillField::first_depth).value_or(c.safe_z - c.bottom_z));
        v[Q::top_dwell] = full ? dwell(DrillField::top_dwell) : sec.format(0.0);
        v[Q::decrement] = len.format(decrement);
        v[Q::breaks] = full ? "+0" : fmt::format("+{}", heidenhain::max_breaks);
        v[Q::min_plunging_depth] = len.format(p.get(DrillField::minimum_depth).value_or(0.0));
        v[Q::bottom_dwell] = dwell(DrillField::bottom_dwell);
        // FMAX is the same number in mm and inch programs: written as it is, not converted.
        v[Q::retraction_feed] = !full && p.get(DrillField::retract_feedrate)
                                    ? feed.format(*p.get(DrillField::retract_feedrate))
                                    : fmt::format("+{}", heidenhain::fmax_feed);
        v[Q::chip_break_distance] =
            len.format(full ? machine.peck_clearance : p.get(DrillField::pecking_retract).value_or(machine.peck_clearance));
    }
    std::vector<TncParameter> params;
    for (const heidenhain::QParameter& q : form->parameters)
        params.push_back({heidenhain::number(q.q), v.at(q.q), std::string(q.comment)});
    return {fmt::format("CYCL DEF {} {}", form->number, form->title), std::move(params)};
}

HeidenhainPost::HeidenhainPost(const Machine& machine, std::ostream& out, PostOptions options)
    : Post(machine, out, std::move(options)) {}

std::string HeidenhainPost::program_name() const {
    // A TNC program name: letters, digits, '_' and '-'.
    std::string s;
    for (char c : options().program_name) s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
    return s.empty() ? "camgen" : s;
}

void HeidenhainPost::on_open() {
    writer().add(fmt::format("BEGIN PGM {} {}", program_name(), machine().units == Units::inch ? "INCH" : "MM")).end();
}

void HeidenhainPost::on_close() {
    if (pending_tool_) flush_tool_call(std::nullopt);
    writer().add("M30").end();
    writer().add(fmt::format("END PGM {} {}", program_name(), machine().units == Units::inch ? "INCH" : "MM")).end();
}

void HeidenhainPost::on_comment(const std::string& text) { writer().add("; " + writer().clean_comment(text)).end(); }

void HeidenhainPost::on_tool_change(const ToolChange& tool) {
    if (pending_tool_) flush_tool_call(std::nullopt);
    // TOOL CALL carries the spindle speed: wait for it.
    pending_tool_ = tool;
}

void HeidenhainPost::flush_tool_call(std::optional<double> rpm) {
    const ToolChange& t = *pending_tool_;
    if (!t.description.empty()) on_comment(fmt::format("T{} {}", t.number, t.description));
    writer().add(fmt::format("TOOL CALL {} Z", t.number)).add(rpm ? rpm_format().word("S", *rpm) : "").end();
    pending_tool_.reset();
}

void HeidenhainPost::on_spindle(const Spindle& s) {
    if (s.state == SpindleState::off) {
        if (pending_tool_) flush_tool_call(std::nullopt);
        writer().add("M5").end();
        return;
    }
    std::string speed = speed_word(s.rpm);  // checks the machine's limit
    if (pending_tool_)
        flush_tool_call(s.rpm);
    else if (s.rpm != speed_)
        writer().add("TOOL CALL Z").add(speed).end();
    speed_ = s.rpm;
    writer().add(s.state == SpindleState::cw ? "M3" : "M4").end();
}

void HeidenhainPost::on_stop(const Stop& stop) {
    if (pending_tool_) flush_tool_call(std::nullopt);
    writer().add(stop.kind == StopKind::optional ? "M1" : "STOP")
        .add(stop.message.empty() ? "" : "; " + writer().clean_comment(stop.message))
        .end();
}

void HeidenhainPost::on_dwell(double seconds) {
    writer().add("CYCL DEF 9.0 DWELL TIME").end();
    writer().add("CYCL DEF 9.1 DWELL " + dwell_format().format(seconds)).end();
}

void HeidenhainPost::on_rapid(const Vec3& to) {
    if (pending_tool_) flush_tool_call(std::nullopt);
    const AxisWords w = axis_words(to);
    if (w.x.empty() && w.y.empty() && w.z.empty()) return;
    // FMAX holds for its block only; the programmed F stays in force for the next L.
    writer().add("L").add(w.x).add(w.y).add(w.z).add("R0 FMAX").end();
}

void HeidenhainPost::rapid_z_from_unknown(double z) {
    if (pending_tool_) flush_tool_call(std::nullopt);
    writer().add("L").add(force_z(z)).add("R0 FMAX").end();
}

// Radius compensation is a word of the L block: R0, RL, RR.
std::string HeidenhainPost::compensation_words(const Compensation& c) const {
    return c.side == CompensationSide::off ? "R0" : c.side == CompensationSide::left ? "RL" : "RR";
}

// A feed move is an L block; its compensation word follows the coordinates.
Post::LinearLayout HeidenhainPost::linear_layout() { return {"L", true}; }

void HeidenhainPost::on_circular(const ArcGeometry& arc, double feed) {
    // CC: the centre (absolute); C: the end point and the direction (DR+ counter-clockwise).
    // The machine file allows XY arcs only; others arrive here as lines.
    nc::Word cx("X", xyz_format(), true), cy("Y", xyz_format(), true);
    writer().add("CC").add(cx.format(arc.centre.x)).add(cy.format(arc.centre.y)).end();
    const std::string_view fs = feed_word(feed);
    const AxisWords w = axis_words(arc.end, {true, true, false});
    writer().add("C").add(w.x).add(w.y).add(w.z)
        .add(arc.direction == ArcDirection::ccw ? "DR+" : "DR-").add(fs).end();
}

std::optional<std::string> HeidenhainPost::canned_limit(const DrillCycle& c, const DrillingCycleSpec&) const {
    if (c.values.degression_type() == DegressionType::factor)
        return "its Q212 takes a decrement value, not a factor";
    if (c.kind == CycleKind::chip_break && peck_depths(c).size() > heidenhain::max_breaks + 1)
        return fmt::format("more than {} chip breaks (Q213) in one hole", heidenhain::max_breaks);
    return std::nullopt;
}

void HeidenhainPost::on_drilling_header(const DrillCycle& c, const DrillingCycleSpec&) {
    auto [title, params] = heidenhain_cycle(c, machine());
    writer().add(title + " ~").end();
    for (size_t i = 0; i < params.size(); ++i)
        writer().raw(fmt::format("  Q{}={} ;{}{}", params[i].q, params[i].value, params[i].comment,
                                 i + 1 < params.size() ? " ~" : ""));
}

void HeidenhainPost::on_drilling_point(const DrillCycle&, const DrillingCycleSpec&, Vec2 at, bool) {
    // M99 calls the cycle at this position; both coordinates every time.
    const AxisWords w = force_xy(at);
    writer().add("L").add(w.x).add(w.y).add("R0 FMAX M99").end();
}

void HeidenhainPost::on_drilling_footer(const DrillCycle&, const DrillingCycleSpec&) {}

std::string heidenhain_length_offset(const Machine&, int tool) { return tool > 0 ? fmt::format("TOOL CALL {}", tool) : ""; }

std::optional<MachineProblem> check_heidenhain_machine(const Machine& machine) {
    // A TNC numbers its blocks 0, 1, 2, ... and its reader checks each number.
    const nc::BlockStyle& b = machine.block;
    if (!b.sequence_numbers || b.sequence_start != 0 || b.sequence_increment != 1 || !b.sequence_prefix.empty()) {
        const char* key = !b.sequence_numbers        ? "showSequenceNumbers"
                          : b.sequence_start != 0     ? "sequenceNumberStart"
                          : b.sequence_increment != 1 ? "sequenceNumberIncrement"
                                                      : "sequenceNumberPrefix";
        return MachineProblem{{fmt::format("/globals/{}", key)},
                              "a Heidenhain program numbers every block 0, 1, 2, ... without a letter (the TNC "
                              "reads the number as the block's): keep showSequenceNumbers true, "
                              "sequenceNumberStart 0, sequenceNumberIncrement 1 and sequenceNumberPrefix \"\""};
    }
    if (machine.block.separator.empty())
        return MachineProblem{{"/globals/variableDelimeter"},
                              "Heidenhain's blocks are words apart (0 BEGIN PGM, L X+10 R0 FMAX): without a separator "
                              "they run together; give variableDelimeter a space"};
    if (!machine.frame.start_block.empty())
        return MachineProblem{{"/frame/startBlock"},
                              "a Heidenhain conversational program has no safe-start block of G words: camgen would "
                              "not write it; leave startBlock empty"};
    return xy_arcs_only_problem(machine, "CC X Y, then C X Y DR+/DR-");
}

}  // namespace camgen
