#pragma once
// Reading NC programs back (the last step of the pipeline, docs/design.md): the text a post wrote, parsed with the
// same machine file into events. Used by `camgen verify`, the round-trip tests and the SVG
// backplot. The machine's globals set up the reader as the CNC-Calc manual (section 7) sets up
// a backplot: arc type, decimal mark, formats and their scales, block style, comments.
#include <iosfwd>
#include <memory>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/common/input_file.hpp"
#include "camgen/events/events.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// How the tool reached the end of a rapid from an unknown position: Z alone first, then X and
// Y (safe: the tool was at its height before it moved across), or with X or Y moved while
// the height was still unknown (a tool touched off on the stock crosses the part).
enum class Approach { z_first, xy_first };

// A word naming an offset as the control's words name it ("G43 H1", "G54"; "": none), kept once
// per process in a table of the distinct words met (never freed: their number is bounded by the
// distinct H, D, T and work offset numbers the programs write). Copying and comparing one is
// copying and comparing 4 bytes: every event read carries the offsets in force
// (SelectedOffsets), and as two std::string they took 5 % of verify --job's time (200,000 holes).
class OffsetWord {
public:
    OffsetWord() = default;  // ""
    explicit OffsetWord(std::string_view text);
    const std::string& str() const;
    bool empty() const { return id_ == 0; }
    friend bool operator==(OffsetWord a, OffsetWord b) { return a.id_ == b.id_; }
    friend bool operator==(OffsetWord a, std::string_view b) { return a.str() == b; }

private:
    std::uint32_t id_ = 0;  // the word's place in the table; 0: ""
};

// The offsets a program has selected, in force at an event: the tool length offset and the
// work offset, as the control's words name them ("" where none is in force). verify --job
// compares them with the ones camgen's post selects (compare.hpp), every move; reading a program
// takes any of them. 16 bytes, trivially copied.
struct SelectedOffsets {
    // The tool length offset: "G43 H1" (ISO mills, LinuxCNC's lathe), "T0101" (a turret's call,
    // its last two digits the offset), "D1" (Sinumerik's cutting edge, selected with T),
    // "TOOL CALL 1" (Heidenhain: the called tool's own length, no register of its own); "": none
    // (G49, or none selected; nccad and GRBL as camgen writes them have none).
    OffsetWord length;
    // The work offset: "G54", "G54.1 P1"; "": none selected (the control's active one).
    OffsetWord work;
    int length_line = 0;  // the line that selected (or cancelled) it; 0: none did
    int work_line = 0;
    // The same offsets (where they were selected aside).
    bool same(const SelectedOffsets& o) const { return length == o.length && work == o.work; }
    // The same offsets selected by the same lines.
    bool operator==(const SelectedOffsets&) const = default;
};

// One event read from a program. Canned drilling cycles come back as DrillCycle, DrillPoint
// (one per hole) and DrillEnd; trace_program (motion.hpp) expands them with longhand_moves.
struct ReadEvent {
    Event event;
    int line = 0;               // 1-based line of the block that made it; 0: not from a program
    bool from_unknown = false;  // a Rapid that starts where the control's position is unknown
                                // (program start, after a tool change or a home run)
    double uncertainty = 0.0;   // mm the end point may be off beyond the written resolution,
                                // because the control computes it (nccad D-form arcs, the
                                // depths of a canned cycle from its rounded parameters)
    Approach approach = Approach::z_first;  // a from_unknown Rapid: whether Z moved first
    double per_revolution = 0.0;  // a feed move in per-revolution mode (G95): its mm per spindle
                                  // turn (its feed follows the spindle speed); else 0
    SelectedOffsets offsets;      // in force at the event
};

// How precisely a program for a machine states values: half a unit of the last decimal written,
// in internal units (a value read back is within this of the value the post was given).
struct ReadResolution {
    double position = 0.0005;  // mm, X/Y/Z/R/Q words
    double offset = 0.0005;    // mm, I/J/K words
    double angle = 0.0005;     // degrees, nccad D words
    double feed = 0.5;         // mm/min
    double rpm = 0.5;          // rev/min
    double dwell = 0.0005;     // s
};

// Receives the events of a program one at a time, in program order, as they are read: nothing
// needs to keep the whole program (a million-hole program is read in constant memory).
class ReadEventSink {
public:
    virtual ~ReadEventSink() = default;
    virtual void read_event(const ReadEvent& event) = 0;
    // The end of the program: every event was handed on.
    virtual void finish() {}
};

namespace reader {
class NcReader;
}

// Reads a program from a stream a line at a time (in blocks of the stream, never the whole
// text), handing each event to the sink as its line is read. The same checks and messages as
// read_program; advance() throws them, and IoError for a line longer than max_program_line or
// more bytes than max_input_size() (a stream without an end: /dev/zero).
class ProgramReader {
public:
    ProgramReader(std::istream& in, const Machine& machine, const std::string& source, ReadEventSink& sink);
    ~ProgramReader();
    ProgramReader(const ProgramReader&) = delete;
    ProgramReader& operator=(const ProgramReader&) = delete;
    // Reads the next line. At the end of the stream closes the program (a program cut short
    // throws) and returns false; every later call returns false.
    bool advance();
    // Reads the rest.
    void read_all();
    // The coarsest resolution in effect in the lines read so far.
    ReadResolution coarsest_resolution() const;

private:
    std::istream& in_;
    ReadEventSink& sink_;
    std::unique_ptr<reader::NcReader> reader_;
    std::string buffer_;  // a block of the stream; lines are cut from it
    std::size_t next_ = 0;  // where the next line starts in buffer_
    bool done_ = false;
    InputBounds bounds_;    // the bytes read and the length of a line, within their limits
    long line_ = 0;         // lines handed on
};

// Reads a program as read_program does, handing each event to `sink` as it is read.
void read_program(std::string_view text, const Machine& machine, const std::string& source, ReadEventSink& sink,
                  ReadResolution* resolution = nullptr);

// Reads an NC program written for `machine`. `source` names the program in messages. When
// `resolution` is given it receives the coarsest resolution the program used (an ISO program
// may switch to inch with G20). Throws
// InputError ("SOURCE:LINE: detail") for any word or code the machine's dialect does not
// write, for motion the machine cannot make (an arc in a plane it lacks, a helix where it has
// none) and for motion from an unknown position; nothing is skipped silently. Throws
// InputError when the machine's dialect has no reader.
std::vector<ReadEvent> read_program(std::string_view text, const Machine& machine, const std::string& source = {},
                                    ReadResolution* resolution = nullptr);

// The resolution of the values in a program for `machine` (in its own units).
ReadResolution read_resolution(const Machine& machine);

// True when camgen can read programs of this dialect ("iso", "nccad", "sinumerik", "heidenhain").
bool has_reader(const std::string& dialect);

}  // namespace camgen
