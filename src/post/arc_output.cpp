// Arc output policy shared by every post: the arc-breaking rules (which arcs become lines or
// one straight move, how many pieces) and fitting an arc block to its rounded words.
#include "camgen/post/arc_output.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace camgen {

namespace {
using P2 = PlaneVec;
// The smallest value step of a format, in the unscaled input unit (0.001 mm for 3 decimals).
double grid_step(const nc::Format& f) { return std::pow(10.0, -f.spec().decimals) / f.spec().scale; }
}  // namespace


double effective_chord_tolerance(const ArcSettings& settings, std::optional<double> operation_tolerance) {
    if (settings.tolerance_mode == ChordToleranceMode::absolute || !operation_tolerance) return settings.chord_tolerance;
    return std::min(*operation_tolerance, settings.chord_tolerance);
}

namespace {
// Chords an arc of `radius` (mm) and `sweep` (radians) needs so that none strays more than
// `tolerance` (mm) from it: segments_for_tolerance without its cap, which would write a long
// helix off its circle without a word (0.49 mm off at 100 times the tolerance).
double chords_for_tolerance(double radius, double sweep, double tolerance) {
    if (radius <= 0.0 || sweep <= 0.0) return 1.0;
    const double max_step = tolerance >= radius ? std::numbers::pi : 2.0 * std::acos(1.0 - tolerance / radius);
    if (!(max_step > 0.0)) return std::numeric_limits<double>::infinity();
    return std::max(1.0, std::ceil(sweep / max_step - 1e-9));
}

std::int64_t as_count(double n) {
    return n >= 9e18 ? std::numeric_limits<std::int64_t>::max() : static_cast<std::int64_t>(n);
}
}  // namespace

std::int64_t segment_count(const ArcGeometry& arc, const ArcSettings& settings, double chord_tolerance) {
    constexpr std::int64_t most = max_arc_chords;
    const std::int64_t n = std::max(as_count(chords_for_tolerance(arc.radius, arc.sweep, chord_tolerance)),
                                    static_cast<std::int64_t>(settings.min_segments));
    if (n > most) return n;
    if (!settings.max_segment_length || chord_length(arc, static_cast<int>(n)) <= *settings.max_segment_length) return n;
    const double max_len = *settings.max_segment_length;
    // Beyond the limit a chord is the arc's length over the count, to a part in 10^14: the
    // count that length needs.
    if (chord_length(arc, static_cast<int>(most)) > max_len)
        return std::max(most + 1, as_count(std::ceil(arc_length(arc) / max_len)));
    // The chord shrinks as n grows (each step is at most 180 degrees here): find the least n
    // whose chord fits, doubling first and then halving the interval.
    std::int64_t lo = n, hi = n;
    while (chord_length(arc, static_cast<int>(hi)) > max_len) {
        lo = hi;
        hi = std::min(hi * 2, most);
    }
    while (hi - lo > 1) {
        std::int64_t mid = lo + (hi - lo) / 2;
        (chord_length(arc, static_cast<int>(mid)) > max_len ? lo : hi) = mid;
    }
    return hi;
}

bool written_as_one_line(const ArcGeometry& arc, const ArcSettings& settings) {
    return (settings.min_radius && arc.radius < *settings.min_radius) ||
           (settings.min_length && arc_length(arc) < *settings.min_length);
}

bool writes_arcs_in(const ArcSettings& settings, Plane plane) {
    return std::find(settings.planes.begin(), settings.planes.end(), plane) != settings.planes.end();
}

bool writes_helices(const ArcSettings& settings) { return settings.helical; }

ArcPlan plan_arc(const ArcGeometry& arc, const ArcSettings& settings, double chord_tolerance) {
    PlanePoint a = to_plane(arc.start, arc.plane), b = to_plane(arc.end, arc.plane);
    const bool helical = std::abs(b.w - a.w) > 1e-9;
    const double length = arc_length(arc);
    auto mm = [](double v) { return std::to_string(v); };
    if (written_as_one_line(arc, settings)) {
        if (settings.min_radius && arc.radius < *settings.min_radius)
            return {ArcTreatment::one_line, 1, "radius " + mm(arc.radius) + " mm is below minRadius"};
        return {ArcTreatment::one_line, 1, "length " + mm(length) + " mm is below minLength"};
    }
    auto lines = [&](std::string why) {
        return ArcPlan{ArcTreatment::lines, segment_count(arc, settings, chord_tolerance), std::move(why)};
    };
    if (!writes_arcs_in(settings, arc.plane)) return lines("plane not supported");
    if (helical && !writes_helices(settings)) return lines("helix not supported");
    if (settings.max_radius && arc.radius > *settings.max_radius)
        return lines("radius " + mm(arc.radius) + " mm is above maxRadius");
    double max_sweep = std::clamp(settings.max_sweep, 1.0, 360.0);
    // A radius word cannot say "full circle", and near 360 degrees it says "which one?".
    if (settings.format == ArcFormat::radius) max_sweep = std::min(max_sweep, 180.0);
    int pieces = static_cast<int>(std::ceil(arc.sweep / (max_sweep / deg_per_rad) - 1e-9));
    return {ArcTreatment::arcs, std::max(pieces, 1), ""};
}

ArcFit fit_arc_block(const ArcGeometry& piece, const Vec3& control_start, const ArcWordFormats& f) {
    ArcFit fit;
    fit.block = piece;
    const Plane plane = piece.plane;
    const double sign = piece.direction == ArcDirection::ccw ? 1.0 : -1.0;
    const double tol = f.tolerance;
    // The rounded ends alone may be half a grid step off in each axis, so the control's
    // midpoint is held to the tolerance plus that.
    const double mid_tol = tol + grid_step(f.xyz) * std::numbers::sqrt2 / 2.0;
    const PlanePoint s3 = to_plane(control_start, plane), e3 = to_plane(piece.end, plane), c3 = to_plane(piece.centre, plane);
    const P2 S{s3.u, s3.v};
    const P2 E{f.xyz.rounded(e3.u), f.xyz.rounded(e3.v)};
    const P2 C{c3.u, c3.v};
    const P2 M = in_plane(point_on_arc(piece, 0.5), plane);  // the intended midpoint
    const double end_w = f.xyz.rounded(e3.w);
    fit.control_end = from_plane({E.u, E.v, end_w}, plane);
    bool full = piece.sweep >= two_pi - 1e-9;
    const double chord = norm(E - S);
    if (chord < 1e-9 && !full) {
        // The rounded ends coincide: a control reads a full circle. Only a nearly full arc
        // may be written as one; a small one is a straight move.
        if (piece.sweep <= std::numbers::pi) {
            fit.result = ArcFitResult::degenerate;
            return fit;
        }
        full = true;
    }
    if (full && chord >= 1e-9) {
        fit.result = ArcFitResult::no_fit;
        return fit;
    }
    const P2 mid_chord = (S + E) * 0.5;
    const P2 left = chord < 1e-9 ? P2{} : P2{-(E - S).v, (E - S).u} * (1.0 / chord);
    // The centre on the perpendicular bisector of the rounded ends nearest the true centre.
    const P2 C_bisector = full ? C : mid_chord + left * dot(C - mid_chord, left);

    // How the control runs an arc from S about `c` by `sweep` (or to E): its midpoint's
    // distance from the intended midpoint.
    auto mid_error = [&](P2 c, double sweep) {
        P2 m = c + rotate(S - c, sign * sweep / 2.0);
        return norm(m - M);
    };
    auto sweep_to_end = [&](P2 c) {
        if (full) return two_pi;
        P2 a = S - c, b = E - c;
        double s = sign * (std::atan2(b.v, b.u) - std::atan2(a.v, a.u));
        while (s <= 0.0) s += two_pi;
        while (s > two_pi) s -= two_pi;
        return s;
    };
    double best = std::numeric_limits<double>::infinity();
    auto accept = [&](P2 c, double radius, double sweep, P2 end, double score) {
        // A half circle whose centre word rounds off the chord reads wider than 180 degrees
        // (180.029 on kosy: a fuzz finding); the reader allows the same slack as here.
        const double widest = (std::min(f.max_sweep, 360.0) + 1e-3) / deg_per_rad + grid_step(f.xyz) / radius;
        if (!full && sweep > widest) return;
        if (score >= best) return;
        best = score;
        fit.block.start = from_plane({S.u, S.v, s3.w}, plane);
        fit.block.centre = from_plane({c.u, c.v, c3.w}, plane);
        fit.block.radius = radius;
        fit.block.sweep = sweep + (piece.sweep >= two_pi + 1e-9 ? piece.sweep - two_pi : 0.0);
        fit.block.start_angle = std::atan2(S.v - c.v, S.u - c.u);
        fit.control_end = from_plane({end.u, end.v, end_w}, plane);
    };

    // Each form: first the words as plain rounding gives them; only when those leave the
    // circle, the neighbouring values around the best centre for the rounded ends.
    switch (f.form) {
        case ArcFormat::ijk_relative:
        case ArcFormat::ijk_absolute: {
            const double step = grid_step(f.ijk);
            const bool relative = f.form == ArcFormat::ijk_relative;
            auto candidate = [&](P2 w) {
                P2 c = relative ? S + w : w;
                double rs = norm(S - c), re = norm(E - c);
                if (f.ijk.is_zero(rs) || f.ijk.is_zero(re)) return;
                double radius_error = std::abs(rs - re), sweep = sweep_to_end(c);
                // With unequal radii a control runs a spiral: halfway it is at the mean radius.
                double m_error = norm(c + rotate(S - c, sign * sweep / 2.0) * ((rs + re) / (2.0 * rs)) - M);
                if (radius_error > tol || m_error > mid_tol) return;
                accept(c, rs, sweep, E, radius_error + m_error);
            };
            const P2 plain = relative ? C - S : C;
            candidate({f.ijk.rounded(plain.u), f.ijk.rounded(plain.v)});
            if (std::isfinite(best)) break;
            const P2 base = relative ? C_bisector - S : C_bisector;
            for (int i = -1; i <= 1; ++i)
                for (int j = -1; j <= 1; ++j) candidate({f.ijk.rounded(base.u + i * step), f.ijk.rounded(base.v + j * step)});
            break;
        }
        case ArcFormat::radius: {
            if (full) break;
            const double step = grid_step(f.xyz);
            const double h = chord / 2.0;
            // Positive R: the control takes the short way round; negative: the long way.
            const double side = (sign > 0) == (piece.sweep <= std::numbers::pi) ? 1.0 : -1.0;
            auto candidate = [&](double r) {
                if (f.xyz.is_zero(r)) return;
                double d2 = r * r - h * h;
                if (d2 < -1e-12) return;  // the control would stop: radius too small
                P2 c = mid_chord + left * (side * std::sqrt(std::max(d2, 0.0)));
                double sweep = sweep_to_end(c), m_error = mid_error(c, sweep);
                if (m_error > mid_tol) return;
                accept(c, r, sweep, E, m_error);
            };
            candidate(f.xyz.rounded(piece.radius));
            if (std::isfinite(best)) break;
            for (int k = -1; k <= 1; ++k) candidate(f.xyz.rounded(norm(S - C_bisector) + k * step));
            break;
        }
        case ArcFormat::nccad_angle: {
            if (full) break;
            const double step = grid_step(f.ijk), d_step = grid_step(f.angle);
            auto candidate = [&](double d, P2 w) {
                if (f.angle.is_zero(d) || d > 180.0 || f.ijk.is_zero(norm(w))) return;
                double sweep = d / deg_per_rad;
                P2 c = S + w;
                P2 end = c + rotate(S - c, sign * sweep);
                double end_error = norm(end - E), m_error = mid_error(c, sweep);
                if (end_error > tol || m_error > mid_tol) return;
                accept(c, norm(w), sweep, end, end_error + m_error);
            };
            const double d0 = f.angle.rounded(piece.sweep * deg_per_rad);
            if (f.angle.is_zero(d0)) {
                fit.result = ArcFitResult::degenerate;
                return fit;
            }
            candidate(d0, {f.ijk.rounded(C.u - S.u), f.ijk.rounded(C.v - S.v)});
            if (std::isfinite(best)) break;
            for (int k = -1; k <= 1; ++k) {
                double d = f.angle.rounded(d0 + k * d_step);
                // The centre of the arc from S to E that sweeps exactly D.
                P2 c_d = mid_chord + left * (sign * chord / (2.0 * std::tan(d / deg_per_rad / 2.0)));
                for (int i = -1; i <= 1; ++i)
                    for (int j = -1; j <= 1; ++j)
                        candidate(d, {f.ijk.rounded(c_d.u - S.u + i * step), f.ijk.rounded(c_d.v - S.v + j * step)});
            }
            break;
        }
    }
    if (!std::isfinite(best)) {
        fit.result = ArcFitResult::no_fit;
        fit.block = piece;
    }
    return fit;
}

}  // namespace camgen
