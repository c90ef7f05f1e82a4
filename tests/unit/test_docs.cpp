// The tables of docs/job-format.md that are generated from the vocabulary tables: the file
// must hold exactly what the tables say. CAMGEN_UPDATE_DOCS=1 rewrites them.
#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "camgen/schema/schema.hpp"
#include "camgen/vocabulary/vocabulary.hpp"
#include "operations/registry.hpp"

using namespace camgen;

namespace {

const std::string doc_path = std::string(CAMGEN_SOURCE_DIR) + "/docs/job-format.md";

std::string read_doc() {
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

void check_section(const std::string& name, const std::string& expected) {
    std::string doc = read_doc();
    auto [a, b] = section(doc, name);
    REQUIRE_MESSAGE(a != std::string::npos, "docs/job-format.md has no generated section " << name);
    REQUIRE(b != std::string::npos);
    if (std::getenv("CAMGEN_UPDATE_DOCS")) {
        doc.replace(a, b - a, expected);
        std::ofstream(doc_path, std::ios::binary) << doc;
        return;
    }
    CHECK_MESSAGE(doc.substr(a, b - a) == expected,
                  "docs/job-format.md section '" << name << "' differs from the vocabulary tables; run "
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

TEST_CASE("docs: the bore-mill key table is the operation's") {
    const std::string table = keys_markdown(BoreMillOp::objects().front());
    CHECK(table.find("| `diameter` | number (length) > 0 | **required** |") != std::string::npos);
    CHECK(table.find("| `direction` | `\"climb\"`, `\"conventional\"` | `\"climb\"` |") != std::string::npos);
    CHECK(table.find("| `stepOver` | number > 0, ≤ 1 | `0.5` |") != std::string::npos);
    CHECK(table.find("| `boltCircle` | object | – |") != std::string::npos);
    check_section("bore-mill keys", table);
}
