#include "camgen/operations/registry.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <algorithm>

#include "camgen/common/error.hpp"
#include "camgen/common/file_kind.hpp"
#include "camgen/common/input_file.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/operations/design_lathe.hpp"
#include "camgen/operations/fanuc_finish.hpp"
#include "camgen/operations/stock.hpp"

namespace camgen {

namespace {

std::string describe(const Tool& t) {
    std::string s = fmt::format("{:g} mm {}", t.diameter, tool_types[static_cast<int>(t.type)].description);
    if (!t.comment.empty()) s += " - " + t.comment;
    // What camgen computed for a library tool, in its line of the program's tool list.
    if (!t.computed.empty()) s += fmt::format(" - library {}: {} computed", t.library, fmt::join(t.computed, ", "));
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

// The errors of one job as read_job finds them, in three groups: the header's (its first and the stock's),
// the tools' and the operations', each group in file order. Only the first InputErrors::shown
// of a group are kept (no later one can be among the first shown of the job), the rest counted.
class JobErrors {
public:
    enum Group { header, tools, operations, groups };

    void add(Group group, const InputError& e) {
        if (kept_[group].size() < InputErrors::shown) kept_[group].push_back(e);
        else ++not_kept_;
    }
    // An error that follows from a tool's (FollowOnError): left out, as the tool's is reported.
    void follow_on(const FollowOnError& e) {
        if (!follow_on_) follow_on_ = e;
    }
    // Throws the errors found so far, if any: one as it is, several as InputErrors, in file order.
    void throw_if_any() const {
        std::vector<InputError> all;
        for (const auto& group : kept_) all.insert(all.end(), group.begin(), group.end());
        if (all.empty()) {
            // Never the case (a follow-on error comes after the tool's own), but an operation
            // must not go missing silently.
            if (follow_on_) throw *follow_on_;
            return;
        }
        // By line (an error without one last); on one line the header's, the tools', the operations'.
        auto line = [](const InputError& e) { return e.line() > 0 ? e.line() : std::numeric_limits<int>::max(); };
        std::stable_sort(all.begin(), all.end(), [&](const InputError& a, const InputError& b) { return line(a) < line(b); });
        if (all.size() == 1 && not_kept_ == 0) throw all.front();
        throw InputErrors(std::move(all), not_kept_);
    }

private:
    std::vector<InputError> kept_[groups];
    std::size_t not_kept_ = 0;
    std::optional<FollowOnError> follow_on_;
};

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

namespace {

// Each turn-rough with "stock": "auto" on a job with a bar roughs from what the outside operations
// before it left of the bar (TurnRoughOp::material): the bar less each one's design as its tool
// clears it (lathe_material_cut), in order, so that an earlier turn-rough's own passes are made
// from what was before it. Drills cut inside only, threads leave their flanks: neither counts.
void rough_from_earlier_material(Job& job, const JobInput& in) {
    if (!job.stock || job.stock->shape != StockShape::bar) return;
    const Stock& bar = *job.stock;
    struct Cut {
        LatheTurnDesign design;
        Vec2 tip_offset;
        std::string what;
    };
    std::vector<Cut> cuts;
    // Up to the last such turn-rough; only the operations before it are designed (each is
    // expanded for it).
    std::size_t end = 0;
    for (std::size_t i = 0; i < job.operations.size(); ++i)
        if (const auto* r = std::get_if<TurnRoughOp>(&job.operations[i]); r && r->stock == RoughStock::from_earlier) end = i + 1;
    for (std::size_t i = 0; i < end; ++i) {
        Operation& op = job.operations[i];
        if (auto* r = std::get_if<TurnRoughOp>(&op); r && r->stock == RoughStock::from_earlier && !cuts.empty()) {
            const double z_lo = std::min(r->boundary.segments.back().end.x, r->tip_boundary.segments.back().end.x) - 1.0;
            std::vector<double> breaks{bar.face_z};
            for (const Cut& c : cuts)
                for (double z : c.design.corners()) breaks.push_back(z);
            const double step = std::max(0.05, (bar.face_z - z_lo) / 20000.0);
            LatheMaterial m = LatheMaterial::bar(r->stock_radius, bar.face_z, z_lo, step, std::move(breaks));
            if (!m.r.empty()) {
                std::string whats;
                for (const Cut& c : cuts) {
                    lathe_material_cut(m, c.design, c.tip_offset);
                    whats += (whats.empty() ? "" : ", ") + c.what;
                }
                const double scale = r->given_x == XValues::diameter ? 2.0 : 1.0;
                const double top = std::min(r->stock_radius, m.top(z_lo + 1.0, std::numeric_limits<double>::infinity()));
                r->material = std::move(m);
                if (!r->whole_bar_over_boundary())
                    r->notes.push_back(fmt::format("roughs from what {} left of the bar (\"stock\": \"auto\"): from X {} down, each "
                                               "pass approachDistance before that material at its level, levels in air left out",
                                               whats, in.show(top * scale)));
            }
        }
        if (i + 1 == end) break;
        LatheDesign d;
        std::vector<std::string> unchecked;
        std::string type;
        visit_exhaustive(
            [&]<OperationType Op>(const Op& o) {
                type = std::string(Op::type);
                if constexpr (std::is_same_v<Op, TurnFaceOp>) design_turn_face(o, job, d, unchecked);
                else if constexpr (std::is_same_v<Op, TurnRoughOp>) design_turn_rough(o, job, d, unchecked);
                else if constexpr (std::is_same_v<Op, TurnProfileOp>) design_turn_profile(o, job, d, unchecked);
                else if constexpr (std::is_same_v<Op, TurnGrooveOp>) design_turn_groove(o, job, d, unchecked);
                else if constexpr (std::is_same_v<Op, TurnPartOp>) design_turn_part(o, job, d, unchecked);
            },
            op);
        for (LatheTurnDesign& t : d.profiles) {
            const auto tool = job.tools.find(t.tool);
            const int orientation = tool != job.tools.end() && tool->second.orientation > 0 ? tool->second.orientation : 2;
            const std::string what = fmt::format("{} ({})", t.path, type);
            cuts.push_back({std::move(t), lathe_tip_offset(orientation, 0.0), what});
            cuts.back().tip_offset = lathe_tip_offset(orientation, cuts.back().design.nose);
        }
    }
}

}  // namespace

Job read_job(std::string_view text, const std::string& source_name, JobLimits limits, const ToolLibraryOptions& tools) {
    // A syntax error ends reading here: the one error.
    JobInput in(text, source_name, limits);
    in.set_tool_library(tools);
    // The header, the tools and each operation are read on after an error of another, and their
    // errors reported together; within one of them the first error is the only one.
    JobErrors errors;
    std::optional<json::Fields> top;
    try {
        top.emplace(in.read_header());
    } catch (const InputError& e) {
        errors.add(JobErrors::header, e);
        // A wrong unit or clearance would make errors of every length measured by it.
        if (!in.units_and_clearance()) errors.throw_if_any();
        top.emplace(in.root(), "", in.source());
    }
    // The stock, before the operations: they take its top.
    try {
        read_stock(*top, in);
    } catch (const InputError& e) {
        errors.add(JobErrors::header, e);
    }
    in.read_tools(*top, [&](const InputError& e) { errors.add(JobErrors::tools, e); });
    Job job;
    const nlohmann::json* operations = nullptr;
    try {
        operations = &in.array(*top, "operations");
    } catch (const InputError& e) {
        errors.add(JobErrors::operations, e);
    }
    for (std::size_t i = 0; operations && i < operations->size(); ++i) {
        try {
            job.operations.push_back(read_operation((*operations)[i], "/operations/" + std::to_string(i), in));
        } catch (const FollowOnError& e) {
            errors.follow_on(e);
        } catch (const InputError& e) {
            errors.add(JobErrors::operations, e);
        }
    }
    errors.throw_if_any();
    // The turned profiles know of each other: each one comes and goes outside the material that
    // it and those before it keep.
    std::vector<const TurnProfileOp*> turned;
    for (const Operation& op : job.operations)
        if (const auto* t = std::get_if<TurnProfileOp>(&op)) turned.push_back(t);
    check_turned_material(turned, in);
    // The grooving and parting blades' rapids likewise, outside what earlier operations keep.
    check_blade_material(job.operations, in);
    const auto path_of = [](const Operation& op) { return visit_exhaustive([]<OperationType Op>(const Op& o) { return o.path; }, op); };
    // Turning operations come in along Z to their first X beyond the bar's face: the stock's
    // faceZ, or the Z an earlier turn-face faced it to. A start inside it (a bar not faced
    // yet) would rapid in X into the stub (the safety check leaves turning moves to the
    // operations and the simulation).
    if (const std::optional<Stock>& stock = in.header().stock; stock && stock->shape == StockShape::bar) {
        double face = stock->face_z;
        bool cut_outside = false;  // an outside operation came before (rough_from_earlier_material)
        for (Operation& op : job.operations) {
            std::optional<double> entry;
            std::string what;
            if (const auto* f = std::get_if<TurnFaceOp>(&op)) face = std::min(face, f->z);
            if (auto* r = std::get_if<TurnRoughOp>(&op)) r->bar_face = face;  // where its cycle may come down
            // A turn-rough from the earlier material comes in beyond it at each level.
            if (const auto* r = std::get_if<TurnRoughOp>(&op);
                r && r->direction == RoughDirection::z && (r->stock == RoughStock::bar || !cut_outside)) {
                const double tip = r->tip_boundary.segments.empty() ? r->boundary.start.x : r->tip_boundary.start.x;
                entry = std::max(r->boundary.start.x, tip) + r->approach, what = "its passes come in";
            }
            if (const auto* t = std::get_if<TurnProfileOp>(&op)) {
                // Under control compensation the tip rapids to the designed start itself.
                const bool control = t->compensation == NoseCompensation::control && !t->control_path.segments.empty();
                const Profile& tip = t->tip_path.segments.empty() || control ? t->profile : t->tip_path;
                entry = tip.start.x + t->approach, what = "it rapids along Z to its start";
            }
            // A face groove moves along X at approachDistance above its z: that must be air.
            if (const auto* g = std::get_if<TurnGrooveOp>(&op); g && g->side == GrooveSide::face)
                entry = g->surface + g->approach, what = "it moves along X over the face groove";
            if (const auto* t = std::get_if<TurnThreadOp>(&op)) {
                const double deepest = t->depths.empty() ? 0.0 : t->depths.back();
                entry = t->start_z + t->approach - deepest * std::tan(t->infeed_angle * rad_per_deg),
                what = "its passes come in";
            }
            cut_outside = cut_outside || std::holds_alternative<TurnFaceOp>(op) || std::holds_alternative<TurnRoughOp>(op) ||
                          std::holds_alternative<TurnProfileOp>(op) ||
                          (std::holds_alternative<TurnGrooveOp>(op) && std::get<TurnGrooveOp>(op).side == GrooveSide::external) ||
                          std::holds_alternative<TurnPartOp>(op);
            if (entry && *entry < face - 1e-9)
                json::fail(in.source(), path_of(op),
                           fmt::format("{} at Z {}, inside the bar, whose face is at Z {} ({}): face the bar first "
                                       "(turn-face) or start beyond its face",
                                       what, in.show(*entry), in.show(face),
                                       face < stock->face_z ? "as an earlier turn-face left it" : "the stock's faceZ"));
        }
    }
    // After a part-off through the centre the part has fallen off (into a catcher or the chips):
    // an operation after it would cut where the part no longer is, or was caught.
    for (std::size_t i = 0; i + 1 < job.operations.size(); ++i) {
        const auto* part = std::get_if<TurnPartOp>(&job.operations[i]);
        if (!part || part->end > 0) continue;
        for (std::size_t k = i + 1; k < job.operations.size(); ++k)
            if (!std::holds_alternative<StopOp>(job.operations[k]) && !std::holds_alternative<CustomOp>(job.operations[k]))
                json::fail(in.source(), path_of(job.operations[k]),
                           fmt::format("{} parts the part off through the centre before this operation, which would cut "
                                       "where the part has fallen off: part off last (or leave a pip with toX, and the "
                                       "program stops for it)",
                                       part->path));
        break;
    }
    // Under a constant surface speed the spindle's speed follows the diameter: its operations
    // feed per revolution, so that the chip stays what the job says (and Sinumerik's G96
    // switches G95 on by itself).
    for (const Operation& op : job.operations)
        visit_exhaustive(
            [&]<OperationType Op>(const Op& o) {
                if constexpr (uses_tool<Op>() && requires { o.feed_mode; }) {
                    const auto tool = in.header().tools.find(o.tool);
                    if (tool == in.header().tools.end() || !(tool->second.surface_speed > 0)) return;
                    if (o.feed_mode != FeedMode::per_revolution)
                        json::fail(in.source(), o.path + (in.root().contains(nlohmann::json::json_pointer(o.path + "/feedMode")) ? "/feedMode" : ""),
                                   fmt::format("tool {} turns at a constant surface speed (surfaceSpeed, G96): the "
                                               "operation must feed per revolution (feedMode \"per-revolution\")",
                                               o.tool));
                }
            },
            op);
    // Every operation is read and its size claimed: only now do patterns make their holes.
    for (Operation& op : job.operations)
        visit_exhaustive(
            []<OperationType Op>(Op& o) {
                if constexpr (requires { make_pending_holes(o); }) make_pending_holes(o);
            },
            op);
    static_cast<JobHeader&>(job) = in.take_header();
    if (job.name.empty()) job.name = job_name(source_name);
    rough_from_earlier_material(job, in);
    link_fanuc_finishing(job, in);
    return job;
}

void check_machine_kind(const Job& job, MachineKind kind, const std::string& machine_name) {
    if (job.stock) check_stock_machine_kind(*job.stock, kind, machine_name);
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
    // Within the limit of an input; a file that is not JSON is named as such.
    const InputText input = read_input(filename, InputRules{.json = true}, std::cin);
    const std::string source = filename == "-" ? "<stdin>" : filename;
    try {
        return read_job(input.text, source);
    } catch (const InputError& e) {
        if (e.path().empty())
            if (auto what = not_json(input.text, input.cut, source, "job")) throw InputError("", *what, 0, source);
        throw;
    }
}

void expand_job(const Job& job, EventSink& sink) {
    int current = 0;
    double rpm = 0.0;
    double surface_speed = 0.0;  // m/min, 0: constant rpm
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
                // What camgen computed for the tool, said where it is changed to.
                if (tool.number != current) {
                    std::vector<std::string> computed;
                    for (const std::string& c : tool.computed)
                        computed.push_back(fmt::format("T{} (library tool \"{}\"): {} computed", tool.number, tool.library, c));
                    notes.insert(notes.begin(), computed.begin(), computed.end());
                }
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
                if (state != want || rpm != tool.rpm || surface_speed != tool.surface_speed) {
                    sink.emit(Spindle{want, tool.rpm, tool.surface_speed});
                    state = want;
                    rpm = tool.rpm;
                    surface_speed = tool.surface_speed;
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
