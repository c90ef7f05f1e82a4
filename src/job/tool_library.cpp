// Tool libraries: reading their files, finding them (as machine files are found) and the
// feeds and speeds computed from their cutting data.
#include "camgen/job/tool_library.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/file_kind.hpp"
#include "camgen/common/input_file.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/job/job_input.hpp"

namespace camgen {

namespace {

namespace fs = std::filesystem;

// Cutting speeds beyond this are a mistake (mm/min given for m/min): 10 km/min.
constexpr double max_surface_speed = 10000.0;

// The keys of a tool library file.
constexpr KeySpec tool_library_keys[] = {
    {.key = "$schema", .type = JsonType::string,
     .description = "the JSON Schema of the file, for editors (camgen ignores it)"},
    {.key = "units", .type = JsonType::string, .default_json = "\"mm\"", .choices = &choices_of<unit_names>,
     .description = "the units of every length in the file (and of surfaceSpeed: m/min for mm, ft/min for inch)"},
    {.key = "tools", .type = JsonType::array, .required = true, .ref = "libraryTool",
     .description = "the tools, each with a name unique within the file"},
};

// The keys of a library tool besides those of a job's tool.
constexpr KeySpec library_tool_own_keys[] = {
    {.key = "name", .type = JsonType::string, .required = true,
     .description = "the name a job's tool gives as its library key, unique within the file"},
    {.key = "number", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .description = "the tool's number in the library (a job's tool may give it as libraryNumber), unique within the file"},
    {.key = "cuttingData", .type = JsonType::array, .ref = "cuttingData",
     .description = "surface speed and feeds per material; the job's material picks one"},
};

// The keys of one material's cutting data.
constexpr KeySpec cutting_data_keys[] = {
    {.key = "material", .type = JsonType::string, .required = true,
     .description = "the material, as a job's material key names it (compared ignoring case)"},
    {.key = "surfaceSpeed", .required = true, .min = Bound{0, false}, .max = Bound{max_surface_speed, true},
     .description = "cutting speed vc at the tool's diameter, m/min (ft/min when units is inch): rpm = vc x 1000 / (pi x D)"},
    {.key = "feedPerTooth", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "feed per tooth fz for milling: feed = fz x flutes x rpm, corrected for a face's stepover below "
                    "half the diameter (needs flutes)"},
    {.key = "feedPerRev", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "feed per revolution for drilling: plungingFeedrate = f x rpm (default: feedPerTooth x flutes)"},
};

// The tools of the library file `source` as its fields give them.
std::vector<LibraryTool> read_library_tools(JobInput& in, const std::string& source) {
    JobInput::Fields top = in.read_library_units();
    top.finish(tool_library_keys);
    top.optional_string("$schema");
    const nlohmann::json& tools = in.array(top, "tools");
    std::vector<LibraryTool> out;
    out.reserve(tools.size());
    const bool inch = in.header().units == Units::inch;
    for (std::size_t i = 0; i < tools.size(); ++i) {
        const std::string path = "/tools/" + std::to_string(i);
        if (!tools[i].is_object()) json::fail(in.source(), path, "expected a library tool object, got " + JobInput::describe(tools[i]));
        JobInput::Fields f(tools[i], path, in.source());
        for (const KeySpec& k : library_tool_own_keys) f.has(k.key);
        LibraryTool entry;
        entry.name = f.string("name");
        if (entry.name.empty()) f.fail("name", "a library tool's name must not be empty");
        for (const LibraryTool& other : out)
            if (other.name == entry.name)
                f.fail("name", fmt::format("tool name \"{}\" is already used by {}", entry.name, other.path));
        if (f.has("number")) {
            const std::int64_t n = f.integer("number");
            if (n < 1) f.fail("number", "a library tool number must be 1 or more");
            for (const LibraryTool& other : out)
                if (other.number == n) f.fail("number", fmt::format("tool number {} is already used by {}", n, other.path));
            entry.number = n;
        }
        entry.tool = in.read_library_tool(f);
        entry.file = source;
        entry.path = path;
        if (const nlohmann::json* data = f.member("cuttingData")) {
            if (!data->is_array()) f.fail("cuttingData", "expected an array, got " + JobInput::describe(*data));
            for (std::size_t k = 0; k < data->size(); ++k) {
                const std::string at = path + "/cuttingData/" + std::to_string(k);
                if (!(*data)[k].is_object())
                    json::fail(in.source(), at, "expected a cuttingData object, got " + JobInput::describe((*data)[k]));
                JobInput::Fields c((*data)[k], at, in.source());
                c.finish(cutting_data_keys);
                CuttingData cd;
                cd.material = c.string("material");
                if (cd.material.empty()) c.fail("material", "a material's name must not be empty");
                for (const CuttingData& other : entry.cutting)
                    if (other.material == cd.material)
                        c.fail("material", fmt::format("material \"{}\" has cutting data twice in this tool", cd.material));
                cd.surface_speed = c.number("surfaceSpeed");
                if (!(cd.surface_speed > 0 && cd.surface_speed <= max_surface_speed))
                    c.fail("surfaceSpeed", fmt::format("surfaceSpeed must be more than 0 and at most {} ({} when units is inch)",
                                                       number_text(max_surface_speed), "ft/min"));
                // ft/min to m/min for an inch library: 0.3048 m a foot.
                if (inch) cd.surface_speed *= 0.3048;
                cd.feed_per_tooth = in.optional_length(c, "feedPerTooth");
                if (cd.feed_per_tooth && !(*cd.feed_per_tooth > 0)) c.fail("feedPerTooth", "feedPerTooth must be > 0");
                cd.feed_per_rev = in.optional_length(c, "feedPerRev");
                if (cd.feed_per_rev && !(*cd.feed_per_rev > 0)) c.fail("feedPerRev", "feedPerRev must be > 0");
                if (cd.feed_per_tooth && !entry.tool.flutes)
                    c.fail("feedPerTooth", "a feedPerTooth needs the tool's flutes (the feed is fz x flutes x rpm)");
                entry.cutting.push_back(std::move(cd));
            }
        }
        out.push_back(std::move(entry));
    }
    return out;
}

// The library files of a place: the file itself, or a folder's *.json (not hidden), sorted.
std::vector<std::string> library_files_in(const std::string& place) {
    std::error_code ec;
    if (!fs::is_directory(place, ec)) return {place};
    std::vector<std::string> files;
    for (fs::directory_iterator it(place, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string file = it->path().filename().string();
        if (file.size() > 5 && file.ends_with(".json") && file[0] != '.' && it->is_regular_file(ec))
            files.push_back(it->path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

std::vector<ObjectSpec> tool_library_objects() {
    std::vector<KeySpec> tool_keys{std::begin(library_tool_own_keys), std::end(library_tool_own_keys)};
    for (const KeySpec& k : JobInput::tool_key_table()) {
        if (k.key == "number" || k.key == "library" || k.key == "libraryNumber") continue;
        KeySpec copy = k;
        copy.required = false;
        if (k.key == "diameter") copy.required = true;
        tool_keys.push_back(copy);
    }
    // The rules of a job's tool (a bull-nose's corner radius, a V's tip angle) hold for a library tool.
    std::vector<KeyRule> rules;
    for (const ObjectSpec& o : JobInput::objects())
        if (o.name == "tool") rules = o.rules;
    return {
        {.name = "toolLibrary", .description = "a camgen tool library: named tools and their cutting data",
         .keys = {std::begin(tool_library_keys), std::end(tool_library_keys)}},
        {.name = "libraryTool", .description = "a tool of the library: a job's tool keys (no number) and cutting data",
         .keys = tool_keys, .rules = rules},
        {.name = "cuttingData", .description = "the cutting data of a tool for one material",
         .keys = {std::begin(cutting_data_keys), std::end(cutting_data_keys)}},
    };
}

const LibraryTool* ToolLibrary::find(std::string_view name) const {
    for (const LibraryTool& t : tools)
        if (t.name == name) return &t;
    return nullptr;
}

const LibraryTool* ToolLibrary::find_number(std::int64_t number) const {
    for (const LibraryTool& t : tools)
        if (t.number == number) return &t;
    return nullptr;
}

std::vector<std::string> tool_library_places(const ToolLibraryOptions& options) {
    if (!options.file.empty()) return {options.file};
    std::vector<std::string> places;
    if (const char* env = std::getenv("CAMGEN_TOOLS")) {
        std::string_view rest = env;
        while (!rest.empty()) {
            const std::size_t colon = rest.find(':');
            std::string_view place = rest.substr(0, colon);
            if (!place.empty()) places.emplace_back(place);
            rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
        }
    }
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    // The XDG rule: an unset or relative XDG_CONFIG_HOME means ~/.config.
    if (xdg && *xdg == '/') places.push_back(std::string(xdg) + "/camgen/tools");
    else if (home && *home) places.push_back(std::string(home) + "/.config/camgen/tools");
    return places;
}

std::vector<LibraryTool> read_tool_library(std::string_view text, const std::string& source) {
    try {
        JobInput in(text, source);
        return read_library_tools(in, source);
    } catch (const InputError& e) {
        // A drawing, a program, a binary file: said as such, not as a JSON syntax error.
        if (e.path().empty())
            if (auto what = not_json(text, false, source, "tool library")) throw InputError("", *what, 0, source);
        throw;
    }
}

ToolLibrary load_tool_library(const ToolLibraryOptions& options) {
    ToolLibrary library;
    library.searched = tool_library_places(options);
    for (const std::string& place : library.searched) {
        std::error_code ec;
        // A place searched by default may well not exist; --tools must.
        if (!fs::exists(place, ec)) {
            if (!options.file.empty()) throw IoError(fmt::format("cannot read the tool library {} (--tools): no such file or folder", place));
            continue;
        }
        for (const std::string& file : library_files_in(place)) {
            std::istringstream no_input;
            const InputText input = read_input(file, InputRules{.what = "tool library", .regular_only = true, .json = true}, no_input);
            std::vector<LibraryTool> tools = read_tool_library(input.text, file);
            library.files.push_back(file);
            // The first tool of a name wins, as the first machine file of a name does; a later
            // file's tool whose number an earlier one has keeps its name but not the number.
            for (LibraryTool& t : tools) {
                if (library.find(t.name)) continue;
                if (t.number && library.find_number(*t.number)) t.number.reset();
                library.tools.push_back(std::move(t));
            }
        }
    }
    return library;
}

double rpm_for_surface_speed(double surface_speed, double diameter) {
    return std::max(1.0, std::floor(surface_speed * 1000.0 / (pi * diameter)));
}

// Radial chip thinning. Below half the diameter the chip a tooth cuts is thinner than the feed
// per tooth: its largest thickness is hex = fz x sqrt(1 - (1 - 2 ae / D)^2) = fz x 2 sqrt(ae (D -
// ae)) / D (the chord relation of the tooth's arc of engagement, as tool makers' milling
// formulas give it, e.g. Sandvik Coromant's "Milling formulas and definitions"; stated with its
// derivation at https://machinecalcs.com/radial-chip-thinning-calculator). The feed per tooth
// that makes the chip the cutting data ask for is its inverse.
double thinned_feed_per_tooth(double feed_per_tooth, double diameter, double engagement) {
    if (!(engagement > 0) || engagement >= diameter / 2) return feed_per_tooth;
    return feed_per_tooth * diameter / (2.0 * std::sqrt(engagement * (diameter - engagement)));
}

namespace {
// A computed feed within the machine's maxFeed, rounded down to a whole mm/min (at least 1).
double tool_library_bounded_feed(const Tool& tool, double feed, std::vector<std::string>& notes, const std::string& how) {
    const double whole = std::max(1.0, std::floor(feed));
    const ToolCutting& c = *tool.cutting;
    if (c.max_feed > 0 && whole > c.max_feed) {
        notes.push_back(fmt::format("feed {} mm/min computed for T{} (library tool \"{}\", {}: {}) is above the machine's "
                                    "maxFeed: {} mm/min",
                                    number_text(whole), tool.number, tool.library, c.material, how, number_text(c.max_feed)));
        return c.max_feed;
    }
    notes.push_back(fmt::format("feed {} mm/min computed for T{} (library tool \"{}\", {}: {})", number_text(whole),
                                tool.number, tool.library, c.material, how));
    return whole;
}
}  // namespace

std::optional<double> computed_milling_feed(const Tool& tool, double engagement, std::vector<std::string>& notes) {
    if (!tool.cutting || !tool.cutting->feed_per_tooth || !tool.flutes) return std::nullopt;
    const double fz = *tool.cutting->feed_per_tooth;
    const double used = thinned_feed_per_tooth(fz, tool.diameter, engagement);
    std::string how = fmt::format("fz {} mm x {} flutes x {} rpm", number_text(used), *tool.flutes, number_text(tool.rpm));
    if (used != fz)
        how = fmt::format("fz {} mm raised to {} mm for the chip thinning of a {} mm stepover, x {} flutes x {} rpm",
                          number_text(fz), number_text(used), number_text(engagement), *tool.flutes, number_text(tool.rpm));
    return tool_library_bounded_feed(tool, used * *tool.flutes * tool.rpm, notes, how);
}

std::optional<double> computed_drilling_feed(const Tool& tool, std::vector<std::string>& notes) {
    if (!tool.cutting || !tool.cutting->feed_per_rev) return std::nullopt;
    const double f = *tool.cutting->feed_per_rev;
    return tool_library_bounded_feed(tool, f * tool.rpm, notes,
                                     fmt::format("{} mm/rev x {} rpm", number_text(f), number_text(tool.rpm)));
}

}  // namespace camgen
