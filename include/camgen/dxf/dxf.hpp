#pragma once
// Reading 2D geometry from an ASCII DXF drawing (R12 to R2018), camgen's own strict reader
// after the group codes of the published DXF reference: LINE, ARC, CIRCLE, LWPOLYLINE and
// POLYLINE (with bulges), POINT, ELLIPSE and SPLINE (fitted by arcs and lines within a tolerance;
// an ellipse that is a circle stays arcs), INSERT of blocks (nested, scaled, rotated, mirrored,
// arrays), entities in an OCS whose extrusion is +Z or -Z (-Z mirrors X: common from CAD
// exports). Model space only unless asked. Binary DXF and DWG are refused by name; every error
// names the file, the line of the group code, and where there is one the entity's type,
// handle and layer.
//
// Then, on what was read: selection (layers, colours, linetypes, blocks, circle diameters),
// chaining of lines, arcs and open polylines into profiles with a gap tolerance (duplicates
// and zero-length pieces dropped with a note), and the nesting of closed profiles.
// Depends on the geometry only. Lengths in the drawing's units (see `Drawing::units`) until a
// caller scales them.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/geometry/profile.hpp"

namespace camgen::dxf {

// A drawing that cannot be read or a selection that finds nothing; what() is the whole
// message ("plate.dxf line 120: CIRCLE (handle 2A, layer HOLES): ...").
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The text the pieces of a drawing name (handles, layer and linetype names, chains of block
// names), owned by the Drawing read (shared by its copies): an Origin's views stay valid while
// the Drawing it came from (or a copy of it) lives. Layer and linetype names are interned (one
// copy of each name), handles kept in chunks, so a piece costs no heap allocation of its own.
struct DrawingText;

// Where a piece came from.
struct Origin {
    std::string_view type;     // the DXF entity: "LINE", "ARC", "LWPOLYLINE", ...
    std::string_view handle;   // group 5 ("" when the writer gave none)
    std::string_view layer;    // resolved: layer "0" inside a block takes the INSERT's
    std::string_view linetype; // resolved: BYLAYER from the layer table, BYBLOCK from the INSERT
    int colour = 7;            // ACI 1..255, resolved as the linetype
    std::size_t line = 0;      // the line of the entity's "0" group in the file
    std::span<const std::string_view> blocks;  // the blocks it was inserted through, outermost first
};

// One thing drawn, in world coordinates of the XY plane.
struct Piece {
    enum class Kind { point, circle, path } kind = Kind::path;
    Origin origin;
    Vec2 centre;            // point, circle
    double radius = 0.0;    // circle
    Profile path;           // path: lines and arcs (a LINE is one segment)
    bool closed = false;    // path: a closed polyline (or a fitted closed curve)
};

struct Layer {
    std::string name;
    int colour = 7;
    std::string linetype = "CONTINUOUS";
};

struct Drawing {
    std::string name;             // the file, as given
    int insunits = 0;             // $INSUNITS (0: none given)
    std::vector<Layer> layers;    // the layer table, then layers only entities name
    std::vector<Piece> pieces;    // model space, inserts expanded, in file order
    std::vector<std::string> notes;
    std::shared_ptr<const DrawingText> text;  // what the pieces' Origins view
};

struct ReadOptions {
    double curve_tolerance = 0.01;   // the arcs and lines of ellipses and splines from the curve, drawing units
    bool paper_space = false;        // also entities of paper space
};

// The largest drawing read, bytes (1 GiB), and the deepest nesting of inserts.
inline constexpr std::size_t max_file_bytes = std::size_t{1} << 30;
inline constexpr int max_insert_depth = 32;
// The most pieces an INSERT array or all inserts together may make.
inline constexpr std::size_t max_pieces = 20'000'000;

// Reads `text`, named `name` in messages. Throws Error.
Drawing read_text(std::string_view text, const std::string& name, const ReadOptions& options = {});
// Reads the file. Throws Error (also for a file that cannot be opened, a binary DXF, a DWG).
// The file is mapped, not copied, and the pages read are let go as the reader moves on: the
// memory of a read is the pieces, not the file.
Drawing read_file(const std::string& path, const ReadOptions& options = {});

// Reads the file as read_file does, but hands each piece to `each` as it is read (model space
// in file order, then the pieces of inserts) instead of keeping it: the Drawing returned has
// no pieces (its layers, units, notes and text are whole). The Origin of a piece views the
// Drawing's text, valid while it lives. With a TABLES section after the entities (rare), the
// pieces before it are held until the end (their layers resolved then). After an Error the
// pieces handed on view text that is gone: drop them.
using PieceSink = std::function<void(Piece&&)>;
Drawing read_file(const std::string& path, const PieceSink& each, const ReadOptions& options = {});
Drawing read_text(std::string_view text, const std::string& name, const PieceSink& each, const ReadOptions& options = {});

// Millimetres per drawing unit of an $INSUNITS code, nullopt for 0 (unitless) and codes
// camgen does not take (an Error names them); `name` gets the unit's name ("inches").
std::optional<double> mm_per_unit(int insunits, std::string* name = nullptr);

// ---- Selection

struct Selection {
    std::vector<std::string> layers;     // empty: any (names compared without case, as CAD does)
    std::vector<int> colours;            // empty: any
    std::vector<std::string> linetypes;  // empty: any
    std::vector<std::string> blocks;     // empty: any (else: inserted through one of these)
    std::optional<double> min_diameter, max_diameter;  // circles only, drawing units
};

// The pieces the selection takes. A layer (linetype, block) the drawing does not have is an
// Error listing those it has; `what` names the caller's need in the message when nothing is
// selected ("holes").
std::vector<const Piece*> select(const Drawing& d, const Selection& s, std::string_view what);

// ---- Chaining

// A chain of pieces: one profile, closed or open, and the pieces it came from in order.
struct Chain {
    Profile profile;
    bool closed = false;
    std::vector<const Piece*> pieces;
};

struct ChainResult {
    std::vector<Chain> chains;
    std::vector<std::string> notes;  // gaps closed, duplicates and zero-length pieces dropped
};

// Joins the path pieces (and circles, as closed profiles) of `pieces` end to end: ends closer
// than `gap` are joined (a note for each joint wider than 1e-6); a piece drawn twice and a
// piece shorter than 1e-6 are dropped with a note. Points are ignored.
ChainResult chain(const std::vector<const Piece*>& pieces, double gap, const std::string& file);
// The same, the pieces' paths moved into the chains (no copy of the geometry: a piece keeps its
// origin, its path left empty). For a caller that owns the pieces and needs their paths no more.
ChainResult chain_taking(const std::vector<Piece*>& pieces, double gap, const std::string& file);

// "LINE handle 1F (line 120)", for messages.
std::string describe(const Origin& o);

// The closed chains nested: for each chain the index of the smallest closed chain that holds
// it, or -1.
std::vector<int> nesting(const std::vector<Chain>& chains);

// The extent of a profile (sampled within 0.001).
struct Box {
    Vec2 min, max;
};
Box extent(const Profile& p);

}  // namespace camgen::dxf
