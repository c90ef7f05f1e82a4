#include "camgen/post/longhand.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/events/visit.hpp"

namespace camgen {

namespace {

// A peck sequence longer than this is a mistake in the job, not a hole.
constexpr size_t max_pecks = 10000;

bool pecks(CycleKind kind) { return kind == CycleKind::deep || kind == CycleKind::chip_break; }

}  // namespace

std::vector<double> peck_depths(const DrillCycle& cycle) {
    std::vector<double> depths;
    peck_depths(cycle, depths);
    return depths;
}

void peck_depths(const DrillCycle& cycle, std::vector<double>& depths) {
    const DrillValues& p = cycle.values;
    depths.clear();
    if (!pecks(cycle.kind) || !p.get(DrillField::first_depth)) {
        depths.push_back(cycle.bottom_z);
        return;
    }
    double peck = *p.get(DrillField::first_depth);
    double depth = cycle.safe_z;
    // As LinuxCNC: pecks are measured from the feed-start plane; the last one ends at bottom.
    while (true) {
        if (!(peck > 0.0))
            throw InputError(cycle.path + "/firstDepth", "a peck depth must be > 0");
        depth -= peck;
        if (depth <= cycle.bottom_z) break;
        depths.push_back(depth);
        if (depths.size() > max_pecks)
            throw InputError(cycle.path + "/firstDepth",
                             fmt::format("more than {} pecks for one hole; use larger pecks", max_pecks));
        // CNC-Calc turning: every peck after the first is subsequentDepth (never with a degression).
        if (auto later = p.get(DrillField::subsequent_depth)) peck = *later;
        if (p.degression_type() == DegressionType::value)
            peck -= p.get(DrillField::degression).value_or(0.0);
        else if (p.degression_type() == DegressionType::factor)
            peck *= p.get(DrillField::degression).value_or(1.0);
        if (p.degression_type() != DegressionType::none) peck = std::max(peck, p.get(DrillField::minimum_depth).value_or(0.0));
    }
    depths.push_back(cycle.bottom_z);
}

Event to_event(const LonghandMove& move) {
    return visit_exhaustive(overloaded{[](const Rapid& m) -> Event { return m; }, [](const Linear& m) -> Event { return m; },
                                       [](const Dwell& m) -> Event { return m; }, [](const Spindle& m) -> Event { return m; }},
                            move);
}

std::vector<LonghandMove> longhand_moves(const DrillCycle& cycle, const Vec3& from, Vec2 hole,
                                  const LonghandOptions& options) {
    LonghandBuffers buffers;
    return longhand_moves(cycle, from, hole, options, buffers);
}

const std::vector<LonghandMove>& longhand_moves(const DrillCycle& cycle, const Vec3& from, Vec2 hole,
                                                const LonghandOptions& options, LonghandBuffers& buffers) {
    const DrillValues& p = cycle.values;
    std::vector<LonghandMove>& ev = buffers.moves;
    ev.clear();
    auto at = [&](double z) { return Vec3{hole.x, hole.y, z}; };
    double z = from.z;
    // Preliminary motion (LinuxCNC/Fanuc): up to the feed-start plane if below it, across in
    // XY, down to the feed-start plane.
    if (z < cycle.safe_z) {
        ev.emplace_back(Rapid{{from.x, from.y, cycle.safe_z}});
        z = cycle.safe_z;
    }
    if (from.x != hole.x || from.y != hole.y) ev.emplace_back(Rapid{at(z)});
    if (z != cycle.safe_z) ev.emplace_back(Rapid{at(cycle.safe_z)});
    auto top_dwell = [&] {
        if (p.get(DrillField::top_dwell) && *p.get(DrillField::top_dwell) > 0.0) ev.emplace_back(Dwell{*p.get(DrillField::top_dwell)});
    };
    auto bottom_dwell = [&] {
        if (p.get(DrillField::bottom_dwell) && *p.get(DrillField::bottom_dwell) > 0.0) ev.emplace_back(Dwell{*p.get(DrillField::bottom_dwell)});
    };
    // From the feed-start plane up to the retract plane, when they differ.
    auto rapid_to_retract = [&] {
        if (cycle.retract_z != cycle.safe_z) ev.emplace_back(Rapid{at(cycle.retract_z)});
    };
    // Out of the hole: at the retract feed to the feed-start plane, else at rapid.
    auto retract_out = [&](std::optional<double> feed) {
        if (feed) {
            ev.emplace_back(Linear{at(cycle.safe_z), *feed});
            rapid_to_retract();
        } else {
            ev.emplace_back(Rapid{at(cycle.retract_z)});
        }
    };
    const double first_feed = cycle.feed * p.get(DrillField::first_feedrate_factor).value_or(1.0);
    const SpindleState forward =
        cycle.spindle_direction == SpindleDirection::cw ? SpindleState::cw : SpindleState::ccw;

    switch (cycle.kind) {
        case CycleKind::drill:
        case CycleKind::dwell:
            // G81 / G82: feed to the bottom, dwell, rapid out.
            top_dwell();
            ev.emplace_back(Linear{at(cycle.bottom_z), cycle.feed});
            bottom_dwell();
            retract_out(p.get(DrillField::retract_feedrate));
            break;
        case CycleKind::deep:
        case CycleKind::chip_break: {
            // G83: after each peck rapid to R, rapid down to clearance above the last peck.
            // G73: after each peck rapid up by the back-off only.
            std::vector<double>& depths = buffers.depths;
            peck_depths(cycle, depths);
            const double back_off = p.get(DrillField::pecking_retract).value_or(options.peck_clearance);
            const double clearance = p.get(DrillField::peck_clearance).value_or(options.peck_clearance);
            top_dwell();
            for (size_t k = 0; k < depths.size(); ++k) {
                ev.emplace_back(Linear{at(depths[k]), k == 0 ? first_feed : cycle.feed});
                if (k + 1 == depths.size()) break;
                if (cycle.kind == CycleKind::deep) {
                    ev.emplace_back(Rapid{at(cycle.safe_z)});
                    top_dwell();
                    ev.emplace_back(Rapid{at(depths[k] + clearance)});
                } else {
                    ev.emplace_back(Rapid{at(depths[k] + back_off)});
                }
            }
            bottom_dwell();
            retract_out(p.get(DrillField::retract_feedrate));
            break;
        }
        case CycleKind::tap:
        case CycleKind::tap_left: {
            // G84 / G74 (Fanuc order): feed in at pitch x speed, dwell, reverse, feed out to R,
            // restore the spindle, rapid to the retract plane.
            const SpindleState in = cycle.kind == CycleKind::tap ? SpindleState::cw : SpindleState::ccw;
            const SpindleState out = cycle.kind == CycleKind::tap ? SpindleState::ccw : SpindleState::cw;
            const double pitch = p.get(DrillField::pitch).value_or(0.0);
            const double rpm_in = p.get(DrillField::tapping_speed).value_or(cycle.spindle_rpm);
            const double rpm_out = p.get(DrillField::retract_speed).value_or(rpm_in);
            if (p.get(DrillField::tapping_speed) || in != forward) ev.emplace_back(Spindle{in, rpm_in});
            ev.emplace_back(Linear{at(cycle.bottom_z), pitch * rpm_in});
            bottom_dwell();
            ev.emplace_back(Spindle{out, rpm_out});
            ev.emplace_back(Linear{at(cycle.safe_z), pitch * rpm_out});
            ev.emplace_back(Spindle{forward, cycle.spindle_rpm});
            rapid_to_retract();
            break;
        }
        case CycleKind::ream:
            // G85: feed in, feed out to R (at the retract feed when set), rapid on.
            ev.emplace_back(Linear{at(cycle.bottom_z), cycle.feed});
            bottom_dwell();
            ev.emplace_back(Linear{at(cycle.safe_z), p.get(DrillField::retract_feedrate).value_or(cycle.feed)});
            rapid_to_retract();
            break;
        case CycleKind::bore_stop:
            // G86: feed in, dwell, spindle stop, rapid out, spindle on again.
            ev.emplace_back(Linear{at(cycle.bottom_z), cycle.feed});
            bottom_dwell();
            ev.emplace_back(Spindle{SpindleState::off, 0.0});
            ev.emplace_back(Rapid{at(cycle.retract_z)});
            ev.emplace_back(Spindle{forward, cycle.spindle_rpm});
            break;
        case CycleKind::bore_dwell: {
            // G89: feed in, dwell, feed out - to R (Fanuc) or to the retract level (LinuxCNC).
            ev.emplace_back(Linear{at(cycle.bottom_z), cycle.feed});
            bottom_dwell();
            const double out_feed = p.get(DrillField::retract_feedrate).value_or(cycle.feed);
            if (options.bore_dwell_feed_out == BoreDwellFeedOut::to_retract) {
                ev.emplace_back(Linear{at(cycle.retract_z), out_feed});
            } else {
                ev.emplace_back(Linear{at(cycle.safe_z), out_feed});
                rapid_to_retract();
            }
            break;
        }
    }
    return ev;
}

}  // namespace camgen
