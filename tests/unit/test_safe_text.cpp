// Text from the job reaches the program cut to a length limit. (That it is safe text, with no
// control bytes, comment terminators or '%', is "field failure: comment text copied raw" in
// test_field_failures.cpp.)
#include <doctest/doctest.h>

#include <string>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_safe_text {

using namespace camgen;

TEST_CASE("safe text: comments are cut at the machine's commentMaxLength, else at the default limit") {
    const std::string long_comment(500, 'x');
    const std::string job = R"({"clearance": 10, "tools": [{"number": 1, "diameter": 5, "rpm": 1000}],
  "operations": [{"type": "drill", "tool": 1, "comment": ")" + long_comment + R"(", "endDepth": 2,
                  "plungingFeedrate": 100, "holes": [[0, 0]]}]})";
    const std::string text = test::post_job(job, "fanuc").text;
    CHECK(text.find("(" + std::string(nc::default_comment_limit, 'x') + ")") != std::string::npos);
    CHECK(text.find(std::string(nc::default_comment_limit + 1, 'x')) == std::string::npos);
}

}  // namespace test_safe_text
