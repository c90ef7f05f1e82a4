#include "camgen/cli/cli.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <limits>
#include <numbers>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "camgen/analysis/backplot.hpp"
#include "camgen/analysis/backplot_html.hpp"
#include "camgen/common/error.hpp"
#include "camgen/common/file_kind.hpp"
#include "camgen/common/input_file.hpp"
#include "camgen/events/events.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/machine_sources.hpp"
#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/cli/output.hpp"
#include "camgen/cli/dxf_commands.hpp"
#include "camgen/dxf/dxf.hpp"
#include "camgen/post/post.hpp"
#include "camgen/post/capabilities.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/reader/tool_table.hpp"
#include "camgen/schema/schema.hpp"
#include "camgen/simulation/design_check.hpp"
#include "camgen/simulation/design_check_lathe.hpp"
#include "camgen/cli/operation_lines.hpp"
#include "camgen/simulation/simulation.hpp"
#include "camgen/simulation/pictures.hpp"
#include "camgen/operations/design.hpp"
#include "camgen/geometry/region.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/analysis/stats.hpp"
#include "src/cli/man.hpp"
#include "camgen/post/safety.hpp"

#ifndef CAMGEN_VERSION
#define CAMGEN_VERSION "0.0.0"
#endif

namespace camgen {

namespace {

struct Options {
    std::string job;
    std::string machine;
    std::string output = "-";
    bool snippet = false;
    bool events = false;
    bool list_machines = false;
    bool describe_json = false;
    std::string describe;
    std::string units;
    std::string plot;   // SVG backplot of the program as read back
    bool stats = false; // statistics of the program as read back, to stderr
    JobLimits limits;   // how large a job may be (--max-holes, --max-elements)
    std::string tools;  // --tools: the tool library (a file or a folder)
    bool quiet = false; // no notes on stderr (warnings and errors still)
};

// `camgen verify PROGRAM --machine M [--job JOB] [--plot F.svg] [--tool-table F [--tool-table-units inch]]`
struct VerifyOptions {
    std::string program;
    std::string machine;
    std::string job;
    std::string plot;
    std::string units;
    std::string tool_table;                // the control's tool table (LinuxCNC's format): G41/G42 radii
    std::string tool_table_units = "mm";   // its lengths
    std::string tools;                     // --tools: the job's tool library
};

// `camgen simulate PROGRAM --machine M --job JOB (--stock-box ... | --bar ...) [--resolution MM]`
struct SimulateOptions {
    std::string program;
    std::string machine;
    std::string job;
    std::string stock_box;  // "x0,y0,z0,x1,y1,z1", mm
    std::string bar;        // "D,L[,FACEZ]", mm
    double resolution = 0.0;
    std::string tools;    // --tools: the job's tool library
    std::string png;      // --png: the top view (and section) or the half-section
    std::string section;  // --section "x0,y0,x1,y1", mm
    std::string plot;     // --plot: the HTML page
    std::string stl;      // --stl: the part as a binary STL
};

// True for a file that can be read more than once: not a pipe (`camgen verify <(...)`), FIFO
// or device.
bool is_regular(const std::string& file) {
    std::error_code ec;
    return std::filesystem::is_regular_file(file, ec);
}

// Opens a file to read; a folder is refused by name (reading one gives nothing, not an error).
std::unique_ptr<std::ifstream> open_to_read(const std::string& file) {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) throw IoError(fmt::format("cannot read {}: {}", file, std::strerror(EISDIR)));
    auto f = std::make_unique<std::ifstream>(file, std::ios::binary);
    if (!*f) throw IoError(fmt::format("cannot read {}: {}", file, std::strerror(errno)));
    return f;
}

// The regular files read so far (the job, the machine's files, the program, the tool table),
// each with what it is: no output may replace one of them.
class Inputs {
public:
    explicit Inputs(std::istream& in) : in_(in) {}
    // Reads an input within the limits (read_input), noting it where it is a regular file.
    InputText read(const std::string& file, const std::string& role, const InputRules& rules) {
        InputText input = read_input(file, rules, in_);
        note(file, role, input.id);
        return input;
    }
    // Notes a file read in another way ("-": standard input, a regular file when it is one).
    void note(const std::string& file, const std::string& role, std::optional<FileId> id = std::nullopt) {
        if (file == "-") id = &in_ == &std::cin ? standard_input_id() : std::nullopt;
        else if (!id) id = regular_file_id(file);
        if (id) files_.push_back({role + " " + (file == "-" ? std::string("(standard input)") : file), *id});
    }
    void note(const std::vector<MachineSource>& sources) {
        for (const MachineSource& m : sources) files_.push_back({"the machine file " + m.file, m.id});
    }
    // Refuses (UsageError, before anything is written) an output that is one of the inputs, or
    // two outputs that are one file: `outputs` are (option, file) pairs, "-" and "" left out.
    // Standard output (`out`, where it is the process's) is an output too: `>> job.json`.
    void check_outputs(const std::vector<std::pair<std::string, std::string>>& outputs, const std::ostream& out) const {
        if (&out == &std::cout)
            if (const std::optional<FileId> id = standard_output_id())
                for (const auto& [what, input] : files_)
                    if (input == *id)
                        throw UsageError(fmt::format("standard output is {} (the same file): camgen never writes over its "
                                                     "input; send the output elsewhere",
                                                     what));
        for (std::size_t i = 0; i < outputs.size(); ++i) {
            const auto& [option, file] = outputs[i];
            if (file.empty() || file == "-") continue;
            const std::optional<FileId> id = regular_file_id(file);
            if (id)
                for (const auto& [what, input] : files_)
                    if (input == *id)
                        throw UsageError(fmt::format("{} {} would replace {} (the same file): camgen never writes over "
                                                     "its input; give another output file",
                                                     option, file, what));
            for (std::size_t j = 0; j < i; ++j) {
                const auto& [other_option, other] = outputs[j];
                if (other.empty() || other == "-") continue;
                if (id ? id == regular_file_id(other) : same_new_file(file, other))
                    throw UsageError(fmt::format("{} {} and {} {} are the same file: give each output its own",
                                                 other_option, other, option, file));
            }
        }
    }

private:
    // Two names of a file that does not exist yet, or is not a regular file.
    static bool same_new_file(const std::string& a, const std::string& b) {
        std::error_code ec1, ec2;
        const auto ca = std::filesystem::weakly_canonical(a, ec1), cb = std::filesystem::weakly_canonical(b, ec2);
        return !ec1 && !ec2 && ca == cb && !std::filesystem::exists(ca, ec1);
    }
    std::istream& in_;
    std::vector<std::pair<std::string, FileId>> files_;
};

// The rules of a job's or a tool table's text (JSON, NUL bytes counted, not kept).
InputRules json_input() { return InputRules{.json = true}; }
// The rules of a program kept in memory, or of a tool table: each line within max_program_line.
InputRules program_input() { return InputRules{.max_line = max_program_line}; }

// Reads a job's text into a Job; a file that is not JSON (a drawing, an NC program, a binary
// file, nothing) is named as such after the JSON parse failed.
Job parse_job(const InputText& input, const std::string& file, const JobLimits& limits, const std::string& machine,
              const ToolLibraryOptions& tools) {
    const std::string source = file == "-" ? "<stdin>" : file;
    try {
        return read_job(input.text, source, limits, tools);
    } catch (const InputError& e) {
        if (e.path().empty())
            if (auto what = not_json(input.text, input.cut, source, "job", machine)) throw InputError("", *what, 0, source);
        throw;
    }
}

// Where the job's library tools come from (--tools, else the search) and the bounds of the
// machine (none: --events) on the speeds and feeds computed from their cutting data.
ToolLibraryOptions library_options(const std::string& tools, const Machine* machine) {
    ToolLibraryOptions options;
    options.file = tools;
    if (machine) {
        options.max_rpm = machine->limits.max_rpm;
        options.max_feed = machine->limits.max_feed;
        options.machine = machine->name;
    }
    return options;
}

// The job's stock bar for a lathe's backplot (none: the job gives no bar).
std::optional<BackplotBar> backplot_bar(const Job& job) {
    if (!job.stock || job.stock->shape != StockShape::bar) return std::nullopt;
    const Stock& s = *job.stock;
    return BackplotBar{s.diameter, s.length, s.face_z, s.bore_diameter};
}

std::string job_stem(const std::string& file) {
    if (file == "-") return "job";
    std::string s = file.substr(file.find_last_of('/') + 1);
    if (auto dot = s.find_last_of('.'); dot != std::string::npos && dot > 0) s.resize(dot);
    return s;
}

// An error raised after reading (by a post) knows its JSON path but not its line: find it.
InputError locate(const InputError& e, const std::string& source, const std::string& text) {
    if (!e.source().empty() || e.line() > 0) return e;
    json::LineMap lines(text);
    std::string p = e.path();
    int line = 0;
    while (true) {
        line = lines.line_of(p);
        if (line > 0 || p.empty()) break;
        p.resize(p.find_last_of('/'));
    }
    return e.located(source == "-" ? "<stdin>" : source, line);
}

// Sets the machine's units from --units; a usage error where its control has no such mode.
void apply_units(Machine& machine, const std::string& units) {
    if (units.empty()) return;
    const Units u = units == "inch" ? Units::inch : Units::mm;
    if (!machine.accepts(u))
        throw UsageError(fmt::format("--units {}: machine {} has no {} mode (its control accepts: {})", units,
                                     machine.name, units, machine.accepted_unit_names()));
    machine.units = u;
}

// The machine of --machine (loaded once: its file may be a pipe) with --units applied.
Machine machine_for(const Machine& loaded, const Options& o) {
    Machine machine = loaded;
    apply_units(machine, o.units);
    return machine;
}

// A stream buffer of 1 MB blocks, for a program that is written out only once it is complete:
// a large program is held once, and never copied as a growing string is.
class BlockBuffer : public std::streambuf {
public:
    BlockBuffer() { next_block(); }
    // Writes the blocks to `out`, in order.
    void write_to(std::ostream& out) const {
        for (std::size_t i = 0; i < blocks_.size(); ++i) {
            const std::size_t size = i + 1 < blocks_.size() ? block_size : static_cast<std::size_t>(pptr() - pbase());
            out.write(blocks_[i].get(), static_cast<std::streamsize>(size));
        }
    }

protected:
    int_type overflow(int_type c) override {
        if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
        if (pptr() == epptr()) next_block();
        *pptr() = traits_type::to_char_type(c);
        pbump(1);
        return c;
    }

private:
    static constexpr std::size_t block_size = std::size_t{1} << 20;
    void next_block() {
        blocks_.push_back(std::make_unique_for_overwrite<char[]>(block_size));
        setp(blocks_.back().get(), blocks_.back().get() + block_size);
    }
    std::vector<std::unique_ptr<char[]>> blocks_;
};

// The stock as the first line of --events: {"event": "stock", "shape": ..., "path": ..., its
// bounding box "min" and "max" (mm), and a bar's sizes}.
std::string stock_json(const Stock& stock) {
    nlohmann::ordered_json j;
    j["event"] = "stock";
    j["shape"] = stock.shape == StockShape::box ? "box" : stock.shape == StockShape::profile ? "profile" : "bar";
    j["path"] = stock.path;
    j["min"] = {stock.min.x, stock.min.y, stock.min.z};
    j["max"] = {stock.max.x, stock.max.y, stock.max.z};
    if (stock.shape == StockShape::bar) {
        j["diameter"] = stock.diameter;
        j["length"] = stock.length;
        j["faceZ"] = stock.face_z;
        if (stock.bore_diameter) j["boreDiameter"] = *stock.bore_diameter;
    }
    return j.dump();
}

// The holes the job's drill and bore-mill operations make, each a hole the safety check logs,
// and a few for the plunges of other operations.
std::size_t drilled_holes(const Job& job) {
    std::size_t holes = 64;
    for (const Operation& op : job.operations) {
        if (const auto* drill = std::get_if<DrillOp>(&op)) holes += drill->holes.size();
        if (const auto* bore = std::get_if<BoreMillOp>(&op)) holes += bore->holes.size();
        if (const auto* thread = std::get_if<ThreadMillOp>(&op)) holes += thread->holes.size();
        if (const auto* chamfer = std::get_if<ChamferOp>(&op)) holes += chamfer->holes.size();
    }
    return holes;
}

// Posts the job into `out`. Unless `out` discards what it got when the run fails (a temporary
// file), the program is held until it is complete, so that a failure writes nothing.
void write_program(const Job& job, const Options& o, const Machine* loaded, std::ostream& out, std::ostream& err,
                   bool out_discards_failures) {
    if (o.events) {
        // The job's stock first, where it gives one: what the events cut.
        if (job.stock) out << stock_json(*job.stock) << '\n';
        EventPrinter printer(out);
        expand_job(job, printer);
        return;
    }
    Machine machine = machine_for(*loaded, o);
    check_machine_kind(job, machine.kind, machine.name);
    PostOptions po;
    po.snippet = o.snippet;
    po.program_name = job.name;
    po.warnings = &err;
    po.notes = o.quiet ? nullptr : &err;
    po.work_offset = job.work_offset;
    po.program_number = job.program_number;
    // Every event is checked before the post sees it, and the post writes into a buffer: an
    // unsafe job, or a cycle a post refuses half-way, writes nothing.
    SafetyLimits limits{job.clearance, {}, machine.longhand(), machine.kind, machine.rough_pattern()};
    for (const auto& [number, tool] : job.tools)
        if (tool.flute_length) limits.flute_lengths[number] = *tool.flute_length;
    std::optional<BlockBuffer> blocks;
    std::optional<std::ostream> buffer;
    if (!out_discards_failures) buffer.emplace(&blocks.emplace());
    std::unique_ptr<Post> post = make_post(machine, out_discards_failures ? out : *buffer, po);
    SafetyCheck check(limits);
    check.reserve_holes(drilled_holes(job));
    if (job.stock && job.stock->for_mill()) check.warn_below_stock(job.stock->bottom(), err);
    // Passes each event through the check, then to the post.
    struct Checked : EventSink {
        SafetyCheck& check;
        Post& post;
        Checked(SafetyCheck& c, Post& p) : check(c), post(p) {}
        void emit(const Event& e) override {
            check.emit(e);
            post.emit(e);
        }
    } checked(check, *post);
    post->open();
    expand_job(job, checked);
    check.finish();
    post->close();
    if (blocks) blocks->write_to(out);
    out.flush();
    if (!out) throw IoError("cannot write the program", errno);
}

// Flushes a stream that is not a file of ours (standard output) and reports a failed write
// with the system's reason: a full disk or /dev/full must not end in exit 0.
void finish_stream(std::ostream& out, const std::string& name) {
    errno = 0;
    out.flush();
    if (!out) {
        const int error = errno ? errno : EIO;
        throw IoError(fmt::format("cannot write {}: {}", name, std::strerror(error)), error);
    }
}

std::string base_name(const std::string& file) { return file.substr(file.find_last_of('/') + 1); }

// Reading a program back for its statistics and a --plot file, in passes over it: `pass` reads
// the program once into a sink (the file again, or the text kept) and returns the coarsest
// resolution it used. The first pass measures the program and plans the drawing, a second
// draws the SVG or the HTML page's drawing, and a third writes the page's block data.
class ReadBack {
public:
    using Pass = std::function<ReadResolution(ReadEventSink&)>;
    ReadBack(const Machine& machine, const std::string& plot_file, Pass pass, TraceOptions options)
        : machine_(machine), html_(!plot_file.empty() && is_html_plot(plot_file)), pass_(std::move(pass)),
          options_(std::move(options)), stats_(machine), plan_(machine.kind) {
        std::vector<TraceSink*> sinks{&stats_};
        if (!plot_file.empty()) sinks.push_back(&plan_);
        TraceFanOut fan(std::move(sinks));
        TraceBuilder trace(machine_, fan, options_);
        resolution_ = pass_(trace);
        notes_ = trace.notes();
    }
    const ProgramStats& stats() const { return stats_.stats(); }
    // What the trace took as given (a G41/G42 radius it does not know).
    const std::vector<std::string>& notes() const { return notes_; }
    ReadResolution resolution() const { return resolution_; }
    // Writes the --plot file: the HTML page (it shows the text that `program` opens at its
    // start) or the SVG drawing.
    void write_plot(std::ostream& out, const std::function<std::istream&()>& program, const BackplotOptions& options) {
        if (html_) {
            HtmlPlot page(plan_, stats(), options);
            const auto read = [&](TraceSink& sink) {
                TraceBuilder trace(machine_, sink, options_);
                (void)pass_(trace);
            };
            read(page);
            page.write(out, program, read);
            return;
        }
        BackplotDrawer drawer(plan_, stats(), options);
        TraceBuilder trace(machine_, drawer, options_);
        (void)pass_(trace);
        out << drawer.take().svg;
    }

private:
    const Machine& machine_;
    bool html_;
    Pass pass_;
    TraceOptions options_;
    std::vector<std::string> notes_;
    StatsAccumulator stats_;
    BackplotPlan plan_;
    ReadResolution resolution_;
};

// `camgen verify`: reads a program back, prints what it does, and compares it with a job.
// --list-machines: a line a machine, its name first (shell completion reads the first word),
// then its description and where it comes from. A user's file that cannot be read is listed
// with the reason, so that the list still shows the rest.
std::string machine_list() {
    const std::vector<MachineEntry> entries = machine_catalogue();
    std::size_t width = 0;
    for (const auto& e : entries) width = std::max(width, e.name.size());
    std::string s;
    for (const auto& e : entries) {
        std::string description;
        try {
            description = (e.text ? parse_machine(e.text, e.name, e.origin) : load_machine(e.path)).description;
        } catch (const std::exception& ex) {
            description = fmt::format("(cannot be read: {})", ex.what());
        }
        std::string origin = e.origin;
        if (e.shadowed) origin += ", replaced by the file of this name above";
        s += fmt::format("{:<{}}  {}  [{}]\n", e.name, width, description, origin);
    }
    return s;
}

// A read-only stream buffer over text that is kept elsewhere (standard input's program, or the
// program just posted, read again).
class TextBuffer : public std::streambuf {
public:
    explicit TextBuffer(std::string_view text) {
        char* begin = const_cast<char*>(text.data());  // never written: the buffer has no put area
        setg(begin, begin, begin + text.size());
    }
};

// Opens text kept in memory as a stream at its start, again at each call.
class TextStream {
public:
    explicit TextStream(std::string_view text) : text_(text) {}
    std::istream& open() {
        stream_.reset();
        buffer_.emplace(text_);
        stream_.emplace(&*buffer_);
        return *stream_;
    }

private:
    std::string_view text_;
    std::optional<TextBuffer> buffer_;
    std::optional<std::istream> stream_;
};

// The program verify reads back, once for each pass over it: a file is opened again for each;
// standard input, a pipe, a FIFO or a device cannot be read twice, so its text is kept when a
// second pass needs it.
class ProgramInput {
public:
    ProgramInput(const std::string& file, std::istream& in, bool several_passes) : file_(file), in_(in) {
        if (several_passes && (file == "-" || !is_regular(file))) {
            text_ = read_input(file, program_input(), in).text;
            kept_.emplace(*text_);
        } else if (file != "-") {
            // A regular file is read as a stream in each pass; its size is known before.
            std::error_code ec;
            const std::uintmax_t size = is_regular(file) ? std::filesystem::file_size(file, ec) : 0;
            if (!ec && size > max_input_size())
                throw IoError(fmt::format("cannot read {}: it is {}, larger than {}, the limit for an input "
                                          "(CAMGEN_MAX_INPUT_SIZE changes it)",
                                          file, size_text(size), size_text(max_input_size())));
        }
    }
    ProgramInput(const ProgramInput&) = delete;  // kept_ views text_
    ProgramInput& operator=(const ProgramInput&) = delete;
    // A stream at the program's start.
    std::istream& open() {
        if (kept_) return kept_->open();
        if (file_ == "-") return in_;
        stream_ = open_to_read(file_);
        return *stream_;
    }

private:
    std::string file_;
    std::istream& in_;
    std::optional<std::string> text_;
    std::optional<TextStream> kept_;  // over text_
    std::unique_ptr<std::istream> stream_;
};

// Compares the program with the job's events in a pass of its own: the job leads, and the
// program is read as far as the comparison needs it.
std::optional<Mismatch> compare_with_job(ProgramInput& program, const std::string& source, const Job& job,
                                         const Machine& machine, const CompareTolerance& tolerance,
                                         const TraceOptions& options, double rounding) {
    std::unique_ptr<ProgramReader> reader;
    TraceComparer comparer(tolerance, [&] { return reader->advance(); });
    TraceBuilder program_trace(machine, comparer.actual(), options);
    reader = std::make_unique<ProgramReader>(program.open(), machine, source, program_trace);
    FeedClamp clamp(machine, comparer.expected());
    TraceBuilder job_trace(machine, clamp,
                           TraceOptions{.compensation_radii = {}, .rounding = rounding, .compensation_orientations = {},
                                        .work_offset = job.work_offset});
    // The job's events one at a time; once the first difference is known the rest says nothing.
    struct Expected : EventSink {
        TraceComparer& comparer;
        TraceBuilder& trace;
        Expected(TraceComparer& c, TraceBuilder& t) : comparer(c), trace(t) {}
        void emit(const Event& e) override {
            if (!comparer.decided()) trace.add_job_event(e);
        }
    } expected(comparer, job_trace);
    expand_job(job, expected);
    job_trace.finish();
    return comparer.mismatch();
}

// The radius of each offset register (D) that a program written for `job` offsets by: the radius
// the job's own G41/G42 carry (its tool's radius where the control offsets, 0 where it only adds
// the wear), else the radius of the job's tool of that number.
std::map<int, double> job_compensation_radii(const Job& job) {
    std::map<int, double> radii;
    for (const auto& [number, tool] : job.tools)
        if (tool.diameter > 0) radii[number] = tool.diameter / 2;
    struct Radii : EventSink {
        std::map<int, double> given;
        int tool = 0;
        void emit(const Event& e) override {
            if (const auto* t = std::get_if<ToolChange>(&e)) tool = t->number;
            const auto* c = std::get_if<Compensation>(&e);
            if (!c || c->side == CompensationSide::off) return;
            double& r = given.try_emplace(c->d_register != 0 ? c->d_register : tool, 0.0).first->second;
            r = std::max(r, c->radius);  // a register the job offsets by in full, and elsewhere by the wear only, is the radius
        }
    } events;
    expand_job(job, events);
    for (const auto& [reg, radius] : events.given) radii[reg] = radius;
    return radii;
}

// The tip orientation of each lathe tool of `job` that has one (a program's G41/G42 in G18: the
// point the control moves is that tip).
std::map<int, int> job_compensation_orientations(const Job& job) {
    std::map<int, int> out;
    for (const auto& [number, tool] : job.tools)
        if (tool.orientation != 0) out[number] = tool.orientation;
    return out;
}

TraceOptions job_trace_options(const Job& job) {
    TraceOptions options{job_compensation_radii(job)};
    options.compensation_orientations = job_compensation_orientations(job);
    return options;
}

// Where a program's G41/G42 radii come from: verify --tool-table (its text), else the job's.
TraceOptions program_trace_options(const VerifyOptions& v, const Job* job, const std::string& tool_table) {
    TraceOptions options;
    if (!v.tool_table.empty()) {
        const std::string& text = tool_table;
        for (const auto& [number, diameter] :
             read_tool_table(text, v.tool_table == "-" ? "<stdin>" : v.tool_table,
                             v.tool_table_units == "inch" ? Units::inch : Units::mm))
            options.compensation_radii[number] = diameter / 2;
    } else if (job) {
        options.compensation_radii = job_compensation_radii(*job);
    }
    if (job) options.compensation_orientations = job_compensation_orientations(*job);
    return options;
}

int run_verify(const VerifyOptions& v, std::istream& in, std::ostream& out) {
    Inputs inputs(in);
    std::vector<MachineSource> machine_files;
    Machine machine = load_machine(v.machine, machine_files);
    inputs.note(machine_files);
    apply_units(machine, v.units);
    if (v.program == "-" && v.job == "-") throw UsageError("the program and the job cannot both come from standard input");
    if (v.tool_table == "-" && (v.program == "-" || v.job == "-"))
        throw UsageError("only one of the program, the job and the tool table can come from standard input");
    std::string source = v.program == "-" ? "<stdin>" : v.program;
    // Every input is read (the program is named) before the plot may be written.
    inputs.note(v.program, "the program");
    InputText job_input;
    if (!v.job.empty()) job_input = inputs.read(v.job, "the job", json_input());
    const std::string& job_text = job_input.text;
    std::string tool_table;
    if (!v.tool_table.empty()) tool_table = inputs.read(v.tool_table, "the tool table", program_input()).text;
    inputs.check_outputs({{"--plot", v.plot}}, out);
    // The job first: its tools give the radii of the program's G41/G42.
    std::optional<Job> job;
    if (!v.job.empty()) {
        try {
            job = parse_job(job_input, v.job, JobLimits{}, v.machine, library_options(v.tools, &machine));
            check_machine_kind(*job, machine.kind, machine.name);
        } catch (const InputErrors&) {
            throw;  // each located already
        } catch (const InputError& e) {
            throw locate(e, v.job, job_text);
        }
    }
    const TraceOptions options = program_trace_options(v, job ? &*job : nullptr, tool_table);
    // The program is read as a stream, never whole, in passes (ReadBack; compare_with_job; the
    // HTML page's copy of the text).
    ProgramInput program(v.program, in, !v.job.empty() || !v.plot.empty());
    std::optional<ReadBack> back;
    try {
        back.emplace(machine, v.plot, [&](ReadEventSink& sink) {
            ProgramReader reader(program.open(), machine, source, sink);
            reader.read_all();
            return reader.coarsest_resolution();
        }, options);
    } catch (const ControlRefusal& e) {
        // The control would stop there: with a job that is the first difference.
        if (!job) throw e.located(source, e.line());
        out << fmt::format("{} on machine {}\n", source, machine.name)
            << fmt::format("MISMATCH {}{}: {}\n", source, e.line() > 0 ? fmt::format(":{}", e.line()) : "", e.detail());
        finish_stream(out, "standard output");
        return exit_invalid_input;
    }
    out << fmt::format("{} on machine {}\n", source, machine.name) << format_stats(back->stats());
    for (const std::string& note : back->notes()) out << "note: " << note << '\n';
    if (!v.plot.empty()) {
        OutputFile plot(v.plot);
        BackplotOptions plot_options;
        plot_options.title = base_name(source), plot_options.machine = machine.name, plot_options.kind = machine.kind;
        if (job) plot_options.bar = backplot_bar(*job);
        back->write_plot(plot.stream(), [&]() -> std::istream& { return program.open(); }, plot_options);
        plot.commit();
    }
    if (!job) {
        finish_stream(out, "standard output");
        return exit_ok;
    }
    try {
        CompareTolerance tolerance = compare_tolerance(machine, back->resolution());
        if (auto m = compare_with_job(program, source, *job, machine, tolerance, options, back->resolution().position)) {
            out << fmt::format("MISMATCH {}{}: {}\n", source, m->line > 0 ? fmt::format(":{}", m->line) : "", m->message);
            finish_stream(out, "standard output");
            return exit_invalid_input;
        }
        out << fmt::format("matches job {}: the same moves within {} mm (inside arcs {} mm), the same feeds, dwells, "
                           "tools, tool length and work offsets, and spindle\n",
                           v.job, fmt::format("{:.4f}", tolerance.position), fmt::format("{:.4f}", tolerance.path));
        finish_stream(out, "standard output");
    } catch (const InputError& e) {
        throw locate(e, v.job, job_text);
    }
    return exit_ok;
}

// The numbers of a comma-separated option, `count` of them (or `count - optional` or more).
std::vector<double> option_numbers(const std::string& text, const char* option, std::size_t count, std::size_t optional,
                                   const char* form) {
    std::vector<double> values;
    std::size_t at = 0;
    while (at <= text.size()) {
        const std::size_t end = std::min(text.find(',', at), text.size());
        const std::string part = text.substr(at, end - at);
        char* stop = nullptr;
        const double v = std::strtod(part.c_str(), &stop);
        if (part.empty() || stop != part.c_str() + part.size() || !std::isfinite(v))
            throw UsageError(fmt::format("{} takes {} in mm, not \"{}\"", option, form, text));
        values.push_back(v);
        at = end + 1;
    }
    if (values.size() > count || values.size() + optional < count)
        throw UsageError(fmt::format("{} takes {} in mm, not \"{}\"", option, form, text));
    return values;
}

// `camgen simulate`: the program read back and swept through the stock; exit 1 on an error.
// The simulated part against the job's design (a mill's): each finding a line, gouges as
// errors ("error: ... gouge"), material left as warnings. The design and its wall probes are
// made once the simulator has laid out its field, before the sweep; the report after it.
struct SimDesignCheck {
    PartDesign design;
    HeightGridView grid;
    DesignProbes probes;
    double tolerance = 0.0, margin = 0.0;
};

std::optional<SimDesignCheck> prepare_design_check(const Job& job, const Machine& machine, const SimStock& stock,
                                                   Simulator& sim) {
    const SimResult& r = sim.result();
    if (r.kind != MachineKind::mill || r.field.heights.empty()) return std::nullopt;
    const HeightField& f = r.field;
    SimDesignCheck c;
    c.design = part_design(job);
    leave_out_operator_cycles(c.design, job, machine);
    HeightGridView& g = c.grid;
    g.x0 = f.x0, g.y0 = f.y0, g.cell = f.cell, g.nx = static_cast<std::size_t>(f.nx), g.ny = static_cast<std::size_t>(f.ny);
    g.top = f.top;
    g.bottom = f.bottom;
    if (stock.kind == SimStock::Kind::profile) {
        g.stock = PlaneRegion{stock.profile, {}};
    } else {
        // The field's last row and column may reach beyond the box: no stock there.
        const double x0 = std::min(stock.min.x, stock.max.x), x1 = std::max(stock.min.x, stock.max.x);
        const double y0 = std::min(stock.min.y, stock.max.y), y1 = std::max(stock.min.y, stock.max.y);
        Profile box;
        box.start = {x0, y0};
        box.segments = {{{x1, y0}}, {{x1, y1}}, {{x0, y1}}, {{x0, y0}}};
        g.stock = PlaneRegion{box, {}};
    }
    // As verify compares: the position, the machine's tolerance and its chords.
    c.tolerance = compare_tolerance(machine).path;
    c.margin = f.cell * std::numbers::sqrt2 / 2.0 + c.tolerance;
    c.probes = design_probes(c.design, g, c.tolerance, c.margin, std::max<std::size_t>(r.cells / 4, 1000));
    sim.set_probes(c.probes.points);
    return c;
}

// Returns the gouges' count.
std::size_t design_check_report(SimDesignCheck& c, const SimResult& r, std::ostream& out) {
    const HeightField& f = r.field;
    HeightGridView& g = c.grid;
    g.height = [&](std::size_t i, std::size_t j) { return static_cast<double>(f.heights[j * g.nx + i]); };
    g.line = [&](std::size_t i, std::size_t j) { return static_cast<int>(f.lines[j * g.nx + i]); };
    const std::vector<DesignFinding> found =
        check_design(c.design, g, c.tolerance, c.margin, ProbeHeights{&c.probes, &r.probe_heights, &r.probe_lines});
    std::size_t gouges = 0;
    out << fmt::format("design check   {} cuts, {} keeps, within {} mm, cells farther than {} mm inside their regions, "
                       "{} points on the walls {} mm apart\n",
                       design_cut_count(c.design), design_keep_count(c.design), number_text(c.tolerance), number_text(c.margin),
                       c.probes.points.size(), number_text(c.probes.spacing, 3));
    for (const std::string& u : c.design.unchecked) out << "  not checked: " << u << '\n';
    for (const DesignFinding& d : found) {
        const bool gouge = d.kind == DesignFinding::Kind::gouge;
        gouges += gouge;
        out << (gouge ? "error: gouge: " : "warning: ") << d.message() << '\n';
    }
    if (found.empty()) out << "  the part is as designed\n";
    return gouges;
}

int run_simulate(const SimulateOptions& v, std::istream& in, std::ostream& out) {
    Inputs inputs(in);
    std::vector<MachineSource> machine_files;
    const Machine machine = load_machine(v.machine, machine_files);
    inputs.note(machine_files);
    if (v.program == "-" && v.job == "-") throw UsageError("the program and the job cannot both come from standard input");
    const std::string source = v.program == "-" ? "<stdin>" : v.program;
    inputs.note(v.program, "the program");
    const InputText job_input = inputs.read(v.job, "the job", json_input());
    SimStock stock;
    if (!v.stock_box.empty() && !v.bar.empty()) throw UsageError("simulate takes one stock: --stock-box or --bar, not both");
    if (!v.stock_box.empty()) {
        if (machine.kind == MachineKind::lathe) throw UsageError(fmt::format("{} is a lathe: its stock is a --bar", machine.name));
        const auto n = option_numbers(v.stock_box, "--stock-box", 6, 0, "x0,y0,z0,x1,y1,z1");
        stock.kind = SimStock::Kind::box;
        stock.min = {n[0], n[1], n[2]};
        stock.max = {n[3], n[4], n[5]};
    } else if (!v.bar.empty()) {
        if (machine.kind != MachineKind::lathe) throw UsageError(fmt::format("{} is a mill: its stock is a --stock-box", machine.name));
        const auto n = option_numbers(v.bar, "--bar", 3, 1, "D,L[,FACEZ]");
        stock.kind = SimStock::Kind::bar;
        stock.bar_diameter = n[0];
        stock.bar_length = n[1];
        stock.face_z = n.size() > 2 ? n[2] : 0.0;
    }
    if (!(v.resolution >= 0)) throw UsageError("--resolution takes a length above 0 in mm");
    // The pictures' options, and no output over an input or another output, before anything is read.
    std::optional<SectionLine> section;
    if (!v.section.empty()) {
        if (machine.kind == MachineKind::lathe)
            throw UsageError(fmt::format("{} is a lathe: --section is a mill's picture (a lathe's --png and --plot show its "
                                         "half-section)", machine.name));
        if (v.png.empty() && v.plot.empty()) throw UsageError("--section is drawn in the --png picture or the --plot page: give one");
        const auto n = option_numbers(v.section, "--section", 4, 0, "x0,y0,x1,y1");
        section = SectionLine{{n[0], n[1]}, {n[2], n[3]}};
        if (!(distance(section->a, section->b) > 0)) throw UsageError("--section takes two different points");
    }
    if (!v.plot.empty() && !is_html_plot(v.plot)) throw UsageError(fmt::format("--plot writes an HTML page: {} must end in .html", v.plot));
    inputs.check_outputs({{"--png", v.png}, {"--plot", v.plot}, {"--stl", v.stl}}, out);
    std::optional<Job> job;
    try {
        job = parse_job(job_input, v.job, JobLimits{}, v.machine, library_options(v.tools, &machine));
        check_machine_kind(*job, machine.kind, machine.name);
    } catch (const InputErrors&) {
        throw;
    } catch (const InputError& e) {
        throw locate(e, v.job, job_input.text);
    }
    if (v.stock_box.empty() && v.bar.empty()) {
        // The job's own stock (read and checked against the machine's kind with the job).
        if (!job->stock)
            throw UsageError(fmt::format("simulate needs the stock: the job's \"stock\" (a box, a profile or a lathe's bar), "
                                         "or --stock-box x0,y0,z0,x1,y1,z1 for a mill or --bar D,L[,FACEZ] for a lathe"));
        const Stock& js = *job->stock;
        switch (js.shape) {
            case StockShape::box:
                stock.kind = SimStock::Kind::box;
                stock.min = js.min;
                stock.max = js.max;
                break;
            case StockShape::profile:
                stock.kind = SimStock::Kind::profile;
                stock.profile = js.outline;
                stock.top = js.top();
                stock.bottom = js.bottom();
                stock.min = js.min;
                stock.max = js.max;
                break;
            case StockShape::bar:
                stock.kind = SimStock::Kind::bar;
                stock.bar_diameter = js.diameter;
                stock.bar_length = js.length;
                stock.face_z = js.face_z;
                stock.bore_diameter = js.bore_diameter;
                break;
        }
    }
    SimOptions options;
    options.resolution = v.resolution;
    // The operation each line belongs to: the program against the job posted again.
    ProgramInput program(v.program, in, true);
    const OperationLines ops = operation_lines(*job, machine, program.open());
    options.operations = ops.spans;
    std::optional<Simulator> sim;
    try {
        sim.emplace(machine, stock, job_tool_shapes(*job), options);
    } catch (const SimInputError& e) {
        throw UsageError(fmt::format("cannot simulate: {}", e.what()));
    }
    std::optional<SimDesignCheck> check = prepare_design_check(*job, machine, stock, *sim);
    // A lathe's turned part against its design (design_check_lathe.hpp).
    std::optional<LatheDesignCheck> lathe_check;
    if (machine.kind == MachineKind::lathe)
        lathe_check = prepare_lathe_design_check(*job, machine, stock, *sim);
    // The page's history of the part, told of each change as the program is swept.
    std::optional<SimHistory> history;
    if (!v.plot.empty()) {
        history.emplace(sim->result());
        sim->observe(&*history);
    }
    try {
        // The offsets the program selects against those the job's post selects: the simulation
        // sweeps the program's coordinates as written, so a move under another tool length
        // offset or work offset is an error of its own (at the first move of each run).
        OffsetCheck offsets(machine, job->work_offset, [&](const Mismatch& m, const Step& s) { sim->report_error(m.line, s.tool, m.message); });
        TraceFanOut both({&offsets, &*sim});
        TraceBuilder trace(machine, both, job_trace_options(*job));
        ProgramReader reader(program.open(), machine, source, trace);
        reader.read_all();
    } catch (const ControlRefusal& e) {
        throw e.located(source, e.line());
    } catch (const SimInputError& e) {
        throw InputError("", e.what(), 0, source);
    }
    const SimResult& r = sim->result();
    out << fmt::format("{} on machine {}\n", source, machine.name);
    if (!ops.note.empty()) out << "note: " << ops.note << '\n';
    out << format_simulation(r);
    const std::size_t gouges = check          ? design_check_report(*check, r, out)
                               : lathe_check ? report_lathe_design_check(*lathe_check, r, ops.spans, out)
                                             : 0;
    // The pictures, also of a part with errors (they show them); each written whole before
    // any replaces its file.
    const PictureLabels labels{base_name(source), machine.name};
    std::vector<std::unique_ptr<OutputFile>> pictures;
    try {
        if (!v.png.empty()) {
            pictures.push_back(std::make_unique<OutputFile>(v.png));
            write_simulation_png(r, section, labels, pictures.back()->stream());
        }
        if (!v.stl.empty()) {
            pictures.push_back(std::make_unique<OutputFile>(v.stl));
            const StlSummary stl = write_simulation_stl(r, StlOptions{}, pictures.back()->stream());
            out << fmt::format("stl: {} triangles{}\n", stl.triangles,
                               stl.block <= 1                  ? std::string()
                               : r.kind == MachineKind::lathe ? fmt::format(", bands of {} samples", stl.block)
                                                              : fmt::format(", blocks of {} x {} cells", stl.block, stl.block));
        }
        if (!v.plot.empty()) {
            history->finish(r);
            pictures.push_back(std::make_unique<OutputFile>(v.plot));
            write_simulation_html(pictures.back()->stream(), r, *history, section, labels,
                                  [&]() -> std::istream& { return program.open(); });
        }
    } catch (const SimInputError& e) {
        throw UsageError(fmt::format("cannot draw the simulation: {}", e.what()));
    }
    for (auto& p : pictures) p->commit();
    finish_stream(out, "standard output");
    return r.errors.empty() && gouges == 0 ? exit_ok : exit_invalid_input;
}

// After posting: read the program back for --stats (to `err`) and --plot (into `plot`, not
// yet committed, so that a failed plot leaves the program file as it was).
void read_back(std::string_view program, const Job& job, const Options& o, const Machine& loaded, std::ostream& err,
               std::optional<OutputFile>& plot) {
    Machine machine = machine_for(loaded, o);
    std::string name = o.output == "-" ? job.name + "." + machine.extension : base_name(o.output);
    std::optional<ReadBack> read;
    try {
        read.emplace(
            machine, o.plot,
            [&](ReadEventSink& sink) {
                ReadResolution resolution;
                read_program(program, machine, name, sink, &resolution);
                return resolution;
            },
            job_trace_options(job));
    } catch (const ControlRefusal& e) {
        throw e.located(name, e.line());
    }
    ReadBack& back = *read;
    if (o.stats) err << format_stats(back.stats());
    if (!o.quiet)
        for (const std::string& note : back.notes()) err << "camgen: note: " << note << '\n';
    if (o.plot.empty()) return;
    TextStream text(program);
    BackplotOptions plot_options;
    plot_options.title = name, plot_options.machine = machine.name, plot_options.kind = machine.kind;
    plot_options.bar = backplot_bar(job);
    back.write_plot(plot.emplace(o.plot).stream(), [&]() -> std::istream& { return text.open(); }, plot_options);
}

}  // namespace

// camgen dxf-info F.dxf: what the drawing holds.
int run_dxf_info(const std::string& file, std::ostream& out) {
    out << dxf_info_file(file);
    finish_stream(out, "standard output");
    return exit_ok;
}

// camgen new --from F.dxf [--machine M] [-o job.json]: a starter job that posts as written
// (on M when given: posted into a buffer first); the end mill the largest of 6, 5, 4, 3, 2
// and 1 mm with which the job reads (its pockets planned) and posts.
int run_new(const std::string& from, const std::string& machine_name, const std::string& output, std::ostream& out, std::ostream& err) {
    namespace fs = std::filesystem;
    if (output != "-") {
        std::error_code ec;
        if (fs::exists(output, ec) && fs::equivalent(output, from, ec)) throw UsageError("-o names the drawing: the job would replace it");
    }
    const dxf::Drawing d = dxf::read_file(from);
    std::optional<Machine> machine;
    if (!machine_name.empty()) machine = load_machine(machine_name);
    std::string dxf_path = from;
    std::string source = "new.json";
    if (output != "-") {
        source = output;
        const fs::path dir = fs::absolute(fs::path(output)).parent_path();
        dxf_path = fs::absolute(fs::path(from)).lexically_relative(dir).generic_string();
    }
    std::string last_error, text;
    std::vector<std::string> notes;
    double used = 0;
    for (double mill : {6.0, 5.0, 4.0, 3.0, 2.0, 1.0}) {
        notes.clear();
        text = starter_job_text(d, dxf_path, mill, notes);
        if (nlohmann::json::parse(text)["operations"].empty()) {
            for (const std::string& n : notes) err << "camgen: note: " << n << '\n';
            err << "camgen: " << from << " holds nothing a starter job machines: no circles and no closed profile\n";
            return exit_invalid_input;
        }
        try {
            const Job job = read_job(text, source, JobLimits{});
            if (machine) {
                Options o;
                o.machine = machine_name;
                std::ostringstream program, quiet;
                write_program(job, o, &*machine, program, quiet, false);
            }
            used = mill;
            break;
        } catch (const InputError& e) {
            last_error = e.what();
        }
    }
    if (used == 0) {
        // (The line is the starter job's, which is not written.)
        err << "camgen: the starter job from " << from << " does not " << (machine ? "post" : "read")
            << " (not written; the line is the one it would have): " << last_error << '\n';
        return exit_invalid_input;
    }
    if (used < 6.0) notes.push_back(fmt::format("the end mill is {} mm: a larger one does not fit the pockets", number_text(used, 1)));
    for (const std::string& n : notes) err << "camgen: note: " << n << '\n';
    if (output == "-") {
        out << text;
        finish_stream(out, "standard output");
    } else {
        OutputFile file(output);
        file.stream() << text;
        file.commit();
    }
    return exit_ok;
}

int run_cli(int argc, const char* const* argv, std::istream& in, std::ostream& out, std::ostream& err) {
    Options o;
    CLI::App app{"camgen: turns a JSON job into the NC program of a machine.\n"
                 "  camgen job.json --machine wabeco -o part.knc   (nccad files end in .knc)\n"
                 "  camgen job.json --machine fanuc -o part.nc\n"
                 "  camgen schema job > job.schema.json           (JSON Schema of job files; machine: of machine files)\n"
                 "Exit codes: 0 done, 1 invalid job or machine file, 2 usage, 3 file error.",
                 "camgen"};
    app.set_version_flag("--version", std::string("camgen ") + CAMGEN_VERSION);
    app.add_option("job", o.job, "The job file (JSON); - reads standard input");
    app.add_option("-m,--machine", o.machine, "Machine name (see --list-machines) or path to a machine JSON file");
    app.add_option("-o,--output", o.output,
                   "Output file, written atomically (default -: standard output), never one of the inputs; "
                   "wabeco/kosy programs end in .knc");
    app.add_flag("--snippet", o.snippet, "Clipboard export: no program start or end blocks");
    app.add_flag("--events", o.events, "Print the machine-independent events, one JSON object per line");
    app.add_option("--units", o.units, "Output units, overriding the machine file")->check(CLI::IsMember({"mm", "inch"}));
    app.add_flag("--list-machines", o.list_machines,
                 "List the machines: the user's (CAMGEN_MACHINES folders, then $XDG_CONFIG_HOME/camgen/machines) "
                 "and the built-in ones, each with its source");
    app.add_option("--describe-machine", o.describe,
                   "Print a machine's settings, drilling cycle table and capabilities (what its post makes and refuses)");
    app.add_flag("--json", o.describe_json,
                 "With --describe-machine: print JSON: \"machine\", the complete machine file (its extends applied; "
                 "a start for your own), and \"capabilities\"");
    app.add_option("--plot", o.plot,
                   "Also write a backplot of the program as read back: F.svg a drawing (XY view, a lathe's XZ "
                   "half-section), F.html an interactive page (block slider, layers, statistics)");
    app.add_option("--tools", o.tools,
                   "The tool library (a JSON file, or a folder of them) whose tools the job names (\"library\"); "
                   "default: CAMGEN_TOOLS (files or folders, colon-separated), then $XDG_CONFIG_HOME/camgen/tools");
    app.add_option("--max-holes", o.limits.holes,
                   fmt::format("Refuse jobs with more holes than this (default {})", JobLimits{}.holes));
    app.add_option("--max-elements", o.limits.path_elements,
                   fmt::format("Refuse jobs with more contour path elements than this (default {})",
                               JobLimits{}.path_elements));
    app.add_flag("--stats", o.stats,
                 "Also print statistics of the program as read back to standard error: path lengths at feed and "
                 "rapid, holes (how many canned, how many longhand), lowest Z, machining time, bounding box per tool");
    app.add_flag("-q,--quiet", o.quiet,
                 "No notes on standard error (\"camgen: note: ...\", e.g. a cycle written longhand although the machine "
                 "has it canned); warnings and errors are still printed");

    // Hidden: the build writes the man page camgen.1 with it, from this same option table.
    bool man = false;
    app.add_flag("--man", man, "Print the man page (roff)")->group("");

    VerifyOptions vo;
    CLI::App* verify = app.add_subcommand(
        "verify", "Read an NC program back with a machine's settings: statistics, an optional SVG backplot, and with "
                  "--job a check that it makes the job's motion (exit 1 and the first difference if not)");
    verify->add_option("program", vo.program, "The NC program; - reads standard input")->required();
    verify->add_option("-m,--machine", vo.machine, "The machine the program was written for")->required();
    verify->add_option("--job", vo.job, "The job the program should carry out");
    verify->add_option("--plot", vo.plot, "Write a backplot of the program: F.svg a drawing, F.html an interactive page");
    verify->add_option("--tools", vo.tools, "The tool library of the job's library tools (as camgen --tools)");
    verify->add_option("--units", vo.units, "The units the program was written in, if not the machine's (as camgen --units)")
        ->check(CLI::IsMember({"mm", "inch"}));
    verify->add_option("--tool-table", vo.tool_table,
                       "The control's tool table (LinuxCNC's format: T1 P1 D6 ...): the diameters its G41/G42 offset by "
                       "(default: the job's tools, else the program's tool comments)");
    verify->add_option("--tool-table-units", vo.tool_table_units,
                       "The units of the tool table's lengths: mm (default) or inch (LinuxCNC's standalone rs274 table)")
        ->check(CLI::IsMember({"mm", "inch"}));

    SimulateOptions so;
    CLI::App* simulate_cmd = app.add_subcommand(
        "simulate", "Sweep an NC program, as read back, through the stock: a mill's height field or a lathe's turned "
                    "profile; volumes per tool, radial engagement, machining time, and the errors (a rapid that "
                    "removes material, a feed deeper than a tool's fluteLength) at their lines (exit 1)");
    simulate_cmd->add_option("program", so.program, "The NC program; - reads standard input")->required();
    simulate_cmd->add_option("-m,--machine", so.machine, "The machine the program was written for")->required();
    simulate_cmd->add_option("--job", so.job, "The job whose tools the program uses (their shapes)")->required();
    simulate_cmd->add_option("--stock-box", so.stock_box, "A mill's stock: the box's corners x0,y0,z0,x1,y1,z1 in mm (default: the job's stock)");
    simulate_cmd->add_option("--bar", so.bar, "A lathe's stock: the bar's diameter, length and face Z (default 0), D,L[,FACEZ] in mm (default: the job's stock)");
    simulate_cmd->add_option("--tools", so.tools, "The tool library of the job's library tools (as camgen --tools)");
    simulate_cmd->add_option("--resolution", so.resolution,
                             "Cell size (mill) or Z step (lathe) in mm (default: 4 million cells, 100,000 steps)");
    simulate_cmd->add_option("--png", so.png,
                             "Write a PNG: a mill's top view shaded and coloured by depth (depth scale, mm scale bar), "
                             "and the --section under it; a lathe's half-section (the turned profile, the bore, the bar as it was)");
    simulate_cmd->add_option("--section", so.section,
                             "A mill's section along the segment x0,y0,x1,y1 (mm): the part's height along it, to scale, "
                             "with the stock as it was; drawn in the --png and on the --plot page");
    simulate_cmd->add_option("--plot", so.plot,
                             "Write an HTML page: the top view (a lathe: the half-section) and the --section, a block "
                             "slider that shows the part cut up to that block (#block=N), and a 3D (WebGL) view of the "
                             "height field; nothing loaded from the network");
    simulate_cmd->add_option("--stl", so.stl,
                             "Write the simulated part as a binary STL in mm: a mill's height field as a closed surface "
                             "(fields over 250,000 cells merged into blocks, their volume kept), a lathe's profile revolved "
                             "(128 segments)");

    std::string info_file;
    CLI::App* info_cmd = app.add_subcommand(
        "dxf-info", "Print what a DXF drawing holds: its units, layers with their entity counts, closed and open "
                    "profiles (chained per layer) with their extents, circles grouped by diameter");
    info_cmd->add_option("drawing", info_file, "The drawing (ASCII DXF)")->required();

    std::string new_from, new_machine, new_output = "-";
    CLI::App* new_cmd = app.add_subcommand(
        "new", "Write a starter job from a drawing: a drill operation per circle diameter, pockets for the closed "
               "profiles inside the outermost one, a contour outside it; it posts as written (on --machine when given: "
               "checked by posting it); edit its depths, tools and feeds");
    new_cmd->add_option("--from", new_from, "The drawing (ASCII DXF)")->required();
    new_cmd->add_option("-m,--machine", new_machine, "Check that the job posts on this machine");
    new_cmd->add_option("-o,--output", new_output, "The job file to write (default -: standard output); the drawing is named relative to it");

    std::string schema_name;
    CLI::App* schema = app.add_subcommand(
        "schema", "Print the JSON Schema (draft 2020-12) of job files (schema job), machine files (schema machine) or "
                  "tool libraries (schema tools), for editors and validators");
    schema->add_option("file", schema_name, "job, machine or tools")->required();

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e, out, err);
        return code == 0 ? exit_ok : exit_usage;
    }

    try {
        if (man) {
            out << man_page(app, CAMGEN_VERSION);
            finish_stream(out, "standard output");
            return exit_ok;
        }
        if (verify->parsed()) return run_verify(vo, in, out);
        if (simulate_cmd->parsed()) return run_simulate(so, in, out);
        if (info_cmd->parsed()) return run_dxf_info(info_file, out);
        if (new_cmd->parsed()) return run_new(new_from, new_machine, new_output, out, err);
        if (schema->parsed()) {
            const std::optional<std::string> text = schema_text(schema_name);
            if (!text) {
                const auto names = schema_names();
                const auto hint = json::did_you_mean(schema_name, names);
                err << fmt::format("camgen: unknown schema \"{}\"{}; camgen schema takes {}\n", schema_name,
                                   hint ? fmt::format(" (did you mean \"{}\"?)", *hint) : "", fmt::join(names, ", "));
                return exit_usage;
            }
            out << *text;
            finish_stream(out, "standard output");
            return exit_ok;
        }
        if (o.describe_json && o.describe.empty()) {
            err << "camgen: --json goes with --describe-machine M\n";
            return exit_usage;
        }
        if (o.list_machines) {
            out << machine_list();
            finish_stream(out, "standard output");
            return exit_ok;
        }
        if (!o.describe.empty()) {
            if (o.describe_json) {
                nlohmann::json described = nlohmann::json::object();
                described["machine"] = resolve_machine_json(o.describe);
                const Machine machine = load_machine(o.describe);
                described["capabilities"] = capabilities_json(machine_capabilities(machine));
                out << described.dump(2) << '\n';
            }
            else out << describe_machine(load_machine(o.describe));
            finish_stream(out, "standard output");
            return exit_ok;
        }
        if (o.job.empty()) {
            err << "camgen: a job file is required (camgen JOB --machine M); see camgen --help\n";
            return exit_usage;
        }
        if (o.machine.empty() && !o.events) {
            err << "camgen: --machine is required (see camgen --list-machines)\n";
            return exit_usage;
        }
        if ((!o.plot.empty() || o.stats) && (o.events || o.machine.empty())) {
            err << "camgen: --plot and --stats read the program back: they need --machine and no --events\n";
            return exit_usage;
        }
        if ((!o.plot.empty() || o.stats) && o.snippet) {
            // A snippet has no program end, and a program without its end is read as cut short.
            err << "camgen: --plot and --stats read the program back: a --snippet is not a whole program\n";
            return exit_usage;
        }
        Inputs inputs(in);
        std::optional<Machine> machine;
        if (!o.machine.empty() && !o.events) {
            std::vector<MachineSource> machine_files;
            machine = load_machine(o.machine, machine_files);  // unknown machine: usage error first
            inputs.note(machine_files);
            if ((!o.plot.empty() || o.stats) && !has_reader(machine->dialect)) {
                err << fmt::format("camgen: --plot and --stats read the program back, and camgen cannot read the {} "
                                   "dialect of machine {} yet\n",
                                   machine->dialect, machine->name);
                return exit_usage;
            }
        }
        const InputText input = inputs.read(o.job, "the job", json_input());
        if (!o.tools.empty()) inputs.note(o.tools, "the tool library");
        const std::string& text = input.text;
        // Before anything is written: no output replaces an input, and the outputs are two files.
        inputs.check_outputs({{"-o", o.output}, {"--plot", o.plot}}, out);
        Job job;
        try {
            job = parse_job(input, o.job, o.limits, o.machine, library_options(o.tools, machine ? &*machine : nullptr));
            if (job.name.empty()) job.name = job_stem(o.job);
            // Every output is written completely (the program, the plot) before any is committed:
            // a failure on the way leaves every file as it was. Reading back needs the text, so
            // then the program is posted into a buffer first.
            const bool read_back_wanted = !o.plot.empty() || o.stats;
            std::optional<OutputFile> file;
            if (o.output != "-") file.emplace(o.output);
            std::ostream& destination = file ? file->stream() : out;
            std::ostringstream buffer;
            try {
                // Into a temporary file straight away: a failure removes it (a million holes
                // longhand are 100 MB of text, held otherwise).
                const Machine* m = machine ? &*machine : nullptr;  // none for --events
                if (read_back_wanted) write_program(job, o, m, buffer, err, false);
                else write_program(job, o, m, destination, err, file && file->discarded_unless_committed());
            } catch (const IoError& e) {
                // The block writer knows the reason, not the file.
                const std::string where = file ? o.output : std::string("standard output");
                throw IoError(fmt::format("cannot write {}: {}", where,
                                          e.error_number() ? std::strerror(e.error_number()) : e.what()),
                              e.error_number());
            }
            std::optional<OutputFile> plot;
            if (read_back_wanted) {
                const std::string_view program = buffer.view();
                destination.write(program.data(), static_cast<std::streamsize>(program.size()));
                read_back(program, job, o, *machine, err, plot);
            }
            if (file) file->commit();
            else finish_stream(out, "standard output");
            if (plot) plot->commit();
        } catch (const InputErrors&) {
            throw;  // each located already
        } catch (const InputError& e) {
            throw locate(e, o.job, text);
        }
        return exit_ok;
    } catch (const InputError& e) {
        // Several errors (InputErrors) are a line each, and each line gets the prefix.
        std::string_view text = e.what();
        if (dynamic_cast<const InputErrors*>(&e))
            for (std::size_t end; (end = text.find('\n')) != std::string_view::npos; text.remove_prefix(end + 1))
                err << "camgen: " << text.substr(0, end) << '\n';
        err << "camgen: " << text << '\n';
        return exit_invalid_input;
    } catch (const dxf::Error& e) {
        err << "camgen: " << e.what() << '\n';
        return exit_invalid_input;
    } catch (const UsageError& e) {
        err << "camgen: " << e.what() << '\n';
        return exit_usage;
    } catch (const IoError& e) {
        err << "camgen: " << e.what() << '\n';
        return exit_io;
    } catch (const std::exception& e) {
        err << "camgen: internal error: " << e.what() << '\n';
        return exit_invalid_input;
    }
}

}  // namespace camgen
