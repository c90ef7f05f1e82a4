#pragma once
// Fanuc T's grooving cycles as camgen models them: G75 (outer and inner diameters, plunges along
// X) and G74 (end face, plunges along Z), the same pattern with X and Z swapped.
// G75 R(e) / G75 X(U) Z(W) P(Δi) Q(Δk) R(Δd) F (Fanuc 0i-TF operator's manual, "Outer diameter /
// internal diameter drilling cycle (G75)", and the public descriptions of the two-block form);
// G74 R(e) / G74 X(U) Z(W) P(Δi) Q(Δk) R(Δd) F ("End face peck drilling cycle (G74)": Δk the
// peck along Z, Δi the shift along X; docs/reference.md lists the sources and what is not
// confirmed). From the start point A where the tool stands: each plunge feeds along the plunge
// axis (G75: X, G74: Z) towards the bottom in pecks (G75: Δi, G74: Δk) counted from A, backing
// off e at rapid between pecks (the next peck feeds the peck + e), the last peck shortened to
// reach the bottom; then out to A's plunge coordinate at rapid, and along the other axis by the
// step (G75: Δk along Z, G74: Δi along X) towards the end point (the last step shortened to reach
// it) for the next plunge; after the last plunge back to A (out to A's plunge coordinate, then
// along the other axis to A). Δd, the relief at the bottom, is not written (0). The post checks
// a GrooveCycle against this model before it writes the cycle; the reader expands a cycle into
// its moves.
#include <algorithm>
#include <cmath>
#include <vector>

#include "camgen/events/events.hpp"

namespace camgen::iso {

// The words of one G75 or G74 in internal units (mm, radius): from the start point (start_x,
// start_z) to the last plunge's bottom (x, z); peck along the plunge axis, step along the other,
// back-off e; feed mm/min. `along_z`: G74, plunging along Z (peck = Δk, step = Δi); else G75,
// plunging along X (peck = Δi, step = Δk).
struct FanucGroove {
    double start_x = 0.0, start_y = 0.0, start_z = 0.0;
    double x = 0.0, z = 0.0;
    double peck = 0.0, step = 0.0, e = 0.0;
    double feed = 0.0;
    bool along_z = false;
};

// The moves the control makes (Rapid and Linear events), from the start point. The bottom may
// lie either side of the start point along the plunge axis (G75: an external groove below the
// start X, an internal one beyond it; the pecks and back-offs mirrored), the end point either
// side along the other; peck and step > 0 (step unused when the end is the start's).
inline std::vector<Event> fanuc_groove_moves(const FanucGroove& g) {
    std::vector<Event> out;
    // d: the plunge axis's coordinate, s: the step axis's.
    const double d0 = g.along_z ? g.start_z : g.start_x, d_end = g.along_z ? g.z : g.x;
    const double s0 = g.along_z ? g.start_x : g.start_z, s_end = g.along_z ? g.x : g.z;
    auto at = [&](double d, double s) { return g.along_z ? Vec3{s, g.start_y, d} : Vec3{d, g.start_y, s}; };
    const double dir = s_end < s0 ? -1.0 : 1.0;
    std::vector<double> ss{s0};
    if (g.step > 0)
        for (int k = 1; dir * (s_end - (s0 + dir * k * g.step)) > 1e-9 && ss.size() < 100000; ++k)
            ss.push_back(s0 + dir * k * g.step);
    if (std::abs(s_end - s0) > 1e-9) ss.push_back(s_end);
    // In the plunge's own direction: p = -1 where the plunge coordinate rises into the material.
    const double p = d_end > d0 ? -1.0 : 1.0;
    for (std::size_t k = 0; k < ss.size(); ++k) {
        if (k > 0) out.emplace_back(Rapid{at(d0, ss[k])});
        std::vector<double> depths;
        if (g.peck > 0)
            for (int n = 1; p * (d0 - p * n * g.peck) > p * d_end + 1e-9 && depths.size() < 100000; ++n)
                depths.push_back(d0 - p * n * g.peck);
        depths.push_back(d_end);
        for (std::size_t n = 0; n < depths.size(); ++n) {
            if (n > 0) out.emplace_back(Rapid{at(p * std::min(p * (depths[n - 1] + p * g.e), p * d0), ss[k])});
            out.emplace_back(Linear{at(depths[n], ss[k]), g.feed, Movement::plunge});
        }
        out.emplace_back(Rapid{at(d0, ss[k])});
    }
    if (ss.size() > 1) out.emplace_back(Rapid{at(d0, s0)});
    return out;
}

}  // namespace camgen::iso
