#include "camgen/job/job_input.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"

namespace camgen {

namespace {

// A tool type's name with its article: "an end-mill", "a drill".
std::string job_input_with_article(std::string_view name) {
    const bool vowel = !name.empty() && std::string_view("aeiou").find(name.front()) != std::string_view::npos;
    return fmt::format("{} {}", vowel ? "an" : "a", name);
}


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
    {.key = "material", .type = JsonType::string,
     .description = "what the stock is made of (\"aluminium\", \"steel\", ...): the cutting data of library tools "
                    "for it give their rpm and feeds (default: none)"},
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
    {.key = "library", .type = JsonType::string,
     .description = "the name of a tool of the tool library (--tools, CAMGEN_TOOLS, ~/.config/camgen/tools): its keys "
                    "and cutting data, the keys given here overriding them"},
    {.key = "libraryNumber", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .description = "the number of a tool of the tool library (its number there), instead of its name; the job's own "
                    "number may differ"},
    {.key = "diameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "cutting diameter (required unless the tool comes from the library)"},
    {.key = "tipAngle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{180, false},
     .description = "included point angle: a drill's (30 or more; needed by drillTip), a chamfer mill's, V-bit's or "
                    "engraver's (required for them)"},
    {.key = "cornerRadius", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a bull-nose end mill's corner radius, at most half the diameter (required for bull-nose, refused "
                    "for other types)"},
    {.key = "tipDiameter", .quantity = Quantity::length, .min = Bound{0, true},
     .description = "a chamfer mill's, V-bit's or engraver's diameter at its point, less than diameter (default: 0, a sharp "
                    "point; refused for other types)"},
    {.key = "noseRadius", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a turning-tool's or threading-tool's nose radius (diameter may then be left out: it is twice the "
                    "nose radius, and must be if both are given; refused for other types)"},
    {.key = "orientation", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{9, true},
     .description = "a lathe tool's tip orientation, LinuxCNC's 1-9 code (the tool table's Q): where the programmed "
                    "point (the imaginary tip) lies on the nose circle, seen with +Z to the right and +X up: 1 "
                    "lower right, 2 lower left, 3 upper left, 4 upper right, 5 right, 6 below, 7 left, 8 above, 9 the "
                    "centre (default: 2 for a turning-tool, the outside tool cutting towards the chuck; none for the "
                    "others; refused for tools that are not lathe tools). A grooving or parting tool's says which way "
                    "its blade cuts and which corner is programmed: 2 (or none) and 1 outside (left, right corner), 3 and "
                    "4 inside a bore (left, right), 7 a face grooving blade (its inner corner)"},
    {.key = "insertAngle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{180, false},
     .description = "a turning-tool's insert: its included angle at the nose (80 C, 55 D, 35 V, 60 T, 90 S), with "
                    "approachAngle; together they say which slopes the insert can follow without rubbing (refused for "
                    "other types)"},
    {.key = "approachAngle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{180, false},
     .description = "a turning-tool's holder: the angle of the main cutting edge from the direction of feed along "
                    "the part (95 for a PCLNR-style holder, 93 for SVJBR), with insertAngle (refused for other types)"},
    {.key = "width", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a grooving-tool's or parting-tool's cutting width (required for them, refused for other types; "
                    "diameter may be left out: it is taken as the width)"},
    {.key = "profileAngle", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{180, false},
     .description = "a threading-tool's included profile angle: 60 for metric and unified threads, 55 for Whitworth "
                    "(required for it, refused for other types)"},
    {.key = "fluteLength", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "how deep the tool can cut; a hole deeper below its referencePlane is refused"},
    {.key = "flutes", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{max_tool_flutes, true},
     .description = "cutting edges: the feed computed from a feed per tooth is fz x flutes x rpm"},
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
    {.key = "rpm", .quantity = Quantity::speed, .min = Bound{0, false},
     .description = "spindle speed (also the tapping speed unless tappingSpeed is given); required unless the tool "
                    "comes from the library, which gives it or computes it from its cutting data for the job's material"},
    {.key = "surfaceSpeed", .min = Bound{0, false}, .max = Bound{10000, true},
     .description = "a turning-tool's, grooving-tool's or parting-tool's constant surface speed (G96) instead of rpm: "
                    "m/min at the work's diameter (ft/min when units is inch); the spindle turns at 1000 x "
                    "surfaceSpeed / (pi x diameter), at most maxRpm; its operations feed per revolution"},
    {.key = "maxRpm", .quantity = Quantity::speed, .min = Bound{0, false},
     .description = "the spindle's limit under surfaceSpeed (G50 S, G96 D, LIMS=), rpm (default: the machine's "
                    "limits.maxRpm; refused above it)"},
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
    std::vector<std::string> not_bull_nose, not_pointed, not_thread_mill, not_nosed, not_lathe, not_turning, not_grooving,
        not_threading, not_surface_speed;
    for (const auto& t : tool_types) {
        if (t.value != ToolType::turning_tool && t.value != ToolType::grooving_tool && t.value != ToolType::parting_tool)
            not_surface_speed.emplace_back(t.name);
        if (t.value != ToolType::bull_nose) not_bull_nose.emplace_back(t.name);
        if (!is_pointed_cutter(t.value)) not_pointed.emplace_back(t.name);
        if (t.value != ToolType::thread_mill) not_thread_mill.emplace_back(t.name);
        if (t.value != ToolType::turning_tool && t.value != ToolType::threading_tool) not_nosed.emplace_back(t.name);
        if (!is_lathe_insert(t.value)) not_lathe.emplace_back(t.name);
        if (t.value != ToolType::turning_tool) not_turning.emplace_back(t.name);
        if (t.value != ToolType::grooving_tool && t.value != ToolType::parting_tool) not_grooving.emplace_back(t.name);
        if (t.value != ToolType::threading_tool) not_threading.emplace_back(t.name);
    }
    return {
        {.name = "job", .description = "a camgen job: the tools, and the operations to run with them, in order",
         .keys = {std::begin(job_keys), std::end(job_keys)}},
        {.name = "tool", .description = "a tool of the job's tool table", .keys = {std::begin(tool_keys), std::end(tool_keys)},
         .groups = {{.keys = {"diameter", "library", "libraryNumber", "noseRadius", "width"}, .min = 1, .max = 5,
                     .description = "`diameter`, or `library` or `libraryNumber` (the library tool's), or a lathe tool's "
                                    "`noseRadius` or `width`"},
                    {.keys = {"rpm", "surfaceSpeed", "library", "libraryNumber"}, .min = 1, .max = 4,
                     .description = "`rpm` or a lathe tool's `surfaceSpeed`, or `library` or `libraryNumber` (the "
                                    "library tool's, or computed from its cutting data)"},
                    {.keys = {"rpm", "surfaceSpeed"}, .min = 0, .max = 1,
                     .description = "`rpm` or `surfaceSpeed`, not both"},
                    {.keys = {"library", "libraryNumber"}, .min = 0, .max = 1,
                     .description = "a library tool by `library` (its name) or by `libraryNumber`, not both"}},
         .rules = {{.when_key = "type", .values = {"bull-nose"}, .require = {"cornerRadius"}},
                   {.when_key = "type", .values = not_bull_nose, .forbid = {"cornerRadius"}},
                   {.when_key = "type", .values = {"chamfer-mill", "v-bit", "engraver"}, .require = {"tipAngle"}},
                   {.when_key = "type", .values = not_pointed, .forbid = {"tipDiameter"}},
                   {.when_key = "type", .values = not_thread_mill, .forbid = {"pitch", "minPitch", "maxPitch"}},
                   {.when_key = "type", .values = not_nosed, .forbid = {"noseRadius"}},
                   {.when_key = "type", .values = not_lathe, .forbid = {"orientation"}},
                   {.when_key = "type", .values = not_turning, .forbid = {"insertAngle", "approachAngle"}},
                   {.when_key = "type", .values = {"grooving-tool", "parting-tool"}, .require = {"width"}},
                   {.when_key = "type", .values = not_grooving, .forbid = {"width"}},
                   {.when_key = "type", .values = {"threading-tool"}, .require = {"profileAngle"}},
                   {.when_key = "type", .values = not_threading, .forbid = {"profileAngle"}},
                   {.when_key = "type", .values = not_surface_speed, .forbid = {"surfaceSpeed", "maxRpm"}}}},
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
    header_.material = top.optional_string("material").value_or("");
    if (top.has("material") && header_.material.empty()) top.fail("material", "material must not be empty");
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
        // The material too, which library tools are read by: an error of another header key
        // must not make every library tool's "give the job's material" as well.
        try {
            Fields again(doc_.root, "", source_);
            header_.material = again.optional_string("material").value_or("");
        } catch (const InputError&) {
        }
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
            // A tool naming a library that failed to read: the library's error is reported.
            const bool follow_on = dynamic_cast<const FollowOnError*>(&e) != nullptr;
            // An operation naming the number the tool says it has may have meant this tool.
            // When the number itself is the error (missing, not an integer, below 1, already
            // used), the tool may have been meant to have another: then any number the table
            // lacks may have meant it.
            const std::optional<std::int64_t> said = integer_member(value, "number");
            if (said) failed_tools_.insert(*said);
            if (!said || e.path() == path + "/number") unnumbered_tool_failed_ = true;
            if (!follow_on) report(e);
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
            if (f.has(key)) f.fail(key, fmt::format("{} is for a thread-mill, not {}", key, job_input_with_article(type_name)));
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
    const LibraryTool* entry = nullptr;
    if (f.has("library") && f.has("libraryNumber"))
        f.fail("libraryNumber", "give library (the library tool's name) or libraryNumber (its number), not both");
    if (auto name = f.optional_string("library")) entry = &library_tool(f, "library", *name, std::nullopt);
    else if (f.has("libraryNumber")) {
        const std::int64_t n = f.integer("libraryNumber");
        if (n < 1) f.fail("libraryNumber", "a library tool number must be 1 or more");
        entry = &library_tool(f, "libraryNumber", fmt::format("number {}", n), n);
    }
    read_tool_keys(f, tool, entry ? &entry->tool : nullptr, false);
    if (entry) {
        tool.library = entry->name;
        apply_cutting_data(f, tool, *entry, f.has("rpm"));
    }
    return tool;
}

Tool JobInput::read_library_tool(Fields& f) {
    known_keys(f, tool_keys);
    for (std::string_view job_only : {"library", "libraryNumber"})
        if (f.has(job_only))
            f.fail(job_only, fmt::format("{} is a key of a job's tool, not of a library tool", job_only));
    Tool tool;
    tool.path = f.path();
    read_tool_keys(f, tool, nullptr, true);
    return tool;
}

JobInput::Fields JobInput::read_library_units() {
    Fields top(doc_.root, "", source_);
    header_.units = top.choice("units", unit_names, Units::mm);
    scale_ = header_.units == Units::inch ? mm_per_inch : 1.0;
    return top;
}

void JobInput::read_tool_keys(Fields& f, Tool& tool, const Tool* base, bool library_tool) {
    // A key of the object, else the base's value (a library tool's).
    const auto from_base = [&](std::string_view key) { return base && !f.has(key); };
    tool.type = from_base("type") ? base->type : f.choice("type", tool_types, ToolType::drill);
    tool.type_given = from_base("type") ? base->type_given : f.has("type");
    const std::string_view type_name = name_of(tool_types, tool.type);
    const bool nosed = tool.type == ToolType::turning_tool || tool.type == ToolType::threading_tool;
    const bool grooving = tool.type == ToolType::grooving_tool || tool.type == ToolType::parting_tool;
    const std::optional<double> nose = optional_length(f, "noseRadius"), width = optional_length(f, "width");
    if (nose && !nosed)
        f.fail("noseRadius", fmt::format("noseRadius is for a turning-tool or threading-tool, not a {}", type_name));
    if (nose && !(*nose > 0)) f.fail("noseRadius", "noseRadius must be > 0");
    if (width && !grooving)
        f.fail("width", fmt::format("width is for a grooving-tool or parting-tool, not a {}", type_name));
    if (width && !(*width > 0)) f.fail("width", "width must be > 0");
    // A lathe tool's diameter is its nose's (turning, threading) or its width (grooving, parting)
    // where the job gives only those.
    if (from_base("diameter") && !nose && !width) tool.diameter = base->diameter;
    else if (!f.has("diameter") && nose) tool.diameter = 2.0 * *nose;
    else if (!f.has("diameter") && width) tool.diameter = *width;
    else tool.diameter = length(f, "diameter");
    if (tool.diameter <= 0) f.fail("diameter", "a tool diameter must be > 0");
    if (nose && std::abs(tool.diameter - 2.0 * *nose) > 1e-9)
        f.fail("noseRadius", fmt::format("noseRadius {} and diameter {} disagree: a {}'s diameter is twice its nose radius "
                                         "(give one of them)",
                                         show(*nose), show(tool.diameter), type_name));
    if (nosed) tool.nose_radius = tool.diameter / 2;
    if (grooving) {
        if (!width && !(base && base->type == tool.type && base->width > 0))
            f.fail("width", fmt::format("a {} needs its width (the cutting width of its blade)", type_name));
        tool.width = width ? *width : base && base->type == tool.type && base->width > 0 ? base->width : 0.0;
    }
    // The tip orientation: LinuxCNC's code (interp_queue.cc latheorigin_x/z: the imaginary tip
    // lies -X of the nose centre for 1, 2, 6; +X for 3, 4, 8; +Z for 1, 4, 5; -Z for 2, 3, 7).
    if (auto o = f.optional_integer("orientation")) {
        if (!is_lathe_insert(tool.type))
            f.fail("orientation", fmt::format("orientation is for a lathe tool (turning-tool, grooving-tool, parting-tool, "
                                              "threading-tool), not a {}",
                                              type_name));
        if (*o < 1 || *o > 9) f.fail("orientation", "orientation is a code from 1 to 9 (LinuxCNC's tool table Q)");
        tool.orientation = static_cast<int>(*o);
    } else if (base && base->type == tool.type && base->orientation) {
        tool.orientation = base->orientation;
    } else if (tool.type == ToolType::turning_tool) {
        tool.orientation = 2;
    }
    for (std::string_view key : {"insertAngle", "approachAngle"}) {
        if (!f.has(key)) continue;
        if (tool.type != ToolType::turning_tool)
            f.fail(key, fmt::format("{} is for a turning-tool, not a {}", key, type_name));
        const std::optional<double> angle = f.optional_number(key);
        if (!(*angle > 0 && *angle < 180))
            f.fail(key, fmt::format("{} {} degrees must be more than 0 and less than 180", key, *angle));
    }
    tool.insert_angle = f.has("insertAngle") ? f.optional_number("insertAngle")
                        : base && base->type == tool.type ? base->insert_angle : std::nullopt;
    tool.approach_angle = f.has("approachAngle") ? f.optional_number("approachAngle")
                          : base && base->type == tool.type ? base->approach_angle : std::nullopt;
    if (tool.type == ToolType::turning_tool && tool.insert_angle.has_value() != tool.approach_angle.has_value())
        f.fail(tool.insert_angle ? "approachAngle" : "insertAngle",
               "a turning-tool's insertAngle and approachAngle go together: the slopes it can follow need both");
    if (tool.insert_angle && *tool.approach_angle + *tool.insert_angle >= 180)
        f.fail("insertAngle", fmt::format("insertAngle {} plus approachAngle {} is 180 degrees or more: the insert's end "
                                          "edge would point into the finished diameter behind the tip",
                                          *tool.insert_angle, *tool.approach_angle));
    if (f.has("profileAngle") && tool.type != ToolType::threading_tool)
        f.fail("profileAngle", fmt::format("profileAngle is for a threading-tool, not a {}", type_name));
    tool.profile_angle = f.has("profileAngle") ? f.optional_number("profileAngle")
                         : base && base->type == tool.type ? base->profile_angle : std::nullopt;
    if (tool.profile_angle && !(*tool.profile_angle > 0 && *tool.profile_angle < 180))
        f.fail("profileAngle", fmt::format("profileAngle {} degrees must be more than 0 and less than 180", *tool.profile_angle));
    if (tool.type == ToolType::threading_tool && !tool.profile_angle)
        f.fail("profileAngle", "a threading-tool needs its profileAngle (60 for metric and unified threads)");
    const bool pointed = is_pointed_cutter(tool.type);
    tool.tip_angle = from_base("tipAngle") ? base->tip_angle : f.optional_number("tipAngle");
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
    tool.corner_radius = from_base("cornerRadius") ? base->corner_radius : optional_length(f, "cornerRadius");
    if (tool.type == ToolType::bull_nose) {
        if (!tool.corner_radius) f.fail("cornerRadius", "a bull-nose end mill needs its cornerRadius");
        if (!(*tool.corner_radius > 0 && *tool.corner_radius <= tool.diameter / 2 + 1e-9))
            f.fail("cornerRadius", fmt::format("cornerRadius {} must be more than 0 and at most half the diameter ({}); a "
                                               "corner radius of half the diameter is a ball-mill",
                                               show(*tool.corner_radius), show(tool.diameter / 2)));
    } else if (tool.corner_radius) {
        f.fail("cornerRadius", fmt::format("cornerRadius is for a bull-nose end mill, not {} (a ball-mill's is half its "
                                           "diameter)",
                                           job_input_with_article(type_name)));
    }
    std::optional<double> tip = from_base("tipDiameter") ? (base->tip_diameter > 0 ? std::optional<double>(base->tip_diameter)
                                                                                   : std::nullopt)
                                                         : optional_length(f, "tipDiameter");
    if (tip) {
        if (!pointed)
            f.fail("tipDiameter", fmt::format("tipDiameter is for a chamfer-mill, v-bit or engraver, not {}", job_input_with_article(type_name)));
        if (!(*tip >= 0 && *tip < tool.diameter))
            f.fail("tipDiameter", fmt::format("tipDiameter {} must be at least 0 and less than the diameter ({})", show(*tip),
                                              show(tool.diameter)));
        tool.tip_diameter = *tip;
    }
    tool.flute_length = from_base("fluteLength") ? base->flute_length : optional_length(f, "fluteLength");
    if (tool.flute_length && !(*tool.flute_length > 0)) f.fail("fluteLength", "fluteLength must be > 0");
    tool.flutes = from_base("flutes") ? base->flutes : f.optional_integer("flutes");
    if (tool.flutes && (*tool.flutes < 1 || *tool.flutes > max_tool_flutes))
        f.fail("flutes", fmt::format("flutes must be between 1 and {}", max_tool_flutes));
    if (base && tool.type == base->type && !f.has("pitch") && !f.has("minPitch") && !f.has("maxPitch")) {
        // A library thread mill's pitches, unless the job gives its own.
        tool.min_pitch = base->min_pitch;
        tool.max_pitch = base->max_pitch;
    } else {
        job_input_thread_mill_pitches(*this, f, tool, type_name);
    }
    // A library tool's own centreCutting (or its type's default) stays unless the job gives
    // either.
    tool.centre_cutting = f.has("centreCutting")                  ? f.boolean("centreCutting", false)
                          : from_base("centreCutting") && !f.has("type") ? base->centre_cutting
                                                                    : tool.type != ToolType::end_mill &&
                                                                          tool.type != ToolType::bull_nose &&
                                                                          tool.type != ToolType::chamfer_mill &&
                                                                          tool.type != ToolType::boring_bar &&
                                                                          tool.type != ToolType::thread_mill;
    // Constant surface speed (G96): a lathe tool that cuts at the work's diameter, not its own.
    const bool css_type = tool.type == ToolType::turning_tool || grooving;
    for (std::string_view key : {"surfaceSpeed", "maxRpm"})
        if (f.has(key) && !css_type)
            f.fail(key, fmt::format("{} is for a turning-tool, grooving-tool or parting-tool (constant surface speed, G96), "
                                    "not a {}{}",
                                    key, type_name,
                                    tool.type == ToolType::threading_tool ? ": a thread is cut at a constant rpm" : ""));
    if (f.has("surfaceSpeed") && f.has("rpm"))
        f.fail("surfaceSpeed", "give rpm (a constant spindle speed, G97) or surfaceSpeed (a constant surface speed, G96), "
                               "not both");
    if (auto vc = f.optional_number("surfaceSpeed")) {
        if (!(*vc > 0 && *vc <= 10000))
            f.fail("surfaceSpeed", fmt::format("surfaceSpeed {} must be more than 0 and at most 10000 m/min (ft/min when "
                                               "units is inch)",
                                               number_text(*vc)));
        tool.surface_speed = scale_ != 1.0 ? *vc * 0.3048 : *vc;
    } else if (base && !f.has("rpm") && base->type == tool.type) {
        tool.surface_speed = base->surface_speed;
    }
    if (auto limit = f.optional_number("maxRpm")) {
        if (!(*limit > 0)) f.fail("maxRpm", "maxRpm must be > 0");
        tool.max_rpm = *limit;
    } else if (base && !f.has("rpm") && base->type == tool.type) {
        tool.max_rpm = base->max_rpm;
    }
    // (Without rpm either, the missing rpm is the error, below.)
    if (f.has("maxRpm") && !(tool.surface_speed > 0) && (f.has("rpm") || library_tool || base))
        f.fail("maxRpm", "maxRpm is the spindle's limit under a constant surface speed: give surfaceSpeed too (with rpm "
                         "the spindle turns at that rpm)");
    if (tool.surface_speed > 0) {
        // The spindle's limit stands for the rpm: the operations' feeds per revolution are
        // carried as mm/min at it, and the post divides by it again.
        tool.rpm = 0.0;
        if (!library_tool) resolve_surface_speed_limit(f, tool);
    } else if (library_tool || base) {
        // A library tool may leave its rpm to its cutting data; a job's tool from the library
        // takes the library's (apply_cutting_data).
        tool.rpm = from_base("rpm") ? base->rpm : f.optional_number("rpm").value_or(0.0);
        if (f.has("rpm") && tool.rpm <= 0) f.fail("rpm", "rpm must be > 0");
    } else {
        tool.rpm = f.number("rpm");
        if (tool.rpm <= 0) f.fail("rpm", "rpm must be > 0");
    }
    tool.direction = from_base("direction") ? base->direction : f.choice("direction", spindle_directions, SpindleDirection::cw);
    tool.comment = from_base("comment") ? base->comment : f.optional_string("comment").value_or("");
    tool.coolant = from_base("coolant") ? base->coolant : f.choice("coolant", coolant_modes, CoolantMode::off);
}

void JobInput::resolve_surface_speed_limit(Fields& f, Tool& tool) const {
    const double machine_limit = library_options_.max_rpm;
    const std::string_view key = f.has("maxRpm") ? "maxRpm" : f.has("surfaceSpeed") ? "surfaceSpeed" : f.has("library") ? "library" : "libraryNumber";
    if (tool.max_rpm > 0 && machine_limit > 0 && tool.max_rpm > machine_limit)
        f.fail(key, fmt::format("maxRpm {} rpm is above the limit of machine {} ({} rpm)", number_text(tool.max_rpm),
                                library_options_.machine, number_text(machine_limit)));
    tool.rpm = tool.max_rpm > 0 ? tool.max_rpm : machine_limit;
    if (!(tool.rpm > 0))
        f.fail(key, "a surfaceSpeed needs the spindle's limit: give maxRpm (there is no machine here whose "
                    "limits.maxRpm it could be)");
}

std::span<const KeySpec> JobInput::tool_key_table() { return tool_keys; }

const LibraryTool& JobInput::library_tool(Fields& f, std::string_view key, const std::string& name,
                                          std::optional<std::int64_t> number) {
    if (!library_) {
        // A library that failed to read is reported once, with its file's own error (its file,
        // path and line); the other tools that name it follow from that error.
        if (library_failed_)
            throw FollowOnError(f.path_of(key), "the tool library failed to read", source_.lines.line_of(f.path_of(key)),
                                source_.name);
        try {
            library_ = load_tool_library(library_options_);
        } catch (const InputError&) {
            library_failed_ = true;
            throw;
        } catch (const IoError& e) {
            library_failed_ = true;
            f.fail(key, e.what());
        }
    }
    const std::string said = number ? name : fmt::format("\"{}\"", name);
    if (library_->tools.empty())
        f.fail(key, fmt::format("no tool library found for tool {}: looked in {} (give one with --tools, or set CAMGEN_TOOLS)",
                                said, fmt::join(library_->searched, ", ")));
    if (number) {
        if (const LibraryTool* entry = library_->find_number(*number)) return *entry;
        std::vector<std::string> numbered;
        for (const LibraryTool& t : library_->tools)
            if (t.number) numbered.push_back(fmt::format("{} ({})", *t.number, t.name));
        const std::size_t shown = 20;
        std::string listed = numbered.empty() ? std::string("none has a number") : std::string();
        for (std::size_t i = 0; i < numbered.size() && i < shown; ++i) listed += (i ? ", " : "") + numbered[i];
        if (numbered.size() > shown) listed += fmt::format(", ... ({} in all)", numbered.size());
        f.fail(key, fmt::format("no tool {} in the tool library ({}); its numbered tools: {}", said,
                                fmt::join(library_->files, ", "), listed));
    }
    if (const LibraryTool* entry = library_->find(name)) return *entry;
    std::vector<std::string> names;
    for (const LibraryTool& t : library_->tools) names.push_back(t.name);
    const auto hint = json::did_you_mean(name, names);
    // The closest few names by their start, beside the one did_you_mean finds.
    std::string listed;
    const std::size_t shown = 20;
    for (std::size_t i = 0; i < names.size() && i < shown; ++i) listed += (i ? ", " : "") + names[i];
    if (names.size() > shown) listed += fmt::format(", ... ({} in all)", names.size());
    f.fail(key, fmt::format("no tool {} in the tool library{} ({}); its tools: {}", said,
                            hint ? fmt::format(" (did you mean \"{}\"?)", *hint) : "", fmt::join(library_->files, ", "),
                            listed));
}

namespace {
// A material's name as compared: lower case.
std::string job_input_lower(std::string_view text) {
    std::string s(text);
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
}
}  // namespace

void JobInput::apply_cutting_data(Fields& f, Tool& tool, const LibraryTool& entry, bool rpm_given) {
    const std::string where = fmt::format("library tool \"{}\" ({} {})", entry.name, entry.file, entry.path);
    // The key the job's tool names the library tool by, which errors point at.
    const std::string_view key = f.has("libraryNumber") ? "libraryNumber" : "library";
    const CuttingData* data = nullptr;
    if (!entry.cutting.empty()) {
        std::vector<std::string> materials;
        for (const CuttingData& c : entry.cutting) materials.push_back(c.material);
        if (header_.material.empty() && doc_.root.is_object() && doc_.root.contains("material")) {
            // The job's material failed to read: its error is reported.
            throw FollowOnError(f.path_of(key), "the job's material failed to read",
                                source_.lines.line_of(f.path_of(key)), source_.name);
        } else if (header_.material.empty()) {
            if (tool.rpm <= 0)
                f.fail(key, fmt::format("{} has cutting data for {}: give the job's material (or this tool's rpm "
                                              "and the operations' feeds)",
                                              where, fmt::join(materials, ", ")));
        } else {
            for (const CuttingData& c : entry.cutting)
                if (job_input_lower(c.material) == job_input_lower(header_.material)) data = &c;
            if (!data) {
                const auto hint = json::did_you_mean(header_.material, materials);
                f.fail(key, fmt::format("{} has no cutting data for material \"{}\"{}; it has {}", where,
                                              header_.material, hint ? fmt::format(" (did you mean \"{}\"?)", *hint) : "",
                                              fmt::join(materials, ", ")));
            }
        }
    }
    if (data) {
        ToolCutting cut;
        cut.material = data->material;
        cut.surface_speed = data->surface_speed;
        cut.feed_per_tooth = data->feed_per_tooth;
        cut.feed_per_rev = data->feed_per_rev;
        if (!cut.feed_per_rev && cut.feed_per_tooth && tool.flutes) cut.feed_per_rev = *cut.feed_per_tooth * *tool.flutes;
        cut.max_feed = library_options_.max_feed;
        cut.path = where;
        if (cut.feed_per_tooth && !tool.flutes)
            f.fail(key, fmt::format("{} gives a feedPerTooth for {} but not its flutes: give flutes", where, cut.material));
        if (!rpm_given && tool.surface_speed == 0 && tool.type == ToolType::turning_tool) {
            // A turning tool cuts at the work's diameter, not its own: its surface speed is a
            // constant surface speed (G96), within the spindle's limit.
            tool.surface_speed = cut.surface_speed;
            resolve_surface_speed_limit(f, tool);
            tool.computed.push_back(fmt::format("constant surface speed {} m/min for {} (G96), at most {} rpm",
                                                number_text(cut.surface_speed), cut.material, number_text(tool.rpm)));
        } else if (!rpm_given && tool.surface_speed == 0) {
            const double wanted = rpm_for_surface_speed(cut.surface_speed, tool.diameter);
            tool.rpm = wanted;
            std::string text = fmt::format("{} rpm from vc {} m/min for {}", number_text(wanted),
                                           number_text(cut.surface_speed), cut.material);
            if (library_options_.max_rpm > 0 && wanted > library_options_.max_rpm) {
                tool.rpm = library_options_.max_rpm;
                text = fmt::format("{} rpm, the limit of machine {} (vc {} m/min for {} wants {} rpm)",
                                   number_text(tool.rpm), library_options_.machine, number_text(cut.surface_speed),
                                   cut.material, number_text(wanted));
            }
            tool.computed.push_back(text);
        }
        tool.cutting = std::move(cut);
    }
    if (tool.rpm <= 0)
        f.fail(key, fmt::format("{} gives no rpm and no cutting data: give this tool's rpm", where));
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
