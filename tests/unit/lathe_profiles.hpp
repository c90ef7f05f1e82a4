#pragma once
// Generated turning profiles shared by the Fanuc roughing tests (test_fanuc_g70, test_fanuc_g71).
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <fmt/format.h>

#include "camgen/geometry/profile.hpp"

namespace camgen::test {

// A profile of lines that never fall in radius nor rise in Z, with faces, tapers and 90-degree
// fillets, from diameter d0 at Z0 towards the chuck.
inline std::string stepped_shaft_profile(std::mt19937& rng, double& d0) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double d = 8 + std::round(u(rng) * 80) / 10, z = 0;
    d0 = d;
    std::string out = "[";
    const int n = 2 + static_cast<int>(u(rng) * 5);
    for (int k = 0; k < n && d < 36; ++k) {
        const double len = 1 + std::round(u(rng) * 60) / 10;
        out += fmt::format(R"({{"line": [{}, {}]}}, )", d, z - len);
        z -= len;
        const double rise = 0.5 + std::round(u(rng) * 40) / 10;
        if (d + rise > 37) break;
        const int kind = rise >= 4 ? static_cast<int>(u(rng) * 3) : static_cast<int>(u(rng) * 2);
        if (kind == 0) {
            out += fmt::format(R"({{"line": [{}, {}]}}, )", d + rise, z);
        } else if (kind == 1) {
            const double dz = std::round(u(rng) * 30) / 10 + 0.5;
            out += fmt::format(R"({{"line": [{}, {}]}}, )", d + rise, z - dz);
            z -= dz;
        } else {
            const double rr = rise / 4;
            out += fmt::format(R"({{"line": [{}, {}]}}, )", d + rise / 2, z);
            out += fmt::format(R"({{"arc": {{"end": [{}, {}], "centre": [{}, {}], "direction": "ccw"}}}}, )", d + rise, z - rr,
                               d + rise / 2, z - rr);
            z -= rr;
        }
        d = std::round((d + rise) * 10) / 10;
    }
    out += fmt::format(R"({{"line": [{}, {}]}}])", d, z - 3);
    return out;
}

// The radius of a (Z, radius) profile that never rises in Z at z (on a face its highest where
// `highest`, the material under it, else its lowest: where a pass may end), -1 outside its Z range.
inline double stepped_profile_radius_at(const Profile& p, double z, bool highest) {
    double best = -1;
    Vec2 a = p.start;
    for (const ProfileSegment& s : p.segments) {
        const Vec2 b = s.end;
        const double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
        if (z >= lo - 1e-9 && z <= hi + 1e-9) {
            double r;
            if (!s.centre) {
                r = std::abs(b.x - a.x) < 1e-12 ? std::max(a.y, b.y) : a.y + (z - a.x) / (b.x - a.x) * (b.y - a.y);
            } else {
                const double rr = distance(a, *s.centre), dz = z - s.centre->x;
                const double h = std::sqrt(std::max(0.0, rr * rr - dz * dz));
                const double r1 = s.centre->y + h, r2 = s.centre->y - h;
                r = std::abs(r1 - (a.y + b.y) / 2) < std::abs(r2 - (a.y + b.y) / 2) ? r1 : r2;
                r = std::clamp(r, std::min(a.y, b.y), std::max(a.y, b.y));
            }
            best = best < 0 ? r : (highest ? std::max(best, r) : std::min(best, r));
        }
        a = b;
    }
    return best;
}

}  // namespace camgen::test
