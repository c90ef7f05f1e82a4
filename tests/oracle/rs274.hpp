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

// Every how-many-th generated case a test that runs rs274 on many generated cases checks:
// $CAMGEN_ORACLE_STRIDE (the sanitized twin sets 4: rs274's run, which is not instrumented,
// takes most of such a test's time, and the code under test takes the same paths), else 1.
// The cases are generated alike either way (a skipped case still draws its random numbers).
int oracle_stride();
// Whether generated case k is checked: one in oracle_stride(), the choice moving by one every
// stride cases (k = 0, 7, 10, 13, 16, 23, ... at 4), so that a case's parity or its number mod 3,
// which some tests use to vary the job, is not always the same.
bool oracle_case(int k);

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

// One move rs274 made in a lathe's XZ plane, X as it prints it (a radius), from where the last
// one ended: a traverse or a feed (one synchronised with the spindle, G33/G76, carries its lead
// from START_SPEED_FEED_SYNC), or an arc (G18: ARC_FEED(Z end, X end, Z centre, X centre, ...)).
struct XzMove {
    bool rapid = false, arc = false;
    double x = 0, z = 0;            // the end
    double cx = 0, cz = 0;          // an arc's centre
    double sync = 0;                // a synchronised feed's lead (mm or inch per revolution), else 0
    double from_x = 0, from_z = 0;  // where it began
};

// rs274's moves in XZ from its canonical calls, lengths times `unit` (25.4: a program in
// inches, into mm). A straight move shorter than `min_step` along both axes is left out (a
// move that goes nowhere, or one within the 4 decimals rs274 prints); arcs are all kept.
std::vector<XzMove> xz_moves(const std::string& canon, double unit = 1.0, double min_step = 1e-9);

}  // namespace camgen::oracle
