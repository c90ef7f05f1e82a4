#pragma once
// Cutter radius compensation (G41/G42 in the XY plane) as a control applies it: programmed moves
// in, tool-centre moves out. The rules are LinuxCNC's interpreter's (rs274ngc: interp_convert.cc
// convert_straight_comp1/2, convert_arc_comp2, interp_queue.cc), so that camgen sees what that
// control cuts, and refuses what it refuses:
//
// - G41/G42 does not move. The first move after it must be straight and longer than the radius;
//   the tool ends a radius from its programmed end, square to the move (to the left for G41).
// - Each later move is offset by the radius; a convex corner gets an arc about the programmed
//   corner (a rapid: a straight line to the same point), a concave one moves the end of the
//   previous move (and of the moves without XY motion after it) back to where the two offsets
//   meet. A corner whose trimmed move would run backwards, or an arc the tool cannot fit in, is an
//   error with the control's own message.
// - G40 does not move either: the next move runs straight from the tool's compensated position to
//   its programmed end, and must not be an arc.
//
// Machine-free: depends on nothing of camgen but the geometry's own types. Lengths mm.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/geometry.hpp"

namespace camgen {

// A move in XY with Z: programmed (the control's input) or of the tool centre (its output).
struct CompMove {
    enum class Kind { rapid, feed, arc };
    Kind kind = Kind::feed;
    Vec3 end;
    Vec2 centre;                                  // an arc's absolute centre
    ArcDirection direction = ArcDirection::ccw;   // an arc's turning, seen from +Z
    int turns = 0;                                // an arc's full turns beyond the first
    std::size_t source = 0;                       // the caller's tag, carried to the tool moves made from it
};

enum class CompSide { off, left, right };

// What the control refuses (or camgen cannot follow: unmodelled), and at which programmed move (its `source`).
struct CompError {
    std::string message;
    std::size_t source = 0;
    bool unmodelled = false;  // the control may run it, camgen cannot follow it (not the control's refusal)
};

class CutterCompensation {
public:
    using Sink = std::function<void(const CompMove&)>;
    explicit CutterCompensation(Sink sink) : sink_(std::move(sink)) {}

    // Where the tool is (compensation off): the start of the next move.
    void set_position(Vec3 p);
    std::optional<Vec3> position() const { return known_ ? std::optional<Vec3>(tool_) : std::nullopt; }
    // The programmed point the next move starts from (under compensation: not the tool's).
    std::optional<Vec3> programmed_position() const { return known_ ? std::optional<Vec3>(programmed_) : std::nullopt; }

    // G41 (left) / G42 (right) with the radius the control offsets by (0: nothing is offset).
    std::optional<CompError> on(CompSide side, double radius, std::size_t source);
    // G40.
    std::optional<CompError> off(std::size_t source);
    // A programmed move. The tool-centre moves reach the sink in order, each once it is final
    // (up to one XY move and the moves after it without XY motion wait for the next move).
    std::optional<CompError> move(const CompMove& programmed);
    // Hands the waiting moves to the sink (at the end of a program, or before anything that is
    // not a move in XY, such as a drilling cycle, which the control refuses under compensation).
    void flush();

    bool active() const { return side_ != CompSide::off; }
    CompSide side() const { return side_; }
    double radius() const { return radius_; }

private:
    struct Queued {
        CompMove move;
        Vec2 direction;              // straight moves: the programmed direction (0: no XY motion)
        double original_sweep = 0;   // arcs: the sweep as programmed (0: a corner arc, never moved)
    };
    std::optional<CompError> entry(const CompMove& p);
    std::optional<CompError> straight(const CompMove& p);
    std::optional<CompError> arc(const CompMove& p);
    std::optional<CompError> move_endpoint_and_flush(Vec2 to, std::size_t source);
    void dequeue();
    void enqueue(const CompMove& m, Vec2 direction, double original_sweep);

    Sink sink_;
    CompSide side_ = CompSide::off;
    double radius_ = 0;
    bool first_ = true;             // no move since G41/G42
    bool arc_not_allowed_ = false;  // the move just after G40
    bool known_ = false;
    Vec3 tool_;                     // where the tool centre is (after the queued moves)
    Vec3 programmed_;               // the programmed point the tool is offset from
    std::vector<Queued> queue_;
    Vec2 endpoint_;                 // where the first queued move starts
    bool endpoint_valid_ = false;
};

// The signed angle an arc turns from `from` to `to` about `centre` (ccw positive), with `turns`
// extra full turns; a full circle when the ends coincide.
double arc_sweep(Vec2 from, Vec2 centre, ArcDirection direction, int turns, Vec2 to);

// Where a lathe tool's imaginary tip lies from its nose centre, (Z, radius) in mm, for tip
// orientation `orientation` (LinuxCNC's codes, rs274ngc interp_queue.cc latheorigin_x/z: the tip
// lies -X of the centre for 1, 2, 6, +X for 3, 4, 8, +Z for 1, 4, 5, -Z for 2, 3, 7, each by
// the radius; 9 and 0: at the centre) and nose radius `radius`.
Vec2 lathe_tip_offset(int orientation, double radius);

// Where the imaginary tip of `orientation` lies from the nose centre, in words for an operator's
// comment: "tip at -X -Z of the nose centre" (9, 0: "tip at the nose centre").
std::string lathe_tip_words(int orientation);

// Fanuc T's imaginary tip number for LinuxCNC's orientation `orientation`, and back (the map is
// its own inverse). Fanuc (and Haas, whose operator's manual gives it in words) numbers the
// direction from the nose centre to the tip: 1 +X+Z, 2 +X-Z, 3 -X-Z, 4 -X+Z, 5 +Z, 6 +X, 7 -Z,
// 8 -X; LinuxCNC's codes are the same figure mirrored in X (its 2 is Fanuc's 3, the outside
// turning tool): 1<->4, 2<->3, 6<->8, 5, 7, 9 and 0 alike. docs/reference.md, "Tip numbers".
int fanuc_tip_number(int orientation);

}  // namespace camgen
