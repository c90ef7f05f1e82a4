// How a pocket's tool gets down, found by the pocket proof (tests/oracle/test_pocket_proof.cpp,
// tests/pocket/proof.py) on random jobs, each case here one of those jobs: the finishing pass
// goes down where its lead-in has room in the cleared pocket, and its leads keep the walls'
// distance (before: a lead into the wall refused the job, or the tool went down beside the
// radial stock); a path too short to ramp on, with no room for a helix, is entered on a straight
// line or along the edge of the area (before: the job was refused); a speck of a ring is not
// ramped on lap after lap; a speck no tool may enter but by plunging refuses a tool that does
// not cut at its centre, naming the place.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/vec.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_pocket_entries {

using namespace camgen;
using Json = nlohmann::json;

namespace {

// The random jobs (seed 2026 of the proof, before the fixes), their tool as tool 1.
const char* const entry_case_0 = R"({"diameter": 7.066, "number": 1, "rpm": 8000, "type": "end-mill"} |
{"angle": 64.031, "comment": "case 0", "endDepth": 2.922, "feed": 600, "finishingFeed": 450, "islands": [{"path": [{"line": [3.827, 4.377]}, {"arc": {"centre": [3.827, 4.879], "direction": "ccw", "end": [4.329, 4.879]}}, {"line": [4.329, 7.621]}, {"arc": {"centre": [3.827, 7.621], "direction": "ccw", "end": [3.827, 8.123]}}, {"line": [2.8, 8.123]}, {"arc": {"centre": [2.8, 7.621], "direction": "ccw", "end": [2.298, 7.621]}}, {"line": [2.298, 4.879]}, {"arc": {"centre": [2.8, 4.879], "direction": "ccw", "end": [2.8, 4.377]}}], "start": [2.8, 4.377]}], "path": [{"arc": {"centre": [27.271, -105.737], "direction": "cw", "end": [54.541, 0.0]}}, {"arc": {"centre": [43.778, 6.294], "direction": "ccw", "end": [54.541, 12.587]}}, {"line": [12.587, 12.587]}, {"line": [12.587, 35.575]}, {"line": [0.0, 35.575]}, {"arc": {"centre": [36.002, 17.788], "direction": "ccw", "end": [0.0, 0.0]}}], "plungeFeed": 150, "rampFeed": 400, "retractPlane": 5, "safeDistance": 1, "start": [0.0, 0.0], "stepOverPercent": 80.917, "stockToLeave": 0.059, "strategy": "zigzag", "tool": 1, "type": "pocket"})";

const char* const entry_case_4 = R"({"diameter": 7.204, "number": 1, "rpm": 8000, "type": "end-mill"} |
{"comment": "case 4", "endDepth": 1.808, "feed": 600, "finishing": {"axialStock": 0.13, "radialStock": 0.082}, "finishingFeed": 450, "leadIn": {"radius": 0.814, "type": "arc"}, "leadOut": {"radius": 2.937, "type": "arc"}, "order": "outside-in", "path": [{"line": [58.676, 0.0]}, {"arc": {"centre": [77.85, 5.793], "direction": "cw", "end": [58.676, 11.586]}}, {"line": [11.586, 11.586]}, {"arc": {"centre": [-43.585, 29.752], "direction": "ccw", "end": [11.586, 47.918]}}, {"line": [0.0, 47.918]}, {"line": [0.0, 0.0]}], "plungeFeed": 150, "rampFeed": 400, "retractPlane": 5, "safeDistance": 1, "start": [0.0, 0.0], "stepOverPercent": 20.009, "stockToLeave": 0.373, "strategy": "offset", "tool": 1, "type": "pocket"})";

const char* const entry_case_51 = R"({"centreCutting": true, "diameter": 6.096, "number": 1, "rpm": 8000, "type": "end-mill"} |
{"comment": "case 51", "direction": "climb", "endDepth": 2.621, "feed": 600, "finishing": {"axialStock": 0.13, "radialStock": 0.365}, "finishingFeed": 450, "leadIn": {"type": "none"}, "leadOut": {"radius": 1.508, "type": "arc"}, "path": [{"arc": {"centre": [18.598, 63.105], "direction": "ccw", "end": [37.196, 0.0]}}, {"line": [37.196, 11.748]}, {"line": [11.748, 11.748]}, {"line": [11.748, 51.862]}, {"line": [0.0, 51.862]}, {"line": [0.0, 0.0]}], "plungeFeed": 150, "rampFeed": 400, "retractPlane": 5, "safeDistance": 1, "start": [0.0, 0.0], "stepOverPercent": 38.045, "stockToLeave": 0.079, "strategy": "offset", "tool": 1, "type": "pocket"})";

const char* const entry_case_840 = R"({"centreCutting": false, "diameter": 4.496, "number": 1, "rpm": 8000, "type": "end-mill"} |
{"comment": "case 840", "direction": "conventional", "endDepth": 2.959, "feed": 600, "finishingFeed": 450, "islands": [{"path": [{"line": [9.7, 9.365]}, {"line": [5.616, 13.463]}, {"line": [1.946, 9.805]}, {"line": [6.03, 5.707]}], "start": [6.03, 5.707]}, {"path": [{"arc": {"centre": [37.561, 21.597], "direction": "ccw", "end": [41.967, 21.597]}}], "start": [41.967, 21.597]}, {"path": [{"arc": {"centre": [39.134, 8.726], "direction": "cw", "end": [40.915, 8.726]}}], "start": [40.915, 8.726]}], "order": "outside-in", "path": [{"line": [17.983, 0.0]}, {"line": [17.983, 4.457]}, {"line": [31.567, 4.457]}, {"line": [31.567, 0.0]}, {"line": [43.625, 0.0]}, {"line": [43.625, 29.246]}, {"line": [31.567, 29.246]}, {"line": [31.567, 8.989]}, {"line": [17.983, 8.989]}, {"line": [17.983, 22.437]}, {"line": [0.0, 22.437]}, {"line": [0.0, 0.0]}], "plungeFeed": 150, "ramp": {"angle": 4.452, "type": "along"}, "rampFeed": 400, "retractPlane": 5, "safeDistance": 1, "start": [0.0, 0.0], "stepDown": 1.324, "stepOverPercent": 39.987, "strategy": "offset", "tool": 1, "type": "pocket"})";

const char* const entry_case_952 = R"({"centreCutting": false, "diameter": 6.927, "number": 1, "rpm": 8000, "type": "end-mill"} |
{"comment": "case 952", "direction": "conventional", "endDepth": 1.923, "feed": 600, "finishingFeed": 450, "islands": [{"path": [{"arc": {"centre": [28.979, 13.132], "direction": "ccw", "end": [32.976, 13.132]}}], "start": [32.976, 13.132]}, {"path": [{"arc": {"centre": [37.449, 11.954], "direction": "ccw", "end": [40.77, 11.954]}}], "start": [40.77, 11.954]}], "path": [{"line": [0.0, 20.488]}, {"line": [14.69, 20.488]}, {"line": [14.69, 18.682]}, {"line": [19.887, 18.682]}, {"line": [19.887, 24.278]}, {"line": [43.775, 24.278]}, {"line": [43.775, 0.0]}, {"line": [19.887, 0.0]}, {"line": [19.887, 10.679]}, {"line": [14.69, 10.679]}, {"line": [14.69, 0.0]}, {"line": [0.0, 0.0]}], "plungeFeed": 150, "ramp": {"angle": 3.517, "type": "along"}, "rampFeed": 400, "retractPlane": 5, "rows": "one-way", "safeDistance": 1, "start": [0.0, 0.0], "stepOverPercent": 59.604, "stockToLeave": 0.171, "strategy": "zigzag", "tool": 1, "type": "pocket"})";

const char* const entry_case_100 = R"({"diameter": 5.867, "number": 1, "rpm": 8000, "type": "end-mill"} |
{"comment": "case 100", "direction": "climb", "endDepth": 1.513, "feed": 600, "finishingFeed": 450, "islands": [{"path": [{"arc": {"centre": [26.128, 17.167], "direction": "ccw", "end": [28.72, 17.167]}}], "start": [28.72, 17.167]}], "order": "inside-out", "path": [{"line": [31.58, -12.495]}, {"line": [31.58, 25.3]}, {"line": [2.162, 25.3]}, {"line": [2.162, -12.495]}], "plungeFeed": 150, "rampFeed": 400, "retractPlane": 5, "safeDistance": 1, "start": [2.162, -12.495], "stepOver": 1.982, "stockToLeave": 0.099, "strategy": "offset", "tool": 1, "type": "pocket"})";

// A job of one pocket from "TOOL | OPERATION".
Json entry_job(const char* text) {
    const std::string s = text;
    const auto bar = s.find(" |\n");
    return {{"name", "entries"}, {"units", "mm"}, {"clearance", 15}, {"tools", Json::array({Json::parse(s.substr(0, bar))})},
            {"operations", Json::array({Json::parse(s.substr(bar + 3))})}};
}

Profile entry_loop(const Json& o) {
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
    // As camgen reads it: an arc whose end is within 0.001 mm of its circle is the exact arc
    // through its ends (case 0's outline arcs, centres to 0.001 mm, move by up to 0.0002 mm).
    make_arcs_exact(p, arc_radius_tolerance);
    return p;
}

// The distance from a point to the nearest wall or island of the job's pocket.
double entry_wall_distance(const Json& op, Vec2 p) {
    double d = distance_to(entry_loop(op), p);
    if (op.contains("islands"))
        for (const Json& i : op["islands"]) d = std::min(d, distance_to(entry_loop(i), p));
    return d;
}

// A move of the tool centre: straight (no centre) or an arc, from where the one before ended.
struct EntryMove {
    Vec3 from, to;
    std::optional<Vec2> centre;
    ArcDirection direction = ArcDirection::ccw;
    int turns = 0;
    Movement movement = Movement::cutting;
    bool rapid = false;
};

std::vector<EntryMove> entry_moves(const Json& job) {
    std::vector<EntryMove> out;
    Vec3 at{};
    for (const Event& e : expand_job(read_job(job.dump(), "entries.json"))) {
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

// The smallest wall distance along a move (every 0.05 mm or closer).
double entry_clearance(const Json& op, const EntryMove& m) {
    double d = 1e300;
    if (!m.centre) {
        const double l = std::hypot(m.to.x - m.from.x, m.to.y - m.from.y);
        const int n = std::max(1, static_cast<int>(std::ceil(l / 0.05)));
        for (int k = 0; k <= n; ++k) {
            const double t = static_cast<double>(k) / n;
            d = std::min(d, entry_wall_distance(op, {m.from.x + (m.to.x - m.from.x) * t, m.from.y + (m.to.y - m.from.y) * t}));
        }
        return d;
    }
    const Vec2 c = *m.centre, a{m.from.x, m.from.y}, b{m.to.x, m.to.y};
    const double rho = distance(a, c);
    const double a0 = std::atan2(a.y - c.y, a.x - c.x), a1 = std::atan2(b.y - c.y, b.x - c.x);
    double sweep = m.direction == ArcDirection::ccw ? a1 - a0 : a0 - a1;
    while (sweep <= 1e-12) sweep += two_pi;
    sweep += two_pi * m.turns;
    const int n = std::max(2, static_cast<int>(std::ceil(sweep * rho / 0.05)));
    for (int k = 0; k <= n; ++k)
        d = std::min(d, entry_wall_distance(op, c + unit_at(a0 + (m.direction == ArcDirection::ccw ? 1 : -1) * sweep * k / n) * rho));
    return d;
}

std::string entry_notes(const Json& job) {
    std::string notes;
    for (const Event& e : expand_job(read_job(job.dump(), "entries.json")))
        if (const auto* s = std::get_if<OperationStart>(&e))
            for (const std::string& n : s->notes) notes += n + "\n";
    return notes;
}

}  // namespace

TEST_CASE("pocket finishing: the tool goes down where the lead-in has room in the cleared pocket, and the leads keep the walls' distance") {
    // The sample's first pocket (its walls' loop started at a corner, where the lead-in began on
    // the wall's offset: the tool went down beside the radial stock), and two random jobs whose
    // leads ran into a wall (refused before).
    Json sample_job;
    {
        std::ifstream f(std::string(CAMGEN_SOURCE_DIR) + "/samples/pocket.json");
        sample_job = Json::parse(f);
        sample_job["operations"] = Json::array({sample_job["operations"][0]});
    }
    for (const Json& job : {sample_job, entry_job(entry_case_4), entry_job(entry_case_51)}) {
        const Json& op = job["operations"][0];
        CAPTURE(op["comment"].get<std::string>());
        const double r = job["tools"][0]["diameter"].get<double>() / 2;
        const double stock = op.value("stockToLeave", 0.0), radial = op["finishing"].value("radialStock", 0.0);
        const double bottom = -op["endDepth"].get<double>();
        int descents = 0, leads = 0;
        for (const EntryMove& m : entry_moves(job)) {
            if (m.rapid) continue;
            // The finishing pass's descents: straight down to the end depth (on the loop itself,
            // beside the radial stock, where the job asks for no lead-in).
            if (m.movement == Movement::plunge && std::abs(m.to.z - bottom) < 1e-9 && !m.centre) {
                ++descents;
                const bool lead_in = op["leadIn"].value("type", "none") != "none";
                CHECK(entry_wall_distance(op, {m.to.x, m.to.y}) >= r + stock + (lead_in ? radial : 0.0) - 1e-6);
            }
            if (m.movement == Movement::lead_in || m.movement == Movement::lead_out) {
                ++leads;
                CHECK(entry_clearance(op, m) >= r + stock - 1e-6);
            }
        }
        CHECK(descents >= 1);
        if (op["leadOut"].value("type", "none") != "none") CHECK(leads >= 1);
    }
}

TEST_CASE("pocket entries: a row too short to ramp on, with no room for a helix, is entered on a straight line or along the area's edge") {
    // Zigzag rows: the first of a chunk shorter than the tool radius at the narrow end of an area
    // (case 0), and rows across a curved sliver of tool-centre area beside an island (case 952):
    // both were refused ("the tool cannot enter the pocket"); the tool does not cut at its centre.
    for (const char* text : {entry_case_0, entry_case_952}) {
        const Json job = entry_job(text);
        const Json& op = job["operations"][0];
        CAPTURE(op["comment"].get<std::string>());
        const double r = job["tools"][0]["diameter"].get<double>() / 2;
        const double keep = r + op.value("stockToLeave", 0.0);
        int ramps = 0;
        for (const EntryMove& m : entry_moves(job)) {
            if (m.movement != Movement::ramp) continue;
            ++ramps;
            CHECK(entry_clearance(op, m) >= keep - 1e-6);
        }
        CHECK(ramps > 0);
        CHECK(entry_notes(job).find("ramp back and forth on a straight line or along the edge of the area") != std::string::npos);
    }
}

TEST_CASE("pocket entries: a speck of a ring is not ramped along lap after lap") {
    // An offset ring 0.15 mm round (beside a corner of the outline) was entered by ramping along
    // it, hundreds of laps a level: a program of 9,000 blocks. Now a straight line at least the
    // tool radius long: a few hundred moves in all.
    const Json job = entry_job(entry_case_840);
    int ramps = 0;
    const std::vector<EntryMove> moves = entry_moves(job);
    for (const EntryMove& m : moves) ramps += m.movement == Movement::ramp;
    CHECK(ramps > 0);
    CHECK(ramps < 500);
    CHECK(moves.size() < 1000);
}

TEST_CASE("pocket entries: a speck of tool-centre area that only a plunge reaches refuses a tool that does not cut at its centre") {
    // An island near a corner cuts the corner off: the tool centre can be there only on a spot
    // 0.05 mm across, and the material around it reaches no other pass.
    Json job = entry_job(entry_case_100);
    std::string error;
    try {
        (void)read_job(job.dump(), "entries.json");
    } catch (const InputError& e) {
        error = e.what();
    }
    CHECK(error.find("/operations/0/tool: the tool cannot enter the pocket at (28.499 mm, 22.268 mm)") != std::string::npos);
    CHECK(error.find("does not cut at its centre") != std::string::npos);
    // A centre-cutting tool plunges there.
    job["tools"][0]["centreCutting"] = true;
    int plunges = 0;
    for (const EntryMove& m : entry_moves(job))
        if (m.movement == Movement::plunge && std::abs(m.to.x - 28.4986) < 0.001 && std::abs(m.to.y - 22.2675) < 0.001) ++plunges;
    CHECK(plunges >= 1);
}

}  // namespace test_pocket_entries
