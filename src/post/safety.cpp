#include "camgen/post/safety.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/events/visit.hpp"

namespace camgen {

namespace {
// Two positions closer than this (mm) are the same; a Z this far past a plane is past it.
constexpr double eps = 1e-6;

std::string z_of(double z) { return fmt::format("{:.3f}", z); }

// The key of an XY position in the hole map (nm).
std::pair<long long, long long> key_of(Vec2 at) { return {std::llround(at.x * 1e6), std::llround(at.y * 1e6)}; }
}  // namespace

SafetyCheck::SafetyCheck(SafetyLimits limits) : limits_(std::move(limits)) {}

void SafetyCheck::fail(const std::string& key, const std::string& detail) const {
    throw InputError(op_path_ + key, detail);
}

std::optional<double> SafetyCheck::drilled_to(Vec2 at) const {
    const auto key = key_of(at);
    if (last_hole_ && key == last_key_) return *last_hole_;
    const auto it = holes_.find(key);
    if (it == holes_.end()) return std::nullopt;
    last_key_ = key;
    last_hole_ = const_cast<double*>(&it->second);
    return it->second;
}

void SafetyCheck::move(const Vec3& to, bool feed) {
    const double retract = op_retract_z_.value_or(limits_.clearance);
    if (!pos_) {
        // From the tool-change position the post goes up, across, then down: only the end counts.
        if (!feed && to.z < retract - eps && !cycle_)
            fail("", fmt::format("a rapid after the tool change ends at Z {}, below the retract plane (Z {})", z_of(to.z),
                                 z_of(retract)));
        pos_ = to;
        return;
    }
    const Vec3 from = *pos_;
    const bool across = std::abs(from.x - to.x) > eps || std::abs(from.y - to.y) > eps;
    const Vec2 xy{to.x, to.y};
    if (!feed) {
        if (across && std::min(from.z, to.z) < retract - eps)
            fail("", fmt::format("a rapid from X{} Y{} to X{} Y{} runs at Z {}, below the retract plane (Z {})",
                                 z_of(from.x), z_of(from.y), z_of(to.x), z_of(to.y), z_of(std::min(from.z, to.z)),
                                 z_of(retract)));
        if (!across && to.z < from.z - eps && to.z < retract - eps) {
            // Down below the retract plane: only the final approach to the feed-start plane, or
            // back into a hole already drilled at least that deep.
            const bool approach = (cycle_ && to.z >= cycle_->safe_z - eps) || (op_safe_z_ && to.z >= *op_safe_z_ - eps);
            const auto drilled_deep_enough = [&] {
                const std::optional<double> hole = drilled_to(xy);
                return hole && *hole <= to.z + eps;
            };
            if (!approach && !drilled_deep_enough()) {
                const std::string message = fmt::format("a rapid down to Z {} at X{} Y{} goes below the retract plane (Z {}) where no "
                                     "hole has been drilled that deep",
                                     z_of(to.z), z_of(to.x), z_of(to.y), z_of(retract));
                // Before its cycle a drilling operation goes down to its retract plane, which
                // the cycle event that follows names.
                if (cycle_) fail("", message);
                if (pending_descent_) fail("", *pending_descent_);
                pending_descent_ = message;
                pending_z_ = to.z;
            }
        }
    } else if (!last_was_feed_ && op_reference_z_ && from.z < *op_reference_z_ - eps) {
        // Below the stock top a feed may go on from where a feed (or arc) brought the tool.
        const std::optional<double> hole = drilled_to({from.x, from.y});
        if (!(hole && *hole <= from.z + eps))
            fail("", fmt::format("a feed starts at Z {}, below the reference plane (Z {}), at X{} Y{} where no hole has "
                                 "been drilled: the tool would plunge into the stock at rapid",
                                 z_of(from.z), z_of(*op_reference_z_), z_of(from.x), z_of(from.y)));
    }
    // A feed straight down makes (or deepens) a hole.
    if (feed && !across && to.z < from.z) {
        const auto key = key_of(xy);
        if (last_hole_ && key == last_key_) {
            *last_hole_ = std::min(*last_hole_, to.z);
        } else {
            auto [it, added] = holes_.try_emplace(key, to.z);
            if (!added) it->second = std::min(it->second, to.z);
            last_key_ = key;
            last_hole_ = &it->second;
        }
    }
    pos_ = to;
    last_was_feed_ = feed;
}

void SafetyCheck::finish() {
    if (pending_descent_) fail("", *pending_descent_);
}

void SafetyCheck::emit(const Event& event) {
    if (pending_descent_) {
        const auto* c = std::get_if<DrillCycle>(&event);
        if (!c || c->retract_z > pending_z_ + eps) fail("", *pending_descent_);
        pending_descent_.reset();
    }
    visit_exhaustive(
        overloaded{
            [&](const OperationStart& op) {
                op_path_ = op.path;
                op_retract_z_.reset();
                op_reference_z_.reset();
                op_safe_z_.reset();
                if (op.planes) {
                    op_retract_z_ = op.planes->retract_z;
                    op_reference_z_ = op.planes->reference_z;
                    op_safe_z_ = op.planes->safe_z;
                }
            },
            [&](const OperationEnd&) {
                op_retract_z_.reset();
                op_reference_z_.reset();
                op_safe_z_.reset();
            },
            [&](const ToolChange& t) {
                tool_ = t.number;
                pos_.reset();
            },
            [&](const Spindle&) {},
            [&](const Rapid& r) { move(r.to, false); },
            [&](const Linear& l) { move(l.to, true); },
            [&](const Arc& a) {
                // An arc's ends: it does not start a hole; its plunge was a feed move before it.
                pos_ = a.to;
                last_was_feed_ = true;
            },
            [&](const Dwell&) {},
            [&](const Compensation&) {},
            [&](const DrillCycle& c) {
                if (c.retract_z < c.reference_z - eps)
                    fail("/retractPlane", fmt::format("the retract plane (Z {}) is below the reference plane (Z {}): "
                                                      "the tool would rapid through the stock between holes",
                                                      z_of(c.retract_z), z_of(c.reference_z)));
                if (limits_.clearance < c.retract_z - eps)
                    fail("/retractPlane", fmt::format("the clearance (Z {}) is below the retract plane (Z {}): moves "
                                                      "at the clearance would run below this operation's retract plane",
                                                      z_of(limits_.clearance), z_of(c.retract_z)));
                if (auto it = limits_.flute_lengths.find(tool_); it != limits_.flute_lengths.end()) {
                    const double depth = c.reference_z - c.bottom_z;
                    if (depth > it->second + eps)
                        fail("/endDepth", fmt::format("the hole is {} mm deep below the reference plane, but tool {} "
                                                      "has a fluteLength of {} mm",
                                                      fmt::format("{:.3f}", depth), tool_,
                                                      fmt::format("{:.3f}", it->second)));
                }
                cycle_ = c;
                op_retract_z_ = c.retract_z;
                op_reference_z_ = c.reference_z;
            },
            [&](const DrillPoint& p) {
                if (!cycle_) throw std::logic_error("drilling point outside a cycle");
                if (!pos_) throw std::logic_error("drilling from an unknown position");
                for (const LonghandMove& m : longhand_moves(*cycle_, *pos_, p.at, limits_.longhand, longhand_buffers_))
                    visit_exhaustive(overloaded{[&](const Rapid& r) { move(r.to, false); },
                                                [&](const Linear& l) { move(l.to, true); }, [](const Dwell&) {},
                                                [](const Spindle&) {}},
                                     m);
            },
            [&](const DrillEnd&) { cycle_.reset(); },
            [&](const Comment&) {},
            [&](const Coolant&) {},
        },
        event);
}

void check_safety(const std::vector<Event>& events, const SafetyLimits& limits) {
    SafetyCheck check(limits);
    for (const Event& e : events) check.emit(e);
    check.finish();
}

}  // namespace camgen
