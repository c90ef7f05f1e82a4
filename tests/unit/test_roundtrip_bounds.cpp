// Generated round trip (issue 10 part 4: every program camgen writes reads back as the job):
// for each built-in machine, each cycle kind and each drilling field the kind uses, at its
// bounds and at awkward values (inch pitches, factors with 4 decimals, pecks that do not divide
// the depth, 71 pecks with a degression, dwells near the machine's resolution, feeds at the
// machine's limits), output canned and longhand, in mm and in inch where the machine accepts
// inch, from a job in mm and the same numbers in an inch job: the job is posted, read back with camgen's reader and compared with the job within
// the tolerance of the program's resolution. Where camgen refuses the job (job reading,
// checked_cycle, choose_canned) it says so with an InputError; a mismatch or a program its
// own reader rejects is a failure.
#include <cstdlib>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <doctest/doctest.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/operations/registry.hpp"

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_roundtrip_bounds {

using namespace camgen;

namespace {

// One generated case: the cycle kind and the extra JSON members of its drill operation.
struct BoundCase {
    CycleKind kind;
    std::string members;  // `"key": value, ...` added to the operation (may be empty)
    double tap_rpm = 300;  // the tap's speed (the tool's rpm)
};

// What a case came to: read back as the job, refused on input, or a failure with its text.
enum class Outcome { matched, refused, failed };

// A number as JSON text, with enough digits to survive the round trip.
std::string num(double v) { return fmt::format("{}", v); }

// The job of one case: one drill operation of `kind` with `members`, two holes, its values in
// `units` (an inch job reads 0.79375 as inches: other values, the same awkward digits).
std::string job_of(const BoundCase& c, Units units) {
    const bool tap = is_tapping(c.kind);
    std::string op = fmt::format(R"("type": "drill", "tool": {}, "cycle": "{}", "retractPlane": 5, "safeDistance": 1)",
                                 tap ? 2 : 1, name_of(cycle_kinds, c.kind));
    const bool has_depth = c.members.find("\"endDepth\"") != std::string::npos;
    if (!has_depth) op += R"(, "endDepth": 20)";
    if (!tap && c.members.find("plungingFeedrate") == std::string::npos) op += R"(, "plungingFeedrate": 150)";
    if (is_pecking(c.kind) && c.members.find("firstDepth") == std::string::npos) op += R"(, "firstDepth": 3.7)";
    if (tap && c.members.find("\"pitch\"") == std::string::npos) op += R"(, "pitch": 1.25)";
    if ((c.kind == CycleKind::dwell || c.kind == CycleKind::bore_dwell) && c.members.find("bottomDwell") == std::string::npos)
        op += R"(, "bottomDwell": 0.5)";
    if (!c.members.empty()) op += ", " + c.members;
    return R"({"name": "bounds", "units": ")" + std::string(name_of(unit_names, units)) +
           R"(", "clearance": 20, "tools": [{"number": 1, "type": "drill", "diameter": 6, "rpm": 1200},)"
           R"( {"number": 2, "type": "tap", "diameter": 8, "rpm": )" + num(c.tap_rpm) + R"(}], "operations": [{)" + op +
           R"(, "holes": [[10, 10], [30.5, 12.25]]}]})";
}

// The cases of one cycle kind on a machine: each field the kind uses at its bounds and at
// awkward values; `unit` is the machine's dwell resolution step in seconds.
std::vector<BoundCase> cases_of(CycleKind k, const Machine& m, double dwell_unit) {
    std::vector<BoundCase> out{{k, ""}};
    auto add = [&](const std::string& members) { out.push_back({k, members}); };
    auto used = [&](DrillField f) { return info(f).used_by.contains(k); };
    if (used(DrillField::plunging_feedrate))
        for (double f : {m.limits.min_feed, m.limits.max_feed, 123.4567, m.limits.min_feed * 0.5, m.limits.max_feed * 2})
            add(fmt::format(R"("plungingFeedrate": {})", num(f)));
    if (used(DrillField::retract_feedrate))
        for (double f : {m.limits.min_feed, m.limits.max_feed, 333.3333})
            add(fmt::format(R"("retractFeedrate": {})", num(f)));
    if (used(DrillField::first_depth)) {
        for (double d : {0.0004, 0.001, 3.7, 6.0, 19.9999, 20.0, 25.0})
            add(fmt::format(R"("firstDepth": {})", num(d)));
        // 71 pecks of 0.3 mm; 71 pecks of a sub-millimetre step that does not divide the depth.
        add(R"("firstDepth": 0.3, "endDepth": 21.3)");
        add(R"("firstDepth": 0.2817, "endDepth": 20)");
        add(R"("firstDepth": 3.7, "endDepth": 7.4004)");
    }
    if (used(DrillField::degression)) {
        // A value degression that shrinks the pecks over a long sequence (71 pecks and more).
        add(R"("firstDepth": 0.6, "degressionType": "value", "degression": 0.0137, "minimumDepth": 0.2713, "endDepth": 21.3)");
        add(R"("firstDepth": 6, "degressionType": "value", "degression": 2, "minimumDepth": 2.5)");
        add(R"("firstDepth": 5, "degressionType": "value", "degression": 0.001, "minimumDepth": 0.001)");
        add(R"("firstDepth": 5, "degressionType": "factor", "degression": 0.7803, "minimumDepth": 0.37)");
        add(R"("firstDepth": 5, "degressionType": "factor", "degression": 1, "minimumDepth": 0.37)");
    }
    if (used(DrillField::pecking_retract))
        for (double r : {0.0004, 0.001, 0.333, 2.0})
            add(fmt::format(R"("peckingRetract": {})", num(r)));
    if (used(DrillField::first_feedrate_factor))
        for (double f : {0.7803, 1.5, 1.0, 0.0001, 0.5, 0.33333})
            add(fmt::format(R"("firstFeedrateFactor": {})", num(f)));
    if (used(DrillField::pitch))
        // Inch pitches: 1/32, 1/20, 1/13 in (as mm); metric fine and coarse; sub-resolution.
        for (double p : {0.79375, 1.27, 25.4 / 13, 0.35, 3.5, 0.0004, 0.001})
            add(fmt::format(R"("pitch": {})", num(p)));
    if (is_tapping(k))
        // Speeds that S rounds: the synchronised feed (pitch x speed) moves with the written S
        // (a fuzz finding: 203.90625 rpm written S204 on linuxcnc, G33.1 feeding 255 mm/min).
        for (double rpm : {203.90625, 299.965, 1.5})
            out.push_back({k, "", rpm});
    if (used(DrillField::tapping_speed))
        for (double s : {0.4, 1.0, 333.0, 123.5, 1000.0})
            add(fmt::format(R"("tappingSpeed": {})", num(s)));
    if (used(DrillField::retract_speed))
        for (double s : {0.4, 777.0, 250.5})
            add(fmt::format(R"("retractSpeed": {})", num(s)));
    for (DrillField f : {DrillField::top_dwell, DrillField::bottom_dwell}) {
        if (!used(f)) continue;
        for (double s : {0.0, dwell_unit * 0.4, dwell_unit * 0.6, dwell_unit, dwell_unit * 1.5, dwell_unit * 2.5, 2.5})
            add(fmt::format(R"("{}": {})", key_of(f), num(s)));
        // Pecks with a dwell: a dwell per peck never becomes two dwells in a row.
        // A last peck below the resolution (20.0004 = 5 x 4 + 0.0004) and 200 pecks of 0.0015 mm.
        if (is_pecking(k)) {
            add(fmt::format(R"("{}": {}, "firstDepth": 4, "endDepth": 20.0004)", key_of(f), num(dwell_unit * 1.5)));
            add(fmt::format(R"("{}": {}, "firstDepth": 0.0015, "endDepth": 0.3)", key_of(f), num(dwell_unit * 1.5)));
        }
    }
    return out;
}

// A machine with every canned cycle turned off: everything written longhand.
Machine longhand_only(Machine m) {
    for (DrillingCycleSpec& s : m.drilling) s.canned = false;
    return m;
}

// Posts `job_json` on `machine`, reads it back and compares; `detail` receives why it failed.
Outcome run_case(const std::string& job_json, const Machine& machine, std::string& detail) {
    std::string program;
    Job job;
    try {
        job = read_job(job_json, "bounds.json");
        std::ostringstream out, warn;
        PostOptions o;
        o.program_name = job.name;
        o.warnings = &warn;
        auto post = make_post(machine, out, o);
        post->open();
        expand_job(job, *post);
        post->close();
        program = out.str();
    } catch (const InputError& e) {
        detail = e.what();
        return Outcome::refused;
    }
    try {
        ReadResolution res;
        std::vector<ReadEvent> events = read_program(program, machine, "prog", &res);
        auto mismatch = compare_traces(trace_expected(expand_job(job), machine), trace_program(events, machine),
                                       compare_tolerance(machine, res, 0.0));
        if (!mismatch) return Outcome::matched;
        detail = fmt::format("line {}: {}\n{}", mismatch->line, mismatch->message, program);
    } catch (const InputError& e) {
        detail = fmt::format("its own reader rejects the program: {}\n{}", e.what(), program);
    }
    return Outcome::failed;
}

}  // namespace

TEST_CASE("every drilling field at its bounds and awkward values reads back as the job on every mill") {
    int matched = 0, refused = 0;
    std::vector<std::string> failures;
    // CAMGEN_BOUNDS_STRIDE=n (the sanitized twin: 3) runs every n-th case: the same code paths,
    // each case a post and a read-back in-process, about six times as long under the sanitizers.
    const char* stride_text = std::getenv("CAMGEN_BOUNDS_STRIDE");
    const long stride = stride_text ? std::max(1L, std::atol(stride_text)) : 1;
    long index = 0;
    for (const auto& listed : list_machines()) {
        const Machine base = load_machine(listed.first);
        // The drill operation's holes are a mill's (a lathe refuses the job; its turn-drill is
        // tested in test_turn_drill.cpp and test_lathe_posts.cpp).
        if (base.kind != MachineKind::mill) continue;
        for (Units units : {Units::mm, Units::inch}) {
            if (!base.accepts(units)) continue;
            Machine unit_machine = base;
            unit_machine.units = units;
            for (bool longhand : {false, true}) {
                const Machine machine = longhand ? longhand_only(unit_machine) : unit_machine;
                const std::string label = fmt::format("{} {} {}", machine.name, name_of(unit_names, units), longhand ? "longhand" : "canned");
                const double dwell_unit = 2 * read_resolution(machine).dwell;
                for (const auto& named : cycle_kinds)
                    for (const BoundCase& c : cases_of(named.value, machine, dwell_unit))
                        for (Units job_units : {Units::mm, Units::inch}) {
                            if (index++ % stride != 0) continue;
                            std::string detail;
                            switch (run_case(job_of(c, job_units), machine, detail)) {
                                case Outcome::matched: ++matched; break;
                                case Outcome::refused: ++refused; break;
                                case Outcome::failed:
                                    failures.push_back(fmt::format("{} {} {} job {{{}}}: {}", label, name_of(cycle_kinds, c.kind),
                                                                   name_of(unit_names, job_units), c.members, detail));
                                    break;
                            }
                        }
            }
        }
    }
    // The first failure with its program, then the first lines of the next ones.
    for (size_t i = 0; i < failures.size() && i < 60; ++i) {
        const std::string shown = i == 0 ? failures[i] : failures[i].substr(0, failures[i].find('\n'));
        MESSAGE(shown);
    }
    CHECK_MESSAGE(failures.empty(), failures.size() << " cases do not read back as their job");
    // Most cases are programs; the refusals are the sub-resolution and out-of-range values,
    // and taps on machines or outputs that cannot tap.
    CHECK(matched > 2 * refused);
    CHECK(matched > 3000 / stride);
}

TEST_CASE("sinumerik CYCLE83: the first depth is taken from the written planes, so rounding does not lengthen every peck") {
    // A safe distance of 4.3125 is written SDIS=4.313; FDEP from the exact plane (-1.6875,
    // written -1.688) made each peck 6.001 mm, and the seventh peck 0.007 mm deeper than the
    // job's. A fuzz_mutated finding (sinumerik-lathe): verify refused camgen's own program.
    const std::string mill = R"({"name": "p", "units": "mm", "clearance": 20,
      "tools": [{"number": 1, "type": "drill", "diameter": 10, "rpm": 800}],
      "operations": [{"type": "drill", "tool": 1, "cycle": "deep", "plungingFeedrate": 100, "safeDistance": 4.3125,
        "retractPlane": 10, "endDepth": 60, "firstDepth": 6, "holes": [[0, 0]]}]})";
    const std::string lathe = R"({"name": "s", "units": "mm", "clearance": 20,
      "tools": [{"number": 2, "type": "drill", "diameter": 10, "rpm": 800, "tipAngle": 118}],
      "operations": [{"type": "turn-drill", "tool": 2, "plungingFeedrate": 100, "startDepth": 0, "endDepth": -60,
        "firstPeckDepth": 6, "peckRetract": 1, "safeDistance": 4.3125, "retractDistance": 5}]})";
    for (const auto& [machine, job] : {std::pair<std::string, std::string>{"sinumerik", mill}, {"sinumerik-lathe", lathe}}) {
        CAPTURE(machine);
        const std::string file = test::file_with("cycle83-rounded-planes-" + machine, job);
        const std::string program = (test::scratch("cycle83-rounded-planes-out") / "p.mpf").string();
        const test::Run post = test::run({file, "--machine", machine, "-o", program, "-q"});
        REQUIRE_MESSAGE(post.code == 0, post.err);
        CHECK(post.out.empty());
        CHECK(test::read_file(program).find("CYCLE83") != std::string::npos);
        const test::Run verify = test::run({"verify", program, "--machine", machine, "--job", file});
        CHECK_MESSAGE(verify.code == 0, verify.err);
    }
}

}  // namespace test_roundtrip_bounds
