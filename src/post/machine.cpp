#include "camgen/post/machine.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <fstream>
#include <span>
#include <sstream>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/post/capabilities.hpp"
#include "src/post/dialect_registry.hpp"
#include "src/post/machine_files.hpp"

namespace camgen {

namespace {

// Bounds of a format's scale. Every scale a control needs lies well inside: 1000 turns seconds
// into milliseconds, 1/6 mm/min into 0.1 mm/s, 1/25.4 mm into inches. Below 1e-3 a metre
// would be written as at most 1 unit; above 1e6 a millimetre would be written as a kilometre.
constexpr double min_scale = 1e-3;
constexpr double max_scale = 1e6;
// The widest integer part a format pads to: more digits than any control reads.
constexpr int max_width = 20;
// The highest first block number: eight digits, as Fanuc's N and program numbers allow.
constexpr int max_sequence_number = 99999999;
// The largest step between block numbers: more would run out of numbers after a few blocks.
constexpr int max_sequence_increment = 1000;
// The highest feed limit or rapid rate, mm/min: 1 km/min, above any machine tool's axes.
constexpr double max_feed_limit = 1e6;
// The highest spindle speed limit, rpm: above any spindle (air-bearing spindles reach 300000).
constexpr double max_rpm_limit = 1e6;

// The choices of a machine file that are not words of the vocabulary.
enum class LineBreak { lf, crlf };
constexpr Named<LineBreak> line_breaks[] = {
    {LineBreak::lf, "\n", "LF"},
    {LineBreak::crlf, "\r\n", "CR LF"},
};
constexpr Named<char> decimal_marks[] = {
    {'.', ".", "point"},
    {',', ",", "comma"},
};
constexpr Named<nc::CommentStyle> comment_styles[] = {
    {nc::CommentStyle::parentheses, "parentheses", "(text)"},
    {nc::CommentStyle::semicolon, "semicolon", "; text"},
};
constexpr Named<FeedUnit> feed_units[] = {
    {FeedUnit::per_minute, "mm/min", "mm/min (in/min for inch output)"},
    {FeedUnit::tenth_mm_per_second, "0.1mm/s", "0.1 mm/s (nccad)"},
};
constexpr Named<ArcFormat> arc_formats[] = {
    {ArcFormat::ijk_relative, "ijk-relative", "I/J/K: the centre minus the start"},
    {ArcFormat::ijk_absolute, "ijk-absolute", "I/J/K: the centre's coordinates"},
    {ArcFormat::radius, "radius", "R, negative over 180 degrees"},
    {ArcFormat::nccad_angle, "nccad-angle", "G02 D<sweep> I J, no end point"},
};
constexpr Named<ChordToleranceMode> chord_tolerance_modes[] = {
    {ChordToleranceMode::absolute, "absolute", "always chordTolerance"},
    {ChordToleranceMode::operation, "operation", "the operation's tolerance, capped by chordTolerance"},
};
constexpr Named<CannedStyle> canned_styles[] = {
    {CannedStyle::standard, "standard", "the dialect's usual canned cycle block"},
    {CannedStyle::rigid_g33_1, "rigid-g33.1", "LinuxCNC rigid tapping: G33.1 Z K, one synchronised move in and out"},
    {CannedStyle::fanuc_g74, "fanuc-g74",
     "Fanuc T end-face peck drilling on a lathe: G74 R(back-off) / G74 Z Q(peck in least increments) F (chip-break)"},
};
constexpr Named<BoreDwellFeedOut> bore_dwell_feed_outs[] = {
    {BoreDwellFeedOut::to_safe, "safe", "bore-dwell feeds out to R (Fanuc)"},
    {BoreDwellFeedOut::to_retract, "retract", "bore-dwell feeds out to the retract level (LinuxCNC)"},
};
constexpr Named<TappingMode> tapping_modes[] = {
    {TappingMode::rigid, "rigid", "the control synchronises the spindle to the feed: canned tapping only"},
    {TappingMode::floating, "floating",
     "taps sit in a floating holder: canned tapping without synchronisation, or longhand feeds with a spindle reversal"},
    {TappingMode::none, "none", "the machine cannot tap: every tap is refused"},
};

// The top-level keys of a machine file.
constexpr KeySpec machine_keys[] = {
    {.key = "extends", .type = JsonType::string,
     .description = "the machine (name, or path relative to this file) this file changes: only what differs is "
                    "given, merged over it (objects member by member; arrays and values replace; null removes)"},
    {.key = "description", .type = JsonType::string, .description = "one line for --list-machines (required unless extends)"},
    {.key = "dialect", .type = JsonType::string,
     .description = "the dialect code that writes for it: iso, nccad, sinumerik or heidenhain (required unless extends)"},
    {.key = "extension", .type = JsonType::string,
     .description = "suggested file extension, without the dot (required unless extends)"},
    {.key = "kind", .type = JsonType::string, .default_json = "\"mill\"", .choices = &choices_of<machine_kinds>,
     .description = "mill or lathe: the operations it runs (a job's operations of the other kind are refused)"},
    {.key = "units", .type = JsonType::string, .default_json = "\"mm\"", .choices = &choices_of<unit_names>,
     .description = "output units; one of acceptedUnits"},
    {.key = "acceptedUnits", .type = JsonType::array, .choices = &choices_of<unit_names>,
     .description = "the units the control has a mode for, selected by the unit word the dialect writes "
                    "(G21/G20, G71/G70, BEGIN PGM MM/INCH); --units outside it is refused (default: [units])"},
    {.key = "globals", .type = JsonType::object, .ref = "globals", .description = "CNC-Calc post processor globals"},
    {.key = "comments", .type = JsonType::string, .default_json = "\"parentheses\"",
     .choices = &choices_of<comment_styles>, .description = "comments in parentheses or after a semicolon"},
    {.key = "commentMaxLength", .type = JsonType::integer, .quantity = Quantity::count, .default_json = "0",
     .description = "the longest comment written, in characters (0: no limit)"},
    {.key = "modalMotion", .type = JsonType::boolean, .default_json = "true",
     .description = "false writes G0/G1/G2/G3 on every motion block"},
    {.key = "formats", .type = JsonType::object, .ref = "formats", .description = "number formats per word family"},
    {.key = "inchFormats", .type = JsonType::object, .ref = "formats",
     .description = "number formats per word family for inch output (default: formats)"},
    {.key = "feedUnit", .type = JsonType::string, .default_json = "\"mm/min\"", .choices = &choices_of<feed_units>,
     .description = "how feeds are written: mm/min (in/min for inch output) or 0.1 mm/s (nccad)"},
    {.key = "limits", .type = JsonType::object, .ref = "limits", .description = "feed and speed limits"},
    {.key = "arcs", .type = JsonType::object, .ref = "arcs", .description = "how arcs are written and when they are broken"},
    {.key = "notes", .type = JsonType::array, .items = JsonType::string,
     .description = "free text about the machine's choices, shown by --describe-machine"},
    {.key = "drilling", .type = JsonType::object, .ref = "drilling",
     .description = "the canned drilling cycles (MillDrillingFields) and longhand settings"},
    {.key = "roughingCycles", .type = JsonType::array, .ref = "roughingCycle",
     .description = "the machine's canned roughing cycles (a lathe's turn-rough); a kind not listed is written longhand"},
    {.key = "threadingCycles", .type = JsonType::array, .ref = "threadingCycle",
     .description = "the canned threading cycles of a lathe (turn-thread's output); none: threads are written longhand"},
    {.key = "groovingCycles", .type = JsonType::array, .ref = "groovingCycle",
     .description = "the canned grooving cycles of a lathe (turn-groove's output); none: grooves are written longhand"},
    {.key = "frame", .type = JsonType::object, .ref = "frame",
     .description = "the program frame: safe-start words, work offsets, coolant codes"},
    {.key = "settings", .type = JsonType::object, .ref = "settings",
     .description = "the dialect's settings, read with the machine: the keys of its dialect only (a file that names "
                    "its dialect is checked against settings-<dialect>)"},
};

// The keys of frame.
constexpr KeySpec frame_keys[] = {
    {.key = "startBlock", .type = JsonType::array, .default_json = "[]", .items = JsonType::string,
     .description = "the words of the safe-start block (cancel compensation, length offset and cycles; absolute; "
                    "plane; feed per minute), written before the unit word"},
    {.key = "workOffsets", .type = JsonType::array, .default_json = "[]", .items = JsonType::string,
     .description = "the work offsets a job may select (its workOffset), as written; \"G505..G599\" or "
                    "\"G54.1 P1..G54.1 P48\" is a range (default: none)"},
    {.key = "coolant", .type = JsonType::object, .ref = "coolantCodes",
     .description = "the code of each coolant mode the control has (default: none)"},
    {.key = "feedModes", .type = JsonType::object, .ref = "feedModeCodes",
     .description = "the code of each feed mode the control has (lathes: G94/G95, Fanuc T G98/G99); the "
                    "startBlock selects per-minute (default: none, feeds per minute only)"},
    {.key = "safeRetract", .type = JsonType::array, .default_json = "[]", .items = JsonType::string,
     .description = "the words of a block that takes Z to the machine's safe height in machine coordinates "
                    "([\"G53\", \"G0\", \"Z0\"], iso only): written where the tool's height is unknown "
                    "before X and Y move, and at the program end (default: none, the job's clearance)"},
};

// The keys of frame.coolant.
constexpr KeySpec coolant_keys[] = {
    {.key = "flood", .type = JsonType::string, .description = "flood coolant on (ISO M8)"},
    {.key = "mist", .type = JsonType::string, .description = "mist coolant on (ISO M7)"},
    {.key = "off", .type = JsonType::string, .description = "coolant off (ISO M9); needed with flood or mist"},
};

// The keys of frame.feedModes.
constexpr KeySpec feed_mode_keys[] = {
    {.key = "per-minute", .type = JsonType::string, .description = "feed per minute (ISO G94, Fanuc T G98)"},
    {.key = "per-revolution", .type = JsonType::string, .description = "feed per revolution (ISO G95, Fanuc T G99)"},
};

// The keys of globals.
constexpr KeySpec globals_keys[] = {
    {.key = "decimalMark", .type = JsonType::string, .default_json = "\".\"", .choices = &choices_of<decimal_marks>,
     .description = "the decimal mark of numbers"},
    {.key = "linebreak", .type = JsonType::string, .default_json = "\"\\n\"", .choices = &choices_of<line_breaks>,
     .description = "the end of a block"},
    {.key = "variableDelimeter", .type = JsonType::string, .default_json = "\" \"",
     .description = "the separator between words"},
    {.key = "tolerance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "0.002",
     .description = "the arc tolerance: every arc block's start and end radii agree within it after rounding"},
    {.key = "showSequenceNumbers", .type = JsonType::boolean, .default_json = "false",
     .description = "number the blocks"},
    {.key = "cutterCompensation", .type = JsonType::boolean, .default_json = "true",
     .description = "the control offsets by a tool radius (G41/G42): false refuses contours with control compensation"},
    {.key = "sequenceNumberStart", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{0, true},
     .max = Bound{max_sequence_number, true}, .default_json = "10", .description = "the first block number"},
    {.key = "sequenceNumberPrefix", .type = JsonType::string, .default_json = "\"N\"",
     .description = "written before a block number (\"\" for Heidenhain)"},
    {.key = "sequenceNumberIncrement", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{max_sequence_increment, true}, .default_json = "5", .description = "the step between block numbers"},
    {.key = "xDiameterProg", .type = JsonType::boolean, .default_json = "false",
     .description = "lathes: X words are diameters (else radii)"},
    {.key = "iDiameterProg", .type = JsonType::boolean, .default_json = "false",
     .description = "lathes: the I word of arcs is a diameter (else a radius); only with xDiameterProg"},
};

// The keys of formats and inchFormats: one format per word family.
constexpr KeySpec format_keys[] = {
    {.key = "xyz", .type = JsonType::object, .ref = "format", .description = "coordinates"},
    {.key = "ijk", .type = JsonType::object, .ref = "format", .description = "arc centres"},
    {.key = "x", .type = JsonType::object, .ref = "format",
     .description = "X words, where they differ from xyz (a lathe's X; what it leaves out is xyz's)"},
    {.key = "z", .type = JsonType::object, .ref = "format", .description = "Z words, where they differ from xyz (what it leaves out is xyz's)"},
    {.key = "i", .type = JsonType::object, .ref = "format", .description = "I words, where they differ from ijk (what it leaves out is ijk's)"},
    {.key = "feed", .type = JsonType::object, .ref = "format", .description = "feeds"},
    {.key = "rpm", .type = JsonType::object, .ref = "format", .description = "spindle speeds"},
    {.key = "dwell", .type = JsonType::object, .ref = "format", .description = "dwell times"},
    {.key = "feedPerRev", .type = JsonType::object, .ref = "format", .description = "feeds per revolution (mm or in)"},
    {.key = "angle", .type = JsonType::object, .ref = "format", .description = "angles (nccad D)"},
    {.key = "code", .type = JsonType::object, .ref = "format", .description = "G and M codes"},
};

// The keys of one format (CNC-Calc createFormat).
constexpr KeySpec format_spec_keys[] = {
    {.key = "prefix", .type = JsonType::string, .description = "written before the number"},
    {.key = "width", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{0, true},
     .max = Bound{max_width, true}, .description = "minimum digits of the integer part"},
    {.key = "zeropad", .type = JsonType::boolean, .description = "pad the integer part with 0 (else with spaces)"},
    {.key = "decimals", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{0, true},
     .max = Bound{12, true}, .description = "maximum decimals (exact count with forceDecimal)"},
    {.key = "scale", .quantity = Quantity::factor, .min = Bound{min_scale, true}, .max = Bound{max_scale, true},
     .description = "the value is multiplied by it; one unit (1 mm, 1 mm/min, 1 s, 1 rpm, 1 degree) times scale must "
                    "not round to 0 at the format's decimals"},
    {.key = "forceDecimal", .type = JsonType::boolean, .description = "always write every decimal (3 -> 3.000)"},
    {.key = "forceSign", .type = JsonType::boolean, .description = "write + before positive values"},
};

// The keys of limits.
constexpr KeySpec limits_keys[] = {
    {.key = "maxFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .max = Bound{max_feed_limit, true}, .default_json = "10000",
     .description = "feeds above it are clamped"},
    {.key = "minFeed", .quantity = Quantity::feed, .min = Bound{0, false}, .max = Bound{max_feed_limit, true}, .default_json = "1",
     .description = "feeds below it are clamped; not above maxFeed"},
    {.key = "rapidRate", .quantity = Quantity::feed, .min = Bound{0, false}, .max = Bound{max_feed_limit, true}, .default_json = "5000",
     .description = "rapid speed, for time estimates"},
    {.key = "maxRpm", .quantity = Quantity::speed, .min = Bound{0, false}, .max = Bound{max_rpm_limit, true},
     .description = "the highest spindle speed (default: no limit)"},
};

// The keys of arcs.
constexpr KeySpec arcs_keys[] = {
    {.key = "format", .type = JsonType::string, .default_json = "\"ijk-relative\"", .choices = &choices_of<arc_formats>,
     .description = "how an arc block gives its centre"},
    {.key = "maxSweep", .quantity = Quantity::angle, .min = Bound{0, false}, .max = Bound{360, true},
     .default_json = "360", .description = "sweep per arc block; longer arcs are split evenly"},
    {.key = "helical", .type = JsonType::boolean, .default_json = "true", .description = "false: helices become lines"},
    {.key = "forceXY", .type = JsonType::boolean, .default_json = "true",
     .description = "write both end coordinates of the plane on every arc block"},
    {.key = "chordTolerance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "0.005",
     .description = "how far the lines of a broken arc may stray from it"},
    {.key = "chordToleranceMode", .type = JsonType::string, .default_json = "\"operation\"",
     .choices = &choices_of<chord_tolerance_modes>,
     .description = "absolute: always chordTolerance; operation: the operation's tolerance, capped by chordTolerance"},
    {.key = "maxRadius", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "an arc of larger radius becomes lines (default: no limit)"},
    {.key = "minRadius", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "an arc of smaller radius becomes one straight move (default: no limit)"},
    {.key = "minLength", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a shorter arc becomes one straight move (default: no limit)"},
    {.key = "maxSegmentLength", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "no line of a broken arc is longer (default: no limit)"},
    {.key = "minSegments", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{100000, true}, .default_json = "1", .description = "a broken arc has at least this many lines"},
    {.key = "planes", .type = JsonType::array, .default_json = "[\"xy\", \"xz\", \"yz\"]",
     .choices = &choices_of<plane_names>, .description = "the planes the control does arcs in; others become lines"},
};

// The keys of drilling.
constexpr KeySpec drilling_keys[] = {
    {.key = "peckClearance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "1",
     .description = "re-approach clearance of longhand deep pecks and back-off of chip-break"},
    {.key = "boreDwellFeedOut", .type = JsonType::string, .default_json = "\"safe\"",
     .choices = &choices_of<bore_dwell_feed_outs>,
     .description = "where a longhand bore-dwell feeds out to: safe (R, Fanuc) or retract (LinuxCNC)"},
    {.key = "tapping", .type = JsonType::string, .default_json = "\"none\"", .choices = &choices_of<tapping_modes>,
     .description = "how the machine taps: rigid (synchronised, canned only), floating (a floating tap holder: canned "
                    "or longhand) or none"},
    {.key = "cycles", .type = JsonType::array, .ref = "drillingCycle",
     .description = "the machine's drilling cycles; a kind not listed is written longhand"},
};

// The names a cycle's "fields" may hold: MillDrillingFields and TurnDrillingFields names.
std::vector<std::string> cycle_field_names() {
    std::vector<std::string> names = drill_field_keys();
    for (std::string& t : turn_drill_field_keys())
        if (std::find(names.begin(), names.end(), t) == names.end()) names.push_back(std::move(t));
    return names;
}

// The keys of one drilling cycle.
constexpr KeySpec cycle_keys[] = {
    {.key = "name", .type = JsonType::string, .required = true, .description = "the cycle's name (G83, CYCLE83)"},
    {.key = "kind", .type = JsonType::string, .required = true, .choices = &choices_of<cycle_kinds>,
     .description = "the cycle kind it writes"},
    {.key = "canned", .type = JsonType::boolean, .default_json = "true", .description = "false: written longhand"},
    {.key = "style", .type = JsonType::string, .default_json = "\"standard\"", .choices = &choices_of<canned_styles>,
     .description = "how the canned cycle is written"},
    {.key = "fields", .type = JsonType::array, .choices = &cycle_field_names,
     .description = "the drilling fields the canned cycle carries: MillDrillingFields names on a mill (safeDistance, "
                    "firstDepth, ...), TurnDrillingFields names on a lathe (firstPeckDepth, peckRetract, ...)"},
};

// The keys of one roughing cycle.
constexpr KeySpec roughing_cycle_keys[] = {
    {.key = "name", .type = JsonType::string, .required = true, .description = "the cycle's name (G71)"},
    {.key = "kind", .type = JsonType::string, .required = true, .choices = &choices_of<roughing_cycle_kinds>,
     .description = "which way its passes run"},
    {.key = "style", .type = JsonType::string, .required = true, .choices = &choices_of<roughing_cycle_styles>,
     .description = "how it is written and what the control makes of it"},
    {.key = "fields", .type = JsonType::array, .choices = &choices_of<roughing_fields>,
     .description = "the values of a turn-rough the cycle carries"},
};

constexpr Named<ThreadCycleStyle> thread_cycle_styles[] = {
    {ThreadCycleStyle::linuxcnc_g76, "linuxcnc-g76",
     "LinuxCNC's G76 P Z I J K R Q H from the drive point (I, J, K diameters under G7)"},
    {ThreadCycleStyle::fanuc_g76, "fanuc-g76",
     "Fanuc T's two-block G76 P(m r a) Q(least depth) R(finish) / G76 X Z P(height) Q(first depth) F(lead) from the "
     "start point (P and Q in least input increments)"},
};

constexpr Named<int> thread_cycle_kinds[] = {{0, "thread", "a straight thread cut in passes (turn-thread)"}};

// The names a threading cycle's "fields" may hold.
std::vector<std::string> thread_cycle_field_list() {
    return {std::begin(thread_cycle_field_names), std::end(thread_cycle_field_names)};
}

// The keys of one threading cycle.
constexpr KeySpec thread_cycle_keys[] = {
    {.key = "name", .type = JsonType::string, .required = true, .description = "the cycle's name (G76)"},
    {.key = "kind", .type = JsonType::string, .required = true, .choices = &choices_of<thread_cycle_kinds>,
     .description = "what it cuts"},
    {.key = "style", .type = JsonType::string, .required = true, .choices = &choices_of<thread_cycle_styles>,
     .description = "how the canned cycle is written and read"},
    {.key = "fields", .type = JsonType::array, .choices = &thread_cycle_field_list,
     .description = "what it carries of a turn-thread: its infeed rules (constant-depth, constant-area), minDepth, "
                    "infeedAngle (flank infeed), springPasses, runout (a chamfered runout)"},
};

constexpr Named<GrooveCycleStyle> groove_cycle_styles[] = {
    {GrooveCycleStyle::fanuc_g75, "fanuc-g75",
     "Fanuc T's G75 R(back-off) / G75 X Z P(peck) Q(Z step, least increments) F from the start point, back to it"},
    {GrooveCycleStyle::fanuc_g74, "fanuc-g74",
     "Fanuc T's G74 R(back-off) / G74 X Z P(X step) Q(peck, least increments) F from the start point, back to it "
     "(face grooving)"},
};

constexpr Named<int> groove_cycle_kinds[] = {
    {0, "groove", "an external or internal groove cut in plunges along X (turn-groove)"},
    {1, "face-groove", "a face groove cut in plunges along Z (turn-groove \"side\": \"face\")"},
};

// The names a grooving cycle's "fields" may hold.
std::vector<std::string> groove_cycle_field_list() {
    return {std::begin(groove_cycle_field_names), std::end(groove_cycle_field_names)};
}

// The keys of one grooving cycle.
constexpr KeySpec groove_cycle_keys[] = {
    {.key = "name", .type = JsonType::string, .required = true, .description = "the cycle's name (G75)"},
    {.key = "kind", .type = JsonType::string, .required = true, .choices = &choices_of<groove_cycle_kinds>,
     .description = "what it cuts"},
    {.key = "style", .type = JsonType::string, .required = true, .choices = &choices_of<groove_cycle_styles>,
     .description = "how the canned cycle is written and read"},
    {.key = "fields", .type = JsonType::array, .choices = &groove_cycle_field_list,
     .description = "what it carries of a turn-groove beyond plain plunges: pecks, fullRetract, dwell, finishPass (a "
                    "finishing allowance and the pass along the bottom), chamfer"},
};

// Refuses machine-file text that is written into programs (prefixes, separators, codes, cycle
// names, dialect settings) when a control would read it as more than the word it is: control
// bytes and line breaks end or split a block, bytes outside printable ASCII are read
// differently by every control, '(' ')' ';' open or close a comment and '%' ends a Fanuc tape.
void check_program_text(const std::string& text, const std::string& path, const json::Source& source) {
    for (size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        std::string what;
        if (c == '\n' || c == '\r') what = "a line break";
        else if (c < 0x20 || c == 0x7F) what = fmt::format("the control byte 0x{:02X}", static_cast<unsigned>(c));
        else if (c >= 0x80) what = fmt::format("the non-ASCII byte 0x{:02X}", static_cast<unsigned>(c));
        else if (c == '(' || c == ')' || c == ';' || c == '%') what = fmt::format("'{}'", static_cast<char>(c));
        else continue;
        json::fail(source, path,
                   fmt::format("{} at character {}: text written into the program must be printable ASCII "
                               "without ( ) ; %", what, i + 1));
    }
}

// Every string inside a dialect settings value, checked as program text.
void check_settings_text(const nlohmann::json& v, const std::string& path, const json::Source& source) {
    if (v.is_string()) check_program_text(v.get<std::string>(), path, source);
    if (v.is_array())
        for (size_t i = 0; i < v.size(); ++i) check_settings_text(v[i], fmt::format("{}/{}", path, i), source);
    if (v.is_object())
        for (const auto& [key, item] : v.items()) check_settings_text(item, path + "/" + key, source);
}

// The strings of a JSON array of strings at `path`, each checked as program text.
std::vector<std::string> strings_at(const nlohmann::json& v, const std::string& path, const json::Source& source) {
    if (!v.is_array()) json::fail(source, path, "expected an array of strings");
    std::vector<std::string> out;
    for (size_t i = 0; i < v.size(); ++i) {
        const std::string item_path = fmt::format("{}/{}", path, i);
        if (!v[i].is_string() || v[i].get<std::string>().empty()) json::fail(source, item_path, "expected a non-empty string");
        check_program_text(v[i].get<std::string>(), item_path, source);
        out.push_back(v[i].get<std::string>());
    }
    return out;
}

// A work offset entry: one word, or a range "G505..G599" / "G54.1 P1..G54.1 P48" of words
// that differ only in their trailing whole number.
std::vector<std::string> expand_work_offset(const std::string& entry, const std::string& path, const json::Source& source) {
    const size_t dots = entry.find("..");
    if (dots == std::string::npos) return {entry};
    const std::string lo = entry.substr(0, dots), hi = entry.substr(dots + 2);
    auto split = [](const std::string& w) {
        size_t d = w.size();
        while (d > 0 && std::isdigit(static_cast<unsigned char>(w[d - 1]))) --d;
        return std::pair<std::string, std::string>{w.substr(0, d), w.substr(d)};
    };
    const auto [lo_prefix, lo_digits] = split(lo);
    const auto [hi_prefix, hi_digits] = split(hi);
    if (lo_prefix != hi_prefix || lo_digits.empty() || hi_digits.empty() || lo_digits.size() > 6 || hi_digits.size() > 6)
        json::fail(source, path, fmt::format("\"{}\": a range is two words that differ only in their trailing number", entry));
    const int a = std::stoi(lo_digits), b = std::stoi(hi_digits);
    if (a > b) json::fail(source, path, fmt::format("\"{}\": the range runs backwards", entry));
    std::vector<std::string> out;
    for (int i = a; i <= b; ++i) out.push_back(lo_prefix + std::to_string(i));
    return out;
}

// The dialects whose settings have `key`, by name.
std::vector<std::string_view> dialects_with_setting(std::string_view key) {
    std::vector<std::string_view> names;
    for (const Dialect& d : dialects())
        for (const KeySpec& k : d.settings_keys)
            if (k.key == key) names.push_back(d.name);
    return names;
}

// Reads the machine file's "settings" (`settings`, nullptr when absent) with the reader of the
// machine's dialect into m.settings: each key from the dialect's table, every error naming the
// file, line and key. A key of another dialect's settings is named as such. A machine of an
// unknown dialect keeps none (make_post refuses it).
void read_dialect_settings(const nlohmann::json* settings, Machine& m, const json::Source& source) {
    const Dialect* d = find_dialect(m.dialect);
    if (!d) return;
    static const nlohmann::json none = nlohmann::json::object();
    json::Fields f(settings ? *settings : none, "/settings", source);
    const auto own = [&](std::string_view key) {
        return std::any_of(d->settings_keys.begin(), d->settings_keys.end(), [&](const KeySpec& k) { return k.key == key; });
    };
    // The first foreign key in the file's order, as Fields::finish names the first unknown one.
    std::optional<std::pair<int, std::string>> foreign;
    if (settings)
        for (const auto& [key, value] : settings->items()) {
            if (own(key) || dialects_with_setting(key).empty()) continue;
            const int line = source.lines.line_of(f.path_of(key));
            if (!foreign || line < foreign->first) foreign = std::pair{line, key};
        }
    if (foreign) {
        const std::vector<std::string_view> owners = dialects_with_setting(foreign->second);
        const std::string ours = d->settings_keys.empty() ? "has no settings"
                                                          : fmt::format("has {}", fmt::join(keys_of(d->settings_keys), ", "));
        f.fail(foreign->second, fmt::format("\"{}\" is a setting of dialect {}, not of this machine's dialect {} (which {})",
                                            foreign->second, fmt::join(owners, " and "), m.dialect, ours));
    }
    if (d->read_settings) m.settings = d->read_settings(f, m, source);
    f.finish(d->settings_keys);
}

nc::FormatSpec default_format(const std::string& key) {
    nc::FormatSpec s;
    if (key == "xyz" || key == "ijk" || key == "x" || key == "z" || key == "i" || key == "dwell" || key == "angle")
        s.decimals = 3;
    if (key == "feedPerRev") s.decimals = 4;
    if (key == "code") s.decimals = 1;
    return s;
}

nc::FormatSpec read_format(json::Fields f, nc::FormatSpec base, const json::Source& source) {
    if (auto v = f.optional_string("prefix")) {
        check_program_text(*v, f.path_of("prefix"), source);
        base.prefix = *v;
    }
    if (auto v = f.optional_integer("width")) {
        if (*v < 0 || *v > max_width) f.fail("width", fmt::format("width must be between 0 and {}", max_width));
        base.width = *v;
    }
    base.zeropad = f.boolean("zeropad", base.zeropad);
    if (auto v = f.optional_integer("decimals")) {
        if (*v < 0 || *v > 12) f.fail("decimals", "decimals must be between 0 and 12");
        base.decimals = *v;
    }
    const auto scale = f.optional_number("scale");
    if (scale) {
        if (!(*scale >= min_scale && *scale <= max_scale))
            f.fail("scale", fmt::format("scale must be between {} and {:.0f}", min_scale, max_scale));
        base.scale = *scale;
    }
    // One unit of the quantity (1 mm, 1 mm/min, 1 s, 1 rpm) must not be written as 0.
    if (base.scale * std::pow(10.0, base.decimals) < 1.0 - 1e-9)
        f.fail(scale ? "scale" : "decimals",
               fmt::format("scale {} with {} decimals writes 1 as 0; the scale must be at least {}", base.scale,
                           base.decimals, std::pow(10.0, -base.decimals)));
    base.force_decimal = f.boolean("forceDecimal", base.force_decimal);
    base.force_sign = f.boolean("forceSign", base.force_sign);
    f.finish(format_spec_keys);
    return base;
}

// The "settings" object of the schema: every dialect's keys (a file that extends another need
// not name its dialect), each described with the dialects that have it.
const ObjectSpec& settings_object() {
    static std::deque<std::string> descriptions;  // the keys' descriptions point into it
    static const ObjectSpec object = [] {
        ObjectSpec o{.name = "settings",
                     .description = "the dialect's settings: iso (fanuc, linuxcnc, grbl), iso-lathe (the iso settings "
                                    "and its own), nccad; sinumerik, sinumerik-lathe and heidenhain have none. camgen "
                                    "refuses a key of another dialect than the machine's"};
        std::vector<std::pair<KeySpec, std::vector<std::string_view>>> keys;
        for (const Dialect& d : dialects())
            for (const KeySpec& k : d.settings_keys) {
                auto it = std::find_if(keys.begin(), keys.end(), [&](const auto& e) { return e.first.key == k.key; });
                if (it == keys.end()) keys.push_back({k, {d.name}});
                else it->second.push_back(d.name);
            }
        for (auto& [k, owners] : keys) {
            descriptions.push_back(fmt::format("{}: {}", fmt::join(owners, ", "), k.description));
            k.description = descriptions.back();
            o.keys.push_back(k);
        }
        return o;
    }();
    return object;
}

}  // namespace

std::vector<ObjectSpec> machine_objects() {
    auto spec = [](std::string_view name, std::string_view description, std::span<const KeySpec> keys) {
        return ObjectSpec{.name = name, .description = description, .keys = {keys.begin(), keys.end()}};
    };
    ObjectSpec machine = spec("machine", "a camgen machine file: the settings of one control", machine_keys);
    // A file that extends another gives only what differs.
    for (std::string_view key : {"description", "dialect", "extension"})
        machine.groups.push_back({.keys = {"extends", key}, .min = 1, .max = 2,
                                  .description = "extends another machine, or says what the inherited file would"});
    std::vector<ObjectSpec> objects = {
        machine,
        spec("globals", "block layout and numbers", globals_keys),
        spec("formats", "number formats per word family", format_keys),
        spec("format", "a number format (CNC-Calc createFormat)", format_spec_keys),
        spec("limits", "feed and speed limits", limits_keys),
        spec("arcs", "arc output and arc breaking", arcs_keys),
        spec("drilling", "drilling cycles and longhand settings", drilling_keys),
        spec("drillingCycle", "one drilling cycle of the machine (a MillDrillingFields entry)", cycle_keys),
        spec("roughingCycle", "one canned roughing cycle of a lathe", roughing_cycle_keys),
        spec("threadingCycle", "one threading cycle of a lathe", thread_cycle_keys),
        spec("groovingCycle", "one grooving cycle of a lathe", groove_cycle_keys),
        spec("frame", "the program frame: safe start, work offsets, coolant", frame_keys),
        spec("coolantCodes", "the code of each coolant mode", coolant_keys),
        spec("feedModeCodes", "the code of each feed mode", feed_mode_keys),
        settings_object(),
    };
    // Each dialect's own settings object, "settings-<dialect>": the schema checks a file's
    // settings against the one of the dialect it names.
    static std::deque<std::string> texts;  // the specs' names and descriptions point into it
    static const std::vector<ObjectSpec> dialect_objects = [] {
        std::vector<ObjectSpec> out;
        for (const Dialect& d : dialects()) {
            const std::string_view name = texts.emplace_back(fmt::format("settings-{}", d.name));
            const std::string_view description =
                texts.emplace_back(d.settings_keys.empty() ? fmt::format("dialect {} has no settings", d.name)
                                                           : fmt::format("the settings of dialect {}", d.name));
            out.push_back(ObjectSpec{.name = name, .description = description,
                                     .keys = {d.settings_keys.begin(), d.settings_keys.end()}});
        }
        return out;
    }();
    objects.insert(objects.end(), dialect_objects.begin(), dialect_objects.end());
    return objects;
}

nc::Format Machine::format(const std::string& key) const {
    // An axis without a format of its own is written in its family's.
    const bool axis = key == "x" || key == "z" || key == "i";
    const std::string family = key == "i" ? "ijk" : "xyz";
    const std::string lookup = axis && !formats.count(key) && !formats.count("inch." + key) ? family : key;
    nc::FormatSpec spec = default_format(lookup);
    if (auto it = formats.find(units == Units::inch ? "inch." + lookup : lookup); it != formats.end())
        spec = it->second;
    else if (auto it2 = formats.find(lookup); it2 != formats.end())
        spec = it2->second;
    spec.decimal_mark = decimal_mark;
    // Diameter programming (CNC-Calc xDiameterProg / iDiameterProg): the word is twice the radius.
    if ((key == "x" && x_diameter) || (key == "i" && x_diameter && i_diameter)) spec.scale *= 2.0;
    bool length = key == "xyz" || key == "ijk" || key == "feedPerRev" || axis;
    if (length && units == Units::inch) spec.scale /= 25.4;
    if (key == "feed") {
        if (feed_unit == FeedUnit::tenth_mm_per_second) spec.scale /= 6.0;  // mm/min -> 0.1 mm/s
        else if (units == Units::inch) spec.scale /= 25.4;
    }
    return nc::Format(spec);
}

bool Machine::accepts(Units u) const {
    return std::find(accepted_units.begin(), accepted_units.end(), u) != accepted_units.end();
}

std::string Machine::accepted_unit_names() const {
    std::vector<std::string> names;
    for (Units u : accepted_units) names.emplace_back(name_of(unit_names, u));
    return fmt::format("{}", fmt::join(names, ", "));
}

bool Machine::has_work_offset(const std::string& word) const {
    return std::find(frame.work_offsets.begin(), frame.work_offsets.end(), word) != frame.work_offsets.end();
}

std::optional<std::string> Machine::coolant_code(CoolantMode mode) const {
    if (auto it = frame.coolant.find(mode); it != frame.coolant.end()) return it->second;
    return std::nullopt;
}

const DrillingCycleSpec* Machine::canned_cycle(CycleKind kind) const {
    for (const auto& c : drilling)
        if (c.kind == kind && c.canned) return &c;
    return nullptr;
}

Machine parse_machine(const std::string& text, const std::string& name, const std::string& source_name) {
    json::Source source{source_name, json::LineMap{}};
    nlohmann::json root = json::parse(text, source_name);
    source.lines = json::LineMap(text);
    return parse_machine_json(root, name, source);
}

Machine parse_machine_json(const nlohmann::json& root, const std::string& name, const json::Source& source) {
    json::Fields f(root, "", source);
    Machine m;
    m.name = name;
    m.source = source.name;
    m.description = f.string("description");
    m.dialect = f.string("dialect");
    m.extension = f.string("extension");
    m.kind = f.choice("kind", machine_kinds, MachineKind::mill);
    m.units = f.choice("units", unit_names, Units::mm);
    m.accepted_units = {m.units};
    if (const auto* au = f.member("acceptedUnits")) {
        if (!au->is_array() || au->empty()) f.fail("acceptedUnits", "expected a non-empty array of \"mm\", \"inch\"");
        m.accepted_units.clear();
        for (size_t i = 0; i < au->size(); ++i) {
            const auto& u = (*au)[i];
            const auto units = value_named(unit_names, u.is_string() ? u.get<std::string>() : "");
            if (!units) json::fail(source, fmt::format("/acceptedUnits/{}", i), "expected \"mm\" or \"inch\"");
            if (!m.accepts(*units)) m.accepted_units.push_back(*units);
        }
        if (!m.accepts(m.units))
            f.fail("units", fmt::format("units \"{}\" is not one of acceptedUnits ({})", name_of(unit_names, m.units),
                                        m.accepted_unit_names()));
    }
    if (const auto* g = f.member("globals")) {
        json::Fields gf(*g, "/globals", source);
        const auto mark = value_named(decimal_marks, gf.optional_string("decimalMark").value_or("."));
        if (!mark) gf.fail("decimalMark", "decimalMark must be \".\" or \",\"");
        m.decimal_mark = *mark;
        m.block.line_break = std::string(name_of(line_breaks, gf.choice("linebreak", line_breaks, LineBreak::lf)));
        m.block.separator = gf.optional_string("variableDelimeter").value_or(" ");
        check_program_text(m.block.separator, gf.path_of("variableDelimeter"), source);
        if (auto t = gf.optional_number("tolerance")) {
            if (!(*t > 0)) gf.fail("tolerance", "tolerance must be > 0");
            m.tolerance = *t;
        }
        m.block.sequence_numbers = gf.boolean("showSequenceNumbers", false);
        m.cutter_compensation = gf.boolean("cutterCompensation", true);
        if (auto v = gf.optional_integer("sequenceNumberStart")) {
            if (*v < 0 || *v > max_sequence_number)
                gf.fail("sequenceNumberStart", fmt::format("sequenceNumberStart must be between 0 and {}", max_sequence_number));
            m.block.sequence_start = *v;
        }
        if (auto v = gf.optional_string("sequenceNumberPrefix")) {
            check_program_text(*v, gf.path_of("sequenceNumberPrefix"), source);
            m.block.sequence_prefix = *v;
        }
        if (auto v = gf.optional_integer("sequenceNumberIncrement")) {
            if (*v < 1 || *v > max_sequence_increment)
                gf.fail("sequenceNumberIncrement",
                        fmt::format("sequenceNumberIncrement must be between 1 and {}", max_sequence_increment));
            m.block.sequence_increment = *v;
        }
        m.x_diameter = gf.boolean("xDiameterProg", false);
        m.i_diameter = gf.boolean("iDiameterProg", false);
        // CNC-Calc: "only used in post processors for lathes".
        for (const char* key : {"xDiameterProg", "iDiameterProg"})
            if (m.kind == MachineKind::mill && gf.boolean(key, false))
                gf.fail(key, fmt::format("{} is for lathes: a mill's X is a coordinate, never a diameter (set \"kind\": "
                                         "\"lathe\")", key));
        gf.finish(globals_keys);
    }
    m.block.comment_style = f.choice("comments", comment_styles, nc::CommentStyle::parentheses);
    if (auto v = f.optional_integer("commentMaxLength")) m.block.comment_max_length = *v;
    m.modal_motion = f.boolean("modalMotion", true);
    for (const char* group : {"formats", "inchFormats"}) {
        const auto* fm = f.member(group);
        if (!fm) continue;
        json::Fields ff(*fm, std::string("/") + group, source);
        std::string pre = std::string(group) == "inchFormats" ? "inch." : "";
        for (const auto& format_key : format_keys) {
            const std::string key(format_key.key);
            if (const auto* spec = ff.member(key)) {
                // An axis format (x, z, i) starts from its family's (xyz, ijk): "x": {"zeropad": true}
                // changes only that, not X's decimals.
                const bool axis = key == "x" || key == "z" || key == "i";
                const std::string family = key == "i" ? "ijk" : "xyz";
                nc::FormatSpec base = default_format(key);
                if (!pre.empty() && m.formats.count(key)) base = m.formats[key];
                else if (axis && m.formats.count(pre + family)) base = m.formats[pre + family];
                else if (axis && m.formats.count(family)) base = m.formats[family];
                m.formats[pre + key] = read_format(json::Fields(*spec, ff.path_of(key), source), base, source);
            }
        }
        ff.finish(format_keys);
    }
    m.feed_unit = f.choice("feedUnit", feed_units, FeedUnit::per_minute);
    if (const auto* l = f.member("limits")) {
        json::Fields lf(*l, "/limits", source);
        auto positive = [&](const char* key, double& out, double most, const char* unit) {
            if (auto v = lf.optional_number(key)) {
                if (!(*v > 0 && *v <= most))
                    lf.fail(key, fmt::format("{} must be > 0 and at most {:.0f} {}", key, most, unit));
                out = *v;
            }
        };
        positive("maxFeed", m.limits.max_feed, max_feed_limit, "mm/min");
        positive("minFeed", m.limits.min_feed, max_feed_limit, "mm/min");
        positive("rapidRate", m.limits.rapid_rate, max_feed_limit, "mm/min");
        // Absent means no limit; a value is a limit, so 0 or below is refused.
        positive("maxRpm", m.limits.max_rpm, max_rpm_limit, "rpm (leave it out for no limit)");
        if (m.limits.min_feed > m.limits.max_feed) lf.fail("minFeed", "minFeed is above maxFeed");
        lf.finish(limits_keys);
    }
    if (const auto* a = f.member("arcs")) {
        json::Fields af(*a, "/arcs", source);
        m.arcs.format = af.choice("format", arc_formats, ArcFormat::ijk_relative);
        if (auto v = af.optional_number("maxSweep")) {
            if (!(*v > 0 && *v <= 360)) af.fail("maxSweep", "maxSweep must be in (0, 360] degrees");
            m.arcs.max_sweep = *v;
        }
        m.arcs.helical = af.boolean("helical", m.arcs.helical);
        m.arcs.force_xy = af.boolean("forceXY", m.arcs.force_xy);
        if (auto v = af.optional_number("chordTolerance")) {
            if (!(*v > 0)) af.fail("chordTolerance", "chordTolerance must be > 0");
            m.arcs.chord_tolerance = *v;
        }
        m.arcs.tolerance_mode = af.choice("chordToleranceMode", chord_tolerance_modes, ChordToleranceMode::operation);
        auto positive = [&](const char* key, std::optional<double>& out) {
            if (auto v = af.optional_number(key)) {
                if (!(*v > 0)) af.fail(key, fmt::format("{} must be > 0 (leave it out for no limit)", key));
                out = *v;
            }
        };
        positive("maxRadius", m.arcs.max_radius);
        positive("minRadius", m.arcs.min_radius);
        positive("minLength", m.arcs.min_length);
        positive("maxSegmentLength", m.arcs.max_segment_length);
        if (m.arcs.max_radius && m.arcs.min_radius && *m.arcs.min_radius >= *m.arcs.max_radius)
            af.fail("minRadius", "minRadius must be below maxRadius");
        if (auto v = af.optional_integer("minSegments")) {
            if (*v < 1 || *v > 100000) af.fail("minSegments", "minSegments must be between 1 and 100000");
            m.arcs.min_segments = *v;
        }
        if (const auto* planes = af.member("planes")) {
            if (!planes->is_array()) af.fail("planes", "expected an array of \"xy\", \"xz\", \"yz\"");
            m.arcs.planes.clear();
            for (size_t i = 0; i < planes->size(); ++i) {
                const auto& p = (*planes)[i];
                std::string s = p.is_string() ? p.get<std::string>() : "";
                if (auto plane = value_named(plane_names, s)) m.arcs.planes.push_back(*plane);
                else json::fail(source, fmt::format("/arcs/planes/{}", i), "expected \"xy\", \"xz\" or \"yz\"");
            }
        }
        af.finish(arcs_keys);
    }
    // A refused combination of settings: named at its first path, on the line of that setting or
    // of its nearest parent the file gives (load_machine names the file of an extends chain that
    // gives one of the paths).
    auto refuse = [&](const MachineProblem& problem) {
        const std::string& path = problem.paths.front();
        std::string given = path;
        while (!given.empty() && !root.contains(nlohmann::json::json_pointer(given))) given.resize(given.rfind('/'));
        throw MachineSettingsError(problem, path, source.lines.line_of(given), source.name);
    };
    if (m.arcs.format == ArcFormat::nccad_angle) {
        // G02 D<angle> I J has no end point and no K: it cannot say "helix" or "other plane".
        if (m.arcs.max_sweep > 180.0)
            refuse({{"/arcs/maxSweep", "/arcs/format"}, "the nccad angle form takes at most 180 degrees per block"});
        if (m.arcs.helical)
            refuse({{"/arcs/helical", "/arcs/format"}, "the nccad angle form cannot write a helix; set \"helical\": false"});
        if (m.arcs.planes != std::vector<Plane>{Plane::xy})
            refuse({{"/arcs/planes", "/arcs/format"}, "the nccad angle form writes XY arcs only; set \"planes\": [\"xy\"]"});
    }
    if (const auto* n = f.member("notes")) {
        if (!n->is_array()) f.fail("notes", "expected an array of strings");
        for (size_t i = 0; i < n->size(); ++i) {
            if (!(*n)[i].is_string()) json::fail(source, fmt::format("/notes/{}", i), "expected a string");
            m.notes.push_back((*n)[i].get<std::string>());
        }
    }
    if (const auto* d = f.member("drilling")) {
        json::Fields df(*d, "/drilling", source);
        if (auto v = df.optional_number("peckClearance")) {
            if (!(*v > 0)) df.fail("peckClearance", "peckClearance must be > 0");
            m.peck_clearance = *v;
        }
        m.bore_dwell_feed_out = df.choice("boreDwellFeedOut", bore_dwell_feed_outs, BoreDwellFeedOut::to_safe);
        m.tapping = df.choice("tapping", tapping_modes, TappingMode::none);
        if (const auto* cycles = df.member("cycles")) {
            if (!cycles->is_array()) df.fail("cycles", "expected an array");
            for (size_t i = 0; i < cycles->size(); ++i) {
                std::string path = fmt::format("/drilling/cycles/{}", i);
                json::Fields cf((*cycles)[i], path, source);
                DrillingCycleSpec c;
                c.name = cf.string("name");
                check_program_text(c.name, cf.path_of("name"), source);
                std::string kind = cf.string("kind");
                if (auto k = value_named(cycle_kinds, kind))
                    c.kind = *k;
                else
                    cf.fail("kind", fmt::format("unknown cycle kind \"{}\"; kinds: {}", kind, fmt::join(names_of(cycle_kinds), ", ")));
                c.canned = cf.boolean("canned", true);
                c.style = cf.choice("style", canned_styles, CannedStyle::standard);
                if (c.style == CannedStyle::rigid_g33_1 && m.tapping != TappingMode::rigid)
                    cf.fail("style", "style rigid-g33.1 taps rigidly: set drilling.tapping to rigid");
                if (c.style == CannedStyle::fanuc_g74 && (c.kind != CycleKind::chip_break || m.kind != MachineKind::lathe))
                    cf.fail("style", "style fanuc-g74 is a lathe's chip-break cycle: kind chip-break on a lathe");
                // A lathe's cycles name CNC-Calc's TurnDrillingFields, and carry the feed-start
                // plane (safeDistance) whatever they list: a turn-drill always has one.
                const bool lathe = m.kind == MachineKind::lathe;
                if (lathe) c.fields.push_back(DrillField::safe_distance);
                if (const auto* fields = cf.member("fields")) {
                    if (!fields->is_array()) cf.fail("fields", "expected an array of field names");
                    for (size_t j = 0; j < fields->size(); ++j) {
                        std::string fn = (*fields)[j].is_string() ? (*fields)[j].get<std::string>() : "";
                        const auto field = lathe ? turn_drill_field_named(fn) : drill_field_named(fn);
                        if (field) c.fields.push_back(*field);
                        if (!field) {
                            auto hint = json::did_you_mean(fn, lathe ? turn_drill_field_keys() : drill_field_keys());
                            json::fail(source, fmt::format("{}/fields/{}", path, j),
                                       fmt::format("unknown {} field \"{}\"{}", lathe ? "TurnDrillingFields" : "drilling", fn,
                                                   hint ? fmt::format(" (did you mean \"{}\"?)", *hint) : ""));
                        }
                    }
                }
                cf.finish(cycle_keys);
                m.drilling.push_back(std::move(c));
            }
        }
        df.finish(drilling_keys);
    }
    if (const auto* rc = f.member("roughingCycles")) {
        if (!rc->is_array()) f.fail("roughingCycles", "expected an array");
        if (m.kind != MachineKind::lathe && rc->size() > 0) f.fail("roughingCycles", "roughing cycles are a lathe's");
        for (size_t i = 0; i < rc->size(); ++i) {
            const std::string path = fmt::format("/roughingCycles/{}", i);
            json::Fields cf((*rc)[i], path, source);
            RoughingCycleSpec c;
            c.name = cf.string("name");
            check_program_text(c.name, cf.path_of("name"), source);
            c.kind = cf.choice("kind", roughing_cycle_kinds, RoughingCycleKind::rough_z);
            (void)cf.string("style");  // required: what the control makes of the cycle has no default
            c.style = cf.choice("style", roughing_cycle_styles, RoughingCycleStyle::linuxcnc);
            if (c.kind == RoughingCycleKind::rough_x && c.style == RoughingCycleStyle::fanuc_g71)
                cf.fail("kind", "style fanuc-g71 is a rough-z cycle (Fanuc's G71); along X: style fanuc-g72");
            if (c.kind == RoughingCycleKind::rough_z && c.style == RoughingCycleStyle::fanuc_g72)
                cf.fail("kind", "style fanuc-g72 is a rough-x cycle (Fanuc's G72); along Z: style fanuc-g71");
            // The pattern the tool moves in (Machine::rough_pattern) is the machine's, one for
            // both axes: Fanuc's and LinuxCNC's cycles cannot be mixed on one machine.
            for (const RoughingCycleSpec& other : m.roughing_cycles)
                if ((other.style == RoughingCycleStyle::linuxcnc) != (c.style == RoughingCycleStyle::linuxcnc))
                    cf.fail("style", fmt::format("{} and {} move in different patterns (LinuxCNC's and Fanuc's); a machine's "
                                                 "roughing cycles are all LinuxCNC's or all Fanuc's",
                                                 other.name, c.name));
            if (const auto* fields = cf.member("fields")) {
                if (!fields->is_array()) cf.fail("fields", "expected an array of field names");
                for (size_t j = 0; j < fields->size(); ++j) {
                    const std::string fn = (*fields)[j].is_string() ? (*fields)[j].get<std::string>() : "";
                    const auto field = value_named(roughing_fields, fn);
                    if (!field)
                        json::fail(source, fmt::format("{}/fields/{}", path, j),
                                   fmt::format("unknown roughing field \"{}\"; fields: {}", fn,
                                               fmt::join(names_of(roughing_fields), ", ")));
                    c.fields.push_back(*field);
                }
            }
            cf.finish(roughing_cycle_keys);
            for (const RoughingCycleSpec& o : m.roughing_cycles)
                if (o.kind == c.kind) json::fail(source, path, fmt::format("a second {} cycle", names_of(roughing_cycle_kinds)[static_cast<int>(c.kind)]));
            m.roughing_cycles.push_back(std::move(c));
        }
    }
    if (const auto* tc = f.member("threadingCycles")) {
        if (!tc->is_array()) f.fail("threadingCycles", "expected an array");
        if (m.kind != MachineKind::lathe) f.fail("threadingCycles", "threading cycles are a lathe's: set kind lathe");
        for (size_t i = 0; i < tc->size(); ++i) {
            const std::string path = fmt::format("/threadingCycles/{}", i);
            json::Fields cf((*tc)[i], path, source);
            ThreadingCycleSpec c;
            c.name = cf.string("name");
            check_program_text(c.name, cf.path_of("name"), source);
            cf.choice("kind", thread_cycle_kinds, 0);
            if (!cf.has("kind")) cf.fail("kind", "a threading cycle needs its kind (\"thread\")");
            if (!cf.has("style")) cf.fail("style", "a threading cycle needs its style");
            c.style = cf.choice("style", thread_cycle_styles, ThreadCycleStyle::linuxcnc_g76);
            if (const auto* fields = cf.member("fields")) {
                if (!fields->is_array()) cf.fail("fields", "expected an array of field names");
                const std::vector<std::string> known = thread_cycle_field_list();
                for (size_t j = 0; j < fields->size(); ++j) {
                    std::string fn = (*fields)[j].is_string() ? (*fields)[j].get<std::string>() : "";
                    if (std::find(known.begin(), known.end(), fn) == known.end()) {
                        auto hint = json::did_you_mean(fn, known);
                        json::fail(source, fmt::format("{}/fields/{}", path, j),
                                   fmt::format("unknown threading field \"{}\"{}; fields: {}", fn,
                                               hint ? fmt::format(" (did you mean \"{}\"?)", *hint) : "",
                                               fmt::join(known, ", ")));
                    }
                    c.fields.push_back(std::move(fn));
                }
            }
            cf.finish(thread_cycle_keys);
            m.threading.push_back(std::move(c));
        }
    }
    if (const auto* gc = f.member("groovingCycles")) {
        if (!gc->is_array()) f.fail("groovingCycles", "expected an array");
        if (m.kind != MachineKind::lathe) f.fail("groovingCycles", "grooving cycles are a lathe's: set kind lathe");
        for (size_t i = 0; i < gc->size(); ++i) {
            const std::string path = fmt::format("/groovingCycles/{}", i);
            json::Fields cf((*gc)[i], path, source);
            GroovingCycleSpec c;
            c.name = cf.string("name");
            check_program_text(c.name, cf.path_of("name"), source);
            c.face = cf.choice("kind", groove_cycle_kinds, 0) == 1;
            if (!cf.has("kind")) cf.fail("kind", "a grooving cycle needs its kind (\"groove\" or \"face-groove\")");
            if (!cf.has("style")) cf.fail("style", "a grooving cycle needs its style");
            c.style = cf.choice("style", groove_cycle_styles, GrooveCycleStyle::fanuc_g75);
            // Each style cuts one kind: G75 along X, G74 along Z.
            if (c.face != (c.style == GrooveCycleStyle::fanuc_g74))
                cf.fail("style", fmt::format("style {} cuts {}, not kind {}", name_of(groove_cycle_styles, c.style),
                                             c.style == GrooveCycleStyle::fanuc_g74 ? "face grooves (kind \"face-groove\")"
                                                                                    : "grooves along X (kind \"groove\")",
                                             name_of(groove_cycle_kinds, c.face ? 1 : 0)));
            // G74 is also Fanuc T's peck drilling (the reader tells them apart by X and P): a
            // drilling cycle of the same name must be that one, not another control's G74.
            for (const DrillingCycleSpec& d : m.drilling)
                if (c.style == GrooveCycleStyle::fanuc_g74 && d.canned && d.name == c.name && d.style != CannedStyle::fanuc_g74)
                    cf.fail("name", fmt::format("{} is also a drilling cycle of this machine of another style than fanuc-g74: "
                                                "the reader could not tell the face grooving from it",
                                                c.name));
            for (const GroovingCycleSpec& o : m.grooving)
                if (o.face == c.face)
                    cf.fail("kind", fmt::format("a second grooving cycle of kind {}: a lathe has one of each kind",
                                                name_of(groove_cycle_kinds, c.face ? 1 : 0)));
            if (const auto* fields = cf.member("fields")) {
                if (!fields->is_array()) cf.fail("fields", "expected an array of field names");
                const std::vector<std::string> known = groove_cycle_field_list();
                for (size_t j = 0; j < fields->size(); ++j) {
                    std::string fn = (*fields)[j].is_string() ? (*fields)[j].get<std::string>() : "";
                    if (std::find(known.begin(), known.end(), fn) == known.end()) {
                        auto hint = json::did_you_mean(fn, known);
                        json::fail(source, fmt::format("{}/fields/{}", path, j),
                                   fmt::format("unknown grooving field \"{}\"{}; fields: {}", fn,
                                               hint ? fmt::format(" (did you mean \"{}\"?)", *hint) : "",
                                               fmt::join(known, ", ")));
                    }
                    c.fields.push_back(std::move(fn));
                }
            }
            cf.finish(groove_cycle_keys);
            m.grooving.push_back(std::move(c));
        }
    }
    if (const auto* fr = f.member("frame")) {
        json::Fields ff(*fr, "/frame", source);
        if (const auto* sb = ff.member("startBlock")) m.frame.start_block = strings_at(*sb, "/frame/startBlock", source);
        if (const auto* wo = ff.member("workOffsets")) {
            std::vector<std::string> entries = strings_at(*wo, "/frame/workOffsets", source);
            for (size_t i = 0; i < entries.size(); ++i)
                for (std::string& w : expand_work_offset(entries[i], fmt::format("/frame/workOffsets/{}", i), source))
                    m.frame.work_offsets.push_back(std::move(w));
        }
        if (const auto* c = ff.member("coolant")) {
            json::Fields cf(*c, "/frame/coolant", source);
            for (const auto& mode : coolant_modes)
                if (auto code = cf.optional_string(mode.name)) {
                    check_program_text(*code, cf.path_of(mode.name), source);
                    m.frame.coolant[mode.value] = *code;
                }
            if (!m.frame.coolant.empty() && !m.frame.coolant.count(CoolantMode::off))
                cf.fail("off", "a machine with coolant needs the code that switches it off");
            cf.finish(coolant_keys);
        }
        if (const auto* fm = ff.member("feedModes")) {
            json::Fields mf(*fm, "/frame/feedModes", source);
            for (const auto& mode : feed_modes)
                if (auto code = mf.optional_string(mode.name)) {
                    check_program_text(*code, mf.path_of(mode.name), source);
                    m.frame.feed_modes[mode.value] = *code;
                }
            if (!m.frame.feed_modes.empty() && m.frame.feed_modes.size() != 2)
                mf.fail("", "a machine with feed modes needs the code of both (per-minute and per-revolution)");
            mf.finish(feed_mode_keys);
        }
        if (const auto* sr = ff.member("safeRetract")) {
            m.frame.safe_retract = strings_at(*sr, "/frame/safeRetract", source);
            // Read back as a move to the machine's top: the ISO reader's G53 G0 Z0.
            if (!m.frame.safe_retract.empty() && m.frame.safe_retract != std::vector<std::string>{"G53", "G0", "Z0"})
                ff.fail("safeRetract", "the safe retract camgen reads back is [\"G53\", \"G0\", \"Z0\"]");
            if (!m.frame.safe_retract.empty() && m.dialect != "iso")
                ff.fail("safeRetract", fmt::format("dialect {} has no G53 safe retract", m.dialect));
        }
        ff.finish(frame_keys);
    }
    if (const auto* s = f.member("settings")) {
        if (!s->is_object()) f.fail("settings", "expected an object");
        check_settings_text(*s, "/settings", source);
    }
    read_dialect_settings(f.member("settings"), m, source);
    f.finish(machine_keys);
    if (auto problem = machine_problem(m)) refuse(*problem);
    return m;
}

std::vector<std::pair<std::string, std::string>> list_machines() {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& e : embedded_machines()) {
        Machine m = parse_machine(e.text, e.name, e.name);
        out.emplace_back(m.name, m.description);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::string describe_machine(const Machine& m) {
    std::string s;
    auto line = [&](std::string_view k, const std::string& v) { s += fmt::format("  {:<24}{}\n", k, v); };
    s += fmt::format("{}: {}\n", m.name, m.description);
    s += "globals\n";
    line("dialect", m.dialect);
    line("kind", std::string(name_of(machine_kinds, m.kind)));
    if (m.kind == MachineKind::lathe) {
        line("xDiameterProg", m.x_diameter ? "yes: X words are diameters" : "no: X words are radii");
        line("iDiameterProg", m.x_diameter && m.i_diameter ? "yes: I words are diameters" : "no: I words are radii");
    }
    line("extension", "." + m.extension);
    line("units", m.units == Units::mm ? "mm" : "inch");
    line("acceptedUnits", m.accepted_unit_names());
    line("decimalMark", std::string(1, m.decimal_mark));
    line("linebreak", m.block.line_break == "\n" ? "\\n" : "\\r\\n");
    line("variableDelimeter", "\"" + m.block.separator + "\"");
    line("showSequenceNumbers", m.block.sequence_numbers ? fmt::format("yes, from {} step {}", m.block.sequence_start, m.block.sequence_increment) : "no");
    line("modalMotion", m.modal_motion ? "yes" : "no, G code on every motion block");
    line("comments", m.block.comment_style == nc::CommentStyle::parentheses ? "(text)" : "; text");
    const char* arcs[] = {"I/J/K relative to start", "I/J/K absolute centre", "radius R", "nccad angle D with I/J"};
    line("arcs", fmt::format("{}, at most {} degrees a block, helices {}", arcs[static_cast<int>(m.arcs.format)], m.arcs.max_sweep,
                             m.arcs.helical ? "allowed" : "as lines"));
    std::vector<std::string> planes;
    for (Plane p : m.arcs.planes) planes.emplace_back(name_of(plane_names, p));
    line("arc planes", fmt::format("{} (others as lines)", fmt::join(planes, ", ")));
    auto limit = [](const std::optional<double>& v) { return v ? fmt::format("{} mm", *v) : std::string("none"); };
    line("arc tolerance", fmt::format("{} mm (start and end radii after rounding)", m.tolerance));
    line("chordTolerance", fmt::format("{} mm{}", m.arcs.chord_tolerance,
                                       m.arcs.tolerance_mode == ChordToleranceMode::operation ? ", or the operation's if smaller" : ""));
    line("arcs as lines", fmt::format("radius above {}; at least {} segment(s), {}", limit(m.arcs.max_radius), m.arcs.min_segments,
                                      m.arcs.max_segment_length ? fmt::format("each at most {} mm", *m.arcs.max_segment_length)
                                                                : std::string("any length")));
    line("arcs as one line", fmt::format("radius below {}, length below {}", limit(m.arcs.min_radius), limit(m.arcs.min_length)));
    line("feed unit", m.feed_unit == FeedUnit::per_minute ? (m.units == Units::mm ? "mm/min" : "in/min") : "0.1 mm/s");
    for (const std::string& n : m.notes) line("note", n);
    s += "limits\n";
    line("maxFeed", fmt::format("{} mm/min", m.limits.max_feed));
    line("minFeed", fmt::format("{} mm/min", m.limits.min_feed));
    line("rapidRate", fmt::format("{} mm/min", m.limits.rapid_rate));
    line("maxRpm", m.limits.max_rpm > 0 ? fmt::format("{} rpm", m.limits.max_rpm) : std::string("none"));
    line("peckClearance", fmt::format("{} mm", m.peck_clearance));
    line("boreDwellFeedOut", m.bore_dwell_feed_out == BoreDwellFeedOut::to_safe ? "to the feed-start plane R"
                                                                                 : "to the retract level");
    for (const auto& t : tapping_modes)
        if (t.value == m.tapping) line("tapping", fmt::format("{}: {}", t.name, t.description));
    s += "program frame\n";
    line("startBlock", m.frame.start_block.empty() ? std::string("-") : fmt::format("{}", fmt::join(m.frame.start_block, " ")));
    line("workOffsets", m.frame.work_offsets.empty()
                            ? std::string("none")
                            : m.frame.work_offsets.size() > 12
                                  ? fmt::format("{} .. {} ({})", m.frame.work_offsets.front(), m.frame.work_offsets.back(),
                                                m.frame.work_offsets.size())
                                  : fmt::format("{}", fmt::join(m.frame.work_offsets, ", ")));
    std::vector<std::string> coolant;
    for (const auto& [mode, code] : m.frame.coolant) coolant.push_back(fmt::format("{} {}", name_of(coolant_modes, mode), code));
    line("coolant", coolant.empty() ? std::string("none") : fmt::format("{}", fmt::join(coolant, ", ")));
    std::vector<std::string> feed;
    for (const auto& [mode, code] : m.frame.feed_modes) feed.push_back(fmt::format("{} {}", name_of(feed_modes, mode), code));
    line("feedModes", feed.empty() ? std::string("per minute only") : fmt::format("{}", fmt::join(feed, ", ")));
    line("safeRetract", m.frame.safe_retract.empty() ? std::string("the job's clearance")
                                                     : fmt::format("{}", fmt::join(m.frame.safe_retract, " ")));
    // What the post makes of these settings: the same functions its refusals call.
    const MachineCapabilities can = machine_capabilities(m);
    const bool lathe = m.kind == MachineKind::lathe;
    s += lathe ? "drilling cycles (TurnDrillingFields; the feed-start plane always)\n" : "drilling cycles (MillDrillingFields)\n";
    for (const CycleCapability& c : can.cycles) line(name_of(cycle_kinds, c.kind), cycle_capability_text(c, m.kind));
    if (lathe) {
        s += "threading cycles (turn-thread)\n";
        if (m.threading.empty()) line("thread", "longhand");
        for (const ThreadingCycleSpec& t : m.threading)
            line("thread", fmt::format("{} ({}){}", t.name, name_of(thread_cycle_styles, t.style),
                                       t.fields.empty() ? std::string() : fmt::format(": {}", fmt::join(t.fields, ", "))));
        s += "grooving cycles (turn-groove)\n";
        if (m.grooving.empty()) line("groove", "longhand");
        for (const GroovingCycleSpec& t : m.grooving)
            line("groove", fmt::format("{} ({}){}", t.name, name_of(groove_cycle_styles, t.style),
                                       t.fields.empty() ? std::string() : fmt::format(": {}", fmt::join(t.fields, ", "))));
    }
    s += "capabilities (what a job may ask; a refusal is the post's own message)\n";
    auto verdict = [](const Capability& c, const std::string& yes) { return c.refused ? "refused: " + *c.refused : yes; };
    if (can.control_compensation)
        line("control compensation", verdict(*can.control_compensation, "yes: G41/G42 for \"compensation\": \"control\""));
    for (const auto& [plane, as_arcs] : can.arcs)
        line(fmt::format("arcs in {}", name_of(plane_names, plane)), as_arcs ? "arc blocks" : "straight moves");
    if (can.helices) line("helices", *can.helices ? "helical arc blocks" : "straight moves");
    line("spindle ccw", verdict(can.ccw_spindle, "yes"));
    line("programNumber", verdict(can.program_number, "yes"));
    line("surface speed", verdict(can.surface_speed, "yes: G96 for a tool's surfaceSpeed, within its maxRpm (else maxRpm above)"));
    return s;
}

}  // namespace camgen
