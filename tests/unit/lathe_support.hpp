#pragma once
// Helpers for the lathe tests: an ISO lathe machine file given as text, and the Z moves of a
// program as a list that a test writes out by hand.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "support.hpp"

namespace camgen::test {

// An ISO lathe machine file: G18, 3 decimals, no length offsets, longhand drilling unless
// `extra` gives a drilling table.
inline std::string lathe_text(bool x_diameter, bool i_diameter, const std::string& extra = "",
                              const std::string& formats = R"("xyz": {"decimals": 3}, "ijk": {"decimals": 3}, "feed": {"decimals": 1})") {
    return fmt::format(R"({{"description": "test lathe", "dialect": "iso", "extension": "nc", "kind": "lathe",
  "globals": {{"xDiameterProg": {}, "iDiameterProg": {}}},
  "formats": {{{}}},
  "arcs": {{"planes": ["xz"]}}{},
  "frame": {{"startBlock": ["G18", "G90"]}},
  "settings": {{"programNumber": 0, "percentLines": false, "toolLengthOffset": false, "endCode": "M30"}}}})",
                       x_diameter, i_diameter, formats, extra);
}

inline Machine lathe(bool x_diameter, bool i_diameter, const std::string& extra = "") {
    return parse_machine(lathe_text(x_diameter, i_diameter, extra), "test-lathe", "test-lathe.json");
}

// The moves along Z of a program as "G0 Z2", "G1 Z-6 F100", "G4 P0.5": each block that
// writes Z or dwells, with its modal motion code and its feed where the block writes one.
inline std::vector<std::string> z_moves(const std::string& program) {
    std::vector<std::string> out;
    std::string motion = "G0";
    for (const std::string& line : lines_of(program)) {
        if (line.empty() || line[0] == '(' || line[0] == '%') continue;
        std::map<char, std::string> w = words_of(line);
        if (w.count('G') && (w['G'] == "0" || w['G'] == "1")) motion = "G" + w['G'];
        if (w.count('G') && w['G'] == "4") out.push_back("G4 P" + w['P']);
        if (w.count('Z')) out.push_back(motion + " Z" + w['Z'] + (w.count('F') ? " F" + w['F'] : ""));
    }
    return out;
}

}  // namespace camgen::test
