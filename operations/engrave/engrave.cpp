// The engrave operation (engrave.hpp).
#include "camgen/operations/engrave/engrave.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/job/tool_geometry.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/dxf_source.hpp"
#include "camgen/operations/engrave/hershey.hpp"
#include "camgen/operations/shapes.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

// Bounds that keep a typo from making a program without end.
constexpr std::size_t engrave_max_characters = 10000;
constexpr std::size_t engrave_max_strokes = 20000;
constexpr int engrave_max_passes = 100;

// Two stroke points closer than this are one (a glyph set very small), mm.
constexpr double engrave_least_step = 0.001;

// The keys of an engrave operation; the heights follow "comment".
constexpr KeySpec engrave_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a v-bit, engraver or chamfer-mill (the line as wide as its V at the depth), a "
                    "ball-mill, bull-nose or end-mill"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "depth", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "how deep the lines are cut below referencePlane (> 0)"},
    {.key = "passes", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{100, true}, .default_json = "1",
     .description = "depth passes of equal steps, back and forth along each stroke"},
    {.key = "text", .type = JsonType::string,
     .description = "the text to engrave (\"\\n\" between lines), in a single-stroke Hershey font"},
    {.key = "font", .type = JsonType::string, .default_json = "\"rowmans\"",
     .description = "a Hershey font of Debian's hershey-fonts-data by name (rowmans, futural, scripts, ...), read from "
                    "$CAMGEN_FONTS or /usr/share/hershey-fonts"},
    {.key = "height", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the text's cap height (the height of an H), required with text"},
    {.key = "spacing", .quantity = Quantity::length, .default_json = "0",
     .description = "added between letters (negative: closer)"},
    {.key = "lineSpacing", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "baseline to baseline of the lines (default: 1.6 x height)"},
    {.key = "align", .type = JsonType::string, .default_json = "\"left\"", .choices = &choices_of<text_aligns>,
     .description = "where the anchor is along the lines: left, centre or right"},
    {.key = "verticalAlign", .type = JsonType::string, .default_json = "\"baseline\"",
     .choices = &choices_of<text_vertical_aligns>,
     .description = "where the anchor is across the text: the first line's baseline, the middle, or the first line's cap top"},
    {.key = "at", .type = JsonType::point, .quantity = Quantity::length,
     .description = "the text along a line: its anchor [x, y]"},
    {.key = "rotation", .quantity = Quantity::angle, .default_json = "0",
     .description = "the line's direction, degrees counter-clockwise from +X"},
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length,
     .description = "or the text around an arc: the arc's centre [x, y]"},
    {.key = "radius", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the arc's radius: where the anchor is (the first line's baseline with verticalAlign baseline)"},
    {.key = "startAngle", .quantity = Quantity::angle, .default_json = "90",
     .description = "where the anchor is on the arc, degrees counter-clockwise from +X"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"cw\"", .choices = &choices_of<arc_directions>,
     .description = "the way the text runs around the arc: cw (the glyphs' tops outward, a circle's top) or ccw (tops "
                    "towards the centre, its bottom)"},
    {.key = "start", .type = JsonType::point, .quantity = Quantity::length,
     .description = "or a path engraved on its line: where it starts [x, y]"},
    {.key = "path", .type = JsonType::array, .ref = "contourElement", .min_items = 1,
     .description = "the path's lines and arcs in XY, each starting where the previous one ends"},
    {.key = "profile", .type = JsonType::object, .ref = "profileSource",
     .description = "or a shape, or every profile of a DXF drawing's selection (open or closed), engraved on its line"},
    {.key = "feed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "cutting feed; required unless the tool comes from the library with a feedPerTooth for the job's "
                    "material"},
    {.key = "plungeFeed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "feed down into each stroke (default: feed)"},
    {.key = "tolerance", .quantity = Quantity::length, .min = Bound{0.0001, true},
     .description = "how far the lines of an arc the machine cannot write may stray from it, and a drawing's curves "
                    "fitted (default: the machine's chordTolerance, which also caps it)"},
};

std::vector<KeySpec> all_engrave_keys() {
    std::vector<KeySpec> keys(std::begin(engrave_keys), std::end(engrave_keys));
    std::vector<KeySpec> heights;
    for (const KeySpec& k : height_keys(true))
        if (k.key != "endDepth" && k.key != "endDepthIsAbsolute") heights.push_back(k);
    keys.insert(keys.begin() + 3, heights.begin(), heights.end());
    return keys;
}

// The characters of a UTF-8 string (JSON text is UTF-8; a byte that does not decode is U+FFFD).
std::u32string engrave_decode(std::string_view s) {
    std::u32string out;
    for (std::size_t i = 0; i < s.size();) {
        const auto b = static_cast<unsigned char>(s[i]);
        int extra = b < 0x80 ? 0 : (b >> 5) == 6 ? 1 : (b >> 4) == 14 ? 2 : (b >> 3) == 30 ? 3 : -1;
        if (extra < 0 || i + static_cast<std::size_t>(extra) >= s.size() + (extra == 0 ? 1 : 0)) {
            out.push_back(0xFFFD);
            ++i;
            continue;
        }
        char32_t c = extra == 0 ? b : extra == 1 ? (b & 0x1F) : extra == 2 ? (b & 0x0F) : (b & 0x07);
        bool ok = true;
        for (int k = 1; k <= extra; ++k) {
            const auto n = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
            if ((n >> 6) != 2) ok = false;
            c = (c << 6) | (n & 0x3F);
        }
        out.push_back(ok ? c : 0xFFFD);
        i += ok ? static_cast<std::size_t>(extra) + 1 : 1;
    }
    return out;
}

// A character shown in a message: "'é' (U+00E9)", a control character by its code alone.
std::string engrave_shown(char32_t c) {
    if (c == '\t') return "a tab (U+0009)";
    if (c < 32 || c == 127) return fmt::format("U+{:04X}", static_cast<unsigned>(c));
    std::string utf8;
    if (c < 0x80) utf8 += static_cast<char>(c);
    else if (c < 0x800) utf8 += static_cast<char>(0xC0 | (c >> 6)), utf8 += static_cast<char>(0x80 | (c & 0x3F));
    else if (c < 0x10000)
        utf8 += static_cast<char>(0xE0 | (c >> 12)), utf8 += static_cast<char>(0x80 | ((c >> 6) & 0x3F)),
            utf8 += static_cast<char>(0x80 | (c & 0x3F));
    else
        utf8 += static_cast<char>(0xF0 | (c >> 18)), utf8 += static_cast<char>(0x80 | ((c >> 12) & 0x3F)),
            utf8 += static_cast<char>(0x80 | ((c >> 6) & 0x3F)), utf8 += static_cast<char>(0x80 | (c & 0x3F));
    return fmt::format("'{}' (U+{:04X})", utf8, static_cast<unsigned>(c));
}

// A polyline as a profile of lines, points closer than engrave_least_step to the last kept one
// left out (the last point kept in their place).
Profile engrave_polyline(const std::vector<Vec2>& pts) {
    Profile p;
    p.start = pts.front();
    Vec2 at = p.start;
    for (std::size_t i = 1; i < pts.size(); ++i) {
        if (distance(pts[i], at) < engrave_least_step) {
            if (i + 1 == pts.size() && !p.segments.empty()) p.segments.back().end = pts[i];
            continue;
        }
        p.segments.push_back({pts[i], std::nullopt, ArcDirection::ccw});
        at = pts[i];
    }
    return p;
}

Vec2 profile_end(const Profile& p) { return p.segments.empty() ? p.start : p.segments.back().end; }

// The width of each line of the text (from its first glyph's left bound to its last's right,
// the spacing between glyphs), mm.
std::vector<double> engrave_line_widths(const HersheyFont& font, std::u32string_view text, double scale, double spacing) {
    std::vector<double> widths{0.0};
    bool first = true;
    for (char32_t c : text) {
        if (c == '\n') {
            widths.push_back(0.0);
            first = true;
            continue;
        }
        const HersheyGlyph* g = font.glyph(c);
        if (!g) continue;
        widths.back() += (first ? 0.0 : spacing) + (g->right - g->left) * scale;
        first = false;
    }
    return widths;
}

}  // namespace

std::vector<Profile> engrave_text_strokes(const HersheyFont& font, std::u32string_view text, const TextStyle& style,
                                          const TextPlacement& place) {
    const double scale = style.height / (font.baseline - font.cap_top);
    const std::vector<double> widths = engrave_line_widths(font, text, scale, style.spacing);
    const std::size_t lines = widths.size();
    // The first line's baseline above the anchor (text Y up).
    double y0 = 0.0;
    if (style.vertical == TextVerticalAlign::top) y0 = -style.height;
    if (style.vertical == TextVerticalAlign::middle) y0 = -(style.height - (static_cast<double>(lines) - 1) * style.line_spacing) / 2.0;
    std::vector<Profile> out;
    std::size_t line = 0;
    double pen = 0.0;
    bool first = true;
    auto line_start = [&](std::size_t k) {
        return style.align == TextAlign::left ? 0.0 : style.align == TextAlign::centre ? -widths[k] / 2.0 : -widths[k];
    };
    pen = line_start(0);
    const double rot = place.rotation * rad_per_deg;
    const Vec2 along{std::cos(rot), std::sin(rot)}, up{-std::sin(rot), std::cos(rot)};
    for (char32_t c : text) {
        if (c == '\n') {
            ++line;
            pen = line_start(line);
            first = true;
            continue;
        }
        const HersheyGlyph* g = font.glyph(c);
        if (!g) continue;
        if (!first) pen += style.spacing;
        first = false;
        const double advance = (g->right - g->left) * scale;
        const double baseline = y0 - static_cast<double>(line) * style.line_spacing;
        // Where a glyph point (font units) goes: along a line at once; around an arc, the
        // glyph turned about the middle of its advance on its line's baseline circle.
        Vec2 origin, gx = along, gy = up;
        double x_ref = 0.0;
        if (place.on_arc) {
            const double s = place.direction == ArcDirection::cw ? 1.0 : -1.0;
            const double r = place.radius + s * baseline;
            x_ref = pen + advance / 2.0;
            const double theta = place.start_angle * rad_per_deg - s * x_ref / r;
            const Vec2 radial{std::cos(theta), std::sin(theta)};
            origin = place.centre + radial * r;
            gy = radial * s;
            gx = Vec2{radial.y, -radial.x} * s;
        }
        for (const std::vector<HersheyPoint>& stroke : g->strokes) {
            std::vector<Vec2> pts;
            for (const HersheyPoint& p : stroke) {
                const double x = pen + (p.x - g->left) * scale, y = baseline + (font.baseline - p.y) * scale;
                if (place.on_arc) pts.push_back(origin + gx * (x - x_ref) + gy * (y - baseline));
                else pts.push_back(place.at + along * x + up * y);
            }
            out.push_back(engrave_polyline(pts));
        }
        pen += advance;
    }
    return out;
}

std::vector<Profile> engrave_order(std::vector<Profile> strokes) {
    std::vector<Profile> out;
    if (strokes.empty()) return out;
    out.reserve(strokes.size());
    std::vector<bool> done(strokes.size(), false);
    out.push_back(strokes.front());
    done[0] = true;
    Vec2 at = profile_end(out.back());
    for (std::size_t n = 1; n < strokes.size(); ++n) {
        std::size_t best = 0;
        bool reverse = false;
        double best_d = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < strokes.size(); ++k) {
            if (done[k]) continue;
            const double ds = distance(at, strokes[k].start), de = distance(at, profile_end(strokes[k]));
            if (ds < best_d) best_d = ds, best = k, reverse = false;
            if (de < best_d) best_d = de, best = k, reverse = true;
        }
        done[best] = true;
        out.push_back(reverse ? reversed(strokes[best]) : std::move(strokes[best]));
        at = profile_end(out.back());
    }
    return out;
}

std::vector<ObjectSpec> EngraveOp::objects() {
    std::vector<ObjectSpec> out{
        {.name = "engrave",
         .description = "engrave text in a single-stroke font along a line or an arc, or a path or a drawing's profiles, "
                        "on their line to a depth",
         .keys = all_engrave_keys(),
         .groups = {{.keys = {"text", "start", "profile"}, .min = 1, .max = 1,
                     .description = "text, a path (start and path) or profile"}}},
    };
    return out;
}

EngraveOp EngraveOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, all_engrave_keys());
    const Tool& tool = in.tool(f);
    const std::string_view tool_type = name_of(tool_types, tool.type);
    switch (tool.type) {
    case ToolType::v_bit:
    case ToolType::engraver:
    case ToolType::chamfer_mill:
    case ToolType::ball_mill:
    case ToolType::bull_nose:
    case ToolType::end_mill: break;
    default:
        f.fail("tool", fmt::format("tool {} ({}) is a {}: an engrave operation needs a v-bit, engraver, chamfer-mill, "
                                   "ball-mill, bull-nose or end-mill",
                                   tool.number, tool.path, tool_type));
    }
    if (!tool.centre_cutting)
        f.fail("tool", fmt::format("tool {} ({}) does not cut at its centre (centreCutting false): engraving plunges into "
                                   "every stroke",
                                   tool.number, tool.path));
    EngraveOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    op.heights = read_heights(f, in, "stroke", "depth");
    const double depth = op.heights.end_depth;
    if (tool.flute_length && depth > *tool.flute_length + 1e-9)
        f.fail("depth", fmt::format("the lines are {} deep, but tool {} ({}) has a fluteLength of {}", in.show(depth),
                                    tool.number, tool.path, in.show(*tool.flute_length)));
    const int passes = f.has("passes") ? f.integer("passes") : 1;
    if (passes < 1 || passes > engrave_max_passes)
        f.fail("passes", fmt::format("passes must be a whole number from 1 to {}", engrave_max_passes));
    op.passes = passes;

    const std::optional<double> width = cut_width_at_depth(tool, depth);
    if (!width) f.fail("tool", fmt::format("tool {} ({}) has no tipAngle: the line's width follows from it", tool.number, tool.path));
    op.width = *width;
    // What the width follows from, in mm (the note is camgen's, not the job's units).
    auto mm = [](double v) { return number_text(v, 4); };
    if (is_pointed_cutter(tool.type)) {
        const double cone = (tool.diameter - tool.tip_diameter) / 2.0 / std::tan(*tool.tip_angle / 2.0 * rad_per_deg);
        op.notes.push_back(fmt::format("the lines are {} mm wide at the top: tool {}'s {}-degree V{}, {} mm deep{}", mm(op.width),
                                       tool.number, mm(*tool.tip_angle),
                                       tool.tip_diameter > 0 ? fmt::format(" with a {} mm tip", mm(tool.tip_diameter)) : "",
                                       mm(depth),
                                       depth > cone + 1e-9 ? fmt::format(" (deeper than its V, {} mm: the walls are "
                                                                         "straight below)", mm(cone))
                                                           : ""));
    } else if (tool.type == ToolType::ball_mill) {
        op.notes.push_back(fmt::format("the lines are {} mm wide at the top: tool {}'s ball of diameter {} mm, {} mm deep",
                                       mm(op.width), tool.number, mm(tool.diameter), mm(depth)));
    } else {
        op.notes.push_back(fmt::format("the lines are {} mm wide: tool {}'s diameter", mm(op.width), tool.number));
    }
    op.tolerance = read_tolerance(f, in);

    const int sources = int(f.has("text")) + int(f.has("start") || f.has("path")) + int(f.has("profile"));
    if (sources != 1) f.fail("", "an engrave operation needs exactly one of text, a path (start and path) or profile");
    std::vector<Profile> strokes;
    if (f.has("text")) {
        for (std::string_view key : {"start", "path"})
            if (f.has(key)) f.fail(key, "give text or a path, not both");
        op.text = f.string("text");
        op.font = f.optional_string("font").value_or(std::string(engrave_default_font));
        const std::u32string text = engrave_decode(op.text);
        if (text.size() > engrave_max_characters)
            f.fail("text", fmt::format("the text has {} characters, more than {}", text.size(), engrave_max_characters));
        HersheyFont font;
        try {
            font = load_hershey_font(op.font, hershey_font_directory());
        } catch (const FontError& e) {
            f.fail(f.has("font") ? "font" : "text", e.what());
        }
        for (std::size_t i = 0; i < text.size(); ++i)
            if (text[i] != '\n' && !font.glyph(text[i]))
                f.fail("text", fmt::format("character {} of the text, {}, is not in font {} (it has characters U+0020 to "
                                           "U+{:04X})",
                                           i + 1, engrave_shown(text[i]), op.font, static_cast<unsigned>(font.last())));
        if (!f.has("height")) f.fail("height", "text needs its height (the cap height, mm)");
        TextStyle style;
        style.height = in.length(f, "height");
        if (!(style.height > 0)) f.fail("height", "height must be > 0");
        style.spacing = in.optional_length(f, "spacing").value_or(0.0);
        style.line_spacing = in.optional_length(f, "lineSpacing").value_or(1.6 * style.height);
        if (!(style.line_spacing > 0)) f.fail("lineSpacing", "lineSpacing must be > 0");
        style.align = f.choice("align", text_aligns, TextAlign::left);
        style.vertical = f.choice("verticalAlign", text_vertical_aligns, TextVerticalAlign::baseline);
        TextPlacement place;
        const bool line = f.has("at"), arc = f.has("centre") || f.has("radius");
        if (line == arc) f.fail(line ? "centre" : "", "text needs at (along a line) or centre and radius (around an arc), one of them");
        if (line) {
            for (std::string_view key : {"startAngle", "direction"})
                if (f.has(key)) f.fail(key, fmt::format("{} is for text around an arc (centre and radius), not along a line (at)", key));
            place.at = in.point(f, "at");
            place.rotation = f.optional_number("rotation").value_or(0.0);
            if (!(std::abs(place.rotation) <= 360.0)) f.fail("rotation", "rotation must be from -360 to 360 degrees");
        } else {
            if (f.has("rotation")) f.fail("rotation", "rotation is for text along a line (at); around an arc give startAngle");
            if (!f.has("centre")) f.fail("centre", "text around an arc needs its centre");
            if (!f.has("radius")) f.fail("radius", "text around an arc needs its radius");
            place.on_arc = true;
            place.centre = in.point(f, "centre");
            place.radius = in.length(f, "radius");
            if (!(place.radius > 0)) f.fail("radius", "radius must be > 0");
            place.start_angle = f.optional_number("startAngle").value_or(90.0);
            if (!(std::abs(place.start_angle) <= 360.0)) f.fail("startAngle", "startAngle must be from -360 to 360 degrees");
            place.direction = f.choice("direction", arc_directions, ArcDirection::cw);
            // Each line's baseline circle must hold its glyphs (tops towards the centre: their
            // cap height inside it) and go round at most once.
            const double scale = style.height / (font.baseline - font.cap_top);
            const std::vector<double> widths = engrave_line_widths(font, text, scale, style.spacing);
            double y0 = 0.0;
            if (style.vertical == TextVerticalAlign::top) y0 = -style.height;
            if (style.vertical == TextVerticalAlign::middle)
                y0 = -(style.height - (static_cast<double>(widths.size()) - 1) * style.line_spacing) / 2.0;
            const double s = place.direction == ArcDirection::cw ? 1.0 : -1.0;
            for (std::size_t k = 0; k < widths.size(); ++k) {
                const double r = place.radius + s * (y0 - static_cast<double>(k) * style.line_spacing);
                const double inner = s > 0 ? r : r - style.height;
                if (!(inner > style.height / 2.0))
                    f.fail("radius", fmt::format("line {} of the text has its {} on a circle of radius {}: too tight for "
                                                 "glyphs {} high (at least half their height inside them)",
                                                 k + 1, s > 0 ? "baseline" : "cap top", in.show(inner), in.show(style.height)));
                if (widths[k] > two_pi * r)
                    f.fail("radius", fmt::format("line {} of the text is {} long, more than once round its circle of radius {} "
                                                 "({})",
                                                 k + 1, in.show(widths[k]), in.show(r), in.show(two_pi * r)));
            }
        }
        strokes = engrave_text_strokes(font, text, style, place);
    } else {
        for (std::string_view key : {"font", "height", "spacing", "lineSpacing", "align", "verticalAlign", "at", "rotation",
                                     "centre", "radius", "startAngle", "direction"})
            if (f.has(key)) f.fail(key, fmt::format("{} is for text; this operation engraves a {}", key,
                                                    f.has("profile") ? "profile" : "path"));
        if (f.has("profile")) {
            if (f.has("start") || f.has("path")) f.fail("profile", "give start and path, or profile, not both");
            if (std::optional<Profile> shape = read_shape_profile(f, in, "profile")) {
                strokes.push_back(std::move(*shape));
            } else {
                DxfProfiles d = read_dxf_profiles(f, in, "profile", op.tolerance.value_or(0.01), op.notes);
                if (d.profiles.empty()) f.fail("profile", "the drawing's selection holds no profile to engrave");
                for (std::size_t i = 0; i < d.profiles.size(); ++i) {
                    if (auto k = first_short_segment(d.profiles[i], min_profile_segment))
                        f.fail("profile", fmt::format("segment {} of the profile from {} is shorter than {} mm", *k, d.describe[i],
                                                      min_profile_segment));
                    strokes.push_back(std::move(d.profiles[i]));
                }
            }
        } else {
            if (!f.has("start") || !f.has("path")) f.fail(f.has("start") ? "path" : "start", "a path needs start and path");
            // The contour's reading of a path: lines and arcs in XY, not crossing itself.
            strokes.push_back(read_profile(f, in, "an engraving"));
        }
    }
    if (strokes.size() > engrave_max_strokes)
        f.fail(f.has("text") ? "text" : "profile",
               fmt::format("{} strokes, more than {} (give them in several operations)", strokes.size(), engrave_max_strokes));
    if (strokes.empty() || std::all_of(strokes.begin(), strokes.end(), [](const Profile& p) { return p.segments.empty(); }))
        f.fail(f.has("text") ? "text" : "", "there is nothing to engrave (the text has no strokes)");

    // Feeds as the other milling operations read them: the engagement is the line's width.
    const CutFeeds feeds = read_cut_feeds(f, in, tool, 0.0, op.notes);
    op.feed = feeds.cutting;
    op.plunge_feed = feeds.plunge;
    op.strokes = engrave_order(std::move(strokes));
    return op;
}

void expand(const EngraveOp& op, const Context& ctx, EventSink& sink) {
    if (op.strokes.empty()) return;
    const Planes z = resolve_planes(op.heights);
    const double depth = z.reference_z - z.bottom_z;
    // The line's width in the program, beside the operation's comment.
    sink.emit(Comment{fmt::format("line width {} mm, {} mm deep", number_text(op.width, 3), number_text(depth, 3))});
    auto cut_along = [&](const Profile& p, double at_z) {
        for (const ProfileSegment& s : p.segments) {
            const Vec3 to{s.end.x, s.end.y, at_z};
            if (s.centre) sink.emit(Arc{to, {s.centre->x, s.centre->y, at_z}, s.direction, Plane::xy, op.feed, 0, Movement::cutting});
            else sink.emit(Linear{to, op.feed, Movement::cutting});
        }
    };
    bool first = true;
    Vec2 last;
    for (const Profile& stroke : op.strokes) {
        const Vec2 s = stroke.start;
        if (first) {
            sink.emit(Rapid{{s.x, s.y, ctx.job.clearance}});
            if (z.retract_z != ctx.job.clearance) sink.emit(Rapid{{s.x, s.y, z.retract_z}});
            first = false;
        } else {
            sink.emit(Rapid{{s.x, s.y, z.retract_z}});
        }
        if (z.safe_z != z.retract_z) sink.emit(Rapid{{s.x, s.y, z.safe_z}});
        // Pass k back along the line where pass k - 1 ended (a closed stroke goes round again).
        const Profile back = reversed(stroke);
        Vec2 at = s;
        for (int k = 1; k <= op.passes; ++k) {
            const double pass_z = k == op.passes ? z.bottom_z : z.reference_z - depth * k / op.passes;
            sink.emit(Linear{{at.x, at.y, pass_z}, op.plunge_feed, Movement::plunge});
            const Profile& p = (k % 2 == 1 || is_closed(stroke)) ? stroke : back;
            cut_along(p, pass_z);
            at = profile_end(p);
        }
        sink.emit(Rapid{{at.x, at.y, z.retract_z}});
        last = at;
    }
    if (z.retract_z != ctx.job.clearance) sink.emit(Rapid{{last.x, last.y, ctx.job.clearance}});
}

std::string default_name(const EngraveOp& op) {
    if (!op.comment.empty()) return op.comment;
    if (!op.text.empty()) {
        std::string shown;
        for (char c : op.text) shown += c == '\n' ? ' ' : c;
        if (shown.size() > 40) shown = shown.substr(0, 37) + "...";
        return fmt::format("engrave \"{}\"", shown);
    }
    return fmt::format("engrave {} stroke{}", op.strokes.size(), op.strokes.size() == 1 ? "" : "s");
}

}  // namespace camgen
