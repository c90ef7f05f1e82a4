#pragma once
// Operation modules: each expands one operation of the job into events. They decide geometry
// and order, never text.
#include "camgen/events/events.hpp"
#include "camgen/job/job.hpp"

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

// Holes up to this count get 2-opt after nearest neighbour in shortest_order (2-opt is
// O(n^2) per pass); larger operations keep the nearest-neighbour order.
inline constexpr size_t max_two_opt_holes = 2000;

// The holes in a short rapid order (DrillOp order "shortest"): nearest neighbour from the
// first hole, which stays first, then 2-opt (see max_two_opt_holes). Same holes, reordered.
std::vector<Vec2> shortest_order(const std::vector<Vec2>& holes);

// The resolved drilling cycle of an operation (absolute planes, drill tip, tapping feed).
DrillCycle resolve_cycle(const DrillOp& op, const Tool& tool);

// The whole job in order: tool changes and spindle control between operations, each
// operation between OperationStart and OperationEnd, spindle off at the end.
void expand_job(const Job& job, EventSink& sink);

}  // namespace camgen
