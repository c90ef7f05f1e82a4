#pragma once
// The Heidenhain TNC drilling cycles as the post writes them and the reader reads them back:
// each cycle's number, title and Q parameters in the order written, with the comment after
// each, and the special values of Q213 and Q208. Q200 (set-up clearance), Q201 (depth) and
// Q204 (2nd set-up clearance) count from the surface Q203.
#include <span>
#include <string_view>

namespace camgen::heidenhain {

// The Q parameters of the drilling cycles, by number.
enum class Q : int {
    setup_clearance = 200,
    depth = 201,             // negative: below the surface
    plunging_depth = 202,
    surface = 203,
    second_setup_clearance = 204,
    min_plunging_depth = 205,
    plunge_feed = 206,
    retraction_feed = 208,
    top_dwell = 210,
    bottom_dwell = 211,
    decrement = 212,
    breaks = 213,            // chip breaks before a full retract; 0: every peck retracts fully
    pitch = 239,             // negative: left-hand
    chip_break_distance = 256,
};

// The number a Q parameter is written with ("Q200").
constexpr int number(Q q) { return static_cast<int>(q); }

// One Q parameter of a cycle definition and the comment written after it.
struct QParameter {
    Q q;
    std::string_view comment;
};

// A drilling cycle: its number, title and parameters in the order written.
struct CycleForm {
    int number;
    std::string_view title;
    std::span<const QParameter> parameters;
};

// Cycle 200 DRILLING: one plunge of Q202 (camgen writes the whole depth).
inline constexpr QParameter drilling_parameters[] = {
    {Q::setup_clearance, "SET-UP CLEARANCE"},
    {Q::depth, "DEPTH"},
    {Q::plunge_feed, "FEED RATE FOR PLNGNG"},
    {Q::plunging_depth, "PLUNGING DEPTH"},
    {Q::top_dwell, "DWELL TIME AT TOP"},
    {Q::surface, "SURFACE COORDINATE"},
    {Q::second_setup_clearance, "2ND SET-UP CLEARANCE"},
    {Q::bottom_dwell, "DWELL TIME AT DEPTH"},
};

// Cycle 203 UNIVERSAL DRILLING: pecks with decrement, chip breaks and a retraction feed.
inline constexpr QParameter universal_drilling_parameters[] = {
    {Q::setup_clearance, "SET-UP CLEARANCE"},
    {Q::depth, "DEPTH"},
    {Q::plunge_feed, "FEED RATE FOR PLNGNG"},
    {Q::plunging_depth, "PLUNGING DEPTH"},
    {Q::top_dwell, "DWELL TIME AT TOP"},
    {Q::surface, "SURFACE COORDINATE"},
    {Q::second_setup_clearance, "2ND SET-UP CLEARANCE"},
    {Q::decrement, "DECREMENT"},
    {Q::breaks, "NR OF BREAKS"},
    {Q::min_plunging_depth, "MIN. PLUNGING DEPTH"},
    {Q::bottom_dwell, "DWELL TIME AT DEPTH"},
    {Q::retraction_feed, "RETRACTION FEED RATE"},
    {Q::chip_break_distance, "DIST FOR CHIP BRKNG"},
};

// Cycle 207 RIGID TAPPING NEW: the pitch's sign gives the hand.
inline constexpr QParameter rigid_tapping_parameters[] = {
    {Q::setup_clearance, "SET-UP CLEARANCE"},
    {Q::depth, "DEPTH"},
    {Q::pitch, "PITCH"},
    {Q::surface, "SURFACE COORDINATE"},
    {Q::second_setup_clearance, "2ND SET-UP CLEARANCE"},
};

// The drilling cycles camgen writes and reads.
inline constexpr CycleForm drilling{200, "DRILLING", drilling_parameters};
inline constexpr CycleForm universal_drilling{203, "UNIVERSAL DRILLING", universal_drilling_parameters};
inline constexpr CycleForm rigid_tapping{207, "RIGID TAPPING NEW", rigid_tapping_parameters};
inline constexpr const CycleForm* cycle_forms[] = {&drilling, &universal_drilling, &rigid_tapping};

// Q213 takes at most 99 chip breaks.
inline constexpr int max_breaks = 99;
// Q208 at this value is a rapid retraction (FMAX), in mm and inch programs alike.
inline constexpr int fmax_feed = 99999;

}  // namespace camgen::heidenhain
