// The program frame (issue 9 part 1): the safe-start block from the machine file, the job's
// work offset and program number, coolant per tool, each written where the control has it,
// refused with the job key's path where it has not, and read back by every dialect's reader.
#include <doctest/doctest.h>

#include "camgen/cli/cli.hpp"
#include "reader_support.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_frame {

using namespace camgen;

namespace {

// A one-hole job with a work offset, a program number and a tool's coolant (JSON fragments,
// empty: not given).
std::string frame_job(const std::string& work_offset, const std::string& coolant, const std::string& program_number = "") {
    std::string header = R"({"name": "frame", "clearance": 10)";
    if (!work_offset.empty()) header += R"(, "workOffset": ")" + work_offset + "\"";
    if (!program_number.empty()) header += R"(, "programNumber": )" + program_number;
    std::string tool = R"({"number": 1, "type": "drill", "diameter": 5, "rpm": 1000)";
    if (!coolant.empty()) tool += R"(, "coolant": ")" + coolant + "\"";
    return header + R"(, "tools": [)" + tool + R"(}], "operations": [
        {"type": "drill", "tool": 1, "retractPlane": 2, "endDepth": 3, "plungingFeedrate": 100, "holes": [[10, 10]]}]})";
}

// The message of the error posting `job` for a machine ("" if none), with its JSON path.
std::string post_error(const std::string& job, const std::string& machine) {
    try {
        (void)test::post_job(job, machine);
    } catch (const InputError& e) {
        return e.path() + ": " + e.detail();
    }
    return "";
}

}  // namespace

TEST_CASE("the safe-start block, the work offset and coolant on every machine, read back") {
    struct Case {
        const char* machine;
        const char* offset;
        const char* coolant;
        const char* start;      // the start block as written
        const char* coolant_on;  // the block that switches coolant on
    };
    const Case cases[] = {
        {"fanuc", "G55", "flood", "N10 G40 G49 G80 G17 G90 G94 G21 G55\n", " M8\n"},
        {"linuxcnc", "G59.1", "mist", "G40 G49 G80 G17 G90 G94 G21 G59.1\n", "M7\n"},
        {"grbl", "G54", "flood", "G40 G49 G17 G90 G94 G21 G54\n", "M8\n"},
        {"sinumerik", "G505", "flood", "N10 G40 G17 G90 G94 G710 G505\n", " M8\n"},
        {"heidenhain", "", "flood", "0 BEGIN PGM frame MM\n", " M8\n"},
        {"wabeco", "", "", "_\n_\n; frame\nG90\n", ""},
        {"kosy", "", "", "_\n_\n; frame\nG90\n", ""},
    };
    for (const Case& c : cases) {
        CAPTURE(c.machine);
        const std::string job = frame_job(c.offset, c.coolant);
        const std::string program = test::post_job(job, c.machine).text;
        CHECK(program.find(c.start) != std::string::npos);
        if (*c.coolant_on) {
            // Coolant on after the spindle, off (M9) before it stops at the end.
            const size_t on = program.find(c.coolant_on), off = program.find(" M9\n") != std::string::npos
                                                                   ? program.find(" M9\n")
                                                                   : program.find("\nM9\n");
            CHECK(on != std::string::npos);
            CHECK(off != std::string::npos);
            CHECK(on < off);
        }
        CHECK(test::round_trip(job, program, c.machine) == "");
        // The reader gives the coolant back as events.
        int coolant_events = 0;
        for (const ReadEvent& e : read_program(program, load_machine(c.machine), "prog"))
            if (std::holds_alternative<Coolant>(e.event)) ++coolant_events;
        CHECK(coolant_events == (*c.coolant_on ? 2 : 0));
    }
}

TEST_CASE("Fanuc extended work offsets G54.1 P1..P48 are written and read back; others are refused") {
    const std::string job = frame_job("G54.1 P7", "");
    const std::string program = test::post_job(job, "fanuc").text;
    CHECK(program.find("G21 G54.1 P7\n") != std::string::npos);
    CHECK(test::round_trip(job, program, "fanuc") == "");
    CHECK(post_error(frame_job("G54.1 P49", ""), "fanuc") ==
          "/workOffset: machine fanuc has no work offset \"G54.1 P49\"; it has G54 .. G54.1 P48");
    CHECK(post_error(frame_job("G59.1", ""), "fanuc").rfind("/workOffset: machine fanuc has no work offset \"G59.1\"", 0) == 0);
    // Read back: an offset the machine lacks is an error naming it.
    CHECK(test::error_of("G0 G59.1 Z10\nM30\n", "fanuc").find("unknown code G59.1") != std::string::npos);
    CHECK(test::error_of("G54.1 P49\nM30\n", "fanuc").find("machine fanuc has no work offset G54.1 P49") != std::string::npos);
}

TEST_CASE("a work offset, coolant or program number the control lacks is refused with the job key's path") {
    CHECK(post_error(frame_job("G54", ""), "wabeco") == "/workOffset: machine wabeco has no work offsets: its control cannot select G54");
    CHECK(post_error(frame_job("G54", ""), "heidenhain").rfind("/workOffset: machine heidenhain has no work offsets", 0) == 0);
    CHECK(post_error(frame_job("", "flood"), "kosy") == "/tools/0/coolant: machine kosy has no flood coolant");
    CHECK(post_error(frame_job("", "mist"), "grbl") == "/tools/0/coolant: machine grbl has no mist coolant (it has: flood)");
    CHECK(post_error(frame_job("", "", "42"), "linuxcnc") == "/programNumber: machine linuxcnc takes no program number");
    CHECK(post_error(frame_job("", "", "42"), "sinumerik") == "/programNumber: machine sinumerik takes no program number");
    // The command line names the job file and the key's line; exit 1.
    test::Run r = test::run({"-", "--machine", "wabeco"}, frame_job("G54", ""));
    CHECK(r.code == 1);
    CHECK(r.err.find("/workOffset") != std::string::npos);
    CHECK(r.err.find("machine wabeco") != std::string::npos);
}

TEST_CASE("a job's program number replaces the machine's O-number") {
    const std::string program = test::post_job(frame_job("", "", "42"), "fanuc").text;
    CHECK(program.rfind("%\nO0042 (frame)\n", 0) == 0);
    CHECK(test::post_job(frame_job("", ""), "fanuc").text.rfind("%\nO1000 (frame)\n", 0) == 0);
}

TEST_CASE("--describe-machine shows the program frame") {
    test::Run d = test::run({"--describe-machine", "linuxcnc"});
    CHECK(d.out.find("G40 G49 G80 G17 G90 G94") != std::string::npos);
    CHECK(d.out.find("G59.3") != std::string::npos);
    CHECK(d.out.find("flood M8") != std::string::npos);
}

TEST_CASE("a machine's safe retract G53 G0 Z0: first where the height is unknown and at the end, read back") {
    Machine m = load_machine("linuxcnc");
    m.frame.safe_retract = {"G53", "G0", "Z0"};
    const Job job = read_job(frame_job("", ""), "job.json");
    const std::string program = test::post_program(job, m);
    // Up in machine coordinates, across, down to the clearance with the length offset.
    CHECK(program.find("T1 M6\nS1000 M3\nG53 G0 Z0\nG0 X10 Y10\nG43 Z10 H1\n") != std::string::npos);
    CHECK(program.find("M5\nG53 G0 Z0\nM2\n") != std::string::npos);
    CHECK(test::round_trip_machine(job, program, m) == "");
    for (const ReadEvent& e : read_program(program, m, "prog"))
        if (e.from_unknown) CHECK(e.approach == Approach::z_first);
    // Without the safe retract, X and Y before Z are an XY-first approach again; G53 is refused
    // on a machine that has none, and any other G53 move is refused.
    CHECK(test::error_of("G53 G0 Z0\nM2\n", "linuxcnc").find("machine linuxcnc has no safe retract") != std::string::npos);
    std::string bad;
    try {
        (void)read_program("G53 G0 Z5\nM2\n", m, "prog");
    } catch (const InputError& e) {
        bad = e.what();
    }
    CHECK(bad.find("G53 only as G53 G0 Z0") != std::string::npos);
}

}  // namespace test_frame
