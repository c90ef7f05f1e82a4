#include "camgen/analysis/backplot.hpp"
#include "camgen/common/markup.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "camgen/nc/format.hpp"

namespace camgen {

namespace {

constexpr const char* palette[] = {"#1f5fbf", "#d62728", "#2a9d3a", "#8e44ad", "#e67e22", "#8c564b", "#d63384", "#17a2b8"};
constexpr const char* font = "font-family=\"DejaVu Sans, Arial, Helvetica, sans-serif\"";

// Every number in the SVG: fixed notation, no exponent, no -0, '.' as decimal mark.
std::string n(double v, int decimals = 2) {
    nc::FormatSpec spec;
    spec.decimals = decimals;
    return nc::Format(spec).format(v);
}

std::string mm(double v) { return n(v, 3); }

std::string clip(std::string s, size_t max) {
    if (s.size() <= max) return s;
    s.resize(max - 3);
    return s + "...";
}

// 1, 2 or 5 times a power of ten, the largest not above `limit`.
double nice_below(double limit) {
    double p = std::pow(10.0, std::floor(std::log10(limit)));
    for (double m : {5.0, 2.0, 1.0})
        if (m * p <= limit) return m * p;
    return p;
}

struct View {
    double min_x = 0, max_y = 0, scale = 1, left = 0, top = 0;
    double x(double mx) const { return left + (mx - min_x) * scale; }
    double y(double my) const { return top + (max_y - my) * scale; }
    std::string at(const Vec3& p) const { return fmt::format("{},{}", n(x(p.x)), n(y(p.y))); }
};

class Svg {
public:
    void add(const std::string& s) {
        out_ += s;
        out_ += '\n';
    }
    std::string text() const { return out_; }
    // Appends what another one holds.
    void add_all(const Svg& other) { out_ += other.out_; }

private:
    std::string out_;
};

double xy_length(const Step& s) { return std::hypot(s.to.x - s.from.x, s.to.y - s.from.y); }

// SVG path commands for one move, continuing from its start.
std::string path_of(const Step& s, const View& v) {
    if (!s.arc) return fmt::format("L{}", v.at(s.to));
    const ArcGeometry& g = *s.arc;
    std::string d;
    if (g.plane == Plane::xy) {
        // Arcs of at most 180 degrees each. The flip of y keeps the picture as seen from
        // above, so a counter-clockwise arc stays counter-clockwise on screen; with y pointing
        // down that is SVG's negative angle direction: sweep flag 0.
        int pieces = std::max(1, static_cast<int>(std::ceil(g.sweep / pi - 1e-9)));
        for (int k = 1; k <= pieces; ++k) {
            Vec3 p = point_on_arc(g, double(k) / pieces);
            d += fmt::format("A{},{} 0 0 {} {}", n(g.radius * v.scale), n(g.radius * v.scale),
                             g.direction == ArcDirection::ccw ? 0 : 1, v.at(p));
        }
        return d;
    }
    // Other planes: the projection of the arc, as points.
    int pieces = std::clamp(static_cast<int>(std::ceil(g.sweep / (pi / 36))), 2, 720);
    for (int k = 1; k <= pieces; ++k) d += fmt::format("L{}", v.at(point_on_arc(g, double(k) / pieces)));
    return d;
}

// A small arrowhead at the middle of a feed move, pointing the way it goes.
std::string arrow(const Step& s, const View& v, const char* colour, const std::string& attributes) {
    Vec3 a, b, m;
    if (s.arc) {
        a = point_on_arc(*s.arc, 0.45), b = point_on_arc(*s.arc, 0.55), m = point_on_arc(*s.arc, 0.5);
    } else {
        a = s.from, b = s.to, m = {(s.from.x + s.to.x) / 2, (s.from.y + s.to.y) / 2, 0};
    }
    double dx = v.x(b.x) - v.x(a.x), dy = v.y(b.y) - v.y(a.y), len = std::hypot(dx, dy);
    if (len < 1e-9) return {};
    dx /= len, dy /= len;
    double cx = v.x(m.x), cy = v.y(m.y), size = 5.0;
    // Tip ahead of the middle, two corners behind it.
    double tx = cx + dx * size, ty = cy + dy * size;
    double bx = cx - dx * size, by = cy - dy * size;
    return fmt::format("<polygon{} points=\"{},{} {},{} {},{}\" fill=\"{}\"/>", attributes, n(tx), n(ty), n(bx - dy * size * 0.6),
                       n(by + dx * size * 0.6), n(bx + dy * size * 0.6), n(by - dx * size * 0.6), colour);
}

}  // namespace

namespace {

// What the drawing shows, for its notes: the XY view of a mill, the XZ half-section of a lathe.
struct ViewText {
    std::string_view note;        // under the legend
    std::string_view name;        // in the subtitle
    std::string_view across, up;  // the axes drawn to the right and up
};
constexpr ViewText xy_view{"XY view from above; moves along Z only show as points.", "XY view", "X", "Y"};
constexpr ViewText section_view{"XZ half-section: Z right, X (radius) up.", "XZ half-section", "Z", "X"};
// A lathe that programs X as a diameter: the section is drawn to scale (the radius up), its
// X labels are the program's diameters.
constexpr ViewText section_view_diameter{"XZ half-section: Z right, X up, labelled as diameters.",
                                         "XZ half-section", "Z", "X"};

// A position of a lathe's program in the half-section drawn as XY: (Z, X, Y).
Vec3 section_of(const Vec3& p) { return {p.z, p.x, p.y}; }

// A step of a lathe's program mapped into the half-section: Z becomes the drawing's X, the
// radius its Y. G18 arcs become XY arcs of the same turn (both planes' (u, v) are (Z, X)).
// Holes on the axis are no circles in a section: their pecks show as moves.
Step section_of(const Step& step) {
    Step s = step;
    s.from = section_of(s.from);
    s.to = section_of(s.to);
    if (s.arc) {
        ArcGeometry& g = *s.arc;
        g.start = section_of(g.start);
        g.end = section_of(g.end);
        g.centre = section_of(g.centre);
        // (Z, X, Y): the XZ plane's (u, v) = (Z, X) become XY's; XY's become YZ's, YZ's XZ's.
        g.plane = g.plane == Plane::xz ? Plane::xy : g.plane == Plane::xy ? Plane::yz : Plane::xz;
    }
    return s;
}

ProgramStats section_of(const ProgramStats& stats) {
    ProgramStats s = stats;
    s.box.min = section_of(stats.box.min);
    s.box.max = section_of(stats.box.max);
    return s;
}

}  // namespace

class BackplotDrawer::Impl {
public:
    Impl(const BackplotPlan& plan, const ProgramStats& program_stats, const BackplotOptions& options)
        : options_(options),
          view_(options.kind != MachineKind::lathe ? xy_view : program_stats.x_diameter ? section_view_diameter : section_view),
          stats_(options.kind == MachineKind::lathe ? section_of(program_stats) : program_stats),
          plan_(plan) {
        const ViewText& view = view_;
        for (const ToolStats& t : stats_.tools) {
            (void)colour_of(t.tool);
            diameter_[t.tool] = t.diameter;
        }
        // The drawing: the XY extent of every known position and hole, with a margin.
        double max_x = 0, max_y = 0;
        bool any = !stats_.box.empty;
        if (any) min_x = stats_.box.min.x, max_x = stats_.box.max.x, min_y = stats_.box.min.y, max_y = stats_.box.max.y;
        for (const auto& [tool, box] : plan_.hole_centres) {
            double r = diameter_[tool] / 2.0;
            min_x = std::min(min_x, box.min.x - r), max_x = std::max(max_x, box.max.x + r);
            min_y = std::min(min_y, box.min.y - r), max_y = std::max(max_y, box.max.y + r);
        }
        // A lathe's bar (section: Z across, the radius up) is drawn whole.
        if (options.kind == MachineKind::lathe && options.bar) {
            const BackplotBar& bar = *options.bar;
            const double u0 = bar.face_z - bar.length, u1 = bar.face_z, r = bar.diameter / 2.0;
            if (!any) min_x = u0, max_x = u1, min_y = 0.0, max_y = r;
            any = true;
            min_x = std::min(min_x, u0), max_x = std::max(max_x, u1);
            min_y = std::min(min_y, 0.0), max_y = std::max(max_y, r);
        }
        span = std::max({max_x - min_x, max_y - min_y, 10.0});
        double pad = span * 0.06;
        min_x -= pad, max_x += pad, min_y -= pad, max_y += pad;
        dx = std::max(max_x - min_x, span * 0.2), dy = std::max(max_y - min_y, span * 0.2);

        v.scale = std::min(draw_w_max / dx, draw_h_max / dy);
        v.min_x = min_x, v.max_y = min_y + dy, v.left = left, v.top = top;
        draw_w = dx * v.scale, draw_h = dy * v.scale;
        legend_x = left + draw_w + 40;
        width = legend_x + legend_w;
        Svg& body = head_;
        // Grid with coordinates every `step` mm.
        double step = nice_below(span / 4.0);
        body.add("<g stroke=\"#e4e4e4\" stroke-width=\"1\">");
        for (double gx = std::ceil(min_x / step) * step; gx <= min_x + dx + 1e-9; gx += step)
            body.add(fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\"/>", n(v.x(gx)), n(top), n(top + draw_h)));
        for (double gy = std::ceil(min_y / step) * step; gy <= min_y + dy + 1e-9; gy += step)
            body.add(fmt::format("<line x1=\"{1}\" y1=\"{0}\" x2=\"{2}\" y2=\"{0}\"/>", n(v.y(gy)), n(left), n(left + draw_w)));
        body.add("</g>");
        body.add(fmt::format("<g {} font-size=\"10\" fill=\"#777\">", font));
        for (double gx = std::ceil(min_x / step) * step; gx <= min_x + dx + 1e-9; gx += step)
            body.add(fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>", n(v.x(gx)), n(top + draw_h + 14),
                                 mm(std::abs(gx) < 1e-9 ? 0.0 : gx)));
        const double up_label = diameter_up() ? 2.0 : 1.0;
        for (double gy = std::ceil(min_y / step) * step; gy <= min_y + dy + 1e-9; gy += step)
            body.add(fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>", n(left - 6), n(v.y(gy) + 3),
                                 mm(std::abs(gy) < 1e-9 ? 0.0 : gy * up_label)));
        body.add(fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{} mm</text>", n(left + draw_w / 2), n(top + draw_h + 28),
                             view.across));
        body.add(fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 {} {})\">{} mm{}</text>",
                             n(left - 40), n(top + draw_h / 2), n(left - 40), n(top + draw_h / 2), view.up,
                             options.kind != MachineKind::lathe ? "" : diameter_up() ? " (diameter)" : " (radius)"));
        body.add("</g>");
        body.add(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#bbb\"/>", n(left), n(top),
                             n(draw_w), n(draw_h)));
        if (options.kind == MachineKind::lathe && options.bar) {
            // The bar's outline: between its bore (a tube) or the axis and its outside.
            const BackplotBar& bar = *options.bar;
            const double u0 = bar.face_z - bar.length, u1 = bar.face_z, r = bar.diameter / 2.0;
            const double inner = bar.bore_diameter ? *bar.bore_diameter / 2.0 : 0.0;
            body.add(fmt::format("<path id=\"bar\" d=\"M{},{}H{}V{}H{}Z\" fill=\"#8a8a8a\" fill-opacity=\"0.12\" stroke=\"#666\" "
                                 "stroke-width=\"1.2\"/>",
                                 n(v.x(u0)), n(v.y(inner)), n(v.x(u1)), n(v.y(r)), n(v.x(u0))));
        }

        // The work zero.
        if (0 >= min_x && 0 <= min_x + dx && 0 >= min_y && 0 <= min_y + dy) {
            double ox = v.x(0), oy = v.y(0);
            body.add(fmt::format("<g stroke=\"#444\" stroke-width=\"1.2\" fill=\"none\"><path d=\"M{0},{1}H{2}M{0},{1}V{3}\"/>"
                                 "<circle cx=\"{0}\" cy=\"{1}\" r=\"4\"/></g>",
                                 n(ox), n(oy), n(ox + 28), n(oy - 28)));
            body.add(fmt::format("<g {} font-size=\"10\" fill=\"#444\"><text x=\"{}\" y=\"{}\">{}</text><text x=\"{}\" y=\"{}\">{}</text>"
                                 "<text x=\"{}\" y=\"{}\">{}0 {}0</text></g>",
                                 font, n(ox + 24), n(oy + 13), view.across, n(ox - 12), n(oy - 22), view.up, n(ox + 6), n(oy - 6),
                                 view.across, view.up));
        }
    }

    void step(const Step& step) {
        if (step.kind != StepKind::rapid && step.kind != StepKind::feed) return;
        const Step s = options_.kind == MachineKind::lathe ? section_of(step) : step;
        band(s);
        move(s);
        plunge(s);
    }

    void hole(const Hole& h) {
        if (options_.kind == MachineKind::lathe) {
            axis_hole(h);
            return;
        }
        const size_t i = holes_++;
        double r = std::max(diameter_[h.tool] / 2.0 * v.scale, 3.0);
        double cx = v.x(h.at.x), cy = v.y(h.at.y);
        const char* c = colour_of(h.tool);
        if (i >= options_.hole_marks || i >= options_.exact) {
            const Vec3 at{h.at.x, h.at.y, 0.0};
            if (i < options_.exact || fresh(Cover::hole, h.tool, at, at, nullptr))
                rings_[h.tool] += fmt::format("M{0},{1}a{2},{2} 0 1 0 {3},0a{2},{2} 0 1 0 -{3},0", n(cx - r), n(cy), n(r), n(2 * r));
            else
                ++thinned_;
        } else {
            hole_marks_.add(fmt::format("<circle{} cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\" fill-opacity=\"0.12\" stroke=\"{}\" stroke-width=\"1.2\"/>",
                                        mark({h.tool}, BackplotLayer::hole), n(cx), n(cy), n(r), c, c));
            hole_marks_.add(fmt::format("<path{} d=\"M{},{}H{}M{},{}V{}\" stroke=\"{}\" stroke-width=\"0.8\"/>", mark({h.tool}, BackplotLayer::hole),
                                        n(cx - r - 3), n(cy), n(cx + r + 3), n(cx), n(cy - r - 3), n(cy + r + 3), c));
        }
        // Beyond options.exact holes only the last of each tool is numbered.
        const int number = static_cast<int>(i) + 1;
        auto first_last = plan_.first_last.find(h.tool);
        if (i >= options_.exact && (first_last == plan_.first_last.end() || number != first_last->second.second)) {
            ++unnumbered_;
            return;
        }
        auto key = std::make_pair(std::lround(h.at.x * 1000.0), std::lround(h.at.y * 1000.0));
        auto [it, fresh_place] = label_at_.try_emplace(key, labels_.size());
        if (fresh_place) labels_.push_back({h.at, {}});
        labels_[it->second].second.push_back({number, h.tool});
    }

    // A hole on a lathe's axis, in the half-section: its bottom (a line across the drill's
    // radius, a dot on the axis) and its number in drilling order.
    void axis_hole(const Hole& h) {
        const size_t i = holes_++;
        const Vec2 at{h.bottom_z, h.at.x};  // (Z, X): the section's (u, v)
        const char* c = colour_of(h.tool);
        const double cx = v.x(at.x), cy = v.y(at.y), r = diameter_[h.tool] / 2.0 * v.scale;
        if (i < options_.exact || fresh(Cover::hole, h.tool, Vec3{at.x, at.y, 0.0}, Vec3{at.x, at.y, 0.0}, nullptr))
            hole_marks_.add(fmt::format("<g{} stroke=\"{}\" stroke-width=\"1.2\"><path d=\"M{},{}V{}\"/><circle cx=\"{}\" cy=\"{}\" "
                                        "r=\"3\" fill=\"{}\"/></g>",
                                        mark({h.tool}, BackplotLayer::hole), c, n(cx), n(cy), n(cy - std::max(r, 3.0)), n(cx), n(cy), c));
        else
            ++thinned_;
        const int number = static_cast<int>(i) + 1;
        auto first_last = plan_.first_last.find(h.tool);
        if (i >= options_.exact && (first_last == plan_.first_last.end() || number != first_last->second.second)) {
            ++unnumbered_;
            return;
        }
        auto key = std::make_pair(std::lround(at.x * 1000.0), std::lround(at.y * 1000.0));
        auto [it, fresh_place] = label_at_.try_emplace(key, labels_.size());
        if (fresh_place) labels_.push_back({at, {}});
        labels_[it->second].second.push_back({number, h.tool});
    }

    // A lathe that programs X as a diameter: its X labels are diameters.
    bool diameter_up() const { return options_.kind == MachineKind::lathe && stats_.x_diameter; }

    BackplotDrawing finish() {
        const ViewText& view = view_;
        Svg body = std::move(head_);
        bands(body);
        moves(body);
        body.add_all(plunges_);
        body.add_all(hole_marks_);
        for (const auto& [tool, d] : rings_)
            body.add(fmt::format("<path{} d=\"{}\" fill=\"{}\" fill-opacity=\"0.12\" stroke=\"{}\" stroke-width=\"1.2\"/>",
                                 mark({tool}, BackplotLayer::hole), d, colour_of(tool), colour_of(tool)));
        const int left_out = numbers(body);

        // Scale bar under the drawing, left.
        double bar = nice_below(120.0 / v.scale);
        double bx = left, by = top + draw_h + 48, bw = bar * v.scale;
        body.add(fmt::format("<g stroke=\"#222\" stroke-width=\"1.5\"><path d=\"M{0},{1}H{2}M{0},{3}V{4}M{2},{3}V{4}\"/></g>", n(bx), n(by),
                             n(bx + bw), n(by - 5), n(by + 5)));
        body.add(fmt::format("<text x=\"{}\" y=\"{}\" {} font-size=\"11\" fill=\"#222\">{} mm</text>", n(bx + bw + 8), n(by + 4), font,
                             mm(bar)));

        const ProgramStats& stats = stats_;
        const BackplotOptions& options = options_;
        // Legend.
        Svg legend;
        double ly = top;
        auto text = [&](double x, const std::string& s, int size = 12, const char* weight = "normal", const char* fill = "#222") {
            legend.add(fmt::format("<text x=\"{}\" y=\"{}\" {} font-size=\"{}\" font-weight=\"{}\" fill=\"{}\">{}</text>", n(x), n(ly), font,
                                   size, weight, fill, html_text(s)));
        };
        double lx = legend_x;
        text(lx, "Key", 13, "bold");
        ly += 20;
        legend.add(fmt::format("<path d=\"M{},{}h36\" stroke=\"#555\" stroke-width=\"1\" stroke-dasharray=\"5 4\"/>", n(lx), n(ly - 4)));
        text(lx + 46, "rapid (G0)");
        ly += 18;
        legend.add(fmt::format("<path d=\"M{},{}h36\" stroke=\"#555\" stroke-width=\"2\"/>", n(lx), n(ly - 4)));
        legend.add(fmt::format("<polygon points=\"{},{} {},{} {},{}\" fill=\"#555\"/>", n(lx + 23), n(ly - 4), n(lx + 13), n(ly - 10),
                               n(lx + 13), n(ly + 2)));
        text(lx + 46, "feed, arrow = direction of cut");
        ly += 18;
        legend.add(fmt::format("<path d=\"M{},{}h36\" stroke=\"#555\" stroke-width=\"10\" stroke-opacity=\"0.25\" "
                               "stroke-linecap=\"round\"/>",
                               n(lx + 5), n(ly - 4)));
        text(lx + 46, "width cut by the tool, darker = deeper");
        ly += 18;
        legend.add(fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"6\" fill=\"#555\" fill-opacity=\"0.12\" stroke=\"#555\"/>", n(lx + 18),
                               n(ly - 4)));
        legend.add(fmt::format("<path d=\"M{},{}h18M{},{}v18\" stroke=\"#555\" stroke-width=\"0.8\"/>", n(lx + 9), n(ly - 4), n(lx + 18),
                               n(ly - 13)));
        text(lx + 46, options.kind == MachineKind::lathe ? "hole on the axis (its bottom), drilling order"
                                                         : "hole (tool size), number = drilling order");
        ly += 18;
        legend.add(fmt::format("<g stroke=\"#555\" stroke-width=\"1.2\"><rect x=\"{0}\" y=\"{1}\" width=\"8\" height=\"8\" "
                               "fill=\"#fff\"/><path d=\"M{0},{1}l8,8M{2},{1}l-8,8\"/></g>",
                               n(lx + 14), n(ly - 8), n(lx + 22)));
        text(lx + 46, "plunge: feed straight down (not a hole)");
        ly += 26;

        text(lx, "Tools", 13, "bold");
        ly += 20;
        for (const ToolStats& t : stats.tools) {
            legend.add(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"14\" height=\"14\" fill=\"{}\"/>", n(lx), n(ly - 11), colour_of(t.tool)));
            text(lx + 22, clip(fmt::format("T{}  {}", t.tool, t.description.empty() ? "(no description)" : t.description), 48), 12, "bold");
            ly += 16;
            std::string line = fmt::format("{} hole{}, feed {} mm, rapid {} mm", t.holes, t.holes == 1 ? "" : "s", n(t.feed_length, 1),
                                           n(t.rapid_length, 1));
            text(lx + 22, line, 11, "normal", "#444");
            ly += 15;
            if (!t.box.empty) {
                if (options.kind == MachineKind::lathe)
                    text(lx + 22, fmt::format("X ({}) {} .. {}, Z {} .. {}", stats.x_diameter ? "diameter" : "radius",
                                              n(t.box.min.x * (stats.x_diameter ? 2 : 1), 1), n(t.box.max.x * (stats.x_diameter ? 2 : 1), 1),
                                              n(t.box.min.z, 1), n(t.box.max.z, 1)),
                         11, "normal", "#444");
                else
                    text(lx + 22, fmt::format("X {} .. {}, Y {} .. {}, Z {} .. {}", n(t.box.min.x, 1), n(t.box.max.x, 1),
                                              n(t.box.min.y, 1), n(t.box.max.y, 1), n(t.box.min.z, 1), n(t.box.max.z, 1)),
                         11, "normal", "#444");
                ly += 20;
            }
        }
        ly += 6;
        text(lx, "Program", 13, "bold");
        ly += 20;
        auto row = [&](const std::string& label, const std::string& value) {
            text(lx, label, 11, "normal", "#444");
            text(lx + 80, value, 11);
            ly += 15;
        };
        auto note = [&](const std::string& value) {
            text(lx + 80, value, 10, "normal", "#555");
            ly += 14;
        };
        row("holes", std::to_string(stats.holes));
        row("feed path", mm(stats.feed_length) + " mm");
        row("rapid path", mm(stats.rapid_length) + " mm");
        if (stats.unmeasured_rapids > 0)
            note(fmt::format("+ {} from the tool change, not measured", stats.unmeasured_rapids));
        row("lowest Z", stats.lowest_z ? mm(*stats.lowest_z) + " mm" : std::string("-"));
        row("time", format_duration(stats.total_time()));
        note(fmt::format("feed {}, dwell {}", format_duration(stats.feed_time), format_duration(stats.dwell_time)));
        note(fmt::format("rapid {} at {} mm/min", format_duration(stats.rapid_time), n(stats.rapid_rate, 0)));
        if (stats.clamped_feeds) note(fmt::format("{} feed moves clamped to the machine's limits", stats.clamped_feeds));
        // Stops do not move: the legend counts them (verify and the HTML page list them).
        if (stats.stops > 0)
            row("stops", stats.optional_stops ? fmt::format("{} ({} optional)", stats.stops, stats.optional_stops)
                                              : std::to_string(stats.stops));
        ly += 8;
        if (left_out > 0) {
            text(lx, fmt::format("{} hole numbers left out where they would overlap.", left_out), 11, "normal", "#777");
            ly += 15;
        }
        if (thinned_ > 0) {
            text(lx, fmt::format("Beyond {} of a kind, {} moves, marks and holes", options.exact, thinned_), 11, "normal", "#777");
            ly += 15;
            text(lx, "are left out where they would cover drawn pixels only.", 11, "normal", "#777");
            ly += 15;
        }
        if (unnumbered_ > 0) {
            text(lx, fmt::format("{} holes after the first {} have no number", unnumbered_, options.exact), 11, "normal", "#777");
            ly += 15;
            text(lx, "(but the last of each tool) and are drawn as plain circles.", 11, "normal", "#777");
            ly += 15;
        }
        if (options.kind != MachineKind::lathe)
            text(lx, "No stock outline: the job format has no stock yet.", 11, "normal", "#777");
        else if (options.bar) {
            text(lx, fmt::format("Grey: the job's bar, diameter {} mm,", mm(options.bar->diameter)), 11, "normal", "#777");
            ly += 15;
            text(lx, fmt::format("{} mm long{}, its face at Z {}.", mm(options.bar->length),
                                 options.bar->bore_diameter ? fmt::format(" (bore {} mm)", mm(*options.bar->bore_diameter)) : "",
                                 mm(options.bar->face_z)),
                 11, "normal", "#777");
        } else
            text(lx, "No bar outline: no stock bar given by a job.", 11, "normal", "#777");
        ly += 15;
        text(lx, std::string(view.note), 11, "normal", "#777");
        ly += 10;

        double height = std::max(top + draw_h + 70, ly + 20);
        Svg svg;
        svg.add(fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">", n(width, 0),
                            n(height, 0)));
        svg.add(fmt::format("<rect width=\"{}\" height=\"{}\" fill=\"#fff\"/>", n(width, 0), n(height, 0)));
        svg.add(fmt::format("<text x=\"{}\" y=\"{}\" {} font-size=\"18\" font-weight=\"bold\" fill=\"#111\">{}</text>", n(left), n(30), font,
                            html_text(options.title.empty() ? "program" : options.title)));
        svg.add(fmt::format("<text x=\"{}\" y=\"{}\" {} font-size=\"12\" fill=\"#555\">{}backplot of the program as camgen reads it back, "
                            "{}</text>",
                            n(left), n(47), font, html_text(options.machine.empty() ? "" : "machine " + options.machine + " - "), view.name));
        return {svg.text() + body.text() + legend.text() + "</svg>\n", {v.min_x, v.max_y, v.scale, v.left, v.top}};
    }

private:
    // What a pixel of the drawing is covered by, per tool, once a kind has more than
    // options.exact elements (then only those that cover a pixel none before did are drawn).
    enum class Cover { rapid, feed, plunge, ramp, lead, width, plunge_mark, hole };

    // The layer classes an element carries for the HTML page ("t1 t7 k-hole"), or none.
    std::string mark(const std::vector<int>& tools, BackplotLayer layer) const {
        if (options_.layers == BackplotLayers::none) return std::string();
        std::string classes;
        for (int t : tools) classes += fmt::format("t{} ", t);
        return fmt::format(" class=\"{}k-{}\"", classes, name_of(backplot_layers, layer));
    }

    // Colours by tool, in order of first use.
    const char* colour_of(int tool) {
        if (!colour_.count(tool)) colour_[tool] = palette[colour_.size() % std::size(palette)];
        return colour_[tool];
    }

    // True when the move (a point where a == b) from `a` to `b` (along `arc` where there is
    // one) covers a pixel of the drawing that `what` of this tool did not cover yet; marks them.
    bool fresh(Cover what, int tool, const Vec3& a, const Vec3& b, const ArcGeometry* arc) {
        const auto cols = static_cast<long>(std::ceil(draw_w)) + 1, rows = static_cast<long>(std::ceil(draw_h)) + 1;
        std::vector<bool>& bits = coverage_[{what, tool}];
        if (bits.empty()) bits.assign(static_cast<size_t>(cols * rows), false);
        const double px = (arc ? arc->radius * arc->sweep : std::hypot(b.x - a.x, b.y - a.y)) * v.scale;
        const int samples = std::clamp(static_cast<int>(std::ceil(px * 2.0)), 1, 100000);
        bool any = false;
        for (int k = 0; k <= samples; ++k) {
            const double t = static_cast<double>(k) / samples;
            const Vec3 p = arc ? point_on_arc(*arc, t) : Vec3{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), 0.0};
            const long c = std::clamp(static_cast<long>(std::floor(v.x(p.x) - left)), 0L, cols - 1);
            const long r = std::clamp(static_cast<long>(std::floor(v.y(p.y) - top)), 0L, rows - 1);
            auto bit = bits[static_cast<size_t>(r * cols + c)];
            if (!bit) {
                bit = true;
                any = true;
            }
        }
        return any;
    }

    // Whether to draw the next element of a kind (`count` so far): all up to options.exact,
    // beyond only those that cover a new pixel.
    bool drawn(std::size_t& count, Cover what, const Step& s) {
        if (count++ < options_.exact) return true;
        if (fresh(what, s.tool, s.from, s.to, s.arc ? &*s.arc : nullptr)) return true;
        ++thinned_;
        return false;
    }

    // The cut's width: each feed move in XY drawn as wide as its tool, deeper levels darker,
    // so that a bore milled with a smaller tool shows its full diameter and passes stand apart.
    void band(const Step& s) {
        if (s.kind != StepKind::feed || !s.from_known || diameter_[s.tool] <= 0) return;
        if (!s.arc && xy_length(s) < 1e-9) return;
        // Moves at one Z are a pass; moves going up or down (ramps, helices, the lines a
        // helix becomes) are drawn together, lightest.
        const bool flat = std::abs(s.to.z - s.from.z) < 1e-9;
        if (flat) {
            lowest_ = seen_ ? std::min(lowest_, s.to.z) : s.to.z;
            highest_ = seen_ ? std::max(highest_, s.to.z) : s.to.z;
            seen_ = true;
        }
        if (!drawn(band_count_, Cover::width, s)) return;
        const std::pair<int, long> key{s.tool, flat ? std::lround(s.to.z * 100) : ramp_level};
        std::string& path = swept_[key];
        if (!swept_last_.count(key) || !(swept_last_[key] == s.from)) path += fmt::format("M{}", v.at(s.from));
        path += path_of(s, v);
        swept_last_[key] = s.to;
    }

    void bands(Svg& body) {
        const double lowest = lowest_, highest = highest_;
        for (const auto& [key, path] : swept_) {
            const double z = key.second / 100.0;
            const double depth = key.second == ramp_level ? 0.0 : highest > lowest ? (highest - z) / (highest - lowest) : 1.0;
            // Seen from above a mill's cutter is a circle: the band ends round. In a lathe's
            // half-section a drill on the axis cuts to its end and no farther: square ends.
            body.add(fmt::format("<path{} d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linecap=\"{}\" "
                                 "stroke-linejoin=\"round\" stroke-opacity=\"{}\"/>",
                                 mark({key.first}, BackplotLayer::width), path, colour_of(key.first), n(diameter_[key.first] * v.scale),
                                 options_.kind == MachineKind::lathe ? "butt" : "round", n(0.08 + 0.17 * depth)));
        }
    }

    // Moves: one path per tool and kind, rapids first so that cuts are drawn over them. With
    // layers, feed moves are split by their kind (plunge, ramp, lead) for the page's switches.
    void move(const Step& s) {
        const BackplotLayer kind =
            options_.layers == BackplotLayers::none && s.kind == StepKind::feed ? BackplotLayer::feed : layer_of(s);
        if (!s.from_known) return;
        if (!s.arc && xy_length(s) < 1e-9) return;  // a move along Z only: seen from above it is a point
        Moves& m = moves_[static_cast<size_t>(kind)];
        if (!drawn(m.count, static_cast<Cover>(kind), s)) return;
        std::string& path = m.d[s.tool];
        if (!m.last.count(s.tool) || !(m.last[s.tool] == s.from)) path += fmt::format("M{}", v.at(s.from));
        path += path_of(s, v);
        m.last[s.tool] = s.to;
        double px = s.arc ? s.arc->radius * s.arc->sweep * v.scale : xy_length(s) * v.scale;
        if (kind != BackplotLayer::rapid && px >= 24) m.arrows.push_back(arrow(s, v, colour_of(s.tool), mark({s.tool}, kind)));
    }

    void moves(Svg& body) {
        for (BackplotLayer kind : {BackplotLayer::rapid, BackplotLayer::feed, BackplotLayer::plunge, BackplotLayer::ramp, BackplotLayer::lead}) {
            Moves& m = moves_[static_cast<size_t>(kind)];
            for (const auto& [tool, path] : m.d) {
                if (kind == BackplotLayer::rapid)
                    body.add(fmt::format("<path{} d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1\" stroke-dasharray=\"5 4\" "
                                         "stroke-opacity=\"0.75\"/>",
                                         mark({tool}, kind), path, colour_of(tool)));
                else
                    body.add(fmt::format("<path{} d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\" stroke-linejoin=\"round\"/>",
                                         mark({tool}, kind), path, colour_of(tool)));
            }
            for (const std::string& a : m.arrows) body.add(a);
        }
    }

    // Plunges that are not holes: where a cutter feeds straight down into the work. The holes'
    // places are sorted by X, then Y, so that each plunge is a binary search (a program of many
    // holes has as many plunges, and a grid's column as many holes as it has rows).
    void plunge(const Step& s) {
        if (s.kind != StepKind::feed || !s.from_known || s.arc || xy_length(s) >= 1e-9 || !(s.to.z < s.from.z)) return;
        if (is_hole(s.to)) return;
        if (plunge_count_++ >= options_.exact && !fresh(Cover::plunge_mark, s.tool, s.to, s.to, nullptr)) {
            ++thinned_;
            return;
        }
        double cx = v.x(s.to.x), cy = v.y(s.to.y);
        plunges_.add(fmt::format("<g{4} stroke=\"{0}\" stroke-width=\"1.2\"><rect x=\"{1}\" y=\"{2}\" width=\"8\" height=\"8\" "
                                 "fill=\"#fff\"/><path d=\"M{1},{2}l8,8M{3},{2}l-8,8\"/></g>",
                                 colour_of(s.tool), n(cx - 4), n(cy - 4), n(cx + 4), mark({s.tool}, BackplotLayer::plunge)));
    }

    bool is_hole(Vec3 p) const {
        const std::vector<Vec2>& places = plan_.places;
        auto it = std::partition_point(places.begin(), places.end(), [&](Vec2 h) { return h.x <= p.x - 1e-6; });
        // Each X within reach (as a rule one) holds its places by Y.
        while (it != places.end() && it->x < p.x + 1e-6) {
            const double x = it->x;
            const auto same_x = std::partition_point(it, places.end(), [x](Vec2 h) { return h.x == x; });
            const auto at = std::partition_point(it, same_x, [&](Vec2 h) { return h.y <= p.y - 1e-6; });
            if (at != same_x && at->y < p.y + 1e-6 && std::abs(x - p.x) < 1e-6) return true;
            it = same_x;
        }
        return false;
    }

    // Numbers where they fit: the first and last hole of each tool first, then in drilling
    // order, leaving out any that would overlap one already placed. Returns how many were left out.
    int numbers(Svg& body) {
        const auto& labels = labels_;
        auto& diameter = diameter_;
        std::vector<size_t> order(labels.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = i;
        auto priority = [&](size_t l) {
            for (const auto& [number, tool] : labels[l].second) {
                auto it = plan_.first_last.find(tool);
                if (it != plan_.first_last.end() && (number == it->second.first || number == it->second.second)) return 0;
            }
            return 1;
        };
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return priority(a) < priority(b); });
        struct Rect {
            double x0, y0, x1, y1;
        };
        std::map<std::pair<int, int>, std::vector<Rect>> placed;  // by 40 px cell
        const double cell = 40.0;
        int left_out = 0;
        for (size_t l : order) {
            const auto& [at, numbers] = labels[l];
            double r = 3.0;
            for (const auto& [number, tool] : numbers) r = std::max(r, diameter[tool] / 2.0 * v.scale);
            std::string spans, plain;
            for (size_t k = 0; k < numbers.size(); ++k) {
                spans += fmt::format("{}<tspan{} fill=\"{}\">{}</tspan>", k ? "<tspan fill=\"#555\">, </tspan>" : "",
                                     mark({numbers[k].second}, BackplotLayer::hole), colour_of(numbers[k].second), numbers[k].first);
                plain += fmt::format("{}{}", k ? ", " : "", numbers[k].first);
            }
            double tx = v.x(at.x) + r * 0.75 + 3, ty = v.y(at.y) - r * 0.75 - 3;
            // Bold 12 px digits are about 8.4 px wide; a little room around each label.
            Rect box{tx - 3, ty - 13, tx + 8.4 * static_cast<double>(plain.size()) + 3, ty + 4};
            bool free = true;
            for (int cx = static_cast<int>(std::floor(box.x0 / cell)); free && cx <= static_cast<int>(std::floor(box.x1 / cell)); ++cx)
                for (int cy = static_cast<int>(std::floor(box.y0 / cell)); free && cy <= static_cast<int>(std::floor(box.y1 / cell)); ++cy)
                    for (const Rect& o : placed[{cx, cy}])
                        if (box.x0 < o.x1 && o.x0 < box.x1 && box.y0 < o.y1 && o.y0 < box.y1) free = false;
            if (!free) {
                left_out += static_cast<int>(numbers.size());
                continue;
            }
            for (int cx = static_cast<int>(std::floor(box.x0 / cell)); cx <= static_cast<int>(std::floor(box.x1 / cell)); ++cx)
                for (int cy = static_cast<int>(std::floor(box.y0 / cell)); cy <= static_cast<int>(std::floor(box.y1 / cell)); ++cy)
                    placed[{cx, cy}].push_back(box);
            body.add(fmt::format("<text{} x=\"{}\" y=\"{}\" {} font-size=\"12\" font-weight=\"bold\" stroke=\"#fff\" stroke-width=\"3\" "
                                 "paint-order=\"stroke\">{}</text>",
                                 mark({}, BackplotLayer::hole), n(tx), n(ty), font, spans));
        }
        return left_out;
    }

    struct Moves {
        std::map<int, std::string> d;  // tool -> path
        std::map<int, Vec3> last;
        std::vector<std::string> arrows;
        std::size_t count = 0;
    };
    static constexpr long ramp_level = std::numeric_limits<long>::max();
    static constexpr double draw_w_max = 720, draw_h_max = 560, left = 60, top = 60, legend_w = 340;

    BackplotOptions options_;
    ViewText view_;
    ProgramStats stats_;
    const BackplotPlan& plan_;
    std::map<int, const char*> colour_;
    std::map<int, double> diameter_;
    double min_x = 0, min_y = 0, span = 0, dx = 0, dy = 0, draw_w = 0, draw_h = 0, legend_x = 0, width = 0;
    View v;
    Svg head_;  // grid, frame and work zero
    std::map<std::pair<int, long>, std::string> swept_;  // (tool, Z in 0.01 mm) -> path
    std::map<std::pair<int, long>, Vec3> swept_last_;
    double lowest_ = 0.0, highest_ = 0.0;
    bool seen_ = false;
    std::size_t band_count_ = 0, plunge_count_ = 0, holes_ = 0;
    std::array<Moves, 5> moves_;
    Svg plunges_, hole_marks_;
    std::map<int, std::string> rings_;  // tool -> the circles of holes beyond options.hole_marks
    std::vector<std::pair<Vec2, std::vector<std::pair<int, int>>>> labels_;  // place -> (number, tool)
    std::map<std::pair<long, long>, size_t> label_at_;
    std::map<std::pair<Cover, int>, std::vector<bool>> coverage_;
    std::size_t thinned_ = 0;     // moves, marks and holes left out beyond options.exact
    std::size_t unnumbered_ = 0;  // holes beyond options.exact without their number
};

BackplotPlan::BackplotPlan(MachineKind kind) : kind_(kind) {}

void BackplotPlan::hole(const Hole& h) {
    // A lathe's holes are on the axis: no circles to fit in the view, no plunges to tell apart
    // from them; they are counted and numbered as a mill's.
    if (kind_ != MachineKind::lathe) {
        hole_centres[h.tool].add(Vec3{h.at.x, h.at.y, 0.0});
        places.push_back(h.at);
    }
    const int number = static_cast<int>(++holes);
    auto [it, fresh] = first_last.try_emplace(h.tool, number, number);
    if (!fresh) it->second.second = number;
}

void BackplotPlan::finish(const TraceSummary&) {
    std::sort(places.begin(), places.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
}

BackplotDrawer::BackplotDrawer(const BackplotPlan& plan, const ProgramStats& stats, const BackplotOptions& options)
    : impl_(std::make_unique<Impl>(plan, stats, options)) {}

BackplotDrawer::~BackplotDrawer() = default;

void BackplotDrawer::step(const Step& step) { impl_->step(step); }

void BackplotDrawer::hole(const Hole& hole) { impl_->hole(hole); }

void BackplotDrawer::finish(const TraceSummary&) { drawing_ = impl_->finish(); }

std::string backplot_svg(const Trace& trace, const ProgramStats& stats, const BackplotOptions& options) {
    return backplot_drawing(trace, stats, options).svg;
}

BackplotDrawing backplot_drawing(const Trace& trace, const ProgramStats& stats, const BackplotOptions& options) {
    BackplotPlan plan(options.kind);
    for (const Hole& h : trace.holes) plan.hole(h);
    plan.finish({});
    BackplotDrawer drawer(plan, stats, options);
    for (const Step& s : trace.steps) drawer.step(s);
    for (const Hole& h : trace.holes) drawer.hole(h);
    drawer.finish({});
    return drawer.take();
}

BackplotLayer layer_of(const Step& step) {
    if (step.kind == StepKind::rapid) return BackplotLayer::rapid;
    switch (step.movement) {
        case Movement::plunge: return BackplotLayer::plunge;
        case Movement::ramp: return BackplotLayer::ramp;
        case Movement::lead_in:
        case Movement::lead_out: return BackplotLayer::lead;
        case Movement::cutting:
        case Movement::finishing: break;
    }
    return BackplotLayer::feed;
}

}  // namespace camgen
