#include "src/cli/man.hpp"

#include <sstream>

#include <fmt/format.h>

namespace camgen {

namespace {

// Text made safe for roff: backslashes escaped, a line that would start with a control
// character ('.' or '\'') made literal, hyphens written as minus signs (so that a copied
// option is typed as an ASCII hyphen).
std::string roff(const std::string& text) {
    std::string out;
    bool line_start = true;
    for (char c : text) {
        if (line_start && (c == '.' || c == '\'')) out += "\\&";
        if (c == '\\') out += "\\e";
        else if (c == '-') out += "\\-";
        else out += c;
        line_start = c == '\n';
    }
    return out;
}

// Reuses --help's formatter for the option names and their argument text, so the page names
// each option exactly as --help does.
class ManFormatter : public CLI::Formatter {
public:
    // One option as a tagged paragraph: its names and arguments, then its description.
    std::string option(const CLI::Option* opt) const {
        const bool positional = !opt->nonpositional();
        std::string names = make_option_name(opt, positional);
        std::string args = make_option_opts(opt);
        return fmt::format(".TP\n\\fB{}\\fR{}\n{}\n", roff(names), roff(args), roff(make_option_desc(opt)));
    }

    // The usage line after the command's name: "[OPTIONS] [job] [SUBCOMMAND]".
    std::string usage(const CLI::App* app) const {
        std::string text = make_usage(app, "");
        if (auto colon = text.find(": "); colon != std::string::npos) text.erase(0, colon + 2);
        while (!text.empty() && text.back() == '\n') text.pop_back();
        return text;
    }

    // The positionals, then the other options, of one app (hidden ones left out, as --help does).
    std::string options(const CLI::App* app) const {
        const auto shown = app->get_options([](const CLI::Option* o) { return !o->get_group().empty(); });
        std::string out;
        for (const CLI::Option* opt : shown)
            if (!opt->nonpositional()) out += option(opt);
        for (const CLI::Option* opt : shown)
            if (opt->nonpositional()) out += option(opt);
        return out;
    }
};

// The app's description: its first line becomes the NAME line's text, the rest the
// DESCRIPTION section, lines that start with a blank (examples) kept as they are.
struct Description {
    std::string summary;
    std::string body;
};

Description split_description(const std::string& text) {
    Description d;
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    if (auto colon = line.find(": "); colon != std::string::npos) line.erase(0, colon + 2);
    d.summary = line;
    bool literal = false;
    while (std::getline(in, line)) {
        const bool example = !line.empty() && line.front() == ' ';
        if (example && !literal) d.body += ".nf\n";
        if (!example && literal) d.body += ".fi\n";
        literal = example;
        d.body += roff(example ? line.substr(line.find_first_not_of(' ')) : line) + '\n';
    }
    if (literal) d.body += ".fi\n";
    return d;
}

}  // namespace

std::string man_page(const CLI::App& app, const std::string& version) {
    ManFormatter format;
    const Description description = split_description(app.get_description());
    std::string page;
    page += fmt::format(".TH CAMGEN 1 \"\" \"camgen {}\" \"User Commands\"\n", roff(version));
    std::string name_line = description.summary;
    if (name_line.ends_with('.')) name_line.pop_back();
    page += fmt::format(".SH NAME\ncamgen \\- {}\n", roff(name_line));
    page += ".SH SYNOPSIS\n";
    page += fmt::format("\\fBcamgen\\fR {}\n", roff(format.usage(&app)));
    for (const CLI::App* sub : app.get_subcommands({}))
        page += fmt::format(".br\n\\fBcamgen {}\\fR {}\n", roff(sub->get_name()), roff(format.usage(sub)));
    page += ".SH DESCRIPTION\n";
    page += fmt::format(".PP\n\\fBcamgen\\fR {}\n", roff(description.summary)) + description.body;
    page += ".SH OPTIONS\n" + format.options(&app);
    page += ".SH COMMANDS\n";
    for (const CLI::App* sub : app.get_subcommands({})) {
        page += fmt::format(".SS \"camgen {}\"\n{}\n", roff(sub->get_name()), roff(sub->get_description()));
        page += format.options(sub);
    }
    page += R"(.SH FILES
A machine is looked up by name in the folders below, in this order; the first file
\fINAME.json\fR wins. A name that contains a slash or ends in \fI.json\fR is a machine file's path instead.
.TP
each folder of \fBCAMGEN_MACHINES\fR (colon-separated)
the user's machine files
.TP
\fI$XDG_CONFIG_HOME/camgen/machines\fR (\fI~/.config/camgen/machines\fR when XDG_CONFIG_HOME is unset)
the user's machine files
.TP
\fI../share/camgen/machines/*.json\fR (beside the executable's \fIbin\fR folder)
the built-in machine files installed with camgen, e.g. \fI/usr/share/camgen/machines\fR
.TP
compiled in
the same built-in files as built into the program, used when there is no installed folder (a run from the build folder, a program linked with the camgen library)
.PP
A job's tool that names a library tool (\fB"library": "NAME"\fR) is looked up in the tool library: the file or folder of \fB--tools\fR alone when it is given, else the files below, in this order; the first tool of a name wins. A folder's \fI*.json\fR files are read in name order.
.TP
each file or folder of \fBCAMGEN_TOOLS\fR (colon-separated)
the user's tool libraries
.TP
\fI$XDG_CONFIG_HOME/camgen/tools\fR (\fI~/.config/camgen/tools\fR when XDG_CONFIG_HOME is unset)
the user's tool libraries
.PP
A library tool's cutting data for the job's \fBmaterial\fR give its rpm (vc x 1000 / (pi x D)) and the feeds of its contour, pocket, face (fz x flutes x rpm, a face's feed corrected for radial chip thinning) and drill operations (feed per rev x rpm) where the job gives none, within the machine's maxRpm and maxFeed; what camgen computed is written in the tool's comment line and printed as a note.
.PP
The JSON Schemas of job and machine files and tool libraries are installed in \fI../share/camgen/schema\fR (and printed by \fBcamgen schema job\fR, \fBcamgen schema machine\fR and \fBcamgen schema tools\fR).
.SH ENVIRONMENT
.TP
\fBCAMGEN_MAX_INPUT_SIZE\fR
the largest input camgen reads (job, machine file, program, tool table): bytes, or a number with K, M or G for KiB, MiB or GiB; default 1G. A larger input, or a program line longer than 1 MiB, ends with exit status 3.
.TP
\fBCAMGEN_MACHINES\fR, \fBXDG_CONFIG_HOME\fR
where the user's machine files are (see FILES).
.TP
\fBCAMGEN_TOOLS\fR, \fBXDG_CONFIG_HOME\fR
where the user's tool libraries are (see FILES).
.SH EXIT STATUS
0 done, 1 invalid job or machine file (the message names the JSON path and line; a job's independent errors come together, a line each, up to 20), 2 usage (unknown option or machine; an output that would replace an input), 3 a file could not be read or written.
.SH SEE ALSO
The README and docs/ of camgen's sources: the job format, the machine files, the library.
)";
    return page;
}

}  // namespace camgen
