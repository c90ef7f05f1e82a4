// -o respects the path it is given: a regular file is replaced atomically and keeps its mode,
// a new one gets 0666 less the umask, a symlink's target is written, an interrupted run leaves
// the old file and no temporary. (A FIFO or a device written into, never replaced, is a field
// failure: test_field_failures.cpp.)
#include <doctest/doctest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_output {

using namespace camgen;
namespace fs = std::filesystem;

namespace {

const std::string plate = CAMGEN_SOURCE_DIR "/samples/plate.json";

struct stat stat_of(const fs::path& p) {
    struct stat st {};
    REQUIRE(::lstat(p.c_str(), &st) == 0);
    return st;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// Files in `dir` whose name marks a camgen temporary.
int temporaries_in(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(".camgen-") != std::string::npos) ++n;
    return n;
}

// A job of a million holes, so that the program takes long enough to interrupt.
fs::path million_hole_job(const fs::path& dir) {
    const fs::path job = dir / "million.json";
    write(job, R"({"clearance": 10, "tools": [{"number": 1, "diameter": 3, "rpm": 3000}],
 "operations": [{"type": "drill", "tool": 1, "endDepth": 2, "plungingFeedrate": 100,
   "grid": {"origin": [0, 0], "countX": 1000, "countY": 1000, "spacingX": 1, "spacingY": 1}}]})");
    return job;
}

// Starts the camgen binary; returns its pid.
pid_t start_camgen(const std::vector<std::string>& args) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        std::vector<char*> argv{const_cast<char*>(camgen::test::camgen_binary())};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        const int devnull = ::open("/dev/null", O_WRONLY);
        ::dup2(devnull, 1);
        ::dup2(devnull, 2);
        ::execv(camgen::test::camgen_binary(), argv.data());
        ::_exit(127);
    }
    return pid;
}

// Waits (up to 20 s) until a temporary appears in `dir`.
bool wait_for_temporary(const fs::path& dir) {
    for (int i = 0; i < 2000; ++i) {
        if (temporaries_in(dir) > 0) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

}  // namespace

TEST_CASE("-o: an existing regular file is replaced atomically and keeps its mode") {
    const fs::path dir = test::scratch("output-regular");
    const fs::path out = dir / "part.nc";
    write(out, "old\n");
    REQUIRE(::chmod(out.c_str(), 0640) == 0);
    const ino_t before = stat_of(out).st_ino;
    const test::Run r = test::run({plate, "--machine", "fanuc", "-o", out.string()});
    REQUIRE(r.code == 0);
    const struct stat st = stat_of(out);
    CHECK(S_ISREG(st.st_mode));
    CHECK((st.st_mode & 07777) == 0640);
    CHECK(st.st_ino != before);  // a new file took its place: no reader ever saw half of it
    CHECK(test::read_file(out.string()).rfind("%\nO1000", 0) == 0);
    CHECK(temporaries_in(dir) == 0);
}

TEST_CASE("-o: a new file gets 0666 less the umask") {
    const fs::path dir = test::scratch("output-new");
    const mode_t old_mask = ::umask(027);
    const test::Run r = test::run({plate, "--machine", "fanuc", "-o", (dir / "a.nc").string()});
    ::umask(022);
    const test::Run r2 = test::run({plate, "--machine", "fanuc", "-o", (dir / "b.nc").string()});
    ::umask(old_mask);
    REQUIRE(r.code == 0);
    REQUIRE(r2.code == 0);
    CHECK((stat_of(dir / "a.nc").st_mode & 07777) == 0640);
    CHECK((stat_of(dir / "b.nc").st_mode & 07777) == 0644);
}

TEST_CASE("-o: a symlink is followed, its target replaced, the link kept") {
    const fs::path dir = test::scratch("output-symlink");
    fs::create_directories(dir / "share");
    write(dir / "share" / "part.nc", "old\n");
    fs::create_symlink("share/part.nc", dir / "link.nc");
    REQUIRE(test::run({plate, "--machine", "fanuc", "-o", (dir / "link.nc").string()}).code == 0);
    CHECK(fs::is_symlink(fs::symlink_status(dir / "link.nc")));
    CHECK(test::read_file((dir / "share" / "part.nc").string()).rfind("%\nO1000", 0) == 0);
    CHECK(temporaries_in(dir) == 0);
    CHECK(temporaries_in(dir / "share") == 0);
    // A dangling link: the file it names is created.
    fs::create_symlink("share/new.nc", dir / "dangling.nc");
    REQUIRE(test::run({plate, "--machine", "fanuc", "-o", (dir / "dangling.nc").string()}).code == 0);
    CHECK(fs::is_regular_file(dir / "share" / "new.nc"));
    CHECK(fs::is_symlink(fs::symlink_status(dir / "dangling.nc")));
}

TEST_CASE("-o: a write that fails names the file and the system's reason, exit 3") {
    const fs::path dir = test::scratch("output-fail");
    const test::Run full = test::run({plate, "--machine", "fanuc", "-o", "/dev/full"});
    CHECK(full.code == 3);
    CHECK(full.err.find("cannot write /dev/full: No space left on device") != std::string::npos);
    const test::Run is_dir = test::run({plate, "--machine", "fanuc", "-o", dir.string()});
    CHECK(is_dir.code == 3);
    CHECK(is_dir.err.find("cannot write " + dir.string() + ": Is a directory") != std::string::npos);
    const test::Run no_dir = test::run({plate, "--machine", "fanuc", "-o", (dir / "missing" / "a.nc").string()});
    CHECK(no_dir.code == 3);
    CHECK(no_dir.err.find("No such file or directory") != std::string::npos);
}

TEST_CASE("-o: SIGINT or SIGTERM in the middle of a million holes leaves the old file and no temporary") {
    const fs::path dir = test::scratch("output-signal");
    const fs::path job = million_hole_job(dir);
    const fs::path out = dir / "part.nc";
    for (int sig : {SIGINT, SIGTERM}) {
        CAPTURE(sig);
        write(out, "old program\n");
        const pid_t pid = start_camgen({job.string(), "--machine", "fanuc", "-o", out.string()});
        REQUIRE(wait_for_temporary(dir));
        ::kill(pid, sig);
        int status = 0;
        REQUIRE(::waitpid(pid, &status, 0) == pid);
        // Either the signal ended it (and the handler removed the temporary) or it had just finished.
        if (WIFSIGNALED(status)) {
            CHECK(WTERMSIG(status) == sig);
            CHECK(test::read_file(out.string()) == "old program\n");
        }
        CHECK(temporaries_in(dir) == 0);
    }
}

TEST_CASE("-o: after SIGKILL the old file is intact and the next run removes the stale temporary") {
    const fs::path dir = test::scratch("output-kill");
    const fs::path job = million_hole_job(dir);
    const fs::path out = dir / "part.nc";
    write(out, "old program\n");
    const pid_t pid = start_camgen({job.string(), "--machine", "fanuc", "-o", out.string()});
    REQUIRE(wait_for_temporary(dir));
    ::kill(pid, SIGKILL);
    int status = 0;
    REQUIRE(::waitpid(pid, &status, 0) == pid);
    REQUIRE(WIFSIGNALED(status));
    CHECK(test::read_file(out.string()) == "old program\n");
    CHECK(temporaries_in(dir) == 1);  // what a killed process leaves
    REQUIRE(test::run({plate, "--machine", "fanuc", "-o", out.string()}).code == 0);
    CHECK(temporaries_in(dir) == 0);
    CHECK(test::read_file(out.string()).rfind("%\nO1000", 0) == 0);
}

TEST_CASE("--plot follows the same rules: into a FIFO, and a failed plot names its file") {
    const fs::path dir = test::scratch("output-plot");
    const fs::path fifo = dir / "plot.svg";
    REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
    std::string received;
    std::thread reader([&] { received = test::read_file(fifo.string()); });
    const test::Run r = test::run({plate, "--machine", "fanuc", "-o", (dir / "p.nc").string(), "--plot", fifo.string()});
    reader.join();
    CHECK(r.code == 0);
    CHECK(S_ISFIFO(stat_of(fifo).st_mode));
    CHECK(received.find("<svg") != std::string::npos);
}

namespace {
// Runs the camgen binary with standard output sent to `stdout_path`; returns its exit code.
int run_binary_to(const std::string& args, const std::string& stdout_path) {
    const std::string cmd = std::string(camgen::test::camgen_binary()) + " " + args + " > " + stdout_path + " 2>/dev/null";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

TEST_CASE("every write is checked: --events, the program, verify, schema and the machine list to a full disk exit 3") {
    const std::string dir = CAMGEN_SOURCE_DIR;
    CHECK(run_binary_to(plate + " --events", "/dev/full") == 3);
    CHECK(run_binary_to(plate + " --machine fanuc", "/dev/full") == 3);
    CHECK(run_binary_to("verify " + dir + "/tests/golden/fanuc/plate.nc --machine fanuc", "/dev/full") == 3);
    CHECK(run_binary_to("verify " + dir + "/tests/golden/fanuc/plate.nc --machine fanuc --job " + plate, "/dev/full") == 3);
    CHECK(run_binary_to("schema job", "/dev/full") == 3);
    CHECK(run_binary_to("--list-machines", "/dev/full") == 3);
    CHECK(run_binary_to("--describe-machine fanuc", "/dev/full") == 3);
    // and the same commands succeed where the write succeeds
    CHECK(run_binary_to(plate + " --events", "/dev/null") == 0);
    CHECK(run_binary_to("schema job", "/dev/null") == 0);
}

TEST_CASE("a --plot that cannot be written leaves -o as it was: nothing is committed before everything is written") {
    const fs::path dir = test::scratch("output-plot-order");
    const fs::path out = dir / "part.nc";
    write(out, "old program\n");
    const test::Run r = test::run({plate, "--machine", "fanuc", "-o", out.string(), "--plot", (dir / "missing" / "p.svg").string()});
    CHECK(r.code == 3);
    CHECK(r.err.find("cannot write " + (dir / "missing" / "p.svg").string() + ": No such file or directory") != std::string::npos);
    CHECK(test::read_file(out.string()) == "old program\n");
    CHECK(temporaries_in(dir) == 0);
    // A new -o file is not created either.
    const test::Run r2 = test::run({plate, "--machine", "fanuc", "-o", (dir / "new.nc").string(), "--plot", (dir / "missing" / "p.svg").string()});
    CHECK(r2.code == 3);
    CHECK_FALSE(fs::exists(dir / "new.nc"));
}

TEST_CASE("a program posted straight into its temporary file: a refusal after text was written leaves nothing") {
    // 20,000 holes are posted (the post hands its text to the file as it goes), then the second
    // operation is refused by the safety check: too deep for the tool's flutes.
    std::string holes;
    for (int i = 0; i < 20000; ++i) holes += fmt::format("{}[{}, {}]", i ? ", " : "", i % 200 * 2, i / 200 * 2);
    const std::string job_text = fmt::format(
        R"({{"clearance": 20, "tools": [{{"number": 1, "diameter": 1, "rpm": 2000}}, {{"number": 2, "diameter": 3, "rpm": 2000, "fluteLength": 20}}],
  "operations": [{{"type": "drill", "tool": 1, "retractPlane": 5, "endDepth": 3, "plungingFeedrate": 100, "holes": [{}]}},
                 {{"type": "drill", "tool": 2, "retractPlane": 5, "endDepth": 25, "plungingFeedrate": 100, "holes": [[1, 1]]}}]}})",
        holes);
    const fs::path dir = test::scratch("output-streamed");
    write(dir / "job.json", job_text);
    const fs::path out = dir / "part.nc";
    write(out, "old program\n");
    for (const char* machine : {"wabeco", "grbl", "fanuc"}) {
        CAPTURE(machine);
        const test::Run r = test::run({(dir / "job.json").string(), "--machine", machine, "-o", out.string()});
        CHECK(r.code == 1);
        CHECK(r.err.find("/operations/1/endDepth: the hole is 25.000 mm deep") != std::string::npos);
        CHECK(test::read_file(out.string()) == "old program\n");
        CHECK(temporaries_in(dir) == 0);
        // To standard output, which cannot take text back, nothing is written either.
        const test::Run s = test::run({(dir / "job.json").string(), "--machine", machine});
        CHECK(s.code == 1);
        CHECK(s.out.empty());
    }
    // And the same job without the refused operation is written whole.
    const std::string good = job_text.substr(0, job_text.find(",\n                 {")) + "]}";
    write(dir / "good.json", good);
    REQUIRE(test::run({(dir / "good.json").string(), "--machine", "wabeco", "-o", out.string()}).code == 0);
    const std::string program = test::read_file(out.string());
    CHECK(program.size() > 200000);
    CHECK(program == test::run({(dir / "good.json").string(), "--machine", "wabeco"}).out);  // held whole, then written
    CHECK(temporaries_in(dir) == 0);
}

}  // namespace test_output
