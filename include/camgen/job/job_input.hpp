#pragma once
// Reading a job file: the parsed document, its header and tool table, and the checked
// accessors every operation's reader uses (lengths in the file's units, points, arrays), each
// error naming the JSON path and line.
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/common/key_spec.hpp"
#include "camgen/job/job.hpp"
#include "camgen/job/tool_library.hpp"

namespace camgen {

// Sanity bounds for values in a job.
inline constexpr double max_job_length = 1e6;  // mm or mm/min: 1 km, 1 km/min
inline constexpr int max_tool_flutes = 1000;     // cutting edges of a tool (a saw has a few hundred)

// How large a job may be, checked before anything is allocated for it: holes over all drill
// operations, path elements over all contours, and the nesting of the JSON text. The command
// line raises them (--max-holes, --max-elements).
struct JobLimits {
    std::size_t holes = 10'000'000;
    std::size_t path_elements = 10'000'000;
    int nesting = 64;
};

// An error that follows from one already reported: an operation names a tool that failed to
// read (or, when a tool's number could not be read, a tool the table lacks). read_job leaves it
// out of the job's errors, which hold the tool's own.
class FollowOnError : public InputError {
public:
    using InputError::InputError;
};

class JobInput {
public:
    using Json = nlohmann::json;
    using Fields = json::Fields;

    // Parses `text`, which must outlive this object (its line map reads it for messages).
    // Throws InputError naming the line for a syntax error or nesting deeper than limits.nesting.
    JobInput(std::string_view text, const std::string& source_name, JobLimits limits = {});
    // Where the job's library tools are found and the machine's bounds on what is computed
    // from their cutting data (the library is read when a tool first names one).
    void set_tool_library(ToolLibraryOptions options) { library_options_ = std::move(options); }

    // Counts `count` more holes (or path elements) against the job's limit before they are
    // made; an InputError at f's `key` when the job would exceed it.
    void claim_holes(double count, Fields& f, std::string_view key) const;
    void claim_path_elements(double count, Fields& f, std::string_view key) const;
    const JobLimits& limits() const { return limits_; }

    // Reads the header: the top-level keys besides "tools" and "operations" ("$schema" is
    // accepted and ignored), throwing at its first error. Returns the top-level object's fields
    // for the caller to read on.
    Fields read_header();
    // After read_header failed: whether "units" and "clearance", which every length after them
    // is measured in or against, read without an error all the same (then the tools and the
    // operations can be read on, and their errors are not the header's).
    bool units_and_clearance();
    // Reads the tool table. A tool's first error goes to `report`, the tool is left out and
    // reading goes on with the next; so does an error of the table itself (not an array,
    // empty). An operation naming a tool that failed (or any missing tool, when a failed
    // tool's number is unknown) then gets a FollowOnError from tool().
    void read_tools(Fields& top, const std::function<void(const InputError&)>& report);
    const JobHeader& header() const { return header_; }
    // Sets the job's stock, read by the operations layer (its profile form reads like a
    // contour's), before the operations are read: they take their stock top from it.
    void set_stock(Stock stock) { header_.stock = std::move(stock); }
    JobHeader take_header() { return std::move(header_); }
    const json::Source& source() const { return source_; }
    const Json& root() const { return doc_.root; }
    // The packed array (holes or path lines, read straight into numbers) `value` stands for,
    // or nullptr: a reader that knows packed arrays reads them so; array() unpacks them for
    // the others.
    const json::PackedArray* packed(const Json& value) const { return doc_.packed_at(value); }

    // A length or feed in the file's units, as mm (mm/min), within +-max_job_length.
    double checked_length(double value, const std::string& path) const;
    double length(Fields& f, std::string_view key) const { return checked_length(f.number(key), f.path_of(key)); }
    std::optional<double> optional_length(Fields& f, std::string_view key) const;
    // A value of `quantity` in the file's units, in internal units (lengths and feeds scaled).
    std::optional<double> optional_quantity(Fields& f, std::string_view key, Quantity quantity) const;
    double coordinate(const Json& value, const std::string& path) const;
    // A coordinate of a packed array (a finite number within 1e9) as mm; `path()` names it
    // and is made only when the value is out of range.
    template <class Path>
    double packed_coordinate(double value, Path&& path) const {
        const double mm = value * scale_;
        if (std::abs(mm) > max_job_length) checked_length(value, path());
        return mm;
    }
    // A point [x, y].
    Vec2 point(const Json& value, const std::string& path) const;
    Vec2 point(Fields& f, std::string_view key) const { return point(f.required(key), f.path_of(key)); }
    // A point [x, y] (at Z `z`, mm) or [x, y, z].
    Vec3 point3(const Json& value, const std::string& path, double z) const;
    Vec3 point3(Fields& f, std::string_view key, double z) const { return point3(f.required(key), f.path_of(key), z); }
    // A required array member (a packed array unpacked into the document).
    const Json& array(Fields& f, std::string_view key) const;
    // A length in mm as the file writes it, for messages ("12.000 mm", "0.5000 in").
    std::string show(double mm) const;
    // The tool `number` of the tool table; an error at f's "tool" key when it is not there (a
    // FollowOnError when it is a tool that failed to read).
    const Tool& tool(Fields& f) const;

    // What a JSON value is, for messages ("a string \"x\"", "an array").
    static std::string describe(const Json& value);
    // Marks the keys of `table` as known and reports any other key of the object, so that a
    // misspelt key is reported (with a hint) before the "missing key" error it would otherwise cause.
    static void known_keys(Fields& f, std::span<const KeySpec> table);
    // The objects the header is made of: the top level ("job", its "operations" items being
    // the "operation" object) and a tool ("tool").
    static std::vector<ObjectSpec> objects();
    // The keys of a job's tool (a library tool has them too, besides number and library).
    static std::span<const KeySpec> tool_key_table();

    // Reads the tool at `f` of a tool library whose text this object holds (its "units" read
    // already by read_library_units): the keys of a job's tool besides number and library, its
    // rpm optional. The caller has marked the library tool's own keys (name, cuttingData) known.
    Tool read_library_tool(Fields& f);
    // Reads a library's "units" (default mm) and returns its top-level fields.
    Fields read_library_units();

private:
    Tool read_tool(const Json& value, const std::string& path);
    // The keys of a tool besides its number: over `base` (a library tool) where given, where
    // the object has no such key; `library_tool`: read for a library (rpm optional).
    void read_tool_keys(Fields& f, Tool& tool, const Tool* base, bool library_tool);
    // The library tool a job's tool names, the library read on first use.
    const LibraryTool& library_tool(Fields& f, std::string_view key, const std::string& name,
                                    std::optional<std::int64_t> number);
    // rpm and cutting data of a tool from the library tool `entry` for the job's material.
    void apply_cutting_data(Fields& f, Tool& tool, const LibraryTool& entry, bool rpm_given);
    // A constant surface speed's limit into tool.rpm: its maxRpm, else the machine's; refused
    // above the machine's, or with neither.
    void resolve_surface_speed_limit(Fields& f, Tool& tool) const;

    JobLimits limits_;
    mutable json::Document doc_;  // mutable: array() unpacks a packed array for a reader that wants JSON
    json::Source source_;
    // What the operations read so far have claimed: a budget the const readers draw on.
    mutable double holes_claimed_ = 0;
    mutable double elements_claimed_ = 0;
    double scale_ = 1.0;
    JobHeader header_;
    // The numbers of the tools that failed to read, and whether one failed whose number is not known.
    std::set<std::int64_t> failed_tools_;
    bool unnumbered_tool_failed_ = false;
    ToolLibraryOptions library_options_;
    std::optional<ToolLibrary> library_;  // read on first use
    bool library_failed_ = false;
};

}  // namespace camgen
