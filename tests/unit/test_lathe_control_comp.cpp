// Nose-radius compensation by the control (issue 30 item 3): a turn-profile with
// "compensation": "control" writes the designed profile under G42 with G40 on the lift, each
// lathe naming what its table must hold; the readers read G41/G42 in G18 back and the trace
// applies them as LinuxCNC does (the values of one rs274 run kept here, so that this file needs
// no rs274: tests/oracle/test_lathe_comp_oracle.cpp runs it on many profiles); refusals at
// their JSON paths.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_lathe_control_comp {

using namespace camgen;

namespace {

std::string job_text(const std::string& tool, const std::string& op_extra, const std::string& path =
                         R"([{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]}, {"arc": {"end": [40, -25], "centre": [40, -20], "direction": "cw"}}, {"line": [40, -40]}])") {
    return fmt::format(R"({{"name": "c", "units": "mm", "clearance": 20,
  "tools": [{{"number": 3, "type": "turning-tool", {} "rpm": 1000}}],
  "operations": [{{"type": "turn-profile", "tool": 3, "feed": 100, "start": [24, 0], "retractX": 50,
                  "compensation": "control", {} "path": {}}}]}})",
                       tool, op_extra, path);
}

std::string refusal(const std::string& text) {
    try {
        (void)read_job(text, "c.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string posted(const std::string& text, const std::string& machine_name) {
    const Job job = read_job(text, "c.json");
    const Machine machine = load_machine(machine_name);
    std::ostringstream out;
    PostOptions o;
    o.program_name = job.name;
    auto post = make_post(machine, out, o);
    post->open();
    expand_job(job, *post);
    post->close();
    return out.str();
}

const std::string good_tool = R"("noseRadius": 0.4, "orientation": 2,)";

}  // namespace

TEST_CASE("control nose compensation: the three lathes write G42 on the entry, G40 on the lift, and name the table") {
    const std::string text = job_text(good_tool, "");
    const std::string linuxcnc = posted(text, "linuxcnc-lathe");
    CHECK(linuxcnc.find("(G42 nose comp: tool table T3 D0.8 nose diameter, Q2 tip at -X -Z of the nose centre)") !=
          std::string::npos);
    CHECK(linuxcnc.find("G42 G1 Z0 F100") != std::string::npos);
    CHECK(linuxcnc.find("G40 X") != std::string::npos);
    CHECK(linuxcnc.find("D3") == std::string::npos);  // no D word: the tool's own table entry
    // The designed profile itself: the chamfer's end and the D30 diameter as drawn.
    CHECK(linuxcnc.find("X30 Z-1") != std::string::npos);
    const std::string fanuc = posted(text, "fanuc-lathe");
    CHECK(fanuc.find("(G42 nose comp: offset 03 R0.4 nose radius, Fanuc tip T3: tip at -X -Z of the nose centre)") !=
          std::string::npos);
    CHECK(fanuc.find("G42 G1") != std::string::npos);
    CHECK(fanuc.find("G40 X") != std::string::npos);
    const std::string sinumerik = posted(text, "sinumerik-lathe");
    CHECK(sinumerik.find("; G42 nose comp: T3 D1 radius 0.4, cutting edge position 2, tip at -X -Z of the nose centre") !=
          std::string::npos);
    CHECK(sinumerik.find("G42 G1") != std::string::npos);
    CHECK(sinumerik.find("G40 X") != std::string::npos);
}

TEST_CASE("control nose compensation: refusals at their JSON paths") {
    // (A turning tool always has a nose radius, its noseRadius or half its diameter; orientation
    // 0, no tip given, is a library user's: the job's tools take 1 to 9.)
    CHECK(refusal(job_text(R"("noseRadius": 0.4, "orientation": 9,)", ""))
              .find("/operations/0/compensation: control compensation needs the tool's tip orientation 1 to 8 (the control "
                    "moves that imaginary tip); tool 3 has orientation 9 (the nose centre: use compensation computer or none)") !=
          std::string::npos);
    CHECK(refusal(job_text(good_tool, R"("approachDistance": 0.4,)"))
              .find("/operations/0/approachDistance: the entry move under G42") != std::string::npos);
    CHECK(refusal(job_text(good_tool, "", R"([{"line": [24.6, 0]}])")).find("/operations/0/path: the profile (0.3") !=
          std::string::npos);
    const std::string rough = R"({"name": "c", "units": "mm", "clearance": 20, "stock": {"bar": {"diameter": 44, "length": 70, "faceZ": 0}},
  "tools": [{"number": 4, "type": "turning-tool", "noseRadius": 0.8, "orientation": 2, "rpm": 1000}],
  "operations": [{"type": "turn-rough", "tool": 4, "feed": 100, "depthOfCut": 2, "start": [24, 0], "compensation": "control",
                  "path": [{"line": [30, -20]}]}]})";
    CHECK(refusal(rough).find("/operations/0/compensation: turn-rough does not write control compensation") != std::string::npos);
}

TEST_CASE("control nose compensation: the trace applies G42 in G18 as LinuxCNC does (one rs274 run)") {
    // rs274 -t (T1 D0.0629921 X0 Z0 Q2: r 0.8, orientation 2) on this program printed these
    // tip positions (radius, Z) and arcs (Z, X centres).
    const std::string program = "G18 G7 G40 G80 G90 G94\nT1 M6\nG0 G43 Z20 H1\nG0 X30 Z5\nG42 G1 X20 Z2 F100\nG1 Z-10\nG1 X24 Z-12\n"
                                "G2 X30 Z-15 I3 K0\nG1 X40\nG40 G0 X50\nM2\n";
    const Machine machine = load_machine("linuxcnc-lathe");
    TraceOptions o;
    o.compensation_radii = {{1, 0.8}};
    o.compensation_orientations = {{1, 2}};
    const Trace t = trace_program(read_program(program, machine, "a.ngc"), machine, o);
    std::vector<Step> moves;
    for (const Step& s : t.steps)
        if ((s.kind == StepKind::feed || s.kind == StepKind::rapid) && s.from_known) moves.push_back(s);
    // The moves from G42 on (before it: the rapids from the tool change).
    REQUIRE(moves.size() >= 7);
    moves.erase(moves.begin(), moves.end() - 7);
    struct Want {
        double x, z;
        bool arc;
        double cz, cx;
    };
    const Want want[] = {{10.0, 0.7470, false, 0, 0},        {10.0, -10.4686, false, 0, 0},  {11.7657, -12.2343, false, 0, 0},
                         {12.0, -12.8, true, -12.8, 11.2},   {14.2, -15.0, true, -12.8, 14.2}, {19.2, -15.0, false, 0, 0},
                         {25.0, -15.0, false, 0, 0}};
    for (std::size_t i = 0; i < moves.size(); ++i) {
        CAPTURE(i);
        CHECK(std::abs(moves[i].to.x - want[i].x) < 1e-4);
        CHECK(std::abs(moves[i].to.z - want[i].z) < 1e-4);
        CHECK(moves[i].arc.has_value() == want[i].arc);
        if (want[i].arc && moves[i].arc) {
            CHECK(std::abs(moves[i].arc->centre.z - want[i].cz) < 1e-4);
            CHECK(std::abs(moves[i].arc->centre.x - want[i].cx) < 1e-4);
        }
    }
    // Without the orientation: the programmed point is the nose centre, with a note.
    TraceOptions no_q;
    no_q.compensation_radii = {{1, 0.8}};
    const Trace u = trace_program(read_program(program, machine, "a.ngc"), machine, no_q);
    bool noted = false;
    for (const std::string& n : u.notes) noted = noted || n.find("whose tip orientation camgen does not know") != std::string::npos;
    CHECK(noted);
}

TEST_CASE("control nose compensation: Fanuc's tip numbers are LinuxCNC's mirrored in X, and a program read alone takes them") {
    // Haas's lathe operator's manual ("Imaginary Tool Tip and Direction", Fanuc-compatible):
    // the direction from the nose centre to the tip for each number, typed here from its text.
    const std::map<int, std::string> fanuc_words = {{1, "+X +Z"}, {2, "+X -Z"}, {3, "-X -Z"}, {4, "-X +Z"},
                                                    {5, "+Z"},    {6, "+X"},    {7, "-Z"},    {8, "-X"}};
    for (const auto& [number, words] : fanuc_words) {
        CAPTURE(number);
        CHECK(lathe_tip_words(fanuc_tip_number(number)) == "tip at " + words + " of the nose centre");
        CHECK(fanuc_tip_number(fanuc_tip_number(number)) == number);
    }
    CHECK(fanuc_tip_number(9) == 9);
    CHECK(fanuc_tip_number(0) == 0);

    // A fanuc-lathe program read without its job: the comment's Fanuc T3 is orientation 2, and
    // the trace is the one the job's orientation gives; an older program's "T2 ... [LinuxCNC
    // numbering]" is read as it was meant; an edited T2 (Fanuc: tip at +X -Z) traces otherwise.
    const std::string fanuc = posted(job_text(good_tool, ""), "fanuc-lathe");
    const Machine machine = load_machine("fanuc-lathe");
    auto feeds = [&](const std::string& program, bool give_orientation) {
        TraceOptions o;
        o.compensation_radii = {{3, 0.4}};
        if (give_orientation) o.compensation_orientations = {{3, 2}};
        std::vector<Vec3> to;
        for (const Step& s : trace_program(read_program(program, machine, "a.nc"), machine, o).steps)
            if (s.kind == StepKind::feed) to.push_back(s.to);
        return to;
    };
    auto same = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (std::abs(a[i].x - b[i].x) > 1e-9 || std::abs(a[i].y - b[i].y) > 1e-9 || std::abs(a[i].z - b[i].z) > 1e-9) return false;
        return true;
    };
    const std::vector<Vec3> with_job = feeds(fanuc, true);
    REQUIRE(!with_job.empty());
    CHECK(same(feeds(fanuc, false), with_job));
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string t = fanuc;
        const std::size_t at = t.find(from);
        REQUIRE(at != std::string::npos);
        return t.replace(at, from.size(), to);
    };
    CHECK(same(feeds(replaced("Fanuc tip T3: tip at -X -Z of the nose centre", "T2 tip at -X -Z of the nose centre [LinuxCNC numbering]"),
                     false),
               with_job));
    CHECK(!same(feeds(replaced("Fanuc tip T3", "Fanuc tip T2"), false), with_job));
}

}  // namespace test_lathe_control_comp
