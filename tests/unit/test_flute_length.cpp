// A tool's fluteLength for every operation that cuts (issue 24): contour and path refuse a cut
// deeper than it at the key or element that makes it (bore-mill's wording), turn-drill's hole
// is checked by the safety check as a drill's, and turn-profile, which cannot know its depth of
// cut, says in a note that it does not check it.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_flute_length {

using namespace camgen;

namespace {

// `text` with the first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

// The error reading `text` gives, or a failure.
InputError refusal(const std::string& text) {
    try {
        (void)read_job(text, "f.json");
    } catch (const InputError& e) {
        return e;
    }
    FAIL("no error");
    return InputError("", "");
}

// A job on a 6 mm end mill with fluteLength 12 and the operation `op`.
std::string mill_job(const std::string& op) {
    return R"({"clearance": 20, "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 8000, "fluteLength": 12}],
  "operations": [)" + op + "]}";
}

std::string contour(double depth) {
    return mill_job(fmt::format(R"({{"type": "contour", "tool": 1, "retractPlane": 5, "endDepth": {}, "feed": 500,
  "start": [0, 0], "path": [{{"line": [40, 0]}}, {{"line": [40, 30]}}, {{"line": [0, 30]}}, {{"line": [0, 0]}}]}})",
                                depth));
}

}  // namespace

TEST_CASE("fluteLength: a contour deeper than the flutes is refused at endDepth") {
    const InputError e = refusal(contour(30));
    CHECK(e.path() == "/operations/0/endDepth");
    CHECK(std::string(e.detail()) ==
          "the contour is 30.000 mm deep below the reference plane, but tool 1 has a fluteLength of 12.000 mm");
    // As deep as the flutes: cut.
    CHECK_NOTHROW(read_job(contour(12), "f.json"));
    // An absolute endDepth below a raised reference plane counts from the plane.
    const InputError abs = refusal(replaced(contour(-8), R"("retractPlane": 5, "endDepth": -8)",
                                R"("retractPlane": 10, "referencePlane": 5, "endDepth": -8, "endDepthIsAbsolute": true)"));
    CHECK(std::string(abs.detail()).find("the contour is 13.000 mm deep") == 0);
}

TEST_CASE("fluteLength: a path deeper below its start than the flutes is refused at the element that goes there") {
    auto path = [](const std::string& z, const std::string& elements) {
        return mill_job(R"({"type": "path", "tool": 1, "z": )" + z + R"(, "feed": 300, "start": [0, 0], "path": [)" + elements + "]}");
    };
    // Lines with a Z (read packed) down to 13 below the start at Z-1.
    InputError e = refusal(path("-1", R"({"line": [10, 0, -5]}, {"line": [20, 0, -14]}, {"line": [30, 0, -1]})"));
    CHECK(e.path() == "/operations/0/path/1/line");
    CHECK(std::string(e.detail()) ==
          "the path goes 13.000 mm deep below its start (z, Z -1.000 mm), but tool 1 has a fluteLength of 12.000 mm");
    // A helix: 3 turns of 5 from Z0.
    e = refusal(path("0", R"({"line": [5, 0]}, {"helix": {"centre": [0, 0], "direction": "ccw", "turns": 3, "pitch": 5}})"));
    CHECK(e.path() == "/operations/0/path/1");
    CHECK(std::string(e.detail()).find("the path goes 15.000 mm deep") == 0);
    // An arc in XZ whose ends are at the start's Z but whose bottom is 12.5 below it.
    const std::string dip = R"({"arc": {"plane": "xz", "end": [25, 0, -1], "centre": [12.5, 0, -1], "direction": "cw"}})";
    e = refusal(path("-1", dip));
    CHECK(e.path() == "/operations/0/path/0");
    CHECK(std::string(e.detail()).find("the path goes 12.500 mm deep") == 0);
    // The same arc the other way goes up, not down: within the flutes.
    CHECK_NOTHROW(read_job(path("-1", replaced(dip, "\"cw\"", "\"ccw\"")), "f.json"));
    CHECK_NOTHROW(read_job(path("-1", R"({"line": [10, 0, -13]})"), "f.json"));
}

TEST_CASE("fluteLength: a turn-drill deeper than the flutes is refused at endDepth, nothing written") {
    const std::string job = R"({"clearance": 20, "tools": [{"number": 1, "diameter": 10, "tipAngle": 118, "rpm": 800, "fluteLength": 25}],
  "operations": [{"type": "turn-drill", "tool": 1, "startDepth": 0, "endDepth": -30, "safeDistance": 2, "plungingFeedrate": 100}]})";
    const std::filesystem::path out = test::scratch("flute-turn-drill") / "p.ngc";
    const test::Run r = test::run({test::file_with("flute-turn-drill", job), "--machine", "linuxcnc-lathe", "-o", out.string()});
    CHECK(r.code == 1);
    CHECK(r.err.find("/operations/0/endDepth: the hole is 30.000 mm deep below the reference plane, but tool 1 has a "
                     "fluteLength of 25.000 mm") != std::string::npos);
    CHECK(!std::filesystem::exists(out));
    const test::Run ok = test::run({test::file_with("flute-turn-drill-ok", replaced(job, "-30", "-25")), "--machine",
                                    "linuxcnc-lathe", "-o", out.string()});
    CHECK(ok.code == 0);
}

TEST_CASE("fluteLength: a turn-profile says in a note that it does not check it") {
    const std::string job = R"({"clearance": 20, "tools": [{"number": 1, "type": "turning-tool", "diameter": 0.8, "rpm": 1000, "fluteLength": 4}],
  "operations": [{"type": "turn-profile", "tool": 1, "feed": 100, "start": [30, 0], "retractX": 34, "path": [{"line": [30, -40]}]}]})";
    // (The tool gives no insert angles: a note says so too, first.)
    std::vector<std::string> notes;
    for (const Event& e : expand_job(read_job(job, "f.json")))
        if (const auto* s = std::get_if<OperationStart>(&e)) notes = s->notes;
    REQUIRE(notes.size() == 2);
    CHECK(notes[1].find("tool 1 has a fluteLength of 4.000 mm: a turn-profile does not check it") == 0);
    // Without fluteLength, no note.
    for (const Event& e : expand_job(read_job(replaced(job, R"(, "fluteLength": 4)", ""), "f.json")))
        if (const auto* s = std::get_if<OperationStart>(&e)) CHECK(s->notes.size() == 1);
}

}  // namespace test_flute_length
