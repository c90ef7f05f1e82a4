#pragma once
// The heights every operation takes, as CNC-Calc's drill header has them: a retract plane the
// tool travels at, a reference plane (the stock top), a safe distance where rapid turns into
// feed, and an end depth that is relative (positive, below the reference plane) unless marked
// absolute. A positive relative depth never means "above the stock".
#include <optional>
#include <string_view>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/job/job_input.hpp"

namespace camgen {

struct Heights {
    double retract_plane = 0.0;            // absolute Z between holes or passes (default: clearance)
    double reference_plane = 0.0;          // absolute Z of the stock top
    std::optional<double> safe_distance;   // where rapid turns into feed (default: the retract plane)
    bool safe_distance_is_absolute = false;
    double end_depth = 0.0;                // the bottom of the cut
    bool end_depth_is_absolute = false;    // false: depth below reference_plane (> 0)
    friend bool operator==(const Heights&, const Heights&) = default;
};

// The absolute Z levels: retract plane, reference plane, where the feed starts, the bottom.
struct Planes {
    double retract_z = 0.0;
    double reference_z = 0.0;
    double safe_z = 0.0;
    double bottom_z = 0.0;
};
Planes resolve_planes(const Heights& heights);

// The keys of the heights, in the order a job lists them: retractPlane, referencePlane,
// [safeDistance,] safeDistanceIsAbsolute, endDepth, endDepthIsAbsolute; `with_safe_distance`
// false leaves safeDistance to a table that has it already (the drilling fields).
std::vector<KeySpec> height_keys(bool with_safe_distance);

// Reads and checks the heights (each error names the key and the Z values involved). Where the
// job gives a mill's stock, referencePlane defaults to its top and a retractPlane not above
// that top is refused. The
// bottom below the safe distance, the safe distance not below the stock top, the retract
// plane above the stock top and not below the safe distance. `what` names the cut in
// messages ("hole", "pass"). `depth_key`: the key of the depth; another than "endDepth" (the
// engrave operation's "depth") is always relative, > 0, without an "...IsAbsolute" key.
// `depth`: an operation whose depth follows from its tool (a chamfer) gives it here, below the
// reference plane; no depth key is then read, and `depth_key` names the key its errors blame.
Heights read_heights(json::Fields& f, const JobInput& in, std::string_view what, std::string_view depth_key = "endDepth",
                     std::optional<double> depth = std::nullopt);

}  // namespace camgen
