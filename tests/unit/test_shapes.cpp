// Shapes as profiles (rectangle, circle, slot, polygon) wherever a job takes a profile, and a
// DXF drawing as the area of a face and the path of a path operation.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "camgen/common/error.hpp"
#include "camgen/geometry/vec.hpp"
#include "camgen/operations/registry.hpp"

namespace test_shapes {

using namespace camgen;

const std::string job_name = CAMGEN_SOURCE_DIR "/tests/dxf/t.json";

std::string job_text(const std::string& op, const std::string& extra = "") {
    return R"({"name": "t", "units": "mm", "clearance": 15, )" + extra + R"("tools": [
      {"number": 2, "type": "end-mill", "diameter": 6, "rpm": 8000}],
      "operations": [)" + op + "]}";
}

std::string job_error(const std::string& op) {
    try {
        read_job(job_text(op), job_name);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const std::string contour_head = R"({"type": "contour", "tool": 2, "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "feed": 500, )";
const std::string pocket_head = R"({"type": "pocket", "tool": 2, "retractPlane": 5, "safeDistance": 1, "endDepth": 3, "feed": 500, )";
const std::string path_head = R"({"type": "path", "tool": 2, "z": -1, "feed": 500, )";
const std::string face_head = R"({"type": "face", "tool": 2, "retractPlane": 5, "safeDistance": 1, "endDepth": 1, "feed": 500, )";

Profile contour_profile(const std::string& profile) {
    Job job = read_job(job_text(contour_head + R"("side": "outside", "profile": )" + profile + "}"), job_name);
    return std::get<ContourOp>(job.operations.at(0)).profile;
}

struct Extent {
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
};
Extent extent_of(const Profile& p) {
    Extent e;
    for (Vec2 v : sample_profile(p, 1e-9)) {
        e.lo = {std::min(e.lo.x, v.x), std::min(e.lo.y, v.y)};
        e.hi = {std::max(e.hi.x, v.x), std::max(e.hi.y, v.y)};
    }
    return e;
}

void check_extent(const Profile& p, Vec2 lo, Vec2 hi) {
    const Extent e = extent_of(p);
    INFO("extent (" << e.lo.x << ", " << e.lo.y << ") .. (" << e.hi.x << ", " << e.hi.y << ")");
    CHECK(std::abs(e.lo.x - lo.x) < 1e-6);
    CHECK(std::abs(e.lo.y - lo.y) < 1e-6);
    CHECK(std::abs(e.hi.x - hi.x) < 1e-6);
    CHECK(std::abs(e.hi.y - hi.y) < 1e-6);
}

// Every arc's ends on its circle.
void check_arcs(const Profile& p) {
    for (std::size_t k = 0; k < p.segments.size(); ++k)
        if (p.segments[k].centre) CHECK(std::abs(distance(segment_start(p, k), *p.segments[k].centre) - distance(p.segments[k].end, *p.segments[k].centre)) < 1e-9);
}

TEST_CASE("shapes: a rectangle by corner or centre, its corners rounded or sharp") {
    const Profile sharp = contour_profile(R"({"rectangle": {"corner": [10, 20], "width": 40, "height": 30}})");
    CHECK(is_closed(sharp));
    CHECK(orientation(sharp) == Orientation::ccw);
    CHECK(sharp.start == Vec2{30, 20});  // the middle of the bottom side: a lead joins a line
    CHECK(sharp.segments.size() == 5);
    CHECK(std::abs(enclosed_area(sharp) - 1200) < 1e-9);
    check_extent(sharp, {10, 20}, {50, 50});
    const Profile round = contour_profile(R"({"rectangle": {"centre": [0, 0], "width": 40, "height": 30, "cornerRadius": 5}})");
    CHECK(is_closed(round));
    CHECK(round.segments.size() == 9);
    CHECK(std::abs(enclosed_area(round, 1e-5) - (1200 - (4 - pi) * 25)) < 1e-3);
    check_extent(round, {-20, -15}, {20, 15});
    check_arcs(round);
    CHECK(round.segments[1].centre == Vec2{15, -10});
    // Half the smaller side: the short sides are arcs only.
    const Profile ends = contour_profile(R"({"rectangle": {"centre": [0, 0], "width": 40, "height": 10, "cornerRadius": 5}})");
    CHECK(is_simple(ends));
    CHECK(ends.segments.size() == 7);
}

TEST_CASE("shapes: a circle, a slot two ways, a polygon by diameter or across flats") {
    const Profile circle = contour_profile(R"({"circle": {"centre": [5, 5], "diameter": 20}})");
    CHECK(circle.start == Vec2{15, 5});
    CHECK(circle.segments.size() == 2);
    CHECK(std::abs(enclosed_area(circle, 1e-5) - pi * 100) < 1e-2);
    check_extent(circle, {-5, -5}, {15, 15});

    const Profile by_centres = contour_profile(R"({"slot": {"centres": [[0, 0], [30, 0]], "width": 10}})");
    const Profile by_length = contour_profile(R"({"slot": {"centre": [15, 0], "length": 40, "width": 10}})");
    CHECK(by_centres.start == by_length.start);
    CHECK(by_centres.segments == by_length.segments);
    CHECK(is_closed(by_centres));
    CHECK(orientation(by_centres) == Orientation::ccw);
    CHECK(std::abs(enclosed_area(by_centres, 1e-5) - (300 + pi * 25)) < 1e-2);
    check_extent(by_centres, {-5, -5}, {35, 5});
    check_arcs(by_centres);
    // Turned 90 degrees about its middle.
    const Profile turned = contour_profile(R"({"slot": {"centre": [0, 0], "length": 40, "width": 10, "angle": 90}})");
    check_extent(turned, {-5, -20}, {5, 20});

    const Profile hex = contour_profile(R"({"polygon": {"centre": [0, 0], "sides": 6, "acrossFlats": 10}})");
    CHECK(hex.segments.size() == 7);  // six sides, the first split at its middle
    const double r = 5 / std::cos(pi / 6);
    CHECK(std::abs(enclosed_area(hex) - 1.5 * std::sqrt(3.0) * r * r) < 1e-9);
    check_extent(hex, {-r, -5}, {r, 5});  // a corner on +X, flats at Y +-5
    const Profile square = contour_profile(R"({"polygon": {"centre": [0, 0], "sides": 4, "diameter": 20, "angle": 45}})");
    CHECK(std::abs(enclosed_area(square) - 200) < 1e-9);
    check_extent(square, {-std::sqrt(50.0), -std::sqrt(50.0)}, {std::sqrt(50.0), std::sqrt(50.0)});
}

TEST_CASE("shapes: a pocket's outline and islands, a face's area, a path and a stock's outline") {
    Job job = read_job(job_text(pocket_head + R"("profile": {"rectangle": {"corner": [0, 0], "width": 60, "height": 40, "cornerRadius": 4}},
        "islands": [{"profile": {"circle": {"centre": [20, 20], "diameter": 8}}},
                    {"profile": {"polygon": {"centre": [42, 20], "sides": 6, "acrossFlats": 10}}}]})"), job_name);
    const PocketOp& pocket = std::get<PocketOp>(job.operations.at(0));
    REQUIRE(pocket.region.islands.size() == 2);
    CHECK(std::abs(enclosed_area(pocket.region.islands[0], 1e-5) - pi * 16) < 1e-2);
    CHECK_FALSE(pocket.steps.empty());

    job = read_job(job_text(face_head + R"("profile": {"circle": {"centre": [0, 0], "diameter": 50}}})"), job_name);
    const FaceOp& face = std::get<FaceOp>(job.operations.at(0));
    CHECK(std::abs(enclosed_area(face.area, 1e-5) - pi * 625) < 0.1);

    job = read_job(job_text(path_head + R"("profile": {"slot": {"centres": [[0, 0], [30, 0]], "width": 10}}})"), job_name);
    const PathOp& path = std::get<PathOp>(job.operations.at(0));
    CHECK(path.start == Vec2{15, -5});
    REQUIRE(path.elements.size() == 5);
    const PathArc& end = std::get<PathArc>(path.elements[1]);
    CHECK(end.centre == Vec3{30, 0, -1});
    CHECK(end.end == Vec3{30, 5, -1});
    CHECK(end.direction == ArcDirection::ccw);
    CHECK(std::get<PathLine>(path.elements[4]).end == Vec3{15, -5, -1});

    job = read_job(job_text(face_head + R"("comment": "the stock's"})", R"("stock": {"profile": {"profile": {"rectangle": {"corner": [0, 0], "width": 80, "height": 50}},
        "top": 0, "bottom": -10}}, )"), job_name);
    CHECK(std::abs(enclosed_area(std::get<FaceOp>(job.operations.at(0)).area) - 4000) < 1e-9);
}

TEST_CASE("shapes: a drawing as a face's area and as a path (open or closed)") {
    Job job = read_job(job_text(face_head + R"("profile": {"dxf": "plate.dxf", "layer": "OUTLINE"}})"), job_name);
    const FaceOp& face = std::get<FaceOp>(job.operations.at(0));
    CHECK(std::abs(enclosed_area(face.area, 1e-5) - (4000 - (4 - pi) * 25)) < 1e-2);

    job = read_job(job_text(path_head + R"("profile": {"dxf": "plate.dxf", "layer": "OUTLINE"}})"), job_name);
    const PathOp& outline = std::get<PathOp>(job.operations.at(0));
    CHECK(outline.start == Vec2{5, 0});
    REQUIRE(outline.elements.size() == 8);
    const PathArc& corner = std::get<PathArc>(outline.elements[1]);
    CHECK(std::abs(corner.centre.x - 75) < 1e-9);
    CHECK(std::abs(corner.centre.y - 5) < 1e-9);
    CHECK(corner.centre.z == -1);
    CHECK(corner.plane == Plane::xy);

    // An open profile is a path's as drawn (a pocket refuses it).
    job = read_job(job_text(path_head + R"("profile": {"dxf": "bad-gap.dxf"}})"), job_name);
    const PathOp& open = std::get<PathOp>(job.operations.at(0));
    REQUIRE(open.elements.size() == 4);
    CHECK(distance(open.start, Vec2{std::get<PathLine>(open.elements.back()).end.x, std::get<PathLine>(open.elements.back()).end.y}) > 0.4);
    CHECK(job_error(face_head + R"("profile": {"dxf": "bad-gap.dxf"}})").find("/operations/0/profile: the area must be closed") != std::string::npos);
    CHECK(job_error(path_head + R"("profile": {"dxf": "plate.dxf"}})").find("/operations/0/profile: a path takes one profile, but the selection holds 8") !=
          std::string::npos);
}

TEST_CASE("shapes: wrong shapes are errors naming the JSON path") {
    auto error = [](const std::string& profile) { return job_error(contour_head + R"("profile": )" + profile + "}"); };
    CHECK(error(R"({"rectangle": {"corner": [0, 0], "width": 10, "height": 20, "cornerRadius": 6}})")
              .find("/operations/0/profile/rectangle/cornerRadius: cornerRadius 6.000 mm is more than half the smaller side (5.000 mm)") != std::string::npos);
    CHECK(error(R"({"rectangle": {"corner": [0, 0], "centre": [1, 1], "width": 10, "height": 20}})")
              .find("/operations/0/profile/rectangle/centre: give corner or centre, not both") != std::string::npos);
    CHECK(error(R"({"rectangle": {"width": 10, "height": 20}})").find("/operations/0/profile/rectangle: needs corner or centre") !=
          std::string::npos);
    CHECK(error(R"({"rectangle": {"corner": [0, 0], "width": 0, "height": 20}})").find("/operations/0/profile/rectangle/width") !=
          std::string::npos);
    CHECK(error(R"({"rectangle": {"corner": [0, 0], "height": 20}})").find("/operations/0/profile/rectangle") != std::string::npos);
    CHECK(error(R"({"circle": {"centre": [0, 0], "diameter": 5}, "slot": {"centre": [0, 0], "length": 4, "width": 2}})")
              .find("/operations/0/profile/slot: give one shape: circle or slot, not both") != std::string::npos);
    CHECK(error(R"({"circle": {"centre": [0, 0], "diameter": 5}, "dxf": "plate.dxf"})")
              .find("/operations/0/profile/circle: give dxf (a drawing) or a circle, not both") != std::string::npos);
    CHECK(error(R"({"circle": {"centre": [0, 0], "diameter": 5}, "layer": "HOLES"})")
              .find("/operations/0/profile/layer: layer is for a profile from a drawing (dxf)") != std::string::npos);
    CHECK(error(R"({"circel": {"centre": [0, 0], "diameter": 5}})").find("circle") != std::string::npos);
    CHECK(error(R"({})").find("/operations/0/profile: a profile needs dxf (a drawing) or one shape") != std::string::npos);
    CHECK(error(R"({"slot": {"centre": [0, 0], "length": 10, "width": 10}})")
              .find("/operations/0/profile/slot/length: length 10.000 mm (end to end) must be more than width 10.000 mm") != std::string::npos);
    CHECK(error(R"({"slot": {"centres": [[0, 0], [0, 0]], "width": 10}})").find("/operations/0/profile/slot/centres: the two centres") !=
          std::string::npos);
    CHECK(error(R"({"slot": {"centres": [[0, 0], [9, 0]], "width": 10, "angle": 3}})")
              .find("/operations/0/profile/slot/angle: angle goes with centre") != std::string::npos);
    CHECK(error(R"({"polygon": {"centre": [0, 0], "sides": 2, "diameter": 10}})").find("/operations/0/profile/polygon/sides") !=
          std::string::npos);
    CHECK(error(R"({"polygon": {"centre": [0, 0], "sides": 6, "diameter": 10, "acrossFlats": 8}})")
              .find("/operations/0/profile/polygon/acrossFlats: give diameter or acrossFlats, not both") != std::string::npos);
    CHECK(job_error(pocket_head + R"("profile": {"circle": {"centre": [0, 0], "diameter": 40}},
        "islands": [{"profile": {"circle": {"centre": [30, 0], "diameter": 8}}}]})")
              .find("/operations/0/islands/0") != std::string::npos);
    CHECK(job_error(path_head + R"("start": [0, 0], "profile": {"circle": {"centre": [0, 0], "diameter": 40}}})")
              .find("/operations/0/profile: give start and path, or profile, not both") != std::string::npos);
    CHECK(job_error(path_head + R"("comment": "none"})").find("/operations/0: a path needs start and path, or profile") != std::string::npos);
    CHECK(job_error(path_head + R"("path": [{"line": [1, 0]}]})").find("/operations/0/start: required key \"start\" is missing") != std::string::npos);
}

}  // namespace test_shapes
