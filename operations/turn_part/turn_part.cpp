#include "camgen/operations/turn_part/turn_part.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

constexpr KeySpec turn_part_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a parting-tool or grooving-tool (orientation none or 2: its programmed point "
                    "is its left corner; 1: its right corner)"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "xValues", .type = JsonType::string, .default_json = "\"diameter\"", .choices = &choices_of<x_values>,
     .description = "startX, toX and reducedFeedX as diameters or as radii"},
    {.key = "feed", .quantity = Quantity::feed, .required = true, .min = Bound{0, false},
     .description = "cutting feed of the plunge, per minute or per revolution (feedMode)"},
    {.key = "feedMode", .type = JsonType::string, .default_json = "\"per-minute\"", .choices = &choices_of<feed_modes>,
     .description = "feed in mm/min or mm/rev; the program feeds the same way (G94/G95, Fanuc T G98/G99)"},
    {.key = "z", .quantity = Quantity::length, .required = true,
     .description = "Z of the parted part's end face: the blade's right (+Z) edge runs there, the part lies on the +Z side"},
    {.key = "startX", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "X (as xValues) of the surface parted from, which must be the largest over the blade's width, the "
                    "chamfer and approachDistance either side: a rapid of the blade through the material an earlier turn-profile "
                    "keeps, or with a bar through the bar's solid that no operation before it turned away, is refused "
                    "(default: the stock bar's diameter; required without a bar)"},
    {.key = "toX", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "X (as xValues) the plunge ends at: 0 parts through; a small remainder (0.5 on the diameter) leaves a "
                    "pip to break off"},
    {.key = "reducedFeed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "the feed below reducedFeedX, near the centre, as feedMode (default: half of feed)"},
    {.key = "reducedFeedX", .quantity = Quantity::length, .min = Bound{0, true},
     .description = "X (as xValues) below which the plunge feeds at reducedFeed (default: a quarter of startX; 0: none)"},
    {.key = "chamfer", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "a 45-degree chamfer on the part's edge, mm along Z and along the radius, cut by the blade's right corner "
                    "after a plunge to its depth"},
    {.key = "peckDepth", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "radial depth of each peck, mm, at least 0.01 and at most 10000 pecks a plunge (default: no pecks, one "
                    "feed)"},
    {.key = "peckRetract", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "0.3",
     .description = "how far the blade backs off (rapid) between pecks to break the chip, mm; with fullRetract, how far "
                    "above the depth reached it comes back down at rapid"},
    {.key = "fullRetract", .type = JsonType::boolean, .default_json = "false",
     .description = "between pecks, rapid out to approachDistance above the surface instead of backing off by peckRetract"},
    {.key = "approachDistance", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "1",
     .description = "how far above the surface (radial) the feeds start, and outside the bar the tool moves along Z, mm"},
};

}  // namespace

std::vector<ObjectSpec> TurnPartOp::objects() {
    return {{.name = "turn-part",
             .description = "parting off on a lathe: a plunge of a parting tool to the centre or a remainder, pecked or not, "
                            "slower near the centre, an optional chamfer on the part's edge",
             .keys = {std::begin(turn_part_keys), std::end(turn_part_keys)}}};
}

TurnPartOp TurnPartOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, turn_part_keys);
    const Tool* tool = nullptr;
    TurnPartOp op;
    op.blade = read_groove_blade(f, in, "turn-part", tool);
    op.path = f.path();
    op.tool = tool->number;
    op.comment = f.optional_string("comment").value_or("");
    op.given_x = f.choice("xValues", x_values, XValues::diameter);
    op.feed_mode = f.choice("feedMode", feed_modes, FeedMode::per_minute);
    const double per = op.feed_mode == FeedMode::per_revolution ? tool->rpm : 1.0;
    op.feed = in.length(f, "feed");
    if (!(op.feed > 0)) f.fail("feed", "feed must be > 0");
    op.slow_feed = in.optional_length(f, "reducedFeed").value_or(op.feed / 2);
    if (!(op.slow_feed > 0)) f.fail("reducedFeed", "reducedFeed must be > 0");
    if (op.slow_feed > op.feed) f.fail("reducedFeed", "reducedFeed must not be more than feed");
    op.feed *= per, op.slow_feed *= per;
    const double scale = op.given_x == XValues::diameter ? 0.5 : 1.0;
    auto x_text = [&](double r) { return in.show(r / scale); };
    const std::optional<Stock>& stock = in.header().stock;
    const bool bar = stock && stock->shape == StockShape::bar;
    if (f.has("startX")) op.surface = in.length(f, "startX") * scale;
    else if (bar) op.surface = stock->diameter / 2;
    else f.fail("startX", "give startX (the X of the surface parted from), or a stock bar whose diameter it is");
    if (!(op.surface > 0)) f.fail("startX", "startX must be > 0");
    if (bar && op.surface > stock->diameter / 2 + 1e-9)
        f.fail("startX", fmt::format("startX {} is beyond the bar's X {}", x_text(op.surface), x_text(stock->diameter / 2)));
    op.outside = bar ? std::max(stock->diameter / 2, op.surface) : op.surface;
    if (bar && stock->bore_diameter) op.notes.push_back("the bar is a tube: the plunge still runs to toX");
    op.end = in.optional_length(f, "toX").value_or(0.0) * scale;
    if (op.end < 0) f.fail("toX", "toX must be 0 or more");
    if (!(op.end < op.surface)) f.fail("toX", fmt::format("toX {} is not below startX {}", x_text(op.end), x_text(op.surface)));
    op.slow_below = f.has("reducedFeedX") ? in.length(f, "reducedFeedX") * scale : op.surface / 4;
    if (op.slow_below < 0) f.fail("reducedFeedX", "reducedFeedX must be 0 or more");
    if (op.slow_below >= op.surface)
        f.fail("reducedFeedX", fmt::format("reducedFeedX {} is not below startX {}", x_text(op.slow_below), x_text(op.surface)));
    const double depth = op.surface - op.end;
    if (tool->flute_length && *tool->flute_length < depth - 1e-9)
        f.fail("tool", fmt::format("tool {} reaches {} deep (its fluteLength), less than the {} from X {} to X {}: its blade is "
                                   "too short to part off there",
                                   tool->number, in.show(*tool->flute_length), in.show(depth), x_text(op.surface), x_text(op.end)));
    op.z = in.length(f, "z");
    op.chamfer = in.optional_length(f, "chamfer").value_or(0.0);
    if (op.chamfer < 0) f.fail("chamfer", "chamfer must be 0 or more");
    if (op.chamfer >= depth)
        f.fail("chamfer", fmt::format("chamfer {} is not less than the depth parted, {}", in.show(op.chamfer), in.show(depth)));
    op.approach = in.optional_length(f, "approachDistance").value_or(1.0);
    if (!(op.approach > 0)) f.fail("approachDistance", "approachDistance must be > 0");
    op.pecks = read_groove_pecks(f, in, depth);
    const double clearance = in.header().clearance;
    if (op.z + op.chamfer + op.approach >= clearance)
        f.fail("z", fmt::format("the parting (with its chamfer and approachDistance) reaches Z {}, at or above the clearance "
                                "(Z {})",
                                in.show(op.z + op.chamfer + op.approach), in.show(clearance)));
    if (bar && op.z > stock->face_z) f.fail("z", fmt::format("z {} is beyond the bar's face (Z {})", in.show(op.z), in.show(stock->face_z)));
    if (bar && op.z - op.blade.width < stock->face_z - stock->length)
        f.fail("z", fmt::format("the blade at z {} reaches beyond the bar's end (Z {})", in.show(op.z),
                                in.show(stock->face_z - stock->length)));
    if (tool->surface_speed > 0)
        op.notes.push_back(fmt::format("parting at a constant surface speed of {} m/min: towards the centre the spindle "
                                       "speeds up to its limit, {} rpm",
                                       number_text(tool->surface_speed), number_text(tool->rpm)));
    else
        op.notes.push_back(fmt::format("parting at a constant {} rpm: the surface speed falls towards the centre; where the "
                                       "spindle runs at constant surface speed, limit its rpm (G50 S, LIMS, G96 D)",
                                       number_text(tool->rpm)));
    if (op.end > 0)
        op.notes.push_back(fmt::format("the plunge stops at X {} and leaves a pip of that X: the part stays on until it is "
                                       "broken off: the program stops (M0) after the plunge for that",
                                       x_text(op.end)));
    return op;
}

void expand(const TurnPartOp& op, const Context& ctx, EventSink& sink) {
    const GrooveBlade& b = op.blade;
    const double out = op.outside + op.approach;
    const double air = op.surface + op.approach;
    const double clearance = ctx.job.clearance;
    const double left = op.z - b.width;  // the blade's left corner
    sink.emit(Comment{op.end > 0 ? "the part stays on a pip: the program stops (M0) for it to be broken off"
                                 : "the part falls off at the end of the plunge: set up a part catcher"});
    sink.emit(Rapid{{out, 0.0, clearance}});
    sink.emit(Rapid{b.at(out, left)});
    sink.emit(Rapid{b.at(air, left)});
    GroovePlunge p;
    p.left_z = left, p.start = air, p.air = air, p.top = op.surface;
    p.feed = op.feed, p.slow_feed = op.slow_feed, p.slow_below = op.slow_below;
    if (op.chamfer > 0) {
        // To the chamfer's depth, out, and down the part's edge by the right corner, which ends
        // where the plunge goes on.
        const double c = op.chamfer;
        p.end = op.surface - c;
        emit_groove_plunge(b, p, op.pecks, sink);
        sink.emit(Rapid{b.at(air, left)});
        sink.emit(Rapid{b.at(air, left + c + op.approach)});
        sink.emit(Linear{b.at(op.surface - c, left), op.feed, Movement::cutting});
        p.start = op.surface - c;
        p.top = op.surface - c;
    }
    p.end = op.end;
    emit_groove_plunge(b, p, op.pecks, sink);
    sink.emit(Rapid{b.at(air, left)});
    sink.emit(Rapid{b.at(out, left)});
    sink.emit(Rapid{{out, 0.0, clearance}});
    // A part left on a pip is broken off by hand: the machine stops (spindle and coolant off,
    // OperatorStops) before anything else moves.
    if (op.end > 0) sink.emit(Stop{StopKind::mandatory, "break off the parted part (it hangs on a pip)", 0.0});
}

std::string default_name(const TurnPartOp& op) { return op.comment.empty() ? "turn part" : op.comment; }

}  // namespace camgen
