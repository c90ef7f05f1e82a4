#pragma once
// The turn-profile operation: a finishing pass of a lathe's tool tip along a 2D profile of
// lines and arcs in XZ (the shared geometry layer's Profile, ProfilePlane::xz), X given as the
// job states it (radius or diameter). No nose-radius compensation: the profile is the path of
// the tool tip. An outside profile: the material it keeps lies between the spindle axis and the
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
    Vec2 lift_direction{0.70710678118654752, 0.70710678118654752};  // unit, (Z, radius): away from the finished surface (turned_lift_direction)
    std::vector<std::string> notes;  // what camgen decided that the job did not ask for
};

// Refuses (InputError at "start" or "retractX") a turn-profile of `ops`, in job order, whose
// approach (the feed along Z from the clearance to its start) runs through material that it or
// an earlier one keeps, or whose return (the rapid along Z at retractX from its end to the
// clearance) runs through material that it or an earlier one keeps. The material a profile
// keeps lies between the spindle axis and the profile, from its start's Z to its end's; what a
// later profile passes above is gone.
void check_turned_material(const std::vector<const TurnProfileOp*>& ops, const JobInput& input);

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

// An element of a profile that a tool's insert cannot follow, and why (for the message).
struct UnfollowableSegment {
    std::size_t index = 0;
    std::string why;
};
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
Vec2 turned_lift_direction(int orientation, const Profile& profile);

// Rapid to the profile's X at the clearance, rapid along Z to approachDistance before its start,
// feed to the start, feed along the profile, feed off its end by lift (turned_lift_direction),
// rapid out to retractX and back to the clearance.
void expand(const TurnProfileOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "turn profile".
std::string default_name(const TurnProfileOp& op);

}  // namespace camgen
