#pragma once
// A control's tool table, for the radius its cutter compensation offsets by (G41/G42 D<n>):
// LinuxCNC's format, a tool a line, `T1 P1 D6.0 Z0 ;comment` (T the tool number, P its pocket, D
// its diameter, X..W its offsets, I J Q a lathe tool's angles and orientation; `;` starts a
// comment). LinuxCNC's standalone interpreter rs274 reads its table in inches.
#include <map>
#include <string>
#include <string_view>

#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen {

// Each tool's diameter in mm (the table's D, in `units`), by tool number; a tool without D has
// diameter 0. Throws InputError ("SOURCE:LINE: detail") for a line that is not a tool: an
// unknown word, a number that is not one, a missing or repeated T, a negative diameter.
std::map<int, double> read_tool_table(std::string_view text, const std::string& source, Units units);

}  // namespace camgen
