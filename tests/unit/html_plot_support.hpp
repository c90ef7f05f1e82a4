#pragma once
// Helpers for the tests of the HTML backplot (unit tests and the browser test): what camgen's
// read-back says about each block, worked out from the trace on its own, and the page's data.
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "camgen/analysis/trace.hpp"

namespace camgen::test {

// Where block `line` leaves the tool, by the read-back trace: the end of the last move of a
// block at or before it, unknown after a tool change until the next move; and the tool then.
struct BlockState {
    bool known = false;
    Vec3 at;
    int tool = -1;  // -1: none yet
};

inline BlockState block_state(const Trace& trace, int line) {
    BlockState b;
    for (const Step& s : trace.steps) {
        if (s.line > line) break;
        if (s.kind == StepKind::tool_change) {
            b.tool = s.tool;
            b.known = false;
        }
        if (s.kind == StepKind::rapid || s.kind == StepKind::feed) {
            b.known = true;
            b.at = s.to;
        }
    }
    return b;
}

// The JSON of the page's <script type="application/json" id="camgen-data"> element.
inline nlohmann::json page_data(const std::string& page) {
    const std::string open = "<script type=\"application/json\" id=\"camgen-data\">";
    const auto from = page.find(open);
    REQUIRE(from != std::string::npos);
    const auto to = page.find("</script>", from);
    REQUIRE(to != std::string::npos);
    return nlohmann::json::parse(page.substr(from + open.size(), to - from - open.size()));
}

}  // namespace camgen::test
