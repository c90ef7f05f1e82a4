#include "camgen/operations/fanuc_finish.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/geometry/lathe_cycle.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"
#include "camgen/operations/turn_rough/turn_rough.hpp"

namespace camgen {

namespace {

bool fanuc_finish_same_profile(const Profile& a, const Profile& b) {
    if (a.segments.size() != b.segments.size() || distance(a.start, b.start) > 1e-9) return false;
    for (std::size_t k = 0; k < a.segments.size(); ++k) {
        const ProfileSegment& s = a.segments[k];
        const ProfileSegment& t = b.segments[k];
        if (distance(s.end, t.end) > 1e-9 || s.centre.has_value() != t.centre.has_value()) return false;
        if (s.centre && (distance(*s.centre, *t.centre) > 1e-9 || s.direction != t.direction)) return false;
    }
    return true;
}

// Distance from p to the segment a-b.
double fanuc_finish_to_segment(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 d = b - a;
    const double len2 = d.x * d.x + d.y * d.y;
    double t = len2 > 0 ? ((p.x - a.x) * d.x + (p.y - a.y) * d.y) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return distance(p, a + d * t);
}

// The moves of the linked cycle against the rough's own, in Fanuc's pattern: equal within 0.001
// mm but for the rapid to A', which the allowance moves `shift` beyond (in air beyond A).
std::optional<std::string> fanuc_finish_moves_differ(const std::vector<LatheCycleMove>& linked,
                                                     const std::vector<LatheCycleMove>& own, Vec2 shift) {
    if (linked.size() != own.size())
        return fmt::format("it would make {} moves, not the turn-rough's {}", linked.size(), own.size());
    // Moves: a rapid to A, four per level (from A's Z), the rapid to A', the shape, the rapid back to A.
    std::size_t levels = 0;
    for (std::size_t n = 1; n + 3 < own.size(); n += 4) {
        if (own[n].kind == LatheCycleMove::Kind::rapid && own[n + 1].kind == LatheCycleMove::Kind::feed &&
            own[n + 2].kind == LatheCycleMove::Kind::rapid && own[n + 3].kind == LatheCycleMove::Kind::rapid &&
            std::abs(own[n].end.x - own[0].end.x) < 1e-9)
            ++levels;
        else
            break;
    }
    const std::size_t to_a_prime = 1 + 4 * levels;
    for (std::size_t n = 0; n < own.size(); ++n) {
        const LatheCycleMove& a = linked[n];
        const LatheCycleMove& b = own[n];
        const Vec2 end = n == to_a_prime ? a.end - shift : a.end;
        double off = distance(end, b.end);
        if (a.kind == LatheCycleMove::Kind::arc) off = std::max(off, distance(a.centre, b.centre));
        if (a.kind != b.kind || off > 0.001)
            return fmt::format("its move {} would run {} mm from the turn-rough's", n + 1, number_text(off, 4));
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> fanuc_g70_air(const Profile& profile, Vec2 start, const Profile& written_shape, double nose,
                                         Vec2 tip_offset) {
    // The kept material: under the profile between its ends, and (conservatively) everything
    // beyond its end towards the chuck. Its boundary as a polyline, arcs within 0.0005 mm.
    const std::vector<Vec2> line = sample_profile(profile, 0.0005);
    const double z_start = profile.start.x, z_end = profile.segments.back().end.x;
    auto radius_at = [&](double z) {
        double r = -std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k + 1 < line.size(); ++k) {
            const Vec2 a = line[k], b = line[k + 1];
            const double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
            if (z < lo - 1e-12 || z > hi + 1e-12) continue;
            if (hi - lo < 1e-12) r = std::max({r, a.y, b.y});
            else r = std::max(r, a.y + (z - a.x) * (b.y - a.y) / (b.x - a.x));
        }
        return r;
    };
    const Vec2 end = line.back();
    // How far the nose centre c is outside the material (negative: inside).
    auto clearance_of = [&](Vec2 c) {
        if (c.x > z_start + 1e-9) {
            double d = std::numeric_limits<double>::infinity();
            for (std::size_t k = 0; k + 1 < line.size(); ++k) d = std::min(d, fanuc_finish_to_segment(c, line[k], line[k + 1]));
            return d;
        }
        if (c.x < z_end - 1e-9) return -1.0;
        const bool inside = c.y < radius_at(c.x) - 1e-9;
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k + 1 < line.size(); ++k) d = std::min(d, fanuc_finish_to_segment(c, line[k], line[k + 1]));
        // The end face of what lies beyond the profile's end, up from its end.
        d = std::min(d, c.y >= end.y ? std::abs(c.x - z_end) : distance(c, end));
        return inside ? -d : d;
    };
    auto check = [&](Vec2 from, Vec2 to, const char* what) -> std::optional<std::string> {
        const int steps = 400;
        for (int k = 0; k <= steps; ++k) {
            const Vec2 tip = from + (to - from) * (static_cast<double>(k) / steps);
            const Vec2 centre = tip - tip_offset;
            if (clearance_of(centre) < nose - 1e-4)
                return fmt::format("G70's rapid {} would run the finishing tool into the finished part near Z {} X {} "
                                   "(radius)",
                                   what, number_text(tip.x, 3), number_text(tip.y, 3));
        }
        return std::nullopt;
    };
    if (auto bad = check(start, written_shape.start, "from the start point down to the shape's first block")) return bad;
    return check(written_shape.segments.back().end, start, "from the shape's end back to the start point");
}

void link_fanuc_finishing(Job& job, const JobInput& in) {
    for (std::size_t i = 0; i < job.operations.size(); ++i) {
        auto* f = std::get_if<TurnProfileOp>(&job.operations[i]);
        if (!f || f->output == CycleOutput::longhand) continue;
        auto* r = i > 0 ? std::get_if<TurnRoughOp>(&job.operations[i - 1]) : nullptr;
        if (!r || !fanuc_finish_same_profile(r->profile, f->profile)) {
            if (f->output == CycleOutput::canned)
                json::fail(in.source(), f->path + "/output",
                           "a turn-profile is canned as Fanuc's G70, which finishes the shape of the turn-rough right "
                           "before it: the operation before this one is not a turn-rough of the same profile (start and "
                           "path); use \"auto\" or \"longhand\"");
            continue;
        }
        TurnProfileOp::FinishLink link;
        link.rough_path = r->path;
        link.along_x = r->direction == RoughDirection::x;
        const TurnCycle c = turn_cycle(*r);
        if (!c.refusal) link.start = fanuc_g71_start(c);
        const auto show = [](double v) { return number_text(v, 4); };
        const Profile& shape = f->tip_path.segments.empty() ? f->profile : f->tip_path;
        const Vec2 allowance{r->allowance_z, r->allowance_x};
        if (link.along_x) {
            link.refusal = "the turn-rough before it roughs along X (G72), whose shape runs from the end face towards the "
                           "start: G70 would run the finishing pass backwards";
        } else if (r->output == CycleOutput::longhand) {
            link.refusal = "the turn-rough before it is written longhand (\"output\": \"longhand\")";
        } else if (c.refusal) {
            link.refusal = "the turn-rough before it is not written as a roughing cycle: " + *c.refusal;
        } else if (r->output == CycleOutput::automatic && !r->whole_bar_over_boundary()) {
            link.refusal = "the turn-rough before it roughs from what earlier operations left, not as a cycle";
        } else if (f->compensation == NoseCompensation::control) {
            link.refusal = "its compensation is control (G42): G70 runs the roughing cycle's shape as written, without "
                           "the control's nose compensation (use computer or none)";
        } else if (f->feed_mode != r->feed_mode) {
            link.refusal = "it and the turn-rough before it feed in different modes (per minute, per revolution): G70 "
                           "takes the shape's F in the mode the program is in";
        } else {
            const LatheCycleAxis axis = LatheCycleAxis::z;
            const LatheCycleModel own = fanuc_g7x(axis, link.start, fanuc_g7x_shape(axis, link.start, c.profile), c.depth, c.retract);
            const Profile written = fanuc_g7x_shape(axis, link.start, shape);
            const LatheCycleModel linked = fanuc_g7x(axis, link.start, written, c.depth, c.retract, allowance);
            const auto tools = [&] {
                return fmt::format("the turn-rough's tool has nose radius {} (compensation {}), this one's {} (compensation "
                                   "{}); G71 roughs to this pass's tip path moved by the allowances, the turn-rough to "
                                   "its own tip path, and the two are one only where both tips run the profile itself "
                                   "(sharp noses or compensation none on both: a nose rolls round the profile's end onto "
                                   "the face up to the bar in the rough, and stops a nose radius short of the end in the "
                                   "finishing)",
                                   show(r->nose_radius), name_of(nose_compensation_modes, r->compensation), show(f->nose_radius),
                                   name_of(nose_compensation_modes, f->compensation));
            };
            if (own.refusal) {
                link.refusal = "Fanuc's G71 does not take the turn-rough's passes: " + *own.refusal;
            } else if (linked.refusal) {
                link.refusal = "G71 on this pass's tip path moved by the allowances: " + *linked.refusal + "; " + tools();
            } else if (auto differ = fanuc_finish_moves_differ(linked.moves, own.moves, Vec2{allowance.x, 0.0})) {
                link.refusal = "G71 on this pass's tip path moved by the allowances would not cut the turn-rough's passes (" +
                               *differ + "): " + tools();
            } else {
                const Vec2 tip_offset = lathe_tip_offset(f->orientation > 0 ? f->orientation : 2, f->nose_radius);
                if (auto air = fanuc_g70_air(f->profile, link.start, written, f->nose_radius, tip_offset))
                    link.refusal = *air;
            }
        }
        if (!link.refusal)
            r->finish = CycleFinish{f->path, shape, allowance, f->feed, f->rpm};
        f->g70 = link;
    }
}

}  // namespace camgen
