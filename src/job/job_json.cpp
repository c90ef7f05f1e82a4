#include "camgen/job/job_json.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "camgen/geometry/arc.hpp"
#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = camgen::json::Fields;
using Source = camgen::json::Source;

constexpr double mm_per_inch = 25.4;
// Sanity bound for generated hole patterns, so a typo cannot exhaust memory.
constexpr double max_pattern_holes = 10'000'000;
// Arc end points may be this far off the circle through the start point, mm.
constexpr double arc_radius_tolerance = 0.001;
constexpr double min_arc_radius = 0.0005;
// Lengths (mm) and feeds (mm/min) beyond this are typos: 1 km, 1 km/min.
constexpr double max_length = 1e6;

std::string describe(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null: return "null";
        case Json::value_t::object: return "an object";
        case Json::value_t::array: return "an array";
        case Json::value_t::string: return "a string " + value.dump();
        case Json::value_t::boolean: return "a boolean (" + value.dump() + ")";
        default: return "a number (" + value.dump() + ")";
    }
}

// cos and sin of an angle in degrees, exact for multiples of 90 degrees.
Vec2 unit_vector(double degrees) {
    double d = std::fmod(degrees, 360.0);
    if (d < 0) d += 360.0;
    if (d == 0.0) return {1.0, 0.0};
    if (d == 90.0) return {0.0, 1.0};
    if (d == 180.0) return {-1.0, 0.0};
    if (d == 270.0) return {0.0, -1.0};
    const double r = degrees * std::numbers::pi / 180.0;
    return {std::cos(r), std::sin(r)};
}

// Marks `keys` as known and reports any other key of the object, so that a misspelt key is
// reported (with a hint) before the "missing key" error it would otherwise cause.
void known_keys(Fields& f, std::initializer_list<std::string_view> keys) {
    for (auto key : keys) f.has(key);
    f.finish();
}

// Reads one job: lengths and feeds are multiplied by `scale` (25.4 for inch files).
class JobReader {
public:
    JobReader(const Source& source) : source_(source) {}

    Job read(const Json& root, const std::string& default_name);

private:
    Tool read_tool(const Json& value, const std::string& path, const std::map<int, Tool>& tools);
    Operation read_operation(const Json& value, const std::string& path);
    DrillOp read_drill(Fields& f, int tool_number);
    ContourOp read_contour(Fields& f, int tool_number);
    void read_holes(Fields& f, std::vector<Vec2>& holes);

    // A length or feed in the file's units, as mm, within +-max_length.
    double checked_length(double value, const std::string& path) const {
        double mm = value * scale_;
        if (std::abs(mm) > max_length)
            camgen::json::fail(source_, path, "a length or feed beyond 1,000,000 mm (or mm/min) is out of range");
        return mm;
    }
    double length(Fields& f, std::string_view key) { return checked_length(f.number(key), f.path_of(key)); }
    std::optional<double> optional_length(Fields& f, std::string_view key) {
        auto v = f.optional_number(key);
        if (v) *v = checked_length(*v, f.path_of(key));
        return v;
    }
    double coordinate(const Json& value, const std::string& path) const {
        return checked_length(camgen::json::number_at(value, path, source_), path);
    }
    Vec2 point(const Json& value, const std::string& path) const {
        if (!value.is_array() || value.size() != 2)
            camgen::json::fail(source_, path, "expected a point [x, y], got " + describe(value));
        return {coordinate(value[0], path + "/0"), coordinate(value[1], path + "/1")};
    }
    Vec2 point(Fields& f, std::string_view key) { return point(f.required(key), f.path_of(key)); }
    // A point [x, y] (at Z `z`, mm) or [x, y, z].
    Vec3 point3(const Json& value, const std::string& path, double z) const {
        if (!value.is_array() || (value.size() != 2 && value.size() != 3))
            camgen::json::fail(source_, path, "expected a point [x, y] or [x, y, z], got " + describe(value));
        Vec3 p{coordinate(value[0], path + "/0"), coordinate(value[1], path + "/1"), z};
        if (value.size() == 3) p.z = coordinate(value[2], path + "/2");
        return p;
    }
    Vec3 point3(Fields& f, std::string_view key, double z) { return point3(f.required(key), f.path_of(key), z); }
    PathArc read_arc(Fields& a, const Vec3& current, double depth);
    PathHelix read_helix(Fields& h, const Vec3& current);
    const Json& array(Fields& f, std::string_view key) {
        const Json& value = f.required(key);
        if (!value.is_array()) f.fail(key, "expected an array, got " + describe(value));
        return value;
    }
    // A length in mm, shown in the file's units for messages.
    std::string show(double mm) const {
        return scale_ == 1.0 ? fmt::format("{:.3f} mm", mm) : fmt::format("{:.4f} in", mm / scale_);
    }

    const Source& source_;
    double scale_ = 1.0;
    Job job_;
};

Job JobReader::read(const Json& root, const std::string& default_name) {
    Fields top(root, "", source_);
    known_keys(top, {"name", "units", "clearance", "tools", "operations"});
    job_.name = top.optional_string("name").value_or(default_name);
    job_.units = top.choice<Units>("units", {{"mm", Units::mm}, {"inch", Units::inch}}, Units::mm);
    scale_ = job_.units == Units::inch ? mm_per_inch : 1.0;
    job_.clearance = length(top, "clearance");

    const Json& tools = array(top, "tools");
    if (tools.empty()) top.fail("tools", "a job needs at least one tool");
    for (std::size_t i = 0; i < tools.size(); ++i) {
        Tool tool = read_tool(tools[i], "/tools/" + std::to_string(i), job_.tools);
        job_.tools.emplace(tool.number, std::move(tool));
    }

    const Json& operations = array(top, "operations");
    for (std::size_t i = 0; i < operations.size(); ++i)
        job_.operations.push_back(read_operation(operations[i], "/operations/" + std::to_string(i)));
    return std::move(job_);
}

Tool JobReader::read_tool(const Json& value, const std::string& path,
                          const std::map<int, Tool>& tools) {
    Fields f(value, path, source_);
    known_keys(f, {"number", "type", "diameter", "tipAngle", "rpm", "direction", "comment"});
    Tool tool;
    tool.path = path;
    tool.number = f.integer("number");
    if (tool.number < 1) f.fail("number", "a tool number must be 1 or more");
    if (auto it = tools.find(tool.number); it != tools.end())
        f.fail("number", fmt::format("tool number {} is already used by {}", tool.number,
                                     it->second.path));
    tool.type = f.choice<ToolType>("type",
                                   {{"drill", ToolType::drill},
                                    {"centre-drill", ToolType::centre_drill},
                                    {"spot-drill", ToolType::spot_drill},
                                    {"tap", ToolType::tap},
                                    {"reamer", ToolType::reamer},
                                    {"boring-bar", ToolType::boring_bar},
                                    {"end-mill", ToolType::end_mill},
                                    {"ball-mill", ToolType::ball_mill}},
                                   ToolType::drill);
    tool.diameter = length(f, "diameter");
    if (tool.diameter <= 0) f.fail("diameter", "a tool diameter must be > 0");
    tool.tip_angle = f.optional_number("tipAngle");
    if (tool.tip_angle && (*tool.tip_angle <= 0 || *tool.tip_angle >= 180))
        f.fail("tipAngle", "tipAngle must be between 0 and 180 degrees (exclusive)");
    tool.rpm = f.number("rpm");
    if (tool.rpm <= 0) f.fail("rpm", "rpm must be > 0");
    tool.direction = f.choice<SpindleDirection>(
        "direction", {{"cw", SpindleDirection::cw}, {"ccw", SpindleDirection::ccw}},
        SpindleDirection::cw);
    tool.comment = f.optional_string("comment").value_or("");
    return tool;
}

Operation JobReader::read_operation(const Json& value, const std::string& path) {
    Fields f(value, path, source_);
    enum class Type { drill, contour };
    const Type type = f.choice<Type>("type", {{"drill", Type::drill}, {"contour", Type::contour}});
    if (type == Type::drill) {
        known_keys(f, {"type", "tool", "comment", "cycle", "retractPlane", "referencePlane",
                       "safeDistance", "safeDistanceIsAbsolute", "endDepth", "endDepthIsAbsolute",
                       "firstDepth", "degressionType", "degression", "minimumDepth",
                       "peckingRetract", "firstFeedrateFactor", "plungingFeedrate",
                       "retractFeedrate", "topDwell", "bottomDwell", "pitch", "tappingSpeed",
                       "retractSpeed", "drillTip", "output", "order", "holes", "grid",
                       "boltCircle", "line"});
    } else {
        known_keys(f, {"type", "tool", "comment", "depth", "feed", "plungeFeed", "tolerance", "start", "path"});
    }
    const int tool = f.integer("tool");
    if (!job_.tools.count(tool)) f.fail("tool", fmt::format("tool {} is not in /tools", tool));
    if (type == Type::drill) return read_drill(f, tool);
    return read_contour(f, tool);
}

// The parameters each cycle kind uses, besides the ones every kind may set.
struct CycleInfo {
    std::string_view name;
    CycleKind kind;
    std::vector<std::string_view> uses;
};

const std::vector<CycleInfo>& cycles() {
    static const std::vector<CycleInfo> table = {
        {"drill", CycleKind::drill, {"plungingFeedrate", "retractFeedrate", "topDwell"}},
        {"dwell", CycleKind::dwell,
         {"plungingFeedrate", "retractFeedrate", "bottomDwell", "topDwell"}},
        {"deep", CycleKind::deep,
         {"plungingFeedrate", "retractFeedrate", "firstDepth", "degressionType", "degression",
          "minimumDepth", "firstFeedrateFactor", "topDwell", "bottomDwell"}},
        {"chip-break", CycleKind::chip_break,
         {"plungingFeedrate", "retractFeedrate", "firstDepth", "degressionType", "degression",
          "minimumDepth", "peckingRetract", "firstFeedrateFactor", "topDwell", "bottomDwell"}},
        {"tap", CycleKind::tap, {"pitch", "tappingSpeed", "retractSpeed", "bottomDwell"}},
        {"tap-left", CycleKind::tap_left, {"pitch", "tappingSpeed", "retractSpeed", "bottomDwell"}},
        {"ream", CycleKind::ream, {"plungingFeedrate", "retractFeedrate", "bottomDwell"}},
        {"bore-stop", CycleKind::bore_stop, {"plungingFeedrate", "bottomDwell"}},
        {"bore-dwell", CycleKind::bore_dwell,
         {"plungingFeedrate", "retractFeedrate", "bottomDwell"}},
    };
    return table;
}

// Every cycle-specific parameter, in the order they are checked.
constexpr std::string_view cycle_parameters[] = {
    "plungingFeedrate", "retractFeedrate", "firstDepth",  "degressionType", "degression",
    "minimumDepth",     "peckingRetract",  "firstFeedrateFactor", "topDwell", "bottomDwell",
    "pitch",            "tappingSpeed",    "retractSpeed"};

DrillOp JobReader::read_drill(Fields& f, int tool_number) {
    DrillOp op;
    op.path = f.path();
    op.tool = tool_number;
    op.comment = f.optional_string("comment").value_or("");
    DrillParams& p = op.params;

    p.kind = f.choice<CycleKind>("cycle",
                                 {{"drill", CycleKind::drill},
                                  {"dwell", CycleKind::dwell},
                                  {"deep", CycleKind::deep},
                                  {"chip-break", CycleKind::chip_break},
                                  {"tap", CycleKind::tap},
                                  {"tap-left", CycleKind::tap_left},
                                  {"ream", CycleKind::ream},
                                  {"bore-stop", CycleKind::bore_stop},
                                  {"bore-dwell", CycleKind::bore_dwell}},
                                 CycleKind::drill);
    const CycleInfo& cycle = *std::find_if(cycles().begin(), cycles().end(),
                                           [&](const CycleInfo& c) { return c.kind == p.kind; });
    const bool tapping = p.kind == CycleKind::tap || p.kind == CycleKind::tap_left;
    // Of the parameters this cycle does not use, report the one that comes first in the file.
    std::optional<std::string_view> unused;
    int unused_line = 0;
    for (std::string_view key : cycle_parameters) {
        if (!f.has(key)) continue;
        if (std::find(cycle.uses.begin(), cycle.uses.end(), key) != cycle.uses.end()) continue;
        const int line = source_.lines.line_of(f.path_of(key));
        if (!unused || line < unused_line) {
            unused = key;
            unused_line = line;
        }
    }
    if (unused) {
        const std::string_view key = *unused;
        std::string detail = fmt::format("{} is not used by cycle {} (it uses: {})", key,
                                         cycle.name, fmt::join(cycle.uses, ", "));
        if (tapping && key == "plungingFeedrate") detail += "; a tapping feed is pitch x rpm";
        f.fail(key, detail);
    }

    // Planes and depths.
    p.retract_plane = optional_length(f, "retractPlane").value_or(job_.clearance);
    p.reference_plane = optional_length(f, "referencePlane").value_or(0.0);
    p.safe_distance = optional_length(f, "safeDistance");
    p.safe_distance_is_absolute = f.boolean("safeDistanceIsAbsolute", false);
    p.end_depth = length(f, "endDepth");
    p.end_depth_is_absolute = f.boolean("endDepthIsAbsolute", false);

    if (p.safe_distance && !p.safe_distance_is_absolute && *p.safe_distance < 0)
        f.fail("safeDistance",
               "a relative safeDistance cannot be negative (it is measured up from "
               "referencePlane; set safeDistanceIsAbsolute for an absolute Z)");
    if (!p.end_depth_is_absolute && p.end_depth <= 0)
        f.fail("endDepth",
               "a relative endDepth must be > 0 (it is the depth below referencePlane; set "
               "endDepthIsAbsolute for an absolute Z)");
    const double safe_z = !p.safe_distance               ? p.retract_plane
                          : p.safe_distance_is_absolute ? *p.safe_distance
                                                        : p.reference_plane + *p.safe_distance;
    const double bottom_z = p.end_depth_is_absolute ? p.end_depth : p.reference_plane - p.end_depth;
    if (bottom_z >= safe_z)
        f.fail("endDepth", fmt::format("endDepth is above the safe distance (hole bottom at Z {}, "
                                       "safe distance at Z {})",
                                       show(bottom_z), show(safe_z)));
    if (p.retract_plane < safe_z)
        f.fail("retractPlane",
               fmt::format("retractPlane is below the safe distance (retract plane at Z {}{}, "
                           "safe distance at Z {})",
                           show(p.retract_plane), f.has("retractPlane") ? "" : ", the clearance",
                           show(safe_z)));

    // Feeds.
    p.plunging_feedrate = optional_length(f, "plungingFeedrate");
    if (!tapping && !p.plunging_feedrate)
        f.fail("plungingFeedrate", fmt::format("cycle {} needs plungingFeedrate", cycle.name));
    if (p.plunging_feedrate && *p.plunging_feedrate <= 0)
        f.fail("plungingFeedrate", "plungingFeedrate must be > 0");
    p.retract_feedrate = optional_length(f, "retractFeedrate");
    if (p.retract_feedrate && *p.retract_feedrate <= 0)
        f.fail("retractFeedrate", "retractFeedrate must be > 0");

    // Dwells.
    p.top_dwell = f.optional_number("topDwell");
    p.bottom_dwell = f.optional_number("bottomDwell");
    if (p.top_dwell && *p.top_dwell < 0) f.fail("topDwell", "a dwell cannot be negative");
    if (p.bottom_dwell && *p.bottom_dwell < 0) f.fail("bottomDwell", "a dwell cannot be negative");
    if ((p.kind == CycleKind::dwell || p.kind == CycleKind::bore_dwell) && !p.bottom_dwell)
        f.fail("bottomDwell", fmt::format("cycle {} needs bottomDwell (seconds)", cycle.name));

    // Pecking.
    p.first_depth = optional_length(f, "firstDepth");
    if ((p.kind == CycleKind::deep || p.kind == CycleKind::chip_break) && !p.first_depth)
        f.fail("firstDepth",
               fmt::format("cycle {} needs firstDepth (the depth of a peck)", cycle.name));
    if (p.first_depth && *p.first_depth <= 0) f.fail("firstDepth", "a peck depth must be > 0");
    p.degression_type = f.choice<DegressionType>("degressionType",
                                                 {{"none", DegressionType::none},
                                                  {"value", DegressionType::value},
                                                  {"factor", DegressionType::factor}},
                                                 DegressionType::none);
    p.degression = p.degression_type == DegressionType::factor ? f.optional_number("degression")
                                                               : optional_length(f, "degression");
    p.minimum_depth = optional_length(f, "minimumDepth");
    if (p.minimum_depth && *p.minimum_depth <= 0)
        f.fail("minimumDepth", "minimumDepth must be > 0");
    switch (p.degression_type) {
        case DegressionType::none:
            if (p.degression) f.fail("degression", "degression has no effect without degressionType");
            if (p.minimum_depth)
                f.fail("minimumDepth", "minimumDepth has no effect without degressionType");
            break;
        case DegressionType::value:
            if (!p.degression || *p.degression <= 0)
                f.fail("degression", "degressionType value needs a degression > 0 (mm taken off each peck)");
            break;
        case DegressionType::factor:
            if (!p.degression || *p.degression <= 0 || *p.degression > 1)
                f.fail("degression",
                       "degressionType factor needs a degression with 0 < degression <= 1 (each "
                       "peck is the previous one times the factor)");
            break;
    }
    if (p.degression_type != DegressionType::none && !p.minimum_depth)
        f.fail("degressionType",
               "a degression needs a positive minimumDepth, or the pecks shrink towards zero "
               "forever");
    p.pecking_retract = optional_length(f, "peckingRetract");
    if (p.pecking_retract && *p.pecking_retract <= 0)
        f.fail("peckingRetract", "peckingRetract must be > 0");
    p.first_feedrate_factor = f.optional_number("firstFeedrateFactor");
    if (p.first_feedrate_factor && *p.first_feedrate_factor <= 0)
        f.fail("firstFeedrateFactor", "firstFeedrateFactor must be > 0");

    // Tapping.
    p.pitch = optional_length(f, "pitch");
    if (tapping && !p.pitch)
        f.fail("pitch", fmt::format("cycle {} needs pitch (the thread lead per revolution)",
                                    cycle.name));
    if (p.pitch && *p.pitch <= 0) f.fail("pitch", "pitch must be > 0");
    p.tapping_speed = f.optional_number("tappingSpeed");
    if (p.tapping_speed && *p.tapping_speed <= 0) f.fail("tappingSpeed", "tappingSpeed must be > 0");
    p.retract_speed = f.optional_number("retractSpeed");
    if (p.retract_speed && *p.retract_speed <= 0) f.fail("retractSpeed", "retractSpeed must be > 0");

    p.drill_tip = f.boolean("drillTip", false);
    if (p.drill_tip) {
        const Tool& tool = job_.tools.at(tool_number);
        if (!tool.tip_angle)
            f.fail("drillTip", fmt::format("drillTip needs the tool's tipAngle, but tool {} ({}) "
                                           "has none",
                                           tool.number, tool.path));
    }
    p.output = f.choice<CycleOutput>("output",
                                     {{"auto", CycleOutput::automatic},
                                      {"canned", CycleOutput::canned},
                                      {"longhand", CycleOutput::longhand}},
                                     CycleOutput::automatic);
    op.order = f.choice<HoleOrder>(
        "order", {{"as-given", HoleOrder::as_given}, {"shortest", HoleOrder::shortest}},
        HoleOrder::as_given);

    read_holes(f, op.holes);
    return op;
}

void JobReader::read_holes(Fields& f, std::vector<Vec2>& holes) {
    const bool any = f.has("holes") || f.has("grid") || f.has("boltCircle") || f.has("line");
    if (!any)
        f.fail("", "a drill operation needs holes: give at least one of holes, grid, boltCircle "
                   "or line");

    if (f.has("holes")) {
        const Json& list = array(f, "holes");
        const std::string base = f.path_of("holes");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string path = base + "/" + std::to_string(i);
            const Json& hole = list[i];
            if (hole.is_object()) {
                Fields h(hole, path, source_);
                known_keys(h, {"x", "y"});
                holes.push_back({length(h, "x"), length(h, "y")});
            } else if (hole.is_array()) {
                holes.push_back(point(hole, path));
            } else {
                camgen::json::fail(source_, path,
                                   "expected a hole [x, y] or {\"x\": ..., \"y\": ...}, got " +
                                       describe(hole));
            }
        }
        if (holes.empty()) f.fail("holes", "holes is empty: a drill operation needs at least one hole");
    }

    if (const Json* value = f.member("grid")) {
        Fields g(*value, f.path_of("grid"), source_);
        known_keys(g, {"origin", "countX", "countY", "spacingX", "spacingY", "rotation"});
        const Vec2 origin = point(g, "origin");
        const int nx = g.integer("countX");
        if (nx < 1) g.fail("countX", "countX must be 1 or more");
        const int ny = g.integer("countY");
        if (ny < 1) g.fail("countY", "countY must be 1 or more");
        if (static_cast<double>(nx) * ny > max_pattern_holes)
            g.fail("", fmt::format("a grid of {} x {} holes is too many", nx, ny));
        const double sx = length(g, "spacingX");
        const double sy = length(g, "spacingY");
        const Vec2 u = unit_vector(g.optional_number("rotation").value_or(0.0));
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                const double lx = i * sx;
                const double ly = j * sy;
                holes.push_back({origin.x + lx * u.x - ly * u.y, origin.y + lx * u.y + ly * u.x});
            }
        }
    }

    if (const Json* value = f.member("boltCircle")) {
        Fields b(*value, f.path_of("boltCircle"), source_);
        known_keys(b, {"centre", "radius", "count", "startAngle"});
        const Vec2 centre = point(b, "centre");
        const double radius = length(b, "radius");
        if (radius <= 0) b.fail("radius", "radius must be > 0");
        const int count = b.integer("count");
        if (count < 1) b.fail("count", "count must be 1 or more");
        if (count > max_pattern_holes) b.fail("count", "count is too large");
        const double start = b.optional_number("startAngle").value_or(0.0);
        for (int i = 0; i < count; ++i) {
            const Vec2 u = unit_vector(start + 360.0 * i / count);
            holes.push_back({centre.x + radius * u.x, centre.y + radius * u.y});
        }
    }

    if (const Json* value = f.member("line")) {
        Fields l(*value, f.path_of("line"), source_);
        known_keys(l, {"start", "end", "count"});
        const Vec2 a = point(l, "start");
        const Vec2 b = point(l, "end");
        const int count = l.integer("count");
        if (count < 1) l.fail("count", "count must be 1 or more");
        if (count > max_pattern_holes) l.fail("count", "count is too large");
        if (count == 1) {
            holes.push_back(a);
        } else {
            for (int i = 0; i < count; ++i) {
                if (i == count - 1) {
                    holes.push_back(b);  // exactly the end point, no rounding
                    break;
                }
                const double t = static_cast<double>(i) / (count - 1);
                holes.push_back({a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t});
            }
        }
    }
}

ContourOp JobReader::read_contour(Fields& f, int tool_number) {
    ContourOp op;
    op.path = f.path();
    op.tool = tool_number;
    op.comment = f.optional_string("comment").value_or("");
    op.depth = length(f, "depth");
    if (op.depth >= job_.clearance)
        f.fail("depth", fmt::format("depth is above the clearance (cut at Z {}, clearance at Z {}); "
                                    "it must be below",
                                    show(op.depth), show(job_.clearance)));
    op.feed = length(f, "feed");
    if (op.feed <= 0) f.fail("feed", "feed must be > 0");
    op.plunge_feed = optional_length(f, "plungeFeed");
    if (op.plunge_feed && *op.plunge_feed <= 0) f.fail("plungeFeed", "plungeFeed must be > 0");
    op.tolerance = optional_length(f, "tolerance");
    // Finer than any control resolves; a smaller value only multiplies the segments of broken arcs.
    if (op.tolerance && !(*op.tolerance >= 0.0001)) f.fail("tolerance", "tolerance must be at least 0.0001 mm");
    op.start = point(f, "start");

    const Json& elements = array(f, "path");
    if (elements.empty()) f.fail("path", "a contour path needs at least one element");
    const std::string base = f.path_of("path");
    Vec3 current{op.start.x, op.start.y, op.depth};
    auto below_clearance = [&](Fields& at, std::string_view key, double z, const char* what) {
        if (z >= job_.clearance)
            at.fail(key, fmt::format("{} is at or above the clearance (Z {}, clearance at Z {})", what, show(z),
                                     show(job_.clearance)));
    };
    for (std::size_t k = 0; k < elements.size(); ++k) {
        const std::string path = base + "/" + std::to_string(k);
        Fields e(elements[k], path, source_);
        known_keys(e, {"line", "arc", "helix"});
        const int given = int(e.has("line")) + int(e.has("arc")) + int(e.has("helix"));
        if (given != 1) e.fail("", "a path element needs exactly one of \"line\", \"arc\" or \"helix\"");
        if (e.has("line")) {
            const Vec3 end = point3(e, "line", op.depth);
            below_clearance(e, "line", end.z, "the line's end");
            op.elements.emplace_back(PathLine{end});
            current = end;
        } else if (e.has("arc")) {
            Fields a(e.required("arc"), e.path_of("arc"), source_);
            PathArc arc = read_arc(a, current, op.depth);
            op.elements.emplace_back(arc);
            current = arc.end;
        } else {
            Fields h(e.required("helix"), e.path_of("helix"), source_);
            PathHelix helix = read_helix(h, current);
            op.elements.emplace_back(helix);
            current.z = helix.end_z;
        }
        op.element_paths.push_back(path);
    }
    return op;
}

PathArc JobReader::read_arc(Fields& a, const Vec3& current, double depth) {
    known_keys(a, {"end", "centre", "direction", "plane"});
    PathArc arc;
    arc.plane = a.choice<Plane>("plane", {{"xy", Plane::xy}, {"xz", Plane::xz}, {"yz", Plane::yz}}, Plane::xy);
    const char* plane_name = arc.plane == Plane::xy ? "xy" : arc.plane == Plane::xz ? "xz" : "yz";
    const char* normal_axis = arc.plane == Plane::xy ? "z" : arc.plane == Plane::xz ? "y" : "x";
    arc.end = point3(a, "end", depth);
    const Json& centre = a.required("centre");
    if (arc.plane != Plane::xy && !(centre.is_array() && centre.size() == 3))
        a.fail("centre", fmt::format("an {} arc needs its centre as [x, y, z], got {}", plane_name, describe(centre)));
    arc.centre = point3(centre, a.path_of("centre"), current.z);
    // The centre's coordinate along the normal axis is the start's: a centre elsewhere on the
    // axis would be a different arc.
    const double c_normal = to_plane(arc.centre, arc.plane).w, s_normal = to_plane(current, arc.plane).w;
    if (std::abs(c_normal - s_normal) > arc_radius_tolerance)
        a.fail("centre", fmt::format("the centre's {} ({}) must be the start's {} ({}) in an {} arc", normal_axis,
                                     show(c_normal), normal_axis, show(s_normal), plane_name));
    arc.centre = from_plane({to_plane(arc.centre, arc.plane).u, to_plane(arc.centre, arc.plane).v, s_normal}, arc.plane);
    arc.direction = a.choice<ArcDirection>("direction", {{"cw", ArcDirection::cw}, {"ccw", ArcDirection::ccw}});
    const PlanePoint s = to_plane(current, arc.plane), e = to_plane(arc.end, arc.plane), c = to_plane(arc.centre, arc.plane);
    const double r_start = std::hypot(s.u - c.u, s.v - c.v);
    const double r_end = std::hypot(e.u - c.u, e.v - c.v);
    if (std::abs(r_start - r_end) > arc_radius_tolerance)
        a.fail("", fmt::format("start is {:.3f} mm from the centre but end is {:.3f} mm{}", r_start, r_end,
                               arc.plane == Plane::xy ? "" : fmt::format(" (in the {} plane)", plane_name)));
    if (r_start <= min_arc_radius)
        a.fail("", fmt::format("the arc radius is {:.4f} mm; it must be more than {} mm", r_start, min_arc_radius));
    // The highest point of the arc: an arc in XZ or YZ may rise above its ends.
    const ArcGeometry g = resolve_arc(current, ArcSpec{arc.end, arc.centre, arc.direction, arc.plane, 0});
    double top = std::max(current.z, arc.end.z);
    if (arc.plane != Plane::xy) {
        const double up = arc.plane == Plane::xz ? 0.0 : std::numbers::pi / 2;  // angle of +Z in (u, v)
        double delta = arc.direction == ArcDirection::ccw ? up - g.start_angle : g.start_angle - up;
        delta = std::fmod(delta, 2 * std::numbers::pi);
        if (delta < 0) delta += 2 * std::numbers::pi;
        if (delta <= g.sweep) top = std::max(top, (arc.plane == Plane::xz ? c.u : c.v) + r_start);
    }
    if (top >= job_.clearance)
        a.fail("", fmt::format("the arc reaches Z {}, at or above the clearance (Z {})", show(top), show(job_.clearance)));
    return arc;
}

PathHelix JobReader::read_helix(Fields& h, const Vec3& current) {
    known_keys(h, {"centre", "direction", "depth", "turns", "pitch"});
    PathHelix helix;
    helix.centre = point(h, "centre");
    helix.direction = h.choice<ArcDirection>("direction", {{"cw", ArcDirection::cw}, {"ccw", ArcDirection::ccw}});
    const double radius = std::hypot(current.x - helix.centre.x, current.y - helix.centre.y);
    if (radius <= min_arc_radius)
        h.fail("centre", fmt::format("the helix radius is {:.4f} mm; it must be more than {} mm", radius, min_arc_radius));
    const bool has_depth = h.has("depth"), has_turns = h.has("turns"), has_pitch = h.has("pitch");
    if (int(has_depth) + int(has_turns) + int(has_pitch) != 2)
        h.fail("", "a helix needs exactly two of \"depth\" (end Z), \"turns\" and \"pitch\" (Z travel per turn, down)");
    std::optional<double> pitch = optional_length(h, "pitch");
    if (pitch && *pitch <= 0) h.fail("pitch", "pitch must be > 0 (the helix goes down by it each turn)");
    if (has_turns) {
        const int turns = h.integer("turns");
        if (turns < 1 || turns > 100000) h.fail("turns", "turns must be a whole number from 1 to 100000");
        helix.turns = turns;
    }
    if (has_depth) {
        helix.end_z = length(h, "depth");
        if (std::abs(helix.end_z - current.z) < 1e-9)
            h.fail("depth", fmt::format("the helix starts and ends at Z {}; a helix must change Z (use an arc for a circle)",
                                        show(current.z)));
        if (helix.end_z >= job_.clearance)
            h.fail("depth", fmt::format("depth is at or above the clearance (Z {}, clearance at Z {})", show(helix.end_z),
                                        show(job_.clearance)));
        if (pitch) {
            const double turns = std::ceil(std::abs(helix.end_z - current.z) / *pitch - 1e-9);
            if (turns > 100000) h.fail("pitch", "pitch is too small: more than 100000 turns");
            helix.turns = static_cast<int>(turns);
        }
    } else {
        helix.end_z = current.z - helix.turns * *pitch;
    }
    return helix;
}

std::string default_name(const std::string& source_name) {
    if (source_name.empty() || source_name.front() == '<') return "job";
    std::string stem = std::filesystem::path(source_name).stem().string();
    return stem.empty() ? "job" : stem;
}

}  // namespace

Job read_job(std::string_view text, const std::string& source_name) {
    const Json root = camgen::json::parse(text, source_name);
    const Source source{source_name, camgen::json::LineMap(text)};
    return JobReader(source).read(root, default_name(source_name));
}

Job read_job_file(const std::string& filename) {
    std::string text;
    if (filename == "-") {
        std::ostringstream buffer;
        buffer << std::cin.rdbuf();
        if (std::cin.bad()) throw IoError("cannot read <stdin>: " + std::string(std::strerror(errno)));
        return read_job(buffer.str(), "<stdin>");
    }
    std::error_code ec;
    if (std::filesystem::is_directory(filename, ec))
        throw IoError("cannot read " + filename + ": " + std::strerror(EISDIR));
    std::ifstream in(filename, std::ios::binary);
    if (!in) throw IoError("cannot read " + filename + ": " + std::strerror(errno));
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) throw IoError("cannot read " + filename + ": " + std::strerror(errno));
    return read_job(text, filename);
}

}  // namespace camgen
