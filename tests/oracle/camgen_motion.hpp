#pragma once
// camgen's own reading of a program in the oracle's normalised form (rs274.hpp's Step), so
// that what camgen's reader and trace make of a program can be compared with rs274's motion.
#include <string>
#include <vector>

#include "camgen/post/machine.hpp"
#include "rs274.hpp"

namespace camgen::oracle {

// The motion camgen's reader makes of a program: moves of zero length and zero dwells
// dropped, feeds and arcs with their rate, spindle entries on changes.
std::vector<Step> read_with_camgen(const std::string& program, const Machine& machine);

}  // namespace camgen::oracle
