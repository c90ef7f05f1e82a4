#pragma once
// The reader base (private to src/reader/): splits a program into blocks of words as the
// machine's block style writes them, and keeps what every dialect shares: the table of a
// block's address words (BlockWords), the modal position with per-axis knowledge, formats and
// their scales, feed, spindle and tool changes, G0-G3 moves and arcs in every arc format,
// drilling cycles as DrillCycle/DrillPoint/DrillEnd events. A dialect (iso_reader.cpp, nccad_reader.cpp,
// sinumerik_reader.cpp, heidenhain_reader.cpp) says which words and codes exist and what they
// do, as the post dialects do in machines/.
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "camgen/geometry/arc.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/nc/format.hpp"
#include "camgen/reader/reader.hpp"

namespace camgen::reader {

inline bool is_blank(char c) { return c == ' ' || c == '\t'; }
inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
// `s` without the blanks (spaces, tabs) at either end.
inline std::string_view trim(std::string_view s) {
    while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
    return s;
}

// One word of a block: a letter (or a named address such as Sinumerik's CR=) and the number
// after it, as written.
struct Word {
    char letter = 0;         // upper case; 0 for a named address
    std::string name;        // a named address without its '=' ("CR"); empty for a letter
    double value = 0.0;      // the number as written, before any scale
    std::string text;        // letter and number as written, for messages ("X10.500")
    bool has_point = false;  // the number has a decimal mark
};

// One block: its words in order, comments and message text.
struct Block {
    int line = 0;
    std::vector<Word> words;
    std::vector<std::string> comments;  // comment texts, in order
    std::string message;                // text after a message code (nccad M01), trimmed
    bool has_message = false;
};

// A G or M code in tenths, so that G33.1 and G81 are both exact: code(81) == 810.
// A number too large to be a code (or not a number) gives a value no code has, never undefined
// behaviour.
constexpr int code(double c) {
    if (!(c > -1e8 && c < 1e8)) return std::numeric_limits<int>::min();
    return static_cast<int>(c * 10.0 + (c < 0 ? -0.5 : 0.5));
}


class NcReader {
public:
    NcReader(const Machine& machine, std::string source);
    virtual ~NcReader() = default;
    NcReader(const NcReader&) = delete;
    NcReader& operator=(const NcReader&) = delete;

    // Reads a whole program, handing each event to `sink` as it is read.
    void read(std::string_view text, ReadEventSink& sink);
    // The same a line at a time: start(), read_line() for each line (without its line break),
    // finish() at the end of the text. Events go to the sink as they are read.
    void start(ReadEventSink& sink);
    void read_line(std::string_view line);
    // How precisely this dialect states values (in the units in effect).
    virtual ReadResolution resolution() const;
    // The coarsest resolution in effect anywhere in the program read.
    ReadResolution coarsest_resolution() const { return coarsest_; }
    // The end of the text: close what is open (a dialect checks the program's end here).
    virtual void finish();
    // What the reader keeps that a block changes without an event, by name ("units": "mm"):
    // units, feed mode, work offset, spindle speed, tool, what it knows of the position, a
    // drilling cycle in progress, and the dialect's own (plane, tool length offset, a modal
    // cycle call, the program's end, ...). A custom block must leave it as it found it.
    virtual std::vector<std::pair<std::string, std::string>> modal_state() const;
    // Whether the dialect takes this line (trimmed) as part of the program's frame ("%", "_").
    bool is_frame_line(std::string_view line) { return frame_line(line); }

protected:
    // ---- dialect hooks ----
    // A line that is not a block of words ("%", "_"): true when the dialect consumed it.
    virtual bool frame_line(std::string_view line) = 0;
    // Interprets one line that is not blank and not a frame line. The default splits it into
    // words (split_line), emits its comments and passes the block on to block(); a dialect
    // whose lines are not all words (Sinumerik MCALL, Heidenhain conversational) reads its own.
    virtual void line(std::string_view text);
    // True when `name=` is an address of the dialect (Sinumerik "CR").
    virtual bool named_word(std::string_view name) const;
    // True when the rest of the line after this word is message text (nccad M01 <message>).
    virtual bool message_code(const Word& word) const;
    // True when words of this letter are written with '.' whatever the decimal mark (nccad
    // O6.1 names output 6, bit 1: not a number).
    virtual bool dotted_word(char letter) const;
    // Interprets one block (words are already split; the sequence number is removed).
    virtual void block(const Block& block) = 0;


    // ---- shared machinery ----
    [[noreturn]] void fail(const std::string& detail) const;

    // The address words of one block that a dialect reads by letter (X, F, T, ...), each letter
    // at most once. The code that gives a word its meaning takes it; a word nobody took is an
    // error (require_all_used).
    class BlockWords {
    public:
        // `letters`: the dialect's address letters (a string that outlives the table).
        BlockWords(const NcReader& reader, std::string_view letters) : reader_(reader), letters_(letters) {}
        // Adds a word of the block; fails for a letter not in `letters` or written twice.
        void add(const Word& w);
        // The word of this letter, now used (nullptr: not written).
        const Word* take(char letter);
        // The taken word's value as a length / an arc centre offset, in mm (nullopt: not written).
        std::optional<double> length(char letter);
        std::optional<double> offset(char letter);
        // The word of this letter without taking it (nullptr: not written).
        const Word* find(char letter) const;
        // The letter is written (taken or not).
        bool has(char letter) const { return find(letter) != nullptr; }
        // The letter is written and not taken yet.
        bool unused(char letter) const;
        // Fails for the first word (by letter) that was not taken: it has no meaning in the block.
        void require_all_used() const;

    private:
        struct Entry {
            const Word* word = nullptr;
            bool used = false;
        };
        const NcReader& reader_;
        std::string_view letters_;
        std::map<char, Entry> words_;
    };

    // Splits a line into words as the machine's block style writes them, the sequence number
    // (if the machine writes them) removed.
    Block split_line(std::string_view text);
    // Emits a block's comments as Comment events (and remembers the last one).
    void emit_comments(const Block& block);
    void emit(Event event, bool from_unknown = false, double uncertainty = 0.0, Approach approach = Approach::z_first);

    // Values of words in internal units (mm, mm/min, rpm, s, degrees), through the machine's
    // formats and their scales. Lengths without a decimal point are an error where the format
    // always writes one (a Fanuc-style control reads X10 as 0.010 mm).
    double length(const Word& w) const;
    double offset(const Word& w) const;
    // The format a word of this letter is written in (X, Z, I: their own; others: xyz / ijk).
    const nc::Format& length_format(char letter) const;
    const nc::Format& offset_format(char letter) const;
    double feed(const Word& w) const;
    double rpm(const Word& w) const;
    double seconds(const Word& w) const;
    double angle(const Word& w) const;
    // Numbers written outside address words (cycle parameters), in internal units through the
    // same formats: a length, a feed, seconds, a spindle speed.
    double length_value(double written) const;
    double feed_value(double written) const;
    double seconds_value(double written) const;
    double rpm_value(double written) const;
    // The word's value as a G/M code in tenths (see code()). Fails for finer values.
    int code_of(const Word& w) const;
    // The word's value as a non-negative whole number (tool, H, D, O-number).
    int integer_of(const Word& w) const;
    // Parses a number written with the machine's decimal mark (message texts). nullopt if not one.
    std::optional<double> parse_number(std::string_view text) const;

    // Switches the length and feed formats to these units (ISO G20/G21).
    void set_units(Units units);

    // Position: absolute mm, each axis known or not.
    bool position_known() const { return known_[0] && known_[1] && known_[2]; }
    Vec3 position() const { return {pos_[0], pos_[1], pos_[2]}; }
    // The control's position is unknown from here (tool change, home or reference run).
    void forget_position();
    // The control took Z to the machine's safe height (G53 G0 Z0): Z is unknown in work
    // coordinates but at the top, so X and Y may move before Z is known again.
    void retract_to_top();
    // A rapid to the given axes (nullopt: unchanged). Emitted once every axis is known; the
    // first one after forget_position() is marked from_unknown.
    void rapid_to(std::optional<double> x, std::optional<double> y, std::optional<double> z);
    // A feed move. Fails from an unknown position or without a feed.
    void linear_to(std::optional<double> x, std::optional<double> y, std::optional<double> z);
    // A thread-cutting move (G33 Z K, G32 Z F) named `name` along Z to `z`, its lead the word
    // `lead` (in the machine's feed-per-revolution format). Fails from an unknown position, with
    // the spindle off, or for a lead not above 0.
    // A thread-cutting move to Z (and X: a taper of at most 45 degrees), `lead` read through the
    // feed-per-revolution format: along Z, or with `along_path` along the move's path (LinuxCNC's
    // G33 K), turned into the ThreadFeed's lead along Z.
    void thread_to(const std::string& name, std::optional<double> x, double z, const Word& lead, bool along_path = false);
    void thread_to(const std::string& name, double z, const Word& lead) { thread_to(name, std::nullopt, z, lead); }

    // The words of an arc block in internal units (nullopt: not written).
    struct ArcWords {
        ArcDirection direction = ArcDirection::cw;
        Plane plane = Plane::xy;
        std::optional<double> x, y, z;  // end point
        std::optional<double> i, j, k;  // centre: offsets from the start or absolute (machine's arc format)
        std::optional<double> r;        // radius, negative for more than 180 degrees
        std::optional<double> d;        // nccad sweep in degrees (no end point)
        bool absolute_centre = false;   // I/J/K are absolute
        int turns = 0;                  // extra full turns of a helix
    };
    // A circular feed move, checked against the machine's arc settings (planes, helices, the
    // largest sweep per block, both radii equal within the machine's tolerance).
    void arc(const ArcWords& words);
    // A G0/G1/G2/G3 block (`motion` in tenths) to its end point X Y Z: G0 and G1 move at once;
    // G2/G3 return the arc's words in `plane` with the centre I J K (from the start, or absolute
    // by the machine's arc format) for the dialect to complete (R, CR, turns) and pass to arc().
    std::optional<ArcWords> move_or_arc(int motion, Plane plane, BlockWords& w);

    // A G or M code (tenths) and the word it was written as, for messages.
    struct Code {
        int value = 0;
        const Word* word = nullptr;
    };
    // Puts a code into its group, which takes one code per block; `group_name` names the group
    // in the message ("modal group").
    void set_group(std::optional<Code>& group, Code c, std::string_view group_name) const;
    // The M codes the ISO and Sinumerik dialects share, one of each group per block.
    struct MCodes {
        std::optional<Code> spindle;      // M3, M4, M5
        std::optional<Code> tool_change;  // M6
        std::optional<Code> stop;         // M0, M1, M2, M30
    };
    // Puts an M code into its group of `m`; false when it is none of them.
    bool shared_m_code(Code c, MCodes& m, std::string_view group_name) const;

    // Whether G code `g` (tenths) selects one of the machine's work offsets, alone (G54) or
    // with a P word (Fanuc G54.1 P1).
    bool work_offset_code(int g) const;
    // Checks the work offset a block selects with code `g` (its word `text`), taking its P word
    // from `w` where the machine's offsets have one; fails for an offset the machine lacks.
    void select_work_offset(int g, const Word& text, BlockWords& w);
    // The tool length offset the program selects from this line on, as SelectedOffsets::length
    // names it ("G43 H1"; "": cancelled). Every event after it carries it.
    void select_length_offset(std::string_view description);
    // The feed mode a G word selects, where it is one of the machine's feed mode codes.
    std::optional<FeedMode> feed_mode_of(const Word& g) const;
    // The feed mode (frame feedModes) and an F word in it: per revolution the feed is F x S,
    // so it follows later spindle speeds.
    void set_feed_mode(FeedMode mode);
    void set_feed(const Word& f);
    // The coolant mode an M word switches to, where it is one of the machine's coolant codes.
    std::optional<CoolantMode> coolant_of(const Word& m) const;
    // The tool diameter a camgen tool description starts with ("10 mm spot drill"), else 0.
    static double diameter_in(std::string_view description);
    // The description in the comment camgen's posts write before changing to this tool
    // ("T1 10 mm drill" -> "10 mm drill"); empty when the last comment is not one.
    std::string commented_description(int tool) const;
    // A program stop for the operator (M0, M1, nccad's M01 message, STOP): ends the drilling
    // cycle, emits Stop and forgets the position (the operator may move the axes).
    void stop(StopKind kind, std::string message);
    // A tool change (M6, TOOL CALL, an operator's pause): ends the drilling cycle, emits
    // ToolChange with the diameter the description starts with, and forgets the position.
    void change_tool(int tool, const std::string& description);
    // A new spindle speed (rpm, S or TOOL CALL S). A running spindle takes it at once unless
    // `switch_code` (the block's M3/M4/M5; nullptr: none) switches the spindle.
    void spindle_speed(double rpm, const Word* switch_code);
    // M3/M4/M5: the spindle on clockwise or counter-clockwise at the speed set before, or off.
    // `speed_word` says where the speed is written, for the message ("S").
    void switch_spindle(const Word& m, std::string_view speed_word);
    // Constant surface speed (G96) held to `limit` rpm: the S words that follow are the surface
    // speed (m/min; ft/min in inch), and the Spindle events carry it with the limit as rpm.
    void constant_surface_speed(double limit);
    // Constant rpm (G97): the S words that follow are rpm again.
    void constant_rpm();
    // A new limit of the spindle (Fanuc T's G50 S, Sinumerik's LIMS=): under G96 the spindle's
    // rpm, taken at once by a running spindle.
    void spindle_limit(double limit);
    bool surface_mode() const { return surface_mode_; }

    // The last comment read (camgen writes "T1 10 mm drill" before a tool change).
    std::string last_comment_;
    // Current feed (mm/min) if any was programmed; FeedUnit and scale already applied.
    std::optional<double> feed_;
    double rpm_ = 0.0;              // rev/min; under G96 the spindle's limit
    double surface_speed_ = 0.0;    // m/min under G96 (surface_mode_), the last S
    bool surface_mode_ = false;     // G96 is in effect
    SpindleState spindle_ = SpindleState::off;
    int tool_ = 0;

    // Drilling: a canned cycle and its holes, as events for trace_program to expand.
    // drill_cycle checks that the cycle's pecks reach its bottom (an error names the line).
    void drill_cycle(const DrillCycle& cycle);
    void drill_point(Vec2 at);
    void drill_end();
    const std::optional<DrillCycle>& current_cycle() const { return cycle_; }

    Machine machine_;  // a copy: G20/G21 change its units
    std::string source_;
    int line_ = 0;

private:
    void load_formats();
    Block split(std::string_view line) const;

    nc::Format xyz_, ijk_, feed_fmt_, rpm_fmt_, dwell_fmt_, angle_fmt_;
    nc::Format x_, z_, i_;  // the axis words' own formats (a lathe's diameter X)
    std::array<double, 3> pos_{};
    std::array<bool, 3> known_{};
    bool was_unknown_ = true;         // the next emitted rapid starts from an unknown position
    Approach approach_ = Approach::z_first;  // how the rapids since the position became unknown moved
    bool at_top_ = false;             // Z is at the machine's safe height (unknown in work coordinates)
    double xy_uncertainty_ = 0.0;     // mm, grows along chains of nccad D-form arcs
    std::optional<DrillCycle> cycle_;
    FeedMode feed_mode_ = FeedMode::per_minute;
    std::optional<double> feed_per_rev_;  // mm/rev, the F word per revolution
    std::string work_offset_;             // the work offset selected last ("G54"; "": none)
    SelectedOffsets offsets_;             // the offsets in force, as every event carries them
    nc::Format feed_rev_fmt_;
    ReadEventSink* sink_ = nullptr;  // where events go (set by start)
    ReadResolution coarsest_;
};

// The reader for a machine's dialect, from the dialect registry (machines/registry.cpp).
// Throws InputError when the dialect has none.
std::unique_ptr<NcReader> make_reader(const Machine& machine, std::string source);

}  // namespace camgen::reader
