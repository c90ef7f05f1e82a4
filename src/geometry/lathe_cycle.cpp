#include "camgen/geometry/lathe_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "camgen/geometry/vec.hpp"

namespace camgen {

namespace {

// One element of the cycle's path in (Z, radius): the line from the start point down to the
// profile's start first, then the profile's, then the closing face.
struct G71Element {
    Vec2 a, b;
    bool arc = false;
    Vec2 c;
    bool ccw = false;
};

double g71_cross(Vec2 u, Vec2 v) { return u.x * v.y - u.y * v.x; }

// A length for a message: at most 4 decimals, no trailing zeros, no -0.
std::string g71_number(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%.4f", v);
    std::string s = text;
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    return s == "-0" ? "0" : s;
}

// Where an element meets the level (radius) x: the Z of the meeting points in the order the
// control finds them (a level element gives both its ends).
std::vector<double> g71_meets(const G71Element& e, double x) {
    std::vector<double> out;
    if (!e.arc) {
        if (std::min(e.a.y, e.b.y) > x + 1e-6 || std::max(e.a.y, e.b.y) < x - 1e-6) return out;
        if (std::abs(e.a.y - e.b.y) < 1e-6) {
            out.push_back(e.a.x);
            out.push_back(e.b.x);
        } else {
            out.push_back((x - e.a.y) / (e.b.y - e.a.y) * (e.b.x - e.a.x) + e.a.x);
        }
        return out;
    }
    const double r = distance(e.a, e.c);
    double s = -(x - r - e.c.y) * (x + r - e.c.y);
    if (s < -1e-6) return out;
    s = std::sqrt(std::max(0.0, s));
    // On the arc: not before its start nor beyond its end, turning its way (within 1e-6).
    auto on = [&](Vec2 p) {
        const double from_start = g71_cross(e.a - e.c, p - e.c), to_end = g71_cross(e.b - e.c, p - e.c);
        return e.ccw ? from_start >= -1e-6 && to_end <= 1e-6 : from_start <= 1e-6 && to_end >= -1e-6;
    };
    if (on(Vec2{e.c.x + s, x})) out.push_back(e.c.x + s);
    if (on(Vec2{e.c.x - s, x})) out.push_back(e.c.x - s);
    return out;
}

class G71Run {
public:
    G71Run(std::vector<G71Element> elements, double start_level, double depth, double retract)
        : el_(std::move(elements)), start_level_(start_level), depth_(depth), retract_(retract) {}

    std::vector<LatheCycleMove> moves;
    std::optional<std::string> refusal;

    void to(LatheCycleMove::Kind kind, Vec2 end) {
        if (++count_ > 2000000) throw std::string("the cycle makes more than 2000000 moves");
        if (!moves.empty() && distance(moves.back().end, end) < 1e-9) return;
        if (moves.empty() && distance(origin, end) < 1e-9) return;
        moves.push_back({kind, end, {}, ArcDirection::ccw});
    }
    void arc_to(const G71Element& e, Vec2 end) {
        if (++count_ > 2000000) throw std::string("the cycle makes more than 2000000 moves");
        moves.push_back({LatheCycleMove::Kind::arc, end, e.c, e.ccw ? ArcDirection::ccw : ArcDirection::cw});
    }
    Vec2 origin;

    // Down element p towards level x: false when it moved (or stays), true when p does not go
    // down from where the tool is.
    bool dive(std::size_t p, Vec2& at, double x, bool fast) {
        const G71Element& e = el_[p];
        const auto kind = fast ? LatheCycleMove::Kind::rapid : LatheCycleMove::Kind::feed;
        if (!e.arc) {
            if (e.a.y <= e.b.y) return true;
            if (x < e.b.y) {
                to(kind, e.b);
                at = e.b;
                return false;
            }
            const std::vector<double> m = g71_meets(e, x);
            if (m.empty()) throw std::string("a level beyond the element it dives along");
            at = Vec2{m.front(), x};
            to(kind, at);
            return false;
        }
        if (distance(at, e.b) < 1e-3) return false;
        const std::vector<double> m = g71_meets(e, x);
        if (e.ccw) {
            if (at.x > e.c.x) return true;
            if (m.empty() || m.back() > e.c.x) {
                arc_to(e, e.b);
                at = e.b;
            } else {
                const Vec2 end{m.back(), x};
                if (distance(at, end) > 1e-3) arc_to(e, end);
                at = end;
            }
            return false;
        }
        if (at.x <= e.c.x) return true;
        if (m.empty() || m.front() < e.c.x) {
            arc_to(e, e.b);
            at = e.b;
        } else {
            const Vec2 end{m.front(), x};
            if (distance(at, end) > 1e-3) arc_to(e, end);
            at = end;
        }
        return false;
    }

    // Along element p where it rises: true when it does not (a pocket starts there).
    bool climb(std::size_t p, Vec2& at) {
        const G71Element& e = el_[p];
        if (!e.arc) {
            if (e.b.y < e.a.y) return true;
            if (distance(at, e.a) > 1e-6) throw std::string("the path is not continuous");
            to(LatheCycleMove::Kind::feed, e.b);
            at = e.b;
            return false;
        }
        if (!e.ccw) {
            if (at.x > e.c.x) return true;
            if (distance(at, e.b) > 1e-3) arc_to(e, e.b);
            at = e.b;
            return false;
        }
        if (at.x < e.c.x) return true;
        Vec2 end = e.b;
        if (e.b.x < e.c.x) end = Vec2{e.c.x, e.c.y + distance(e.a, e.c)};
        if (distance(at, end) > 1e-3) arc_to(e, end);
        at = end;
        return true;  // the control looks for a pocket after every G3
    }

    void pocket(std::size_t p, Vec2 at, int depth_of_call) {
        if (depth_of_call > 10000) throw std::string("too many pockets");
        double x = start_level_;
        int idle = 0;
        while (p < el_.size()) {
            if (++idle > 1000) throw std::string("the cycle does not progress");
            while (x > at.y) x -= depth_;
            if (dive(p, at, x, p == 0)) {
                for (; p < el_.size(); ++p)
                    if (climb(p, at)) {
                        pocket(p, at, depth_of_call + 1);
                        return;
                    }
                return;
            }
            if (at.y > x || std::abs(at.y - x) > 1e-6) {
                ++p;
                continue;
            }
            for (std::size_t ip = p; ip < el_.size(); ++ip) {
                const std::vector<double> m = g71_meets(el_[ip], at.y);
                if (m.empty()) continue;
                const double z = ip != p ? m.front() : m.back();
                const double length = std::abs(z - at.x);
                if (length < 1e-6) {
                    if (ip == p) continue;
                    ++p;
                    break;
                }
                to(LatheCycleMove::Kind::feed, Vec2{z, at.y});
                const double e = std::min(1.0, length / 2 / retract_) * retract_;
                to(LatheCycleMove::Kind::rapid, Vec2{z + e, at.y + e});
                to(LatheCycleMove::Kind::rapid, Vec2{at.x - e, at.y + e});
                to(p == 0 ? LatheCycleMove::Kind::rapid : LatheCycleMove::Kind::feed, at);
                x -= depth_;
                idle = 0;
                break;
            }
        }
    }

private:
    std::vector<G71Element> el_;
    double start_level_, depth_, retract_;
    long count_ = 0;
};

// What the model's refusals call the axes: G71's, or G72's (the model runs G72 with the axes
// swapped, and says what that means on the lathe).
struct G7xWords {
    const char* start_above;   // S beyond the profile's start across the passes
    const char* start_beyond;  // S beyond it along the passes
    const char* not_towards;   // the profile does not run the passes' way
    const char* ends_below;    // the profile ends nearer the levels' end than it starts
    const char* falls;         // an element goes back up the levels
    const char* turns_back;    // an element runs against the passes
    const char* arc_half;      // an arc the control does not take
    const char* level;         // what a level is
    // G72 only: the profile does not rise across the passes (rs274 then turns it the other way).
    const char* flat = nullptr;
};

constexpr G7xWords g7x_words_z{
    "the start point is not above the profile's start",
    "the start point is not beyond the profile's start in Z (the control's cycle is not modelled down a line along X)",
    "the profile does not run towards -Z",
    "the profile ends below its start",
    " falls in radius (a pocket)",
    " turns back towards +Z",
    " is an arc the control does not take (not within a half above or below its centre, towards -Z)",
    "radius",
};

constexpr G7xWords g7x_words_x{
    "the start point is not beyond the profile's start in Z",
    "the start point is not outside the profile's start in X (the control's cycle is not modelled down a line along Z)",
    "the profile does not run towards -X",
    "the profile ends on the -Z side of its start",
    " falls in Z (a pocket)",
    " turns back towards +X",
    " is an arc the control does not take (not within a half on the +Z or -Z side of its centre, towards -X)",
    "Z",
    "the profile ends at the Z it starts at (LinuxCNC's G72 turns such a profile the other way)",
};

// The elements of a profile for a G71 (appended to `el`), or why the cycle does not take it: its
// Z never rises and its radius never falls (no pocket); arcs within a quarter the control takes;
// the refusals in `words`.
// `slack`: how far an arc's end may lie beyond its quarter in Z (rounded words: Fanuc's 0.001 mm).
std::optional<std::string> g71_elements(const Profile& profile, std::vector<G71Element>& el, const G7xWords& words,
                                        double slack = 0.0) {
    for (std::size_t k = 0; k < profile.segments.size(); ++k) {
        const ProfileSegment& s = profile.segments[k];
        G71Element e{segment_start(profile, k), s.end};
        if (s.centre) {
            e.arc = true;
            e.c = *s.centre;
            e.ccw = s.direction == ArcDirection::ccw;
        }
        const std::string which = "element " + std::to_string(k);
        if (e.b.y < e.a.y) return std::string(which + words.falls);
        if (!e.arc) {
            if (e.b.x - e.a.x > 1e-3) return std::string(which + words.turns_back);
        } else {
            const double in = e.a.y - e.c.y, ex = e.b.y - e.c.y, dz = e.b.x - e.a.x;
            // The control's own test, and no pocket: a G3 on the right of its top quarter, a G2 on
            // the left of its bottom one.
            const bool control = e.ccw ? in >= -1e-3 && ex >= -1e-3 && dz <= -1e-3 : in <= 1e-3 && ex <= 1e-3 && dz <= -1e-3;
            if (!control) return std::string(which + words.arc_half);
            // (An end at the centre's Z, as a quarter's is, comes out a rounding error either
            // side of it from an offset or a shift: 1e-7 mm past it is no pocket.)
            slack = std::max(slack, 1e-7);
            const bool rising = e.ccw ? e.a.x >= e.c.x - slack && e.b.x >= e.c.x - slack
                                      : e.a.x <= e.c.x + slack && e.b.x <= e.c.x + slack;
            if (!rising) return std::string(which + " is an arc that" + words.falls);
        }
        el.push_back(e);
    }
    return std::nullopt;
}

// The (Z, radius) point with its coordinates swapped: G72's frame, in which it is G71.
Vec2 g7x_swapped(Vec2 p) { return Vec2{p.y, p.x}; }

ArcDirection g7x_reversed(ArcDirection d) { return d == ArcDirection::ccw ? ArcDirection::cw : ArcDirection::ccw; }

// A profile with Z and X swapped (its arcs turning the other way): G72's in G71's frame and back.
Profile g7x_swapped_profile(const Profile& profile) {
    Profile swapped = profile;
    swapped.start = g7x_swapped(profile.start);
    for (ProfileSegment& s : swapped.segments) {
        s.end = g7x_swapped(s.end);
        if (s.centre) s.centre = g7x_swapped(*s.centre);
        s.direction = g7x_reversed(s.direction);
    }
    return swapped;
}

// A model's moves from G71's frame back to G72's.
void g7x_swap_moves(LatheCycleModel& model) {
    for (LatheCycleMove& m : model.moves) {
        m.end = g7x_swapped(m.end);
        if (m.kind == LatheCycleMove::Kind::arc) {
            m.centre = g7x_swapped(m.centre);
            m.direction = g7x_reversed(m.direction);
        }
    }
}

// G71 in its own frame (Z along the passes, radius across them), its refusals in `words`.
LatheCycleModel g7x_model(Vec2 start, const Profile& profile, double depth, double retract, const G7xWords& words) {
    LatheCycleModel out;
    auto refuse = [&](std::string why) {
        out.moves.clear();
        out.refusal = std::move(why);
        return out;
    };
    if (!(depth > 0) || !(retract > 0)) return refuse("the depth of cut and the retract must be above 0");
    if (profile.segments.empty()) return refuse("the profile has no element");
    const Vec2 p0 = profile.start, pe = profile.segments.back().end;
    if (!(start.y > p0.y + 1e-6)) return refuse(words.start_above);
    if (!(start.x > p0.x + 1e-3))
        return refuse(words.start_beyond);
    if (!(p0.x - pe.x > 1e-3)) return refuse(words.not_towards);
    if (p0.y > pe.y) return refuse(words.ends_below);
    // G72 decides which way to turn the profile by the sign of its Z from the start to the end:
    // one that stays at a Z is turned the other way (not modelled).
    if (words.flat && !(pe.y - p0.y > 1e-6)) return refuse(words.flat);
    std::vector<G71Element> el;
    el.push_back({start, p0});
    if (auto why = g71_elements(profile, el, words)) return refuse(*why);
    // A level through a corner of the profile: there the control's cycle turns on tolerances
    // (rs274 runs some such profiles without end), and the model does not follow it.
    for (double x = start.y; x > p0.y - 1e-4; x -= depth) {
        auto through = [&](double r) { return std::abs(x - r) < 1e-4; };
        bool hit = through(p0.y);
        for (const ProfileSegment& s : profile.segments) hit = hit || through(s.end.y);
        if (hit)
            return refuse(std::string("a level of the cycle (") + words.level + " " + g71_number(x) +
                          ") runs through a corner of the profile: the control's cycle is not modelled there");
    }
    if (pe.y < start.y) el.push_back({pe, Vec2{pe.x, start.y}});
    G71Run run(std::move(el), start.y, depth, retract);
    run.origin = start;
    try {
        run.moves.push_back({LatheCycleMove::Kind::rapid, start, {}, ArcDirection::ccw});
        run.pocket(0, start, 0);
    } catch (const std::string& why) {
        return refuse(why);
    }
    out.moves = std::move(run.moves);
    return out;
}


}  // namespace

LatheCycleModel linuxcnc_g7x(LatheCycleAxis axis, Vec2 start, const Profile& profile, double depth, double retract) {
    if (axis == LatheCycleAxis::z) return g7x_model(start, profile, depth, retract, g7x_words_z);
    // G72: the control turns the profile a quarter and flips it so that it is G71's, runs G71
    // and turns the moves back; together a swap of Z and X (which turns arcs the other way).
    LatheCycleModel out = g7x_model(g7x_swapped(start), g7x_swapped_profile(profile), depth, retract, g7x_words_x);
    g7x_swap_moves(out);
    return out;
}

Profile fanuc_g7x_shape(LatheCycleAxis axis, Vec2 start, const Profile& profile) {
    if (axis == LatheCycleAxis::x)
        return g7x_swapped_profile(fanuc_g7x_shape(LatheCycleAxis::z, g7x_swapped(start), g7x_swapped_profile(profile)));
    Profile shape;
    shape.plane = profile.plane;
    shape.start = Vec2{start.x, profile.start.y};
    shape.segments.push_back({profile.start, std::nullopt, ArcDirection::ccw});
    for (const ProfileSegment& s : profile.segments) shape.segments.push_back(s);
    return shape;
}

namespace {

// What Fanuc's model's refusals call the axes: G71's, or G72's (run with the axes swapped).
struct FanucWords {
    const char* first_block;  // block ns does not move along the axis across the passes
    const char* start_above;  // A not beyond A' across the passes
    const char* not_towards;  // the shape does not run the passes' way
    const char* ends_above;   // the shape ends beyond A across the passes
    const G7xWords& elements;
};

const FanucWords fanuc_words_z{"the finishing shape's first block is not along X from the start point (type I)",
                               "the start point is not above the finishing shape's start",
                               "the finishing shape does not run towards -Z",
                               "the finishing shape ends above the start point",
                               g7x_words_z};
const FanucWords fanuc_words_x{"the finishing shape's first block is not along Z from the start point (type I)",
                               "the start point is not beyond the finishing shape's start in Z",
                               "the finishing shape does not run towards -X",
                               "the finishing shape ends beyond the start point in Z",
                               g7x_words_x};

// Fanuc's type I G71 in its own frame (Z along the passes, radius across them).
LatheCycleModel fanuc_model(Vec2 start, const Profile& written, double depth, double retract, Vec2 allowance,
                            const FanucWords& words) {
    LatheCycleModel out;
    auto refuse = [&](std::string why) {
        out.moves.clear();
        out.refusal = std::move(why);
        return out;
    };
    if (!(depth > 0) || !(retract > 0)) return refuse("the depth of cut and the retract must be above 0");
    if (written.segments.empty()) return refuse("the finishing shape has no element");
    if (std::abs(written.start.x - start.x) > 1e-6) return refuse(words.first_block);
    if (allowance.x < 0 || allowance.y < 0) return refuse("a negative finishing allowance is not modelled");
    // The allowance moves the whole shape, A' with it (Fanuc's Δw along the passes, Δu/2 across).
    const Profile shape = fanuc_moved_shape(written, allowance);
    const Vec2 a1 = shape.start, pe = shape.segments.back().end;
    if (!(start.y > a1.y + 1e-6)) return refuse(words.start_above);
    if (!(a1.x - pe.x > 1e-3)) return refuse(words.not_towards);
    if (pe.y > start.y + 1e-6) return refuse(words.ends_above);
    std::vector<G71Element> el;
    if (auto why = g71_elements(shape, el, words.elements, 1e-3)) return refuse(*why);
    std::vector<double> corners{a1.y};
    for (const ProfileSegment& s : shape.segments) corners.push_back(s.end.y);
    // Sorted, so that each level looks up its nearest corners (a read program's shape may have
    // 10^5 blocks and the cycle 10^6 levels: every corner for every level would not end).
    std::sort(corners.begin(), corners.end());
    std::vector<double> levels;
    for (int k = 1; start.y - k * depth > a1.y - 1e-4; ++k) {
        if (k > 1000000) return refuse("the cycle makes more than 1000000 levels");
        const double x = start.y - k * depth;
        const auto near = std::lower_bound(corners.begin(), corners.end(), x - 1e-4);
        if (near != corners.end() && std::abs(x - *near) < 1e-4)
            return refuse(std::string("a level of the cycle (") + words.elements.level + " " + g71_number(x) +
                          ") runs through a corner of the finishing shape: the control's cycle is not modelled there");
        levels.push_back(x);
    }
    // Each level looks for the element it meets: bounded, so that a read program's cycle ends.
    if (static_cast<double>(levels.size()) * static_cast<double>(el.size()) > 5e7)
        return refuse("the cycle's " + std::to_string(levels.size()) + " levels over a shape of " + std::to_string(el.size()) +
                      " elements are more than camgen models");
    auto add = [&](LatheCycleMove::Kind kind, Vec2 end) { out.moves.push_back({kind, end, {}, ArcDirection::ccw}); };
    add(LatheCycleMove::Kind::rapid, start);
    for (double x : levels) {
        // Where the level meets the shape: the first element reaching it (monotone: the only
        // one), or the end's Z above the shape's end.
        std::optional<double> z;
        for (const G71Element& e : el) {
            const std::vector<double> m = g71_meets(e, x);
            if (!m.empty()) {
                z = e.arc ? (e.ccw ? m.back() : m.front()) : m.front();
                break;
            }
        }
        if (!z) z = pe.x;
        if (start.x - *z < retract - 1e-9)
            return refuse(std::string("a pass (") + words.elements.level + " " + g71_number(x) + ") is shorter than the retract");
        add(LatheCycleMove::Kind::rapid, Vec2{start.x, x});
        add(LatheCycleMove::Kind::feed, Vec2{*z, x});
        add(LatheCycleMove::Kind::rapid, Vec2{*z + retract, x + retract});
        add(LatheCycleMove::Kind::rapid, Vec2{start.x, x + retract});
    }
    add(LatheCycleMove::Kind::rapid, a1);
    for (const G71Element& e : el) {
        if (e.arc)
            out.moves.push_back({LatheCycleMove::Kind::arc, e.b, e.c, e.ccw ? ArcDirection::ccw : ArcDirection::cw});
        else
            add(LatheCycleMove::Kind::feed, e.b);
    }
    add(LatheCycleMove::Kind::rapid, start);
    return out;
}

}  // namespace

LatheCycleModel fanuc_g7x(LatheCycleAxis axis, Vec2 start, const Profile& shape, double depth, double retract, Vec2 allowance) {
    if (axis == LatheCycleAxis::z) return fanuc_model(start, shape, depth, retract, allowance, fanuc_words_z);
    // G72: G71 with Z and X swapped, as LinuxCNC's (and as the manual draws it).
    LatheCycleModel out =
        fanuc_model(g7x_swapped(start), g7x_swapped_profile(shape), depth, retract, g7x_swapped(allowance), fanuc_words_x);
    g7x_swap_moves(out);
    return out;
}

Profile fanuc_moved_shape(const Profile& shape, Vec2 allowance) {
    Profile moved = shape;
    moved.start = moved.start + allowance;
    for (ProfileSegment& s : moved.segments) {
        s.end = s.end + allowance;
        if (s.centre) s.centre = *s.centre + allowance;
    }
    return moved;
}

LatheCycleModel fanuc_g70(LatheCycleAxis axis, Vec2 start, const Profile& shape) {
    LatheCycleModel out;
    if (shape.segments.empty()) {
        out.refusal = "the finishing shape has no element";
        return out;
    }
    const bool along_x = axis == LatheCycleAxis::z;  // G71's ns moves along X from A, G72's along Z
    if (std::abs((along_x ? shape.start.x - start.x : shape.start.y - start.y)) > 1e-6) {
        out.refusal = along_x ? "the finishing shape's first block is not along X from the start point (type I)"
                              : "the finishing shape's first block is not along Z from the start point (type I)";
        return out;
    }
    auto add = [&](LatheCycleMove::Kind kind, Vec2 end) { out.moves.push_back({kind, end, {}, ArcDirection::ccw}); };
    add(LatheCycleMove::Kind::rapid, shape.start);
    for (const ProfileSegment& s : shape.segments) {
        if (s.centre) out.moves.push_back({LatheCycleMove::Kind::arc, s.end, *s.centre, s.direction});
        else add(LatheCycleMove::Kind::feed, s.end);
    }
    add(LatheCycleMove::Kind::rapid, start);
    return out;
}

}  // namespace camgen
