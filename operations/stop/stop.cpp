#include "camgen/operations/stop/stop.hpp"

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

constexpr KeySpec stop_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "message", .type = JsonType::string, .required = true,
     .description = "what the operator reads at the stop: one line of at most 100 characters"},
    {.key = "optional", .type = JsonType::boolean, .default_json = "false",
     .description = "stop only where the operator's optional-stop switch is on (M1); false: always (M0)"},
    {.key = "spinUp", .quantity = Quantity::time, .min = Bound{0, true}, .max = Bound{60, true}, .default_json = "2",
     .description = "how long the program waits after it restarts the spindle after the stop"},
};

// Words that begin camgen's own operator messages for a tool change (nccad's M01, the pause of
// a machine without a tool changer): a reader takes a message that begins so for one.
constexpr std::string_view reserved_starts[] = {"Insert tool ", "Set spindle speed to "};

}  // namespace

std::optional<std::string> stop_message_problem(std::string_view message) {
    if (message.find_first_not_of(' ') == std::string_view::npos) return "the message is empty: say what the operator is to do";
    for (const char c : message)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
            return "the message has a control character (a line break, a tab, ...): it is one line";
    if (message.size() > max_stop_message)
        return fmt::format("the message has {} characters, more than the {} a control shows on one line", message.size(),
                           max_stop_message);
    for (std::string_view start : reserved_starts)
        if (message.substr(0, start.size()) == start)
            return fmt::format("the message begins with \"{}\", as camgen's tool-change pauses do: a reader would take the "
                               "stop for a tool change; reword it",
                               start.substr(0, start.size() - 1));
    return std::nullopt;
}

std::vector<ObjectSpec> StopOp::objects() {
    return {{.name = "stop",
             .description = "stop the program for the operator with a message (the spindle and coolant stop before it "
                            "and restart after it)",
             .keys = {std::begin(stop_keys), std::end(stop_keys)}}};
}

StopOp StopOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, stop_keys);
    StopOp op;
    op.path = f.path();
    op.message = f.string("message");
    if (auto problem = stop_message_problem(op.message)) f.fail("message", *problem);
    op.kind = f.boolean("optional", false) ? StopKind::optional : StopKind::mandatory;
    if (auto s = in.optional_quantity(f, "spinUp", Quantity::time)) {
        if (!(*s >= 0 && *s <= 60)) f.fail("spinUp", "spinUp must be between 0 and 60 s");
        op.spin_up = *s;
    }
    return op;
}

void expand(const StopOp& op, const Context&, EventSink& sink) { sink.emit(Stop{op.kind, op.message, op.spin_up}); }

std::string default_name(const StopOp& op) { return op.kind == StopKind::optional ? "optional stop" : "stop"; }

}  // namespace camgen
