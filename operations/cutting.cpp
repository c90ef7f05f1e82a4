#include "camgen/operations/cutting.hpp"
#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/common/large_buffer.hpp"
#include "camgen/operations/dxf_source.hpp"
#include "camgen/operations/shapes.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

constexpr KeySpec head_key_table[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true}, .description = "a tool number from tools (its diameter is the cutter's)"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"", .description = "written as a comment before the operation"},
};

constexpr KeySpec tolerance_key_table[] = {
    {.key = "tolerance", .quantity = Quantity::length, .min = Bound{0.0001, true}, .description = "how far the lines of an arc the machine cannot write may stray from it (default: the machine's "
                    "chordTolerance, which also caps it)"},
};

// The keys of a profile's start and path; "start" and "path" are renamed by profile_keys.
constexpr KeySpec profile_key_table[] = {
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length, .description = "where the profile starts [x, y]"},
    {.key = "path", .type = JsonType::array, .ref = "contourElement", .min_items = 1, .description = "the profile's lines and arcs in XY, each starting where the previous one ends"},
    {.key = "profile", .type = JsonType::object, .ref = "profileSource", .description = "or the profile from a DXF drawing (its lines, arcs and polylines on the selection, chained) or a shape (rectangle, circle, slot, polygon)"},
};

constexpr KeySpec depth_pass_key_table[] = {
    {.key = "stepDown", .quantity = Quantity::length, .min = Bound{0, false}, .description = "the most each depth pass takes (default: one pass at endDepth)"},
    {.key = "equalSteps", .type = JsonType::boolean, .default_json = "true", .description = "passes of equal depth (else: full steps and a smaller last one)"},
};

constexpr KeySpec feed_key_table[] = {
    {.key = "feed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "cutting feed; required unless the tool comes from the library with a feedPerTooth for the job's material (default: then fz x flutes x rpm)"},
    {.key = "plungeFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed straight down (default: feed)"},
    {.key = "rampFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of a ramp (default: feed)"},
    {.key = "leadInFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of the lead-in (default: feed)"},
    {.key = "leadOutFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of the lead-out (default: feed)"},
    {.key = "finishingFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .description = "feed of the finishing pass (default: feed)"},
};

// The keys of a profile element: exactly one of them.
constexpr KeySpec contour_element_keys[] = {
    {.key = "line", .type = JsonType::point, .quantity = Quantity::length, .description = "a straight line to [x, y]"},
    {.key = "arc", .type = JsonType::object, .ref = "contourArc", .description = "an arc about an absolute centre"},
};

constexpr KeySpec contour_arc_keys[] = {
    {.key = "end", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "end point [x, y]"},
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "absolute centre [x, y]"},
    {.key = "direction", .type = JsonType::string, .required = true, .choices = &choices_of<arc_directions>, .description = "seen from +Z: cw (G2) or ccw (G3)"},
};

constexpr KeySpec finishing_keys[] = {
    {.key = "radialStock", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0", .description = "what the roughing passes leave on the wall for the finishing pass"},
    {.key = "axialStock", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0", .description = "what the roughing passes leave on the floor for the finishing pass"},
    {.key = "stepDown", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the finishing step: the most each finishing pass takes in depth (default: one pass at endDepth)"},
};

constexpr Named<Lead::Kind> lead_kinds[] = {
    {Lead::Kind::none, "none", "straight onto the profile (control compensation gets a line anyway)"},
    {Lead::Kind::arc, "arc", "a tangent arc"},
    {Lead::Kind::line, "line", "a straight line"},
};
constexpr KeySpec lead_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .choices = &choices_of<lead_kinds>, .description = "none, arc or line"},
    {.key = "radius", .quantity = Quantity::length, .min = Bound{0, false}, .description = "arc: its radius (default: the tool's diameter)"},
    {.key = "sweep", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{180, true}, .default_json = "90", .description = "arc: degrees turned"},
    {.key = "length", .quantity = Quantity::length, .min = Bound{0, false}, .description = "line: its length (default: the tool's diameter)"},
    {.key = "angle", .quantity = Quantity::angle, .min = Bound{0, true}, .max = Bound{90, true}, .default_json = "0", .description = "line: degrees from the profile's tangent towards the tool's side"},
};

constexpr Named<Ramp::Kind> ramp_kinds[] = {
    {Ramp::Kind::plunge, "plunge", "straight down at plungeFeed"},
    {Ramp::Kind::along, "along", "down along the profile at an angle, then back to its start at depth"},
    {Ramp::Kind::helix, "helix", "a helix down before the lead-in"},
};
constexpr KeySpec ramp_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .choices = &choices_of<ramp_kinds>, .description = "plunge, along or helix"},
    {.key = "angle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{45, true}, .default_json = "5", .description = "degrees above horizontal"},
    {.key = "radius", .quantity = Quantity::length, .min = Bound{0, false}, .description = "helix: its radius (default: the tool's radius)"},
};

constexpr KeySpec tab_keys[] = {
    {.key = "count", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true}, .max = Bound{1000, true}, .description = "tabs spread by length over the profile's straight runs (and arcs long enough), clear of the corners"},
    {.key = "spacing", .quantity = Quantity::length, .min = Bound{0, false}, .description = "or one tab every so many mm of the profile, spread the same way"},
    {.key = "at", .type = JsonType::array, .quantity = Quantity::length, .min_items = 1, .description = "or tabs at these places: each a distance along the profile as drawn from its start, or a point [x, y] near the profile (its nearest point; at most the tool's diameter away)"},
    {.key = "width", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "width of a tab at its top, at its narrowest: in the middle of the cut (a tool diameter wider where it meets the wall)"},
    {.key = "height", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "height of a tab above the bottom of the cut"},
    {.key = "rampAngle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{90, true}, .default_json = "90", .description = "degrees of a tab's flanks above horizontal: below 90 a trapezoid, the tool climbing and descending along the path"},
};


// ---- Where the tabs go: planned on reading, on the profile as drawn.

// The length of segment k of `p`, which starts at `from` (an arc: its sweep times the start's radius).
double tab_segment_length(const Profile& p, std::size_t k, Vec2 from) {
    const ProfileSegment& s = p.segments[k];
    return s.centre ? segment_sweep(p, k) * norm(from - *s.centre) : norm(s.end - from);
}

// The unit tangent of travel of segment `s` at its point `at`.
Vec2 tab_tangent(const ProfileSegment& s, Vec2 from, Vec2 at) {
    if (!s.centre) return (s.end - from) * (1.0 / norm(s.end - from));
    const Vec2 radial = (at - *s.centre) * (1.0 / norm(at - *s.centre));
    return s.direction == ArcDirection::ccw ? left_of(radial) : (left_of(radial) * -1);
}

// The point of `p` nearest to `x`: how far along `p` it is, and how far from `x`.
struct TabNearest {
    double along = 0.0;
    double distance = 0.0;
};
TabNearest tab_nearest(const Profile& p, Vec2 x) {
    TabNearest best{0.0, norm(x - p.start)};
    double done = 0.0;
    Vec2 from = p.start;
    for (std::size_t k = 0; k < p.segments.size(); ++k) {
        const ProfileSegment& s = p.segments[k];
        const double l = tab_segment_length(p, k, from);
        auto consider = [&](double along, double d) {
            if (d < best.distance) best = {along, d};
        };
        if (l > 0 && !s.centre) {
            const Vec2 d = s.end - from;
            const double t = std::clamp(((x - from).x * d.x + (x - from).y * d.y) / (l * l), 0.0, 1.0);
            consider(done + t * l, norm((x - (from + (d * t)))));
        } else if (l > 0) {
            const Vec2 c = *s.centre;
            const double r = norm(from - c);
            const double sweep = l / r;
            const double sign = s.direction == ArcDirection::ccw ? 1.0 : -1.0;
            double delta = sign * (std::atan2(x.y - c.y, x.x - c.x) - std::atan2(from.y - c.y, from.x - c.x));
            delta = std::fmod(std::fmod(delta, 2 * pi) + 2 * pi, 2 * pi);
            if (delta <= sweep) consider(done + delta * r, std::abs(norm(x - c) - r));
            consider(done, norm(x - from));
            consider(done + l, norm(x - s.end));
        }
        done += l;
        from = s.end;
    }
    return best;
}

// A stretch of a closed profile that can hold tabs: a straight run (consecutive collinear
// lines, across the profile's start too) or an arc (consecutive arcs about one centre), from
// `from` to `from + length` mm along the profile (`from` < 0: it goes on past the profile's
// end onto its start), with what the tool's path does there.
struct TabRun {
    double from = 0.0;
    double length = 0.0;
    bool arc = false;
    double scale = 1.0;        // the tool path's length per mm of the profile: an arc's (R -+ d) / R
    double corner_in = 0.0;    // what a concave corner at either end takes off the tool path, mm
    double corner_out = 0.0;
    Vec2 t_in, t_out;          // tangents of travel at its ends
    Vec2 centre;               // an arc's
    double radius = 0.0;
    ArcDirection direction = ArcDirection::ccw;
};

// The runs of closed profile `p` with the tool `tool_left` of its drawn direction, its centre
// `d` mm from the profile (0: on it).
std::vector<TabRun> tab_runs(const Profile& p, bool tool_left, double d) {
    std::vector<TabRun> runs;
    auto joins = [](const TabRun& a, const TabRun& b) {
        if (a.arc != b.arc) return false;
        if (!a.arc) return std::abs(a.t_out.x * b.t_in.y - a.t_out.y * b.t_in.x) < 1e-9 && a.t_out.x * b.t_in.x + a.t_out.y * b.t_in.y > 0;
        return norm(a.centre - b.centre) < 1e-6 && std::abs(a.radius - b.radius) < 1e-6 && a.direction == b.direction;
    };
    double done = 0.0;
    Vec2 from = p.start;
    for (std::size_t k = 0; k < p.segments.size(); ++k) {
        const ProfileSegment& s = p.segments[k];
        TabRun r;
        r.from = done;
        r.length = tab_segment_length(p, k, from);
        r.arc = s.centre.has_value();
        r.t_in = tab_tangent(s, from, from);
        r.t_out = tab_tangent(s, from, s.end);
        if (r.arc) {
            r.centre = *s.centre;
            r.radius = norm(from - *s.centre);
            r.direction = s.direction;
        }
        if (!runs.empty() && joins(runs.back(), r)) {
            runs.back().length += r.length;
            runs.back().t_out = r.t_out;
        } else {
            runs.push_back(r);
        }
        done += r.length;
        from = s.end;
    }
    if (runs.size() > 1 && joins(runs.back(), runs.front())) {
        runs.front().from -= runs.back().length;
        runs.front().length += runs.back().length;
        runs.front().t_in = runs.back().t_in;
        runs.pop_back();
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
        TabRun& r = runs[i];
        TabRun& next = runs[(i + 1) % runs.size()];
        const double turn = std::atan2(r.t_out.x * next.t_in.y - r.t_out.y * next.t_in.x, r.t_out.x * next.t_in.x + r.t_out.y * next.t_in.y);
        // A corner turning towards the tool shortens its path on both sides by d tan(turn / 2).
        if (std::abs(turn) > 1e-9 && (turn > 0) == tool_left) {
            const double cut = std::abs(turn) < 179 * rad_per_deg ? d * std::tan(std::abs(turn) / 2) : 1e9;
            r.corner_out = cut;
            next.corner_in = cut;
        }
        if (r.arc) {
            const bool centre_on_tool_side = (r.direction == ArcDirection::ccw) == tool_left;
            r.scale = std::max(0.0, (r.radius + (centre_on_tool_side ? -d : d)) / r.radius);
        }
    }
    return runs;
}

// What the tool needs around one tab: `half` mm each side of its centre along its path (half
// the tab's width, the tool's radius and the flank), `foot` the tab's width on the part at its
// foot (with its flanks).
struct TabReach {
    double half = 0.0;
    double foot = 0.0;
};
TabReach tab_reach(const Tabs& tabs, double tool_radius) {
    const double flank = tabs.ramp_angle < 90 ? tabs.height / std::tan(tabs.ramp_angle * rad_per_deg) : 0.0;
    return {tabs.width / 2 + tool_radius + flank, tabs.width + 2 * flank};
}

// Where on run `r` a tab's centre may go without its tool path reaching a corner (or past the
// profile's start): one or two stretches [lo, hi] of the profile's length.
std::vector<std::pair<double, double>> tab_room(const TabRun& r, double half) {
    if (r.scale <= 0) return {};
    const double h = half / r.scale;
    const double lo = r.from + h + r.corner_in, hi = r.from + r.length - h - r.corner_out;
    std::vector<std::pair<double, double>> out;
    auto keep = [&](double a, double b) {
        if (b >= a - 1e-9) out.push_back({a, std::max(a, b)});
    };
    if (r.from < 0) {  // the profile starts on this run: the tool goes down there
        keep(lo, std::min(hi, -h));
        keep(std::max(lo, h), hi);
    } else {
        keep(lo, hi);
    }
    return out;
}

// Tabs spread by length: `count` of them over the runs' room, one a straight run on those with
// the most room first, then each next one on the run (straight or arc) whose room per tab stays
// largest (ties: the earlier run), evenly within each stretch. `centres` empty when they do not fit; `capacity`:
// how many would.
struct TabSpread {
    std::vector<double> centres;
    int capacity = 0;
};
TabSpread spread_tabs(const std::vector<TabRun>& runs, int count, double half, double total) {
    struct Stretch {
        std::size_t run;
        double lo, hi, pitch;
        int tabs = 0;
        int capacity() const { return std::max(1, static_cast<int>(std::floor((hi - lo) / pitch + 1e-9))); }
        bool more() const { return tabs < capacity(); }
    };
    std::vector<Stretch> stretches;
    std::vector<double> room(runs.size(), -1.0);  // a run's room (-1: none)
    TabSpread out;
    for (std::size_t i = 0; i < runs.size(); ++i)
        for (const auto& [lo, hi] : tab_room(runs[i], half)) {
            stretches.push_back({i, lo, hi, 2 * half / runs[i].scale});
            room[i] = std::max(room[i], 0.0) + (hi - lo);
            out.capacity += stretches.back().capacity();
        }
    if (out.capacity < count) return out;
    // One a run first on the straight runs (the sides; arcs too when there is no straight run).
    std::vector<std::size_t> usable, sides;
    for (std::size_t i = 0; i < runs.size(); ++i)
        if (room[i] >= 0) usable.push_back(i);
    for (std::size_t i : usable)
        if (!runs[i].arc) sides.push_back(i);
    if (sides.empty()) sides = usable;
    std::stable_sort(sides.begin(), sides.end(), [&](std::size_t a, std::size_t b) { return room[a] > room[b]; });
    // A run's next tab goes to its stretch with the most room per tab that takes one more.
    auto more = [&](std::size_t i) { return std::any_of(stretches.begin(), stretches.end(), [&](const Stretch& s) { return s.run == i && s.more(); }); };
    auto add_to = [&](std::size_t i) {
        Stretch* best = nullptr;
        for (Stretch& s : stretches)
            if (s.run == i && s.more() && (!best || (s.hi - s.lo) / (s.tabs + 1) > (best->hi - best->lo) / (best->tabs + 1) + 1e-12)) best = &s;
        ++best->tabs;
    };
    std::vector<int> per_run(runs.size(), 0);
    int placed = 0;
    for (std::size_t k = 0; k < sides.size() && placed < count; ++k, ++placed) {
        add_to(sides[k]);
        ++per_run[sides[k]];
    }
    for (; placed < count; ++placed) {
        std::optional<std::size_t> pick;
        for (std::size_t i : usable)
            if (more(i) && (!pick || room[i] / (per_run[i] + 1) > room[*pick] / (per_run[*pick] + 1) + 1e-12)) pick = i;
        add_to(*pick);  // the capacity holds count: some run takes more
        ++per_run[*pick];
    }
    for (const Stretch& s : stretches)
        for (int j = 0; j < s.tabs; ++j) {
            const double c = s.lo + (s.hi - s.lo) * (j + 0.5) / s.tabs;
            out.centres.push_back(c < 0 ? c + total : c);
        }
    std::sort(out.centres.begin(), out.centres.end());
    return out;
}

// The run that holds a tab at `at` mm along a profile `total` long (its centre on it, its foot
// on it if any run holds it so), and `at` in that run's terms.
std::pair<const TabRun*, double> tab_run_at(const std::vector<TabRun>& runs, double at, double foot, double total) {
    std::pair<const TabRun*, double> on{nullptr, at};
    for (const TabRun& r : runs)
        for (double x : {at, at - total}) {
            if (x < r.from - 1e-9 || x > r.from + r.length + 1e-9) continue;
            const bool fits = x - foot / 2 >= r.from - 1e-9 && x + foot / 2 <= r.from + r.length + 1e-9;
            if (fits) return {&r, x};
            if (!on.first) on = {&r, x};
        }
    return on;
}

// The tabs' centres along the profile as drawn (see Tabs): spread, or the job's positions
// checked against the runs they sit on, the profile's start and each other.
void plan_tabs(Tabs& tabs, Fields& t, const JobInput& in, const TabGeometry& g, const std::vector<std::string>& at_paths,
               const char* count_key) {
    const double total = profile_length(*g.profile);
    const std::vector<TabRun> runs = tab_runs(*g.profile, g.tool_left, g.distance);
    const TabReach reach = tab_reach(tabs, g.tool_radius);
    const std::string lift = fmt::format("the tool lifts over {} along its path for each", in.show(2 * reach.half));
    if (tabs.at.empty()) {
        TabSpread spread = spread_tabs(runs, tabs.count, reach.half, total);
        if (!spread.centres.empty()) {
            tabs.centres = std::move(spread.centres);
            return;
        }
        double longest = 0.0;
        for (const TabRun& r : runs) longest = std::max(longest, r.length);
        if (spread.capacity == 0)
            t.fail("width", fmt::format("a tab {} wide does not fit on any straight run or arc of this profile: {}, and stays {} clear of "
                                        "every corner and of the profile's start; the longest run is {} long",
                                        in.show(reach.foot), lift, in.show(reach.half), in.show(longest)));
        t.fail(count_key, fmt::format("{} tabs {} wide do not fit on this profile: {}, and stays {} clear of every corner and of the "
                                      "profile's start; its straight runs and arcs hold {}",
                                      tabs.count, in.show(reach.foot), lift, in.show(reach.half), spread.capacity));
    }
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t k = 0; k < tabs.at.size(); ++k) {
        const double at = tabs.at[k];
        const auto [run, x] = tab_run_at(runs, at, reach.foot, total);
        const std::string& where = at_paths[k];
        if (!run) json::fail(in.source(), where, fmt::format("{} is not on the profile, which is {} long", in.show(at), in.show(total)));
        const std::string what = run->arc ? "arc" : "straight run";
        if (x - reach.foot / 2 < run->from - 1e-9 || x + reach.foot / 2 > run->from + run->length + 1e-9)
            json::fail(in.source(), where,
                       fmt::format("a tab {} wide at its foot at {} along the profile does not fit on the {} it sits on, which is {} "
                                   "long (from {} to {} along the profile)",
                                   in.show(reach.foot), in.show(at), what, in.show(run->length),
                                   in.show(run->from < 0 ? run->from + total : run->from), in.show(std::fmod(run->from + run->length + total, total))));
        if (run->scale <= 0)
            json::fail(in.source(), where, fmt::format("the tab at {} sits on an arc of radius {} that the tool's path passes by", in.show(at),
                                                      in.show(run->radius)));
        const double h = reach.half / run->scale;
        if (std::min(at, total - at) < h - 1e-9)
            json::fail(in.source(), where,
                       fmt::format("the tab at {} is closer than {} to the profile's start, where the tool goes down and the passes "
                                   "join ({}): they would cut it; move it, or start the profile elsewhere",
                                   in.show(at), in.show(h), lift));
        order.push_back({at, k});
    }
    std::sort(order.begin(), order.end());
    for (std::size_t i = 0; order.size() > 1 && i < order.size(); ++i) {
        const auto [a, ka] = order[i];
        const auto [b, kb] = order[(i + 1) % order.size()];
        const double apart = i + 1 < order.size() ? b - a : b + total - a;
        const double need = reach.half / tab_run_at(runs, a, reach.foot, total).first->scale +
                            reach.half / tab_run_at(runs, b, reach.foot, total).first->scale;
        if (apart < need - 1e-9)
            json::fail(in.source(), at_paths[std::max(ka, kb)],
                       fmt::format("this tab and the one at {} overlap: their centres are {} apart along the profile and {}",
                                   at_paths[std::min(ka, kb)], in.show(apart), lift));
    }
    for (const auto& [a, k] : order) tabs.centres.push_back(a);
}

// The elements of a profile as JSON (lines and arcs).
void read_elements(Fields& f, const JobInput& in, const std::string& base, Profile& p, std::string_view what, std::string_view key) {
    const Json& elements = in.array(f, key);
    if (elements.empty()) f.fail(key, fmt::format("{} needs at least one line or arc", what));
    in.claim_path_elements(static_cast<double>(elements.size()), f, key);
    Vec2 at = p.start;
    for (std::size_t k = 0; k < elements.size(); ++k) {
        const std::string path = base + "/" + std::to_string(k);
        Fields e(elements[k], path, in.source());
        JobInput::known_keys(e, contour_element_keys);
        if (int(e.has("line")) + int(e.has("arc")) != 1) e.fail("", "a contour element needs exactly one of \"line\" or \"arc\"");
        ProfileSegment s;
        if (e.has("line")) {
            s.end = in.point(e, "line");
        } else {
            Fields a(e.required("arc"), e.path_of("arc"), in.source());
            JobInput::known_keys(a, contour_arc_keys);
            s.end = in.point(a, "end");
            s.centre = in.point(a, "centre");
            s.direction = a.choice("direction", arc_directions);
            const double r0 = norm(at - *s.centre), r1 = norm(s.end - *s.centre);
            if (std::abs(r0 - r1) > arc_radius_tolerance)
                a.fail("", fmt::format("start is {:.3f} mm from the centre but end is {:.3f} mm", r0, r1));
            if (r0 < min_profile_segment) a.fail("centre", "the centre is the arc's start: an arc needs a radius");
        }
        p.segments.push_back(s);
        at = s.end;
    }
}

// The lines of a profile read straight into numbers ({"line": [x, y]} each, see PackedArray).
void read_packed_lines(const json::PackedArray& packed, const std::string& base, const JobInput& in, Profile& p) {
    reserve_large(p.segments, packed.size());
    for (std::size_t k = 0; k < packed.size(); ++k) {
        auto line_path = [&] { return fmt::format("{}/{}/line", base, k); };
        if (packed.has_z(k)) json::fail(in.source(), line_path(), "expected a point [x, y], got an array");
        ProfileSegment s;
        s.end = {in.packed_coordinate(packed.x(k), [&] { return line_path() + "/0"; }),
                 in.packed_coordinate(packed.y(k), [&] { return line_path() + "/1"; })};
        p.segments.push_back(s);
    }
}

}  // namespace

void check_cutting_tool(Fields& f, const Tool& tool, std::string_view what) {
    if (tool.type == ToolType::thread_mill)
        f.fail("tool", fmt::format("tool {} ({}) is a thread mill: {} cuts with an end mill, a ball mill or a bull-nose end "
                                   "mill; a thread mill's teeth cut only a thread's flanks (the thread-mill operation)",
                                   tool.number, tool.path, what));
    // Tools whose side does not cut, or that do not turn about the spindle's axis as a mill
    // does: along a profile their diameter would be offset as a cutter's and cut air or rub.
    // A tool typed "drill" is refused too; one without a type (a drill by default) stays
    // allowed: jobs before tool types gave their end mills none (untyped_milling_note).
    switch (tool.type) {
    case ToolType::drill:
        if (!tool.type_given) break;
        [[fallthrough]];
    case ToolType::centre_drill:
    case ToolType::spot_drill:
    case ToolType::tap:
    case ToolType::reamer:
    case ToolType::boring_bar:
    case ToolType::turning_tool:
    case ToolType::grooving_tool:
    case ToolType::parting_tool:
    case ToolType::threading_tool:
        f.fail("tool", fmt::format("tool {} is a {}: {} cuts with an end mill, a ball mill or a bull-nose end mill (its "
                                   "side cuts along the profile; a {}'s does not){}",
                                   tool.number, tool_types[static_cast<int>(tool.type)].description, what,
                                   tool_types[static_cast<int>(tool.type)].description,
                                   tool.type == ToolType::drill ? "; give an end mill \"type\": \"end-mill\"" : ""));
    default:
        break;
    }
    if (!is_pointed_cutter(tool.type)) return;
    const std::string_view kind = tool_types[static_cast<int>(tool.type)].description;
    f.fail("tool", fmt::format("tool {} is {} {}: {} cuts with an end mill, a ball mill or a bull-nose end mill (the side "
                               "of a pointed tool is not its diameter); a chamfer mill or a V-bit cuts chamfers with the "
                               "chamfer operation",
                               tool.number, kind.front() == 'e' ? "an" : "a", kind, what));
}

std::optional<std::string> untyped_milling_note(const Tool& tool) {
    if (tool.type != ToolType::drill || tool.type_given) return std::nullopt;
    return fmt::format("tool {} has no type: it mills as an end mill (a tool without a type is a drill, whose side does not "
                       "cut; give \"type\": \"end-mill\")",
                       tool.number);
}

Profile read_profile(Fields& f, const JobInput& in, std::string_view what, std::string_view start_key, std::string_view path_key,
                     std::vector<std::string>* notes) {
    if (f.has("profile") && start_key == "start") {
        if (f.has(start_key) || f.has(path_key)) f.fail("profile", fmt::format("give {} and {}, or profile, not both", start_key, path_key));
        if (std::optional<Profile> shape = read_shape_profile(f, in, "profile")) return std::move(*shape);
        std::vector<std::string> own;
        const double tolerance = read_tolerance(f, in).value_or(0.01);
        DxfProfiles d = read_dxf_profiles(f, in, "profile", tolerance, notes ? *notes : own);
        if (d.profiles.size() != 1) {
            std::string list;
            for (std::size_t i = 0; i < d.profiles.size() && i < 8; ++i)
                list += fmt::format("{}{} {}", i ? "; " : "", d.closed[i] ? "a closed profile from" : "an open profile from", d.describe[i]);
            if (d.profiles.size() > 8) list += fmt::format("; and {} more", d.profiles.size() - 8);
            f.fail("profile", fmt::format("{} takes one profile, but the selection holds {}: {}; select one by layer, colour, linetype or "
                                          "block (or raise gapTolerance to join pieces)",
                                          what, d.profiles.size(), list));
        }
        Profile& p = d.profiles.front();
        if (auto k = first_short_segment(p, min_profile_segment))
            f.fail("profile", fmt::format("segment {} of {} is shorter than {} mm", *k, d.describe.front(), min_profile_segment));
        if (!is_simple(p))
            f.fail("profile", fmt::format("the profile from {} crosses or touches itself", d.describe.front()));
        return std::move(p);
    }
    Profile p;
    p.start = in.point(f, start_key);
    const std::string base = f.path_of(path_key);
    if (const json::PackedArray* packed = in.packed(f.required(path_key))) {
        in.claim_path_elements(static_cast<double>(packed->size()), f, path_key);
        read_packed_lines(*packed, base, in, p);
    } else {
        read_elements(f, in, base, p, what, path_key);
    }
    // An arc's end within arc_radius_tolerance of its circle: the exact arc through both ends,
    // once, for every stage (make_arcs_exact, profile.hpp).
    make_arcs_exact(p, arc_radius_tolerance);
    if (auto k = first_short_segment(p, min_profile_segment))
        json::fail(in.source(), base + "/" + std::to_string(*k), fmt::format("this element is shorter than {} mm: remove it", min_profile_segment));
    if (!is_simple(p))
        f.fail(path_key, is_closed(p) ? "the profile crosses or touches itself" : "the open profile crosses or touches itself");
    return p;
}

Lead read_lead(Fields& f, const JobInput& in, std::string_view key, double tool_diameter) {
    Lead lead;
    const Json* value = f.member(key);
    if (!value) return lead;
    Fields l(*value, f.path_of(key), in.source());
    JobInput::known_keys(l, lead_keys);
    lead.kind = l.choice("type", lead_kinds);
    lead.radius = in.optional_length(l, "radius").value_or(tool_diameter);
    lead.sweep = l.optional_number("sweep").value_or(90.0);
    lead.length = in.optional_length(l, "length").value_or(tool_diameter);
    lead.angle = l.optional_number("angle").value_or(0.0);
    if (!(lead.radius > 0)) l.fail("radius", "radius must be > 0");
    if (!(lead.sweep > 0 && lead.sweep <= 180)) l.fail("sweep", "sweep must be more than 0 and at most 180 degrees");
    if (!(lead.length > 0)) l.fail("length", "length must be > 0");
    if (!(lead.angle >= 0 && lead.angle <= 90)) l.fail("angle", "angle must be from 0 to 90 degrees");
    return lead;
}

namespace {

// The feed of `key`, or `fallback`.
double feed_of(Fields& f, const JobInput& in, std::string_view key, double fallback) {
    const std::optional<double> v = in.optional_length(f, key);
    if (v && !(*v > 0)) f.fail(key, fmt::format("{} must be > 0", key));
    return v.value_or(fallback);
}


// What camgen cuts must be what the offset promises: every arc on its circle, and (for
// profiles of ordinary size) every segment's ends and middle at `distance` from the profile
// or farther. A path that is not is refused rather than cut (a fuzz finding: an offset "arc"
// whose end lay 49 mm from its centre on a radius-5 arc, the pocket's side missing).
void check_offset(const Profile& path, const Profile& walk, double distance, const char* which) {
    constexpr double slack = 1e-5;
    const bool sample = path.segments.size() * walk.segments.size() <= 25'000'000;
    Vec2 from = path.start;
    for (std::size_t k = 0; k < path.segments.size(); ++k) {
        const ProfileSegment& s = path.segments[k];
        bool bad = false;
        if (s.centre) bad = std::abs(norm(from - *s.centre) - norm(s.end - *s.centre)) > slack;
        if (!bad && sample) {
            Profile one;
            one.start = from;
            one.segments.push_back(s);
            for (double t : {0.0, 0.5, 1.0})
                if (distance_to(walk, point_at(one, t * profile_length(one)).point) < distance - slack) bad = true;
        }
        if (bad)
            throw PlanError("path", fmt::format("camgen could not offset this profile for the {} path (segment {} of its offset is "
                                                "wrong): please report it; use compensation control or side on meanwhile",
                                                which, k));
        from = s.end;
    }
}

// The shortest move written under G41/G42, mm (see plan).
constexpr double control_min_move = 0.01;

// Removes the segments shorter than `min_length` from a path: a line after one starts where the
// one before ends; else the segment before is extended to its end. Returns how many were removed.
std::size_t merge_short_segments(Profile& p, double min_length) {
    if (p.segments.size() < 2) return 0;
    std::vector<ProfileSegment> kept;
    kept.reserve(p.segments.size());
    std::size_t removed = 0;
    Vec2 from = p.start;
    for (std::size_t k = 0; k < p.segments.size(); ++k) {
        const ProfileSegment& s = p.segments[k];
        Profile one;
        one.start = from;
        one.segments.push_back(s);
        const bool next_is_line = k + 1 < p.segments.size() && !p.segments[k + 1].centre;
        if (profile_length(one) < min_length && (next_is_line || !kept.empty()) && p.segments.size() - removed > 2) {
            // The segment before reaches its end (an arc's end then lies off its circle by less
            // than min_length, which every control tolerates).
            if (!next_is_line) kept.back().end = s.end;
            // else: the next line starts where the one before ended
            ++removed;
            if (!next_is_line) from = s.end;
            continue;
        }
        kept.push_back(s);
        from = s.end;
    }
    p.segments = std::move(kept);
    return removed;
}

}  // namespace

OffsetPlan plan_offsets(const OffsetRequest& op, const std::function<std::string(double)>& show) {
    OffsetPlan plan;
    const Profile& profile = *op.profile;
    // Climb: the tool left of its travel with a clockwise spindle, right with a counter-clockwise one.
    plan.tool_left = tool_left_of_travel(op.direction, op.spindle);
    // The profile in the direction the tool walks it: reversed into a copy of its own only when
    // it must be (a contour of a million segments holds its profile and its paths, no more).
    Profile reversed_profile;
    const Profile* walk = &profile;
    bool reversed_walk = false;
    if (op.side != ContourSide::on) {
        OffsetSide drawn = OffsetSide::left;
        switch (op.side) {
            case ContourSide::left: drawn = OffsetSide::left; break;
            case ContourSide::right: drawn = OffsetSide::right; break;
            case ContourSide::inside: drawn = side_for(orientation(profile), Region::inside); break;
            case ContourSide::outside: drawn = side_for(orientation(profile), Region::outside); break;
            case ContourSide::on: break;
        }
        if ((drawn == OffsetSide::left) != plan.tool_left) {
            reversed_profile = reversed(profile);
            walk = &reversed_profile;
            reversed_walk = true;
        }
    }
    const OffsetSide side = plan.tool_left ? OffsetSide::left : OffsetSide::right;
    const bool computer = op.compensation != CompensationMode::control;
    const double radius = computer && op.side != ContourSide::on ? op.tool_radius : 0.0;
    const double finishing_stock = op.finishing ? op.finishing_stock : 0.0;
    const std::size_t n = profile.segments.size();
    auto element_path = [&](std::size_t k) { return op.json_path + "/path/" + std::to_string(k); };
    // `last`: the walk is not needed after this path (a reversed one may then be moved into it).
    auto offset = [&](double distance, const char* which, bool last) -> Profile {
        if (distance <= 0 && last && reversed_walk) return std::move(reversed_profile);
        if (distance <= 0) return *walk;
        OffsetResult r = offset_profile(*walk, distance, side);
        if (r.empty())
            throw PlanError("path", fmt::format("the {} path is empty: the tool (radius {}) with the stock left does not fit {} the profile",
                                                which, show(op.tool_radius), op.side == ContourSide::inside ? "inside" : "beside"));
        for (const OffsetNote& note : r.notes) {
            std::string where = op.json_path + "/path";
            if (note.segment && *note.segment < n) where = element_path(reversed_walk ? n - 1 - *note.segment : *note.segment);
            plan.notes.push_back(fmt::format("{}: the {} path: {}", where, which, note.message));
        }
        check_offset(r.profile, *walk, distance, which);
        if (!r.others.empty())
            plan.notes.push_back(fmt::format("the {} path falls apart into {} pieces where the tool does not fit; only the longest "
                                             "is cut",
                                             which, r.others.size() + 1));
        return r.profile;
    };
    plan.rough = offset(radius + op.stock_to_leave + finishing_stock, "roughing", !op.finishing);
    if (op.finishing) plan.finish = offset(radius + op.stock_to_leave, "finishing", true);
    if (!computer || op.compensation != CompensationMode::computer) {
        // Under G41/G42 a move of a few microns (a stock offset's corner arc at a nearly straight
        // joint) is written rounded and may point anywhere: the control takes it for a corner it
        // cannot reach. Such moves are merged into their neighbours.
        std::size_t merged = merge_short_segments(plan.rough, control_min_move);
        if (op.finishing) merged += merge_short_segments(plan.finish, control_min_move);
        if (merged > 0)
            plan.notes.push_back(fmt::format("{}: {} move{} shorter than {} mm merged into {} neighbour{} (the control compensates: a "
                                             "shorter move, rounded, may point any way)",
                                             op.json_path, merged, merged == 1 ? "" : "s", control_min_move, merged == 1 ? "its" : "their",
                                             merged == 1 ? "" : "s"));
    }
    return plan;
}


std::vector<KeySpec> profile_keys(std::string_view what) {
    (void)what;
    return {std::begin(profile_key_table), std::end(profile_key_table)};
}

std::vector<KeySpec> cut_feed_keys() { return {std::begin(feed_key_table), std::end(feed_key_table)}; }

std::vector<KeySpec> depth_pass_keys() { return {std::begin(depth_pass_key_table), std::end(depth_pass_key_table)}; }

std::vector<ObjectSpec> cutting_objects() {
    std::vector<ObjectSpec> out = profile_source_objects();
    std::vector<ObjectSpec> own{
        {.name = "contourElement", .description = "one element of a profile: exactly one of line or arc",
         .keys = {std::begin(contour_element_keys), std::end(contour_element_keys)},
         .groups = {{.keys = {"line", "arc"}, .min = 1, .max = 1, .description = "exactly one of line or arc"}}},
        {.name = "contourArc", .description = "an arc in XY about an absolute centre", .keys = {std::begin(contour_arc_keys), std::end(contour_arc_keys)}},
        {.name = "contourFinishing", .description = "stock the roughing passes leave for the finishing pass",
         .keys = {std::begin(finishing_keys), std::end(finishing_keys)}},
        {.name = "contourLead", .description = "a lead-in or lead-out: a tangent arc or a straight line",
         .keys = {std::begin(lead_keys), std::end(lead_keys)}},
        {.name = "contourRamp", .description = "how the tool goes down to a pass", .keys = {std::begin(ramp_keys), std::end(ramp_keys)}},
        {.name = "contourTabs", .description = "tabs: count, spacing or places, width, height and flanks",
         .keys = {std::begin(tab_keys), std::end(tab_keys)},
         .groups = {{.keys = {"count", "spacing", "at"}, .min = 1, .max = 1, .description = "exactly one of count, spacing or at"}}},
    };
    for (ObjectSpec& o : own) out.push_back(std::move(o));
    return out;
}

Ramp read_ramp(Fields& f, const JobInput& in, std::string_view key, double tool_radius) {
    Ramp ramp;
    const Json* value = f.member(key);
    if (!value) return ramp;
    Fields r(*value, f.path_of(key), in.source());
    JobInput::known_keys(r, ramp_keys);
    ramp.kind = r.choice("type", ramp_kinds);
    ramp.angle = r.optional_number("angle").value_or(5.0);
    if (!(ramp.angle > 0 && ramp.angle <= 45)) r.fail("angle", "angle must be more than 0 and at most 45 degrees");
    ramp.radius = in.optional_length(r, "radius").value_or(tool_radius);
    if (!(ramp.radius > 0)) r.fail("radius", "radius must be > 0");
    return ramp;
}

std::optional<Finishing> read_finishing(Fields& f, const JobInput& in, double total_depth) {
    const Json* value = f.member("finishing");
    if (!value) return std::nullopt;
    Fields fin(*value, f.path_of("finishing"), in.source());
    JobInput::known_keys(fin, finishing_keys);
    Finishing finishing;
    finishing.radial_stock = in.optional_length(fin, "radialStock").value_or(0.0);
    finishing.axial_stock = in.optional_length(fin, "axialStock").value_or(0.0);
    if (!(finishing.radial_stock >= 0)) fin.fail("radialStock", "radialStock must be >= 0");
    if (!(finishing.axial_stock >= 0)) fin.fail("axialStock", "axialStock must be >= 0");
    if (finishing.axial_stock >= total_depth)
        fin.fail("axialStock", fmt::format("axialStock {} is not less than the depth of the cut ({})", in.show(finishing.axial_stock),
                                           in.show(total_depth)));
    finishing.step_down = in.optional_length(fin, "stepDown");
    if (finishing.step_down && !(*finishing.step_down > 0)) fin.fail("stepDown", "stepDown must be > 0");
    if (finishing.step_down && total_depth / *finishing.step_down > max_depth_passes)
        fin.fail("stepDown", fmt::format("stepDown {} makes more than {} passes", in.show(*finishing.step_down), max_depth_passes));
    return finishing;
}

double read_cutting_feed(Fields& f, const JobInput& in, const Tool& tool, double engagement, std::vector<std::string>& notes,
                         std::optional<CircularCut> circle) {
    const std::optional<double> computed = f.has("feed") ? std::nullopt : computed_milling_feed(tool, engagement, notes);
    if (computed) {
        if (!circle || !(circle->wall > 0) || !(circle->centre > 0)) return *computed;
        const double scale = circle->centre / circle->wall;
        // Rounded down to a whole mm/min as the computed feed is; within the machine's maxFeed.
        double centre = std::max(1.0, std::floor(*computed * scale));
        if (tool.cutting && tool.cutting->max_feed > 0) centre = std::min(centre, tool.cutting->max_feed);
        notes.push_back(fmt::format("the tool centre's feed is {} mm/min: the computed {} mm/min is the cutting edge's, at "
                                    "radius {}; the centre goes round at radius {}",
                                    number_text(centre), number_text(*computed), in.show(circle->wall), in.show(circle->centre)));
        return centre;
    }
    if (!f.has("feed") && tool.cutting)
        f.fail("feed", fmt::format("required key \"feed\" is missing, and the cutting data of {} for {} give no "
                                   "feedPerTooth to compute it from",
                                   tool.cutting->path, tool.cutting->material));
    const double feed = in.length(f, "feed");
    if (!(feed > 0)) f.fail("feed", "feed must be > 0");
    return feed;
}

CutFeeds read_cut_feeds(Fields& f, const JobInput& in, const Tool& tool, double engagement, std::vector<std::string>& notes) {
    CutFeeds feeds;
    feeds.cutting = read_cutting_feed(f, in, tool, engagement, notes);
    feeds.plunge = feed_of(f, in, "plungeFeed", feeds.cutting);
    feeds.ramp = feed_of(f, in, "rampFeed", feeds.cutting);
    feeds.lead_in = feed_of(f, in, "leadInFeed", feeds.cutting);
    feeds.lead_out = feed_of(f, in, "leadOutFeed", feeds.cutting);
    feeds.finishing = feed_of(f, in, "finishingFeed", feeds.cutting);
    return feeds;
}

std::optional<double> read_step_down(Fields& f, const JobInput& in, double total_depth) {
    const std::optional<double> step_down = in.optional_length(f, "stepDown");
    if (step_down && !(*step_down > 0)) f.fail("stepDown", "stepDown must be > 0");
    if (step_down && total_depth / *step_down > max_depth_passes)
        f.fail("stepDown", fmt::format("stepDown {} makes more than {} passes", in.show(*step_down), max_depth_passes));
    return step_down;
}

double read_step_over(Fields& f, const JobInput& in, double tool_diameter, double default_percent, std::string& key) {
    if (f.has("stepOver") && f.has("stepOverPercent")) f.fail("stepOverPercent", "give stepOver or stepOverPercent, not both");
    double step = 0.0;
    if (f.has("stepOver")) {
        key = "stepOver";
        step = in.length(f, "stepOver");
        if (!(step > 0)) f.fail("stepOver", "stepOver must be > 0");
    } else {
        key = "stepOverPercent";
        const double percent = f.optional_number("stepOverPercent").value_or(default_percent);
        if (!(percent > 0 && percent <= 100)) f.fail("stepOverPercent", "stepOverPercent must be more than 0 and at most 100");
        step = tool_diameter * percent / 100;
    }
    if (step > tool_diameter * (1 + 1e-9))
        f.fail(key, fmt::format("rows {} apart leave material between them: the step must be at most the tool diameter ({})", in.show(step),
                                in.show(tool_diameter)));
    if (step < tool_diameter * 0.01) f.fail(key, fmt::format("a step of {} is less than 1 % of the tool diameter", in.show(step)));
    return step;
}

std::vector<KeySpec> tolerance_keys() { return {std::begin(tolerance_key_table), std::end(tolerance_key_table)}; }

std::vector<KeySpec> operation_head_keys() { return {std::begin(head_key_table), std::end(head_key_table)}; }

std::optional<double> read_tolerance(Fields& f, const JobInput& in) {
    const std::optional<double> tolerance = in.optional_length(f, "tolerance");
    if (tolerance && !(*tolerance >= 0.0001)) f.fail("tolerance", "tolerance must be at least 0.0001 mm");
    return tolerance;
}

std::optional<Tabs> read_tabs(Fields& f, const JobInput& in, const TabGeometry& g, double total_depth, bool closed) {
    const Json* value = f.member("tabs");
    if (!value) return std::nullopt;
    Fields t(*value, f.path_of("tabs"), in.source());
    JobInput::known_keys(t, tab_keys);
    if (!closed) t.fail("", "tabs hold the part of a closed profile; this profile is open");
    if (int(t.has("count")) + int(t.has("spacing")) + int(t.has("at")) != 1) t.fail("", "tabs need exactly one of count, spacing or at");
    Tabs tabs;
    tabs.width = in.length(t, "width");
    tabs.height = in.length(t, "height");
    if (!(tabs.width > 0)) t.fail("width", "width must be > 0");
    if (!(tabs.height > 0)) t.fail("height", "height must be > 0");
    if (tabs.height >= total_depth)
        t.fail("height", fmt::format("a tab {} high does not fit in a cut {} deep", in.show(tabs.height), in.show(total_depth)));
    tabs.ramp_angle = t.optional_number("rampAngle").value_or(90.0);
    if (!(tabs.ramp_angle > 0 && tabs.ramp_angle <= 90)) t.fail("rampAngle", "rampAngle must be more than 0 and at most 90 degrees");
    const double length = profile_length(*g.profile);
    std::vector<std::string> at_paths;
    const char* count_key = "count";
    if (t.has("count")) {
        tabs.count = t.integer("count");
        if (tabs.count < 1 || tabs.count > 1000) t.fail("count", "count must be from 1 to 1000");
    } else if (t.has("spacing")) {
        count_key = "spacing";
        const double spacing = in.length(t, "spacing");
        if (!(spacing > 0)) t.fail("spacing", "spacing must be > 0");
        const double n = std::floor(length / spacing);
        if (n > 1000) t.fail("spacing", "spacing makes more than 1000 tabs");
        tabs.count = std::max(1, static_cast<int>(n));
    } else {
        const Json& places = in.array(t, "at");
        if (places.empty()) t.fail("at", "at needs at least one place");
        if (places.size() > 1000) t.fail("at", "at names more than 1000 tabs");
        for (std::size_t k = 0; k < places.size(); ++k) {
            const std::string where = t.path_of("at") + "/" + std::to_string(k);
            at_paths.push_back(where);
            if (places[k].is_array()) {
                const Vec2 x = in.point(places[k], where);
                const TabNearest near = tab_nearest(*g.profile, x);
                if (near.distance > g.tool_diameter)
                    json::fail(in.source(), where, fmt::format("this point is {} from the profile, more than the tool's diameter ({})",
                                                               in.show(near.distance), in.show(g.tool_diameter)));
                tabs.at.push_back(near.along);
            } else {
                if (!places[k].is_number())
                    json::fail(in.source(), where, "expected a distance along the profile or a point [x, y], got " + JobInput::describe(places[k]));
                const double at = in.coordinate(places[k], where);
                if (!(at >= 0 && at <= length))
                    json::fail(in.source(), where, fmt::format("{} is not on the profile: it is {} long", in.show(at), in.show(length)));
                tabs.at.push_back(at);
            }
        }
        tabs.count = static_cast<int>(tabs.at.size());
    }
    plan_tabs(tabs, t, in, g, at_paths, count_key);
    return tabs;
}

GuardBlame guard_blame(Movement movement, bool rapid, bool control) {
    switch (rapid ? Movement::cutting : movement) {
        case Movement::lead_in:
            return {"leadIn", control ? "start the profile in the middle of a straight side with room for the tool beside it, or give a "
                                        "leadIn that stays clear"
                                      : "give a shorter or different leadIn, or start the profile where the lead has room"};
        case Movement::lead_out: return {"leadOut", "give a shorter or different leadOut, or end the profile where the lead has room"};
        case Movement::ramp: return {"ramp", "give a smaller ramp radius, a plunge, or start the profile where the ramp has room"};
        case Movement::plunge:
            // The tool goes down where the lead-in starts: the lead decides where that is.
            return {"leadIn", control ? "start the profile in the middle of a straight side with room for the tool beside it, or give a "
                                        "leadIn that starts clear of the part"
                                      : "give a leadIn that starts clear of the part, or start the profile where there is room"};
        case Movement::cutting:
        case Movement::finishing: return {"path", "the tool does not fit the profile there"};
    }
    return {"path", "the tool does not fit the profile there"};
}

std::vector<double> pass_depths(double top, double bottom, std::optional<double> step_down, bool equal_steps) {
    const double total = top - bottom;
    if (!step_down || *step_down >= total) return {bottom};
    const int n = static_cast<int>(std::ceil(total / *step_down - 1e-9));
    std::vector<double> z;
    for (int k = 1; k < n; ++k) z.push_back(equal_steps ? top - total * k / n : top - *step_down * k);
    z.push_back(bottom);
    return z;
}


// The length of the straight move that switches compensation on or off: LinuxCNC wants an
// entry move at least the tool radius long; a tenth more keeps it so after rounding.
double Cutter::switch_length() const { return std::max(s_.tool_radius * 1.1, s_.tool_radius + 0.1); }

Vec2 Cutter::side_normal(Vec2 t) const { return s_.tool_left ? left_of(t) : (left_of(t) * -1); }

// A straight lead under control compensation: the control sets the tool a radius square to
// the move that switches compensation on (LinuxCNC) or to the next one (Fanuc), so that move
// runs from where the tool goes down, clear of the part, to a point on the profile's tangent
// a little before its start, and a straight run along the tangent takes the tool onto the
// profile; the lead's angle and length are those of the first move (none: square to the
// path). The lead-out mirrors it: on along the path (a closed one: over its start again; an
// open one: straight on past its end), then away.
Profile Cutter::control_line_lead_in(const Profile& p) const {
    const ProfilePoint s = point_at(p, 0.0);
    Lead lead = s_.lead_in;
    if (lead.kind == Lead::Kind::none) lead = Lead{Lead::Kind::line, 0, 90, switch_length(), 90};
    const double a = lead.angle * rad_per_deg;
    const Vec2 q = s.point - (s.tangent * switch_length());
    Profile out;
    out.start = (q - (s.tangent * (lead.length * std::cos(a)))) + (side_normal(s.tangent) * (lead.length * std::sin(a)));
    out.segments.push_back({q, std::nullopt, ArcDirection::ccw});
    out.segments.push_back({s.point, std::nullopt, ArcDirection::ccw});
    return out;
}

Profile Cutter::control_line_lead_out(const Profile& p) const {
    Lead lead = s_.lead_out;
    if (lead.kind == Lead::Kind::none) lead = Lead{Lead::Kind::line, 0, 90, switch_length(), 90};
    const double a = lead.angle * rad_per_deg;
    const double total = profile_length(p);
    Profile out;
    out.start = point_at(p, total).point;
    ProfilePoint e;
    if (is_closed(p)) {
        const Profile over = sub_profile(p, 0.0, std::min(switch_length(), total));
        out.segments = over.segments;
        e = point_at(over, profile_length(over));
    } else {
        e = point_at(p, total);
        e.point = e.point + (e.tangent * switch_length());
        out.segments.push_back({e.point, std::nullopt, ArcDirection::ccw});
    }
    const Vec2 away = (e.point + (e.tangent * (lead.length * std::cos(a)))) + (side_normal(e.tangent) * (lead.length * std::sin(a)));
    out.segments.push_back({away, std::nullopt, ArcDirection::ccw});
    return out;
}

// The lead-in onto `p`'s start; its path's start is where the tool goes down.
Profile Cutter::lead_in(const Profile& p) const {
    const ProfilePoint s = point_at(p, 0.0);
    Lead lead = s_.lead_in;
    if (control_compensates() && lead.kind != Lead::Kind::arc) return control_line_lead_in(p);
    Profile out;
    out.start = s.point;
    Vec2 tangent_at_start = s.tangent;  // of travel where the lead begins
    if (lead.kind == Lead::Kind::arc) {
        const double rho = std::max(lead.radius, control_compensates() ? s_.tool_radius * 1.5 : 0.0);
        const Vec2 c = s.point + (side_normal(s.tangent) * rho);
        const double turn = (s_.tool_left ? -1 : 1) * lead.sweep * rad_per_deg;
        out.start = c + rotated((s.point - c), turn);
        out.segments.push_back({s.point, c, s_.tool_left ? ArcDirection::ccw : ArcDirection::cw});
        const Vec2 radial = (out.start - c) * (1.0 / rho);
        tangent_at_start = s_.tool_left ? left_of(radial) : (left_of(radial) * -1);
    } else if (lead.kind == Lead::Kind::line) {
        const double a = lead.angle * rad_per_deg;
        out.start = (s.point - (s.tangent * (lead.length * std::cos(a)))) + (side_normal(s.tangent) * (lead.length * std::sin(a)));
        out.segments.push_back({s.point, std::nullopt, ArcDirection::ccw});
        tangent_at_start = (s.point - out.start) * (1.0 / lead.length);
    }
    if (control_compensates() && lead.kind == Lead::Kind::arc) {
        // The compensation comes on along a straight line before the arc.
        Profile entry;
        entry.start = out.start - (tangent_at_start * switch_length());
        entry.segments.push_back({out.start, std::nullopt, ArcDirection::ccw});
        entry.segments.insert(entry.segments.end(), out.segments.begin(), out.segments.end());
        return entry;
    }
    return out;
}

// The lead-out from `p`'s end.
Profile Cutter::lead_out(const Profile& p) const {
    const ProfilePoint e = point_at(p, profile_length(p));
    Lead lead = s_.lead_out;
    if (control_compensates() && lead.kind != Lead::Kind::arc) return control_line_lead_out(p);
    Profile out;
    out.start = e.point;
    Vec2 tangent_at_end = e.tangent;
    if (lead.kind == Lead::Kind::arc) {
        const double rho = std::max(lead.radius, control_compensates() ? s_.tool_radius * 1.5 : 0.0);
        const Vec2 c = e.point + (side_normal(e.tangent) * rho);
        const double turn = (s_.tool_left ? 1 : -1) * lead.sweep * rad_per_deg;
        const Vec2 end = c + rotated((e.point - c), turn);
        out.segments.push_back({end, c, s_.tool_left ? ArcDirection::ccw : ArcDirection::cw});
        const Vec2 radial = (end - c) * (1.0 / rho);
        tangent_at_end = s_.tool_left ? left_of(radial) : (left_of(radial) * -1);
    } else if (lead.kind == Lead::Kind::line) {
        const double a = lead.angle * rad_per_deg;
        const Vec2 end = (e.point + (e.tangent * (lead.length * std::cos(a)))) + (side_normal(e.tangent) * (lead.length * std::sin(a)));
        out.segments.push_back({end, std::nullopt, ArcDirection::ccw});
        tangent_at_end = (end - e.point) * (1.0 / lead.length);
    }
    if (control_compensates() && lead.kind == Lead::Kind::arc) {
        const Vec2 from = out.segments.back().end;
        out.segments.push_back({(from + (tangent_at_end * switch_length())), std::nullopt, ArcDirection::ccw});
    }
    return out;
}

CompensationSide Cutter::compensation_side() const {
    const bool left = s_.compensation == CompensationMode::inverse_wear ? !s_.tool_left : s_.tool_left;
    return left ? CompensationSide::left : CompensationSide::right;
}

// The radius the control offsets by: the tool's when it compensates alone; with wear only
// the wear, which camgen does not know (0).
double Cutter::compensation_radius() const { return s_.compensation == CompensationMode::control ? s_.tool_radius : 0.0; }

void Cutter::rapid(Vec3 to) {
    if (known_ && to == at_) return;
    sink_.emit(Rapid{to});
    at_ = to;
    known_ = true;
}

void Cutter::feed_to(Vec3 to, double feed, Movement m) {
    if (to == at_) return;
    sink_.emit(Linear{to, feed, m});
    at_ = to;
}

// The segments of `p` from the tool's position, Z going linearly from `z0` to `z1` along it.
void Cutter::follow(const Profile& p, double z0, double z1, double feed, Movement m) {
    const double total = profile_length(p);
    double done = 0.0;
    Vec2 from = p.start;
    for (const ProfileSegment& s : p.segments) {
        Profile one;
        one.start = from;
        one.segments.push_back(s);
        done += profile_length(one);
        const double z = total > 0 ? z0 + (z1 - z0) * done / total : z1;
        const Vec3 to{s.end.x, s.end.y, z};
        if (s.centre)
            sink_.emit(Arc{to, {s.centre->x, s.centre->y, at_.z}, s.direction, Plane::xy, feed, 0, m});
        else
            sink_.emit(Linear{to, feed, m});
        at_ = to;
        from = s.end;
    }
}

// One pass along `p` at `z`, rising over the tabs where `z` is below their top.
void Cutter::cut_pass(const Profile& p, double z, double feed, Movement m) {
    const double tab_top = s_.tabs ? s_.z.bottom_z + s_.tabs->height : -1e300;
    if (!s_.tabs || z >= tab_top - 1e-9) {
        follow(p, z, z, feed, m);
        return;
    }
    follow_over_tabs(p, 0.0, profile_length(p), z, z, feed, m);
}


// Where along `p` the tool rises over the tabs: each tab's centre (planned on the profile
// as drawn) is the nearest point of `p` to it. Worked out once for each path.
const std::vector<Cutter::TabSpan>& Cutter::tab_intervals(const Profile& p) {
    if (tab_path_ == &p) return tab_spans_;
    tab_path_ = &p;
    tab_spans_.clear();
    const double half = s_.tabs->width / 2 + s_.tool_radius;
    for (double c : s_.tabs->centres) {
        const double along = tab_nearest(p, point_at(*s_.drawn, c).point).along;
        tab_spans_.push_back({along - half, along + half});
    }
    std::sort(tab_spans_.begin(), tab_spans_.end(), [](const TabSpan& x, const TabSpan& y) { return x.a < y.a; });
    return tab_spans_;
}

// From `x0` to `x1` mm along `p` (backwards when x1 < x0), the tool at `x0`, Z going
// linearly from `z0` to `z1` but never below a tab: up to its top where it begins (at `feed`,
// or along its flank at the ramp angle), over it, and down after it (at plungeFeed, or along
// the flank).
void Cutter::follow_over_tabs(const Profile& p, double x0, double x1, double z0, double z1, double feed, Movement m) {
    const double total = profile_length(p);
    const double top = s_.z.bottom_z + s_.tabs->height;
    const bool ramped = s_.tabs->ramp_angle < 90;
    const double slope = ramped ? std::tan(s_.tabs->ramp_angle * rad_per_deg) : 0.0;  // dz per mm on a flank
    const double flank = ramped ? s_.tabs->height / slope : 0.0;
    const double lo = std::min(x0, x1), hi = std::max(x0, x1);
    if (hi - lo <= 1e-12) return;
    const double grade = (z1 - z0) / (x1 - x0);
    auto base = [&](double x) { return z0 + grade * (x - x0); };
    // The tabs near [lo, hi], shifted by the path's length on a closed path.
    std::vector<TabSpan> near;
    const std::vector<double> shifts = is_closed(p) ? std::vector<double>{-total, 0.0, total} : std::vector<double>{0.0};
    for (const TabSpan& s : tab_intervals(p))
        for (double shift : shifts)
            if (s.b + shift + flank >= lo && s.a + shift - flank <= hi) near.push_back({s.a + shift, s.b + shift});
    // The floor the tabs set at x, on the piece of their outline that holds `probe`.
    auto floor_at = [&](double x, double probe) {
        double z = -1e300;
        for (const TabSpan& s : near) {
            if (probe < s.a - flank || probe > s.b + flank) continue;
            z = std::max(z, probe < s.a ? top - (s.a - x) * slope : probe > s.b ? top - (x - s.b) * slope : top);
        }
        return z;
    };
    // Every place where the Z the tool follows may bend or jump.
    std::vector<double> at{lo, hi};
    auto station = [&](double x) {
        if (x > lo && x < hi) at.push_back(x);
    };
    for (const TabSpan& s : near) {
        for (double x : {s.a - flank, s.a, s.b, s.b + flank}) station(x);
        if (grade != 0) station(x0 + (top - z0) / grade);
        if (ramped) {
            if (slope != grade) station((z0 - grade * x0 - top + s.a * slope) / (slope - grade));
            if (-slope != grade) station((z0 - grade * x0 - top - s.b * slope) / (-slope - grade));
        }
    }
    std::sort(at.begin(), at.end());
    if (x1 < x0) std::reverse(at.begin(), at.end());
    // Pieces on which the Z is linear, joined where one goes on as the other.
    struct Piece {
        double u, v, zu, zv;
    };
    std::vector<Piece> pieces;
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
        const double u = at[k], v = at[k + 1];
        if (std::abs(v - u) <= 1e-9) continue;
        const double probe = (u + v) / 2;
        const Piece q{u, v, std::max(base(u), floor_at(u, probe)), std::max(base(v), floor_at(v, probe))};
        if (!pieces.empty()) {
            Piece& last = pieces.back();
            const bool same_line = std::abs(last.zv - q.zu) <= 1e-9 &&
                                   std::abs((last.zv - last.zu) / (last.v - last.u) - (q.zv - q.zu) / (q.v - q.u)) <= 1e-9;
            if (same_line) {
                last.v = q.v;
                last.zv = q.zv;
                continue;
            }
        }
        pieces.push_back(q);
    }
    for (const Piece& q : pieces) {
        if (q.zu > at_.z + 1e-9) feed_to({at_.x, at_.y, q.zu}, feed, m);
        else if (q.zu < at_.z - 1e-9) feed_to({at_.x, at_.y, q.zu}, s_.feeds.plunge, Movement::plunge);
        const Profile piece = q.u < q.v ? sub_profile(p, q.u, q.v) : reversed(sub_profile(p, q.v, q.u));
        follow(piece, q.zu, q.zv, feed, m);
    }
}

// Down from the tool's Z to `z` at its XY: straight at plunge feed, or a helix turning
// about a centre `away` (a unit vector) from the tool, on the side away from the profile.
void Cutter::go_down(double z, Vec2 away, double radius) {
    if (s_.ramp.kind == Ramp::Kind::helix) {
        const double rho = radius > 0 ? radius : s_.ramp.radius;
        const double per_turn = 2 * pi * rho * std::tan(s_.ramp.angle * rad_per_deg);
        const int turns = std::max(1, static_cast<int>(std::ceil((at_.z - z) / per_turn - 1e-9)));
        const Vec3 centre{at_.x + away.x * rho, at_.y + away.y * rho, at_.z};
        sink_.emit(Arc{{at_.x, at_.y, z}, centre, s_.tool_left ? ArcDirection::ccw : ArcDirection::cw, Plane::xy,
                       s_.feeds.ramp, turns - 1, Movement::ramp});
        at_.z = z;
        return;
    }
    feed_to({at_.x, at_.y, z}, s_.feeds.plunge, Movement::plunge);
}

// One pass at `z` from the profile's start, the tool at its start at `z_prev`: down (plunge
// there, or a ramp along the profile and back at depth), then the whole profile.
void Cutter::retract(bool done) { rapid({at_.x, at_.y, done ? s_.clearance : s_.z.retract_z}); }

void Cutter::pass_from_start(const Profile& p, double z_prev, double z, double feed, Movement m) {
    if (s_.ramp.kind == Ramp::Kind::along && z_prev > z) {
        const double total = profile_length(p);
        double l = (z_prev - z) / std::tan(s_.ramp.angle * rad_per_deg);
        l = std::min(l, total);
        if (s_.tabs) {
            // Down and back rise over the tabs as the passes do.
            follow_over_tabs(p, 0.0, l, z_prev, z, s_.feeds.ramp, Movement::ramp);
            follow_over_tabs(p, l, 0.0, z, z, s_.feeds.ramp, Movement::ramp);
        } else {
            const Profile down = sub_profile(p, 0.0, l);
            follow(down, z_prev, z, s_.feeds.ramp, Movement::ramp);
            follow(reversed(down), z, z, s_.feeds.ramp, Movement::ramp);
        }
    } else {
        feed_to({at_.x, at_.y, z}, s_.feeds.plunge, Movement::plunge);
    }
    cut_pass(p, z, feed, m);
}

// Every pass of one path: lead in once (each pass for an open path), down pass by pass,
// lead out, and up.
void Cutter::cut_run(const Profile& p, bool closed, const std::vector<double>& depths, Movement m, double feed, bool last_run) {
    const Profile in = lead_in(p), out = lead_out(p);
    double z_prev = s_.z.reference_z;
    for (std::size_t k = 0; k < depths.size(); ++k) {
        const double z = depths[k];
        const bool enter = k == 0 || !closed;
        if (enter) {
            const Vec2 a = in.start;
            if (first_) {
                rapid({a.x, a.y, s_.clearance});
                first_ = false;
            }
            rapid({a.x, a.y, s_.z.retract_z});
            rapid({a.x, a.y, s_.z.safe_z});
            // Along a ramp the tool enters at the previous level and ramps on the profile.
            const double entry_z = s_.ramp.kind == Ramp::Kind::along ? std::max(z_prev, z) : z;
            if (at_.z > entry_z) go_down(entry_z, side_normal(point_at(p, 0.0).tangent));
            if (control_compensates()) sink_.emit(Compensation{compensation_side(), s_.tool, compensation_radius()});
            follow(in, at_.z, at_.z, s_.feeds.lead_in, Movement::lead_in);
            pass_from_start(p, at_.z, z, feed, m);
        } else {
            pass_from_start(p, at_.z, z, feed, m);
        }
        z_prev = z;
        const bool leave = k + 1 == depths.size() || !closed;
        if (leave) {
            if (control_compensates() && !out.segments.empty()) {
                // Off on the last straight move of the lead-out.
                Profile before = out, last = out;
                before.segments.pop_back();
                last.start = before.segments.empty() ? out.start : before.segments.back().end;
                last.segments = {out.segments.back()};
                follow(before, at_.z, at_.z, s_.feeds.lead_out, Movement::lead_out);
                sink_.emit(Compensation{CompensationSide::off, 0, 0.0});
                follow(last, at_.z, at_.z, s_.feeds.lead_out, Movement::lead_out);
            } else {
                follow(out, at_.z, at_.z, s_.feeds.lead_out, Movement::lead_out);
            }
            const bool done = last_run && k + 1 == depths.size();
            // Across to the next entry at the retract plane: rapids across stay above it.
            rapid({at_.x, at_.y, done ? s_.clearance : s_.z.retract_z});
        }
    }
}


}  // namespace camgen
