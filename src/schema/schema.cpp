#include "camgen/schema/schema.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <variant>

#include <fmt/format.h>

#include "camgen/common/key_spec.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/stock.hpp"

namespace camgen {

namespace {

using OJson = nlohmann::ordered_json;

constexpr std::string_view draft = "https://json-schema.org/draft/2020-12/schema";
constexpr std::string_view id_base = "https://camgen.example/schema/";

// Which file a schema is for: job lengths and feeds follow the job's units, a machine's are mm.
enum class SchemaKind { job, machine };

// A bound as JSON: whole numbers as integers (0, not 0.0).
OJson number_json(double v) {
    if (v == std::floor(v) && std::abs(v) < 1e15) return static_cast<std::int64_t>(v);
    return v;
}

// "mm", "mm/min; in/min when units is inch", ... ("" for quantities without a unit).
std::string unit_note(Quantity q, SchemaKind file) {
    const std::string_view unit = unit_of(q);
    if (unit.empty()) return "";
    if (file == SchemaKind::job && scales_with_units(q))
        return fmt::format("{}; {} when units is inch", unit, q == Quantity::feed ? "in/min" : "in");
    return std::string(unit);
}

// The JSON Schema type name of a plain JSON type.
std::string_view type_name(JsonType t) {
    switch (t) {
        case JsonType::number: return "number";
        case JsonType::integer: return "integer";
        case JsonType::string: return "string";
        case JsonType::boolean: return "boolean";
        case JsonType::object: return "object";
        case JsonType::array:
        case JsonType::point:
        case JsonType::point3: return "array";
    }
    return "null";
}

// A point: [x, y], or for point3 also [x, y, z].
OJson point_schema(JsonType t) {
    OJson s;
    s["type"] = "array";
    s["items"] = OJson{{"type", "number"}};
    s["minItems"] = 2;
    s["maxItems"] = t == JsonType::point3 ? 3 : 2;
    return s;
}

// A reference to the object named `name` in $defs.
OJson ref_to(std::string_view name) { return OJson{{"$ref", fmt::format("#/$defs/{}", name)}}; }

// The choices as a JSON array.
OJson enum_of(Choices choices) {
    OJson e = OJson::array();
    for (const auto& c : choices()) e.push_back(c);
    return e;
}

// The schema of one key's value.
OJson value_schema(const KeySpec& k, SchemaKind file) {
    OJson s;
    switch (k.type) {
        case JsonType::point:
        case JsonType::point3: s = point_schema(k.type); break;
        case JsonType::object:
            if (!k.ref.empty()) s = ref_to(k.ref);
            else s["type"] = "object";
            break;
        case JsonType::array: {
            s["type"] = "array";
            if (!k.ref.empty()) s["items"] = ref_to(k.ref);
            else if (k.choices) s["items"] = OJson{{"type", "string"}, {"enum", enum_of(k.choices)}};
            else if (k.items) s["items"] = OJson{{"type", type_name(*k.items)}};
            if (k.min_items > 0) s["minItems"] = k.min_items;
            break;
        }
        default: s["type"] = type_name(k.type); break;
    }
    if (k.type == JsonType::string && k.choices) s["enum"] = enum_of(k.choices);
    if (k.or_boolean) {
        s["type"] = OJson::array({"string", "boolean"});
        if (s.contains("enum")) {
            s["enum"].push_back(true);
            s["enum"].push_back(false);
        }
    }
    if (k.min) s[k.min->inclusive ? "minimum" : "exclusiveMinimum"] = number_json(k.min->value);
    if (k.max) s[k.max->inclusive ? "maximum" : "exclusiveMaximum"] = number_json(k.max->value);
    if (!k.default_json.empty()) s["default"] = OJson::parse(k.default_json);
    const std::string unit = unit_note(k.quantity, file);
    s["description"] = unit.empty() ? std::string(k.description) : fmt::format("{} ({})", k.description, unit);
    return s;
}

// A key group: at least one of all the keys (anyOf), or exactly the allowed counts (oneOf of
// the subsets that may be given, each refusing the other keys).
OJson group_schema(const KeyGroup& g) {
    OJson s;
    if (!g.description.empty()) s["description"] = g.description;
    if (g.min == 1 && g.max >= g.keys.size()) {
        OJson any = OJson::array();
        for (auto key : g.keys) any.push_back(OJson{{"required", OJson::array({key})}});
        s["anyOf"] = any;
        return s;
    }
    OJson one = OJson::array();
    const std::size_t n = g.keys.size();
    // A group that may be left out (min 0) takes the subset of none as well.
    for (std::size_t mask = g.min == 0 ? 0 : 1; mask < (std::size_t{1} << n); ++mask) {
        OJson required = OJson::array(), absent = OJson::object();
        for (std::size_t i = 0; i < n; ++i) {
            if (mask & (std::size_t{1} << i)) required.push_back(g.keys[i]);
            else absent[std::string(g.keys[i])] = false;
        }
        if (required.size() < g.min || required.size() > g.max) continue;
        one.push_back(OJson{{"required", required}, {"properties", absent}});
    }
    s["oneOf"] = one;
    return s;
}

// A rule as if/then. An absent choice counts as its default: the "if" needs the key only when
// the default is not one of the rule's values.
OJson rule_schema(const ObjectSpec& spec, const KeyRule& r) {
    OJson condition;
    condition["properties"][std::string(r.when_key)]["enum"] = r.values;
    bool default_matches = false;
    for (const auto& k : spec.keys) {
        if (k.key != r.when_key || k.default_json.empty()) continue;
        const OJson d = OJson::parse(k.default_json);
        for (const auto& v : r.values) default_matches = default_matches || (d.is_string() && d.get<std::string>() == v);
    }
    if (!default_matches) condition["required"] = OJson::array({r.when_key});
    OJson then;
    if (!r.require.empty()) then["required"] = r.require;
    for (auto key : r.forbid) then["properties"][std::string(key)] = false;
    return OJson{{"if", condition}, {"then", then}};
}

// The schema of an object: its keys (and no others), the required ones, its groups and rules.
OJson object_schema(const ObjectSpec& spec, SchemaKind file) {
    OJson s;
    s["type"] = "object";
    s["description"] = spec.description;
    OJson properties = OJson::object();
    OJson required = OJson::array();
    for (const auto& k : spec.keys) {
        properties[std::string(k.key)] = value_schema(k, file);
        if (k.required) required.push_back(k.key);
    }
    s["properties"] = properties;
    if (!required.empty()) s["required"] = required;
    s["additionalProperties"] = false;
    OJson all = OJson::array();
    for (const auto& g : spec.groups) all.push_back(group_schema(g));
    for (const auto& r : spec.rules)
        if (!r.require.empty() || !r.forbid.empty()) all.push_back(rule_schema(spec, r));
    if (!all.empty()) s["allOf"] = all;
    if (!spec.also_point) return s;
    OJson either;
    either["description"] = spec.description;
    either["anyOf"] = OJson::array({point_schema(JsonType::point), s});
    return either;
}

// A whole schema: the header, the first object at the top level and the others in $defs.
OJson file_schema(std::string_view name, std::string_view title, const std::vector<ObjectSpec>& objects,
                  const OJson& extra_defs, SchemaKind file) {
    OJson s;
    s["$schema"] = draft;
    s["$id"] = fmt::format("{}{}.schema.json", id_base, name);
    s["title"] = title;
    const OJson top = object_schema(objects.front(), file);
    for (const auto& [key, value] : top.items()) s[key] = value;
    OJson defs = OJson::object();
    for (std::size_t i = 1; i < objects.size(); ++i) defs[std::string(objects[i].name)] = object_schema(objects[i], file);
    for (const auto& [key, value] : extra_defs.items()) defs[key] = value;
    s["$defs"] = defs;
    return s;
}

// The "operation" object, and the objects of every operation type (iterating the Operation
// variant): an operation's "type" decides which object checks it.
OJson operation_defs() {
    OJson dispatch = OJson::array(), defs = OJson::object();
    [&]<std::size_t... I>(std::index_sequence<I...>) {
        (
            [&] {
                using Op = std::variant_alternative_t<I, Operation>;
                const std::vector<ObjectSpec> objects = Op::objects();
                if (objects.empty() || objects.front().name != Op::type)
                    throw std::logic_error("an operation's first object must be named by its type");
                for (const auto& spec : objects) {
                    OJson o = object_schema(spec, SchemaKind::job);
                    if (spec.name == Op::type)
                        o["properties"]["type"] = OJson{{"const", Op::type}, {"description", "the kind of operation"}};
                    defs[std::string(spec.name)] = o;
                }
                OJson condition;
                condition["properties"]["type"]["const"] = Op::type;
                dispatch.push_back(OJson{{"if", condition}, {"then", ref_to(Op::type)}});
            }(),
            ...);
    }(std::make_index_sequence<std::variant_size_v<Operation>>());
    OJson operation;
    operation["type"] = "object";
    operation["description"] = "an operation; its type decides its other keys";
    operation["properties"]["type"] = OJson{{"enum", operation_type_names()}, {"description", "the kind of operation"}};
    operation["required"] = OJson::array({"type"});
    operation["allOf"] = dispatch;
    OJson all;
    all["operation"] = operation;
    for (const auto& [key, value] : defs.items()) all[key] = value;
    return all;
}

// Every operation type's objects, in registration order (each type's own object first).
std::vector<ObjectSpec> operation_objects() {
    std::vector<ObjectSpec> out;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
        (
            [&] {
                const std::vector<ObjectSpec> objects = std::variant_alternative_t<I, Operation>::objects();
                out.insert(out.end(), objects.begin(), objects.end());
            }(),
            ...);
    }(std::make_index_sequence<std::variant_size_v<Operation>>());
    return out;
}

// The value column of a key: its type, quantity, unit, bounds, choices or object.
std::string value_text(const KeySpec& k) {
    const auto bounded = [&](std::string s) {
        if (k.min) s += (k.min->inclusive ? " >= " : " > ") + fmt::format("{}", k.min->value);
        if (k.max) s += std::string(k.min ? "," : "") + (k.max->inclusive ? " <= " : " < ") + fmt::format("{}", k.max->value);
        return s;
    };
    switch (k.type) {
        case JsonType::point: return "`[x, y]`";
        case JsonType::point3: return "`[x, y]` or `[x, y, z]`";
        case JsonType::boolean: return "boolean";
        case JsonType::integer: return bounded("integer");
        case JsonType::object: return k.ref.empty() ? "object" : fmt::format("`{}` object", k.ref);
        case JsonType::array:
            if (k.ref.empty()) return "array";
            return k.min_items > 0 ? fmt::format("array of `{}`, at least {}", k.ref, k.min_items)
                                   : fmt::format("array of `{}`", k.ref);
        case JsonType::string: {
            if (!k.choices) return "string";
            std::string s;
            for (const auto& c : k.choices()) s += (s.empty() ? "`\"" : ", `\"") + c + "\"`";
            return k.or_boolean ? s + ", `true`, `false`" : s;
        }
        case JsonType::number: break;
    }
    return k.quantity == Quantity::choice ? bounded("number") : quantity_text(k.quantity, k.min, k.max);
}

}  // namespace

std::optional<std::string> keys_markdown(std::string_view name) {
    std::vector<ObjectSpec> objects = operation_objects();
    for (ObjectSpec& o : stock_objects()) objects.push_back(std::move(o));
    for (ObjectSpec& o : machine_objects()) objects.push_back(std::move(o));
    for (ObjectSpec& o : tool_library_objects()) objects.push_back(std::move(o));
    for (const ObjectSpec& spec : objects) {
        if (spec.name != name) continue;
        std::string s = "| key | value | default | meaning |\n| --- | --- | --- | --- |\n";
        for (const KeySpec& k : spec.keys) {
            // A default that is no constant is in the description ("(default: the tool's radius)").
            const bool described = k.description.find("(default:") != std::string_view::npos;
            const std::string def = k.required              ? "**required**"
                                    : !k.default_json.empty() ? fmt::format("`{}`", k.default_json)
                                    : described               ? "see meaning"
                                                              : "none";
            s += fmt::format("| `{}` | {} | {} | {} |\n", k.key, value_text(k), def, k.description);
        }
        for (const KeyGroup& g : spec.groups) s += fmt::format("\nOf these: {}.\n", g.description);
        return s;
    }
    return std::nullopt;
}

OJson job_schema() {
    std::vector<ObjectSpec> objects = JobInput::objects();
    for (ObjectSpec& o : stock_objects()) objects.push_back(std::move(o));
    return file_schema("job", "camgen job", objects, operation_defs(), SchemaKind::job);
}

OJson machine_schema() {
    const std::vector<ObjectSpec> objects = machine_objects();
    OJson s = file_schema("machine", "camgen machine", objects, OJson::object(), SchemaKind::machine);
    // A file that names its dialect: its settings are that dialect's (settings-<dialect>).
    constexpr std::string_view prefix = "settings-";
    for (const ObjectSpec& o : objects) {
        if (!o.name.starts_with(prefix)) continue;
        OJson condition;
        condition["properties"]["dialect"]["const"] = o.name.substr(prefix.size());
        condition["required"] = OJson::array({"dialect"});
        OJson then;
        then["properties"]["settings"] = ref_to(o.name);
        s["allOf"].push_back(OJson{{"if", condition}, {"then", then}});
    }
    return s;
}

OJson tools_schema() {
    // A library's lengths follow its units, as a job's do.
    return file_schema("tools", "camgen tool library", tool_library_objects(), OJson::object(), SchemaKind::job);
}

std::vector<std::string> schema_names() { return {"job", "machine", "tools"}; }

std::optional<std::string> schema_text(std::string_view name) {
    if (name == "job") return job_schema().dump(2) + "\n";
    if (name == "machine") return machine_schema().dump(2) + "\n";
    if (name == "tools") return tools_schema().dump(2) + "\n";
    return std::nullopt;
}

}  // namespace camgen
