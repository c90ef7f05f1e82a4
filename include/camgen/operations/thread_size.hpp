#pragma once
// The size of a thread as thread-mill and turn-thread read it: a designation from the tables
// (key `thread`: M10, M10x1.25, 1/4-20 UNC) or its majorDiameter, minorDiameter and pitch,
// not both. mm.
#include <string>
#include <string_view>

#include "camgen/job/job_input.hpp"
#include "camgen/operations/thread_mill/thread_mill.hpp"

namespace camgen {

struct ThreadSize {
    std::string name;    // the table's name of the designation, "" when given by diameters
    double major = 0.0;  // diameter
    double minor = 0.0;  // diameter: d3 of an external thread, D1 of an internal one (from the tables)
    double pitch = 0.0;
};

// Reads the thread of an operation `what` ("a thread-mill"); `example` is a designation for its
// messages ("M10x1.5"), `fine` one with a fine pitch ("M10x1.25"). Errors name their key.
ThreadSize read_thread_size(json::Fields& f, const JobInput& in, ThreadSide side, std::string_view what,
                            std::string_view example, std::string_view fine);

}  // namespace camgen
