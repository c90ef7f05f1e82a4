// The DXF reader against drawings written by ezdxf (tests/dxf/make_drawings.py): every
// entity, OCS extrusion -Z, nested and mirrored inserts, arrays, units; each compared with the
// geometry the writer was given (tests/dxf/NAME.expected.json), positions within 1e-6, arcs as
// arcs. Then selection, chaining, nesting and the errors of bad drawings.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "camgen/dxf/dxf.hpp"
#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/vec.hpp"

namespace test_dxf {

using namespace camgen;
using nlohmann::json;

std::string drawing(const std::string& name) { return std::string(CAMGEN_SOURCE_DIR "/tests/dxf/") + name; }

json expected(const std::string& name) {
    std::ifstream in(drawing(name + ".expected.json"));
    return json::parse(in);
}

void near(Vec2 got, const json& want, const std::string& what) {
    INFO(what << ": got (" << got.x << ", " << got.y << "), want " << want.dump());
    CHECK(std::abs(got.x - want[0].get<double>()) < 1e-6);
    CHECK(std::abs(got.y - want[1].get<double>()) < 1e-6);
}

// Distance of `p` from the polyline through `pts`.
double off_polyline(Vec2 p, const std::vector<Vec2>& pts) {
    double best = 1e300;
    for (std::size_t i = 1; i < pts.size(); ++i) {
        const Vec2 a = pts[i - 1], ab = pts[i] - a;
        const double t = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
        best = std::min(best, distance(p, a + ab * t));
    }
    return best;
}

// Compares what camgen read with what the writer was given.
void compare(const std::string& name, double tolerance = 0.01) {
    dxf::ReadOptions o;
    o.curve_tolerance = tolerance;
    const dxf::Drawing d = dxf::read_file(drawing(name + ".dxf"), o);
    const json want = expected(name);
    CHECK(d.insunits == want["units"].get<int>());
    std::vector<const dxf::Piece*> points, circles, paths;
    for (const dxf::Piece& p : d.pieces)
        (p.kind == dxf::Piece::Kind::point ? points : p.kind == dxf::Piece::Kind::circle ? circles : paths).push_back(&p);
    REQUIRE(points.size() == want["points"].size());
    REQUIRE(circles.size() == want["circles"].size());
    REQUIRE(paths.size() == want["paths"].size());
    for (std::size_t i = 0; i < points.size(); ++i) near(points[i]->centre, want["points"][i], "point");
    for (std::size_t i = 0; i < circles.size(); ++i) {
        near(circles[i]->centre, want["circles"][i], "circle");
        CHECK(std::abs(circles[i]->radius - want["circles"][i][2].get<double>()) < 1e-6);
    }
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const json& w = want["paths"][i];
        const Profile& p = paths[i]->path;
        INFO(name << " path " << i << " (" << paths[i]->origin.type << ")");
        CHECK(paths[i]->closed == w["closed"].get<bool>());
        if (w.contains("curve")) {
            // Fitted by lines: every point the writer's curve passes through lies within the
            // tolerance of the lines, and every vertex of the lines lies on the writer's curve
            // as sampled finely.
            std::vector<Vec2> ours = sample_profile(p, 1e-4);
            for (const json& q : w["curve"]) CHECK(off_polyline({q[0].get<double>(), q[1].get<double>()}, ours) <= tolerance + 1e-9);
            near(p.start, w["curve"][0], "curve start");
            continue;
        }
        near(p.start, w["start"], "start");
        REQUIRE(p.segments.size() == w["segments"].size());
        for (std::size_t k = 0; k < p.segments.size(); ++k) {
            const json& s = w["segments"][k];
            near(p.segments[k].end, s, "end");
            REQUIRE(p.segments[k].centre.has_value() == (s.size() == 5));
            if (s.size() == 5) {
                near(*p.segments[k].centre, json::array({s[2], s[3]}), "centre");
                CHECK((p.segments[k].direction == ArcDirection::ccw) == (s[4] == "ccw"));
            }
        }
    }
}

TEST_CASE("dxf: every entity type ezdxf writes reads as the geometry it was given") { compare("entities"); }
TEST_CASE("dxf: the curves are fitted within a tighter tolerance when asked") { compare("entities", 0.0005); }
TEST_CASE("dxf: extrusion (0, 0, -1) mirrors X and turns arcs clockwise") { compare("ocs"); }
// Written by FreeCAD's own exporter (tests/dxf/make_freecad.py, freecadcmd): its lines, arcs and
// circles, on a layer per object, at the positions FreeCAD was given.
TEST_CASE("dxf: FreeCAD's DXF export reads as the geometry FreeCAD was given") { compare("freecad"); }
TEST_CASE("dxf: nested, rotated, scaled, mirrored inserts and arrays") {
    compare("blocks");
    const dxf::Drawing d = dxf::read_file(drawing("blocks.dxf"));
    // Layer 0 inside a block takes the insert's layer; the block path is kept.
    for (const dxf::Piece& p : d.pieces) {
        CHECK(p.origin.layer == "HOLES");
        REQUIRE(!p.origin.blocks.empty());
        CHECK(p.origin.blocks.back() == "HOLE");
    }
    CHECK(d.pieces.front().origin.blocks.front() == "PAIR");
}
TEST_CASE("dxf: units from $INSUNITS") {
    compare("inch");
    std::string name;
    CHECK(dxf::mm_per_unit(1, &name) == 25.4);
    CHECK(name == "inches");
    CHECK(dxf::mm_per_unit(4) == 1.0);
    CHECK(!dxf::mm_per_unit(0, &name));
    CHECK(name == "unitless");
}

std::string error_of(const std::string& text) {
    try {
        dxf::read_text(text, "t.dxf");
    } catch (const dxf::Error& e) {
        return e.what();
    }
    return "";
}

TEST_CASE("dxf: bad drawings are each a clear error") {
    auto file_error = [](const std::string& name) {
        try {
            dxf::read_file(drawing(name));
        } catch (const dxf::Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(file_error("bad-truncated.dxf").find("cut short") != std::string::npos);
    const std::string entity = file_error("bad-entity.dxf");
    CHECK(entity.find("does not read 3DFACE") != std::string::npos);
    CHECK(entity.find("handle ") != std::string::npos);
    CHECK(entity.find("layer 0") != std::string::npos);
    CHECK(entity.find("bad-entity.dxf line ") == entity.find(drawing("")) + drawing("").size());
    CHECK(error_of("AutoCAD Binary DXF\r\n\x1a") .find("a binary DXF") != std::string::npos);
    CHECK(error_of(std::string("AC1032\0\0\0\0\0", 11)).find("a DWG drawing") != std::string::npos);
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\nLINE\n5\n2A\n8\nCUT\n10\nabc\n20\n0\n11\n1\n21\n1\n0\nENDSEC\n0\nEOF\n") ==
          "t.dxf line 11: LINE (handle 2A, layer CUT): group code 10 needs a number, got \"abc\"");
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n8\nH\n10\n1\n20\n1\n0\nENDSEC\n0\nEOF\n") ==
          "t.dxf line 5: CIRCLE (layer H): group code 40 is missing");
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\nENDSEC\n") == "t.dxf line 5: the file ends inside the drawing (no EOF): it is cut short (truncated)");
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\n") == "t.dxf line 5: the file ends after group code 0 without its value: it is cut short");
    CHECK(error_of("{\"units\": \"mm\"}\n").find("expected a group code") != std::string::npos);
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\n1\n20\n1\n40\n1\n210\n1\n220\n0\n230\n0\n0\nENDSEC\n0\nEOF\n")
              .find("not in the XY plane") != std::string::npos);
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nNOPE\n10\n0\n20\n0\n0\nENDSEC\n0\nEOF\n") ==
          "t.dxf line 5: INSERT (layer 0): block NOPE is not defined in the BLOCKS section");
    CHECK(error_of("0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nA\n10\n0\n20\n0\n0\nINSERT\n2\nA\n10\n0\n20\n0\n0\nENDBLK\n0\nENDSEC\n"
                   "0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nA\n10\n0\n20\n0\n0\nENDSEC\n0\nEOF\n")
              .find("block A inserts itself") != std::string::npos);
}

TEST_CASE("dxf: a layer that does not exist names those that do") {
    const dxf::Drawing d = dxf::read_file(drawing("plate.dxf"));
    dxf::Selection s;
    s.layers = {"HOLE"};
    try {
        dxf::select(d, s, "holes");
        FAIL("no error");
    } catch (const dxf::Error& e) {
        CHECK(std::string(e.what()) == drawing("plate.dxf") + ": layer HOLE not found; layers are: 0, Defpoints, OUTLINE, POCKET, HOLES");
    }
    s.layers = {"holes"};  // names without case, as CAD does
    CHECK(dxf::select(d, s, "holes").size() == 5);
    s.min_diameter = 4.9, s.max_diameter = 5.1;
    CHECK(dxf::select(d, s, "holes").size() == 4);
}

TEST_CASE("dxf: chaining joins pieces into closed profiles, nests them, and notes gaps and duplicates") {
    const dxf::Drawing d = dxf::read_file(drawing("plate.dxf"));
    dxf::Selection s;
    s.layers = {"OUTLINE", "POCKET"};
    const dxf::ChainResult r = dxf::chain(dxf::select(d, s, "a profile"), 0.01, "plate.dxf");
    REQUIRE(r.chains.size() == 3);
    for (const dxf::Chain& c : r.chains) CHECK(c.closed);
    CHECK(r.notes.empty());
    const std::vector<int> parent = dxf::nesting(r.chains);
    // The outline holds the pocket, which holds the island.
    CHECK(parent[0] == -1);
    CHECK(parent[2] == 0);  // the four pieces of the pocket, chained
    CHECK(parent[1] == 2);  // the island circle
    CHECK(r.chains[2].pieces.size() == 4);
    CHECK(std::abs(enclosed_area(r.chains[2].profile) - (40 * 20 + pi * 100)) < 0.1);

    const dxf::Drawing gap = dxf::read_file(drawing("bad-gap.dxf"));
    const dxf::ChainResult tight = dxf::chain(dxf::select(gap, {}, "a profile"), 0.1, "bad-gap.dxf");
    CHECK(tight.chains.size() == 1);
    CHECK(!tight.chains[0].closed);
    const dxf::ChainResult loose = dxf::chain(dxf::select(gap, {}, "a profile"), 0.6, "bad-gap.dxf");
    REQUIRE(loose.chains.size() == 1);
    CHECK(loose.chains[0].closed);
    REQUIRE(loose.notes.size() == 1);
    CHECK(loose.notes[0].find("a gap of 0.5 between LINE handle") != std::string::npos);

    // A piece drawn twice is left out with a note.
    const std::string twice = "0\nSECTION\n2\nENTITIES\n0\nLINE\n5\nA1\n10\n0\n20\n0\n11\n5\n21\n0\n0\nLINE\n5\nA2\n10\n5\n20\n0\n11\n0\n21\n0\n"
                              "0\nENDSEC\n0\nEOF\n";
    const dxf::Drawing t = dxf::read_text(twice, "t.dxf");
    const dxf::ChainResult tr = dxf::chain(dxf::select(t, {}, "a profile"), 0.01, "t.dxf");
    CHECK(tr.chains.size() == 1);
    REQUIRE(tr.notes.size() == 1);
    CHECK(tr.notes[0] == "t.dxf: LINE handle A2 (line 17, layer 0) is drawn twice (also LINE handle A1 (line 5, layer 0)): left out");
}

// ---- The fit of ellipses and splines by arcs and lines, against the exact curves.

// The curve of tests/dxf/curves.expected.json at parameter t: an ellipse in closed form, a
// (rational) spline by the Cox-de Boor recursion (not camgen's de Boor).
struct ExactCurve {
    json def;
    double t0 = 0, t1 = 1;
    explicit ExactCurve(const json& c) : def(c) {
        if (def.contains("ellipse")) {
            t0 = def["ellipse"]["t0"].get<double>();
            t1 = def["ellipse"]["t1"].get<double>();
        } else {
            const auto& k = def["spline"]["knots"];
            const int p = def["spline"]["degree"].get<int>();
            t0 = k[p].get<double>();
            t1 = k[k.size() - 1 - p].get<double>();
        }
    }
    static double basis(const std::vector<double>& k, int i, int p, double t) {
        if (p == 0) return (k[i] <= t && t < k[i + 1]) ? 1.0 : 0.0;
        double v = 0;
        if (k[i + p] > k[i]) v += (t - k[i]) / (k[i + p] - k[i]) * basis(k, i, p - 1, t);
        if (k[i + p + 1] > k[i + 1]) v += (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) * basis(k, i + 1, p - 1, t);
        return v;
    }
    Vec2 at(double t) const {
        if (def.contains("ellipse")) {
            const json& e = def["ellipse"];
            const Vec2 c{e["centre"][0].get<double>(), e["centre"][1].get<double>()};
            const Vec2 major{e["major"][0].get<double>(), e["major"][1].get<double>()};
            const Vec2 minor = Vec2{-major.y, major.x} * e["ratio"].get<double>();
            return c + major * std::cos(t) + minor * std::sin(t);
        }
        const json& sp = def["spline"];
        const std::vector<double> k = sp["knots"].get<std::vector<double>>();
        const int p = sp["degree"].get<int>();
        const std::size_t n = sp["control"].size();
        if (t >= t1) return {sp["control"][n - 1][0].get<double>(), sp["control"][n - 1][1].get<double>()};
        Vec2 sum;
        double wsum = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double b = basis(k, static_cast<int>(i), p, t) * sp["weights"][i].get<double>();
            sum = sum + Vec2{sp["control"][i][0].get<double>(), sp["control"][i][1].get<double>()} * b;
            wsum += b;
        }
        return sum * (1.0 / wsum);
    }
};

// The exact distance of q from the segment k of p (a line or an arc).
double off_segment(const Profile& p, std::size_t k, Vec2 q) {
    const Vec2 a = segment_start(p, k), b = p.segments[k].end;
    if (!p.segments[k].centre) {
        const Vec2 ab = b - a;
        const double t = std::clamp(dot(q - a, ab) / std::max(dot(ab, ab), 1e-300), 0.0, 1.0);
        return distance(q, a + ab * t);
    }
    const Vec2 c = *p.segments[k].centre;
    const bool ccw = p.segments[k].direction == ArcDirection::ccw;
    const double sa = std::atan2(a.y - c.y, a.x - c.x);
    auto turn = [&](Vec2 v) {
        double u = std::atan2(v.y - c.y, v.x - c.x) - sa;
        if (ccw && u < 0) u += two_pi;
        if (!ccw && u > 0) u -= two_pi;
        return std::abs(u);
    };
    if (turn(q) <= turn(b)) return std::abs(distance(q, c) - distance(a, c));
    return std::min(distance(q, a), distance(q, b));
}

// The largest distance of the fit from the curve, measured both ways: the curve's points (20,000
// even steps of its parameter) from the fit, and the fit's points (64 on each segment) from the
// curve (the nearest of its 20,000 points, refined by a ternary search of the parameter).
double fit_deviation(const Profile& fit, const ExactCurve& curve) {
    constexpr int n = 20000;
    std::vector<Vec2> dense(n + 1);
    for (int i = 0; i <= n; ++i) dense[i] = curve.at(curve.t0 + (curve.t1 - curve.t0) * i / n);
    double worst = 0;
    for (const Vec2& q : dense) {
        double best = 1e300;
        for (std::size_t k = 0; k < fit.segments.size(); ++k) best = std::min(best, off_segment(fit, k, q));
        worst = std::max(worst, best);
    }
    for (std::size_t k = 0; k < fit.segments.size(); ++k) {
        Profile one;
        one.start = segment_start(fit, k);
        one.segments.push_back(fit.segments[k]);
        const double length = profile_length(one);
        for (int j = 0; j <= 64; ++j) {
            const Vec2 q = point_at(one, length * j / 64).point;
            int nearest = 0;
            for (int i = 1; i <= n; ++i)
                if (distance(dense[i], q) < distance(dense[nearest], q)) nearest = i;
            const double step = (curve.t1 - curve.t0) / n;
            double lo = curve.t0 + step * std::max(nearest - 1, 0), hi = curve.t0 + step * std::min(nearest + 1, n);
            for (int it = 0; it < 60; ++it) {
                const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
                if (distance(curve.at(m1), q) < distance(curve.at(m2), q)) hi = m2;
                else lo = m1;
            }
            worst = std::max(worst, std::min(distance(curve.at((lo + hi) / 2), q), distance(dense[nearest], q)));
        }
    }
    return worst;
}

TEST_CASE("dxf: ellipses and splines are fitted by arcs and lines within the tolerance of the exact curve") {
    const json want = expected("curves");
    for (double tolerance : {0.01, 0.001}) {
        dxf::ReadOptions o;
        o.curve_tolerance = tolerance;
        const dxf::Drawing d = dxf::read_file(drawing("curves.dxf"), o);
        REQUIRE(d.pieces.size() == want["curves"].size());
        for (std::size_t i = 0; i < d.pieces.size(); ++i) {
            const ExactCurve curve(want["curves"][i]);
            // The test's own curve is ezdxf's.
            for (std::size_t j = 0; j <= 20; ++j)
                near(curve.at(curve.t0 + (curve.t1 - curve.t0) * double(j) / 20), want["curves"][i]["points"][j], "the exact curve");
            const Profile& fit = d.pieces[i].path;
            std::size_t arcs = 0;
            for (const ProfileSegment& s : fit.segments) arcs += s.centre ? 1 : 0;
            const double deviation = fit_deviation(fit, curve);
            INFO("curve " << i << " at tolerance " << tolerance << ": " << fit.segments.size() << " segments, " << arcs
                          << " arcs, largest deviation " << deviation);
            CHECK(arcs > 0);
            CHECK(deviation <= tolerance + 1e-9);
        }
    }
}

}  // namespace test_dxf

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"

namespace test_dxf {

// A job in tests/dxf/ (so that drawings are found beside it) with one operation.
std::string job_text(const std::string& op, const std::string& units = "mm") {
    return R"({"name": "t", "units": ")" + units + R"(", "clearance": 15, "tools": [
      {"number": 1, "type": "drill", "diameter": 5, "rpm": 1800},
      {"number": 2, "type": "end-mill", "diameter": 6, "rpm": 8000}],
      "operations": [)" + op + "]}";
}
const std::string job_name = CAMGEN_SOURCE_DIR "/tests/dxf/t.json";

std::string job_error(const std::string& op, const std::string& units = "mm") {
    try {
        read_job(job_text(op, units), job_name);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const std::string drill_head = R"({"type": "drill", "tool": 1, "cycle": "drill", "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "plungingFeedrate": 100, )";
const std::string contour_head = R"({"type": "contour", "tool": 2, "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "feed": 500, )";

TEST_CASE("dxf in a job: holes from a drawing's circles, selected by layer and diameter, transformed") {
    Job job = read_job(job_text(drill_head + R"("drawing": {"dxf": "plate.dxf", "layer": "HOLES", "diameter": [4.9, 5.1],
        "transform": {"rotate": 90, "translate": [100, 0]}}})"), job_name);
    const auto& drill = std::get<DrillOp>(job.operations.at(0));
    REQUIRE(drill.holes.size() == 4);
    // (8, 8) turned 90 degrees is (-8, 8), moved by (100, 0).
    CHECK(std::abs(drill.holes[0].x - 92) < 1e-9);
    CHECK(std::abs(drill.holes[0].y - 8) < 1e-9);
    CHECK(std::abs(drill.holes[2].x - 58) < 1e-9);
    CHECK(std::abs(drill.holes[2].y - 72) < 1e-9);
    // Mirrored in X and scaled.
    job = read_job(job_text(drill_head + R"("drawing": {"dxf": "plate.dxf", "layer": "HOLES", "diameter": [6, 7],
        "transform": {"mirror": "x", "scale": 2}}})"), job_name);
    const auto& small = std::get<DrillOp>(job.operations.at(0));
    REQUIRE(small.holes.size() == 1);
    CHECK(small.holes[0] == Vec2{-80, 88});
}

TEST_CASE("dxf in a job: units from $INSUNITS against the job's") {
    // An inch drawing in a mm job: scaled by 25.4.
    Job job = read_job(job_text(drill_head + R"("drawing": {"dxf": "inch.dxf"}})"), job_name);
    const auto& d = std::get<DrillOp>(job.operations.at(0));
    REQUIRE(d.holes.size() == 1);
    CHECK(std::abs(d.holes[0].x - 25.4) < 1e-9);
    CHECK(std::abs(d.holes[0].y - 12.7) < 1e-9);
    CHECK(d.notes.empty());
}

TEST_CASE("dxf in a job: a contour and a pocket from a drawing") {
    Job job = read_job(job_text(contour_head + R"("side": "outside", "profile": {"dxf": "plate.dxf", "layer": "OUTLINE"}})"), job_name);
    const Profile& outline = std::get<ContourOp>(job.operations.at(0)).profile;
    CHECK(outline.start == Vec2{5, 0});
    REQUIRE(outline.segments.size() == 8);
    CHECK(outline.segments[1].centre.has_value());
    CHECK(std::abs(outline.segments[1].centre->x - 75) < 1e-9);
    CHECK(std::abs(outline.segments[1].centre->y - 5) < 1e-9);
    CHECK(is_closed(outline));
    job = read_job(job_text(R"({"type": "pocket", "tool": 2, "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "feed": 500,
        "profile": {"dxf": "plate.dxf", "layer": "POCKET"}})"), job_name);
    const PocketOp& pocket = std::get<PocketOp>(job.operations.at(0));
    CHECK(pocket.region.islands.size() == 1);
    CHECK(std::abs(enclosed_area(pocket.region.outer) - (800 + pi * 100)) < 0.1);
    CHECK(std::abs(enclosed_area(pocket.region.islands[0]) - pi * 16) < 0.1);
}

TEST_CASE("dxf in a job: bad drawings and selections are errors naming the key, the drawing and the entity") {
    CHECK(job_error(drill_head + R"("drawing": {"dxf": "plate.dxf", "layer": "HOLE"}})")
              .find("/operations/0/drawing: " CAMGEN_SOURCE_DIR "/tests/dxf/plate.dxf: layer HOLE not found; layers are: 0, Defpoints, "
                    "OUTLINE, POCKET, HOLES") != std::string::npos);
    CHECK(job_error(drill_head + R"("drawing": {"dxf": "missing.dxf"}})").find("cannot open the drawing") != std::string::npos);
    CHECK(job_error(drill_head + R"("drawing": {"dxf": "bad-truncated.dxf"}})").find("cut short") != std::string::npos);
    CHECK(job_error(drill_head + R"("drawing": {"dxf": "bad-entity.dxf"}})").find("does not read 3DFACE") != std::string::npos);
    CHECK(job_error(drill_head + R"("drawing": {"dxf": "plate.dxf", "layer": "OUTLINE"}})")
              .find("plate.dxf has no circles or points on layer OUTLINE") != std::string::npos);
    const std::string gap = job_error(R"({"type": "pocket", "tool": 2, "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "feed": 500,
        "profile": {"dxf": "bad-gap.dxf"}})");
    CHECK(gap.find("/operations/0/profile: a pocket needs closed profiles, but the one from LINE handle") != std::string::npos);
    CHECK(gap.find("is open (its ends are 0.500 mm apart") != std::string::npos);
    CHECK(job_error(contour_head + R"("profile": {"dxf": "bad-crossing.dxf"}})").find("crosses or touches itself") != std::string::npos);
    CHECK(job_error(contour_head + R"("profile": {"dxf": "plate.dxf"}})").find("a contour takes one profile, but the selection holds 8") !=
          std::string::npos);
    CHECK(job_error(contour_head + R"("start": [0, 0], "profile": {"dxf": "plate.dxf"}})").find("give start and path, or profile, not both") !=
          std::string::npos);
    // The gap closed when the tolerance allows it, with a note naming both entities.
    Job job = read_job(job_text(R"({"type": "pocket", "tool": 2, "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "feed": 500,
        "profile": {"dxf": "bad-gap.dxf", "gapTolerance": 0.6}})"), job_name);
    const PocketOp& p = std::get<PocketOp>(job.operations.at(0));
    REQUIRE(!p.notes.empty());
    CHECK(p.notes[0].find("/operations/0/profile: bad-gap.dxf: a gap of 0.5 between LINE handle") != std::string::npos);
}

}  // namespace test_dxf
