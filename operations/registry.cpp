#include <type_traits>

#include <fmt/format.h>

#include "operations/registry.hpp"

namespace camgen {

namespace {

const char* tool_type_name(ToolType t) {
    switch (t) {
        case ToolType::drill: return "drill";
        case ToolType::centre_drill: return "centre drill";
        case ToolType::spot_drill: return "spot drill";
        case ToolType::tap: return "tap";
        case ToolType::reamer: return "reamer";
        case ToolType::boring_bar: return "boring bar";
        case ToolType::end_mill: return "end mill";
        case ToolType::ball_mill: return "ball mill";
    }
    return "tool";
}

std::string describe(const Tool& t) {
    std::string s = fmt::format("{:g} mm {}", t.diameter, tool_type_name(t.type));
    if (!t.comment.empty()) s += " - " + t.comment;
    return s;
}

std::string default_name(const Operation& op) {
    if (const auto* d = std::get_if<DrillOp>(&op))
        return d->comment.empty() ? fmt::format("drill {} hole{}", d->holes.size(), d->holes.size() == 1 ? "" : "s")
                                  : d->comment;
    const auto& c = std::get<ContourOp>(op);
    return c.comment.empty() ? "contour" : c.comment;
}

}  // namespace

void expand_job(const Job& job, EventSink& sink) {
    int current = 0;
    double rpm = 0.0;
    SpindleState state = SpindleState::off;
    for (const Operation& op : job.operations) {
        std::visit(
            [&](const auto& o) {
                const Tool& tool = job.tools.at(o.tool);
                // The spindle stops as the last act of the previous tool.
                if (tool.number != current && state != SpindleState::off) {
                    sink.emit(Spindle{SpindleState::off, 0.0});
                    state = SpindleState::off;
                }
                std::optional<double> tolerance;
                if constexpr (std::is_same_v<std::decay_t<decltype(o)>, ContourOp>) tolerance = o.tolerance;
                sink.emit(OperationStart{default_name(op), o.path, tolerance});
                SpindleState want = tool.direction == SpindleDirection::cw ? SpindleState::cw : SpindleState::ccw;
                if (tool.number != current) {
                    sink.emit(ToolChange{tool.number, tool.diameter, describe(tool)});
                    current = tool.number;
                    state = SpindleState::off;
                }
                if (state != want || rpm != tool.rpm) {
                    sink.emit(Spindle{want, tool.rpm});
                    state = want;
                    rpm = tool.rpm;
                }
                expand(o, Context{job, tool}, sink);
                sink.emit(OperationEnd{});
            },
            op);
    }
    if (state != SpindleState::off) sink.emit(Spindle{SpindleState::off, 0.0});
}

}  // namespace camgen
