#pragma once
// What a lathe job designs (PartDesign::lathe, made by part_design as it visits the turn-drill
// and turn-profile operations): the turned part as a function of Z, checked against a simulated
// bar by `camgen simulate --job` (simulation/design_check_lathe.hpp). The part is the bar less
// what the operations remove:
//
// - a turn-profile keeps the material between the spindle axis and its profile, over the Z its
//   profile covers and above it up to the clearance at the radius of its start (the tool feeds
//   down along Z to the start); it removes what lies beyond, down to what its tool leaves as the
//   tip follows its path (the compensated tip_path, whose nose runs along the profile, or with
//   "compensation": "none" the profile itself, where a nose leaves material on slopes, on arcs
//   and in concave corners, `left_radius`; the nose is swept as orientation 2's);
// - a turn-face removes the bar's end beyond its Z, a turn-rough the material beyond the
//   profile moved by its allowances (design_turn_face, design_turn_rough);
// - a turn-drill removes a bore of its drill's radius on the axis, down to its depth with the
//   drill's point (above startDepth too: the drill comes down the axis), and keeps the part
//   around and below it;
// - a face turn-groove removes its ring from the face down to its bottom (LatheRingDesign),
//   and keeps the part around and below it (the simulation holds the ring as a LatheGap).
//
// In (u, v) = (Z, radius), mm, as a turn-profile's Profile is. A turn-profile has no inside
// (bore) side and no stock-to-leave key yet: neither is designed.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camgen/geometry/profile.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen {

struct Job;
struct TurnDrillOp;
struct TurnProfileOp;
struct TurnFaceOp;
struct TurnRoughOp;
struct TurnGrooveOp;
struct TurnPartOp;
struct TurnThreadOp;

// A straight stretch of a tool tip's path in (Z, radius), mm.
struct LatheTipMove {
    Vec2 from, to;
    bool chord = false;  // a chord of an arc (within LatheTurnDesign::chord of it)
};

// A turn-profile's design.
struct LatheTurnDesign {
    std::string path;        // the operation's JSON path
    int tool = 0;
    Profile profile;         // (Z, radius): the approach along Z from the clearance, then the operation's profile
    std::vector<LatheTipMove> tip;  // the tip's whole path (approach, profile with arcs as chords, feed out, return)
    double nose = 0.0;       // the tool's nose radius, mm (its program point is the imaginary tip)
    bool nose_compensated = false;  // camgen ran the nose along the profile (NoseCompensation::computer)
    double chord = 0.0;      // mm: the chords of arcs in `tip` stay within this of the arcs
    double z_lo = 0.0, z_hi = 0.0;  // the Z it designs: the profile's lowest Z up to the clearance
    // A grooving or parting tool's blade (blade_hi > blade_lo): `tip` is its programmed point,
    // its flat edge covers Z from the point's Z + blade_lo to + blade_hi (nose 0), its body
    // straight out in +X: it clears only the Z it covers.
    double blade_lo = 0.0, blade_hi = 0.0;

    // The least and the greatest radius of `profile` at Z in [a, b] (none where it has no point
    // there): exact for lines and arcs.
    std::optional<std::pair<double, double>> radius_range(double a, double b) const;
    // The least radius the tool clears at Z z as its tip follows `tip` (its nose circle's centre a
    // nose radius above the tip in Z and radius, its body toward +Z and +X, as the simulation
    // sweeps a turning tool): the radius the operation leaves there; infinity where it clears none.
    double left_radius(double z) const;
    // The Z of the profile's corners (its start and every element's end), in order.
    std::vector<double> corners() const;
};

// The outer radius of the material an outside operation's tool leaves at most, as radii over
// intervals of Z (a conservative bound: never less than what the real cut leaves). Made from the
// bar (its radius below its face, none above) and cut by the designs of the operations that turn
// the outside, in order (lathe_material_cut). Within each interval [z[i], z[i+1]] at most r[i]
// is left; below z[0] the bar, above z.back() nothing (the bar's face, or beyond the range
// asked for). A turn-rough roughs from it (TurnRoughOp::material).
//
// Why it is a bound: a tool's nose is a disc of the nose radius (the insert contains it whole,
// whatever its angles), whose centre is the tip less lathe_tip_offset; a blade's edge is flat
// across its width. Along one straight tip move the lowest radius such a shape reaches at Z z is
// a convex function of z where the move reaches z (the lower edge of the sum of a segment and a
// convex shape), so its greatest on an interval the move covers whole is at the interval's ends:
// the interval's radius is cut to that (plus the chord tolerance where the move is a chord of an arc), and
// an interval a move covers only in part is left as it was. The threads' flanks stay (a thread
// cuts a helix, not a round), so turn-thread cuts nothing of it.
struct LatheMaterial {
    std::vector<double> z;  // rising, z.size() == r.size() + 1
    std::vector<double> r;

    // The bar of `radius` from z_lo up to its face at face_z, intervals at most `step` long,
    // with a bound at each of `breaks` in that range (the Z of corners: what is cut stays sharp).
    static LatheMaterial bar(double radius, double face_z, double z_lo, double step, std::vector<double> breaks);
    // The most left on any interval that meets (a, b) (0 where none does).
    double top(double a, double b) const;
    // The highest Z below which more than `v` may be left: the top of the highest interval whose
    // radius is above v; -infinity where none is.
    double front(double v) const;
    // Whether more than `v` may be left somewhere in (a, b).
    bool above(double a, double b, double v) const;
};

// `m` less what the tool of design `d` clears along its tip's path: a nose disc of d.nose whose
// centre is the tip less `tip_offset` (lathe_tip_offset of the tool's orientation), or d's blade.
void lathe_material_cut(LatheMaterial& m, const LatheTurnDesign& d, Vec2 tip_offset);

// A turn-drill's design.
struct LatheHoleDesign {
    std::string path;
    int tool = 0;
    double top_z = 0.0;      // startDepth, the face the hole starts at
    double bottom_z = 0.0;   // the point's depth (endDepth, less the tip's length with drillTip)
    double radius = 0.0;     // the drill's radius, mm
    double flat = 0.0;       // the radius of the flat at its point (a drill's: 0), mm
    double slope = 0.0;      // mm of Z per mm of radius along the point (0: a flat end)
    // An internal thread's tool nose (radius > 0): its centre `nose_above` mm above bottom_z
    // (the tip's Z) and a nose radius inside `radius` (the tip's radius): the bore's end is
    // what the nose leaves, rounded, not a flat. With a slope too (a chamfered runout): what the
    // nose leaves along the tip's cone from `radius` down to `flat` at bottom_z.
    double nose = 0.0;
    double nose_above = 0.0;

    // An internal groove (groove_chamfer >= 0): the bore opened to `radius` between Z bottom_z
    // (its -Z wall) and top_z (its +Z wall), 45-degree chamfers of groove_chamfer from the bore's
    // radius `groove_surface` at bottom_z - chamfer and top_z + chamfer; nothing beyond.
    double groove_chamfer = -1.0;
    double groove_surface = 0.0;
    bool groove() const { return groove_chamfer >= 0; }

    // The designed bore's radius at Z z: 0 below the point, the point's cone (or the nose's
    // round), the radius above.
    double radius_at(double z) const {
        if (groove()) {
            const double c = groove_chamfer;
            if (z >= bottom_z && z <= top_z) return radius;
            const double out = z < bottom_z ? bottom_z - z : z - top_z;  // beyond the nearer wall
            return c > 0 && out <= c ? groove_surface + c - out : 0.0;
        }
        if (nose > 0 && slope > 0) {
            // An internal thread's chamfered runout: the tip's path the radius down to the cone
            // from `radius` to `flat` at bottom_z; what the nose disc (centre nose_above above the
            // tip, nose inside it) reaches at z along that path: concave in the centre's Z, its
            // most found by halving.
            const double lo = std::max(bottom_z + nose_above, z - nose), hi = z + nose;
            if (lo > hi) return 0.0;
            auto reach = [&](double cz) {
                const double tip = std::min(radius, flat + (cz - nose_above - bottom_z) / slope);
                const double e = z - cz;
                return tip - nose + std::sqrt(std::max(0.0, nose * nose - e * e));
            };
            double a = lo, b = hi;
            for (int k = 0; k < 60; ++k) {
                const double m1 = a + (b - a) / 3, m2 = b - (b - a) / 3;
                if (reach(m1) < reach(m2)) a = m1;
                else b = m2;
            }
            return std::max({reach(lo), reach(hi), reach((a + b) / 2)});
        }
        if (nose > 0) {
            const double e = bottom_z + nose_above - z;
            if (e <= 0) return radius;
            return e > nose ? 0.0 : radius - nose + std::sqrt(nose * nose - e * e);
        }
        if (z < bottom_z) return 0.0;
        if (!(slope > 0)) return radius;
        return std::min(radius, flat + (z - bottom_z) / slope);
    }
    // The most and the least of radius_at over Z in [a, b] (a hole's radius rises with Z; a
    // groove's rises to its walls and falls beyond them).
    double radius_most(double a, double b) const {
        if (!groove()) return radius_at(b);
        if (b >= bottom_z && a <= top_z) return radius;
        return std::max(radius_at(a), radius_at(b));
    }
    double radius_least(double a, double b) const {
        if (!groove()) return radius_at(a);
        return std::min(radius_at(a), radius_at(b));
    }
};

// A face groove's design: the ring from `inner` to `outer` (radii) removed from the face at
// face_z down to bottom_z, 45-degree chamfers of `chamfer` on its edges in the face (the ring
// widens by z - (face_z - chamfer) on each side above face_z - chamfer); the part kept around
// and below it.
struct LatheRingDesign {
    std::string path;
    int tool = 0;
    double inner = 0.0, outer = 0.0;  // mm, radius
    double face_z = 0.0, bottom_z = 0.0;
    double chamfer = 0.0;
    // The ring's radii at Z z in [bottom_z, face_z].
    double lo_at(double z) const { return inner - std::max(0.0, z - (face_z - chamfer)); }
    double hi_at(double z) const { return outer + std::max(0.0, z - (face_z - chamfer)); }
    // The radii the ring may reach somewhere in Z [a, b] (its widest there): false where it has
    // no Z in [a, b].
    bool allowed(double a, double b, double& lo, double& hi) const {
        if (b < bottom_z || a > face_z) return false;
        const double z = std::min(b, face_z);
        lo = lo_at(z), hi = hi_at(z);
        return true;
    }
    // The radii it must clear at every Z in [a, b] (its narrowest there): false unless [a, b]
    // lies within [bottom_z, face_z].
    bool required(double a, double b, double& lo, double& hi) const {
        if (a < bottom_z || b > face_z) return false;
        lo = lo_at(a), hi = hi_at(a);
        return true;
    }
};

struct LatheDesign {
    std::vector<LatheTurnDesign> profiles;
    std::vector<LatheHoleDesign> holes;
    std::vector<LatheRingDesign> rings;
    bool empty() const { return profiles.empty() && holes.empty() && rings.empty(); }
};

// An operation's design added to `design`, or why it has none to `unchecked` ("PATH: why").
void design_turn_drill(const TurnDrillOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked);
void design_turn_profile(const TurnProfileOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked);
// A turn-face designs the bar's end at its Z: nothing kept above it between its inner and outer
// radius (a profile along the inner radius from its start Z down to its Z, then out along the
// face), its tip's whole path as the passes make it.
void design_turn_face(const TurnFaceOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked);
// A turn-rough designs the boundary it roughs to (the profile moved by the allowances, closed by
// the face at its end up to the bar): kept there, removed beyond, down to what its tool leaves;
// its tip's whole path as the passes make it.
void design_turn_rough(const TurnRoughOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked);
// A turn-groove designs its groove (walls, bottom, 45-degree chamfers on its edges): removed
// down to it over its Z, kept below; its blade's whole path as the plunges make it. An internal
// groove designs a LatheHoleDesign of its bottom's radius between its walls (the part kept
// around it); a face groove designs its ring (LatheRingDesign: walls, bottom and chamfers).
void design_turn_groove(const TurnGrooveOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked);
// A turn-part designs the slot its blade parts through (down to the remainder radius) and the
// chamfer on the part's edge; the part and the bar either side are kept (the simulation keeps
// the parted part where it was).
void design_turn_part(const TurnPartOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked);
// An external turn-thread designs its minor diameter over its length (from startZ down to endZ,
// then up its end to the major diameter): a turned part is round, and the passes remove all
// around what lies beyond the thread's root, as the simulation sweeps them (the helix and its
// flanks are not designed); its tip's whole path as the passes make it. An internal thread
// designs a bore of its major diameter down to endZ (a LatheHoleDesign whose end is the tool's
// nose, swept as orientation 3 where the tool has none), the part kept around it. A chamfered
// runout designs the last pass's taper instead of the end at endZ: outside from the root at
// endZ + runoutLength up to the major at endZ; inside a cone from the major down to the minor.
void design_turn_thread(const TurnThreadOp& op, const Job& job, LatheDesign& design, std::vector<std::string>& unchecked);

}  // namespace camgen
