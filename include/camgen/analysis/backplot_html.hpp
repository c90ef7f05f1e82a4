#pragma once
// The interactive backplot (`--plot F.html`): one self-contained HTML page (inline CSS and
// script, nothing from the network) with the backplot drawing (backplot.hpp), a slider that
// steps through the program block by block showing the block's text and the tool's position
// after it (numbers and a marker in the drawing), switches for the drawing's layers (each tool,
// each kind of move) and the statistics. Everything comes from the program as read back.
#include <cstddef>
#include <string>
#include <string_view>

#include "camgen/analysis/backplot.hpp"

namespace camgen {

// How much the page draws as it is. The block data (text and position of every block) is
// never thinned: the slider reaches every block.
struct HtmlPlotLimits {
    // Rapid and feed moves drawn as they are; above this, runs of straight moves whose inner
    // points lie within half a pixel of one line are drawn as that line (the page says so).
    std::size_t moves = 20000;
    // Holes drawn with their own circle and cross; above this, the rest as plain circles.
    std::size_t holes = 5000;
};

// The page for `program`, the NC text that was read back into `trace` (its steps' lines are
// the program's lines; a block is a line). Deterministic; every text from the program or the
// job is escaped (markup and the embedded data alike).
std::string backplot_html(std::string_view program, const Trace& trace, const ProgramStats& stats,
                          const BackplotOptions& options, const HtmlPlotLimits& limits = {});

// True when a --plot file name asks for the HTML page (it ends in .html or .htm, any case).
bool is_html_plot(std::string_view file);

}  // namespace camgen
