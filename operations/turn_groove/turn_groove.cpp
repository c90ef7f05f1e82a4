#include "camgen/operations/turn_groove/turn_groove.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

constexpr Named<GrooveSide> turn_groove_sides[] = {
    {GrooveSide::external, "external", "into an outside diameter, plunging along -X"},
    {GrooveSide::internal, "internal", "into a bore, plunging along +X (a blade cutting towards +X, orientation 3 or 4)"},
    {GrooveSide::face, "face", "into an end face between innerX and outerX, plunging along -Z (a blade whose edge faces -Z, "
                               "orientation 7)"},
};

constexpr KeySpec turn_groove_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "side", .type = JsonType::string, .default_json = "\"external\"", .choices = &choices_of<turn_groove_sides>,
     .description = "external: into an outside diameter (along -X); internal: into a bore (along +X, startX the bore, "
                    "bottomX beyond it); face: into the end face at z, between innerX and outerX (along -Z)"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a grooving-tool or parting-tool (external: orientation none or 2: its "
                    "programmed point is its left corner; 1: its right corner; internal: 3 left, 4 right; face: 7, its "
                    "inner corner)"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "xValues", .type = JsonType::string, .default_json = "\"diameter\"", .choices = &choices_of<x_values>,
     .description = "startX and bottomX as diameters or as radii"},
    {.key = "feed", .quantity = Quantity::feed, .required = true, .min = Bound{0, false},
     .description = "cutting feed of the plunges and the pass along the bottom, per minute or per revolution (feedMode)"},
    {.key = "feedMode", .type = JsonType::string, .default_json = "\"per-minute\"", .choices = &choices_of<feed_modes>,
     .description = "feed in mm/min or mm/rev; the program feeds the same way (G94/G95, Fanuc T G98/G99)"},
    {.key = "z", .quantity = Quantity::length, .required = true,
     .description = "Z of the groove's wall on the +Z side (towards the bar's face); the groove runs width towards the "
                    "chuck (face: the Z of the end face it is cut into)"},
    {.key = "width", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the groove's width along Z, mm: at least the tool's width (external and internal: required; face: "
                    "none, innerX and outerX)"},
    {.key = "innerX", .quantity = Quantity::length, .min = Bound{0, true},
     .description = "face: X (as xValues) of the groove's inner wall"},
    {.key = "outerX", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "face: X (as xValues) of its outer wall; outerX - innerX (radial) at least the tool's width"},
    {.key = "bottomZ", .quantity = Quantity::length,
     .description = "face: Z of the groove's bottom (give depth or bottomZ)"},
    {.key = "depth", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the groove's depth below startX, radial (per side), mm (give depth or bottomX); internal: beyond "
                    "startX; face: below z, along Z"},
    {.key = "bottomX", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "X (as xValues) of the groove's bottom (give depth or bottomX; internal: beyond startX; not for face)"},
    {.key = "startX", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "X (as xValues) of the surface the groove is cut into, which must be the largest over the groove, its "
                    "chamfers and approachDistance either side: a rapid of the blade through the material an earlier "
                    "turn-profile keeps, or with a bar through the bar's solid that no operation before it turned away, is "
                    "refused (default: the stock bar's diameter; required without a bar); internal: "
                    "the bore's X, the least over them, a rapid through the bar's solid that nothing before bored out "
                    "refused (default: the bar's bore); not for face"},
    {.key = "chamfer", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "a 45-degree chamfer on each edge of the groove, mm along Z and along the radius: the +Z edge's cut "
                    "by the blade's right corner, the -Z edge's by its left corner"},
    {.key = "stepover", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the most distance between neighbouring plunges of a groove wider than the tool, mm, at most the "
                    "tool's width (default: 0.75 of it); the plunges are equally spaced"},
    {.key = "finishAllowance", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0.1",
     .description = "radial material the plunges of a groove wider than the tool leave on the bottom for the finishing "
                    "pass along it, mm"},
    {.key = "peckDepth", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "radial depth of each peck, mm, at least 0.01 and at most 10000 pecks a plunge (default: no pecks, one "
                    "feed to the bottom)"},
    {.key = "peckRetract", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "0.3",
     .description = "how far the blade backs off (rapid) between pecks to break the chip, mm; with fullRetract, how far "
                    "above the depth reached it comes back down at rapid"},
    {.key = "fullRetract", .type = JsonType::boolean, .default_json = "false",
     .description = "between pecks, rapid out to approachDistance above the surface (clears the chips) instead of "
                    "backing off by peckRetract"},
    {.key = "dwell", .quantity = Quantity::time, .min = Bound{0, true}, .default_json = "0",
     .description = "seconds at the bottom of each plunge that reaches it and at the end of the pass along it"},
    {.key = "approachDistance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "1",
     .description = "how far above the surface (radial) the feeds start, and outside the bar the tool moves along Z, mm "
                    "(internal: inside the bore's surface, where the blade moves along Z in and out of the bore; face: "
                    "above the face, along Z)"},
    {.key = "output", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<cycle_outputs>,
     .description = "auto: the machine's grooving cycle (Fanuc T G75; a face groove: G74) where it carries the groove, "
                    "else longhand with a note; canned: the cycle or an error; longhand: G0/G1 moves"},
};

}  // namespace

GrooveBlade read_groove_blade(Fields& f, const JobInput& in, std::string_view what, const Tool*& out, GrooveSide side) {
    const Tool& tool = in.tool(f);
    out = &tool;
    if (tool.type != ToolType::grooving_tool && tool.type != ToolType::parting_tool)
        f.fail("tool", fmt::format("a {} needs a grooving-tool or parting-tool (a blade of a width); tool {} is a {}", what,
                                   tool.number, name_of(tool_types, tool.type)));
    const int o = tool.orientation;
    GrooveBlade b;
    b.width = tool.width;
    switch (side) {
    case GrooveSide::external:
        if (o != 0 && o != 1 && o != 2)
            f.fail("tool", fmt::format("tool {} has orientation {}: a {}'s programmed point is a corner of its blade's edge, "
                                       "the left one (orientation 2, or none) or the right one (orientation 1){}",
                                       tool.number, o, what,
                                       what == "turn-groove" && (o == 3 || o == 4) ? " (3 and 4 are an internal groove's: \"side\": \"internal\")"
                                       : what == "turn-groove" && o == 7          ? " (7 is a face groove's: \"side\": \"face\")"
                                                                                  : ""));
        b.right_point = o == 1;
        break;
    case GrooveSide::internal:
        // The orientation is the one thing a tool says about which way its blade cuts: a blade
        // cutting towards -X in a bore would be swept (and driven) the wrong way.
        if (o != 3 && o != 4)
            f.fail("tool", fmt::format("an internal {} needs a grooving-tool whose blade cuts towards +X, into the bore's "
                                       "wall: orientation 3 (programmed at its left corner) or 4 (its right corner); tool "
                                       "{} has {}",
                                       what, tool.number, o == 0 ? std::string("none") : std::to_string(o)));
        b.right_point = o == 4;
        break;
    case GrooveSide::face:
        if (o != 7)
            f.fail("tool", fmt::format("a face {} needs a grooving-tool whose blade's edge faces -Z, its width along X: "
                                       "orientation 7 (programmed at the edge's inner, -X, corner); tool {} has {}",
                                       what, tool.number, o == 0 ? std::string("none") : std::to_string(o)));
        break;
    }
    return b;
}

GroovePecks read_groove_pecks(Fields& f, const JobInput& in, double depth) {
    GroovePecks p;
    if (auto q = in.optional_length(f, "peckDepth")) {
        if (!(*q > 0)) f.fail("peckDepth", "peckDepth must be > 0");
        // (A peck of a nanometre made a program of millions of lines, or none at all; one below
        // the program's resolution, pecks written at the same X.)
        if (*q < groove_min_peck)
            f.fail("peckDepth", fmt::format("peckDepth must be at least {}", in.show(groove_min_peck)));
        const double pecks = std::ceil(depth / *q - 1e-9);
        if (pecks > groove_max_pecks)
            f.fail("peckDepth", fmt::format("peckDepth {} makes {} pecks of the {} deep plunge, more than {}: use larger pecks",
                                            in.show(*q), number_text(pecks, 0), in.show(depth), number_text(groove_max_pecks, 0)));
        p.peck = *q;
    }
    p.retract = in.optional_length(f, "peckRetract").value_or(0.3);
    if (!(p.retract > 0)) f.fail("peckRetract", "peckRetract must be > 0");
    p.full = f.boolean("fullRetract", false);
    if (p.peck == 0 && (f.has("peckRetract") || f.has("fullRetract")))
        f.fail(f.has("peckRetract") ? "peckRetract" : "fullRetract", "peckRetract and fullRetract go with peckDepth: without it "
                                                                      "the plunge is one feed");
    return p;
}

void emit_groove_plunge(const GrooveBlade& blade, const GroovePlunge& p, const GroovePecks& pecks, EventSink& sink) {
    auto at = [&](double r) { return blade.at(r, p.left_z); };
    // A feed from radius a down to b, split where the reduced feed begins.
    auto feed_down = [&](double a, double b) {
        if (p.slow_below > b && p.slow_below < a) {
            sink.emit(Linear{at(p.slow_below), p.feed, Movement::plunge});
            sink.emit(Linear{at(b), p.slow_feed, Movement::plunge});
        } else {
            sink.emit(Linear{at(b), b < p.slow_below ? p.slow_feed : p.feed, Movement::plunge});
        }
    };
    // The depths reached: pecks from the surface down, the last at the end.
    std::vector<double> depths;
    if (pecks.peck > 0) {
        const int n = std::max(1, static_cast<int>(std::ceil((p.top - p.end) / pecks.peck - 1e-9)));
        for (int k = 1; k < n; ++k) depths.push_back(p.top - pecks.peck * k);
    }
    depths.push_back(p.end);
    double from = p.start;
    for (std::size_t k = 0; k < depths.size(); ++k) {
        if (k > 0) {
            // Back off from the depth reached, then come back to just above it at rapid.
            const double back = depths[k - 1] + pecks.retract;
            if (pecks.full) {
                sink.emit(Rapid{at(p.air)});
                sink.emit(Rapid{at(std::min(back, p.air))});
            } else {
                sink.emit(Rapid{at(std::min(back, p.air))});
            }
            from = std::min(back, p.air);
        }
        feed_down(from, depths[k]);
        from = depths[k];
    }
    if (p.dwell > 0) sink.emit(Dwell{p.dwell});
}

std::vector<ObjectSpec> TurnGrooveOp::objects() {
    return {{.name = "turn-groove",
             .description = "an external groove on a lathe: plunges of a grooving tool, pecked or not, a pass along its "
                            "bottom, chamfered edges",
             .keys = {std::begin(turn_groove_keys), std::end(turn_groove_keys)}}};
}

TurnGrooveOp TurnGrooveOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, turn_groove_keys);
    const Tool* tool = nullptr;
    TurnGrooveOp op;
    op.side = f.choice("side", turn_groove_sides, GrooveSide::external);
    const bool internal = op.side == GrooveSide::internal, face = op.side == GrooveSide::face;
    // Keys of another side, refused by name.
    auto not_here = [&](std::string_view key, std::string_view why) {
        if (f.has(key))
            f.fail(key, fmt::format("{} groove has no {}: {}", face ? "a face" : internal ? "an internal" : "an external", key, why));
    };
    if (face) {
        not_here("startX", "it is cut into the end face at z");
        not_here("bottomX", "its bottom is at depth below z, or at bottomZ");
        not_here("width", "it runs from innerX to outerX");
    } else {
        for (std::string_view k : {"innerX", "outerX", "bottomZ"})
            not_here(k, "innerX, outerX and bottomZ are a face groove's (\"side\": \"face\")");
    }
    op.blade = read_groove_blade(f, in, "turn-groove", tool, op.side);
    op.path = f.path();
    op.tool = tool->number;
    op.comment = f.optional_string("comment").value_or("");
    op.given_x = f.choice("xValues", x_values, XValues::diameter);
    op.feed_mode = f.choice("feedMode", feed_modes, FeedMode::per_minute);
    op.feed = in.length(f, "feed");
    if (!(op.feed > 0)) f.fail("feed", "feed must be > 0");
    if (op.feed_mode == FeedMode::per_revolution) op.feed *= tool->rpm;
    const double scale = op.given_x == XValues::diameter ? 0.5 : 1.0;
    auto x_text = [&](double r) { return in.show(r / scale); };
    const std::optional<Stock>& stock = in.header().stock;
    const bool bar = stock && stock->shape == StockShape::bar;
    const double bar_r = bar ? stock->diameter / 2 : 0.0;
    const double bar_bore = bar ? stock->bore_diameter.value_or(0.0) / 2 : 0.0;
    double width = 0.0;
    const char* depth_key = f.has("depth") ? "depth" : face ? "bottomZ" : "bottomX";
    if (!face) {
        if (f.has("startX")) op.surface = in.length(f, "startX") * scale;
        else if (!internal && bar) op.surface = bar_r;
        else if (internal && bar && bar_bore > 0) op.surface = bar_bore;
        else if (internal)
            f.fail("startX", "give startX (the X of the bore the groove is cut into), or a stock bar with a bore (boreDiameter)");
        else f.fail("startX", "give startX (the X of the surface the groove is cut into), or a stock bar whose diameter it is");
        if (!(op.surface > 0)) f.fail("startX", "startX must be > 0");
        op.outside = bar ? std::max(bar_r, op.surface) : op.surface;
        if (bar && op.surface > bar_r + 1e-9)
            f.fail("startX", fmt::format("startX {} is beyond the bar's X {}: a groove is cut into the bar", x_text(op.surface),
                                         x_text(bar_r)));
        if (internal && bar && op.surface < bar_bore - 1e-9)
            f.fail("startX", fmt::format("startX {} is inside the bar's bore (X {}): an internal groove is cut into the "
                                         "bore's wall",
                                         x_text(op.surface), x_text(bar_bore)));
        op.z_right = in.length(f, "z");
        width = in.length(f, "width");
        if (!(width > 0)) f.fail("width", "width must be > 0");
        if (width < op.blade.width - 1e-9)
            f.fail("width", fmt::format("the groove's width {} is narrower than tool {}'s width {}: a groove is at least as "
                                        "wide as its tool",
                                        in.show(width), tool->number, in.show(op.blade.width)));
        op.z_left = op.z_right - width;
        if (f.has("depth") == f.has("bottomX")) f.fail("depth", "give the groove's depth or its bottomX (one of them)");
        if (f.has("depth")) {
            const double depth = in.length(f, "depth");
            if (!(depth > 0)) f.fail("depth", "depth must be > 0");
            op.bottom = internal ? op.surface + depth : op.surface - depth;
            if (!internal && !(op.bottom > 0))
                f.fail("depth", fmt::format("depth {} reaches the spindle axis from X {} (radius {}): a groove keeps a core; "
                                            "turn-part parts off",
                                            in.show(depth), x_text(op.surface), in.show(op.surface)));
        } else {
            op.bottom = in.length(f, "bottomX") * scale;
            if (!(op.bottom > 0)) f.fail("bottomX", "bottomX must be > 0: a groove keeps a core; turn-part parts off");
            if (!internal && !(op.bottom < op.surface))
                f.fail("bottomX", fmt::format("bottomX {} is not below startX {}: there is no groove to cut", x_text(op.bottom),
                                              x_text(op.surface)));
            if (internal && !(op.bottom > op.surface))
                f.fail("bottomX", fmt::format("bottomX {} is not beyond startX {}: an internal groove's bottom lies outward "
                                              "of its bore",
                                              x_text(op.bottom), x_text(op.surface)));
        }
        if (internal && bar && op.bottom >= bar_r - 1e-9)
            f.fail(depth_key, fmt::format("the groove's bottom X {} reaches the bar's outside X {}", x_text(op.bottom),
                                          x_text(bar_r)));
    } else {
        op.surface = in.length(f, "z");
        if (!f.has("innerX") || !f.has("outerX"))
            f.fail(f.has("innerX") ? "outerX" : "innerX", "give a face groove's innerX and outerX (its walls)");
        op.z_left = in.length(f, "innerX") * scale;
        op.z_right = in.length(f, "outerX") * scale;
        if (!(op.z_left >= 0)) f.fail("innerX", "innerX must be 0 or more");
        if (!(op.z_right > op.z_left))
            f.fail("outerX", fmt::format("outerX {} is not beyond innerX {}", x_text(op.z_right), x_text(op.z_left)));
        width = op.z_right - op.z_left;
        if (width < op.blade.width - 1e-9)
            f.fail("outerX", fmt::format("the groove is {} wide (radial, outerX - innerX), narrower than tool {}'s width {}: "
                                         "the blade must fit between its walls",
                                         in.show(width), tool->number, in.show(op.blade.width)));
        if (bar && op.z_right > bar_r + 1e-9)
            f.fail("outerX", fmt::format("outerX {} is beyond the bar's X {}: a face groove is cut into the bar's face",
                                         x_text(op.z_right), x_text(bar_r)));
        if (f.has("depth") == f.has("bottomZ")) f.fail("depth", "give the groove's depth or its bottomZ (one of them)");
        if (f.has("depth")) {
            const double depth = in.length(f, "depth");
            if (!(depth > 0)) f.fail("depth", "depth must be > 0");
            op.bottom = op.surface - depth;
        } else {
            op.bottom = in.length(f, "bottomZ");
            if (!(op.bottom < op.surface))
                f.fail("bottomZ", fmt::format("bottomZ {} is not below z {}: there is no groove to cut", in.show(op.bottom),
                                              in.show(op.surface)));
        }
        if (bar && op.surface > stock->face_z + 1e-9)
            f.fail("z", fmt::format("z {} is beyond the bar's face (Z {}): the groove is cut into the bar", in.show(op.surface),
                                    in.show(stock->face_z)));
        if (bar && op.bottom < stock->face_z - stock->length + 1e-9)
            f.fail(depth_key, fmt::format("the groove's bottom Z {} reaches the bar's end (Z {})", in.show(op.bottom),
                                          in.show(stock->face_z - stock->length)));
    }
    const double depth = std::abs(op.surface - op.bottom);
    if (tool->flute_length && *tool->flute_length < depth - 1e-9)
        f.fail(depth_key, fmt::format("the groove is {} deep, more than tool {}'s fluteLength {} (how deep its blade reaches)",
                                      in.show(depth), tool->number, in.show(*tool->flute_length)));
    op.chamfer = in.optional_length(f, "chamfer").value_or(0.0);
    if (op.chamfer < 0) f.fail("chamfer", "chamfer must be 0 or more");
    if (op.chamfer >= depth)
        f.fail("chamfer", fmt::format("chamfer {} is not less than the groove's depth {}", in.show(op.chamfer), in.show(depth)));
    if (face && op.z_left - op.chamfer < -1e-9)
        f.fail("chamfer", fmt::format("chamfer {} on the inner wall at X {} reaches past the spindle axis", in.show(op.chamfer),
                                      x_text(op.z_left)));
    if (face && bar && op.z_right + op.chamfer > bar_r + 1e-9)
        f.fail("chamfer", fmt::format("chamfer {} on the outer wall at X {} reaches beyond the bar's X {}", in.show(op.chamfer),
                                      x_text(op.z_right), x_text(bar_r)));
    if (internal && bar && op.z_right + op.chamfer > stock->face_z + 1e-9)
        f.fail("chamfer", fmt::format("the groove's chamfer reaches Z {}, beyond the bar's face (Z {})",
                                      in.show(op.z_right + op.chamfer), in.show(stock->face_z)));
    op.approach = in.optional_length(f, "approachDistance").value_or(1.0);
    if (!(op.approach > 0)) f.fail("approachDistance", "approachDistance must be > 0");
    // A face groove's inner chamfer is entered from approachDistance inside its line's start:
    // that must not be past the spindle axis.
    if (face && op.chamfer > 0 && op.z_left - op.chamfer - op.approach < -1e-9)
        f.fail("approachDistance",
               fmt::format("the inner chamfer (at X {}, chamfer {}) is entered from approachDistance {} inside it, past the "
                           "spindle axis: give a smaller approachDistance or chamfer",
                           x_text(op.z_left), in.show(op.chamfer), in.show(op.approach)));
    // Inside a bore the blade moves along Z approachDistance inside the bore's surface (less the
    // chamfer's reach): it must stay off the spindle axis, on the bore's side of it.
    if (internal && !(op.surface - op.approach > 0))
        f.fail("approachDistance", fmt::format("approachDistance {} from the bore's X {} reaches the spindle axis: the blade "
                                               "moves along Z inside the bore, less than the bore's radius ({}) from it",
                                               in.show(op.approach), x_text(op.surface), in.show(op.surface)));
    op.dwell = f.optional_number("dwell").value_or(0.0);
    if (op.dwell < 0) f.fail("dwell", "dwell must be 0 or more");
    op.pecks = read_groove_pecks(f, in, depth);
    op.output = f.choice("output", cycle_outputs, CycleOutput::automatic);
    const double stepover = in.optional_length(f, "stepover").value_or(0.75 * op.blade.width);
    if (!(stepover > 0) || stepover > op.blade.width + 1e-9)
        f.fail("stepover", fmt::format("stepover {} must be more than 0 and at most tool {}'s width {} (the plunges overlap)",
                                       in.show(stepover), tool->number, in.show(op.blade.width)));
    const double spread = width - op.blade.width;  // the left corner's travel from the +Z wall to the -Z wall
    const int count = spread < 1e-9 ? 1 : static_cast<int>(std::ceil(spread / stepover - 1e-9)) + 1;
    if (count > 10000) f.fail("stepover", fmt::format("stepover {} makes {} plunges: more than 10000", in.show(stepover), count));
    for (int k = 0; k < count; ++k)
        op.plunges.push_back(k == count - 1 ? op.z_left : op.z_right - op.blade.width - (count == 1 ? 0.0 : spread * k / (count - 1)));
    if (count > 1) {
        op.finish = in.optional_length(f, "finishAllowance").value_or(0.1);
        if (op.finish < 0) f.fail("finishAllowance", "finishAllowance must be 0 or more");
        if (op.finish >= depth)
            f.fail("finishAllowance", fmt::format("finishAllowance {} is not less than the groove's depth {}", in.show(op.finish),
                                                  in.show(depth)));
    } else {
        (void)f.optional_number("finishAllowance");
    }
    if (internal)
        op.notes.push_back(fmt::format("an internal groove: the bore (X {}) must be there before it, made by an earlier "
                                       "operation or the stock's boreDiameter, from the face down to the groove; the blade "
                                       "moves along Z inside it at X {} (camgen simulate checks what the program cuts)",
                                       x_text(op.surface), x_text(op.surface - op.approach)));
    const double clearance = in.header().clearance;
    if (face) {
        if (op.surface + op.approach >= clearance)
            f.fail("z", fmt::format("the face groove's approach level (z + approachDistance, Z {}) is at or above the "
                                    "clearance (Z {})",
                                    in.show(op.surface + op.approach), in.show(clearance)));
        return op;
    }
    if (bar && op.z_right > stock->face_z + 1e-9)
        f.fail("z", fmt::format("z {} is beyond the bar's face (Z {}): the groove is cut into the bar", in.show(op.z_right),
                                in.show(stock->face_z)));
    if (bar && op.z_left - op.chamfer < stock->face_z - stock->length - 1e-9)
        f.fail("z", fmt::format("the groove at z {} (width {}, chamfer {}) reaches beyond the bar's end (Z {})",
                                in.show(op.z_right), in.show(width), in.show(op.chamfer), in.show(stock->face_z - stock->length)));
    if (op.z_right + op.chamfer + op.approach >= clearance)
        f.fail("z", fmt::format("the groove (with its chamfer and approachDistance) reaches Z {}, at or above the clearance "
                                "(Z {})",
                                in.show(op.z_right + op.chamfer + op.approach), in.show(clearance)));
    return op;
}

GrooveCycle groove_cycle(const TurnGrooveOp& op) {
    GrooveCycle c;
    c.path = op.path;
    c.output = op.output;
    c.width = op.blade.width;
    c.right_point = op.blade.right_point;
    c.surface = op.surface;
    c.bottom = op.bottom;
    c.first_z = op.plunges.front();
    c.last_z = op.plunges.back();
    c.chamfer = op.chamfer;
    c.peck = op.pecks.peck;
    c.retract = op.pecks.retract;
    c.full_retract = op.pecks.full;
    c.dwell = op.dwell;
    c.feed = op.feed;
    const std::size_t n = op.plunges.size();
    c.finish = n > 1 ? op.finish : 0.0;
    c.side = op.side;
    c.air = op.surface + c.into() * op.approach;
    if (c.peck > 0) c.fields.push_back("pecks");
    if (c.full_retract) c.fields.push_back("fullRetract");
    if (c.dwell > 0) c.fields.push_back("dwell");
    if (c.finish > 0) c.fields.push_back("finishPass");
    if (c.chamfer > 0) c.fields.push_back("chamfer");
    if (n > 1) {
        const double spacing = (c.first_z - c.last_z) / static_cast<double>(n - 1);
        c.z_step = spacing;
        // G75's Z step is written in whole micrometres: a plain groove's plunges are spaced by
        // the spacing rounded up to one (the last one shorter), where that stays within the
        // blade's width.
        const double whole = std::ceil(spacing * 1000.0 - 1e-6) / 1000.0;
        if (c.plain() && whole <= c.width + 1e-9) c.z_step = whole;
    }
    return c;
}

void expand(const TurnGrooveOp& op, const Context& ctx, EventSink& sink) {
    const GrooveCycle c = groove_cycle(op);
    const double clearance = ctx.job.clearance;
    const Vec3 start = c.start();
    if (op.side == GrooveSide::external) {
        const double out = op.outside + op.approach;  // outside the bar: Z moves elsewhere
        sink.emit(Rapid{{out, 0.0, clearance}});
        sink.emit(Rapid{{out, 0.0, start.z}});
    } else {
        // Internal: at the clearance over the bore, then along Z into it at the approach radius
        // (inside the bore's wall); face: at the clearance over the first plunge, then down.
        sink.emit(Rapid{{start.x, 0.0, clearance}});
    }
    sink.emit(Rapid{start});
    if (op.output == CycleOutput::longhand)
        for (const Event& e : groove_cycle_moves(c)) sink.emit(e);
    else
        sink.emit(c);
    const Vec3 end = groove_cycle_end(c);
    if (op.side == GrooveSide::external) {
        const double out = op.outside + op.approach;
        sink.emit(Rapid{{out, 0.0, end.z}});
        sink.emit(Rapid{{out, 0.0, clearance}});
    } else {
        sink.emit(Rapid{{end.x, 0.0, clearance}});
    }
}

std::string default_name(const TurnGrooveOp& op) { return op.comment.empty() ? "turn groove" : op.comment; }

}  // namespace camgen
