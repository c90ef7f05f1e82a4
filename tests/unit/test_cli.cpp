// The command line: exit codes, messages with JSON path and line, atomic output files.
#include <filesystem>
#include <fstream>

#include <doctest/doctest.h>
#include <unistd.h>

#include "camgen/cli/cli.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_cli {

namespace fs = std::filesystem;
using namespace camgen;
using test::Run;
using test::run;

namespace {

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

const std::string sample = CAMGEN_SOURCE_DIR "/samples/plate.json";

}  // namespace

TEST_CASE("posting a sample to stdout and to a file") {
    Run r = run({sample, "--machine", "wabeco"});
    CHECK(r.code == 0);
    CHECK(r.out.rfind("_\n_\n", 0) == 0);
    fs::path dir = test::scratch("cli-ok");
    Run f = run({sample, "--machine", "fanuc", "-o", (dir / "plate.nc").string()});
    CHECK(f.code == 0);
    CHECK(test::read_file((dir / "plate.nc").string()).rfind("%\nO1000", 0) == 0);
    // Only the program is left in the folder: no temporary files.
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}) == 1);
}

TEST_CASE("a job from standard input") {
    Run r = run({"-", "--machine", "fanuc"}, test::read_file(sample));
    CHECK(r.code == 0);
    CHECK(r.out.find("G81") != std::string::npos);
}

namespace {

// A pipe holding `text` (written whole, the writing end closed), named as the shell's <(...)
// names it: /dev/fd/N. Reading it again gives nothing, as with a FIFO's writer gone.
class PipeFile {
public:
    explicit PipeFile(const std::string& text) {
        REQUIRE(::pipe(fds_) == 0);
        REQUIRE(text.size() < 65536);  // a pipe's buffer: the write must not wait for a reader
        REQUIRE(::write(fds_[1], text.data(), text.size()) == static_cast<ssize_t>(text.size()));
        ::close(fds_[1]);
    }
    ~PipeFile() { ::close(fds_[0]); }
    std::string path() const { return "/dev/fd/" + std::to_string(fds_[0]); }

private:
    int fds_[2]{-1, -1};
};

}  // namespace

TEST_CASE("a job and a program from pipes (<(...)): read once, as a stream, and kept for the passes that need them") {
    const std::string drilling = test::read_file(CAMGEN_SOURCE_DIR "/samples/drilling.json");
    const Run from_file = run({CAMGEN_SOURCE_DIR "/samples/drilling.json", "--machine", "grbl"});
    REQUIRE(from_file.code == 0);
    {
        // It could not seek to the end for the size: "cannot read /dev/fd/N: Illegal seek".
        PipeFile job(drilling);
        const Run r = run({job.path(), "--machine", "grbl"});
        CHECK(r.code == 0);
        CHECK(r.err == "");
        CHECK(r.out == from_file.out);
    }
    {
        // A machine file from a pipe was loaded three times (the usage check, the post, the
        // read-back): "line 1, column 1: syntax error ... unexpected end of input".
        PipeFile machine(test::read_file(CAMGEN_SOURCE_DIR "/machines/grbl.json"));
        const Run r = run({CAMGEN_SOURCE_DIR "/samples/drilling.json", "--machine", machine.path(), "--stats"});
        CHECK(r.code == 0);
        CHECK(r.out == from_file.out);
        CHECK(r.err.find("holes          25\n") != std::string::npos);
    }
    // verify with --job and --plot reads the program three times: a pipe's text is kept, as
    // standard input's is (the second pass read nothing: "the program does not end with M2").
    const fs::path dir = test::scratch("cli-pipes");
    const std::string plot = (dir / "p.html").string(), again = (dir / "f.html").string(), program = (dir / "p.nc").string();
    write(program, from_file.out);
    PipeFile job(drilling), nc(from_file.out);
    const Run r = run({"verify", nc.path(), "--machine", "grbl", "--job", job.path(), "--plot", plot});
    CHECK(r.code == 0);
    CHECK(r.out.find("matches job /dev/fd/") != std::string::npos);
    REQUIRE(run({"verify", program, "--machine", "grbl", "--plot", again}).code == 0);
    // The same page, but for the title (which the drawing shows too).
    const std::string a = test::read_file(plot), b = test::read_file(again);
    REQUIRE(a.find("<g stroke") != std::string::npos);
    CHECK(a.substr(a.find("<g stroke")) == b.substr(b.find("<g stroke")));
}

TEST_CASE("--events prints one JSON object per line") {
    Run r = run({sample, "--events"});
    CHECK(r.code == 0);
    auto lines = test::lines_of(r.out);
    REQUIRE(lines.size() > 5);
    for (const auto& l : lines) CHECK(nlohmann::json::parse(l).contains("event"));
    CHECK(nlohmann::json::parse(lines[0])["event"] == "operation-start");
    CHECK(r.out.find(R"({"event":"drill-point","at":[90.0,40.0]})") != std::string::npos);
}

TEST_CASE("--list-machines and --describe-machine") {
    Run r = run({"--list-machines"});
    CHECK(r.code == 0);
    CHECK(r.out.find("wabeco") != std::string::npos);
    CHECK(r.out.find("fanuc") != std::string::npos);
    Run d = run({"--describe-machine", "wabeco"});
    CHECK(d.code == 0);
    CHECK(d.out.find("canned G81") != std::string::npos);
    CHECK(d.out.find("0.1 mm/s") != std::string::npos);
}

TEST_CASE("usage errors exit 2") {
    CHECK(run({}).code == 2);
    CHECK(run({sample}).code == 2);  // no machine
    Run u = run({sample, "--machine", "wabecco"});
    CHECK(u.code == 2);
    CHECK(u.err.find("did you mean \"wabeco\"") != std::string::npos);
    CHECK(run({sample, "--machine", "fanuc", "--bogus"}).code == 2);
    // A snippet has no program end: it cannot be read back as a whole program.
    Run s = run({sample, "--machine", "fanuc", "--snippet", "--stats"});
    CHECK(s.code == 2);
    CHECK(s.err == "camgen: --plot and --stats read the program back: a --snippet is not a whole program\n");
    CHECK(run({"--version"}).code == 0);
}

TEST_CASE("an invalid job exits 1 with path and line, and -o leaves no file behind") {
    fs::path dir = test::scratch("cli-bad");
    struct Case {
        const char* name;
        std::string json;
        std::string expect;
    };
    std::string good = test::read_file(sample);
    std::vector<Case> cases = {
        {"wrong type", R"({"clearance": "high", "tools": [], "operations": []})", "/clearance"},
        {"unknown key", "{\n \"clearance\": 5,\n \"tols\": []\n}", ":3: /tols: unknown key \"tols\" (did you mean \"tools\"?)"},
        {"missing tool", R"({"clearance": 5, "tools": [{"number": 1, "diameter": 3, "rpm": 100}],
"operations": [{"type": "drill", "tool": 2, "endDepth": 1, "plungingFeedrate": 10, "holes": [[0,0]]}]})",
         ":2: /operations/0/tool"},
        {"NaN", R"({"clearance": NaN})", "NaN"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        fs::path job = dir / "job.json";
        write(job, c.json);
        fs::path out = dir / "out.knc";
        Run r = run({job.string(), "--machine", "wabeco", "-o", out.string()});
        CHECK(r.code == 1);
        CHECK(r.err.find(c.expect) != std::string::npos);
        CHECK(r.err.find("job.json") != std::string::npos);
        CHECK(!fs::exists(out));
        CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}) == 1);
    }
}

TEST_CASE("an error while posting keeps an existing output file and names the line") {
    fs::path dir = test::scratch("cli-keep");
    fs::path out = dir / "part.knc";
    write(out, "previous program\n");
    fs::path job = dir / "job.json";
    write(job, R"({"clearance": 5,
"tools": [{"number": 1, "diameter": 6, "rpm": 2000, "direction": "ccw"}],
"operations": [
  {"type": "drill", "tool": 1, "endDepth": 3, "plungingFeedrate": 50, "holes": [[0, 0]]}]})");
    Run r = run({job.string(), "--machine", "wabeco", "-o", out.string()});
    CHECK(r.code == 1);
    CHECK(r.err.find("job.json:4: /operations/0") != std::string::npos);
    CHECK(test::read_file(out.string()) == "previous program\n");
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}) == 2);
}

TEST_CASE("an unreadable job or unwritable output exits 3") {
    CHECK(run({"/nonexistent/job.json", "--machine", "fanuc"}).code == 3);
    CHECK(run({sample, "--machine", "fanuc", "-o", "/nonexistent/dir/out.nc"}).code == 3);
    // A folder given as a file: named, not read as an empty text ("unexpected end of input",
    // "the program does not end with M2 or M30", or std::bad_alloc).
    const fs::path dir = test::scratch("cli-folder-args") / "a.json";
    fs::create_directories(dir);
    const std::string folder = dir.string(), program = CAMGEN_SOURCE_DIR "/tests/golden/fanuc/plate.nc";
    const std::vector<std::vector<std::string>> runs = {
        {folder, "--machine", "fanuc"},
        {"verify", folder, "--machine", "fanuc"},
        {"verify", folder, "--machine", "fanuc", "--plot", (dir.parent_path() / "p.svg").string()},
        {"verify", program, "--machine", "fanuc", "--job", folder},
    };
    for (const auto& args : runs) {
        const Run r = run(args);
        CHECK(r.code == 3);
        CHECK(r.err == "camgen: cannot read " + folder + ": Is a directory\n");
    }
    const Run m = run({sample, "--machine", folder});
    CHECK(m.code == 3);
    CHECK(m.err == "camgen: cannot read machine file " + folder + ": Is a directory\n");
}

TEST_CASE("--machine takes the path of a machine file: no sequence numbers; a decimal comma is refused on ISO") {
    fs::path dir = test::scratch("cli-machine-path");
    std::string text = test::read_file(CAMGEN_SOURCE_DIR "/machines/fanuc.json");
    auto replace = [&](const std::string& from, const std::string& to) {
        auto at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    };
    replace("\"decimalMark\": \".\"", "\"decimalMark\": \",\"");
    replace("\"showSequenceNumbers\": true", "\"showSequenceNumbers\": false");
    write(dir / "myfanuc.json", text);
    Run r = run({sample, "--machine", (dir / "myfanuc.json").string()});
    CHECK(r.code == 1);
    CHECK(r.err.find((dir / "myfanuc.json").string() + ":8: /globals/decimalMark: the iso dialect's controls read a decimal "
                     "point only") != std::string::npos);
    replace("\"decimalMark\": \",\"", "\"decimalMark\": \".\"");
    write(dir / "myfanuc.json", text);
    r = run({sample, "--machine", (dir / "myfanuc.json").string()});
    CHECK(r.code == 0);
    CHECK(r.out.find("G99 G81 X10.000 Y10.000 Z-1.500 R2.000 F80\n") != std::string::npos);
    CHECK(r.out.find("\nN") == std::string::npos);
}

TEST_CASE("a broken machine file exits 1 naming the machine file, the JSON path and the line") {
    fs::path dir = test::scratch("cli-machine-bad");
    write(dir / "bad.json", "{\n  \"description\": \"x\",\n  \"dialect\": \"iso\",\n  \"extension\": \"nc\",\n"
                            "  \"limits\": {\"maxFeed\": -5}\n}\n");
    Run r = run({sample, "--machine", (dir / "bad.json").string(), "-o", (dir / "out.nc").string()});
    CHECK(r.code == 1);
    CHECK(r.err.find("bad.json:5: /limits/maxFeed: maxFeed must be > 0") != std::string::npos);
    CHECK(!fs::exists(dir / "out.nc"));
    write(dir / "typo.json", "{\"description\": \"x\", \"dialect\": \"iso\", \"extension\": \"nc\", \"limts\": {}}");
    Run t = run({sample, "--machine", (dir / "typo.json").string()});
    CHECK(t.code == 1);
    CHECK(t.err.find("unknown key \"limts\" (did you mean \"limits\"?)") != std::string::npos);
}

TEST_CASE("--units inch on a machine whose control has no inch mode is refused, naming the machine") {
    // nccad has no unit word: inch numbers would be read as mm, a part 25.4 times too small.
    for (const char* name : {"wabeco", "kosy"}) {
        CAPTURE(name);
        Run r = run({sample, "--machine", name, "--units", "inch"});
        CHECK(r.code == 2);
        CHECK(r.out.empty());
        CHECK(r.err.find(std::string("machine ") + name + " has no inch mode") != std::string::npos);
        Run v = run({"verify", CAMGEN_SOURCE_DIR "/tests/golden/wabeco/plate.knc", "--machine", name, "--units", "inch"});
        CHECK(v.code == 2);
    }
    Run ok = run({sample, "--machine", "linuxcnc", "--units", "inch"});
    CHECK(ok.code == 0);
    CHECK(ok.out.find("G20") != std::string::npos);
    Run d = run({"--describe-machine", "wabeco"});
    CHECK(d.out.find("acceptedUnits") != std::string::npos);
}

TEST_CASE("a machine file whose units are not among its acceptedUnits is refused") {
    fs::path dir = test::scratch("cli-units");
    std::string text = test::read_file(CAMGEN_SOURCE_DIR "/machines/wabeco.json");
    const std::string from = "\"units\": \"mm\"";
    text.replace(text.find(from), from.size(), "\"units\": \"inch\"");
    write(dir / "wabeco-inch.json", text);
    Run r = run({sample, "--machine", (dir / "wabeco-inch.json").string()});
    CHECK(r.code == 1);
    CHECK(r.err.find("/units") != std::string::npos);
    CHECK(r.err.find("acceptedUnits") != std::string::npos);
}

}  // namespace test_cli
