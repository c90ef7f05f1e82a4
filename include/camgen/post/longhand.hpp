#pragma once
// Longhand drilling: the exact moves a canned cycle makes, as plain rapids, feeds and dwells.
// Shared by every post (for cycles a control lacks) and by the reader (to expand the canned
// cycles it reads), so both mean the same motion.
#include <variant>
#include <vector>

#include "camgen/events/events.hpp"

namespace camgen {

// Where a bore-dwell (G89) cycle's feed out of the hole ends. Fanuc feeds out to the
// feed-start plane R and rapids on to the retract level; LinuxCNC 2.9 feeds all the way out
// to the retract level (its G98/G99 "clear Z").
enum class BoreDwellFeedOut { to_safe, to_retract };

// Motion settings of the control being emulated.
struct LonghandOptions {
    double peck_clearance = 1.0;  // mm: G83 re-approach stop above the last peck; G73 back-off
                                  // (where the cycle gives no peckClearance / peckingRetract)
    BoreDwellFeedOut bore_dwell_feed_out = BoreDwellFeedOut::to_safe;
};

// The depths at which successive pecks end, from safe_z down to bottom_z: first depth, then
// subsequent depth or a degression by value or factor bounded below by minimum_depth. One entry (bottom_z) for
// cycles without pecking. Throws InputError when the pecks could not reach the bottom.
std::vector<double> peck_depths(const DrillCycle& cycle);
// As above, into `depths` (emptied first).
void peck_depths(const DrillCycle& cycle, std::vector<double>& depths);

// The moves that drill one hole at `hole`, starting from `from`, as LinuxCNC/Fanuc canned
// cycles move: if `from` is below safe_z (R), rapid up to it first; rapid in XY; rapid down to
// safe_z; the cycle; the final retract to retract_z (the G98 level, or R for G99). Pecks are
// measured from safe_z. Spindle events appear only for tapping and bore-stop.
// One move of a longhand cycle: only these events occur in one.
using LonghandMove = std::variant<Rapid, Linear, Dwell, Spindle>;
// The move as an event.
Event to_event(const LonghandMove& move);

std::vector<LonghandMove> longhand_moves(const DrillCycle& cycle, const Vec3& from, Vec2 hole,
                                  const LonghandOptions& options);

// Buffers longhand_moves reuses from hole to hole, so that a program of many holes allocates
// nothing per hole or per peck.
struct LonghandBuffers {
    std::vector<LonghandMove> moves;
    std::vector<double> depths;
};
// As above, into buffers.moves (emptied first), which it returns.
const std::vector<LonghandMove>& longhand_moves(const DrillCycle& cycle, const Vec3& from, Vec2 hole,
                                                const LonghandOptions& options, LonghandBuffers& buffers);

}  // namespace camgen
