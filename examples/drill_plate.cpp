// camgen as a library (docs/library.md): a job built in C++ (no JSON), posted for a Fanuc mill
// and a Wabeco mill (nccad), each program read back, measured and compared with the job.
// Prints one line per machine:
//   fanuc: 27 blocks, 4 holes read back (4 canned, 0 longhand), lowest Z -9.8, matches the job
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/stats.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "camgen/post/safety.hpp"
#include "camgen/reader/reader.hpp"

namespace {

// A plate with four holes: a Ø6 drill, 8 mm deep below the stock top at Z 0, plus its tip.
camgen::Job plate_job() {
    camgen::Job job;
    job.name = "plate";
    job.clearance = 10.0;  // absolute Z, mm

    camgen::Tool drill;
    drill.number = 2;
    drill.type = camgen::ToolType::drill;
    drill.diameter = 6.0;
    drill.tip_angle = 118.0;
    drill.rpm = 1200.0;
    drill.comment = "6 mm HSS drill";
    job.tools[drill.number] = drill;

    camgen::DrillOp holes;
    holes.path = "/operations/0";  // names the operation in messages
    holes.comment = "four holes";
    holes.tool = drill.number;
    holes.holes = {{10.0, 10.0}, {50.0, 10.0}, {50.0, 40.0}, {10.0, 40.0}};
    holes.params.kind = camgen::CycleKind::drill;
    holes.params.retract_plane = 5.0;
    holes.params.reference_plane = 0.0;
    holes.params.safe_distance = 1.0;  // feed from 1 mm above the stock
    holes.params.end_depth = 8.0;      // below the reference plane
    holes.params.drill_tip = true;
    holes.params.values.set(camgen::DrillField::plunging_feedrate, 120.0);  // mm/min
    job.operations.push_back(holes);
    return job;
}

// The NC program of `job` for `machine`: every event passes the safety checks before the post
// writes it, as camgen's command line does.
std::string post(const camgen::Job& job, const camgen::Machine& machine) {
    camgen::check_machine_kind(job, machine.kind, machine.name);
    camgen::PostOptions options;
    options.program_name = job.name;
    options.warnings = &std::cerr;
    std::ostringstream program;
    std::unique_ptr<camgen::Post> writer = camgen::make_post(machine, program, options);
    camgen::SafetyLimits limits{job.clearance, {}, machine.longhand()};
    const std::vector<camgen::Event> events = camgen::expand_job(job);
    camgen::check_safety(events, limits);
    writer->open();
    for (const camgen::Event& event : events) writer->emit(event);
    writer->close();
    return program.str();
}

// Reads `program` back with `machine`'s reader and compares its motion with the job's.
void report(const camgen::Job& job, const camgen::Machine& machine, const std::string& program) {
    camgen::ReadResolution resolution;
    const camgen::Trace trace =
        camgen::trace_program(camgen::read_program(program, machine, job.name, &resolution), machine);
    const camgen::ProgramStats stats = camgen::compute_stats(trace, machine);
    const auto mismatch = camgen::compare_traces(camgen::trace_expected(camgen::expand_job(job), machine), trace,
                                                 camgen::compare_tolerance(machine, resolution));
    std::size_t blocks = 0;
    for (char c : program) blocks += c == '\n';
    std::cout << machine.name << ": " << blocks << " blocks, " << stats.holes << " holes read back ("
              << stats.canned_holes << " canned, " << stats.longhand_holes << " longhand), lowest Z "
              << stats.lowest_z.value_or(0.0) << ", "
              << (mismatch ? "MISMATCH at line " + std::to_string(mismatch->line) + ": " + mismatch->message
                           : std::string("matches the job"))
              << '\n';
}

}  // namespace

int main() {
    try {
        const camgen::Job job = plate_job();
        for (const std::string name : {"fanuc", "wabeco"}) {
            const camgen::Machine machine = camgen::load_machine(name);
            report(job, machine, post(job, machine));
        }
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "drill_plate: " << e.what() << '\n';
        return 1;
    }
}
