#pragma once
// Longhand drilling: the exact moves a canned cycle makes, as plain rapids, feeds and dwells.
// Shared by every post (for cycles a control lacks) and by the reader (to expand the canned
// cycles it reads), so both mean the same motion.
#include <vector>

#include "camgen/events.hpp"

namespace camgen {

// Motion settings of the control being emulated.
struct LonghandOptions {
    double peck_clearance = 1.0;  // mm above the previous peck where the rapid re-approach stops
};

// The depths at which successive pecks end, from safe_z down to bottom_z: first depth,
// degression by value or factor bounded below by minimum_depth. One entry (bottom_z) for
// cycles without pecking. Throws InputError when the pecks could not reach the bottom.
std::vector<double> peck_depths(const DrillCycle& cycle);

// The moves that drill one hole at `hole`, starting from `from` (the tool above the hole's
// neighbourhood at or above retract_z): rapid in XY, rapid to safe_z, the cycle, and the
// final retract to retract_z. Spindle events appear only for tapping and bore-stop.
std::vector<Event> longhand_moves(const DrillCycle& cycle, const Vec3& from, Vec2 hole,
                                  const LonghandOptions& options);

}  // namespace camgen
