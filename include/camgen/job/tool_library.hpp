#pragma once
// Tool libraries: JSON files of named (and optionally numbered) tools (the keys of a job's tool) with
// their cutting data per material, found as machine files are (--tools, CAMGEN_TOOLS,
// $XDG_CONFIG_HOME/camgen/tools). A job's tool names one (key "library", or "libraryNumber"); its spindle speed
// and its operations' feeds are computed from the cutting data for the job's "material" where
// the job does not give them, within the machine's limits.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/job/job.hpp"

namespace camgen {

// Where a job's library tools come from, and the machine bounds what is computed from them.
struct ToolLibraryOptions {
    std::string file;        // --tools: a library file or a folder of them; "": the search (CAMGEN_TOOLS, then the XDG folder)
    double max_rpm = 0.0;    // the machine's spindle limit, rpm (0: none)
    double max_feed = 0.0;   // the machine's feed limit, mm/min (0: none)
    std::string machine;     // the machine's name, for notes ("" : no machine)
};

// The cutting data of a library tool for one material (library key cuttingData). Speeds m/min,
// lengths mm.
struct CuttingData {
    std::string material;
    double surface_speed = 0.0;              // vc, m/min
    std::optional<double> feed_per_tooth;    // fz, mm
    std::optional<double> feed_per_rev;      // drilling, mm
};

// One tool of a library: what its keys make of it (its number 0, its rpm 0 where it gives none)
// and its cutting data.
struct LibraryTool {
    std::string name;
    std::optional<std::int64_t> number;  // its library number, if it has one
    Tool tool;
    std::vector<CuttingData> cutting;
    std::string file;   // the library file it is in
    std::string path;   // its JSON path there ("/tools/3")
};

// The tools of every library file found, the first of a name kept.
struct ToolLibrary {
    std::vector<LibraryTool> tools;
    std::vector<std::string> files;    // the files read, in order
    std::vector<std::string> searched; // where camgen looked, for "found nowhere"
    const LibraryTool* find(std::string_view name) const;
    const LibraryTool* find_number(std::int64_t number) const;
};

// The objects of a library file, for its JSON Schema: the file ("toolLibrary"), a tool
// ("libraryTool": a job tool's keys besides number and library) and "cuttingData".
std::vector<ObjectSpec> tool_library_objects();

// The places a library is searched for: `options.file` alone when given, else the entries of
// CAMGEN_TOOLS (colon-separated, each a file or a folder) and $XDG_CONFIG_HOME/camgen/tools
// (default ~/.config/camgen/tools).
std::vector<std::string> tool_library_places(const ToolLibraryOptions& options);

// Reads every library file of those places (a folder's *.json, sorted). A file's errors name
// it, the JSON path and the line (InputError); a given --tools that does not exist is an IoError.
ToolLibrary load_tool_library(const ToolLibraryOptions& options);

// Reads one library file's text; `source` names it in messages.
std::vector<LibraryTool> read_tool_library(std::string_view text, const std::string& source);

// The spindle speed that cuts at `surface_speed` (m/min) with a tool of `diameter` (mm):
// vc x 1000 / (pi x D), rounded down to a whole rpm (at least 1).
double rpm_for_surface_speed(double surface_speed, double diameter);

// The feed per tooth that makes the chip of `feed_per_tooth` (mm) at a radial engagement
// `engagement` (mm) below half the `diameter`: fz x D / (2 sqrt(ae (D - ae))); fz itself at
// half the diameter or more (or an engagement of 0: not known).
double thinned_feed_per_tooth(double feed_per_tooth, double diameter, double engagement);

// The milling feed (mm/min) of a tool whose cutting data give a feed per tooth: fz (corrected
// for `engagement`, see above) x flutes x rpm, rounded down to a whole mm/min, within the
// machine's maxFeed; what was computed (and clamped) is appended to `notes`. nullopt when the
// tool has no such cutting data.
std::optional<double> computed_milling_feed(const Tool& tool, double engagement, std::vector<std::string>& notes);

// The drilling feed (mm/min) of a tool whose cutting data give a feed per revolution (or a feed
// per tooth and flutes): f x rpm, rounded down, within maxFeed; notes as above.
std::optional<double> computed_drilling_feed(const Tool& tool, std::vector<std::string>& notes);

}  // namespace camgen
