#pragma once
// The job: plain value types read from JSON (src/job_json.cpp). All lengths are mm, feeds
// mm/min, times seconds, speeds rpm: inch input is converted once, when it is read.
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "camgen/geometry/geometry.hpp"

namespace camgen {

enum class Units { mm, inch };
enum class SpindleDirection { cw, ccw };
enum class ToolType { drill, centre_drill, spot_drill, tap, reamer, boring_bar, end_mill, ball_mill };

// A tool of the job's tool table.
struct Tool {
    int number = 0;
    ToolType type = ToolType::drill;
    double diameter = 0.0;                 // mm
    std::optional<double> tip_angle;       // degrees, included angle of the point
    double rpm = 0.0;                      // rev/min, > 0
    SpindleDirection direction = SpindleDirection::cw;
    std::string comment;
    std::string path;                      // JSON path, for messages
};

// Drilling cycle kinds (REFERENCE.md §2-§3): drill G81, dwell G82, deep G83, chip-break G73,
// tap G84, tap-left G74, ream G85, bore-stop G86, bore-dwell G89.
enum class CycleKind { drill, dwell, deep, chip_break, tap, tap_left, ream, bore_stop, bore_dwell };

enum class DegressionType { none, value, factor };

// How a drilling cycle is written: canned when the machine's cycle covers every parameter.
enum class CycleOutput { automatic, canned, longhand };

enum class HoleOrder { as_given, shortest };

// The optional drilling parameters of the CNC-Calc drill header. Present means used.
// Z values are absolute mm unless named relative.
struct DrillParams {
    CycleKind kind = CycleKind::drill;
    double retract_plane = 0.0;                  // absolute Z between holes
    double reference_plane = 0.0;                // absolute Z of the surface
    std::optional<double> safe_distance;         // where rapid turns into feed
    bool safe_distance_is_absolute = false;
    double end_depth = 0.0;                      // bottom of the hole
    bool end_depth_is_absolute = false;          // false: depth below reference_plane (> 0)
    std::optional<double> first_depth;           // first peck, mm
    DegressionType degression_type = DegressionType::none;
    std::optional<double> degression;            // mm (value) or factor
    std::optional<double> minimum_depth;         // mm, lower bound for a peck
    std::optional<double> pecking_retract;       // mm, chip-break back-off
    std::optional<double> first_feedrate_factor; // first peck feed = feed x factor
    std::optional<double> plunging_feedrate;     // mm/min; required except for tapping
    std::optional<double> retract_feedrate;      // mm/min; absent: rapid out
    std::optional<double> top_dwell;             // s
    std::optional<double> bottom_dwell;          // s
    std::optional<double> pitch;                 // mm per revolution
    std::optional<double> tapping_speed;         // rpm
    std::optional<double> retract_speed;         // rpm
    bool drill_tip = false;                      // add the tool's tip length to the depth
    CycleOutput output = CycleOutput::automatic;
    friend bool operator==(const DrillParams&, const DrillParams&) = default;
};

// Drill a list of holes with one cycle.
struct DrillOp {
    std::string path;          // JSON path of the operation, for messages
    std::string comment;
    int tool = 0;
    DrillParams params;
    std::vector<Vec2> holes;   // as the job gives them; expand() reorders them for order = shortest
    HoleOrder order = HoleOrder::as_given;
};

// A straight line to an end point (a job's [x, y] is at the operation's depth).
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

// Whole turns of a helix about an axis parallel to Z through `centre`, from the current point
// to the same X and Y at `end_z`, Z changing evenly with the angle.
struct PathHelix {
    Vec2 centre;
    ArcDirection direction = ArcDirection::cw;
    int turns = 1;
    double end_z = 0.0;
};

using PathElement = std::variant<PathLine, PathArc, PathHelix>;

// Cut a path of lines, arcs and helices, starting at `start` at `depth`.
struct ContourOp {
    std::string path;
    std::string comment;
    int tool = 0;
    Vec2 start;
    std::vector<PathElement> elements;
    std::vector<std::string> element_paths;  // JSON path of each element, for messages
    double depth = 0.0;                  // absolute Z of the cut (and of [x, y] points)
    double feed = 0.0;                   // mm/min
    std::optional<double> plunge_feed;   // mm/min; absent: feed
    std::optional<double> tolerance;     // mm, for arcs that become lines (capped by the machine's)
};

using Operation = std::variant<DrillOp, ContourOp>;

// A whole job.
struct Job {
    std::string name;
    Units units = Units::mm;            // the units the file was written in
    double clearance = 0.0;             // absolute Z, safe between operations
    std::map<int, Tool> tools;          // by tool number
    std::vector<Operation> operations;  // in order
};

}  // namespace camgen
