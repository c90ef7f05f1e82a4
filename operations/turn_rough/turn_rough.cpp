#include "camgen/operations/turn_rough/turn_rough.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/geometry/lathe_cycle.hpp"
#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

// Z differences below this are the same Z, mm.
constexpr double turn_rough_same = 1e-9;

constexpr KeySpec turn_rough_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a turning-tool of orientation 2"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "xValues", .type = JsonType::string, .default_json = "\"diameter\"", .choices = &choices_of<x_values>,
     .description = "the points' X, startX and allowanceX as diameters or as radii"},
    {.key = "feed", .quantity = Quantity::feed, .required = true, .min = Bound{0, false},
     .description = "cutting feed, per minute or per revolution (feedMode)"},
    {.key = "feedMode", .type = JsonType::string, .default_json = "\"per-minute\"", .choices = &choices_of<feed_modes>,
     .description = "feed in mm/min or mm/rev; the program feeds the same way (G94/G95, Fanuc T G98/G99)"},
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length, .required = true,
     .description = "where the finished profile starts [x, z], at its +Z end"},
    {.key = "path", .type = JsonType::array, .required = true, .ref = "turnProfileElement", .min_items = 1,
     .description = "the finished profile's elements [x, z], Z never rising along it (X may fall: an undercut)"},
    {.key = "startX", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "X (as xValues) of the bar roughed from (default: the stock bar's diameter; required without a bar)"},
    {.key = "stock", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<rough_stocks>,
     .description = "what it roughs from: \"auto\" what the operations before it left of the job's stock bar (each pass "
                    "begins approachDistance before that material at its level, levels in air are left out), \"bar\" "
                    "the whole bar of startX"},
    {.key = "allowanceX", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "material left for finishing in X, as xValues gives X (on the diameter by default, like Fanuc's "
                    "G71 U): the profile is moved out by it"},
    {.key = "allowanceZ", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "material left for finishing on faces, mm: the profile is moved towards +Z by it"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"z\"", .choices = &choices_of<rough_directions>,
     .description = "which way the passes run: \"z\" along -Z towards the chuck (turning), \"x\" along -X towards the "
                    "axis (facing)"},
    {.key = "depthOfCut", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "the most material one pass takes, mm: radial (per side) along Z, axial along X; the passes are "
                    "equal"},
    {.key = "approachDistance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "1",
     .description = "how far beyond the profile's start (in Z) each pass begins, and how far outside the bar the tool "
                    "rapids, mm"},
    {.key = "compensation", .type = JsonType::string, .default_json = "\"computer\"", .choices = &choices_of<nose_compensation_modes>,
     .description = "who makes up for the tool's nose radius in the passes and the last pass along the boundary: "
                    "computer (the nose circle stays on the boundary) or none (the tip does)"},
    {.key = "lift", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "0.5",
     .description = "how far each pass lifts off at 45 degrees (in Z and in X) before it rapids back, mm; at most half "
                    "the depth of a pass (along X, steeper than the profile's steepest fall towards the chuck)"},
    {.key = "output", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<cycle_outputs>,
     .description = "auto: the machine's roughing cycle (LinuxCNC G71 along Z, G72 along X, with the boundary as a "
                    "subroutine) where it makes passes that leave the allowances, else longhand with a note; canned: the "
                    "cycle or an error; longhand: passes of G0 and G1"},
};

// The Z range of a segment of a profile (an arc's may reach beyond its ends).
std::pair<double, double> turn_rough_z_range(const Profile& p, std::size_t k) {
    const Vec2 a = segment_start(p, k), b = p.segments[k].end;
    double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
    const ProfileSegment& s = p.segments[k];
    if (!s.centre) return {lo, hi};
    const Vec2 c = *s.centre;
    const double r = distance(a, c);
    const double a0 = std::atan2(a.y - c.y, a.x - c.x), sw = segment_sweep(p, k);
    for (double ang : {0.0, pi}) {
        double d = s.direction == ArcDirection::ccw ? ang - a0 : a0 - ang;
        d = std::fmod(d, two_pi);
        if (d < 0) d += two_pi;
        if (d > 1e-12 && d < sw - 1e-12) {
            lo = std::min(lo, c.x + r * std::cos(ang));
            hi = std::max(hi, c.x + r * std::cos(ang));
        }
    }
    return {lo, hi};
}

// Where segment k of p meets the level v: the Z of its crossings.
void turn_rough_crossings(const Profile& p, std::size_t k, double v, std::vector<double>& out) {
    const Vec2 a = segment_start(p, k);
    const ProfileSegment& s = p.segments[k];
    if (!s.centre) {
        if ((a.y - v) * (s.end.y - v) > 0 || std::abs(s.end.y - a.y) < 1e-15) return;
        out.push_back(a.x + (v - a.y) * (s.end.x - a.x) / (s.end.y - a.y));
        return;
    }
    const Vec2 c = *s.centre;
    const double r = distance(a, c), dv = v - c.y;
    if (std::abs(dv) > r) return;
    const double du = std::sqrt(r * r - dv * dv);
    const double a0 = std::atan2(a.y - c.y, a.x - c.x), sw = segment_sweep(p, k);
    for (double side : {-1.0, 1.0}) {
        const double ang = std::atan2(dv, side * du);
        double d = s.direction == ArcDirection::ccw ? ang - a0 : a0 - ang;
        d = std::fmod(d, two_pi);
        if (d < 0) d += two_pi;
        if (d <= sw + 1e-12) out.push_back(c.x + side * du);
    }
}

// The radius of segment k at Z z (z within its range; an arc monotone in Z).
double turn_rough_radius_on(const Profile& p, std::size_t k, double z) {
    const Vec2 a = segment_start(p, k);
    const ProfileSegment& s = p.segments[k];
    if (!s.centre) {
        if (std::abs(s.end.x - a.x) < turn_rough_same) return std::min(a.y, s.end.y);
        return a.y + (z - a.x) * (s.end.y - a.y) / (s.end.x - a.x);
    }
    const Vec2 c = *s.centre;
    const double r = distance(a, c), du = z - c.x;
    const double dv = std::sqrt(std::max(0.0, r * r - du * du));
    // The half of the circle the arc lies on: the one its midpoint is on.
    const double a0 = std::atan2(a.y - c.y, a.x - c.x), sw = segment_sweep(p, k);
    const double mid = a0 + (s.direction == ArcDirection::ccw ? sw / 2 : -sw / 2);
    return std::sin(mid) >= 0 ? c.y + dv : c.y - dv;
}

// The steepest fall towards the chuck along a profile, degrees from -Z (0: it never falls). An
// arc's direction of travel turns one way along it, so its steepest fall is at an end.
double turn_rough_steepest_fall(const Profile& p) {
    double worst = 0.0;
    auto fall_of = [&](double dz, double dr) {
        // A direction of travel with Z never rising: falling where the radius shrinks.
        if (dr < 0) worst = std::max(worst, std::atan2(-dr, std::max(0.0, -dz)) * deg_per_rad);
    };
    for (std::size_t k = 0; k < p.segments.size(); ++k) {
        const ProfileSegment& s = p.segments[k];
        const Vec2 a = segment_start(p, k);
        if (!s.centre) {
            fall_of(s.end.x - a.x, s.end.y - a.y);
            continue;
        }
        const double sign = s.direction == ArcDirection::ccw ? 1.0 : -1.0;
        for (const Vec2 q : {a, s.end}) {
            const Vec2 r = q - *s.centre;
            fall_of(-sign * r.y, sign * r.x);
        }
    }
    return worst;
}

// Computer compensation: the tip path that keeps the nose circle on the boundary, closed by the
// face at its end up to the bar (the face stands at the end's Z: the nose must not pass it).
// Along X the passes at Z levels just below the boundary's start stop where the nose meets its
// start corner: unless the boundary starts up a face, a face of one nose radius is put before
// it, round whose top the nose rolls onto the first element; the tip path keeps that roll and
// leaves the face out (the last pass ends on the start corner, not below it).
void turn_rough_compensate(TurnRoughOp& op, const Tool& tool, Fields& f, const JobInput& in) {
    Profile closed = op.boundary;
    const Vec2 end = closed.segments.back().end;
    if (end.y < op.stock_radius) closed.segments.push_back({Vec2{end.x, op.stock_radius}, std::nullopt, ArcDirection::ccw});
    bool lead = false;
    if (op.direction == RoughDirection::x) {
        const Vec2 t = point_at(closed, 0.0).tangent;
        if (std::abs(t.x) > 1e-9 || !(t.y > 0)) {
            lead = true;
            const Vec2 b0 = closed.start;
            closed.start = Vec2{b0.x, b0.y - op.nose_radius};
            closed.segments.insert(closed.segments.begin(), ProfileSegment{b0, std::nullopt, ArcDirection::ccw});
        }
    }
    const std::size_t first = lead ? 1 : 0;  // the boundary's element 0 in `closed`
    const NosePath nose = nose_path(closed, op.nose_radius, tool.orientation);
    if (nose.refusal) {
        const std::size_t k = nose.refusal->index;
        if (k >= first && k - first < op.boundary.segments.size())
            json::fail(in.source(), f.path_of("path") + "/" + std::to_string(k - first),
                       nose.refusal->why + " (the profile with its allowances)");
        if (k < first) f.fail("start", "the nose round the start of the profile (with its allowances): " + nose.refusal->why);
        f.fail("path", "the face from the profile's end up to the bar: " + nose.refusal->why);
    }
    op.tip_boundary = nose.tip;
    if (lead) {
        // The lead face's offset: a line at one Z, the first of the tip path.
        const ProfileSegment& s = op.tip_boundary.segments.front();
        if (s.centre || std::abs(s.end.x - op.tip_boundary.start.x) > 1e-9)
            throw std::logic_error("turn-rough: the nose path does not begin with the lead face's offset");
        op.tip_boundary.start = s.end;
        op.tip_boundary.segments.erase(op.tip_boundary.segments.begin());
    }
    for (std::size_t k : nose.concave_corners)
        if (k >= first && k - first < op.boundary.segments.size())  // the corner at the end face: where the roughing stops anyway
            op.notes.push_back(fmt::format("{}/{}: the sharp concave corner before this element keeps the nose's radius ({}) "
                                           "beyond the allowances",
                                           f.path_of("path"), k - first, in.show(op.nose_radius)));
}

}  // namespace

double turn_rough_boundary_at(const TurnRoughOp& op, double z) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < op.tip_boundary.segments.size(); ++k) {
        const auto [lo, hi] = turn_rough_z_range(op.tip_boundary, k);
        if (z < lo - turn_rough_same || z > hi + turn_rough_same) continue;
        best = std::min(best, turn_rough_radius_on(op.tip_boundary, k, std::clamp(z, lo, hi)));
    }
    return best;
}

std::vector<TurnRoughSpan> turn_rough_spans(const TurnRoughOp& op, double v) {
    const Profile& b = op.tip_boundary;
    const double z_hi = b.start.x, z_lo = b.segments.back().end.x;
    std::vector<double> zs{z_lo, z_hi};
    for (std::size_t k = 0; k < b.segments.size(); ++k) turn_rough_crossings(b, k, v, zs);
    std::sort(zs.begin(), zs.end(), std::greater<>());
    std::vector<TurnRoughSpan> out;
    for (std::size_t i = 0; i + 1 < zs.size(); ++i) {
        const double hi = std::min(zs[i], z_hi), lo = std::max(zs[i + 1], z_lo);
        if (hi - lo < 1e-6) continue;
        if (!(turn_rough_boundary_at(op, (hi + lo) / 2) < v)) continue;
        if (!out.empty() && std::abs(out.back().lo - hi) < 1e-9) out.back().lo = lo;
        else out.push_back({lo, hi});
    }
    return out;
}

std::vector<ObjectSpec> TurnRoughOp::objects() {
    return {{.name = "turn-rough",
             .description = "roughing the outside of a bar on a lathe to a profile plus allowances, in passes along Z or along X",
             .keys = {std::begin(turn_rough_keys), std::end(turn_rough_keys)}}};
}

TurnRoughOp TurnRoughOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, turn_rough_keys);
    const OutsideTurningHead head = read_outside_turning_head(f, in, "turn-rough");
    const Tool& tool = *head.tool;
    TurnRoughOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    const XValues xv = head.given_x;
    op.given_x = xv;
    op.feed_mode = head.feed_mode;
    op.feed = head.feed;
    const double scale = xv == XValues::diameter ? 0.5 : 1.0;
    op.profile = read_turned_profile(f, in, xv);
    for (std::size_t k = 0; k < op.profile.segments.size(); ++k) {
        const auto [lo, hi] = turn_rough_z_range(op.profile, k);
        const Vec2 a = segment_start(op.profile, k);
        if (hi > a.x + turn_rough_same || lo < op.profile.segments[k].end.x - turn_rough_same)
            json::fail(in.source(), f.path_of("path") + "/" + std::to_string(k),
                       "this element turns back towards +Z: a turn-rough cuts along Z towards the chuck, and its "
                       "profile's Z must never rise from the start to the end");
    }
    if (auto bad = first_unfollowable(op.profile, tool))
        json::fail(in.source(), f.path_of("path") + "/" + std::to_string(bad->index), bad->why);
    if (!tool.insert_angle)
        op.notes.push_back(fmt::format("tool {} gives no insertAngle and approachAngle: camgen does not check that its "
                                       "insert can follow the profile's slopes",
                                       tool.number));
    op.allowance_x = in.optional_length(f, "allowanceX").value_or(0.0) * scale;
    op.allowance_z = in.optional_length(f, "allowanceZ").value_or(0.0);
    if (op.allowance_x < 0) f.fail("allowanceX", "allowanceX must be 0 or more");
    if (op.allowance_z < 0) f.fail("allowanceZ", "allowanceZ must be 0 or more");
    op.boundary = op.profile;
    const Vec2 shift{op.allowance_z, op.allowance_x};
    op.boundary.start = op.boundary.start + shift;
    for (ProfileSegment& s : op.boundary.segments) {
        s.end = s.end + shift;
        if (s.centre) s.centre = *s.centre + shift;
    }
    const std::optional<Stock>& stock = in.header().stock;
    const bool bar = stock && stock->shape == StockShape::bar;
    if (f.has("startX")) op.stock_radius = in.length(f, "startX") * scale;
    else if (bar) op.stock_radius = stock->diameter / 2;
    else f.fail("startX", "give startX (the X of the bar roughed from), or a stock bar whose diameter it is");
    op.stock = f.choice("stock", rough_stocks, RoughStock::from_earlier);
    double top = 0.0;
    for (std::size_t k = 0; k < op.boundary.segments.size(); ++k) {
        const Vec2 a = segment_start(op.boundary, k);
        top = std::max({top, a.y, op.boundary.segments[k].end.y});
    }
    if (op.boundary.start.y >= op.stock_radius)
        f.fail(f.has("startX") ? "startX" : "start",
               fmt::format("the profile starts (with allowanceX) at X {}, not below the bar's X {}: there is nothing to rough",
                           in.show(op.boundary.start.y / scale), in.show(op.stock_radius / scale)));
    if (top > op.stock_radius + turn_rough_same)
        f.fail("path", fmt::format("the profile (with allowanceX) reaches X {}, beyond the bar's X {}: a turn-rough cuts "
                                   "within the bar",
                                   in.show(top / scale), in.show(op.stock_radius / scale)));
    op.direction = f.choice("direction", rough_directions, RoughDirection::z);
    if (op.direction == RoughDirection::x && op.boundary.start.x - op.boundary.segments.back().end.x < 1e-3)
        f.fail("direction", "along X the passes step down in Z from the profile's start to its end, and this profile "
                            "ends at the Z it starts at: rough it along Z");
    op.steepest_fall = turn_rough_steepest_fall(op.boundary);
    op.depth_of_cut = in.length(f, "depthOfCut");
    if (!(op.depth_of_cut > 0)) f.fail("depthOfCut", "depthOfCut must be > 0");
    op.approach = in.optional_length(f, "approachDistance").value_or(1.0);
    if (!(op.approach > 0)) f.fail("approachDistance", "approachDistance must be > 0");
    op.lift = in.optional_length(f, "lift").value_or(0.5);
    if (!(op.lift > 0)) f.fail("lift", "lift must be > 0");
    op.output = f.choice("output", cycle_outputs, CycleOutput::automatic);
    if (op.boundary.start.x + op.approach >= in.header().clearance)
        f.fail("start", fmt::format("the passes begin at Z {} (the start, allowanceZ and approachDistance), at or above the "
                                    "clearance (Z {})",
                                    in.show(op.boundary.start.x + op.approach), in.show(in.header().clearance)));
    op.nose_radius = tool.nose_radius;
    op.compensation = f.choice("compensation", nose_compensation_modes, NoseCompensation::computer);
    if (op.compensation == NoseCompensation::control)
        f.fail("compensation", "turn-rough does not write control compensation (G41/G42): its passes and last pass are "
                               "compensated by camgen (computer) or not at all (none); finish the profile with a turn-profile "
                               "whose compensation is control");
    op.tip_boundary = op.boundary;
    if (op.compensation == NoseCompensation::computer && op.nose_radius > 0)
        turn_rough_compensate(op, tool, f, in);
    const double bottom = [&] {
        const Profile& tb = op.tip_boundary;
        double b = op.stock_radius;
        for (std::size_t k = 0; k < tb.segments.size(); ++k) {
            const Vec2 a = segment_start(tb, k);
            b = std::min({b, a.y, tb.segments[k].end.y});
            const ProfileSegment& s = tb.segments[k];
            if (s.centre) {
                const double r = distance(a, *s.centre);
                const double a0 = std::atan2(a.y - s.centre->y, a.x - s.centre->x), sw = segment_sweep(tb, k);
                double d = s.direction == ArcDirection::ccw ? -pi / 2 - a0 : a0 + pi / 2;
                d = std::fmod(d, two_pi);
                if (d < 0) d += two_pi;
                if (d <= sw) b = std::min(b, s.centre->y - r);
            }
        }
        return b;
    }();
    op.bottom = bottom;
    const double extent = op.direction == RoughDirection::x ? op.boundary.start.x - op.boundary.segments.back().end.x
                                                            : op.stock_radius - bottom;
    const int count = static_cast<int>(std::ceil(extent / op.depth_of_cut - 1e-9));
    if (count > 100000)
        f.fail("depthOfCut", fmt::format("depthOfCut {} makes {} passes: more than 100000", in.show(op.depth_of_cut), count));
    return op;
}

namespace {
Vec3 turn_rough_at(double r, double z) { return {r, 0.0, z}; }

// Feeds along `path` from its end back to its start (arcs turned round).
void turn_rough_backwards(const TurnRoughOp& op, const Profile& path, EventSink& sink) {
    const std::vector<ProfileSegment>& segs = path.segments;
    for (std::size_t k = segs.size(); k-- > 0;) {
        const Vec2 to = segment_start(path, k);
        const ProfileSegment& s = segs[k];
        if (s.centre)
            sink.emit(Arc{turn_rough_at(to.y, to.x), turn_rough_at(s.centre->y, s.centre->x),
                          s.direction == ArcDirection::cw ? ArcDirection::ccw : ArcDirection::cw, Plane::xz, op.feed, 0,
                          Movement::cutting});
        else
            sink.emit(Linear{turn_rough_at(to.y, to.x), op.feed, Movement::cutting});
    }
}

// The machine's roughing cycle for `op` where it makes the roughing (`via`, a point outside the
// bar on the way to its start, first): the cycle, then off the end of its last pass at 45
// degrees (above it the levels or the pass along the boundary have cut) and out of the bar;
// true. Otherwise the cycle with why it is not used (a note where the machine has one, an error
// under "canned"), false: the caller writes the passes.
bool emit_turn_cycle(const TurnRoughOp& op, const Context& ctx, EventSink& sink, double outside, std::optional<Vec3> via) {
    TurnCycle c = turn_cycle(op);
    c.finish = op.finish;
    if (!c.refusal && op.output == CycleOutput::automatic && !op.whole_bar_over_boundary()) {
        // Passes from what the earlier operations left take less than the cycle, which roughs
        // from the bar; "canned" writes the cycle anyway.
        c.refusal = "the operations before it removed part of the bar over the profile, and the cycle roughs from the "
                    "bar, in air there: camgen's passes start from what they left (\"output\": \"canned\" writes the cycle)";
        c.moves.clear();
    }
    if (c.refusal) {
        sink.emit(c);
        return false;
    }
    if (via) sink.emit(Rapid{*via});
    sink.emit(Rapid{c.start});
    // The way out, part of the cycle's moves (turn_cycle_exit): where LinuxCNC's cycle ends, on
    // the last pass, a feed off it at 45 degrees and out of the bar; where Fanuc's ends, at its
    // start point in air, a rapid out of the bar.
    c.lift = std::min(op.lift, c.depth / 2);
    c.out_x = outside;
    c.out_z = ctx.job.clearance;
    sink.emit(c);
    return true;
}

// Passes along -X at Z levels; then down the end face and along the boundary back to its start.
void expand_along_x(const TurnRoughOp& op, const Context& ctx, EventSink& sink) {
    const double z_hi = op.boundary.start.x;
    const Vec2 end = op.boundary.segments.back().end;
    const double outside = op.stock_radius + op.approach;
    const std::vector<double> levels = turn_rough_x_levels(op);
    const double step = (z_hi - end.x) / static_cast<double>(levels.size() + 1);
    const double lift = std::min(op.lift, step / 2);
    // Off the face a pass leaves, steeper than any fall of the boundary towards the chuck, so
    // that the lift stays outside the boundary above the pass: the boundary rises at most at the
    // steepest fall from the pass's end towards +Z. 45 degrees where it falls less.
    const double angle = std::max(45.0, (op.steepest_fall + 90.0) / 2.0) / deg_per_rad;
    const double dz = std::sqrt(2.0) * lift * std::cos(angle), dr = std::sqrt(2.0) * lift * std::sin(angle);
    sink.emit(Rapid{turn_rough_at(outside, ctx.job.clearance)});
    if (op.output != CycleOutput::longhand && emit_turn_cycle(op, ctx, sink, outside, std::nullopt)) return;
    const bool from_material = !op.material.r.empty();
    // Where a pass at Z z begins with the earlier material: approachDistance outside the most
    // of it at z and above (the tool stands towards +Z of its tip).
    auto begin_at = [&](double z) {
        return from_material ? std::min(outside, op.material.top(z, std::numeric_limits<double>::infinity()) + op.approach)
                             : outside;
    };
    double ran = std::numeric_limits<double>::infinity();  // the Z of the pass before that ran
    for (double level : levels) {
        const double r_end = turn_rough_boundary_at(op, level);
        if (!(r_end < op.stock_radius - 1e-6)) continue;  // the boundary is at the bar here: nothing to take
        // A pass takes what lies above its end from its Z up to the pass before: none there, in air.
        if (from_material && !op.material.above(level, ran, r_end)) continue;
        ran = level;
        sink.emit(Rapid{turn_rough_at(outside, level)});
        if (const double in = begin_at(level); in < outside && in > r_end) sink.emit(Rapid{turn_rough_at(in, level)});
        sink.emit(Linear{turn_rough_at(r_end, level), op.feed, Movement::cutting});
        sink.emit(Linear{turn_rough_at(r_end + dr, level + dz), op.feed, Movement::lead_out});
        sink.emit(Rapid{turn_rough_at(std::max(outside, r_end + dr), level + dz)});
    }
    // The last pass: down the end face from outside the bar, along the tip boundary to its start
    // (with compensation the tip boundary goes on up the end face to the bar: its end is there).
    const Profile& tip = op.tip_boundary;
    const Vec2 tip_end = tip.segments.back().end;
    sink.emit(Rapid{turn_rough_at(outside, tip_end.x)});
    if (const double in = begin_at(tip_end.x); in < outside && in > tip_end.y) sink.emit(Rapid{turn_rough_at(in, tip_end.x)});
    sink.emit(Linear{turn_rough_at(tip_end.y, tip_end.x), op.feed,
                     tip_end.y < op.stock_radius ? Movement::cutting : Movement::lead_in});
    turn_rough_backwards(op, tip, sink);
    // Off the start: above it is air (the passes begin there along Z too).
    const Vec2 b0 = tip.start;
    sink.emit(Linear{turn_rough_at(b0.y + lift, b0.x + lift), op.feed, Movement::lead_out});
    sink.emit(Rapid{turn_rough_at(outside, b0.x + lift)});
    sink.emit(Rapid{turn_rough_at(outside, ctx.job.clearance)});
}
}  // namespace

std::vector<double> turn_rough_x_levels(const TurnRoughOp& op) {
    const double z_hi = op.boundary.start.x, z_lo = op.boundary.segments.back().end.x;
    const int count = std::max(1, static_cast<int>(std::ceil((z_hi - z_lo) / op.depth_of_cut - 1e-9)));
    const double step = (z_hi - z_lo) / count;
    std::vector<double> levels;
    for (int k = 1; k < count; ++k) levels.push_back(z_hi - step * k);
    return levels;
}

namespace {
// The cycle's first level and depth of cut (its I): depths from depthOfCut down in steps of
// 2.5 % (rounded to 0.0001), the first level from one cut below `top` towards it, until no level
// (first, first - I, ... down to `low`) lies within 0.005 mm of a corner of the boundary and
// `model_at` (the control's cycle from that first level) covers it; `c` gets the start
// (`start_at` the first level), depth, retract and moves, or the refusal.
void choose_cycle_levels(TurnCycle& c, const TurnRoughOp& op, double top, double low, const std::vector<double>& corners,
                         const std::function<LatheCycleModel(double, double, double)>& model_at,
                         const std::function<Vec3(double)>& start_at) {
    const double room = top - low;
    std::optional<std::string> last_refusal;
    for (int i = 0; i <= 8; ++i) {
        const double depth = std::round(op.depth_of_cut * (1.0 - i / 40.0) * 1e4) / 1e4;
        if (!(depth > 0.0001)) break;
        for (int j = 0; j < 32; ++j) {
            const double below = std::min(depth, room - 0.01) * (1.0 - j / 64.0);
            const double level0 = std::round((top - below) * 1e4) / 1e4;
            if (!(level0 > low + 0.005)) continue;
            bool near = false;
            for (double v = level0; v > low - 0.01 && !near; v -= depth)
                for (double k : corners) near = near || std::abs(v - k) < 0.005;
            if (near) continue;
            const double retract = std::round(std::min(op.lift, depth / 2) * 1e4) / 1e4;
            LatheCycleModel model = model_at(level0, depth, retract);
            if (model.refusal) {
                last_refusal = model.refusal;
                if (model.refusal->find("runs through a corner") != std::string::npos) continue;
                c.refusal = *model.refusal;
                return;
            }
            c.start = start_at(level0);
            c.depth = depth;
            c.retract = retract;
            c.moves = std::move(model.moves);
            return;
        }
    }
    c.refusal = last_refusal.value_or("every start and depth of cut tried puts a level within 0.005 mm of a corner of the boundary");
}

// The roughing cycle along X: LinuxCNC's G72 on the tip boundary walked backwards from the top
// of its end face (at the bar: the cycle comes in along the line from its start to there, which
// stays outside the bar), from a start outside the bar whose Z is the first level.
TurnCycle turn_cycle_along_x(const TurnRoughOp& op) {
    TurnCycle c;
    c.path = op.path;
    c.output = op.output;
    c.feed = op.feed;
    c.along_x = true;
    Profile sub = reversed(op.tip_boundary);
    if (sub.start.y < op.stock_radius) {
        ProfileSegment& first = sub.segments.front();
        if (!first.centre && std::abs(first.end.x - sub.start.x) < 1e-9) sub.start.y = op.stock_radius;  // the end face, longer
        else sub.segments.insert(sub.segments.begin(), ProfileSegment{sub.start, std::nullopt, ArcDirection::ccw}),
             sub.start.y = op.stock_radius;
    }
    c.profile = sub;
    const double outside = op.stock_radius + op.approach;
    // The levels go down from the start's Z by I: the first within a pass of the material's
    // face (the boundary's start, or the bar's face beyond it). A level within 0.005 mm of a
    // corner's Z is where the control's cycle turns on its tolerances: another start (and I).
    const double top = std::max(op.tip_boundary.start.x, op.bar_face.value_or(op.tip_boundary.start.x));
    const double low = sub.start.x;  // the end face's Z: the lowest of the sub
    std::vector<double> corners{sub.start.x};
    for (const ProfileSegment& s : sub.segments) corners.push_back(s.end.x);
    const double room = top - low;
    if (!(room > 0.02)) {
        c.refusal = "the boundary is less than 0.02 mm long in Z";
        return c;
    }
    choose_cycle_levels(c, op, top, low, corners, [&](double level0, double depth, double retract) {
        return linuxcnc_g72(Vec2{level0, outside}, sub, depth, retract);
    }, [&](double level0) { return turn_rough_at(outside, level0); });
    return c;
}
}  // namespace

TurnCycle turn_cycle(const TurnRoughOp& op) {
    if (op.direction == RoughDirection::x) return turn_cycle_along_x(op);
    const Profile& path = op.tip_boundary;
    TurnCycle c;
    c.path = op.path;
    c.output = op.output;
    c.profile = path;
    c.feed = op.feed;
    const double z_start = std::max(op.boundary.start.x, path.start.x) + op.approach;
    const Vec2 p0 = path.start;
    auto show = [](double v) { return number_text(v, 4); };
    if (op.bar_face && p0.x < *op.bar_face - 1e-9) {
        c.refusal = fmt::format("the boundary starts at Z {}, inside the bar whose face is at Z {}: the cycle comes down "
                                "to it in one line from its start point",
                                show(p0.x), show(*op.bar_face));
        return c;
    }
    // The start S beyond the part, at or below the bar's radius (in air: beyond the face), so
    // that the first level, S's radius, cuts no more than a pass; the levels go down from it
    // by I (at most depthOfCut). A level within 0.005 mm of a corner of the boundary is where the
    // control's cycle turns on its tolerances: another S (and I) is taken.
    std::vector<double> corners{p0.y};
    for (const ProfileSegment& s : path.segments) corners.push_back(s.end.y);
    const double room = op.stock_radius - p0.y;
    if (!(room > 0.02)) {
        c.refusal = "the bar is less than 0.02 mm above the boundary's start";
        return c;
    }
    choose_cycle_levels(c, op, op.stock_radius, p0.y, corners, [&](double level0, double depth, double retract) {
        return linuxcnc_g71(Vec2{z_start, level0}, path, depth, retract);
    }, [&](double level0) { return turn_rough_at(level0, z_start); });
    return c;
}

bool TurnRoughOp::whole_bar_over_boundary() const {
    if (material.r.empty() || tip_boundary.segments.empty()) return true;
    const double lo = std::min(tip_boundary.segments.back().end.x, boundary.segments.back().end.x);
    // Up to the bar's face as the earlier turn-faces left it (a face's stub is no level's).
    double hi = std::max(tip_boundary.start.x, boundary.start.x);
    if (bar_face) hi = std::min(hi, *bar_face);
    for (std::size_t i = 0; i < material.r.size(); ++i)
        if (material.z[i + 1] > lo && material.z[i] < hi && material.r[i] < stock_radius - 1e-6) return false;
    return true;
}

void expand(const TurnRoughOp& op, const Context& ctx, EventSink& sink) {
    if (op.direction == RoughDirection::x) {
        expand_along_x(op, ctx, sink);
        return;
    }
    const Profile& path = op.tip_boundary;
    const double z_start = std::max(op.boundary.start.x, path.start.x) + op.approach;  // where passes begin, beyond the part
    const double outside = op.stock_radius + op.approach;        // outside the bar
    sink.emit(Rapid{turn_rough_at(outside, ctx.job.clearance)});
    // The control roughs from its start point down, whatever earlier operations left (over what
    // they removed it cuts air); it comes down outside the bar beyond the part.
    if (op.output != CycleOutput::longhand && emit_turn_cycle(op, ctx, sink, outside, turn_rough_at(outside, z_start))) return;
    const bool from_material = !op.material.r.empty();
    const double inf = std::numeric_limits<double>::infinity();
    // The most there is to rough: the bar, or the most the earlier operations left from the
    // boundary's end up.
    const double top = from_material ? std::min(op.stock_radius, op.material.top(path.segments.back().end.x, inf))
                                     : op.stock_radius;
    // The levels: equal steps from the top down to the boundary's lowest point; the pass along
    // the boundary takes the last step.
    const int count = std::max(1, static_cast<int>(std::ceil((top - op.bottom) / op.depth_of_cut - 1e-9)));
    const double step = (top - op.bottom) / count;
    std::vector<double> levels;
    for (int k = 1; k < count; ++k) levels.push_back(top - step * k);
    const double lift = step > 1e-6 ? std::min(op.lift, step / 2) : op.lift;
    // Where a pass at level v comes in from air: approachDistance beyond the profile's start, or
    // beyond the earlier material at v (all of it above v lies below that Z).
    auto entry = [&](double v) { return from_material ? op.material.front(v) + op.approach : z_start; };
    // Where the tip is between passes: outside the bar, or lifted off the last pass at the Z it
    // came in at (air beyond it at that radius and above).
    Vec2 at{ctx.job.clearance, outside};
    auto rapid_to = [&](Vec2 p) {
        if (distance(p, at) > 0) sink.emit(Rapid{turn_rough_at(p.y, p.x)});
        at = p;
    };
    // In air to level v at Z e: along Z where the tip is (outside, or above what is left beyond
    // the higher of the two Zs), then down.
    auto come_in = [&](double v, double e) {
        if (at.y >= outside - 1e-12 || e > at.x) rapid_to({e, at.y});
        rapid_to({std::max(e, at.x), v});
        rapid_to({e, v});
    };
    double above = top;  // the level before (the top at first)
    for (double level : levels) {
        std::vector<TurnRoughSpan> spans;
        for (const TurnRoughSpan& s : turn_rough_spans(op, level)) {
            const bool open = s.hi >= path.start.x - 1e-9;
            // A span with nothing of the material above the level (or beyond the start, where
            // it is open) is in air: left out.
            if (!from_material || op.material.above(s.lo, open ? inf : s.hi, level)) spans.push_back(s);
        }
        for (const TurnRoughSpan& s : spans) {
            const bool open = s.hi >= path.start.x - 1e-9;
            const bool first = &s == &spans.front();
            // From air along the level: beyond the start, or beyond the material where it ends
            // within the span.
            const bool from_air = first && (open || (from_material && op.material.front(level) <= s.hi + 1e-9));
            double back_to = z_start;
            if (from_air) {
                const double e = entry(level);
                come_in(level, e);
                if (e > s.hi + 1e-9) sink.emit(Linear{turn_rough_at(level, s.hi), op.feed, Movement::cutting});
                back_to = e;
            } else {
                // A span between walls: over the part outside the bar, down the column the
                // passes above have cleared, feed in.
                if (at.y < outside - 1e-12) rapid_to({at.x, outside});
                rapid_to({s.hi, outside});
                rapid_to({s.hi, above + lift});
                sink.emit(Linear{turn_rough_at(level, s.hi), op.feed, Movement::plunge});
            }
            sink.emit(Linear{turn_rough_at(level, s.lo), op.feed, Movement::cutting});
            const double back = std::min(lift, s.hi - s.lo);
            sink.emit(Linear{turn_rough_at(level + lift, s.lo + back), op.feed, Movement::lead_out});
            at = {s.lo + back, level + lift};
            // Back above what this level has left: along it to where it came in, or out of the bar.
            if (from_air && spans.size() == 1) {
                rapid_to({back_to, level + lift});
            } else {
                rapid_to({s.lo + back, outside});
                rapid_to({z_start, outside});
            }
        }
        above = level;
    }
    // The last pass along the boundary: what the levels left in steps comes off, the allowances
    // stay.
    const Vec2 b0 = path.start;
    // From the earlier material: approachDistance beyond it at the start's radius, or beyond the
    // start where the material ends further in.
    double e_last = z_start;
    if (from_material) {
        e_last = op.material.front(b0.y) + op.approach;
        if (!(e_last > b0.x + 1e-6)) e_last = b0.x + op.approach;
    }
    come_in(b0.y, e_last);
    sink.emit(Linear{turn_rough_at(b0.y, b0.x), op.feed, Movement::lead_in});
    for (const ProfileSegment& s : path.segments) {
        if (s.centre)
            sink.emit(Arc{turn_rough_at(s.end.y, s.end.x), turn_rough_at(s.centre->y, s.centre->x), s.direction, Plane::xz,
                          op.feed, 0, Movement::cutting});
        else
            sink.emit(Linear{turn_rough_at(s.end.y, s.end.x), op.feed, Movement::cutting});
    }
    // Up the face at the profile's end to the bar, and off it.
    const Vec2 end = path.segments.back().end;
    if (end.y < op.stock_radius) sink.emit(Linear{turn_rough_at(op.stock_radius, end.x), op.feed, Movement::cutting});
    sink.emit(Linear{turn_rough_at(std::max(end.y, op.stock_radius) + lift, end.x + lift), op.feed, Movement::lead_out});
    sink.emit(Rapid{turn_rough_at(outside, end.x + lift)});
    sink.emit(Rapid{turn_rough_at(outside, ctx.job.clearance)});
}

std::string default_name(const TurnRoughOp& op) { return op.comment.empty() ? "turn rough" : op.comment; }

}  // namespace camgen
