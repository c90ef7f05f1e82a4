// Must compile: the control case for the two compile-failure tests beside it, the same visitor
// over exactly the Event variant.
#include "camgen/events/events.hpp"
#include "camgen/events/visit.hpp"

namespace camgen {
static_assert(!is_exhaustive_visitor<decltype(overloaded{[](const Rapid&) {}}), Event>);

int visit_event(const Event& e) {
    return visit_exhaustive(overloaded{
                                [](const OperationStart&) { return 0; }, [](const OperationEnd&) { return 0; },
                                [](const ToolChange&) { return 0; },     [](const Spindle&) { return 0; },       [](const Coolant&) { return 0; },
                                [](const Rapid&) { return 0; },          [](const Linear&) { return 0; },
                                [](const Arc&) { return 0; },            [](const Dwell&) { return 0; },
                                [](const Compensation&) { return 0; },   [](const DrillCycle&) { return 0; },
                                [](const DrillPoint&) { return 0; },     [](const DrillEnd&) { return 0; },
                                [](const Comment&) { return 0; },       [](const Stop&) { return 0; },
                                [](const CustomBlock&) { return 0; },   [](const ThreadFeed&) { return 0; }, [](const ThreadCycle&) { return 0; }, [](const TurnCycle&) { return 0; }, [](const GrooveCycle&) { return 0; }, [](const FinishCycle&) { return 0; },
                            },
                            e);
}
}  // namespace camgen
