// The way off a turn-profile's end (the lift, the rapid out to retractX): on generated profiles
// that run towards -Z and towards +Z (outside), and inside (bore) profiles, for tool
// orientations 1 to 9, two nose radii, two lifts and compensation none, computer and control,
// the job is refused or its lift and way out keep the nose circle out of the material the
// profile keeps (measured here on its own sampling of the profile, no deeper than the nose is at
// the end of the cut). The tester's left-hand job (a +Z profile ending down a face) is refused,
// a back-turning +Z profile with orientation 1 is accepted (G41 under control compensation).
// A turn-face to the axis runs the nose's centre to the axis (no nub), and a turn-rough after
// it simulates without a crash on the three lathes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/reader/reader.hpp"
#include "reader_support.hpp"
#include "support.hpp"

namespace test_turn_lift {

using namespace camgen;

namespace {

struct P {
    double z, r;
};

// A profile as [x, z] diameters: points joined by lines (arcs are not needed: the lift leaves
// from the last element, whatever it is).
struct Shape {
    std::vector<P> pts;  // (Z, radius), the first the start
    bool inside = false; // a bore: the material lies between it and the bar (radius 25)
};

std::string job_of(const Shape& s, int orientation, double nose, const std::string& comp, double lift, double retract_d) {
    std::string path;
    for (std::size_t i = 1; i < s.pts.size(); ++i)
        path += fmt::format(R"({}{{"line": [{}, {}]}})", i > 1 ? ", " : "", 2 * s.pts[i].r, s.pts[i].z);
    return fmt::format(
        R"({{"clearance": 20, "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": {}, "orientation": {}, "rpm": 1000}}],
  "operations": [{{"type": "turn-profile", "tool": 1, "feed": 100, "compensation": "{}", "lift": {}, "approachDistance": 2,
                  "start": [{}, {}], "retractX": {}, "path": [{}]}}]}})",
        nose, orientation, comp, lift, 2 * s.pts[0].r, s.pts[0].z, retract_d, path);
}

// The tip's offset from the nose centre (LinuxCNC's codes), (Z, radius).
P tip_offset(int o, double r) {
    switch (o) {
    case 1: return {r, -r};
    case 2: return {-r, -r};
    case 3: return {-r, r};
    case 4: return {r, r};
    case 5: return {r, 0};
    case 6: return {0, -r};
    case 7: return {-r, 0};
    case 8: return {0, r};
    default: return {0, 0};
    }
}

// The kept material's outline as camgen takes it: the profile closed through the axis. (An
// inside profile, whose material lies outside it, is not supported and cannot be told from an
// outside one: camgen takes its material to lie inside it too, and refuses an inside tool's lift
// towards the axis.)
std::vector<P> ring_of(const Shape& s) {
    std::vector<P> ring = s.pts;
    const double base = 0.0;
    ring.push_back({s.pts.back().z, base});
    ring.push_back({s.pts.front().z, base});
    return ring;
}

// How deep a nose circle about c reaches into the ring (< 0: clear).
double depth(const std::vector<P>& ring, P c, double r) {
    double best = std::numeric_limits<double>::infinity();
    int crossings = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const P a = ring[i], b = ring[(i + 1) % ring.size()];
        const double dz = b.z - a.z, dr = b.r - a.r, l2 = dz * dz + dr * dr;
        double t = l2 > 0 ? ((c.z - a.z) * dz + (c.r - a.r) * dr) / l2 : 0;
        t = std::clamp(t, 0.0, 1.0);
        best = std::min(best, std::hypot(c.z - a.z - t * dz, c.r - a.r - t * dr));
        // A ray towards -Z.
        if ((a.r > c.r) != (b.r > c.r) && a.z + (c.r - a.r) * dz / dr < c.z) ++crossings;
    }
    return crossings % 2 ? r + best : r - best;
}

P mirrored(P p) { return {-40.0 - p.z, p.r}; }  // about Z-20

std::vector<Shape> shapes() {
    std::vector<Shape> out;
    // Outside, towards -Z: along a diameter, up a shoulder, down a taper, down a face to the
    // axis, up a chamfer, a falling slope at the end.
    const std::vector<std::vector<P>> minus = {
        {{0, 10}, {-30, 10}},
        {{0, 10}, {-15, 10}, {-15, 16}, {-30, 16}},
        {{0, 10}, {-15, 10}, {-15, 16}},
        {{0, 6}, {0, 10}, {-10, 10}, {-20, 14}},
        {{0, 12}, {-20, 12}, {-20, 0.5}},
        {{0, 12}, {-10, 12}, {-20, 8}},
        {{0, 12}, {-10, 12}, {-12, 6}},
        {{0, 12}, {-10, 12}, {-10, 6}},
        {{-5, 14}, {-5, 10}, {-20, 10}, {-22, 12}},
    };
    for (const auto& m : minus) {
        out.push_back({m, false});
        // The mirror image runs towards +Z from the -Z end: its start must be its largest X
        // for the approach along Z to pass above it; the generator keeps those that are.
        Shape s{{}, false};
        for (const P& p : m) s.pts.push_back(mirrored(p));
        out.push_back(s);
    }
    // Reversed: the same outlines travelled the other way.
    for (const auto& m : minus) {
        Shape s{{m.rbegin(), m.rend()}, false};
        out.push_back(s);
    }
    // Inside (bores): towards -Z and +Z.
    out.push_back({{{0, 12}, {-20, 12}}, true});
    out.push_back({{{0, 14}, {0, 12}, {-20, 12}, {-20, 8}}, true});
    out.push_back({{{-20, 12}, {0, 12}}, true});
    out.push_back({{{-20, 8}, {-20, 12}, {0, 12}, {0, 14}}, true});
    return out;
}

}  // namespace

TEST_CASE("turn-profile lift: every orientation, both directions, inside and out: refused or clear of the kept material") {
    int accepted = 0, refused = 0;
    for (const Shape& s : shapes()) {
        const std::vector<P> ring = ring_of(s);
        double top = 0;
        for (const P& p : s.pts) top = std::max(top, p.r);
        for (int o = 1; o <= 9; ++o)
            for (double nose : {0.4, 0.8})
                for (const std::string comp : {"none", "computer", "control"})
                    for (double lift : {0.5, 2.0}) {
                        const std::string text = job_of(s, o, nose, comp, lift, 2 * top + 4);
                        Job j;
                        try {
                            j = read_job(text, "lift.json");
                        } catch (const InputError&) {
                            ++refused;
                            continue;
                        }

                        ++accepted;
                        INFO(text);
                        // The tip's moves from the lift on: the lead-out feed, then rapids.
                        const std::vector<Event> ev = expand_job(j);
                        std::vector<P> tips;
                        bool on = false;
                        P last{0, 0};
                        for (const Event& e : ev) {
                            P to{std::numeric_limits<double>::quiet_NaN(), 0};
                            if (const auto* l = std::get_if<Linear>(&e)) {
                                to = {l->to.z, l->to.x};
                                if (l->movement == Movement::lead_out && !on) on = true, tips.push_back(last);
                            } else if (const auto* r = std::get_if<Rapid>(&e)) {
                                to = {r->to.z, r->to.x};
                            } else if (const auto* a = std::get_if<Arc>(&e)) {
                                to = {a->to.z, a->to.x};
                            }
                            if (std::isnan(to.z)) continue;
                            if (on) tips.push_back(to);
                            last = to;
                        }
                        REQUIRE(tips.size() >= 3);
                        const P off = tip_offset(o, nose);
                        auto centre = [&](P t) { return P{t.z - off.z, t.r - off.r}; };
                        // Under control compensation the lift (G40) starts where the control leaves
                        // the nose: its centre a radius off the last programmed point, square to the
                        // last element, on the air side (right of travel, or left where the profile's
                        // turning sense puts the material on the right).
                        std::vector<P> c_track;
                        for (const P& t : tips) c_track.push_back(centre(t));
                        if (comp == "control") {
                            double twice = 0;
                            for (std::size_t i = 0; i < ring.size(); ++i) {
                                const P a = ring[i], b = ring[(i + 1) % ring.size()];
                                twice += a.z * b.r - b.z * a.r;
                            }
                            const P a = s.pts[s.pts.size() - 2], b = s.pts.back();
                            const double len = std::hypot(b.z - a.z, b.r - a.r);
                            const P right{(b.r - a.r) / len, -(b.z - a.z) / len};
                            const double side = twice < 0 ? -1.0 : 1.0;
                            c_track[0] = {tips[0].z + right.z * side * nose, tips[0].r + right.r * side * nose};
                        }
                        const double allowed = std::max(0.0, depth(ring, c_track[0], nose)) + 0.003;
                        // The lift and the way out (up to the rapid back along Z at retractX).
                        for (std::size_t i = 0; i + 1 < tips.size() && i < 2; ++i) {
                            const P a = c_track[i], b = c_track[i + 1];
                            const int n = std::max(1, static_cast<int>(std::hypot(b.z - a.z, b.r - a.r) / 0.01));
                            double worst = -1e9;
                            for (int k = 0; k <= n; ++k) {
                                const P c{a.z + (b.z - a.z) * k / n, a.r + (b.r - a.r) * k / n};
                                worst = std::max(worst, depth(ring, c, nose));
                            }
                            CHECK_MESSAGE(worst <= allowed, "move " << i << " reaches " << worst << " deep, the end "
                                                                    << allowed);
                        }
                    }
    }
    MESSAGE("accepted " << accepted << ", refused " << refused);
    CHECK(accepted > 300);
    CHECK(refused > 300);
}

TEST_CASE("turn-profile lift: the tester's left-hand profile down a face is refused; a back-turned taper is accepted") {
    const std::string o1 =
        R"({"name":"o1","units":"mm","clearance":20,
 "tools":[{"number":3,"type":"turning-tool","noseRadius":0.4,"orientation":1,"rpm":1200}],
 "operations":[{"type":"turn-profile","tool":3,"feed":0.1,"feedMode":"per-revolution","start":[40,-20],
   "path":[{"line":[40,-5]},{"line":[10,-5]}],"retractX":44,"compensation":"COMP"}]})";
    auto with = [&](const std::string& comp) {
        std::string t = o1;
        t.replace(t.find("COMP"), 4, comp);
        return t;
    };
    for (const std::string comp : {"none", "computer", "control"}) {
        INFO(comp);
        try {
            (void)read_job(with(comp), "o1.json");
            FAIL("accepted");
        } catch (const InputError& e) {
            INFO(e.what());
            if (comp == "none") {
                CHECK(e.path() == "/operations/0/lift");
                CHECK(std::string(e.detail()).find("into the material this profile keeps") != std::string::npos);
            } else {
                // The corner into the face at Z-5 (its material turning from below to -Z) is out
                // of a left-hand tool's reach: the words agree with the angle now.
                CHECK(e.path() == "/operations/0/path/1");
                CHECK(std::string(e.detail()).find("touches this element's surface from +Z and +X (its material lies 224.0 "
                                                   "degrees") != std::string::npos);
            }
        }
    }
    // Back-turning: a taper and a diameter towards +Z, lifted back over the diameter.
    const std::string back =
        R"({"clearance":20,"tools":[{"number":3,"type":"turning-tool","noseRadius":0.4,"orientation":1,"rpm":1200}],
 "operations":[{"type":"turn-profile","tool":3,"feed":100,"start":[40,-20],"approachDistance":2,
   "path":[{"line":[30,-15]},{"line":[30,-5]}],"retractX":44,"compensation":"COMP"}]})";
    for (const std::string comp : {"none", "computer", "control"}) {
        std::string t = back;
        t.replace(t.find("COMP"), 4, comp);
        INFO(comp);
        const Job j = read_job(t, "back.json");
        const auto& op = std::get<TurnProfileOp>(j.operations[0]);
        CHECK(op.material_right);
        CHECK(op.lift_direction.x < 0);
        CHECK(op.lift_direction.y > 0);
        bool left = false;
        for (const Event& e : expand_job(j))
            if (const auto* c = std::get_if<Compensation>(&e)) left = left || c->side == CompensationSide::left;
        CHECK(left == (comp == "control"));
        if (comp == "computer") {
            // The nose runs on the profile's air side: above the diameter 30 (radius 15.4 centre).
            CHECK(op.tip_path.segments.back().end.y == doctest::Approx(15.0));
        }
    }
}

TEST_CASE("turn-face to the axis: the nose centre reaches it; a turn-rough after it simulates without a crash") {
    const std::filesystem::path dir = test::scratch("turn-lift-nub");
    int k = 0;
    for (double nose : {0.4, 0.8, 1.2})
        for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
            const std::string text = fmt::format(
                R"({{"clearance":20,"stock":{{"bar":{{"diameter":44,"length":70,"faceZ":1}}}},
 "tools":[{{"number":4,"type":"turning-tool","noseRadius":{},"orientation":2,"rpm":1000}}],
 "operations":[{{"type":"turn-face","tool":4,"z":0,"feedMode":"per-revolution","feed":0.15}},
  {{"type":"turn-rough","tool":4,"feedMode":"per-revolution","feed":0.25,"depthOfCut":1.5,"start":[0,0],
   "path":[{{"line":[10,0]}},{{"line":[10,-20]}},{{"line":[30,-20]}},{{"line":[30,-30]}}]}}]}})",
                nose);
            INFO(machine << " nose " << nose);
            const Job j = read_job(text, "nub.json");
            CHECK(std::get<TurnFaceOp>(j.operations[0]).tip_end == doctest::Approx(-nose));
            const std::string job = (dir / fmt::format("n{}.json", k)).string();
            const std::string nc = (dir / fmt::format("n{}.nc", k++)).string();
            std::ofstream(job) << text;
            const test::Run posted = test::run({job, "--machine", machine, "-q", "-o", nc});
            REQUIRE_MESSAGE(posted.code == 0, posted.err);
            const test::Run r = test::run({"simulate", nc, "--machine", machine, "--job", job});
            CHECK_MESSAGE(r.code == 0, std::string(r.out + r.err));
            CHECK_MESSAGE(r.out.find("crash") == std::string::npos, r.out);
            CHECK_MESSAGE(r.out.find("  the part is as designed\n") != std::string::npos, r.out);
        }
    // innerX above the axis: the tip stops there.
    const Job j = read_job(
        R"({"clearance":20,"tools":[{"number":4,"type":"turning-tool","noseRadius":0.8,"orientation":2,"rpm":1000}],
 "operations":[{"type":"turn-face","tool":4,"z":0,"startZ":1,"outerX":40,"innerX":10,"feed":50}]})",
        "f.json");
    CHECK(std::get<TurnFaceOp>(j.operations[0]).tip_end == doctest::Approx(5.0));
}

}  // namespace test_turn_lift
