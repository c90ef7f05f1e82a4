#include "camgen/operations/registry.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>
#include <algorithm>

#include "camgen/common/error.hpp"
#include "camgen/events/visit.hpp"

namespace camgen {

namespace {

std::string describe(const Tool& t) {
    std::string s = fmt::format("{:g} mm {}", t.diameter, tool_types[static_cast<int>(t.type)].description);
    if (!t.comment.empty()) s += " - " + t.comment;
    return s;
}

// The operation type named `type` reads the object.
template <std::size_t I = 0>
Operation read_as(std::string_view type, json::Fields& f, const JobInput& in) {
    if constexpr (I < std::variant_size_v<Operation>) {
        using Op = std::variant_alternative_t<I, Operation>;
        if (type == Op::type) return Op::read(f, in);
        return read_as<I + 1>(type, f, in);
    } else {
        throw std::logic_error("operation type checked before reading");
    }
}

Operation read_operation(const nlohmann::json& value, const std::string& path, const JobInput& in) {
    json::Fields f(value, path, in.source());
    const std::string type = f.string("type");
    const std::vector<std::string> types = operation_type_names();
    if (std::find(types.begin(), types.end(), type) == types.end())
        f.fail_choice("type", type, types);
    return read_as(type, f, in);
}

// The job's name when the file gives none: the file's stem.
std::string job_name(const std::string& source_name) {
    if (source_name.empty() || source_name.front() == '<') return "job";
    std::string stem = std::filesystem::path(source_name).stem().string();
    return stem.empty() ? "job" : stem;
}

}  // namespace

std::vector<std::string> operation_type_names() {
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
        return std::vector<std::string>{std::string(std::variant_alternative_t<I, Operation>::type)...};
    }(std::make_index_sequence<std::variant_size_v<Operation>>());
}

Job read_job(std::string_view text, const std::string& source_name, JobLimits limits) {
    JobInput in(text, source_name, limits);
    json::Fields top = in.read_header();
    Job job;
    const nlohmann::json& operations = in.array(top, "operations");
    for (std::size_t i = 0; i < operations.size(); ++i)
        job.operations.push_back(read_operation(operations[i], "/operations/" + std::to_string(i), in));
    // The turned profiles know of each other: each one comes and goes outside the material that
    // it and those before it keep.
    std::vector<const TurnProfileOp*> turned;
    for (const Operation& op : job.operations)
        if (const auto* t = std::get_if<TurnProfileOp>(&op)) turned.push_back(t);
    check_turned_material(turned, in);
    // Every operation is read and its size claimed: only now do patterns make their holes.
    for (Operation& op : job.operations)
        visit_exhaustive(
            []<OperationType Op>(Op& o) {
                if constexpr (requires { make_pending_holes(o); }) make_pending_holes(o);
            },
            op);
    static_cast<JobHeader&>(job) = in.take_header();
    if (job.name.empty()) job.name = job_name(source_name);
    return job;
}

void check_machine_kind(const Job& job, MachineKind kind, const std::string& machine_name) {
    for (const Operation& op : job.operations)
        visit_exhaustive(
            [&]<OperationType Op>(const Op& o) {
                constexpr std::optional<MachineKind> kind_of_op = machine_kind_of<Op>();
                if constexpr (!kind_of_op) return;
                constexpr MachineKind made_for = kind_of_op.value_or(MachineKind::mill);
                if (made_for == kind) return;
                throw InputError(o.path + "/type",
                                 fmt::format("operation \"{}\" ({}) is made for a {}, and machine {} is a {}: post the "
                                             "job for a {} machine",
                                             Op::type, default_name(o), name_of(machine_kinds, made_for), machine_name,
                                             name_of(machine_kinds, kind), name_of(machine_kinds, made_for)));
            },
            op);
}

Job read_job_file(const std::string& filename) {
    std::string text;
    if (filename == "-") {
        std::ostringstream buffer;
        buffer << std::cin.rdbuf();
        if (std::cin.bad()) throw IoError("cannot read <stdin>: " + std::string(std::strerror(errno)));
        return read_job(buffer.str(), "<stdin>");
    }
    std::error_code ec;
    if (std::filesystem::is_directory(filename, ec))
        throw IoError("cannot read " + filename + ": " + std::strerror(EISDIR));
    std::ifstream in(filename, std::ios::binary);
    if (!in) throw IoError("cannot read " + filename + ": " + std::strerror(errno));
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) throw IoError("cannot read " + filename + ": " + std::strerror(errno));
    return read_job(text, filename);
}

void expand_job(const Job& job, EventSink& sink) {
    int current = 0;
    double rpm = 0.0;
    FeedMode feed_mode = FeedMode::per_minute;  // of the operation before
    SpindleState state = SpindleState::off;
    CoolantMode coolant = CoolantMode::off;
    // Coolant stops before the spindle does.
    auto coolant_off = [&] {
        if (coolant == CoolantMode::off) return;
        sink.emit(Coolant{CoolantMode::off, ""});
        coolant = CoolantMode::off;
    };
    for (const Operation& op : job.operations) {
        visit_exhaustive(
            [&]<OperationType Op>(const Op& o) {
                if constexpr (!uses_tool<Op>()) {
                    // The tool in the spindle stays, and the spindle and coolant as they are.
                    static const Tool no_tool{};
                    // The feed mode stays the one of the operation before (no G94/G95 for nothing).
                    sink.emit(OperationStart{default_name(o), o.path, std::nullopt, {}, std::nullopt, feed_mode});
                    expand(o, Context{job, current ? job.tools.at(current) : no_tool}, sink);
                    sink.emit(OperationEnd{});
                    return;
                }
                const Tool& tool = job.tools.at(o.tool);
                // The spindle stops as the last act of the previous tool.
                if (tool.number != current) coolant_off();
                if (tool.number != current && state != SpindleState::off) {
                    sink.emit(Spindle{SpindleState::off, 0.0});
                    state = SpindleState::off;
                }
                std::optional<double> tolerance;
                if constexpr (requires { o.tolerance; }) tolerance = o.tolerance;
                std::vector<std::string> notes;
                if constexpr (requires { o.notes; }) notes = o.notes;
                std::optional<OperationPlanes> planes;
                if constexpr (requires { o.heights; }) {
                    const Planes z = resolve_planes(o.heights);
                    planes = OperationPlanes{z.retract_z, z.reference_z, z.safe_z};
                }
                feed_mode = FeedMode::per_minute;
                if constexpr (requires { o.feed_mode; }) feed_mode = o.feed_mode;
                sink.emit(OperationStart{default_name(o), o.path, tolerance, notes, planes, feed_mode});
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
                // The tool's coolant, once the spindle runs.
                if (tool.coolant != coolant) {
                    sink.emit(Coolant{tool.coolant, tool.path + "/coolant"});
                    coolant = tool.coolant;
                }
                expand(o, Context{job, tool}, sink);
                sink.emit(OperationEnd{});
            },
            op);
    }
    coolant_off();
    if (state != SpindleState::off) sink.emit(Spindle{SpindleState::off, 0.0});
}

std::vector<Event> expand_job(const Job& job) {
    EventRecorder r;
    expand_job(job, r);
    return std::move(r.events);
}

}  // namespace camgen
