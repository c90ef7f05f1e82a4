#include "camgen/operations/turn_drill/turn_drill.hpp"

#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/drill/drill.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

// The keys of a turn-drill operation besides the TurnDrillingFields, which follow them.
constexpr KeySpec turn_drill_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "startDepth", .quantity = Quantity::length, .required = true,
     .description = "absolute Z of the face of the material, where the hole starts"},
    {.key = "endDepth", .quantity = Quantity::length, .required = true,
     .description = "absolute Z of the bottom of the hole (before the drill tip), below startDepth"},
    {.key = "safeDistance", .quantity = Quantity::length, .required = true,
     .description = "absolute Z where the rapid approach turns into feed, at or above startDepth"},
    {.key = "retractDistance", .quantity = Quantity::length,
     .description = "absolute Z the drill goes to after the hole, at or above safeDistance (default: clearance)"},
    {.key = "drillTip", .type = JsonType::boolean, .default_json = "false",
     .description = "add the drill's tip length (drillDiameter / 2) / tan(drillTipAngle / 2) to the depth"},
    {.key = "drillDiameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the drill's diameter for drillTip (default: the tool's)"},
    {.key = "drillTipAngle", .quantity = Quantity::angle, .min = Bound{30, true}, .max = Bound{180, false},
     .description = "the drill's included point angle for drillTip (default: the tool's tipAngle)"},
    {.key = "feedMode", .type = JsonType::string, .default_json = "\"per-minute\"", .choices = &choices_of<feed_modes>,
     .description = "plungingFeedrate and retractFeedrate per minute (mm/min) or per spindle revolution (mm/rev); the "
                    "program feeds the same way (G94/G95, Fanuc T G98/G99)"},
    {.key = "output", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<cycle_outputs>,
     .description = "canned cycle or plain moves: auto, canned or longhand"},
    {.key = "unsupported", .type = JsonType::string, .default_json = "\"refuse\"", .choices = &choices_of<unsupported_cycles>,
     .description = "where the machine cannot make the cycle at all (a tap on a machine that cannot tap): refuse the job, "
                    "or stop the program at the clearance after the operation with a message that lists the holes, for "
                    "the operator to make them by hand"},
};

// A TurnDrillingFields row as a key of the operation: the quantity and bound of its field.
KeySpec key_of_turn_field(const TurnDrillFieldInfo& t) {
    const DrillFieldInfo& d = info(t.field);
    return KeySpec{.key = t.key, .quantity = d.quantity, .min = d.min, .description = t.description};
}

std::vector<KeySpec> all_turn_drill_keys() {
    std::vector<KeySpec> keys(std::begin(turn_drill_keys), std::end(turn_drill_keys));
    for (const auto& t : turn_drill_fields) keys.push_back(key_of_turn_field(t));
    return keys;
}

// The TurnDrillingFields the job gives, with their bounds checked.
DrillValues read_turn_fields(Fields& f, const JobInput& in) {
    DrillValues values;
    for (const auto& t : turn_drill_fields) {
        const DrillFieldInfo& d = info(t.field);
        const std::optional<double> v = in.optional_quantity(f, t.key, d.quantity);
        if (v && d.min && (d.min->inclusive ? *v < d.min->value : *v <= d.min->value)) {
            if (!d.bound_message.empty()) f.fail(t.key, std::string(d.bound_message));
            f.fail(t.key, fmt::format("{} must be {} {}", t.key, d.min->inclusive ? ">=" : ">", d.min->value));
        }
        values.set(t.field, v);
    }
    return values;
}

std::string_view turn_key(DrillField field) { return turn_field_of(field)->key; }

// The cycle kind the parameters ask for (CNC-Calc picks the cycle by the fields in use): a
// pitch taps, pecks with a back-off break the chip, other pecks retract fully, a lower dwell
// alone dwells. Parameters that contradict each other are refused.
CycleKind kind_of(Fields& f, const DrillValues& v, const Tool& tool) {
    const bool pecks = v.has(DrillField::first_depth);
    if (v.has(DrillField::pitch)) {
        for (DrillField other : {DrillField::plunging_feedrate, DrillField::retract_feedrate, DrillField::first_depth,
                                 DrillField::top_dwell})
            if (v.has(other))
                f.fail(turn_key(other), fmt::format("{} has no meaning when tapping (pitch): the tap feeds pitch x "
                                                    "spindle speed, in and out",
                                                    turn_key(other)));
        return tool.direction == SpindleDirection::cw ? CycleKind::tap : CycleKind::tap_left;
    }
    if (!v.has(DrillField::plunging_feedrate))
        f.fail("plungingFeedrate", "a turn-drill needs plungingFeedrate (or pitch, to tap)");
    for (DrillField later : {DrillField::subsequent_depth, DrillField::peck_clearance, DrillField::pecking_retract})
        if (v.has(later) && !pecks)
            f.fail(turn_key(later), fmt::format("{} is a pecking parameter: it needs firstPeckDepth", turn_key(later)));
    if (v.has(DrillField::peck_clearance) && v.has(DrillField::pecking_retract))
        f.fail(turn_key(DrillField::pecking_retract),
               "give peckClearance (a full retract between pecks) or peckRetract (a back-off to break the chip), not both");
    if (pecks) return v.has(DrillField::pecking_retract) ? CycleKind::chip_break : CycleKind::deep;
    return v.used(DrillField::bottom_dwell) ? CycleKind::dwell : CycleKind::drill;
}

// The drill-tip length drillTip asks for (0 without it).
double tip_length(Fields& f, const JobInput& in, const Tool& tool) {
    const bool tip = f.boolean("drillTip", false);
    const std::optional<double> diameter = in.optional_length(f, "drillDiameter");
    const std::optional<double> angle = f.optional_number("drillTipAngle");
    for (const char* key : {"drillDiameter", "drillTipAngle"})
        if (!tip && f.has(key)) f.fail(key, fmt::format("{} has no effect without drillTip", key));
    if (!tip) return 0.0;
    if (diameter && !(*diameter > 0)) f.fail("drillDiameter", "drillDiameter must be > 0");
    if (angle && (*angle < 30 || *angle >= 180))
        f.fail("drillTipAngle", fmt::format("drillTipAngle {} degrees is not a drill point: it must be between 30 "
                                            "(inclusive) and 180 degrees",
                                            *angle));
    if (!angle && !tool.tip_angle)
        f.fail("drillTip", fmt::format("drillTip needs drillTipAngle or the tool's tipAngle, but tool {} ({}) has none",
                                       tool.number, tool.path));
    return drill_tip_length(diameter.value_or(tool.diameter), angle ? *angle : *tool.tip_angle);
}

}  // namespace

std::vector<ObjectSpec> TurnDrillOp::objects() {
    return {{.name = "turn-drill",
             .description = "drill one hole on a lathe's spindle axis (CNC-Calc onDrilling with its TurnDrillingFields)",
             .keys = all_turn_drill_keys()}};
}

TurnDrillOp TurnDrillOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, all_turn_drill_keys());
    const Tool& tool = in.tool(f);
    // Its teeth cut sideways only, at a thread's depth: it cannot go down into material.
    if (tool.type == ToolType::thread_mill)
        f.fail("tool", fmt::format("tool {} ({}) is a thread mill: a turn-drill goes down into the material, which a thread "
                                   "mill's teeth cannot cut (the thread-mill operation mills threads)",
                                   tool.number, tool.path));
    TurnDrillOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");

    DrillCycle& c = op.cycle;
    c.path = op.path;
    c.reference_z = in.length(f, "startDepth");
    const double end = in.length(f, "endDepth");
    c.safe_z = in.length(f, "safeDistance");
    c.retract_z = in.optional_length(f, "retractDistance").value_or(in.header().clearance);
    if (!(end < c.reference_z))
        f.fail("endDepth", fmt::format("endDepth (Z {}) is not below startDepth (Z {}): the hole's bottom must be below "
                                       "the face it starts at",
                                       in.show(end), in.show(c.reference_z)));
    if (c.safe_z < c.reference_z)
        f.fail("safeDistance", fmt::format("safeDistance (Z {}) is below startDepth, the face of the material (Z {}): the "
                                           "rapid approach would end inside the material",
                                           in.show(c.safe_z), in.show(c.reference_z)));
    if (c.retract_z < c.safe_z)
        f.fail(f.has("retractDistance") ? "retractDistance" : "safeDistance",
               fmt::format("retractDistance{} (Z {}) is below safeDistance (Z {})",
                           f.has("retractDistance") ? "" : ", the clearance,", in.show(c.retract_z), in.show(c.safe_z)));
    if (c.retract_z <= c.reference_z)
        f.fail("retractDistance", fmt::format("retractDistance (Z {}) is not above startDepth, the face of the material "
                                              "(Z {}): the drill would rapid away through the material",
                                              in.show(c.retract_z), in.show(c.reference_z)));
    // Checked here, not by the safety check after expansion, so that the message names the
    // turn-drill's own key (a drill's is retractPlane).
    if (c.retract_z > in.header().clearance + 1e-6)
        f.fail("retractDistance", fmt::format("the clearance (Z {}) is below retractDistance (Z {}): moves at the clearance "
                                              "would run below this operation's retract plane",
                                              in.show(in.header().clearance), in.show(c.retract_z)));

    c.values = read_turn_fields(f, in);
    op.feed_mode = f.choice("feedMode", feed_modes, FeedMode::per_minute);
    if (op.feed_mode == FeedMode::per_revolution)
        for (DrillField feed : {DrillField::plunging_feedrate, DrillField::retract_feedrate})
            if (auto per_rev = c.values.get(feed)) c.values.set(feed, *per_rev * tool.rpm);
    c.kind = kind_of(f, c.values, tool);
    c.bottom_z = end - tip_length(f, in, tool);
    c.output = f.choice("output", cycle_outputs, CycleOutput::automatic);
    c.unsupported = f.choice("unsupported", unsupported_cycles, UnsupportedCycle::refuse);
    c.spindle_rpm = tool.rpm;
    c.spindle_direction = tool.direction;
    c.feed = is_tapping(c.kind) ? c.values.value_or(DrillField::pitch, 0.0) * tool.rpm
                                : c.values.value_or(DrillField::plunging_feedrate, 0.0);
    return op;
}

void expand(const TurnDrillOp& op, const Context& context, EventSink& sink) {
    expand_cycle(op.cycle, {Vec2{0.0, 0.0}}, context, sink);
}

std::string default_name(const TurnDrillOp& op) {
    return op.comment.empty() ? fmt::format("centre drill to Z{:g}", op.cycle.bottom_z + 0.0) : op.comment;
}

}  // namespace camgen
