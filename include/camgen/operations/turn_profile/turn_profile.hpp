#pragma once
// The turn-profile operation: a finishing pass of a lathe's tool tip along a 2D profile of
// lines and arcs in XZ (the shared geometry layer's Profile, ProfilePlane::xz), X given as the
// job states it (radius or diameter). With a nose radius the program is, by default, the path of
// the imaginary tip that runs the nose circle along the profile (computer compensation,
// nose_path); "compensation": "none" makes the profile the tip's path. An outside profile: the material it keeps lies between the spindle axis and the
// profile, and the tool comes and goes on the air side of it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"

namespace camgen {

// Who makes up for a turning tool's nose radius on a turn-profile and on turn-rough's last pass.
enum class NoseCompensation { computer, none, control };
inline constexpr Named<NoseCompensation> nose_compensation_modes[] = {
    {NoseCompensation::computer, "computer",
     "camgen moves the path so that the nose circle runs along the profile: the program is the path of the "
     "imaginary tip of the tool's orientation (no G41/G42)"},
    {NoseCompensation::none, "none",
     "the profile is the path of the imaginary tip: a nose radius leaves material on tapers, chamfers and arcs"},
    {NoseCompensation::control, "control",
     "the program runs the designed profile with G41/G42 in G18 and the control offsets the nose by the radius and "
     "orientation in its tool table (turn-profile only; turn-rough refuses it)"},
};

// An element of a profile that a tool cannot follow or reach, and why (for the message).
struct UnfollowableSegment {
    std::size_t index = 0;
    std::string why;
};

// The paths of a nose of radius `nose_radius` (> 0) whose circle runs along `profile` on its
// air side (the right of travel in (Z, radius): the material lies on the left, towards the
// spindle axis): the nose centre's (the profile offset by the radius, lines parallel, arcs about
// their centres, an arc about each convex corner; offset_profile) and the programmed point's
// (the centre's moved by lathe_tip_offset for `orientation`: the same lines and arcs).
// `refusal`: an element the nose cannot follow (a concave arc tighter than the nose, an element
// its neighbours' offsets cut away, a neck it cannot pass); `concave_corners`: the elements
// that begin at a sharp concave corner, where the nose leaves its own radius.
struct NosePath {
    Profile centre;
    Profile tip;
    std::optional<UnfollowableSegment> refusal;
    std::vector<std::size_t> concave_corners;
};
// With `material_right` (a profile that runs towards +Z, turned_material_right) the material
// lies on the right of travel and the nose runs on its left.
NosePath nose_path(const Profile& profile, double nose_radius, int orientation, bool material_right = false);

// The first element of `profile` that a nose of tip orientation `orientation` cannot reach: the
// directions from the nose centre to where it touches the profile (the left normal of travel,
// turning about each convex corner) must lie on the tip's half of the nose, within 90 degrees
// of the direction from the centre to the imaginary tip (the insert's body lies on the other
// half); 9 and 0 (no tip given) reach every direction. A necessary condition only: an insert's
// angles narrow it (first_unfollowable, orientation 2).
// With `material_right` the material directions are the right normals of travel.
std::optional<UnfollowableSegment> first_unreachable(const Profile& profile, int orientation, int tool_number,
                                                    bool material_right = false);

// Whether the material a turned profile keeps (between the spindle axis and the profile, the
// profile closed through the axis) lies on the right of travel in (Z, radius): a profile that
// runs towards +Z (a left-hand tool's, cutting towards the tailstock). Else on the left.
bool turned_material_right(const Profile& profile);

struct TurnProfileOp {
    static constexpr std::string_view type = "turn-profile";
    static constexpr MachineKind machine_kind = MachineKind::lathe;
    // Reads one operation of this type (its "type" is already read).
    static TurnProfileOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    XValues given_x = XValues::diameter;  // how the job gave X: messages show X the same way
    FeedMode feed_mode = FeedMode::per_minute;
    double feed = 0.0;            // mm/min (a job's mm/rev times the tool's speed)
    Profile profile;              // XZ: u = Z, v = X as a radius, mm
    double retract_x = 0.0;       // radius the tool leaves the profile's end to, mm
    double approach = 1.0;        // mm before the start where the approach along Z turns from rapid to feed
    double lift = 0.5;            // mm the tool feeds off the profile's end before it rapids
    bool material_right = false;  // the profile runs towards +Z: its material on the right of travel (turned_material_right)
    Vec2 lift_direction{0.70710678118654752, 0.70710678118654752};  // unit, (Z, radius): away from the finished surface (turned_lift_direction)
    NoseCompensation compensation = NoseCompensation::computer;
    double nose_radius = 0.0;     // the tool's, mm (0: a sharp tip)
    Profile tip_path;             // where the tip goes: nose_path's tip, or the profile itself (empty: the profile)
    // Control compensation: the tool's tip orientation, the profile the program writes under
    // G42 (the designed one, ending a nose radius short of its end, where the nose's leading
    // point reaches it) and the point the G40 move lifts the tip to (Z, radius).
    int orientation = 0;
    Profile control_path;
    Vec2 control_exit;
    double nose_low = 0.0;        // the nose's least radius less the programmed point's, mm (<= 0)
    double rpm = 0.0;             // the tool's speed, rev/min
    // "auto": Fanuc's G70 after the turn-rough right before it of the same profile, where exact
    // (link_fanuc_finishing); "canned": that or an error; "longhand": its own moves.
    CycleOutput output = CycleOutput::automatic;
    // The turn-rough right before it of the same profile (set by read_job): expand emits a
    // FinishCycle (G70 where the machine's pattern is Fanuc's and `refusal` is empty).
    struct FinishLink {
        std::string rough_path;
        bool along_x = false;
        Vec2 start;                          // the rough's cycle's start point A (Z, radius)
        std::optional<std::string> refusal;  // why G70 does not finish it
    };
    std::optional<FinishLink> g70;
    std::vector<std::string> notes;  // what camgen decided that the job did not ask for
};

// Refuses (InputError at "start" or "retractX") a turn-profile of `ops`, in job order, whose
// approach (the feed along Z from the clearance to its start) runs through material that it or
// an earlier one keeps, or whose return (the rapid along Z at retractX from its end to the
// clearance) runs through material that it or an earlier one keeps; and (InputError at "lift"
// or "retractX") one whose lift off its end or rapid out along X to retractX runs its nose
// circle deeper into the material it keeps than the nose lies at the end of its cut. The
// material a profile keeps lies between the spindle axis and the profile, from its start's Z to
// its end's; what a later profile passes above is gone.
void check_turned_material(const std::vector<const TurnProfileOp*>& ops, const JobInput& input);

// The material a turn-profile keeps, in (u, v) = (Z, radius): the profile's sampling closed
// through the spindle axis (from its end down to the axis, along it, up to its start). What
// check_turned_material and the blades' checks (check_blade_material) measure moves against.
struct KeptMaterial {
    std::vector<Vec2> ring;
    double u_min = 0.0, u_max = 0.0, v_max = 0.0;
    const TurnProfileOp* op = nullptr;  // null: the material under another operation's outline (check_blade_material)
};
KeptMaterial kept_by(const TurnProfileOp& op);
// The material under an outside profile in (Z, radius) (a turn-rough's boundary, a groove's
// outline), closed through the spindle axis as kept_by closes a turn-profile's; `op` null.
KeptMaterial kept_under(const Profile& profile);

// An interval along Z, mm.
struct ZSpan {
    double lo, hi;
};
// Where the line at radius `level` (> 0) runs inside the kept material: Z intervals, in order.
std::vector<ZSpan> kept_inside_at(const KeptMaterial& k, double level);
// The largest radius of the kept material between Z `lo` and `hi`.
double kept_largest_radius(const KeptMaterial& k, double lo, double hi);

// Material that a move along Z at a radius runs through: where along Z, and the first
// operation that keeps it.
struct KeptMaterialHit {
    ZSpan span;
    const KeptMaterial* kept;
};
// The first stretch (from `hi` down when `downwards`, else from `lo` up) of the move along Z at
// `radius` between Z `lo` and `hi` that runs inside what `kept` keeps (by more than a few µm)
// and that none of the first `cut` of them passed above (what a profile passes above is gone).
// A tool whose body stands straight out from `radius` (a blade) meets the material iff this
// line does: the material a profile keeps reaches down to the axis.
std::optional<KeptMaterialHit> first_kept_hit(const std::vector<KeptMaterial>& kept, std::size_t cut, double radius,
                                              double lo, double hi, bool downwards);

// Reads an outside turning profile: "start" [x, z] and "path" (its elements, lines and arcs,
// each from where the one before ends), X as `xv` says; refuses a negative X, a start or an
// element at or above the clearance, an arc through the spindle axis, an element without length
// and a profile that crosses itself. (u, v) = (Z, radius), mm.
Profile read_turned_profile(json::Fields& f, const JobInput& input, XValues xv);

// What turn-face and turn-rough read first: their tool (an outside turning tool, orientation 2;
// another is refused at "tool", naming `what`), how the job gives X ("xValues") and the cutting
// feed ("feed" in "feedMode", returned per minute).
struct OutsideTurningHead {
    const Tool* tool = nullptr;
    XValues given_x = XValues::diameter;
    FeedMode feed_mode = FeedMode::per_minute;
    double feed = 0.0;  // mm/min
};
OutsideTurningHead read_outside_turning_head(json::Fields& f, const JobInput& input, std::string_view what);

// The first element of `profile` (travelled from its start) whose direction leaves the range
// the tool's insert can follow without rubbing (a turning tool of orientation 2 with its
// insertAngle and approachAngle: rising up to approachAngle from the direction of feed, -Z;
// falling towards the chuck by at most 180 - approachAngle - insertAngle, the end edge's
// clearance); none when the tool gives no insert angles.
std::optional<UnfollowableSegment> first_unfollowable(const Profile& profile, const Tool& tool);

// The unit direction, (Z, radius), in which a tool of tip orientation `orientation` lifts off
// the end of `profile`: from its imaginary tip towards its nose centre (LinuxCNC's codes); for
// orientation 2 (and none) +Z +X at 45 degrees, or halfway between the falling surface behind
// the end and +X where that is steeper than 45 degrees.
// A profile whose material lies on the right (`material_right`, running towards +Z) takes the
// mirror image in Z of that rule for orientation 1 (and for 0 and 9).
Vec2 turned_lift_direction(int orientation, const Profile& profile, bool material_right = false);

// Rapid to the start's X at the clearance, rapid along Z to approachDistance before its start,
// feed to the start, feed along the profile (the tip path), feed off its end by lift (turned_lift_direction),
// rapid out to retractX and back to the clearance.
void expand(const TurnProfileOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "turn profile".
std::string default_name(const TurnProfileOp& op);

}  // namespace camgen
