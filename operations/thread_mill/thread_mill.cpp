#include "camgen/operations/thread_mill/thread_mill.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/cutting.hpp"
#include "camgen/operations/thread_size.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

// At most this many helix turns per hole and pass, and radial passes, so that a typo cannot
// make millions of arcs.
constexpr double thread_max_turns = 100000;
constexpr int thread_max_passes = 100;

// The least radial room (mm) between the tool and the thread where it must not touch it: an
// internal thread's minor diameter around the tool at the hole's centre, an external
// thread's major diameter beside the tool at the lead-in's start.
constexpr double thread_clearance = 0.1;

// The shortest partial last turn of a helix (mm along its circle): shorter, the end rounds
// onto the start (or the start's neighbour) and a control reads a full circle or nothing.
constexpr double thread_least_arc = 0.002;

// The keys of a thread-mill operation; the heights follow "comment", the hole sources come last.
constexpr KeySpec thread_mill_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a thread-mill whose pitch (or minPitch to maxPitch) holds the thread's"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "thread", .type = JsonType::string,
     .description = "the thread by its designation: ISO 261 metric, M10 (coarse pitch) or M10x1.25 (a coarse or fine "
                    "pitch of the size), or ASME B1.1 Unified, 1/4-20 UNC, #10-32 UNF"},
    {.key = "majorDiameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "or the thread by its diameters: the major diameter (with minorDiameter and pitch)"},
    {.key = "minorDiameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the minor diameter: an internal thread's D1 (the tool's first contact), an external thread's d3 "
                    "(its last pass)"},
    {.key = "pitch", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the thread's pitch: the helix advances exactly this per turn (with majorDiameter and minorDiameter)"},
    {.key = "side", .type = JsonType::string, .default_json = "\"internal\"", .choices = &choices_of<thread_sides>,
     .description = "internal (in a hole) or external (on a boss whose axis each hole gives)"},
    {.key = "hand", .type = JsonType::string, .default_json = "\"right\"", .choices = &choices_of<thread_hands>,
     .description = "right- or left-hand thread"},
    {.key = "direction", .type = JsonType::string, .default_json = "\"climb\"", .choices = &choices_of<cut_directions>,
     .description = "climb or conventional milling; with the hand and the spindle it decides the sequence (give one "
                    "of them)"},
    {.key = "sequence", .type = JsonType::string, .choices = &choices_of<thread_orders>,
     .description = "bottom-up or top-down; with the hand and the spindle it decides the direction (default: what "
                    "direction gives)"},
    {.key = "passes", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true},
     .max = Bound{100, true}, .default_json = "1", .description = "radial passes to the thread's full depth, equal steps"},
    {.key = "springPass", .type = JsonType::boolean, .default_json = "false",
     .description = "one more pass at the full depth, for the tool's deflection"},
    {.key = "feed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "feed of the tool centre along the leads and the helix; required unless the tool comes from the "
                    "library with a feedPerTooth for the job's material (default: then fz x flutes x rpm at the "
                    "thread's last diameter, scaled to the tool centre's radius)"},
    {.key = "plungeFeed", .quantity = Quantity::feed, .min = Bound{0, false},
     .description = "feed from the safe distance down to the lead-in's start, in the clear (default: feed)"},
    {.key = "tolerance", .quantity = Quantity::length, .min = Bound{0.0001, true},
     .description = "how far the lines of a helix the machine cannot write may stray from it (default: the machine's "
                    "chordTolerance, which also caps it)"},
};

std::vector<KeySpec> all_thread_mill_keys() {
    std::vector<KeySpec> keys(std::begin(thread_mill_keys), std::end(thread_mill_keys));
    const std::vector<KeySpec> heights = height_keys(true);
    keys.insert(keys.begin() + 3, heights.begin(), heights.end());
    const std::vector<KeySpec> holes = hole_keys();
    keys.insert(keys.end(), holes.begin(), holes.end());
    return keys;
}

// The helix's turning sense about the thread's axis: an internal thread is milled with the
// tool left of its travel (climb with M3) counter-clockwise, an external one clockwise.
ArcDirection thread_arc_direction(ThreadSide side, CutDirection cut, SpindleDirection spindle) {
    const bool left = tool_left_of_travel(cut, spindle);
    return (side == ThreadSide::internal) == left ? ArcDirection::ccw : ArcDirection::cw;
}

// Whether a helix turning `dir` rises along a thread of `hand` (a right-hand helix rises
// counter-clockwise seen from above).
bool thread_rises(ArcDirection dir, ThreadHand hand) { return (dir == ArcDirection::ccw) == (hand == ThreadHand::right); }

Vec2 thread_unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

}  // namespace

ThreadRadii thread_radii(const ThreadMillOp& op, double tool_diameter) {
    const double r = tool_diameter / 2.0;
    if (op.side == ThreadSide::internal) return {op.minor / 2.0 - r, op.major / 2.0 - r};
    return {op.major / 2.0 + r, op.minor / 2.0 + r};
}

std::vector<double> thread_pass_radii(const ThreadMillOp& op, double tool_diameter) {
    const ThreadRadii r = thread_radii(op, tool_diameter);
    std::vector<double> radii;
    for (int k = 1; k <= op.passes; ++k) radii.push_back(r.first_contact + (r.last - r.first_contact) * k / op.passes);
    radii.back() = r.last;  // exactly, no rounding
    if (op.spring_pass) radii.push_back(r.last);
    return radii;
}

double thread_lead_rise(const ThreadMillOp& op, double radius, double tool_diameter) {
    if (op.side == ThreadSide::internal) return op.pitch / 4.0;
    return op.pitch * (tool_diameter / 2.0) / (4.0 * radius);
}

std::vector<ObjectSpec> ThreadMillOp::objects() {
    std::vector<ObjectSpec> objects{
        {.name = "thread-mill",
         .description = "mill internal or external threads with a thread mill: per radial pass a helical lead-in arc, a "
                        "helix at exactly the pitch, a helical lead-out arc",
         .keys = all_thread_mill_keys(),
         .groups = {hole_group("a thread-mill operation needs holes"),
                    {.keys = {"thread", "majorDiameter"}, .min = 1, .max = 1,
                     .description = "the thread by its designation or by its diameters"}}}};
    for (ObjectSpec& o : hole_objects()) objects.push_back(std::move(o));
    return objects;
}

ThreadMillOp ThreadMillOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, all_thread_mill_keys());
    const Tool& tool = in.tool(f);
    const std::string_view tool_type = name_of(tool_types, tool.type);
    if (tool.type != ToolType::thread_mill)
        f.fail("tool", fmt::format("tool {} ({}) is a {}: a thread-mill operation needs a tool of type \"thread-mill\"",
                                   tool.number, tool.path, tool_type));
    ThreadMillOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    op.heights = read_heights(f, in, "thread");
    op.side = f.choice("side", thread_sides, ThreadSide::internal);
    op.hand = f.choice("hand", thread_hands, ThreadHand::right);

    // The thread: a designation from the tables, or its diameters and pitch.
    const ThreadSize size = read_thread_size(f, in, op.side, "a thread-mill", "M10x1.5", "M10x1.25");
    op.thread = size.name, op.major = size.major, op.minor = size.minor, op.pitch = size.pitch;
    const std::string what = op.thread.empty() ? fmt::format("the thread (pitch {})", in.show(op.pitch)) : op.thread;
    if (op.pitch < tool.min_pitch - 1e-6 || op.pitch > tool.max_pitch + 1e-6)
        f.fail(f.has("thread") ? "thread" : "pitch",
               tool.min_pitch == tool.max_pitch
                   ? fmt::format("{} has pitch {}, but tool {} ({}) is a multi-form thread mill of pitch {}", what,
                                 in.show(op.pitch), tool.number, tool.path, in.show(tool.min_pitch))
                   : fmt::format("{} has pitch {}, but tool {} ({}) cuts pitches from {} to {}", what, in.show(op.pitch),
                                 tool.number, tool.path, in.show(tool.min_pitch), in.show(tool.max_pitch)));
    // The tool must fit: at the hole's centre its teeth stay clear of the minor diameter.
    if (op.side == ThreadSide::internal && tool.diameter > op.minor - 2.0 * thread_clearance)
        f.fail("tool", fmt::format("tool {} ({}, diameter {}) does not fit {}: an internal thread needs a tool at least "
                                   "{} smaller than its minor diameter ({}), so that it enters at the centre in the clear",
                                   tool.number, tool.path, in.show(tool.diameter), what, in.show(2.0 * thread_clearance),
                                   in.show(op.minor)));

    op.direction = f.choice("direction", cut_directions, CutDirection::climb);
    const ArcDirection dir = thread_arc_direction(op.side, op.direction, tool.direction);
    const ThreadOrder natural = thread_rises(dir, op.hand) ? ThreadOrder::bottom_up : ThreadOrder::top_down;
    if (f.has("sequence")) {
        op.sequence = f.choice("sequence", thread_orders, natural);
        if (op.sequence != natural) {
            if (f.has("direction"))
                f.fail("sequence", fmt::format("a {}-hand {} thread milled {} with the spindle {} is milled {}: hand, "
                                               "direction and sequence cannot all be chosen (give direction or sequence)",
                                            name_of(thread_hands, op.hand), name_of(thread_sides, op.side),
                                            name_of(cut_directions, op.direction),
                                            tool.direction == SpindleDirection::cw ? "clockwise (M3)" : "counter-clockwise (M4)",
                                            name_of(thread_orders, natural)));
            op.direction = op.direction == CutDirection::climb ? CutDirection::conventional : CutDirection::climb;
        }
    } else {
        op.sequence = natural;
    }

    const int passes = f.has("passes") ? f.integer("passes") : 1;
    if (passes < 1 || passes > thread_max_passes)
        f.fail("passes", fmt::format("passes must be a whole number from 1 to {}", thread_max_passes));
    op.passes = passes;
    op.spring_pass = f.boolean("springPass", false);

    const Planes z = resolve_planes(op.heights);
    if (z.bottom_z >= z.reference_z)
        f.fail("endDepth", fmt::format("endDepth is not below referencePlane (thread bottom at Z {}, top at Z {}): there is "
                                       "no thread to mill",
                                       in.show(z.bottom_z), in.show(z.reference_z)));
    const double length = z.reference_z - z.bottom_z;
    if (length / op.pitch * (op.passes + (op.spring_pass ? 1 : 0)) > thread_max_turns)
        f.fail("endDepth", fmt::format("the thread is {} long at pitch {}: more than {} helix turns a hole", in.show(length),
                                       in.show(op.pitch), thread_max_turns));
    // The leads go beyond the thread's ends; the lowest point of the first pass's is the deepest.
    const std::vector<double> radii = thread_pass_radii(op, tool.diameter);
    double deepest = 0.0;
    for (double r : radii) deepest = std::max(deepest, thread_lead_rise(op, r, tool.diameter));
    if (tool.flute_length && length + deepest > *tool.flute_length + 1e-9)
        f.fail("endDepth",
               fmt::format("the thread is milled {} deep below the reference plane ({} and the lead arc's {} below "
                           "endDepth), but tool {} ({}) has a fluteLength of {}",
                           in.show(length + deepest), in.show(length), in.show(deepest), tool.number, tool.path,
                           in.show(*tool.flute_length)));
    if (op.side == ThreadSide::external) {
        // The lead-in starts a quarter turn of a circle of the tool's radius away from the
        // helix: there the tool must be clear of the major diameter.
        const double a = tool.diameter / 2.0, r = radii.back();
        const double start = std::hypot(r + a, a) - a;
        if (start < op.major / 2.0 + thread_clearance)
            f.fail("tool", fmt::format("tool {} ({}, diameter {}) is too small for the lead-in of {}: its arc of the tool's "
                                       "radius starts {} from the axis, within {} of the major diameter ({})",
                                       tool.number, tool.path, in.show(tool.diameter), what, in.show(start),
                                       in.show(thread_clearance), in.show(op.major)));
    }

    // A feed computed from the tool's cutting data is the edge's at the thread's last diameter.
    std::vector<std::string> computed_notes;
    {
        const ThreadRadii radii = thread_radii(op, tool.diameter);
        const double wall = op.side == ThreadSide::internal ? op.major / 2.0 : op.minor / 2.0;
        op.feed = read_cutting_feed(f, in, tool, 0.0, computed_notes, CircularCut{.centre = radii.last, .wall = wall});
    }
    const std::optional<double> plunge = in.optional_quantity(f, "plungeFeed", Quantity::feed);
    if (plunge && !(*plunge > 0)) f.fail("plungeFeed", "plungeFeed must be > 0");
    op.plunge_feed = plunge.value_or(op.feed);
    op.tolerance = in.optional_length(f, "tolerance");
    if (op.tolerance && !(*op.tolerance >= 0.0001)) f.fail("tolerance", "tolerance must be at least 0.0001 mm");

    static_cast<HoleSet&>(op) = read_hole_set(f, in, type);
    op.notes.insert(op.notes.begin(), computed_notes.begin(), computed_notes.end());
    return op;
}

void expand(const ThreadMillOp& op, const Context& ctx, EventSink& sink) {
    if (op.holes.empty()) return;
    const Planes z = resolve_planes(op.heights);
    std::vector<Vec2> reordered;
    const std::vector<Vec2>& holes = visit_order(op, reordered);
    const double tool_d = ctx.tool.diameter, a = tool_d / 2.0;
    const ArcDirection dir = thread_arc_direction(op.side, op.direction, ctx.tool.direction);
    const ArcDirection lead_dir = op.side == ThreadSide::internal ? dir
                                  : dir == ArcDirection::ccw     ? ArcDirection::cw
                                                                 : ArcDirection::ccw;
    const double sense = dir == ArcDirection::ccw ? 1.0 : -1.0;  // of the helix's angle
    const double up = op.sequence == ThreadOrder::bottom_up ? 1.0 : -1.0;
    const double z_start = op.sequence == ThreadOrder::bottom_up ? z.bottom_z : z.reference_z;
    const double z_end = op.sequence == ThreadOrder::bottom_up ? z.reference_z : z.bottom_z;
    const double length = z.reference_z - z.bottom_z;
    // Whole turns and the partial last turn's angle (radians): the helix turns length / pitch.
    const double turns = length / op.pitch;
    const double start_angle = 0.0;  // every helix starts on +X of the axis
    const std::vector<double> radii = thread_pass_radii(op, tool_d);

    bool at_first = true;
    Vec2 last_end;
    // Whether every pass starts and ends at the same point (internal: the hole's axis).
    const bool same_start = op.side == ThreadSide::internal;
    for (const Vec2& h : holes) {
        for (std::size_t k = 0; k < radii.size(); ++k) {
            const double r = radii[k], rise = thread_lead_rise(op, r, tool_d);
            // Whole turns, then the partial last turn's angle. A remainder shorter than
            // thread_least_arc along the circle (either way) is no arc a control can tell from a
            // full circle or from none: the turns are rounded to it instead.
            int whole = static_cast<int>(std::floor(turns));
            double partial = (turns - whole) * two_pi;
            if (partial * r < thread_least_arc) partial = 0.0;
            if ((two_pi - partial) * r < thread_least_arc) {
                ++whole;
                partial = 0.0;
            }
            const double end_angle = start_angle + sense * partial;
            const bool spring = op.spring_pass && k + 1 == radii.size();
            const Vec2 t = h + thread_unit(start_angle) * r;  // the helix's start
            const Vec2 e = h + thread_unit(end_angle) * r;    // ... and end
            Vec2 lead_in_centre, lead_start, lead_out_centre, lead_end;
            if (op.side == ThreadSide::internal) {
                // A half circle of half the radius through the axis, tangent to the helix.
                lead_in_centre = h + thread_unit(start_angle) * (r / 2.0);
                lead_start = h;
                lead_out_centre = h + thread_unit(end_angle) * (r / 2.0);
                lead_end = h;
            } else {
                // A quarter circle of the tool's radius outside the helix, tangent to it.
                lead_in_centre = h + thread_unit(start_angle) * (r + a);
                lead_start = lead_in_centre + thread_unit(start_angle + pi + sense * pi / 2.0) * a;
                lead_out_centre = h + thread_unit(end_angle) * (r + a);
                lead_end = lead_out_centre + thread_unit(end_angle + pi - sense * pi / 2.0) * a;
            }
            const double z_in = z_start - up * rise, z_out = z_end + up * rise;
            if (at_first) {
                sink.emit(Rapid{{lead_start.x, lead_start.y, ctx.job.clearance}});
                if (z.retract_z != ctx.job.clearance) sink.emit(Rapid{{lead_start.x, lead_start.y, z.retract_z}});
                at_first = false;
            } else {
                sink.emit(Rapid{{lead_start.x, lead_start.y, k == 0 || !same_start ? z.retract_z : z.safe_z}});
            }
            if ((k == 0 || !same_start) && z.safe_z != z.retract_z)
                sink.emit(Rapid{{lead_start.x, lead_start.y, z.safe_z}});
            sink.emit(Linear{{lead_start.x, lead_start.y, z_in}, op.plunge_feed, Movement::plunge});
            sink.emit(Arc{{t.x, t.y, z_start}, {lead_in_centre.x, lead_in_centre.y, z_in}, lead_dir, Plane::xy, op.feed, 0,
                          Movement::lead_in});
            const Movement cut = spring ? Movement::finishing : Movement::cutting;
            double at_z = z_start;
            if (whole > 0) {
                const double z_turns = z_start + up * whole * op.pitch;
                const bool last = partial == 0.0;
                sink.emit(Arc{{t.x, t.y, last ? z_end : z_turns}, {h.x, h.y, at_z}, dir, Plane::xy, op.feed, whole - 1, cut});
                at_z = last ? z_end : z_turns;
            }
            if (partial > 0.0) sink.emit(Arc{{e.x, e.y, z_end}, {h.x, h.y, at_z}, dir, Plane::xy, op.feed, 0, cut});
            sink.emit(Arc{{lead_end.x, lead_end.y, z_out}, {lead_out_centre.x, lead_out_centre.y, z_end}, lead_dir, Plane::xy,
                          op.feed, 0, Movement::lead_out});
            // Between passes that start where this one ends (internal: the axis) the safe
            // distance will do; elsewhere the tool travels at the retract plane.
            sink.emit(Rapid{{lead_end.x, lead_end.y, k + 1 == radii.size() || !same_start ? z.retract_z : z.safe_z}});
            last_end = lead_end;
        }
    }
    if (z.retract_z != ctx.job.clearance) sink.emit(Rapid{{last_end.x, last_end.y, ctx.job.clearance}});
}

std::string default_name(const ThreadMillOp& op) {
    if (!op.comment.empty()) return op.comment;
    const std::string thread = op.thread.empty() ? fmt::format("{:g} x {:g}", op.major, op.pitch) : op.thread;
    return fmt::format("thread {} {}{}, {} hole{}", thread, name_of(thread_sides, op.side),
                       op.hand == ThreadHand::left ? " left-hand" : "", op.holes.size(), op.holes.size() == 1 ? "" : "s");
}


ThreadSize read_thread_size(json::Fields& f, const JobInput& in, ThreadSide side, std::string_view what,
                            std::string_view example, std::string_view fine) {
    ThreadSize size;
    if (f.has("thread")) {
        for (std::string_view key : {"majorDiameter", "minorDiameter", "pitch"})
            if (f.has(key))
                f.fail(key, fmt::format("give the thread by its designation or by majorDiameter, minorDiameter and pitch, "
                                        "not both (a fine pitch is part of the designation: {})",
                                        fine));
        std::string why;
        const std::optional<ThreadDesignation> t = find_thread(f.optional_string("thread").value_or(""), why);
        if (!t) f.fail("thread", why);
        size.name = t->name;
        size.major = t->major;
        size.pitch = t->pitch;
        size.minor = side == ThreadSide::internal ? internal_minor_diameter(t->major, t->pitch)
                                                  : external_minor_diameter(t->major, t->pitch);
        return size;
    }
    for (std::string_view key : {"majorDiameter", "minorDiameter", "pitch"})
        if (!f.has(key))
            f.fail(key, fmt::format("{} needs thread (a designation such as {}), or majorDiameter, minorDiameter and pitch",
                                    what, example));
    size.major = in.length(f, "majorDiameter");
    size.minor = in.length(f, "minorDiameter");
    size.pitch = in.length(f, "pitch");
    if (!(size.pitch > 0)) f.fail("pitch", "pitch must be > 0");
    if (!(size.minor > 0)) f.fail("minorDiameter", "minorDiameter must be > 0");
    if (!(size.major > size.minor))
        f.fail("minorDiameter", fmt::format("minorDiameter ({}) must be less than majorDiameter ({})", in.show(size.minor),
                                            in.show(size.major)));
    // More than a 60-degree profile's full depth (the triangle H) is no thread.
    if ((size.major - size.minor) / 2.0 > thread_triangle_height(size.pitch) + 1e-9)
        f.fail("minorDiameter",
               fmt::format("the thread is {} deep ((majorDiameter - minorDiameter) / 2), deeper than a 60-degree "
                           "thread of pitch {} can be ({}, its fundamental triangle)",
                           in.show((size.major - size.minor) / 2.0), in.show(size.pitch),
                           in.show(thread_triangle_height(size.pitch))));
    return size;
}

}  // namespace camgen
