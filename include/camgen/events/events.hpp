#pragma once
// The event vocabulary between operations and posts, after LinuxCNC's canonical machining
// functions. Operations emit events; posts turn them into NC text; the reader turns NC text
// back into them. Units: mm, mm/min, seconds, rpm. Positions are absolute.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/geometry.hpp"
#include "camgen/geometry/lathe_cycle.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen {

enum class SpindleState { cw, ccw, off };
enum class CompensationSide { off, left, right };

// The absolute heights of an operation that moves between them itself (a contour): the plane
// it travels at, the stock top, and where rapid turns into feed.
struct OperationPlanes {
    double retract_z = 0.0;
    double reference_z = 0.0;
    double safe_z = 0.0;
    friend bool operator==(const OperationPlanes&, const OperationPlanes&) = default;
};

// An operation begins. `path` is its JSON path ("/operations/2"), for messages. `tolerance`
// is the operation's own tolerance for arcs that become lines (mm), if it has one.
// `feed_mode` is how the program states its feeds (the events' feeds stay mm/min).
struct OperationStart {
    std::string name;
    std::string path;
    std::optional<double> tolerance = std::nullopt;
    std::vector<std::string> notes = {};  // what the operation decided that the job did not ask for
    std::optional<OperationPlanes> planes = std::nullopt;
    FeedMode feed_mode = FeedMode::per_minute;
    friend bool operator==(const OperationStart&, const OperationStart&) = default;
};

// The operation that began last ends.
struct OperationEnd {
    friend bool operator==(const OperationEnd&, const OperationEnd&) = default;
};

// Change to a tool. Afterwards the tool's position is unknown but above every clearance
// (at the machine's tool-change position), so the next rapid goes XY first, then Z.
struct ToolChange {
    int number = 0;
    double diameter = 0.0;   // mm
    std::string description;
    friend bool operator==(const ToolChange&, const ToolChange&) = default;
};

// Spindle on (direction, rpm) or off. `surface_speed`: constant surface speed (G96), m/min at
// the work's diameter; then `rpm` is the spindle's limit (G50 S, D, LIMS=). 0: a constant rpm.
struct Spindle {
    SpindleState state = SpindleState::off;
    double rpm = 0.0;
    double surface_speed = 0.0;
    friend bool operator==(const Spindle&, const Spindle&) = default;
};

// Coolant on (flood or mist) or off. `path`: the JSON path of the job key that asked for it
// (for messages where the machine has no such coolant).
struct Coolant {
    CoolantMode mode = CoolantMode::off;
    std::string path;
    friend bool operator==(const Coolant&, const Coolant&) = default;
};

// Straight move at rapid rate to `to`.
struct Rapid {
    Vec3 to;
    friend bool operator==(const Rapid&, const Rapid&) = default;
};

// Straight move at `feed` mm/min to `to`.
struct Linear {
    Vec3 to;
    double feed = 0.0;
    Movement movement = Movement::cutting;
    friend bool operator==(const Linear&, const Linear&) = default;
};

// Circular move in `plane` from the current position to `to` around the absolute `centre`,
// clockwise or counter-clockwise as seen looking down the plane's normal axis (Z for XY,
// Y for XZ, X for YZ), at `feed` mm/min. When `to` differs from the start along the plane's
// normal axis the move is helical. `to` equal to the start (in the plane) is a full circle.
// `turns` counts extra full turns of a helix (0 for a plain arc).
struct Arc {
    Vec3 to;
    Vec3 centre;
    ArcDirection direction = ArcDirection::cw;
    Plane plane = Plane::xy;
    double feed = 0.0;
    int turns = 0;
    Movement movement = Movement::cutting;
    friend bool operator==(const Arc&, const Arc&) = default;
};

// The geometry of an Arc event that starts at `start` (see resolve_arc in geometry/arc.hpp).
inline ArcGeometry resolve_arc(const Vec3& start, const Arc& arc, double same_point = 1e-9) {
    return resolve_arc(start, ArcSpec{arc.to, arc.centre, arc.direction, arc.plane, arc.turns}, same_point);
}

// Stay in place for `seconds`.
struct Dwell {
    double seconds = 0.0;
    friend bool operator==(const Dwell&, const Dwell&) = default;
};

// Cutter radius compensation from the next move that can carry it (CNC-Calc onCompensation):
// the side, the control's offset register (D) and the tool radius it holds, so that a reader
// of the program can interpret it.
struct Compensation {
    CompensationSide side = CompensationSide::off;
    int d_register = 0;    // 0: the tool's number
    double radius = 0.0;   // mm; 0: unknown (only the control's tool table knows it)
    // A lathe's nose-radius compensation (G41/G42 in G18): the tool's tip orientation
    // (LinuxCNC's codes 1-8, lathe_tip_offset), the point the program moves being the imaginary
    // tip of that orientation; 0: a mill's cutter, or unknown (only the control's table knows it).
    int orientation = 0;
    friend bool operator==(const Compensation&, const Compensation&) = default;
};

// A drilling cycle, resolved to absolute values (the CNC-Calc drill header). Before it the
// tool stands above the first hole at retract_z. Between holes it returns to retract_z; the
// feed starts at safe_z; bottom_z is the bottom of the hole (drill tip already added).
struct DrillCycle {
    CycleKind kind = CycleKind::drill;
    CycleOutput output = CycleOutput::automatic;
    std::string path;                  // JSON path of the operation, for messages
    double retract_z = 0.0;
    double reference_z = 0.0;
    double safe_z = 0.0;
    double bottom_z = 0.0;
    double feed = 0.0;                 // mm/min, plunge (for taps: pitch x tapping rpm)
    double spindle_rpm = 0.0;          // the spindle speed the operation runs at
    SpindleDirection spindle_direction = SpindleDirection::cw;  // the operation's spindle direction
    DrillValues values;                // the optional fields set, resolved (mm, mm/min, s, rpm)
    // Where the machine cannot make the cycle at all: refused, or a stop for the operator that
    // lists its holes (OperatorStops, camgen/post/stops.hpp).
    UnsupportedCycle unsupported = UnsupportedCycle::refuse;
    friend bool operator==(const DrillCycle&, const DrillCycle&) = default;
};

// One hole of the current drilling cycle.
struct DrillPoint {
    Vec2 at;
    friend bool operator==(const DrillPoint&, const DrillPoint&) = default;
};

// The current drilling cycle ends; the tool is at retract_z above the last hole.
struct DrillEnd {
    friend bool operator==(const DrillEnd&, const DrillEnd&) = default;
};

// A comment for the operator.
struct Comment {
    std::string text;
    friend bool operator==(const Comment&, const Comment&) = default;
};

// How a program stop waits for the operator: always (M0), or only where the operator's
// optional-stop switch is on (M1).
enum class StopKind { mandatory, optional };

// The longest message of a stop (characters): every control shows it on one line.
inline constexpr std::size_t max_stop_message = 100;

// The program stops and shows `message` to the operator until the operator starts it again.
// A job's stop comes where the tool is at the clearance; the posts stop the spindle and the
// coolant before it and restart them after it (OperatorStops), and take the position as
// unknown after it (the operator may have moved the axes).
struct Stop {
    StopKind kind = StopKind::mandatory;
    std::string message;
    double spin_up = 0.0;  // s the program waits after it restarts the spindle (a job's stop; 0 read back)
    friend bool operator==(const Stop&, const Stop&) = default;
};

// The lines of a custom block for one machine (by its name) or one dialect.
struct CustomText {
    std::string name;
    std::vector<std::string> lines;
    friend bool operator==(const CustomText&, const CustomText&) = default;
};

// Lines written into the program as they are: those given for the machine's name, else for
// its dialect. The post reads them back with the machine's reader first and refuses what the
// reader cannot read and what would change the motion or the machine's state (docs/job-format.md,
// "custom").
struct CustomBlock {
    std::vector<CustomText> texts;
    std::string path;  // JSON path of the operation's "text", for messages
    friend bool operator==(const CustomBlock&, const CustomBlock&) = default;
};

// A straight move synchronised with the spindle (thread cutting: LinuxCNC and Sinumerik G33 K,
// Fanuc G32 F): the tool advances `lead` mm along Z per spindle revolution, from where it stands
// to `to`. Its feed is the lead times the spindle's rpm; the control waits for the spindle's
// index before it starts, so that every pass of a thread runs in the same groove. A move that
// changes X too (a chamfered runout's pull-out, at most 45 degrees from Z) still advances `lead`
// along Z per revolution: the posts write the word each control measures (LinuxCNC's K along the
// path, Fanuc's F and Sinumerik's K along Z, the longer axis).
struct ThreadFeed {
    Vec3 to;
    double lead = 0.0;  // mm per revolution along Z
    friend bool operator==(const ThreadFeed&, const ThreadFeed&) = default;
};

// A threading cycle (LinuxCNC G76, Fanuc's two-block G76, Sinumerik CYCLE97), resolved to
// absolute values (mm, radius). Before it the tool stands at `start`, the drive point: X the
// radius the last pass returns to, outside the thread (inside the bore), Z where the passes begin
// before the flank infeed moves them. Each pass of depth d (radial, from the crest) comes in at
// Z start.z - d tan(infeed_angle), cuts synchronised with the spindle to end_z + (depth - d)
// tan(infeed_angle) (the flank ends where the last pass does) and returns to the radius
// start.x + (depth - d) outward; after the last pass the tool stands at (start.x, end_z). Cut
// along -Z. With a chamfered runout (runout > 0, LinuxCNC G76 E L2) each pass's straight part
// ends `runout` above its end Z and a synchronised taper pulls the tool out by the thread's depth
// over that length (the last pass from the root to the crest, the earlier ones parallel to it,
// ending in air). `thread_cycle_moves` gives the moves, which posts without the cycle write
// longhand.
struct ThreadCycle {
    std::string path;                   // JSON path of the operation, for messages
    CycleOutput output = CycleOutput::automatic;
    Vec3 start;
    double end_z = 0.0;
    double lead = 0.0;                  // mm per revolution along Z
    double crest_x = 0.0;               // radius of the thread's crest (an internal thread's: the bore's)
    double first_depth = 0.0;           // radial depth of the first pass
    double depth = 0.0;                 // radial depth of the thread
    double degression = 2.0;            // the infeed rule: depth after pass n = first_depth x n^(1/degression)
    double min_depth = 0.0;             // the least radial depth of a pass, 0: none
    double infeed_angle = 0.0;          // degrees from radial
    int spring_passes = 0;
    std::vector<std::string> fields;    // what the canned cycle must carry ("constant-area", "infeedAngle", ...)
    std::vector<double> depths;         // each pass's cumulative radial depth, the spring passes included
    double runout = 0.0;                // a chamfered runout's length along Z (G76 E), 0: straight
    friend bool operator==(const ThreadCycle&, const ThreadCycle&) = default;
};

// A canned roughing cycle along -Z or -X (turn-rough's output: LinuxCNC's G71 or G72 with its
// profile as a subroutine), resolved to absolute values (mm, radius). Before it the tool stands at `start`
// (Z, radius in x); `profile` ((Z, radius)) is what the cycle roughs to: the finished profile
// moved by the allowances, as the tool tip follows it (a nose's tip path where camgen makes up
// for the nose), so that the control leaves no offset of its own (LinuxCNC D0). `moves` are
// the moves the control makes of it (camgen's model of the cycle, lathe_cycle.hpp), which a
// post without the cycle writes longhand, and which the safety check, the simulation and
// verify see. `refusal`: why the control's cycle cannot make this roughing (then `moves` is
// empty and the operation's own passes follow the event: a post notes the reason, or refuses
// it under output "canned").
// The turn-profile that finishes a roughing cycle's shape with Fanuc T's G70 (read_job links a
// turn-profile to the turn-rough right before it, of the same profile, where the cycle roughs the
// finishing pass's tip path moved by the allowances: docs/reference.md). Under Fanuc's pattern the
// cycle's shape is then `shape` and its second block's U/W the allowance; elsewhere nothing changes.
struct CycleFinish {
    std::string path;                   // the turn-profile's JSON path
    Profile shape;                      // the finishing pass's tip path (Z, radius)
    Vec2 allowance;                     // (Z, radius): the cycle's boundary less `shape` (Fanuc's W, U/2)
    double feed = 0.0;                  // the finishing feed, mm/min: written in the shape, where G70 takes it
    double rpm = 0.0;                   // the finishing tool's speed (a feed per revolution is feed / rpm)
    friend bool operator==(const CycleFinish& a, const CycleFinish& b) {
        return a.path == b.path && a.shape.plane == b.shape.plane && a.shape.start == b.shape.start &&
               a.shape.segments == b.shape.segments && a.allowance == b.allowance && a.feed == b.feed && a.rpm == b.rpm;
    }
};

struct TurnCycle {
    std::string path;                   // JSON path of the operation, for messages
    CycleOutput output = CycleOutput::automatic;
    Vec3 start;
    Profile profile;                    // (Z, radius)
    double depth = 0.0;                 // radial depth between levels (LinuxCNC I)
    double retract = 0.0;               // the 45-degree escape off each pass (LinuxCNC R)
    double feed = 0.0;                  // mm/min
    std::vector<LatheCycleMove> moves;  // what the control makes of it, from `start`
    std::optional<std::string> refusal;
    // Passes along -X at Z levels `depth` apart (LinuxCNC's G72: `profile` is then the boundary
    // walked backwards from the top of its end face, the control's G71 with Z and X swapped),
    // else along -Z (G71).
    bool along_x = false;
    // The way out after the cycle (turn-rough's), part of its moves (lift 0: none). LinuxCNC's
    // pattern ends on the last pass: a feed `lift` off it at 45 degrees (+X, +Z), a rapid out to
    // radius `out_x` (or the lift's, beyond it) and one to Z `out_z`. Fanuc's ends at its start
    // point A, in air beyond the part: a rapid out to radius out_x (or A's, beyond it) at A's Z
    // and one to out_z.
    double lift = 0.0;
    double out_x = 0.0;
    double out_z = 0.0;
    std::optional<CycleFinish> finish;  // a turn-profile finishes its shape with G70 (Fanuc's pattern)
    friend bool operator==(const TurnCycle& a, const TurnCycle& b) {
        auto same_profile = [](const Profile& x, const Profile& y) {
            return x.plane == y.plane && x.start == y.start && x.segments == y.segments;
        };
        return a.path == b.path && a.output == b.output && a.start == b.start && same_profile(a.profile, b.profile) &&
               a.depth == b.depth && a.retract == b.retract && a.feed == b.feed && a.moves == b.moves &&
               a.refusal == b.refusal && a.along_x == b.along_x && a.lift == b.lift && a.out_x == b.out_x &&
               a.out_z == b.out_z && a.finish == b.finish;
    }
};

// A turn-profile that finishes the shape of the Fanuc roughing cycle before it (CycleFinish) with
// G70 P Q: under Fanuc's pattern (finish_cycle_moves) from the clearance to the cycle's start
// point A, G70's moves (fanuc_g70: a rapid to A', the shape at `feed`, a rapid back to A) and out
// at rapid to radius out_x at A's Z, then to the clearance; in any other pattern, or where
// `refusal` says why G70 is not used, the turn-profile's own moves (`plain`).
using PlainMove = std::variant<Rapid, Linear, Arc, Compensation>;
struct FinishCycle {
    std::string path;                   // the turn-profile's JSON path
    CycleOutput output = CycleOutput::automatic;
    std::string rough_path;             // the turn-rough whose cycle's shape it runs
    bool along_x = false;               // the cycle is G72 (passes along X)
    Vec2 start;                         // the cycle's start point A (Z, radius)
    Profile shape;                      // the finishing pass's tip path (Z, radius)
    double feed = 0.0;                  // mm/min
    double clearance = 0.0;             // Z the tool comes from and leaves to
    double out_x = 0.0;                 // radius of the way out (retractX)
    std::vector<PlainMove> plain;       // the turn-profile's own moves
    std::optional<std::string> refusal; // why G70 does not finish it (then `plain` on every machine)
    friend bool operator==(const FinishCycle& a, const FinishCycle& b) {
        return a.path == b.path && a.output == b.output && a.rough_path == b.rough_path && a.along_x == b.along_x &&
               a.start == b.start && a.shape.start == b.shape.start && a.shape.segments == b.shape.segments &&
               a.feed == b.feed && a.clearance == b.clearance && a.out_x == b.out_x && a.plain == b.plain &&
               a.refusal == b.refusal;
    }
};

// A turn-groove's groove as a grooving cycle (Fanuc T's G75) would cut it, resolved (mm,
// radius). The blade is `width` wide; its programmed point is its left corner, or its right one
// (`right_point`); the Zs below are the left corner's. Before it the tool stands at `start()`:
// the approach radius `air` over the first plunge. `fields` names what the groove asks beyond
// plain plunges ("pecks", "fullRetract", "dwell", "finishPass", "chamfer"); a canned cycle must
// carry each. The moves (`groove_cycle_moves`, which posts without the cycle write longhand):
// - plain (fields within "pecks": no chamfer, dwell, full retract, and one plunge or no finishing
//   allowance): G75's pattern: plunges at first_z, first_z - z_step, ... while above last_z, then
//   at last_z; each fed down from `air` in pecks of `peck` counted from `air` (0: one feed), a
//   rapid back-off of `retract` between them, to `bottom` + `finish`, then a rapid out to `air`,
//   and along Z at `air` to the next; after the last, back along Z to the start.
// - otherwise turn-groove's own: the same plunges but pecks counted from `surface` (a full
//   retract out to `air` and back to `retract` above the depth reached), the last plunge on to
//   the bottom and along it to the +Z wall (a dwell at both ends), or one plunge's dwell at the
//   bottom; then the chamfers (the right corner down the +Z edge's, the left down the -Z edge's).
// `side` says where: external (the above: cut along -X into an outside diameter, every move
// along Z at `air`); internal (into a bore, along +X: the radii the same but `air` < `surface`
// < `bottom`, "down" is +X, `finish` and `peck` still positive); face (into an end face, along
// -Z: `air`, `surface`, `bottom` are Zs, `first_z`/`last_z`/`z_step` radii of the blade's inner
// (-X) corner, `width` along X, every move along X at the Z `air`). `at` maps (depth coordinate,
// step coordinate) to the programmed point alike.
enum class GrooveSide { external, internal, face };
struct GrooveCycle {
    std::string path;                   // JSON path of the operation, for messages
    CycleOutput output = CycleOutput::automatic;
    double width = 0.0;                 // the blade's width
    bool right_point = false;           // the programmed point is the blade's right (+Z) corner
    double air = 0.0;                   // radius of the approach level, where the tool stands
    double surface = 0.0;               // radius of the surface the groove is cut into
    double bottom = 0.0;                // radius of the groove's bottom
    double finish = 0.0;                // radial allowance the plunges leave for the pass along the bottom
    double first_z = 0.0;               // the left corner's Z at the first plunge (the +Z wall less the width)
    double last_z = 0.0;                // the left corner's Z at the last plunge (the -Z wall)
    double z_step = 0.0;                // the distance between plunges (the last one shorter), 0: one plunge
    double chamfer = 0.0;               // each edge's 45-degree chamfer
    double peck = 0.0;                  // radial depth of each peck, 0: one feed
    double retract = 0.0;               // back-off between pecks (full retract: how far above the depth it returns)
    bool full_retract = false;
    double dwell = 0.0;                 // s
    double feed = 0.0;                  // mm/min
    std::vector<std::string> fields;    // what the canned cycle must carry
    GrooveSide side = GrooveSide::external;
    // The programmed point of the blade whose left corner is at radius r, Z left_z (a face
    // groove: whose inner corner is at Z r, radius left_z).
    Vec3 at(double r, double left_z) const {
        if (side == GrooveSide::face) return {left_z + (right_point ? width : 0.0), 0.0, r};
        return {r, 0.0, left_z + (right_point ? width : 0.0)};
    }
    // +1 where the groove's depth coordinate falls into the material (external: radius, face:
    // Z), -1 where it rises (internal: radius).
    double into() const { return side == GrooveSide::internal ? -1.0 : 1.0; }
    Vec3 start() const { return at(air, first_z); }
    // The moves follow G75's pattern (see above).
    bool plain() const;
    // The left corner's Z of each plunge.
    std::vector<double> plunges() const;
    friend bool operator==(const GrooveCycle&, const GrooveCycle&) = default;
};

using Event = std::variant<OperationStart, OperationEnd, ToolChange, Spindle, Coolant, Rapid, Linear, Arc,
                           Dwell, Compensation, DrillCycle, DrillPoint, DrillEnd, Comment, Stop, CustomBlock,
                           ThreadFeed, ThreadCycle, TurnCycle, GrooveCycle, FinishCycle>;

// How a roughing cycle moves: LinuxCNC's G71/G72 (the event's `moves`), or Fanuc T's type I
// G71/G72 (fanuc_g7x in lathe_cycle.hpp from the start point A: the event's start moved out by
// one depth of cut (along X: towards +Z), so that its levels are the event's; each pass back
// along Z (along X) to A's; the tool ends at A). Where Fanuc's model does not take the cycle,
// its moves are LinuxCNC's.
enum class RoughCyclePattern { linuxcnc_g71, fanuc_g71 };

// The moves of a roughing cycle (Rapid, Linear and Arc events in XZ at the cycle's feed), from
// its start, and its way out (turn_cycle_exit): none where the cycle carries a refusal.
std::vector<Event> turn_cycle_moves(const TurnCycle& cycle, RoughCyclePattern pattern = RoughCyclePattern::linuxcnc_g71);
// The control's moves of the cycle as LatheCycleMove (Z, radius) in the pattern (no way out);
// and where the tool ends after the way out.
std::vector<LatheCycleMove> turn_cycle_path(const TurnCycle& cycle, RoughCyclePattern pattern);
Vec3 turn_cycle_end(const TurnCycle& cycle, RoughCyclePattern pattern);
// The way out after the control's moves (lift, out_x, out_z), in the pattern: written longhand
// after a canned cycle too.
std::vector<Event> turn_cycle_exit(const TurnCycle& cycle, RoughCyclePattern pattern);
// A finishing cycle's moves in the machine's roughing pattern (FinishCycle), from the clearance; and
// where they end.
std::vector<Event> finish_cycle_moves(const FinishCycle& cycle, RoughCyclePattern pattern);
Vec3 finish_cycle_end(const FinishCycle& cycle, RoughCyclePattern pattern);
// Under G70, the moves before it (from the clearance to A) and after it (from A, where G70
// ends, out to the clearance): finish_cycle_moves is entry, G70's moves, exit.
std::vector<Event> finish_cycle_entry(const FinishCycle& cycle);
std::vector<Event> finish_cycle_exit(const FinishCycle& cycle);
// Whether G70 finishes it in this pattern (Fanuc's, no refusal).
inline bool finish_cycle_g70(const FinishCycle& cycle, RoughCyclePattern pattern) {
    return pattern == RoughCyclePattern::fanuc_g71 && !cycle.refusal;
}
// The cycle's shape under Fanuc's pattern written for G70 from A (fanuc_g7x_shape of the
// finishing shape), and the control's G70 moves on it.
Profile finish_cycle_written_shape(const FinishCycle& cycle);
// Fanuc's start point A for a roughing cycle (Z, radius): the event's start moved out by depth
// (along X: moved by depth towards +Z).
Vec2 fanuc_g71_start(const TurnCycle& cycle);

// How a threading cycle's passes move in air: LinuxCNC's G76 (each pass returns out to the drive
// line moved out by depth - d, the next pass starts from there; the tool ends at (start.x, end_z))
// or Fanuc's two-block G76 (each pass from and back to the start point at start.x, Z the start;
// the tool ends where it began). The cutting passes are the same.
enum class ThreadCyclePattern { linuxcnc_g76, fanuc_g76 };


// The moves of a grooving cycle (Rapid, Linear, Dwell), from its start; and where they end.
std::vector<Event> groove_cycle_moves(const GrooveCycle& cycle);
Vec3 groove_cycle_end(const GrooveCycle& cycle);

// The moves of a threading cycle (Rapid and ThreadFeed events), from its drive point.
std::vector<Event> thread_cycle_moves(const ThreadCycle& cycle,
                                      ThreadCyclePattern pattern = ThreadCyclePattern::linuxcnc_g76);
// Where the tool stands after them.
Vec3 thread_cycle_end(const ThreadCycle& cycle, ThreadCyclePattern pattern = ThreadCyclePattern::linuxcnc_g76);

// Receives events one at a time (a post, a recorder, the event printer).
class EventSink {
public:
    virtual ~EventSink() = default;
    virtual void emit(const Event& event) = 0;
};

// Keeps every event it receives.
class EventRecorder : public EventSink {
public:
    void emit(const Event& event) override { events.push_back(event); }
    std::vector<Event> events;
};

// Writes each event as one JSON object per line (`camgen --events`).
class EventPrinter : public EventSink {
public:
    explicit EventPrinter(std::ostream& out) : out_(out) {}
    void emit(const Event& event) override;

private:
    std::ostream& out_;
};

// The JSON text of one event (no line break).
std::string event_to_json(const Event& event);

}  // namespace camgen
