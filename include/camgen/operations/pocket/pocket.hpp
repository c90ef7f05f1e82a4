#pragma once
// The pocket operation: clear the material inside an outline and around islands, in depth
// passes, by contour-parallel rings (strategy offset) or parallel rows (zigzag, with a
// cleanup ring along the walls), with an optional finishing pass along the walls and islands
// and a floor pass. Every path and every move camgen adds (entries, links) is planned on
// reading and runs through the part-aware check (part_guard.hpp) against the outline and the
// islands. Lengths mm, feeds mm/min, angles degrees.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/region.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/heights.hpp"

namespace camgen {

enum class PocketStrategy { offset, zigzag };
inline constexpr Named<PocketStrategy> pocket_strategies[] = {
    {PocketStrategy::offset, "offset", "rings parallel to the walls and islands, stepOver apart"},
    {PocketStrategy::zigzag, "zigzag", "parallel rows at angle, stepOver apart, then a cleanup ring along the walls and islands"},
};

enum class PocketOrder { inside_out, outside_in };
inline constexpr Named<PocketOrder> pocket_orders[] = {
    {PocketOrder::inside_out, "inside-out", "offset: from the middle of each area out to its walls"},
    {PocketOrder::outside_in, "outside-in", "offset: from the walls in to the middle"},
};

enum class RowDirection { both_ways, one_way };
inline constexpr Named<RowDirection> row_directions[] = {
    {RowDirection::both_ways, "both-ways", "zigzag: every other row walked back, linked at depth"},
    {RowDirection::one_way, "one-way", "zigzag: every row walked the same way; the tool lifts before each return"},
};

// How the tool gets down to the start of a step that is not reached at depth: a helix of
// `radius` about `centre`, a ramp along the step's own path at the ramp angle (laps of a ring,
// or back and forth on a row), a ramp back and forth on `track` (a path too short to ramp on,
// with no room for a helix: a straight line from its start into the pocket, or a piece of the
// edge of the area being cleared, from its start), a plunge (a centre-cutting tool), or a drop
// onto floor cleared at this depth already (any tool).
struct PocketEntry {
    enum class Kind { helix, along, track, plunge, drop } kind = Kind::helix;
    double radius = 0.0;
    Vec2 centre;
    Profile track;  // from the step's start
};

// The finishing pass along one wall or island: the tool-centre loop, started where its leads
// have room in the cleared pocket, and the leads it gets there (those of the job, or shorter
// ones, or none, where nothing longer has room anywhere on the loop).
struct PocketFinish {
    Profile path;
    Lead lead_in, lead_out;
};

// One path of a depth level: a ring or a row of the tool centre, and how the tool gets to its
// start from the step before: fed at depth (`stay_down`) or lifted to the retract plane and
// entered.
struct PocketStep {
    Profile path;
    bool closed = false;
    bool stay_down = false;
    PocketEntry entry;
};

struct PocketOp {
    static constexpr std::string_view type = "pocket";
    // Reads one operation of this type (its "type" is already read).
    static PocketOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("pocket") first.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    double tool_radius = 0.0;
    bool centre_cutting = false;
    Heights heights;
    PlaneRegion region;                          // as drawn: the outline and the islands, XY
    PocketStrategy strategy = PocketStrategy::offset;
    PocketOrder order = PocketOrder::inside_out;
    RowDirection rows = RowDirection::both_ways;
    double angle = 0.0;                     // zigzag rows, degrees from +X
    double step_over = 0.0;                 // mm between rings or rows
    CutDirection direction = CutDirection::climb;
    SpindleDirection spindle = SpindleDirection::cw;
    double stock_to_leave = 0.0;            // radial, on every wall and island
    std::optional<double> step_down;        // absent: one pass
    bool equal_steps = true;
    std::optional<Finishing> finishing;
    Lead lead_in, lead_out;                 // of the finishing pass along the walls
    Ramp ramp;                              // how the tool enters (default: a helix)
    CutFeeds feeds;
    std::optional<double> tolerance;        // mm, for arcs that become lines

    // Planned on reading:
    bool tool_left = true;                  // the tool left of its travel
    std::vector<PocketStep> steps;          // one depth level's paths, in order
    std::vector<PocketFinish> finish_loops;  // the finishing pass's paths (walls, islands)
    std::vector<std::string> notes;         // what camgen decided that the job did not ask for
};

// Clears each depth level, the floor and the walls: see pocket.cpp.
void expand(const PocketOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "pocket".
std::string default_name(const PocketOp& op);

}  // namespace camgen
