#pragma once
// LinuxCNC 2.9's threading cycle G76 P Z I J K R Q H as its interpreter cuts it (the LinuxCNC
// G-code manual, G76; held to rs274's trace by tests/oracle/test_thread_cycle_oracle.cpp). The
// post checks a cycle against it before it writes G76; the reader expands a G76 into its moves.
#include <cmath>
#include <vector>

#include "camgen/events/events.hpp"

namespace camgen::iso {

// The words of one G76 in internal units (mm, radius): from the drive point (x, z) where the
// tool stands; the thread's crest at x + i (i < 0: external; i > 0: internal); j the first
// depth, k the thread's depth from the crest; r the degression, q the compound angle (degrees),
// h the spring passes; z the end; p the lead; e the taper's length along Z and l which ends
// taper (camgen models l 0 and 2, the exit).
struct LinuxcncG76 {
    double drive_x = 0.0, drive_y = 0.0, drive_z = 0.0;
    double p = 0.0, z = 0.0, i = 0.0, j = 0.0, k = 0.0, r = 1.0, q = 0.0;
    int h = 0;
    double e = 0.0;
    int l = 0;
};

// The radial depths of its passes: j x n^(1/r) while below k, then k, then h spring passes at k.
inline std::vector<double> linuxcnc_g76_depths(const LinuxcncG76& g) {
    std::vector<double> out;
    double depth = g.j;
    int pass = 1;
    while (depth < g.k && out.size() < 10000) {
        out.push_back(depth);
        ++pass;
        depth = g.j * std::pow(static_cast<double>(pass), 1.0 / g.r);
    }
    for (int s = 0; s <= g.h; ++s) out.push_back(g.k);
    return out;
}

// Its moves: each pass from the drive point's radius moved out by k - depth, at the drive Z
// moved towards the end by depth x tan q; in at the crest less the depth; synchronised to the
// end Z moved back by (k - depth) tan q; out again. The tool ends at the drive X and the end Z.
// An exit taper (E > 0, L2): the synchronised move stops e above the pass's end and a second,
// synchronised along its path at p x hypot(e, k) / e (p along Z), goes out by k to the pass's
// end Z (rs274ngc's threading_pass); the ThreadFeeds carry p, the lead along Z.
inline std::vector<Event> linuxcnc_g76_moves(const LinuxcncG76& g) {
    std::vector<Event> out;
    const bool boring = g.i > 0;
    const double crest = g.drive_x + g.i;
    const double t = std::tan(g.q * 3.14159265358979323846 / 180.0);
    for (double d : linuxcnc_g76_depths(g)) {
        const double back = boring ? g.drive_x + d - g.k : g.drive_x - d + g.k;
        const double cut = boring ? crest + d : crest - d;
        const double z0 = g.drive_z - d * t, z1 = g.z + (g.k - d) * t;
        out.emplace_back(Rapid{{back, g.drive_y, z0}});
        out.emplace_back(Rapid{{cut, g.drive_y, z0}});
        if (g.e > 0 && (g.l & 2)) {
            out.emplace_back(ThreadFeed{{cut, g.drive_y, z1 + g.e}, g.p});
            out.emplace_back(ThreadFeed{{boring ? cut - g.k : cut + g.k, g.drive_y, z1}, g.p});
        } else {
            out.emplace_back(ThreadFeed{{cut, g.drive_y, z1}, g.p});
        }
        out.emplace_back(Rapid{{back, g.drive_y, z1}});
    }
    return out;
}

}  // namespace camgen::iso
