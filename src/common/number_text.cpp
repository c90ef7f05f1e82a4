#include "camgen/common/number_text.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace camgen {

std::string number_text(double value, int decimals) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    int places = decimals;
    // A small value keeps two significant digits (where the last decimals would hold less).
    if (value != 0.0 && std::abs(value) < std::pow(10.0, 1 - decimals))
        places = std::clamp(1 - static_cast<int>(std::floor(std::log10(std::abs(value)))), decimals, 12);
    std::string s = fmt::format("{:.{}f}", value, places);
    if (s.find('.') != std::string::npos) {
        while (s.back() == '0') s.pop_back();
        if (s.back() == '.') s.pop_back();
    }
    if (s == "-0") s = "0";
    return s;
}

}  // namespace camgen
