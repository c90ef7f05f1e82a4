#include "camgen/vocabulary/vocabulary.hpp"

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

std::vector<std::string> drill_field_keys() {
    std::vector<std::string> out;
    for (const auto& f : drill_fields) out.emplace_back(f.key);
    return out;
}

}  // namespace camgen
