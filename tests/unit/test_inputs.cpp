// Inputs (issue 25): an output never replaces an input (the job, a machine file of the extends
// chain, the program, job and tool table of verify), every input is read within a size limit
// (and a program within a line-length limit), a FIFO or a device named by extends is refused by
// its type, and a file that is not JSON where a job or machine file was expected is named for
// what it is. (Honest messages: test_honest_messages.cpp.)
#include <doctest/doctest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "camgen/common/file_kind.hpp"
#include "camgen/common/input_file.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_inputs {

// The peak memory a run that must not hold its input may reach: far below the 1 GiB it reads.
// AddressSanitizer's allocator and shadow memory alone take about 450 MB (the sanitized twin,
// whose test programs are the same objects linked with its runtime).
const long peak_limit_kb = camgen::test::sanitizer_runtime() ? 600 * 1024 : 200 * 1024;

using namespace camgen;
namespace fs = std::filesystem;

namespace {

const std::string plate = CAMGEN_SOURCE_DIR "/samples/plate.json";
const std::string source_dir = CAMGEN_SOURCE_DIR;

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// A copy of plate.json in a scratch folder.
fs::path job_copy(const fs::path& dir) {
    const fs::path job = dir / "job.json";
    write(job, test::read_file(plate));
    return job;
}

// What a run of the camgen binary did.
struct BinaryRun {
    int code = -1;          // exit code; -1: killed by a signal or by the timeout
    bool timed_out = false;
    double seconds = 0.0;
    long max_rss_kb = 0;    // the child's peak resident memory
    std::string err;
};

// Runs the camgen binary with `env` set (NAME=VALUE), standard input from `stdin_file` ("" :
// /dev/null), standard output appended to `stdout_file` ("" : /dev/null); killed after
// `timeout` seconds.
BinaryRun run_binary(const std::vector<std::string>& args, const std::vector<std::string>& env = {},
                     const std::string& stdin_file = "", double timeout = 60.0, const std::string& stdout_file = "") {
    const fs::path err_file = test::scratch("inputs-binary-err") / "err.txt";
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        for (const std::string& e : env) ::putenv(const_cast<char*>(e.c_str()));
        std::vector<char*> argv{const_cast<char*>(camgen::test::camgen_binary())};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        const int in = ::open(stdin_file.empty() ? "/dev/null" : stdin_file.c_str(), O_RDONLY);
        const int out = ::open(stdout_file.empty() ? "/dev/null" : stdout_file.c_str(), O_WRONLY | O_APPEND);
        const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(in, 0);
        ::dup2(out, 1);
        ::dup2(err, 2);
        ::execv(camgen::test::camgen_binary(), argv.data());
        ::_exit(127);
    }
    BinaryRun r;
    int status = 0;
    struct rusage usage {};
    while (true) {
        const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
        if (done == pid) break;
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout) {
            ::kill(pid, SIGKILL);
            ::wait4(pid, &status, 0, &usage);
            r.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.code = !r.timed_out && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.max_rss_kb = usage.ru_maxrss;
    r.err = test::read_file(err_file.string());
    return r;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

// ---- inputs are never outputs ----

TEST_CASE("-o onto the job, directly or through a symlink, is a usage error naming both, and the job is untouched") {
    const fs::path dir = test::scratch("inputs-o-job");
    const fs::path job = job_copy(dir);
    const std::string before = test::read_file(job.string());
    fs::create_symlink("job.json", dir / "link.nc");
    for (const std::string& out : {job.string(), (dir / "link.nc").string(), (dir / "." / "job.json").string()}) {
        const test::Run r = test::run({job.string(), "--machine", "fanuc", "-o", out});
        CHECK(r.code == 2);
        CHECK(r.err == "camgen: -o " + out + " would replace the job " + job.string() +
                           " (the same file): camgen never writes over its input; give another output file\n");
        CHECK(r.out.empty());
        CHECK(test::read_file(job.string()) == before);
    }
    CHECK(fs::is_symlink(dir / "link.nc"));
    // Nothing else was made beside it (no temporary, no plot).
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}) == 2);
}

TEST_CASE("--plot onto the job, and -o and --plot onto one file, are usage errors; nothing is written") {
    const fs::path dir = test::scratch("inputs-plot-job");
    const fs::path job = job_copy(dir);
    const std::string before = test::read_file(job.string());
    const test::Run r = test::run({job.string(), "--machine", "fanuc", "-o", (dir / "p.nc").string(), "--plot", job.string()});
    CHECK(r.code == 2);
    CHECK(contains(r.err, "--plot " + job.string() + " would replace the job " + job.string()));
    CHECK(test::read_file(job.string()) == before);
    CHECK_FALSE(fs::exists(dir / "p.nc"));
    // One new file named twice.
    const std::string same = (dir / "same.svg").string();
    const test::Run twice = test::run({job.string(), "--machine", "fanuc", "-o", same, "--plot", same});
    CHECK(twice.code == 2);
    CHECK(twice.err == "camgen: -o " + same + " and --plot " + same + " are the same file: give each output its own\n");
    CHECK_FALSE(fs::exists(same));
}

TEST_CASE("-o onto a machine file of the extends chain is a usage error; the machine file is untouched") {
    const fs::path dir = test::scratch("inputs-o-machine");
    const fs::path base = dir / "base.json", mine = dir / "mine.json";
    write(base, test::read_file(source_dir + "/machines/fanuc.json"));
    write(mine, R"({"extends": "base.json", "description": "mine"})");
    const std::string base_before = test::read_file(base.string()), mine_before = test::read_file(mine.string());
    for (const fs::path& target : {base, mine}) {
        const test::Run r = test::run({plate, "--machine", mine.string(), "-o", target.string()});
        CHECK(r.code == 2);
        CHECK(contains(r.err, "-o " + target.string() + " would replace the machine file " + target.string()));
    }
    CHECK(test::read_file(base.string()) == base_before);
    CHECK(test::read_file(mine.string()) == mine_before);
    // The same machine posts where the output is another file.
    CHECK(test::run({plate, "--machine", mine.string(), "-o", (dir / "p.nc").string()}).code == 0);
}

TEST_CASE("verify: --plot onto the program, the job or the tool table is a usage error; each file is untouched") {
    const fs::path dir = test::scratch("inputs-verify");
    const fs::path program = dir / "p.nc", job = job_copy(dir), table = dir / "tool.tbl";
    write(program, test::read_file(source_dir + "/tests/golden/fanuc/plate.nc"));
    write(table, "T1 P1 D10\n");
    const std::string p_before = test::read_file(program.string());
    struct Case {
        std::vector<std::string> args;
        std::string what;
    };
    const std::vector<Case> cases = {
        {{"verify", program.string(), "--machine", "fanuc", "--plot", program.string()}, "the program " + program.string()},
        {{"verify", program.string(), "--machine", "fanuc", "--job", job.string(), "--plot", job.string()},
         "the job " + job.string()},
        {{"verify", program.string(), "--machine", "fanuc", "--tool-table", table.string(), "--plot", table.string()},
         "the tool table " + table.string()},
    };
    for (const Case& c : cases) {
        const test::Run r = test::run(c.args);
        CHECK(r.code == 2);
        CHECK(contains(r.err, " would replace " + c.what + " (the same file)"));
        CHECK(r.out.empty());
    }
    CHECK(test::read_file(program.string()) == p_before);
    CHECK(test::read_file(table.string()) == "T1 P1 D10\n");
    CHECK(test::read_file(job.string()) == test::read_file(plate));
}

TEST_CASE("the binary: -o onto the job given as standard input, or through a symlink, exits 2 and leaves it") {
    const fs::path dir = test::scratch("inputs-binary-clash");
    const fs::path job = job_copy(dir);
    const std::string before = test::read_file(job.string());
    fs::create_symlink(job, dir / "link.json");
    const BinaryRun from_stdin = run_binary({"-", "--machine", "fanuc", "-o", job.string()}, {}, job.string());
    CHECK(from_stdin.code == 2);
    CHECK(contains(from_stdin.err, "would replace the job (standard input)"));
    const BinaryRun link = run_binary({(dir / "link.json").string(), "--machine", "wabeco", "-o", job.string()});
    CHECK(link.code == 2);
    const BinaryRun verify = run_binary({"verify", job.string(), "--machine", "fanuc", "--plot", (dir / "link.json").string()});
    CHECK(verify.code == 2);
    // Standard output appended to the job (`>> job.json`), or to verify's program.
    const BinaryRun appended = run_binary({job.string(), "--machine", "fanuc"}, {}, "", 60.0, job.string());
    CHECK(appended.code == 2);
    CHECK(appended.err == "camgen: standard output is the job " + job.string() +
                              " (the same file): camgen never writes over its input; send the output elsewhere\n");
    const fs::path program = dir / "p.nc";
    write(program, test::read_file(source_dir + "/tests/golden/fanuc/plate.nc"));
    const BinaryRun report = run_binary({"verify", program.string(), "--machine", "fanuc"}, {}, "", 60.0, program.string());
    CHECK(report.code == 2);
    CHECK(test::read_file(program.string()) == test::read_file(source_dir + "/tests/golden/fanuc/plate.nc"));
    CHECK(test::read_file(job.string()) == before);
    CHECK(fs::is_symlink(dir / "link.json"));
    // Standard output into another file is fine.
    write(dir / "out.nc", "");
    CHECK(run_binary({job.string(), "--machine", "fanuc"}, {}, "", 60.0, (dir / "out.nc").string()).code == 0);
    CHECK(test::read_file((dir / "out.nc").string()).rfind("%\nO1000", 0) == 0);
}

// ---- bounded reads ----

// The two cases that bound a child's peak memory run in a process of their own (ctest
// unit/input-memory, --no-skip): a child's ru_maxrss counts the test process it was forked
// from, which the other cases (the simulations, in-process) grow beyond the bound.
TEST_CASE("inputs without an end end quickly with exit 3 and the limit: /dev/zero as job, machine, extends, program" *
          doctest::skip()) {
    const fs::path dir = test::scratch("inputs-dev-zero");
    const std::string extends_zero = (dir / "zero.json").string();
    write(extends_zero, R"({"extends": "/dev/zero"})");
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"/dev/zero", "--machine", "fanuc"},
         "camgen: cannot read /dev/zero: it goes on longer than 1 GiB, the limit for an input (CAMGEN_MAX_INPUT_SIZE "
         "changes it)\n"},
        {{plate, "--machine", "/dev/zero"},
         "camgen: cannot read machine file /dev/zero: it goes on longer than 1 GiB, the limit for an input "
         "(CAMGEN_MAX_INPUT_SIZE changes it)\n"},
        {{plate, "--machine", extends_zero},
         "camgen: cannot read machine file /dev/zero: it is a character device, not a regular file (the extends of " +
             extends_zero + " names a file)\n"},
        {{"verify", "/dev/zero", "--machine", "fanuc"},
         "camgen: cannot read /dev/zero: line 1 is longer than 1 MiB, the limit for a line of a program\n"},
        {{"verify", "/dev/zero", "--machine", "fanuc", "--plot", (dir / "p.svg").string()},
         "camgen: cannot read /dev/zero: line 1 is longer than 1 MiB, the limit for a line of a program\n"},
        {{"verify", source_dir + "/tests/golden/fanuc/plate.nc", "--machine", "fanuc", "--tool-table", "/dev/zero"},
         "camgen: cannot read /dev/zero: line 1 is longer than 1 MiB, the limit for a line of a program\n"},
        {{"verify", source_dir + "/tests/golden/fanuc/plate.nc", "--machine", "fanuc", "--job", "/dev/zero"},
         "camgen: cannot read /dev/zero: it goes on longer than 1 GiB, the limit for an input (CAMGEN_MAX_INPUT_SIZE "
         "changes it)\n"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args);
        const BinaryRun r = run_binary(c.args, {}, "", 60.0);
        CHECK_FALSE(r.timed_out);
        CHECK(r.code == 3);
        CHECK(r.err == c.message);
        // Counted, not kept: never near the gigabyte it read (and never std::bad_alloc).
        CHECK(r.max_rss_kb < peak_limit_kb);
        CHECK(r.seconds < 30);
    }
    CHECK_FALSE(fs::exists(dir / "p.svg"));
}

TEST_CASE("an extends naming a FIFO is refused by its type at once; a FIFO or pipe as --machine or job still works") {
    const fs::path dir = test::scratch("inputs-fifo");
    const fs::path fifo = dir / "base-fifo.json";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    const std::string mine = (dir / "mine.json").string();
    write(mine, R"({"extends": "base-fifo.json"})");
    // No writer ever opens the FIFO: reading it would wait forever.
    const BinaryRun r = run_binary({plate, "--machine", mine}, {}, "", 20.0);
    CHECK_FALSE(r.timed_out);
    CHECK(r.code == 3);
    CHECK(r.err == "camgen: cannot read machine file " + (dir / "base-fifo.json").string() +
                       ": it is a FIFO (named pipe), not a regular file (the extends of " + mine + " names a file)\n");
    // A folder named by extends says so.
    fs::create_directories(dir / "folder.json");
    write(mine, R"({"extends": "folder.json"})");
    const test::Run folder = test::run({plate, "--machine", mine});
    CHECK(folder.code == 3);
    CHECK(folder.err == "camgen: cannot read machine file " + (dir / "folder.json").string() + ": Is a directory\n");
}

TEST_CASE("a regular file above the limit is refused by its size before it is read" * doctest::skip()) {
    const fs::path dir = test::scratch("inputs-sparse");
    // A sparse file of 1 GiB and a byte: its size says enough, nothing is read.
    const fs::path big = dir / "big.json";
    write(big, "{");
    fs::resize_file(big, (std::uint64_t{1} << 30) + 1);
    const BinaryRun r = run_binary({big.string(), "--machine", "fanuc"}, {}, "", 20.0);
    CHECK(r.code == 3);
    CHECK(r.err == "camgen: cannot read " + big.string() +
                       ": it is 1.0 GiB, larger than 1 GiB, the limit for an input (CAMGEN_MAX_INPUT_SIZE changes it)\n");
    CHECK(r.max_rss_kb < peak_limit_kb);
    const BinaryRun program = run_binary({"verify", big.string(), "--machine", "fanuc"}, {}, "", 20.0);
    CHECK(program.code == 3);
    CHECK(contains(program.err, "larger than 1 GiB, the limit for an input"));
    CHECK(program.max_rss_kb < peak_limit_kb);
    fs::remove(big);
}

TEST_CASE("CAMGEN_MAX_INPUT_SIZE sets the limit for every input: files, standard input, machine files, programs") {
    const fs::path dir = test::scratch("inputs-limit-env");
    const std::string job = test::read_file(plate);  // about 800 bytes
    REQUIRE(job.size() > 512);
    REQUIRE(job.size() < 1024);
    const std::string limit = "CAMGEN_MAX_INPUT_SIZE=512";
    const BinaryRun file = run_binary({plate, "--machine", "fanuc"}, {limit});
    CHECK(file.code == 3);
    CHECK(file.err == fmt::format("camgen: cannot read {}: it is {} bytes, larger than 512 bytes, the limit for an input "
                                  "(CAMGEN_MAX_INPUT_SIZE changes it)\n",
                                  plate, job.size()));
    const BinaryRun piped = run_binary({"-", "--machine", "fanuc"}, {limit}, plate);
    CHECK(piped.code == 3);  // standard input is a regular file here, but read as a stream
    CHECK(contains(piped.err, "cannot read <stdin>: it goes on longer than 512 bytes"));
    const BinaryRun kib = run_binary({plate, "--machine", "fanuc"}, {"CAMGEN_MAX_INPUT_SIZE=1k"});
    CHECK(kib.code == 0);
    const BinaryRun machine = run_binary({plate, "--machine", source_dir + "/machines/fanuc.json"}, {"CAMGEN_MAX_INPUT_SIZE=100"});
    CHECK(machine.code == 3);
    CHECK(contains(machine.err, "cannot read machine file " + source_dir + "/machines/fanuc.json: it is"));
    const std::string program = source_dir + "/tests/golden/fanuc/plate.nc";
    const BinaryRun verify = run_binary({"verify", "-", "--machine", "fanuc"}, {"CAMGEN_MAX_INPUT_SIZE=100"}, program);
    CHECK(verify.code == 3);
    CHECK(contains(verify.err, "cannot read <stdin>: it goes on longer than 100 bytes"));
    // At the limit is within it; the default needs no variable.
    CHECK(run_binary({plate, "--machine", "fanuc"}, {fmt::format("CAMGEN_MAX_INPUT_SIZE={}", job.size())}).code == 0);
    CHECK(run_binary({plate, "--machine", "fanuc"}, {"CAMGEN_MAX_INPUT_SIZE=4M"}).code == 0);
    const BinaryRun bad = run_binary({plate, "--machine", "fanuc"}, {"CAMGEN_MAX_INPUT_SIZE=lots"});
    CHECK(bad.code == 2);
    CHECK(bad.err == "camgen: CAMGEN_MAX_INPUT_SIZE=lots: not a size (a number of bytes > 0, or with K, M or G for KiB, "
                     "MiB or GiB)\n");
}

TEST_CASE("a program line longer than 1 MiB is refused naming the line, streamed or kept") {
    const fs::path dir = test::scratch("inputs-long-line");
    const fs::path program = dir / "long.nc";
    write(program, "%\nO1000\n(" + std::string(max_program_line + 10, 'x') + ")\nM30\n%\n");
    const test::Run streamed = test::run({"verify", program.string(), "--machine", "fanuc"});
    CHECK(streamed.code == 3);
    CHECK(streamed.err == "camgen: cannot read " + program.string() +
                              ": line 3 is longer than 1 MiB, the limit for a line of a program\n");
    const test::Run kept = test::run({"verify", "-", "--machine", "fanuc", "--plot", (dir / "p.svg").string()},
                                     test::read_file(program.string()));
    CHECK(kept.code == 3);
    CHECK(kept.err == "camgen: cannot read <stdin>: line 3 is longer than 1 MiB, the limit for a line of a program\n");
    CHECK_FALSE(fs::exists(dir / "p.svg"));
}

TEST_CASE("read_input: sizes, the NUL cut of JSON text, identities") {
    std::istringstream none;
    const fs::path dir = test::scratch("inputs-read-input");
    write(dir / "a.json", "{\"a\": 1}");
    const InputText a = read_input((dir / "a.json").string(), InputRules{.json = true}, none);
    CHECK(a.text == "{\"a\": 1}");
    REQUIRE(a.id);
    CHECK(a.id == regular_file_id((dir / "a.json").string()));
    CHECK_FALSE(a.cut);
    // A binary stream: kept up to 64 KiB, the rest counted.
    std::istringstream binary(std::string(1 << 20, '\0'));
    const InputText b = read_input("-", InputRules{.json = true}, binary);
    CHECK(b.cut);
    CHECK(b.text.size() <= (1u << 16));
    CHECK_FALSE(b.id);
    CHECK(size_text(1u << 30) == "1 GiB");
    CHECK(size_text(1536) == "1.5 KiB");
    CHECK(size_text(100) == "100 bytes");
    CHECK(max_input_size() == default_max_input_size);
}

// ---- files that are not JSON ----

TEST_CASE("file_kind tells drawings, models, programs and binary files from JSON with a mistake") {
    CHECK(file_kind("  0\nSECTION\n  2\nHEADER\n") == FileKind::dxf);
    CHECK(file_kind("999\ndxfrw 0.6.3\n  0\nSECTION\n") == FileKind::dxf);
    CHECK(file_kind(std::string("AutoCAD Binary DXF\r\n\x1a\0", 22)) == FileKind::dxf);
    CHECK(file_kind("<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\">") == FileKind::svg);
    CHECK(file_kind("<!DOCTYPE html>\n<html><body></body></html>") == FileKind::html);
    CHECK(file_kind("ISO-10303-21;\nHEADER;\n") == FileKind::step);
    CHECK(file_kind("solid part\n facet normal 0 0 1\n") == FileKind::stl);
    CHECK(file_kind("%PDF-1.7\n") == FileKind::pdf);
    CHECK(file_kind("PK\x03\x04rest") == FileKind::archive);
    CHECK(file_kind("") == FileKind::empty);
    CHECK(file_kind(" \n\t\n") == FileKind::empty);
    CHECK(file_kind(std::string("ab\0cd", 5)) == FileKind::binary);
    CHECK(file_kind("\xFF\xFE{\0") == FileKind::utf16);
    CHECK(file_kind("G0 X10 Y10\nG1 Z-1 F100\nM30\n") == FileKind::nc_program);
    CHECK(file_kind("0 BEGIN PGM PART MM\n1 L X+0 R0 FMAX\n") == FileKind::nc_program);
    // JSON with a mistake is left to the JSON error.
    CHECK(file_kind("{\"clearance\": 5,,}") == FileKind::unknown);
    CHECK(file_kind("[1, 2") == FileKind::unknown);
    CHECK(file_kind("clearance: 5\ntools: []\n") == FileKind::unknown);  // YAML
    CHECK(file_kind("G-code is fun\n") == FileKind::unknown);
}

TEST_CASE("every program camgen writes, given as a job, is named an NC program with the verify command") {
    int programs = 0;
    for (const auto& machine_dir : fs::directory_iterator(source_dir + "/tests/golden")) {
        if (!machine_dir.is_directory()) continue;
        for (const auto& f : fs::directory_iterator(machine_dir.path())) {
            if (f.path().extension() == ".err" || f.path().extension() == ".svg" || f.path().extension() == ".html") continue;
            CAPTURE(f.path());
            const test::Run r = test::run({f.path().string(), "--machine", "fanuc"});
            CHECK(r.code == 1);
            CHECK(r.err == "camgen: " + f.path().string() + ": this looks like an NC program, not a job; to check it: "
                               "camgen verify " + f.path().string() + " --machine fanuc\n");
            ++programs;
        }
    }
    CHECK(programs > 50);
}

TEST_CASE("a drawing, a model, a binary or an empty file given as a job or machine file is named as such") {
    const fs::path dir = test::scratch("inputs-kinds");
    write(dir / "part.dxf", "  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n  0\nENDSEC\n  0\nEOF\n");
    write(dir / "part.step", "ISO-10303-21;\nHEADER;\nENDSEC;\nEND-ISO-10303-21;\n");
    write(dir / "empty.json", "");
    write(dir / "blob.bin", std::string("\x7f" "ELF\x02\x01\x01\0\0\0\0", 12));
    const std::string svg = source_dir + "/samples/plate.svg";
    struct Case {
        std::string file;
        std::string job_message;
    };
    const std::vector<Case> cases = {
        {(dir / "part.dxf").string(),
         "a DXF drawing, not a job: camgen reads jobs in JSON (docs/job-format.md); name the drawing in a job, as a drill's "
         "\"drawing\" or a contour's or pocket's \"profile\": {\"dxf\": \"part.dxf\", \"layer\": ...}"},
        {svg, "an SVG drawing, not a job: camgen reads jobs in JSON (docs/job-format.md); SVG import is not built yet"},
        {(dir / "part.step").string(),
         "a STEP model, not a job: camgen reads jobs in JSON (docs/job-format.md); STEP import is not built yet"},
        {(dir / "empty.json").string(), "the file is empty: a job is a JSON object (docs/job-format.md)"},
        {(dir / "blob.bin").string(), "a binary file, not a job: camgen reads jobs in JSON text (docs/job-format.md)"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.file);
        const test::Run r = test::run({c.file, "--machine", "wabeco", "-o", (dir / "out.knc").string()});
        CHECK(r.code == 1);
        CHECK(r.err == "camgen: " + c.file + ": " + c.job_message + "\n");
        const test::Run v = test::run({"verify", source_dir + "/tests/golden/fanuc/plate.nc", "--machine", "fanuc", "--job", c.file});
        CHECK(v.code == 1);
        CHECK(v.err == "camgen: " + c.file + ": " + c.job_message + "\n");
        CHECK_THROWS_WITH_AS(read_job_file(c.file), (c.file + ": " + c.job_message).c_str(), InputError);
    }
    CHECK_FALSE(fs::exists(dir / "out.knc"));
    // As a machine file.
    const test::Run m = test::run({plate, "--machine", (dir / "part.dxf").string()});
    CHECK(m.code == 1);
    CHECK(m.err == "camgen: " + (dir / "part.dxf").string() +
                       ": a DXF drawing, not a machine file: camgen reads machine files in JSON (docs/machine-files.md)\n");
    const std::string program = source_dir + "/tests/golden/heidenhain/plate.h";
    const test::Run p = test::run({plate, "--machine", program});
    CHECK(p.code == 1);
    CHECK(p.err == "camgen: " + program + ": this looks like an NC program, not a machine file; to check it: camgen "
                                          "verify " + program + " --machine M\n");
    // From standard input.
    const test::Run s = test::run({"-", "--machine", "fanuc"}, test::read_file(source_dir + "/tests/golden/fanuc/plate.nc"));
    CHECK(s.err == "camgen: <stdin>: this looks like an NC program, not a job; to check it: camgen verify - --machine fanuc\n");
    // /dev/zero read within a smaller limit is a binary file.
    const BinaryRun zero = run_binary({"-", "--machine", "fanuc"}, {"CAMGEN_MAX_INPUT_SIZE=1M"}, "/dev/zero", 20.0);
    CHECK(zero.code == 3);
    write(dir / "zeros.json", std::string(1000, '\0'));
    const test::Run zeros = test::run({(dir / "zeros.json").string(), "--machine", "fanuc"});
    CHECK(zeros.code == 1);
    CHECK(contains(zeros.err, "a binary file, not a job"));
}

TEST_CASE("a job with a JSON mistake keeps its JSON message; a valid job is never judged by its first bytes") {
    const test::Run r = test::run({"-", "--machine", "fanuc"}, "{\"clearance\": 5,,}");
    CHECK(r.code == 1);
    CHECK(contains(r.err, "<stdin>:1: line 1, column 17: syntax error"));
    // Valid JSON that is no job object: its own message.
    const test::Run a = test::run({"-", "--machine", "fanuc"}, "[1, 2]");
    CHECK(a.code == 1);
    CHECK_FALSE(contains(a.err, "not a job"));
}

}  // namespace test_inputs
