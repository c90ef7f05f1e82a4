// A face's area as the region geometry reads it, found by the pocket proof's random faces with
// arc centres to 0.001 mm (tests/oracle/test_pocket_proof.cpp): an area the region geometry
// refused (an arc's end a hair off its circle at a sharp corner, the next segment crossing back
// over it) was refused for that, at its path, not as "the area grown by the tool radius and the
// overhang is empty" (what growing an area it cannot read gave). Since arcs within 0.001 mm of
// their circles are made exact as they are read (make_arcs_exact, geometry/profile.hpp), that
// area is faced, as its exact twin is.
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_face_area {

using namespace camgen;
using Json = nlohmann::json;

TEST_CASE("face: an area whose arcs' ends are a hair off their circles at sharp corners is faced as its exact twin") {
    const Json job = Json::parse(R"({"name": "face", "units": "mm", "clearance": 15,
      "tools": [{"diameter": 16.396, "number": 1, "rpm": 3000, "type": "end-mill"}],
      "operations": [{"type": "face", "tool": 1, "comment": "case 1075", "angle": 90, "endDepth": 0.986, "feed": 900,
        "overhang": 2.545, "referencePlane": 1.548, "retractPlane": 6.548, "safeDistance": 1, "stepOverPercent": 61.927,
        "start": [8.032, 7.858], "path": [{"line": [-4.017, 9.017]}, {"line": [-19.175, -6.204]}, {"line": [-8.77, -25.588]},
          {"arc": {"centre": [8.043, -46.654], "direction": "cw", "end": [10.567, -19.82]}},
          {"arc": {"centre": [42.138, -2.973], "direction": "cw", "end": [8.032, 7.858]}}]}]})");
    // (refused before: "/operations/0/path: the outline crosses itself at (8.032, 7.858), where
    // segment 4 meets segment 0: they cross by a hair at their joint")
    const Job given = read_job(job.dump(), "face.json");
    CHECK(std::get<FaceOp>(given.operations.at(0)).row_paths.size() > 2);
    // The same area with the arcs' centres where both their ends are on their circles: the same
    // program, byte for byte.
    Json exact = job;
    exact["operations"][0]["path"][3]["arc"]["centre"] = Json::array({8.042544272214135, -46.65413593824631});
    exact["operations"][0]["path"][4]["arc"]["centre"] = Json::array({42.13803224627175, -2.9733520758617358});
    const Job read = read_job(exact.dump(), "face.json");
    CHECK(std::get<FaceOp>(read.operations.at(0)).row_paths.size() > 2);
    const Machine machine = load_machine("linuxcnc");
    CHECK(test::post_program(given, machine) == test::post_program(read, machine));
}

}  // namespace test_face_area
