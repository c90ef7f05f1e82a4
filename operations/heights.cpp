#include "camgen/operations/heights.hpp"


#include <fmt/format.h>

namespace camgen {

Planes resolve_planes(const Heights& p) {
    Planes z;
    z.retract_z = p.retract_plane;
    z.reference_z = p.reference_plane;
    z.safe_z = !p.safe_distance               ? p.retract_plane
               : p.safe_distance_is_absolute ? *p.safe_distance
                                             : p.reference_plane + *p.safe_distance;
    z.bottom_z = p.end_depth_is_absolute ? p.end_depth : p.reference_plane - p.end_depth;
    return z;
}

std::vector<KeySpec> height_keys(bool with_safe_distance) {
    std::vector<KeySpec> keys{
        {.key = "retractPlane", .quantity = Quantity::length,
         .description = "absolute Z the tool travels at between holes or passes (default: clearance)"},
        {.key = "referencePlane", .quantity = Quantity::length,
         .description = "absolute Z of the stock top; relative values are measured from it (default: the top of the "
                        "job's stock where it gives one, else 0)"},
    };
    if (with_safe_distance)
        keys.push_back({.key = "safeDistance", .quantity = Quantity::length, .min = Bound{0, true},
                        .description = "where rapid turns into feed: the height above referencePlane (>= 0), or an "
                                       "absolute Z with safeDistanceIsAbsolute (default: the retract plane)"});
    keys.push_back({.key = "safeDistanceIsAbsolute", .type = JsonType::boolean, .default_json = "false",
                    .description = "safeDistance is an absolute Z (else: the height above referencePlane, >= 0)"});
    keys.push_back({.key = "endDepth", .quantity = Quantity::length, .required = true,
                    .description = "bottom of the hole or cut: depth below referencePlane (> 0), or an absolute Z "
                                   "with endDepthIsAbsolute"});
    keys.push_back({.key = "endDepthIsAbsolute", .type = JsonType::boolean, .default_json = "false",
                    .description = "endDepth is an absolute Z (else: the depth below referencePlane, > 0)"});
    return keys;
}

Heights read_heights(json::Fields& f, const JobInput& in, std::string_view what, std::string_view depth_key,
                     std::optional<double> depth) {
    const bool end_depth = depth_key == "endDepth" && !depth;
    Heights p;
    p.retract_plane = in.optional_length(f, "retractPlane").value_or(in.header().clearance);
    // A mill's stock gives the stock top; without one it is Z0.
    const Stock* stock = in.header().stock && in.header().stock->for_mill() ? &*in.header().stock : nullptr;
    p.reference_plane = in.optional_length(f, "referencePlane").value_or(stock ? stock->top() : 0.0);
    p.safe_distance = in.optional_length(f, "safeDistance");
    p.safe_distance_is_absolute = f.boolean("safeDistanceIsAbsolute", false);
    p.end_depth = depth ? *depth : in.length(f, depth_key);
    p.end_depth_is_absolute = end_depth && f.boolean("endDepthIsAbsolute", false);

    if (p.safe_distance && !p.safe_distance_is_absolute && *p.safe_distance < 0)
        f.fail("safeDistance",
               "a relative safeDistance cannot be negative (it is measured up from "
               "referencePlane; set safeDistanceIsAbsolute for an absolute Z)");
    if (!end_depth && !(p.end_depth > 0))
        f.fail(depth_key, fmt::format("{} must be > 0 (it is the depth below referencePlane)", depth_key));
    if (!p.end_depth_is_absolute && p.end_depth <= 0)
        f.fail("endDepth",
               "a relative endDepth must be > 0 (it is the depth below referencePlane; set "
               "endDepthIsAbsolute for an absolute Z)");
    const Planes z = resolve_planes(p);
    if (z.bottom_z >= z.safe_z)
        f.fail(depth_key, fmt::format("{} is above the safe distance ({} bottom at Z {}, "
                                       "safe distance at Z {})",
                                       depth_key, what, in.show(z.bottom_z), in.show(z.safe_z)));
    if (p.retract_plane < z.safe_z)
        f.fail("retractPlane",
               fmt::format("retractPlane is below the safe distance (retract plane at Z {}{}, "
                           "safe distance at Z {})",
                           in.show(p.retract_plane), f.has("retractPlane") ? "" : ", the clearance",
                           in.show(z.safe_z)));

    // The job's stock top: the tool travels above it. (A retract plane left out is the clearance,
    // which the stock's reading checked.)
    if (stock && f.has("retractPlane") && !(p.retract_plane > stock->top()))
        f.fail("retractPlane", fmt::format("retractPlane (Z {}) is not above the stock top (Z {}, {}): between {}s the tool "
                                           "would rapid through the material",
                                           in.show(p.retract_plane), in.show(stock->top()), stock->path, what));
    // The stock top (referencePlane) is where the material starts: nothing may rapid below it.
    if (p.retract_plane <= p.reference_plane)
        f.fail("retractPlane",
               fmt::format("retractPlane{} (Z {}) is not above referencePlane, the stock top (Z {}): between {}s "
                           "the tool would rapid through the material",
                           f.has("retractPlane") ? "" : ", the clearance,", in.show(p.retract_plane),
                           in.show(p.reference_plane), what));
    if (z.safe_z < p.reference_plane)
        f.fail("safeDistance",
               fmt::format("the safe distance (Z {}) is below referencePlane, the stock top (Z {}): the rapid "
                           "approach would end inside the material",
                           in.show(z.safe_z), in.show(p.reference_plane)));
    return p;
}

}  // namespace camgen
