// LinuxCNC oracle for engraving (issue 29, item 4): samples/engrave.json posted for linuxcnc and
// fanuc runs through rs274 to PROGRAM_END, move for move as camgen reads it back, and the cuts at
// the part number's depth in rs274's own trace are the font's glyphs, read here from the .jhf
// file independently of camgen's reader, scaled to the cap height and placed, within 0.001 mm.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "camgen/operations/registry.hpp"
#include "camgen/post/post.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_engrave_oracle {

using namespace camgen;
using OStep = camgen::oracle::Step;

namespace {

std::string engrave_read_text(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

using Line = std::vector<Vec2>;

// The glyphs of `text` in `font` (one record a line, as Debian's files are), the cap height
// `height` from H's extent, centred on `anchor` along +X, baseline on it.
std::vector<Line> oracle_glyphs(const std::string& font, const std::string& text, double height, Vec2 anchor) {
    std::vector<std::string> records;
    std::istringstream in(engrave_read_text("/usr/share/hershey-fonts/" + font + ".jhf"));
    for (std::string l; std::getline(in, l);) records.push_back(l);
    auto strokes_of = [&](char c, int& left, int& right) {
        const std::string& r = records.at(static_cast<std::size_t>(c - 32));
        left = r[8] - 'R', right = r[9] - 'R';
        std::vector<std::vector<std::pair<int, int>>> out(1);
        for (std::size_t i = 10; i + 1 < r.size(); i += 2) {
            if (r[i] == ' ') out.emplace_back();
            else out.back().push_back({r[i] - 'R', r[i + 1] - 'R'});
        }
        return out;
    };
    int l = 0, r = 0, top = 100, base = -100;
    for (const auto& s : strokes_of('H', l, r))
        for (const auto& p : s) top = std::min(top, p.second), base = std::max(base, p.second);
    const double scale = height / (base - top);
    double width = 0.0;
    for (char c : text) {
        strokes_of(c, l, r);
        width += (r - l) * scale;
    }
    std::vector<Line> out;
    double pen = anchor.x - width / 2.0;
    for (char c : text) {
        const auto strokes = strokes_of(c, l, r);
        for (const auto& s : strokes) {
            Line line;
            for (const auto& p : s) {
                const Vec2 v{pen + (p.first - l) * scale, anchor.y + (base - p.second) * scale};
                if (line.empty() || std::hypot(v.x - line.back().x, v.y - line.back().y) > 1e-9) line.push_back(v);
            }
            if (line.size() >= 2) out.push_back(line);
        }
        pen += (r - l) * scale;
    }
    return out;
}

// rs274's cutting runs at depth z: from each feed down to z, the feeds at z that follow.
std::vector<Line> oracle_runs(const std::vector<OStep>& steps, double z) {
    std::vector<Line> runs;
    Vec3 at{};
    bool open = false;
    for (const OStep& s : steps) {
        const bool at_z = s.kind == OStep::Kind::feed && std::abs(s.to.z - z) < 1e-6;
        if (at_z && std::abs(at.z - z) > 1e-6) runs.push_back({{s.to.x, s.to.y}}), open = true;
        else if (at_z && open) runs.back().push_back({s.to.x, s.to.y});
        else open = false;
        if (s.kind == OStep::Kind::traverse || s.kind == OStep::Kind::feed || s.kind == OStep::Kind::arc) at = s.to;
    }
    return runs;
}

// The largest distance between a glyph stroke and the run that is it (forwards or backwards),
// every stroke matched to a run of its own; infinity where one has none.
double oracle_worst(const std::vector<Line>& runs, const std::vector<Line>& want) {
    std::vector<bool> used(runs.size(), false);
    double worst = 0.0;
    for (const Line& w : want) {
        double best = INFINITY;
        std::size_t which = 0;
        for (std::size_t k = 0; k < runs.size(); ++k) {
            if (used[k] || runs[k].size() != w.size()) continue;
            for (bool back : {false, true}) {
                double d = 0.0;
                for (std::size_t i = 0; i < w.size(); ++i) {
                    const Vec2 a = runs[k][back ? w.size() - 1 - i : i];
                    d = std::max(d, std::hypot(a.x - w[i].x, a.y - w[i].y));
                }
                if (d < best) best = d, which = k;
            }
        }
        if (best == INFINITY) return INFINITY;
        used[which] = true;
        worst = std::max(worst, best);
    }
    return worst;
}

}  // namespace

TEST_CASE("engraving: rs274 runs samples/engrave.json for linuxcnc and fanuc; the part number's cuts are the font's glyphs") {
    const std::string rs274 = oracle::find_rs274().value_or("");
    REQUIRE_MESSAGE(!rs274.empty(), "rs274 (LinuxCNC's standalone interpreter) was not found");
    const Job job = read_job(engrave_read_text(CAMGEN_SOURCE_DIR "/samples/engrave.json"), "engrave.json");
    // The sample's part number: "SN 2026-042" in rowmans, 4 high, centred on (40, 6), 0.2 deep.
    const std::vector<Line> want = oracle_glyphs("rowmans", "SN 2026-042", 4, {40, 6});
    REQUIRE(want.size() == 13);
    for (const char* name : {"linuxcnc", "fanuc"}) {
        INFO(std::string(name));
        const Machine machine = load_machine(name);
        const std::string program = oracle::posted_program(job, machine);
        std::vector<OStep> theirs;
        REQUIRE_NOTHROW(theirs = oracle::run_rs274(rs274, program));
        // camgen reads the program as rs274 runs it (from the first feed on).
        oracle::check_read_as_run(theirs, program, machine);
        // The part number is the only cut at Z-0.2 that runs along +X only (the arc's text is at
        // Z-0.2 too): its runs are those within its band of Y.
        std::vector<Line> runs;
        for (const Line& r : oracle_runs(theirs, -0.2))
            if (std::all_of(r.begin(), r.end(), [](Vec2 p) { return p.y > 4 && p.y < 11; })) runs.push_back(r);
        CHECK(runs.size() == want.size());
        const double worst = oracle_worst(runs, want);
        MESSAGE(std::string(name) << ": " << runs.size() << " strokes of the part number, worst distance from the font's glyphs " << worst << " mm");
        CHECK(worst <= 0.001);
    }
}

}  // namespace test_engrave_oracle
