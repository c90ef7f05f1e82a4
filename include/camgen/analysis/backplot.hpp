#pragma once
// The backplot: an SVG drawing of a program as read back (XY view, looking down Z), what a
// machinist looks at before running a program: rapids dashed, feed moves solid with their
// direction, one colour per tool, holes marked and numbered in drilling order, a grid with
// coordinates, the work zero, a scale bar and a legend with the statistics.
#include <string>

#include "camgen/analysis/trace.hpp"
#include "camgen/analysis/stats.hpp"

namespace camgen {

struct BackplotOptions {
    std::string title;    // the program's name ("plate.nc")
    std::string machine;  // the machine's name
    MachineKind kind = MachineKind::mill;  // a lathe's program is drawn as an XZ half-section
};

// The SVG text. Deterministic: every number goes through one fixed formatter. A lathe's
// program (options.kind) is drawn as a half-section: Z to the right, X (the radius) up, the
// spindle axis at X0 - the profile, the drilled hole's pecks along the axis, rapids dashed.
std::string backplot_svg(const Trace& trace, const ProgramStats& stats, const BackplotOptions& options);

}  // namespace camgen
