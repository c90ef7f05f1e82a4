#pragma once
// Operation modules: each expands one operation of the job into events. They decide geometry
// and order, never text.
#include "camgen/events.hpp"
#include "camgen/job.hpp"

namespace camgen {

// What an operation may know besides itself.
struct Context {
    const Job& job;
    const Tool& tool;
};

// Drilling: position above the first hole at the clearance, then down to the retract plane,
// the cycle over every hole, and back up to the clearance.
void expand(const DrillOp& op, const Context& context, EventSink& sink);

// Contour: rapid above the start at the clearance, feed down to depth, cut the path, rapid up.
void expand(const ContourOp& op, const Context& context, EventSink& sink);

// The resolved drilling cycle of an operation (absolute planes, drill tip, tapping feed).
DrillCycle resolve_cycle(const DrillOp& op, const Tool& tool);

// The whole job in order: tool changes and spindle control between operations, each
// operation between OperationStart and OperationEnd, spindle off at the end.
void expand_job(const Job& job, EventSink& sink);

}  // namespace camgen
