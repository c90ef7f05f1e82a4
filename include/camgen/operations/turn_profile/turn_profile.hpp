#pragma once
// The turn-profile operation: a finishing pass of a lathe's tool tip along a 2D profile of
// lines and arcs in XZ (the shared geometry layer's Profile, ProfilePlane::xz), X given as the
// job states it (radius or diameter). No nose-radius compensation: the profile is the path of
// the tool tip. An outside profile: the material it keeps lies between the spindle axis and the
// profile, and the tool comes and goes on the air side of it.
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
    std::vector<std::string> notes;  // what camgen decided that the job did not ask for
};

// Refuses (InputError at "start" or "retractX") a turn-profile of `ops`, in job order, whose
// approach (the feed along Z from the clearance to its start) runs through material that it or
// an earlier one keeps, or whose return (the rapid along Z at retractX from its end to the
// clearance) runs through material that it or an earlier one keeps. The material a profile
// keeps lies between the spindle axis and the profile, from its start's Z to its end's; what a
// later profile passes above is gone.
void check_turned_material(const std::vector<const TurnProfileOp*>& ops, const JobInput& input);

// Rapid to the profile's X at the clearance, feed along Z to its start, feed along the
// profile, feed out to retractX, rapid back to the clearance.
void expand(const TurnProfileOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "turn profile".
std::string default_name(const TurnProfileOp& op);

}  // namespace camgen
