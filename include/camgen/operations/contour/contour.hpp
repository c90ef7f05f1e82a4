#pragma once
// The contour operation: a machinist's profile cut. A closed or open 2D profile of lines and
// arcs in XY (the geometry layer's Profile), cut beside it (left, right, inside, outside) or on
// it, climb or conventional, with the tool radius offset by camgen (computer), by the control
// (G41/G42) or both (wear, inverse wear); in depth passes from the stock top down to the end
// depth (the heights every operation takes), with an optional finishing pass, lead-in and
// lead-out, plunge or ramp entry, and tabs that hold a through-cut part.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/heights.hpp"

namespace camgen {

struct ContourOp {
    static constexpr std::string_view type = "contour";
    // Reads one operation of this type (its "type" is already read).
    static ContourOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("contour") first.
    static std::vector<ObjectSpec> objects();
    std::string path;
    // The JSON path of segment k, for messages.
    std::string element_path(std::size_t k) const { return path + "/path/" + std::to_string(k); }
    std::string comment;
    int tool = 0;
    double tool_radius = 0.0;
    Heights heights;
    Profile profile;                         // as drawn, XY
    ContourSide side = ContourSide::outside;
    CutDirection direction = CutDirection::climb;
    SpindleDirection spindle = SpindleDirection::cw;
    CompensationMode compensation = CompensationMode::computer;
    double stock_to_leave = 0.0;             // radial, left on the wall after every pass
    std::optional<double> step_down;         // absent: one pass
    bool equal_steps = true;
    std::optional<Finishing> finishing;
    Lead lead_in, lead_out;
    Ramp ramp;
    std::optional<Tabs> tabs;
    ContourFeeds feeds;
    std::optional<double> tolerance;  // mm, for arcs that become lines (capped by the machine's)

    // Planned on reading (so that what cannot be cut is an error naming the operation):
    bool tool_left = true;            // the tool is left of its travel
    Profile rough;                    // the path of the roughing passes (programmed path)
    Profile finish;                   // the path of the finishing pass (empty: none)
    std::vector<std::string> notes;   // what camgen decided that the job did not ask for
};

// Lead in, cut each pass, lead out, retract (the cutting engine's Cutter).
void expand(const ContourOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "contour".
std::string default_name(const ContourOp& op);

}  // namespace camgen
