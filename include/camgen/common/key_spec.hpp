#pragma once
// The keys of one JSON object of a job or machine file, declared once as a table: the reader
// takes its known-key list from the table, and the JSON Schema (src/schema/) is generated from
// it. Depends on nothing of camgen but the vocabulary.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen {

// The JSON type of a value. A point is an array [x, y]; a point3 is [x, y] or [x, y, z].
enum class JsonType { number, integer, string, boolean, array, object, point, point3 };

// The strings a choice takes (or the items of an array of choices).
using Choices = std::vector<std::string> (*)();

// The names of a vocabulary table, as a Choices function: choices_of<cycle_kinds>.
template <const auto& Table>
std::vector<std::string> choices_of() {
    return names_of(Table);
}

// One key of an object: its type, what it measures, its bounds, its default and a line of
// description. Quantities with a unit get the unit appended in the schema's description.
struct KeySpec {
    std::string_view key;
    JsonType type = JsonType::number;
    Quantity quantity = Quantity::choice;
    bool required = false;
    std::optional<Bound> min = std::nullopt;      // numbers; integers use the value as is
    std::optional<Bound> max = std::nullopt;
    std::string_view default_json = {};           // the default as JSON text ("" : none, or not a constant)
    Choices choices = nullptr;                    // a string's values, or an array's items'
    std::string_view ref = {};                    // the object (or array item) it holds, by ObjectSpec name
    std::optional<JsonType> items = std::nullopt; // an array's item type (when no ref or choices)
    std::size_t min_items = 0;                    // arrays
    std::string_view description = {};
    bool or_boolean = false;                      // a string of choices that also takes true or false
};

// How many of `keys` an object must have: at least `min`, at most `max`.
struct KeyGroup {
    std::vector<std::string_view> keys;
    std::size_t min = 1;
    std::size_t max = 1;
    std::string_view description = {};
};

// Keys that depend on a choice: when `when_key` has one of `values` (an absent key counts as
// its default), the keys `require` are needed and the keys `forbid` refused.
struct KeyRule {
    std::string_view when_key;
    std::vector<std::string> values;
    std::vector<std::string_view> require;
    std::vector<std::string_view> forbid;
};

// One object of a file: its name (the schema's $defs name), its keys and the rules between
// them. `also_point`: the object may be given as a point [x, y] instead.
struct ObjectSpec {
    std::string_view name;
    std::string_view description;
    std::vector<KeySpec> keys;
    std::vector<KeyGroup> groups = {};
    std::vector<KeyRule> rules = {};
    bool also_point = false;
};

// The keys of a table, in order.
inline std::vector<std::string_view> keys_of(std::span<const KeySpec> table) {
    std::vector<std::string_view> out;
    out.reserve(table.size());
    for (const auto& k : table) out.push_back(k.key);
    return out;
}

}  // namespace camgen
