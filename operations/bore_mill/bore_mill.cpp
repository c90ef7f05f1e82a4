#include "camgen/operations/bore_mill/bore_mill.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/cutting.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

// At most this many helix turns per hole (and rings), so that a typo in the pitch or stepOver
// cannot make millions of arcs.
constexpr double max_helix_turns = 100000;

// The innermost ring of a bore cleared ring by ring: its tool overlaps the centre by a tenth
// of the tool diameter, so that no core is left standing.
constexpr double inner_ring_fraction = 0.4;

// The keys of a bore-mill operation; the heights follow "comment", the hole sources come last.
constexpr KeySpec bore_mill_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools; its diameter must be smaller than the bore's"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "diameter", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "diameter of the hole milled"},
    {.key = "pitch", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "the most the helix goes down per turn; it makes whole turns, so it may go down a little less"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"climb\"",
     .choices = &choices_of<cut_directions>,
     .description = "climb or conventional milling (with the tool's spindle direction this decides G2 or G3)"},
    {.key = "stepOver", .quantity = Quantity::factor, .min = Bound{0, false}, .max = Bound{1, true},
     .default_json = "0.5",
     .description = "in a bore wider than twice the tool, the most the rings are apart, as a fraction of the tool "
                    "diameter"},
    {.key = "finishingAllowance", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "radial stock the roughing leaves for one finishing circle at the bottom (0: no finishing)"},
    {.key = "feed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "cutting feed: the circle at the bottom and the way back to the centre; required unless the tool "
                    "comes from the library with a feedPerTooth for the job's material (default: then fz x flutes x rpm "
                    "at the wall, x (bore - tool diameter) / bore for the tool centre)"},
    {.key = "rampFeed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "feed of the helix (default: feed)"},
    {.key = "plungeFeed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "feed from the safe distance above the centre to the start of the helix (default: feed)"},
    {.key = "finishingFeed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "feed of the finishing circle (default: feed)"},
    {.key = "tolerance", .quantity = Quantity::length, .min = Bound{0.0001, true},
     .description = "how far the lines of a helix the machine cannot write may stray from it (default: the machine's "
                    "chordTolerance, which also caps it)"},
};

// The keys of a bore-mill operation: bore_mill_keys with the heights after "comment", then the
// hole sources.
std::vector<KeySpec> all_bore_mill_keys() {
    std::vector<KeySpec> keys(std::begin(bore_mill_keys), std::end(bore_mill_keys));
    const std::vector<KeySpec> heights = height_keys(true);
    keys.insert(keys.begin() + 3, heights.begin(), heights.end());
    const std::vector<KeySpec> holes = hole_keys();
    keys.insert(keys.end(), holes.begin(), holes.end());
    return keys;
}

// An optional feed: > 0, else `fallback`.
double read_feed(Fields& f, const JobInput& in, std::string_view key, double fallback) {
    const std::optional<double> v = in.optional_quantity(f, key, Quantity::feed);
    if (v && *v <= 0) f.fail(key, fmt::format("{} must be > 0", key));
    return v.value_or(fallback);
}

// The direction the tool turns round the hole: with the tool left of its travel (climb with a
// clockwise spindle) it goes round the wall counter-clockwise.
ArcDirection arc_direction(CutDirection cut, SpindleDirection spindle) {
    return tool_left_of_travel(cut, spindle) ? ArcDirection::ccw : ArcDirection::cw;
}

}  // namespace

double ring_count(double bore, double tool, double step_over, double allowance) {
    const double outer = (bore - tool) / 2.0 - allowance;
    if (outer <= tool / 2.0) return 1;
    return 1 + std::ceil((outer - inner_ring_fraction * tool) / (step_over * tool) - 1e-9);
}

std::vector<double> ring_radii(double bore, double tool, double step_over, double allowance) {
    const double outer = (bore - tool) / 2.0 - allowance;
    const double inner = inner_ring_fraction * tool;
    const int rings = static_cast<int>(ring_count(bore, tool, step_over, allowance));
    if (rings == 1) return {outer};
    std::vector<double> radii;
    for (int i = 0; i < rings; ++i) radii.push_back(inner + (outer - inner) * i / (rings - 1));
    radii.back() = outer;  // exactly, no rounding
    return radii;
}

int helix_turns(double drop, double pitch) {
    return std::max(1, static_cast<int>(std::ceil(drop / pitch - 1e-9)));
}

std::vector<ObjectSpec> BoreMillOp::objects() {
    std::vector<ObjectSpec> objects{{.name = "bore-mill",
                                     .description = "mill circular holes or counterbores with a smaller tool: a helix "
                                                    "down at a pitch, a circle at the bottom, an optional finishing circle",
                                     .keys = all_bore_mill_keys(),
                                     .groups = {hole_group("a bore-mill operation needs holes")}}};
    for (ObjectSpec& o : hole_objects()) objects.push_back(std::move(o));
    return objects;
}

BoreMillOp BoreMillOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, all_bore_mill_keys());
    const Tool& tool = in.tool(f);
    // Its teeth cut sideways only, at a thread's depth: it cannot go down into material.
    if (tool.type == ToolType::thread_mill)
        f.fail("tool", fmt::format("tool {} ({}) is a thread mill: a bore-mill goes down into the material, which a thread "
                                   "mill's teeth cannot cut (the thread-mill operation mills threads)",
                                   tool.number, tool.path));
    BoreMillOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    op.heights = read_heights(f, in, "hole");

    op.diameter = in.length(f, "diameter");
    if (op.diameter <= 0) f.fail("diameter", "diameter must be > 0");
    if (tool.diameter >= op.diameter)
        f.fail("diameter", fmt::format("the bore (diameter {}) is not larger than tool {} (diameter {}, {}): a bore-mill "
                                       "needs a tool smaller than the bore",
                                       in.show(op.diameter), tool.number, in.show(tool.diameter), tool.path));
    op.pitch = in.length(f, "pitch");
    if (op.pitch <= 0) f.fail("pitch", "pitch must be > 0 (the helix goes down by at most pitch each turn)");
    const Planes z = resolve_planes(op.heights);
    // The helix starts at the stock top: a bottom at or above it would mill nothing (or upwards).
    if (z.bottom_z >= z.reference_z)
        f.fail("endDepth", fmt::format("endDepth is not below referencePlane, the stock top (bore bottom at Z {}, stock "
                                       "top at Z {}): there is nothing to mill",
                                       in.show(z.bottom_z), in.show(z.reference_z)));
    op.step_over = f.optional_number("stepOver").value_or(0.5);
    if (!(op.step_over > 0 && op.step_over <= 1)) f.fail("stepOver", "stepOver must be > 0 and at most 1");
    op.finishing_allowance = in.optional_length(f, "finishingAllowance").value_or(0.0);
    if (op.finishing_allowance < 0) f.fail("finishingAllowance", "finishingAllowance cannot be negative");
    const double wall = (op.diameter - tool.diameter) / 2.0;
    if (op.finishing_allowance >= wall)
        f.fail("finishingAllowance",
               fmt::format("finishingAllowance ({}) leaves the roughing nothing to mill: it must be less than half the "
                           "difference of the bore's and the tool's diameters ({})",
                           in.show(op.finishing_allowance), in.show(wall)));
    // Counted before anything is made, so that a typo cannot make millions of arcs.
    const double rings = ring_count(op.diameter, tool.diameter, op.step_over, op.finishing_allowance);
    if (rings > max_helix_turns)
        f.fail("stepOver", fmt::format("stepOver is too small for the bore: more than {} rings", max_helix_turns));
    if (rings * std::ceil((z.reference_z - z.bottom_z) / op.pitch) > max_helix_turns)
        f.fail("pitch", fmt::format("pitch is too small: more than {} helix turns a hole", max_helix_turns));
    if (tool.flute_length && z.reference_z - z.bottom_z > *tool.flute_length)
        f.fail("endDepth", fmt::format("the bore is {} deep below the reference plane, but tool {} has a fluteLength of {}",
                                       in.show(z.reference_z - z.bottom_z), tool.number, in.show(*tool.flute_length)));
    op.direction = f.choice("direction", cut_directions, CutDirection::climb);

    // A feed computed from the tool's cutting data is the edge's on the bore's wall.
    std::vector<std::string> computed_notes;
    op.feed = read_cutting_feed(f, in, tool, 0.0, computed_notes,
                                CircularCut{.centre = (op.diameter - tool.diameter) / 2.0, .wall = op.diameter / 2.0});
    op.ramp_feed = read_feed(f, in, "rampFeed", op.feed);
    op.plunge_feed = read_feed(f, in, "plungeFeed", op.feed);
    op.finishing_feed = read_feed(f, in, "finishingFeed", op.feed);
    op.tolerance = in.optional_length(f, "tolerance");
    // Finer than any control resolves; a smaller value only multiplies the segments of broken helices.
    if (op.tolerance && !(*op.tolerance >= 0.0001)) f.fail("tolerance", "tolerance must be at least 0.0001 mm");

    static_cast<HoleSet&>(op) = read_hole_set(f, in, type);
    op.notes.insert(op.notes.begin(), computed_notes.begin(), computed_notes.end());
    return op;
}

void expand(const BoreMillOp& op, const Context& ctx, EventSink& sink) {
    if (op.holes.empty()) return;
    const Planes z = resolve_planes(op.heights);
    std::vector<Vec2> reordered;
    const std::vector<Vec2>& holes = visit_order(op, reordered);
    const std::vector<double> radii = ring_radii(op.diameter, ctx.tool.diameter, op.step_over, op.finishing_allowance);
    const double finish_radius = (op.diameter - ctx.tool.diameter) / 2.0;
    const ArcDirection direction = arc_direction(op.direction, ctx.tool.direction);
    const int turns = helix_turns(z.reference_z - z.bottom_z, op.pitch);

    const Vec2 first = holes.front();
    sink.emit(Rapid{{first.x, first.y, ctx.job.clearance}});
    if (z.retract_z != ctx.job.clearance) sink.emit(Rapid{{first.x, first.y, z.retract_z}});
    for (const Vec2& h : holes) {
        const Vec3 bottom_centre{h.x, h.y, z.bottom_z};
        if (&h != &holes.front()) sink.emit(Rapid{{h.x, h.y, z.retract_z}});
        for (std::size_t k = 0; k < radii.size(); ++k) {
            if (z.safe_z != z.retract_z || k > 0) sink.emit(Rapid{{h.x, h.y, z.safe_z}});
            // Every circle starts and ends on +X of the centre.
            const Vec3 top{h.x + radii[k], h.y, z.reference_z};
            const Vec3 start_bottom{top.x, top.y, z.bottom_z};
            sink.emit(Linear{top, op.plunge_feed, Movement::lead_in});
            sink.emit(Arc{start_bottom, {h.x, h.y, z.reference_z}, direction, Plane::xy, op.ramp_feed, turns - 1,
                          Movement::ramp});
            sink.emit(Arc{start_bottom, bottom_centre, direction, Plane::xy, op.feed, 0, Movement::cutting});
            if (k + 1 == radii.size() && op.finishing_allowance > 0) {
                const Vec3 finish{h.x + finish_radius, h.y, z.bottom_z};
                sink.emit(Linear{finish, op.finishing_feed, Movement::lead_in});
                sink.emit(Arc{finish, bottom_centre, direction, Plane::xy, op.finishing_feed, 0, Movement::finishing});
            }
            // Back to the centre before rising: a tool that rose on the wall would mark it.
            sink.emit(Linear{bottom_centre, op.feed, Movement::lead_out});
            sink.emit(Rapid{{h.x, h.y, k + 1 == radii.size() ? z.retract_z : z.safe_z}});
        }
    }
    const Vec2 last = holes.back();
    if (z.retract_z != ctx.job.clearance) sink.emit(Rapid{{last.x, last.y, ctx.job.clearance}});
}

std::string default_name(const BoreMillOp& op) {
    if (!op.comment.empty()) return op.comment;
    return fmt::format("mill {} bore{} {:g} mm", op.holes.size(), op.holes.size() == 1 ? "" : "s", op.diameter);
}

}  // namespace camgen
