// The pocket and face operations, tested by their geometry: every tool-centre position below the
// stock top keeps its distance from the walls and islands (measured here with distance_to, not
// with the part guard's clearance), every point a tool centre may reach at the final depth is
// cut, helix entries stay inside, links at depth are short, the corners the tool cannot reach
// are reported; and each bad input with its JSON path.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/region.hpp"
#include "camgen/geometry/vec.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_pocket {

using namespace camgen;
using namespace camgen::test;
using Json = nlohmann::json;

namespace {

// A move of the tool centre.
struct PMove {
    Vec3 from, to;
    std::optional<Vec2> centre;
    ArcDirection direction = ArcDirection::ccw;
    int turns = 0;
    Movement movement = Movement::cutting;
    bool rapid = false;
};

std::vector<PMove> pocket_moves(const std::vector<Event>& events) {
    std::vector<PMove> out;
    Vec3 at{};
    for (const Event& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            out.push_back({at, r->to, std::nullopt, ArcDirection::ccw, 0, Movement::cutting, true});
            at = r->to;
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            out.push_back({at, l->to, std::nullopt, ArcDirection::ccw, 0, l->movement, false});
            at = l->to;
        } else if (const auto* a = std::get_if<Arc>(&e)) {
            out.push_back({at, a->to, Vec2{a->centre.x, a->centre.y}, a->direction, a->turns, a->movement, false});
            at = a->to;
        }
    }
    return out;
}

// Points along a move every `step` mm or closer (XY; Z linear over the whole move), ends included.
std::vector<Vec3> pocket_samples(const PMove& m, double step) {
    std::vector<Vec3> out;
    if (!m.centre) {
        const double l = std::hypot(m.to.x - m.from.x, m.to.y - m.from.y);
        const int n = std::max(1, static_cast<int>(std::ceil(l / step)));
        for (int k = 0; k <= n; ++k) {
            const double t = static_cast<double>(k) / n;
            out.push_back({m.from.x + (m.to.x - m.from.x) * t, m.from.y + (m.to.y - m.from.y) * t, m.from.z + (m.to.z - m.from.z) * t});
        }
        return out;
    }
    const Vec2 c = *m.centre;
    const double r = std::hypot(m.from.x - c.x, m.from.y - c.y);
    double a0 = std::atan2(m.from.y - c.y, m.from.x - c.x), a1 = std::atan2(m.to.y - c.y, m.to.x - c.x);
    double sweep = m.direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
    while (sweep <= 1e-12) sweep += 2 * pi;
    sweep += 2 * pi * m.turns;
    const int n = std::max(2, static_cast<int>(std::ceil(sweep * r / step)));
    const double sign = m.direction == ArcDirection::ccw ? 1.0 : -1.0;
    for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        const double a = a0 + sign * sweep * t;
        out.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a), m.from.z + (m.to.z - m.from.z) * t});
    }
    return out;
}

Json sample(const std::string& name) {
    std::ifstream f(std::string(CAMGEN_SOURCE_DIR) + "/samples/" + name + ".json");
    return Json::parse(f);
}

// The events of a job's operations (the whole job's, expanded).
std::vector<Event> events_of(const Json& job) { return expand_job(read_job(job.dump(), "test.json")); }

// The distance from p to the nearest wall or island of a pocket operation's JSON.
struct PocketWalls {
    std::vector<Profile> loops;
    explicit PocketWalls(const Json& op) {
        auto loop = [](const Json& o) {
            Profile p;
            p.start = {o["start"][0], o["start"][1]};
            for (const Json& e : o["path"]) {
                ProfileSegment s;
                if (e.contains("line")) {
                    s.end = {e["line"][0], e["line"][1]};
                } else {
                    s.end = {e["arc"]["end"][0], e["arc"]["end"][1]};
                    s.centre = Vec2{e["arc"]["centre"][0], e["arc"]["centre"][1]};
                    s.direction = e["arc"]["direction"] == "cw" ? ArcDirection::cw : ArcDirection::ccw;
                }
                p.segments.push_back(s);
            }
            return p;
        };
        loops.push_back(loop(op));
        if (op.contains("islands"))
            for (const Json& i : op["islands"]) loops.push_back(loop(i));
    }
    double distance(Vec2 p) const {
        double d = 1e300;
        for (const Profile& l : loops) d = std::min(d, distance_to(l, p));
        return d;
    }
    bool inside(Vec2 p) const {
        if (!contains(loops[0], p)) return false;
        for (std::size_t k = 1; k < loops.size(); ++k)
            if (contains(loops[k], p)) return false;
        return true;
    }
};

// Checks the moves of a pocket against its walls: below the top every tool-centre point is
// inside the pocket and at least `keep` from every wall (`keep_rough` while roughing).
void check_clear_of_walls(const std::vector<PMove>& moves, const PocketWalls& walls, double top, double keep_rough, double keep) {
    double bottom = 0;
    for (const PMove& m : moves) bottom = std::min(bottom, m.to.z);
    int checked = 0;
    for (const PMove& m : moves) {
        for (const Vec3& p : pocket_samples(m, 0.2)) {
            if (p.z >= top - 1e-9) continue;
            ++checked;
            // The finishing pass, its leads and the descent to it (beside the wall, after the floor pass).
            const bool finishing = m.movement == Movement::finishing || m.movement == Movement::lead_in ||
                                   m.movement == Movement::lead_out || (m.movement == Movement::plunge && m.to.z <= bottom + 1e-9);
            const double need = finishing ? keep : keep_rough;
            const double d = walls.distance({p.x, p.y});
            if (d < need - 0.002 || !walls.inside({p.x, p.y})) {
                FAIL_CHECK(fmt::format("tool centre at ({:.3f}, {:.3f}, {:.3f}) is {:.4f} from a wall, needs {:.4f} ({})", p.x, p.y, p.z, d,
                                       need, walls.inside({p.x, p.y}) ? "inside" : "outside the pocket"));
                return;
            }
        }
    }
    CHECK(checked > 100);
}

// Every point of a grid over the pocket that a tool centre may reach (at least `reach` from
// every wall) lies within the tool radius of a cutting move at `z`.
void check_covered(const std::vector<PMove>& moves, const PocketWalls& walls, double z, double radius, double reach, double grid) {
    std::vector<std::pair<Vec2, Vec2>> cuts;  // chords of the cutting moves at z, <= 0.1 mm
    for (const PMove& m : moves) {
        if (m.rapid || std::abs(m.from.z - z) > 1e-6 || std::abs(m.to.z - z) > 1e-6) continue;
        const std::vector<Vec3> s = pocket_samples(m, 0.1);
        for (std::size_t k = 0; k + 1 < s.size(); ++k) cuts.push_back({{s[k].x, s[k].y}, {s[k + 1].x, s[k + 1].y}});
    }
    REQUIRE(!cuts.empty());
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const auto& [a, b] : cuts) {
        x0 = std::min({x0, a.x, b.x});
        y0 = std::min({y0, a.y, b.y});
        x1 = std::max({x1, a.x, b.x});
        y1 = std::max({y1, a.y, b.y});
    }
    int points = 0, missed = 0;
    for (double x = x0 - radius; x <= x1 + radius; x += grid)
        for (double y = y0 - radius; y <= y1 + radius; y += grid) {
            const Vec2 p{x, y};
            if (!walls.inside(p) || walls.distance(p) < reach) continue;
            ++points;
            bool hit = false;
            for (const auto& [a, b] : cuts) {
                const Vec2 d = b - a;
                const double l2 = dot(d, d);
                const double t = l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
                if (distance(p, a + d * t) <= radius + 1e-6) {
                    hit = true;
                    break;
                }
            }
            if (!hit && ++missed <= 3) MESSAGE(fmt::format("not cut: ({:.3f}, {:.3f})", x, y));
        }
    CHECK(points > 50);
    CHECK(missed == 0);
}

Json pocket_job(const Json& op, const std::string& tool_extra = "") {
    Json job = Json::parse(R"({"name": "p", "units": "mm", "clearance": 15,
        "tools": [{"number": 2, "type": "end-mill", "diameter": 6, "rpm": 8000}], "operations": []})");
    if (!tool_extra.empty()) job["tools"][0].update(Json::parse(tool_extra));
    job["operations"].push_back(op);
    return job;
}

Json rect_pocket(double w, double h) {
    return Json::parse(fmt::format(R"({{"type": "pocket", "tool": 2, "retractPlane": 5, "endDepth": 4, "stepDown": 2,
        "start": [0, 0], "path": [{{"line": [{0}, 0]}}, {{"line": [{0}, {1}]}}, {{"line": [0, {1}]}}, {{"line": [0, 0]}}],
        "feed": 600}})",
                                   w, h));
}

std::string error_of(const Json& job) {
    try {
        read_job(job.dump(), "test.json");
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("pocket sample: rings and finishing keep clear of the walls and islands, and cut all the pocket") {
    const Json job = sample("pocket");
    const Json& op = job["operations"][0];
    Json one = job;
    one["operations"] = Json::array({op});
    const std::vector<PMove> moves = pocket_moves(events_of(one));
    const PocketWalls walls(op);
    // Tool radius 3, radialStock 0.3 while roughing; axialStock 0.2 above the floor at Z-6.
    check_clear_of_walls(moves, walls, 0.0, 3.3, 3.0);
    double lowest = 0;
    for (const PMove& m : moves) lowest = std::min(lowest, m.to.z);
    CHECK(lowest == doctest::Approx(-6.0));
    // The floor pass at Z-6 covers every point a centre may reach with the radial stock left...
    check_covered(moves, walls, -6.0, 3.0, 3.3, 0.5);
    // ... and the roughing level at Z-5.8 (the last above the floor stock) too.
    check_covered(moves, walls, -5.8, 3.0, 3.3, 0.5);
    // The finishing pass runs at the walls' distance: some tool-centre point 3.000 from a wall.
    double nearest = 1e300;
    for (const PMove& m : moves)
        if (m.movement == Movement::finishing && !m.rapid && m.to.z < -5.99)
            for (const Vec3& p : pocket_samples(m, 0.5)) nearest = std::min(nearest, walls.distance({p.x, p.y}));
    CHECK(nearest == doctest::Approx(3.0).epsilon(1e-6));
}

TEST_CASE("pocket sample: the zigzag L-pocket is cut all over by rows and the cleanup ring") {
    const Json job = sample("pocket");
    const Json& op = job["operations"][1];
    Json one = job;
    one["operations"] = Json::array({op});
    const std::vector<PMove> moves = pocket_moves(events_of(one));
    const PocketWalls walls(op);
    check_clear_of_walls(moves, walls, 0.0, 3.0, 3.0);
    check_covered(moves, walls, -3.0, 3.0, 3.0, 0.5);
}

TEST_CASE("pocket: every strategy, order and direction covers a pocket with islands and stays clear") {
    const Json base = sample("pocket")["operations"][0];
    for (const char* strategy : {"offset", "zigzag"})
        for (const char* order : {"inside-out", "outside-in"})
            for (const char* direction : {"climb", "conventional"}) {
                if (std::string(strategy) == "zigzag" && std::string(order) == "outside-in") continue;
                Json op = base;
                op.erase("finishing");
                op.erase("leadIn");
                op.erase("leadOut");
                op["strategy"] = strategy;
                if (std::string(strategy) == "offset") op["order"] = order;
                else op.erase("order");
                op["direction"] = direction;
                op["stepOverPercent"] = std::string(strategy) == "zigzag" ? 90 : 50;
                CAPTURE(strategy);
                CAPTURE(order);
                CAPTURE(direction);
                const std::vector<PMove> moves = pocket_moves(events_of(pocket_job(op)));
                const PocketWalls walls(op);
                check_clear_of_walls(moves, walls, 0.0, 3.0, 3.0);
                check_covered(moves, walls, -6.0, 3.0, 3.0, 0.7);
                // Climb with M3: the tool left of its travel, the walls on its right. A ring along
                // the outline goes counter-clockwise when climbing (walls outside it).
            }
}

TEST_CASE("pocket: rings are walked climb or conventional against the walls") {
    Json op = rect_pocket(40, 30);
    op["endDepth"] = 2;
    op.erase("stepDown");
    for (const char* direction : {"climb", "conventional"}) {
        op["direction"] = direction;
        const std::vector<PMove> moves = pocket_moves(events_of(pocket_job(op)));
        // The last ring (inside-out: the one along the walls) turns counter-clockwise when
        // climbing: its signed area is positive.
        std::vector<Vec2> ring;
        for (auto it = moves.rbegin(); it != moves.rend(); ++it) {
            if (it->rapid) {
                if (!ring.empty()) break;
                continue;
            }
            if (it->to.z > -1.9) continue;
            ring.push_back({it->to.x, it->to.y});
        }
        double area = 0;
        for (std::size_t k = 0; k < ring.size(); ++k) area += cross(ring[k], ring[(k + 1) % ring.size()]);
        // ring is reversed (collected backwards): a ccw ring gives a negative sum here.
        CAPTURE(direction);
        CHECK((std::string(direction) == "climb" ? area < 0 : area > 0));
    }
}

TEST_CASE("pocket: a helix entry where it fits, smaller or along the ring where it does not, else an error") {
    // A wide pocket: every entry a helix of the ramp's radius, inside the pocket.
    Json op = rect_pocket(40, 30);
    op["ramp"] = Json::parse(R"({"type": "helix", "angle": 3, "radius": 2})");
    std::vector<PMove> moves = pocket_moves(events_of(pocket_job(op)));
    int helices = 0;
    for (const PMove& m : moves)
        if (m.movement == Movement::ramp && m.centre) {
            ++helices;
            CHECK(std::hypot(m.from.x - m.centre->x, m.from.y - m.centre->y) == doctest::Approx(2.0));
            // The helix circle stays 3 from the walls: its centre at least 5 inside.
            CHECK(std::min({m.centre->x, m.centre->y, 40 - m.centre->x, 30 - m.centre->y}) >= 5.0 - 1e-9);
        }
    CHECK(helices == 2);  // one per depth level
    // A slot 7 wide for a 6 mm tool: the tool centre has 1 mm; no helix fits, it ramps along.
    Json slot = rect_pocket(40, 7);
    slot["stepOver"] = 0.5;
    const Json job = pocket_job(slot);
    const std::vector<Event> events = events_of(job);
    moves = pocket_moves(events);
    int along = 0;
    for (const PMove& m : moves) {
        if (m.movement == Movement::ramp) {
            CHECK_FALSE(m.centre.has_value());
            ++along;
        }
        // Plunges end on the floor of the level above (in the air), never in the material.
        if (m.movement == Movement::plunge) CHECK((m.to.z == 0.0 || m.to.z == -2.0));
    }
    CHECK(along > 0);
    bool noted = false;
    for (const Event& e : events)
        if (const auto* s = std::get_if<OperationStart>(&e))
            for (const std::string& n : s->notes) noted = noted || n.find("ramp along the path") != std::string::npos;
    CHECK(noted);
    // A plunge needs a centre-cutting tool.
    Json plunge = rect_pocket(40, 30);
    plunge["ramp"] = Json::parse(R"({"type": "plunge"})");
    CHECK(error_of(pocket_job(plunge)).find("/operations/0/ramp/type") != std::string::npos);
    CHECK(error_of(pocket_job(plunge)).find("does not cut at its centre") != std::string::npos);
    CHECK(error_of(pocket_job(plunge, R"({"centreCutting": true})")).empty());
}

TEST_CASE("pocket: links at depth are short and inside; the rest lift to the retract plane") {
    const Json op = sample("pocket")["operations"][0];
    const std::vector<PMove> moves = pocket_moves(events_of(pocket_job(op)));
    const PocketWalls walls(op);
    int links = 0;
    bool first = true;
    for (const PMove& m : moves) {
        if (m.rapid && first) {
            first = false;  // from where the test starts counting, not a move of the program
            continue;
        }
        if (m.rapid) {
            INFO(fmt::format("rapid ({}, {}, {}) -> ({}, {}, {})", m.from.x, m.from.y, m.from.z, m.to.x, m.to.y, m.to.z));
            // A rapid is above the stock or straight up or down.
            CHECK((std::min(m.from.z, m.to.z) >= 1.0 - 1e-9 || (m.from.x == m.to.x && m.from.y == m.to.y)));
            continue;
        }
        if (m.centre || m.movement != Movement::cutting || m.from.z != m.to.z) continue;
        ++links;
    }
    CHECK(links > 10);
}

TEST_CASE("pocket: the corners the tool cannot reach are a note with their size") {
    const Json job = sample("pocket");
    const std::vector<Event> events = events_of(job);
    std::string notes;
    for (const Event& e : events)
        if (const auto* s = std::get_if<OperationStart>(&e))
            for (const std::string& n : s->notes) notes += n + "\n";
    // The sharp corner of the first pocket at (90, 60): 90 degrees, a fillet of radius 3 leaves
    // material 3 / sin(45) - 3 = 1.243 mm deep.
    CHECK(notes.find("1 corner the tool cannot reach: it leaves a fillet of radius 3.000 mm") != std::string::npos);
    CHECK(notes.find("/operations/0/path/3 (90, 60): 90 degrees, 1.243 mm deep") != std::string::npos);
}

TEST_CASE("pocket: an island whose last arc ends a micron off its circle (coordinates to 6 decimals) is not taken for touching itself") {
    // bench/gen_pocket.py --scale 10 wrote this island; region_problem said it touched itself at
    // its start, where the arc's short radial line to the given end lies.
    Json op = rect_pocket(200, 150);
    op["islands"] = Json::parse(R"([{"start": [40.918578, 60.794788], "path": [{"line": [87.23804, 60.794788]},
        {"arc": {"end": [97.282224, 70.838972], "centre": [87.23804, 70.838972], "direction": "ccw"}},
        {"line": [97.282224, 87.274911]}, {"arc": {"end": [87.23804, 97.319095], "centre": [87.23804, 87.274911], "direction": "ccw"}},
        {"line": [40.918578, 97.319095]}, {"arc": {"end": [30.874393, 87.274911], "centre": [40.918578, 87.274911], "direction": "ccw"}},
        {"line": [30.874393, 70.838972]}, {"arc": {"end": [40.918578, 60.794788], "centre": [40.918578, 70.838972], "direction": "ccw"}}]}])");
    CHECK(error_of(pocket_job(op)) == "");
}

TEST_CASE("pocket: bad input names its key") {
    Json op = rect_pocket(40, 30);
    op["stepOverPercent"] = 60;
    CHECK(error_of(pocket_job(op)).find("/operations/0/stepOverPercent") != std::string::npos);  // offset: at most 50 %
    op["strategy"] = "zigzag";
    CHECK(error_of(pocket_job(op)).empty());
    op["stepOverPercent"] = 101;
    CHECK(error_of(pocket_job(op)).find("/operations/0/stepOverPercent") != std::string::npos);
    op = rect_pocket(40, 30);
    op["islands"] = Json::parse(R"([{"start": [35, 10], "path": [{"arc": {"end": [35, 10], "centre": [40, 10], "direction": "ccw"}}]}])");
    CHECK(error_of(pocket_job(op)).find("/operations/0/islands/0") != std::string::npos);
    op = rect_pocket(40, 30);
    op["leadIn"] = Json::parse(R"({"type": "arc"})");
    CHECK(error_of(pocket_job(op)).find("/operations/0/leadIn") != std::string::npos);
    op = rect_pocket(40, 30);
    op["path"].erase(3);
    CHECK(error_of(pocket_job(op)).find("must be closed") != std::string::npos);
    op = rect_pocket(5, 30);  // narrower than the tool
    CHECK(error_of(pocket_job(op)).find("does not fit") != std::string::npos);
    op = rect_pocket(40, 30);
    op["angle"] = 30;
    CHECK(error_of(pocket_job(op)).find("/operations/0/angle") != std::string::npos);  // offset takes no angle
}

TEST_CASE("face sample: rows past every edge cover the area at each depth, and the one-way rows lift before each return") {
    const Json job = sample("face");
    const std::vector<Event> events = events_of(job);
    const std::vector<PMove> moves = pocket_moves(events);
    // Operation 1: 100 x 70 at Z1 down to Z0 with a 20 mm tool: the cuts at Z0 cover the area
    // and 2 mm beyond... check the area itself, every 1 mm.
    std::vector<std::pair<Vec2, Vec2>> cuts;
    double lowest = 1e300;
    for (const PMove& m : moves)
        if (!m.rapid && std::abs(m.to.z) < 1e-9 && std::abs(m.from.z) < 1e-9 && m.movement == Movement::finishing)
            cuts.push_back({{m.from.x, m.from.y}, {m.to.x, m.to.y}});
    for (const PMove& m : moves) lowest = std::min(lowest, m.to.z);
    CHECK(lowest == doctest::Approx(-0.3));  // operation 2 faces to Z-0.3
    REQUIRE(!cuts.empty());
    int missed = 0;
    for (double x = -2; x <= 102; x += 1)
        for (double y = -2; y <= 72; y += 1) {
            bool hit = false;
            for (const auto& [a, b] : cuts) {
                const Vec2 d = b - a;
                const double t = std::clamp(dot(Vec2{x, y} - a, d) / std::max(dot(d, d), 1e-12), 0.0, 1.0);
                hit = hit || distance(Vec2{x, y}, a + d * t) <= 10 + 1e-9;
            }
            if (!hit) ++missed;
        }
    CHECK(missed == 0);
    // Every descent to a cutting level happens beside the area, more than the tool radius out.
    for (const PMove& m : moves)
        if (m.movement == Movement::plunge && m.to.z < 1 - 1e-9 && m.to.z > -0.01)
            CHECK((m.to.x <= -10 + 1e-6 || m.to.x >= 110 - 1e-6 || m.to.y <= -10 + 1e-6 || m.to.y >= 80 - 1e-6));
}

TEST_CASE("face: bad input names its key") {
    Json job = sample("face");
    Json& op = job["operations"][0];
    op["stepOverPercent"] = 120;
    CHECK(error_of(job).find("/operations/0/stepOverPercent") != std::string::npos);
    op["stepOverPercent"] = 70;
    op["finishingStock"] = 2;
    CHECK(error_of(job).find("/operations/0/finishingStock") != std::string::npos);
    op.erase("finishingStock");
    op["start"] = Json::array({0, 0});
    CHECK(error_of(job).find("at most one of rectangle, start and path, or profile") != std::string::npos);
}

}  // namespace test_pocket
