#pragma once
// What a job can ask of a machine, as its post decides it: control compensation, arcs in each
// plane, helices, each kind of drilling cycle, a counter-clockwise spindle, a program number.
// Each verdict comes from the one Post function that the post's own refusal calls
// (Post::control_compensation_refusal, cycle_capability, ccw_spindle_refusal,
// program_number_refusal; writes_arcs_in and writes_helices for arcs), so --describe-machine
// (text and --json) cannot promise what the post refuses, nor refuse what it posts.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "camgen/post/post.hpp"

namespace camgen {

// One capability a job may ask for; `refused`: why the machine does not have it, as the
// post's message says it (nullopt: it has it).
struct Capability {
    std::optional<std::string> refused;
    bool supported() const { return !refused; }
};

// The capabilities of one machine, for what the operations of its kind ask: a mill's contour
// (control compensation), path (arcs in XY, XZ and YZ, helices) and drill (every cycle kind);
// a lathe's turn-profile (arcs in XZ) and turn-drill (drill, dwell, deep, chip-break, tap,
// tap-left: no reaming or boring). Both kinds: a counter-clockwise spindle, a program number.
struct MachineCapabilities {
    MachineKind kind = MachineKind::mill;
    std::optional<Capability> control_compensation;  // mills only
    std::vector<std::pair<Plane, bool>> arcs;         // each plane asked: true arc blocks, false straight moves
    std::optional<bool> helices;                      // mills only: true helical arc blocks, false straight moves
    std::vector<CycleCapability> cycles;              // each cycle kind the operations ask for
    Capability ccw_spindle;
    Capability program_number;
    Capability surface_speed;                         // G96 constant surface speed (a tool's surfaceSpeed)
};

// The capabilities of `machine`, asked of its dialect's post. Throws InputError where no post
// can be made for it (as posting would).
MachineCapabilities machine_capabilities(const Machine& machine);

// The capabilities as the "capabilities" member of `--describe-machine M --json`:
// {"controlCompensation": {"supported": false, "refused": "..."}, "arcs": {"xy": "arcs", "xz":
// "lines", ...}, "helices": "arcs", "drilling": {"drill": {"supported": true, "canned": "G81",
// "fields": [...], "longhand": true}, ...}, "counterClockwiseSpindle": {...},
// "programNumber": {...}, "constantSurfaceSpeed": {...}} (mill-only members left out for a lathe). Drilling fields are named
// as the machine file names them (TurnDrillingFields on a lathe).
nlohmann::json capabilities_json(const MachineCapabilities& capabilities);

// How a cycle kind is made, in words for --describe-machine: "canned G81; fields: ...",
// "longhand", "refused: <message>", a rigid tap's "...; never longhand (rigid tapping)".
std::string cycle_capability_text(const CycleCapability& cycle, MachineKind kind);

}  // namespace camgen
