#pragma once
// The custom operation: lines of the control's own language, given per machine or per dialect
// and written into the program as they are. It needs no tool. The post reads them back with
// the machine's reader before it writes them and refuses what the reader cannot read and what
// would change the motion or the machine's state (camgen/post/stops.hpp, docs/job-format.md).
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"

namespace camgen {

// The longest line of a custom block (characters) and the most lines a text may have.
inline constexpr std::size_t max_custom_line = 200;
inline constexpr std::size_t max_custom_lines = 1000;

// A custom block.
struct CustomOp {
    static constexpr std::string_view type = "custom";
    // No tool of its own, on a mill or a lathe alike.
    static constexpr bool uses_tool = false;
    static constexpr bool any_machine_kind = true;
    // Reads one operation of this type (its "type" is already read).
    static CustomOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema.
    static std::vector<ObjectSpec> objects();
    std::string path;
    int tool = 0;  // none
    std::string comment;
    std::vector<CustomText> texts;  // by machine or dialect name
};

// The CustomBlock event.
void expand(const CustomOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "custom block".
std::string default_name(const CustomOp& op);

}  // namespace camgen
