#pragma once
// The job's own parts that every operation shares: its header (name, units, clearance) and
// its tool table. All lengths are mm, feeds mm/min, times seconds, speeds rpm: inch input is
// converted once, when it is read. The operations themselves live in operations/<type>/.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "camgen/geometry/geometry.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen {

// What a tool's library gives for the job's material (library key cuttingData), and the
// machine's feed bound that a feed computed from it keeps to. Speeds m/min, lengths mm.
struct ToolCutting {
    std::string material;
    double surface_speed = 0.0;              // m/min (vc)
    std::optional<double> feed_per_tooth;    // mm (fz), for milling
    std::optional<double> feed_per_rev;      // mm, for drilling (feedPerRev, else fz x flutes)
    double max_feed = 0.0;                   // mm/min, the machine's maxFeed (0: no machine known)
    std::string path;                        // the library entry's JSON path and file, for messages
};

// A tool of the job's tool table.
struct Tool {
    int number = 0;
    ToolType type = ToolType::drill;
    // Whether the job (or its library tool) gave the type: a tool without one is a drill, and
    // jobs from before tool types gave their end mills none, so milling takes such a tool as
    // an end mill (with a note) while refusing one typed "drill".
    bool type_given = false;
    double diameter = 0.0;                 // mm
    std::optional<double> tip_angle;       // degrees, included angle of the point (drills, chamfer mill, V-bit)
    std::optional<double> corner_radius;   // mm, a bull-nose end mill's corner radius (0 < r <= diameter / 2)
    double tip_diameter = 0.0;             // mm, a chamfer mill's or V-bit's flat at its point (0: pointed)
    std::optional<double> flute_length;    // mm, how deep it can cut (job key fluteLength)
    std::optional<int> flutes;             // number of cutting edges (job key flutes)
    // A thread mill's pitches: a multi-form tool's teeth cut one pitch (min = max, job key
    // pitch); a single-profile tool cuts any pitch from min to max (minPitch, maxPitch). mm.
    double min_pitch = 0.0;
    double max_pitch = 0.0;
    // A lathe's tool in the turret (is_lathe_insert): its nose radius (turning and threading
    // tools: diameter / 2; grooving and parting tools: 0), the tip orientation (LinuxCNC's 1-9
    // code: where the programmed point, the imaginary tip, lies on the nose circle; 0: none
    // given), the insert's included angle and the holder's approach angle (degrees; both or
    // neither, turning tools only), a grooving or parting tool's width and a threading tool's
    // profile angle (mm, degrees).
    double nose_radius = 0.0;
    int orientation = 0;
    std::optional<double> insert_angle;
    std::optional<double> approach_angle;
    double width = 0.0;
    std::optional<double> profile_angle;
    bool centre_cutting = true;            // cuts at its centre: may plunge into material
    double rpm = 0.0;                      // rev/min, > 0; with surface_speed the spindle's limit (maxRpm)
    // Constant surface speed (G96) of a turning, grooving or parting tool, m/min at the work's
    // diameter (job key surfaceSpeed); 0: the constant rpm.
    double surface_speed = 0.0;
    double max_rpm = 0.0;                  // job key maxRpm, the limit under surface_speed; 0: the machine's
    SpindleDirection direction = SpindleDirection::cw;
    std::string comment;
    CoolantMode coolant = CoolantMode::off;  // while the tool cuts
    std::string path;                      // JSON path, for messages
    std::string library;                   // the library tool it was taken from (job key library), or ""
    std::optional<ToolCutting> cutting;    // its library's cutting data for the job's material
    std::vector<std::string> computed;     // what camgen computed for it ("13262 rpm from vc 250 m/min ...")
};

// The shape of the stock: a box or a prism over a closed outline (mills), a bar (lathes).
enum class StockShape { box, profile, bar };

// The material before the first operation (job key "stock"), in mm. Every shape fills `min`
// and `max`, its bounding box: a mill's stock from its bottom (min.z) to its top (max.z); a
// bar lies along Z, its axis at X0 Y0, from its face (max.z = face_z) back to min.z.
struct Stock {
    StockShape shape = StockShape::box;
    Vec3 min;                              // mm
    Vec3 max;                              // mm
    Profile outline;                       // profile: closed, in XY, as drawn
    double diameter = 0.0;                 // bar: outer diameter
    double length = 0.0;                   // bar: along Z
    double face_z = 0.0;                   // bar: Z of its face (towards the tailstock end of the work)
    std::optional<double> bore_diameter;   // bar: a tube's inner diameter
    std::string path;                      // JSON path of the shape's object ("/stock/box"), for messages
    int line = 0;                          // ... its line in the job file
    std::string source;                    // ... and the file's name
    // Z of the stock top (a bar: its face) and of its bottom (a bar: its far end).
    double top() const { return max.z; }
    double bottom() const { return min.z; }
    // Whether it is a mill's stock (box or profile) rather than a lathe's bar.
    bool for_mill() const { return shape != StockShape::bar; }
};

// What a job says besides its operations.
struct JobHeader {
    std::string name;
    Units units = Units::mm;            // the units the file was written in
    double clearance = 0.0;             // absolute Z, safe between operations
    std::string work_offset;            // the work offset the program selects ("G54"); empty: none written
    std::optional<int> program_number;  // the program number, overriding the machine's
    std::map<int, Tool> tools;          // by tool number
    std::optional<Stock> stock;         // the material, where the job gives it
    std::string material;               // what the stock is made of (job key material), for library cutting data
};

}  // namespace camgen
