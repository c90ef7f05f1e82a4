#pragma once
// The post processor base: turns events into NC text for one machine. It mirrors the
// CNC-Calc calls (on_open, on_close, on_rapid, on_linear, on_circular, on_compensation,
// on_drilling_header/point/footer, on_tool_change, on_spindle, on_dwell, on_comment). Shared
// behaviour (modal words, arc splitting and breaking, longhand cycles, feed limits) lives
// here; a dialect overrides only what differs.
#include <memory>
#include <optional>
#include <set>
#include <ostream>
#include <string>
#include <string_view>

#include "camgen/post/arc_output.hpp"
#include "camgen/post/longhand.hpp"
#include "camgen/events/events.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/stops.hpp"
#include "camgen/nc/block_writer.hpp"
#include "camgen/nc/format.hpp"

namespace camgen {

struct PostOptions {
    bool snippet = false;              // CNC-Calc clipboard export: no program start or end
    std::string program_name;          // the job's name, for the program header
    std::ostream* warnings = nullptr;  // where warnings go (stderr); nullptr: dropped
    std::ostream* notes = nullptr;     // where notes go (stderr unless --quiet); nullptr: dropped
    std::string work_offset;           // the job's work offset ("G54"); empty: none written
    std::optional<int> program_number; // the job's program number, overriding the machine's
};

// How a machine makes drilling cycles of one kind (Post::cycle_capability).
struct CycleCapability {
    CycleKind kind = CycleKind::drill;
    std::optional<DrillingCycleSpec> canned;    // its canned cycle, written where it carries the job's values
    bool longhand = true;                       // written longhand where it does not (or the job asks);
                                                // false for a rigid tap, which longhand moves would break
    std::optional<std::string> refused;         // why no cycle of this kind is made at all: the message
    std::string refused_key;                    // the operation's key the refusal names ("cycle", "output")
};

// Where in a program a custom block is written: what a post has written before it (the
// read-back of the block starts a program so).
struct ProgramPoint {
    std::string operation_path;
    FeedMode feed_mode = FeedMode::per_minute;
    int tool = 0;                      // 0: none yet
    Spindle spindle;
    std::optional<Vec3> position;      // where the tool is, if known
};

class Post : public EventSink {
public:
    // The lines of a custom block for `machine`: those given for its name, else for its
    // dialect. Throws InputError at the block's path when it gives neither.
    static const CustomText& custom_text(const Machine& machine, const CustomBlock& block);
    // What `text`'s lines do, read back by the machine's reader in a program that `options`
    // frames and that stands at `point` (comments and dwells), once the lines are found safe to
    // write there: an InputError at the block's path names the line the reader cannot read, a
    // line that would move the tool, change the tool, switch the spindle or the coolant, stop
    // the program or end it, and a change of the reader's state (camgen/reader: units, work
    // offset, spindle speed, a modal cycle call, ...; not where `state` is `unchecked`: a
    // comparison takes the block's comments and dwells from a job the post has checked).
    enum class StateCheck { checked, unchecked };
    static std::vector<Event> custom_block_events(const Machine& machine, const PostOptions& options,
                                                  const CustomBlock& block, const CustomText& text,
                                                  const ProgramPoint& point, StateCheck state = StateCheck::checked);

    Post(const Machine& machine, std::ostream& out, PostOptions options);
    ~Post() override;

    // Writes the program start (nothing for a snippet).
    void open();
    // Writes one event of a job; its stops as OperatorStops makes them (camgen/post/stops.hpp).
    void emit(const Event& event) override;
    // Writes the program end (nothing for a snippet) and flushes. Throws IoError.
    void close();
    // Hands the blocks finished so far to the stream (a block being built stays), so that the
    // stream's lines are the program's so far (which line an operation starts at).
    void flush_blocks() { out_.flush(); }
    // How many holes were written as canned cycles so far.
    int canned_holes() const { return canned_holes_; }
    // How many holes were written longhand so far.
    int longhand_holes() const { return longhand_holes_; }

    // ---- capabilities: what a job can ask of this machine. Each is one function that the
    // post's refusal calls and that --describe-machine prints (machine_capabilities in
    // capabilities.hpp), so that the description and the posts cannot disagree. ----
    // Why the control cannot offset the cutter by its radius (G41/G42 for a contour's
    // "compensation": "control"), as the message says it; nullopt where it can.
    virtual std::optional<std::string> control_compensation_refusal() const;
    // How drilling cycles of `kind` are made: canned, longhand, or refused and why.
    CycleCapability cycle_capability(CycleKind kind) const;
    // Why the spindle cannot run counter-clockwise (a tool's "direction": "ccw"), as the
    // message says it; nullopt where it can.
    virtual std::optional<std::string> ccw_spindle_refusal() const { return std::nullopt; }
    // Why the spindle cannot turn at a constant surface speed (a lathe tool's surfaceSpeed,
    // G96), as the message says it; nullopt where it can (the lathe dialects).
    virtual std::optional<std::string> surface_speed_refusal() const;
    // Why a job's programNumber is refused (the dialect writes none: takes_program_number), as
    // the message says it; nullopt where it is written.
    std::optional<std::string> program_number_refusal() const;

protected:
    // ---- CNC-Calc calls: a dialect overrides what differs ----
    virtual void on_open() {}
    virtual void on_close() {}
    virtual void on_operation_start(const OperationStart& op);
    virtual void on_operation_end() {}
    virtual void on_tool_change(const ToolChange& tool) = 0;
    // ISO: M5, or S.. M3/M4.
    virtual void on_spindle(const Spindle& spindle);
    virtual void on_dwell(double seconds) = 0;
    // Coolant to `coolant.mode`: the machine's code in a block of its own. An InputError at the
    // job key's path where the machine has no such coolant.
    virtual void on_coolant(const Coolant& coolant);
    // Whether the dialect writes a program number (a job's programNumber is refused otherwise).
    virtual bool takes_program_number() const { return false; }
    virtual void on_comment(const std::string& text);
    // A stop for the operator (the spindle and coolant are off already): M0 or M1 with the
    // message as a comment in its block (inline_comment).
    virtual void on_stop(const Stop& stop);
    // A rapid to `to`; the base writes G0 with the modal axis words that changed.
    virtual void on_rapid(const Vec3& to);
    // A feed move; the base writes the block linear_layout() describes: pending compensation,
    // the motion word, axis words and F.
    virtual void on_linear(const Vec3& to, double feed);
    // A move synchronised with the spindle from `from` (thread cutting). The base refuses it: a
    // dialect that cuts threads writes its block (G33 Z K, G32 Z F).
    virtual void on_thread_feed(const Vec3& from, const ThreadFeed& move);
    // One arc block, already split to the machine's maximum sweep and in a supported plane,
    // fitted to the rounded words (fit_arc_block): arc.start is where the control stands,
    // arc.centre / arc.radius / arc.sweep are what the I/J/K, R or D words must say.
    virtual void on_circular(const ArcGeometry& arc, double feed);
    // Compensation is retained and written by the next linear move (CNC-Calc rule).
    virtual void on_compensation(const Compensation& compensation);
    // Canned drilling, called only when the cycle is written canned.
    virtual void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec);
    virtual void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec,
                                   Vec2 at, bool first);
    virtual void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec);
    // Why the canned `spec` cannot carry this cycle although it has every field the cycle
    // uses (a value the control cannot express, e.g. a degression factor where it takes only
    // a value), or nullopt. The cycle is then written longhand (output "auto") or refused.
    virtual std::optional<std::string> canned_limit(const DrillCycle& cycle, const DrillingCycleSpec& spec) const;
    // A canned threading cycle, called only when it is written canned (from the cycle's drive
    // point, where the tool stands). The base refuses it: a dialect with threadingCycles writes it.
    virtual void on_thread_cycle(const ThreadCycle& cycle, const ThreadingCycleSpec& spec);
    // Why the canned threading cycle `spec` would not cut the cycle's passes although it carries
    // every field (the control's own arithmetic on the rounded words gives other passes), or
    // nullopt. The cycle is then written longhand (output "auto") or refused. The base: a
    // dialect that writes no threading cycle says so.
    virtual std::optional<std::string> thread_cycle_limit(const ThreadCycle& cycle, const ThreadingCycleSpec& spec) const;
    // A canned roughing cycle, called only when it is written canned (from the cycle's start,
    // where the tool stands). The base refuses it: a dialect with roughingCycles writes it.
    virtual void on_turn_cycle(const TurnCycle& cycle, const RoughingCycleSpec& spec);
    // Why the canned roughing cycle `spec` would not make the cycle's moves (the control's own
    // arithmetic on the rounded words), or nullopt; then the moves are written longhand (output
    // "auto") or refused. The base: a dialect that writes no roughing cycle says so.
    virtual std::optional<std::string> turn_cycle_limit(const TurnCycle& cycle, const RoughingCycleSpec& spec) const;
    // A canned grooving cycle, called only when it is written canned (from its start, where the
    // tool stands; it must leave the tool at groove_cycle_end). The base refuses it.
    virtual void on_groove_cycle(const GrooveCycle& cycle, const GroovingCycleSpec& spec);
    // Why the canned grooving cycle `spec` would not cut the cycle's moves although it carries
    // every field (the control's own arithmetic on the rounded words), or nullopt. The base: the
    // dialect writes no grooving cycle.
    virtual std::optional<std::string> groove_cycle_limit(const GrooveCycle& cycle, const GroovingCycleSpec& spec) const;
    // Why G70 cannot finish `cycle` here (the turn-rough before it was not written as the linked
    // cycle), or nullopt: then on_finish_cycle writes it from A, where the tool stands, and the
    // control ends at A. The base: the dialect writes no G70.
    virtual std::optional<std::string> finish_cycle_limit(const FinishCycle& cycle) const;
    virtual void on_finish_cycle(const FinishCycle& cycle);
    // Why this machine cannot tap (a cycle of tapping kind `kind`) at all, whatever its tapping
    // mode says (nccad: the spindle cannot reverse), or nullopt. Said after "machine M cannot
    // tap: ". Asked through cycle_capability.
    virtual std::optional<std::string> tapping_impossible(CycleKind kind) const;

    // ---- word hooks: how a dialect spells a word of a block the base writes ----
    // The words that switch cutter radius compensation: G40, or G41/G42 D<register> (the
    // compensation's D register, else the tool number).
    virtual std::string compensation_words(const Compensation& compensation) const;
    // The radius word of an arc block in radius format: R, negative above 180 degrees.
    virtual std::string radius_word(double radius) const;
    // Whether an arc block writes its plane's end coordinates even when unchanged (the
    // machine's forceXY).
    virtual bool force_arc_end() const;
    // How a feed move's block is laid out: its motion word and where the compensation words go.
    struct LinearLayout {
        std::string_view motion;               // "G1" (motion_word), or "L" (Heidenhain)
        bool compensation_after_axes = false;  // false: before the motion word
    };
    // The layout of the feed move being written (the base: the modal G1, compensation first).
    virtual LinearLayout linear_layout();
    // A rapid to `to` while the tool's height is unknown (program start, after a tool change):
    // Z alone first (rapid_z_from_unknown), then X and Y at that height.
    virtual void rapid_from_unknown(const Vec3& to);
    // The block that moves Z alone to `z` (mm) from an unknown height: the first move of a
    // tool. ISO adds the tool length offset (G43 H) to it.
    virtual void rapid_z_from_unknown(double z);

    // ---- shared helpers ----
    // A comment written inside a block, after its words: "(text)" or "; text" by the machine's
    // comment style, the text made safe (clean_comment).
    std::string inline_comment(std::string_view text) const;
    // The safe-start block: the machine's frame startBlock words, `unit_word` (may be empty)
    // and the job's work offset, in one block (nothing when all are empty).
    void write_start_block(const std::string& unit_word);
    // The machine's safe retract block (frame safeRetract, e.g. G53 G0 Z0); Z is unknown after it.
    void write_safe_retract();
    // A feed in mm/min within the machine's limits: clamped, with one warning per operation and
    // feed. Fails for a feed that is not a number above 0.
    double clamped_feed(double mm_per_min);
    // The F word for a feed in mm/min: clamped to the machine's limits (with a warning),
    // converted to the machine's feed unit, modal. Like every word the post's modal words
    // write (motion_word, axis_words, force_xy, force_z), the text lives in its word: valid
    // until that word is written again, so add it to the block first.
    std::string_view feed_word(double mm_per_min);
    // The S word for a spindle speed; an InputError above the machine's maxRpm or where it would
    // be written as S0.
    std::string speed_word(double rpm) const;
    // The spindle speed as the machine writes it, without a letter (for a message to the
    // operator), checked as speed_word checks it.
    std::string speed_text(double rpm) const;
    // The lead of a thread-cutting move as `letter` and the machine's feed-per-revolution format
    // ("K2.5"); fails where it would be written as 0, the spindle stands still, or the lead
    // times the spindle speed is beyond the machine's maxFeed (the axis could not follow).
    std::string lead_word(std::string_view letter, double lead);
    // The G word for motion mode `code` (0, 1, 2, 3, 81, ...), modal.
    std::string_view motion_word(double code);
    // Forget modal state that the control may have changed (after a cycle, a tool change).
    void reset_modal_axes();
    // Writes a warning (where the options say).
    void warn(const std::string& message);
    // Writes a note: a choice camgen made that the user may not expect (where the options say).
    void note(const std::string& message);
    // InputError at the current operation's path (plus `key`).
    [[noreturn]] void fail(const std::string& key, const std::string& detail) const;
    // The word for a G or M code as this machine writes it ("G0" or "G00").
    std::string g(double code) const;
    // The word for an M code as this machine writes it ("M3" or "M03").
    std::string m(double code) const;

    // ---- the post's state, through named operations ----
    // The machine the post writes for.
    const Machine& machine() const { return machine_; }
    // The options the post was made with (program name, snippet).
    const PostOptions& options() const { return options_; }
    // Where blocks go.
    nc::BlockWriter& writer() { return out_; }
    // The machine's format for lengths (X, Y, Z, R, ...).
    const nc::Format& xyz_format() const { return xyz_fmt_; }
    // The machine's format for spindle speeds.
    const nc::Format& rpm_format() const { return rpm_fmt_; }
    // The machine's format for dwell times.
    const nc::Format& dwell_format() const { return dwell_fmt_; }
    // The JSON path of the operation being written ("/operations/2"), for messages.
    const std::string& operation_path() const { return op_path_; }
    // The tool the last tool change selected (0: none yet).
    int current_tool() const { return tool_; }
    // Where the tool stands (absolute mm) as far as the events have moved it.
    const Vec3& position() const { return pos_; }
    // The tool now stands at `at` (a dialect moved it on its own, such as to a retract plane).
    void set_position(const Vec3& at) { pos_ = at; }

    // The axis words of one block; an empty text is a word not written.
    struct AxisWords {
        std::string_view x, y, z;
    };
    // Which axis words a block writes even when the control already has the value.
    struct ForcedAxes {
        bool x = false, y = false, z = false;
    };
    // The X, Y and Z words of a move to `to`: modal (empty when unchanged) unless forced.
    AxisWords axis_words(const Vec3& to, ForcedAxes forced);
    // The X, Y and Z words of a move to `to`, each empty when unchanged (modal).
    AxisWords axis_words(const Vec3& to) { return axis_words(to, ForcedAxes{}); }
    // The X and Y words of a position, written whatever the modal state (z stays empty).
    AxisWords force_xy(Vec2 at);
    // The Z word, written whatever the modal state.
    std::string_view force_z(double z);
    // The Z the control was last told, if known.
    std::optional<double> written_z() const { return z_.last(); }
    // The control stands at this Z without a Z word saying so (a cycle returned it there).
    void assume_z(double z) { z_.set_last(z); }
    // The control's Z is unknown: the next Z word is written.
    void forget_z() { z_.reset(); }
    // The control is in motion mode `code` without a word saying so (a modal cycle call).
    void assume_motion(double code) { motion_.set_last(code); }
    // The motion mode is unknown: the next motion word is written.
    void forget_motion() { motion_.reset(); }
    // The control is in plane `code` (17, 18, 19): the program start selected it.
    void assume_plane(double code) { plane_.set_last(code); }
    // How F is written now: per minute or per revolution.
    FeedMode feed_mode_now() const { return feed_mode_; }
    // The feed is unknown: the next F word is written, per minute or per revolution.
    void forget_feed() {
        feed_.reset();
        feed_rev_.reset();
    }
    // The F word of a feed (mm/min) at spindle speed `rpm` in the feed mode now, clamped as
    // feed_word, not modal (Fanuc's finishing feed in a G71 shape, for G70).
    std::string feed_text(double mm_per_min, double rpm);
    // The F value feed_word and feed_text write (mm/min, or mm per revolution at `rpm`), clamped
    // to the machine's limits; fails where the spindle stands still or F would read 0.
    double checked_feed(double mm_per_min, double rpm);

private:
    const Machine& machine_;
    PostOptions options_;
    nc::BlockWriter out_;
    nc::Format xyz_fmt_, ijk_fmt_, feed_fmt_, rpm_fmt_, dwell_fmt_, angle_fmt_, code_fmt_;
    nc::Format x_fmt_, z_fmt_, i_fmt_;  // the axis words' own formats (a lathe's diameter X)
    nc::Format feed_rev_fmt_;           // feeds per revolution
    nc::Word x_, y_, z_, feed_, motion_, plane_;
    nc::Word feed_rev_;                        // F per revolution
    FeedMode feed_mode_ = FeedMode::per_minute;  // how F is written now (the start block: per minute)
    double spindle_rpm_ = 0.0;                 // the spindle speed now, for feeds per revolution
    Spindle spindle_;                          // the spindle as the job's events left it
    // Switches the feed mode to the operation's: the machine's code in a block of its own.
    void select_feed_mode(FeedMode mode);
    Vec3 pos_;
    LonghandBuffers longhand_buffers_;  // reused by every longhand hole's moves
    bool pos_known_ = false;
    std::optional<Compensation> pending_compensation_;  // written by the next feed move
    int tool_ = 0;
    std::string op_path_;
    std::string op_name_;                      // the current operation's name, for notes

    // One event after OperatorStops.
    void handle(const Event& event);
    // Passes the events OperatorStops makes on to handle().
    struct Handler : EventSink {
        Post& post;
        explicit Handler(Post& p) : post(p) {}
        void emit(const Event& event) override { post.handle(event); }
    };
    Handler handler_{*this};
    OperatorStops stops_;
    // Writes a custom block's lines for this machine, once its reader has read them back in a
    // program like this one (check_custom) and found nothing but comments and dwells that
    // leave its state as it was; refuses them otherwise.
    void handle_custom(const CustomBlock& block);
    // Writes the lines as they are (the probe program of check_custom writes them unchecked).
    void write_custom_lines(const std::vector<std::string>& lines);
    bool unchecked_custom_ = false;
    void handle_arc(const Arc& arc);
    // Straight moves along `arc` in `segments` equal chords, ending exactly at its end; above
    // max_arc_chords an error naming the operation, the count, the limit and `chord_tolerance`
    // (mm). `why`: why the arc is not written as arcs.
    void write_lines(const ArcGeometry& arc, std::int64_t segments, double feed, double chord_tolerance, std::string_view why);
    // Writes one arc block whose rounded words keep the control on the circle, or breaks it.
    void write_arc_block(const ArcGeometry& piece, double feed, double chord_tolerance, int depth);
    // Where the control stands at the start of an arc block (see arc_actual_end_).
    Vec3 arc_control_start(const Vec3& start) const;
    void handle_drill_cycle(const DrillCycle& cycle);
    // A threading cycle: canned where the machine's cycle carries it (thread_cycle_limit),
    // else its moves longhand with a note (output "auto") or refused (output "canned").
    void handle_thread_cycle(const ThreadCycle& cycle);
    // A roughing cycle: canned where the machine's cycle makes its moves (turn_cycle_limit),
    // else its moves longhand with a note (output "auto") or refused (output "canned"); one
    // carrying a refusal writes nothing but the note (the operation's passes follow it).
    void handle_turn_cycle(const TurnCycle& cycle);
    // A grooving cycle: canned where the machine's cycle carries it (groove_cycle_limit), else
    // its moves longhand with a note (output "auto") or refused (output "canned").
    void handle_groove_cycle(const GrooveCycle& cycle);
    // A finishing pass after a linked Fanuc roughing cycle: under the machine's Fanuc pattern the
    // way to A, G70 (canned where finish_cycle_limit allows, else longhand in G70's pattern with a
    // note, or refused under "canned") and the way out; elsewhere, or refused by read_job, the
    // turn-profile's own moves (refused under "canned", a note where the machine has Fanuc's cycle).
    void handle_finish_cycle(const FinishCycle& cycle);
    // A lathe cycle (threading, roughing, grooving) not written canned, `reason` why: refused at
    // its `/output` under "canned", else a note, where the machine has such a cycle, that its
    // `what` ("thread", "roughing", "groove") is written longhand.
    void cycle_not_canned(const std::string& path, CycleOutput output, bool has_cycle, std::string_view what,
                          const std::string& reason);
    // The cycle as this machine can run it: feeds clamped to its limits (every dialect writes
    // the same clamped values, canned or longhand); refused when a value would be written as 0
    // or below the machine's resolution (speeds, pecks, dwells), when it needs more pecks than
    // any control takes, or when a tap's synchronised feed is above the machine's limit (a
    // tap's feed is never clamped: it must match its pitch).
    DrillCycle checked_cycle(const DrillCycle& cycle);
    void handle_drill_point(Vec2 at);
    void handle_drill_end();
    // Whether the machine's canned cycle of a cycle's kind can write it, and if not, why.
    struct CannedFit {
        const DrillingCycleSpec* spec = nullptr;  // the machine's canned cycle of the kind, if any
        std::vector<std::string> missing;         // keys of used fields it cannot carry
        std::optional<std::string> limit;         // a value it cannot express
        bool fits() const { return spec && missing.empty() && !limit; }
    };
    CannedFit canned_fit(const DrillCycle& cycle) const;
    // The canned cycle to write `cycle` with, or nullptr for longhand; refuses taps the
    // machine cannot make safely and notes an "auto" cycle that goes longhand.
    const DrillingCycleSpec* choose_canned(const DrillCycle& cycle);
    // The message that refuses a longhand tap on a machine that taps rigidly; `why` says why it
    // would be longhand, `remedy` what the job can change.
    std::string longhand_tap_refusal(const std::string& why, const std::string& remedy) const;
    // Throws longhand_tap_refusal at the cycle's "output".
    [[noreturn]] void refuse_longhand_tap(const DrillCycle& cycle, const std::string& why, const std::string& remedy) const;
    void replay(const LonghandMove& event);

    std::optional<DrillCycle> cycle_;
    const DrillingCycleSpec* cycle_spec_ = nullptr;  // canned spec for the current cycle
    bool first_point_ = true;
    std::set<std::pair<std::string, double>> warned_feeds_;
    bool opened_ = false;
    int canned_holes_ = 0;                     // holes written as canned cycles
    int longhand_holes_ = 0;                   // holes written longhand
    std::optional<double> op_tolerance_;       // the current operation's tolerance, mm
    std::optional<Vec3> arc_actual_end_;       // where the control ended the last arc block
    Vec3 arc_believed_end_;                    // ... and where the post's modal words think it is
};

// The post for a machine, by its dialect. Throws InputError for an unknown dialect.
std::unique_ptr<Post> make_post(const Machine& machine, std::ostream& out, PostOptions options);

// The tool length offset the machine's post selects for `tool` (0: before any tool), as the
// reader names the one a program selects (SelectedOffsets::length in reader.hpp): "G43 H1",
// "T0101", "D1", "TOOL CALL 1"; "" where the post selects none (nccad, GRBL, a machine file
// with toolLengthOffset false). What verify --job expects in force at every move of the tool.
std::string post_length_offset(const Machine& machine, int tool);

// Whether the machine's start block selects the XY plane (G17).
bool starts_in_xy(const Machine& machine);

// Which optional drilling fields a cycle uses (for matching against a canned cycle).
std::vector<DrillField> drill_fields_used(const DrillCycle& cycle);

}  // namespace camgen
