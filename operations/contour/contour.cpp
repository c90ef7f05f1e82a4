#include "operations/registry.hpp"

namespace camgen {

void expand(const ContourOp& op, const Context& ctx, EventSink& sink) {
    sink.emit(Rapid{{op.start.x, op.start.y, ctx.job.clearance}});
    Vec3 at{op.start.x, op.start.y, op.depth};
    sink.emit(Linear{at, op.plunge_feed.value_or(op.feed)});
    for (const PathElement& e : op.elements) {
        if (const auto* line = std::get_if<PathLine>(&e)) {
            sink.emit(Linear{line->end, op.feed});
            at = line->end;
        } else if (const auto* arc = std::get_if<PathArc>(&e)) {
            sink.emit(Arc{arc->end, arc->centre, arc->direction, arc->plane, op.feed, 0});
            at = arc->end;
        } else {
            const auto& helix = std::get<PathHelix>(e);
            // Whole turns: the end is above or below the start; the first turn is the
            // arc's own sweep, the others are extra turns.
            Vec3 end{at.x, at.y, helix.end_z};
            sink.emit(Arc{end, {helix.centre.x, helix.centre.y, at.z}, helix.direction, Plane::xy, op.feed, helix.turns - 1});
            at = end;
        }
    }
    sink.emit(Rapid{{at.x, at.y, ctx.job.clearance}});
}

}  // namespace camgen
