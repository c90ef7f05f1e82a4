// What a lathe job designs (design_lathe.hpp): each turn-profile's kept profile and what its
// tool leaves, each turn-drill's bore.
#include "camgen/operations/design_lathe.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/operations/registry.hpp"

namespace camgen {

namespace {

// The chords of a profile's arcs in a tip path stay within this of the arcs, mm: far below any
// machine's tolerance, which the check adds.
constexpr double lathe_design_chord = 1e-4;
// The most chords of one arc.
constexpr int lathe_design_max_chords = 100'000;

const Tool* lathe_design_tool(const Job& job, int number) {
    const auto it = job.tools.find(number);
    return it == job.tools.end() ? nullptr : &it->second;
}

// An arc's start angle and signed sweep in (u, v) (counter-clockwise positive).
struct LatheDesignArc {
    Vec2 centre;
    double radius = 0.0, start = 0.0, sweep = 0.0;
};
LatheDesignArc lathe_design_arc(const Profile& p, std::size_t k) {
    const Vec2 a = segment_start(p, k);
    const ProfileSegment& s = p.segments[k];
    LatheDesignArc arc;
    arc.centre = *s.centre;
    arc.radius = distance(a, arc.centre);
    arc.start = std::atan2(a.y - arc.centre.y, a.x - arc.centre.x);
    arc.sweep = segment_sweep(p, k) * (s.direction == ArcDirection::ccw ? 1.0 : -1.0);
    return arc;
}

// Whether the angle lies on the arc's sweep.
bool lathe_design_on_arc(const LatheDesignArc& arc, double angle) {
    double d = arc.sweep >= 0 ? angle - arc.start : arc.start - angle;
    d = std::fmod(d, two_pi);
    if (d < 0) d += two_pi;
    return d <= std::abs(arc.sweep) + 1e-12;
}

// The least radius a tip moving from a to b clears at Z z ((u, v) = (Z, radius)), with a nose of
// radius n whose centre is n above the tip in both: where the tip is at or below z - n, the
// body clears down to the tip's radius; where it is between z - n and z, the nose's lower
// quarter reaches v + n - sqrt(n^2 - w^2), w = u + n - z, which is convex along the move: its
// least value is at an end of that stretch or where its derivative is 0.
double lathe_design_reach(Vec2 a, Vec2 b, double n, double z) {
    const double du = b.x - a.x, dv = b.y - a.y;
    double best = std::numeric_limits<double>::infinity();
    // The stretch of the move (t in [0, 1]) whose Z lies in [lo, hi].
    auto stretch = [&](double lo, double hi, double& t0, double& t1) {
        if (std::abs(du) < 1e-15) {
            t0 = 0, t1 = 1;
            return a.x >= lo && a.x <= hi;
        }
        double s0 = (lo - a.x) / du, s1 = (hi - a.x) / du;
        if (s0 > s1) std::swap(s0, s1);
        t0 = std::max(0.0, s0), t1 = std::min(1.0, s1);
        return t0 <= t1;
    };
    double t0 = 0, t1 = 0;
    if (stretch(-std::numeric_limits<double>::infinity(), z - n, t0, t1)) best = std::min(a.y + t0 * dv, a.y + t1 * dv);
    if (n > 0 && stretch(z - n, z, t0, t1)) {
        auto g = [&](double t) {
            const double w = a.x + t * du + n - z;
            return a.y + t * dv + n - std::sqrt(std::max(0.0, n * n - w * w));
        };
        best = std::min({best, g(t0), g(t1)});
        if (du * dv < 0) {
            const double w = n * std::abs(dv) / std::hypot(du, dv);
            const double t = (z - n + w - a.x) / du;
            if (t > t0 && t < t1) best = std::min(best, g(t));
        }
    }
    return best;
}

}  // namespace

std::optional<std::pair<double, double>> LatheTurnDesign::radius_range(double a, double b) const {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    auto take = [&](double v) { lo = std::min(lo, v), hi = std::max(hi, v); };
    auto in = [&](double u) { return u >= a && u <= b; };
    for (std::size_t k = 0; k < profile.segments.size(); ++k) {
        const Vec2 p = segment_start(profile, k), q = profile.segments[k].end;
        if (!profile.segments[k].centre) {
            const double du = q.x - p.x;
            if (std::abs(du) < 1e-15) {
                if (in(p.x)) take(p.y), take(q.y);
                continue;
            }
            const double s0 = std::max(0.0, std::min((a - p.x) / du, (b - p.x) / du));
            const double s1 = std::min(1.0, std::max((a - p.x) / du, (b - p.x) / du));
            if (s0 <= s1) take(p.y + s0 * (q.y - p.y)), take(p.y + s1 * (q.y - p.y));
            continue;
        }
        // An arc: its points in the window are sub-arcs that end at its ends or where it meets
        // Z a or b; on each, the radius is greatest or least at those ends or at its top or bottom.
        const LatheDesignArc arc = lathe_design_arc(profile, k);
        if (in(p.x)) take(p.y);
        if (in(q.x)) take(q.y);
        for (double u : {a, b}) {
            const double du = u - arc.centre.x;
            if (std::abs(du) > arc.radius) continue;
            const double dv = std::sqrt(arc.radius * arc.radius - du * du);
            for (double side : {1.0, -1.0})
                if (lathe_design_on_arc(arc, std::atan2(side * dv, du))) take(arc.centre.y + side * dv);
        }
        if (in(arc.centre.x))
            for (double side : {1.0, -1.0})
                if (lathe_design_on_arc(arc, side * pi / 2)) take(arc.centre.y + side * arc.radius);
    }
    if (lo > hi) return std::nullopt;
    return std::make_pair(lo, hi);
}

double LatheTurnDesign::left_radius(double z) const {
    double best = std::numeric_limits<double>::infinity();
    if (blade_hi > blade_lo) {
        // The stretch of each move whose point lies in [z - blade_hi, z - blade_lo]: its edge
        // covers z there; the radius is linear along it, least at an end of the stretch.
        const double lo = z - blade_hi, hi = z - blade_lo;
        for (const LatheTipMove& m : tip) {
            const double du = m.to.x - m.from.x, dv = m.to.y - m.from.y;
            double t0 = 0, t1 = 1;
            if (std::abs(du) < 1e-15) {
                if (m.from.x < lo || m.from.x > hi) continue;
            } else {
                double s0 = (lo - m.from.x) / du, s1 = (hi - m.from.x) / du;
                if (s0 > s1) std::swap(s0, s1);
                t0 = std::max(0.0, s0), t1 = std::min(1.0, s1);
                if (t0 > t1) continue;
            }
            best = std::min({best, m.from.y + t0 * dv, m.from.y + t1 * dv});
        }
        return best;
    }
    for (const LatheTipMove& m : tip) {
        if (std::min(m.from.x, m.to.x) > z) continue;  // all of it above z: it clears nothing there
        best = std::min(best, lathe_design_reach(m.from, m.to, nose, z));
    }
    return best;
}

std::vector<double> LatheTurnDesign::corners() const {
    std::vector<double> out;
    for (const ProfileSegment& s : profile.segments) out.push_back(s.end.x);
    return out;
}

void design_turn_drill(const TurnDrillOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked) {
    const Tool* tool = lathe_design_tool(job, op.tool);
    if (!tool) return unchecked.push_back(op.path + ": its tool is not in the job");
    if (tool->type == ToolType::turning_tool)
        return unchecked.push_back(op.path + ": its tool is a turning tool, which has no drill's bore");
    LatheHoleDesign hole;
    hole.path = op.path;
    hole.tool = tool->number;
    hole.top_z = op.cycle.reference_z;
    hole.bottom_z = op.cycle.bottom_z;
    hole.radius = tool->diameter / 2;
    // The point as the simulation sweeps it (simulation's tool_shape): drills, centre and spot
    // drills, chamfer mills and V-bits a cone of their tip angle (118 degrees for a drill, 90 for
    // the others where none is given) with a chamfer mill's or V-bit's flat; the rest flat.
    switch (tool->type) {
    case ToolType::drill:
    case ToolType::centre_drill:
    case ToolType::spot_drill:
    case ToolType::chamfer_mill:
    case ToolType::v_bit:
    case ToolType::engraver: {
        const double angle = tool->tip_angle.value_or(tool->type == ToolType::drill ? 118.0 : 90.0);
        if (is_pointed_cutter(tool->type))
            hole.flat = std::min(tool->tip_diameter / 2, hole.radius);
        hole.slope = 1.0 / std::tan(angle / 2 * rad_per_deg);
        break;
    }
    default: hole.flat = hole.radius; break;
    }
    design.holes.push_back(std::move(hole));
}

void design_turn_profile(const TurnProfileOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked) {
    const Tool* tool = lathe_design_tool(job, op.tool);
    if (!tool) return unchecked.push_back(op.path + ": its tool is not in the job");
    if (tool->type != ToolType::turning_tool)
        return unchecked.push_back(op.path + ": its tool is not a turning tool (the simulation sweeps other tools on the "
                                             "spindle's axis only)");
    LatheTurnDesign d;
    d.path = op.path;
    d.tool = tool->number;
    d.nose = tool->diameter / 2;  // as the simulation's tool_shape
    d.nose_compensated = op.compensation != NoseCompensation::none && op.nose_radius > 0;
    d.chord = lathe_design_chord;
    const double clearance = job.clearance;
    const Vec2 start = op.profile.start;
    // The kept profile: the approach (down along Z at the start's radius), then the profile.
    d.profile.plane = ProfilePlane::xz;
    d.profile.start = {clearance, start.y};
    d.profile.segments.push_back({start, std::nullopt, ArcDirection::ccw});
    for (const ProfileSegment& s : op.profile.segments) d.profile.segments.push_back(s);
    d.z_hi = clearance;
    // The tip's path as expand() makes it: the approach, the profile, the lift off its end, the
    // rapid out to retractX and the return along Z to the clearance.
    // The tip's path is the compensated one where camgen compensates the nose (tip_path).
    const Profile& tp = op.tip_path.segments.empty() ? op.profile : op.tip_path;
    d.tip.push_back({{clearance, tp.start.y}, tp.start, false});
    for (std::size_t k = 0; k < tp.segments.size(); ++k) {
        const Vec2 a = segment_start(tp, k);
        const ProfileSegment& s = tp.segments[k];
        if (!s.centre) {
            d.tip.push_back({a, s.end, false});
            continue;
        }
        const LatheDesignArc arc = lathe_design_arc(tp, k);
        const int n = std::min(lathe_design_max_chords,
                               std::max(1, segments_for_tolerance(arc.radius, std::abs(arc.sweep), lathe_design_chord)));
        Vec2 from = a;
        for (int i = 1; i <= n; ++i) {
            const Vec2 to = i == n ? s.end : arc.centre + unit_at(arc.start + arc.sweep * i / n) * arc.radius;
            d.tip.push_back({from, to, true});
            from = to;
        }
    }
    const Vec2 tip_end = tp.segments.back().end;
    // Under control compensation the G40 move lifts the tip from where the control left it.
    const bool control = op.compensation == NoseCompensation::control && !op.control_path.segments.empty();
    const Vec2 lifted = control ? op.control_exit : tip_end + op.lift_direction * op.lift;
    d.tip.push_back({tip_end, lifted, false});
    d.tip.push_back({lifted, {lifted.x, op.retract_x}, false});
    d.tip.push_back({{lifted.x, op.retract_x}, {clearance, op.retract_x}, false});
    // The lowest Z of the profile (an arc may reach below its ends).
    d.z_lo = start.x;
    for (std::size_t k = 0; k < op.profile.segments.size(); ++k) {
        d.z_lo = std::min(d.z_lo, op.profile.segments[k].end.x);
        if (!op.profile.segments[k].centre) continue;
        const LatheDesignArc arc = lathe_design_arc(op.profile, k);
        if (lathe_design_on_arc(arc, pi)) d.z_lo = std::min(d.z_lo, arc.centre.x - arc.radius);
    }
    design.profiles.push_back(std::move(d));
}

namespace {

// The tip's moves of an operation's expansion, arcs as chords within lathe_design_chord.
class LatheDesignTipRecorder : public EventSink {
public:
    LatheDesignTipRecorder(Vec2 from, std::vector<LatheTipMove>& out) : at_(from), out_(out) {}
    void emit(const Event& e) override {
        if (const auto* r = std::get_if<Rapid>(&e)) to({r->to.z, r->to.x});
        else if (const auto* l = std::get_if<Linear>(&e)) to({l->to.z, l->to.x});
        else if (const auto* a = std::get_if<Arc>(&e)) arc(*a);
        else if (const auto* t = std::get_if<ThreadFeed>(&e)) to({t->to.z, t->to.x});
        else if (const auto* c = std::get_if<ThreadCycle>(&e))
            for (const Event& m : thread_cycle_moves(*c)) emit(m);
        else if (const auto* t = std::get_if<TurnCycle>(&e))
            for (const Event& m : turn_cycle_moves(*t)) emit(m);
        else if (const auto* f = std::get_if<FinishCycle>(&e))
            for (const Event& m : finish_cycle_moves(*f, RoughCyclePattern::linuxcnc_g71)) emit(m);
        else if (const auto* g = std::get_if<GrooveCycle>(&e))
            for (const Event& m : groove_cycle_moves(*g)) emit(m);
    }

private:
    void to(Vec2 p, bool chord = false) {
        if (distance(p, at_) > 0) out_.push_back({at_, p, chord});
        at_ = p;
    }
    void arc(const Arc& a) {
        const Vec2 c{a.centre.z, a.centre.x}, end{a.to.z, a.to.x};
        Profile one;
        one.plane = ProfilePlane::xz;
        one.start = at_;
        one.segments.push_back({end, c, a.direction});
        const LatheDesignArc g = lathe_design_arc(one, 0);
        const int n = std::min(lathe_design_max_chords,
                               std::max(1, segments_for_tolerance(g.radius, std::abs(g.sweep), lathe_design_chord)));
        for (int i = 1; i <= n; ++i) to(i == n ? end : g.centre + unit_at(g.start + g.sweep * i / n) * g.radius, true);
    }
    Vec2 at_;
    std::vector<LatheTipMove>& out_;
};

// The design of an operation turned by a turning tool, its tip's path from its expansion.
template <class Op>
bool lathe_design_turned(const Op& op, const Job& job, LatheTurnDesign& d, std::vector<std::string>& unchecked) {
    const Tool* tool = lathe_design_tool(job, op.tool);
    if (!tool) return unchecked.push_back(op.path + ": its tool is not in the job"), false;
    d.path = op.path;
    d.tool = tool->number;
    d.nose = tool->diameter / 2;  // as the simulation's tool_shape
    d.chord = lathe_design_chord;
    d.profile.plane = ProfilePlane::xz;
    const Context ctx{job, *tool};
    LatheDesignTipRecorder rec({job.clearance, 0.0}, d.tip);
    expand(op, ctx, rec);
    return true;
}

}  // namespace

void design_turn_face(const TurnFaceOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked) {
    LatheTurnDesign d;
    if (!lathe_design_turned(op, job, d, unchecked)) return;
    d.profile.start = {op.start_z, op.inner};
    d.profile.segments.push_back({{op.z, op.inner}, std::nullopt, ArcDirection::ccw});
    d.profile.segments.push_back({{op.z, op.outer}, std::nullopt, ArcDirection::ccw});
    d.z_lo = op.z;
    d.z_hi = op.start_z;
    design.profiles.push_back(std::move(d));
}

void design_turn_rough(const TurnRoughOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked) {
    LatheTurnDesign d;
    if (!lathe_design_turned(op, job, d, unchecked)) return;
    d.nose_compensated = op.compensation == NoseCompensation::computer && op.nose_radius > 0;
    d.profile.start = op.boundary.start;
    d.profile.segments = op.boundary.segments;
    const Vec2 end = op.boundary.segments.back().end;
    if (end.y < op.stock_radius) d.profile.segments.push_back({{end.x, op.stock_radius}, std::nullopt, ArcDirection::ccw});
    d.z_hi = op.boundary.start.x;
    d.z_lo = end.x;
    for (std::size_t k = 0; k < op.boundary.segments.size(); ++k) {
        d.z_lo = std::min(d.z_lo, op.boundary.segments[k].end.x);
        if (!op.boundary.segments[k].centre) continue;
        const LatheDesignArc arc = lathe_design_arc(op.boundary, k);
        if (lathe_design_on_arc(arc, pi)) d.z_lo = std::min(d.z_lo, arc.centre.x - arc.radius);
    }
    design.profiles.push_back(std::move(d));
}

namespace {

// The design of a blade's cut: `outline` (Z falling) kept below, the blade's path.
void lathe_design_blade(const Job& job, LatheTurnDesign& d, const GrooveBlade& blade, std::vector<Vec2> outline) {
    d.nose = 0.0;
    d.blade_lo = blade.right_point ? -blade.width : 0.0;
    d.blade_hi = d.blade_lo + blade.width;
    (void)job;
    d.profile.start = outline.front();
    for (std::size_t k = 1; k < outline.size(); ++k) d.profile.segments.push_back({outline[k], std::nullopt, ArcDirection::ccw});
    d.z_hi = outline.front().x;
    d.z_lo = outline.back().x;
}

}  // namespace

void design_turn_groove(const TurnGrooveOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked) {
    if (op.side == GrooveSide::face) {
        if (!lathe_design_tool(job, op.tool)) return unchecked.push_back(op.path + ": its tool is not in the job");
        LatheRingDesign r;
        r.path = op.path;
        r.tool = op.tool;
        r.inner = op.z_left;
        r.outer = op.z_right;
        r.face_z = op.surface;
        r.bottom_z = op.bottom;
        r.chamfer = op.chamfer;
        design.rings.push_back(std::move(r));
        return;
    }
    if (op.side == GrooveSide::internal) {
        if (!lathe_design_tool(job, op.tool)) return unchecked.push_back(op.path + ": its tool is not in the job");
        LatheHoleDesign h;
        h.path = op.path;
        h.tool = op.tool;
        h.top_z = op.z_right;
        h.bottom_z = op.z_left;
        h.radius = op.bottom;
        h.groove_chamfer = op.chamfer;
        h.groove_surface = op.surface;
        design.holes.push_back(std::move(h));
        return;
    }
    LatheTurnDesign d;
    if (!lathe_design_turned(op, job, d, unchecked)) return;
    const double c = op.chamfer, R = op.surface;
    std::vector<Vec2> outline;
    outline.push_back({op.z_right + c, R});
    if (c > 0) outline.push_back({op.z_right, R - c});
    outline.push_back({op.z_right, op.bottom});
    outline.push_back({op.z_left, op.bottom});
    if (c > 0) outline.push_back({op.z_left, R - c});
    outline.push_back({op.z_left - c, R});
    lathe_design_blade(job, d, op.blade, std::move(outline));
    design.profiles.push_back(std::move(d));
}

void design_turn_part(const TurnPartOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked) {
    LatheTurnDesign d;
    if (!lathe_design_turned(op, job, d, unchecked)) return;
    const double c = op.chamfer, R = op.surface, left = op.z - op.blade.width;
    std::vector<Vec2> outline;
    outline.push_back({op.z + c, R});
    if (c > 0) outline.push_back({op.z, R - c});
    outline.push_back({op.z, op.end});
    outline.push_back({left, op.end});
    outline.push_back({left, R});
    lathe_design_blade(job, d, op.blade, std::move(outline));
    design.profiles.push_back(std::move(d));
}

void design_turn_thread(const TurnThreadOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked) {
    if (op.side == ThreadSide::internal) {
        const Tool* tool = lathe_design_tool(job, op.tool);
        LatheHoleDesign h;
        h.path = op.path;
        h.tool = op.tool;
        h.top_z = op.start_z;
        h.bottom_z = op.end_z;
        h.radius = op.root_radius();
        h.nose = tool ? tool->nose_radius : 0.0;
        h.nose_above = -lathe_tip_offset(tool && tool->orientation > 0 ? tool->orientation : 3, h.nose).x;
        if (op.runout == ThreadRunout::chamfered) {
            // The runout's cone: the bore narrows from the major at endZ + runoutLength to the
            // minor at endZ, as the last pass's pull-out cuts it (rounded by the nose).
            h.flat = op.surface_radius();
            h.slope = op.runout_length / (op.root_radius() - op.surface_radius());
        }
        design.holes.push_back(std::move(h));
        return;
    }
    LatheTurnDesign d;
    if (!lathe_design_turned(op, job, d, unchecked)) return;
    d.profile.start = {op.start_z, op.root_radius()};
    if (op.runout == ThreadRunout::chamfered) {
        // The runout: the root up to endZ + runoutLength, then the last pass's taper to the crest.
        d.profile.segments.push_back({{op.end_z + op.runout_length, op.root_radius()}, std::nullopt, ArcDirection::ccw});
        d.profile.segments.push_back({{op.end_z, op.surface_radius()}, std::nullopt, ArcDirection::ccw});
    } else {
        d.profile.segments.push_back({{op.end_z, op.root_radius()}, std::nullopt, ArcDirection::ccw});
        d.profile.segments.push_back({{op.end_z, op.surface_radius()}, std::nullopt, ArcDirection::ccw});
    }
    d.z_lo = op.end_z;
    d.z_hi = op.start_z;
    design.profiles.push_back(std::move(d));
}


LatheMaterial LatheMaterial::bar(double radius, double face_z, double z_lo, double step, std::vector<double> breaks) {
    LatheMaterial m;
    if (!(face_z > z_lo)) return m;
    const int n = std::max(1, static_cast<int>(std::ceil((face_z - z_lo) / step)));
    for (int i = 0; i <= n; ++i) breaks.push_back(i == n ? face_z : z_lo + (face_z - z_lo) * i / n);
    std::sort(breaks.begin(), breaks.end());
    for (double b : breaks) {
        if (b < z_lo || b > face_z) continue;
        if (!m.z.empty() && b - m.z.back() < 1e-9) {
            if (b == face_z) m.z.back() = face_z;  // the face itself stays exact
            continue;
        }
        m.z.push_back(b);
    }
    m.r.assign(m.z.size() - 1, radius);
    return m;
}

double LatheMaterial::top(double a, double b) const {
    double best = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i)
        if (z[i + 1] > a && z[i] < b) best = std::max(best, r[i]);
    return best;
}

double LatheMaterial::front(double v) const {
    for (std::size_t i = r.size(); i-- > 0;)
        if (r[i] > v) return z[i + 1];
    return -std::numeric_limits<double>::infinity();
}

bool LatheMaterial::above(double a, double b, double v) const {
    for (std::size_t i = 0; i < r.size(); ++i)
        if (z[i + 1] > a && z[i] < b && r[i] > v) return true;
    return false;
}

namespace {

// The lowest radius a nose disc of radius n reaches at Z z while its centre moves from a to b
// ((Z, radius)); infinity where the disc does not reach z. Along the move the disc's lowest
// point at z is c.y - sqrt(n^2 - (c.x - z)^2), convex in the move's parameter: least at an end
// of the stretch where |c.x - z| <= n, or where its derivative is 0.
double lathe_material_disc_reach(Vec2 a, Vec2 b, double n, double z) {
    const double du = b.x - a.x, dv = b.y - a.y;
    double t0 = 0.0, t1 = 1.0;
    if (std::abs(du) < 1e-15) {
        if (std::abs(a.x - z) > n) return std::numeric_limits<double>::infinity();
    } else {
        double s0 = (z - n - a.x) / du, s1 = (z + n - a.x) / du;
        if (s0 > s1) std::swap(s0, s1);
        t0 = std::max(0.0, s0), t1 = std::min(1.0, s1);
        if (t0 > t1) return std::numeric_limits<double>::infinity();
    }
    auto g = [&](double t) {
        const double w = a.x + t * du - z;
        return a.y + t * dv - std::sqrt(std::max(0.0, n * n - w * w));
    };
    double best = std::min(g(t0), g(t1));
    if (std::abs(du) >= 1e-15 && n > 0) {
        const double w = -n * dv * (du > 0 ? 1.0 : -1.0) / std::hypot(du, dv);
        const double t = (z + w - a.x) / du;
        if (t > t0 && t < t1) best = std::min(best, g(t));
    }
    return best;
}

// The lowest radius a flat edge reaches at Z z, covering Z from the tip's + lo to + hi, while the
// tip moves from a to b; infinity where it does not cover z.
double lathe_material_edge_reach(Vec2 a, Vec2 b, double lo, double hi, double z) {
    const double du = b.x - a.x, dv = b.y - a.y;
    double t0 = 0.0, t1 = 1.0;
    if (std::abs(du) < 1e-15) {
        if (a.x + lo > z || a.x + hi < z) return std::numeric_limits<double>::infinity();
    } else {
        double s0 = (z - hi - a.x) / du, s1 = (z - lo - a.x) / du;
        if (s0 > s1) std::swap(s0, s1);
        t0 = std::max(0.0, s0), t1 = std::min(1.0, s1);
        if (t0 > t1) return std::numeric_limits<double>::infinity();
    }
    return std::min(a.y + t0 * dv, a.y + t1 * dv);
}

}  // namespace

void lathe_material_cut(LatheMaterial& m, const LatheTurnDesign& d, Vec2 tip_offset) {
    if (m.r.empty()) return;
    const bool blade = d.blade_hi > d.blade_lo;
    for (const LatheTipMove& mv : d.tip) {
        // The move's shape in (Z, radius): the nose's centre, or the blade's tip.
        const Vec2 a = blade ? mv.from : mv.from - tip_offset, b = blade ? mv.to : mv.to - tip_offset;
        const double lo = blade ? std::min(a.x, b.x) + d.blade_lo : std::min(a.x, b.x) - d.nose;
        const double hi = blade ? std::max(a.x, b.x) + d.blade_hi : std::max(a.x, b.x) + d.nose;
        auto reach = [&](double z) {
            return blade ? lathe_material_edge_reach(a, b, d.blade_lo, d.blade_hi, z) : lathe_material_disc_reach(a, b, d.nose, z);
        };
        // The intervals the move covers whole.
        auto first = std::lower_bound(m.z.begin(), m.z.end(), lo);
        for (std::size_t i = static_cast<std::size_t>(first - m.z.begin()); i + 1 < m.z.size() && m.z[i + 1] <= hi; ++i) {
            const double bound = std::max(reach(m.z[i]), reach(m.z[i + 1]));
            m.r[i] = std::min(m.r[i], std::max(0.0, bound + (mv.chord ? d.chord : 0.0)));
        }
    }
}

}  // namespace camgen
