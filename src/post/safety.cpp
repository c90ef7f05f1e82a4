#include "camgen/post/safety.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/large_buffer.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/geometry/arc.hpp"

namespace camgen {

namespace {
// Two positions closer than this (mm) are the same; a Z this far past a plane is past it.
constexpr double eps = 1e-6;

std::string z_of(double z) { return fmt::format("{:.3f}", z); }

}  // namespace

DrilledHoles::Entry DrilledHoles::entry_of(Vec2 at, double z) {
    return {std::llround(at.x * 1e6), std::llround(at.y * 1e6), z};
}

void DrilledHoles::reserve(std::size_t holes) { reserve_large(log_, log_.size() + holes); }

void DrilledHoles::drill(Vec2 at, double z) {
    const Entry hole = entry_of(at, z);
    if (current_ && same_place(*current_, hole)) {
        current_->z = std::min(current_->z, z);
        return;
    }
    if (current_) log_.push_back(*current_);
    current_ = hole;
}

bool DrilledHoles::reaches(Vec2 at, double z, double eps) {
    const Entry place = entry_of(at, z);
    // A peck goes back into the hole it is drilling: no need to ask the log.
    if (current_ && same_place(*current_, place) && current_->z <= z + eps) return true;
    const std::optional<double> depth = lowest_at(place);
    return depth && *depth <= z + eps;
}

std::optional<double> DrilledHoles::depth_at(Vec2 at) { return lowest_at(entry_of(at, 0.0)); }

std::optional<double> DrilledHoles::lowest_at(const Entry& place) {
    std::optional<double> depth = logged_depth(place);
    if (current_ && same_place(*current_, place)) depth = std::min(depth.value_or(current_->z), current_->z);
    return depth;
}

std::optional<double> DrilledHoles::logged_depth(const Entry& place) {
    sort_tail();
    std::optional<double> depth;
    std::size_t begin = 0;
    for (const std::size_t end : run_ends_) {
        const auto first = log_.begin() + static_cast<std::ptrdiff_t>(begin);
        const auto last = log_.begin() + static_cast<std::ptrdiff_t>(end);
        // A place drilled twice (by two operations) has an entry for each.
        for (auto it = std::lower_bound(first, last, place, before); it != last && same_place(*it, place); ++it)
            depth = std::min(depth.value_or(it->z), it->z);
        begin = end;
    }
    return depth;
}

void DrilledHoles::sort_tail() {
    const std::size_t sorted = run_ends_.empty() ? 0 : run_ends_.back();
    if (sorted == log_.size()) return;
    std::sort(log_.begin() + static_cast<std::ptrdiff_t>(sorted), log_.end(), before);
    run_ends_.push_back(log_.size());
    // Merge the last run into the one before while it is at least as long: run lengths then
    // at least halve from run to run, so there are at most log2(n) of them.
    while (run_ends_.size() >= 2) {
        const std::size_t end = run_ends_.back();
        const std::size_t middle = run_ends_[run_ends_.size() - 2];
        const std::size_t begin = run_ends_.size() >= 3 ? run_ends_[run_ends_.size() - 3] : 0;
        if (end - middle < middle - begin) break;
        std::inplace_merge(log_.begin() + static_cast<std::ptrdiff_t>(begin),
                           log_.begin() + static_cast<std::ptrdiff_t>(middle),
                           log_.begin() + static_cast<std::ptrdiff_t>(end), before);
        run_ends_.pop_back();
        run_ends_.back() = end;
    }
}

SafetyCheck::SafetyCheck(SafetyLimits limits) : limits_(std::move(limits)) {}

void SafetyCheck::fail(const std::string& key, const std::string& detail) const {
    throw InputError(op_path_ + key, detail);
}

void SafetyCheck::reach(double z) {
    if (!op_lowest_z_ || z < *op_lowest_z_) op_lowest_z_ = z;
}

void SafetyCheck::move(const Vec3& to, bool feed) {
    reach(to.z);
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
    // A turning move (SafetyLimits::kind): off the axis, or on it in an operation without
    // drilling planes (a turn-profile that starts at X0 comes down the axis to its start).
    if (limits_.kind == MachineKind::lathe && (op_planeless_ || std::abs(from.x) > eps || std::abs(to.x) > eps)) {
        pos_ = to;
        last_was_feed_ = feed;
        return;
    }
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
            if (!approach && !drilled(xy, to.z)) {
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
        if (!drilled({from.x, from.y}, from.z))
            fail("", fmt::format("a feed starts at Z {}, below the reference plane (Z {}), at X{} Y{} where no hole has "
                                 "been drilled: the tool would plunge into the stock at rapid",
                                 z_of(from.z), z_of(*op_reference_z_), z_of(from.x), z_of(from.y)));
    }
    // A feed straight down makes (or deepens) a hole.
    if (feed && !across && to.z < from.z) {
        holes_.drill(xy, to.z);
        if (hole_checked_ && xy == *hole_checked_) own_depth_ = std::min(own_depth_.value_or(to.z), to.z);
        else if (hole_checked_) own_answers_ = false;
    }
    pos_ = to;
    last_was_feed_ = feed;
}

bool SafetyCheck::drilled(Vec2 at, double z) {
    if (hole_checked_ && !(at == *hole_checked_ && own_depth_ && *own_depth_ <= z + eps)) own_answers_ = false;
    return holes_.reaches(at, z, eps);
}

SafetyCheck::HoleShape SafetyCheck::shape_of(Vec2 hole) const {
    const Vec3& from = *pos_;
    const int across = from.x == hole.x && from.y == hole.y                             ? 0
                       : std::abs(from.x - hole.x) > eps || std::abs(from.y - hole.y) > eps ? 2
                                                                                           : 1;
    return {from.z, last_was_feed_, across};
}

void SafetyCheck::drill_point(Vec2 at) {
    if (!cycle_) throw std::logic_error("drilling point outside a cycle");
    if (!pos_) throw std::logic_error("drilling from an unknown position");
    const HoleShape shape = shape_of(at);
    if (checked_hole_ && checked_hole_->shape == shape) {
        if (checked_hole_->lowest_z) holes_.drill(at, *checked_hole_->lowest_z);
        pos_ = Vec3{at.x, at.y, checked_hole_->end_z};
        last_was_feed_ = checked_hole_->end_feed;
        return;
    }
    hole_checked_ = at;
    own_depth_.reset();
    own_answers_ = true;
    for (const LonghandMove& m : longhand_moves(*cycle_, *pos_, at, limits_.longhand, longhand_buffers_))
        visit_exhaustive(overloaded{[&](const Rapid& r) { move(r.to, false); },
                                    [&](const Linear& l) { move(l.to, true); }, [](const Dwell&) {},
                                    [](const Spindle&) {}},
                         m);
    hole_checked_.reset();
    // Every cycle ends above its hole; a hole that did not is checked in full each time.
    const bool ends_above = pos_->x == at.x && pos_->y == at.y;
    if (own_answers_ && ends_above) checked_hole_ = CheckedHole{shape, own_depth_, pos_->z, last_was_feed_};
    else checked_hole_.reset();
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
    // A hole's check stands for the next holes of its cycle only: nothing may come between.
    if (!std::holds_alternative<DrillPoint>(event)) checked_hole_.reset();
    visit_exhaustive(
        overloaded{
            [&](const OperationStart& op) {
                op_path_ = op.path;
                op_lowest_z_.reset();
                op_retract_z_.reset();
                op_reference_z_.reset();
                op_safe_z_.reset();
                op_planeless_ = !op.planes;
                if (op.planes) {
                    op_retract_z_ = op.planes->retract_z;
                    op_reference_z_ = op.planes->reference_z;
                    op_safe_z_ = op.planes->safe_z;
                }
            },
            [&](const OperationEnd&) {
                if (stock_bottom_ && op_lowest_z_ && *op_lowest_z_ < *stock_bottom_ - eps && warnings_)
                    *warnings_ << fmt::format("camgen: warning: {}: the operation goes down to Z {}, {} mm below the "
                                                     "stock bottom (Z {}): into what holds the stock\n",
                                                     op_path_, z_of(*op_lowest_z_),
                                                     z_of(*stock_bottom_ - *op_lowest_z_), z_of(*stock_bottom_));
                op_lowest_z_.reset();
                op_retract_z_.reset();
                op_reference_z_.reset();
                op_safe_z_.reset();
                op_planeless_ = false;
            },
            [&](const ToolChange& t) {
                tool_ = t.number;
                pos_.reset();
            },
            [&](const Spindle&) {},
            [&](const Rapid& r) { move(r.to, false); },
            [&](const Linear& l) { move(l.to, true); },
            [&](const ThreadFeed& t) { move(t.to, true); },
            [&](const ThreadCycle& c) {
                for (const Event& m : thread_cycle_moves(c)) emit(m);
            },
            [&](const TurnCycle& c) {
                for (const Event& m : turn_cycle_moves(c, limits_.rough_pattern)) emit(m);
            },
            [&](const FinishCycle& c) {
                for (const Event& m : finish_cycle_moves(c, limits_.rough_pattern)) emit(m);
            },
            [&](const GrooveCycle& c) {
                for (const Event& m : groove_cycle_moves(c)) emit(m);
            },
            [&](const Arc& a) {
                // An arc in XY (or a helix) is lowest at an end; one in XZ or YZ may dip between.
                reach(a.to.z);
                if (a.plane != Plane::xy && pos_) {
                    const ArcGeometry g = resolve_arc(*pos_, a);
                    for (const Vec3& p : linearize_arc(g, 64)) reach(p.z);
                }
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
                reach(c.bottom_z);
                cycle_ = c;
                op_retract_z_ = c.retract_z;
                op_reference_z_ = c.reference_z;
            },
            [&](const DrillPoint& p) { drill_point(p.at); },
            [&](const DrillEnd&) { cycle_.reset(); },
            [&](const Comment&) {},
            [&](const Coolant&) {},
            [&](const Stop&) {
                // The operator works at the machine: the tool waits at the clearance.
                if (pos_ && pos_->z < limits_.clearance - eps)
                    fail("", fmt::format("the program would stop with the tool at Z {}, below the clearance (Z {})",
                                         z_of(pos_->z), z_of(limits_.clearance)));
                // The operator may move the axes.
                pos_.reset();
            },
            [&](const CustomBlock&) {},
        },
        event);
}

void check_safety(const std::vector<Event>& events, const SafetyLimits& limits) {
    SafetyCheck check(limits);
    for (const Event& e : events) check.emit(e);
    check.finish();
}

}  // namespace camgen
