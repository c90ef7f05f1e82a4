#include "camgen/job/job_input.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {


// The top-level keys of a job.
constexpr KeySpec job_keys[] = {
    {.key = "$schema", .type = JsonType::string,
     .description = "the JSON Schema of the file, for editors (camgen ignores it)"},
    {.key = "name", .type = JsonType::string,
     .description = "job name, for the NC program header (default: the file name without extension)"},
    {.key = "units", .type = JsonType::string, .default_json = "\"mm\"", .choices = &choices_of<unit_names>,
     .description = "the units of every length and feed in the file"},
    {.key = "clearance", .quantity = Quantity::length, .required = true,
     .description = "absolute Z that is safe for moves between operations"},
    {.key = "workOffset", .type = JsonType::string,
     .description = "the work offset the program selects, as the control writes it: G54 .. G59, and where the "
                    "machine has them G59.1 (LinuxCNC), G54.1 P1 (Fanuc), G505 (Sinumerik); refused on a machine "
                    "without it (default: none written)"},
    {.key = "programNumber", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{99999999, true},
     .description = "the program number (Fanuc O-number), overriding the machine's; refused where the control "
                    "takes none (default: the machine's)"},
    {.key = "stock", .type = JsonType::object, .ref = "stock",
     .description = "the material before the first operation: a box or a closed profile on a mill, a bar on a lathe "
                    "(default: none; the safety checks and face use it where it is given)"},
    {.key = "tools", .type = JsonType::array, .required = true, .ref = "tool", .min_items = 1,
     .description = "the tool table, at least one tool"},
    {.key = "operations", .type = JsonType::array, .required = true, .ref = "operation",
     .description = "what to do, in order (may be empty)"},
};

// The keys of a tool.
constexpr KeySpec tool_keys[] = {
    {.key = "number", .type = JsonType::integer, .quantity = Quantity::count, .required = true,
     .min = Bound{1, true}, .description = "tool number (T word), unique within the job"},
    {.key = "type", .type = JsonType::string, .default_json = "\"drill\"", .choices = &choices_of<tool_types>,
     .description = "kind of tool"},
    {.key = "diameter", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "cutting diameter"},
    {.key = "tipAngle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{180, false},
     .description = "included point angle: a drill's (30 or more; needed by drillTip), a chamfer mill's or V-bit's "
                    "(required for them)"},
    {.key = "cornerRadius", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a bull-nose end mill's corner radius, at most half the diameter (required for bull-nose, refused "
                    "for other types)"},
    {.key = "tipDiameter", .quantity = Quantity::length, .min = Bound{0, true},
     .description = "a chamfer mill's or V-bit's diameter at its point, less than diameter (default: 0, a sharp "
                    "point; refused for other types)"},
    {.key = "fluteLength", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "how deep the tool can cut; a hole deeper below its referencePlane is refused"},
    {.key = "flutes", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{1000, true}, .description = "number of flutes (cutting edges)"},
    {.key = "pitch", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a multi-form thread mill's pitch: the one pitch its rows of teeth cut (a thread-mill needs pitch, "
                    "or minPitch and maxPitch; refused for other types)"},
    {.key = "minPitch", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a single-profile thread mill's finest pitch (with maxPitch; refused for other types)"},
    {.key = "maxPitch", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a single-profile thread mill's coarsest pitch (with minPitch; refused for other types)"},
    {.key = "centreCutting", .type = JsonType::boolean,
     .description = "the tool cuts at its centre and may plunge into material (default: false for end mills, bull-nose end mills, chamfer mills, thread mills and boring bars, true for the rest); "
                    "a pocket plunges only with such a tool"},
    {.key = "rpm", .quantity = Quantity::speed, .required = true, .min = Bound{0, false},
     .description = "spindle speed (also the tapping speed unless tappingSpeed is given)"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"cw\"",
     .choices = &choices_of<spindle_directions>, .description = "spindle direction: cw (M3) or ccw (M4)"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"", .description = "free text for the tool list"},
    {.key = "coolant", .type = JsonType::string, .default_json = "\"off\"", .choices = &choices_of<coolant_modes>,
     .description = "coolant while the tool cuts: flood (M8), mist (M7) or off; refused on a machine without it"},
};

}  // namespace

std::vector<ObjectSpec> JobInput::objects() {
    // The shape keys each tool type takes: cornerRadius for a bull-nose end mill only, tipDiameter
    // for chamfer mills and V-bits only, which need a tipAngle.
    std::vector<std::string> not_bull_nose, not_pointed, not_thread_mill;
    for (const auto& t : tool_types) {
        if (t.value != ToolType::bull_nose) not_bull_nose.emplace_back(t.name);
        if (t.value != ToolType::chamfer_mill && t.value != ToolType::v_bit) not_pointed.emplace_back(t.name);
        if (t.value != ToolType::thread_mill) not_thread_mill.emplace_back(t.name);
    }
    return {
        {.name = "job", .description = "a camgen job: the tools, and the operations to run with them, in order",
         .keys = {std::begin(job_keys), std::end(job_keys)}},
        {.name = "tool", .description = "a tool of the job's tool table", .keys = {std::begin(tool_keys), std::end(tool_keys)},
         .rules = {{.when_key = "type", .values = {"bull-nose"}, .require = {"cornerRadius"}},
                   {.when_key = "type", .values = not_bull_nose, .forbid = {"cornerRadius"}},
                   {.when_key = "type", .values = {"chamfer-mill", "v-bit"}, .require = {"tipAngle"}},
                   {.when_key = "type", .values = not_pointed, .forbid = {"tipDiameter"}},
                   {.when_key = "type", .values = not_thread_mill, .forbid = {"pitch", "minPitch", "maxPitch"}}}},
    };
}

JobInput::JobInput(std::string_view text, const std::string& source_name, JobLimits limits)
    : limits_(limits), doc_(json::parse_document(text, source_name, limits.nesting)),
      source_{source_name, json::LineMap::borrowing(text)} {}

namespace {
// Draws `count` from a budget of `limit`, or fails naming what would be too many.
void claim(double& claimed, double count, std::size_t limit, const char* what, const char* option, json::Fields& f,
           std::string_view key) {
    if (claimed + count > static_cast<double>(limit))
        f.fail(key, fmt::format("the job would have more than {} {} ({} here, {} before); raise the limit with {}", limit,
                                what, count, claimed, option));
    claimed += count;
}
}  // namespace

void JobInput::claim_holes(double count, Fields& f, std::string_view key) const {
    claim(holes_claimed_, count, limits_.holes, "holes", "--max-holes", f, key);
}

void JobInput::claim_path_elements(double count, Fields& f, std::string_view key) const {
    claim(elements_claimed_, count, limits_.path_elements, "path elements", "--max-elements", f, key);
}

std::string JobInput::describe(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null: return "null";
        case Json::value_t::object: return "an object";
        case Json::value_t::array: return "an array";
        case Json::value_t::string: return "a string " + value.dump();
        case Json::value_t::boolean: return "a boolean (" + value.dump() + ")";
        default: return "a number (" + value.dump() + ")";
    }
}

void JobInput::known_keys(Fields& f, std::span<const KeySpec> table) { f.finish(table); }

JobInput::Fields JobInput::read_header() {
    Fields top(doc_.root, "", source_);
    known_keys(top, job_keys);
    top.optional_string("$schema");
    if (auto name = top.optional_string("name")) header_.name = *name;
    header_.units = top.choice("units", unit_names, Units::mm);
    scale_ = header_.units == Units::inch ? mm_per_inch : 1.0;
    header_.clearance = length(top, "clearance");
    header_.work_offset = top.optional_string("workOffset").value_or("");
    if (auto n = top.optional_integer("programNumber")) {
        if (*n < 1 || *n > 99999999) top.fail("programNumber", "a program number must be between 1 and 99999999");
        header_.program_number = static_cast<int>(*n);
    }

    return top;
}

bool JobInput::units_and_clearance() {
    try {
        Fields top(doc_.root, "", source_);
        header_.units = top.choice("units", unit_names, Units::mm);
        scale_ = header_.units == Units::inch ? mm_per_inch : 1.0;
        header_.clearance = length(top, "clearance");
        return true;
    } catch (const InputError&) {
        return false;
    }
}

namespace {
// The integer member `key` of an object, if it is one.
std::optional<std::int64_t> integer_member(const nlohmann::json& value, const char* key) {
    if (!value.is_object() || !value.contains(key)) return std::nullopt;
    const nlohmann::json& member = value.at(key);
    if (member.is_number_unsigned() &&
        member.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        return std::nullopt;
    if (!member.is_number_integer()) return std::nullopt;
    return member.get<std::int64_t>();
}
}  // namespace

void JobInput::read_tools(Fields& top, const std::function<void(const InputError&)>& report) {
    const Json* tools = nullptr;
    try {
        tools = &array(top, "tools");
        if (tools->empty()) top.fail("tools", "a job needs at least one tool");
    } catch (const InputError& e) {
        unnumbered_tool_failed_ = true;
        report(e);
        return;
    }
    for (std::size_t i = 0; i < tools->size(); ++i) {
        const Json& value = (*tools)[i];
        const std::string path = "/tools/" + std::to_string(i);
        try {
            Tool tool = read_tool(value, path);
            header_.tools.emplace(tool.number, std::move(tool));
        } catch (const InputError& e) {
            // An operation naming the number the tool says it has may have meant this tool.
            // When the number itself is the error (missing, not an integer, below 1, already
            // used), the tool may have been meant to have another: then any number the table
            // lacks may have meant it.
            const std::optional<std::int64_t> said = integer_member(value, "number");
            if (said) failed_tools_.insert(*said);
            if (!said || e.path() == path + "/number") unnumbered_tool_failed_ = true;
            report(e);
        }
    }
}

namespace {
// A thread-mill's pitch, or minPitch and maxPitch, into `tool` (refused for other types).
void job_input_thread_mill_pitches(const JobInput& in, json::Fields& f, Tool& tool, std::string_view type_name) {
    auto optional_length = [&](std::string_view key) { return in.optional_length(f, key); };
    auto show = [&](double v) { return in.show(v); };
    const std::optional<double> pitch = optional_length("pitch"), min = optional_length("minPitch"),
                                max = optional_length("maxPitch");
    if (tool.type != ToolType::thread_mill) {
        for (std::string_view key : {"pitch", "minPitch", "maxPitch"})
            if (f.has(key)) f.fail(key, fmt::format("{} is for a thread-mill, not a {}", key, type_name));
        return;
    }
    if (pitch && (min || max))
        f.fail(min ? "minPitch" : "maxPitch", "a thread-mill has pitch (a multi-form tool) or minPitch and maxPitch (a "
                                              "single-profile tool), not both");
    if (!pitch && !(min && max))
        f.fail(pitch || min || max ? (min ? "maxPitch" : "minPitch") : "",
               "a thread-mill needs pitch (a multi-form tool: the pitch of its teeth) or minPitch and maxPitch (a "
               "single-profile tool: the pitches it can cut)");
    for (std::string_view key : {"pitch", "minPitch", "maxPitch"})
        if (const std::optional<double> v = optional_length(key); v && !(*v > 0))
            f.fail(key, fmt::format("{} must be > 0", key));
    tool.min_pitch = pitch ? *pitch : *min;
    tool.max_pitch = pitch ? *pitch : *max;
    if (tool.min_pitch > tool.max_pitch)
        f.fail("maxPitch", fmt::format("maxPitch ({}) is less than minPitch ({})", show(tool.max_pitch), show(tool.min_pitch)));
}
}  // namespace

Tool JobInput::read_tool(const Json& value, const std::string& path) {
    Fields f(value, path, source_);
    known_keys(f, tool_keys);
    Tool tool;
    tool.path = path;
    tool.number = f.integer("number");
    if (tool.number < 1) f.fail("number", "a tool number must be 1 or more");
    if (auto it = header_.tools.find(tool.number); it != header_.tools.end())
        f.fail("number", fmt::format("tool number {} is already used by {}", tool.number, it->second.path));
    tool.type = f.choice("type", tool_types, ToolType::drill);
    tool.diameter = length(f, "diameter");
    if (tool.diameter <= 0) f.fail("diameter", "a tool diameter must be > 0");
    const bool pointed = tool.type == ToolType::chamfer_mill || tool.type == ToolType::v_bit;
    const std::string_view type_name = name_of(tool_types, tool.type);
    tool.tip_angle = f.optional_number("tipAngle");
    if (pointed) {
        // Engraving V-bits go down to 10 degrees, chamfer mills are 60 to 120.
        if (!tool.tip_angle) f.fail("tipAngle", fmt::format("a {} needs its tipAngle (the included angle of its point)", type_name));
        if (!(*tool.tip_angle > 0 && *tool.tip_angle < 180))
            f.fail("tipAngle", fmt::format("tipAngle {} degrees is not a {}'s point: it must be more than 0 and less than 180 "
                                           "degrees",
                                           *tool.tip_angle, type_name));
    } else if (tool.tip_angle && (*tool.tip_angle < 30 || *tool.tip_angle >= 180)) {
        // Drill points are 60 to 140 degrees (centre drills 60, spot drills 90 to 142); below 30 a
        // point is a needle whose tip length, added by drillTip, would be several diameters.
        f.fail("tipAngle", fmt::format("tipAngle {} degrees is not a drill point: it must be between 30 (inclusive) "
                                       "and 180 degrees (drills are 60 to 140)",
                                       *tool.tip_angle));
    }
    tool.corner_radius = optional_length(f, "cornerRadius");
    if (tool.type == ToolType::bull_nose) {
        if (!tool.corner_radius) f.fail("cornerRadius", "a bull-nose end mill needs its cornerRadius");
        if (!(*tool.corner_radius > 0 && *tool.corner_radius <= tool.diameter / 2 + 1e-9))
            f.fail("cornerRadius", fmt::format("cornerRadius {} must be more than 0 and at most half the diameter ({}); a "
                                               "corner radius of half the diameter is a ball-mill",
                                               show(*tool.corner_radius), show(tool.diameter / 2)));
    } else if (tool.corner_radius) {
        f.fail("cornerRadius", fmt::format("cornerRadius is for a bull-nose end mill, not a {} (a ball-mill's is half its "
                                           "diameter)",
                                           type_name));
    }
    if (auto tip = optional_length(f, "tipDiameter")) {
        if (!pointed)
            f.fail("tipDiameter", fmt::format("tipDiameter is for a chamfer-mill or v-bit, not a {}", type_name));
        if (!(*tip >= 0 && *tip < tool.diameter))
            f.fail("tipDiameter", fmt::format("tipDiameter {} must be at least 0 and less than the diameter ({})", show(*tip),
                                              show(tool.diameter)));
        tool.tip_diameter = *tip;
    }
    tool.flute_length = optional_length(f, "fluteLength");
    if (tool.flute_length && !(*tool.flute_length > 0)) f.fail("fluteLength", "fluteLength must be > 0");
    if (f.has("flutes")) {
        const int flutes = f.integer("flutes");
        if (flutes < 1 || flutes > 1000) f.fail("flutes", "flutes must be a whole number from 1 to 1000");
        tool.flutes = flutes;
    }
    job_input_thread_mill_pitches(*this, f, tool, type_name);
    tool.centre_cutting = f.has("centreCutting") ? f.boolean("centreCutting", false)
                                                  : tool.type != ToolType::end_mill && tool.type != ToolType::bull_nose &&
                                                        tool.type != ToolType::chamfer_mill && tool.type != ToolType::boring_bar &&
                                                        tool.type != ToolType::thread_mill;
    tool.rpm = f.number("rpm");
    if (tool.rpm <= 0) f.fail("rpm", "rpm must be > 0");
    tool.direction = f.choice("direction", spindle_directions, SpindleDirection::cw);
    tool.comment = f.optional_string("comment").value_or("");
    tool.coolant = f.choice("coolant", coolant_modes, CoolantMode::off);
    return tool;
}

const Tool& JobInput::tool(Fields& f) const {
    const int number = f.integer("tool");
    auto it = header_.tools.find(number);
    if (failed_tools_.contains(number) || (it == header_.tools.end() && unnumbered_tool_failed_)) {
        const std::string path = f.path_of("tool");
        throw FollowOnError(path, fmt::format("tool {} is not in /tools: it failed to read", number),
                            source_.lines.line_of(path), source_.name);
    }
    if (it == header_.tools.end()) f.fail("tool", fmt::format("tool {} is not in /tools", number));
    return it->second;
}

double JobInput::checked_length(double value, const std::string& path) const {
    double mm = value * scale_;
    if (std::abs(mm) > max_job_length)
        json::fail(source_, path, "a length or feed beyond 1,000,000 mm (or mm/min) is out of range");
    return mm;
}

std::optional<double> JobInput::optional_length(Fields& f, std::string_view key) const {
    auto v = f.optional_number(key);
    if (v) *v = checked_length(*v, f.path_of(key));
    return v;
}

std::optional<double> JobInput::optional_quantity(Fields& f, std::string_view key, Quantity quantity) const {
    return scales_with_units(quantity) ? optional_length(f, key) : f.optional_number(key);
}

double JobInput::coordinate(const Json& value, const std::string& path) const {
    return checked_length(json::number_at(value, path, source_), path);
}

Vec2 JobInput::point(const Json& value, const std::string& path) const {
    if (!value.is_array() || value.size() != 2)
        json::fail(source_, path, "expected a point [x, y], got " + describe(value));
    return {coordinate(value[0], path + "/0"), coordinate(value[1], path + "/1")};
}

Vec3 JobInput::point3(const Json& value, const std::string& path, double z) const {
    if (!value.is_array() || (value.size() != 2 && value.size() != 3))
        json::fail(source_, path, "expected a point [x, y] or [x, y, z], got " + describe(value));
    Vec3 p{coordinate(value[0], path + "/0"), coordinate(value[1], path + "/1"), z};
    if (value.size() == 3) p.z = coordinate(value[2], path + "/2");
    return p;
}

const JobInput::Json& JobInput::array(Fields& f, std::string_view key) const {
    const Json& value = f.required(key);
    if (const json::PackedArray* packed = doc_.packed_at(value)) const_cast<Json&>(value) = packed->to_json();
    if (!value.is_array()) f.fail(key, "expected an array, got " + describe(value));
    return value;
}

std::string JobInput::show(double mm) const {
    return scale_ == 1.0 ? fmt::format("{:.3f} mm", mm) : fmt::format("{:.4f} in", mm / scale_);
}

}  // namespace camgen
