#include "camgen/vocabulary/vocabulary.hpp"

#include <cstdio>

namespace camgen {

namespace {
constexpr bool rows_in_enum_order() {
    for (std::size_t i = 0; i < drill_fields.size(); ++i)
        if (static_cast<std::size_t>(drill_fields[i].field) != i) return false;
    return true;
}
static_assert(rows_in_enum_order(), "drill_fields rows must follow the DrillField enum");
}  // namespace

std::string_view unit_of(Quantity quantity) {
    switch (quantity) {
        case Quantity::length: return "mm";
        case Quantity::feed: return "mm/min";
        case Quantity::time: return "s";
        case Quantity::speed: return "rpm";
        case Quantity::angle: return "degrees";
        case Quantity::factor:
        case Quantity::count:
        case Quantity::choice: return "";
    }
    return "";
}

std::optional<DrillField> drill_field_named(std::string_view key) {
    for (const auto& f : drill_fields)
        if (f.key == key) return f.field;
    return std::nullopt;
}

const TurnDrillFieldInfo* turn_field_of(DrillField f) {
    for (const auto& t : turn_drill_fields)
        if (t.field == f) return &t;
    return nullptr;
}

std::optional<DrillField> turn_drill_field_named(std::string_view key) {
    for (const auto& t : turn_drill_fields)
        if (t.key == key) return t.field;
    return std::nullopt;
}

std::vector<std::string> turn_drill_field_keys() {
    std::vector<std::string> out;
    for (const auto& t : turn_drill_fields) out.emplace_back(t.key);
    return out;
}

std::vector<std::string> drill_field_keys() {
    std::vector<std::string> out;
    for (const auto& f : drill_fields) out.emplace_back(f.key);
    return out;
}

namespace {

// A number as the docs write it: "0", "1", "0.5".
std::string bound_text(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", v);
    return buffer;
}

// The value column of a field: quantity, unit and bound ("length (mm) > 0").
std::string value_text(const DrillFieldInfo& f) {
    if (f.field == DrillField::degression_type) {
        std::string s;
        for (const auto& n : degression_types) s += (s.empty() ? "`\"" : ", `\"") + std::string(n.name) + "\"`";
        return s;
    }
    if (f.field == DrillField::degression) return "length (mm) or factor";
    return quantity_text(f.quantity, f.min);
}

// The kinds of a set, by name, joined with ", "; "every cycle" for all of them.
std::string kinds_text(CycleSet set) {
    bool all = true;
    std::string s;
    for (const auto& n : cycle_kinds) {
        if (!set.contains(n.value)) {
            all = false;
            continue;
        }
        s += (s.empty() ? "" : ", ") + std::string(n.name);
    }
    return all ? "every cycle" : s;
}

}  // namespace

std::string quantity_text(Quantity quantity, std::optional<Bound> min, std::optional<Bound> max) {
    static constexpr const char* names[] = {"length", "feed", "time", "speed", "factor", "angle", "count", "choice"};
    std::string s = names[static_cast<int>(quantity)];
    if (!unit_of(quantity).empty()) s += " (" + std::string(unit_of(quantity)) + ")";
    if (min) s += (min->inclusive ? " >= " : " > ") + bound_text(min->value);
    if (max) s += std::string(min ? "," : "") + (max->inclusive ? " <= " : " < ") + bound_text(max->value);
    return s;
}

std::string drill_fields_markdown() {
    std::string s = "| key | value | used by | meaning |\n| --- | --- | --- | --- |\n";
    for (const auto& f : drill_fields) {
        std::string used = kinds_text(f.used_by);
        if (!f.required_by.empty()) used += "; **required** by " + kinds_text(f.required_by);
        s += "| `" + std::string(f.key) + "` | " + value_text(f) + " | " + used + " | " + std::string(f.description) + " |\n";
    }
    return s;
}

std::string cycle_kinds_markdown() {
    std::string s = "| `cycle` | what it does | fields it uses (**required**) |\n| --- | --- | --- |\n";
    for (const auto& k : cycle_kinds) {
        std::string fields;
        for (const auto& f : drill_fields) {
            if (f.in_planes || !f.used_by.contains(k.value)) continue;
            const std::string key(f.key);
            fields += (fields.empty() ? "" : ", ") + (f.required_by.contains(k.value) ? "**" + key + "**" : key);
        }
        s += "| `" + std::string(k.name) + "` | " + std::string(k.description) + " | " + fields + " |\n";
    }
    return s;
}

}  // namespace camgen
