#pragma once
// Runs LinuxCNC's standalone interpreter (rs274, Debian package linuxcnc-uspace) on an NC
// program and reads back the canonical machining calls it prints: the oracle for camgen's
// ISO canned cycles and their longhand expansion (LinuxCNC follows Fanuc: G98 returns to the
// initial Z, G99 to R; pecks are measured from R).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/geometry.hpp"

namespace camgen::oracle {

// One observable step of the machine, normalised so that two programs that move the same
// way give equal lists: zero-length moves and zero dwells are dropped, a feed move carries
// the feed rate in force, spindle entries appear only when the spindle's state changes.
struct Step {
    enum class Kind { traverse, feed, dwell, spindle, rigid_tap, arc };
    Kind kind = Kind::traverse;
    Vec3 to;                 // traverse, feed, rigid_tap, arc
    double value = 0.0;      // feed, arc: mm/min; dwell: seconds; spindle: rpm (0: stopped)
    std::string spindle;     // spindle: "cw", "ccw" or "off"
    Vec2 centre;             // arc (in the XY plane): its centre
    int rotation = 0;        // arc: turns counter-clockwise (> 0) or clockwise (< 0)
};

// Text of one step, for messages: "feed (10, 10, -1) F100".
std::string describe(const Step& step);

// The path of rs274: $CAMGEN_RS274, else "rs274" on PATH, else /usr/bin/rs274; nullopt if
// none exists.
std::optional<std::string> find_rs274();

// Runs `rs274 -g` on `program` (NC text). Throws std::runtime_error with rs274's message when
// it rejects the program or does not reach PROGRAM_END. Tools 1 to 99 have zero length and the
// diameter `tool_diameters` gives them (mm; else 1 inch): cutter compensation offsets by it.
std::vector<Step> run_rs274(const std::string& rs274, const std::string& program,
                            const std::map<int, double>& tool_diameters = {});

// The same run, giving rs274's canonical calls as it printed them (for what parse_canon leaves
// out, such as arcs in XZ).
std::string run_rs274_canon(const std::string& rs274, const std::string& program,
                            const std::map<int, double>& tool_diameters = {});

// The same with lathe tools: `orientations` gives a tool its tip orientation (the table's Q,
// LinuxCNC's codes), which G41/G42 in G18 move the imaginary tip of.
std::string run_rs274_canon(const std::string& rs274, const std::string& program, const std::map<int, double>& tool_diameters,
                            const std::map<int, int>& orientations);

// Normalises rs274's canonical output (exposed for tests of the parser itself).
std::vector<Step> parse_canon(const std::string& canon);

}  // namespace camgen::oracle
