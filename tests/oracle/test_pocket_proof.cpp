// The proof of the pocket and face operations (issue 26), its LinuxCNC half: the pocket and
// face samples and seeded random jobs (outlines: rectangles with and without corner radii,
// convex and star-shaped polygons with arcs, necks that split the area, L and U shapes, circles
// and slots; 0 to 3 islands, circles, rectangles and triangles, some near the walls and each
// other so that their offsets merge; strategies offset and zigzag with every order, direction,
// row mode, angles, steps, stockToLeave, finishing, leads and ramps; faces over rectangles and
// profiles; about a third of the jobs with their arcs' centres to 0.001 mm, as drawings give
// them, the ends a little off the circles). Each job is refused with an error naming its
// operation (a tool too big, a spot only a plunge reaches, an arc's end a hair off at a sharp
// corner: any other reason fails), or it is posted for linuxcnc and fanuc; LinuxCNC's
// interpreter (`rs274 -g`) runs both programs to PROGRAM_END, and its motion equals camgen's
// read-back of the same program within 0.001 mm, move for move.
//
// With CAMGEN_POCKET_PROOF=FILE the tool-centre moves rs274 made for each operation of the
// linuxcnc program go to FILE (one JSON object a line, with the operation's job): the geometry
// half, tests/pocket/proof.py, checks their coverage and clearance with shapely (ctest
// pocket/proof runs both). Seed and counts are printed; CAMGEN_POCKET_SEED, CAMGEN_POCKET_CASES
// and CAMGEN_FACE_CASES change them; CAMGEN_VARIANTS (the sanitizer build's 10, of 50) scales
// the default counts down.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../unit/support.hpp"
#include "camgen/common/error.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_pocket_proof {

using namespace camgen;
using namespace camgen::oracle;
using camgen::oracle::Step;  // not camgen::Step (analysis/trace.hpp), which a unity build may see too
using Json = nlohmann::json;

namespace {

int proof_env_int(const char* name, int fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::atoi(v) : fallback;
}

double pr3(double v) {
    const double r = std::round(v * 1000.0) / 1000.0;
    return r == 0.0 ? 0.0 : r;  // no -0 in the jobs
}

// ---- Loops of lines and arcs, as the generator draws them (its own geometry: sampled
// polygons for the validity of what it draws, nothing of camgen's).

struct GSeg {
    Vec2 end;
    std::optional<Vec2> centre;
    bool cw = false;
};

struct GLoop {
    Vec2 start;
    std::vector<GSeg> segs;
};

GLoop reversed_loop(const GLoop& l) {
    GLoop out;
    out.start = l.start;
    Vec2 at = l.start;
    std::vector<Vec2> starts;
    for (const GSeg& s : l.segs) {
        starts.push_back(at);
        at = s.end;
    }
    for (std::size_t k = l.segs.size(); k-- > 0;) out.segs.push_back({starts[k], l.segs[k].centre, !l.segs[k].cw});
    return out;
}

void put_loop(Json& into, const GLoop& l) {
    into["start"] = Json::array({l.start.x, l.start.y});
    Json path = Json::array();
    for (const GSeg& s : l.segs) {
        if (!s.centre) {
            path.push_back({{"line", Json::array({s.end.x, s.end.y})}});
        } else {
            path.push_back({{"arc",
                             {{"end", Json::array({s.end.x, s.end.y})},
                              {"centre", Json::array({s.centre->x, s.centre->y})},
                              {"direction", s.cw ? "cw" : "ccw"}}}});
        }
    }
    into["path"] = path;
}

// The sweep of an arc from `a` to `b` about `c`, radians, in (0, 2 pi].
double gen_sweep(Vec2 a, Vec2 b, Vec2 c, bool cw) {
    const double a0 = std::atan2(a.y - c.y, a.x - c.x), a1 = std::atan2(b.y - c.y, b.x - c.x);
    double s = cw ? a0 - a1 : a1 - a0;
    while (s <= 1e-12) s += two_pi;
    while (s > two_pi + 1e-12) s -= two_pi;
    return s;
}

// The loop as a polygon, arcs in chords at most `chord` off them (the last point not repeated).
std::vector<Vec2> gen_polygon(const GLoop& l, double chord) {
    std::vector<Vec2> out{l.start};
    Vec2 at = l.start;
    for (const GSeg& s : l.segs) {
        if (s.centre) {
            const Vec2 c = *s.centre;
            const double rho = distance(at, c);
            const double sweep = gen_sweep(at, s.end, c, s.cw);
            const double step = 2 * std::acos(1 - std::min(chord, rho / 2) / rho);
            const int n = std::max(2, static_cast<int>(std::ceil(sweep / step)));
            const double a0 = std::atan2(at.y - c.y, at.x - c.x);
            for (int k = 1; k < n; ++k) out.push_back(c + unit_at(a0 + (s.cw ? -1 : 1) * sweep * k / n) * rho);
        }
        out.push_back(s.end);
        at = s.end;
    }
    out.pop_back();
    return out;
}

bool gen_inside(const std::vector<Vec2>& poly, Vec2 p) {
    bool in = false;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
        if ((poly[i].y > p.y) != (poly[j].y > p.y) && p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
            in = !in;
    return in;
}

double gen_point_segment(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 d = b - a;
    const double l2 = dot(d, d);
    const double t = l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
    return distance(p, a + d * t);
}

double gen_distance(const std::vector<Vec2>& poly, Vec2 p) {
    double d = 1e300;
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) d = std::min(d, gen_point_segment(p, poly[j], poly[i]));
    return d;
}

double gen_segments_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return 0.0;
    return std::min({gen_point_segment(a, c, d), gen_point_segment(b, c, d), gen_point_segment(c, a, b), gen_point_segment(d, a, b)});
}

// The polygon is simple, its non-neighbouring edges at least `gap` apart, and its area some.
bool gen_simple(const std::vector<Vec2>& poly, double gap) {
    const std::size_t n = poly.size();
    if (n < 3) return false;
    double area = 0;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) area += cross(poly[j], poly[i]);
    if (std::abs(area) < 1.0) return false;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 2; j < n; ++j) {
            if (i == 0 && j == n - 1) continue;
            if (gen_segments_distance(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n]) < gap) return false;
        }
    return true;
}

// ---- The generator

class ProofGen {
public:
    explicit ProofGen(unsigned seed) : rng_(seed) {}

    double u() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
    double uni(double a, double b) { return a + (b - a) * u(); }
    bool chance(double p) { return u() < p; }
    int below(int n) { return std::min(n - 1, static_cast<int>(u() * n)); }

    // A closed loop through the vertices (counter-clockwise), some edges arcs bulging out (or
    // in) by up to `bulge` of their length.
    GLoop polygon_loop(std::vector<Vec2> v, double arc_share, double bulge, bool inward) {
        for (Vec2& p : v) p = {pr3(p.x), pr3(p.y)};
        GLoop l;
        l.start = v[0];
        for (std::size_t k = 0; k < v.size(); ++k) {
            const Vec2 a = v[k], b = v[(k + 1) % v.size()];
            const double len = distance(a, b);
            GSeg s{b, std::nullopt, false};
            if (len > 2 && chance(arc_share)) {
                const Vec2 out_normal = Vec2{b.y - a.y, a.x - b.x} * (1 / len);  // right of a -> b: outside a ccw loop
                const double side = inward && chance(0.3) ? -1.0 : 1.0;
                const double h = len * uni(0.05, bulge);
                const double rho = (len * len / 4 + h * h) / (2 * h);
                const Vec2 mid = (a + b) * 0.5;
                // The centre exact (both ends on its circle), or as a drawing gives it, to 0.001 mm
                // (the end then up to half a micron or more off the circle).
                const Vec2 exact = mid + out_normal * (side * (h - rho));
                const Vec2 c = three_decimals_ ? Vec2{pr3(exact.x), pr3(exact.y)} : exact;
                if (std::abs(distance(a, c) - distance(b, c)) <= 0.0009) {
                    s.centre = c;
                    s.cw = cross(a - c, b - c) < 0;  // the minor arc
                }
            }
            l.segs.push_back(s);
        }
        return l;
    }

    // A rectangle from (x0, y0), w x h, corners rounded by radii[k] (0: sharp), counter-clockwise
    // from the lower left.
    static GLoop rounded_rect(double x0, double y0, double w, double h, const std::array<double, 4>& radii) {
        const double x1 = x0 + w, y1 = y0 + h;
        const Vec2 corner[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
        const Vec2 dir_in[4] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};  // the direction of the side arriving at corner k
        GLoop l;
        std::vector<GSeg> segs;
        auto p = [](Vec2 v) { return Vec2{pr3(v.x), pr3(v.y)}; };
        // Start just after corner 0.
        l.start = p(corner[0] + Vec2{radii[0], 0});
        for (int k = 1; k <= 4; ++k) {
            const int c = k % 4;
            const double rc = radii[c];
            const Vec2 din = dir_in[c], dout = dir_in[(c + 1) % 4];
            const Vec2 before = p(corner[c] - din * rc), after = p(corner[c] + dout * rc);
            segs.push_back({before, std::nullopt, false});
            if (rc > 0) segs.push_back({after, p(corner[c] - din * rc + dout * rc), false});
        }
        // The last arc ends at the start; drop a zero-length closing line.
        std::vector<GSeg> clean;
        Vec2 at = l.start;
        for (const GSeg& s : segs) {
            if (!s.centre && distance(at, s.end) < 1e-9) continue;
            clean.push_back(s);
            at = s.end;
        }
        l.segs = clean;
        return l;
    }

    static GLoop circle_loop(Vec2 c, double rho, bool cw) {
        GLoop l;
        l.start = {pr3(c.x + rho), pr3(c.y)};
        l.segs.push_back({l.start, Vec2{pr3(c.x), pr3(c.y)}, cw});
        return l;
    }

    std::vector<Vec2> star(Vec2 c, int n, double r_min, double r_max, double ellipse) {
        std::vector<Vec2> v;
        for (int k = 0; k < n; ++k) {
            const double a = (k + 0.15 + 0.7 * u()) * two_pi / n;
            const double rad = uni(r_min, r_max);
            v.push_back(c + Vec2{rad * std::cos(a), rad * ellipse * std::sin(a)});
        }
        return v;
    }

    // An outline for a tool of radius r and stock s; `kind` names it for the summary.
    GLoop outline(double r, double s, std::string& kind) {
        const double reach = r + s;
        for (;;) {
            const int k = below(20);
            GLoop l;
            if (k < 5) {
                kind = "rectangle";
                const double w = pr3(uni(20, 60)), h = pr3(uni(20, 60));
                std::array<double, 4> radii{0, 0, 0, 0};
                const double most = std::min(w, h) / 2 - 0.5;
                const double mode = u();
                if (mode < 0.4) {
                } else if (mode < 0.75) {
                    kind = "rounded rectangle";
                    radii.fill(pr3(uni(0.5, std::min(most, 10.0))));
                } else {
                    kind = "rectangle, mixed corners";
                    for (double& rc : radii) rc = chance(0.3) ? 0.0 : pr3(uni(0.3, std::min(most, 12.0)));
                }
                l = rounded_rect(pr3(uni(-20, 20)), pr3(uni(-20, 20)), w, h, radii);
            } else if (k < 9) {
                kind = "convex polygon";
                const double a = uni(10, 30);
                l = polygon_loop(star(Vec2{uni(-10, 10), uni(-10, 10)}, 3 + below(7), a, a, uni(0.5, 1.0)), 0.3, 0.3, false);
            } else if (k < 13) {
                kind = "star polygon";
                l = polygon_loop(star(Vec2{uni(-10, 10), uni(-10, 10)}, 5 + below(8), uni(6, 15), uni(18, 32), 1.0), 0.25, 0.15, true);
            } else if (k < 16) {
                kind = "neck";
                // Two boxes joined by a channel about as wide as the tool with its stock.
                const double a = uni(12, 25), b = uni(12, 25), len = uni(3, 15);
                const double h1 = uni(15, 30), h2 = uni(15, 30);
                const double w = std::min({pr3(2 * reach * uni(0.7, 1.6)), h1 - 2, h2 - 2});
                const double yc = uni(w / 2 + 1, std::min(h1, h2) - w / 2 - 1);
                std::vector<Vec2> v{{0, 0},      {a, 0},          {a, yc - w / 2},     {a + len, yc - w / 2}, {a + len, 0},
                                    {a + len + b, 0}, {a + len + b, h2}, {a + len, h2}, {a + len, yc + w / 2}, {a, yc + w / 2},
                                    {a, h1},     {0, h1}};
                l = polygon_loop(v, 0.0, 0.1, false);
            } else if (k < 18) {
                kind = "L or U shape";
                const double w = uni(30, 60), h = uni(30, 60), t = uni(2 * reach + 2, 20);
                std::vector<Vec2> v;
                if (chance(0.5)) v = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, h}, {0, h}};
                else {
                    const double t2 = uni(2 * reach + 2, 20);
                    v = {{0, 0}, {w, 0}, {w, h}, {w - t2, h}, {w - t2, t}, {t, t}, {t, h}, {0, h}};
                }
                l = polygon_loop(v, 0.15, 0.15, true);
            } else if (k < 19) {
                kind = "circle";
                l = circle_loop({pr3(uni(-10, 10)), pr3(uni(-10, 10))}, pr3(uni(10, 30)), chance(0.5));
            } else {
                kind = "slot";
                // Two half circles joined by lines (a slot or an obround), counter-clockwise.
                const double rho = pr3(uni(reach + 0.5, 15)), len = pr3(uni(5, 40));
                l.start = {0, -rho};
                l.segs = {{{len, -rho}, std::nullopt, false}, {{len, rho}, Vec2{len, 0}, false}, {{0, rho}, std::nullopt, false},
                          {{0, -rho}, Vec2{0, 0}, false}};
            }
            if (!gen_simple(gen_polygon(l, 0.01), 0.05)) continue;
            if (chance(0.5)) l = reversed_loop(l);
            return l;
        }
    }

    // Up to `count` islands inside the outline, apart from it and each other; some near them.
    std::vector<GLoop> islands(const GLoop& outline, int count, double reach, int& near) {
        const std::vector<Vec2> poly = gen_polygon(outline, 0.01);
        double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
        for (Vec2 p : poly) {
            x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
        }
        const double size = std::min(x1 - x0, y1 - y0);
        std::vector<std::pair<Vec2, double>> placed;  // centre, bounding radius
        std::vector<GLoop> out;
        for (int i = 0; i < count; ++i) {
            for (int attempt = 0; attempt < 40; ++attempt) {
                const double rho = uni(1.0, std::max(1.5, std::min(8.0, 0.22 * size)));
                const bool close = chance(0.45);
                const double gap = close ? uni(0.05, 2.2 * reach) : uni(0.5, 6);
                const Vec2 c{pr3(uni(x0, x1)), pr3(uni(y0, y1))};
                if (!gen_inside(poly, c) || gen_distance(poly, c) < rho + gap) continue;
                bool apart = true;
                for (const auto& [pc, pr] : placed) apart = apart && distance(c, pc) >= rho + pr + gap;
                if (!apart) continue;
                GLoop l;
                const double shape = u();
                if (shape < 0.5) {
                    l = circle_loop(c, pr3(rho), chance(0.5));
                } else if (shape < 0.7) {
                    // An axis-parallel rectangle, rounded or not, within the bounding circle.
                    const double w = rho * uni(0.8, 1.35), h = std::sqrt(std::max(0.5, 4 * rho * rho - w * w)) * uni(0.6, 0.98);
                    std::array<double, 4> radii{0, 0, 0, 0};
                    if (chance(0.5)) radii.fill(pr3(uni(0.2, std::min(w, h) / 2 - 0.1)));
                    l = rounded_rect(pr3(c.x - w / 2), pr3(c.y - h / 2), pr3(w), pr3(h), radii);
                } else if (shape < 0.85) {
                    // A turned rectangle.
                    const double a = uni(0, pi), w = rho * uni(0.8, 1.35);
                    const double h = std::sqrt(std::max(0.5, 4 * rho * rho - w * w)) * uni(0.5, 0.98);
                    std::vector<Vec2> v;
                    for (Vec2 q : {Vec2{-w / 2, -h / 2}, Vec2{w / 2, -h / 2}, Vec2{w / 2, h / 2}, Vec2{-w / 2, h / 2}}) v.push_back(c + rotated(q, a));
                    l = polygon_loop(v, 0.0, 0.1, false);
                } else {
                    l = polygon_loop(star(c, 3, rho * 0.85, rho * 0.98, 1.0), 0.2, 0.15, false);
                }
                const std::vector<Vec2> ip = gen_polygon(l, 0.01);
                bool fits = gen_simple(ip, 0.05);
                for (Vec2 p : ip) fits = fits && distance(p, c) <= rho + 1e-6;
                if (!fits) continue;
                if (chance(0.5)) l = reversed_loop(l);
                near += close;
                placed.push_back({c, rho});
                out.push_back(l);
                break;
            }
        }
        return out;
    }

    // A pocket job (one operation, tool number `number`, comment `comment`).
    Json pocket(int number, const std::string& comment, std::string& kind) {
        three_decimals_ = chance(0.3);
        const double d = pr3(uni(4, 8));
        const double r = d / 2;
        Json tool = {{"number", number}, {"type", "end-mill"}, {"diameter", d}, {"rpm", 8000}};
        Json op = {{"type", "pocket"}, {"tool", number}, {"comment", comment}, {"retractPlane", 5}, {"safeDistance", 1}};
        const double depth = pr3(uni(1, 3));
        op["endDepth"] = depth;
        if (chance(0.15)) op["stepDown"] = pr3(uni(depth / 2.5, depth / 1.5));
        const double stock = chance(0.5) ? 0.0 : pr3(uni(0.05, 0.5));
        if (stock > 0 || chance(0.2)) op["stockToLeave"] = stock;
        double radial = 0;
        if (chance(0.3)) {
            radial = chance(0.15) ? 0.0 : pr3(uni(0.05, 0.5));
            Json fin = {{"radialStock", radial}};
            if (chance(0.6)) fin["axialStock"] = pr3(uni(0.1, std::min(0.3, depth / 2)));
            op["finishing"] = fin;
            for (const char* key : {"leadIn", "leadOut"}) {
                const double m = u();
                if (m < 0.3) op[key] = {{"type", "arc"}, {"radius", pr3(uni(0.3, r))}};
                else if (m < 0.45) op[key] = {{"type", "line"}, {"length", pr3(uni(0.3, r))}};
                else if (m < 0.55) op[key] = {{"type", "none"}};
            }
        }
        const double ramp = u();
        if (ramp < 0.15) op["ramp"] = {{"type", "helix"}, {"angle", pr3(uni(2, 10))}, {"radius", pr3(uni(0.3 * r, 1.2 * r))}};
        else if (ramp < 0.3) op["ramp"] = {{"type", "along"}, {"angle", pr3(uni(2, 10))}};
        else if (ramp < 0.4) op["ramp"] = {{"type", "plunge"}};
        if (ramp < 0.4 || chance(0.2)) tool["centreCutting"] = ramp >= 0.3 || chance(0.5);
        if (ramp >= 0.3 && ramp < 0.4) tool["centreCutting"] = true;
        const bool zigzag = chance(0.45);
        op["strategy"] = zigzag ? "zigzag" : "offset";
        if (zigzag) {
            op["stepOverPercent"] = pr3(uni(20, 100));
            const double a = u();
            if (a < 0.25) {
            } else if (a < 0.4) op["angle"] = 90;
            else if (a < 0.5) op["angle"] = 45;
            else op["angle"] = pr3(uni(-180, 180));
            if (chance(0.5)) op["rows"] = chance(0.5) ? "one-way" : "both-ways";
        } else {
            if (chance(0.8)) op["stepOverPercent"] = pr3(uni(20, 50));
            else op["stepOver"] = pr3(uni(0.2, 0.5) * d);
            if (chance(0.6)) op["order"] = chance(0.5) ? "outside-in" : "inside-out";
        }
        if (chance(0.6)) op["direction"] = chance(0.5) ? "conventional" : "climb";
        const GLoop outer = outline(r, stock + radial, kind);
        put_loop(op, outer);
        const double n = u();
        const int count = n < 0.35 ? 0 : n < 0.65 ? 1 : n < 0.85 ? 2 : 3;
        int near = 0;
        const std::vector<GLoop> isl = islands(outer, count, r + stock + radial, near);
        if (!isl.empty()) {
            Json list = Json::array();
            for (const GLoop& l : isl) {
                Json i;
                put_loop(i, l);
                list.push_back(i);
            }
            op["islands"] = list;
            kind += fmt::format(", {} island{}{}", isl.size(), isl.size() == 1 ? "" : "s", near ? " (near)" : "");
        }
        if (three_decimals_) kind += ", 3-decimal arc centres";
        op["feed"] = 600;
        op["plungeFeed"] = 150;
        op["rampFeed"] = 400;
        op["finishingFeed"] = 450;
        return {{"name", "proof"}, {"units", "mm"}, {"clearance", 15}, {"tools", Json::array({tool})}, {"operations", Json::array({op})}};
    }

    // A face job.
    Json face(int number, const std::string& comment, std::string& kind) {
        three_decimals_ = chance(0.3);
        const double d = pr3(uni(6, 20));
        Json tool = {{"number", number}, {"type", "end-mill"}, {"diameter", d}, {"rpm", 3000}};
        const double ref = chance(0.5) ? 0.0 : pr3(uni(0, 2));
        const double depth = pr3(uni(0.2, 1.5));
        Json op = {{"type", "face"}, {"tool", number}, {"comment", comment}, {"referencePlane", ref}, {"retractPlane", pr3(ref + 5)},
                   {"safeDistance", 1}, {"endDepth", depth}};
        if (chance(0.5)) {
            kind = "rectangle";
            const double x = pr3(uni(-30, 30)), y = pr3(uni(-30, 30)), w = pr3(uni(10, 80)), h = pr3(uni(10, 80));
            // Corners given in any order.
            const bool fx = chance(0.5), fy = chance(0.5);
            op["rectangle"] = {{"corner", Json::array({fx ? x + w : x, fy ? y + h : y})},
                               {"oppositeCorner", Json::array({fx ? x : x + w, fy ? y : y + h})}};
        } else {
            GLoop l;
            for (;;) {
                const double m = u();
                if (m < 0.3) {
                    kind = "rounded rectangle";
                    const double w = pr3(uni(10, 80)), h = pr3(uni(10, 80));
                    std::array<double, 4> radii{};
                    for (double& rc : radii) rc = chance(0.3) ? 0.0 : pr3(uni(0.5, std::min(w, h) / 2 - 0.2));
                    l = rounded_rect(pr3(uni(-20, 20)), pr3(uni(-20, 20)), w, h, radii);
                } else if (m < 0.6) {
                    kind = "convex profile";
                    const double a = uni(8, 35);
                    l = polygon_loop(star(Vec2{uni(-10, 10), uni(-10, 10)}, 3 + below(7), a, a, uni(0.5, 1.0)), 0.3, 0.3, false);
                } else if (m < 0.85) {
                    kind = "star profile";
                    l = polygon_loop(star(Vec2{uni(-10, 10), uni(-10, 10)}, 5 + below(6), uni(6, 15), uni(18, 32), 1.0), 0.25, 0.15, true);
                } else {
                    kind = "circle";
                    l = circle_loop({pr3(uni(-10, 10)), pr3(uni(-10, 10))}, pr3(uni(5, 30)), chance(0.5));
                }
                if (gen_simple(gen_polygon(l, 0.01), 0.05)) break;
            }
            if (chance(0.5)) l = reversed_loop(l);
            put_loop(op, l);
        }
        if (chance(0.8)) op["overhang"] = pr3(uni(0, 3));
        if (chance(0.5)) op["rows"] = chance(0.5) ? "one-way" : "both-ways";
        const double a = u();
        if (a < 0.4) {
        } else if (a < 0.55) op["angle"] = 90;
        else if (a < 0.65) op["angle"] = 45;
        else op["angle"] = pr3(uni(-180, 180));
        if (chance(0.8)) op["stepOverPercent"] = pr3(uni(30, 100));
        else op["stepOver"] = pr3(uni(0.3, 1.0) * d);
        if (chance(0.2)) op["stepDown"] = pr3(uni(depth / 2.5, depth));
        if (chance(0.2)) op["finishingStock"] = pr3(uni(0.05, 0.4 * depth));
        if (three_decimals_) kind += ", 3-decimal arc centres";
        op["feed"] = 900;
        op["plungeFeed"] = 300;
        op["finishingFeed"] = 600;
        return {{"name", "proof"}, {"units", "mm"}, {"clearance", 15}, {"tools", Json::array({tool})}, {"operations", Json::array({op})}};
    }

private:
    std::mt19937 rng_;
    bool three_decimals_ = false;  // this job's bulging arcs' centres rounded to 0.001 mm
};

// ---- Running the programs

double proof_dist(Vec3 a, Vec3 b) { return std::hypot(a.x - b.x, a.y - b.y, a.z - b.z); }

// rs274's motion and camgen's read-back of the same program agree move for move (from the
// first feed: before it rs274 starts at the origin, camgen's reader nowhere).
void check_same_motion(const std::vector<Step>& by_rs274, const std::vector<Step>& by_camgen, const std::string& what, double& worst) {
    const auto from_first_feed = [](std::vector<Step> steps) {
        const auto feed = std::find_if(steps.begin(), steps.end(), [](const Step& s) { return s.kind == Step::Kind::feed; });
        steps.erase(steps.begin(), feed);
        return steps;
    };
    const std::vector<Step> a = from_first_feed(by_rs274), b = from_first_feed(by_camgen);
    INFO(what);
    REQUIRE(a.size() > 10);
    REQUIRE(a.size() == b.size());
    int bad = 0;
    for (std::size_t i = 0; i < a.size() && bad < 5; ++i) {
        double d = proof_dist(a[i].to, b[i].to);
        bool same = a[i].kind == b[i].kind && std::abs(a[i].value - b[i].value) < 1e-6;
        if (a[i].kind == Step::Kind::arc) {
            d = std::max(d, std::hypot(a[i].centre.x - b[i].centre.x, a[i].centre.y - b[i].centre.y));
            same = same && a[i].rotation == b[i].rotation;
        }
        worst = std::max(worst, d);
        if (!same || !(d < 0.001)) {
            ++bad;
            FAIL_CHECK(fmt::format("{}: move {} differs: rs274 {}, camgen {}", what, i, describe(a[i]), describe(b[i])));
        }
    }
}

// The text of rs274's canonical calls from the line naming `comment` up to the next operation's.
std::vector<std::pair<std::size_t, std::size_t>> operation_chunks(const std::string& canon, const std::vector<std::string>& comments) {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    std::size_t from = 0;
    for (const std::string& c : comments) {
        const std::size_t at = canon.find("COMMENT(\"" + c + "\")", from);
        if (at == std::string::npos) throw std::runtime_error("rs274's output lacks the comment " + c);
        const std::size_t line = canon.rfind('\n', at);
        const std::size_t begin = line == std::string::npos ? 0 : line + 1;
        if (!out.empty()) out.back().second = begin;
        out.push_back({begin, canon.size()});
        from = at + 1;
    }
    return out;
}

Json step_json(const Step& s) {
    switch (s.kind) {
        case Step::Kind::traverse: return Json::array({"t", s.to.x, s.to.y, s.to.z});
        case Step::Kind::feed: return Json::array({"f", s.to.x, s.to.y, s.to.z});
        case Step::Kind::arc: return Json::array({"a", s.to.x, s.to.y, s.to.z, s.centre.x, s.centre.y, s.rotation});
        default: return nullptr;
    }
}

// One program of several operations, each given by its one-operation job (JSON) and comment.
struct Batch {
    Job job;
    std::vector<Json> jobs;
    std::vector<std::string> comments;
    std::vector<std::string> kinds;  // "pocket" or "face"
    std::vector<std::string> names;
};

struct ProofTotals {
    int programs = 0;
    int operations = 0;
    int rs274_runs = 0;
    double worst = 0.0;  // the largest difference between rs274 and camgen's read-back, mm
};

void run_batch(const std::string& rs274, const Batch& b, std::ofstream* dump, ProofTotals& t) {
    for (const char* machine_name : {"linuxcnc", "fanuc"}) {
        const Machine machine = load_machine(machine_name);
        const std::string program = test::post_program(b.job, machine);
        std::string canon;
        try {
            canon = run_rs274_canon(rs274, program, test::tool_diameters(b.job));
        } catch (const std::exception& e) {
            std::string jobs;
            for (const Json& j : b.jobs) jobs += "\n" + j.dump();
            FAIL_CHECK(fmt::format("{}: {}\nthe jobs:{}", machine_name, e.what(), jobs));
            continue;
        }
        ++t.rs274_runs;
        const std::vector<Step> steps = parse_canon(canon);
        check_same_motion(steps, read_with_camgen(program, machine),
                          fmt::format("{} program of {}", machine_name, b.names.front() + (b.names.size() > 1 ? " .. " + b.names.back() : "")),
                          t.worst);
        if (std::string(machine_name) != "linuxcnc" || !dump) continue;
        // The linuxcnc motion of each operation for the geometry check.
        Vec3 at{0, 0, 0};
        const auto chunks = operation_chunks(canon, b.comments);
        // The position before the first operation: where the canon before it left the tool.
        {
            const std::vector<Step> head = parse_canon(canon.substr(0, chunks.front().first));
            for (const Step& s : head)
                if (s.kind == Step::Kind::traverse || s.kind == Step::Kind::feed || s.kind == Step::Kind::arc) at = s.to;
        }
        for (std::size_t k = 0; k < chunks.size(); ++k) {
            Json moves = Json::array();
            const Vec3 start = at;
            for (const Step& s : parse_canon(canon.substr(chunks[k].first, chunks[k].second - chunks[k].first))) {
                const Json m = step_json(s);
                if (m.is_null()) continue;
                moves.push_back(m);
                at = s.to;
            }
            const Json record = {{"kind", b.kinds[k]}, {"name", b.names[k]}, {"job", b.jobs[k]}, {"start", Json::array({start.x, start.y, start.z})},
                                 {"moves", moves}};
            *dump << record.dump() << "\n";
        }
        dump->flush();  // the geometry half reads the file as it grows
    }
    ++t.programs;
    t.operations += static_cast<int>(b.jobs.size());
}

std::string proof_read_text(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("pocket proof: the pocket and face samples and random jobs are refused with a reason or run through rs274 as camgen reads them") {
    const auto rs274 = find_rs274();
    REQUIRE_MESSAGE(rs274, "rs274 (linuxcnc-uspace) is needed");
    const auto began = std::chrono::steady_clock::now();
    const unsigned seed = static_cast<unsigned>(proof_env_int("CAMGEN_POCKET_SEED", 2026));
    // The sanitizer build reads CAMGEN_VARIANTS=10 (of the Release build's 50): a fifth of the jobs.
    const int scale = std::clamp(proof_env_int("CAMGEN_VARIANTS", 50), 1, 50);
    const int pockets = proof_env_int("CAMGEN_POCKET_CASES", 1000 * scale / 50);
    const int faces = proof_env_int("CAMGEN_FACE_CASES", 300 * scale / 50);
    const char* dump_path = std::getenv("CAMGEN_POCKET_PROOF");
    std::optional<std::ofstream> dump;
    if (dump_path && *dump_path) {
        dump.emplace(dump_path);
        REQUIRE_MESSAGE(dump->good(), "cannot write ", dump_path);
    }
    ProofTotals totals;

    // The samples, whole.
    for (const char* name : {"pocket", "face"}) {
        const std::string text = proof_read_text(std::filesystem::path(CAMGEN_SOURCE_DIR) / "samples" / (std::string(name) + ".json"));
        const Json sample = Json::parse(text);
        Batch b;
        b.job = read_job(text, std::string(name) + ".json");
        for (std::size_t k = 0; k < sample["operations"].size(); ++k) {
            Json one = sample;
            one["operations"] = Json::array({sample["operations"][k]});
            b.jobs.push_back(one);
            b.comments.push_back(sample["operations"][k]["comment"]);
            b.kinds.push_back(sample["operations"][k]["type"]);
            b.names.push_back(fmt::format("samples/{}.json operation {}", name, k));
        }
        run_batch(*rs274, b, dump ? &*dump : nullptr, totals);
    }

    // The random jobs: each read alone (refused, or planned), then up to 20 in one program.
    ProofGen gen(seed);
    constexpr std::size_t per_program = 20;
    std::map<std::string, int> refusals, kinds_posted, kinds_refused;
    int posted_pockets = 0, posted_faces = 0, refused_pockets = 0, refused_faces = 0;
    Batch batch;
    auto flush = [&]() {
        if (batch.jobs.empty()) return;
        run_batch(*rs274, batch, dump ? &*dump : nullptr, totals);
        batch = Batch{};
    };
    for (int k = 0; k < pockets + faces; ++k) {
        const bool is_face = k >= pockets;
        const std::string comment = fmt::format("case {}", k);
        std::string kind;
        const int number = static_cast<int>(batch.jobs.size()) + 1;
        const Json job_json = is_face ? gen.face(number, comment, kind) : gen.pocket(number, comment, kind);
        const std::string label = fmt::format("{} {}", is_face ? "face" : "pocket", kind.substr(0, kind.find(',')));
        Job job;
        try {
            job = read_job(job_json.dump(), "proof.json");
        } catch (const InputError& e) {
            const std::string what = e.what();
            INFO("seed ", seed, " ", comment, ": ", job_json.dump());
            CHECK_MESSAGE(what.find("/operations/0") != std::string::npos, what);
            // The reason: the message after the operation's path up to its next ':', numbers as #.
            std::string reason = what.substr(what.find("/operations/0"));
            reason = reason.substr(reason.find(": ") == std::string::npos ? 0 : reason.find(": ") + 2);
            reason = reason.substr(0, reason.find(':'));
            const std::string shape = std::regex_replace(reason, std::regex("-?[0-9]+(\\.[0-9]+)?"), "#");
            refusals[fmt::format("{}: {}", is_face ? "face" : "pocket", shape)]++;
            // The generator draws valid regions (simple loops, islands apart): the only reasons are
            // a tool too big for the pocket, a spot of it only a plunge reaches with a tool that
            // does not cut at its centre, and (arc centres to 0.001 mm) a sharp corner where an
            // arc's end a hair off its circle makes the next segment cross back over it, which the
            // region geometry refuses by name.
            const bool hair = kind.find("3-decimal") != std::string::npos && what.find("they cross by a hair") != std::string::npos;
            const bool expected = hair || (!is_face && (what.find("with the stock left does not fit in the pocket") != std::string::npos ||
                                                        what.find("the tool cannot enter the pocket at") != std::string::npos));
            CHECK_MESSAGE(expected, "an unexpected refusal: ", what);
            kinds_refused[label]++;
            if (dump) *dump << Json{{"kind", "refused"}, {"name", fmt::format("seed {} {} ({})", seed, comment, kind)}, {"message", what}, {"job", job_json}}.dump() << "\n";
            (is_face ? refused_faces : refused_pockets)++;
            continue;
        }
        (is_face ? posted_faces : posted_pockets)++;
        kinds_posted[label]++;
        if (batch.jobs.empty()) {
            batch.job = job;
        } else {
            for (const auto& [n, tool] : job.tools) batch.job.tools[n] = tool;
            for (Operation& op : job.operations) batch.job.operations.push_back(std::move(op));
        }
        batch.jobs.push_back(job_json);
        batch.comments.push_back(comment);
        batch.kinds.push_back(is_face ? "face" : "pocket");
        batch.names.push_back(fmt::format("seed {} {} ({})", seed, comment, kind));
        if (batch.jobs.size() == per_program) flush();
    }
    flush();

    std::string why;
    for (const auto& [reason, n] : refusals) why += fmt::format("\n  {} x {}", n, reason);
    std::string shapes;
    for (const auto& [label, n] : kinds_posted) shapes += fmt::format("\n  {}: {} posted, {} refused", label, n, kinds_refused[label]);
    for (const auto& [label, n] : kinds_refused)
        if (!kinds_posted.count(label)) shapes += fmt::format("\n  {}: 0 posted, {} refused", label, n);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    MESSAGE(fmt::format("pocket proof: seed {}; {} random pockets ({} posted, {} refused), {} random faces ({} posted, {} refused); "
                        "{} programs of {} operations (samples too) through rs274 {} times (linuxcnc and fanuc); "
                        "largest difference rs274 - camgen's read-back {:.5f} mm; {:.1f} s{}{}",
                        seed, pockets, posted_pockets, refused_pockets, faces, posted_faces, refused_faces, totals.programs,
                        totals.operations, totals.rs274_runs, totals.worst, seconds, shapes, why));
    // Most random jobs post: a refusal is for a tool that does not fit, not for a shape camgen cannot plan.
    CHECK(posted_pockets >= pockets * 8 / 10);
    CHECK(posted_faces >= faces * 95 / 100);
    CHECK(totals.rs274_runs == 2 * totals.programs);
}

}  // namespace test_pocket_proof
