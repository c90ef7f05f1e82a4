#pragma once
// The face operation: mill the top of the stock flat over a rectangle or any closed profile,
// in parallel rows that run past its edges by an overhang (both ways, linked beyond the edge,
// or one way, lifting before each return), in depth passes down to the end depth, with an
// optional finishing pass at the full depth. The rows are the region's hatch (geometry layer),
// grown by the tool radius and the overhang, so that the tool leaves the area at every row's
// end. Facing cuts everything within the tool radius of the area at the levels it cuts: nothing
// of the part may stand there. Lengths mm, feeds mm/min, angles degrees.
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
#include "camgen/operations/pocket/pocket.hpp"

namespace camgen {

struct FaceOp {
    static constexpr std::string_view type = "face";
    // Reads one operation of this type (its "type" is already read).
    static FaceOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("face") first.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    double tool_radius = 0.0;
    Heights heights;
    Profile area;                           // the area faced, closed, XY
    double overhang = 0.0;                  // how far the tool clears the area's edge
    RowDirection rows = RowDirection::both_ways;
    double angle = 0.0;                     // the rows' direction, degrees from +X
    double step_over = 0.0;                 // mm between rows
    std::optional<double> step_down;        // absent: one pass
    bool equal_steps = true;
    double finishing_stock = 0.0;           // left by the roughing passes for the finishing pass
    CutFeeds feeds;

    // Planned on reading: the rows of the tool centre, in cutting order, each walked a to b.
    std::vector<std::pair<Vec2, Vec2>> row_paths;
    std::vector<std::string> notes;
};

// Each depth: the rows, linked beyond the edge or lifted between: see face.cpp.
void expand(const FaceOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "face".
std::string default_name(const FaceOp& op);

}  // namespace camgen
