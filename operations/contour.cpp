#include "camgen/operations.hpp"

namespace camgen {

void expand(const ContourOp& op, const Context& ctx, EventSink& sink) {
    const double z = op.depth;
    sink.emit(Rapid{{op.start.x, op.start.y, ctx.job.clearance}});
    sink.emit(Linear{{op.start.x, op.start.y, z}, op.plunge_feed.value_or(op.feed)});
    Vec2 at = op.start;
    for (const PathElement& e : op.elements) {
        if (const auto* line = std::get_if<PathLine>(&e)) {
            sink.emit(Linear{{line->end.x, line->end.y, z}, op.feed});
            at = line->end;
        } else {
            const auto& arc = std::get<PathArc>(e);
            sink.emit(Arc{{arc.end.x, arc.end.y, z}, {arc.centre.x, arc.centre.y, z}, arc.direction, Plane::xy, op.feed, 0});
            at = arc.end;
        }
    }
    sink.emit(Rapid{{at.x, at.y, ctx.job.clearance}});
}

}  // namespace camgen
