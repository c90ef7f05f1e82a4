#include "camgen/operations/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/dxf_source.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;
using Json = nlohmann::json;

constexpr std::string_view shape_names[] = {"rectangle", "circle", "slot", "polygon"};

constexpr KeySpec shape_key_table[] = {
    {.key = "rectangle", .type = JsonType::object, .ref = "shapeRectangle", .description = "or a rectangle: width and height, placed by its corner or centre, corners rounded or not"},
    {.key = "circle", .type = JsonType::object, .ref = "shapeCircle", .description = "or a circle: centre and diameter"},
    {.key = "slot", .type = JsonType::object, .ref = "shapeSlot", .description = "or an obround slot: two centres, or centre, length and angle; and width"},
    {.key = "polygon", .type = JsonType::object, .ref = "shapePolygon", .description = "or a regular polygon: centre, sides, diameter or acrossFlats, angle"},
};

constexpr KeySpec shape_rectangle_keys[] = {
    {.key = "width", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "size in X"},
    {.key = "height", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "size in Y"},
    {.key = "corner", .type = JsonType::point, .quantity = Quantity::length, .description = "the corner of least X and Y [x, y]"},
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .description = "or the centre [x, y]"},
    {.key = "cornerRadius", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "the corners rounded by arcs of this radius (at most half the smaller side)"},
};

constexpr KeySpec shape_circle_keys[] = {
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "the centre [x, y]"},
    {.key = "diameter", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "the diameter"},
};

constexpr KeySpec shape_slot_keys[] = {
    {.key = "width", .quantity = Quantity::length, .required = true, .min = Bound{0, false}, .description = "the slot's width (its ends' diameter)"},
    {.key = "centres", .type = JsonType::array, .quantity = Quantity::length, .items = JsonType::point, .min_items = 2,
     .description = "the centres of its two end arcs [[x, y], [x, y]]"},
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .description = "or the slot's middle [x, y]"},
    {.key = "length", .quantity = Quantity::length, .min = Bound{0, false}, .description = "with centre: the overall length, end to end (more than width)"},
    {.key = "angle", .quantity = Quantity::angle, .default_json = "0", .description = "with centre: the slot's direction, degrees from +X"},
};

constexpr KeySpec shape_polygon_keys[] = {
    {.key = "centre", .type = JsonType::point, .quantity = Quantity::length, .required = true, .description = "the centre [x, y]"},
    {.key = "sides", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{3, true}, .max = Bound{1000, true},
     .description = "how many sides"},
    {.key = "diameter", .quantity = Quantity::length, .min = Bound{0, false}, .description = "across the corners (the circumscribed circle)"},
    {.key = "acrossFlats", .quantity = Quantity::length, .min = Bound{0, false}, .description = "or across the flats (the inscribed circle)"},
    {.key = "angle", .quantity = Quantity::angle, .default_json = "0", .description = "the direction of the first corner from the centre, degrees from +X"},
};

std::vector<KeySpec> profile_source_keys() {
    std::vector<KeySpec> keys = dxf_source_objects()[0].keys;
    for (KeySpec& k : keys)
        if (k.key == "dxf") {
            k.required = false;
            k.description = "the profile from a DXF drawing (relative to the job file): its lines, arcs and polylines on the selection, chained";
        }
    keys.insert(keys.end(), std::begin(shape_key_table), std::end(shape_key_table));
    return keys;
}

// The profile's builder: segments from the current end.
struct ShapeWalk {
    Profile p;
    Vec2 at;
    explicit ShapeWalk(Vec2 start) : at(start) { p.start = start; }
    void line(Vec2 to) {
        if (distance(at, to) > 1e-9) p.segments.push_back({to, std::nullopt, ArcDirection::ccw});
        at = to;
    }
    void arc(Vec2 to, Vec2 centre) {
        if (distance(at, to) > 1e-9) p.segments.push_back({to, centre, ArcDirection::ccw});
        at = to;
    }
};

double positive_length(Fields& s, const JobInput& in, std::string_view key) {
    const double v = in.length(s, key);
    if (!(v >= min_profile_segment)) s.fail(key, fmt::format("{} must be at least {} mm", key, min_profile_segment));
    return v;
}

// Exactly one of `a` and `b` in `s`.
void one_of(Fields& s, std::string_view a, std::string_view b) {
    if (s.has(a) && s.has(b)) s.fail(b, fmt::format("give {} or {}, not both", a, b));
    if (!s.has(a) && !s.has(b)) s.fail("", fmt::format("needs {} or {}", a, b));
}

Profile read_rectangle(Fields& s, const JobInput& in) {
    JobInput::known_keys(s, shape_rectangle_keys);
    const double w = positive_length(s, in, "width"), h = positive_length(s, in, "height");
    one_of(s, "corner", "centre");
    const Vec2 lo = s.has("corner") ? in.point(s, "corner") : in.point(s, "centre") - Vec2{w / 2, h / 2};
    const double r = in.optional_length(s, "cornerRadius").value_or(0.0);
    if (!(r >= 0)) s.fail("cornerRadius", "cornerRadius must be >= 0");
    if (r > std::min(w, h) / 2 + 1e-9)
        s.fail("cornerRadius", fmt::format("cornerRadius {} is more than half the smaller side ({}): the corners would overlap",
                                           in.show(r), in.show(std::min(w, h) / 2)));
    if (r > 0 && r < min_profile_segment) s.fail("cornerRadius", fmt::format("cornerRadius must be 0 or at least {} mm", min_profile_segment));
    const Vec2 hi = lo + Vec2{w, h};
    ShapeWalk k({lo.x + w / 2, lo.y});
    k.line({hi.x - r, lo.y});
    if (r > 0) k.arc({hi.x, lo.y + r}, {hi.x - r, lo.y + r});
    k.line({hi.x, hi.y - r});
    if (r > 0) k.arc({hi.x - r, hi.y}, {hi.x - r, hi.y - r});
    k.line({lo.x + r, hi.y});
    if (r > 0) k.arc({lo.x, hi.y - r}, {lo.x + r, hi.y - r});
    k.line({lo.x, lo.y + r});
    if (r > 0) k.arc({lo.x + r, lo.y}, {lo.x + r, lo.y + r});
    k.line(k.p.start);
    return k.p;
}

Profile read_circle(Fields& s, const JobInput& in) {
    JobInput::known_keys(s, shape_circle_keys);
    const Vec2 c = in.point(s, "centre");
    const double r = positive_length(s, in, "diameter") / 2;
    ShapeWalk k({c.x + r, c.y});
    k.arc({c.x - r, c.y}, c);
    k.arc(k.p.start, c);
    return k.p;
}

Profile read_slot(Fields& s, const JobInput& in) {
    JobInput::known_keys(s, shape_slot_keys);
    const double w = positive_length(s, in, "width");
    one_of(s, "centres", "centre");
    Vec2 a, b;
    if (s.has("centres")) {
        for (const char* key : {"length", "angle"})
            if (s.has(key)) s.fail(key, fmt::format("{} goes with centre; centres place the slot", key));
        const Json& list = in.array(s, "centres");
        if (list.size() != 2) s.fail("centres", fmt::format("centres needs two points [[x, y], [x, y]], got {}", list.size()));
        a = in.point(list[0], s.path_of("centres") + "/0");
        b = in.point(list[1], s.path_of("centres") + "/1");
        if (distance(a, b) < min_profile_segment)
            s.fail("centres", "the two centres are at the same place: give a circle for a round hole");
    } else {
        if (!s.has("length")) s.fail("", "a slot by its centre needs length (end to end)");
        const double length = positive_length(s, in, "length");
        if (length < w + min_profile_segment)
            s.fail("length", fmt::format("length {} (end to end) must be more than width {}: give a circle for a round hole",
                                         in.show(length), in.show(w)));
        const double angle = s.optional_number("angle").value_or(0.0);
        if (!std::isfinite(angle) || std::abs(angle) > 360) s.fail("angle", "angle must be from -360 to 360 degrees");
        const Vec2 c = in.point(s, "centre");
        const Vec2 u{std::cos(angle * rad_per_deg), std::sin(angle * rad_per_deg)};
        a = c - u * ((length - w) / 2);
        b = c + u * ((length - w) / 2);
    }
    const Vec2 u = (b - a) * (1.0 / distance(a, b));
    const Vec2 n{-u.y, u.x};
    const double h = w / 2;
    ShapeWalk k((a + b) * 0.5 - n * h);
    k.line(b - n * h);
    k.arc(b + n * h, b);
    k.line(a + n * h);
    k.arc(a - n * h, a);
    k.line(k.p.start);
    return k.p;
}

Profile read_polygon(Fields& s, const JobInput& in) {
    JobInput::known_keys(s, shape_polygon_keys);
    const Vec2 c = in.point(s, "centre");
    const int sides = s.integer("sides");
    if (sides < 3 || sides > 1000) s.fail("sides", "sides must be a whole number from 3 to 1000");
    one_of(s, "diameter", "acrossFlats");
    const double half_turn = pi / sides;
    const double radius = s.has("diameter") ? positive_length(s, in, "diameter") / 2
                                            : positive_length(s, in, "acrossFlats") / 2 / std::cos(half_turn);
    const double angle = s.optional_number("angle").value_or(0.0);
    if (!std::isfinite(angle) || std::abs(angle) > 360) s.fail("angle", "angle must be from -360 to 360 degrees");
    auto corner = [&](int i) {
        const double t = angle * rad_per_deg + 2 * half_turn * i;
        return c + Vec2{radius * std::cos(t), radius * std::sin(t)};
    };
    if (distance(corner(0), corner(1)) < min_profile_segment)
        s.fail("sides", fmt::format("the sides are shorter than {} mm: give fewer sides or a circle", min_profile_segment));
    ShapeWalk k((corner(0) + corner(1)) * 0.5);
    for (int i = 1; i <= sides; ++i) k.line(corner(i % sides));
    k.line(k.p.start);
    return k.p;
}

}  // namespace

std::vector<ObjectSpec> profile_source_objects() {
    return {
        {.name = "profileSource", .description = "a profile from a DXF drawing (dxf and its selection) or a shape: exactly one of dxf, rectangle, circle, slot or polygon",
         .keys = profile_source_keys(),
         .groups = {{.keys = {"dxf", "rectangle", "circle", "slot", "polygon"}, .min = 1, .max = 1,
                     .description = "exactly one of dxf, rectangle, circle, slot or polygon"}}},
        dxf_source_objects()[1],
        {.name = "shapeRectangle", .description = "a rectangle: width and height, placed by exactly one of corner or centre",
         .keys = {std::begin(shape_rectangle_keys), std::end(shape_rectangle_keys)},
         .groups = {{.keys = {"corner", "centre"}, .min = 1, .max = 1, .description = "exactly one of corner or centre"}}},
        {.name = "shapeCircle", .description = "a circle", .keys = {std::begin(shape_circle_keys), std::end(shape_circle_keys)}},
        {.name = "shapeSlot", .description = "an obround slot: straight sides and round ends, by exactly one of centres or centre (with length)",
         .keys = {std::begin(shape_slot_keys), std::end(shape_slot_keys)},
         .groups = {{.keys = {"centres", "centre"}, .min = 1, .max = 1, .description = "exactly one of centres or centre"}}},
        {.name = "shapePolygon", .description = "a regular polygon, sized by exactly one of diameter (across the corners) or acrossFlats",
         .keys = {std::begin(shape_polygon_keys), std::end(shape_polygon_keys)},
         .groups = {{.keys = {"diameter", "acrossFlats"}, .min = 1, .max = 1, .description = "exactly one of diameter or acrossFlats"}}},
    };
}

bool names_a_shape(const Json& value) {
    if (!value.is_object()) return false;
    return std::any_of(std::begin(shape_names), std::end(shape_names), [&](std::string_view n) { return value.contains(std::string(n)); });
}

std::optional<Profile> read_shape_profile(Fields& f, const JobInput& in, std::string_view key) {
    Fields p(f.required(key), f.path_of(key), in.source());
    const std::vector<KeySpec> keys = profile_source_keys();
    JobInput::known_keys(p, keys);
    std::vector<std::string_view> given;
    for (std::string_view n : shape_names)
        if (p.has(n)) given.push_back(n);
    if (given.empty()) {
        if (!p.has("dxf")) p.fail("", "a profile needs dxf (a drawing) or one shape: rectangle, circle, slot or polygon");
        return std::nullopt;
    }
    if (p.has("dxf")) p.fail(given.front(), fmt::format("give dxf (a drawing) or a {}, not both", given.front()));
    if (given.size() > 1) p.fail(given[1], fmt::format("give one shape: {} or {}, not both", given[0], given[1]));
    const std::vector<ObjectSpec> drawing = dxf_source_objects();
    for (const KeySpec& k : drawing[0].keys)
        if (p.has(k.key))
            p.fail(k.key, fmt::format("{} is for a profile from a drawing (dxf); a {} is placed by its own keys", k.key, given.front()));
    Fields s(p.required(given.front()), p.path_of(given.front()), in.source());
    const std::string_view shape = given.front();
    if (shape == "rectangle") return read_rectangle(s, in);
    if (shape == "circle") return read_circle(s, in);
    if (shape == "slot") return read_slot(s, in);
    return read_polygon(s, in);
}

}  // namespace camgen
