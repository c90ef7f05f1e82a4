#pragma once
// Fanuc T's G70 after G71: which turn-profile finishes the shape of the turn-rough right before it.
#include <optional>
#include <string>

#include "camgen/job/job_input.hpp"
#include "camgen/operations/registry.hpp"

namespace camgen {

// Links each turn-profile (output "auto" or "canned") to the turn-rough right before it where
// both have the same profile (start and elements within 1e-9 mm): the turn-profile's g70 is set
// (the rough's cycle's start point A), with a refusal where Fanuc's G70 would not cut camgen's
// finishing pass or the G71 on the finishing shape moved by the allowances would not cut the
// turn-rough's passes; where there is none the turn-rough's `finish` carries the finishing shape
// (TurnCycle::finish). Machine-independent: the posts and the trace use it only under Fanuc's
// roughing pattern. A turn-profile with output "canned" without such a turn-rough is refused at
// its "output". Runs after rough_from_earlier_material.
void link_fanuc_finishing(Job& job, const JobInput& input);

// Why the finishing tool's rapids in G70 (from A down to A', and from the shape's end straight
// back to A) would not stay in air beside the finished profile (Z, radius) it keeps, or nullopt.
// `tip_offset`: the imaginary tip from the nose centre (lathe_tip_offset), `nose` its radius.
std::optional<std::string> fanuc_g70_air(const Profile& profile, Vec2 start, const Profile& written_shape, double nose,
                                         Vec2 tip_offset);

}  // namespace camgen
