#pragma once
// Text for the HTML pages camgen writes (the backplot, the simulation): markup escaped, JSON
// that can stand inside a <script> element.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace camgen {

// The five characters that could open or close markup or an attribute, as references.
std::string html_text(std::string_view s);

// A JSON value as text inside a <script> element: ASCII only (bytes that are no UTF-8 become
// U+FFFD), and '<', '>', '&' as \u escapes, so that no "</script>" or "<!--" can appear in it.
// Those three occur in JSON only inside strings, so replacing them is safe.
std::string script_json(const nlohmann::json& value);

}  // namespace camgen
