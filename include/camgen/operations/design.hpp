#pragma once
// What a job designs: the part its operations leave, as a simulated part is checked against it
// (`camgen simulate --job`). 2.5D: regions in XY with heights. Each operation contributes
//
// - cuts: where it removes material and down to which floor (a pocket's region less its
//   islands down to the bottom, a contour's band of one tool diameter beside its wall, a hole's
//   disc down to its bottom with the drill's point, a face's area); a tab raises its contour's
//   floor over its width (`overrides`); the stretch where the tool climbs onto a tab may keep
//   material (`may_leave`);
// - keeps: the part beside a cut that must stay up to the stock top (a contour's part side, a
//   pocket's islands and a band around its walls, a band around a hole).
//
// At a point the designed height is the lowest floor of the cuts that cover it (a tab: its own
// operation's floor there is the tab's top), else the top of the keeps that cover it; nothing is
// designed elsewhere (the scrap outside an outside contour, what a path passes through).
// Operations without a designed part (path, custom, stops, open contours) are named in
// `unchecked`. A lathe's operations design its turned part (`lathe`, design_lathe.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/region.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/design_lathe.hpp"

namespace camgen {

struct Job;

// A floor: flat at `z`; or a drill's point or a hole's chamfer: z + slope x the distance from
// `apex`; or a chamfer beside a profile: z + slope x the distance from `edge` (a negative slope
// falls away from it); either no lower than `lowest` (a cone's tip).
struct DesignFloor {
    double z = 0.0;
    std::optional<Vec2> apex;
    double slope = 0.0;  // mm of height per mm from the apex or edge (a drill: 1 / tan of half the tip angle)
    std::shared_ptr<const Profile> edge;
    double lowest = -std::numeric_limits<double>::infinity();
    double at(Vec2 p) const {
        if (edge) return std::max(lowest, z + slope * distance_to(*edge, p));
        if (!apex) return z;
        const double dx = p.x - apex->x, dy = p.y - apex->y;
        return std::max(lowest, z + slope * std::sqrt(dx * dx + dy * dy));
    }
};

// An operation's holes: discs of one radius about their centres (a cut: each disc; a keep: each
// ring from `hole` out to `radius`), kept as centres rather than as a region each (a hundred
// thousand holes). A feature with discs has an empty `region`; its floor's apex, if it has one,
// is each disc's centre; its `what` names a hole by its index ("hole" -> "hole 3 at (20, 10)").
struct DesignDiscs {
    std::vector<Vec2> centres;
    double radius = 0.0;  // mm, each disc's
    double hole = 0.0;    // mm, a keep's ring: the hole's radius inside it (0: a full disc)
};

// Material an operation removes.
struct DesignCut {
    std::string path;   // the operation's JSON path
    std::string what;   // for messages: "the pocket", "the band beside the wall", "hole 3 at (20, 10)", "tab 2"
    PlaneRegion region;
    std::optional<DesignDiscs> discs;  // set: the region is these discs
    DesignFloor floor;
    double top_z = 0.0;           // the stock top the operation starts from
    double axial_allowance = 0.0; // mm it may leave on its floor (its stated stock)
    bool overrides = false;       // a tab: its operation's floor here, not the lowest
    bool may_leave = false;       // where the tool may cut to the floor or not (a tab's ends, a face's overhang)
};

// Part material beside a cut that must stay, up to top_z.
struct DesignKeep {
    std::string path;
    std::string what;
    PlaneRegion region;
    std::optional<DesignDiscs> discs;  // set: the region is these rings
    double top_z = 0.0;
};

struct PartDesign {
    std::vector<DesignCut> cuts;
    std::vector<DesignKeep> keeps;
    std::vector<std::string> unchecked;  // "/operations/3 (path): a path has no designed part"
    LatheDesign lathe;                   // a lathe job's turned part
};

// How many cuts and keeps a design has, each disc counted.
std::size_t design_cut_count(const PartDesign& design);
std::size_t design_keep_count(const PartDesign& design);

// The job's design. `keep_band`: how far beside a pocket's wall or a hole the part is kept
// (0: one tool diameter, at least 3 mm).
PartDesign part_design(const Job& job, double keep_band = 0.0);

}  // namespace camgen
