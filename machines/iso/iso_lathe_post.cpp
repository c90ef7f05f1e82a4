// The ISO lathe dialect: the ISO post in the XZ plane; canned drilling on the spindle axis
// under G17 (LinuxCNC) or in Fanuc T's G74; T0101 turret calls; G50 S / G97 S spindle.
#include "machines/iso/iso_lathe_post.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/geometry/lathe_cycle.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"

namespace camgen {

IsoLathePost::IsoLathePost(const Machine& machine, std::ostream& out, PostOptions options)
    : IsoPost(machine, out, std::move(options)), lathe_(settings_of<iso::LatheSettings>(this->machine())) {}

std::string iso_lathe_length_offset(const Machine& machine, int tool) {
    // The turret call selects the tool's own offset, which holds its length (on_tool_change).
    if (settings_of<iso::LatheSettings>(machine).tool_call == iso::LatheToolCall::turret)
        return tool > 0 ? fmt::format("T{:02}{:02}", tool, tool) : std::string();
    return iso_length_offset(machine, tool);
}

void IsoLathePost::on_open() {
    IsoPost::on_open();
    const auto& b = machine().frame.start_block;
    if (std::find(b.begin(), b.end(), "G18") != b.end()) assume_plane(18);
}

void IsoLathePost::on_tool_change(const ToolChange& tool) {
    if (lathe_.tool_call == iso::LatheToolCall::m6) {
        IsoPost::on_tool_change(tool);
        return;
    }
    // A turret: T<tool><offset>, the tool's own offset number; the offset holds its length.
    if (tool.number > 99) fail("", fmt::format("tool {}: a turret call T0101 takes tools 1 to 99", tool.number));
    if (!tool.description.empty()) writer().comment(fmt::format("T{} {}", tool.number, tool.description));
    writer().add(fmt::format("T{:02}{:02}", tool.number, tool.number)).end();
    length_offset_pending_ = false;
}

void IsoLathePost::on_compensation(const Compensation& c) {
    if (c.side != CompensationSide::off) {
        const char* code = c.side == CompensationSide::left ? "G41" : "G42";
        if (lathe_.tool_call == iso::LatheToolCall::turret)
            // Fanuc's own tip number (LinuxCNC's mirrored in X), and the direction in words.
            writer().comment(fmt::format("{} nose comp: offset {:02} R{} nose radius, Fanuc tip T{}: {}", code,
                                         current_tool(), number_text(c.radius), fanuc_tip_number(c.orientation),
                                         lathe_tip_words(c.orientation)));
        else
            writer().comment(fmt::format("{} nose comp: tool table T{} D{} nose diameter, Q{} {}", code, current_tool(),
                                         number_text(2 * c.radius), c.orientation, lathe_tip_words(c.orientation)));
    }
    IsoPost::on_compensation(c);
}

// G41/G42 without D: the control takes the tool's own entry (LinuxCNC's tool table, Fanuc T's
// offset of T0101).
std::string IsoLathePost::compensation_words(const Compensation& c) const {
    return g(c.side == CompensationSide::off ? 40 : c.side == CompensationSide::left ? 41 : 42);
}

void IsoLathePost::on_spindle(const Spindle& s) {
    if (s.state == SpindleState::off) {
        IsoPost::on_spindle(s);
        return;
    }
    const std::string on = m(s.state == SpindleState::cw ? 3 : 4);
    if (s.surface_speed > 0) {
        // Constant surface speed: S in m/min (ft/min in inch), the spindle held to its limit.
        const std::string limit = speed_text(s.rpm);
        const double vc = machine().units == Units::inch ? s.surface_speed / 0.3048 : s.surface_speed;
        if (rpm_format().is_zero(vc))
            fail("", fmt::format("surface speed {} m/min would be written as S0 on machine {}", number_text(s.surface_speed),
                                 machine().name));
        if (lathe_.spindle_limit) {
            // Fanuc T: G50 S clamps the speed G96 computes.
            if (limit_written_ != s.rpm) writer().add(g(iso::spindle_limit_code)).add("S" + limit).end();
            limit_written_ = s.rpm;
            writer().add(g(iso::surface_speed_code)).add(rpm_format().word("S", vc)).add(on).end();
        } else {
            writer().add(g(iso::surface_speed_code)).add("D" + limit).add(rpm_format().word("S", vc)).add(on).end();
        }
        surface_mode_ = true;
        return;
    }
    if (!lathe_.spindle_limit) {
        // LinuxCNC: after a G96, a bare S would be a surface speed.
        if (surface_mode_) writer().add(g(iso::constant_rpm_code)).add(speed_word(s.rpm)).add(on).end();
        else IsoPost::on_spindle(s);
        surface_mode_ = false;
        return;
    }
    // Fanuc T: the speed limit first (it also caps constant surface speed), then the speed in
    // rpm; a limit a G96 left below this speed is raised to the machine's again.
    if (limit_written_ == 0 || s.rpm > limit_written_) {
        writer().add(g(iso::spindle_limit_code)).add(rpm_format().word("S", machine().limits.max_rpm)).end();
        limit_written_ = machine().limits.max_rpm;
    }
    writer().add(g(iso::constant_rpm_code)).add(speed_word(s.rpm)).add(on).end();
    surface_mode_ = false;
}

std::optional<std::string> IsoLathePost::canned_limit(const DrillCycle& c, const DrillingCycleSpec& spec) const {
    // LinuxCNC's G83 and G73 (and Fanuc's G83) come back or back off by the control's own
    // clearance: a job's other value cannot be written.
    const double fixed = machine().peck_clearance;
    auto differs = [&](DrillField f) {
        auto v = c.values.get(f);
        return v && std::abs(*v - fixed) > 1e-9;
    };
    if (c.kind == CycleKind::deep && differs(DrillField::peck_clearance))
        return fmt::format("its peck clearance is the control's, {} mm", number_text(fixed));
    if (c.kind == CycleKind::chip_break && spec.style != CannedStyle::fanuc_g74 && differs(DrillField::pecking_retract))
        return fmt::format("its back-off is the control's, {} mm", number_text(fixed));
    return std::nullopt;
}

void IsoLathePost::on_drilling_header(const DrillCycle& c, const DrillingCycleSpec& spec) {
    IsoPost::on_drilling_header(c, spec);
    // Under G18 a canned cycle drills along Y (LinuxCNC): the axial hole needs G17.
    if (lathe_.drilling_plane && spec.style != CannedStyle::fanuc_g74) writer().add(g(17)).end();
}

void IsoLathePost::on_drilling_point(const DrillCycle& c, const DrillingCycleSpec& spec, Vec2 at, bool first) {
    if (spec.style != CannedStyle::fanuc_g74) {
        IsoPost::on_drilling_point(c, spec, at, first);
        return;
    }
    // G74: from the start point (X0 at the feed-start Z) peck Q, back off R(e), on to Z; the
    // control then returns to the start point. Q is unsigned, in least input increments.
    on_rapid({at.x, at.y, position().z});
    on_rapid({at.x, at.y, c.safe_z});
    const DrillValues& p = c.values;
    const double back_off = p.get(DrillField::pecking_retract).value_or(machine().peck_clearance);
    writer().add(g(iso::face_peck_code)).add(xyz_format().word("R", back_off)).end();
    nc::FormatSpec q = xyz_format().spec();
    q.scale *= std::pow(10.0, q.decimals);
    q.decimals = 0;
    q.force_decimal = false;
    writer().add(g(iso::face_peck_code)).add(force_z(c.bottom_z)).add(nc::Format(q).word("Q", *p.get(DrillField::first_depth)))
        .add(feed_word(c.feed)).end();
    assume_z(c.safe_z);
    forget_motion();
    on_rapid({at.x, at.y, c.retract_z});
}

void IsoLathePost::on_thread_feed(const Vec3& from, const ThreadFeed& t) {
    if (std::abs(t.to.y - from.y) > 1e-9) fail("", "a thread-cutting move that leaves the XZ plane");
    const double dx = std::abs(t.to.x - from.x), dz = std::abs(t.to.z - from.z);
    // A taper (a chamfered runout's pull-out): at most 45 degrees from Z, where Fanuc's G32 F is
    // the lead along Z, the longer axis; LinuxCNC's G33 K follows the path (K = lead x path / Z).
    if (dx > 1e-9 && !(dz > 0 && dx <= dz + 0.001))
        fail("", "a thread-cutting move steeper than 45 degrees from Z: camgen writes a taper's lead along Z only");
    const bool g32 = lathe_.thread_move == iso::LatheThreadMove::g32_f;
    const double along = g32 || dx <= 1e-9 ? t.lead : t.lead * std::hypot(dx, dz) / dz;
    const std::string lead = lead_word(g32 ? "F" : "K", along);
    writer().add(g(g32 ? iso::thread_g32_code : iso::thread_g33_code));
    if (dx > 1e-9) writer().add(force_xy({t.to.x, t.to.y}).x);
    writer().add(force_z(t.to.z)).add(lead).end();
    // The synchronised move is not a mode the next feed move continues, and G32's F was the
    // lead, not a feed: the next move writes its motion word and its feed.
    forget_motion();
    if (g32) forget_feed();
}

IsoLathePost::G76Words IsoLathePost::g76_words(const ThreadCycle& c) const {
    G76Words w;
    // The control reads back what the text says: each value through its format, rounded.
    auto put = [&](const nc::Format& f, std::string_view letter, double v) {
        w.text.push_back(f.word(letter, v));
        return f.rounded(v);
    };
    const nc::Format x = machine().format("x");  // I, J, K are diameters under G7, as X
    const nc::Format z = machine().format("z");
    const nc::Format p = machine().format("feedPerRev");
    w.read.drive_x = x.rounded(c.start.x);
    w.read.drive_y = c.start.y;
    w.read.drive_z = z.rounded(c.start.z);
    w.read.p = put(p, "P", c.lead);
    w.read.z = put(z, "Z", c.end_z);
    w.read.i = put(x, "I", c.crest_x - c.start.x);
    // Equal steps (R1): the control cuts J, 2J, ... while below K, then K; a J rounded down
    // would leave a sliver of a pass before K, so the step is the least written value that
    // gives the cycle's count of passes.
    double j = c.first_depth;
    if (c.degression == 1.0) {
        const std::size_t cutting = c.depths.size() - static_cast<std::size_t>(std::max(c.spring_passes, 0));
        iso::LinuxcncG76 probe;
        probe.k = x.rounded(c.depth);
        probe.r = 1.0;
        for (int step = 0; step <= 40; ++step) {
            probe.j = x.rounded(c.first_depth + step * 1e-5);
            if (probe.j < c.first_depth - 1e-9) continue;
            if (iso::linuxcnc_g76_depths(probe).size() == cutting) {
                j = probe.j;
                break;
            }
        }
    }
    w.read.j = put(x, "J", j);
    w.read.k = put(x, "K", c.depth);
    w.read.r = c.degression;
    w.text.push_back(fmt::format("R{}", number_text(c.degression)));
    if (c.infeed_angle > 0) {
        w.read.q = std::round(c.infeed_angle * 1e4) / 1e4;
        w.text.push_back(fmt::format("Q{}", number_text(w.read.q, 4)));
    }
    w.read.h = c.spring_passes;
    if (c.spring_passes > 0) w.text.push_back(fmt::format("H{}", c.spring_passes));
    if (c.runout > 0) {
        // The exit taper: E along the drive line (Z, not a diameter), L2 the exit alone.
        w.read.e = put(z, "E", c.runout);
        w.read.l = 2;
        w.text.push_back("L2");
    }
    return w;
}

IsoLathePost::FanucG76Words IsoLathePost::fanuc_g76_words(const ThreadCycle& c) const {
    FanucG76Words w;
    const nc::Format x = machine().format("x");  // the last pass's diameter
    const nc::Format z = machine().format("z");
    const nc::Format lead = machine().format("feedPerRev");
    // P and Q: radial, in least input increments (the length format's last decimal), no point.
    nc::FormatSpec inc_spec = z.spec();
    inc_spec.scale *= std::pow(10.0, inc_spec.decimals);
    inc_spec.decimals = 0;
    inc_spec.force_decimal = false;
    const nc::Format inc(inc_spec);
    // The tool angle a: the flank infeed at a/2, one of the control's angles.
    const double a = 2.0 * c.infeed_angle;
    const int* angle = std::find_if(std::begin(iso::fanuc_g76_tool_angles), std::end(iso::fanuc_g76_tool_angles),
                                    [&](int v) { return std::abs(v - a) < 1e-6; });
    if (angle == std::end(iso::fanuc_g76_tool_angles)) {
        w.refusal = fmt::format("its tool angle a (twice the infeedAngle, {} degrees) is not one of 80, 60, 55, 30, 29, 0",
                                number_text(a, 4));
        return w;
    }
    const std::size_t cutting = c.depths.size() - static_cast<std::size_t>(std::max(c.spring_passes, 0));
    iso::FanucG76& g = w.read;
    g.start_x = x.rounded(c.start.x);
    g.start_y = c.start.y;
    g.start_z = z.rounded(c.start.z);
    g.angle = *angle;
    const double out = c.start.x >= c.crest_x ? 1.0 : -1.0;
    g.k = inc.rounded(c.depth);
    g.x = x.rounded(c.crest_x - out * c.depth);
    g.z = z.rounded(c.end_z);
    g.lead = lead.rounded(c.lead);
    // The finishing passes: the spring passes at the full height after a roughing that ends
    // there (d = 0); without a spring pass, the last cutting pass is the one finishing pass and
    // the roughing ends at the one before it (d = k - that depth).
    if (c.spring_passes > 0) {
        g.m = c.spring_passes;
        g.finish = 0.0;
    } else if (cutting >= 2) {
        // (d rounded: the roughing must end at the pass before the last, not one pass later or
        // earlier: the written d nearest to the depths, of three; the check below decides)
        g.m = 1;
        g.finish = z.rounded(c.depth - c.depths[cutting - 2]);
    } else {
        w.refusal = "it cuts one pass and no spring pass, and G76 cuts at least one finishing pass after its roughing";
        return w;
    }
    if (g.m > 99) {
        w.refusal = "G76 cuts at most 99 finishing passes";
        return w;
    }
    if (c.degression == 1.0) {
        // Equal steps: a least depth of the step makes sqrt's steps the step (first x n while
        // first x sqrt(n) is less); a step rounded down would leave a sliver of a pass before the
        // end, so the least increment up.
        g.first = inc.rounded(c.first_depth);
        if (g.first < c.first_depth - 1e-9) g.first = inc.rounded(g.first + 1.0 / inc_spec.scale);
        g.least = g.first;
    } else {
        g.first = inc.rounded(c.first_depth);
        g.least = inc.rounded(c.min_depth);
    }
    if (!(g.first > 0)) {
        w.refusal = "its first depth rounds to 0";
        return w;
    }
    if (c.spring_passes == 0) {
        const double written = g.finish, step = 1.0 / z.spec().scale / std::pow(10.0, z.spec().decimals);
        auto fits = [&](double finish) {
            iso::FanucG76 probe = g;
            probe.finish = finish;
            const std::vector<double> d = iso::fanuc_g76_depths(probe);
            if (d.size() != c.depths.size()) return false;
            for (std::size_t n = 0; n < d.size(); ++n)
                if (std::abs(d[n] - c.depths[n]) > 0.001) return false;
            return true;
        };
        for (double f : {written, written + step, written - step})
            if (f >= 0 && fits(f)) {
                g.finish = z.rounded(f);
                break;
            }
    }
    w.first.push_back(fmt::format("P{:02}{:02}{:02}", g.m, 0, g.angle));
    w.first.push_back(inc.word("Q", g.least));
    w.first.push_back(z.word("R", g.finish));
    w.second.push_back(x.word("X", c.crest_x - out * c.depth));
    w.second.push_back(z.word("Z", c.end_z));
    w.second.push_back(inc.word("P", c.depth));
    w.second.push_back(inc.word("Q", g.first));
    return w;
}

std::optional<std::string> IsoLathePost::thread_cycle_limit(const ThreadCycle& c, const ThreadingCycleSpec& spec) const {
    // G76 cuts every pass by its own depth rule from the rounded words: the moves it makes must
    // be the cycle's within 0.001 mm.
    std::vector<Event> control;
    if (spec.style == ThreadCycleStyle::fanuc_g76) {
        const FanucG76Words w = fanuc_g76_words(c);
        if (!w.refusal.empty()) return w.refusal;
        control = iso::fanuc_g76_moves(w.read);
    } else if (spec.style == ThreadCycleStyle::linuxcnc_g76) {
        if (c.min_depth > 0) return std::string("it takes no least depth of cut");
        control = iso::linuxcnc_g76_moves(g76_words(c).read);
    } else {
        return IsoPost::thread_cycle_limit(c, spec);
    }
    const std::vector<Event> wanted = thread_cycle_moves(c, machine().thread_pattern());
    // (moves a pass: Fanuc's five, four under a radial infeed; LinuxCNC's four, five with a runout)
    const std::size_t per_pass = c.depths.empty() ? 1 : std::max<std::size_t>(1, wanted.size() / c.depths.size());
    if (control.size() != wanted.size())
        return fmt::format("its rounded words make {} passes, not {}", control.size() / per_pass, wanted.size() / per_pass);
    auto at = [](const Event& e) {
        if (const auto* r = std::get_if<Rapid>(&e)) return r->to;
        return std::get<ThreadFeed>(e).to;
    };
    for (size_t n = 0; n < control.size(); ++n) {
        const Vec3 a = at(control[n]), b = at(wanted[n]);
        const double off = std::hypot(a.x - b.x, a.y - b.y, a.z - b.z);
        if (off > 0.001)
            return fmt::format("its pass {} would run {} mm from camgen's", n / per_pass + 1, number_text(off, 4));
    }
    return std::nullopt;
}

void IsoLathePost::on_thread_cycle(const ThreadCycle& c, const ThreadingCycleSpec& spec) {
    if (spec.style == ThreadCycleStyle::fanuc_g76) {
        const FanucG76Words w = fanuc_g76_words(c);
        if (!w.refusal.empty()) throw std::logic_error("a Fanuc G76 written that cannot be: " + w.refusal);
        const std::string lead = lead_word("F", c.lead);  // the checks of a synchronised move: spindle on, within maxFeed
        writer().add(spec.name);
        for (const std::string& t : w.first) writer().add(t);
        writer().end();
        writer().add(spec.name);
        for (const std::string& t : w.second) writer().add(t);
        writer().add(lead).end();
        // The cycle ends at its start point, in no motion mode camgen writes; its F was the lead.
        forget_motion();
        forget_feed();
        return;
    }
    if (spec.style != ThreadCycleStyle::linuxcnc_g76) IsoPost::on_thread_cycle(c, spec);
    const G76Words w = g76_words(c);
    (void)lead_word("P", c.lead);  // the checks of a synchronised move: spindle on, within maxFeed
    writer().add(spec.name);
    for (const std::string& t : w.text) writer().add(t);
    writer().end();
    // G76 leaves the tool at the drive X and the end Z, in no motion mode camgen writes.
    assume_z(c.end_z);
    forget_motion();
}

void IsoLathePost::profile_blocks(const Profile& profile, std::vector<std::string>& lines, Profile& read) const {
    const nc::Format x = machine().format("x");  // diameters
    const nc::Format z = machine().format("z");
    const nc::Format& len = xyz_format();       // I, K: radial mm
    auto point = [&](Vec2 p) { return Vec2{z.rounded(p.x), x.rounded(p.y)}; };
    Vec2 at = read.start;
    for (const ProfileSegment& s : profile.segments) {
        const Vec2 end = point(s.end);
        if (!s.centre) {
            lines.push_back(fmt::format("{} {} {}", g(1), x.word("X", s.end.y), z.word("Z", s.end.x)));
            read.segments.push_back({end, std::nullopt, ArcDirection::ccw});
        } else {
            const double i = len.rounded(s.centre->y - at.y), k = len.rounded(s.centre->x - at.x);
            lines.push_back(fmt::format("{} {} {} {} {}", g(s.direction == ArcDirection::ccw ? 3 : 2), x.word("X", s.end.y),
                                        z.word("Z", s.end.x), len.word("I", s.centre->y - at.y), len.word("K", s.centre->x - at.x)));
            read.segments.push_back({end, Vec2{at.x + k, at.y + i}, s.direction});
        }
        at = end;
    }
}

IsoLathePost::FanucG71Words IsoLathePost::fanuc_g71_words(const TurnCycle& c) const {
    FanucG71Words w;
    const nc::Format x = machine().format("x");
    const nc::Format z = machine().format("z");
    const nc::Format& len = xyz_format();  // U/W(depth) and R(retract) of the first block: radial mm, mm along Z
    const LatheCycleAxis axis = c.along_x ? LatheCycleAxis::x : LatheCycleAxis::z;
    const Vec2 a = fanuc_g71_start(c);
    // Linked to a G70: the finishing pass's tip path, the allowances in U and W; else the boundary, U0 W0.
    const Profile shape = fanuc_g7x_shape(axis, a, c.finish ? c.finish->shape : c.profile);
    const Vec2 allowance = c.finish ? c.finish->allowance : Vec2{0.0, 0.0};
    w.allowance = Vec2{z.rounded(allowance.x), x.rounded(allowance.y)};
    w.u_allow = x.word("U", allowance.y);
    w.w_allow = z.word("W", allowance.x);
    w.start = Vec2{z.rounded(a.x), x.rounded(a.y)};
    w.read.plane = ProfilePlane::xz;
    if (axis == LatheCycleAxis::z) {
        // G71: up to A along X; ns along X only from A (type I), at rapid: the control moves to
        // each level so.
        w.a_word = x.word("X", a.y);
        w.read.start = Vec2{w.start.x, x.rounded(shape.start.y)};
        w.shape.push_back(fmt::format("{} {}", g(0), x.word("X", shape.start.y)));
        w.u = len.word("U", c.depth);
    } else {
        // G72: the same along Z.
        w.a_word = z.word("Z", a.x);
        w.read.start = Vec2{z.rounded(shape.start.x), w.start.y};
        w.shape.push_back(fmt::format("{} {}", g(0), z.word("Z", shape.start.x)));
        w.u = len.word("W", c.depth);
    }
    profile_blocks(shape, w.shape, w.read);
    w.depth = len.rounded(c.depth);
    w.retract = len.rounded(c.retract);
    w.r = len.word("R", c.retract);
    return w;
}

namespace {
// Why a control's moves (from the rounded words) are not camgen's within 0.001 mm, if they are not.
std::optional<std::string> lathe_cycle_moves_differ(const std::vector<LatheCycleMove>& control,
                                                    const std::vector<LatheCycleMove>& camgen) {
    if (control.size() != camgen.size())
        return fmt::format("its rounded words make {} moves, not {}", control.size(), camgen.size());
    for (std::size_t n = 0; n < camgen.size(); ++n) {
        const LatheCycleMove& a = control[n];
        const LatheCycleMove& b = camgen[n];
        double off = distance(a.end, b.end);
        if (a.kind == LatheCycleMove::Kind::arc) off = std::max(off, distance(a.centre, b.centre));
        if (a.kind != b.kind || off > 0.001)
            return fmt::format("its move {} would run {} mm from camgen's", n + 1, number_text(off, 4));
    }
    return std::nullopt;
}
}  // namespace

std::optional<std::string> IsoLathePost::fanuc_g71_limit(const TurnCycle& c) const {
    const LatheCycleAxis axis = c.along_x ? LatheCycleAxis::x : LatheCycleAxis::z;
    const Vec2 a = fanuc_g71_start(c);
    // camgen's moves in Fanuc's pattern (linked to a G70: the finishing shape moved by the allowances).
    const LatheCycleModel own =
        c.finish ? fanuc_g7x(axis, a, fanuc_g7x_shape(axis, a, c.finish->shape), c.depth, c.retract, c.finish->allowance)
                 : fanuc_g7x(axis, a, fanuc_g7x_shape(axis, a, c.profile), c.depth, c.retract);
    if (own.refusal) return *own.refusal;
    const FanucG71Words w = fanuc_g71_words(c);
    const LatheCycleModel control = fanuc_g7x(axis, w.start, w.read, w.depth, w.retract, w.allowance);
    if (control.refusal) return "from its rounded words: " + *control.refusal;
    return lathe_cycle_moves_differ(control.moves, own.moves);
}

void IsoLathePost::write_fanuc_g71(const TurnCycle& c, const RoughingCycleSpec& spec) {
    const FanucG71Words w = fanuc_g71_words(c);
    // Up to A (the event's start is A's Z, one depth of cut lower; along X: A's X, one depth of
    // cut towards -Z), then the two blocks, then the finishing shape ns..nf, which the control
    // skips after the cycle. With U0 W0 the shape is the rough's own boundary; where a turn-profile
    // is linked to it (link_fanuc_finishing), the finishing pass's tip path with U W, finished by
    // G70 (on_finish_cycle).
    writer().add(g(0)).add(w.a_word).end();
    writer().add(spec.name).add(w.u).add(w.r).end();
    const nc::BlockStyle& style = writer().style();
    const long count = static_cast<long>(w.shape.size());
    long ns = 0, step = 1;
    if (style.sequence_numbers) {
        // The program's own numbers: the shape's blocks follow the cycle's second block.
        step = style.sequence_increment;
        ns = writer().next_sequence() + step;
    } else {
        ns = next_shape_number_;
        next_shape_number_ += count;
    }
    const long nf = ns + (count - 1) * step;
    if (nf > 99999) throw InputError(c.path, fmt::format("the finishing shape's sequence numbers reach N{}, above N99999", nf));
    writer().add(spec.name).add(fmt::format("P{}", ns)).add(fmt::format("Q{}", nf)).add(w.u_allow).add(w.w_allow)
        .add(feed_word(c.feed)).end();
    // Linked to a G70: the finishing feed in the shape's first feed block (G70 takes the F of
    // blocks ns..nf, G71 its own block's).
    const std::string finish_feed = c.finish ? " " + feed_text(c.finish->feed, c.finish->rpm) : std::string();
    for (long k = 0; k < count; ++k) {
        if (!style.sequence_numbers) writer().add(fmt::format("N{}", ns + k));
        writer().add(w.shape[static_cast<std::size_t>(k)] + (k == 1 ? finish_feed : std::string())).end();
    }
    if (c.finish) linked_ = LinkedShape{c.finish->path, ns, nf};
    else linked_.reset();
    // The control returns to A, in no motion mode camgen writes (and an F in the shape, skipped
    // by G71, is not relied on either way).
    reset_modal_axes();
    forget_motion();
    forget_feed();
}

std::optional<std::string> IsoLathePost::finish_cycle_limit(const FinishCycle& c) const {
    if (!linked_ || linked_->finishing_path != c.path)
        return fmt::format("the turn-rough before it ({}) was not written as the roughing cycle whose shape G70 runs",
                           c.rough_path);
    return std::nullopt;
}

void IsoLathePost::on_finish_cycle(const FinishCycle&) {
    // From A, where the tool stands: the shape ns..nf at its own F, back to A.
    writer().add("G70").add(fmt::format("P{}", linked_->ns)).add(fmt::format("Q{}", linked_->nf)).end();
    linked_.reset();
    // The control returns to A, in no motion mode and at no feed camgen writes.
    reset_modal_axes();
    forget_motion();
    forget_feed();
}

IsoLathePost::G71Words IsoLathePost::g71_words(const TurnCycle& c) const {
    G71Words w;
    const nc::Format x = machine().format("x");  // diameters under G7
    const nc::Format z = machine().format("z");
    const nc::Format& len = xyz_format();       // I, K of the arcs, I and R of G71: radial mm
    auto point = [&](Vec2 p) { return Vec2{z.rounded(p.x), x.rounded(p.y)}; };
    w.start = point(Vec2{c.start.z, c.start.x});
    w.profile.plane = ProfilePlane::xz;
    w.profile.start = point(c.profile.start);
    w.sub.push_back(fmt::format("{} {} {}", g(1), x.word("X", c.profile.start.y), z.word("Z", c.profile.start.x)));
    profile_blocks(c.profile, w.sub, w.profile);
    w.depth = len.rounded(c.depth);
    w.retract = len.rounded(c.retract);
    w.i = len.word("I", c.depth);
    w.r = len.word("R", c.retract);
    return w;
}

std::optional<std::string> IsoLathePost::turn_cycle_limit(const TurnCycle& c, const RoughingCycleSpec& spec) const {
    if (spec.style == RoughingCycleStyle::fanuc_g71 || spec.style == RoughingCycleStyle::fanuc_g72) return fanuc_g71_limit(c);
    if (spec.style != RoughingCycleStyle::linuxcnc) return IsoPost::turn_cycle_limit(c, spec);
    const G71Words w = g71_words(c);
    const LatheCycleModel control =
        linuxcnc_g7x(c.along_x ? LatheCycleAxis::x : LatheCycleAxis::z, w.start, w.profile, w.depth, w.retract);
    if (control.refusal) return "from its rounded words: " + *control.refusal;
    return lathe_cycle_moves_differ(control.moves, c.moves);
}

void IsoLathePost::on_turn_cycle(const TurnCycle& c, const RoughingCycleSpec& spec) {
    if (spec.style == RoughingCycleStyle::fanuc_g71 || spec.style == RoughingCycleStyle::fanuc_g72) {
        write_fanuc_g71(c, spec);
        return;
    }
    if (spec.style != RoughingCycleStyle::linuxcnc) IsoPost::on_turn_cycle(c, spec);
    const G71Words w = g71_words(c);
    const int n = next_sub_++;
    // The profile: defined where it is used, before the cycle (the control skips a definition).
    writer().add(fmt::format("o{}", n)).add("sub").end();
    for (const std::string& line : w.sub) writer().add(line).end();
    writer().add(fmt::format("o{}", n)).add("endsub").end();
    writer().add(spec.name).add(fmt::format("Q{}", n)).add("D0").add(w.i).add(w.r).add(feed_word(c.feed)).end();
    // The control leaves the tool where its last pass ends, in no motion mode camgen writes.
    reset_modal_axes();
    forget_motion();
}

IsoLathePost::GrooveWords IsoLathePost::groove_words(const GrooveCycle& c) const {
    // G75 (external and internal grooves) plunges along X and steps along Z; G74 (face grooves)
    // plunges along Z and steps along X: the same words with the axes' roles swapped.
    GrooveWords w;
    const bool along_z = c.side == GrooveSide::face;
    const nc::Format x = machine().format("x");
    const nc::Format z = machine().format("z");
    // P and Q: unsigned, in least input increments without a decimal point (as G74's Q), radial.
    nc::FormatSpec inc = xyz_format().spec();
    inc.scale *= std::pow(10.0, inc.decimals);
    inc.decimals = 0;
    inc.force_decimal = false;
    const nc::Format pq(inc);
    const Vec3 start = c.start();
    const Vec3 last = c.at(c.bottom + c.into() * c.finish, c.last_z);
    w.read.along_z = along_z;
    w.read.start_x = x.rounded(start.x);
    w.read.start_y = start.y;
    w.read.start_z = z.rounded(start.z);
    w.back_off = xyz_format().word("R", c.retract);
    w.read.e = xyz_format().rounded(c.retract);
    w.text.push_back(x.word("X", last.x));
    w.read.x = x.rounded(last.x);
    w.text.push_back(z.word("Z", last.z));
    w.read.z = z.rounded(last.z);
    // The plunge's length as written: a peck at or beyond it is one peck, written as the least
    // value at or beyond the plunge (the control refuses a peck longer than the plunge).
    const double plunge = along_z ? std::abs(w.read.start_z - w.read.z) : std::abs(w.read.start_x - w.read.x);
    const double whole = std::ceil(plunge * inc.scale - 1e-6) / inc.scale;
    const double peck = c.peck > 0 && c.peck < whole ? c.peck : whole;
    w.read.peck = pq.rounded(peck);
    const std::string peck_word = pq.word(along_z ? "Q" : "P", peck);
    std::string step_word;
    if (c.plunges().size() > 1) {
        // A step beyond the travel (the spacing rounded up to a whole µm) is written as the
        // travel: the same plunges, and the control refuses a longer one.
        const double travel = along_z ? std::abs(w.read.start_x - w.read.x) : std::abs(w.read.start_z - w.read.z);
        const double step = std::min(c.z_step, std::ceil(travel * inc.scale - 1e-6) / inc.scale);
        step_word = pq.word(along_z ? "P" : "Q", step);
        w.read.step = pq.rounded(step);
    }
    // In the order of the manual's format: X Z P Q.
    if (along_z) {
        if (!step_word.empty()) w.text.push_back(step_word);
        w.text.push_back(peck_word);
    } else {
        w.text.push_back(peck_word);
        if (!step_word.empty()) w.text.push_back(step_word);
    }
    w.read.feed = c.feed;
    return w;
}

std::optional<std::string> IsoLathePost::groove_cycle_limit(const GrooveCycle& c, const GroovingCycleSpec& spec) const {
    // G75 and G74 make their plunges from the rounded words: they must be the cycle's within 0.001 mm.
    if (spec.style != GrooveCycleStyle::fanuc_g75 && spec.style != GrooveCycleStyle::fanuc_g74)
        return IsoPost::groove_cycle_limit(c, spec);
    const bool along_z = spec.style == GrooveCycleStyle::fanuc_g74;
    if (!c.plain())
        return fmt::format("{} plunges only, pecks counted from its start, back to its start at the end", spec.name);
    if ((c.side == GrooveSide::face) != along_z)
        return along_z ? fmt::format("{} plunges along Z, this groove along X", spec.name)
                       : fmt::format("{} plunges along X, a face groove along Z", spec.name);
    const GrooveWords w = groove_words(c);
    if (!(w.read.e > 0)) return std::string("its back-off R would be written as 0");
    // The control refuses a back-off longer than the peck.
    if (w.read.e > w.read.peck + 1e-9)
        return fmt::format("its back-off R {} is longer than its peck {}", number_text(w.read.e, 3), number_text(w.read.peck, 3));
    const std::vector<Event> control = iso::fanuc_groove_moves(w.read);
    const std::vector<Event> wanted = groove_cycle_moves(c);
    if (control.size() != wanted.size())
        return fmt::format("its rounded words make {} moves, not {}", control.size(), wanted.size());
    auto at = [](const Event& e) -> std::optional<Vec3> {
        if (const auto* r = std::get_if<Rapid>(&e)) return r->to;
        if (const auto* l = std::get_if<Linear>(&e)) return l->to;
        return std::nullopt;
    };
    for (size_t n = 0; n < control.size(); ++n) {
        const auto a = at(control[n]), b = at(wanted[n]);
        if (!a || !b || control[n].index() != wanted[n].index()) return fmt::format("its move {} is of another kind", n + 1);
        const double off = std::hypot(a->x - b->x, a->y - b->y, a->z - b->z);
        if (off > 0.001) return fmt::format("its move {} would end {} mm from camgen's", n + 1, number_text(off, 4));
    }
    return std::nullopt;
}

void IsoLathePost::on_groove_cycle(const GrooveCycle& c, const GroovingCycleSpec& spec) {
    if (spec.style != GrooveCycleStyle::fanuc_g75 && spec.style != GrooveCycleStyle::fanuc_g74) IsoPost::on_groove_cycle(c, spec);
    const GrooveWords w = groove_words(c);
    writer().add(spec.name).add(w.back_off).end();
    writer().add(spec.name);
    for (const std::string& t : w.text) writer().add(t);
    writer().add(feed_word(c.feed)).end();
    // The cycle returns the tool to its start point, in no motion mode camgen writes.
    reset_modal_axes();
}

bool IsoLathePost::writes_return_level() const {
    for (const auto& [mode, code] : machine().frame.feed_modes)
        if (code == "G98" || code == "G99") return false;
    return true;
}

void IsoLathePost::on_drilling_footer(const DrillCycle& c, const DrillingCycleSpec& spec) {
    IsoPost::on_drilling_footer(c, spec);
    if (lathe_.drilling_plane && spec.style != CannedStyle::fanuc_g74) writer().add(g(18)).end();
}

}  // namespace camgen
