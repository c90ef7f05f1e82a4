#pragma once
// Help writing a job from a drawing: `camgen dxf-info F.dxf` (what the drawing holds) and
// `camgen new --from F.dxf` (a starter job).
#include <string>
#include <vector>

#include "camgen/dxf/dxf.hpp"

namespace camgen {

// The report of dxf-info: units, layers with their entity counts (by type), closed and open
// profiles (chained per layer) with their extents, circles grouped by diameter, points.
std::string dxf_info_text(const dxf::Drawing& d);
// The same for the drawing at `path`, read piece by piece (circles and points counted, not
// kept): the memory of dxf-info is the paths it chains, not the drawing. Throws dxf::Error.
std::string dxf_info_file(const std::string& path);

// A starter job for the drawing at `dxf_path` (as the job names it, relative to the job):
// a drill operation per circle diameter (the circles that are not a pocket's islands), a
// contour outside the outermost closed profile (the largest), and a pocket for each closed
// profile directly inside it (with the profiles inside that as its islands). An operation
// names the drawing with a selection (layer, diameter) where that selects exactly its
// geometry, else it holds the geometry itself. `end_mill_mm`: the end mill's diameter.
// `notes` gets what was left out (open profiles, circles outside the outline, ...).
std::string starter_job_text(const dxf::Drawing& d, const std::string& dxf_path, double end_mill_mm, std::vector<std::string>& notes);

}  // namespace camgen
