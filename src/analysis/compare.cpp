// Comparing two traces as positions visited (motion.hpp). Each trace becomes a list of items:
// tool changes, spindle states, dwells, stops, and paths (maximal runs of rapid or of feed moves).
// Two paths match when every block end and every sampled arc point of each lies on the other,
// in order (so a circle the wrong way round fails although every point is on the circle),
// both end at the same point, and the feed agrees where they overlap.
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "camgen/geometry/vec.hpp"
#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/nc/format.hpp"
#include "camgen/post/arc_output.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"

namespace camgen {

namespace {

constexpr double tiny = 1e-9;

std::string num3(double v) {
    nc::FormatSpec spec;
    spec.decimals = 3;
    spec.force_decimal = true;
    return nc::Format(spec).format(v);
}

// A point in the program's terms: on a lathe X and Z, X as a diameter where the machine programs it so.
std::string point(const Vec3& p, const CompareTolerance& tol) {
    if (tol.lathe) return fmt::format("X{} Z{}", num3(tol.x_diameter ? 2.0 * p.x : p.x), num3(p.z));
    return fmt::format("X{} Y{} Z{}", num3(p.x), num3(p.y), num3(p.z));
}

double dist(const Vec3& a, const Vec3& b) { return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z)); }

// One straight or circular piece of a path: what the comparison needs of its step (a long path
// is held while it is compared: a helix of thousands of turns written as millions of chords).
struct Seg {
    Vec3 a, b;
    std::shared_ptr<const ArcGeometry> arc;  // a circular move (shared: paths are copied as they merge)
    double feed = 0.0;         // mm/min
    double pitch = 0.0;        // see Step::pitch
    double uncertainty = 0.0;  // mm, see Step::uncertainty
    int line = 0;
    StepKind kind = StepKind::feed;
    explicit Seg(const Step& s)
        : a(s.from), b(s.to), arc(s.arc ? std::make_shared<const ArcGeometry>(*s.arc) : nullptr), feed(s.feed), pitch(s.pitch),
          uncertainty(s.uncertainty), line(s.line), kind(s.kind) {}
    double length() const {
        if (!arc) return dist(a, b);
        const ArcGeometry& g = *arc;
        PlanePoint s = to_plane(g.start, g.plane), e = to_plane(g.end, g.plane);
        return std::hypot(g.radius * g.sweep, e.w - s.w);
    }
    Vec3 at(double t) const {
        if (arc) return point_on_arc(*arc, t);
        return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
    }
};

struct Path {
    bool rapid = true;
    bool start_known = true;
    Vec3 start;
    std::vector<Seg> segs;
    // The offsets in force at its first move, and where a later move of it runs under others
    // (the first such: a work offset selected between two holes of a canned cycle).
    int tool = 0;
    int line = 0;  // of its first move (first_line: of its first segment, 0 without one)
    SelectedOffsets offsets;
    std::optional<SelectedOffsets> changed;
    int changed_line = 0;
    Vec3 end() const { return segs.empty() ? start : segs.back().b; }
    int first_line() const { return segs.empty() ? 0 : segs.front().line; }
    // A move at `line` under `o`: the first change of offsets is kept.
    void moves_under(const SelectedOffsets& o, int at) {
        if (!changed && !o.same(offsets)) {
            changed = o;
            changed_line = at;
        }
    }
};

struct Item {
    enum class Kind { path, tool, spindle, dwell, stop } kind = Kind::path;
    Step step;  // tool, spindle, dwell, stop
    Path path;
    int line() const { return kind == Kind::path ? path.first_line() : step.line; }
};

// Turns one side's steps into items as they come, handing each on once it is complete.
// A spindle change counts where it matters: before the next feed move, dwell or tool change,
// and only if it changes the state then in effect. So a control that reverses its spindle
// for a tap at the retract plane (LinuxCNC's M4 before G33.1) matches one that reverses at R,
// and a speed written again unchanged says nothing. Rapids of `nowhere` mm or less are dropped.
class ItemBuilder {
public:
    // `one_line`: the machine's arc rules for the job's side (nullptr: arcs stay arcs).
    ItemBuilder(double nowhere, const ArcSettings* one_line, std::function<void(Item&&)> out)
        : nowhere_(nowhere), one_line_(one_line), out_(std::move(out)) {}

    void step(const Step& step) {
        // An arc the post writes as one straight move from its start to its end (a bore a hair
        // wider than its tool: a helix of radius 0.001 mm, one plunge) is that move here. Its
        // points are within the arc's diameter of the move's at the same fraction (both lie in
        // the circle, at the same height), and within its length.
        std::optional<Step> as_line;
        if (one_line_ && step.kind == StepKind::feed && step.arc && written_as_one_line(*step.arc, *one_line_)) {
            as_line = step;
            as_line->arc.reset();
            as_line->uncertainty += std::min(2.0 * step.arc->radius, step.arc->radius * step.arc->sweep);
        }
        const Step& s = as_line ? *as_line : step;
        switch (s.kind) {
            case StepKind::tool_change:
                flush_spindle();
                made({Item::Kind::tool, s, {}});
                break;
            case StepKind::spindle: pending_ = s; break;
            case StepKind::dwell:
                flush_spindle();
                made({Item::Kind::dwell, s, {}});
                break;
            case StepKind::stop:
                flush_spindle();
                made({Item::Kind::stop, s, {}});
                break;
            case StepKind::rapid:
            case StepKind::feed: {
                bool rapid = s.kind == StepKind::rapid;
                if (!rapid) flush_spindle();
                bool extend = open_ && open_->path.rapid == rapid && s.from_known;
                if (!extend) {
                    Item it{Item::Kind::path, {}, {}};
                    it.path.rapid = rapid;
                    it.path.start_known = s.from_known;
                    it.path.start = s.from_known ? s.from : s.to;
                    it.path.tool = s.tool;
                    it.path.line = s.line;
                    it.path.offsets = s.offsets;
                    made(std::move(it));
                } else {
                    open_->path.moves_under(s.offsets, s.line);
                }
                if (s.from_known && (s.arc || dist(s.from, s.to) > tiny)) open_->path.segs.emplace_back(s);
                break;
            }
        }
    }

    void finish() {
        flush_spindle();
        close_path();
        if (last_) out_(std::move(*last_));
        last_.reset();
    }

private:
    void flush_spindle() {
        if (!pending_) return;
        bool same = pending_->spindle == state_ &&
                    (state_ == SpindleState::off || (pending_->rpm == rpm_ && pending_->surface_speed == surface_speed_));
        state_ = pending_->spindle;
        rpm_ = pending_->rpm;
        surface_speed_ = pending_->surface_speed;
        if (!same) made({Item::Kind::spindle, *pending_, {}});
        pending_.reset();
    }

    // A new item: the path before it is complete. A path stays open for the moves that extend it.
    void made(Item&& item) {
        close_path();
        if (item.kind == Item::Kind::path) open_ = std::move(item);
        else kept(std::move(item));
    }

    void close_path() {
        if (!open_) return;
        Item path = std::move(*open_);
        open_.reset();
        if (!dropped(path)) kept(std::move(path));
    }

    // A path that goes nowhere from a known start says nothing; nor does a rapid shorter than
    // the resolution (a longhand re-approach that rounds onto the Z it starts from is not
    // written at all).
    bool dropped(const Item& i) const {
        if (!i.path.start_known) return false;
        if (i.path.segs.empty()) return true;
        if (!i.path.rapid) return false;
        double length = 0.0;
        for (const Seg& g : i.path.segs) length += g.length();
        return length <= nowhere_;
    }

    // What was on either side of a dropped rapid is one path again: the last item kept waits
    // for the next, which it may take in.
    void kept(Item&& i) {
        if (last_ && i.kind == Item::Kind::path && last_->kind == Item::Kind::path && i.path.start_known &&
            last_->path.rapid == i.path.rapid) {
            last_->path.moves_under(i.path.offsets, i.path.line);
            if (i.path.changed) last_->path.moves_under(*i.path.changed, i.path.changed_line);
            auto& segs = last_->path.segs;
            segs.insert(segs.end(), std::make_move_iterator(i.path.segs.begin()), std::make_move_iterator(i.path.segs.end()));
            return;
        }
        if (last_) out_(std::move(*last_));
        last_ = std::move(i);
    }

    double nowhere_;
    const ArcSettings* one_line_;
    std::function<void(Item&&)> out_;
    std::optional<Step> pending_;  // a spindle step not yet in effect
    SpindleState state_ = SpindleState::off;
    double rpm_ = 0.0;
    double surface_speed_ = 0.0;
    std::optional<Item> open_;  // the path being made
    std::optional<Item> last_;  // the last item kept
};

// A point of one path to be found on the other.
struct Sample {
    Vec3 p;
    size_t seg = 0;              // index of the segment it lies on
    const Seg* step = nullptr;  // the move it lies on (nullptr: the path's start)
    bool vertex = false;         // a block end (else a point inside a move)
    bool check_feed = false;     // inside a move: the feeds must agree here
};

// Hands each sample of the path to `f`, in order, until it returns a mismatch (made one at a
// time: a helix of thousands of turns written as chords has millions).
template <class F>
std::optional<Mismatch> each_sample(const Path& path, F f) {
    if (auto m = f(Sample{path.start, 0, path.segs.empty() ? nullptr : &path.segs.front(), true, false})) return m;
    for (size_t i = 0; i < path.segs.size(); ++i) {
        const Seg& s = path.segs[i];
        int n = 2;
        if (s.arc) {
            const ArcGeometry& g = *s.arc;
            n = static_cast<int>(std::ceil(std::max(g.sweep / (5.0 * std::numbers::pi / 180.0), s.length() / 1.0)));
            n = std::clamp(n, 4, 5000);
        }
        for (int k = 1; k < n; ++k)
            if (auto m = f(Sample{s.at(double(k) / n), i, &s, false, true})) return m;
        if (auto m = f(Sample{s.b, i, &s, true, false})) return m;
    }
    return std::nullopt;
}

// Where on a segment a point lies: the parameter t in [0, 1] nearest to it, at or after t_min
// (minus `slack`), and its distance. Arcs: the angle about the centre, over every turn.
struct Hit {
    double t = 0.0;
    double d = 1e300;
};

Hit locate(const Seg& s, const Vec3& p, double t_min, double tol) {
    double len = s.length();
    double slack = len > 0 ? tol / len : 1.0;
    if (!s.arc) {
        Vec3 ab{s.b.x - s.a.x, s.b.y - s.a.y, s.b.z - s.a.z};
        double l2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
        double t = l2 > 0 ? ((p.x - s.a.x) * ab.x + (p.y - s.a.y) * ab.y + (p.z - s.a.z) * ab.z) / l2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        if (t < t_min - slack) return {};
        return {std::max(t, t_min), dist(p, s.at(t))};
    }
    const ArcGeometry& g = *s.arc;
    PlanePoint c = to_plane(g.centre, g.plane), q = to_plane(p, g.plane);
    double phi = std::atan2(q.v - c.v, q.u - c.u) - g.start_angle;
    if (g.direction == ArcDirection::cw) phi = -phi;
    phi = std::fmod(phi, two_pi);
    if (phi < 0) phi += two_pi;
    Hit best;
    // The point's angle comes round once a turn. Only a few turns can hold the answer: the
    // first ones at or after t_min, and on a helix the ones at the point's height (a helix of
    // thousands of turns made every lookup scan them all: a fuzz finding, verify of a bore at
    // pitch 0.0006 mm ran for minutes).
    std::array<double, 7> ts{0.0, 1.0};
    std::size_t count = 2;
    const double last_turn = std::floor((g.sweep + two_pi - phi) / two_pi);
    auto turn = [&](double k) {
        if (k < 0 || k > last_turn) return;
        ts[count++] = std::min((phi + k * two_pi) / g.sweep, 1.0);
    };
    const double k_min = std::max(0.0, std::ceil(((t_min - slack) * g.sweep - phi) / two_pi));
    turn(k_min);
    turn(k_min + 1);
    const PlanePoint a3 = to_plane(s.a, g.plane), b3 = to_plane(s.b, g.plane);
    if (std::abs(b3.w - a3.w) > 1e-12) {  // a helix
        const double k_z = std::round(((q.w - a3.w) / (b3.w - a3.w) * g.sweep - phi) / two_pi);
        turn(k_z - 1);
        turn(k_z);
        turn(k_z + 1);
    }
    // In order (at most seven: insertion).
    for (std::size_t i = 1; i < count; ++i)
        for (std::size_t j = i; j > 0 && ts[j] < ts[j - 1]; --j) std::swap(ts[j], ts[j - 1]);
    const bool helical = std::abs(b3.w - a3.w) > 1e-12;
    const double quarter = std::numbers::pi / 2.0 / g.sweep;  // a quarter turn, in t
    for (std::size_t i = 0; i < count; ++i) {
        const double t_angle = ts[i];
        // On a helix the nearest point may lie up to a quarter turn after the one at the same
        // angle (below): that one may come before t_min while the nearest does not (fuzz
        // finding 14, a 0.013 mm helix whose centre was rounded by 0.0005 mm).
        if (t_angle < t_min - slack && (!helical || t_angle + quarter < t_min - slack)) continue;
        double t = std::max(t_angle, t_min - slack);
        double d = dist(p, s.at(t));
        if (d > tol && helical) {
            // On a steep helix of a small radius the point at the same angle is not the nearest:
            // a rounded X or Y turns the angle, and the pitch turns that into height (a chord of
            // a 0.028 mm helix at 3 mm a turn read 0.0086 mm off at its angle, 0.005 mm off in
            // truth: a fuzz finding). The nearest point within a quarter turn either side.
            double lo = std::max(t_min - slack, t_angle - quarter);
            double hi = std::min(1.0, t_angle + quarter);
            for (int k = 0; k < 40 && hi - lo > 1e-12; ++k) {
                const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
                if (dist(p, s.at(m1)) <= dist(p, s.at(m2))) hi = m2;
                else lo = m1;
            }
            const double refined = (lo + hi) / 2.0, d_refined = dist(p, s.at(refined));
            if (d_refined < d) {
                t = refined;
                d = d_refined;
            }
        }
        if (d <= tol) return {std::max(t, t_min), d};
        if (d < best.d) best = {std::max(t, t_min), d};
    }
    if (helical && g.radius < 2.0 * tol) {
        // A helix no wider than the tolerance: a point near its axis (a chord across it, from
        // rounded ends) has an angle that says nothing, and its nearest point may be half a
        // turn from the one at its angle. Look along the turn at the point's height, and
        // refine the nearest of those samples.
        const double t_z = std::clamp((q.w - a3.w) / (b3.w - a3.w), 0.0, 1.0);
        const double half = std::numbers::pi / g.sweep;
        const double lo = std::max(t_min - slack, t_z - half), hi = std::min(1.0, t_z + half);
        if (lo <= hi) {
            constexpr int n = 32;
            double t_best = lo, d_best = dist(p, s.at(lo));
            for (int i = 1; i <= n; ++i) {
                const double t = lo + (hi - lo) * i / n, d = dist(p, s.at(t));
                if (d < d_best) t_best = t, d_best = d;
            }
            double a = std::max(lo, t_best - (hi - lo) / n), b = std::min(hi, t_best + (hi - lo) / n);
            for (int k = 0; k < 40 && b - a > 1e-12; ++k) {
                const double m1 = a + (b - a) / 3.0, m2 = b - (b - a) / 3.0;
                if (dist(p, s.at(m1)) <= dist(p, s.at(m2))) b = m2;
                else a = m1;
            }
            if (const double d = dist(p, s.at((a + b) / 2.0)); d < d_best) t_best = (a + b) / 2.0, d_best = d;
            if (d_best <= tol) return {std::max(t_best, t_min), d_best};
            if (d_best < best.d) best = {std::max(t_best, t_min), d_best};
        }
    }
    return best;
}

std::string describe_path(const Path& p) { return p.rapid ? "rapid" : "feed"; }

std::string describe_seg(const Seg& s, const CompareTolerance& tol) {
    if (!s.arc)
        return fmt::format("{} move from {} to {}", s.kind == StepKind::rapid ? "rapid" : "feed", point(s.a, tol), point(s.b, tol));
    const ArcGeometry& g = *s.arc;
    return fmt::format("{} arc from {} to {} about {}", g.direction == ArcDirection::cw ? "cw" : "ccw", point(s.a, tol), point(s.b, tol),
                       point(g.centre, tol));
}

std::string describe_step(const Step& s) {
    switch (s.kind) {
        case StepKind::tool_change: return fmt::format("a change to tool {}", s.tool);
        case StepKind::spindle:
            if (s.spindle != SpindleState::off && s.surface_speed > 0)
                return fmt::format("spindle {} at {} m/min (G96) up to {} rpm", s.spindle == SpindleState::cw ? "cw" : "ccw",
                                   num3(s.surface_speed), num3(s.rpm));
            return s.spindle == SpindleState::off ? std::string("spindle off")
                                                  : fmt::format("spindle {} at {} rpm", s.spindle == SpindleState::cw ? "cw" : "ccw", num3(s.rpm));
        case StepKind::dwell: return fmt::format("a dwell of {} s", num3(s.seconds));
        case StepKind::stop: return s.stop == StopKind::optional ? "an optional stop" : "a stop";
        default: return s.kind == StepKind::rapid ? "a rapid move" : "a feed move";
    }
}

std::string describe_item(const Item& i, const CompareTolerance& tol) {
    if (i.kind != Item::Kind::path) return describe_step(i.step);
    return fmt::format("{} moves to {}", describe_path(i.path), point(i.path.end(), tol));
}

// Finds every sample of `from` on `onto`, in order. `from_is_job` only changes the words.
// `onto_next` is the item after `onto` (for messages: what the other side does instead).
std::optional<Mismatch> follow(const Path& from, const Path& onto, const Path* onto_next, bool from_is_job,
                               const CompareTolerance& tol) {
    size_t k = 0;
    double t = 0.0;
    std::optional<Vec3> last;  // the sample found last
    return each_sample(from, [&](const Sample& s) -> std::optional<Mismatch> {
        double extra = s.step ? s.step->uncertainty : 0.0;
        bool found = false;
        std::optional<Mismatch> wrong_feed;
        // The point is looked for no further along `onto` than twice the way from the last one
        // (and a millimetre): a point of the first pass not found where it should be is not
        // found again on a later pass through the same place (a plunge at the pass's start),
        // which named a line of that pass as the difference.
        // Where on `onto` the last point lay is known within that move's uncertainty (a point
        // within 1.4 mm of an arc written with whole-millimetre I and J "lies" at its end).
        const double known = k < onto.segs.size() ? onto.segs[k].uncertainty : 0.0;
        const double reach = last ? 2.0 * dist(*last, s.p) + 1.0 + 10.0 * (tol.path + extra + known) : 1e300;
        double skipped = 0.0;  // the length of `onto`'s moves passed over whole
        for (size_t j = k; j < onto.segs.size() && !found; ++j) {
            if (j > k + 1) skipped += onto.segs[j - 1].length();
            if (skipped > reach) break;
            const Seg& seg = onto.segs[j];
            // Block ends on straight moves must meet exactly; on or near arcs, the arc may be
            // chords or have a rounded centre.
            double limit = (s.vertex && !seg.arc ? tol.position : tol.path) + extra + seg.uncertainty + tiny;
            Hit h = locate(seg, s.p, j == k ? t : 0.0, limit);
            if (h.d > limit) {
                if (wrong_feed) break;  // the run of segments the point is near has ended
                continue;
            }
            // A move that follows the spindle (a tap, a per-revolution feed) feeds at pitch x
            // speed: the speed written to the resolution of S moves its feed by up to pitch x
            // that resolution (a fuzz finding: 0.2296875 mm/rev at 802.3125 rpm, S802).
            double feed_limit = tol.feed + std::max(s.step->pitch, seg.pitch) * tol.rpm + tiny;
            // A move no longer than the position tolerance may round to nothing and not be
            // written at all, its feed with it (a bore's way back to a centre 0.0001 mm away).
            const bool feed_matters = s.check_feed && !from.rapid && s.step->length() > tol.position + tiny;
            if (feed_matters && std::abs(s.step->feed - seg.feed) > feed_limit) {
                // A point within the tolerance of a corner lies on both moves that meet there (a
                // tiny arc written as one short line after a plunge): look on along the moves it
                // is near for one at its feed before calling it a mismatch.
                if (!wrong_feed) {
                    const Seg& job = from_is_job ? *s.step : seg;
                    const Seg& prog = from_is_job ? seg : *s.step;
                    wrong_feed = Mismatch{prog.line, fmt::format("the program feeds at {} mm/min where the job feeds at {} mm/min (near {})",
                                                                 num3(prog.feed), num3(job.feed), point(s.p, tol))};
                }
                continue;
            }
            k = j;
            t = h.t;
            found = true;
        }
        if (!found && wrong_feed) return wrong_feed;
        if (onto.segs.empty()) found = dist(s.p, onto.start) <= tol.position + extra + tiny;
        if (found) {
            last = s.p;
            return std::nullopt;
        }
        // Where the other path goes on from the last point both share: inside the segment
        // matched last, or after it.
        bool inside = k < onto.segs.size() && t < 1.0 - 1e-9;
        const Seg* near = inside                                   ? &onto.segs[k]
                          : k + 1 < onto.segs.size()                  ? &onto.segs[k + 1]
                          : onto_next && !onto_next->segs.empty() ? &onto_next->segs.front()
                          : onto.segs.empty()                     ? nullptr
                                                                  : &onto.segs.back();
        const Seg* mine = s.seg < from.segs.size() ? &from.segs[s.seg] : nullptr;
        std::string what = mine ? describe_seg(*mine, tol)
                                : fmt::format("{} path from {}", describe_path(from), point(from.start, tol));
        std::string there = near ? describe_seg(*near, tol) : fmt::format("{} path that stays at {}", describe_path(onto), point(onto.start, tol));
        if (from_is_job)
            return Mismatch{near ? near->line : from.first_line(),
                            fmt::format("the job's {} is not in the program (there the program has a {})", what, there)};
        return Mismatch{mine ? mine->line : from.first_line(),
                        fmt::format("the program's {} is not in the job (there the job has a {})", what, there)};
    });
}

std::optional<Mismatch> compare_paths(const Path& job, const Path& prog, const Path* job_next, const Path* prog_next,
                                      const CompareTolerance& tol) {
    double prog_start_extra = prog.segs.empty() ? 0.0 : prog.segs.front().uncertainty;
    double prog_end_extra = prog.segs.empty() ? 0.0 : prog.segs.back().uncertainty;
    if (dist(job.start, prog.start) > tol.position + tiny + prog_start_extra) {
        return Mismatch{prog.first_line(), fmt::format("the program's {} path starts at {}, the job's at {}", describe_path(prog),
                                                       point(prog.start, tol), point(job.start, tol))};
    }
    if (auto m = follow(job, prog, prog_next, true, tol)) return m;
    if (auto m = follow(prog, job, job_next, false, tol)) return m;
    if (dist(job.end(), prog.end()) > tol.position + prog_end_extra + tiny) {
        int line = prog.segs.empty() ? 0 : prog.segs.back().line;
        return Mismatch{line, fmt::format("the program's {} path ends at {}, the job's at {}", describe_path(prog), point(prog.end(), tol),
                                          point(job.end(), tol))};
    }
    return std::nullopt;
}

// The offsets in force along two paths at the same place in their traces: the same at their
// first moves, and the same after a change (a program that selects another work offset between
// two holes of a canned cycle changes it inside a rapid path; a job never does).
std::optional<Mismatch> compare_offsets(const Path& job, const Path& prog) {
    if (auto d = offsets_difference(job.offsets, prog.offsets, prog.tool)) return Mismatch{prog.line, *d};
    const SelectedOffsets& job_after = job.changed ? *job.changed : job.offsets;
    if (prog.changed)
        if (auto d = offsets_difference(job_after, *prog.changed, prog.tool)) return Mismatch{prog.changed_line, *d};
    if (job.changed && !prog.changed)
        if (auto d = offsets_difference(*job.changed, prog.offsets, prog.tool)) return Mismatch{prog.line, *d};
    return std::nullopt;
}

// The first difference between two items at the same place in their traces. `job_next` and
// `prog_next`: the next path on each side (for messages).
std::optional<Mismatch> compare_items(const Item& a, const Item& b, const Path* job_next, const Path* prog_next,
                                      const CompareTolerance& tol) {
    if (a.kind != b.kind)
        return Mismatch{b.line(), fmt::format("the program has {} where the job has {}", describe_item(b, tol), describe_item(a, tol))};
    switch (a.kind) {
        case Item::Kind::tool:
            if (a.step.tool != b.step.tool)
                return Mismatch{b.line(), fmt::format("the program changes to tool {}, the job to tool {}", b.step.tool, a.step.tool)};
            break;
        case Item::Kind::spindle:
            // A surface speed is written in the rpm's format: its tolerance too.
            if (a.step.spindle != b.step.spindle || std::abs(a.step.rpm - b.step.rpm) > tol.rpm + tiny ||
                std::abs(a.step.surface_speed - b.step.surface_speed) > tol.rpm + tiny)
                return Mismatch{b.line(), fmt::format("the program sets {}, the job {}", describe_step(b.step), describe_step(a.step))};
            break;
        case Item::Kind::dwell:
            if (std::abs(a.step.seconds - b.step.seconds) > tol.dwell + tiny)
                return Mismatch{b.line(), fmt::format("the program has {}, the job {}", describe_step(b.step), describe_step(a.step))};
            break;
        case Item::Kind::stop:
            // A stop that always waits does where the job's waits only at the operator's switch (a
            // control without an optional stop), not the other way round.
            if (a.step.stop == StopKind::mandatory && b.step.stop == StopKind::optional)
                return Mismatch{b.line(), "the program has an optional stop where the job stops always"};
            break;
        case Item::Kind::path:
            if (a.path.rapid != b.path.rapid)
                return Mismatch{b.line(), fmt::format("the program has {} where the job has {}", describe_item(b, tol), describe_item(a, tol))};
            if (auto m = compare_offsets(a.path, b.path)) return m;
            return compare_paths(a.path, b.path, job_next, prog_next, tol);
    }
    return std::nullopt;
}

// One side of a comparison: its items not compared yet.
class Side : public TraceSink {
public:
    // `one_line`: see ItemBuilder (the job's side only).
    Side(double nowhere, const ArcSettings* one_line, std::function<void()> changed)
        : builder_(nowhere, one_line, [this](Item&& i) { add(std::move(i)); }), changed_(std::move(changed)) {}
    void step(const Step& s) override {
        if (!stopped_) builder_.step(s);
    }
    void hole(const Hole&) override {}
    void finish(const TraceSummary&) override {
        if (!stopped_) builder_.finish();
        ended_ = true;
        changed_();
    }
    // Its first item can be compared: it is there and so is the next path after it, or the
    // side has ended.
    bool ready() const { return !items_.empty() && (ended_ || next_path() != nullptr); }
    bool exhausted() const { return ended_ && items_.empty(); }
    bool has_items() const { return !items_.empty(); }
    bool ended() const { return ended_; }
    const Item& front() const { return items_.front(); }
    const Path* next_path() const {
        for (size_t j = 1; j < items_.size(); ++j)
            if (items_[j].kind == Item::Kind::path) return &items_[j].path;
        return nullptr;
    }
    void pop() {
        last_line_ = items_.front().line();
        items_.pop_front();
    }
    // The line of the last item compared (0: none).
    int last_line() const { return last_line_; }
    // The result is known: the rest is not looked at.
    void stop() {
        stopped_ = true;
        items_.clear();
    }

private:
    void add(Item&& i) {
        items_.push_back(std::move(i));
        changed_();
    }
    ItemBuilder builder_;
    std::function<void()> changed_;
    std::deque<Item> items_;
    bool ended_ = false;
    bool stopped_ = false;
    int last_line_ = 0;
};

}  // namespace

std::optional<std::string> offsets_difference(const SelectedOffsets& job, const SelectedOffsets& program, int tool) {
    const auto at = [](int line) { return line > 0 ? fmt::format(" (line {})", line) : std::string(); };
    if (job.length != program.length) {
        const std::string prog = program.length.empty()
                                     ? (program.length_line > 0 ? fmt::format("with no tool length offset (cancelled at line {})",
                                                                              program.length_line)
                                                                : std::string("with no tool length offset selected"))
                                     : fmt::format("under the tool length offset {}{}", program.length.str(), at(program.length_line));
        return fmt::format("tool {} moves {} where the job's post selects {} for it: every position of the tool is off by "
                           "the difference between their lengths",
                           tool, prog, job.length.empty() ? std::string("none") : job.length.str());
    }
    if (job.work != program.work) {
        const std::string prog = program.work.empty() ? std::string("in no work offset selected (the control's active one)")
                                                      : fmt::format("in work offset {}{}", program.work.str(), at(program.work_line));
        const std::string expected = job.work.empty() ? std::string("none (the post selects none: the control's active one)")
                                                      : job.work.str();
        return fmt::format("tool {} moves {} where the job's work offset is {}: every position is off by the difference "
                           "between the two",
                           tool, prog, expected);
    }
    return std::nullopt;
}

OffsetCheck::OffsetCheck(const Machine& machine, std::string work_offset, std::function<void(const Mismatch&, const Step&)> found)
    : machine_(machine), found_(std::move(found)) {
    expected_.work = OffsetWord(work_offset);
}

void OffsetCheck::step(const Step& s) {
    if (s.kind == StepKind::tool_change) {
        expected_.length = OffsetWord(post_length_offset(machine_, s.tool));
        reported_.reset();
        return;
    }
    if (s.kind != StepKind::rapid && s.kind != StepKind::feed) return;
    if (s.offsets.same(expected_)) {
        reported_.reset();
        return;
    }
    // Once for each run of moves under the same wrong offsets.
    if (reported_ && reported_->same(s.offsets)) return;
    reported_ = s.offsets;
    if (auto d = offsets_difference(expected_, s.offsets, s.tool)) found_(Mismatch{s.line, *d}, s);
}

CompareTolerance compare_tolerance(const Machine& machine, double position) {
    return compare_tolerance(machine, has_reader(machine.dialect) ? read_resolution(machine) : ReadResolution{}, position);
}

CompareTolerance compare_tolerance(const Machine& machine, const ReadResolution& res, double position) {
    CompareTolerance t;
    // Half a unit on each of three axes is at most sqrt(3) half units away.
    t.position = std::max(position, res.position * std::sqrt(3.0));
    t.path = t.position + machine.tolerance + machine.arcs.chord_tolerance;
    t.feed = res.feed;
    t.dwell = res.dwell;
    t.rpm = res.rpm;
    t.arcs = machine.arcs;
    t.lathe = machine.kind == MachineKind::lathe;
    t.x_diameter = machine.x_diameter;
    return t;
}

class TraceComparer::Impl {
public:
    Impl(const CompareTolerance& tol, std::function<bool()> more_actual)
        : tol_(tol), more_actual_(std::move(more_actual)), job_(tol.path, &tol_.arcs, [this] { advance(); }),
          prog_(tol.path, nullptr, [this] { advance(); }) {}

    // Compares what both sides have, asking for more of the actual side while the expected one
    // waits for it.
    void advance() {
        if (advancing_) return;
        advancing_ = true;
        while (!decided_) {
            if (job_.ready() && prog_.ready()) {
                if (auto m = compare_items(job_.front(), prog_.front(), job_.next_path(), prog_.next_path(), tol_)) {
                    decide(std::move(m));
                    break;
                }
                job_.pop();
                prog_.pop();
            } else if (job_.exhausted() && prog_.exhausted()) {
                decide(std::nullopt);
            } else if (prog_.exhausted() && job_.has_items()) {
                decide(Mismatch{prog_.last_line(), fmt::format("the program ends where the job still has {}", describe_item(job_.front(), tol_))});
            } else if (job_.exhausted() && prog_.has_items()) {
                decide(Mismatch{prog_.front().line(),
                                fmt::format("the program has {} after the end of the job's motion", describe_item(prog_.front(), tol_))});
            } else if ((job_.ready() || job_.exhausted()) && !prog_.ended() && more_actual_) {
                if (!more_actual_() && !prog_.ended()) throw std::logic_error("the actual trace ended without finishing");
            } else {
                break;
            }
        }
        advancing_ = false;
    }

    void decide(std::optional<Mismatch> m) {
        mismatch_ = std::move(m);
        decided_ = true;
        job_.stop();
        prog_.stop();
    }

    CompareTolerance tol_;
    std::function<bool()> more_actual_;
    Side job_, prog_;
    bool advancing_ = false, decided_ = false;
    std::optional<Mismatch> mismatch_;
};

TraceComparer::TraceComparer(const CompareTolerance& tolerance, std::function<bool()> more_actual)
    : impl_(std::make_unique<Impl>(tolerance, std::move(more_actual))) {}

TraceComparer::~TraceComparer() = default;

TraceSink& TraceComparer::expected() { return impl_->job_; }

TraceSink& TraceComparer::actual() { return impl_->prog_; }

bool TraceComparer::decided() const { return impl_->decided_; }

const std::optional<Mismatch>& TraceComparer::mismatch() const { return impl_->mismatch_; }

std::optional<Mismatch> compare_traces(const Trace& expected, const Trace& actual, const CompareTolerance& tol) {
    // The expected trace leads and the actual one follows as it is asked for, as verify --job
    // reads a program.
    size_t next = 0;
    TraceComparer* self = nullptr;
    TraceComparer comparer(tol, [&] {
        if (next < actual.steps.size()) {
            self->actual().step(actual.steps[next++]);
            return true;
        }
        if (next++ == actual.steps.size()) self->actual().finish({});
        return false;
    });
    self = &comparer;
    for (const Step& s : expected.steps) comparer.expected().step(s);
    comparer.expected().finish({});
    if (!comparer.decided()) throw std::logic_error("a comparison of two finished traces is not decided");
    return comparer.mismatch();
}

}  // namespace camgen
