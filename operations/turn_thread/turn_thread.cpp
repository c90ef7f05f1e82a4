#include "camgen/operations/turn_thread/turn_thread.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/thread_size.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/vocabulary/threads.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

// The most cutting passes a thread may take (a finer rule than this is a mistake).
constexpr int turn_thread_max_passes = 200;
// The profile angle of the threads of the tables (ISO 68-1, ASME B1.1), degrees, and how far a
// tool's may differ from it.
constexpr double turn_thread_profile = 60.0;
constexpr double turn_thread_profile_slack = 0.5;

constexpr Named<ThreadSide> turn_thread_sides[] = {
    {ThreadSide::external, "external", "on the bar: the tool cuts from the major diameter in to the minor (d3)"},
    {ThreadSide::internal, "internal", "in a bore of the minor diameter (D1): the tool cuts out to the major"},
};

constexpr KeySpec turn_thread_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "tool", .type = JsonType::integer, .quantity = Quantity::count, .required = true, .min = Bound{1, true},
     .description = "a tool number from tools: a threading-tool of profileAngle 60, its rpm the constant spindle speed "
                    "of the thread (direction ccw for a left-hand thread)"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the operation"},
    {.key = "thread", .type = JsonType::string,
     .description = "the thread by its designation: ISO 261 metric, M20 (coarse pitch) or M20x1.5 (a coarse or fine "
                    "pitch of the size), or ASME B1.1 Unified, 1/4-20 UNC, #10-32 UNF"},
    {.key = "majorDiameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "or the thread by its diameters: the major diameter (with minorDiameter and pitch)"},
    {.key = "minorDiameter", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the minor diameter: an external thread's d3 (its last pass), an internal thread's D1 (the bore)"},
    {.key = "pitch", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "the thread's pitch (with majorDiameter and minorDiameter)"},
    {.key = "side", .type = JsonType::string, .default_json = "\"external\"", .choices = &choices_of<turn_thread_sides>,
     .description = "external (on the bar) or internal (in a bore)"},
    {.key = "hand", .type = JsonType::string, .default_json = "\"right\"", .choices = &choices_of<thread_hands>,
     .description = "right-hand, or left-hand: cut towards the chuck like a right-hand one with the spindle reversed "
                    "(the tool's direction ccw, the insert upside down)"},
    {.key = "starts", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{1, true}, .max = Bound{12, true},
     .default_json = "1",
     .description = "the thread's starts: the lead is pitch x starts, each start's passes begin one pitch further along Z"},
    {.key = "startZ", .quantity = Quantity::length, .required = true,
     .description = "Z of the thread's free end (towards +Z), where each pass enters it, mm"},
    {.key = "endZ", .quantity = Quantity::length, .required = true,
     .description = "Z where the thread ends towards the chuck, below startZ: each pass leaves it there, mm"},
    {.key = "runout", .type = JsonType::string, .default_json = "\"straight\"", .choices = &choices_of<thread_runouts>,
     .description = "how the thread ends at endZ"},
    {.key = "runoutLength", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "a chamfered runout's length along Z, ending at endZ: over it each pass pulls out by the thread's "
                    "depth, synchronised with the spindle (LinuxCNC G76 E); at least the thread's depth (45 degrees or "
                    "flatter), mm (default: one lead)"},
    {.key = "infeed", .type = JsonType::string, .default_json = "\"constant-area\"", .choices = &choices_of<thread_infeeds>,
     .description = "how the passes' depths grow"},
    {.key = "firstDepth", .quantity = Quantity::length, .required = true, .min = Bound{0, false},
     .description = "the radial depth of the first pass, mm (constant-depth: the most any pass takes)"},
    {.key = "minDepth", .quantity = Quantity::length, .min = Bound{0, true}, .default_json = "0",
     .description = "the least radial depth a pass takes (as Fanuc G76's Q), mm; 0: no least"},
    {.key = "springPasses", .type = JsonType::integer, .quantity = Quantity::count, .min = Bound{0, true},
     .max = Bound{10, true}, .default_json = "1", .description = "passes again at the full depth, for the tool's deflection"},
    {.key = "infeedAngle", .quantity = Quantity::angle, .min = Bound{0, true},
     .description = "degrees from radial: 0 radial infeed; a flank infeed up to half the profile angle (default: half the "
                    "tool's profileAngle less 0.5, 29.5 for 60)"},
    {.key = "approachDistance", .quantity = Quantity::length, .min = Bound{0, false},
     .description = "how far beyond startZ each pass starts, for the axis to reach the spindle's speed, mm (default: "
                    "3 x the lead)"},
    {.key = "retract", .quantity = Quantity::length, .min = Bound{0, false}, .default_json = "1",
     .description = "radial distance outside the thread (inside the bore) at which the tool returns, mm"},
    {.key = "output", .type = JsonType::string, .default_json = "\"auto\"", .choices = &choices_of<cycle_outputs>,
     .description = "auto: the machine's threading cycle (LinuxCNC G76) where it carries the thread's infeed rule, "
                    "minDepth, infeedAngle and springPasses and cuts camgen's passes, else longhand with a note; "
                    "canned: the cycle or an error; longhand: passes of G0 and G33/G32"},
};

}  // namespace

std::vector<double> thread_pass_depths(ThreadInfeed infeed, double total, double first, double min_depth) {
    std::vector<double> out;
    if (!(total > 0) || !(first > 0)) return out;
    if (infeed == ThreadInfeed::constant_depth) {
        const int n = std::max(1, static_cast<int>(std::ceil(total / first - 1e-9)));
        for (int k = 1; k < n; ++k) out.push_back(total * k / n);
        out.push_back(total);
        return out;
    }
    double at = 0.0;
    for (int k = 1; static_cast<int>(out.size()) <= turn_thread_max_passes; ++k) {
        double next = first * std::sqrt(static_cast<double>(k));
        next = std::max(next, at + min_depth);
        if (next >= total - 1e-9) break;
        out.push_back(next);
        at = next;
    }
    out.push_back(total);
    return out;
}

std::vector<ObjectSpec> TurnThreadOp::objects() {
    return {{.name = "turn-thread",
             .description = "a straight thread cut on a lathe with a threading tool, external or internal, in passes "
                            "synchronised with the spindle",
             .keys = {std::begin(turn_thread_keys), std::end(turn_thread_keys)}}};
}

TurnThreadOp TurnThreadOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, turn_thread_keys);
    const Tool& tool = in.tool(f);
    TurnThreadOp op;
    op.path = f.path();
    op.tool = tool.number;
    op.comment = f.optional_string("comment").value_or("");
    op.side = f.choice("side", turn_thread_sides, ThreadSide::external);
    op.hand = f.choice("hand", thread_hands, ThreadHand::right);
    if (tool.type != ToolType::threading_tool)
        f.fail("tool", fmt::format("a turn-thread needs a threading-tool; tool {} is a {}", tool.number,
                                   name_of(tool_types, tool.type)));
    // The thread: a designation from the tables, or its diameters and pitch.
    const ThreadSize size = read_thread_size(f, in, op.side, "a turn-thread", "M20x2.5", "M20x1.5");
    op.thread = size.name, op.major = size.major, op.minor = size.minor, op.pitch = size.pitch;
    const std::string what = op.thread.empty() ? fmt::format("the thread (pitch {})", in.show(op.pitch)) : op.thread;
    // The tool's tip must point at the thread's root: -X of its nose for an external thread
    // (orientations 1, 2, 6), +X for an internal one (3, 4, 8); none: the tip is the nose's point
    // towards the root (the simulation sweeps it as 2 outside, 3 inside).
    if (tool.orientation > 0) {
        const bool inward = tool.orientation == 1 || tool.orientation == 2 || tool.orientation == 6;
        const bool outward = tool.orientation == 3 || tool.orientation == 4 || tool.orientation == 8;
        if (op.side == ThreadSide::external ? !inward : !outward)
            f.fail("tool", fmt::format("an {} thread needs a threading-tool whose tip points {} (orientation {}); tool {} has "
                                       "orientation {}",
                                       op.side == ThreadSide::external ? "external" : "internal",
                                       op.side == ThreadSide::external ? "to -X, at the axis" : "to +X, at the bore's wall",
                                       op.side == ThreadSide::external ? "1, 2 or 6" : "3, 4 or 8", tool.number,
                                       tool.orientation));
    }
    const double profile = tool.profile_angle.value_or(0.0);
    if (std::abs(profile - turn_thread_profile) > turn_thread_profile_slack)
        f.fail("tool", fmt::format("tool {} has a profileAngle of {} degrees; {} has the 60-degree profile of ISO 68-1 "
                                   "and ASME B1.1: its flanks would be cut wrong",
                                   tool.number, number_text(profile), what));
    // A left-hand thread: the passes run towards the chuck as for a right-hand one, the spindle
    // reversed, so that the helix winds the other way.
    const SpindleDirection wanted = op.hand == ThreadHand::right ? SpindleDirection::cw : SpindleDirection::ccw;
    if (tool.direction != wanted)
        f.fail("hand", fmt::format("a {}-hand thread is cut towards the chuck with the spindle turning {}: tool {} turns "
                                   "{} (give the threading tool \"direction\": \"{}\"{})",
                                   op.hand == ThreadHand::right ? "right" : "left", wanted == SpindleDirection::cw ? "cw" : "ccw",
                                   tool.number, tool.direction == SpindleDirection::cw ? "cw" : "ccw",
                                   wanted == SpindleDirection::cw ? "cw" : "ccw",
                                   wanted == SpindleDirection::ccw ? ", its insert upside down" : ""));
    op.starts = static_cast<int>(f.optional_integer("starts").value_or(1));
    if (op.starts < 1 || op.starts > 12) f.fail("starts", "starts must be from 1 to 12");
    op.start_z = in.length(f, "startZ");
    op.end_z = in.length(f, "endZ");
    if (!(op.end_z < op.start_z))
        f.fail("endZ", fmt::format("endZ ({}) must be below startZ ({}): the passes cut towards the chuck", in.show(op.end_z),
                                   in.show(op.start_z)));
    op.runout = f.choice("runout", thread_runouts, ThreadRunout::straight);
    if (op.runout == ThreadRunout::straight && f.has("runoutLength"))
        f.fail("runoutLength", "runoutLength is the length of a chamfered runout: give \"runout\": \"chamfered\" with it");
    op.infeed = f.choice("infeed", thread_infeeds, ThreadInfeed::constant_area);
    op.first_depth = in.length(f, "firstDepth");
    if (!(op.first_depth > 0)) f.fail("firstDepth", "firstDepth must be > 0");
    op.min_depth = in.optional_length(f, "minDepth").value_or(0.0);
    if (op.min_depth < 0) f.fail("minDepth", "minDepth must be 0 or more");
    op.spring_passes = static_cast<int>(f.optional_integer("springPasses").value_or(1));
    if (op.spring_passes < 0 || op.spring_passes > 10) f.fail("springPasses", "springPasses must be from 0 to 10");
    op.infeed_angle = f.optional_number("infeedAngle").value_or(profile / 2.0 - 0.5);
    if (!(op.infeed_angle >= 0) || op.infeed_angle > profile / 2.0 + 1e-9)
        f.fail("infeedAngle", fmt::format("infeedAngle must be from 0 (radial) to half the tool's profileAngle ({} degrees)",
                                          number_text(profile / 2.0)));
    op.approach = in.optional_length(f, "approachDistance").value_or(3.0 * op.lead());
    if (!(op.approach > 0)) f.fail("approachDistance", "approachDistance must be > 0");
    op.retract = in.optional_length(f, "retract").value_or(1.0);
    if (!(op.retract > 0)) f.fail("retract", "retract must be > 0");
    op.output = f.choice("output", cycle_outputs, CycleOutput::automatic);
    if (op.runout == ThreadRunout::chamfered) {
        op.runout_length = in.optional_length(f, "runoutLength").value_or(op.lead());
        if (!(op.runout_length > 0)) f.fail("runoutLength", "runoutLength must be > 0");
    }

    const double total = op.root_radius() > op.surface_radius() ? op.root_radius() - op.surface_radius()
                                                                : op.surface_radius() - op.root_radius();
    if (op.first_depth > total + 1e-9)
        f.fail("firstDepth", fmt::format("firstDepth {} is more than the thread's depth {}", in.show(op.first_depth),
                                         in.show(total)));
    if (op.min_depth > total + 1e-9)
        f.fail("minDepth", fmt::format("minDepth {} is more than the thread's depth {}", in.show(op.min_depth), in.show(total)));
    if (op.runout == ThreadRunout::chamfered) {
        // The pull-out: the thread's depth over runoutLength. Steeper than 45 degrees, X would be
        // the longer axis, along which Fanuc's G32 F and Sinumerik's G33 take the lead.
        const std::string key = f.has("runoutLength") ? "runoutLength" : "runout";
        if (op.runout_length < total - 1e-9)
            f.fail(key, fmt::format("a chamfered runout of length {} is steeper than 45 degrees for the thread's depth {} "
                                    "(Fanuc G32 and Sinumerik G33 measure such a taper's lead along X): give a "
                                    "runoutLength of at least the depth",
                                    in.show(op.runout_length), in.show(total)));
        if (op.runout_length > op.start_z - op.end_z - 1e-9)
            f.fail(key, fmt::format("a chamfered runout of length {} is not shorter than the thread (startZ {} to endZ {})",
                                    in.show(op.runout_length), in.show(op.start_z), in.show(op.end_z)));
    }
    op.depths = thread_pass_depths(op.infeed, total, op.first_depth, op.min_depth);
    if (static_cast<int>(op.depths.size()) > turn_thread_max_passes)
        f.fail("firstDepth", fmt::format("firstDepth {} makes more than {} passes", in.show(op.first_depth),
                                         turn_thread_max_passes));
    for (int k = 0; k < op.spring_passes; ++k) op.depths.push_back(total);

    // The passes start beyond the thread and return outside it (inside the bore): all of that in
    // the part's reach.
    const double clearance = in.header().clearance;
    const double shift = total * std::tan(op.infeed_angle * pi / 180.0);
    const double top = op.start_z + op.approach + (op.starts - 1) * op.pitch;
    if (top >= clearance)
        f.fail("startZ", fmt::format("the passes start at Z {} (startZ, approachDistance and the starts), at or above the "
                                     "clearance (Z {})",
                                     in.show(top), in.show(clearance)));
    // (a chamfered runout's first returns lie the thread's depth further in)
    const double inward = op.runout == ThreadRunout::chamfered ? total : 0.0;
    if (op.side == ThreadSide::internal && op.surface_radius() - op.retract - inward <= 0)
        f.fail("retract", fmt::format("retract {} inside a bore of diameter {} passes the axis{}", in.show(op.retract),
                                      in.show(op.minor), inward > 0 ? " (with the chamfered runout's pull-out)" : ""));
    if (const std::optional<Stock>& stock = in.header().stock; stock && stock->shape == StockShape::bar) {
        if (op.start_z > stock->face_z + 1e-9)
            f.fail("startZ", fmt::format("the thread starts at Z {}, beyond the bar's face (Z {})", in.show(op.start_z),
                                         in.show(stock->face_z)));
        if (op.end_z < stock->face_z - stock->length - 1e-9)
            f.fail("endZ", fmt::format("the thread ends at Z {}, beyond the bar's far end (Z {}): it is longer than the part",
                                       in.show(op.end_z), in.show(stock->face_z - stock->length)));
        if (op.side == ThreadSide::external && op.major > stock->diameter + 1e-9)
            f.fail(f.has("thread") ? "thread" : "majorDiameter",
                   fmt::format("{} has a major diameter of {}, more than the bar's {}", what, in.show(op.major),
                               in.show(stock->diameter)));
    }
    if (op.approach <= shift + 1e-9)
        f.fail("approachDistance", fmt::format("approachDistance {} is not beyond the flank infeed's shift of the last pass "
                                               "along Z ({}: the depth x tan(infeedAngle)): that pass would start in the "
                                               "thread",
                                               in.show(op.approach), in.show(shift)));
    if (op.side == ThreadSide::internal)
        op.notes.push_back(fmt::format("an internal thread: the bore (D1 {}) must be there before it, made by an earlier "
                                       "operation or the stock's boreDiameter; the passes rapid inside it at X {} (camgen "
                                       "simulate checks what the program cuts)",
                                       in.show(op.minor), in.show(2 * (op.surface_radius() - op.retract))));
    op.notes.push_back(fmt::format("{}: {} passes of depths {} mm (radial){}", what, op.depths.size(),
                                   [&] {
                                       std::string s;
                                       for (double d : op.depths) s += (s.empty() ? "" : ", ") + number_text(d, 3);
                                       return s;
                                   }(),
                                   op.spring_passes == 1   ? ", the last a spring pass"
                                   : op.spring_passes > 1 ? fmt::format(", the last {} spring passes", op.spring_passes)
                                                          : ""));
    return op;
}

namespace {
Vec3 turn_thread_at(double r, double z) { return {r, 0.0, z}; }
}  // namespace



ThreadCycle thread_cycle(const TurnThreadOp& op, int start) {
    const double out = op.side == ThreadSide::external ? 1.0 : -1.0;
    const double total = std::abs(op.root_radius() - op.surface_radius());
    ThreadCycle c;
    c.path = op.path;
    c.output = op.output;
    c.start = turn_thread_at(op.surface_radius() + out * op.retract, op.start_z + op.approach + start * op.pitch);
    c.end_z = op.end_z;
    c.lead = op.lead();
    c.crest_x = op.surface_radius();
    c.depth = total;
    const int cutting = static_cast<int>(op.depths.size()) - op.spring_passes;
    if (op.infeed == ThreadInfeed::constant_depth) {
        // Equal steps: the first is the step, the cycle's J.
        c.degression = 1.0;
        c.first_depth = total / cutting;
        c.fields.emplace_back("constant-depth");
    } else {
        c.degression = 2.0;
        c.first_depth = std::min(op.first_depth, total);
        c.fields.emplace_back("constant-area");
    }
    // A least depth that changes the passes is the cycle's to carry; one that does not is not used.
    if (op.min_depth > 0 && thread_pass_depths(op.infeed, total, op.first_depth, 0.0) !=
                                thread_pass_depths(op.infeed, total, op.first_depth, op.min_depth)) {
        c.min_depth = op.min_depth;
        c.fields.emplace_back("minDepth");
    }
    c.infeed_angle = op.infeed_angle;
    if (op.infeed_angle > 0) c.fields.emplace_back("infeedAngle");
    c.spring_passes = op.spring_passes;
    if (op.spring_passes > 0) c.fields.emplace_back("springPasses");
    c.depths = op.depths;
    if (op.runout == ThreadRunout::chamfered) {
        c.runout = op.runout_length;
        c.fields.emplace_back("runout");
    }
    return c;
}

void expand(const TurnThreadOp& op, const Context& ctx, EventSink& sink) {
    const double out = op.side == ThreadSide::external ? 1.0 : -1.0;  // the direction out of the material, in X
    const double surface = op.surface_radius();
    const double away = surface + out * op.retract;                      // the returns' X
    const double tan_a = std::tan(op.infeed_angle * pi / 180.0);
    sink.emit(Rapid{turn_thread_at(away, ctx.job.clearance)});
    if (op.output != CycleOutput::longhand) {
        // A cycle per start from its drive point; the post writes it canned or its moves.
        for (int s = 0; s < op.starts; ++s) {
            const ThreadCycle c = thread_cycle(op, s);
            sink.emit(Rapid{c.start});
            sink.emit(c);
        }
        sink.emit(Rapid{turn_thread_at(away, ctx.job.clearance)});
        return;
    }
    const double total = std::abs(op.root_radius() - surface);
    const bool chamfered = op.runout == ThreadRunout::chamfered;
    for (int s = 0; s < op.starts; ++s) {
        for (double depth : op.depths) {
            // Flank infeed: the pass starts earlier along the feed by depth x tan(angle), so that
            // the groove moves along Z with the depth and the tool cuts on its leading flank.
            const double z0 = op.start_z + op.approach + s * op.pitch - depth * tan_a;
            const double r = surface - out * depth;
            // A chamfered runout ends the pass (total - depth) outside the crest: the return
            // stays retract beyond that (as LinuxCNC's G76 returns).
            const double back = chamfered ? away + out * (total - depth) : away;
            sink.emit(Rapid{turn_thread_at(back, z0)});
            sink.emit(Rapid{turn_thread_at(r, z0)});
            if (chamfered) {
                sink.emit(ThreadFeed{turn_thread_at(r, op.end_z + op.runout_length), op.lead()});
                sink.emit(ThreadFeed{turn_thread_at(r + out * total, op.end_z), op.lead()});
            } else {
                sink.emit(ThreadFeed{turn_thread_at(r, op.end_z), op.lead()});
            }
            sink.emit(Rapid{turn_thread_at(back, op.end_z)});
        }
    }
    sink.emit(Rapid{turn_thread_at(away, ctx.job.clearance)});
}

std::string default_name(const TurnThreadOp& op) {
    if (!op.comment.empty()) return op.comment;
    return op.thread.empty() ? "turn thread" : "turn thread " + op.thread;
}

}  // namespace camgen
