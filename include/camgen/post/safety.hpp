#pragma once
// Safety checks on the events of a job, before a post writes any text: rapids below the
// retract plane, feeds that start inside the stock where no hole is, planes in the wrong
// order, holes deeper than the tool's flutes. Each failure is an InputError naming the
// operation's JSON path.
#include <map>
#include <unordered_map>
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

private:
    // A rapid or feed move to `to` (feed: true for a feed move).
    void move(const Vec3& to, bool feed);
    // The Z a hole at `at` has been drilled down to, if any.
    std::optional<double> drilled_to(Vec2 at) const;
    // InputError at the current operation's path plus `key`.
    [[noreturn]] void fail(const std::string& key, const std::string& detail) const;

    SafetyLimits limits_;
    std::string op_path_;                  // the current operation's JSON path
    std::optional<DrillCycle> cycle_;      // the drilling cycle running, if any
    std::optional<double> op_retract_z_;   // the current operation's retract plane (else the clearance)
    std::optional<double> op_reference_z_; // the current operation's reference plane, if it has one
    std::optional<double> op_safe_z_;      // where a contour's rapid approach may end
    bool last_was_feed_ = false;           // the tool got where it is by feed
    std::optional<Vec3> pos_;              // where the tool is (unknown after a tool change)
    int tool_ = 0;
    // The key of an XY position in the hole table (nm) and its hash.
    using HoleKey = std::pair<long long, long long>;
    struct HoleHash {
        std::size_t operator()(const HoleKey& k) const noexcept {
            return std::hash<long long>{}(k.first * 0x9E3779B97F4A7C15LL ^ k.second);
        }
    };
    // The Z each hole reaches, by XY in nm: hashed, as a job of a million holes looks up
    // every one of them.
    std::unordered_map<HoleKey, double, HoleHash> holes_;
    // The hole looked up last (its entry stays put as the table grows): a cycle's pecks all
    // look up the hole they are in.
    mutable HoleKey last_key_{};
    mutable double* last_hole_ = nullptr;
    LonghandBuffers longhand_buffers_;     // reused by every hole's moves
    std::optional<std::string> pending_descent_;  // a rapid down to a retract plane not yet known: the error
    double pending_z_ = 0.0;                      // ... and the Z it went down to
};

// Runs every check over `events`; throws InputError at the first unsafe one.
void check_safety(const std::vector<Event>& events, const SafetyLimits& limits);

}  // namespace camgen
