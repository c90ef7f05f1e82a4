#pragma once
// The interactive backplot (`--plot F.html`): one self-contained HTML page (inline CSS and
// script, nothing from the network) with the backplot drawing (backplot.hpp), a slider that
// steps through the program block by block showing the block's text and the tool's position
// after it (numbers and a marker in the drawing), switches for the drawing's layers (each tool,
// each kind of move) and the statistics. Everything comes from the program as read back.
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <memory>
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

// The page as the trace is read a second time (the streaming core of backplot_html, as
// BackplotDrawer is backplot_svg's): the drawing made as the steps come (beyond limits.moves
// moves of the plan, thinned as they come); then, as the page is written, a third reading
// writes each block's position straight into it, and the program's text is copied into it a
// line at a time. So the page of a program of millions of blocks holds a drawing of bounded
// size, neither the program's trace nor its text.
class HtmlPlot : public TraceSink {
public:
    // `plan` (finished) and `stats` of the first pass; both must outlive the plot.
    HtmlPlot(const BackplotPlan& plan, const ProgramStats& stats, const BackplotOptions& options,
             const HtmlPlotLimits& limits = {});
    ~HtmlPlot() override;
    void step(const Step& step) override;
    void hole(const Hole& hole) override;
    void finish(const TraceSummary& summary) override;
    // Writes the page, once finished. `program` opens the text that was read back, at its
    // start (it is called twice: the lines are counted, then copied); `read_again` hands the
    // trace once more to the sink it is given (steps, holes, finish).
    void write(std::ostream& out, const std::function<std::istream&()>& program,
               const std::function<void(TraceSink&)>& read_again) const;

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

// The page for `program`, the NC text that was read back into `trace` (its steps' lines are
// the program's lines; a block is a line). Deterministic; every text from the program or the
// job is escaped (markup and the embedded data alike).
std::string backplot_html(std::string_view program, const Trace& trace, const ProgramStats& stats,
                          const BackplotOptions& options, const HtmlPlotLimits& limits = {});

// True when a --plot file name asks for the HTML page (it ends in .html or .htm, any case).
bool is_html_plot(std::string_view file);

}  // namespace camgen
