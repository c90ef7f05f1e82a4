// verify --job and simulate --job compare the offsets a program selects with those camgen's
// post selects (SelectedOffsets, compare.hpp): the tool length offset at every move of a tool
// (G43 H<tool> on ISO mills and LinuxCNC's lathe, the turret's T0101, Sinumerik's D1,
// Heidenhain's TOOL CALL; none on nccad and GRBL) and the job's work offset. For each machine a
// sample is posted and matches; each edit of the program (another register, no G43, G49
// before the cut, another work offset, a work offset selected between two holes of a canned
// cycle) is a MISMATCH naming the line and both offsets, and plain verify still reads it.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/reader/reader.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "support.hpp"

namespace test_verify_offsets {

namespace fs = std::filesystem;
using namespace camgen;
using test::Run;
using test::run;

namespace {

const std::string samples = CAMGEN_SOURCE_DIR "/samples/";

// The 1-based number of the first line holding `what` (at or after line `from`); 0: none.
int line_of(const std::string& text, const std::string& what, int from = 1) {
    std::istringstream in(text);
    std::string l;
    for (int n = 1; std::getline(in, l); ++n)
        if (n >= from && l.find(what) != std::string::npos) return n;
    return 0;
}

// `text` with the first `what` at or after line `from` replaced by `with`.
std::string replaced(const std::string& text, const std::string& what, const std::string& with, int from = 1) {
    std::istringstream in(text);
    std::string out, l;
    bool done = false;
    for (int n = 1; std::getline(in, l); ++n) {
        if (!done && n >= from) {
            if (auto at = l.find(what); at != std::string::npos) {
                l.replace(at, what.size(), with);
                done = true;
            }
        }
        out += l + "\n";
    }
    REQUIRE_MESSAGE(done, what << " not in the program");
    return out;
}

// `text` with `line` inserted before its line `before` (1-based).
std::string inserted(const std::string& text, int before, const std::string& line) {
    REQUIRE(before > 0);
    std::istringstream in(text);
    std::string out, l;
    for (int n = 1; std::getline(in, l); ++n) {
        if (n == before) out += line + "\n";
        out += l + "\n";
    }
    return out;
}

// A job: the sample with a work offset (empty: as it is).
std::string job_file(const fs::path& dir, const std::string& sample, const std::string& work_offset) {
    if (work_offset.empty()) return samples + sample + ".json";
    std::string text = test::read_file(samples + sample + ".json");
    REQUIRE(text.rfind("{", 0) == 0);
    text.insert(1, "\"workOffset\": \"" + work_offset + "\",");
    const fs::path p = dir / (sample + "-" + work_offset + ".json");
    std::ofstream(p) << text;
    return p.string();
}

struct Setup {
    fs::path dir;
    std::string machine, job, program;  // the program as posted
};

Setup posted(const std::string& name, const std::string& sample, const std::string& machine, const std::string& work_offset) {
    Setup s{test::scratch("verify-offsets-" + name), machine, {}, {}};
    s.job = job_file(s.dir, sample, work_offset);
    Run p = run({s.job, "--machine", machine});
    REQUIRE(p.code == 0);
    s.program = p.out;
    return s;
}

// verify --job of `program`.
Run verify(const Setup& s, const std::string& program, const std::string& name) {
    const fs::path file = s.dir / name;
    std::ofstream(file) << program;
    return run({"verify", file.string(), "--machine", s.machine, "--job", s.job});
}

void check_matches(const Setup& s) {
    Run v = verify(s, s.program, "as-posted.nc");
    CHECK_MESSAGE(v.code == 0, v.out);
    CHECK(v.out.find("matches job " + s.job + ": ") != std::string::npos);
    CHECK(v.out.find("tools, tool length and work offsets, and spindle") != std::string::npos);
}

// The edited program is a mismatch at `line` whose message holds each of `words`; without the
// job it is read as it is.
void check_mismatch(const Setup& s, const std::string& program, int line, const std::vector<std::string>& words) {
    CAPTURE(program);
    Run v = verify(s, program, "edited.nc");
    CHECK(v.code == 1);
    const std::string at = fmt::format("MISMATCH {}:{}: ", (s.dir / "edited.nc").string(), line);
    CHECK_MESSAGE(v.out.find(at) != std::string::npos, v.out);
    for (const std::string& w : words) CHECK_MESSAGE(v.out.find(w) != std::string::npos, w << "\n--- in ---\n" << v.out);
    Run plain = run({"verify", (s.dir / "edited.nc").string(), "--machine", s.machine});
    CHECK_MESSAGE(plain.code == 0, plain.out << plain.err);
}

}  // namespace

TEST_CASE("verify --job: the tool length offset on LinuxCNC and Fanuc is G43 H<tool>") {
    for (const std::string machine : {"linuxcnc", "fanuc"}) {
        CAPTURE(machine);
        const Setup s = posted(machine + "-length", "plate", machine, "");
        check_matches(s);
        const std::string z10 = machine == "fanuc" ? "G0 G43 Z10.000 " : "G0 G43 Z10 ";
        const int g43_1 = line_of(s.program, z10 + "H1"), g43_2 = line_of(s.program, z10 + "H2");
        REQUIRE(g43_1 > 0);
        REQUIRE(g43_2 > g43_1);
        // The rapid down is made once X and Y are known: on the next line.
        // Another tool's register, none, a register no tool has.
        for (const std::string h : {"H2", "H0", "H99"}) {
            CAPTURE(h);
            check_mismatch(s, replaced(s.program, z10 + "H1", z10 + h), g43_1 + 1,
                           {"tool 1 moves under the tool length offset G43 " + h + fmt::format(" (line {})", g43_1),
                            "the job's post selects G43 H1"});
        }
        // No G43 for tool 2: tool 1's offset stays in force.
        check_mismatch(s, replaced(s.program, z10 + "H2", machine == "fanuc" ? "G0 Z10.000" : "G0 Z10"), g43_2 + 1,
                       {fmt::format("tool 2 moves under the tool length offset G43 H1 (line {})", g43_1),
                        "the job's post selects G43 H2"});
        // G49 before the cycle cuts: the feed moves (and the rapids before them) run without it.
        const int cycle = line_of(s.program, "G81", g43_1);
        REQUIRE(cycle > 0);
        check_mismatch(s, inserted(s.program, cycle, "G49"), cycle + 1,
                       {fmt::format("tool 1 moves with no tool length offset (cancelled at line {})", cycle),
                        "the job's post selects G43 H1"});
    }
}

TEST_CASE("verify --job: the work offset is the job's, everywhere, also between two holes of a canned cycle") {
    for (const std::string machine : {"linuxcnc", "fanuc", "sinumerik", "grbl"}) {
        CAPTURE(machine);
        const Setup s = posted(machine + "-work", "plate", machine, "G54");
        check_matches(s);
        const int start = line_of(s.program, "G54");
        REQUIRE(start > 0);
        // Another work offset in the start block: the first move is under it.
        {
            const std::string edited = replaced(s.program, "G54", "G55");
            Run v = verify(s, edited, "edited.nc");
            CHECK(v.code == 1);
            CHECK_MESSAGE(v.out.find(fmt::format("tool 1 moves in work offset G55 (line {}) where the job's work offset is G54",
                                                 start)) != std::string::npos,
                          v.out);
            CHECK(run({"verify", (s.dir / "edited.nc").string(), "--machine", machine}).code == 0);
        }
        // No work offset selected: the control's active one.
        {
            const std::string edited = replaced(s.program, " G54", "");
            Run v = verify(s, edited, "edited.nc");
            CHECK(v.code == 1);
            CHECK_MESSAGE(v.out.find("tool 1 moves in no work offset selected (the control's active one) where the job's work "
                                     "offset is G54") != std::string::npos,
                          v.out);
        }
        // G55 between the second and the third hole of the first tool (a canned cycle on all but
        // GRBL, which drills longhand): the third hole is the first move under it.
        const std::string third = machine == "fanuc" || machine == "sinumerik" ? "X90.000 Y10.000" : machine == "grbl" ? "X90" : "X90 Y10";
        const int hole = line_of(s.program, third);
        REQUIRE(hole > 0);
        if (machine != "grbl") CHECK(line_of(s.program, machine == "sinumerik" ? "CYCLE81" : "G81") < hole);
        check_mismatch(s, inserted(s.program, hole, machine == "sinumerik" ? "N1 G55" : "G55"), hole + 1,
                       {fmt::format("tool 1 moves in work offset G55 (line {}) where the job's work offset is G54", hole),
                        "every position is off by the difference"});
    }
}

TEST_CASE("verify --job: a job without a work offset expects none selected (the post writes none)") {
    const Setup s = posted("none-work", "plate", "linuxcnc", "");
    check_matches(s);
    CHECK(line_of(s.program, "G54") == 0);
    const int start = line_of(s.program, "G21");
    check_mismatch(s, replaced(s.program, "G21", "G21 G54"), line_of(s.program, "X10 Y10"),  // the first move
                   {fmt::format("tool 1 moves in work offset G54 (line {}) where the job's work offset is none", start)});
}

TEST_CASE("verify --job: Sinumerik's cutting edge D is the length offset, D1 as the post writes it") {
    for (const std::string machine : {"sinumerik", "sinumerik-lathe"}) {
        CAPTURE(machine);
        const std::string sample = machine == "sinumerik" ? "plate" : "shaft";
        const Setup s = posted(machine + "-d", sample, machine, "");
        check_matches(s);
        const std::string tool = machine == "sinumerik" ? "T1" : "T4";  // the first tool
        const int first = line_of(s.program, tool + " D1");
        REQUIRE(first > 0);
        // The M6 on the next line makes the edge count; the first move after it names the line.
        const int move = line_of(s.program, "X", first + 2);
        check_mismatch(s, replaced(s.program, tool + " D1", tool + " D2"), move,
                       {"moves under the tool length offset D2", "the job's post selects D1"});
        check_mismatch(s, replaced(s.program, tool + " D1", tool), move,
                       {"moves under the tool length offset " + tool + " without D: the control's default edge",
                        "the job's post selects D1"});
        // D0 selects no edge: no length offset at all.
        check_mismatch(s, replaced(s.program, tool + " D1", tool + " D0"), move,
                       {"moves with no tool length offset (cancelled at line", "the job's post selects D1"});
        // D without T changes the edge of the tool in the spindle from its block on.
        const Run d2 = verify(s, inserted(s.program, move, "D2"), "edge.nc");
        CHECK(d2.code == 1);
        CHECK_MESSAGE(d2.out.find(fmt::format("edge.nc:{}: ", move + 1)) != std::string::npos, d2.out);
        CHECK_MESSAGE(d2.out.find("moves under the tool length offset D2") != std::string::npos, d2.out);
    }
}

TEST_CASE("Sinumerik's reader: D0 and a D without T, read as the control selects them") {
    const fs::path dir = test::scratch("verify-offsets-d0");
    const auto read = [&](const std::string& name, const std::string& program) {
        std::ofstream(dir / name) << program;
        return run({"verify", (dir / name).string(), "--machine", "sinumerik"});
    };
    const std::string head = "T1 D1\nM6\nS1000 M3\nG0 X0. Y0. Z5.\n";
    CHECK(read("d0.mpf", head + "D0\nG1 Z-1. F100\nM30\n").code == 0);
    // Under D0 the control has no radius: a G41 would cut on the programmed path.
    Run comp = read("d0-comp.mpf", head + "D0\nG41 G1 X5. F100\nM30\n");
    CHECK(comp.code != 0);
    CHECK_MESSAGE(comp.err.find("d0-comp.mpf:6: G41 under D0: no cutting edge selected") != std::string::npos, comp.err);
    Run none = read("d-first.mpf", "D0\nT1 D1\nM6\nM30\n");
    CHECK(none.code != 0);
    CHECK_MESSAGE(none.err.find("d-first.mpf:1: D0 without a tool in the spindle") != std::string::npos, none.err);
}

TEST_CASE("verify --job: lathes: Fanuc T's turret offset digits, LinuxCNC's G43 H") {
    {
        const Setup s = posted("fanuc-lathe", "shaft", "fanuc-lathe", "G54");
        check_matches(s);
        const int call = line_of(s.program, "T0404");
        REQUIRE(call > 0);
        // Tool 4 with offset 05: read (plain verify), and not the job's.
        check_mismatch(s, replaced(s.program, "T0404", "T0405"), line_of(s.program, "X", call),
                       {fmt::format("tool 4 moves under the tool length offset T0405 (line {})", call),
                        "the job's post selects T0404"});
        check_mismatch(s, replaced(s.program, "T0404", "T0400"), line_of(s.program, "X", call),
                       {"tool 4 moves under the tool length offset T0400", "the job's post selects T0404"});
        check_mismatch(s, replaced(s.program, "G54", "G59"), line_of(s.program, "X", call),
                       {"tool 4 moves in work offset G59", "where the job's work offset is G54"});
    }
    {
        const Setup s = posted("linuxcnc-lathe", "shaft", "linuxcnc-lathe", "");
        check_matches(s);
        const int g43 = line_of(s.program, "G0 G43 Z20 H4");
        REQUIRE(g43 > 0);
        check_mismatch(s, replaced(s.program, "G0 G43 Z20 H4", "G0 G43 Z20 H5"), g43 + 1,
                       {fmt::format("tool 4 moves under the tool length offset G43 H5 (line {})", g43), "the job's post selects G43 H4"});
        check_mismatch(s, replaced(s.program, "G0 G43 Z20 H4", "G0 Z20"), g43 + 1,
                       {"tool 4 moves with no tool length offset selected", "the job's post selects G43 H4"});
    }
}

TEST_CASE("verify --job: GRBL as camgen writes it has no tool length offset: a G43 H is refused") {
    // GRBL 1.1 has only G43.1 (a dynamic offset): grbl.json's lengthOffsetH is false, and the
    // reader refuses G43 H, with the job and without.
    const Setup s = posted("grbl", "plate", "grbl", "");
    check_matches(s);
    CHECK(line_of(s.program, "G43") == 0);
    const int z = line_of(s.program, "G0 Z10");
    REQUIRE(z > 0);
    const std::string program = replaced(s.program, "G0 Z10", "G0 G43 Z10 H1");
    Run v = verify(s, program, "edited.nc");
    CHECK(v.code == 1);
    const std::string refusal = fmt::format("edited.nc:{}: G43: machine grbl takes no tool length offset from a table", z);
    CHECK_MESSAGE(v.err.find(refusal) != std::string::npos, v.out << v.err);
    Run plain = run({"verify", (s.dir / "edited.nc").string(), "--machine", s.machine});
    CHECK(plain.code == 1);
    CHECK_MESSAGE(plain.err.find(refusal) != std::string::npos, plain.err);
}

TEST_CASE("controls without length offset registers or work offsets: Heidenhain, nccad (wabeco, kosy)") {
    // Heidenhain's TOOL CALL applies the called tool's own length: the offset is the tool's,
    // which verify compares as the tool. nccad has no tool length offsets at all (the operator
    // touches each tool off). Neither has work offsets: a job that asks for one does not post.
    for (const std::string machine : {"heidenhain", "wabeco", "kosy"}) {
        CAPTURE(machine);
        const Setup s = posted(machine, "plate", machine, "");
        check_matches(s);
        const Machine m = load_machine(machine);
        const std::vector<ReadEvent> events = read_program(s.program, m);
        int moves = 0;
        for (const ReadEvent& e : events) {
            if (!std::holds_alternative<Rapid>(e.event) && !std::holds_alternative<Linear>(e.event)) continue;
            ++moves;
            CHECK(e.offsets.work == "");
            if (machine == "heidenhain") CHECK(e.offsets.length.str().rfind("TOOL CALL ", 0) == 0);
            else CHECK(e.offsets.length == "");
        }
        CHECK(moves > 10);
        CHECK(post_length_offset(m, 1) == (machine == "heidenhain" ? "TOOL CALL 1" : ""));
        Run p = run({job_file(s.dir, "plate", "G54"), "--machine", machine});
        CHECK(p.code == 1);
        CHECK(p.err.find("has no work offsets") != std::string::npos);
    }
}

TEST_CASE("the length offset each post selects, as its reader reads it back") {
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"linuxcnc", "G43 H3"}, {"fanuc", "G43 H3"},          {"grbl", ""},     {"linuxcnc-lathe", "G43 H3"},
        {"fanuc-lathe", "T0303"}, {"sinumerik", "D1"},        {"sinumerik-lathe", "D1"},
        {"heidenhain", "TOOL CALL 3"}, {"wabeco", ""},         {"kosy", ""}};
    for (const auto& [machine, length] : expected) {
        CAPTURE(machine);
        const Machine m = load_machine(machine);
        CHECK(post_length_offset(m, 3) == length);
        CHECK(post_length_offset(m, 0) == "");
    }
}

TEST_CASE("simulate --job: a move under offsets the post does not select is an error, exit 1") {
    const Setup s = posted("simulate", "plate", "linuxcnc", "G54");
    const std::string box = "0,0,-8,100,50,0";
    const fs::path good = s.dir / "good.ngc", bad = s.dir / "bad.ngc";
    std::ofstream(good) << s.program;
    const int g43 = line_of(s.program, "G0 G43 Z10 H1");
    const int hole = line_of(s.program, "X90 Y10");
    std::ofstream(bad) << inserted(replaced(s.program, "G0 G43 Z10 H1", "G0 G43 Z10 H2"), hole, "G55");
    Run ok = run({"simulate", good.string(), "--machine", "linuxcnc", "--job", s.job, "--stock-box", box});
    CHECK_MESSAGE(ok.code == 0, ok.out << ok.err);
    CHECK(ok.out.find("simulation: no errors") != std::string::npos);
    Run v = run({"simulate", bad.string(), "--machine", "linuxcnc", "--job", s.job, "--stock-box", box});
    CHECK(v.code == 1);
    CHECK_MESSAGE(v.out.find(fmt::format("error: line {} (/operations/0), tool 1: tool 1 moves under the tool length offset G43 H2 "
                                         "(line {}) where the job's post selects G43 H1",
                                         g43 + 1, g43)) != std::string::npos,
                  v.out);
    // Once for each run of moves under the same offsets: the third hole under G55 (still H2),
    // then tool 2 (its length right) under the G55 selected between the holes.
    CHECK_MESSAGE(v.out.find(fmt::format("error: line {} (/operations/0), tool 1: tool 1 moves under the tool length offset G43 H2",
                                         hole + 1)) != std::string::npos,
                  v.out);
    const int tool2 = line_of(s.program, "G0 G43 Z10 H2") + 2;  // the move after it, one line was inserted
    CHECK_MESSAGE(v.out.find(fmt::format("error: line {} (/operations/1), tool 2: tool 2 moves in work offset G55 (line {}) where the "
                                         "job's work offset is G54",
                                         tool2, hole)) != std::string::npos,
                  v.out);
    CHECK(v.out.find("simulation: 3 errors") != std::string::npos);
}

}  // namespace test_verify_offsets
