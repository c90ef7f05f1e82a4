#pragma once
// Reading the job's "stock" (the struct is the job layer's `Stock`, job.hpp, so that a
// simulation can use it without the operations): a box by its corners or by a size and an
// origin, or a prism over a closed profile (read as a contour's), on a mill; a bar on a lathe.
// Lengths in the file's units, converted to mm; each error names the JSON path and line.
#include <string>
#include <vector>

#include "camgen/common/key_spec.hpp"
#include "camgen/job/job_input.hpp"

namespace camgen {

// Reads "stock" of the top-level object, if it is there, into the input's header (before the
// operations are read: they take the stock top from it). Also refuses a clearance that is not
// above the stock top. Throws InputError at the first problem.
void read_stock(json::Fields& top, JobInput& in);

// The objects of "stock", for the JSON Schema: stock, stockBox, stockProfile, stockBar.
std::vector<ObjectSpec> stock_objects();

// Refuses a stock made for another kind of machine than `kind` (a bar on a mill, a box or
// profile on a lathe): an InputError at the stock's shape, naming both.
void check_stock_machine_kind(const Stock& stock, MachineKind kind, const std::string& machine_name);

// How the stock reads in messages: "the stock top (Z 0.000 mm, /stock/box)".
std::string stock_top_text(const Stock& stock, const JobInput& in);

}  // namespace camgen
