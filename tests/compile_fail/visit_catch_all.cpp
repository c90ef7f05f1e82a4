// Must NOT compile: a visitor with a catch-all overload, which would swallow an event
// alternative added later. The build fails with visit_exhaustive's static_assert ("catch-all").
#include "camgen/events/events.hpp"
#include "camgen/events/visit.hpp"

namespace camgen {
int visit_with_catch_all(const Event& e) {
    return visit_exhaustive(overloaded{
                                [](const Rapid&) { return 1; },
                                [](const auto&) { return 0; },
                            },
                            e);
}
}  // namespace camgen
