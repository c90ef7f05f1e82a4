#pragma once
// The stop operation: the program stops for the operator (M0, or M1 where the operator's
// optional-stop switch is on) and shows a message. It needs no tool: the tool in the spindle
// stays, at the clearance where the operation before it left it. The posts stop the spindle
// and the coolant before the stop and restart them after it (OperatorStops).
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"

namespace camgen {

// A stop for the operator with a message.
struct StopOp {
    static constexpr std::string_view type = "stop";
    // No tool of its own, on a mill or a lathe alike.
    static constexpr bool uses_tool = false;
    static constexpr bool any_machine_kind = true;
    // Reads one operation of this type (its "type" is already read).
    static StopOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    int tool = 0;  // none
    std::string message;
    StopKind kind = StopKind::mandatory;
    double spin_up = 2.0;  // s the program waits after restarting the spindle
};

// The Stop event.
void expand(const StopOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: "stop" or "optional stop".
std::string default_name(const StopOp& op);

// Why `message` cannot be a stop's message (empty, a control byte, too long, or words that
// camgen's readers take for a tool change), or nullopt.
std::optional<std::string> stop_message_problem(std::string_view message);

}  // namespace camgen
