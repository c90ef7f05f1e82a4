#pragma once
// Fanuc T's grooving cycle G75 R(e) / G75 X(U) Z(W) P(Δi) Q(Δk) R(Δd) F as camgen models it
// (Fanuc 0i-TF operator's manual, "Outer diameter / internal diameter drilling cycle (G75)", and
// the public descriptions of the two-block form). From the start point A where the tool stands:
// each plunge feeds towards X in pecks of Δi, backing off e at rapid between pecks (the next peck
// feeds Δi + e), the last peck shortened to reach X; then out to A's X at rapid and along Z by
// Δk towards Z (the last shift shortened to reach Z) for the next plunge; after the plunge at Z,
// back to A (out to A's X, then to A's Z). Δd, the relief along Z at the bottom, is not written
// (0). The post checks a GrooveCycle against this model before it writes G75; the reader expands
// a G75 into its moves.
#include <algorithm>
#include <vector>

#include "camgen/events/events.hpp"

namespace camgen::iso {

// The words of one G75 in internal units (mm, radius): from the start point (start_x, start_z)
// to the last plunge's bottom (x, z); peck Δi, step Δk, back-off e; feed mm/min.
struct FanucG75 {
    double start_x = 0.0, start_y = 0.0, start_z = 0.0;
    double x = 0.0, z = 0.0;
    double peck = 0.0, step = 0.0, e = 0.0;
    double feed = 0.0;
};

// The moves the control makes (Rapid and Linear events), from the start point. An external
// groove: x below start_x; an internal one (the manual's "internal diameter"): x beyond it, the
// pecks and back-offs mirrored; peck and step > 0 (step unused when z is start_z).
inline std::vector<Event> fanuc_g75_moves(const FanucG75& g) {
    std::vector<Event> out;
    auto at = [&](double r, double z) { return Vec3{r, g.start_y, z}; };
    const double dir = g.z < g.start_z ? -1.0 : 1.0;
    std::vector<double> zs{g.start_z};
    if (g.step > 0)
        for (int k = 1; dir * (g.z - (g.start_z + dir * k * g.step)) > 1e-9 && zs.size() < 100000; ++k)
            zs.push_back(g.start_z + dir * k * g.step);
    if (std::abs(g.z - g.start_z) > 1e-9) zs.push_back(g.z);
    for (std::size_t k = 0; k < zs.size(); ++k) {
        if (k > 0) out.emplace_back(Rapid{at(g.start_x, zs[k])});
        std::vector<double> depths;
        // In the plunge's own direction: s = -1 where X rises into the material.
        const double s = g.x > g.start_x ? -1.0 : 1.0;
        if (g.peck > 0)
            for (int n = 1; s * (g.start_x - s * n * g.peck) > s * g.x + 1e-9 && depths.size() < 100000; ++n)
                depths.push_back(g.start_x - s * n * g.peck);
        depths.push_back(g.x);
        for (std::size_t n = 0; n < depths.size(); ++n) {
            if (n > 0) out.emplace_back(Rapid{at(s * std::min(s * (depths[n - 1] + s * g.e), s * g.start_x), zs[k])});
            out.emplace_back(Linear{at(depths[n], zs[k]), g.feed, Movement::plunge});
        }
        out.emplace_back(Rapid{at(g.start_x, zs[k])});
    }
    if (zs.size() > 1) out.emplace_back(Rapid{at(g.start_x, g.start_z)});
    return out;
}

}  // namespace camgen::iso
