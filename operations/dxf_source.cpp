#include "camgen/operations/dxf_source.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/dxf/dxf.hpp"
#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/geometry/transform.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;
using Json = nlohmann::json;

enum class DxfMirror { none, x, y };
constexpr Named<DxfMirror> dxf_mirrors[] = {
    {DxfMirror::none, "none", "as drawn"},
    {DxfMirror::x, "x", "X reversed (mirrored about the Y axis)"},
    {DxfMirror::y, "y", "Y reversed (mirrored about the X axis)"},
};

constexpr KeySpec dxf_source_key_table[] = {
    {.key = "dxf", .type = JsonType::string, .required = true, .description = "the drawing (ASCII DXF), relative to the job file"},
    {.key = "layer", .type = JsonType::string, .description = "only entities on this layer (names without case, as CAD does)"},
    {.key = "colour", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true}, .max = Bound{255, true},
     .description = "only entities of this colour (AutoCAD colour index; BYLAYER resolved)"},
    {.key = "linetype", .type = JsonType::string, .description = "only entities of this linetype (BYLAYER resolved)"},
    {.key = "block", .type = JsonType::string, .description = "only entities inserted through this block"},
    {.key = "diameter", .type = JsonType::array, .quantity = Quantity::length, .items = JsonType::number, .min_items = 2,
     .description = "only circles of a diameter from [min, max] (in the job's units)"},
    {.key = "gapTolerance", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0.01",
     .description = "ends of profile pieces at most this far apart are joined (a note for each gap closed)"},
    {.key = "transform", .type = JsonType::object, .ref = "dxfTransform",
     .description = "from drawing to work coordinates: scaled, mirrored, rotated, then moved"},
};

constexpr KeySpec dxf_transform_key_table[] = {
    {.key = "scale", .quantity = Quantity::count, .min = Bound{0, false}, .default_json = "1", .description = "scale factor (after the drawing's units)"},
    {.key = "mirror", .type = JsonType::string, .default_json = "\"none\"", .choices = &choices_of<dxf_mirrors>,
     .description = "none, x (X reversed) or y (Y reversed)"},
    {.key = "rotate", .quantity = Quantity::angle, .default_json = "0", .description = "counter-clockwise turn about the drawing's origin"},
    {.key = "translate", .type = JsonType::point, .quantity = Quantity::length, .description = "where the drawing's origin goes [x, y]"},
};

// What a dxfSource object says, read.
struct DxfSourceRead {
    dxf::Drawing drawing;
    dxf::Selection selection;
    double to_mm = 1.0;          // mm per drawing unit, times the scale
    Eigen::Isometry2d place = Eigen::Isometry2d::Identity();
    double gap = 0.01;           // mm
    std::string path;            // the object's JSON path
};

DxfSourceRead read_dxf_source(Fields& f, const JobInput& in, std::string_view key, double curve_tolerance, std::vector<std::string>& notes) {
    DxfSourceRead r;
    r.path = f.path_of(key);
    Fields d(f.required(key), r.path, in.source());
    JobInput::known_keys(d, dxf_source_key_table);
    const std::string file = d.string("dxf");
    std::filesystem::path where(file);
    const std::string& job = in.source().name;
    if (where.is_relative() && job != "<stdin>" && !job.empty()) where = std::filesystem::path(job).parent_path() / where;

    double scale = 1.0, rotate = 0.0;
    DxfMirror mirror = DxfMirror::none;
    Vec2 translate;
    if (const Json* t = d.member("transform")) {
        Fields tf(*t, d.path_of("transform"), in.source());
        JobInput::known_keys(tf, dxf_transform_key_table);
        scale = tf.optional_number("scale").value_or(1.0);
        if (!(scale > 0) || scale > 1e6) tf.fail("scale", "scale must be more than 0 and at most 1000000");
        mirror = tf.choice("mirror", dxf_mirrors, DxfMirror::none);
        rotate = tf.optional_number("rotate").value_or(0.0);
        if (!std::isfinite(rotate) || std::abs(rotate) > 360) tf.fail("rotate", "rotate must be from -360 to 360 degrees");
        if (tf.has("translate")) translate = in.point(tf, "translate");
    }
    r.gap = in.optional_length(d, "gapTolerance").value_or(0.01);
    if (!(r.gap >= 0)) d.fail("gapTolerance", "gapTolerance must be >= 0");

    // The units first (the curve tolerance is in the drawing's units), then the geometry.
    dxf::ReadOptions options;
    try {
        // $INSUNITS is read with everything else; the tolerance is set after a first look at
        // the header, which costs one scan of its first lines.
        r.drawing = dxf::read_file(where.string(), options);
    } catch (const dxf::Error& e) {
        d.fail("dxf", e.what());
    }
    std::string unit_name;
    std::optional<double> unit = dxf::mm_per_unit(r.drawing.insunits, &unit_name);
    if (!unit) {
        if (r.drawing.insunits != 0)
            d.fail("dxf", fmt::format("{}: its units ($INSUNITS {}) are not a length camgen knows: set them to mm or inches in the CAD program",
                                      file, r.drawing.insunits));
        unit = in.checked_length(1.0, r.path);
        notes.push_back(fmt::format("{}: {} gives no units ($INSUNITS): taken in the job's units", r.path, file));
    }
    r.to_mm = *unit * scale;
    if (curve_tolerance / r.to_mm < options.curve_tolerance * 0.999 || curve_tolerance / r.to_mm > options.curve_tolerance * 1.001) {
        options.curve_tolerance = curve_tolerance / r.to_mm;
        try {
            r.drawing = dxf::read_file(where.string(), options);
        } catch (const dxf::Error& e) {
            d.fail("dxf", e.what());
        }
    }
    for (const std::string& n : r.drawing.notes) notes.push_back(r.path + ": " + n);

    if (auto v = d.optional_string("layer")) r.selection.layers = {*v};
    if (auto v = d.optional_string("linetype")) r.selection.linetypes = {*v};
    if (auto v = d.optional_string("block")) r.selection.blocks = {*v};
    if (auto v = d.optional_integer("colour")) {
        if (*v < 1 || *v > 255) d.fail("colour", "colour must be an AutoCAD colour index from 1 to 255");
        r.selection.colours = {*v};
    }
    if (d.has("diameter")) {
        const Json& list = in.array(d, "diameter");
        if (list.size() != 2) d.fail("diameter", "diameter needs [min, max]");
        const double lo = in.checked_length(list[0].is_number() ? list[0].get<double>() : -1, d.path_of("diameter") + "/0");
        const double hi = in.checked_length(list[1].is_number() ? list[1].get<double>() : -1, d.path_of("diameter") + "/1");
        if (!(lo >= 0) || !(hi >= lo)) d.fail("diameter", "diameter needs [min, max] with 0 <= min <= max");
        r.selection.min_diameter = lo / r.to_mm;
        r.selection.max_diameter = hi / r.to_mm;
    }
    Eigen::Isometry2d m = Eigen::Isometry2d::Identity();
    m.translate(Eigen::Vector2d(translate.x, translate.y));
    m.rotate(rotate * rad_per_deg);
    if (mirror != DxfMirror::none) {
        Eigen::Matrix2d flip = Eigen::Matrix2d::Identity();
        flip(mirror == DxfMirror::x ? 0 : 1, mirror == DxfMirror::x ? 0 : 1) = -1;
        m.linear() = m.linear() * flip;
    }
    r.place = m;
    return r;
}

Vec2 dxf_to_work(const DxfSourceRead& r, Vec2 p) { return apply(r.place, p * r.to_mm); }

Profile dxf_profile_to_work(const DxfSourceRead& r, const Profile& p) {
    Profile scaled = p;
    scaled.start = scaled.start * r.to_mm;
    for (ProfileSegment& s : scaled.segments) {
        s.end = s.end * r.to_mm;
        if (s.centre) s.centre = *s.centre * r.to_mm;
    }
    return transformed(scaled, r.place);
}

std::string dxf_selection_words(const DxfSourceRead& r) {
    std::vector<std::string> parts;
    if (!r.selection.layers.empty()) parts.push_back("layer " + r.selection.layers[0]);
    if (!r.selection.colours.empty()) parts.push_back("colour " + std::to_string(r.selection.colours[0]));
    if (!r.selection.linetypes.empty()) parts.push_back("linetype " + r.selection.linetypes[0]);
    if (!r.selection.blocks.empty()) parts.push_back("block " + r.selection.blocks[0]);
    if (r.selection.min_diameter) parts.push_back("the diameter range");
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : ", ") + p;
    return out.empty() ? "the whole drawing" : out;
}

}  // namespace

std::vector<ObjectSpec> dxf_source_objects() {
    return {
        {.name = "dxfSource", .description = "geometry from a DXF drawing, selected by layer, colour, linetype, block or diameter",
         .keys = {std::begin(dxf_source_key_table), std::end(dxf_source_key_table)}},
        {.name = "dxfTransform", .description = "drawing to work coordinates: scale, mirror, rotate, translate, in that order",
         .keys = {std::begin(dxf_transform_key_table), std::end(dxf_transform_key_table)}},
    };
}

std::vector<Vec2> read_dxf_holes(Fields& f, const JobInput& in, std::string_view key, std::vector<std::string>& notes) {
    DxfSourceRead r = read_dxf_source(f, in, key, 0.01, notes);
    std::vector<const dxf::Piece*> picked;
    try {
        picked = dxf::select(r.drawing, r.selection, "holes");
    } catch (const dxf::Error& e) {
        f.fail(key, e.what());
    }
    std::vector<Vec2> holes;
    std::vector<const dxf::Piece*> from;
    std::map<std::pair<long long, long long>, std::vector<std::size_t>> cells;
    for (const dxf::Piece* p : picked) {
        if (p->kind == dxf::Piece::Kind::path) continue;
        const Vec2 at = dxf_to_work(r, p->centre);
        // A hole drawn twice (a counterbore's two circles, a point in a circle) is drilled once:
        // holes in cells of 1e-5 mm, the neighbouring cells searched.
        const long long cx = std::llround(std::floor(at.x * 1e5)), cy = std::llround(std::floor(at.y * 1e5));
        std::optional<std::size_t> same;
        for (long long dx = -1; dx <= 1 && !same; ++dx)
            for (long long dy = -1; dy <= 1 && !same; ++dy) {
                const auto found = cells.find({cx + dx, cy + dy});
                if (found == cells.end()) continue;
                for (std::size_t i : found->second)
                    if (distance(holes[i], at) < 1e-6) same = i;
            }
        if (same) {
            notes.push_back(fmt::format("{}: {} is at the same place as {}: one hole", r.path, dxf::describe(p->origin),
                                        dxf::describe(from[*same]->origin)));
            continue;
        }
        cells[{cx, cy}].push_back(holes.size());
        holes.push_back(at);
        from.push_back(p);
    }
    if (holes.empty())
        f.fail(key, fmt::format("{} has no circles or points on {}", std::filesystem::path(r.drawing.name).filename().string(),
                                dxf_selection_words(r)));
    in.claim_holes(static_cast<double>(holes.size()), f, key);
    return holes;
}

DxfProfiles read_dxf_profiles(Fields& f, const JobInput& in, std::string_view key, double curve_tolerance, std::vector<std::string>& notes) {
    DxfSourceRead r = read_dxf_source(f, in, key, curve_tolerance, notes);
    dxf::ChainResult chained;
    try {
        std::vector<const dxf::Piece*> picked = dxf::select(r.drawing, r.selection, "a profile");
        chained = dxf::chain(picked, r.gap / r.to_mm, std::filesystem::path(r.drawing.name).filename().string());
    } catch (const dxf::Error& e) {
        f.fail(key, e.what());
    }
    for (const std::string& n : chained.notes) notes.push_back(r.path + ": " + n);
    if (chained.chains.empty())
        f.fail(key, fmt::format("{} has no lines, arcs or polylines on {}", std::filesystem::path(r.drawing.name).filename().string(),
                                dxf_selection_words(r)));
    DxfProfiles out;
    for (const dxf::Chain& c : chained.chains) {
        out.profiles.push_back(dxf_profile_to_work(r, c.profile));
        // An arc whose end a join left within arc_radius_tolerance of its circle: the exact arc
        // through both ends, as a job's (make_arcs_exact, profile.hpp).
        make_arcs_exact(out.profiles.back(), arc_radius_tolerance);
        out.closed.push_back(c.closed);
        std::string words = dxf::describe(c.pieces.front()->origin);
        if (c.pieces.size() > 1 && !c.closed) words += " to " + dxf::describe(c.pieces.back()->origin);
        else if (c.pieces.size() > 1) words += fmt::format(" and {} more", c.pieces.size() - 1);
        out.describe.push_back(words);
    }
    out.parent = dxf::nesting(chained.chains);
    in.claim_path_elements(static_cast<double>(r.drawing.pieces.size()), f, key);
    return out;
}

}  // namespace camgen
