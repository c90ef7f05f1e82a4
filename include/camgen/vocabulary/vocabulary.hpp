#pragma once
// The words that job files, machine files, events, posts, readers, messages, the JSON Schema
// and the docs share, each declared once as a table: cycle kinds, drilling fields (CNC-Calc's
// MillDrillingFields), planes, arc directions, tool types, spindle directions, units and the
// other choices a job makes. Everything that lists these words iterates these tables.
// Depends on nothing of camgen but the geometry's enums.
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/geometry/geometry.hpp"

namespace camgen {

// What a number measures. It decides inch scaling (length and feed), the unit named in
// messages, docs and the schema.
enum class Quantity { length, feed, time, speed, factor, angle, count, choice };

// The internal unit of a quantity ("mm", "mm/min", "s", "rpm", "degrees"; "" for none).
std::string_view unit_of(Quantity quantity);
// True for the quantities a job in inch gives in inch (lengths, feeds).
constexpr bool scales_with_units(Quantity q) { return q == Quantity::length || q == Quantity::feed; }

// One value of an enumeration as job and machine files write it, with a line for the docs.
template <class E>
struct Named {
    E value;
    std::string_view name;
    std::string_view description;
};

// The name of `value` in `table`.
template <class E, std::size_t N>
constexpr std::string_view name_of(const Named<E> (&table)[N], E value) {
    for (const auto& n : table)
        if (n.value == value) return n.name;
    return "?";
}
// The value named `name` in `table`, if any.
template <class E, std::size_t N>
constexpr std::optional<E> value_named(const Named<E> (&table)[N], std::string_view name) {
    for (const auto& n : table)
        if (n.name == name) return n.value;
    return std::nullopt;
}
// The names of a table, in order.
template <class E, std::size_t N>
std::vector<std::string> names_of(const Named<E> (&table)[N]) {
    std::vector<std::string> out;
    for (const auto& n : table) out.emplace_back(n.name);
    return out;
}

enum class Units { mm, inch };
inline constexpr Named<Units> unit_names[] = {
    {Units::mm, "mm", "millimetres"},
    {Units::inch, "inch", "inches (lengths in in, feeds in in/min)"},
};

// What a machine is: a mill (the tool turns; XY positions, Z into the work) or a lathe (the
// work turns; X is the distance from the spindle axis, Z runs along it). Operations are made
// for one kind, and a machine of the other kind refuses them.
enum class MachineKind { mill, lathe };
inline constexpr Named<MachineKind> machine_kinds[] = {
    {MachineKind::mill, "mill", "a milling machine: the tool turns, X and Y position it, Z feeds into the work"},
    {MachineKind::lathe, "lathe", "a lathe: the work turns, X is the radius (written as a diameter where the control "
                                  "programs diameters), Z runs along the spindle axis"},
};

// How feeds are given: per minute (ISO G94, Fanuc T G98) or per spindle revolution (ISO G95,
// Fanuc T G99), as lathes feed. Events always carry mm/min; a post writes per revolution by
// dividing by the spindle speed.
enum class FeedMode { per_minute, per_revolution };
inline constexpr Named<FeedMode> feed_modes[] = {
    {FeedMode::per_minute, "per-minute", "feeds in mm/min (in/min)"},
    {FeedMode::per_revolution, "per-revolution", "feeds in mm (in) per spindle revolution"},
};

// How a lathe job gives X: as the radius (the distance from the spindle axis) or as the
// diameter, as drawings of turned parts do.
enum class XValues { radius, diameter };
inline constexpr Named<XValues> x_values[] = {
    {XValues::radius, "radius", "X is the distance from the spindle axis"},
    {XValues::diameter, "diameter", "X is the diameter (twice the distance from the spindle axis)"},
};

// Coolant: off, flood (ISO M8) or mist (ISO M7).
enum class CoolantMode { off, flood, mist };
inline constexpr Named<CoolantMode> coolant_modes[] = {
    {CoolantMode::off, "off", "no coolant (ISO M9)"},
    {CoolantMode::flood, "flood", "flood coolant (ISO M8)"},
    {CoolantMode::mist, "mist", "mist coolant (ISO M7)"},
};

inline constexpr Named<Plane> plane_names[] = {
    {Plane::xy, "xy", "G17, arcs seen from +Z"},
    {Plane::xz, "xz", "G18, arcs seen from +Y"},
    {Plane::yz, "yz", "G19, arcs seen from +X"},
};

inline constexpr Named<ArcDirection> arc_directions[] = {
    {ArcDirection::cw, "cw", "clockwise (G2)"},
    {ArcDirection::ccw, "ccw", "counter-clockwise (G3)"},
};

enum class SpindleDirection { cw, ccw };
inline constexpr Named<SpindleDirection> spindle_directions[] = {
    {SpindleDirection::cw, "cw", "clockwise (M3)"},
    {SpindleDirection::ccw, "ccw", "counter-clockwise (M4)"},
};

enum class ToolType {
    drill, centre_drill, spot_drill, tap, reamer, boring_bar, end_mill, ball_mill, bull_nose, chamfer_mill, v_bit,
    engraver, thread_mill, turning_tool, grooving_tool, parting_tool, threading_tool
};
// `description` is how a tool comment names the type ("10 mm spot drill").
inline constexpr Named<ToolType> tool_types[] = {
    {ToolType::drill, "drill", "drill"},
    {ToolType::centre_drill, "centre-drill", "centre drill"},
    {ToolType::spot_drill, "spot-drill", "spot drill"},
    {ToolType::tap, "tap", "tap"},
    {ToolType::reamer, "reamer", "reamer"},
    {ToolType::boring_bar, "boring-bar", "boring bar"},
    {ToolType::end_mill, "end-mill", "end mill"},
    {ToolType::ball_mill, "ball-mill", "ball mill"},
    {ToolType::bull_nose, "bull-nose", "bull-nose end mill"},
    {ToolType::chamfer_mill, "chamfer-mill", "chamfer mill"},
    {ToolType::v_bit, "v-bit", "V-bit"},
    {ToolType::engraver, "engraver", "engraver"},
    {ToolType::thread_mill, "thread-mill", "thread mill"},
    {ToolType::turning_tool, "turning-tool", "turning tool"},
    {ToolType::grooving_tool, "grooving-tool", "grooving tool"},
    {ToolType::parting_tool, "parting-tool", "parting tool"},
    {ToolType::threading_tool, "threading-tool", "threading tool"},
};
// Whether a tool type cuts with a cone of its tipAngle (with a flat of its tipDiameter at the
// point): a chamfer mill, a V-bit, an engraver (a single-flute engraving cutter: geometrically a
// V-bit, named as the shop names it).
constexpr bool is_pointed_cutter(ToolType t) {
    return t == ToolType::chamfer_mill || t == ToolType::v_bit || t == ToolType::engraver;
}
// Whether a tool type is a lathe's tool in the turret (turning, grooving, parting, threading),
// with a nose or a width and a tip orientation, rather than one turning on the spindle's axis.
constexpr bool is_lathe_insert(ToolType t) {
    return t == ToolType::turning_tool || t == ToolType::grooving_tool || t == ToolType::parting_tool ||
           t == ToolType::threading_tool;
}

// Drilling cycle kinds, after the Fanuc/LinuxCNC canned cycles named in the descriptions.
enum class CycleKind { drill, dwell, deep, chip_break, tap, tap_left, ream, bore_stop, bore_dwell };
inline constexpr Named<CycleKind> cycle_kinds[] = {
    {CycleKind::drill, "drill", "G81: feed to depth, rapid out"},
    {CycleKind::dwell, "dwell", "G82: feed to depth, dwell, rapid out"},
    {CycleKind::deep, "deep", "G83: pecks with a full retract to the feed-start plane"},
    {CycleKind::chip_break, "chip-break", "G73: pecks with a short back-off to break the chip"},
    {CycleKind::tap, "tap", "G84: right-hand tapping, spindle reversal at the bottom"},
    {CycleKind::tap_left, "tap-left", "G74: left-hand tapping"},
    {CycleKind::ream, "ream", "G85: feed in, feed out"},
    {CycleKind::bore_stop, "bore-stop", "G86: feed in, spindle stop, rapid out"},
    {CycleKind::bore_dwell, "bore-dwell", "G89: feed in, dwell, feed out"},
};
constexpr bool is_tapping(CycleKind k) { return k == CycleKind::tap || k == CycleKind::tap_left; }
constexpr bool is_pecking(CycleKind k) { return k == CycleKind::deep || k == CycleKind::chip_break; }

// A set of cycle kinds.
class CycleSet {
public:
    constexpr CycleSet() = default;
    constexpr CycleSet(std::initializer_list<CycleKind> kinds) {
        for (CycleKind k : kinds) bits_ |= bit(k);
    }
    static constexpr CycleSet all() {
        CycleSet s;
        for (const auto& n : cycle_kinds) s.bits_ |= bit(n.value);
        return s;
    }
    constexpr bool contains(CycleKind k) const { return (bits_ & bit(k)) != 0; }
    constexpr bool empty() const { return bits_ == 0; }
    constexpr CycleSet without(CycleSet other) const {
        CycleSet s;
        s.bits_ = bits_ & ~other.bits_;
        return s;
    }

private:
    static constexpr std::uint32_t bit(CycleKind k) { return std::uint32_t{1} << static_cast<int>(k); }
    std::uint32_t bits_ = 0;
};

enum class DegressionType { none, value, factor };
inline constexpr Named<DegressionType> degression_types[] = {
    {DegressionType::none, "none", "every peck is firstDepth"},
    {DegressionType::value, "value", "each peck is the previous one less degression (mm)"},
    {DegressionType::factor, "factor", "each peck is the previous one times degression"},
};

// How a drilling cycle is written: canned when the machine's cycle covers every parameter.
enum class CycleOutput { automatic, canned, longhand };
inline constexpr Named<CycleOutput> cycle_outputs[] = {
    {CycleOutput::automatic, "auto", "canned where the machine's cycle carries every field used, else longhand"},
    {CycleOutput::canned, "canned", "canned, or an error naming what the machine's cycle cannot carry"},
    {CycleOutput::longhand, "longhand", "plain rapids, feeds and dwells"},
};

// What becomes of a drilling cycle the machine cannot make at all (a tap where it cannot tap):
// refused, or left to the operator at a stop that lists its holes.
enum class UnsupportedCycle { refuse, stop };
inline constexpr Named<UnsupportedCycle> unsupported_cycles[] = {
    {UnsupportedCycle::refuse, "refuse", "the job is refused, nothing is written"},
    {UnsupportedCycle::stop, "stop",
     "a stop with a message for the operator that lists the holes and what to do at them, instead of the cycle"},
};

// The kind of a feed move, as CNC-Calc's getFeedrate(movement) tells them apart: each has its
// own feed in a job, and statistics and the backplot show them apart.
enum class Movement { cutting, plunge, ramp, lead_in, lead_out, finishing };
inline constexpr Named<Movement> movements[] = {
    {Movement::cutting, "cutting", "along the profile"},
    {Movement::plunge, "plunge", "straight down into the material"},
    {Movement::ramp, "ramp", "down along the profile or a helix"},
    {Movement::lead_in, "lead-in", "onto the profile"},
    {Movement::lead_out, "lead-out", "off the profile"},
    {Movement::finishing, "finishing", "the finishing pass"},
};

// Which way a milling cutter meets the material (contour, bore-mill). Climb: the tool is left
// of its travel with a clockwise spindle (M3), so it goes counter-clockwise round a hole;
// conventional: right. A counter-clockwise spindle swaps them.
enum class CutDirection { climb, conventional };
inline constexpr Named<CutDirection> cut_directions[] = {
    {CutDirection::climb, "climb", "down milling: the path is walked so that the tool is left of its travel (M3)"},
    {CutDirection::conventional, "conventional", "up milling: the tool right of its travel (M3)"},
};

// Whether the tool is left of its travel for a cut direction and spindle direction.
constexpr bool tool_left_of_travel(CutDirection cut, SpindleDirection spindle) {
    return (cut == CutDirection::climb) == (spindle == SpindleDirection::cw);
}

enum class HoleOrder { as_given, shortest };
inline constexpr Named<HoleOrder> hole_orders[] = {
    {HoleOrder::as_given, "as-given", "in the order the job lists them"},
    {HoleOrder::shortest, "shortest", "nearest neighbour from the first hole, then 2-opt"},
};

// The optional drilling parameters of a cycle (CNC-Calc's MillDrillingFields, plus
// safeDistance for controls whose cycle has no separate feed-start plane). A machine's
// drilling table names the fields each canned cycle carries.
enum class DrillField {
    safe_distance, plunging_feedrate, retract_feedrate, first_depth, subsequent_depth, degression_type,
    degression, minimum_depth, pecking_retract, peck_clearance, first_feedrate_factor, pitch, tapping_speed,
    retract_speed, top_dwell, bottom_dwell
};

// A bound on a value: `value` itself allowed or not.
struct Bound {
    double value = 0.0;
    bool inclusive = false;
};

// One drilling field: its job-file key, what it measures, its bounds, the cycle kinds that use
// it and need it, and a line of description.
struct DrillFieldInfo {
    DrillField field;
    std::string_view key;
    Quantity quantity;
    std::optional<Bound> min;           // checked when the job reads it (see bound_message)
    CycleSet used_by;                   // other cycle kinds refuse the key
    CycleSet required_by;               // these kinds need it
    std::optional<double> neutral;      // a value that changes nothing: not counted as used
    bool in_planes = false;             // resolved into the cycle's planes, not carried as a value
    std::string_view bound_message;     // the message when the bound fails ("" : "KEY must be > N")
    std::string_view required_hint;     // said after "cycle X needs KEY"
    std::string_view description;
};

inline constexpr CycleSet tapping_kinds{CycleKind::tap, CycleKind::tap_left};
inline constexpr CycleSet pecking_kinds{CycleKind::deep, CycleKind::chip_break};

// Table order is the order of "it uses: ..." lists and of the fields in --events.
inline constexpr auto drill_fields = std::to_array<DrillFieldInfo>({
    {DrillField::safe_distance, "safeDistance", Quantity::length, std::nullopt, CycleSet::all(), {}, std::nullopt,
     true, "", "",
     "where rapid turns into feed: mm above referencePlane, or an absolute Z with safeDistanceIsAbsolute "
     "(default: the retract plane)"},
    {DrillField::plunging_feedrate, "plungingFeedrate", Quantity::feed, Bound{0.0, false},
     CycleSet::all().without(tapping_kinds), CycleSet::all().without(tapping_kinds), std::nullopt, false, "", "",
     "feed into the hole"},
    {DrillField::retract_feedrate, "retractFeedrate", Quantity::feed, Bound{0.0, false},
     {CycleKind::drill, CycleKind::dwell, CycleKind::deep, CycleKind::chip_break, CycleKind::ream, CycleKind::bore_dwell},
     {}, std::nullopt, false, "", "", "feed out of the hole (default: rapid out, or plungingFeedrate where the cycle feeds out)"},
    {DrillField::first_depth, "firstDepth", Quantity::length, Bound{0.0, false}, pecking_kinds, pecking_kinds,
     std::nullopt, false, "a peck depth must be > 0", "(the depth of a peck)", "depth of each peck (the first one when a degression applies)"},
    {DrillField::subsequent_depth, "subsequentDepth", Quantity::length, Bound{0.0, false}, pecking_kinds, {},
     std::nullopt, false, "a peck depth must be > 0", "",
     "depth of every peck after the first (CNC-Calc turning's subsequentPecksDepths; default: firstDepth); not with a "
     "degression"},
    {DrillField::degression_type, "degressionType", Quantity::choice, std::nullopt, pecking_kinds, {}, std::nullopt,
     false, "", "", "how pecks shrink: next = previous - degression (value) or previous x degression (factor)"},
    {DrillField::degression, "degression", Quantity::length, std::nullopt, pecking_kinds, {}, std::nullopt, false, "",
     "", "mm > 0 taken off each peck (degressionType value), or a factor 0 < f <= 1 (factor)"},
    {DrillField::minimum_depth, "minimumDepth", Quantity::length, Bound{0.0, false}, pecking_kinds, {}, std::nullopt,
     false, "", "", "smallest peck once a degression applies; required with a degression"},
    {DrillField::pecking_retract, "peckingRetract", Quantity::length, Bound{0.0, false}, {CycleKind::chip_break}, {},
     std::nullopt, false, "", "", "how far the drill backs off between pecks to break the chip (default: the machine's peckClearance)"},
    {DrillField::peck_clearance, "peckClearance", Quantity::length, Bound{0.0, false}, {CycleKind::deep}, {},
     std::nullopt, false, "", "",
     "where the rapid back into the hole turns to feed, above the previous peck (default: the machine's peckClearance)"},
    {DrillField::first_feedrate_factor, "firstFeedrateFactor", Quantity::factor, Bound{0.0, false}, pecking_kinds, {},
     1.0, false, "", "", "feed of the first peck = plungingFeedrate x factor"},
    {DrillField::pitch, "pitch", Quantity::length, Bound{0.0, false}, tapping_kinds, tapping_kinds, std::nullopt,
     false, "", "(the thread lead per revolution)", "thread lead per revolution; tapping feed = pitch x spindle speed"},
    {DrillField::tapping_speed, "tappingSpeed", Quantity::speed, Bound{0.0, false}, tapping_kinds, {}, std::nullopt,
     false, "", "", "spindle speed into the hole (default: the tool's rpm)"},
    {DrillField::retract_speed, "retractSpeed", Quantity::speed, Bound{0.0, false}, tapping_kinds, {}, std::nullopt,
     false, "", "", "spindle speed out of the hole (default: the tapping speed)"},
    {DrillField::top_dwell, "topDwell", Quantity::time, Bound{0.0, true},
     {CycleKind::drill, CycleKind::dwell, CycleKind::deep, CycleKind::chip_break}, {}, 0.0, false,
     "a dwell cannot be negative", "", "dwell at the feed-start plane before drilling (and before each deep peck)"},
    {DrillField::bottom_dwell, "bottomDwell", Quantity::time, Bound{0.0, true},
     CycleSet::all().without({CycleKind::drill}), {CycleKind::dwell, CycleKind::bore_dwell}, 0.0, false,
     "a dwell cannot be negative", "(seconds)", "dwell at the bottom of the hole"},
});
// One field of CNC-Calc's TurnDrillingFields (the parameters of onDrilling that a lathe's
// drilling cycle may carry): its name in turn-drill operations and lathe machine files, and
// the drilling field it is carried as (its quantity, bound and motion are that field's).
struct TurnDrillFieldInfo {
    std::string_view key;
    DrillField field;
    std::string_view description;
};

// The TurnDrillingFields, in CNC-Calc's order (its spellings evened out: subsequentPeckDepths,
// peckRetract, lowerDwell). A turn-drill's feed-start plane (safeDistance) is always carried.
inline constexpr auto turn_drill_fields = std::to_array<TurnDrillFieldInfo>({
    {"plungingFeedrate", DrillField::plunging_feedrate, "feed into the hole"},
    {"retractFeedrate", DrillField::retract_feedrate, "feed out of the hole (default: rapid out)"},
    {"firstPeckDepth", DrillField::first_depth, "depth of the first peck; pecking when present"},
    {"subsequentPeckDepths", DrillField::subsequent_depth, "depth of every later peck (default: firstPeckDepth)"},
    {"peckClearance", DrillField::peck_clearance,
     "full retract between pecks; the rapid back in turns to feed this far above the previous peck"},
    {"peckRetract", DrillField::pecking_retract, "chip breaking: the drill backs off this far between pecks"},
    {"upperDwell", DrillField::top_dwell, "dwell (s) at the feed-start plane before drilling (and before each deep peck)"},
    {"lowerDwell", DrillField::bottom_dwell, "dwell (s) at the bottom of the hole"},
    {"pitch", DrillField::pitch, "tapping on the axis: the thread lead; the feed is pitch x spindle speed"},
});
// The TurnDrillingFields row carried as drilling field `f`, if any.
const TurnDrillFieldInfo* turn_field_of(DrillField f);
// The drilling field of a TurnDrillingFields name ("firstPeckDepth"), if it is one.
std::optional<DrillField> turn_drill_field_named(std::string_view key);
// The TurnDrillingFields names, in table order.
std::vector<std::string> turn_drill_field_keys();

// How many drilling fields there are.
inline constexpr std::size_t drill_field_count = drill_fields.size();

// The row of a field.
constexpr const DrillFieldInfo& info(DrillField f) { return drill_fields[static_cast<std::size_t>(f)]; }
// The job-file key of a field ("plungingFeedrate").
constexpr std::string_view key_of(DrillField f) { return info(f).key; }
// The field of a job-file key, if it is one.
std::optional<DrillField> drill_field_named(std::string_view key);
// The keys of every drilling field, in table order.
std::vector<std::string> drill_field_keys();

// A quantity as the docs write it, with its unit and bounds: "length (mm) > 0",
// "angle (degrees) > 0, <= 180".
std::string quantity_text(Quantity quantity, std::optional<Bound> min, std::optional<Bound> max = std::nullopt);

// The drilling fields as a Markdown table (key, value, cycles, meaning) for docs/job-format.md.
std::string drill_fields_markdown();
// The cycle kinds as a Markdown table (kind, what it does, the fields it uses; required ones
// in bold) for docs/job-format.md.
std::string cycle_kinds_markdown();

// The values of the drilling fields, in internal units (mm, mm/min, s, rpm, factors; the
// degression type as its enum's number). Present: the job set it, or a program said it.
class DrillValues {
public:
    std::optional<double> get(DrillField f) const { return values_[index(f)]; }
    bool has(DrillField f) const { return values_[index(f)].has_value(); }
    double value_or(DrillField f, double fallback) const { return values_[index(f)].value_or(fallback); }
    void set(DrillField f, std::optional<double> v) { values_[index(f)] = v; }
    // The degression type (none when unset).
    DegressionType degression_type() const {
        return static_cast<DegressionType>(static_cast<int>(value_or(DrillField::degression_type, 0.0)));
    }
    void set_degression_type(DegressionType t) {
        set(DrillField::degression_type, t == DegressionType::none ? std::nullopt : std::optional<double>(static_cast<int>(t)));
    }
    // True when the field is set to something other than its neutral value (a 0 s dwell, a
    // first feed factor of 1 change nothing).
    bool used(DrillField f) const {
        const auto& v = values_[index(f)];
        return v && !(info(f).neutral && *v == *info(f).neutral);
    }
    friend bool operator==(const DrillValues&, const DrillValues&) = default;

private:
    static constexpr std::size_t index(DrillField f) { return static_cast<std::size_t>(f); }
    std::array<std::optional<double>, drill_field_count> values_{};
};

}  // namespace camgen
