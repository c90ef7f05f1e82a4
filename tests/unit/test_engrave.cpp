// Engraving (issue 29, item 4): the Hershey font reader (strict, bounded: damaged records are
// errors, never crashes), text set from the font's glyphs (compared with the .jhf read here,
// independently), its alignment, spacing and placement along a line and around an arc, the
// strokes' order, a V-bit's line width, paths, and the refusals with their JSON paths.
#include <algorithm>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/job/tool_geometry.hpp"
#include "camgen/operations/engrave/hershey.hpp"
#include "camgen/reader/reader.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_engrave {

using namespace camgen;

namespace {

const std::string font_dir = "/usr/share/hershey-fonts";

std::string engrave_text_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// The test's own reading of a .jhf glyph (one record a line, as Debian's files are): the
// strokes of character `c` in font units, Y down, and its bounds.
struct RawGlyph {
    int left = 0, right = 0;
    std::vector<std::vector<std::pair<int, int>>> strokes;
};
RawGlyph raw_glyph(const std::string& font, char c) {
    std::istringstream in(engrave_text_of(font_dir + "/" + font + ".jhf"));
    std::string line;
    for (int k = 0; k <= c - 32; ++k) std::getline(in, line);
    RawGlyph g;
    g.left = line[8] - 'R';
    g.right = line[9] - 'R';
    g.strokes.emplace_back();
    for (std::size_t i = 10; i + 1 < line.size(); i += 2) {
        if (line[i] == ' ') {
            g.strokes.emplace_back();
            continue;
        }
        const std::pair<int, int> p{line[i] - 'R', line[i + 1] - 'R'};
        if (g.strokes.back().empty() || g.strokes.back().back() != p) g.strokes.back().push_back(p);
    }
    std::erase_if(g.strokes, [](const auto& s) { return s.empty(); });
    return g;
}

using Polyline = std::vector<Vec2>;

// The engraving's cuts as the program is read back: each run of feed moves at the bottom Z,
// its points from the plunge on.
std::vector<Polyline> cut_runs(const std::string& program, const Machine& machine, double bottom_z) {
    const Trace t = trace_program(read_program(program, machine, "e.nc"), machine);
    std::vector<Polyline> runs;
    bool open = false;
    for (const Step& s : t.steps) {
        const bool at_bottom = s.kind == StepKind::feed && std::abs(s.to.z - bottom_z) < 1e-6;
        if (at_bottom && std::abs(s.from.z - bottom_z) > 1e-6) {
            runs.push_back({{s.to.x, s.to.y}});
            open = true;
        } else if (at_bottom && open) {
            runs.back().push_back({s.to.x, s.to.y});
        } else {
            open = false;
        }
    }
    return runs;
}

// Whether `run` is `want` (or it backwards), point for point within `tol`.
bool same_line(const Polyline& run, const Polyline& want, double tol) {
    if (run.size() != want.size()) return false;
    auto close = [&](bool back) {
        for (std::size_t i = 0; i < run.size(); ++i)
            if (distance(run[i], want[back ? want.size() - 1 - i : i]) > tol) return false;
        return true;
    };
    return close(false) || close(true);
}

// The worst distance from each expected stroke to the run that matches it; -1 when one has none.
double match_all(const std::vector<Polyline>& runs, const std::vector<Polyline>& want, double tol) {
    std::vector<bool> used(runs.size(), false);
    for (const Polyline& w : want) {
        bool found = false;
        for (std::size_t k = 0; k < runs.size() && !found; ++k)
            if (!used[k] && same_line(runs[k], w, tol)) used[k] = found = true;
        if (!found) return -1;
    }
    return std::count(used.begin(), used.end(), true) == static_cast<long>(runs.size()) ? 0.0 : -1;
}

// The strokes of `text` (one line) in `font` as the test sets them: cap height `height` from
// H's extent, left-aligned at `at` along +X, `spacing` between glyphs.
std::vector<Polyline> expected_text(const std::string& font, const std::string& text, double height, Vec2 at, double spacing) {
    const RawGlyph h = raw_glyph(font, 'H');
    int top = 1000, base = -1000;
    for (const auto& s : h.strokes)
        for (const auto& p : s) top = std::min(top, p.second), base = std::max(base, p.second);
    const double scale = height / (base - top);
    std::vector<Polyline> out;
    double pen = 0.0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const RawGlyph g = raw_glyph(font, text[i]);
        if (i > 0) pen += spacing;
        for (const auto& s : g.strokes) {
            Polyline pl;
            for (const auto& p : s) pl.push_back({at.x + pen + (p.first - g.left) * scale, at.y + (base - p.second) * scale});
            if (pl.size() >= 2) out.push_back(pl);
        }
        pen += (g.right - g.left) * scale;
    }
    return out;
}

std::string engrave_job(const std::string& keys, const std::string& tool = R"("type": "v-bit", "diameter": 3, "tipAngle": 60, "tipDiameter": 0.1)") {
    return fmt::format(R"({{"name": "e", "units": "mm", "clearance": 10,
  "stock": {{"box": {{"size": [100, 60, 10], "origin": [0, 0, -10]}}}},
  "tools": [{{"number": 1, {}, "rpm": 12000}}],
  "operations": [{{"type": "engrave", "tool": 1, "retractPlane": 2, "safeDistance": 0.5, "feed": 400, {}}}]}})",
                       tool, keys);
}

// The feed moves at the bottom of a job's events, as polylines (from the events, not a program).
std::vector<Polyline> event_runs(const std::string& job_text, double bottom_z) {
    const Job job = read_job(job_text, "e.json");
    std::vector<Polyline> runs;
    Vec3 at{};
    bool open = false;
    for (const Event& e : expand_job(job)) {
        if (const auto* r = std::get_if<Rapid>(&e)) at = r->to, open = false;
        if (const auto* l = std::get_if<Linear>(&e)) {
            const bool bottom = std::abs(l->to.z - bottom_z) < 1e-9;
            if (bottom && std::abs(at.z - bottom_z) > 1e-9) runs.push_back({{l->to.x, l->to.y}}), open = true;
            else if (bottom && open) runs.back().push_back({l->to.x, l->to.y});
            at = l->to;
        }
    }
    return runs;
}

std::string error_of(const std::string& job_text) {
    try {
        read_job(job_text, "e.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Extent in X and Y of polylines.
struct Box {
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
};
Box box_of(const std::vector<Polyline>& runs) {
    Box b;
    for (const Polyline& r : runs)
        for (Vec2 p : r) b.x0 = std::min(b.x0, p.x), b.y0 = std::min(b.y0, p.y), b.x1 = std::max(b.x1, p.x), b.y1 = std::max(b.y1, p.y);
    return b;
}

}  // namespace

TEST_CASE("hershey: Debian's fonts read; every glyph of rowmans as the file has it") {
    const HersheyFont f = load_hershey_font("rowmans", font_dir);
    CHECK(f.glyphs.size() == 96);
    CHECK(f.cap_top == -12);
    CHECK(f.baseline == 9);
    for (char c = 33; c < 127; ++c) {
        CAPTURE(c);
        const RawGlyph raw = raw_glyph("rowmans", c);
        const HersheyGlyph* g = f.glyph(static_cast<char32_t>(c));
        REQUIRE(g);
        CHECK(g->left == raw.left);
        CHECK(g->right == raw.right);
        REQUIRE(g->strokes.size() == raw.strokes.size());
    }
    CHECK(f.glyph(U'\u00e9') == nullptr);
    CHECK(f.glyph(U'\n') == nullptr);
    // Every font of the package reads.
    for (const char* name : {"futural", "scripts", "timesr", "gothiceng", "markers", "japanese"}) CHECK_NOTHROW(load_hershey_font(name, font_dir));
}

TEST_CASE("hershey: damaged records are errors naming the file and line, never a crash") {
    const std::string good = "  501  9I[RFJ[ RRFZ[ RMTWT\n  502  2G\\KF\n";
    CHECK(parse_hershey(good, "t.jhf", "t").glyphs.size() == 2);
    auto error = [](const std::string& text) {
        try {
            parse_hershey(text, "t.jhf", "t");
        } catch (const FontError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(error("  501  9I[RFJ[ RRFZ[ RMTW\n") == "t.jhf line 1: glyph 501 has 9 vertices (18 characters), but its record ends after 17 characters");
    CHECK(error("  501  8I[RFJ[ RRFZ[ RMTWT\n") == "t.jhf line 1: glyph 501 has 8 vertices (16 characters), but its record has 18 characters");
    CHECK(error("  5x1  9I[RFJ[ RRFZ[ RMTWT\n") == "t.jhf line 1: the glyph number (columns 1 to 5) is \"  5x1\", not a number");
    CHECK(error("  501  0\n") == "t.jhf line 1: the vertex count is 0: a glyph has at least its bounds");
    CHECK(error("  501  1[I\n") == "t.jhf line 1: glyph 501: its left bound (9) is right of its right bound (-9)");
    CHECK(error("  501  1IQ\n\n  502  1IQ\n") == "t.jhf line 2: an empty line where a glyph record should be");
    CHECK(error("  501  3IQ ARS\n") == "t.jhf line 1: glyph 501: vertex 1 is \" A\": a space only lifts the pen, as \" R\"");
    CHECK(error(std::string("  501  1I\x01\n")) == "t.jhf line 1: glyph 501: byte 1 at vertex 0 is no coordinate (characters ' ' to '~')");
    CHECK(error("") == "t.jhf: no glyphs: not a Hershey font");
    CHECK(error("  50") == "t.jhf line 1: a glyph record needs 8 characters of number and vertex count, this line has 4");
    CHECK(error(std::string(hershey_max_bytes + 1, 'R')).find("not a Hershey font") != std::string::npos);
    // A record wrapped onto the next line (the original distribution's 72 columns) reads.
    CHECK(parse_hershey("  501  9I[RFJ[ RR\nFZ[ RMTWT\n", "t.jhf", "t").glyphs.at(0).strokes.size() == 3);
    // Fuzz-ish: every line of rowmans cut short at every length, and every character of it
    // replaced by a few bytes: an error or a font, never a crash or a hang.
    const std::string text = engrave_text_of(font_dir + "/rowmans.jhf");
    std::istringstream in(text);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    int errors = 0, fonts = 0;
    for (std::size_t k = 0; k < lines.size(); k += 7) {
        for (std::size_t cut = 0; cut < lines[k].size(); cut += 3) {
            std::string damaged;
            for (std::size_t i = 0; i < lines.size(); ++i) damaged += (i == k ? lines[i].substr(0, cut) : lines[i]) + "\n";
            error(damaged).empty() ? ++fonts : ++errors;
        }
        for (std::size_t at = 0; at < lines[k].size(); at += 2)
            for (char b : {'\0', ' ', 'R', '\x7f', '\xff', '9'}) {
                std::string damaged;
                for (std::size_t i = 0; i < lines.size(); ++i) {
                    std::string l = lines[i];
                    if (i == k) l[at] = b;
                    damaged += l + "\n";
                }
                error(damaged).empty() ? ++fonts : ++errors;
            }
    }
    CHECK(errors > 500);
    CHECK(fonts > 0);  // some replacements are other valid coordinates
}

TEST_CASE("hershey: a missing font names the folder, CAMGEN_FONTS and the package; a bad name is refused") {
    const std::string dir = test::scratch("fonts").string();
    std::ofstream(dir + "/mine.jhf") << "  501  9I[RFJ[ RRFZ[ RMTWT\n";
    CHECK(load_hershey_font("mine", dir).glyphs.size() == 1);
    try {
        load_hershey_font("nosuch", dir);
        FAIL("no error");
    } catch (const FontError& e) {
        CHECK(std::string(e.what()) == fmt::format("font \"nosuch\" not found: no {}/nosuch.jhf (the default folder; the fonts are "
                                                   "Debian's package hershey-fonts-data, apt-get install hershey-fonts-data; "
                                                   "CAMGEN_FONTS names another folder); the folder holds mine",
                                                   dir));
    }
    CHECK_THROWS_WITH_AS(load_hershey_font("../etc/passwd", dir), doctest::Contains("is not a font name"), FontError);
}

TEST_CASE("engrave: the text's strokes are the font's glyphs, scaled and placed, as linuxcnc and fanuc read them back") {
    // "SN 2026-042" in rowmans, 5 mm high, from (10, 20), 0.3 mm spacing; the V-bit 0.2 deep.
    const std::string job = engrave_job(R"("text": "SN 2026-042", "height": 5, "spacing": 0.3, "at": [10, 20], "depth": 0.2)");
    const std::vector<Polyline> want = expected_text("rowmans", "SN 2026-042", 5, {10, 20}, 0.3);
    REQUIRE(want.size() == 13);
    for (const char* name : {"linuxcnc", "fanuc"}) {
        CAPTURE(name);
        const test::Posted p = test::post_job(job, name);
        const std::vector<Polyline> runs = cut_runs(p.text, load_machine(name), -0.2);
        CHECK(runs.size() == want.size());
        CHECK(match_all(runs, want, 0.001) == 0.0);
    }
    // Another font, futural, the same.
    const std::string fut = engrave_job(R"("text": "Rev B", "font": "futural", "height": 3, "at": [5, 5], "depth": 0.1)");
    CHECK(match_all(event_runs(fut, -0.1), expected_text("futural", "Rev B", 3, {5, 5}, 0), 1e-9) == 0.0);
}

TEST_CASE("engrave: alignment along and across the text, rotation, spacing and line spacing") {
    // H in rowmans: bounds -11 to 11, its uprights at -7 and 7, 21 units high (-12 to 9).
    auto runs = [](const std::string& keys) { return event_runs(engrave_job(keys + R"(, "depth": 0.2)"), -0.2); };
    const double u = 21.0 / 21.0;  // mm per unit at height 21
    const Box left = box_of(runs(R"("text": "H", "height": 21, "at": [50, 30])"));
    CHECK(left.x0 == doctest::Approx(50 + 4 * u));
    CHECK(left.x1 == doctest::Approx(50 + 18 * u));
    CHECK(left.y0 == doctest::Approx(30));
    CHECK(left.y1 == doctest::Approx(51));
    const Box centre = box_of(runs(R"("text": "H", "height": 21, "at": [50, 30], "align": "centre", "verticalAlign": "top")"));
    CHECK(centre.x0 == doctest::Approx(43));
    CHECK(centre.x1 == doctest::Approx(57));
    CHECK(centre.y1 == doctest::Approx(30));
    const Box right = box_of(runs(R"("text": "H", "height": 21, "at": [50, 30], "align": "right", "verticalAlign": "middle")"));
    CHECK(right.x1 == doctest::Approx(50 - 4 * u));
    CHECK(right.y0 == doctest::Approx(30 - 10.5));
    CHECK(right.y1 == doctest::Approx(30 + 10.5));
    // Two lines, middle: from the first's cap top to the second's baseline, centred on the anchor.
    const Box two = box_of(runs(R"("text": "H\nH", "height": 10, "lineSpacing": 15, "at": [50, 30], "verticalAlign": "middle")"));
    CHECK(two.y1 - two.y0 == doctest::Approx(25));
    CHECK((two.y1 + two.y0) / 2 == doctest::Approx(30));
    // Spacing: "HH" with 2 mm more between them: the second H's left upright 22 + 2 units on.
    const Box hh = box_of(runs(R"("text": "HH", "height": 21, "spacing": 2, "at": [0, 0])"));
    CHECK(hh.x1 == doctest::Approx(22 + 2 + 18));
    // Rotation 90: the text runs up +Y, its tops towards -X.
    const Box up = box_of(runs(R"("text": "H", "height": 21, "at": [50, 30], "rotation": 90)"));
    CHECK(up.y0 == doctest::Approx(34));
    CHECK(up.y1 == doctest::Approx(48));
    CHECK(up.x0 == doctest::Approx(29));
    CHECK(up.x1 == doctest::Approx(50));
}

TEST_CASE("engrave: text around an arc, each glyph upright to it; clockwise over the top, counter-clockwise under") {
    // "I" in rowmans is one upright at the middle of its advance: on the arc it lies along the
    // radius at startAngle, from the baseline circle out (cw) or in (ccw) by the height.
    auto runs = [](const std::string& keys) { return event_runs(engrave_job(keys + R"(, "depth": 0.2)"), -0.2); };
    const std::vector<Polyline> top = runs(R"("text": "I", "height": 5, "centre": [50, 30], "radius": 20, "startAngle": 90, "align": "centre")");
    REQUIRE(top.size() == 1);
    for (Vec2 p : top[0]) CHECK(p.x == doctest::Approx(50));
    CHECK(std::min(top[0].front().y, top[0].back().y) == doctest::Approx(50));
    CHECK(std::max(top[0].front().y, top[0].back().y) == doctest::Approx(55));
    const std::vector<Polyline> under = runs(R"("text": "I", "height": 5, "centre": [50, 30], "radius": 20, "startAngle": 270, "direction": "ccw", "align": "centre")");
    REQUIRE(under.size() == 1);
    for (Vec2 p : under[0]) CHECK(p.x == doctest::Approx(50));
    CHECK(std::min(under[0].front().y, under[0].back().y) == doctest::Approx(10));
    CHECK(std::max(under[0].front().y, under[0].back().y) == doctest::Approx(15));
    // "II" left-aligned at 90 degrees, clockwise: the uprights' middles at arc lengths 4 and
    // 4 + 8 (+ 1 spacing) units along the circle of radius 20 (rowmans I: bounds -4 to 4).
    const double s = 5.0 / 21.0;
    const std::vector<Polyline> ii = runs(R"("text": "II", "height": 5, "spacing": 1, "centre": [50, 30], "radius": 20, "startAngle": 90)");
    REQUIRE(ii.size() == 2);
    for (std::size_t k = 0; k < 2; ++k) {
        const double arc = k == 0 ? 4 * s : 12 * s + 1;
        const double angle = 90.0 * rad_per_deg - arc / 20.0;
        const Vec2 base{50 + 20 * std::cos(angle), 30 + 20 * std::sin(angle)};
        const Vec2 a = ii[k].front(), b = ii[k].back();
        const Vec2 low = distance(a, Vec2{50, 30}) < distance(b, Vec2{50, 30}) ? a : b;
        CHECK(distance(low, base) < 1e-9);
        // Upright: along the radius.
        const Vec2 d = ii[k].front() - ii[k].back();
        CHECK(std::abs(cross(d, base - Vec2{50, 30})) < 1e-9);
    }
}

TEST_CASE("engrave: strokes ordered nearest first, each entered from above, passes back and forth; V width noted") {
    const std::string job = engrave_job(R"("text": "HI", "height": 5, "at": [10, 10], "depth": 0.3, "passes": 2, "plungeFeed": 100)");
    const Job j = read_job(job, "e.json");
    const auto& op = std::get<EngraveOp>(j.operations.at(0));
    REQUIRE(op.strokes.size() == 4);
    // H: its left upright, then the nearest end: the crossbar's left end is nearer than the right upright.
    // Each next stroke starts at the end nearest to where the last one ended.
    for (std::size_t k = 1; k < op.strokes.size(); ++k) {
        const Vec2 end = op.strokes[k - 1].segments.back().end;
        for (std::size_t m = k + 1; m < op.strokes.size(); ++m) {
            CHECK(distance(end, op.strokes[k].start) <= distance(end, op.strokes[m].start) + 1e-12);
            CHECK(distance(end, op.strokes[k].start) <= distance(end, op.strokes[m].segments.back().end) + 1e-12);
        }
    }
    // 60-degree V, 0.1 tip, 0.3 deep: 0.1 + 2 x 0.3 x tan 30.
    CHECK(op.width == doctest::Approx(0.1 + 0.6 * std::tan(30 * rad_per_deg)));
    CHECK(op.notes.at(0) == "the lines are 0.4464 mm wide at the top: tool 1's 60-degree V with a 0.1 mm tip, 0.3 mm deep");
    // Per stroke: rapid above its start at the retract plane, down to the safe distance, plunge
    // at 100 to -0.15, cut, plunge to -0.3, cut back, rapid up to the retract plane.
    const std::vector<Event> ev = expand_job(j);
    int plunges = 0, retracts = 0;
    for (std::size_t i = 0; i < ev.size(); ++i) {
        if (const auto* l = std::get_if<Linear>(&ev[i]); l && l->movement == Movement::plunge) {
            ++plunges;
            CHECK(l->feed == 100);
        }
        if (const auto* r = std::get_if<Rapid>(&ev[i]); r && r->to.z == 2) ++retracts;
    }
    CHECK(plunges == 8);
    CHECK(retracts >= 4);
    const std::vector<Polyline> deep = event_runs(job, -0.3), half = event_runs(job, -0.15);
    REQUIRE(deep.size() == 4);
    REQUIRE(half.size() == 4);
    for (std::size_t k = 0; k < 4; ++k) CHECK(distance(deep[k].front(), half[k].back()) < 1e-9);  // back along it
    // A ball mill's width is its chord at the depth; an end mill's its diameter.
    Tool ball;
    ball.type = ToolType::ball_mill;
    ball.diameter = 2;
    CHECK(*cut_width_at_depth(ball, 0.2) == doctest::Approx(2 * std::sqrt(1 - 0.8 * 0.8)));
    Tool vee;
    vee.type = ToolType::v_bit;
    vee.diameter = 6;
    vee.tip_angle = 90;
    CHECK(*cut_width_at_depth(vee, 10) == 6);  // above the cone: the tool's diameter
    CHECK(*cut_width_at_depth(vee, 1) == doctest::Approx(2));
    // An engraver (a single-flute engraving cutter) is a V by its geometry: the same width and
    // note as the V-bit's, and the same cone in the simulation and the chamfer.
    const std::string engraver_job = engrave_job(R"("text": "HI", "height": 5, "at": [10, 10], "depth": 0.3)",
                                                 R"("type": "engraver", "diameter": 3, "tipAngle": 60, "tipDiameter": 0.1)");
    const Job ej = read_job(engraver_job, "e.json");
    const auto& eop = std::get<EngraveOp>(ej.operations.at(0));
    CHECK(eop.width == op.width);
    CHECK(eop.notes.at(0) == op.notes.at(0));
    vee.type = ToolType::engraver;
    CHECK(*cut_width_at_depth(vee, 1) == doctest::Approx(2));
    CHECK(is_cone_tool(vee));
}

TEST_CASE("engrave: a path and a profile engraved on their line") {
    const std::string job = engrave_job(R"("start": [10, 10], "path": [{"line": [20, 10]}, {"arc": {"end": [20, 20], "centre": [20, 15], "direction": "ccw"}}], "depth": 0.2)");
    const Job j = read_job(job, "e.json");
    bool arc = false;
    for (const Event& e : expand_job(j))
        if (const auto* a = std::get_if<Arc>(&e)) {
            arc = true;
            CHECK(a->to == Vec3{20, 20, -0.2});
            CHECK(a->centre == Vec3{20, 15, -0.2});
        }
    CHECK(arc);
    const std::string circle = engrave_job(R"("profile": {"circle": {"centre": [50, 30], "diameter": 10}}, "depth": 0.2)");
    CHECK(std::get<EngraveOp>(read_job(circle, "e.json").operations.at(0)).strokes.size() == 1);
}

TEST_CASE("engrave: every profile of a DXF drawing's selection, open or closed, in nearest order") {
    // A line (10,10)-(30,10), an arc about (50,30) of radius 5 from 0 to 180 degrees, a circle
    // about (20,30) of radius 4, on layer MARK: three strokes; from the circle (the first, from
    // and back to (24, 30)) the line's end (30, 10) is the nearest: the line is cut reversed, to
    // (10, 10); from there the arc's end (45, 30) is nearer than its start (55, 30): the arc is
    // cut reversed too (clockwise).
    const std::filesystem::path dir = test::scratch("engrave-dxf");
    std::ofstream(dir / "m.dxf") << "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\nMARK\n10\n10\n20\n10\n30\n0\n11\n30\n21\n10\n31\n0\n"
                                  "0\nARC\n8\nMARK\n10\n50\n20\n30\n30\n0\n40\n5\n50\n0\n51\n180\n"
                                  "0\nCIRCLE\n8\nMARK\n10\n20\n20\n30\n30\n0\n40\n4\n0\nENDSEC\n0\nEOF\n";
    const std::string job = engrave_job(R"("profile": {"dxf": "m.dxf", "layer": "MARK"}, "depth": 0.2)", R"("type": "v-bit", "diameter": 3, "tipAngle": 90)");
    const Job j = read_job(job, (dir / "e.json").string());
    const auto& op = std::get<EngraveOp>(j.operations.at(0));
    REQUIRE(op.strokes.size() == 3);
    CHECK(op.width == doctest::Approx(0.4));
    CHECK(op.strokes[0].start == Vec2{24, 30});
    CHECK(op.strokes[1].start == Vec2{30, 10});
    CHECK(op.strokes[1].segments.at(0).end == Vec2{10, 10});
    CHECK(op.strokes[2].start == Vec2{45, 30});
    REQUIRE(op.strokes[2].segments.size() == 1);
    CHECK(op.strokes[2].segments[0].end == Vec2{55, 30});
    CHECK(op.strokes[2].segments[0].direction == ArcDirection::cw);
}

TEST_CASE("engrave: refusals name the JSON path: a character the font lacks, a bad font, a wrong tool, flutes") {
    CHECK(error_of(engrave_job(R"("text": "Nº 12", "height": 5, "at": [0, 0], "depth": 0.2)")) ==
          "e.json:4: /operations/0/text: character 2 of the text, 'º' (U+00BA), is not in font rowmans (it has characters U+0020 to U+007E)");
    // DEL (U+007F) is a control character: the font's 96th record is not engraved for it.
    CHECK(error_of(engrave_job(R"("text": "A\u007fB", "height": 5, "at": [0, 0], "depth": 0.2)")).find("character 2 of the text, U+007F, is not in font") != std::string::npos);
    CHECK(error_of(engrave_job(R"("text": "A\tB", "height": 5, "at": [0, 0], "depth": 0.2)")).find("character 2 of the text, a tab (U+0009), is not in font") != std::string::npos);
    CHECK(error_of(engrave_job(R"("text": "A", "font": "nosuch", "height": 5, "at": [0, 0], "depth": 0.2)"))
              .find("/operations/0/font: font \"nosuch\" not found: no /usr/share/hershey-fonts/nosuch.jhf") != std::string::npos);
    CHECK(error_of(engrave_job(R"("text": "A", "font": "../x", "height": 5, "at": [0, 0], "depth": 0.2)")).find("/operations/0/font: \"../x\" is not a font name") != std::string::npos);
    for (const char* type : {R"("type": "drill", "diameter": 3, "tipAngle": 118)", R"("type": "tap", "diameter": 6)",
                             R"("type": "thread-mill", "diameter": 6, "pitch": 1)", R"("type": "spot-drill", "diameter": 6, "tipAngle": 90)"}) {
        CAPTURE(type);
        const std::string e = error_of(engrave_job(R"("text": "A", "height": 5, "at": [0, 0], "depth": 0.2)", type));
        CAPTURE(e);
        CHECK(e.find("/operations/0/tool: tool 1 (/tools/0) is a ") != std::string::npos);
        CHECK(e.find(": an engrave operation needs a v-bit, engraver, chamfer-mill, ball-mill, bull-nose or end-mill") != std::string::npos);
    }
    CHECK(error_of(engrave_job(R"("text": "A", "height": 5, "at": [0, 0], "depth": 0.5)", R"("type": "v-bit", "diameter": 3, "tipAngle": 60, "fluteLength": 0.4)")) ==
          "e.json:4: /operations/0/depth: the lines are 0.500 mm deep, but tool 1 (/tools/0) has a fluteLength of 0.400 mm");
    CHECK(error_of(engrave_job(R"("text": "A", "at": [0, 0], "depth": 0.2)")) == "e.json:4: /operations/0/height: text needs its height (the cap height, mm)");
    CHECK(error_of(engrave_job(R"("text": "A", "height": 5, "depth": 0.2)")).find("text needs at (along a line) or centre and radius") != std::string::npos);
    CHECK(error_of(engrave_job(R"("text": "ABCDEFGHIJ", "height": 5, "centre": [0, 0], "radius": 5, "depth": 0.2)")).find("/operations/0/radius: line 1 of the text is ") != std::string::npos);
    CHECK(error_of(engrave_job(R"("text": "A", "height": 5, "at": [0, 0], "depth": 0)")).find("/operations/0/depth") != std::string::npos);
    CHECK(error_of(engrave_job(R"("text": "A", "start": [0, 0], "height": 5, "at": [0, 0], "depth": 0.2)")).find("exactly one of text, a path") != std::string::npos);
}

TEST_CASE("engrave: camgen simulate finds a stroke cut 0.1 mm too deep as a gouge of its operation") {
    // samples/engrave.json on linuxcnc simulates as designed (test_simulate_design.cpp runs it on
    // every mill); its second stroke (the N's upright, 4 mm long) plunged to Z-0.3 instead of
    // Z-0.2 and cut there is a gouge 0.1 mm below the design at that stroke.
    const std::filesystem::path dir = test::scratch("engrave-gouge");
    const std::string job = CAMGEN_SOURCE_DIR "/samples/engrave.json";
    const std::string program = (dir / "e.ngc").string();
    REQUIRE(test::run({job, "--machine", "linuxcnc", "-q", "-o", program}).code == 0);
    std::string text = test::read_file(program);
    const test::Run ok = test::run({"simulate", program, "--machine", "linuxcnc", "--job", job});
    CHECK(ok.code == 0);
    CHECK_MESSAGE(ok.out.find("  the part is as designed\n") != std::string::npos, ok.out);
    const std::string plunge = "G1 Z-0.2 F100";
    std::size_t at = text.find(plunge);
    REQUIRE(at != std::string::npos);
    at = text.find(plunge, at + 1);
    REQUIRE(at != std::string::npos);
    const int line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n')) + 1;
    text.replace(at, plunge.size(), "G1 Z-0.3 F100");
    const std::string deep = (dir / "deep.ngc").string();
    std::ofstream(deep) << text;
    const test::Run r = test::run({"simulate", deep, "--machine", "linuxcnc", "--job", job});
    CHECK(r.code == 1);
    CHECK_MESSAGE(r.out.find("error: gouge: /operations/0 (stroke 1): material removed 0.1 mm below the designed -0.2 at ") != std::string::npos, r.out);
    CHECK_MESSAGE(r.out.find(fmt::format(", by line {} (", line)) != std::string::npos, r.out);
}

}  // namespace test_engrave
