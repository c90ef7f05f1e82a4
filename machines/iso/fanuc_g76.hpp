#pragma once
// Fanuc T's multiple threading cycle G76 in two blocks (0i-TF, G code system A):
//   G76 P(m r a) Q(least depth) R(finishing allowance)
//   G76 X Z R(taper) P(thread height) Q(first depth) F(lead)
// as camgen models it. There is no Fanuc interpreter here to hold this model to: it is the
// operator's manual's description (REFERENCE.md section 10, and public descriptions of the
// cycle), with camgen's reading where the text leaves a choice; tests/unit/test_fanuc_g76.cpp
// holds camgen's posts and reader to it, not the model to a control.
//  - Depths (radial, from the crest): pass n is first x sqrt(n) (constant area); a step below
//    the least depth Q of the first block is made that least; roughing ends with the pass that
//    reaches the height less the finishing allowance d (clamped there), then the m finishing
//    passes cut at the full height k (with d = 0 they are spring passes at k).
//  - One-edge infeed: the tool angle a (80, 60, 55, 30, 29 or 0 degrees) is the flank's; each
//    pass moves along the flank at a/2 from radial: a pass of depth d starts at the start point's
//    Z less d tan(a/2) and ends at Z plus (k - d) tan(a/2), the last one at Z.
//  - Each pass: from the start point (x0, z0) along Z to the pass's start, in along X to its
//    depth, synchronised to its end, out along X to x0, back along Z to the start point; the
//    cycle ends at the start point.
//  - r, the chamfer at the thread's end in 0.1 leads, and the taper R of the second block: camgen
//    writes and reads 0 (a straight thread with a straight runout).
// Words: P(m r a) six digits, two each; Q and P of the second block in least input increments
// without a decimal point (0.001 mm, 0.0001 inch), radial; R(d) a length with a decimal point,
// radial; X the thread's last diameter (the root outside, the major inside), Z its end.
#include <cmath>
#include <vector>

#include "camgen/events/events.hpp"

namespace camgen::iso {

// The tool angles (a of P) the control takes.
inline constexpr int fanuc_g76_tool_angles[] = {80, 60, 55, 30, 29, 0};

// One cycle in internal units (mm, radius): the start point (where the tool stands), the last
// pass's radius x and Z; the height k, the first depth, the least depth, the finishing
// allowance d (all radial), the finishing passes m, the tool angle a (degrees), the lead.
struct FanucG76 {
    double start_x = 0.0, start_y = 0.0, start_z = 0.0;
    double x = 0.0, z = 0.0;
    double k = 0.0, first = 0.0, least = 0.0, finish = 0.0;
    int m = 1;
    int angle = 0;
    double lead = 0.0;
};

// The cumulative radial depths of its passes, the finishing passes included.
inline std::vector<double> fanuc_g76_depths(const FanucG76& g) {
    std::vector<double> out;
    const double rough_end = g.k - g.finish;
    double at = 0.0;
    for (int n = 1; n <= 10000; ++n) {
        double d = g.first * std::sqrt(static_cast<double>(n));
        if (d - at < g.least) d = at + g.least;
        if (d >= rough_end) {
            if (rough_end > at) out.push_back(rough_end);
            break;
        }
        out.push_back(d);
        at = d;
    }
    for (int s = 0; s < g.m; ++s) out.push_back(g.k);
    return out;
}

// Its moves (Rapid and ThreadFeed), from the start point back to it.
inline std::vector<Event> fanuc_g76_moves(const FanucG76& g) {
    std::vector<Event> out;
    const bool external = g.x < g.start_x;
    const double crest = external ? g.x + g.k : g.x - g.k;
    const double t = std::tan(g.angle / 2.0 * 3.14159265358979323846 / 180.0);
    const Vec3 start{g.start_x, g.start_y, g.start_z};
    for (double d : fanuc_g76_depths(g)) {
        const double cut = external ? crest - d : crest + d;
        const double z0 = g.start_z - d * t, z1 = g.z + (g.k - d) * t;
        if (t != 0.0) out.emplace_back(Rapid{{g.start_x, g.start_y, z0}});
        out.emplace_back(Rapid{{cut, g.start_y, z0}});
        out.emplace_back(ThreadFeed{{cut, g.start_y, z1}, g.lead});
        out.emplace_back(Rapid{{g.start_x, g.start_y, z1}});
        out.emplace_back(Rapid{start});
    }
    return out;
}

}  // namespace camgen::iso
