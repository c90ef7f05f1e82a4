#include "camgen/analysis/stats.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "camgen/nc/format.hpp"

namespace camgen {

namespace {


std::string num(double v, int decimals = 3) {
    nc::FormatSpec spec;
    spec.decimals = decimals;
    spec.force_decimal = decimals > 0;
    return nc::Format(spec).format(v);
}

double length_of(const Step& s) {
    if (!s.from_known) return 0.0;
    if (!s.arc) return std::sqrt((s.to.x - s.from.x) * (s.to.x - s.from.x) + (s.to.y - s.from.y) * (s.to.y - s.from.y) +
                                 (s.to.z - s.from.z) * (s.to.z - s.from.z));
    const ArcGeometry& g = *s.arc;
    double dw = to_plane(g.end, g.plane).w - to_plane(g.start, g.plane).w;
    return std::hypot(g.radius * g.sweep, dw);
}

}  // namespace

std::string format_duration(double seconds) {
    long tenths = std::lround(seconds * 10.0);
    long h = tenths / 36000, m = tenths / 600 % 60;
    double s = static_cast<double>(tenths % 600) / 10.0;
    if (h > 0) return fmt::format("{} h {:02} min {:04.1f} s", h, m, s);
    if (m > 0) return fmt::format("{} min {:04.1f} s", m, s);
    return fmt::format("{:.1f} s", s);
}

namespace {

std::string range(const Box& b, int axis) {
    auto get = [&](const Vec3& v) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
    return fmt::format("{} .. {}", num(get(b.min)), num(get(b.max)));
}

}  // namespace

std::string lathe_x_range(const Box& b, bool diameter) {
    const double k = diameter ? 2.0 : 1.0;
    return fmt::format("{} .. {}", num(k * b.min.x), num(k * b.max.x));
}

void Box::add(const Vec3& p) {
    if (empty) {
        min = max = p;
        empty = false;
        return;
    }
    min = {std::min(min.x, p.x), std::min(min.y, p.y), std::min(min.z, p.z)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y), std::max(max.z, p.z)};
}

void Box::add(const Box& b) {
    if (b.empty) return;
    add(b.min);
    add(b.max);
}

Box box_of(const Step& s) {
    Box b;
    b.add(s.to);
    if (!s.from_known) return b;
    b.add(s.from);
    if (!s.arc) return b;
    // The arc's extremes along the plane's axes: the quadrant points its sweep passes.
    const ArcGeometry& g = *s.arc;
    for (int q = 0; q < 4; ++q) {
        double angle = q * std::numbers::pi / 2.0;
        double delta = g.direction == ArcDirection::ccw ? angle - g.start_angle : g.start_angle - angle;
        delta = std::fmod(delta, two_pi);
        if (delta < 0) delta += two_pi;
        if (delta <= g.sweep) b.add(point_on_arc(g, delta / g.sweep));
    }
    return b;
}

double surface_speed_rpm(double surface_speed, double limit, double radius) {
    const double r = std::abs(radius);
    if (!(r > 0)) return limit;
    return std::min(limit, 1000.0 * surface_speed / (two_pi * r));
}

double surface_speed_feed_time(const SurfaceSpeedFeed& c, double x0, double x1, double length, bool* clamped) {
    if (!(length > 0)) return 0.0;
    // Minutes per mm at radius r: 1 / (f x rpm(r)) = max(1 / (f limit), 2 pi r / (1000 vc f)),
    // clamped to [1 / max_feed, 1 / min_feed]; linear in r between the breakpoints below.
    const double slope = two_pi / (1000.0 * c.surface_speed * c.per_rev);  // min/mm per mm of radius
    const double floor_at_limit = 1.0 / (c.per_rev * c.limit);
    const double fastest = c.max_feed > 0 ? 1.0 / c.max_feed : 0.0;
    const double slowest = c.min_feed > 0 ? 1.0 / c.min_feed : std::numeric_limits<double>::infinity();
    bool was_clamped = false;
    auto inverse = [&](double r) {
        const double v = std::max(floor_at_limit, slope * r);
        if (v < fastest || v > slowest) was_clamped = true;
        return std::clamp(v, fastest, slowest);
    };
    std::vector<double> ts{0.0, 1.0};
    const double dx = x1 - x0;
    auto crossing = [&](double x) {
        if (dx == 0) return;
        const double t = (x - x0) / dx;
        if (t > 0 && t < 1) ts.push_back(t);
    };
    crossing(0.0);
    for (double v : {floor_at_limit, fastest, slowest})
        if (std::isfinite(v) && v > 0) {
            crossing(v / slope);
            crossing(-v / slope);
        }
    std::sort(ts.begin(), ts.end());
    double minutes = 0.0;
    for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
        const double a = ts[i], b = ts[i + 1];
        minutes += (b - a) * length * 0.5 * (inverse(std::abs(x0 + a * dx)) + inverse(std::abs(x0 + b * dx)));
    }
    if (clamped) *clamped = was_clamped;
    return minutes * 60.0;
}

StatsAccumulator::StatsAccumulator(const Machine& machine) : limits_(machine.limits) {
    stats_.rapid_rate = limits_.rapid_rate;
    stats_.kind = machine.kind;
    stats_.x_diameter = machine.kind == MachineKind::lathe && machine.x_diameter;
}

ToolStats& StatsAccumulator::tool_stats(int tool) {
    for (ToolStats& t : stats_.tools)
        if (t.tool == tool) return t;
    ToolStats t;
    t.tool = tool;
    stats_.tools.push_back(t);
    return stats_.tools.back();
}

void StatsAccumulator::step(const Step& s) {
    ProgramStats& st = stats_;
    const MachineLimits& lim = limits_;
    switch (s.kind) {
        case StepKind::tool_change: (void)tool_stats(s.tool); break;
        case StepKind::spindle:
            spindle_rpm_ = s.spindle == SpindleState::off ? 0.0 : s.rpm;
            surface_speed_ = s.spindle == SpindleState::off ? 0.0 : s.surface_speed;
            break;
        case StepKind::stop:
            ++st.stops;
            if (s.stop == StopKind::optional) ++st.optional_stops;
            break;
        case StepKind::dwell: {
            st.dwell_time += s.seconds;
            tool_stats(s.tool).time += s.seconds;
            break;
        }
        case StepKind::rapid:
        case StepKind::feed: {
            ToolStats& t = tool_stats(s.tool);
            Box b = box_of(s);
            t.box.add(b);
            st.box.add(b);
            st.lowest_z = st.lowest_z ? std::min(*st.lowest_z, b.min.z) : b.min.z;
            double len = length_of(s);
            double time;
            if (s.kind == StepKind::rapid) {
                if (!s.from_known) ++st.unmeasured_rapids;
                st.rapid_length += len;
                if (s.from_known) st.rapid_xy_length += std::hypot(s.to.x - s.from.x, s.to.y - s.from.y);
                t.rapid_length += len;
                time = len / lim.rapid_rate * 60.0;
                st.rapid_time += time;
            } else {
                if (surface_speed_ > 0 && spindle_rpm_ > 0 && s.pitch > 0 && s.from_known) {
                    // A feed per revolution under G96: the spindle's speed, and so the feed,
                    // follows the radius (exactly along a straight move, in 256 chords along an arc).
                    const SurfaceSpeedFeed c{surface_speed_, spindle_rpm_, s.pitch, lim.min_feed, lim.max_feed};
                    bool clamped = false;
                    if (!s.arc) {
                        time = surface_speed_feed_time(c, s.from.x, s.to.x, len, &clamped);
                    } else {
                        constexpr int chords = 256;
                        time = 0.0;
                        double x = s.from.x;
                        for (int i = 1; i <= chords; ++i) {
                            const double next = point_on_arc(*s.arc, static_cast<double>(i) / chords).x;
                            bool c_clamped = false;
                            time += surface_speed_feed_time(c, x, next, len / chords, &c_clamped);
                            clamped = clamped || c_clamped;
                            x = next;
                        }
                    }
                    if (clamped) ++st.clamped_feeds;
                    const double r_far = std::max(std::abs(b.min.x), std::abs(b.max.x));
                    const double r_near = b.min.x <= 0 && b.max.x >= 0 ? 0.0 : std::min(std::abs(b.min.x), std::abs(b.max.x));
                    const double slow = surface_speed_rpm(surface_speed_, spindle_rpm_, r_far);
                    const double fast = surface_speed_rpm(surface_speed_, spindle_rpm_, r_near);
                    const bool first = t.surface_speed_max == 0;
                    t.surface_speed_min = first ? surface_speed_ : std::min(t.surface_speed_min, surface_speed_);
                    t.surface_speed_max = std::max(t.surface_speed_max, surface_speed_);
                    t.rpm_min = first ? slow : std::min(t.rpm_min, slow);
                    t.rpm_max = std::max(t.rpm_max, fast);
                    st.feed_length += len;
                    t.feed_length += len;
                    st.feed_time += time;
                    st.movement_length[static_cast<std::size_t>(s.movement)] += len;
                    st.movement_time[static_cast<std::size_t>(s.movement)] += time;
                    t.time += time;
                    break;
                }
                double f = std::clamp(s.feed, lim.min_feed, lim.max_feed);
                if (f != s.feed) ++st.clamped_feeds;
                st.feed_length += len;
                t.feed_length += len;
                time = len / f * 60.0;
                st.feed_time += time;
                st.movement_length[static_cast<std::size_t>(s.movement)] += len;
                st.movement_time[static_cast<std::size_t>(s.movement)] += time;
            }
            t.time += time;
            break;
        }
    }
}

void StatsAccumulator::hole(const Hole& h) {
    ++stats_.holes;
    ++tool_stats(h.tool).holes;
}

void StatsAccumulator::finish(const TraceSummary& summary) {
    ProgramStats& st = stats_;
    st.canned_holes = std::min(summary.canned_holes, st.holes);
    st.longhand_holes = st.holes - st.canned_holes;
    st.stop_notes = summary.stops;
    // Descriptions as the trace knows them at its end (a later change may name a tool).
    for (ToolStats& t : st.tools)
        for (const ToolInfo& i : summary.tools)
            if (i.number == t.tool) t.diameter = i.diameter, t.description = i.description;
    // A tool that never moved (a snippet's tool 0 with no motion) says nothing.
    std::erase_if(st.tools, [](const ToolStats& t) { return t.box.empty && t.holes == 0 && t.time == 0.0; });
}

ProgramStats compute_stats(const Trace& trace, const Machine& machine) {
    StatsAccumulator stats(machine);
    for (const Step& s : trace.steps) stats.step(s);
    for (const Hole& h : trace.holes) stats.hole(h);
    stats.finish({trace.canned_holes, trace.tools, trace.notes, trace.stops, trace.stop_count});
    return stats.stats();
}

std::string format_stats(const ProgramStats& st) {
    std::string out;
    auto line = [&](std::string_view label, const std::string& value) { out += fmt::format("{:<15}{}\n", label, value); };
    line("holes", std::to_string(st.holes));
    if (st.holes > 0) line("hole cycles", fmt::format("{} canned, {} longhand", st.canned_holes, st.longhand_holes));
    line("feed path", num(st.feed_length) + " mm");
    std::string rapid = num(st.rapid_length) + " mm";
    if (st.unmeasured_rapids > 0)
        rapid += fmt::format(" (+ {} rapid{} from the tool-change position, not measured)", st.unmeasured_rapids,
                             st.unmeasured_rapids == 1 ? "" : "s");
    line("rapid path", rapid);
    // A lathe has no Y: its rapids' projection on XZ is the rapid path itself.
    const bool lathe = st.kind == MachineKind::lathe;
    if (!lathe) line("rapid in XY", num(st.rapid_xy_length) + " mm");
    line("lowest Z", st.lowest_z ? num(*st.lowest_z) + " mm" : std::string("-"));
    line("time", fmt::format("{} (feed {}, rapid {} at {} mm/min, dwell {}){}", format_duration(st.total_time()),
                             format_duration(st.feed_time), format_duration(st.rapid_time), num(st.rapid_rate, 0),
                             format_duration(st.dwell_time),
                             st.clamped_feeds ? fmt::format("; {} feed move{} clamped to the machine's limits",
                                                            st.clamped_feeds, st.clamped_feeds == 1 ? "" : "s")
                                              : std::string()));
    if (st.stops > 0) {
        line("stops", st.optional_stops ? fmt::format("{} ({} optional)", st.stops, st.optional_stops) : std::to_string(st.stops));
        constexpr std::size_t listed = 20;
        for (std::size_t i = 0; i < st.stop_notes.size() && i < listed; ++i) {
            const StopNote& n = st.stop_notes[i];
            line("", fmt::format("{}{}{}", n.line ? fmt::format("line {}: ", n.line) : std::string(),
                                 n.kind == StopKind::optional ? "optional: " : "",
                                 n.message.empty() ? std::string("(no message)") : n.message));
        }
        if (st.stops > static_cast<int>(std::min(listed, st.stop_notes.size())))
            line("", fmt::format("and {} more", st.stops - static_cast<int>(std::min(listed, st.stop_notes.size()))));
    }
    std::vector<std::string> kinds;
    for (const auto& m : movements) {
        const auto k = static_cast<std::size_t>(m.value);
        if (st.movement_length[k] > 0)
            kinds.push_back(fmt::format("{} {} mm {}", m.name, num(st.movement_length[k]), format_duration(st.movement_time[k])));
    }
    if (!kinds.empty()) line("feed by kind", fmt::format("{}", fmt::join(kinds, ", ")));
    for (const ToolStats& t : st.tools) {
        line(fmt::format("tool {}", t.tool), t.description.empty() ? std::string("-") : t.description);
        if (!t.box.empty && lathe)
            line("", fmt::format("X ({}) {}  Z {}", st.x_diameter ? "diameter" : "radius", lathe_x_range(t.box, st.x_diameter),
                                 range(t.box, 2)));
        else if (!t.box.empty)
            line("", fmt::format("X {}  Y {}  Z {}", range(t.box, 0), range(t.box, 1), range(t.box, 2)));
        line("", fmt::format("{} hole{}, feed {} mm, rapid {} mm, {}", t.holes, t.holes == 1 ? "" : "s", num(t.feed_length),
                             num(t.rapid_length), format_duration(t.time)));
        if (t.surface_speed_max > 0)
            line("", fmt::format("surface speed {} m/min (G96), {} .. {} rpm",
                                 t.surface_speed_min == t.surface_speed_max
                                     ? num(t.surface_speed_max, 0)
                                     : fmt::format("{} .. {}", num(t.surface_speed_min, 0), num(t.surface_speed_max, 0)),
                                 num(t.rpm_min, 0), num(t.rpm_max, 0)));
    }
    return out;
}

}  // namespace camgen
