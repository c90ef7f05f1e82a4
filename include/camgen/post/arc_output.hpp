#pragma once
// Arc output policy shared by every post (the arc-breaking rules of the machine file, and
// arc blocks whose rounded words keep the control on the circle).
#include <cstdint>
#include <optional>
#include <string>

#include "camgen/geometry/arc.hpp"
#include "camgen/nc/format.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// ---- arc-breaking rules, shared by every post: which arcs a machine writes as arcs, as lines or as one straight move ----

// The chord tolerance for one arc: the machine's, or with ChordToleranceMode::operation the
// operation's tolerance when it has one, capped by the machine's (mm).
double effective_chord_tolerance(const ArcSettings& settings, std::optional<double> operation_tolerance);

// The most straight segments one broken arc is written as. An arc that needs more to keep its
// chord tolerance (or max_segment_length) is refused: the post names the operation.
inline constexpr std::int64_t max_arc_chords = 10'000'000;

// How many equal straight segments replace an arc: enough for the chord tolerance, at least
// min_segments, and more while a segment would be longer than max_segment_length. Not capped:
// above max_arc_chords it is what the arc would need (for the message), not a count to write.
std::int64_t segment_count(const ArcGeometry& arc, const ArcSettings& settings, double chord_tolerance);

// Whether the rules write `arc` as one straight move from its start to its end: a radius below
// min_radius, or a length (a helix counts its depth) below min_length. plan_arc and verify
// (compare.hpp: the job's arc is compared as that move) both ask this.
bool written_as_one_line(const ArcGeometry& arc, const ArcSettings& settings);

// Whether the machine writes arcs in `plane` as arc blocks (else as straight moves): its
// arcs.planes. plan_arc, the post's refusal of control compensation and --describe-machine
// (machine_capabilities) all ask this.
bool writes_arcs_in(const ArcSettings& settings, Plane plane);
// Whether the machine writes a helix (an arc whose end differs along the plane's normal) as
// helical arc blocks, else as straight moves: its arcs.helical. Asked by plan_arc and
// --describe-machine.
bool writes_helices(const ArcSettings& settings);

// What the post does with one arc.
enum class ArcTreatment {
    arcs,      // arc blocks: `count` pieces of equal sweep
    lines,     // `count` equal straight segments (plane, helix or large radius)
    one_line,  // one straight move from start to end (small radius or short arc)
};
struct ArcPlan {
    ArcTreatment treatment = ArcTreatment::arcs;
    std::int64_t count = 1;    // for lines: may exceed max_arc_chords (see segment_count)
    std::string reason;        // why it is not written as arcs ("" for arcs)
};

// Applies the rules in the seed's order of effect: an arc that is too small (min_radius,
// min_length) is one straight move; one in an unsupported plane, a helix the machine cannot
// do, or a radius above max_radius becomes segment_count() lines; otherwise arc blocks of at
// most max_sweep degrees (at most 180 for the radius form, which cannot say "full circle").
ArcPlan plan_arc(const ArcGeometry& arc, const ArcSettings& settings, double chord_tolerance);

// ---- rounded arcs stay on the circle ----

// The formats a control reads an arc block with, the arc form, and the arc tolerance (mm).
struct ArcWordFormats {
    nc::Format xyz;
    nc::Format ijk;
    nc::Format angle;
    ArcFormat form = ArcFormat::ijk_relative;
    double tolerance = 0.002;
    // The machine's widest arc block in degrees: rounding may not widen a piece cut at the
    // limit past what the reader allows (one grid step over the radius).
    double max_sweep = 360.0;
};

enum class ArcFitResult {
    ok,           // `block` is safe to write
    degenerate,   // the rounded end equals the start (or D/R rounds to 0): write a straight move
    no_fit,       // no choice of words keeps the control on the circle: break the arc
};

// One arc block as it will be written: `block` has start = the control's start, the centre
// (and for the radius form `radius`, for the nccad form `sweep`) adjusted so that their
// rounded words describe a circle through the control's start and the rounded end whose
// radii agree within the tolerance, and whose midpoint lies within the tolerance (plus half a
// grid diagonal of the rounded ends) of the intended arc's; `control_end` is where the control
// will stop. Plainly rounded words are kept when they pass; only otherwise are neighbours tried.
struct ArcFit {
    ArcFitResult result = ArcFitResult::ok;
    ArcGeometry block;
    Vec3 control_end;
};

// Fits `piece` (at most 360 degrees; at most 180 for the nccad form) to the rounded words.
// `control_start` is where the control stands (the rounded previous end, or the computed end
// of an nccad angle arc).
ArcFit fit_arc_block(const ArcGeometry& piece, const Vec3& control_start, const ArcWordFormats& formats);

}  // namespace camgen
