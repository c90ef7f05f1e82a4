// The interactive backplot page: the SVG drawing of backplot.cpp with its layers marked, the
// per-block data of the read-back trace, and a small script that steps through it.
#include "camgen/analysis/backplot_html.hpp"
#include "camgen/common/markup.hpp"
#include "camgen/geometry/vec.hpp"

#include "camgen/common/error.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <functional>
#include <istream>
#include <numbers>
#include <optional>
#include <ostream>
#include <sstream>
#include <streambuf>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace camgen {

namespace {

// Positions in the page's data are integers of this many mm (a tenth of the finest
// resolution a program writes, 0.001 mm).
constexpr double data_unit = 0.0001;

// A coordinate in data units, held within 100 km so that the differences stay exact integers
// (in the script's doubles too) whatever a program says.
long long data_units(double mm) { return std::llround(std::clamp(mm / data_unit, -1e12, 1e12)); }

// A count as people read it: 1,234,567.
std::string grouped(std::size_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

bool is_move(const Step& s) { return s.kind == StepKind::rapid || s.kind == StepKind::feed; }

// Where a position is drawn: (X, Y) seen from above, (Z, X) in a lathe's half-section; and
// the axis the drawing looks along (Z, Y), which tells passes apart.
Vec2 drawn(const Vec3& p, MachineKind kind) { return kind == MachineKind::lathe ? Vec2{p.z, p.x} : Vec2{p.x, p.y}; }
double depth(const Vec3& p, MachineKind kind) { return kind == MachineKind::lathe ? p.y : p.z; }


// The ends of the straight moves of a run from `start`, as a cone of directions: a line from
// the start to a point inside the cone passes within `tolerance` of every end added so far
// (each end at distance d allows asin(tolerance / d) either side of its direction). Ends must
// lead away from the start, so that they lie between the start and the last end.
class Run {
public:
    Run(Vec2 start, double tolerance) : start_(start), tolerance_(tolerance) {}

    // Whether the line from the start to `end` passes within the tolerance of every end added.
    bool reaches(Vec2 end) const {
        const double d = distance(start_, end);
        if (d < reach_) return false;
        if (!aimed_) return true;
        const double angle = std::remainder(direction(end) - reference_, 2.0 * std::numbers::pi);
        return angle >= low_ && angle <= high_;
    }

    void add(Vec2 end) {
        const double d = distance(start_, end);
        reach_ = d;
        if (d <= tolerance_) return;  // near the start, any line passes close enough
        const double angle = aimed_ ? std::remainder(direction(end) - reference_, 2.0 * std::numbers::pi) : 0.0;
        const double spread = std::asin(tolerance_ / d);
        if (!aimed_) {
            aimed_ = true;
            reference_ = direction(end);
            low_ = -spread, high_ = spread;
            return;
        }
        low_ = std::max(low_, angle - spread);
        high_ = std::min(high_, angle + spread);
    }

private:
    double direction(Vec2 p) const { return std::atan2(p.y - start_.y, p.x - start_.x); }

    Vec2 start_;
    double tolerance_;
    double reach_ = 0.0;       // distance of the last end from the start
    bool aimed_ = false;       // an end beyond the tolerance narrowed the cone
    double reference_ = 0.0;   // direction of that end, radians
    double low_ = 0.0, high_ = 0.0;  // the cone, radians about the reference
};

// Whether `s` may extend the straight run that ends with `last` into one drawn line: the same
// tool, kind and layer, straight, across the view (a move along the view's axis is drawn as a
// mark), and in the same pass (the cut-width band groups moves by depth).
bool continues(const Step& last, const Step& s, MachineKind kind) {
    const bool last_flat = depth(last.from, kind) == depth(last.to, kind), flat = depth(s.from, kind) == depth(s.to, kind);
    return last.kind == s.kind && !last.arc && !s.arc && last.from_known && s.from_known && last.tool == s.tool &&
           layer_of(last) == layer_of(s) && last.to == s.from && last_flat == flat &&
           (!flat || depth(last.to, kind) == depth(s.to, kind)) && distance(drawn(last.from, kind), drawn(last.to, kind)) > 0 &&
           distance(drawn(s.from, kind), drawn(s.to, kind)) > 0;
}

// The steps as drawn when a program has more moves than `limits.moves`: runs of straight moves
// whose inner points lie within half a pixel of the line from the run's start to its end become
// that line (one pass, constant work and memory per move: the step that may still grow is held
// back). Half a pixel: the drawing is at most 720 px wide for at least 1.12 times the span of
// the positions in view, so a pixel is at least span / 643 mm; span / 1500 is under half.
class Thinning : public TraceSink {
public:
    Thinning(TraceSink& out, const ProgramStats& stats, MachineKind kind) : out_(out), kind_(kind) {
        const Box& b = stats.box;
        const Vec2 lo = drawn(b.min, kind), hi = drawn(b.max, kind);
        tolerance_ = std::max({hi.x - lo.x, hi.y - lo.y, 10.0}) / 1500.0;
    }
    void step(const Step& s) override {
        if (run_ && is_move(s) && continues(*held_, s, kind_) && run_->reaches(drawn(s.to, kind_))) {
            run_->add(drawn(s.to, kind_));
            held_->to = s.to;
            merged_ = true;
            return;
        }
        pass_on();
        held_ = s;
        run_.reset();
        if (is_move(s) && !s.arc && s.from_known) {
            run_.emplace(drawn(s.from, kind_), tolerance_);
            run_->add(drawn(s.to, kind_));
        }
    }
    void hole(const Hole& h) override { out_.hole(h); }
    void finish(const TraceSummary& summary) override {
        pass_on();
        out_.finish(summary);
    }
    // Whether any moves became one line (else the drawing is the program's, and says nothing).
    bool merged() const { return merged_; }
    // The moves drawn.
    std::size_t moves() const { return moves_; }

private:
    void pass_on() {
        if (!held_) return;
        if (is_move(*held_)) ++moves_;
        out_.step(*held_);
        held_.reset();
    }

    TraceSink& out_;
    MachineKind kind_;
    double tolerance_ = 0.0;
    std::optional<Step> held_;  // the last step, passed on when the next does not extend it
    std::optional<Run> run_;    // the run that ends with held_, when that is a straight move
    bool merged_ = false;
    std::size_t moves_ = 0;
};

// The per-block data, written as the steps come (a pass of its own, while the page is
// written): for each line that moves the tool or changes it, (line step, layer or -1 for
// "position unknown", X, Y, Z steps in data units); each value as a difference from the record
// before, which keeps the numbers short. A block's last move gives its position, so each
// record is held until a step of another line comes.
class BlockMoves : public TraceSink {
public:
    explicit BlockMoves(std::ostream& out) : out_(out) {}
    void step(const Step& s) override {
        if (!is_move(s) && s.kind != StepKind::tool_change) return;
        Record r{s.line, -1, x_, y_, z_};
        if (is_move(s)) {
            r.kind = static_cast<int>(layer_of(s));
            r.x = x_ = data_units(s.to.x);
            r.y = y_ = data_units(s.to.y);
            r.z = z_ = data_units(s.to.z);
        }
        if (!held_ || held_->line != r.line) write_held();
        held_ = r;
    }
    void hole(const Hole&) override {}
    void finish(const TraceSummary&) override {
        write_held();
        out_ << text_;
    }

private:
    struct Record {
        int line, kind;
        long long x, y, z;
    };
    void write_held() {
        if (!held_) return;
        const Record& r = *held_;
        fmt::format_to(std::back_inserter(text_), "{}{},{},{},{},{}", written_any_ ? "," : "", r.line - written_.line, r.kind,
                       r.x - written_.x, r.y - written_.y, r.z - written_.z);
        if (text_.size() > 65536) {
            out_ << text_;
            text_.clear();
        }
        written_any_ = true;
        written_ = r;
        held_.reset();
    }

    std::ostream& out_;
    std::string text_;  // records not yet written out
    bool written_any_ = false;
    long long x_ = 0, y_ = 0, z_ = 0;  // the last known position, in data units
    std::optional<Record> held_;
    Record written_{0, 0, 0, 0, 0};
};

// Calls f with each of the program's lines as the reader counts them: split at '\n', a
// trailing '\r' dropped, no block after a final newline (std::getline's split). One line is
// held at a time.
template <class F>
void for_each_line(std::istream& program, F&& f) {
    std::string line;
    while (std::getline(program, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        f(std::string_view(line));
    }
    if (program.bad()) throw IoError("cannot read the program again for the page: the read failed");
}

// The program's lines joined by '\n' as one script_json string, made a line at a time (a line
// break is ASCII: no UTF-8 sequence, valid or not, spans one, so each line's escapes are those
// of the whole).
void write_program_json(std::ostream& out, std::istream& program) {
    out << '"';
    bool first = true;
    for_each_line(program, [&](std::string_view line) {
        if (!first) out << "\\n";
        first = false;
        const std::string quoted = script_json(std::string(line));
        out.write(quoted.data() + 1, static_cast<std::streamsize>(quoted.size() - 2));
    });
    out << '"';
}

// A read-only stream buffer over text kept elsewhere.
class ViewBuffer : public std::streambuf {
public:
    explicit ViewBuffer(std::string_view text) {
        char* begin = const_cast<char*>(text.data());  // never written: the buffer has no put area
        setg(begin, begin, begin + text.size());
    }
    void rewind() { setg(eback(), eback(), egptr()); }
};

constexpr const char* style = R"CSS(
body{margin:0;font:14px/1.4 "DejaVu Sans",Arial,Helvetica,sans-serif;color:#222;background:#f4f4f4}
header{padding:8px 16px;background:#fff;border-bottom:1px solid #ccc}
h1{font-size:18px;margin:0}h2{font-size:14px;margin:12px 0 6px}
header p{margin:2px 0 0;color:#555;font-size:12px}
main{display:flex;flex-wrap:wrap;gap:12px;padding:12px}
#view{flex:1 1 640px;min-width:320px;background:#fff;border:1px solid #ccc}
#view svg{display:block;width:100%;height:auto}
aside{flex:0 1 420px;min-width:300px}
aside section{background:#fff;border:1px solid #ccc;padding:4px 12px 10px;margin-bottom:12px}
.controls{display:flex;gap:6px;align-items:center}
.controls input[type=range]{flex:1}
pre{margin:0;font:12px/1.35 "DejaVu Sans Mono",monospace;white-space:pre-wrap;word-break:break-all}
#nc-before,#nc-after{color:#888}
#nc-current{background:#fff3b0;border-left:3px solid #e0a800;padding-left:4px}
table{border-collapse:collapse}td,th{padding:1px 8px 1px 0;text-align:left;font-weight:normal}
th{color:#555}td.num{font-family:"DejaVu Sans Mono",monospace;text-align:right}
label{display:block}label.off{color:#999}
.swatch{display:inline-block;width:12px;height:12px;margin-right:4px;vertical-align:-1px;background:#555}
.note{color:#666;font-size:12px}
)CSS";

constexpr const char* script = R"JS(
"use strict";
(function () {
  const data = JSON.parse(document.getElementById("camgen-data").textContent);
  const $ = (id) => document.getElementById(id);
  const nc = data.nc.split("\n");
  const count = data.moves.length / 5;
  const recLine = new Int32Array(count), recKind = new Int8Array(count);
  const recX = new Float64Array(count), recY = new Float64Array(count), recZ = new Float64Array(count);
  {
    const m = data.moves;
    let l = 0, x = 0, y = 0, z = 0;
    for (let i = 0; i < count; ++i) {
      l += m[5 * i]; x += m[5 * i + 2]; y += m[5 * i + 3]; z += m[5 * i + 4];
      recLine[i] = l; recKind[i] = m[5 * i + 1];
      recX[i] = x * data.unit; recY[i] = y * data.unit; recZ[i] = z * data.unit;
    }
  }
  const toolLine = [], toolNumber = [];
  for (let i = 0, l = 0; i < data.tools.length; i += 2) {
    l += data.tools[i];
    toolLine.push(l);
    toolNumber.push(data.tools[i + 1]);
  }
  // The last index whose line is at or before n, or -1.
  function lastAtOrBefore(lines, n) {
    let lo = 0, hi = lines.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (lines[mid] <= n) lo = mid + 1; else hi = mid;
    }
    return lo - 1;
  }
  function mm(v) { return (Math.abs(v) < 0.0005 ? 0 : v).toFixed(3); }

  const svg = document.querySelector("#view svg");
  const ns = "http://www.w3.org/2000/svg";
  const marker = document.createElementNS(ns, "g");
  marker.setAttribute("id", "marker");
  marker.setAttribute("pointer-events", "none");
  for (const [tag, attrs] of [["circle", {r: 7, fill: "none", stroke: "#fff", "stroke-width": 4}],
                              ["circle", {r: 7, fill: "none", stroke: "#000", "stroke-width": 2}],
                              ["path", {d: "M-12,0H-4M4,0H12M0,-12V-4M0,4V12", stroke: "#000", "stroke-width": 1.5}]]) {
    const e = document.createElementNS(ns, tag);
    for (const k in attrs) e.setAttribute(k, attrs[k]);
    marker.appendChild(e);
  }
  svg.appendChild(marker);
  // Where the drawing puts a position (backplot frame: min u, max v, scale, left, top).
  function place(x, y, z) {
    const f = data.frame, u = data.lathe ? z : x, v = data.lathe ? x : y;
    return [f[3] + (u - f[0]) * f[2], f[4] + (f[1] - v) * f[2]];
  }

  const slider = $("slider");
  function numbered(from, to) {
    const out = [];
    for (let k = Math.max(1, from); k <= Math.min(nc.length, to); ++k) out.push(k + "  " + nc[k - 1]);
    return out.join("\n");
  }
  function show(n) {
    n = Math.min(Math.max(1, Math.round(n) || 1), nc.length);
    $("line-no").textContent = n;
    $("nc-before").textContent = numbered(n - 3, n - 1);
    $("nc-no").textContent = n;
    $("nc-text").textContent = nc[n - 1];
    $("nc-after").textContent = numbered(n + 1, n + 3);
    const i = lastAtOrBefore(recLine, n);
    const known = i >= 0 && recKind[i] >= 0;
    $("pos-x").textContent = known ? mm(recX[i]) : "?";
    $("pos-y").textContent = known ? mm(recY[i]) : "?";
    $("pos-z").textContent = known ? mm(recZ[i]) : "?";
    if (data.lathe) $("pos-d").textContent = known ? mm(2 * recX[i]) : "?";
    $("move").textContent = i >= 0 && recLine[i] === n ? (recKind[i] >= 0 ? data.kinds[recKind[i]] : "tool change: position unknown")
                                                       : "no motion";
    const t = lastAtOrBefore(toolLine, n);
    $("tool").textContent = t >= 0 ? "T" + toolNumber[t] : "-";
    if (known) {
      const p = place(recX[i], recY[i], recZ[i]);
      marker.setAttribute("transform", "translate(" + p[0].toFixed(2) + "," + p[1].toFixed(2) + ")");
      marker.style.display = "";
    } else {
      marker.style.display = "none";
    }
  }
  slider.addEventListener("input", () => show(+slider.value));
  function step(by) {
    slider.value = +slider.value + by;
    slider.dispatchEvent(new Event("input"));
  }
  $("prev").addEventListener("click", () => step(-1));
  $("next").addEventListener("click", () => step(1));

  // Layers: an unchecked box hides every element of its class (tN: a tool, k-NAME: a kind).
  const boxes = Array.from(document.querySelectorAll("#layers input[data-class]"));
  function applyLayers() {
    const rules = [];
    for (const box of boxes) if (!box.checked) rules.push("#view ." + box.dataset.class + "{display:none}");
    $("layer-style").textContent = rules.join("\n");
  }
  for (const box of boxes) box.addEventListener("change", applyLayers);
  for (const swatch of document.querySelectorAll(".swatch[data-class]")) {
    const e = document.querySelector("#view ." + swatch.dataset.class + "[stroke]");
    if (e) swatch.style.background = e.getAttribute("stroke");
  }

  // #block=N shows block N; #block=A,B,C&check steps the slider to each as a user would and
  // records what the page shows, then switches each layer off and on again (a browser test).
  function fromHash() {
    const m = /^#block=([0-9]+(?:,[0-9]+)*)(&check)?$/.exec(location.hash);
    if (!m) return;
    const log = [];
    for (const b of m[1].split(",")) {
      slider.value = b;
      slider.dispatchEvent(new Event("input"));
      const shown = {block: +b, line: +$("line-no").textContent, nc: $("nc-text").textContent, x: $("pos-x").textContent,
                     y: $("pos-y").textContent, z: $("pos-z").textContent, tool: $("tool").textContent, move: $("move").textContent,
                     marker: marker.style.display === "none" ? null : marker.getAttribute("transform")};
      log.push(JSON.stringify(shown));
    }
    if (m[2]) {
      for (const box of boxes) {
        const all = Array.from(document.querySelectorAll("#view ." + box.dataset.class));
        const visible = () => all.filter((e) => getComputedStyle(e).display !== "none").length;
        const before = visible();
        box.click();
        const hidden = visible();
        box.click();
        log.push(JSON.stringify({layer: box.dataset.class, elements: all.length, before: before, hidden: hidden, after: visible()}));
      }
    }
    $("steps").textContent = log.join("\n");
  }
  window.addEventListener("hashchange", fromHash);
  show(+slider.value);
  fromHash();
})();
)JS";

}  // namespace

bool is_html_plot(std::string_view file) {
    auto ends = [&](std::string_view suffix) {
        if (file.size() < suffix.size()) return false;
        return std::equal(suffix.begin(), suffix.end(), file.end() - static_cast<std::ptrdiff_t>(suffix.size()),
                          [](char a, char b) { return std::tolower(static_cast<unsigned char>(b)) == a; });
    };
    return ends(".html") || ends(".htm");
}

namespace {
// The drawing's options on the page: its layers marked for the switches, and hole marks up to
// the limit.
BackplotOptions layered(const BackplotOptions& options, const HtmlPlotLimits& limits) {
    BackplotOptions o = options;
    o.layers = BackplotLayers::classes;
    o.hole_marks = limits.holes;
    return o;
}
}  // namespace

class HtmlPlot::Impl {
public:
    Impl(const BackplotPlan& plan, const ProgramStats& stats, const BackplotOptions& options, const HtmlPlotLimits& limits)
        : plan_(plan), stats_(stats), options_(options), limits_(limits), drawer_(plan, stats, layered(options, limits)) {
        if (plan.moves > limits.moves) thinning_.emplace(drawer_, stats, options.kind);
    }

    void step(const Step& s) {
        if (is_move(s)) {
            ++counts_[static_cast<std::size_t>(layer_of(s))];
            ++moves_;
        }
        if (s.kind == StepKind::tool_change) {
            fmt::format_to(std::back_inserter(tools_), "{}{},{}", tools_.empty() ? "" : ",", s.line - tool_line_, s.tool);
            tool_line_ = s.line;
        }
        drawing().step(s);
    }
    void hole(const Hole& h) { drawing().hole(h); }
    void finish(const TraceSummary& summary) {
        drawing().finish(summary);
        drawing_ = drawer_.take();
    }

    void write(std::ostream& out, const std::function<std::istream&()>& program,
               const std::function<void(TraceSink&)>& read_again) const;

private:
    TraceSink& drawing() { return thinning_ ? static_cast<TraceSink&>(*thinning_) : drawer_; }

    const BackplotPlan& plan_;
    const ProgramStats& stats_;
    BackplotOptions options_;
    HtmlPlotLimits limits_;
    BackplotDrawer drawer_;
    std::optional<Thinning> thinning_;  // between the steps and the drawer, beyond limits.moves
    std::string tools_;  // the (line step, tool) pairs of the tool changes
    int tool_line_ = 0;
    std::array<std::size_t, std::size(backplot_layers)> counts_{};  // moves of each layer
    std::size_t moves_ = 0;
    BackplotDrawing drawing_;
};

HtmlPlot::HtmlPlot(const BackplotPlan& plan, const ProgramStats& stats, const BackplotOptions& options, const HtmlPlotLimits& limits)
    : impl_(std::make_unique<Impl>(plan, stats, options, limits)) {}
HtmlPlot::~HtmlPlot() = default;
void HtmlPlot::step(const Step& step) { impl_->step(step); }
void HtmlPlot::hole(const Hole& hole) { impl_->hole(hole); }
void HtmlPlot::finish(const TraceSummary& summary) { impl_->finish(summary); }
void HtmlPlot::write(std::ostream& out, const std::function<std::istream&()>& program,
                     const std::function<void(TraceSink&)>& read_again) const {
    impl_->write(out, program, read_again);
}

std::string backplot_html(std::string_view program, const Trace& trace, const ProgramStats& stats,
                          const BackplotOptions& options, const HtmlPlotLimits& limits) {
    BackplotPlan plan(options.kind);
    for (const Step& s : trace.steps) plan.step(s);
    for (const Hole& h : trace.holes) plan.hole(h);
    plan.finish({});
    HtmlPlot plot(plan, stats, options, limits);
    const auto replay = [&](TraceSink& sink) {
        for (const Step& s : trace.steps) sink.step(s);
        for (const Hole& h : trace.holes) sink.hole(h);
        sink.finish({});
    };
    replay(plot);
    std::ostringstream page;
    ViewBuffer buffer(program);
    std::istream text(&buffer);
    const auto open = [&]() -> std::istream& {
        buffer.rewind();
        text.clear();
        return text;
    };
    plot.write(page, open, replay);
    return std::move(page).str();
}

void HtmlPlot::Impl::write(std::ostream& out, const std::function<std::istream&()>& program,
                           const std::function<void(TraceSink&)>& read_again) const {
    const BackplotOptions& options = options_;
    const ProgramStats& stats = stats_;
    const HtmlPlotLimits& limits = limits_;
    const bool lathe = options.kind == MachineKind::lathe;
    const bool thin = thinning_ && thinning_->merged();
    const BackplotDrawing& drawing = drawing_;
    std::size_t lines = 0;
    for_each_line(program(), [&](std::string_view) { ++lines; });
    const std::string title = options.title.empty() ? "program" : options.title;

    auto add = [&](std::string_view s) { out << s; };
    add("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    add("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
    add(fmt::format("<title>{} - camgen backplot</title>\n", html_text(title)));
    add(fmt::format("<style>{}</style>\n<style id=\"layer-style\"></style>\n</head>\n<body>\n", style));
    add(fmt::format("<header><h1>{}</h1><p>{}backplot of the program as camgen reads it back, {}</p></header>\n", html_text(title),
                    options.machine.empty() ? "" : html_text("machine " + options.machine + " - "),
                    lathe ? "XZ half-section" : "XY view"));
    add("<main>\n<div id=\"view\">\n");
    add(drawing.svg);
    add("</div>\n<aside>\n");

    // The block: slider, the block's text amid its neighbours, the position after it.
    add("<section id=\"block\"><h2>Block</h2>\n<div class=\"controls\"><button id=\"prev\" type=\"button\" title=\"previous "
        "block\">&#9664;</button>");
    add(fmt::format("<input id=\"slider\" type=\"range\" min=\"1\" max=\"{}\" value=\"1\" aria-label=\"block\">",
                    std::max<std::size_t>(lines, 1)));
    add("<button id=\"next\" type=\"button\" title=\"next block\">&#9654;</button></div>\n");
    add(fmt::format("<p>line <output id=\"line-no\">1</output> of {}</p>\n", lines));
    add("<pre id=\"nc-before\"></pre><pre id=\"nc-current\"><span id=\"nc-no\"></span>  <span id=\"nc-text\"></span></pre>"
        "<pre id=\"nc-after\"></pre>\n");
    add("<h2>Tool after this block</h2>\n<table>\n");
    // A lathe's X as the program writes it first (a diameter under xDiameterProg), the other beside it.
    add(lathe && stats.x_diameter
            ? "<tr><th>X</th><td class=\"num\" id=\"pos-d\"></td><td>mm (diameter, as programmed)</td></tr>\n"
              "<tr><th>r</th><td class=\"num\" id=\"pos-x\"></td><td>mm (radius)</td></tr>\n"
              "<tr hidden><th>Y</th><td class=\"num\" id=\"pos-y\"></td><td>mm</td></tr>\n"
        : lathe ? "<tr><th>X</th><td class=\"num\" id=\"pos-x\"></td><td>mm (radius, as programmed)</td></tr>\n"
                "<tr><th>&#216;</th><td class=\"num\" id=\"pos-d\"></td><td>mm (diameter)</td></tr>\n"
                "<tr hidden><th>Y</th><td class=\"num\" id=\"pos-y\"></td><td>mm</td></tr>\n"
              : "<tr><th>X</th><td class=\"num\" id=\"pos-x\"></td><td>mm</td></tr>\n"
                "<tr><th>Y</th><td class=\"num\" id=\"pos-y\"></td><td>mm</td></tr>\n");
    add("<tr><th>Z</th><td class=\"num\" id=\"pos-z\"></td><td>mm</td></tr>\n");
    add("<tr><th>tool</th><td id=\"tool\" colspan=\"2\"></td></tr>\n<tr><th>move</th><td id=\"move\" colspan=\"2\"></td></tr>\n");
    add("</table></section>\n");

    // Layers: each tool, each kind (with how many moves of the program are of it).
    add("<section id=\"layers\"><h2>Layers</h2>\n");
    for (const ToolStats& t : stats.tools)
        add(fmt::format("<label><input type=\"checkbox\" checked data-class=\"t{0}\"><span class=\"swatch\" data-class=\"t{0}\"></span>"
                        "T{0} {1}</label>\n",
                        t.tool, html_text(t.description)));
    std::array<std::size_t, std::size(backplot_layers)> counts = counts_;
    counts[static_cast<std::size_t>(BackplotLayer::width)] = counts[static_cast<std::size_t>(BackplotLayer::feed)];
    counts[static_cast<std::size_t>(BackplotLayer::hole)] = plan_.holes;
    for (const auto& layer : backplot_layers) {
        const std::size_t n = counts[static_cast<std::size_t>(layer.value)];
        const bool moves = layer.value != BackplotLayer::width && layer.value != BackplotLayer::hole;
        add(fmt::format("<label{}><input type=\"checkbox\" {} data-class=\"k-{}\">{} <span class=\"note\">{}{}</span></label>\n",
                        n ? "" : " class=\"off\"", n ? "checked" : "disabled", layer.name, layer.name, html_text(layer.description),
                        n == 0 ? ": none in this program"
                               : moves ? fmt::format(", {} move{}", grouped(n), n == 1 ? "" : "s")
                               : layer.value == BackplotLayer::hole ? fmt::format(", {}", grouped(n))
                                                                    : std::string()));
    }
    if (thin)
        add(fmt::format("<p class=\"note\" id=\"thinned\">Drawing thinned: {} moves are drawn as {} lines (runs of straight moves "
                        "whose points lie within half a pixel of one line). The slider and the numbers show every block.</p>\n",
                        grouped(moves_), grouped(thinning_->moves())));
    if (plan_.holes > limits.holes && !lathe)
        add(fmt::format("<p class=\"note\" id=\"plain-holes\">Holes beyond the first {} are drawn as plain circles (no cross), {} of "
                        "{}.</p>\n",
                        grouped(limits.holes), grouped(plan_.holes - limits.holes), grouped(plan_.holes)));
    add("</section>\n");

    add(fmt::format("<section id=\"stats\"><h2>Statistics</h2>\n<pre>{}</pre></section>\n", html_text(format_stats(stats))));
    add("</aside>\n</main>\n<pre id=\"steps\" hidden></pre>\n");

    // The data: every block's text, and where each block leaves the tool (written in pieces:
    // the lists and the text are the size of the program).
    const BackplotFrame& f = drawing.frame;
    std::string kinds;
    for (const auto& layer : backplot_layers) kinds += fmt::format("{}\"{}\"", kinds.empty() ? "" : ",", layer.name);
    add("<script type=\"application/json\" id=\"camgen-data\">");
    add(fmt::format("{{\"lathe\":{},\"unit\":{},\"frame\":[{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}],\"kinds\":[{}],\n\"tools\":[",
                    lathe ? "true" : "false", data_unit, f.min_u + 0.0, f.max_v + 0.0, f.scale, f.left, f.top, kinds));
    add(tools_);
    add("],\n\"moves\":[");
    BlockMoves moves(out);
    read_again(moves);
    add("],\n\"nc\":");
    write_program_json(out, program());
    add("}");
    add("</script>\n<script>");
    add(script);
    add("</script>\n</body>\n</html>\n");
}

}  // namespace camgen
