#pragma once
// Geometry from a DXF drawing in a job: the object {"dxf": "plate.dxf", "layer": ..., ...} that
// drill and bore-mill take as "drawing" (holes: its circles' centres and its points) and
// contour and pocket take as "profile" (its lines, arcs and polylines chained; a pocket's
// outline and islands by nesting). The file is found relative to the job; its $INSUNITS
// against the job's units (a drawing without units is taken in the job's units, with a note);
// a transform maps drawing coordinates to work coordinates.
#include <string>
#include <string_view>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"

namespace camgen {

// The objects dxfSource and dxfTransform, for the JSON Schema.
std::vector<ObjectSpec> dxf_source_objects();

// The holes of the drawing at f's `key`: centres of the selected circles and the points.
std::vector<Vec2> read_dxf_holes(json::Fields& f, const JobInput& in, std::string_view key, std::vector<std::string>& notes);

// The profiles of the drawing at f's `key`, in work coordinates (mm), with each closed one's
// parent by nesting (-1: outermost). `curve_tolerance` (mm) fits ellipses and splines.
struct DxfProfiles {
    std::vector<Profile> profiles;
    std::vector<bool> closed;
    std::vector<int> parent;
    std::vector<std::string> describe;  // "LINE handle 2A (line 120, layer OUTLINE) and 3 more"
};
DxfProfiles read_dxf_profiles(json::Fields& f, const JobInput& in, std::string_view key, double curve_tolerance,
                              std::vector<std::string>& notes);

}  // namespace camgen
