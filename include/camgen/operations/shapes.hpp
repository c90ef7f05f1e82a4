#pragma once
// Shapes as profiles in a job, for the common cases without a drawing: the object that
// contour, pocket (outline and islands), face (area), path and a stock's profile take as
// "profile" holds either a drawing ("dxf", see dxf_source.hpp) or exactly one shape:
//   "rectangle": {"width", "height", "corner" | "centre", "cornerRadius"}
//   "circle":    {"centre", "diameter"}
//   "slot":      {"width", "centres": [[x, y], [x, y]] | "centre", "length", "angle"}
//   "polygon":   {"centre", "sides", "diameter" | "acrossFlats", "angle"}
// Each shape is a closed profile walked counter-clockwise (seen from +Z), starting in the
// middle of a straight side (a circle: at its +X point), so that a lead joins it on a line.
#include <optional>
#include <string_view>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"

namespace camgen {

// The objects profileSource, dxfTransform, shapeRectangle, shapeCircle, shapeSlot and
// shapePolygon, for the JSON Schema.
std::vector<ObjectSpec> profile_source_objects();

// Whether the profile object `value` names a shape (one of rectangle, circle, slot, polygon).
bool names_a_shape(const nlohmann::json& value);

// The shape of the profile object at f's `key`, in mm; nullopt when it names a drawing ("dxf").
// Errors name the JSON path: a shape with dxf or another shape, a drawing's key (layer, ...)
// with a shape, sizes that make no shape.
std::optional<Profile> read_shape_profile(json::Fields& f, const JobInput& in, std::string_view key);

}  // namespace camgen
