#include "camgen/operations/turn_face/turn_face.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

constexpr KeySpec turn_face_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a turning-tool of orientation 2"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "xValues", .type = JsonType::string, .default_json = "\"diameter\"", .choices = &choices_of<x_values>,
     .description = "outerX and innerX as diameters or as radii"},
    {.key = "feed", .quantity = Quantity::feed, .required = true, .min = Bound{0, false},
     .description = "cutting feed across the face, per minute or per revolution (feedMode)"},
    {.key = "feedMode", .type = JsonType::string, .default_json = "\"per-minute\"", .choices = &choices_of<feed_modes>,
     .description = "feed in mm/min or mm/rev; the program feeds the same way (G94/G95, Fanuc T G98/G99)"},
    {.key = "outerX", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "X (as xValues) the face starts at (default: the stock bar's diameter; required without a bar)"},
    {.key = "innerX", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "X (as xValues) the face ends at: 0 faces to the spindle axis"},
    {.key = "startZ", .quantity = Quantity::length,
     .description = "Z of the face before facing (default: the stock bar's face; required without a bar)"},
    {.key = "z", .quantity = Quantity::length, .required = true, .description = "Z of the finished face"},
    {.key = "stepdown", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the most material one pass takes off in Z; the passes are equal (default: one pass)"},
    {.key = "approachDistance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "1",
     .description = "how far outside the outer X the feed across the face begins (radial), mm"},
    {.key = "lift", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "0.5",
     .description = "how far the tool feeds off the face in +Z and +X (each) before it rapids back across, mm"},
};

double turn_face_radius(const JobInput& in, Fields& f, std::string_view key, XValues xv) {
    const double v = in.length(f, key);
    if (v < 0) f.fail(key, fmt::format("{} is negative: X is measured from the spindle axis", key));
    return xv == XValues::diameter ? v / 2.0 : v;
}

}  // namespace

std::vector<ObjectSpec> TurnFaceOp::objects() {
    return {{.name = "turn-face",
             .description = "facing the bar's end on a lathe in passes down to a Z, lifting off the face before each "
                            "return",
             .keys = {std::begin(turn_face_keys), std::end(turn_face_keys)}}};
}

TurnFaceOp TurnFaceOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, turn_face_keys);
    const OutsideTurningHead head = read_outside_turning_head(f, in, "turn-face");
    const Tool& tool = *head.tool;
    TurnFaceOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    const XValues xv = head.given_x;
    op.given_x = xv;
    op.feed_mode = head.feed_mode;
    op.feed = head.feed;
    const std::optional<Stock>& stock = in.header().stock;
    const bool bar = stock && stock->shape == StockShape::bar;
    if (f.has("outerX")) op.outer = turn_face_radius(in, f, "outerX", xv);
    else if (bar) op.outer = stock->diameter / 2;
    else f.fail("outerX", "give outerX (the X the face starts at), or a stock bar whose diameter it is");
    if (f.has("innerX")) op.inner = turn_face_radius(in, f, "innerX", xv);
    if (!(op.inner < op.outer)) f.fail("innerX", "innerX must be less than outerX: the face runs from outerX in to innerX");
    // To the axis the tip goes past the centre by the nose radius: the nose's centre reaches the
    // axis and its lowest point on the face sweeps the whole face. With the tip only at X0 the
    // nose's round would leave a nub of up to its radius standing at the centre.
    op.tip_end = op.inner > 0 ? op.inner : -tool.nose_radius;
    if (f.has("startZ")) op.start_z = in.length(f, "startZ");
    else if (bar) op.start_z = stock->face_z;
    else f.fail("startZ", "give startZ (the Z of the face before), or a stock bar whose face it is");
    op.z = in.length(f, "z");
    if (op.z > op.start_z) f.fail("z", fmt::format("z {} is above startZ {}: facing takes material off the end", in.show(op.z), in.show(op.start_z)));
    const double clearance = in.header().clearance;
    op.approach = in.optional_length(f, "approachDistance").value_or(1.0);
    if (!(op.approach > 0)) f.fail("approachDistance", "approachDistance must be > 0");
    op.lift = in.optional_length(f, "lift").value_or(0.5);
    if (!(op.lift > 0)) f.fail("lift", "lift must be > 0");
    if (op.start_z + op.lift >= clearance)
        f.fail("z", fmt::format("the face's Z {} and the lift {} reach the clearance (Z {}): the tool returns below it",
                                in.show(op.start_z), in.show(op.lift), in.show(clearance)));
    const double depth = op.start_z - op.z;
    int count = 1;
    if (auto step = in.optional_length(f, "stepdown")) {
        if (!(*step > 0)) f.fail("stepdown", "stepdown must be > 0");
        count = std::max(1, static_cast<int>(std::ceil(depth / *step - 1e-9)));
        if (count > 10000) f.fail("stepdown", fmt::format("stepdown {} makes {} passes: more than 10000", in.show(*step), count));
    }
    // Equal passes; a face already at z still gets one pass (a skim at z).
    for (int k = 1; k <= count; ++k) op.passes.push_back(k == count ? op.z : op.start_z - depth * k / count);
    return op;
}

void expand(const TurnFaceOp& op, const Context& ctx, EventSink& sink) {
    const double out = op.outer + op.approach;
    // (radius, Z) as a position.
    auto at = [](double r, double z) { return Vec3{r, 0.0, z}; };
    sink.emit(Rapid{at(out, ctx.job.clearance)});
    for (double z : op.passes) {
        sink.emit(Rapid{at(out, z)});
        sink.emit(Linear{at(op.tip_end, z), op.feed, Movement::cutting});
        // Off the face before the return: the return runs lift above the face just cut.
        sink.emit(Linear{at(op.tip_end + op.lift, z + op.lift), op.feed, Movement::lead_out});
        sink.emit(Rapid{at(out, z + op.lift)});
    }
    sink.emit(Rapid{at(out, ctx.job.clearance)});
}

std::string default_name(const TurnFaceOp& op) { return op.comment.empty() ? "turn face" : op.comment; }

}  // namespace camgen
