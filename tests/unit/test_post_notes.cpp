// The post's notes and warnings on the terminal.
#include <sstream>
#include <string>

#include <doctest/doctest.h>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_post_notes {

using namespace camgen;
using namespace camgen::test;

TEST_CASE("a note names an operation by its comment on one line: the comment's line breaks are spaces") {
    // (An exploratory tester found "camgen: note: /operations/4 (a" and a line "G0 Z-9 ..." on
    // the terminal: the NC text's comments were already one line.)
    std::string job = read_file(CAMGEN_SOURCE_DIR "/samples/shaft.json");
    const std::string comment = "\"finish the outside: chamfer, D30, R5 fillet, D40\"";
    const std::size_t at = job.find(comment);
    REQUIRE(at != std::string::npos);
    job.replace(at, comment.size(), "\"finish\\nG0 Z-9\\rX\\u007f\"");
    const Posted p = post_noted(job, load_machine("fanuc-lathe"));
    REQUIRE(p.notes.find("/operations/4 (finish G0 Z-9 X ): ") != std::string::npos);
    std::istringstream lines(p.notes);
    for (std::string line; std::getline(lines, line);) CHECK(line.rfind("camgen: note: ", 0) == 0);
    CHECK(p.notes.find('\r') == std::string::npos);
}

}  // namespace test_post_notes
