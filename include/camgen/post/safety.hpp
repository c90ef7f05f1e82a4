#pragma once
// Safety checks on the events of a job, before a post writes any text: rapids below the
// retract plane, feeds that start inside the stock where no hole is, planes in the wrong
// order, holes deeper than the tool's flutes. Each failure is an InputError naming the
// operation's JSON path. Where the job gives a stock, an operation that goes below its bottom
// gets a warning (a through-cut does by design; a 30 mm cut in a 10 mm plate must not pass
// silently).
#include <cstddef>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/post/longhand.hpp"

namespace camgen {

// What the checks need to know besides the events.
struct SafetyLimits {
    double clearance = 0.0;                // absolute Z, mm: the job's clearance
    std::map<int, double> flute_lengths;   // mm, by tool number (tools that give fluteLength)
    LonghandOptions longhand;              // how the machine's cycles move (peck clearance)
    // On a lathe the retract-plane rules hold for moves on the spindle axis (a turn-drill's);
    // a move off the axis is a turning move, whose air lies outside the part radially, not
    // above it in Z: the turning operations plan it there and check it themselves
    // (check_turned_material, check_blade_material, turn-face and turn-rough by construction).
    MachineKind kind = MachineKind::mill;
    // How the machine's roughing and finishing cycles move (Machine::rough_pattern): the
    // cycles are checked as the control runs them.
    RoughCyclePattern rough_pattern = RoughCyclePattern::linuxcnc_g71;
};

// The holes drilled so far: the lowest Z reached at each XY (keyed in nm). A job of a million
// holes drills each once, one after the other, and looks up only the hole it is in, so holes
// are appended to a log (24 bytes each, no allocation per hole, no random access) and sorted
// only when a lookup needs another hole: what was appended since becomes a sorted run, and runs
// of similar size are merged (a binary counter), so an append costs O(log n) amortized and a
// lookup O(log^2 n) even when lookups and new holes alternate.
class DrilledHoles {
public:
    // Makes room for `holes` more holes in the log at once (a million holes grow it by
    // doubling otherwise: 48 MB touched and copied for 24 MB kept).
    void reserve(std::size_t holes);
    // Records that the hole at `at` reaches down to `z` (mm).
    void drill(Vec2 at, double z);
    // Whether a hole at `at` has been drilled down to `z` or deeper (within `eps`, mm).
    bool reaches(Vec2 at, double z, double eps);
    // The lowest Z a hole at `at` has been drilled to, if any.
    std::optional<double> depth_at(Vec2 at);

private:
    // A hole: its XY in nm and the lowest Z (mm) one drilling reached there.
    struct Entry {
        long long x = 0, y = 0;
        double z = 0.0;
    };
    static Entry entry_of(Vec2 at, double z);
    static bool same_place(const Entry& a, const Entry& b) { return a.x == b.x && a.y == b.y; }
    // The log's order: by X, then Y.
    static bool before(const Entry& a, const Entry& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }
    // depth_at of an entry's place.
    std::optional<double> lowest_at(const Entry& place);
    // The lowest Z of the logged entries at `place`'s XY, if any (sorts the log's tail first).
    std::optional<double> logged_depth(const Entry& place);
    // Turns the unsorted tail of the log into a run and merges runs of similar size.
    void sort_tail();

    // The hole being drilled now (not in the log yet): the pecks of a cycle deepen it and look
    // it up without touching the log.
    std::optional<Entry> current_;
    std::vector<Entry> log_;                // sorted runs, then the tail in drilling order
    std::vector<std::size_t> run_ends_;     // where each sorted run ends in log_
};

// An event sink that checks the motion of the events it receives; drilling cycles are
// checked as the moves they make (canned and longhand move alike).
class SafetyCheck : public EventSink {
public:
    explicit SafetyCheck(SafetyLimits limits);
    // Checks one event; throws InputError at the first unsafe one.
    void emit(const Event& event) override;
    // After the last event: throws if a descent is still waiting for its drilling cycle.
    void finish();
    // Room for `holes` holes in the log of holes drilled (a hint: the holes a job's drilling
    // operations drill, known once it is read; more still fit).
    void reserve_holes(std::size_t holes) { holes_.reserve(holes); }
    // Where the job gives a stock: an operation whose moves go below `bottom` (absolute Z, mm)
    // gets a warning on `warnings` ("camgen: warning: PATH: ..."), at its end.
    void warn_below_stock(double bottom, std::ostream& warnings) {
        stock_bottom_ = bottom;
        warnings_ = &warnings;
    }

private:
    // A rapid or feed move to `to` (feed: true for a feed move).
    void move(const Vec3& to, bool feed);
    // Whether a hole at `at` reaches `z`; notes whether the hole being checked answered it.
    bool drilled(Vec2 at, double z);
    // Checks the moves of one hole of the running cycle.
    void drill_point(Vec2 at);

    // What the moves of a cycle's hole depend on besides its XY: where the tool starts (its
    // height, how it got there) and how far across it goes. Two holes of one cycle with the
    // same shape make the same moves, shifted in XY (longhand_moves).
    struct HoleShape {
        double from_z = 0.0;
        bool from_feed = false;
        int across = 0;  // 0: already at the hole; 1: within eps of it; 2: farther
        friend bool operator==(const HoleShape&, const HoleShape&) = default;
    };
    HoleShape shape_of(Vec2 hole) const;
    // A hole whose moves passed, and every lookup of which was answered by its own feeds: a
    // hole of the same shape passes as well (its own feeds drill the same depths before the
    // same lookups, and more drilling only answers more lookups), so its moves need not be
    // made and checked again. Only the drilling and where it leaves the tool remain.
    struct CheckedHole {
        HoleShape shape;
        std::optional<double> lowest_z;  // the lowest of its feeds straight down, if any
        double end_z = 0.0;              // where it leaves the tool, above the hole
        bool end_feed = false;           // ... and whether by a feed
    };
    std::optional<CheckedHole> checked_hole_;  // the last hole checked, if the last event
    // While a hole's moves are checked: the hole, the lowest Z its own feeds reached so far, and
    // whether every lookup so far was answered by them.
    std::optional<Vec2> hole_checked_;
    std::optional<double> own_depth_;
    bool own_answers_ = true;
    // InputError at the current operation's path plus `key`.
    [[noreturn]] void fail(const std::string& key, const std::string& detail) const;

    SafetyLimits limits_;
    std::string op_path_;                  // the current operation's JSON path
    std::optional<DrillCycle> cycle_;      // the drilling cycle running, if any
    std::optional<double> op_retract_z_;   // the current operation's retract plane (else the clearance)
    std::optional<double> op_reference_z_; // the current operation's reference plane, if it has one
    std::optional<double> op_safe_z_;      // where a contour's rapid approach may end
    bool op_planeless_ = false;            // the operation has no retract and reference planes (a
                                           // lathe's turning operations: its moves on the axis too)
    bool last_was_feed_ = false;           // the tool got where it is by feed
    std::optional<Vec3> pos_;              // where the tool is (unknown after a tool change)
    int tool_ = 0;
    DrilledHoles holes_;
    LonghandBuffers longhand_buffers_;     // reused by every hole's moves
    std::optional<double> stock_bottom_;   // the stock bottom, where a warning is wanted
    std::ostream* warnings_ = nullptr;     // ... and where it goes
    std::optional<double> op_lowest_z_;    // the lowest Z the current operation's moves reach
    // Lowers op_lowest_z_ to `z`.
    void reach(double z);
    std::optional<std::string> pending_descent_;  // a rapid down to a retract plane not yet known: the error
    double pending_z_ = 0.0;                      // ... and the Z it went down to
};

// Runs every check over `events`; throws InputError at the first unsafe one.
void check_safety(const std::vector<Event>& events, const SafetyLimits& limits);

}  // namespace camgen
