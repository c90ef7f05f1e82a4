// Machine files a user extends (issue 14 part 2): the user's folders (CAMGEN_MACHINES, then
// $XDG_CONFIG_HOME/camgen/machines) before the built-in machines, "extends" as a JSON merge
// patch over another machine, --list-machines with each machine's source, and
// --describe-machine M --json printing the complete machine file.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "machines/iso/iso_settings.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_machine_files {

using namespace camgen;
using namespace camgen::test;

namespace {

namespace fs = std::filesystem;

// Sets an environment variable for one test and puts the old value back.
class EnvGuard {
public:
    EnvGuard(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        setenv(name, value.c_str(), 1);
    }
    ~EnvGuard() {
        if (old_) setenv(name_, old_->c_str(), 1);
        else unsetenv(name_);
    }
    EnvGuard(const EnvGuard&) = delete;
    EnvGuard& operator=(const EnvGuard&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

// A user's configuration: XDG_CONFIG_HOME at a scratch folder, CAMGEN_MACHINES unset unless
// `camgen_machines` is given. machines() is the XDG machine folder.
struct UserConfig {
    explicit UserConfig(const std::string& name, const std::string& camgen_machines = "")
        : root(scratch("machines-" + name)), xdg("XDG_CONFIG_HOME", root.string()),
          env("CAMGEN_MACHINES", camgen_machines) {
        fs::create_directories(machines());
    }
    fs::path machines() const { return root / "camgen" / "machines"; }
    std::string write(const std::string& file, const std::string& text) const {
        const fs::path p = machines() / file;
        std::ofstream(p) << text;
        return p.string();
    }
    fs::path root;
    EnvGuard xdg, env;
};

std::string post(const std::string& machine, const std::string& job_file) {
    const Run r = run({job_file, "--machine", machine, "-q"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    return r.out;
}

// The samples' plate job (holes, canned and longhand) and its contour.
std::string plate_job() { return std::string(CAMGEN_SOURCE_DIR) + "/samples/plate.json"; }

}  // namespace

TEST_CASE("a user machine that extends wabeco with block numbers and a decimal comma changes exactly those words") {
    // (An ISO machine refuses the comma: its controls read a decimal point only, test_machine_checks.)
    UserConfig user("seq-comma");
    user.write("shopmill.json", R"({"extends": "wabeco", "description": "our mill",
        "globals": {"decimalMark": ",", "showSequenceNumbers": true, "sequenceNumberStart": 10, "sequenceNumberIncrement": 10}})");
    const std::vector<std::string> base = lines_of(post("wabeco", plate_job()));
    const std::vector<std::string> mine = lines_of(post("shopmill", plate_job()));
    REQUIRE(base.size() == mine.size());
    int numbered = 0, with_comma = 0, with_point = 0;
    for (std::size_t i = 0; i < base.size(); ++i) {
        CAPTURE(base[i]);
        CAPTURE(mine[i]);
        std::string line = mine[i];
        // Block numbers: N10, N20, ... on every block that is not a comment or the % line.
        const std::string number = fmt::format("N{} ", 10 * (numbered + 1));
        if (line.starts_with(number)) {
            line = line.substr(number.size());
            ++numbered;
        }
        // Comments and M01 messages (the operator's text) keep their own commas and points, and
        // so does the spindle's output word M10 O6.1 (a port and its bit, not a number).
        const bool text = line.find(';') != std::string::npos || line.starts_with("M01") || line.find(" O6.") != std::string::npos;
        if (line.find(',') != std::string::npos && !text) ++with_comma;
        if (base[i].find('.') != std::string::npos && !text) ++with_point;
        std::string restored = line;
        if (!text) std::replace(restored.begin(), restored.end(), ',', '.');
        CHECK(restored == base[i]);
    }
    CHECK(numbered > static_cast<int>(base.size()) / 2);
    // Every decimal point of wabeco's blocks became a comma, and no other word changed.
    CHECK(with_comma == with_point);
    CHECK(with_comma >= 2);
}

TEST_CASE("an extension of an extension applies both, the nearer file winning") {
    UserConfig user("chain");
    user.write("base-shop.json", R"({"extends": "fanuc", "description": "shop fanuc", "settings": {"programNumber": 4242},
        "limits": {"maxRpm": 8000}})");
    user.write("cell-3.json", R"({"extends": "base-shop", "settings": {"programNumber": 4343}})");
    const Machine m = load_machine("cell-3");
    CHECK(m.name == "cell-3");
    CHECK(m.description == "shop fanuc");
    CHECK(m.limits.max_rpm == 8000);
    CHECK(m.dialect == "iso");
    const std::string out = post("cell-3", plate_job());
    CHECK(out.find("O4343") != std::string::npos);
    CHECK(out.find("O4242") == std::string::npos);
    // Everything else is fanuc's.
    std::string fanuc = post("fanuc", plate_job());
    const auto at = fanuc.find("O1000");
    REQUIRE(at != std::string::npos);
    fanuc.replace(at, 5, "O4343");
    CHECK(out == fanuc);
}

TEST_CASE("an extension's dialect settings merge over its base's, and their errors name its file and line") {
    UserConfig user("settings");
    // Settings merge key by key: the lathe keeps fanuc-lathe's turret and spindle limit.
    user.write("shop-lathe.json", "{\"extends\": \"fanuc-lathe\",\n \"settings\": {\"programNumber\": 77}}");
    const Machine lathe = load_machine("shop-lathe");
    const auto& s = settings_of<iso::LatheSettings>(lathe);
    CHECK(s.program_number == 77);
    CHECK(s.tool_call == iso::LatheToolCall::turret);
    CHECK(s.spindle_limit);
    CHECK_FALSE(s.percent == settings_of<iso::Settings>(load_machine("linuxcnc-lathe")).percent);
    // A key of the lathe variant's dialect on a mill that extends fanuc: the user's file and line.
    const std::string mill = user.write("shop-mill.json", "{\"extends\": \"fanuc\",\n \"settings\":\n {\"toolCall\": \"turret\"}}");
    try {
        load_machine("shop-mill");
        FAIL("shop-mill was accepted");
    } catch (const InputError& e) {
        CHECK(e.source() == mill);
        CHECK(e.line() == 3);
        CHECK(e.path() == "/settings/toolCall");
        CHECK(e.detail().find("a setting of dialect iso-lathe, not of this machine's dialect iso") != std::string::npos);
    }
    // A misspelt key two files down the chain is named in the file that holds it.
    const std::string cell = user.write("cell.json", "{\"extends\": \"shop-lathe\",\n \"settings\": {\"spindleLimt\": false}}");
    try {
        load_machine("cell");
        FAIL("cell was accepted");
    } catch (const InputError& e) {
        CHECK(e.source() == cell);
        CHECK(e.line() == 2);
        CHECK(e.detail() == "unknown key \"spindleLimt\" (did you mean \"spindleLimit\"?)");
    }
}

TEST_CASE("a cycle of extensions is an error naming the files") {
    UserConfig user("cycle");
    const std::string a = user.write("mill-a.json", R"({"extends": "mill-b", "description": "a"})");
    const std::string b = user.write("mill-b.json", R"({"extends": "mill-a.json"})");
    const Run r = run({plate_job(), "--machine", "mill-a"});
    CHECK(r.code == exit_invalid_input);
    CHECK(r.err.find("a cycle of extensions") != std::string::npos);
    CHECK(r.err.find(a) != std::string::npos);
    CHECK(r.err.find(b) != std::string::npos);
    CHECK(r.err.find("/extends") != std::string::npos);
    // A file that extends itself by path is the shortest cycle.
    const std::string self = user.write("selfish.json", R"({"extends": "./selfish.json"})");
    CHECK_THROWS_WITH_AS(load_machine("selfish"), doctest::Contains("a cycle of extensions"), InputError);
}

TEST_CASE("an error in an extending file names that file and line; one in the base names the base") {
    UserConfig user("errors");
    const std::string f = user.write("wrong.json", "{\n  \"extends\": \"fanuc\",\n  \"limits\": {\"maxFeed\": -5}\n}\n");
    try {
        load_machine("wrong");
        FAIL("accepted a negative maxFeed");
    } catch (const InputError& e) {
        CHECK(e.source() == f);
        CHECK(e.line() == 3);
        CHECK(e.path() == "/limits/maxFeed");
    }
    // An unknown key in the extending file: its own file and line.
    const std::string g = user.write("typo.json", "{\"extends\": \"fanuc\",\n \"globalz\": {}}\n");
    try {
        load_machine("typo");
        FAIL("accepted an unknown key");
    } catch (const InputError& e) {
        CHECK(e.source() == g);
        CHECK(e.line() == 2);
    }
    // An unknown machine to extend: the path /extends and the known names.
    user.write("orphan.json", R"({"extends": "fanuk"})");
    CHECK_THROWS_WITH_AS(load_machine("orphan"), doctest::Contains("did you mean \"fanuc\""), InputError);
    user.write("number.json", R"({"extends": 5})");
    CHECK_THROWS_WITH_AS(load_machine("number"), doctest::Contains("/extends"), InputError);
}

TEST_CASE("a user's file of a built-in's name replaces it, and extending its own name extends the built-in") {
    UserConfig user("shadow");
    user.write("grbl.json", R"({"extends": "grbl", "description": "our grbl", "settings": {"endCode": "M30"}})");
    const Machine m = load_machine("grbl");
    CHECK(m.description == "our grbl");
    CHECK(post("grbl", plate_job()).find("M30") != std::string::npos);
    const Run list = run({"--list-machines"});
    REQUIRE(list.code == 0);
    CHECK(list.out.find("our grbl  [" + (user.machines() / "grbl.json").string() + "]") != std::string::npos);
    CHECK(list.out.find("[built-in, replaced by the file of this name above]") != std::string::npos);
    // The known machines of a message name grbl once, though two files of that name exist.
    user.write("orphan.json", R"({"extends": "grbll"})");
    try {
        load_machine("orphan");
        FAIL("extended an unknown machine");
    } catch (const InputError& e) {
        const std::string what = e.what();
        CHECK(what.find("did you mean \"grbl\"") != std::string::npos);
        const auto known = what.substr(what.find("known machines:"));
        CHECK(known.find("grbl,") != std::string::npos);
        CHECK(known.find("grbl,") == known.rfind("grbl,"));
    }
}

TEST_CASE("CAMGEN_MACHINES folders come before the XDG folder, and --list-machines shows each machine's source") {
    const fs::path extra = scratch("machines-env-extra");
    UserConfig user("env", extra.string());
    std::ofstream(extra / "router.json") << R"({"extends": "grbl", "description": "router from CAMGEN_MACHINES"})";
    user.write("router.json", R"({"extends": "grbl", "description": "router from XDG"})");
    user.write("broken.json", R"({"extends": "grbl", "limits": {"maxFeed": "fast"}})");
    CHECK(load_machine("router").description == "router from CAMGEN_MACHINES");
    const Run list = run({"--list-machines"});
    REQUIRE(list.code == 0);
    const std::vector<std::string> lines = lines_of(list.out);
    REQUIRE(lines.size() >= 13);
    // Search order: CAMGEN_MACHINES, XDG, then the built-in machines by name.
    CHECK(lines[0].starts_with("router "));
    CHECK(lines[0].find("[" + (extra / "router.json").string() + "]") != std::string::npos);
    CHECK(lines[1].starts_with("broken "));
    CHECK(lines[1].find("(cannot be read:") != std::string::npos);
    CHECK(lines[2].find("router from XDG") != std::string::npos);
    CHECK(lines[2].find("replaced by the file of this name above") != std::string::npos);
    CHECK(lines[3].starts_with("fanuc "));
    for (std::size_t i = 3; i < lines.size(); ++i) CHECK(lines[i].ends_with("[built-in]"));
}

TEST_CASE("--describe-machine M --json prints the complete machine file, which reads as the same machine") {
    UserConfig user("describe");
    user.write("shop.json", R"({"extends": "wabeco", "description": "shop wabeco", "limits": {"maxFeed": 900}})");
    const Run r = run({"--describe-machine", "shop", "--json"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    // The file is the "machine" member; beside it the capabilities (test_describe_truth.cpp).
    const nlohmann::json described = nlohmann::json::parse(r.out);
    REQUIRE(described.size() == 2);
    REQUIRE(described.contains("capabilities"));
    const nlohmann::json doc = described["machine"];
    CHECK_FALSE(doc.contains("extends"));
    CHECK(doc["limits"]["maxFeed"] == 900);
    CHECK(doc["dialect"] == "nccad");
    const std::string resolved = (scratch("machines-describe-out") / "resolved.json").string();
    std::ofstream(resolved) << doc.dump(2);
    CHECK(post(resolved, plate_job()) == post("shop", plate_job()));
    // A built-in prints as its own file says.
    const Run builtin = run({"--describe-machine", "fanuc", "--json"});
    REQUIRE(builtin.code == 0);
    CHECK(nlohmann::json::parse(builtin.out)["machine"] ==
          nlohmann::json::parse(read_file(std::string(CAMGEN_SOURCE_DIR) + "/machines/fanuc.json")));
    CHECK(run({"--json"}).code == exit_usage);
}

}  // namespace test_machine_files
