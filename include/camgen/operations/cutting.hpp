#pragma once
// The cutting engine every operation that mills along a path shares (contour, pocket, face),
// as holes.* serves drill and bore-mill: the keys and readers of profiles, leads, ramps,
// finishing, tabs and feeds; the offset planning of a profile cut beside (`plan_offsets`, a
// library user can call it on structs); and the `Cutter` that turns paths into events (depth
// passes, leads, ramps, compensation switching, tabs, links) driven by a `CutSettings` value.
// Operations decide which paths to cut in which order; the Cutter decides how the tool gets
// onto, along and off each of them. Lengths mm, feeds mm/min, angles degrees.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/events/events.hpp"
#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/heights.hpp"

namespace camgen {

// Where the tool cuts, seen along the profile as drawn (left, right), on it, or for a closed
// profile inside or outside whatever the drawing direction.
enum class ContourSide { left, right, on, inside, outside };
inline constexpr Named<ContourSide> contour_sides[] = {
    {ContourSide::left, "left", "left of the profile as drawn"},
    {ContourSide::right, "right", "right of the profile as drawn"},
    {ContourSide::on, "on", "the tool centre on the profile (no offset)"},
    {ContourSide::inside, "inside", "inside a closed profile (a pocket wall)"},
    {ContourSide::outside, "outside", "outside a closed profile (a part's outline)"},
};

// Who offsets the tool radius (Fusion's compensation types).
enum class CompensationMode { computer, control, wear, inverse_wear };
inline constexpr Named<CompensationMode> compensation_modes[] = {
    {CompensationMode::computer, "computer", "camgen offsets the path by the tool radius; no G41/G42"},
    {CompensationMode::control, "control",
     "the program is the profile itself with G41/G42 (RL/RR): the control offsets by the radius in its tool table"},
    {CompensationMode::wear, "wear",
     "camgen offsets by the radius and writes G41/G42 too: the control's table holds only the wear (negative shrinks the cut)"},
    {CompensationMode::inverse_wear, "inverse-wear", "as wear with G41 and G42 swapped: a positive wear shrinks the cut"},
};

// A lead-in or lead-out: none, a tangent arc (radius, sweep in degrees) or a straight line
// (length, angle in degrees from the tangent towards the tool's side).
struct Lead {
    enum class Kind { none, arc, line } kind = Kind::none;
    double radius = 0.0;
    double sweep = 90.0;
    double length = 0.0;
    double angle = 0.0;
};

// How the tool gets down to each pass: plunge straight down, ramp along the path at an
// angle (degrees above horizontal), or a helix of a radius at that angle before the lead-in.
struct Ramp {
    enum class Kind { plunge, along, helix } kind = Kind::plunge;
    double angle = 5.0;
    double radius = 0.0;
};

// Tabs on a closed through-cut, each `width` mm wide on the part (the tool stays up over its
// width plus the tool's diameter along the path) and `height` mm above the bottom of the cut,
// with flanks at `ramp_angle` degrees (90: straight up and down; less: a trapezoid, `width` at
// its top, the tool climbing and descending along the path at that angle).
// Where: `count` tabs spread by length over the profile's straight runs (consecutive collinear
// lines, across a closed profile's start too) and arcs long enough, none within the tool radius
// plus half a tab (and its flank) of a corner or of the profile's start; or the explicit
// positions `at`, mm along the profile as drawn from its start (a job's points near the profile
// are read as the distance of their nearest point). Reading plans `centres` from either.
struct Tabs {
    int count = 0;
    std::vector<double> at;
    double width = 0.0;
    double height = 0.0;
    double ramp_angle = 90.0;
    std::vector<double> centres;  // planned on reading: mm along the profile as drawn, ascending
};

// The finishing pass: after roughing that leaves `radial_stock` on the wall and
// `axial_stock` on the floor, the final offset at the full depth: in one pass, or in steps of
// at most `step_down` (a tall wall finished in several depths).
struct Finishing {
    double radial_stock = 0.0;
    double axial_stock = 0.0;
    std::optional<double> step_down;
};

// The feeds of each movement kind, mm/min (CNC-Calc's getFeedrate(movement)).
struct CutFeeds {
    double cutting = 0.0;
    double plunge = 0.0;
    double ramp = 0.0;
    double lead_in = 0.0;
    double lead_out = 0.0;
    double finishing = 0.0;
};
using ContourFeeds = CutFeeds;

// ---- Keys and reading

// A segment shorter than this is refused: no control writes it as a move of its own, mm.
inline constexpr double min_profile_segment = 0.001;
// Sanity bound on depth passes, so that a tiny step cannot make a program without end.
inline constexpr double max_depth_passes = 10000;

// The keys of a profile ("start", "path"), of the feeds (feed, plungeFeed, rampFeed,
// leadInFeed, leadOutFeed, finishingFeed), of the depth passes (stepDown, equalSteps), each in
// the order a job lists them.
std::vector<KeySpec> profile_keys(std::string_view what);
std::vector<KeySpec> cut_feed_keys();
std::vector<KeySpec> depth_pass_keys();

// The objects the cutting keys hold (contourElement, contourArc, contourFinishing,
// contourLead, contourRamp, contourTabs), for the JSON Schema.
std::vector<ObjectSpec> cutting_objects();

// Refuses a pointed tool (chamfer-mill, v-bit) for an operation that cuts with the tool's side
// at its diameter (contour, pocket, face; `what` names it: "a contour"): an error at "tool".
// Other tool types are accepted as they always were.
void check_cutting_tool(json::Fields& f, const Tool& tool, std::string_view what);
// The note for a tool given no type (a drill by default) that contour, pocket or face mill
// with, as with an end mill; none for a typed tool.
std::optional<std::string> untyped_milling_note(const Tool& tool);

// A profile from `start_key` and `path_key` (lines and arcs; packed lines read straight into
// numbers), refused when an element is shorter than min_profile_segment or the profile crosses
// itself. `what` names the owner in messages ("a contour").
// Or, when f has "profile" (and `start_key` is "start"), the one profile of a DXF drawing's
// selection (dxf_source.hpp), its notes added to `notes`.
Profile read_profile(json::Fields& f, const JobInput& in, std::string_view what, std::string_view start_key = "start",
                     std::string_view path_key = "path", std::vector<std::string>* notes = nullptr);
// The lead at `key` (none when absent); radius and length default to the tool's diameter.
Lead read_lead(json::Fields& f, const JobInput& in, std::string_view key, double tool_diameter);
// The ramp at `key` (a plunge when absent); a helix radius defaults to the tool's radius.
Ramp read_ramp(json::Fields& f, const JobInput& in, std::string_view key, double tool_radius);
// The finishing pass at "finishing", checked against the depth of the cut.
std::optional<Finishing> read_finishing(json::Fields& f, const JobInput& in, double total_depth);
// The feeds: "feed", each other one defaulting to it. Where the job gives no feed and `tool` has
// library cutting data with a feed per tooth, the feed is computed from them (corrected for a
// radial `engagement` below half the diameter, mm; 0: not known, no correction) and a note saying
// so appended to `notes`; else "feed" is required.
CutFeeds read_cut_feeds(json::Fields& f, const JobInput& in, const Tool& tool, double engagement,
                        std::vector<std::string>& notes);
// An operation's cutting feed "feed", or where it gives none the feed computed from its tool's
// library cutting data (fz x flutes x rpm, fz corrected for a radial `engagement` below half
// the diameter; 0: not known), else refused as missing. `circle`: the tool centre goes round a
// circle of radius `circle->centre` to cut at radius `circle->wall` (a bore's or a thread's);
// a computed feed is for the cutting edge, so the centre's is scaled by centre / wall (slower
// inside a hole, faster outside a boss), with a note. What was computed goes to `notes`.
struct CircularCut {
    double centre = 0.0;  // mm, the tool centre's radius
    double wall = 0.0;    // mm, the radius the tool cuts at
};
double read_cutting_feed(json::Fields& f, const JobInput& in, const Tool& tool, double engagement,
                         std::vector<std::string>& notes, std::optional<CircularCut> circle = std::nullopt);
// "stepDown" (absent: one pass), checked against the depth's pass count.
std::optional<double> read_step_down(json::Fields& f, const JobInput& in, double total_depth);
// The step between rings or rows: "stepOver" (a length) or "stepOverPercent" (of the tool's
// diameter, `default_percent` when neither is given), checked: more than 0, at least 1 % of
// the diameter and at most the diameter (rows further apart leave material between them).
// `key` is set to the key that gave it, for later messages.
double read_step_over(json::Fields& f, const JobInput& in, double tool_diameter, double default_percent, std::string& key);
// The key "tolerance" (the chord tolerance of arcs a machine writes as lines).
std::vector<KeySpec> tolerance_keys();
// The keys every operation with a tool starts with: type, tool, comment.
std::vector<KeySpec> operation_head_keys();
// The machine's chord tolerance cap for arcs made lines ("tolerance"), if given.
std::optional<double> read_tolerance(json::Fields& f, const JobInput& in);

// What the tabs need to know of the cut they sit on.
struct TabGeometry {
    const Profile* profile = nullptr;  // as drawn
    bool tool_left = true;             // the tool left of the profile as drawn
    double distance = 0.0;             // of the tool centre from the profile while roughing
    double tool_radius = 0.0;
    double tool_diameter = 0.0;
};
// The tabs at "tabs" of a closed cut `total_depth` deep, planned (see Tabs).
std::optional<Tabs> read_tabs(json::Fields& f, const JobInput& in, const TabGeometry& g, double total_depth, bool closed);

// The pass depths from the top down (absolute Z): steps of at most `step_down` from `top` to
// `bottom`, equal (each (top - bottom) / n) or full steps with a smaller last one.
std::vector<double> pass_depths(double top, double bottom, std::optional<double> step_down, bool equal_steps);

// ---- Offset planning

// A profile cut beside: what to offset by how much.
struct OffsetRequest {
    const Profile* profile = nullptr;   // as drawn
    ContourSide side = ContourSide::outside;
    CutDirection direction = CutDirection::climb;
    SpindleDirection spindle = SpindleDirection::cw;
    CompensationMode compensation = CompensationMode::computer;
    double tool_radius = 0.0;
    double stock_to_leave = 0.0;
    double finishing_stock = 0.0;       // radialStock of a finishing pass
    bool finishing = false;             // plan a finishing path too
    std::string json_path;              // the operation's, for notes ("/operations/2")
};
// The paths: the tool's side of its travel, the roughing and finishing paths (programmed: the
// tool centre, or the profile under control compensation) and the notes of what camgen decided.
struct OffsetPlan {
    bool tool_left = true;
    Profile rough;
    Profile finish;   // empty: no finishing pass
    std::vector<std::string> notes;
};
// Planning refuses with the key to blame ("path") and a sentence.
struct PlanError : std::runtime_error {
    PlanError(std::string key, const std::string& message) : std::runtime_error(message), key(std::move(key)) {}
    std::string key;
};
// `show` writes a length as the job's units do. Throws PlanError.
OffsetPlan plan_offsets(const OffsetRequest& request, const std::function<std::string(double)>& show);

// ---- The cutter

// Everything the Cutter needs, resolved.
struct CutSettings {
    int tool = 0;
    double tool_radius = 0.0;
    bool tool_left = true;                      // the tool left of its travel
    CompensationMode compensation = CompensationMode::computer;
    Lead lead_in, lead_out;
    Ramp ramp;
    const Tabs* tabs = nullptr;                 // tabs, with centres along `drawn`
    const Profile* drawn = nullptr;             // the profile as drawn (tabs)
    CutFeeds feeds;
    Planes z;
    double clearance = 0.0;                     // the job's clearance height, absolute Z
};

// Emits the moves of paths, keeping track of where the tool is.
class Cutter {
public:
    Cutter(const CutSettings& settings, EventSink& sink) : s_(settings), sink_(sink) {}

    // Every pass of one path at `depths` (absolute Z, top down): lead in once (each pass for an
    // open path), down pass by pass, lead out, up to the retract plane (the clearance after the
    // `last_run`).
    void cut_run(const Profile& p, bool closed, const std::vector<double>& depths, Movement m, double feed, bool last_run);

    // The primitives operations link paths with.
    void rapid(Vec3 to);
    void feed_to(Vec3 to, double feed, Movement m);
    // The segments of `p` from the tool's position, Z going linearly from `z0` to `z1` along it.
    void follow(const Profile& p, double z0, double z1, double feed, Movement m);
    // Down from the tool's Z to `z` at its XY: a plunge, or the settings' helix about a centre
    // `away` (a unit vector) from the tool, of `radius` (0: the ramp's radius).
    void go_down(double z, Vec2 away, double radius = 0.0);
    // Up to the retract plane (the clearance when `done`).
    void retract(bool done);
    // The tool's position (valid after the first rapid).
    Vec3 at() const { return at_; }
    bool known() const { return known_; }
    // Carries on from where another cutter left the tool (no first rapid to the clearance).
    void continue_from(Vec3 at) {
        at_ = at;
        known_ = true;
        first_ = false;
    }

    // The lead-in onto `p`'s start (its path's start is where the tool goes down) and the
    // lead-out from its end.
    Profile lead_in(const Profile& p) const;
    Profile lead_out(const Profile& p) const;

private:
    bool control_compensates() const { return s_.compensation != CompensationMode::computer; }
    double switch_length() const;
    Vec2 side_normal(Vec2 t) const;
    Profile control_line_lead_in(const Profile& p) const;
    Profile control_line_lead_out(const Profile& p) const;
    CompensationSide compensation_side() const;
    double compensation_radius() const;
    void cut_pass(const Profile& p, double z, double feed, Movement m);
    struct TabSpan {
        double a = 0.0, b = 0.0;
    };
    const std::vector<TabSpan>& tab_intervals(const Profile& p);
    void follow_over_tabs(const Profile& p, double x0, double x1, double z0, double z1, double feed, Movement m);
    void pass_from_start(const Profile& p, double z_prev, double z, double feed, Movement m);

    const CutSettings& s_;
    EventSink& sink_;
    Vec3 at_;
    bool known_ = false;
    bool first_ = true;
    const Profile* tab_path_ = nullptr;  // the path tab_spans_ are on
    std::vector<TabSpan> tab_spans_;
};

// The key of an operation's that made the move a part guard refused, and a hint: "leadIn",
// "ramp", "path", ...; `control` says the control compensates.
struct GuardBlame {
    std::string key;
    std::string hint;
};
GuardBlame guard_blame(Movement movement, bool rapid, bool control);

}  // namespace camgen
