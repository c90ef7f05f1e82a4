#include "camgen/post/capabilities.hpp"

#include <sstream>

#include <fmt/format.h>

#include "camgen/post/arc_output.hpp"

namespace camgen {

namespace {

// The cycle kinds a lathe's turn-drill asks for (its kind follows from its fields: pitch taps,
// pecks with or without a back-off, a dwell, else a plain drill).
constexpr CycleKind lathe_cycle_kinds[] = {CycleKind::drill, CycleKind::dwell, CycleKind::deep,
                                           CycleKind::chip_break, CycleKind::tap, CycleKind::tap_left};

Capability capability(std::optional<std::string> refused) { return Capability{std::move(refused)}; }

// The names of the fields a canned cycle carries, as the machine file names them.
std::vector<std::string> field_names(const DrillingCycleSpec& spec, MachineKind kind) {
    std::vector<std::string> names;
    for (DrillField d : spec.fields) {
        if (kind == MachineKind::mill) names.emplace_back(key_of(d));
        else if (const TurnDrillFieldInfo* t = turn_field_of(d)) names.emplace_back(t->key);
    }
    return names;
}

nlohmann::json capability_json(const Capability& c) {
    nlohmann::json j = {{"supported", c.supported()}};
    if (c.refused) j["refused"] = *c.refused;
    return j;
}

}  // namespace

MachineCapabilities machine_capabilities(const Machine& machine) {
    // A post that writes nowhere: only its decisions are asked for.
    std::ostringstream nowhere;
    const std::unique_ptr<Post> post = make_post(machine, nowhere, PostOptions{});
    MachineCapabilities c;
    c.kind = machine.kind;
    if (machine.kind == MachineKind::mill) {
        c.control_compensation = capability(post->control_compensation_refusal());
        for (Plane p : {Plane::xy, Plane::xz, Plane::yz}) c.arcs.emplace_back(p, writes_arcs_in(machine.arcs, p));
        c.helices = writes_helices(machine.arcs);
        for (const auto& named : cycle_kinds) c.cycles.push_back(post->cycle_capability(named.value));
    } else {
        c.arcs.emplace_back(Plane::xz, writes_arcs_in(machine.arcs, Plane::xz));
        for (CycleKind k : lathe_cycle_kinds) c.cycles.push_back(post->cycle_capability(k));
    }
    c.ccw_spindle = capability(post->ccw_spindle_refusal());
    c.program_number = capability(post->program_number_refusal());
    c.surface_speed = capability(post->surface_speed_refusal());
    return c;
}

std::string cycle_capability_text(const CycleCapability& cycle, MachineKind kind) {
    if (cycle.refused) return "refused: " + *cycle.refused;
    if (!cycle.canned) return "longhand";
    const std::vector<std::string> fields = field_names(*cycle.canned, kind);
    return fmt::format("canned {}; fields: {}{}", cycle.canned->name, fields.empty() ? "-" : fmt::format("{}", fmt::join(fields, ", ")),
                       cycle.longhand ? "" : "; never longhand (rigid tapping)");
}

nlohmann::json capabilities_json(const MachineCapabilities& c) {
    nlohmann::json j = nlohmann::json::object();
    if (c.control_compensation) j["controlCompensation"] = capability_json(*c.control_compensation);
    nlohmann::json arcs = nlohmann::json::object();
    for (const auto& [plane, as_arcs] : c.arcs) arcs[std::string(name_of(plane_names, plane))] = as_arcs ? "arcs" : "lines";
    j["arcs"] = arcs;
    if (c.helices) j["helices"] = *c.helices ? "arcs" : "lines";
    nlohmann::json drilling = nlohmann::json::object();
    for (const CycleCapability& cycle : c.cycles) {
        nlohmann::json d = {{"supported", !cycle.refused},
                            {"canned", cycle.canned ? nlohmann::json(cycle.canned->name) : nlohmann::json(nullptr)},
                            {"fields", cycle.canned ? field_names(*cycle.canned, c.kind) : std::vector<std::string>{}},
                            {"longhand", cycle.longhand}};
        if (cycle.refused) d["refused"] = *cycle.refused;
        drilling[std::string(name_of(cycle_kinds, cycle.kind))] = d;
    }
    j["drilling"] = drilling;
    j["counterClockwiseSpindle"] = capability_json(c.ccw_spindle);
    j["programNumber"] = capability_json(c.program_number);
    j["constantSurfaceSpeed"] = capability_json(c.surface_speed);
    return j;
}

}  // namespace camgen
