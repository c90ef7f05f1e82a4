#include "camgen/operations/drill/drill.hpp"

#include <cmath>
#include <iterator>
#include <numbers>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

// The keys of a drill operation besides the drilling fields (drill_fields), which follow them.
constexpr KeySpec drill_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "cycle", .type = JsonType::string, .default_json = "\"drill\"", .choices = &choices_of<cycle_kinds>,
     .description = "the drilling cycle"},
    {.key = "drillTip", .type = JsonType::boolean, .default_json = "false",
     .description = "add the tool's tip length (from diameter and tipAngle) to the depth"},
    {.key = "output", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<cycle_outputs>,
     .description = "canned cycle or plain moves: auto, canned or longhand"},
    {.key = "unsupported", .type = JsonType::string, .default_json = "\"refuse\"", .choices = &choices_of<unsupported_cycles>,
     .description = "where the machine cannot make the cycle at all (a tap on a machine that cannot tap): refuse the job, "
                    "or stop the program at the clearance after the operation with a message that lists the holes, for "
                    "the operator to make them by hand"},
};

// A drilling field of the vocabulary's table as a key of the drill operation.
KeySpec key_of_field(const DrillFieldInfo& d) {
    KeySpec k{.key = d.key, .quantity = d.quantity, .min = d.min, .description = d.description};
    if (d.quantity == Quantity::choice) {
        k.type = JsonType::string;
        k.default_json = "\"none\"";
        k.choices = &choices_of<degression_types>;
    }
    return k;
}

// The keys of a drill operation: drill_keys with the heights after "cycle", the hole sources,
// then the drilling fields (safeDistance is one of them).
std::vector<KeySpec> all_drill_keys() {
    std::vector<KeySpec> keys(std::begin(drill_keys), std::end(drill_keys));
    const std::vector<KeySpec> heights = height_keys(false);
    keys.insert(keys.begin() + 4, heights.begin(), heights.end());
    const std::vector<KeySpec> holes = hole_keys();
    keys.insert(keys.end(), holes.begin(), holes.end());
    for (const auto& d : drill_fields) keys.push_back(key_of_field(d));
    return keys;
}

// Per cycle kind: the drilling fields it needs and those it refuses; and the degression's
// partners (see read_degression).
std::vector<KeyRule> drill_rules() {
    std::vector<KeyRule> rules;
    for (const auto& kind : cycle_kinds) {
        KeyRule r{.when_key = "cycle", .values = {std::string(kind.name)}, .require = {}, .forbid = {}};
        for (const auto& d : drill_fields) {
            // A plunging feed may come from the tool's library cutting data: not required here.
            if (d.required_by.contains(kind.value) && d.field != DrillField::plunging_feedrate) r.require.push_back(d.key);
            if (!d.in_planes && !d.used_by.contains(kind.value)) r.forbid.push_back(d.key);
        }
        rules.push_back(std::move(r));
    }
    const std::string_view degression = key_of(DrillField::degression), minimum = key_of(DrillField::minimum_depth);
    rules.push_back({.when_key = key_of(DrillField::degression_type),
                     .values = {std::string(name_of(degression_types, DegressionType::none))},
                     .require = {},
                     .forbid = {degression, minimum}});
    rules.push_back({.when_key = key_of(DrillField::degression_type),
                     .values = {std::string(name_of(degression_types, DegressionType::value)),
                                std::string(name_of(degression_types, DegressionType::factor))},
                     .require = {degression, minimum},
                     .forbid = {key_of(DrillField::subsequent_depth)}});
    return rules;
}

// The fields a cycle kind uses, in table order ("plungingFeedrate, retractFeedrate, topDwell").
std::vector<std::string_view> fields_used_by(CycleKind kind) {
    std::vector<std::string_view> out;
    for (const auto& f : drill_fields)
        if (!f.in_planes && f.used_by.contains(kind)) out.push_back(f.key);
    return out;
}



// Reads one optional drilling field: presence, bounds and the cycle's need of it.
void read_field(Fields& f, const JobInput& in, const DrillFieldInfo& info, CycleKind kind, DrillValues& values) {
    if (info.quantity == Quantity::choice) return;  // degressionType: read with its partner
    const std::string_view key = info.key;
    std::optional<double> v = in.optional_quantity(f, key, info.quantity);
    if (!v && info.required_by.contains(kind))
        f.fail(key, fmt::format("cycle {} needs {}{}{}", name_of(cycle_kinds, kind), key,
                                info.required_hint.empty() ? "" : " ", info.required_hint));
    if (v && info.min && (info.min->inclusive ? *v < info.min->value : *v <= info.min->value)) {
        if (!info.bound_message.empty()) f.fail(key, std::string(info.bound_message));
        f.fail(key, fmt::format("{} must be {} {}", key, info.min->inclusive ? ">=" : ">", info.min->value));
    }
    values.set(info.field, v);
}

// degressionType and degression: a value in mm or a factor, bounded below by minimumDepth.
void read_degression(Fields& f, const JobInput& in, DrillValues& values) {
    const DegressionType type = f.choice("degressionType", degression_types, DegressionType::none);
    values.set_degression_type(type);
    const std::optional<double> degression = type == DegressionType::factor ? f.optional_number("degression")
                                                                            : in.optional_length(f, "degression");
    values.set(DrillField::degression, degression);
    const std::optional<double> minimum = values.get(DrillField::minimum_depth);
    switch (type) {
        case DegressionType::none:
            if (degression) f.fail("degression", "degression has no effect without degressionType");
            if (minimum) f.fail("minimumDepth", "minimumDepth has no effect without degressionType");
            break;
        case DegressionType::value:
            if (!degression || *degression <= 0)
                f.fail("degression", "degressionType value needs a degression > 0 (mm taken off each peck)");
            break;
        case DegressionType::factor:
            if (!degression || *degression <= 0 || *degression > 1)
                f.fail("degression",
                       "degressionType factor needs a degression with 0 < degression <= 1 (each "
                       "peck is the previous one times the factor)");
            break;
    }
    if (type != DegressionType::none && values.has(DrillField::subsequent_depth))
        f.fail("subsequentDepth", "subsequentDepth and a degression both set the later pecks: give one of them");
    if (type != DegressionType::none && !minimum)
        f.fail("degressionType",
               "a degression needs a positive minimumDepth, or the pecks shrink towards zero "
               "forever");
}

}  // namespace

std::vector<ObjectSpec> DrillOp::objects() {
    std::vector<ObjectSpec> objects{{.name = "drill", .description = "drill a list of holes with one cycle",
                                     .keys = all_drill_keys(), .groups = {hole_group("a drill operation needs holes")},
                                     .rules = drill_rules()}};
    for (ObjectSpec& o : hole_objects()) objects.push_back(std::move(o));
    return objects;
}

DrillOp DrillOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, all_drill_keys());
    const Tool& tool = in.tool(f);
    // Its teeth cut sideways only, at a thread's depth: it cannot go down into material.
    if (tool.type == ToolType::thread_mill)
        f.fail("tool", fmt::format("tool {} ({}) is a thread mill: a drill operation goes down into the material, which a thread "
                                   "mill's teeth cannot cut (the thread-mill operation mills threads)",
                                   tool.number, tool.path));

    DrillOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    DrillParams& p = op.params;

    p.kind = f.choice("cycle", cycle_kinds, CycleKind::drill);
    const std::string_view cycle_name = name_of(cycle_kinds, p.kind);
    // Of the parameters this cycle does not use, report the one that comes first in the file.
    std::optional<std::string_view> unused;
    int unused_line = 0;
    for (const auto& d : drill_fields) {
        if (d.in_planes || !f.has(d.key) || d.used_by.contains(p.kind)) continue;
        const int line = in.source().lines.line_of(f.path_of(d.key));
        if (!unused || line < unused_line) {
            unused = d.key;
            unused_line = line;
        }
    }
    if (unused) {
        const std::string_view key = *unused;
        std::string detail = fmt::format("{} is not used by cycle {} (it uses: {})", key, cycle_name,
                                         fmt::join(fields_used_by(p.kind), ", "));
        if (is_tapping(p.kind) && key == key_of(DrillField::plunging_feedrate)) detail += "; a tapping feed is pitch x rpm";
        f.fail(key, detail);
    }

    // Planes and depths.
    static_cast<Heights&>(p) = read_heights(f, in, "hole");

    // The optional fields, by the vocabulary's table; then the degression, which reads two.
    // The plunging feed, where the job gives none, from the tool's library cutting data (a
    // feed per revolution x rpm).
    std::vector<std::string> computed_notes;
    for (const auto& d : drill_fields) {
        if (d.in_planes) continue;
        if (d.field == DrillField::plunging_feedrate && !f.has(d.key) && d.used_by.contains(p.kind))
            if (const auto feed = computed_drilling_feed(tool, computed_notes)) {
                p.values.set(d.field, *feed);
                continue;
            }
        read_field(f, in, d, p.kind, p.values);
    }
    read_degression(f, in, p.values);

    p.drill_tip = f.boolean("drillTip", false);
    if (p.drill_tip && !tool.tip_angle)
        f.fail("drillTip", fmt::format("drillTip needs the tool's tipAngle, but tool {} ({}) "
                                       "has none",
                                       tool.number, tool.path));
    p.output = f.choice("output", cycle_outputs, CycleOutput::automatic);
    p.unsupported = f.choice("unsupported", unsupported_cycles, UnsupportedCycle::refuse);
    static_cast<HoleSet&>(op) = read_hole_set(f, in, type);
    op.notes.insert(op.notes.begin(), computed_notes.begin(), computed_notes.end());
    return op;
}


std::string default_name(const DrillOp& d) {
    return d.comment.empty() ? fmt::format("drill {} hole{}", d.holes.size(), d.holes.size() == 1 ? "" : "s")
                             : d.comment;
}


DrillCycle resolve_cycle(const DrillOp& op, const Tool& tool) {
    const DrillParams& p = op.params;
    const Planes z = resolve_planes(p);
    DrillCycle c;
    c.kind = p.kind;
    c.output = p.output;
    c.unsupported = p.unsupported;
    c.path = op.path;
    c.values = p.values;
    c.retract_z = z.retract_z;
    c.reference_z = z.reference_z;
    c.safe_z = z.safe_z;
    c.bottom_z = z.bottom_z;
    if (p.drill_tip && tool.tip_angle) c.bottom_z -= drill_tip_length(tool.diameter, *tool.tip_angle);
    c.spindle_rpm = tool.rpm;
    c.spindle_direction = tool.direction;
    c.feed = is_tapping(p.kind) ? p.values.value_or(DrillField::pitch, 0.0) *
                                      p.values.value_or(DrillField::tapping_speed, tool.rpm)
                                : p.values.value_or(DrillField::plunging_feedrate, 0.0);
    return c;
}

double drill_tip_length(double diameter, double tip_angle) {
    const double half = tip_angle * std::numbers::pi / 360.0;
    return diameter / 2.0 / std::tan(half);
}

void expand(const DrillOp& op, const Context& ctx, EventSink& sink) {
    if (op.holes.empty()) return;
    std::vector<Vec2> reordered;
    expand_cycle(resolve_cycle(op, ctx.tool), visit_order(op, reordered), ctx, sink);
}

void expand_cycle(const DrillCycle& c, const std::vector<Vec2>& holes, const Context& ctx, EventSink& sink) {
    const Vec2 first = holes.front();
    sink.emit(Rapid{{first.x, first.y, ctx.job.clearance}});
    if (c.retract_z != ctx.job.clearance) sink.emit(Rapid{{first.x, first.y, c.retract_z}});
    sink.emit(c);
    for (const Vec2& h : holes) sink.emit(DrillPoint{h});
    sink.emit(DrillEnd{});
    const Vec2 last = holes.back();
    if (c.retract_z != ctx.job.clearance) sink.emit(Rapid{{last.x, last.y, ctx.job.clearance}});
}

}  // namespace camgen
