// What a job designs (design.hpp): each operation's cuts and keeps as regions with heights.
#include "camgen/operations/design.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "camgen/common/number_text.hpp"
#include "camgen/events/visit.hpp"
#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/registry.hpp"

namespace camgen {

namespace {

// A flat floor at z.
DesignFloor design_flat(double z) {
    DesignFloor f;
    f.z = z;
    return f;
}

// The largest region of an offset (the one a band is made of), or none.
std::optional<PlaneRegion> design_largest(const RegionOffset& o) {
    std::optional<PlaneRegion> best;
    double area = -1.0;
    for (const PlaneRegion& r : o.regions)
        if (const double a = region_area(r); a > area) area = a, best = r;
    return best;
}

// The region grown by d (d = 0: as it is).
std::optional<PlaneRegion> design_grown(const PlaneRegion& r, double d) {
    if (d <= 0.0) return normalised(r);
    return design_largest(grow_region(r, d));
}

// The points outside `inner` within `width` of it: its growth less itself.
std::optional<PlaneRegion> design_band_outside(const PlaneRegion& inner, double width) {
    std::optional<PlaneRegion> grown = design_grown(inner, width);
    if (!grown) return std::nullopt;
    PlaneRegion band = *grown;
    band.islands = {reversed(normalised(inner).outer)};
    return normalised(band);
}

// What a tool of radius r reaches of a region from inside it: the region shrunk by r and grown
// back (a sharp concave corner keeps a fillet of r). Empty where the tool does not fit.
std::vector<PlaneRegion> design_opening(const PlaneRegion& region, double r) {
    std::vector<PlaneRegion> out;
    for (const PlaneRegion& centre : offset_region(region, r).regions)
        for (PlaneRegion& g : grow_region(centre, r).regions) out.push_back(std::move(g));
    return out;
}

// The region with what a tool of radius r cannot reach from outside it filled: grown by r and
// shrunk back (a sharp concave corner of a part's outline is rounded by r).
std::optional<PlaneRegion> design_closing(const PlaneRegion& region, double r) {
    const std::optional<PlaneRegion> grown = design_grown(region, r);
    if (!grown) return std::nullopt;
    return design_largest(offset_region(*grown, r));
}

// A stretch of a band beside a closed profile: between lengths from and to along it, from
// offset o0 to o1 on the side `sign` (+1: left of the profile's travel), as a polygon.
PlaneRegion design_stretch(const Profile& p, double from, double to, double o0, double o1, double sign) {
    const Profile piece = sub_profile(p, from, to);
    const std::vector<Vec2> pts = sample_profile(piece, 0.01);
    PlaneRegion r;
    if (pts.size() < 2) return r;
    auto normal_at = [&](std::size_t i) {
        const Vec2 a = pts[i == 0 ? 0 : i - 1], b = pts[i + 1 < pts.size() ? i + 1 : i];
        const Vec2 d = b - a;
        const double n = norm(d);
        return n > 0 ? Vec2{-d.y / n * sign, d.x / n * sign} : Vec2{0.0, 0.0};
    };
    std::vector<Vec2> loop;
    for (std::size_t i = 0; i < pts.size(); ++i) loop.push_back(pts[i] + normal_at(i) * o0);
    for (std::size_t i = pts.size(); i-- > 0;) loop.push_back(pts[i] + normal_at(i) * o1);
    r.outer.start = loop.front();
    for (std::size_t i = 1; i < loop.size(); ++i) r.outer.segments.push_back({loop[i], std::nullopt, ArcDirection::ccw});
    r.outer.segments.push_back({loop.front(), std::nullopt, ArcDirection::ccw});
    return normalised(r);
}

class Designer {
public:
    Designer(const Job& job, double keep_band) : job_(job), keep_band_(keep_band) {}

    PartDesign run() {
        for (const Operation& op : job_.operations)
            visit_exhaustive(overloaded{
                                 [&](const DrillOp& o) { drill(o); },
                                 [&](const BoreMillOp& o) { bore(o); },
                                 [&](const ContourOp& o) { contour(o); },
                                 [&](const PocketOp& o) { pocket(o); },
                                 [&](const FaceOp& o) { face(o); },
                                 [&](const PathOp& o) { skip(o.path, "a path has no designed part"); },
                                 [&](const ThreadMillOp& o) { thread(o); },
                                 [&](const EngraveOp& o) { engrave(o); },
                                 [&](const ChamferOp& o) { chamfer(o); },
                                 [&](const CustomOp& o) { skip(o.path, "custom blocks have no designed part"); },
                                 [&](const StopOp&) {},
                                 // A lathe's part: design_lathe.cpp.
                                 [&](const TurnDrillOp& o) { design_turn_drill(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnProfileOp& o) { design_turn_profile(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnFaceOp& o) { design_turn_face(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnRoughOp& o) { design_turn_rough(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnGrooveOp& o) { design_turn_groove(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnPartOp& o) { design_turn_part(o, job_, design_.lathe, design_.unchecked); },
                                 [&](const TurnThreadOp& o) { design_turn_thread(o, job_, design_.lathe, design_.unchecked); },
                             },
                             op);
        return std::move(design_);
    }

private:
    double band_for(double diameter) const { return keep_band_ > 0.0 ? keep_band_ : std::max(diameter, 3.0); }

    void skip(const std::string& path, const std::string& why) { design_.unchecked.push_back(path + ": " + why); }

    const Tool* tool_of(int number) const {
        const auto it = job_.tools.find(number);
        return it == job_.tools.end() ? nullptr : &it->second;
    }

    void holes(const std::string& path, const std::vector<Vec2>& centres, double radius, double top, DesignFloor floor) {
        if (centres.empty()) return;
        DesignCut cut;
        cut.path = path;
        cut.what = "hole";
        cut.discs = DesignDiscs{centres, radius, 0.0};
        cut.floor = floor;
        cut.top_z = top;
        design_.cuts.push_back(std::move(cut));
        DesignKeep keep;
        keep.path = path;
        keep.what = "the part around hole";
        keep.discs = DesignDiscs{centres, radius + band_for(2.0 * radius), radius};
        keep.top_z = top;
        design_.keeps.push_back(std::move(keep));
    }

    void drill(const DrillOp& op) {
        const Tool* tool = tool_of(op.tool);
        if (!tool) return skip(op.path, "its tool is not in the job");
        const DrillCycle c = resolve_cycle(op, *tool);
        DesignFloor floor = design_flat(c.bottom_z);
        if (tool->tip_angle && *tool->tip_angle > 0.0 && *tool->tip_angle < 180.0) {
            floor.apex = Vec2{0.0, 0.0};  // placed at each hole
            floor.slope = 1.0 / std::tan(*tool->tip_angle / 2.0 * rad_per_deg);
        }
        holes(op.path, op.holes, tool->diameter / 2.0, c.reference_z, floor);
    }

    // A thread as the height field holds it (its flanks are undercuts it cannot): the tool's
    // sweep, down to the lowest its lead takes it, may reach any depth there (may_leave: the last
    // turn's floor is a helix); the part beyond the thread's outer edge (internal: the major
    // diameter) and inside its core (external: the minor diameter) is kept.
    void thread(const ThreadMillOp& op) {
        const Tool* tool = tool_of(op.tool);
        if (!tool) return skip(op.path, "its tool is not in the job");
        if (op.holes.empty()) return;
        const Planes z = resolve_planes(op.heights);
        const double radius = tool->diameter / 2.0;
        double rise = 0.0, widest = 0.0;
        for (const double r : thread_pass_radii(op, tool->diameter)) {
            rise = std::max(rise, thread_lead_rise(op, r, tool->diameter));
            widest = std::max(widest, r);
        }
        DesignCut cut;
        cut.path = op.path;
        cut.what = "thread";
        cut.floor = design_flat(z.bottom_z - rise);
        cut.top_z = z.reference_z;
        cut.may_leave = true;
        DesignKeep keep;
        keep.path = op.path;
        keep.top_z = z.reference_z;
        if (op.side == ThreadSide::internal) {
            // The half-circle leads stay inside the thread's circle.
            cut.discs = DesignDiscs{op.holes, op.major / 2.0, 0.0};
            keep.what = "the part around thread";
            keep.discs = DesignDiscs{op.holes, op.major / 2.0 + band_for(op.major), op.major / 2.0};
        } else {
            // The quarter-circle leads of the tool's radius reach at most a tool radius beyond the
            // widest pass (and the tool its radius beyond that).
            cut.discs = DesignDiscs{op.holes, widest + 2.0 * radius, op.minor / 2.0};
            keep.what = "the core of thread";
            keep.discs = DesignDiscs{op.holes, op.minor / 2.0, 0.0};
        }
        design_.cuts.push_back(std::move(cut));
        design_.keeps.push_back(std::move(keep));
    }

    // Engraving: each stroke's piece a band of the line's width about it (a stadium: a
    // rectangle with half discs at its ends; a stroke without length a disc), down to the depth.
    // A V's, a ball's or a bull-nose's flanks rise from that floor towards the band's edges: the
    // band may keep material there (may_leave), but nothing in it may be cut below the depth.
    void engrave(const EngraveOp& op) {
        const Tool* tool = tool_of(op.tool);
        if (!tool) return skip(op.path, "its tool is not in the job");
        const Planes z = resolve_planes(op.heights);
        const double h = op.width / 2.0;
        const bool flat = tool->type == ToolType::end_mill;
        auto add = [&](PlaneRegion region, std::size_t stroke) {
            DesignCut cut;
            cut.path = op.path;
            cut.what = fmt::format("stroke {}", stroke);
            cut.region = std::move(region);
            cut.floor.z = z.bottom_z;
            cut.top_z = z.reference_z;
            cut.may_leave = !flat;
            design_.cuts.push_back(std::move(cut));
        };
        std::vector<Vec2> dots;
        for (std::size_t k = 0; k < op.strokes.size(); ++k) {
            const std::vector<Vec2> pts = sample_profile(op.strokes[k], 0.005);
            if (op.strokes[k].segments.empty() || pts.size() < 2) {
                dots.push_back(op.strokes[k].start);
                continue;
            }
            for (std::size_t i = 1; i < pts.size(); ++i) {
                const Vec2 a = pts[i - 1], b = pts[i];
                const double len = distance(a, b);
                if (len < 1e-9) continue;
                const Vec2 n = Vec2{-(b.y - a.y), b.x - a.x} * (h / len);
                PlaneRegion r;
                r.outer.start = a + n;
                r.outer.segments = {{b + n, std::nullopt, ArcDirection::ccw},
                                    {b - n, b, ArcDirection::cw},
                                    {a - n, std::nullopt, ArcDirection::ccw},
                                    {a + n, a, ArcDirection::cw}};
                add(normalised(r), k);
            }
        }
        if (!dots.empty()) {
            DesignCut cut;
            cut.path = op.path;
            cut.what = "dot";
            cut.discs = DesignDiscs{dots, h, 0.0};
            cut.floor.z = z.bottom_z;
            cut.top_z = z.reference_z;
            cut.may_leave = !flat;
            design_.cuts.push_back(std::move(cut));
        }
    }

    // A chamfer: its sloped face as a cut whose floor rises with the distance from the edge (a
    // hole's: from its centre), `width` into the part; on the air side the cone's continuation
    // down to the tip's depth (may_leave: beyond the tool's axis its cone rises again); the part
    // beyond the chamfer kept up to the top face. Open profiles have none.
    void chamfer(const ChamferOp& op) {
        const Planes z = resolve_planes(op.heights);
        const ChamferGeometry& g = op.geometry;
        const double slope = 1.0 / std::tan(op.angle * rad_per_deg);
        const double lower = z.reference_z - g.height;  // the chamfer's lower edge
        const double band = band_for(2.0 * g.reach);
        auto add_cut = [&](std::string what, DesignFloor floor, bool may_leave) -> DesignCut& {
            DesignCut cut;
            cut.path = op.path;
            cut.what = std::move(what);
            cut.floor = std::move(floor);
            cut.top_z = z.reference_z;
            cut.may_leave = may_leave;
            design_.cuts.push_back(std::move(cut));
            return design_.cuts.back();
        };
        auto add_keep = [&](std::string what) -> DesignKeep& {
            DesignKeep keep;
            keep.path = op.path;
            keep.what = std::move(what);
            keep.top_z = z.reference_z;
            design_.keeps.push_back(std::move(keep));
            return design_.keeps.back();
        };
        if (op.on_holes()) {
            if (op.holes.empty()) return;
            const double r = op.diameter / 2.0;
            // About each hole's centre: lower + slope x (distance - r).
            DesignFloor floor = design_flat(lower - slope * r);
            floor.apex = Vec2{0.0, 0.0};
            floor.slope = slope;
            add_cut("the chamfer of hole", floor, false).discs = DesignDiscs{op.holes, r + op.width, r};
            floor.lowest = z.bottom_z;
            add_cut("the tool's cone inside hole", floor, true).discs = DesignDiscs{op.holes, r, 0.0};
            add_keep("the part beyond the chamfer of hole").discs = DesignDiscs{op.holes, r + op.width + band, r + op.width};
            return;
        }
        if (!is_closed(op.profile)) return skip(op.path, "only a chamfer of a closed profile has a designed part");
        PlaneRegion shape;
        shape.outer = op.profile;
        shape = normalised(shape);
        const bool tool_inside = op.side == ContourSide::inside ||
                                 (op.side == ContourSide::left && orientation(op.profile) == Orientation::ccw) ||
                                 (op.side == ContourSide::right && orientation(op.profile) == Orientation::cw);
        const auto edge = std::make_shared<const Profile>(op.profile);
        // The points inside the shape within d of its edge.
        auto inner_band = [&](double d) -> std::optional<PlaneRegion> {
            PlaneRegion b = shape;
            for (const PlaneRegion& i : offset_region(shape, d).regions) b.islands.push_back(reversed(i.outer));
            return normalised(b);
        };
        const std::optional<PlaneRegion> face = tool_inside ? design_band_outside(shape, op.width) : inner_band(op.width);
        const std::optional<PlaneRegion> air = tool_inside ? inner_band(g.reach) : design_band_outside(shape, g.reach);
        if (!face || !air) return skip(op.path, "its chamfer's band is empty");
        DesignFloor up = design_flat(lower);
        up.slope = slope;
        up.edge = edge;
        add_cut("the chamfer", up, false).region = *face;
        DesignFloor down = design_flat(lower);
        down.slope = -slope;
        down.edge = edge;
        down.lowest = z.bottom_z;
        add_cut("the tool's cone beside the chamfer", down, true).region = *air;
        if (tool_inside) {
            const std::optional<PlaneRegion> out = design_grown(shape, op.width);
            if (!out) return;
            if (std::optional<PlaneRegion> around = design_band_outside(*out, band)) add_keep("the part beyond the chamfer").region = *around;
        } else {
            for (const PlaneRegion& i : offset_region(shape, op.width).regions) add_keep("the part inside the chamfer").region = i;
        }
    }

    void bore(const BoreMillOp& op) {
        const Planes z = resolve_planes(op.heights);
        holes(op.path, op.holes, op.diameter / 2.0, z.reference_z, design_flat(z.bottom_z));
    }

    void contour(const ContourOp& op) {
        const bool outside = op.side == ContourSide::outside, inside = op.side == ContourSide::inside;
        if (!(outside || inside) || !is_closed(op.profile))
            return skip(op.path, "only a contour inside or outside a closed profile has a designed part");
        const Planes z = resolve_planes(op.heights);
        const double d = 2.0 * op.tool_radius, s = op.stock_to_leave;
        PlaneRegion shape;
        shape.outer = op.profile;
        shape = normalised(shape);
        // The part's wall: the profile with the stock the contour leaves on it.
        std::optional<PlaneRegion> wall;
        if (outside) wall = design_grown(shape, s);
        else wall = s > 0.0 ? design_largest(offset_region(shape, s)) : std::optional<PlaneRegion>(shape);
        if (!wall) return skip(op.path, "its wall with the stock to leave is empty");
        // The band the tool sweeps: one diameter beside the wall, less what it cannot reach (an
        // outline's sharp concave corner keeps a fillet of the radius, as does a sharp corner of a
        // pocket wall).
        std::vector<PlaneRegion> bands;
        if (outside) {
            const std::optional<PlaneRegion> grown = design_grown(*wall, d), closed = design_closing(*wall, op.tool_radius);
            if (grown && closed) {
                PlaneRegion band = *grown;
                band.islands = {reversed(closed->outer)};
                bands.push_back(normalised(band));
            }
        } else {
            const std::vector<PlaneRegion> inner = offset_region(*wall, d).regions;
            for (PlaneRegion open : design_opening(*wall, op.tool_radius)) {
                for (const PlaneRegion& i : inner)
                    if (region_contains(open, i.outer.start)) open.islands.push_back(reversed(i.outer));
                bands.push_back(normalised(open));
            }
        }
        if (bands.empty()) return skip(op.path, "its band is empty");
        for (const PlaneRegion& band : bands) {
            DesignCut cut;
            cut.path = op.path;
            cut.what = "the band beside the contour's wall";
            cut.region = band;
            cut.floor.z = z.bottom_z;
            cut.top_z = z.reference_z;
            design_.cuts.push_back(std::move(cut));
        }
        DesignKeep keep;
        keep.path = op.path;
        keep.top_z = z.reference_z;
        if (outside) {
            keep.what = "the part inside the contour";
            keep.region = *wall;
        } else {
            std::optional<PlaneRegion> around = design_band_outside(*wall, band_for(d));
            if (!around) return;
            keep.what = "the part around the contour";
            keep.region = *around;
        }
        design_.keeps.push_back(std::move(keep));
        if (!op.tabs) return;
        // The band's side of the profile as drawn: +1 left of its travel.
        const ProfilePoint first = point_at(op.profile, std::min(1.0, profile_length(op.profile) / 2.0));
        const Vec2 probe = first.point + Vec2{-first.tangent.y, first.tangent.x} * 1e-3;
        const bool left_inside = contains(op.profile, probe);
        const double sign = (outside != left_inside) ? 1.0 : -1.0;
        const double length = profile_length(op.profile);
        for (std::size_t i = 0; i < op.tabs->centres.size(); ++i) {
            const double c = op.tabs->centres[i], w = op.tabs->width;
            DesignCut tab;
            tab.path = op.path;
            tab.what = fmt::format("tab {}", i);
            tab.region = design_stretch(op.profile, std::max(0.0, c - w / 2.0), std::min(length, c + w / 2.0), s, s + d, sign);
            tab.floor.z = std::min(z.reference_z, z.bottom_z + op.tabs->height);
            tab.top_z = z.reference_z;
            tab.overrides = true;
            design_.cuts.push_back(tab);
            // Where the tool climbs onto it and comes down again: a diameter each side, and the
            // run of a sloped flank.
            const double run = op.tabs->ramp_angle < 90.0 ? op.tabs->height / std::tan(op.tabs->ramp_angle * rad_per_deg) : 0.0;
            DesignCut shoulder = tab;
            shoulder.what = fmt::format("the ends of tab {}", i);
            shoulder.region = design_stretch(op.profile, std::max(0.0, c - w / 2.0 - d - run), std::min(length, c + w / 2.0 + d + run),
                                             s, s + d, sign);
            shoulder.floor.z = z.bottom_z;
            shoulder.overrides = false;
            shoulder.may_leave = true;
            design_.cuts.push_back(std::move(shoulder));
        }
    }

    void pocket(const PocketOp& op) {
        const Planes z = resolve_planes(op.heights);
        const double s = op.stock_to_leave, d = 2.0 * op.tool_radius;
        std::vector<PlaneRegion> walls = s > 0.0 ? offset_region(op.region, s).regions : std::vector<PlaneRegion>{normalised(op.region)};
        // What the tool reaches of it (a sharp corner keeps a fillet of the tool's radius).
        std::size_t made = 0;
        for (const PlaneRegion& w : walls)
            for (PlaneRegion& open : design_opening(w, op.tool_radius)) {
                DesignCut cut;
                cut.path = op.path;
                cut.what = "the pocket";
                cut.region = std::move(open);
                cut.floor.z = z.bottom_z;
                cut.top_z = z.reference_z;
                design_.cuts.push_back(std::move(cut));
                ++made;
            }
        if (made == 0) return skip(op.path, "its tool fits nowhere in its region");
        PlaneRegion outline;
        outline.outer = op.region.outer;
        if (std::optional<PlaneRegion> around = design_band_outside(outline, band_for(d))) {
            DesignKeep keep;
            keep.path = op.path;
            keep.what = "the part around the pocket";
            keep.region = *around;
            keep.top_z = z.reference_z;
            design_.keeps.push_back(std::move(keep));
        }
        for (std::size_t i = 0; i < op.region.islands.size(); ++i) {
            PlaneRegion island;
            island.outer = op.region.islands[i];
            DesignKeep keep;
            keep.path = op.path;
            keep.what = fmt::format("island {}", i);
            keep.region = normalised(island);
            keep.top_z = z.reference_z;
            design_.keeps.push_back(std::move(keep));
        }
    }

    void face(const FaceOp& op) {
        const Planes z = resolve_planes(op.heights);
        DesignCut cut;
        cut.path = op.path;
        cut.what = "the faced area";
        cut.region.outer = op.area;
        cut.region = normalised(cut.region);
        cut.floor.z = z.bottom_z;
        cut.top_z = z.reference_z;
        // Beyond its edge the tool overhangs: it may cut there, down to the same floor, as far as
        // the overhang and its diameter reach.
        if (std::optional<PlaneRegion> beyond = design_grown(cut.region, op.overhang + 2.0 * op.tool_radius)) {
            DesignCut over = cut;
            over.what = "the overhang beyond the faced area";
            over.region = *beyond;
            over.may_leave = true;
            design_.cuts.push_back(std::move(cut));
            design_.cuts.push_back(std::move(over));
            return;
        }
        design_.cuts.push_back(std::move(cut));
    }

    const Job& job_;
    double keep_band_;
    PartDesign design_;
};

}  // namespace

std::size_t design_cut_count(const PartDesign& design) {
    std::size_t n = 0;
    for (const DesignCut& c : design.cuts) n += c.discs ? c.discs->centres.size() : 1;
    return n;
}

std::size_t design_keep_count(const PartDesign& design) {
    std::size_t n = 0;
    for (const DesignKeep& k : design.keeps) n += k.discs ? k.discs->centres.size() : 1;
    return n;
}

PartDesign part_design(const Job& job, double keep_band) { return Designer(job, keep_band).run(); }

}  // namespace camgen
