#pragma once
// The job's own parts that every operation shares: its header (name, units, clearance) and
// its tool table. All lengths are mm, feeds mm/min, times seconds, speeds rpm: inch input is
// converted once, when it is read. The operations themselves live in operations/<type>/.
#include <map>
#include <optional>
#include <string>

#include "camgen/geometry/geometry.hpp"
#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen {

// A tool of the job's tool table.
struct Tool {
    int number = 0;
    ToolType type = ToolType::drill;
    double diameter = 0.0;                 // mm
    std::optional<double> tip_angle;       // degrees, included angle of the point
    std::optional<double> flute_length;    // mm, how deep it can cut (job key fluteLength)
    bool centre_cutting = true;            // cuts at its centre: may plunge into material
    double rpm = 0.0;                      // rev/min, > 0
    SpindleDirection direction = SpindleDirection::cw;
    std::string comment;
    CoolantMode coolant = CoolantMode::off;  // while the tool cuts
    std::string path;                      // JSON path, for messages
};

// What a job says besides its operations.
struct JobHeader {
    std::string name;
    Units units = Units::mm;            // the units the file was written in
    double clearance = 0.0;             // absolute Z, safe between operations
    std::string work_offset;            // the work offset the program selects ("G54"); empty: none written
    std::optional<int> program_number;  // the program number, overriding the machine's
    std::map<int, Tool> tools;          // by tool number
};

}  // namespace camgen
