#pragma once
// What LinuxCNC 2.9's G71 roughing cycle (and G72, below) makes of a profile: the moves the control makes, as a
// model camgen computes itself (held to rs274 by tests/oracle/test_g71_model_oracle.cpp). The
// linuxcnc-lathe reader expands a G71 it reads back into these moves, so that verify, stats and
// the simulation see what the control will cut; a canned turn-rough carries them (TurnCycle) as
// the longhand it equals.
//
// The model covers the profiles camgen writes as a G71 (the rest are refused with a reason):
// the profile's Z never rises and its radius never falls (no pocket), lines and arcs that keep
// to one quarter of their circle, started from a point above the profile's start and not
// before it in Z, and D0 (no finishing offset: camgen hands the control the boundary it
// roughs to). Its moves, in (Z, radius):
// - a rapid to the start point S; the profile is closed by a face from its end up to S's
//   radius when it ends below it;
// - levels x = S's radius, then x - I, x - 2I, ... (by repeated subtraction, as the control);
//   while a level is at or above the profile's start radius: a rapid down the line from S to
//   the profile's start to where it meets the level, a feed along -Z to the first element of
//   the profile that reaches the level, a rapid escape of R (scaled down to half the pass's
//   length where the pass is shorter than 2R) at 45 degrees (+Z, +X), a rapid back along the
//   level to R (as scaled) before the pass's start, a rapid to the pass's start;
// - a rapid to the profile's start (unless the last level met it there) and a feed along the
//   whole profile and its closing face: the last pass. The control stays where it ends.
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/geometry.hpp"
#include "camgen/geometry/profile.hpp"

namespace camgen {

// One move of a lathe cycle in (Z, radius): a rapid, a feed, or an arc (feed) around `centre`.
struct LatheCycleMove {
    enum class Kind { rapid, feed, arc };
    Kind kind = Kind::rapid;
    Vec2 end;                     // (Z, radius)
    Vec2 centre;                  // an arc's
    ArcDirection direction = ArcDirection::ccw;  // an arc's, in (Z, radius): ccw is G3 in G18
    friend bool operator==(const LatheCycleMove&, const LatheCycleMove&) = default;
};

struct LatheCycleModel {
    std::vector<LatheCycleMove> moves;
    std::optional<std::string> refusal;  // why the model does not cover this profile (moves empty)
};

// Which of LinuxCNC's roughing cycles: G71 (passes along -Z at radial levels) or G72 (passes
// along -X at Z levels).
enum class LatheCycleAxis { z, x };

// LinuxCNC's `G71 Q<sub> D0 I<depth> R<retract>` (axis z) or `G72 ...` (axis x) from start (Z,
// radius) on `profile` ((Z, radius), its start the sub's first point). depth and retract > 0.
// G72 is G71 with Z and X swapped (the control turns the profile a quarter and flips it: LinuxCNC
// 2.9 interp_g7x.cc, do_g72), so that everything above holds with the roles swapped: the levels
// are Z = S's Z, S's Z - I, ...; each pass feeds along -X to the profile; the profile's X never
// rises and its Z never falls along the sub (it runs from outside towards the axis and +Z, with
// no pocket); the last pass runs along the whole profile and a closing line along Z from its
// end to S's Z where it ends below it. A G72 profile is a turn-rough's boundary walked backwards
// from the top of its end face.
LatheCycleModel linuxcnc_g7x(LatheCycleAxis axis, Vec2 start, const Profile& profile, double depth, double retract);

inline LatheCycleModel linuxcnc_g71(Vec2 start, const Profile& profile, double depth, double retract) {
    return linuxcnc_g7x(LatheCycleAxis::z, start, profile, depth, retract);
}
inline LatheCycleModel linuxcnc_g72(Vec2 start, const Profile& profile, double depth, double retract) {
    return linuxcnc_g7x(LatheCycleAxis::x, start, profile, depth, retract);
}

// Fanuc T's type I G71 (G code system A), `G71 U(depth) R(retract)` / `G71 P Q U0 W0 F` from
// the start point A = start (Z, radius), as camgen models it from the 0i-TF manual's
// description (no Fanuc control was run; docs/reference.md lists what is the manual's and what
// is camgen's reading). `shape` is the finishing shape ns..nf ((Z, radius)) from A' = its start,
// which lies at A's Z (block ns moves along X only), towards -Z, its radius never falling (the
// same profiles as linuxcnc_g71: lines and arcs within a quarter). U0 W0: no finishing offset.
// Moves: a rapid to A; levels x = A - depth, A - 2 depth, ... while above A': a rapid down to
// the level at A's Z (block ns is G0), a feed along -Z to where the level meets the shape (its
// end's Z where the level is above the shape's end), a rapid escape of `retract` at 45 degrees
// (+Z, +X), a rapid along +Z back to A's Z; then a rapid to A' and a feed along the whole shape
// (the pass that leaves the even allowance, here none), and a rapid straight back to A, where
// the control ends. Refused: a level within 0.0001 mm of a corner's radius, a pass shorter than
// the retract, a shape ending above A.
// Axis x: Fanuc T's type I G72, `G72 W(depth) R(retract)` / `G72 P Q U0 W0 F`: the same with Z
// and X swapped (arcs turning the other way): block ns moves along Z only (A' at A's X), the
// shape runs towards -X and its Z never falls; levels Z = A - depth, A - 2 depth, ... while
// beyond A'; each pass feeds along -X from A's X, escapes by `retract` at 45 degrees (+X, +Z)
// and rapids along +X back to A's X; then the pass along the shape and a rapid back to A.
// `allowance` (Z, radius), both >= 0: the second block's W and U/2 (G71 and G72 alike: U a
// diameter along X, W along Z). The control roughs to the shape moved by it, the whole shape
// with A' (so the last pass starts W beyond A in Z under G71, U/2 beyond A in X under G72, in
// air: camgen's reading, docs/reference.md), and leaves that much for G70.
LatheCycleModel fanuc_g7x(LatheCycleAxis axis, Vec2 start, const Profile& shape, double depth, double retract,
                          Vec2 allowance = {0.0, 0.0});

inline LatheCycleModel fanuc_g71(Vec2 start, const Profile& shape, double depth, double retract) {
    return fanuc_g7x(LatheCycleAxis::z, start, shape, depth, retract);
}
inline LatheCycleModel fanuc_g72(Vec2 start, const Profile& shape, double depth, double retract) {
    return fanuc_g7x(LatheCycleAxis::x, start, shape, depth, retract);
}

// A finishing shape moved by an allowance (Z, radius): every point, A' with them.
Profile fanuc_moved_shape(const Profile& shape, Vec2 allowance);

// Fanuc T's G70 P(ns) Q(nf) from the start point A = start (Z, radius) on the finishing shape
// ns..nf as written (from A': block ns along X from A for a G71 shape, axis z; along Z for a
// G72 shape, axis x): a rapid to A' (block ns is G0), the shape at the finishing feed (the F
// of blocks ns..nf), a rapid straight back to A, where the control ends. Refused: block ns
// not along its axis from A.
LatheCycleModel fanuc_g70(LatheCycleAxis axis, Vec2 start, const Profile& shape);

// The finishing shape camgen writes for Fanuc's G71 (axis z) from the start point A (Z, radius)
// on a profile (Z, radius) that starts below and before A: A' = (A's Z, the profile's start
// radius), then the profile. G72 (axis x): A' = (the profile's start Z, A's radius), then the
// profile (which starts inside and on the -Z side of A).
Profile fanuc_g7x_shape(LatheCycleAxis axis, Vec2 start, const Profile& profile);
inline Profile fanuc_g71_shape(Vec2 start, const Profile& profile) { return fanuc_g7x_shape(LatheCycleAxis::z, start, profile); }

}  // namespace camgen
