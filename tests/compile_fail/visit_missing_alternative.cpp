// Must NOT compile: an event alternative that a visitor does not handle. The variant is the
// real Event with one alternative added; the visitor handles every alternative of Event, as
// camgen's visitors do. The build fails with visit_exhaustive's static_assert
// ("does not handle every alternative"), which the ctest test looks for.
#include "camgen/events/events.hpp"
#include "camgen/events/visit.hpp"

namespace camgen {
struct NewEvent {};

template <class V, class T>
struct with_alternative;
template <class... A, class T>
struct with_alternative<std::variant<A...>, T> {
    using type = std::variant<A..., T>;
};

int visit_extended(const with_alternative<Event, NewEvent>::type& e) {
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
