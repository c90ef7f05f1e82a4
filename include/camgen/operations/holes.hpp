#pragma once
// The hole sources of the operations that work at holes (drill, bore-mill): a list of holes, a
// grid, a bolt circle and a line, and the order the holes are visited in. One set of keys, one
// reading and one set of messages for every such operation.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/job/job_input.hpp"

namespace camgen {

// Appends the holes of one pattern (a grid, bolt circle or line) to a list.
using HolePattern = std::function<void(std::vector<Vec2>&)>;

// The holes of an operation, as read from the job.
struct HoleSet {
    std::vector<Vec2> holes;   // as the job gives them; order = shortest reorders them (visit_order)
    HoleOrder order = HoleOrder::as_given;
    // Patterns read and counted against the job's hole limit but not made yet: read_job makes
    // them (make_pending_holes) once every operation is read, so that a job over the limit is
    // refused before any pattern allocates its holes.
    std::vector<HolePattern> pending_patterns;
    // What camgen decided that the job did not ask for (a drawing's units, a hole drawn twice).
    std::vector<std::string> notes;
};

// The keys of the hole sources, in the order a job lists them: order, holes, grid,
// boltCircle, line, drawing (a DXF drawing's circles and points, dxf_source.hpp).
std::vector<KeySpec> hole_keys();

// The key group saying an operation needs at least one hole source; `description` names the
// operation ("a drill operation needs holes").
KeyGroup hole_group(std::string_view description);

// The objects the hole sources hold (drillHole, drillGrid, drillBoltCircle, drillLine), for
// the JSON Schema.
std::vector<ObjectSpec> hole_objects();

// Reads the order and the hole sources of an operation of type `op_type` ("drill"): the list
// at once (the document holds it already), the patterns counted against the job's hole limit
// and made later by make_pending_holes.
HoleSet read_hole_set(json::Fields& f, const JobInput& in, std::string_view op_type);

// Makes the pending patterns' holes, after the holes of the list, in the job's key order.
void make_pending_holes(HoleSet& set);

// Holes up to this count get 2-opt after nearest neighbour in shortest_order (2-opt is
// O(n^2) per pass); larger operations keep the nearest-neighbour order.
inline constexpr std::size_t max_two_opt_holes = 2000;

// The holes in a short rapid order (order "shortest"): nearest neighbour from the first hole,
// which stays first, then 2-opt (see max_two_opt_holes). Same holes, reordered.
std::vector<Vec2> shortest_order(const std::vector<Vec2>& holes);

// The holes in the order the operation visits them.
std::vector<Vec2> visit_order(const HoleSet& set);
// The same without a copy when that is the job's own order (a million holes are 16 MB):
// `storage` holds the list when it is reordered.
const std::vector<Vec2>& visit_order(const HoleSet& set, std::vector<Vec2>& storage);

}  // namespace camgen
