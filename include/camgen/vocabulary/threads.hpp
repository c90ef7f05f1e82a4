#pragma once
// Screw thread tables: ISO metric (coarse and fine pitches) and Unified inch (UNC, UNF)
// nominal sizes, and the diameters of the 60-degree basic profile they share.
//
// Sources: ISO 261 (ISO general-purpose metric screw threads, general plan: the nominal
// diameters 1 to 64 mm of its first and second choice with their coarse and fine pitches),
// ISO 68-1 (the basic profile: fundamental triangle H = 0.866025 P, internal minor diameter
// D1 = D - 1.082532 P, external minor diameter d3 = d - 1.226869 P, the last with the root
// rounded to H/6, as in ISO 965-1), ASME B1.1 (Unified inch screw threads: basic major
// diameters and threads per inch of the UNC and UNF series, numbered sizes #0 to #12 and
// fractional sizes 1/4 to 1 inch). camgen's REFERENCE notes (section 10) hold the same coarse
// pitches and formulas.
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace camgen {

// The series a thread of the tables belongs to.
enum class ThreadSeries { metric_coarse, metric_fine, unc, unf };

// One ISO 261 nominal size: its major diameter (mm), coarse pitch and fine pitches (mm, 0: none).
struct MetricThreadSize {
    std::string_view name;     // "M10"
    double major = 0.0;        // mm
    double coarse = 0.0;       // mm
    double fine[4] = {};       // mm, coarsest first; 0 ends the list
};

// One ASME B1.1 size: its basic major diameter (inch) and threads per inch (0: no such series).
struct UnifiedThreadSize {
    std::string_view name;     // "1/4", "#10"
    double major_inch = 0.0;
    int unc_tpi = 0;
    int unf_tpi = 0;
};

// The tables themselves (see the sources above).
std::span<const MetricThreadSize> metric_thread_sizes();
std::span<const UnifiedThreadSize> unified_thread_sizes();

// A thread of the tables: its designation as camgen writes it, series, major diameter and pitch.
struct ThreadDesignation {
    std::string name;          // "M10x1.5", "1/4-20 UNC"
    ThreadSeries series = ThreadSeries::metric_coarse;
    double major = 0.0;        // mm: D of an internal, d of an external thread
    double pitch = 0.0;        // mm
};

// The fundamental triangle's height H of a 60-degree thread of pitch P (mm).
constexpr double thread_triangle_height(double pitch) { return 0.8660254037844386 * pitch; }
// The basic minor diameter D1 of an internal thread: D - 5/4 H (ISO 68-1).
constexpr double internal_minor_diameter(double major, double pitch) { return major - 1.25 * thread_triangle_height(pitch); }
// The minor diameter d3 of an external thread, its root rounded to H/6: d - 17/12 H (ISO 965-1).
constexpr double external_minor_diameter(double major, double pitch) {
    return major - 17.0 / 12.0 * thread_triangle_height(pitch);
}

// Looks a designation up: "M10" (the coarse pitch), "M10x1.25" (a coarse or fine pitch of
// the size), "1/4-20 UNC", "#10-32 UNF", "1/4-28" (the series from the threads per inch).
// Not found: nullopt and `why` says what the tables hold for it.
std::optional<ThreadDesignation> find_thread(std::string_view designation, std::string& why);

}  // namespace camgen
