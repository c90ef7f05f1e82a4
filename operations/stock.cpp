#include "camgen/operations/stock.hpp"

#include <algorithm>
#include <array>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/geometry/region.hpp"
#include "camgen/operations/cutting.hpp"

namespace camgen {

namespace {

using Json = nlohmann::json;
using Fields = json::Fields;

constexpr KeySpec stock_keys[] = {
    {.key = "box", .type = JsonType::object, .ref = "stockBox", .description = "a mill's stock: a box, by its corners or by its size"},
    {.key = "profile", .type = JsonType::object, .ref = "stockProfile",
     .description = "a mill's stock: a closed outline in XY from a bottom up to a top"},
    {.key = "bar", .type = JsonType::object, .ref = "stockBar", .description = "a lathe's stock: a bar (or tube) on the spindle axis"},
};

constexpr KeySpec stock_box_keys[] = {
    {.key = "min", .type = JsonType::array, .quantity = Quantity::length, .items = JsonType::number, .min_items = 3,
     .description = "the corner with the least X, Y and Z [x, y, z]"},
    {.key = "max", .type = JsonType::array, .quantity = Quantity::length, .items = JsonType::number, .min_items = 3,
     .description = "the opposite corner [x, y, z], above min in X, Y and Z; its Z is the stock top"},
    {.key = "size", .type = JsonType::array, .quantity = Quantity::length, .items = JsonType::number, .min_items = 3,
     .description = "or the box's size [x, y, z], each > 0"},
    {.key = "origin", .type = JsonType::array, .quantity = Quantity::length, .items = JsonType::number, .min_items = 3,
     .description = "with size: the corner with the least X, Y and Z [x, y, z] (default: [0, 0, -size z]: the top at Z0, "
                    "the work zero at the front left top corner)"},
};

constexpr KeySpec stock_profile_extra_keys[] = {
    {.key = "top", .quantity = Quantity::length, .required = true, .description = "absolute Z of the stock top"},
    {.key = "bottom", .quantity = Quantity::length, .required = true, .description = "absolute Z of the stock bottom, below top"},
};

constexpr KeySpec stock_bar_keys[] = {
    {.key = "diameter", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "the bar's outer diameter"},
    {.key = "length", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "how far the bar reaches back from its face, along Z"},
    {.key = "faceZ", .quantity = Quantity::length, .default_json = "0", .description = "absolute Z of the bar's face"},
    {.key = "boreDiameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a tube's inner diameter, less than diameter (default: none, a solid bar)"},
};

std::vector<KeySpec> stock_profile_keys() {
    std::vector<KeySpec> keys = profile_keys("stock");
    keys.insert(keys.end(), std::begin(stock_profile_extra_keys), std::end(stock_profile_extra_keys));
    return keys;
}

constexpr std::array<const char*, 3> stock_axis_names{"X", "Y", "Z"};

// A point [x, y, z] at `key`, as mm.
Vec3 stock_triple(Fields& f, const JobInput& in, std::string_view key) {
    const Json& value = f.required(key);
    const std::string path = f.path_of(key);
    if (!value.is_array() || value.size() != 3)
        json::fail(in.source(), path, "expected a point [x, y, z], got " + JobInput::describe(value));
    return {in.coordinate(value[0], path + "/0"), in.coordinate(value[1], path + "/1"), in.coordinate(value[2], path + "/2")};
}

double stock_axis(const Vec3& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

Stock read_stock_box(Fields& b, const JobInput& in) {
    JobInput::known_keys(b, stock_box_keys);
    Stock s;
    s.shape = StockShape::box;
    if (b.has("min") == b.has("size")) b.fail("", "a stock box needs either min and max, or size (and origin)");
    if (b.has("min")) {
        if (b.has("origin")) b.fail("origin", "origin goes with size; with min and max the box is given");
        if (b.has("size")) b.fail("size", "size goes without min and max");
        s.min = stock_triple(b, in, "min");
        s.max = stock_triple(b, in, "max");
        for (int axis = 0; axis < 3; ++axis)
            if (!(stock_axis(s.max, axis) - stock_axis(s.min, axis) >= min_profile_segment))
                json::fail(in.source(), b.path_of("max") + "/" + std::to_string(axis),
                           fmt::format("max {} ({}) must be above min {} ({})", stock_axis_names[axis],
                                       in.show(stock_axis(s.max, axis)), stock_axis_names[axis], in.show(stock_axis(s.min, axis))));
    } else {
        if (b.has("max")) b.fail("max", "max goes with min; with size the box is given by its size and origin");
        const Vec3 size = stock_triple(b, in, "size");
        for (int axis = 0; axis < 3; ++axis)
            if (!(stock_axis(size, axis) >= min_profile_segment))
                json::fail(in.source(), b.path_of("size") + "/" + std::to_string(axis),
                           fmt::format("the size in {} ({}) must be more than 0", stock_axis_names[axis], in.show(stock_axis(size, axis))));
        s.min = b.has("origin") ? stock_triple(b, in, "origin") : Vec3{0.0, 0.0, -size.z};
        s.max = {s.min.x + size.x, s.min.y + size.y, s.min.z + size.z};
    }
    s.outline.start = {s.min.x, s.min.y};
    for (Vec2 p : {Vec2{s.max.x, s.min.y}, Vec2{s.max.x, s.max.y}, Vec2{s.min.x, s.max.y}, Vec2{s.min.x, s.min.y}})
        s.outline.segments.push_back({p, std::nullopt, ArcDirection::ccw});
    return s;
}

Stock read_stock_profile(Fields& p, const JobInput& in) {
    JobInput::known_keys(p, stock_profile_keys());
    Stock s;
    s.shape = StockShape::profile;
    s.outline = read_profile(p, in, "the stock's outline");
    if (!is_closed(s.outline))
        p.fail("path", fmt::format("the stock's outline must be closed, but it ends at ({}, {}), not at its start ({}, {})",
                                   in.show(s.outline.segments.back().end.x), in.show(s.outline.segments.back().end.y),
                                   in.show(s.outline.start.x), in.show(s.outline.start.y)));
    if (const std::optional<RegionProblem> problem = region_problem(PlaneRegion{s.outline, {}})) p.fail("path", problem->message);
    const double top = in.length(p, "top"), bottom = in.length(p, "bottom");
    if (!(top - bottom >= min_profile_segment))
        p.fail("bottom", fmt::format("bottom (Z {}) must be below top (Z {})", in.show(bottom), in.show(top)));
    const std::vector<Vec2> points = sample_profile(s.outline, 0.001);
    s.min = {points.front().x, points.front().y, bottom};
    s.max = {points.front().x, points.front().y, top};
    for (Vec2 q : points) {
        s.min.x = std::min(s.min.x, q.x);
        s.min.y = std::min(s.min.y, q.y);
        s.max.x = std::max(s.max.x, q.x);
        s.max.y = std::max(s.max.y, q.y);
    }
    return s;
}

Stock read_stock_bar(Fields& b, const JobInput& in) {
    JobInput::known_keys(b, stock_bar_keys);
    Stock s;
    s.shape = StockShape::bar;
    s.diameter = in.length(b, "diameter");
    if (!(s.diameter > 0)) b.fail("diameter", "a bar's diameter must be > 0");
    s.length = in.length(b, "length");
    if (!(s.length > 0)) b.fail("length", "a bar's length must be > 0");
    s.face_z = in.optional_length(b, "faceZ").value_or(0.0);
    s.bore_diameter = in.optional_length(b, "boreDiameter");
    if (s.bore_diameter && !(*s.bore_diameter > 0 && *s.bore_diameter < s.diameter))
        b.fail("boreDiameter", fmt::format("boreDiameter {} must be more than 0 and less than the bar's diameter ({})",
                                           in.show(*s.bore_diameter), in.show(s.diameter)));
    const double r = s.diameter / 2;
    s.min = {-r, -r, s.face_z - s.length};
    s.max = {r, r, s.face_z};
    return s;
}

}  // namespace

std::vector<ObjectSpec> stock_objects() {
    return {
        {.name = "stock", .description = "the material before the first operation: exactly one of box, profile (mills) or bar (lathes)",
         .keys = {std::begin(stock_keys), std::end(stock_keys)},
         .groups = {{.keys = {"box", "profile", "bar"}, .min = 1, .max = 1, .description = "exactly one of box, profile or bar"}}},
        {.name = "stockBox", .description = "a box of stock: min and max, or size and optionally origin",
         .keys = {std::begin(stock_box_keys), std::end(stock_box_keys)},
         .groups = {{.keys = {"min", "size"}, .min = 1, .max = 1, .description = "exactly one of min (with max) or size"},
                    {.keys = {"max", "size"}, .min = 1, .max = 1, .description = "exactly one of max (with min) or size"},
                    {.keys = {"min", "origin"}, .min = 0, .max = 1, .description = "origin only with size"}}},
        {.name = "stockProfile", .description = "stock as a prism: a closed outline in XY from bottom up to top",
         .keys = stock_profile_keys()},
        {.name = "stockBar", .description = "a lathe's bar (or tube) on the spindle axis, from its face back along Z",
         .keys = {std::begin(stock_bar_keys), std::end(stock_bar_keys)}},
    };
}

void read_stock(Fields& top, JobInput& in) {
    const Json* value = top.member("stock");
    if (!value) return;
    Fields f(*value, top.path_of("stock"), in.source());
    if (!value->is_object()) f.fail("", "expected an object, got " + JobInput::describe(*value));
    // A shape's keys straight in "stock": said where they go.
    for (const auto& [key, shape] : {std::pair{"min", "box"}, std::pair{"max", "box"}, std::pair{"size", "box"},
                                     std::pair{"origin", "box"}, std::pair{"start", "profile"}, std::pair{"path", "profile"},
                                     std::pair{"top", "profile"}, std::pair{"bottom", "profile"},
                                     std::pair{"diameter", "bar"}, std::pair{"length", "bar"}, std::pair{"faceZ", "bar"},
                                     std::pair{"boreDiameter", "bar"}})
        if (f.has(key) && !f.has(shape))
            f.fail(key, fmt::format("{} belongs in the stock's {}: \"stock\": {{\"{}\": {{\"{}\": ...}}}}", key, shape, shape, key));
    JobInput::known_keys(f, stock_keys);
    const int given = int{f.has("box")} + int{f.has("profile")} + int{f.has("bar")};
    if (given != 1)
        f.fail(given == 0 ? "" : f.has("bar") ? "bar" : "profile",
               "a stock is exactly one of box, profile (mills) or bar (lathes)");
    const std::string_view key = f.has("box") ? "box" : f.has("profile") ? "profile" : "bar";
    const Json& shape = f.required(key);
    Fields s(shape, f.path_of(key), in.source());
    if (!shape.is_object()) s.fail("", "expected an object, got " + JobInput::describe(shape));
    Stock stock = key == "box" ? read_stock_box(s, in) : key == "profile" ? read_stock_profile(s, in) : read_stock_bar(s, in);
    stock.path = s.path();
    stock.line = in.source().lines.line_of_early(stock.path);
    stock.source = in.source().name;
    // Every move between operations runs at the clearance: above the material. (The stock is
    // kept all the same: the operations read against it, with errors of their own.)
    in.set_stock(std::move(stock));
    const Stock& kept = *in.header().stock;
    const double clearance = in.header().clearance;
    if (!(clearance > kept.top()))
        top.fail("clearance", fmt::format("the clearance (Z {}) is not above {}: moves between operations would run "
                                          "through the material",
                                          in.show(clearance), stock_top_text(kept, in)));
}

std::string stock_top_text(const Stock& stock, const JobInput& in) {
    return fmt::format("{} (Z {}, {})", stock.for_mill() ? "the stock top" : "the bar's face", in.show(stock.top()), stock.path);
}

void check_stock_machine_kind(const Stock& stock, MachineKind kind, const std::string& machine_name) {
    const MachineKind made_for = stock.for_mill() ? MachineKind::mill : MachineKind::lathe;
    if (made_for == kind) return;
    throw InputError(stock.path,
                     fmt::format("a stock {} is for a {}, and machine {} is a {}: {}", stock.for_mill() ? "box or profile" : "bar",
                                 name_of(machine_kinds, made_for), machine_name, name_of(machine_kinds, kind),
                                 kind == MachineKind::lathe ? "give a lathe's stock as a bar" : "give a mill's stock as a box or profile"),
                     stock.line, stock.source);
}

}  // namespace camgen
