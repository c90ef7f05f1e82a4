#pragma once
// Which operation of a job each line of a program belongs to, for a program read back (camgen
// simulate's volumes and errors per operation): the job is posted again for the machine, the
// line each operation starts at noted, and the program's lines matched with the posted ones.
// A program camgen wrote for this job and machine matches line for line; a hand-edited one
// matches around its edits (an added line belongs to the operation of the line before it).
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/simulation/simulation.hpp"

namespace camgen {

struct OperationLines {
    std::vector<OperationSpan> spans;  // by first line, as SimOptions::operations takes them
    std::string note;                  // empty, or why some or all lines have no operation
};

// `program`: the program's text, read to its end.
OperationLines operation_lines(const Job& job, const Machine& machine, std::istream& program);

}  // namespace camgen
