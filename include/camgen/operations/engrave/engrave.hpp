#pragma once
// The engrave operation (issue 29, item 4): text in a Hershey single-stroke font (hershey.hpp,
// read at run time from Debian's hershey-fonts-data), placed along a line or around an arc, or
// any path or drawing's profiles, cut on their line to a depth below the reference plane. The
// strokes are ordered to keep the rapids short (nearest neighbour, a stroke reversed where its
// end is nearer); each is entered from above its start at the plunge feed, cut (in `passes`
// depth steps, back and forth along it) and left by a rapid to the retract plane. A V-bit's line
// is as wide at the top as its V at the depth (tool_geometry.hpp); the width is said in a note.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/job/job_input.hpp"
#include "camgen/operations/context.hpp"
#include "camgen/operations/heights.hpp"

namespace camgen {

// Where the text's anchor is along its lines: their start, middle or end.
enum class TextAlign { left, centre, right };
inline constexpr Named<TextAlign> text_aligns[] = {
    {TextAlign::left, "left", "the lines start at the anchor"},
    {TextAlign::centre, "centre", "the lines are centred on the anchor"},
    {TextAlign::right, "right", "the lines end at the anchor"},
};

// Where the anchor is across the text: on the first line's baseline, in the middle between the
// first line's cap top and the last line's baseline, or at the first line's cap top.
enum class TextVerticalAlign { baseline, middle, top };
inline constexpr Named<TextVerticalAlign> text_vertical_aligns[] = {
    {TextVerticalAlign::baseline, "baseline", "the anchor is on the first line's baseline"},
    {TextVerticalAlign::middle, "middle", "the anchor is midway between the first line's cap top and the last line's baseline"},
    {TextVerticalAlign::top, "top", "the anchor is at the first line's cap height"},
};

// The font when the job names none.
inline constexpr std::string_view engrave_default_font = "rowmans";

// How text is set: the font, its cap height and spacings, mm; the alignment.
struct TextStyle {
    double height = 0.0;        // cap height
    double spacing = 0.0;       // added between letters
    double line_spacing = 0.0;  // baseline to baseline
    TextAlign align = TextAlign::left;
    TextVerticalAlign vertical = TextVerticalAlign::baseline;
};

// Where text is placed: along a line from `at` turned by `rotation` degrees counter-clockwise,
// or around an arc about `centre` of `radius` (the first line's baseline... as vertical
// alignment puts it), its anchor at `start_angle` degrees, running clockwise (the glyphs' tops
// outward: a circle's top) or counter-clockwise (tops towards the centre: its bottom); each
// glyph upright to the arc at its middle.
struct TextPlacement {
    bool on_arc = false;
    Vec2 at;
    double rotation = 0.0;
    Vec2 centre;
    double radius = 0.0;
    double start_angle = 90.0;
    ArcDirection direction = ArcDirection::cw;
};

struct HersheyFont;

// The strokes of `text` ('\n' between lines) set in `font`, as polylines in XY (mm). A
// character the font lacks is refused by the caller before (engrave_missing_character).
std::vector<Profile> engrave_text_strokes(const HersheyFont& font, std::u32string_view text, const TextStyle& style,
                                          const TextPlacement& place);

// Engrave text, a path or a drawing's profiles with a V-bit, chamfer mill, ball, bull-nose or
// end mill.
struct EngraveOp {
    static constexpr std::string_view type = "engrave";
    // Reads one operation of this type (its "type" is already read).
    static EngraveOp read(json::Fields& f, const JobInput& input);
    // The objects of its input, for the JSON Schema: the operation ("engrave") first.
    static std::vector<ObjectSpec> objects();
    std::string path;          // JSON path of the operation, for messages
    std::string comment;
    int tool = 0;
    Heights heights;           // the depth below the reference plane
    int passes = 1;            // equal depth steps
    double feed = 0.0;         // mm/min along the strokes
    double plunge_feed = 0.0;  // mm/min down into each stroke
    std::optional<double> tolerance;  // mm, for arcs that become lines (capped by the machine's)
    std::string text;          // the text engraved ("" for a path or profiles)
    std::string font;          // its font's name
    double width = 0.0;        // mm, the line's width at the reference plane
    std::vector<Profile> strokes;     // in cutting order, each in the direction its first pass runs
    std::vector<std::string> notes;   // the line's width, computed feeds, a drawing's notes
};

// The order strokes are cut in: from the first, each next the one whose start or end is
// nearest where the last ended (reversed where its end is), ties to the earlier. Deterministic.
std::vector<Profile> engrave_order(std::vector<Profile> strokes);

// Per stroke: a rapid at the retract plane above its start, down to the safe distance, feed down
// at plungeFeed, cut (passes back and forth), rapid up to the retract plane.
void expand(const EngraveOp& op, const Context& context, EventSink& sink);

// The operation's name for comments: its comment, else "engrave \"SN 0042\"" or "engrave 3 strokes".
std::string default_name(const EngraveOp& op);

}  // namespace camgen
