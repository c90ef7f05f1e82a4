#pragma once
// The path operation: the tool centre fed along lines, arcs in any plane and helices, at
// absolute Z (no compensation, no depth passes: for engraving, 3D arcs and hand-made paths;
// the contour operation is the machinist's profile), entered by feeding down from the
// clearance above its start.
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"

namespace camgen {

// A straight line to an end point (a job's [x, y] is at the Z where the line starts).
struct PathLine {
    Vec3 end;
};

// An arc in `plane` to an end point around an absolute centre, clockwise or counter-clockwise
// seen looking down the plane's normal axis (Z, Y, X: the G17/G18/G19 convention). The
// centre's coordinate along the normal axis is the start's. An end that differs from the start
// along the normal axis makes a helical arc; an end equal to the start in the plane is a full
// circle.
struct PathArc {
    Vec3 end;
    Vec3 centre;
    ArcDirection direction = ArcDirection::cw;
    Plane plane = Plane::xy;
};

// A helix about an axis parallel to Z through `centre`, from the current point to `end_z`, Z
// changing evenly with the angle: `turns` whole turns, then `partial` radians more (a z and a
// pitch that are not a whole number of turns apart keep the pitch: the helix ends elsewhere
// on its circle, at `end`).
struct PathHelix {
    Vec2 centre;
    ArcDirection direction = ArcDirection::cw;
    int turns = 1;
    double end_z = 0.0;
    double partial = 0.0;  // radians of the last, partial turn (0: whole turns only)
    Vec2 end;              // X and Y where it ends (the start's when partial is 0)
};

using PathElement = std::variant<PathLine, PathArc, PathHelix>;

// Cut a path of lines, arcs and helices, starting at `start` at `depth`.
struct PathOp {
    static constexpr std::string_view type = "path";
    // Reads one operation of this type (its "type" is already read).
    static PathOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("contour") first.
    static std::vector<ObjectSpec> objects();
    std::string path;
    // The JSON path of element k, for messages.
    std::string element_path(std::size_t k) const { return path + "/path/" + std::to_string(k); }
    std::string comment;
    int tool = 0;
    Vec2 start;
    std::vector<PathElement> elements;
    double z = 0.0;                      // absolute Z of the start: the job's "z" ([x, y] points keep the current Z)
    double feed = 0.0;                   // mm/min
    std::optional<double> plunge_feed;   // mm/min; absent: feed
    std::optional<double> tolerance;     // mm, for arcs that become lines (capped by the machine's)
    std::vector<std::string> notes;      // what camgen decided that the job did not ask for (a drawing's gaps closed, ...)
};

// Rapid above the start at the clearance, feed down to depth, cut the path, rapid up.
void expand(const PathOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "path".
std::string default_name(const PathOp& op);

}  // namespace camgen
