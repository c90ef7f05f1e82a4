#pragma once
// The turn-thread operation: a straight thread cut on a lathe with a threading tool in passes
// synchronised with the spindle, external (on the bar, from its major diameter in to the minor)
// or internal (in a bore, from its minor diameter out to the major). The thread is a designation
// of the tables (camgen/vocabulary/threads.hpp: ISO 261 metric, ASME B1.1 unified) or its
// diameters and pitch; it runs from startZ (its free end, +Z) to endZ. Each pass rapids in air
// to approachDistance beyond startZ at the retract X, in to its depth, cuts along -Z to endZ
// synchronised with the spindle (a ThreadFeed: lead mm per revolution), rapids straight out to
// the retract X (a straight runout: the thread ends in a relief groove or off the part) and back
// along Z in air. The depths follow the infeed rule (constant depth, or constant area: the
// depth after pass n is firstDepth x sqrt(n), as Fanuc's G76 and LinuxCNC's G76 R2 cut), never
// less than minDepth a pass, then springPasses at the full depth. A flank infeed moves each
// pass's start by -depth x tan(infeedAngle) along Z, so that the tool cuts on its leading edge.
// A left-hand thread is cut towards the chuck with the spindle reversed (a tool of direction
// ccw); a multi-start thread repeats the passes with the start moved by one pitch per start (the
// lead is pitch x starts). (Z, radius), mm.
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/thread_mill/thread_mill.hpp"

namespace camgen {

// How the depth of a thread's passes grows.
enum class ThreadInfeed { constant_area, constant_depth };
inline constexpr Named<ThreadInfeed> thread_infeeds[] = {
    {ThreadInfeed::constant_area, "constant-area",
     "the depth after pass n is firstDepth x sqrt(n): each pass takes about the same chip area (Fanuc G76, LinuxCNC G76 R2)"},
    {ThreadInfeed::constant_depth, "constant-depth", "equal depths of at most firstDepth (LinuxCNC G76 R1)"},
};

// How the thread ends at endZ.
enum class ThreadRunout { straight, chamfered };
inline constexpr Named<ThreadRunout> thread_runouts[] = {
    {ThreadRunout::straight, "straight", "the tool leaves the thread straight out along X at endZ (into a relief groove or off the part)"},
    {ThreadRunout::chamfered, "chamfered",
     "each pass ends with a taper synchronised with the spindle, pulling out by the thread's depth over runoutLength "
     "(no relief groove needed; LinuxCNC G76 E L2)"},
};

struct TurnThreadOp {
    static constexpr std::string_view type = "turn-thread";
    static constexpr MachineKind machine_kind = MachineKind::lathe;
    // Reads one operation of this type (its "type" is already read).
    static TurnThreadOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    std::string comment;
    int tool = 0;
    std::string thread;                 // the designation ("M20x2.5"), or "" for one given by its diameters
    ThreadSide side = ThreadSide::external;
    ThreadHand hand = ThreadHand::right;
    double major = 0.0;                 // diameter, mm
    double minor = 0.0;                 // diameter, mm: d3 of an external thread, D1 of an internal one
    double pitch = 0.0;                 // mm
    int starts = 1;
    double start_z = 0.0;               // the thread's free end, mm
    double end_z = 0.0;                 // where it ends towards the chuck, mm
    ThreadRunout runout = ThreadRunout::straight;
    double runout_length = 0.0;         // a chamfered runout's length along Z, mm
    ThreadInfeed infeed = ThreadInfeed::constant_area;
    double first_depth = 0.0;           // radial, mm
    double min_depth = 0.0;             // radial, mm; 0: none
    int spring_passes = 1;
    double infeed_angle = 0.0;          // degrees from the radial direction
    double approach = 0.0;              // mm beyond startZ where each pass starts
    double retract = 1.0;               // radial mm outside the surface (inside the bore) for the returns
    CycleOutput output = CycleOutput::automatic;  // a threading cycle (ThreadCycle) or longhand passes
    std::vector<double> depths;         // the cumulative radial depth of each pass, the spring passes included
    std::vector<std::string> notes;
    // The lead, mm per revolution.
    double lead() const { return pitch * starts; }
    // The radius the thread starts from (the bar's major, the bore's minor) and the one it ends at.
    double surface_radius() const { return (side == ThreadSide::external ? major : minor) / 2.0; }
    double root_radius() const { return (side == ThreadSide::external ? minor : major) / 2.0; }
};

// The cumulative radial depths of a thread's cutting passes to `total` (spring passes not
// included): constant depth, equal steps of at most `first`; constant area, first x sqrt(n)
// while below total; a step below `min_depth` made min_depth; the last pass at total.
std::vector<double> thread_pass_depths(ThreadInfeed infeed, double total, double first, double min_depth);

// The threading cycle of one start (0, 1, ...): the drive point approachDistance beyond startZ
// (one pitch further per start) at the retract X; the passes' depths; the fields it uses.
ThreadCycle thread_cycle(const TurnThreadOp& op, int start);

// Output longhand: for each start, for each pass: rapid in air to the pass's start, in to its
// depth, a ThreadFeed to endZ, out to the retract X, back along Z; then back to the clearance.
// A chamfered runout: the ThreadFeed ends runoutLength above endZ, a second (tapered) one pulls
// out by the thread's depth to endZ, and the returns lie (depth - d) further out.
// Otherwise a ThreadCycle per start from its drive point (its passes end short of endZ by
// (depth - d) tan(infeedAngle), the flank's shadow of the last pass, as G76 cuts them).
void expand(const TurnThreadOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "turn thread <designation>".
std::string default_name(const TurnThreadOp& op);

}  // namespace camgen
