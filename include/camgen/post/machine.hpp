#pragma once
// A machine: the settings of one control, read from machines/<name>.json (installed or
// compiled in, see installed_machine_dir) or from a file given by path, plus the name of the dialect code that writes for it.
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "camgen/common/key_spec.hpp"
#include "camgen/vocabulary/vocabulary.hpp"
#include "camgen/post/longhand.hpp"
#include "camgen/nc/block_writer.hpp"
#include "camgen/nc/format.hpp"

namespace camgen {

// How arcs are written (CNC-Calc useRadius / absoluteArcCenter, plus nccad's angle form).
enum class ArcFormat { ijk_relative, ijk_absolute, radius, nccad_angle };

// How feeds are written: mm/min (in/min for inch output), or nccad's 0.1 mm/s.
enum class FeedUnit { per_minute, tenth_mm_per_second };

// How a canned cycle is written: the dialect's standard form, or LinuxCNC's rigid tapping
// (G33.1 Z K: one synchronised move in and out, positioned with G0, no cancel code).
// Fanuc T's two-block end-face peck drilling (G74 R(e) / G74 Z Q F) is a style of its own.
enum class CannedStyle { standard, rigid_g33_1, fanuc_g74 };

// How the machine can tap: rigid (the control synchronises the spindle to the feed: Fanuc
// M29 G84, LinuxCNC G33.1, Heidenhain 207, Sinumerik CYCLE84), floating (a floating tap holder
// takes up the difference: G84 without synchronisation, or longhand feeds with a spindle
// reversal), or not at all.
enum class TappingMode { rigid, floating, none };

// One drilling cycle the machine offers (a MillDrillingFields entry).
struct DrillingCycleSpec {
    std::string name;                  // "G83", "CYCLE83", "CYCL DEF 203"
    CycleKind kind = CycleKind::drill;
    bool canned = true;                // false: written longhand
    CannedStyle style = CannedStyle::standard;  // machine file key "style"
    std::vector<DrillField> fields;    // the optional parameters the canned cycle carries
};

// Which way a canned roughing cycle's passes run: along -Z (turning: G71, CYCLE95 longitudinal)
// or along -X (facing: G72, CYCLE95 face).
enum class RoughingCycleKind { rough_z, rough_x };
inline constexpr Named<RoughingCycleKind> roughing_cycle_kinds[] = {
    {RoughingCycleKind::rough_z, "rough-z", "passes along -Z at radial levels (turning)"},
    {RoughingCycleKind::rough_x, "rough-x", "passes along -X at Z levels (facing)"},
};

// How a canned roughing cycle is written and what the control makes of it.
enum class RoughingCycleStyle { linuxcnc, fanuc_g71, fanuc_g72 };
inline constexpr Named<RoughingCycleStyle> roughing_cycle_styles[] = {
    {RoughingCycleStyle::linuxcnc, "linuxcnc",
     "LinuxCNC 2.9: the profile as a subroutine o<n> sub ... o<n> endsub, the cycle G71 Q<n> D I R F from the start "
     "point (G72 alike)"},
    {RoughingCycleStyle::fanuc_g71, "fanuc-g71",
     "Fanuc T type I (G code system A): G71 U(depth) R(retract) / G71 P(ns) Q(nf) U0 W0 F from the start point, the "
     "finishing shape as the N-numbered blocks ns..nf right after it (ns along X only); kind rough-z"},
    {RoughingCycleStyle::fanuc_g72, "fanuc-g72",
     "Fanuc T type I (G code system A): G72 W(depth) R(retract) / G72 P(ns) Q(nf) U0 W0 F from the start point, the "
     "finishing shape as the N-numbered blocks ns..nf right after it (ns along Z only); kind rough-x"},
};

// The values of a roughing operation a canned roughing cycle can carry.
enum class RoughingField { depth_of_cut, retract, allowance };
inline constexpr Named<RoughingField> roughing_fields[] = {
    {RoughingField::depth_of_cut, "depthOfCut", "the depth of each pass (LinuxCNC I)"},
    {RoughingField::retract, "retract", "how far each pass lifts off at 45 degrees (LinuxCNC R)"},
    {RoughingField::allowance, "allowance",
     "one finishing allowance offset all round the profile (LinuxCNC D), not separate X and Z allowances"},
};

// One canned roughing cycle the machine offers (machine file "roughingCycles").
struct RoughingCycleSpec {
    std::string name;                  // "G71"
    RoughingCycleKind kind = RoughingCycleKind::rough_z;
    RoughingCycleStyle style = RoughingCycleStyle::linuxcnc;
    std::vector<RoughingField> fields;  // what it carries
};

// How a canned threading cycle is written: LinuxCNC's G76 P Z I J K R Q H, Fanuc T's two-block
// G76 P(m r a) Q R / G76 X Z P(k) Q(first depth) F.
enum class ThreadCycleStyle { linuxcnc_g76, fanuc_g76 };

// What a turn-thread may ask of a threading cycle (machine file threadingCycles[].fields).
inline constexpr const char* thread_cycle_field_names[] = {"constant-depth", "constant-area", "minDepth", "infeedAngle",
                                                           "springPasses", "runout"};

// One threading cycle the machine offers (machine file threadingCycles).
struct ThreadingCycleSpec {
    std::string name;                  // "G76"
    ThreadCycleStyle style = ThreadCycleStyle::linuxcnc_g76;
    std::vector<std::string> fields;   // what it carries: thread_cycle_field_names
};

// How a canned grooving cycle is written: Fanuc T's two-block G75 R(e) / G75 X Z P Q F (plunges
// along X), or its G74 R(e) / G74 X Z P Q F (face grooving, plunges along Z).
enum class GrooveCycleStyle { fanuc_g75, fanuc_g74 };

// What a turn-groove may ask of a grooving cycle beyond plain plunges (machine file
// groovingCycles[].fields; GrooveCycle::fields).
inline constexpr const char* groove_cycle_field_names[] = {"pecks", "fullRetract", "dwell", "finishPass", "chamfer"};

// One grooving cycle the machine offers (machine file groovingCycles).
struct GroovingCycleSpec {
    std::string name;                  // "G75"
    GrooveCycleStyle style = GrooveCycleStyle::fanuc_g75;
    bool face = false;                 // kind "face-groove": it cuts face grooves (along Z), else external and internal ones
    std::vector<std::string> fields;   // what it carries: groove_cycle_field_names
};

// Limits of the machine. Feeds mm/min, speeds rpm.
struct MachineLimits {
    double max_feed = 10000.0;
    double min_feed = 1.0;
    double rapid_rate = 5000.0;        // for time estimates
    double max_rpm = 0.0;              // 0: no limit
};

// Where the chord tolerance for arcs that become lines comes from: always the machine's, or
// the operation's tolerance capped by the machine's.
enum class ChordToleranceMode { absolute, operation };

// Arc output and arc-breaking settings: how arc blocks are written and which arcs are split,
// written as lines or as one straight move. Lengths mm, angles degrees.
struct ArcSettings {
    ArcFormat format = ArcFormat::ijk_relative;
    double max_sweep = 360.0;          // degrees per block; longer arcs are split evenly
    bool helical = true;               // false: helices become lines
    std::vector<Plane> planes = {Plane::xy, Plane::xz, Plane::yz};  // others become lines
    double chord_tolerance = 0.005;    // mm (CIRC_TOL): chord deviation of arcs that become lines
    ChordToleranceMode tolerance_mode = ChordToleranceMode::operation;
    std::optional<double> max_radius;  // mm; larger arcs become lines
    std::optional<double> min_radius;  // mm; smaller arcs become one straight move
    std::optional<double> min_length;  // mm; shorter arcs (helix length) become one straight move
    int min_segments = 1;              // at least this many lines for an arc that becomes lines
    std::optional<double> max_segment_length;  // mm; no line of a broken arc is longer
    bool force_xy = true;              // write both end coordinates on every arc block
};

// The program frame (machine file "frame"): the words of the safe-start block, the work
// offsets and the coolant codes the control has. Words are written as given.
struct FrameSettings {
    std::vector<std::string> start_block;   // "G40", "G49", "G80", ...: before the unit word
    std::vector<std::string> work_offsets;  // "G54", "G59.1", "G54.1 P1": ranges expanded
    std::map<CoolantMode, std::string> coolant;  // the code of each coolant mode it has ("M8")
    std::map<FeedMode, std::string> feed_modes;  // the code of each feed mode it has ("G95"); none: per minute only
    std::vector<std::string> safe_retract;  // the block that takes Z to the machine's safe height
                                            // ("G53", "G0", "Z0"); empty: the job's clearance
};

// A dialect's machine-file "settings", as its dialect reads them (machines/<dialect>/): the base
// of each dialect's own struct (iso::Settings, ...). They are read once, with the machine file
// (parse_machine: each key from the dialect's key table, errors naming the file, line and key),
// and shared by the dialect's post and reader; a variant's struct (iso::LatheSettings) extends
// its base dialect's.
struct DialectSettings {
    virtual ~DialectSettings() = default;
};

struct Machine {
    std::string name;                  // "wabeco"
    std::string description;           // one line for --list-machines
    std::string dialect;               // the dialect code that writes for it: "iso", "nccad"
    std::string extension;             // suggested file extension, without dot
    MachineKind kind = MachineKind::mill;  // machine file "kind": the operations it runs
    bool x_diameter = false;           // CNC-Calc xDiameterProg (lathes): X words are diameters
    bool i_diameter = false;           // CNC-Calc iDiameterProg (lathes): I words are diameters, where X is
    Units units = Units::mm;           // output units
    std::vector<Units> accepted_units = {Units::mm};  // the units the control has a mode for
    nc::BlockStyle block;
    bool modal_motion = true;          // false: G0/G1/G2/G3 written on every motion block
    bool cutter_compensation = true;   // the control offsets by a tool radius (G41/G42, RL/RR)
    char decimal_mark = '.';
    double tolerance = 0.002;          // mm (CNC-Calc tolerance): the arc tolerance. After rounding,
                                       // every arc block's start and end radii agree within it
    std::vector<std::string> notes;    // free text about the machine's choices, for --describe-machine
    std::map<std::string, nc::FormatSpec> formats;  // "xyz", "ijk", "feed", "rpm", "dwell", "angle";
                                                    // "x", "z", "i" where an axis has its own
    FeedUnit feed_unit = FeedUnit::per_minute;
    MachineLimits limits;
    ArcSettings arcs;
    double peck_clearance = 1.0;       // mm, re-approach clearance of longhand deep/chip-break
    BoreDwellFeedOut bore_dwell_feed_out = BoreDwellFeedOut::to_safe;  // longhand G89 feed-out end
    TappingMode tapping = TappingMode::none;  // machine file drilling.tapping
    std::vector<DrillingCycleSpec> drilling;
    std::vector<RoughingCycleSpec> roughing_cycles;  // machine file "roughingCycles"
    std::vector<ThreadingCycleSpec> threading;  // machine file threadingCycles
    std::vector<GroovingCycleSpec> grooving;    // machine file groovingCycles
    FrameSettings frame;
    // The dialect's settings (machine file "settings"), read by parse_machine; null for a machine
    // made in code, whose dialect takes its defaults (settings_of).
    std::shared_ptr<const DialectSettings> settings;
    std::string source;                // where it was read from, for messages

    // The format named `key` for the output units, with the decimal mark applied. The axis
    // formats "x", "z" and "i" are the machine's own where it gives them, else "xyz" / "ijk";
    // "x" doubles its values under xDiameterProg, "i" under xDiameterProg and iDiameterProg.
    nc::Format format(const std::string& key) const;
    // Whether the control has a mode for these units (a unit word the post writes).
    bool accepts(Units u) const;
    // The units the control accepts, by name ("mm, inch").
    std::string accepted_unit_names() const;
    // Whether the control has this work offset ("G54", "G54.1 P3").
    bool has_work_offset(const std::string& word) const;
    // The code that switches coolant to `mode`, if the control has it.
    std::optional<std::string> coolant_code(CoolantMode mode) const;
    // The machine's canned cycle of this kind, if any.
    const DrillingCycleSpec* canned_cycle(CycleKind kind) const;
    // How longhand cycles move on this machine (so that they equal its canned cycles).
    LonghandOptions longhand() const { return {peck_clearance, bore_dwell_feed_out}; }
    // How its roughing cycles move (TurnCycle events, canned or longhand, along Z and along X):
    // Fanuc T's type I G71/G72 where its first roughing cycle is of a Fanuc style, else LinuxCNC's.
    RoughCyclePattern rough_pattern() const {
        if (!roughing_cycles.empty() && roughing_cycles.front().style != RoughingCycleStyle::linuxcnc)
            return RoughCyclePattern::fanuc_g71;
        return RoughCyclePattern::linuxcnc_g71;
    }
    // How its threading cycles move in air (ThreadCycle events, canned or longhand): as its first
    // threading cycle does, LinuxCNC's G76 where it has none.
    ThreadCyclePattern thread_pattern() const {
        return !threading.empty() && threading.front().style == ThreadCycleStyle::fanuc_g76 ? ThreadCyclePattern::fanuc_g76
                                                                                               : ThreadCyclePattern::linuxcnc_g76;
    }
};

// The machine's dialect settings as the dialect's struct S: the defaults of S for a machine
// made in code without them. Throws std::logic_error when they are another dialect's.
template <class S>
const S& settings_of(const Machine& machine) {
    static const S defaults{};
    if (!machine.settings) return defaults;
    if (const auto* s = dynamic_cast<const S*>(machine.settings.get())) return *s;
    throw std::logic_error("machine " + machine.name + ": its settings are not those of dialect " + machine.dialect);
}

// Settings of a machine file that its dialect would write as wrong motion, or that camgen
// could not read back: the JSON paths of the settings involved (changing any one of them
// helps; the first is named unless a file of an "extends" chain gives a later one) and why,
// in a machinist's words.
struct MachineProblem {
    std::vector<std::string> paths;
    std::string detail;
};

// The first problem of a machine's settings, if any: every dialect's (formats that pad with
// spaces or rescale G and M codes, code decimals that lose G33.1), then its dialect's (decimal
// mark, the start block's modes against xDiameterProg, arc planes against its arc forms).
// parse_machine and load_machine refuse a machine that has one.
std::optional<MachineProblem> machine_problem(const Machine& machine);

// A machine file compiled into the program.
struct EmbeddedMachine {
    const char* name;
    const char* text;
};
const std::vector<EmbeddedMachine>& embedded_machines();

// The folder of machine files installed beside the running executable, if there is one:
// <prefix>/share/camgen/machines for <prefix>/bin/camgen, wherever the prefix is. It holds the
// built-in machines of an installed camgen; without it (a run from the build folder, a program
// linked with the library but not installed beside it) the compiled-in copies are the built-ins.
std::optional<std::string> installed_machine_dir();

// Parses a machine file's text. Throws InputError naming the JSON path and line.
Machine parse_machine(const std::string& text, const std::string& name, const std::string& source);

// The objects of a machine file, for the JSON Schema: the top level ("machine") first, then
// globals, formats, format, limits, arcs, drilling, drillingCycle, frame, coolantCodes,
// feedModeCodes, settings (every dialect's keys) and settings-<dialect> for each dialect.
std::vector<ObjectSpec> machine_objects();

// A machine camgen finds by name. Search order, first match wins: each folder of
// CAMGEN_MACHINES (colon-separated), then $XDG_CONFIG_HOME/camgen/machines (default
// ~/.config/camgen/machines), then the built-in machines (installed_machine_dir, else the
// compiled-in copies). A user's file of a built-in's name
// replaces it (and may extend it: "extends" of its own name means the next one down).
struct MachineEntry {
    std::string name;
    std::string origin;           // "built-in" or the file's path
    std::string path;             // the file; empty for a compiled-in machine
    const char* text = nullptr;   // a compiled-in machine's text
    bool shadowed = false;        // an entry of the same name earlier in the search order wins
};
// The user's machine folders, in search order (they need not exist).
std::vector<std::string> user_machine_dirs();
// Every machine file in search order, shadowed ones included.
std::vector<MachineEntry> machine_catalogue();

// The complete machine file of a name or path with its "extends" chain applied (each file is
// merged over the one it extends as a JSON merge patch: objects member by member, arrays and
// values replaced, null removes): what `--describe-machine M --json` prints. Throws InputError
// naming the file for an unknown or cyclic "extends", IoError for an unreadable file.
nlohmann::json resolve_machine_json(const std::string& name_or_path);

// A machine by name (see MachineEntry) or by path to a JSON file (contains '/' or ends in
// .json), with its "extends" chain applied. Errors name the file (of the chain) and line that
// holds the value. Throws UsageError for an unknown name, IoError for an unreadable file.
Machine load_machine(const std::string& name_or_path);

// Names and one-line descriptions of the compiled-in machines, sorted by name.
std::vector<std::pair<std::string, std::string>> list_machines();

// A human-readable description of the machine: globals, limits, its drilling table and capabilities.
std::string describe_machine(const Machine& machine);

}  // namespace camgen
