// The PNG of a simulated part, drawn with cairo: a mill's shaded top view coloured by depth
// (and a section), a lathe's half-section.
#include "camgen/simulation/pictures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include <cairo.h>
#include <fmt/format.h>

#include "camgen/common/number_text.hpp"

namespace camgen {

namespace {

// The colour ramp of depth: the uncut top, light blue, blue, dark blue, the bottom.
constexpr std::array<std::pair<double, Rgb>, 5> png_depth_stops{{{0.0, {226, 216, 190}},
                                                                 {0.25, {132, 196, 206}},
                                                                 {0.5, {64, 140, 204}},
                                                                 {0.75, {40, 76, 164}},
                                                                 {1.0, {22, 26, 84}}}};

// The top view fits this box, px.
constexpr double png_view_width = 900, png_view_height = 640;
constexpr double png_margin = 24, png_title = 34, png_scale_panel = 64;

struct PngSurface {
    cairo_surface_t* surface = nullptr;
    cairo_t* cr = nullptr;
    PngSurface(int w, int h) {
        surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
        cr = cairo_create(surface);
        cairo_set_source_rgb(cr, 0xf4 / 255.0, 0xf4 / 255.0, 0xf4 / 255.0);
        cairo_paint(cr);
        cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr, 13);
    }
    ~PngSurface() {
        cairo_destroy(cr);
        cairo_surface_destroy(surface);
    }
    PngSurface(const PngSurface&) = delete;
    PngSurface& operator=(const PngSurface&) = delete;
};

void png_colour(cairo_t* cr, Rgb c) { cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0); }

void png_text(cairo_t* cr, double x, double y, const std::string& text, double align = 0.0) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, text.c_str(), &e);
    cairo_move_to(cr, x - align * e.x_advance, y);
    cairo_show_text(cr, text.c_str());
}

// A round length near `target`: 1, 2 or 5 times a power of ten, mm.
double png_nice(double target) {
    const double p = std::pow(10.0, std::floor(std::log10(std::max(target, 1e-6))));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= target * 0.7) return m * p;
    return 10 * p;
}

// A horizontal mm scale bar at (x, y) for `scale` px per mm, about `target_px` long.
void png_scale_bar(cairo_t* cr, double x, double y, double scale, double target_px, const char* what) {
    const double mm = png_nice(target_px / scale);
    const double len = mm * scale;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, x + 0.5, y + 0.5, len, 6);
    cairo_stroke(cr);
    cairo_rectangle(cr, x + 0.5, y + 0.5, len / 2, 6);
    cairo_fill(cr);
    png_text(cr, x, y + 22, "0");
    png_text(cr, x + len, y + 22, fmt::format("{} mm", number_text(mm)), 0.5);
    png_text(cr, x + len + 40, y + 22, what);
}

void png_write(cairo_surface_t* surface, std::ostream& out) {
    cairo_surface_flush(surface);
    const cairo_status_t status = cairo_surface_write_to_png_stream(
        surface,
        [](void* closure, const unsigned char* data, unsigned int length) {
            static_cast<std::ostream*>(closure)->write(reinterpret_cast<const char*>(data), length);
            return CAIRO_STATUS_SUCCESS;
        },
        &out);
    if (status != CAIRO_STATUS_SUCCESS) throw SimInputError(fmt::format("cannot make the PNG: {}", cairo_status_to_string(status)));
}

// How many times Z is stretched in a section whose stock is `px` thick: 1 from 60 px up.
double png_exaggeration(double px) { return px >= 60 || !(px > 0) ? 1.0 : std::ceil(60 / px); }

// The section panel under the top view; returns its height, px.
double png_section(cairo_t* cr, const HeightField& f, const SectionLine& line, double left, double top, double width,
                   TopViewFrame& frame) {
    const std::vector<SectionSample> samples = field_section(f, line);
    const double length = distance(line.a, line.b);
    const double sx = length > 0 ? width / length : 1.0;
    const double thick = f.top - f.bottom;
    // Drawn to scale unless the stock would be under 60 px thick: then Z is stretched by a
    // whole factor, which the panel states.
    const double exaggeration = png_exaggeration(thick * sx);
    const double sz = sx * exaggeration;
    const double base = top + 28 + thick * sz;  // px of the bottom
    frame.section_left = left, frame.section_base = base, frame.section_scale = sx, frame.section_z_scale = sz;
    cairo_set_source_rgb(cr, 0, 0, 0);
    png_text(cr, left, top + 16,
             fmt::format("Section A-B from ({}, {}) to ({}, {}) mm, {} mm long{}", number_text(line.a.x, 3),
                         number_text(line.a.y, 3), number_text(line.b.x, 3), number_text(line.b.y, 3),
                         number_text(length, 3),
                         exaggeration > 1 ? fmt::format(", Z drawn {} times larger", number_text(exaggeration, 0)) : ""));
    auto px = [&](double d) { return left + d * sx; };
    auto py = [&](double z) { return base - (z - f.bottom) * sz; };
    // The material, a column from the bottom to each sample's height up to the next sample.
    png_colour(cr, {150, 160, 176});
    for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
        const SectionSample& s = samples[k];
        if (!s.inside || !(s.height > f.bottom)) continue;
        const double x0 = px(s.distance), x1 = px(samples[k + 1].distance);
        cairo_rectangle(cr, x0, py(s.height), std::max(x1 - x0, 0.0), py(f.bottom) - py(s.height));
    }
    cairo_fill(cr);
    // The profile's top, then the stock as it was (dashed).
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.5);
    bool open = false;
    for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
        const SectionSample& s = samples[k];
        if (!s.inside) {
            open = false;
            continue;
        }
        const double x0 = px(s.distance), x1 = px(samples[k + 1].distance), y = py(s.height);
        if (!open) cairo_move_to(cr, x0, y);
        else cairo_line_to(cr, x0, y);
        cairo_line_to(cr, x1, y);
        open = true;
    }
    cairo_stroke(cr);
    const double dash[] = {5.0, 4.0};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_line_width(cr, 1);
    cairo_set_source_rgb(cr, 0.75, 0.1, 0.1);
    for (std::size_t k = 0; k + 1 < samples.size();) {
        if (!samples[k].stock) {
            ++k;
            continue;
        }
        std::size_t e = k;
        while (e + 1 < samples.size() && samples[e].stock) ++e;
        cairo_rectangle(cr, px(samples[k].distance) + 0.5, py(f.top) + 0.5, px(samples[e].distance) - px(samples[k].distance),
                        py(f.bottom) - py(f.top));
        k = e + 1;
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_source_rgb(cr, 0, 0, 0);
    png_text(cr, px(0), py(f.bottom) + 16, "A", 0.5);
    png_text(cr, px(length), py(f.bottom) + 16, "B", 0.5);
    png_text(cr, left + width + 6, py(f.top) + 4, fmt::format("Z {}", number_text(f.top, 3)));
    png_text(cr, left + width + 6, py(f.bottom) + 4, fmt::format("Z {}", number_text(f.bottom, 3)));
    return (base - top) + 24;
}

TopViewFrame png_mill(const SimResult& r, const std::optional<SectionLine>& section, const PictureLabels& labels,
                      std::ostream& out) {
    const HeightField& f = r.field;
    const double w = f.nx * f.cell, h = f.ny * f.cell;
    const double scale = std::min(png_view_width / w, png_view_height / h);
    const int vw = std::max(1, static_cast<int>(std::ceil(w * scale))), vh = std::max(1, static_cast<int>(std::ceil(h * scale)));
    const double left = png_margin, top = png_margin + png_title;
    const double thick = f.top - f.bottom;
    // Section panel height: the stock's thickness at the section's scale, at least 60 px.
    double section_height = 0;
    if (section) {
        const double length = distance(section->a, section->b);
        const double sx = length > 0 ? vw / length : 1.0;
        section_height = 28 + thick * sx * png_exaggeration(thick * sx) + 24 + 8;
    }
    const int width = static_cast<int>(left + vw + 150);
    const int height = static_cast<int>(top + vh + png_scale_panel + section_height + png_margin);
    TopViewFrame frame;
    frame.left = left, frame.top = top, frame.scale = scale, frame.x0 = f.x0, frame.y1 = f.y0 + h;
    frame.width = width, frame.height = height;
    PngSurface png(width, height);
    cairo_t* cr = png.cr;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, 15);
    png_text(cr, left, png_margin + 14,
             fmt::format("{} on {}: the simulated part from above, {} x {} cells of {} mm", labels.program, labels.machine,
                         f.nx, f.ny, number_text(r.resolution)));
    cairo_set_font_size(cr, 13);

    // Each pixel: the lowest of the cells it covers (a cut narrower than a pixel still shows).
    std::vector<float> px_height(static_cast<std::size_t>(vw) * vh);
    std::vector<char> px_material(px_height.size());
    for (int py = 0; py < vh; ++py) {
        const double ya = frame.y1 - (py + 1) / scale, yb = frame.y1 - py / scale;
        int j0 = static_cast<int>(std::floor((ya - f.y0) / f.cell)), j1 = static_cast<int>(std::ceil((yb - f.y0) / f.cell)) - 1;
        j0 = std::clamp(j0, 0, f.ny - 1), j1 = std::clamp(std::max(j1, j0), 0, f.ny - 1);
        for (int pxi = 0; pxi < vw; ++pxi) {
            const double xa = f.x0 + pxi / scale, xb = f.x0 + (pxi + 1) / scale;
            int i0 = static_cast<int>(std::floor((xa - f.x0) / f.cell)), i1 = static_cast<int>(std::ceil((xb - f.x0) / f.cell)) - 1;
            i0 = std::clamp(i0, 0, f.nx - 1), i1 = std::clamp(std::max(i1, i0), 0, f.nx - 1);
            float lowest = static_cast<float>(f.top);
            bool material = true;
            for (int j = j0; j <= j1; ++j)
                for (int i = i0; i <= i1; ++i) {
                    const float v = f.heights[static_cast<std::size_t>(j) * f.nx + i];
                    lowest = std::min(lowest, v);
                    if (!(v > f.bottom)) material = false;
                }
            px_height[static_cast<std::size_t>(py) * vw + pxi] = lowest;
            px_material[static_cast<std::size_t>(py) * vw + pxi] = material;
        }
    }
    cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_RGB24, vw, vh);
    {
        unsigned char* data = cairo_image_surface_get_data(image);
        const int stride = cairo_image_surface_get_stride(image);
        // Shading: light from the upper left, 45 degrees up; a flat area is its colour exactly.
        const double lx = -0.5, ly = 0.5, lz = std::sqrt(0.5);
        auto hat = [&](int i, int j) {
            i = std::clamp(i, 0, vw - 1), j = std::clamp(j, 0, vh - 1);
            return static_cast<double>(px_height[static_cast<std::size_t>(j) * vw + i]);
        };
        for (int j = 0; j < vh; ++j)
            for (int i = 0; i < vw; ++i) {
                const std::size_t k = static_cast<std::size_t>(j) * vw + i;
                Rgb c = no_material_colour;
                if (px_material[k]) {
                    c = depth_colour(thick > 0 ? (f.top - px_height[k]) / thick : 0.0);
                    // The slope in mm per mm (y up the picture).
                    const double gx = (hat(i + 1, j) - hat(i - 1, j)) * scale / 2, gy = (hat(i, j - 1) - hat(i, j + 1)) * scale / 2;
                    const double n = std::sqrt(gx * gx + gy * gy + 1);
                    const double shade = std::clamp((-gx * lx - gy * ly + lz) / n / lz, 0.55, 1.3);
                    c = {std::min(255, static_cast<int>(std::lround(c.r * shade))), std::min(255, static_cast<int>(std::lround(c.g * shade))),
                         std::min(255, static_cast<int>(std::lround(c.b * shade)))};
                }
                auto* p = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(j) * stride) + i;
                *p = (static_cast<std::uint32_t>(c.r) << 16) | (static_cast<std::uint32_t>(c.g) << 8) | static_cast<std::uint32_t>(c.b);
            }
        cairo_surface_mark_dirty(image);
    }
    cairo_set_source_surface(cr, image, left, top);
    cairo_paint(cr);
    cairo_surface_destroy(image);
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, left - 0.5, top - 0.5, vw + 1, vh + 1);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    png_text(cr, left, top + vh + 16, fmt::format("X {} to {}, Y {} to {} mm", number_text(f.x0, 3), number_text(f.x0 + w, 3),
                                                  number_text(f.y0, 3), number_text(f.y0 + h, 3)));

    // The depth scale: the ramp from the top (up) to the bottom, its Z at each end and between.
    const double bar_x = left + vw + 16, bar_h = std::min(static_cast<double>(vh), 300.0);
    for (int k = 0; k < static_cast<int>(bar_h); ++k) {
        png_colour(cr, depth_colour(k / std::max(bar_h - 1, 1.0)));
        cairo_rectangle(cr, bar_x, top + k, 18, 1);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, bar_x - 0.5, top - 0.5, 19, bar_h + 1);
    cairo_stroke(cr);
    const double tick = png_nice(thick / 4);
    for (double d = 0; d <= thick + 1e-9; d += tick) {
        const double y = top + (thick > 0 ? d / thick : 0) * (bar_h - 1);
        cairo_move_to(cr, bar_x + 18, y + 0.5);
        cairo_line_to(cr, bar_x + 23, y + 0.5);
        cairo_stroke(cr);
        png_text(cr, bar_x + 26, y + 4, fmt::format("Z {}", number_text(f.top - d, 3)));
    }
    if (std::fmod(thick, tick) > tick * 0.2) png_text(cr, bar_x + 26, top + bar_h + 4, fmt::format("Z {}", number_text(f.bottom, 3)));
    png_text(cr, bar_x, top + bar_h + 22, "depth");
    png_scale_bar(cr, left, top + vh + 28, scale, vw / 4.0, "");

    if (section) {
        // The section's line on the top view, its ends A and B.
        auto at = [&](Vec2 p) { return Vec2{left + (p.x - f.x0) * scale, top + (frame.y1 - p.y) * scale}; };
        const Vec2 a = at(section->a), b = at(section->b);
        for (auto [width_px, grey] : {std::pair{4.0, 1.0}, std::pair{1.5, 0.0}}) {
            cairo_set_source_rgb(cr, grey, grey, grey);
            cairo_set_line_width(cr, width_px);
            cairo_move_to(cr, a.x, a.y);
            cairo_line_to(cr, b.x, b.y);
            cairo_stroke(cr);
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        png_text(cr, a.x - 12, a.y - 4, "A");
        png_text(cr, b.x + 4, b.y - 4, "B");
        png_section(cr, f, *section, left, top + vh + png_scale_panel, vw, frame);
    }
    png_write(png.surface, out);
    return frame;
}

TopViewFrame png_lathe(const SimResult& r, const PictureLabels& labels, std::ostream& out) {
    const LatheProfile& p = r.lathe;
    const double length = p.nz * p.dz;
    double bar = 0;
    for (int k = 0; k < p.nz; ++k) bar = std::max(bar, p.outside[k]);
    const double radius = std::max(bar, 1e-3);
    const double scale = std::min(png_view_width / length, 360.0 / radius);
    const double left = png_margin + 10, top = png_margin + png_title + 10;
    const int vw = static_cast<int>(std::ceil(length * scale)), vh = static_cast<int>(std::ceil(radius * scale));
    const int width = static_cast<int>(left + vw + 110), height = static_cast<int>(top + vh + 90);
    TopViewFrame frame;
    frame.left = left, frame.top = top, frame.scale = scale, frame.x0 = p.z0, frame.y1 = radius;
    frame.width = width, frame.height = height;
    PngSurface png(width, height);
    cairo_t* cr = png.cr;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, 15);
    png_text(cr, png_margin, png_margin + 14,
             fmt::format("{} on {}: half-section of the turned part, {} samples of {} mm along Z", labels.program,
                         labels.machine, p.nz, number_text(r.resolution)));
    cairo_set_font_size(cr, 13);
    auto px = [&](double z) { return left + (z - p.z0) * scale; };
    auto py = [&](double rad) { return top + (radius - rad) * scale; };
    // The material between the bore and the outside, sample by sample.
    png_colour(cr, {150, 160, 176});
    for (int k = 0; k < p.nz; ++k) {
        if (!(p.outside[k] > p.bore[k])) continue;
        const double z = p.z0 + k * p.dz;
        cairo_rectangle(cr, px(z), py(p.outside[k]), p.dz * scale, (p.outside[k] - p.bore[k]) * scale);
    }
    cairo_fill(cr);
    // The rings of air inside the material (face grooves), in the background's colour, edged.
    if (!p.gaps.empty()) {
        cairo_set_source_rgb(cr, 0xf4 / 255.0, 0xf4 / 255.0, 0xf4 / 255.0);
        for (int k = 0; k < p.nz; ++k)
            if (const std::vector<LatheGap>* gaps = p.gaps_at(k))
                for (const LatheGap& g : *gaps)
                    cairo_rectangle(cr, px(p.z0 + k * p.dz), py(g.hi), p.dz * scale, (g.hi - g.lo) * scale);
        cairo_fill(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_line_width(cr, 1.5);
        for (int k = 0; k < p.nz; ++k)
            if (const std::vector<LatheGap>* gaps = p.gaps_at(k))
                for (const LatheGap& g : *gaps)
                    for (double rad : {g.lo, g.hi}) {
                        cairo_move_to(cr, px(p.z0 + k * p.dz), py(rad));
                        cairo_line_to(cr, px(p.z0 + (k + 1) * p.dz), py(rad));
                    }
        // Their ends along Z (a groove's bottom, a wall's step): where material and air differ
        // between a sample and the one below it.
        auto material = [&](int k) {
            std::vector<std::pair<double, double>> m;
            const std::size_t i = static_cast<std::size_t>(k);
            if (!(p.outside[i] > p.bore[i])) return m;
            double from = p.bore[i];
            if (const std::vector<LatheGap>* gaps = p.gaps_at(k))
                for (const LatheGap& g : *gaps) m.emplace_back(from, g.lo), from = g.hi;
            m.emplace_back(from, p.outside[i]);
            return m;
        };
        for (int k = 1; k < p.nz; ++k) {
            if (!p.gaps_at(k) && !p.gaps_at(k - 1)) continue;
            std::vector<double> edges;  // the radii where either side's material starts or ends
            for (int j : {k - 1, k})
                for (const auto& [lo, hi] : material(j)) edges.push_back(lo), edges.push_back(hi);
            std::sort(edges.begin(), edges.end());
            const auto below = material(k - 1), above = material(k);
            auto in = [](const std::vector<std::pair<double, double>>& m, double r) {
                for (const auto& [lo, hi] : m)
                    if (r > lo && r < hi) return true;
                return false;
            };
            const double z = px(p.z0 + k * p.dz);
            for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
                const double mid = (edges[e] + edges[e + 1]) / 2;
                if (!(edges[e + 1] > edges[e]) || in(below, mid) == in(above, mid)) continue;
                cairo_move_to(cr, z, py(edges[e]));
                cairo_line_to(cr, z, py(edges[e + 1]));
            }
        }
        cairo_stroke(cr);
    }
    // Its outline, sample by sample.
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.5);
    for (const std::vector<double>* edge : {&p.outside, &p.bore}) {
        bool open = false;
        for (int k = 0; k < p.nz; ++k) {
            if (!(p.outside[k] > p.bore[k]) || (edge == &p.bore && !(p.bore[k] > 0))) {
                open = false;
                continue;
            }
            const double z = p.z0 + k * p.dz, y = py((*edge)[k]);
            if (!open) cairo_move_to(cr, px(z), y);
            else cairo_line_to(cr, px(z), y);
            cairo_line_to(cr, px(z + p.dz), y);
            open = true;
        }
        cairo_stroke(cr);
    }
    // The bar as it was (dashed) and the spindle's axis (dash-dot).
    const double dash[] = {5.0, 4.0};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_line_width(cr, 1);
    cairo_set_source_rgb(cr, 0.75, 0.1, 0.1);
    cairo_rectangle(cr, px(p.z0), py(radius), length * scale, radius * scale);
    cairo_stroke(cr);
    const double axis_dash[] = {12.0, 3.0, 2.0, 3.0};
    cairo_set_dash(cr, axis_dash, 4, 0);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, px(p.z0) - 10, py(0) + 0.5);
    cairo_line_to(cr, px(p.z0 + length) + 10, py(0) + 0.5);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    png_text(cr, px(p.z0 + length) + 14, py(0) + 4, "axis");
    png_text(cr, px(p.z0 + length) + 14, py(radius) + 4, fmt::format("D {}", number_text(2 * radius, 3)));
    png_text(cr, px(p.z0), py(0) + 18, fmt::format("Z {}", number_text(p.z0, 3)), 0.5);
    png_text(cr, px(p.z0 + length), py(0) + 18, fmt::format("Z {}", number_text(p.z0 + length, 3)), 0.5);
    png_scale_bar(cr, left, py(0) + 34, scale, vw / 4.0, "radius up, Z to the right");
    png_write(png.surface, out);
    return frame;
}

}  // namespace

Rgb depth_colour(double fraction) {
    const double t = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
    for (std::size_t k = 1; k < png_depth_stops.size(); ++k) {
        const auto& [t1, c1] = png_depth_stops[k];
        if (t <= t1) {
            const auto& [t0, c0] = png_depth_stops[k - 1];
            const double u = (t - t0) / (t1 - t0);
            auto mix = [&](int a, int b) { return static_cast<int>(std::lround(a + (b - a) * u)); };
            return {mix(c0.r, c1.r), mix(c0.g, c1.g), mix(c0.b, c1.b)};
        }
    }
    return png_depth_stops.back().second;
}

std::vector<SectionSample> field_section(const HeightField& f, const SectionLine& line) {
    std::vector<SectionSample> out;
    const double length = distance(line.a, line.b);
    // A sample every quarter cell (at most 200,000), each the cell under it.
    const int n = static_cast<int>(std::clamp(std::ceil(length / (f.cell / 4)), 1.0, 200'000.0));
    out.reserve(static_cast<std::size_t>(n) + 1);
    for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        const Vec2 p = line.a + (line.b - line.a) * t;
        SectionSample s;
        s.distance = length * t;
        const double fi = std::floor((p.x - f.x0) / f.cell), fj = std::floor((p.y - f.y0) / f.cell);
        if (fi >= 0 && fj >= 0 && fi < f.nx && fj < f.ny) {
            const std::size_t index = static_cast<std::size_t>(fj) * f.nx + static_cast<std::size_t>(fi);
            s.inside = true;
            s.height = f.heights[index];
            s.stock = had_stock(f, index);
        }
        out.push_back(s);
    }
    return out;
}

TopViewFrame write_simulation_png(const SimResult& result, const std::optional<SectionLine>& section,
                                  const PictureLabels& labels, std::ostream& out) {
    if (result.kind == MachineKind::lathe) {
        if (section) throw SimInputError("a section is a mill's picture; a lathe's PNG is its half-section");
        return png_lathe(result, labels, out);
    }
    return png_mill(result, section, labels, out);
}

}  // namespace camgen
