// The thread tables (sources in threads.hpp) and the reading of a designation.
#include "camgen/vocabulary/threads.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>

namespace camgen {

namespace {

// ISO 261, first and second choice, 1 to 64 mm: coarse pitch, then the fine pitches.
constexpr MetricThreadSize thread_metric_table[] = {
    {"M1", 1, 0.25, {0.2}},          {"M1.2", 1.2, 0.25, {0.2}},      {"M1.4", 1.4, 0.3, {0.2}},
    {"M1.6", 1.6, 0.35, {0.2}},      {"M1.8", 1.8, 0.35, {0.2}},      {"M2", 2, 0.4, {0.25}},
    {"M2.5", 2.5, 0.45, {0.35}},     {"M3", 3, 0.5, {0.35}},          {"M3.5", 3.5, 0.6, {0.35}},
    {"M4", 4, 0.7, {0.5}},           {"M5", 5, 0.8, {0.5}},           {"M6", 6, 1, {0.75}},
    {"M7", 7, 1, {0.75}},            {"M8", 8, 1.25, {1, 0.75}},      {"M10", 10, 1.5, {1.25, 1, 0.75}},
    {"M12", 12, 1.75, {1.5, 1.25, 1}}, {"M14", 14, 2, {1.5, 1.25, 1}}, {"M16", 16, 2, {1.5, 1}},
    {"M18", 18, 2.5, {2, 1.5, 1}},   {"M20", 20, 2.5, {2, 1.5, 1}},   {"M22", 22, 2.5, {2, 1.5, 1}},
    {"M24", 24, 3, {2, 1.5, 1}},     {"M27", 27, 3, {2, 1.5, 1}},     {"M30", 30, 3.5, {3, 2, 1.5, 1}},
    {"M33", 33, 3.5, {3, 2, 1.5}},   {"M36", 36, 4, {3, 2, 1.5}},     {"M39", 39, 4, {3, 2, 1.5}},
    {"M42", 42, 4.5, {4, 3, 2, 1.5}}, {"M45", 45, 4.5, {4, 3, 2, 1.5}}, {"M48", 48, 5, {4, 3, 2, 1.5}},
    {"M52", 52, 5, {4, 3, 2, 1.5}},  {"M56", 56, 5.5, {4, 3, 2, 1.5}}, {"M60", 60, 5.5, {4, 3, 2, 1.5}},
    {"M64", 64, 6, {4, 3, 2, 1.5}},
};

// ASME B1.1: basic major diameter (inch), UNC and UNF threads per inch.
constexpr UnifiedThreadSize thread_unified_table[] = {
    {"#0", 0.060, 0, 80},   {"#1", 0.073, 64, 72},  {"#2", 0.086, 56, 64},  {"#3", 0.099, 48, 56},
    {"#4", 0.112, 40, 48},  {"#5", 0.125, 40, 44},  {"#6", 0.138, 32, 40},  {"#8", 0.164, 32, 36},
    {"#10", 0.190, 24, 32}, {"#12", 0.216, 24, 28}, {"1/4", 0.25, 20, 28},  {"5/16", 0.3125, 18, 24},
    {"3/8", 0.375, 16, 24}, {"7/16", 0.4375, 14, 20}, {"1/2", 0.5, 13, 20}, {"9/16", 0.5625, 12, 18},
    {"5/8", 0.625, 11, 18}, {"3/4", 0.75, 10, 16},  {"7/8", 0.875, 9, 14},  {"1", 1.0, 8, 12},
};

constexpr double thread_mm_per_inch = 25.4;

std::string_view thread_trim(std::string_view s) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
    return s;
}

// A whole number or decimal (no sign, no exponent) making up all of `s`.
std::optional<double> thread_number(std::string_view s) {
    s = thread_trim(s);
    if (s.empty() || s.find_first_not_of("0123456789.") != std::string_view::npos) return std::nullopt;
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
    return v;
}

std::string thread_pitch_list(const MetricThreadSize& m) {
    std::string out = fmt::format("{:g} (coarse)", m.coarse);
    for (double p : m.fine)
        if (p > 0) out += fmt::format(", {:g}", p);
    return out;
}

std::optional<ThreadDesignation> thread_metric(std::string_view text, std::string& why) {
    std::string_view rest = text.substr(1);
    std::optional<double> pitch;
    if (const std::size_t x = rest.find_first_of("xX"); x != std::string_view::npos) {
        pitch = thread_number(rest.substr(x + 1));
        if (!pitch || !(*pitch > 0)) {
            why = fmt::format("\"{}\" has no pitch after the x (M10x1.25)", text);
            return std::nullopt;
        }
        rest = rest.substr(0, x);
    }
    const std::optional<double> size = thread_number(rest);
    if (!size) {
        why = fmt::format("\"{}\" is not a metric size such as M10 or M10x1.25", text);
        return std::nullopt;
    }
    for (const MetricThreadSize& m : thread_metric_table) {
        if (std::abs(m.major - *size) > 1e-9) continue;
        ThreadDesignation t{fmt::format("M{:g}x{:g}", m.major, pitch.value_or(m.coarse)), ThreadSeries::metric_coarse,
                            m.major, pitch.value_or(m.coarse)};
        if (!pitch || std::abs(*pitch - m.coarse) < 1e-9) return t;
        for (double p : m.fine)
            if (p > 0 && std::abs(*pitch - p) < 1e-9) {
                t.series = ThreadSeries::metric_fine;
                return t;
            }
        why = fmt::format("{} has no pitch {:g} in ISO 261: its pitches are {} (or give majorDiameter, minorDiameter and "
                          "pitch)",
                          m.name, *pitch, thread_pitch_list(m));
        return std::nullopt;
    }
    why = fmt::format("M{:g} is not an ISO 261 size (M1 to M64; or give majorDiameter, minorDiameter and pitch)", *size);
    return std::nullopt;
}

std::optional<ThreadDesignation> thread_unified(std::string_view text, std::string& why) {
    std::string_view body = text;
    std::optional<ThreadSeries> series;
    for (auto [suffix, s] : {std::pair{std::string_view("UNC"), ThreadSeries::unc}, {std::string_view("UNF"), ThreadSeries::unf}})
        if (body.size() >= 3 && body.substr(body.size() - 3) == suffix) {
            series = s;
            body = thread_trim(body.substr(0, body.size() - 3));
        }
    const std::size_t dash = body.rfind('-');
    const std::optional<double> tpi = dash == std::string_view::npos ? std::nullopt : thread_number(body.substr(dash + 1));
    if (!tpi || *tpi != std::floor(*tpi) || *tpi < 1) {
        why = fmt::format("\"{}\" is neither a metric size (M10, M10x1.25) nor a Unified one (1/4-20 UNC, #10-32 UNF)", text);
        return std::nullopt;
    }
    const std::string_view size = thread_trim(body.substr(0, dash));
    for (const UnifiedThreadSize& u : thread_unified_table) {
        if (u.name != size) continue;
        const int n = static_cast<int>(*tpi);
        const bool unc = n == u.unc_tpi, unf = n == u.unf_tpi;
        if ((!unc && !unf) || (series == ThreadSeries::unc && !unc) || (series == ThreadSeries::unf && !unf)) {
            std::string has;
            if (u.unc_tpi) has = fmt::format("{}-{} UNC", u.name, u.unc_tpi);
            if (u.unf_tpi) has += fmt::format("{}{}-{} UNF", has.empty() ? "" : " and ", u.name, u.unf_tpi);
            why = fmt::format("\"{}\" is not in ASME B1.1's UNC and UNF series: {} has {}", text, u.name, has);
            return std::nullopt;
        }
        const ThreadSeries s = unc ? ThreadSeries::unc : ThreadSeries::unf;
        return ThreadDesignation{fmt::format("{}-{} {}", u.name, n, s == ThreadSeries::unc ? "UNC" : "UNF"), s,
                                 u.major_inch * thread_mm_per_inch, thread_mm_per_inch / n};
    }
    why = fmt::format("\"{}\" is not a Unified size of the table (#0 to #12, 1/4 to 1 inch)", size);
    return std::nullopt;
}

}  // namespace

std::span<const MetricThreadSize> metric_thread_sizes() { return thread_metric_table; }
std::span<const UnifiedThreadSize> unified_thread_sizes() { return thread_unified_table; }

std::optional<ThreadDesignation> find_thread(std::string_view designation, std::string& why) {
    const std::string_view text = thread_trim(designation);
    if (text.empty()) {
        why = "the thread designation is empty";
        return std::nullopt;
    }
    if (text.front() == 'M' || text.front() == 'm') return thread_metric(text, why);
    return thread_unified(text, why);
}

}  // namespace camgen
