#include <cmath>
#include <numbers>

#include "camgen/operations.hpp"

namespace camgen {

DrillCycle resolve_cycle(const DrillOp& op, const Tool& tool) {
    const DrillParams& p = op.params;
    DrillCycle c;
    c.kind = p.kind;
    c.output = p.output;
    c.path = op.path;
    c.params = p;
    c.retract_z = p.retract_plane;
    c.reference_z = p.reference_plane;
    c.safe_z = !p.safe_distance ? p.retract_plane
               : p.safe_distance_is_absolute ? *p.safe_distance
                                             : p.reference_plane + *p.safe_distance;
    c.bottom_z = p.end_depth_is_absolute ? p.end_depth : p.reference_plane - p.end_depth;
    if (p.drill_tip && tool.tip_angle) {
        // Tip length of a point of included angle a on diameter d: (d/2) / tan(a/2).
        double half = *tool.tip_angle * std::numbers::pi / 360.0;
        c.bottom_z -= tool.diameter / 2.0 / std::tan(half);
    }
    c.spindle_rpm = tool.rpm;
    c.spindle_direction = tool.direction;
    bool tapping = p.kind == CycleKind::tap || p.kind == CycleKind::tap_left;
    c.feed = tapping ? p.pitch.value_or(0.0) * p.tapping_speed.value_or(tool.rpm) : p.plunging_feedrate.value_or(0.0);
    return c;
}

void expand(const DrillOp& op, const Context& ctx, EventSink& sink) {
    if (op.holes.empty()) return;
    DrillCycle c = resolve_cycle(op, ctx.tool);
    const Vec2 first = op.holes.front();
    sink.emit(Rapid{{first.x, first.y, ctx.job.clearance}});
    if (c.retract_z != ctx.job.clearance) sink.emit(Rapid{{first.x, first.y, c.retract_z}});
    sink.emit(c);
    for (const Vec2& h : op.holes) sink.emit(DrillPoint{h});
    sink.emit(DrillEnd{});
    const Vec2 last = op.holes.back();
    if (c.retract_z != ctx.job.clearance) sink.emit(Rapid{{last.x, last.y, ctx.job.clearance}});
}

}  // namespace camgen
