#include "camgen/geometry/compensation.hpp"
#include "camgen/geometry/vec.hpp"

#include <cmath>
#include <numbers>

namespace camgen {

namespace {

constexpr double half_pi = pi / 2;
// The angle within which two directions count as one (LinuxCNC's TOLERANCE_CONCAVE_CORNER), rad.
constexpr double corner_tolerance = 0.05;
// How much further a moved arc may turn than programmed (LinuxCNC, mm programs), rad.
constexpr double arc_growth_tolerance = 0.0254;

Vec2 xy(Vec3 p) { return {p.x, p.y}; }
Vec2 polar(double r, double a) { return {r * std::cos(a), r * std::sin(a)}; }
double angle_of(Vec2 from, Vec2 to) { return std::atan2(to.y - from.y, to.x - from.x); }
// LinuxCNC's turn: +1 counter-clockwise, -1 clockwise, more for extra turns.
int turn_of(ArcDirection d, int turns) { return d == ArcDirection::ccw ? 1 + turns : -1 - turns; }
bool tool_inside_arc(CompSide side, int turn) {
    return (side == CompSide::left && turn > 0) || (side == CompSide::right && turn < 0);
}

}  // namespace

double arc_sweep(Vec2 from, Vec2 centre, ArcDirection direction, int turns, Vec2 to) {
    const int turn = turn_of(direction, turns);
    double alpha = std::atan2(from.y - centre.y, from.x - centre.x);
    double beta = std::atan2(to.y - centre.y, to.x - centre.x);
    if (turn > 0) {
        if (beta <= alpha) beta += 2 * pi;
        return beta - alpha + (turn - 1) * 2 * pi;
    }
    if (alpha <= beta) alpha += 2 * pi;
    return beta - alpha + (turn + 1) * 2 * pi;
}

void CutterCompensation::set_position(Vec3 p) {
    flush();
    tool_ = programmed_ = p;
    known_ = true;
}

std::optional<CompError> CutterCompensation::on(CompSide side, double radius, std::size_t source) {
    if (side == CompSide::off) return off(source);
    if (side_ != CompSide::off) return CompError{"Cannot turn cutter radius comp on when already on", source};
    side_ = side;
    radius_ = std::abs(radius);
    first_ = true;
    return std::nullopt;
}

std::optional<CompError> CutterCompensation::off(std::size_t source) {
    if (side_ != CompSide::off && radius_ > 0 && !first_) {
        if (auto e = move_endpoint_and_flush(xy(tool_), source)) return e;
        dequeue();
        programmed_ = tool_;  // the next move starts from where the tool is
        arc_not_allowed_ = true;
    }
    side_ = CompSide::off;
    first_ = true;
    return std::nullopt;
}

void CutterCompensation::flush() { dequeue(); }

void CutterCompensation::dequeue() {
    endpoint_valid_ = false;
    for (const Queued& q : queue_) sink_(q.move);
    queue_.clear();
}

void CutterCompensation::enqueue(const CompMove& m, Vec2 direction, double original_sweep) {
    queue_.push_back({m, direction, original_sweep});
}

std::optional<CompError> CutterCompensation::move_endpoint_and_flush(Vec2 to, std::size_t source) {
    for (Queued& q : queue_) {
        if (q.move.kind == CompMove::Kind::arc) {
            const double r1 = distance(xy(q.move.end), q.move.centre);
            const double r2 = distance(to, q.move.centre);
            const double sweep = arc_sweep(endpoint_, q.move.centre, q.move.direction, q.move.turns, to);
            if (std::abs(r1 - r2) > 0.01)
                return CompError{"cutter compensation made an arc whose ends are not on one circle", source};
            if (q.original_sweep != 0.0 && endpoint_valid_ && std::abs(sweep) > std::abs(q.original_sweep) + arc_growth_tolerance)
                return CompError{"Arc move in concave corner cannot be reached by the tool without gouging", source};
        } else {
            const double dot = q.direction.x * (to.x - endpoint_.x) + q.direction.y * (to.y - endpoint_.y);
            if (endpoint_valid_ && dot < 0)
                return CompError{q.move.kind == CompMove::Kind::rapid
                                     ? "Straight traverse in concave corner cannot be reached by the tool without gouging"
                                     : "Straight feed in concave corner cannot be reached by the tool without gouging",
                                 source};
        }
        q.move.end.x = to.x;
        q.move.end.y = to.y;
    }
    dequeue();
    endpoint_ = to;
    endpoint_valid_ = true;
    return std::nullopt;
}

std::optional<CompError> CutterCompensation::move(const CompMove& p) {
    if (!known_) {
        // The first move of a program: the tool is taken to be at its end (a reader's start).
        if (side_ != CompSide::off) return CompError{"a move under cutter compensation from an unknown position", p.source};
        sink_(p);
        tool_ = programmed_ = p.end;
        known_ = true;
        return std::nullopt;
    }
    if (side_ == CompSide::off || radius_ <= 0) {
        if (arc_not_allowed_ && p.kind == CompMove::Kind::arc)
            return CompError{"The move just after exiting cutter compensation mode must be straight, not an arc", p.source};
        arc_not_allowed_ = false;
        sink_(p);
        tool_ = programmed_ = p.end;
        return std::nullopt;
    }
    if (first_) return entry(p);
    return p.kind == CompMove::Kind::arc ? arc(p) : straight(p);
}

std::optional<CompError> CutterCompensation::entry(const CompMove& p) {
    if (p.kind == CompMove::Kind::arc) {
        if (distance(xy(tool_), xy(p.end)) <= radius_)
            return CompError{"Radius of cutter compensation entry arc is not greater than the tool radius", p.source};
        return CompError{"an arc as the first move after G41/G42 (LinuxCNC runs it; write a straight entry move)",
                         p.source, true};
    }
    const Vec2 c = xy(tool_), e = xy(p.end);
    if (distance(c, e) <= radius_)
        return CompError{"Length of cutter compensation entry move is not greater than the tool radius", p.source};
    const double alpha = angle_of(c, e) + (side_ == CompSide::left ? half_pi : -half_pi);
    const Vec2 end = e + polar(radius_, alpha);
    endpoint_ = c;
    endpoint_valid_ = true;
    CompMove m = p;
    m.end = {end.x, end.y, p.end.z};
    enqueue(m, polar(1, alpha), 0);
    first_ = false;
    tool_ = m.end;
    programmed_ = p.end;
    return std::nullopt;
}

std::optional<CompError> CutterCompensation::straight(const CompMove& p) {
    const Vec2 c = xy(tool_), op = xy(programmed_), pe = xy(p.end);
    const double r = radius_;
    if (pe == op) {  // no XY motion: waits with the move before it
        CompMove m = p;
        m.end = {c.x, c.y, p.end.z};
        enqueue(m, {0, 0}, 0);
        tool_ = m.end;
        programmed_ = p.end;
        return std::nullopt;
    }
    double theta = angle_of(op, c);
    double alpha = angle_of(op, pe);
    double beta = 0, gamma = 0;
    if (side_ == CompSide::left) {
        if (theta < alpha) theta += 2 * pi;
        beta = theta - alpha - half_pi;
        gamma = half_pi;
    } else {
        if (alpha < theta) alpha += 2 * pi;
        beta = alpha - theta - half_pi;
        gamma = -half_pi;
    }
    const Vec2 end = pe + polar(r, alpha + gamma);
    Vec2 mid = op + polar(r, alpha + gamma);
    const bool front_arc = !queue_.empty() && queue_.front().move.kind == CompMove::Kind::arc;
    bool concave = false;
    if (beta < -corner_tolerance || beta > pi + corner_tolerance) {
        concave = true;
    } else if (beta > pi - corner_tolerance && front_arc) {
        const int turn = turn_of(queue_.front().move.direction, queue_.front().move.turns);
        concave = (side_ == CompSide::right && turn > 0) || (side_ == CompSide::left && turn < 0);
    }
    if (!concave && beta > corner_tolerance) {  // convex: around the corner
        if (auto e = move_endpoint_and_flush(c, p.source)) return e;
        CompMove corner;
        corner.source = p.source;
        corner.end = {mid.x, mid.y, tool_.z};
        if (p.kind == CompMove::Kind::rapid) {
            corner.kind = CompMove::Kind::rapid;
        } else {
            corner.kind = CompMove::Kind::arc;
            corner.centre = op;
            corner.direction = side_ == CompSide::left ? ArcDirection::cw : ArcDirection::ccw;
        }
        enqueue(corner, {0, 0}, 0);
        dequeue();
        endpoint_ = mid;
        endpoint_valid_ = true;
    } else if (concave) {
        if (!front_arc) {  // line to line: back along the previous move
            const double halfcorner = (beta + pi) / 2;
            if (halfcorner == 0.0) return CompError{"Zero degree inside corner is invalid for cutter compensation", p.source};
            const double retreat = r / std::tan(halfcorner);
            mid = c + polar(retreat, theta + gamma);
        } else {  // arc to line
            const Queued& prev = queue_.front();
            const double oldrad = distance(prev.move.centre, xy(prev.move.end));
            const int prev_turn = turn_of(prev.move.direction, prev.move.turns);
            const double base = angle_of(op, pe);
            const double th = prev_turn > 0 ? base + half_pi : base - half_pi;
            const double phi = angle_of(op, prev.move.centre);
            const bool inside = tool_inside_arc(side_, prev_turn);
            const double oldrad_uncomp = inside ? oldrad + r : oldrad - r;
            const double d = oldrad_uncomp * std::cos(th - phi);
            const double l = (inside ? d - r : d + r) / oldrad;
            if (l > 1.0 || l < -1.0)
                return CompError{"Arc to straight motion makes a corner the compensated tool can't fit in without gouging", p.source};
            double angle = 0;
            if (inside)
                angle = prev_turn > 0 ? -std::acos(l) + th + pi : std::acos(l) + th + pi;
            else
                angle = prev_turn > 0 ? std::acos(l) + th + pi : -std::acos(l) + th + pi;
            mid = prev.move.centre + polar(oldrad, angle);
        }
        if (auto e = move_endpoint_and_flush(mid, p.source)) return e;
    } else {  // straight on
        dequeue();
        endpoint_ = c;
        endpoint_valid_ = true;
    }
    CompMove m = p;
    m.end = {end.x, end.y, p.end.z};
    enqueue(m, {pe.x - op.x, pe.y - op.y}, 0);
    tool_ = m.end;
    programmed_ = p.end;
    return std::nullopt;
}

std::optional<CompError> CutterCompensation::arc(const CompMove& p) {
    const Vec2 c = xy(tool_), op = xy(programmed_), pe = xy(p.end), centre = p.centre;
    const double r = radius_;
    const int turn = turn_of(p.direction, p.turns);
    const double arc_radius = distance(centre, pe);
    double theta = angle_of(op, c);
    theta = side_ == CompSide::left ? theta - half_pi : theta + half_pi;
    double delta = angle_of(op, centre);
    const double alpha = turn > 0 ? delta - half_pi : delta + half_pi;
    double beta = side_ == CompSide::left ? theta - alpha : alpha - theta;
    beta = beta > 1.5 * pi ? beta - 2 * pi : beta < -half_pi ? beta + 2 * pi : beta;
    const bool inside = tool_inside_arc(side_, turn);
    double gamma = 0;
    if (inside) {
        gamma = angle_of(pe, centre);
        if (arc_radius <= r) return CompError{"Tool radius not less than arc radius with comp", p.source};
    } else {
        gamma = angle_of(centre, pe);
        delta += pi;
    }
    const Vec2 new_end = pe + polar(r, gamma);
    const double sweep = arc_sweep(op, centre, p.direction, p.turns, pe);
    const bool front_arc = !queue_.empty() && queue_.front().move.kind == CompMove::Kind::arc;
    CompMove m = p;
    m.end = {new_end.x, new_end.y, p.end.z};
    if (beta < -corner_tolerance || beta > pi + corner_tolerance || (std::abs(beta - pi) < corner_tolerance && !inside)) {
        Vec2 mid;
        if (!front_arc) {  // line to arc
            const double cy = arc_radius * std::sin(beta - half_pi);
            const double from_centre = inside ? arc_radius - r : arc_radius + r;
            const double l = (inside ? cy + r : cy - r) / from_centre;
            if (l > 1.0 || l < -1.0)
                return CompError{"Arc move in concave corner cannot be reached by the tool without gouging", p.source};
            double angle = 0;
            if (inside)
                angle = turn > 0 ? theta + std::asin(l) : theta - std::asin(l);
            else
                angle = turn > 0 ? theta + pi - std::asin(l) : theta + pi + std::asin(l);
            mid = centre + polar(from_centre, angle);
        } else {  // arc to arc
            const Queued& prev = queue_.front();
            const double oldrad = distance(prev.move.centre, xy(prev.move.end));
            const double newrad = inside ? arc_radius - r : arc_radius + r;
            const double arc_cc = distance(prev.move.centre, centre);
            if (oldrad == 0 || arc_cc == 0) return CompError{"Arc to arc motion is invalid because the arcs have the same center", p.source};
            const double a = (oldrad * oldrad + arc_cc * arc_cc - newrad * newrad) / (2 * oldrad * arc_cc);
            if (a > 1.0 || a < -1.0)
                return CompError{"Arc to arc motion makes a corner the compensated tool can't fit in without gouging", p.source};
            const double pullback = std::acos(a);
            const double cc_dir = angle_of(prev.move.centre, centre);
            const int prev_turn = turn_of(prev.move.direction, prev.move.turns);
            double dir = 0;
            if (tool_inside_arc(side_, prev_turn))
                dir = turn > 0 ? cc_dir + pullback : cc_dir - pullback;
            else
                dir = turn > 0 ? cc_dir - pullback : cc_dir + pullback;
            mid = prev.move.centre + polar(oldrad, dir);
        }
        if (auto e = move_endpoint_and_flush(mid, p.source)) return e;
        enqueue(m, {0, 0}, sweep);
    } else if (beta > corner_tolerance) {  // convex: around the corner, then the arc
        const Vec2 mid = op + polar(r, delta);
        dequeue();
        CompMove corner;
        corner.kind = CompMove::Kind::arc;
        corner.source = p.source;
        corner.end = {mid.x, mid.y, tool_.z};
        corner.centre = op;
        corner.direction = side_ == CompSide::left ? ArcDirection::cw : ArcDirection::ccw;
        enqueue(corner, {0, 0}, 0);
        dequeue();
        endpoint_ = mid;
        endpoint_valid_ = true;
        enqueue(m, {0, 0}, sweep);
    } else {
        dequeue();
        endpoint_ = c;
        endpoint_valid_ = true;
        enqueue(m, {0, 0}, sweep);
    }
    tool_ = m.end;
    programmed_ = p.end;
    return std::nullopt;
}

Vec2 lathe_tip_offset(int orientation, double radius) {
    Vec2 d{0.0, 0.0};
    if (orientation == 2 || orientation == 6 || orientation == 1) d.y = -radius;
    if (orientation == 3 || orientation == 8 || orientation == 4) d.y = radius;
    if (orientation == 2 || orientation == 7 || orientation == 3) d.x = -radius;
    if (orientation == 1 || orientation == 5 || orientation == 4) d.x = radius;
    return d;
}

std::string lathe_tip_words(int orientation) {
    const Vec2 d = lathe_tip_offset(orientation, 1.0);
    if (d.x == 0.0 && d.y == 0.0) return "tip at the nose centre";
    std::string s = "tip at";
    if (d.y != 0.0) s += d.y > 0 ? " +X" : " -X";
    if (d.x != 0.0) s += d.x > 0 ? " +Z" : " -Z";
    return s + " of the nose centre";
}

int fanuc_tip_number(int orientation) {
    switch (orientation) {
        case 1: return 4;
        case 2: return 3;
        case 3: return 2;
        case 4: return 1;
        case 6: return 8;
        case 8: return 6;
        default: return orientation;
    }
}

}  // namespace camgen
