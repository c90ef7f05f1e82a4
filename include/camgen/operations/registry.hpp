#pragma once
// The operation types and the whole job. Each operation type lives in its own folder
// (operations/<type>/) with its reading and its expansion; this file registers them, once, in
// the Operation variant: a new type is one folder plus one entry there. Reading, expansion and
// naming iterate the variant, and a visitor that misses a type does not compile.
#include <concepts>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job.hpp"
#include "camgen/job/tool_library.hpp"
#include "camgen/operations/bore_mill/bore_mill.hpp"
#include "camgen/operations/chamfer/chamfer.hpp"
#include "camgen/operations/contour/contour.hpp"
#include "camgen/operations/custom/custom.hpp"
#include "camgen/operations/drill/drill.hpp"
#include "camgen/operations/engrave/engrave.hpp"
#include "camgen/operations/face/face.hpp"
#include "camgen/operations/path/path.hpp"
#include "camgen/operations/pocket/pocket.hpp"
#include "camgen/operations/stop/stop.hpp"
#include "camgen/operations/thread_mill/thread_mill.hpp"
#include "camgen/operations/turn_drill/turn_drill.hpp"
#include "camgen/operations/turn_face/turn_face.hpp"
#include "camgen/operations/turn_groove/turn_groove.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"
#include "camgen/operations/turn_part/turn_part.hpp"
#include "camgen/operations/turn_rough/turn_rough.hpp"
#include "camgen/operations/turn_thread/turn_thread.hpp"

namespace camgen {

// What every operation type offers: its "type" name, its reading, the objects of its input
// (its keys, for the JSON Schema), its tool, its JSON path, its name for comments and its
// expansion.
template <class Op>
concept OperationType = requires(const Op& op, json::Fields& f, const JobInput& in, const Context& ctx, EventSink& sink) {
    { Op::type } -> std::convertible_to<std::string_view>;
    { Op::read(f, in) } -> std::same_as<Op>;
    { Op::objects() } -> std::same_as<std::vector<ObjectSpec>>;
    { op.tool } -> std::convertible_to<int>;
    { op.path } -> std::convertible_to<std::string>;
    { default_name(op) } -> std::convertible_to<std::string>;
    expand(op, ctx, sink);
};

// The kind of machine an operation type is made for: its `machine_kind`, else a mill; none
// where it says `any_machine_kind` (a stop).
template <class Op>
constexpr std::optional<MachineKind> machine_kind_of() {
    if constexpr (requires { Op::any_machine_kind; }) return std::nullopt;
    else if constexpr (requires { Op::machine_kind; }) return Op::machine_kind;
    else return MachineKind::mill;
}

// Whether an operation type cuts with a tool of its own (false: it says `uses_tool = false`; the
// tool in the spindle stays and the spindle keeps its state).
template <class Op>
constexpr bool uses_tool() {
    if constexpr (requires { Op::uses_tool; }) return Op::uses_tool;
    else return true;
}

// Every operation type: the registration line.
using Operation = std::variant<DrillOp, ContourOp, PathOp, BoreMillOp, TurnDrillOp, TurnProfileOp, TurnFaceOp, TurnRoughOp, StopOp,
                               CustomOp, PocketOp, FaceOp, ThreadMillOp, EngraveOp, ChamferOp, TurnGrooveOp,
                               TurnPartOp, TurnThreadOp>;

// A whole job: header, tools and operations in order.
struct Job : JobHeader {
    std::vector<Operation> operations;
};

// The "type" names of the operation types, in registration order.
std::vector<std::string> operation_type_names();

// Parses and validates a job. `source_name` names the file in messages.
// Throws InputError (JSON path + line) on any problem. Inch input is converted to mm here.
// `limits` bound its size (holes, path elements, nesting) before anything is allocated for it.
// `tools`: where its library tools are found and the machine's limits on what is computed from
// their cutting data.
Job read_job(std::string_view text, const std::string& source_name, JobLimits limits = {},
             const ToolLibraryOptions& tools = {});

// Refuses a job with a stock or an operation made for another kind of machine than `kind` (a
// bar on a mill, a drill operation on a lathe, a turning operation on a mill): an InputError at
// the stock's shape, else at the first such operation's "type", naming it and both kinds.
void check_machine_kind(const Job& job, MachineKind kind, const std::string& machine_name);

// Refuses (InputError at "startX", a face groove's at "z") a turn-groove or turn-part one of
// whose rapids (the approach along Z and in to the approach level, the moves along Z there
// between plunges and to the chamfers, the way out) runs through material: that earlier
// turn-profiles keep (external and face); with a stock bar, the bar's solid that the operations
// before it did not remove (outside: turn-faces, turn-roughs, turn-profiles, external grooves and
// part-offs; inside also its bore, turn-drills and internal grooves). Refuses (InputError at
// "thread", else "majorDiameter" or "minorDiameter") a turn-thread cut on more than its
// diameter: outside, material beyond its major (what an earlier turn-profile keeps, or the bar's
// solid left) over its length; inside, with a bar, solid within its minor. `operations` in job
// order.
void check_blade_material(const std::vector<Operation>& operations, const JobInput& input);

// Reads a job from a file ("-" = standard input). Throws IoError when it cannot be read.
Job read_job_file(const std::string& filename);

// The whole job in order: tool changes and spindle control between operations, each
// operation between OperationStart and OperationEnd, spindle off at the end.
void expand_job(const Job& job, EventSink& sink);
// The same, as a list.
std::vector<Event> expand_job(const Job& job);

}  // namespace camgen
