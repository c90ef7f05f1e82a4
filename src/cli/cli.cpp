#include "camgen/cli.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "camgen/error.hpp"
#include "camgen/events.hpp"
#include "camgen/job_json.hpp"
#include "camgen/json_util.hpp"
#include "camgen/machine.hpp"
#include "camgen/operations.hpp"
#include "camgen/output.hpp"
#include "camgen/post.hpp"
#include "camgen/stats.hpp"

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
    bool stats = false;
    std::string describe;
    std::string units;
};

// Reads the whole job text ("-" = standard input).
std::string read_text(const std::string& file, std::istream& in) {
    std::ostringstream ss;
    if (file == "-") {
        ss << in.rdbuf();
        return ss.str();
    }
    std::ifstream f(file, std::ios::binary);
    if (!f) throw IoError(fmt::format("cannot read {}: {}", file, std::strerror(errno)));
    ss << f.rdbuf();
    if (f.bad()) throw IoError(fmt::format("cannot read {}", file));
    return ss.str();
}

std::string stem_of(const std::string& file) {
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

// Sends every event to two sinks (the post and the statistics).
struct TeeSink : EventSink {
    EventSink& a;
    EventSink& b;
    TeeSink(EventSink& first, EventSink& second) : a(first), b(second) {}
    void emit(const Event& e) override {
        a.emit(e);
        b.emit(e);
    }
};

void write_program(const Job& job, const Options& o, std::ostream& out, std::ostream& err) {
    if (o.events) {
        EventPrinter printer(out);
        StatsSink stats;
        TeeSink tee(printer, stats);
        expand_job(job, tee);
        if (o.stats) err << "camgen: " << format_stats(stats.stats()) << '\n';
        return;
    }
    Machine machine = load_machine(o.machine);
    if (!o.units.empty()) machine.units = o.units == "inch" ? Units::inch : Units::mm;
    PostOptions po;
    po.snippet = o.snippet;
    po.program_name = job.name;
    po.warnings = &err;
    std::unique_ptr<Post> post = make_post(machine, out, po);
    StatsSink stats(machine.longhand());
    TeeSink tee(*post, stats);
    post->open();
    expand_job(job, tee);
    post->close();
    if (o.stats) err << "camgen: " << format_stats(stats.stats()) << '\n';
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::istream& in, std::ostream& out, std::ostream& err) {
    Options o;
    CLI::App app{"camgen: turns a JSON job into the NC program of a machine.\n"
                 "  camgen job.json --machine wabeco -o part.knc   (nccad files end in .knc)\n"
                 "  camgen job.json --machine fanuc -o part.nc\n"
                 "Exit codes: 0 done, 1 invalid job or machine file, 2 usage, 3 file error.",
                 "camgen"};
    app.set_version_flag("--version", std::string("camgen ") + CAMGEN_VERSION);
    app.add_option("job", o.job, "The job file (JSON); - reads standard input");
    app.add_option("-m,--machine", o.machine, "Machine name (see --list-machines) or path to a machine JSON file");
    app.add_option("-o,--output", o.output,
                   "Output file, written atomically (default -: standard output); wabeco/kosy programs end in .knc");
    app.add_flag("--snippet", o.snippet, "Clipboard export: no program start or end blocks");
    app.add_flag("--events", o.events, "Print the machine-independent events, one JSON object per line");
    app.add_flag("--stats", o.stats, "Print the rapid and feed path lengths and the hole count to standard error");
    app.add_option("--units", o.units, "Output units, overriding the machine file")->check(CLI::IsMember({"mm", "inch"}));
    app.add_flag("--list-machines", o.list_machines, "List the built-in machines");
    app.add_option("--describe-machine", o.describe, "Print a machine's settings and drilling cycle table");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e, out, err);
        return code == 0 ? exit_ok : exit_usage;
    }

    try {
        if (o.list_machines) {
            for (const auto& [name, description] : list_machines()) out << fmt::format("{:<12}{}\n", name, description);
            return exit_ok;
        }
        if (!o.describe.empty()) {
            out << describe_machine(load_machine(o.describe));
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
        if (!o.machine.empty() && !o.events) (void)load_machine(o.machine);  // unknown machine: usage error first
        std::string text = read_text(o.job, in);
        Job job;
        try {
            job = read_job(text, o.job == "-" ? "<stdin>" : o.job);
            if (job.name.empty()) job.name = stem_of(o.job);
            if (o.output == "-") {
                write_program(job, o, out, err);
                out.flush();
            } else {
                AtomicFile file(o.output);
                write_program(job, o, file.stream(), err);
                file.commit();
            }
        } catch (const InputError& e) {
            throw locate(e, o.job, text);
        }
        return exit_ok;
    } catch (const InputError& e) {
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
