// Turning (issue 30 items 1 and 2): the lathe tools' keys, turn-face, turn-rough and
// turn-profile's approach and retract. The roughing is measured on its own moves against the
// profile, worked out here independently of the planner: it never goes below the profile
// moved by the allowances, reaches it everywhere (so the allowances are all that is left), and
// every rapid runs in air above what the passes before it left. Many random profiles, rising
// and with undercuts, not only the sample.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_turn_rough {

using namespace camgen;

namespace {

// The error read_job gives for `text` ("" when none).
std::string refusal(const std::string& text) {
    try {
        (void)read_job(text, "turn.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string tool_job(const std::string& tool) {
    return R"({"clearance": 20, "tools": [)" + tool + R"(], "operations": []})";
}

// One straight move of the tool tip in (Z, radius), a rapid or a feed.
struct TipMove {
    Vec2 from, to;
    bool rapid = false;
    Movement movement = Movement::cutting;
};

// The tip's moves of a job's events, arcs as chords of at most 0.01 degree... (0.0005 mm at
// these radii).
std::vector<TipMove> tip_moves(const Job& job) {
    std::vector<TipMove> out;
    Vec2 at{job.clearance, 0.0};
    bool started = false;
    std::vector<Event> events;
    for (const Event& e : expand_job(job)) {
        if (const auto* c = std::get_if<TurnCycle>(&e)) {
            for (const Event& m : turn_cycle_moves(*c)) events.push_back(m);
        } else {
            events.push_back(e);
        }
    }
    for (const Event& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            const Vec2 to{r->to.z, r->to.x};
            if (started) out.push_back({at, to, true});
            at = to, started = true;
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            const Vec2 to{l->to.z, l->to.x};
            out.push_back({at, to, false, l->movement});
            at = to;
        } else if (const auto* a = std::get_if<Arc>(&e)) {
            const Vec2 c{a->centre.z, a->centre.x}, to{a->to.z, a->to.x};
            const double r = std::hypot(at.x - c.x, at.y - c.y);
            const double a0 = std::atan2(at.y - c.y, at.x - c.x), a1 = std::atan2(to.y - c.y, to.x - c.x);
            double sweep = a->direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
            while (sweep <= 0) sweep += 2 * M_PI;
            const int n = std::max(1, static_cast<int>(sweep / 0.0002));
            for (int k = 1; k <= n; ++k) {
                const double ang = a0 + (a->direction == ArcDirection::ccw ? 1 : -1) * sweep * k / n;
                const Vec2 p = k == n ? to : Vec2{c.x + r * std::cos(ang), c.y + r * std::sin(ang)};
                out.push_back({at, p, false, a->movement});
                at = p;
            }
        }
    }
    return out;
}

// A profile of straight elements as points (Z, radius), Z never rising.
using Points = std::vector<Vec2>;

// The profile's radius at Z z moved by the allowances (the least where a face stands at z);
// infinity outside it. Worked out from the points alone.
double boundary_at(const Points& p, double z, double ax, double az) {
    const double u = z - az;
    double best = INFINITY;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
        const Vec2 a = p[i], b = p[i + 1];
        if (u > a.x + 1e-12 || u < b.x - 1e-12) continue;
        if (std::abs(a.x - b.x) < 1e-12) best = std::min({best, a.y, b.y});
        else best = std::min(best, a.y + (u - a.x) * (b.y - a.y) / (b.x - a.x));
    }
    return best + ax;
}

// The job text of a turn-rough of `p` (radii) from a bar of radius `bar`.
// Written longhand unless `output` says otherwise.
std::string rough_job(const Points& p, double bar, double ax, double az, double doc, const std::string& tool_extra = "",
                      const std::string& op_extra = "", const std::string& output = "longhand") {
    std::string path;
    for (std::size_t i = 1; i < p.size(); ++i)
        path += fmt::format("{}{{\"line\": [{}, {}]}}", i > 1 ? ", " : "", p[i].y, p[i].x);
    return fmt::format(R"({{"clearance": 20, "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000{}}}],
  "operations": [{{"type": "turn-rough", "tool": 1, "compensation": "none", "feed": 200, "output": "{}", "xValues": "radius", "startX": {}, "allowanceX": {},
                  "allowanceZ": {}, "depthOfCut": {}, "start": [{}, {}], "path": [{}]{}}}]}})",
                       tool_extra, output, bar, ax, az, doc, p[0].y, p[0].x, path, op_extra);
}

// The JSON of a turn-rough of `p` (radii) with the tool of rough_job, without startX: camgen's own
// passes (longhand) unless `extra` gives another output.
std::string rough_op(const Points& p, double ax, double az, double doc, const std::string& extra = "") {
    std::string path;
    for (std::size_t i = 1; i < p.size(); ++i)
        path += fmt::format("{}{{\"line\": [{}, {}]}}", i > 1 ? ", " : "", p[i].y, p[i].x);
    const std::string output = extra.find("\"output\"") == std::string::npos ? R"("output": "longhand", )" : "";
    return fmt::format(R"({{"type": "turn-rough", "tool": 1, {}"compensation": "none", "feed": 200, "xValues": "radius",
                  "allowanceX": {}, "allowanceZ": {}, "depthOfCut": {}, "start": [{}, {}], "path": [{}]{}}})",
                       output, ax, az, doc, p[0].y, p[0].x, path, extra);
}

// A job on a bar of radius `bar` whose face is at face_z, with these operations.
std::string bar_job(double bar, double face_z, const std::string& operations, const std::string& tool_extra = "") {
    return fmt::format(R"({{"clearance": 20, "stock": {{"bar": {{"diameter": {}, "length": 80, "faceZ": {}}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000{}}}],
  "operations": [{}]}})",
                       2 * bar, face_z, tool_extra, operations);
}

// The tip moves of the operation at `index` of a job (between its OperationStart and End).
std::vector<TipMove> operation_moves(const Job& job, const std::string& path) {
    std::vector<TipMove> out;
    Vec2 at{job.clearance, 0.0};
    bool in = false;
    for (const Event& e : expand_job(job)) {
        if (const auto* s = std::get_if<OperationStart>(&e)) in = s->path == path;
        Vec2 to = at;
        bool rapid = false;
        Movement movement = Movement::cutting;
        if (const auto* r = std::get_if<Rapid>(&e)) to = {r->to.z, r->to.x}, rapid = true;
        else if (const auto* l = std::get_if<Linear>(&e)) to = {l->to.z, l->to.x}, movement = l->movement;
        else if (const auto* a = std::get_if<Arc>(&e)) to = {a->to.z, a->to.x}, movement = a->movement;
        else continue;
        if (in) out.push_back({at, to, rapid, movement});
        at = to;
    }
    return out;
}

// A random profile from Z0 towards -Z: `undercuts` lets the radius fall.
Points random_profile(std::mt19937& rng, bool undercuts, double bar) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Points p{{0.0, 2.0 + 4.0 * u(rng)}};
    const int n = 3 + static_cast<int>(u(rng) * 5);
    bool last_vertical = true;
    for (int i = 0; i < n; ++i) {
        const Vec2 a = p.back();
        const double kind = u(rng);
        double dz = -(0.5 + 5.0 * u(rng)), dr = 0.0;
        // Faces rise only; falls stay within 48 degrees, which a 35-degree insert in a 93-degree
        // holder follows (it clears 52).
        if (kind < 0.3 && !last_vertical) dz = 0.0, dr = 0.5 + 3 * u(rng);
        else if (kind < 0.7) dr = 3.0 * u(rng);
        if (undercuts && dz < 0 && u(rng) < 0.4) dr = -std::min(3.0 * u(rng), 1.1 * -dz);
        const double r = std::clamp(a.y + dr, 1.0, bar - 1.0);
        if (std::abs(r - a.y) < 1e-3 && dz == 0.0) continue;
        p.push_back({a.x + dz, r});
        last_vertical = dz == 0.0;
    }
    if (p.size() < 2) p.push_back({p[0].x - 3, p[0].y});
    return p;
}

// What the checks of one roughing found.
struct RoughCheck {
    double deepest_gouge = 0.0;   // the most any feed went below the boundary (or the bar past its end), mm
    double most_left = 0.0;       // the most the boundary was missed by, at any Z of it, mm
    double rapid_in_material = 0.0;  // the most a rapid ran below what the moves before it left, mm
    int rapids_without_lift = 0;  // rapids straight after a cutting feed, without a lift off it
};

// `bar_top`: the bar's face (default: the boundary's start).
RoughCheck check_rough(const Points& p, double bar, double ax, double az, const std::vector<TipMove>& moves,
                       double bar_top = NAN) {
    RoughCheck c;
    const double z_hi = p.front().x + az, z_lo = p.back().x + az;
    if (std::isnan(bar_top)) bar_top = z_hi;
    // The material, as a radius every 0.01 mm of Z, the bar up to its face.
    const double g0 = z_lo - 5.0, dz = 0.01;
    const int cells = static_cast<int>((std::max(z_hi, bar_top) + 5.0 - g0) / dz);
    std::vector<double> material(cells);
    for (int i = 0; i < cells; ++i) material[i] = g0 + (i + 0.5) * dz <= bar_top ? bar : 0.0;
    auto z_of = [&](int i) { return g0 + (i + 0.5) * dz; };
    std::vector<double> reached(cells, INFINITY);
    for (std::size_t m = 0; m < moves.size(); ++m) {
        const TipMove& mv = moves[m];
        const double lo = std::min(mv.from.x, mv.to.x), hi = std::max(mv.from.x, mv.to.x);
        const int i0 = std::max(0, static_cast<int>(std::ceil((lo - g0) / dz - 0.5)));
        const int i1 = std::min(cells - 1, static_cast<int>(std::floor((hi - g0) / dz - 0.5)));
        for (int i = i0; i <= i1; ++i) {
            const double z = z_of(i);
            const double t = hi - lo < 1e-12 ? 0.0 : (z - mv.from.x) / (mv.to.x - mv.from.x);
            const double r = mv.from.y + t * (mv.to.y - mv.from.y);
            if (mv.rapid) {
                c.rapid_in_material = std::max(c.rapid_in_material, material[i] - r);
                continue;
            }
            const double b = z < z_lo ? bar : z > z_hi ? 0.0 : boundary_at(p, z, ax, az);
            c.deepest_gouge = std::max(c.deepest_gouge, b - r);
            reached[i] = std::min(reached[i], r);
            material[i] = std::min(material[i], r);
        }
        if (mv.rapid && hi - lo < 1e-12) {
            // Straight in X: against the material either side of its Z.
            const int i = static_cast<int>(std::floor((mv.to.x - g0) / dz - 0.5));
            if (i >= 0 && i + 1 < cells)
                c.rapid_in_material =
                    std::max(c.rapid_in_material, std::min(material[i], material[i + 1]) - std::min(mv.from.y, mv.to.y));
        }
        if (mv.rapid && m > 0 && !moves[m - 1].rapid && moves[m - 1].movement != Movement::lead_out) ++c.rapids_without_lift;
    }
    for (int i = 0; i < cells; ++i) {
        const double z = z_of(i);
        if (z <= z_lo + 0.02 || z >= z_hi - 0.02) continue;
        c.most_left = std::max(c.most_left, reached[i] - boundary_at(p, z, ax, az));
    }
    return c;
}

// The checks of a roughing along X, on the material as rows of radius: a feed along -X at a Z
// takes what lies above it (towards +Z) on the rows it crosses, as the insert's body stands
// there; each row keeps its top Z. The boundary's top at a row is worked out from the points:
// the highest Z where the boundary (moved by the allowances) stands above the row, the end face
// below.
RoughCheck check_rough_x(const Points& p, double bar, double ax, double az, const std::vector<TipMove>& moves,
                         double bar_top = NAN) {
    RoughCheck c;
    const double z_hi = p.front().x + az, z_lo = p.back().x + az, dr = 0.01;
    const int rows = static_cast<int>(bar / dr);  // rows beyond the bar hold no material
    auto r_of = [&](int i) { return (i + 0.5) * dr; };
    std::vector<double> top(rows, std::isnan(bar_top) ? z_hi : bar_top);
    // The highest Z at which the kept part reaches the row's radius.
    auto keep_top = [&](double r) {
        if (r < boundary_at(p, z_hi, ax, az)) return z_hi;
        double best = z_lo;
        for (std::size_t i = 0; i + 1 < p.size(); ++i) {
            const double r0 = p[i].y + ax, r1 = p[i + 1].y + ax;
            if ((r0 - r) * (r1 - r) > 0 || std::abs(r1 - r0) < 1e-12) continue;
            best = std::max(best, p[i].x + az + (r - r0) / (r1 - r0) * (p[i + 1].x - p[i].x));
        }
        return best;
    };
    for (std::size_t m = 0; m < moves.size(); ++m) {
        const TipMove& mv = moves[m];
        const double lo = std::min(mv.from.y, mv.to.y), hi = std::max(mv.from.y, mv.to.y);
        if (!mv.rapid) {
            // The tip against the boundary, every 0.005 mm along the move.
            const double len = std::hypot(mv.to.x - mv.from.x, mv.to.y - mv.from.y);
            const int n = std::max(1, static_cast<int>(len / 0.005));
            for (int k = 0; k <= n; ++k) {
                const double t = static_cast<double>(k) / n;
                const double z = mv.from.x + t * (mv.to.x - mv.from.x), r = mv.from.y + t * (mv.to.y - mv.from.y);
                const double b = z < z_lo - 1e-9 ? bar : z > z_hi + 1e-9 ? 0.0 : boundary_at(p, z, ax, az);
                c.deepest_gouge = std::max(c.deepest_gouge, b - r);
            }
        }
        if (hi - lo < 1e-12) {
            if (mv.rapid) {
                // Straight along Z: against the rows either side of its radius.
                const int i = static_cast<int>(std::floor(mv.to.y / dr - 0.5));
                if (i >= 0 && i + 1 < rows)
                    c.rapid_in_material =
                        std::max(c.rapid_in_material, std::min(top[i], top[i + 1]) - std::min(mv.from.x, mv.to.x));
            }
        } else {
            const int i0 = std::max(0, static_cast<int>(std::ceil(lo / dr - 0.5)));
            const int i1 = std::min(rows - 1, static_cast<int>(std::floor(hi / dr - 0.5)));
            for (int i = i0; i <= i1; ++i) {
                const double z = mv.from.x + (r_of(i) - mv.from.y) / (mv.to.y - mv.from.y) * (mv.to.x - mv.from.x);
                if (mv.rapid) c.rapid_in_material = std::max(c.rapid_in_material, top[i] - z);
                else top[i] = std::min(top[i], z);
            }
        }
        if (mv.rapid && m > 0 && !moves[m - 1].rapid && moves[m - 1].movement != Movement::lead_out) ++c.rapids_without_lift;
    }
    double least = INFINITY;
    for (double z = z_lo; z <= z_hi; z += 0.01) least = std::min(least, boundary_at(p, z, ax, az));
    for (int i = 0; i < rows; ++i) {
        const double r = r_of(i);
        if (r <= least + 0.02 || r >= bar - 0.02) continue;
        c.most_left = std::max(c.most_left, top[i] - keep_top(r));
    }
    return c;
}

}  // namespace

TEST_CASE("lathe tools: noseRadius, orientation, insert angles, width and profileAngle belong to their types") {
    Job job = read_job(tool_job(R"({"number": 1, "type": "turning-tool", "noseRadius": 0.8, "rpm": 900})"), "t.json");
    CHECK(job.tools.at(1).diameter == doctest::Approx(1.6));
    CHECK(job.tools.at(1).nose_radius == doctest::Approx(0.8));
    CHECK(job.tools.at(1).orientation == 2);  // the default: outside, towards the chuck
    job = read_job(tool_job(R"({"number": 1, "type": "turning-tool", "diameter": 0.8, "orientation": 3, "rpm": 900,
                                "insertAngle": 55, "approachAngle": 93})"),
                   "t.json");
    CHECK(job.tools.at(1).nose_radius == doctest::Approx(0.4));
    CHECK(job.tools.at(1).orientation == 3);
    CHECK(*job.tools.at(1).insert_angle == 55);
    job = read_job(tool_job(R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 500})"), "t.json");
    CHECK(job.tools.at(1).width == 3);
    CHECK(job.tools.at(1).diameter == 3);
    job = read_job(tool_job(R"({"number": 1, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 500})"), "t.json");
    CHECK(*job.tools.at(1).profile_angle == 60);

    CHECK(refusal(tool_job(R"({"number": 1, "type": "drill", "diameter": 5, "noseRadius": 0.4, "rpm": 900})"))
              .find("/tools/0/noseRadius: noseRadius is for a turning-tool or threading-tool, not a drill") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "end-mill", "diameter": 5, "orientation": 2, "rpm": 900})"))
              .find("/tools/0/orientation: orientation is for a lathe tool") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "turning-tool", "diameter": 0.8, "orientation": 10, "rpm": 900})"))
              .find("/tools/0/orientation:") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "turning-tool", "diameter": 0.8, "insertAngle": 80, "rpm": 900})"))
              .find("/tools/0/approachAngle: a turning-tool's insertAngle and approachAngle go together") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "turning-tool", "diameter": 0.8, "insertAngle": 90, "approachAngle": 95, "rpm": 900})"))
              .find("/tools/0/insertAngle: insertAngle 90 plus approachAngle 95") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "turning-tool", "noseRadius": 0.4, "diameter": 1, "rpm": 900})"))
              .find("/tools/0/noseRadius: noseRadius 0.400 mm and diameter 1.000 mm disagree") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "grooving-tool", "diameter": 3, "rpm": 900})"))
              .find("/tools/0/width: a grooving-tool needs its width") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "turning-tool", "diameter": 1, "width": 3, "rpm": 900})"))
              .find("/tools/0/width: width is for a grooving-tool or parting-tool, not a turning-tool") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "threading-tool", "diameter": 0.2, "rpm": 900})"))
              .find("/tools/0/profileAngle: a threading-tool needs its profileAngle") != std::string::npos);
    CHECK(refusal(tool_job(R"({"number": 1, "type": "turning-tool", "diameter": 1, "profileAngle": 60, "rpm": 900})"))
              .find("/tools/0/profileAngle: profileAngle is for a threading-tool, not a turning-tool") != std::string::npos);
}

TEST_CASE("turn-face: equal passes to z, each fed across to the axis, lifted off in Z and X, returned above the face") {
    const Job job = read_job(R"({"clearance": 20, "stock": {"bar": {"diameter": 40, "length": 50, "faceZ": 1.2}},
  "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.8, "rpm": 1000}],
  "operations": [{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.5}]})",
                             "face.json");
    const std::vector<TipMove> moves = tip_moves(job);
    std::vector<double> passes;
    for (std::size_t i = 0; i < moves.size(); ++i) {
        const TipMove& m = moves[i];
        if (m.rapid || m.movement != Movement::cutting) continue;
        // Across the face at one Z from outside the bar (radius 20 + 1) in past the axis by the
        // nose radius 0.8 (the nose's centre on the axis: no nub left).
        CHECK(m.from.x == doctest::Approx(m.to.x));
        CHECK(m.from.y == doctest::Approx(21));
        CHECK(m.to.y == doctest::Approx(-0.8));
        passes.push_back(m.to.x);
        // Then off the face: +Z and +X by the lift, and only then a rapid, above the face.
        REQUIRE(i + 2 < moves.size());
        const TipMove& lift = moves[i + 1];
        CHECK_FALSE(lift.rapid);
        CHECK(lift.to.x == doctest::Approx(m.to.x + 0.5));
        CHECK(lift.to.y == doctest::Approx(-0.3));
        CHECK(moves[i + 2].rapid);
        CHECK(moves[i + 2].to.x == doctest::Approx(m.to.x + 0.5));
        CHECK(moves[i + 2].to.y == doctest::Approx(21));
    }
    REQUIRE(passes.size() == 3);  // 1.2 mm in passes of at most 0.5
    CHECK(passes[0] == doctest::Approx(0.8));
    CHECK(passes[1] == doctest::Approx(0.4));
    CHECK(passes[2] == doctest::Approx(0.0));
    CHECK(refusal(R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.8, "rpm": 1000}],
  "operations": [{"type": "turn-face", "tool": 1, "feed": 150, "z": 0}]})")
              .find("/operations/0/outerX: give outerX") != std::string::npos);
    CHECK(refusal(R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.8, "orientation": 3, "rpm": 1000}],
  "operations": [{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "outerX": 30, "startZ": 1}]})")
              .find("/operations/0/tool: a turn-face needs a turning-tool of orientation 2") != std::string::npos);
}

TEST_CASE("turn-rough: random rising profiles and profiles with undercuts are roughed to exactly the allowances") {
    std::mt19937 rng(30);
    const double bar = 15.0;
    int cases = 0;
    double worst_gouge = 0, worst_left = 0, worst_rapid = 0;
    for (int n = 0; n < 120; ++n) {
        const bool undercuts = n % 2 == 1;
        const Points p = random_profile(rng, undercuts, bar - 0.5);
        const double ax = (n % 3) * 0.2, az = (n % 4) * 0.05, doc = 0.7 + (n % 5) * 0.4;
        const std::string text =
            rough_job(p, bar, ax, az, doc, undercuts ? R"(, "insertAngle": 35, "approachAngle": 93)" : "");
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "rough.json"));
        const RoughCheck c = check_rough(p, bar, ax, az, tip_moves(job));
        CHECK(c.deepest_gouge <= 1e-9);
        CHECK(c.most_left <= 1e-6);
        CHECK(c.rapid_in_material <= 1e-9);
        CHECK(c.rapids_without_lift == 0);
        worst_gouge = std::max(worst_gouge, c.deepest_gouge);
        worst_left = std::max(worst_left, c.most_left);
        worst_rapid = std::max(worst_rapid, c.rapid_in_material);
        ++cases;
    }
    MESSAGE("turn-rough: " << cases << " random profiles; worst gouge " << worst_gouge << " mm, worst left beyond the "
                           << "allowance " << worst_left << " mm, worst rapid into material " << worst_rapid << " mm");
}

TEST_CASE("turn-rough canned: the control's G71 passes on random rising profiles leave exactly the allowances, rapids in air") {
    // The same checks on the moves of the roughing cycle (TurnCycle, LinuxCNC's G71 as camgen
    // models it): its escapes off each pass are rapids at 45 degrees, not feeds, so only the
    // rapids' air is checked, not a lift before them.
    std::mt19937 rng(31);
    const double bar = 15.0;
    int canned = 0;
    double worst_gouge = 0, worst_left = 0, worst_rapid = 0;
    for (int n = 0; n < 120; ++n) {
        const Points p = random_profile(rng, false, bar - 0.5);
        const double ax = (n % 3) * 0.2, az = (n % 4) * 0.05, doc = 0.7 + (n % 5) * 0.4;
        const std::string text = rough_job(p, bar, ax, az, doc, "", "", "auto");
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "rough.json"));
        bool cycle = false;
        for (const Event& e : expand_job(job))
            if (const auto* c = std::get_if<TurnCycle>(&e); c && !c->refusal) cycle = true;
        canned += cycle ? 1 : 0;
        const RoughCheck c = check_rough(p, bar, ax, az, tip_moves(job));
        CHECK(c.deepest_gouge <= 1e-9);
        CHECK(c.most_left <= 1e-6);
        CHECK(c.rapid_in_material <= 1e-9);
        worst_gouge = std::max(worst_gouge, c.deepest_gouge);
        worst_left = std::max(worst_left, c.most_left);
        worst_rapid = std::max(worst_rapid, c.rapid_in_material);
    }
    CHECK(canned >= 100);
    MESSAGE("turn-rough canned: " << canned << " of 120 random rising profiles as a roughing cycle; worst gouge " << worst_gouge
                                  << " mm, worst left beyond the allowance " << worst_left << " mm, worst rapid into material "
                                  << worst_rapid << " mm");
}

TEST_CASE("turn-rough: the check finds a pass 0.1 mm into the allowance and a rapid through material") {
    const Points p{{0, 5}, {-10, 5}, {-10, 10}, {-20, 10}};
    Job job = read_job(rough_job(p, 15, 0.3, 0.1, 1.0), "rough.json");
    std::vector<TipMove> moves = tip_moves(job);
    REQUIRE(check_rough(p, 15, 0.3, 0.1, moves).deepest_gouge <= 1e-9);
    // One feed along Z 0.1 mm deeper: found.
    std::vector<TipMove> deeper = moves;
    for (TipMove& m : deeper)
        if (!m.rapid && m.movement == Movement::cutting && std::abs(m.from.y - m.to.y) < 1e-12 && std::abs(m.to.y - 5.3) < 1e-9) {
            m.from.y -= 0.1, m.to.y -= 0.1;
            break;
        }
    CHECK(check_rough(p, 15, 0.3, 0.1, deeper).deepest_gouge == doctest::Approx(0.1));
    // The first return made at the pass's own level rather than lifted: through material.
    std::vector<TipMove> low = moves;
    for (std::size_t i = 1; i < low.size(); ++i)
        if (low[i].rapid && low[i - 1].movement == Movement::lead_out) {
            low[i].from.y -= 2.0, low[i].to.y -= 2.0;
            break;
        }
    CHECK(check_rough(p, 15, 0.3, 0.1, low).rapid_in_material > 0.4);
}

TEST_CASE("turn-rough: the sample shaft's profile with an arc, allowances on the diameter; refusals") {
    const Job job = read_job(R"({"clearance": 20, "stock": {"bar": {"diameter": 44, "length": 70}},
  "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.8, "insertAngle": 80, "approachAngle": 95, "rpm": 1000}],
  "operations": [{"type": "turn-rough", "tool": 1, "compensation": "none", "feed": 200, "depthOfCut": 1.5, "allowanceX": 0.4, "allowanceZ": 0.1,
                  "start": [24, 0], "path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]},
                  {"arc": {"end": [40, -25], "centre": [40, -20], "direction": "cw"}}, {"line": [40, -40]}]}]})",
                             "shaft.json");
    const std::vector<TipMove> moves = tip_moves(job);
    // Independently: the boundary is the profile 0.2 out (radius) and 0.1 towards +Z.
    auto boundary = [](double z) {
        const double u = z - 0.1;
        double r;
        if (u > -1) r = 14 + (0 - u);
        else if (u > -20) r = 15;
        else if (u > -25) r = 20 - std::sqrt(std::max(0.0, 25 - (u + 20) * (u + 20)));
        else r = 20;
        return r + 0.2;
    };
    double gouge = 0, left = 0;
    for (double z = -39.85; z < 0.05; z += 0.013) {
        double reached = INFINITY;
        for (const TipMove& m : moves) {
            if (m.rapid) continue;
            const double lo = std::min(m.from.x, m.to.x), hi = std::max(m.from.x, m.to.x);
            if (z < lo || z > hi || hi - lo < 1e-12) continue;
            const double r = m.from.y + (z - m.from.x) / (m.to.x - m.from.x) * (m.to.y - m.from.y);
            reached = std::min(reached, r);
        }
        gouge = std::max(gouge, boundary(z) - reached);
        left = std::max(left, reached - boundary(z));
    }
    MESSAGE("shaft roughing: worst gouge " << gouge << " mm, worst left " << left << " mm beyond the allowance");
    CHECK(gouge <= 1e-6);
    CHECK(left <= 1e-3);  // the arc's chords in this test
    // Every pass takes at most depthOfCut (1.5 mm radial): the levels from the bar (22) down.
    std::vector<double> levels;
    for (const TipMove& m : moves)
        if (!m.rapid && m.movement == Movement::cutting && std::abs(m.from.y - m.to.y) < 1e-12 && m.to.x < m.from.x)
            levels.push_back(m.to.y);
    levels.erase(std::unique(levels.begin(), levels.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }), levels.end());
    REQUIRE(levels.size() >= 2);
    CHECK(22 - levels.front() <= 1.5 + 1e-9);
    for (std::size_t i = 1; i < levels.size(); ++i)
        if (levels[i] < levels[i - 1]) CHECK(levels[i - 1] - levels[i] <= 1.5 + 1e-9);

    const std::string tool = R"({"number": 1, "type": "turning-tool", "noseRadius": 0.8, "insertAngle": 80, "approachAngle": 95, "rpm": 1000})";
    CHECK(refusal(R"({"clearance": 20, "tools": [)" + tool + R"(], "operations": [{"type": "turn-rough", "tool": 1,
  "feed": 200, "depthOfCut": 1, "startX": 40, "start": [20, 0], "path": [{"line": [20, -5]}, {"line": [10, -10]}, {"line": [10, -20]}]}]})")
              .find("/operations/0/path/1: this element falls towards the chuck at 45.0 degrees, and tool 1's insert (80 "
                    "degrees in a 95 degree holder) clears only 5.0") != std::string::npos);
    CHECK(refusal(R"({"clearance": 20, "tools": [)" + tool + R"(], "operations": [{"type": "turn-rough", "tool": 1,
  "feed": 200, "depthOfCut": 1, "startX": 40, "start": [20, 0], "path": [{"line": [20, -5]}, {"line": [30, -2]}]}]})")
              .find("/operations/0/path/1: this element turns back towards +Z") != std::string::npos);
    CHECK(refusal(R"({"clearance": 20, "tools": [)" + tool + R"(], "operations": [{"type": "turn-rough", "tool": 1,
  "feed": 200, "depthOfCut": 1, "start": [20, 0], "path": [{"line": [20, -5]}]}]})")
              .find("/operations/0/startX: give startX") != std::string::npos);
    // A 35-degree insert in a 93-degree holder clears 52 degrees: the same 45-degree fall is cut.
    CHECK(refusal(R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "insertAngle": 35,
  "approachAngle": 93, "rpm": 1000}], "operations": [{"type": "turn-rough", "tool": 1,
  "feed": 200, "depthOfCut": 1, "startX": 40, "start": [20, 0], "path": [{"line": [20, -5]}, {"line": [10, -10]}, {"line": [10, -20]}]}]})")
              .empty());
}

TEST_CASE("turn-profile: rapids to approachDistance before the start, lifts off the end before it rapids") {
    const Job job = read_job(R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}],
  "operations": [{"type": "turn-profile", "tool": 1, "compensation": "none", "feed": 100, "start": [24, 0], "retractX": 44,
                  "path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]}, {"line": [40, -20]}, {"line": [40, -40]}]}]})",
                             "finish.json");
    const std::vector<TipMove> moves = tip_moves(job);
    REQUIRE(moves.size() >= 9);
    // In: a rapid along Z to 1 mm before the start, then 1 mm of feed.
    CHECK(moves[0].rapid);
    CHECK(moves[0].to.x == doctest::Approx(1.0));
    CHECK(moves[0].to.y == doctest::Approx(12.0));
    CHECK_FALSE(moves[1].rapid);
    CHECK(moves[1].to.x == doctest::Approx(0.0));
    // Out: off the finished D40 by 0.5 mm at 45 degrees (+Z, +X), then rapids.
    const std::size_t n = moves.size();
    CHECK_FALSE(moves[n - 3].rapid);
    CHECK(moves[n - 3].movement == Movement::lead_out);
    CHECK(moves[n - 3].to.x == doctest::Approx(-40 + 0.5 / std::sqrt(2.0)));
    CHECK(moves[n - 3].to.y == doctest::Approx(20 + 0.5 / std::sqrt(2.0)));
    CHECK(moves[n - 2].rapid);
    CHECK(moves[n - 2].to.y == doctest::Approx(22));
    CHECK(moves[n - 1].rapid);
    CHECK(moves[n - 1].to.x == doctest::Approx(20));
    // A facing profile (the issue's: Z0 in to the axis) no longer returns across the face at
    // feed: it lifts off (+Z) and rapids.
    const Job face = read_job(R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000}],
  "operations": [{"type": "turn-profile", "tool": 1, "compensation": "none", "feed": 100, "start": [34, 0], "retractX": 34, "path": [{"line": [0, 0]}]}]})",
                              "face.json");
    const std::vector<TipMove> f = tip_moves(face);
    REQUIRE(f.size() >= 3);
    const TipMove& lift = f[f.size() - 3];
    CHECK(lift.to.x > 0.3);  // off the face
    for (std::size_t i = 0; i < f.size(); ++i)
        if (!f[i].rapid && f[i].movement != Movement::lead_out && f[i].movement != Movement::lead_in) {
            // Cutting moves only at Z0, inwards.
            CHECK(f[i].to.x == doctest::Approx(0));
            CHECK(f[i].to.y <= f[i].from.y);
        }
    CHECK(f.back().rapid);
}

TEST_CASE("turn-profile: a slope the insert cannot follow is refused at its element") {
    CHECK(refusal(R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "insertAngle": 55,
  "approachAngle": 93, "rpm": 1000}], "operations": [{"type": "turn-profile", "tool": 1, "compensation": "none", "feed": 100, "start": [20, 0],
  "retractX": 30, "path": [{"line": [20, -5]}, {"line": [12, -7]}, {"line": [12, -10]}]}]})")
              .find("/operations/0/path/1: this element falls towards the chuck at 63.4 degrees, and tool 1's insert (55 "
                    "degrees in a 93 degree holder) clears only 32.0") != std::string::npos);
    // Without insert angles nothing is checked, and a note says so.
    CHECK(refusal(R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 1000}],
  "operations": [{"type": "turn-profile", "tool": 1, "compensation": "none", "feed": 100, "start": [20, 0], "retractX": 30,
  "path": [{"line": [20, -5]}, {"line": [12, -7]}, {"line": [12, -10]}]}]})")
              .empty());
}

TEST_CASE("turn-rough along X: random rising profiles and profiles with undercuts are roughed to exactly the allowances") {
    std::mt19937 rng(72);
    const double bar = 15.0;
    int cases = 0, passes = 0;
    double worst_gouge = 0, worst_left = 0, worst_rapid = 0;
    for (int n = 0; n < 120; ++n) {
        const bool undercuts = n % 2 == 1;
        const Points p = random_profile(rng, undercuts, bar - 0.5);
        const double ax = (n % 3) * 0.2, az = (n % 4) * 0.05, doc = 0.7 + (n % 5) * 0.4;
        const std::string text = rough_job(p, bar, ax, az, doc, undercuts ? R"(, "insertAngle": 35, "approachAngle": 93)" : "",
                                           R"(, "direction": "x")");
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "rough.json"));
        const std::vector<TipMove> moves = tip_moves(job);
        const RoughCheck c = check_rough_x(p, bar, ax, az, moves);
        CHECK(c.deepest_gouge <= 1e-9);
        CHECK(c.most_left <= 1e-6);
        CHECK(c.rapid_in_material <= 1e-9);
        CHECK(c.rapids_without_lift == 0);
        // Every pass feeds along -X at one Z, the levels at most depthOfCut apart from the start.
        double above = p.front().x + az;
        for (const TipMove& m : moves) {
            if (m.rapid || m.movement != Movement::cutting || std::abs(m.from.x - m.to.x) > 1e-12 || m.from.y < bar) continue;
            CHECK(m.to.y < m.from.y);
            CHECK(above - m.to.x <= doc + 1e-9);
            above = m.to.x;
            ++passes;
        }
        CHECK(above - (p.back().x + az) <= doc + 1e-9);
        worst_gouge = std::max(worst_gouge, c.deepest_gouge);
        worst_left = std::max(worst_left, c.most_left);
        worst_rapid = std::max(worst_rapid, c.rapid_in_material);
        ++cases;
    }
    MESSAGE("turn-rough along X: " << cases << " random profiles, " << passes << " passes; worst gouge " << worst_gouge
                                   << " mm, worst left beyond the allowance " << worst_left << " mm, worst rapid into material "
                                   << worst_rapid << " mm");
}

TEST_CASE("turn-rough along X: the check finds a pass 0.1 mm into the allowance, a low return and a pass left out") {
    const Points p{{0, 5}, {-10, 5}, {-10, 10}, {-20, 10}};
    const std::string dir = R"(, "direction": "x")";
    const Job job = read_job(rough_job(p, 15, 0.3, 0.1, 1.0, "", dir), "rough.json");
    const std::vector<TipMove> moves = tip_moves(job);
    REQUIRE(check_rough_x(p, 15, 0.3, 0.1, moves).deepest_gouge <= 1e-9);
    REQUIRE(check_rough_x(p, 15, 0.3, 0.1, moves).rapid_in_material <= 1e-9);
    // The levels: 20 mm in 20 steps of 1 from Z 0.1, the last left to the pass along the boundary.
    std::vector<double> levels;
    for (const TipMove& m : moves)
        if (!m.rapid && m.movement == Movement::cutting && m.from.y > 15 && std::abs(m.from.x - m.to.x) < 1e-12)
            levels.push_back(m.to.x);
    REQUIRE(levels.size() == 20);  // 19 levels and the end face
    CHECK(levels[0] == doctest::Approx(-0.9));
    CHECK(levels[18] == doctest::Approx(-18.9));
    CHECK(levels[19] == doctest::Approx(-19.9));
    // A pass 0.1 mm further in: found.
    std::vector<TipMove> deeper = moves;
    for (TipMove& m : deeper)
        if (!m.rapid && m.movement == Movement::cutting && std::abs(m.to.x + 4.9) < 1e-9) {
            m.to.y -= 0.1;
            break;
        }
    CHECK(check_rough_x(p, 15, 0.3, 0.1, deeper).deepest_gouge == doctest::Approx(0.1));
    // The return made 1 mm below the pass's lift: through the layer below it.
    std::vector<TipMove> low = moves;
    for (std::size_t i = 1; i < low.size(); ++i)
        if (low[i].rapid && low[i - 1].movement == Movement::lead_out) {
            low[i].from.x -= 1.0, low[i].to.x -= 1.0;
            break;
        }
    CHECK(check_rough_x(p, 15, 0.3, 0.1, low).rapid_in_material > 0.4);
    // Without the pass along the boundary the steps stay.
    std::vector<TipMove> no_last(moves.begin(), moves.end() - 8);
    CHECK(check_rough_x(p, 15, 0.3, 0.1, no_last).most_left > 0.5);
    // A lift at 45 degrees off a pass under a 50-degree fall would enter the part: the lift
    // is steeper than the fall.
    const Points fall{{0, 12}, {-5, 12}, {-7, 9.6164}, {-15, 9.6164}};
    const Job steep = read_job(rough_job(fall, 15, 0, 0, 0.8, R"(, "insertAngle": 35, "approachAngle": 93)", dir), "fall.json");
    const std::vector<TipMove> sm = tip_moves(steep);
    CHECK(check_rough_x(fall, 15, 0, 0, sm).deepest_gouge <= 1e-9);
    for (std::size_t i = 1; i < sm.size(); ++i)
        if (sm[i].movement == Movement::lead_out && !sm[i].rapid && sm[i].from.x > -7 && sm[i].from.x < -5) {
            const double dz = sm[i].to.x - sm[i].from.x, dr = sm[i].to.y - sm[i].from.y;
            CHECK(std::atan2(dr, dz) * 180 / M_PI > 50.0);
        }
}

TEST_CASE("turn-rough along X: refusals") {
    CHECK(refusal(rough_job({{0, 5}, {0, 10}}, 15, 0, 0, 1.0, "", R"(, "direction": "x")"))
              .find("/operations/0/direction: along X the passes step down in Z") != std::string::npos);
    CHECK(refusal(rough_job({{0, 5}, {-5, 10}}, 15, 0, 0, 1.0, "", R"(, "direction": "y")"))
              .find("/operations/0/direction:") != std::string::npos);
}

TEST_CASE("turn-rough from what a turn-face left: the passes come in 1 mm before the faced Z0, not the bar's face") {
    // A bar faced from Z3 to Z0; the profile given from Z1 (in air after the face).
    const std::string face = R"({"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 1})";
    const Points p{{1, 12}, {-20, 12}};
    for (const char* stock : {"auto", "bar"}) {
        const Job job = read_job(bar_job(22, 3, std::string(face) + ", " +
                                                    rough_op(p, 0, 0, 2.5, fmt::format(R"(, "stock": "{}")", stock))),
                                 "faced.json");
        const bool from_face = std::string(stock) == "auto";
        const std::vector<TipMove> moves = operation_moves(job, "/operations/1");
        // The cutting feeds along -Z at a level below the bar: each starts where the tip came in.
        // The passes: a feed along -Z straight after a rapid.
        std::vector<double> levels, starts;
        for (std::size_t i = 1; i < moves.size(); ++i) {
            const TipMove& m = moves[i];
            if (moves[i - 1].rapid && !m.rapid && m.movement == Movement::cutting && std::abs(m.from.y - m.to.y) < 1e-12 &&
                m.to.x < m.from.x)
                levels.push_back(m.from.y), starts.push_back(m.from.x);
        }
        // 22 to 12 in 4 steps of 2.5, the last along the boundary.
        REQUIRE(levels.size() == 3);
        CHECK(levels[0] == doctest::Approx(19.5));
        CHECK(levels[2] == doctest::Approx(14.5));
        for (int k = 0; k < 3; ++k) CHECK(starts[k] == doctest::Approx(from_face ? 1.0 : 2.0));
        // The pass along the boundary comes in 1 mm before its start (Z1) either way.
        for (std::size_t i = 1; i < moves.size(); ++i)
            if (moves[i].movement == Movement::lead_in) {
                CHECK(moves[i].from.x == doctest::Approx(2.0));
                CHECK(moves[i].to.x == doctest::Approx(1.0));
            }
        bool noted = false;
        for (const Event& e : expand_job(job))
            if (const auto* s = std::get_if<OperationStart>(&e); s && s->path == "/operations/1")
                for (const std::string& n : s->notes) noted = noted || n.find("roughs from what /operations/0 (turn-face) left") == 0;
        // Only the face moved: the passes come in before it, and no note is said (the note is for
        // earlier operations that took some of the bar over the profile, when "auto" roughs from
        // what they left instead of a roughing cycle from the bar).
        CHECK_FALSE(noted);
    }
}

TEST_CASE("turn-rough \"output\": \"auto\" after earlier operations: a cycle after a face alone, passes from the material after a rough") {
    // The cycle roughs from the bar: worth it where the earlier operations left the whole bar over
    // the profile (a face moves only the face); after an earlier rough over the profile camgen's
    // passes from what it left are written instead, the TurnCycle carrying why (a note where the
    // machine has the cycle).
    const Points first{{0, 15}, {-30, 15}}, second{{0, 12}, {-40, 12}};
    const std::string face = R"({"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 1})";
    auto cycles = [](const Job& job) {
        std::vector<TurnCycle> out;
        for (const Event& e : expand_job(job))
            if (const auto* c = std::get_if<TurnCycle>(&e)) out.push_back(*c);
        return out;
    };
    const std::vector<TurnCycle> faced =
        cycles(read_job(bar_job(22, 3, face + ", " + rough_op(second, 0, 0, 1.5, R"(, "output": "auto")")), "faced.json"));
    REQUIRE(faced.size() == 1);
    CHECK_FALSE(faced[0].refusal);
    CHECK_FALSE(faced[0].moves.empty());
    const std::vector<TurnCycle> twice = cycles(read_job(
        bar_job(22, 0, rough_op(first, 0, 0, 1.5) + ", " + rough_op(second, 0, 0, 1.5, R"(, "output": "auto")")), "twice.json"));
    REQUIRE(twice.size() == 1);
    REQUIRE(twice[0].refusal);
    CHECK(twice[0].refusal->find("the operations before it removed part of the bar over the profile") == 0);
    CHECK(twice[0].moves.empty());
    // Posted for linuxcnc-lathe (which has G71) the note says so; "canned" writes G71 anyway.
    const std::string program = test::post_program(
        read_job(bar_job(22, 0, rough_op(first, 0, 0, 1.5) + ", " + rough_op(second, 0, 0, 1.5, R"(, "output": "canned")")),
                 "canned.json"),
        load_machine("linuxcnc-lathe"));
    CHECK(program.find("G71 Q") != std::string::npos);
}

TEST_CASE("turn-rough from what an earlier turn-rough left: the levels it removed are left out, passes start at its end") {
    // First D30 from Z0 to Z-30, then D24 from Z0 to Z-40: over Z0..Z-30 only 15 down to 12 is
    // left; below Z-30 the whole bar. Both with a nose of 0.4, compensation none.
    const Points first{{0, 15}, {-30, 15}}, second{{0, 12}, {-40, 12}};
    const Job job = read_job(bar_job(22, 0, rough_op(first, 0, 0, 1.5) + ", " + rough_op(second, 0, 0, 1.5)), "twice.json");
    const Job bar = read_job(bar_job(22, 0, rough_op(first, 0, 0, 1.5) + ", " + rough_op(second, 0, 0, 1.5, R"(, "stock": "bar")")),
                             "twice.json");
    auto passes = [](const std::vector<TipMove>& moves) {
        std::vector<Vec2> out;  // (start Z, level) of each feed along -Z straight after a rapid
        for (std::size_t i = 1; i < moves.size(); ++i) {
            const TipMove& m = moves[i];
            if (moves[i - 1].rapid && !m.rapid && m.movement == Movement::cutting && std::abs(m.from.y - m.to.y) < 1e-12 &&
                m.to.x < m.from.x)
                out.push_back({m.from.x, m.from.y});
        }
        return out;
    };
    const std::vector<Vec2> p = passes(operation_moves(job, "/operations/1"));
    const std::vector<Vec2> old = passes(operation_moves(bar, "/operations/1"));
    // The same levels from the bar (22 to 12 in 7 steps of 10/7), each pass along -Z.
    REQUIRE(old.size() == 6);
    REQUIRE(p.size() == 6);
    for (std::size_t k = 0; k < 6; ++k) {
        CHECK(p[k].y == doctest::Approx(22 - 10.0 / 7 * (k + 1)));
        CHECK(old[k].x == doctest::Approx(1.0));
    }
    // Above what the first left at its end (15.4: the nose's round in the corner at Z-30) the
    // passes begin 1 mm before Z-30; below it, 1 mm before Z0.
    for (std::size_t k = 0; k < 4; ++k) CHECK(p[k].x == doctest::Approx(-29.0));
    CHECK(p[4].x == doctest::Approx(1.0));
    CHECK(p[5].x == doctest::Approx(1.0));
    // The same second roughing only over the first's Z: 15 down to 12, two levels of 1.5.
    const Points inside{{0, 12}, {-20, 12}};
    const Job short_job = read_job(bar_job(22, 0, rough_op(first, 0, 0, 1.5) + ", " + rough_op(inside, 0, 0, 1.5)), "twice.json");
    const std::vector<Vec2> q = passes(operation_moves(short_job, "/operations/1"));
    REQUIRE(q.size() == 1);
    CHECK(q[0].y == doctest::Approx(13.5));
    CHECK(q[0].x == doctest::Approx(1.0));
    // A second roughing to the first's own boundary has nothing to take: only the pass along it.
    const Job same = read_job(bar_job(22, 0, rough_op(first, 0, 0, 1.5) + ", " + rough_op(first, 0, 0, 1.5)), "twice.json");
    CHECK(passes(operation_moves(same, "/operations/1")).empty());
}

// Random profiles roughed after an earlier face or rough: the checks of the whole job's moves
// on the bar (the earlier operation's cuts included).
void check_after_earlier(bool along_x) {
    std::mt19937 rng(along_x ? 830 : 30);
    const double bar = 15.0;
    int cases = 0, fewer = 0;
    double worst_gouge = 0, worst_left = 0, worst_rapid = 0;
    const std::string dir = along_x ? R"(, "direction": "x")" : "";
    for (int n = 0; n < 80; ++n) {
        const bool undercuts = n % 2 == 1, faced = n % 4 < 2;
        const Points p = random_profile(rng, undercuts, bar - 2.0);
        const double ax = (n % 3) * 0.2, az = (n % 4) * 0.05, doc = 0.7 + (n % 5) * 0.4;
        const double z_hi = p.front().x + az;
        const std::string tool = undercuts ? R"(, "insertAngle": 35, "approachAngle": 93)" : "";
        // Faced from 0.4 beyond the profile's start to 0.6 within it; or roughed first with 1.3 more
        // on the radius and 0.2 more on faces.
        const double face_z = faced ? z_hi + 0.4 : z_hi;
        const std::string earlier =
            faced ? fmt::format(R"({{"type": "turn-face", "tool": 1, "feed": 150, "z": {}, "stepdown": 0.5}})", z_hi - 0.6)
                  : rough_op(p, ax + 1.3, az + 0.2, doc + 0.3, dir);
        const std::string text = bar_job(bar, face_z, earlier + ", " + rough_op(p, ax, az, doc, dir), tool);
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "after.json"));
        // Faced: the rough's own moves on the bar as the face leaves it (nothing beyond its Z; the
        // face takes some of the profile's length). Roughed first: the whole job's moves.
        const std::vector<TipMove> moves = faced ? operation_moves(job, "/operations/1") : tip_moves(job);
        const double top = faced ? z_hi - 0.6 : face_z;
        const RoughCheck c = along_x ? check_rough_x(p, bar, ax, az, moves, top) : check_rough(p, bar, ax, az, moves, top);
        CHECK(c.deepest_gouge <= 1e-9);
        CHECK(c.most_left <= 1e-6);
        CHECK(c.rapid_in_material <= 1e-9);
        CHECK(c.rapids_without_lift == 0);
        // No more feeding (mm of cutting feeds) than from the whole bar.
        const Job whole = read_job(bar_job(bar, face_z, earlier + ", " + rough_op(p, ax, az, doc, dir + R"(, "stock": "bar")"), tool),
                                   "after.json");
        auto cutting = [](const std::vector<TipMove>& m) {
            double mm = 0;
            for (const TipMove& t : m)
                if (!t.rapid && t.movement == Movement::cutting) mm += std::hypot(t.to.x - t.from.x, t.to.y - t.from.y);
            return mm;
        };
        const double now = cutting(operation_moves(job, "/operations/1")), before = cutting(operation_moves(whole, "/operations/1"));
        CHECK(now <= before + 1e-9);
        // Less after a rough always (its passes begin where the first left more than their
        // level, or outside what it left); after a face along Z (the passes begin 1 mm before
        // the faced end), while along X the face leaves the whole bar below it.
        if (!faced || !along_x) CHECK(now < before - 1e-6);
        fewer += now < before - 1e-6;
        worst_gouge = std::max(worst_gouge, c.deepest_gouge);
        worst_left = std::max(worst_left, c.most_left);
        worst_rapid = std::max(worst_rapid, c.rapid_in_material);
        ++cases;
    }
    MESSAGE(std::string(along_x ? "turn-rough along X" : "turn-rough") << " after a face or a rough: " << cases << " random profiles ("
                         << fewer << " feeding less than from the whole bar); worst gouge " << worst_gouge
                         << " mm, worst left " << worst_left << " mm, worst rapid into material " << worst_rapid << " mm");
    CHECK(fewer >= cases / 2);
}

TEST_CASE("turn-rough after a face or a rough, random profiles: no gouge, nothing left, no rapid into material") {
    check_after_earlier(false);
}

TEST_CASE("turn-rough along X after a face or a rough, random profiles: no gouge, nothing left, no rapid into material") {
    check_after_earlier(true);
}

}  // namespace test_turn_rough