#pragma once
// The checks of a machine's settings against what its dialect writes and reads back, which
// the dialects assemble into their check (Dialect::check_machine). Each returns the problem,
// naming the settings involved, or nothing. machine_problem (machine.hpp) runs every dialect's
// checks and then the machine's dialect's.
#include <optional>
#include <span>
#include <string_view>

#include "camgen/post/machine.hpp"

namespace camgen {

// Where the machine writes arcs in one plane only, it writes no plane word on them: the start
// block must select that plane (a start block without G17/G18/G19 leaves the control in
// `control_default`).
std::optional<MachineProblem> single_arc_plane_problem(const Machine& machine, Plane control_default);

// The start block's `word` makes the control read X as a diameter (`diameter`) or as a radius:
// it must agree with xDiameterProg, which decides what camgen writes. `word_means` says it for
// the message ("LinuxCNC's G7").
std::optional<MachineProblem> diameter_mode_problem(const Machine& machine, std::string_view word, bool diameter,
                                                    std::string_view word_means);

// arcs.planes other than XY, for a dialect whose arc blocks are XY arcs only; `form` names
// them for the message ("CC X Y / C X Y").
std::optional<MachineProblem> xy_arcs_only_problem(const Machine& machine, std::string_view form);

// A decimal comma, for a dialect whose control reads a decimal point only; `why` says what a
// comma would do there.
std::optional<MachineProblem> decimal_point_only_problem(const Machine& machine, std::string_view why);

// The start block's words: no unit word (`unit_words`: camgen writes it from "units"), at most
// one plane word (G17/G18/G19), and each one of `known_words`, the safe-start words the
// dialect's post relies on and its reader reads back.
std::optional<MachineProblem> start_block_problem(const Machine& machine, std::span<const std::string_view> unit_words,
                                                  std::span<const std::string_view> known_words);

}  // namespace camgen
