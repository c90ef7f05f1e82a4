#pragma once
#include <array>
// What a program does, in numbers: path lengths at feed and at rapid, bounding box per tool,
// lowest Z, holes, estimated machining time (`camgen verify`, `--stats`, the backplot legend).
#include <optional>
#include <string>
#include <vector>

#include "camgen/post/machine.hpp"
#include "camgen/analysis/trace.hpp"

namespace camgen {

// An axis-aligned box around motion, mm. Empty until a point is added.
struct Box {
    Vec3 min, max;
    bool empty = true;
    void add(const Vec3& p);
    void add(const Box& b);
};

// The box around a move, arcs included with their extremes (not only their ends).
Box box_of(const Step& step);

// Numbers for one tool, over the moves made while it was in the spindle.
struct ToolStats {
    int tool = 0;
    double diameter = 0.0;     // mm, 0: unknown
    std::string description;
    Box box;                   // every known position, rapids included
    double feed_length = 0.0;  // mm
    double rapid_length = 0.0; // mm
    double time = 0.0;         // s
    int holes = 0;
    // Constant surface speed (G96) while the tool fed: the surface speeds (m/min) and the rpm
    // the spindle turned at over the feed moves, min(limit, 1000 vc / (pi d)); 0: none.
    double surface_speed_min = 0.0, surface_speed_max = 0.0;
    double rpm_min = 0.0, rpm_max = 0.0;
};

// A feed per revolution under a constant surface speed: vc m/min at the work's diameter, the
// spindle held to `limit` rpm, `per_rev` mm a turn, the feed clamped to the machine's
// [min_feed, max_feed] mm/min.
struct SurfaceSpeedFeed {
    double surface_speed = 0.0;  // m/min
    double limit = 0.0;          // rpm
    double per_rev = 0.0;        // mm/rev
    double min_feed = 0.0;       // mm/min (0: none)
    double max_feed = 0.0;       // mm/min (0: none)
};

// The spindle's rpm at radius r (mm) under a constant surface speed: min(limit, 1000 vc / (2 pi r)).
double surface_speed_rpm(double surface_speed, double limit, double radius);

// The time (s) a straight feed move of `length` mm takes from radius-signed X x0 to x1 (the
// lathe's X, radius; the spindle's speed follows |x|) under `feed`. Exact: the inverse of the
// feed is piecewise linear in |x| (the limit, the clamps), integrated between its breakpoints.
// `clamped`: set when the feed reached the machine's limits on the way.
double surface_speed_feed_time(const SurfaceSpeedFeed& feed, double x0, double x1, double length, bool* clamped = nullptr);

// Numbers for a whole program.
struct ProgramStats {
    double feed_length = 0.0;       // mm
    double rapid_length = 0.0;      // mm, rapids from known positions
    double rapid_xy_length = 0.0;   // mm, the same rapids projected on XY (what hole order shortens)
    int unmeasured_rapids = 0;      // rapids from the tool-change position (length unknown, not counted)
    std::optional<double> lowest_z; // mm
    int holes = 0;
    int canned_holes = 0;           // holes drilled by a canned cycle
    int longhand_holes = 0;         // holes drilled with plain moves
    double feed_time = 0.0;         // s, each feed clamped to the machine's limits
    double rapid_time = 0.0;        // s, at the machine's rapid rate
    double dwell_time = 0.0;        // s
    int clamped_feeds = 0;          // feed moves whose feed was outside the machine's limits
    double rapid_rate = 0.0;        // mm/min used for rapids
    // Feed length (mm) and time (s) by movement kind, in the order of the vocabulary's table.
    std::array<double, std::size(movements)> movement_length{};
    std::array<double, std::size(movements)> movement_time{};
    int stops = 0;                  // stops for the operator (M0, M1, ...)
    int optional_stops = 0;         // of which optional (M1)
    std::vector<StopNote> stop_notes;  // the first of them, with their lines and messages
    Box box;
    std::vector<ToolStats> tools;   // in order of first use
    // The machine's kind and how it programs X: a lathe's statistics say X as the program does
    // (a diameter under xDiameterProg; the boxes stay radii) and have no Y.
    MachineKind kind = MachineKind::mill;
    bool x_diameter = false;
    double total_time() const { return feed_time + rapid_time + dwell_time; }
};

// Measures a trace as it is made (the streaming core of compute_stats): constant memory
// whatever the program's length (a little per tool).
class StatsAccumulator : public TraceSink {
public:
    explicit StatsAccumulator(const Machine& machine);
    void step(const Step& step) override;
    void hole(const Hole& hole) override;
    void finish(const TraceSummary& summary) override;
    // The statistics, complete after finish.
    const ProgramStats& stats() const { return stats_; }

private:
    ToolStats& tool_stats(int tool);
    MachineLimits limits_;
    ProgramStats stats_;
    double surface_speed_ = 0.0;  // m/min under G96, else 0
    double spindle_rpm_ = 0.0;    // rpm, under G96 the limit
};

// Measures a trace. Feeds are clamped to machine.limits, rapids run at limits.rapid_rate.
ProgramStats compute_stats(const Trace& trace, const Machine& machine);

// A time as people read it: "50.3 s", "2 min 05.3 s", "1 h 02 min 05.3 s".
std::string format_duration(double seconds);

// A lathe's X extent of a box as the program writes X: "24.000 .. 44.000" (twice the box's
// radii where `diameter`, xDiameterProg), mm.
std::string lathe_x_range(const Box& box, bool diameter);

// The statistics as lines of text, numbers through a fixed formatter (deterministic).
std::string format_stats(const ProgramStats& stats);

}  // namespace camgen
