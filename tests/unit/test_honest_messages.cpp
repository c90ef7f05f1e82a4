// Honest messages (issue 25): numbers in errors, warnings and notes are rounded (no float
// expansion, no exponent, no -0), a per-revolution feed is told in mm/rev, and a message about
// an operation names a key that operation has (a turn-drill's retractDistance, not a drill's
// retractPlane).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/common/number_text.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_honest_messages {

using namespace camgen;
namespace fs = std::filesystem;

namespace {
const std::string source_dir = CAMGEN_SOURCE_DIR;
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST_CASE("number_text rounds, drops trailing zeros, never prints an exponent or -0") {
    CHECK(number_text(0.12000000000000001) == "0.12");
    CHECK(number_text(2.5) == "2.5");
    CHECK(number_text(1000) == "1000");
    CHECK(number_text(1e12) == "1000000000000");
    CHECK(number_text(-0.00001) == "-0.00001");
    CHECK(number_text(0.000012345) == "0.000012");
    CHECK(number_text(0.00008) == "0.00008");  // not 0.0001
    CHECK(number_text(0.00012345) == "0.00012");
    CHECK(number_text(0.0012) == "0.0012");
    CHECK(number_text(3.2398696036443e-09) == "0.0000000032");
    CHECK(number_text(-0.00000000000001) == "0");
    CHECK(number_text(-0.0) == "0");
    CHECK(number_text(1.0 / 3.0) == "0.3333");
    CHECK(number_text(2.0 / 3.0, 2) == "0.67");
    CHECK(number_text(25.4 * 0.1) == "2.54");
}

namespace {
// A turn-drill job for fanuc-lathe (minFeed 1 mm/min) with the operation's keys given.
std::string turn_drill_job(const std::string& keys, int rpm = 60) {
    return fmt::format(R"({{"name": "t", "units": "mm", "clearance": 20, "tools": [
  {{"number": 1, "type": "drill", "diameter": 6, "rpm": {}}}],
"operations": [{{"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": -10, "safeDistance": 2, {}}}]}})",
                       rpm, keys);
}
}  // namespace

TEST_CASE("a per-revolution feed raised to the machine's minimum is told in mm/rev, rounded") {
    const test::Run r = test::run({"-", "--machine", "fanuc-lathe"},
                                  turn_drill_job(R"("feedMode": "per-revolution", "plungingFeedrate": 0.002)"));
    CHECK(r.code == 0);
    CHECK(contains(r.err, "camgen: warning: /operations/0: feed 0.002 mm/rev (0.12 mm/min at 60 rpm) is below the minimum "
                          "of machine fanuc-lathe; raised to 1 mm/min (0.0167 mm/rev)\n"));
    CHECK_FALSE(std::regex_search(r.err, std::regex("[0-9]\\.[0-9]{5,}")));
    // Per minute it stays in mm/min.
    const test::Run m = test::run({"-", "--machine", "fanuc-lathe"}, turn_drill_job(R"("plungingFeedrate": 0.12)"));
    CHECK(contains(m.err, "feed 0.12 mm/min is below the minimum of machine fanuc-lathe; raised to 1 mm/min\n"));
}

TEST_CASE("a turn-drill's messages name its own keys, never a drill operation's") {
    // retractDistance above the clearance: was reported at /operations/0/retractPlane.
    const test::Run r = test::run({"-", "--machine", "fanuc-lathe"},
                                  turn_drill_job(R"("retractDistance": 25, "plungingFeedrate": 50)"));
    CHECK(r.code == 1);
    CHECK(r.err == "camgen: <stdin>:3: /operations/0/retractDistance: the clearance (Z 20.000 mm) is below "
                   "retractDistance (Z 25.000 mm): moves at the clearance would run below this operation's retract plane\n");
    // A peck below the machine's resolution: firstPeckDepth, not firstDepth.
    const test::Run peck = test::run({"-", "--machine", "fanuc-lathe"},
                                     turn_drill_job(R"("plungingFeedrate": 50, "firstPeckDepth": 0.0001)"));
    CHECK(peck.code == 1);
    CHECK(contains(peck.err, "/operations/0/firstPeckDepth: firstPeckDepth 0.0001 mm is below the resolution of machine "
                             "fanuc-lathe (0.001 mm)"));
    // More pecks than any control takes.
    const test::Run many = test::run({"-", "--machine", "fanuc-lathe"},
                                     turn_drill_job(R"("plungingFeedrate": 50, "firstPeckDepth": 0.001)"));
    CHECK(many.code == 1);
    CHECK(contains(many.err, "/operations/0/firstPeckDepth: more than"));
}

TEST_CASE("tests/errors/messages.txt: every message about an operation names a key that operation type has") {
    // The keys of each operation type, from its key table (its first object).
    std::map<std::string, std::set<std::string>> keys_of;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
        ([&] {
            using Op = std::variant_alternative_t<I, Operation>;
            const std::vector<ObjectSpec> objects = Op::objects();
            for (const KeySpec& k : objects.front().keys) keys_of[std::string(Op::type)].insert(std::string(k.key));
        }(), ...);
    }(std::make_index_sequence<std::variant_size_v<Operation>>{});
    REQUIRE(keys_of.count("turn-drill"));
    // The operation types of each sample.
    std::map<std::string, std::vector<std::string>> types_of;
    for (const auto& f : fs::directory_iterator(source_dir + "/samples")) {
        if (f.path().extension() != ".json") continue;
        const auto doc = nlohmann::json::parse(test::read_file(f.path().string()));
        for (const auto& op : doc["operations"]) types_of[f.path().stem().string()].push_back(op["type"].get<std::string>());
    }
    std::ifstream golden(source_dir + "/tests/errors/messages.txt");
    int checked = 0;
    for (std::string line; std::getline(golden, line);) {
        // "SAMPLE MUTATION POINTER | 1 camgen: <stdin>:LINE: /operations/N/KEY...: detail"
        const std::size_t bar = line.find(" | 1 camgen: <stdin>:");
        if (bar == std::string::npos) continue;
        std::istringstream label(line.substr(0, bar));
        std::string sample, mutation, pointer;
        label >> sample >> mutation >> pointer;
        const std::size_t at = line.find(": /operations/", bar);
        if (at == std::string::npos) continue;
        const std::string path = line.substr(at + 2, line.find(": ", at + 2) - at - 2);
        const std::size_t slash = path.find('/', std::string("/operations/").size());
        if (slash == std::string::npos) continue;
        std::size_t index = std::stoul(path.substr(std::string("/operations/").size()));
        // An operation removed before it: the message's index is one less than the sample's.
        if (mutation == "removed" && pointer.rfind("/operations/", 0) == 0 && pointer.find('/', 12) == std::string::npos &&
            std::stoul(pointer.substr(12)) <= index)
            ++index;
        const std::string key = path.substr(slash + 1, path.find('/', slash + 1) - slash - 1);
        const auto types = types_of.find(sample);
        if (types == types_of.end() || index >= types->second.size()) continue;
        // A mutation of the operation's type, or a key the mutation made up, is not the operation's.
        if (pointer == fmt::format("/operations/{}/type", index) || pointer == fmt::format("/operations/{}", index) ||
            mutation == "unknown-key" || mutation == "misspelt-key")
            continue;
        CAPTURE(line);
        CHECK(keys_of[types->second[index]].count(key) == 1);
        ++checked;
    }
    CHECK(checked > 1000);
}

}  // namespace test_honest_messages
