// The tables of docs/job-format.md that are generated from the vocabulary and key tables: the file
// must hold exactly what the tables say. CAMGEN_UPDATE_DOCS=1 rewrites them.
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "camgen/schema/schema.hpp"
#include "camgen/vocabulary/vocabulary.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/stock.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_docs {

using namespace camgen;

namespace {

const std::string job_format_doc = std::string(CAMGEN_SOURCE_DIR) + "/docs/job-format.md";
const std::string reference_doc = std::string(CAMGEN_SOURCE_DIR) + "/docs/reference.md";

std::string read_doc(const std::string& doc_path) {
    std::ifstream in(doc_path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// The text between "<!-- generated: NAME -->\n" and "<!-- end generated -->" (npos pair if absent).
std::pair<size_t, size_t> section(const std::string& doc, const std::string& name) {
    const std::string open = "<!-- generated: " + name + " -->\n";
    const size_t a = doc.find(open);
    if (a == std::string::npos) return {std::string::npos, std::string::npos};
    const size_t b = doc.find("<!-- end generated -->", a);
    return {a + open.size(), b};
}

void check_section(const std::string& name, const std::string& expected, const std::string& doc_path = job_format_doc) {
    std::string doc = read_doc(doc_path);
    auto [a, b] = section(doc, name);
    REQUIRE_MESSAGE(a != std::string::npos, doc_path << " has no generated section " << name);
    REQUIRE(b != std::string::npos);
    if (std::getenv("CAMGEN_UPDATE_DOCS")) {
        doc.replace(a, b - a, expected);
        std::ofstream(doc_path, std::ios::binary) << doc;
        return;
    }
    CHECK_MESSAGE(doc.substr(a, b - a) == expected,
                  doc_path << " section '" << name << "' differs from the vocabulary or key tables; run "
                  "CAMGEN_UPDATE_DOCS=1 build/camgen_tests -tc='docs*'");
}

}  // namespace

TEST_CASE("docs: the drilling-field table is the vocabulary's") {
    const std::string table = drill_fields_markdown();
    // Every field, with its bound and who needs it.
    for (const auto& f : drill_fields) CHECK(table.find("| `" + std::string(f.key) + "` |") != std::string::npos);
    CHECK(table.find("| `firstDepth` | length (mm) > 0 | deep, chip-break; **required** by deep, chip-break |") !=
          std::string::npos);
    CHECK(table.find("| `topDwell` | time (s) >= 0 | drill, dwell, deep, chip-break |") != std::string::npos);
    check_section("drilling fields", table);
}

TEST_CASE("docs: the cycle table is the vocabulary's") {
    const std::string table = cycle_kinds_markdown();
    CHECK(table.find("| `tap` | G84: right-hand tapping, spindle reversal at the bottom | **pitch**, tappingSpeed, "
                     "retractSpeed, bottomDwell |") != std::string::npos);
    CHECK(table.find("| `bore-stop` | G86: feed in, spindle stop, rapid out | **plungingFeedrate**, bottomDwell |") !=
          std::string::npos);
    check_section("cycle kinds", table);
}

TEST_CASE("docs: the stock key tables are the stock's key tables") {
    for (const ObjectSpec& spec : stock_objects()) {
        const std::optional<std::string> table = keys_markdown(spec.name);
        REQUIRE(table);
        for (const KeySpec& k : spec.keys) CHECK(table->find("| `" + std::string(k.key) + "` |") != std::string::npos);
        check_section(std::string(spec.name) + " keys", *table);
    }
}

TEST_CASE("docs: the tool library's key tables are its key tables") {
    for (const ObjectSpec& spec : tool_library_objects()) {
        if (spec.name == "libraryTool") continue;  // a job tool's keys, documented with them
        const std::optional<std::string> table = keys_markdown(spec.name);
        REQUIRE(table);
        for (const KeySpec& k : spec.keys) CHECK(table->find("| `" + std::string(k.key) + "` |") != std::string::npos);
        check_section(std::string(spec.name) + " keys", *table);
    }
}

TEST_CASE("docs: the contour, path, bore-mill, thread-mill, engrave, stop, custom, pocket and face key tables are the operations' key tables") {
    std::vector<ObjectSpec> objects = ContourOp::objects();
    const std::vector<ObjectSpec> path = PathOp::objects();
    objects.insert(objects.end(), path.begin(), path.end());
    // bore-mill's own object (its hole sources are drilling's, documented there).
    objects.push_back(BoreMillOp::objects().front());
    objects.push_back(ThreadMillOp::objects().front());
    objects.push_back(EngraveOp::objects().front());
    objects.push_back(ChamferOp::objects().front());
    objects.push_back(StopOp::objects().front());
    objects.push_back(TurnGrooveOp::objects().front());
    objects.push_back(TurnPartOp::objects().front());
    objects.push_back(CustomOp::objects().front());
    // pocket's and face's own objects (their leads, ramps and finishing are contour's).
    for (const ObjectSpec& o : PocketOp::objects())
        if (o.name == "pocket" || o.name == "pocketIsland") objects.push_back(o);
    for (const ObjectSpec& o : FaceOp::objects())
        if (o.name == "face" || o.name == "faceRectangle") objects.push_back(o);
    for (const ObjectSpec& spec : objects) {
        const std::optional<std::string> table = keys_markdown(spec.name);
        REQUIRE(table);
        // Every key, with its default or "required".
        for (const KeySpec& k : spec.keys) CHECK(table->find("| `" + std::string(k.key) + "` |") != std::string::npos);
        check_section(std::string(spec.name) + " keys", *table);
    }
    const std::string contour = *keys_markdown("contour");
    CHECK(contour.find("| `endDepth` | length (mm) | **required** |") != std::string::npos);
    CHECK(contour.find("| `side` | `\"left\"`, `\"right\"`, `\"on\"`, `\"inside\"`, `\"outside\"` | `\"outside\"` |") !=
          std::string::npos);
    CHECK(keys_markdown("contourLead")->find("| `sweep` | angle (degrees) > 0, <= 180 | `90` |") != std::string::npos);
    const std::string bore = *keys_markdown("bore-mill");
    CHECK(bore.find("| `diameter` | length (mm) > 0 | **required** |") != std::string::npos);
    CHECK(bore.find("| `direction` | `\"climb\"`, `\"conventional\"` | `\"climb\"` |") != std::string::npos);
    CHECK_FALSE(keys_markdown("no such object"));
}

TEST_CASE("docs: the dialect settings tables of the reference are the dialects' key tables") {
    for (const char* dialect : {"iso", "iso-lathe", "nccad"}) {
        const std::string name = std::string("settings-") + dialect;
        const std::optional<std::string> table = keys_markdown(name);
        REQUIRE(table);
        check_section(name + " keys", *table, reference_doc);
    }
    CHECK(keys_markdown("settings-iso")->find("| `toolChange` | `\"m6\"`, `\"pause\"`, `\"none\"`, `true`, `false` | "
                                              "`\"m6\"` |") != std::string::npos);
    CHECK(keys_markdown("settings-iso-lathe")->find("| `spindleLimit` | boolean | `false` |") != std::string::npos);
}

}  // namespace test_docs
