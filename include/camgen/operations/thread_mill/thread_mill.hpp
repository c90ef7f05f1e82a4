#pragma once
// The thread-mill operation: an internal or external 60-degree thread milled with a thread
// mill at every hole of the hole sources (holes.hpp). Per radial pass the tool enters on a
// helical lead-in arc, follows a helix that advances exactly the thread's pitch per turn (the
// last turn partial where the length is not a whole number of pitches) and leaves on a
// helical lead-out arc; a spring pass repeats the last radius. The leads keep to the thread's
// helix (internal: a half circle through the hole's centre, whose angle about the centre is
// half its own, so that Z follows the helix exactly), so that the tool never cuts off the
// thread before or after it.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/heights.hpp"
#include "camgen/operations/holes.hpp"
#include "camgen/vocabulary/threads.hpp"

namespace camgen {

// Which thread: in a hole (internal, a nut's) or on a boss (external, a bolt's).
enum class ThreadSide { internal, external };
inline constexpr Named<ThreadSide> thread_sides[] = {
    {ThreadSide::internal, "internal", "in a hole: the tool's teeth reach out to the major diameter"},
    {ThreadSide::external, "external", "on a boss: the tool's teeth reach in to the minor diameter"},
};

// The thread's hand: right-hand rises turning counter-clockwise seen from above.
enum class ThreadHand { right, left };
inline constexpr Named<ThreadHand> thread_hands[] = {
    {ThreadHand::right, "right", "right-hand: tightens clockwise"},
    {ThreadHand::left, "left", "left-hand: tightens counter-clockwise"},
};

// The way the helix goes along the thread.
enum class ThreadOrder { bottom_up, top_down };
inline constexpr Named<ThreadOrder> thread_orders[] = {
    {ThreadOrder::bottom_up, "bottom-up", "from endDepth up to the reference plane"},
    {ThreadOrder::top_down, "top-down", "from the reference plane down to endDepth"},
};

// Mill threads with a thread mill (the holes: HoleSet; for an external thread each is the
// axis of a boss).
struct ThreadMillOp : HoleSet {
    static constexpr std::string_view type = "thread-mill";
    // Reads one operation of this type (its "type" is already read).
    static ThreadMillOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("thread-mill") first.
    static std::vector<ObjectSpec> objects();
    std::string path;          // JSON path of the operation, for messages
    std::string comment;
    int tool = 0;
    Heights heights;           // the thread from endDepth up to the reference plane
    ThreadSide side = ThreadSide::internal;
    ThreadHand hand = ThreadHand::right;
    CutDirection direction = CutDirection::climb;
    ThreadOrder sequence = ThreadOrder::bottom_up;  // follows from hand, side, direction and the spindle
    std::string thread;        // the designation ("M10x1.5"), or "" for one given by its diameters
    double major = 0.0;        // mm, major diameter (internal: D, reached by the last pass)
    double minor = 0.0;        // mm, minor diameter (external: d3, reached by the last pass)
    double pitch = 0.0;        // mm, the helix's advance per turn
    int passes = 1;            // radial passes, equal depths
    bool spring_pass = false;  // the last radius once more
    double feed = 0.0;         // mm/min, the tool centre along leads and helix
    double plunge_feed = 0.0;  // mm/min, down to the lead-in's start (in the clear)
    std::optional<double> tolerance;  // mm, for helices that become lines (capped by the machine's)
};

// The tool centre's radii about the thread's axis for a tool of `tool_diameter`: the first
// radius where its teeth touch the thread (internal: the minor diameter; external: the major)
// and the final one (internal: major / 2 - tool radius; external: minor / 2 + tool radius).
struct ThreadRadii {
    double first_contact = 0.0;
    double last = 0.0;
};
ThreadRadii thread_radii(const ThreadMillOp& op, double tool_diameter);

// The radius of each pass, in order: `passes` equal radial steps from the first contact to
// the last radius, then the last once more for a spring pass.
std::vector<double> thread_pass_radii(const ThreadMillOp& op, double tool_diameter);

// How far (mm) along the axis a lead arc goes at a pass of tool-centre radius `radius`:
// internal, a quarter pitch (the half circle through the centre turns a quarter turn about
// it); external, the pitch times the quarter turn of its arc (of the tool's radius) seen from
// the axis at the helix, pitch x tool radius / (4 x radius).
double thread_lead_rise(const ThreadMillOp& op, double radius, double tool_diameter);

// Per hole and pass: to the safe distance above the lead-in's start (internal: the hole's
// centre), down to it at plungeFeed, the lead-in arc, the helix, the lead-out arc, up to the
// safe distance (after the last pass the retract plane).
void expand(const ThreadMillOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "thread M10x1.5 internal, 2 holes".
std::string default_name(const ThreadMillOp& op);

}  // namespace camgen
