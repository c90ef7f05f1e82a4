// turn-groove and turn-part (issue 30): the blade's moves measured against the groove and the
// parting slot worked out here from the job's keys alone (walls, bottom, 45-degree chamfers):
// every feed keeps the blade's edge out of what the part keeps, every rapid runs where the bar
// or the moves before it left air, no Z move below the surface except the pass along the
// bottom and the chamfers, every feed starts within approachDistance of the surface, and the
// moves together cut the whole groove. Many random grooves and partings, both programmed
// corners, pecks of both kinds, chamfers; and the bad inputs refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/design.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

namespace test_turn_groove {

using namespace camgen;
namespace fs = std::filesystem;

namespace {

std::string refusal(const std::string& text) {
    try {
        (void)read_job(text, "groove.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// The blade's programmed point's moves in (Z, radius).
struct BladeMove {
    Vec2 from, to;
    bool rapid = false;
};

std::vector<BladeMove> blade_moves(const Job& job) {
    std::vector<BladeMove> out;
    Vec2 at{job.clearance, 0.0};
    bool started = false;
    std::vector<Event> events;
    for (const Event& e : expand_job(job)) {
        if (const auto* c = std::get_if<GrooveCycle>(&e)) {
            const std::vector<Event> moves = groove_cycle_moves(*c);
            events.insert(events.end(), moves.begin(), moves.end());
        } else {
            events.push_back(e);
        }
    }
    for (const Event& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e)) {
            const Vec2 to{r->to.z, r->to.x};
            if (started) out.push_back({at, to, true});
            at = to, started = true;
        } else if (const auto* l = std::get_if<Linear>(&e)) {
            const Vec2 to{l->to.z, l->to.x};
            out.push_back({at, to, false});
            at = to;
        } else {
            REQUIRE(std::get_if<Arc>(&e) == nullptr);
        }
    }
    return out;
}

// What the part keeps: the largest radius of material at Z z after the operation, from the
// keys: the surface R, a slot [lo, hi] down to `bottom`, 45-degree chamfers of c on its edges
// (left: whether the -Z edge has one).
struct Kept {
    double R = 0, lo = 0, hi = 0, bottom = 0, c = 0;
    bool left_chamfer = true;
    double at(double z) const {
        if (z > lo && z < hi) return bottom;
        if (c > 0 && z >= hi && z < hi + c) return R - c + (z - hi);
        if (left_chamfer && c > 0 && z <= lo && z > lo - c) return R - c + (lo - z);
        return R;
    }
};

// Checks one operation's moves (the only operation of `job`) against `kept`: the blade `w`
// wide, programmed at its left corner (or its right, `right`), the bar of radius R before.
void check_blade(const Job& job, const Kept& kept, double w, bool right, double approach) {
    const std::vector<BladeMove> moves = blade_moves(job);
    REQUIRE(!moves.empty());
    const double off = right ? -w : 0.0;  // the left corner from the programmed point
    // What the moves have cleared so far, on a grid of Z.
    const double z0 = kept.lo - kept.c - approach - 2 * w - 1, z1 = kept.hi + kept.c + approach + 2 * w + 1;
    const double dz = 0.002;
    const int n = static_cast<int>((z1 - z0) / dz) + 1;
    std::vector<double> cleared(static_cast<std::size_t>(n), kept.R);
    const double eps = 1e-6;
    int feeds = 0;
    for (std::size_t m = 0; m < moves.size(); ++m) {
        const BladeMove& mv = moves[m];
        INFO("move " << m << (mv.rapid ? " rapid" : " feed") << " from Z" << mv.from.x << " R" << mv.from.y << " to Z"
                     << mv.to.x << " R" << mv.to.y);
        if (mv.from.y > kept.R + approach * 3 && mv.to.y > kept.R + approach * 3) continue;  // far out: air
        if (!mv.rapid) {
            ++feeds;
            // No feed from far away: it starts within approachDistance of the surface.
            CHECK(mv.from.y <= kept.R + approach + eps);
        }
        // Z moves only at the air level, but for the bottom pass and the chamfers (feeds).
        if (mv.rapid && std::abs(mv.to.x - mv.from.x) > 1e-9) CHECK(std::min(mv.from.y, mv.to.y) >= kept.R + approach - eps);
        // The least radius the blade's edge reaches at Z z along the move: where its left corner
        // lies in [z - w, z] (the edge a hair narrower: a wall's own Z is the part's), the radius
        // linear along the move, least at an end of that stretch; infinity where it never covers z.
        const double l0 = mv.from.x + off, l1 = mv.to.x + off, du = l1 - l0, dv = mv.to.y - mv.from.y;
        auto reach = [&](double z) -> double {
            const double lo = z - w + 1e-7, hi = z - 1e-7;
            double t0 = 0, t1 = 1;
            if (std::abs(du) < 1e-12) {
                if (l0 < lo || l0 > hi) return INFINITY;
            } else {
                double s0 = (lo - l0) / du, s1 = (hi - l0) / du;
                if (s0 > s1) std::swap(s0, s1);
                t0 = std::max(0.0, s0), t1 = std::min(1.0, s1);
                if (t0 > t1) return INFINITY;
            }
            return std::min(mv.from.y + t0 * dv, mv.from.y + t1 * dv);
        };
        if (!mv.rapid)
            for (double z : {kept.lo - kept.c, kept.lo, kept.hi, kept.hi + kept.c})
                for (double e : {-2e-7, 2e-7}) {
                    INFO("Z " << z + e << " kept " << kept.at(z + e));
                    CHECK(reach(z + e) >= kept.at(z + e) - eps);
                }
        // The deepest the move goes into what it must leave (a rapid: what the bar and the moves
        // before it left; a feed: what the part keeps), and where.
        double worst = 0, worst_z = 0;
        for (int k = 0; k < n; ++k) {
            const double z = z0 + k * dz, r = reach(z);
            if (!std::isfinite(r)) continue;
            double& c = cleared[static_cast<std::size_t>(k)];
            const double into = (mv.rapid ? std::min(kept.R, c) : kept.at(z)) - r;
            if (into > worst) worst = into, worst_z = z;
            c = std::min(c, r);
        }
        INFO("deepest at Z " << worst_z << ": " << worst << " mm");
        CHECK(worst <= eps);
    }
    CHECK(feeds > 0);
    // The moves together cut everything the design removes: cleared down to the kept radius.
    for (int k = 0; k < n; ++k) {
        const double z = z0 + k * dz;
        if (z < kept.lo - kept.c - 1e-3 || z > kept.hi + kept.c + 1e-3) continue;
        if (std::abs(z - kept.lo) < 3e-3 || std::abs(z - kept.hi) < 3e-3) continue;  // the walls: the grid's step
        if (cleared[static_cast<std::size_t>(k)] > kept.at(z) + eps) {
            INFO("Z " << z << ": cleared to " << cleared[static_cast<std::size_t>(k)] << ", kept " << kept.at(z));
            CHECK(cleared[static_cast<std::size_t>(k)] <= kept.at(z) + eps);
            break;
        }
    }
}

std::string groove_job(const std::string& tool, const std::string& op) {
    return fmt::format(R"({{"clearance": 20, "stock": {{"bar": {{"diameter": 40, "length": 80, "faceZ": 0}}}},
  "tools": [{}], "operations": [{}]}})",
                       tool, op);
}

}  // namespace

TEST_CASE("turn-groove: the sample-like groove's moves, worked out by hand") {
    // A 3 mm tool in a 3 mm groove, 2 deep from D40 at Z-10: one plunge from 1 mm above.
    const Job job = read_job(groove_job(R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 800})",
                                        R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3, "depth": 2})"),
                             "g.json");
    std::vector<std::string> got;
    for (const BladeMove& m : blade_moves(job)) got.push_back(fmt::format("{} Z{} R{}", m.rapid ? "G0" : "G1", m.to.x, m.to.y));
    const std::vector<std::string> want{"G0 Z-13 R21", "G0 Z-13 R21", "G1 Z-13 R18", "G0 Z-13 R21", "G0 Z-13 R21", "G0 Z20 R21"};
    // (the first rapid, to R21 at the clearance, is the start; rapids to where the tool is stay)
    CHECK(got == want);
    check_blade(job, {20, -13, -10, 18, 0}, 3, false, 1);
}

TEST_CASE("turn-groove: random grooves keep the blade out of the part and cut the whole groove") {
    std::mt19937 rng(3031);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n = 0; n < 60; ++n) {
        const double w = 1.5 + 3.0 * u(rng);
        const double width = u(rng) < 0.3 ? w : w + 10.0 * u(rng);
        const double depth = 0.5 + 6.0 * u(rng);
        const double c = u(rng) < 0.5 ? 0.0 : std::min(depth * 0.9, 0.2 + 1.5 * u(rng));
        const double z = -5.0 - 20.0 * u(rng);
        const bool right = u(rng) < 0.5;
        const double a = 0.5 + u(rng);
        std::string extra;
        if (u(rng) < 0.6) extra += fmt::format(R"(, "peckDepth": {:.3f})", 0.3 + 2.0 * u(rng));
        if (!extra.empty() && u(rng) < 0.5) extra += R"(, "fullRetract": true)";
        if (!extra.empty() && u(rng) < 0.5) extra += fmt::format(R"(, "peckRetract": {:.3f})", 0.1 + u(rng));
        if (width > w && u(rng) < 0.5) extra += fmt::format(R"(, "stepover": {:.3f})", w * (0.3 + 0.7 * u(rng)));
        if (u(rng) < 0.3) extra += R"(, "dwell": 0.4)";
        const std::string text = groove_job(
            fmt::format(R"({{"number": 1, "type": "grooving-tool", "width": {:.3f}, "rpm": 800{}}})", w,
                        right ? R"(, "orientation": 1)" : ""),
            fmt::format(R"({{"type": "turn-groove", "tool": 1, "feed": 30, "z": {:.3f}, "width": {:.3f}, "depth": {:.3f},
                          "chamfer": {:.3f}, "approachDistance": {:.3f}{}}})",
                        z, width, depth, c, a, extra));
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "g.json"));
        const auto& op = std::get<TurnGrooveOp>(job.operations[0]);
        // From the text's rounded numbers, as the job reads them.
        const double wz = op.z_right, wl = op.z_right - std::stod(fmt::format("{:.3f}", width));
        check_blade(job, {20, wl, wz, 20 - std::stod(fmt::format("{:.3f}", depth)), std::stod(fmt::format("{:.3f}", c))},
                    op.blade.width, right, op.approach);
    }
}

TEST_CASE("turn-part: random partings keep the blade out of the part and the bar, and part through") {
    std::mt19937 rng(3032);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n = 0; n < 40; ++n) {
        const double w = 2.0 + 2.0 * u(rng);
        const double c = u(rng) < 0.5 ? 0.0 : 0.2 + 1.5 * u(rng);
        const double z = -10.0 - 40.0 * u(rng);
        const bool right = u(rng) < 0.5;
        const double to = u(rng) < 0.5 ? 0.0 : 0.5 + u(rng);
        std::string extra;
        if (u(rng) < 0.6) extra += fmt::format(R"(, "peckDepth": {:.3f})", 1.0 + 4.0 * u(rng));
        if (!extra.empty() && u(rng) < 0.5) extra += R"(, "fullRetract": true)";
        const std::string text = groove_job(
            fmt::format(R"({{"number": 1, "type": "parting-tool", "width": {:.3f}, "rpm": 600{}}})", w,
                        right ? R"(, "orientation": 1)" : ""),
            fmt::format(R"({{"type": "turn-part", "tool": 1, "feed": 40, "z": {:.3f}, "toX": {:.3f}, "chamfer": {:.3f}{}}})", z,
                        to, c, extra));
        INFO(text);
        Job job;
        REQUIRE_NOTHROW(job = read_job(text, "p.json"));
        const auto& op = std::get<TurnPartOp>(job.operations[0]);
        Kept k{20, op.z - op.blade.width, op.z, op.end, op.chamfer, false};
        check_blade(job, k, op.blade.width, right, op.approach);
    }
}

TEST_CASE("turn-part: the feed drops to reducedFeed below reducedFeedX") {
    const Job job = read_job(groove_job(R"({"number": 1, "type": "parting-tool", "width": 3, "rpm": 500})",
                                        R"({"type": "turn-part", "tool": 1, "feedMode": "per-revolution", "feed": 0.08,
                                           "z": -30, "reducedFeedX": 8, "reducedFeed": 0.04})"),
                             "p.json");
    std::vector<std::pair<double, double>> feeds;  // (radius reached, feed mm/min)
    for (const Event& e : expand_job(job))
        if (const auto* l = std::get_if<Linear>(&e)) feeds.push_back({l->to.x, l->feed});
    REQUIRE(feeds.size() == 2);
    CHECK(feeds[0].first == doctest::Approx(4));
    CHECK(feeds[0].second == doctest::Approx(40));
    CHECK(feeds[1].first == doctest::Approx(0));
    CHECK(feeds[1].second == doctest::Approx(20));
}

TEST_CASE("turn-groove and turn-part refuse what they cannot cut") {
    const std::string tool = R"({"number": 1, "type": "grooving-tool", "width": 3, "rpm": 800, "fluteLength": 12})";
    CHECK(refusal(groove_job(tool, R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 2.5, "depth": 2})"))
              .find("narrower than tool 1's width 3") != std::string::npos);
    CHECK(refusal(groove_job(tool, R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3, "depth": 20})"))
              .find("reaches the spindle axis") != std::string::npos);
    CHECK(refusal(groove_job(tool, R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3, "depth": 14})"))
              .find("more than tool 1's fluteLength 12") != std::string::npos);
    CHECK(refusal(groove_job(tool, R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": 2, "width": 3, "depth": 2})"))
              .find("/operations/0/z: z 2.000 mm is beyond the bar's face") != std::string::npos);
    CHECK(refusal(groove_job(tool, R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3})"))
              .find("give the groove's depth or its bottomX") != std::string::npos);
    CHECK(refusal(groove_job(R"({"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 800})",
                             R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3, "depth": 2})"))
              .find("needs a grooving-tool or parting-tool") != std::string::npos);
    const std::string part = R"({"number": 1, "type": "parting-tool", "width": 3, "rpm": 800, "fluteLength": 15})";
    const std::string short_blade = refusal(groove_job(part, R"({"type": "turn-part", "tool": 1, "feed": 30, "z": -30})"));
    CHECK(short_blade.find("/operations/0/tool") != std::string::npos);
    CHECK(short_blade.find("too short to part off") != std::string::npos);
    CHECK(refusal(groove_job(part, R"({"type": "turn-part", "tool": 1, "feed": 30, "z": -30, "toX": 12})")).empty());
    // Pecks: at least 0.01 mm, at most 10000 a plunge (an exploratory tester: a peckDepth of 1e-9
    // hung turn-part building billions of pecks, and made turn-groove write 400,000 pecks that
    // did not advance, then feed the rest at once).
    for (const char* op : {R"({"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3, "depth": 2, "peckDepth": 1e-9})",
                           R"({"type": "turn-part", "tool": 1, "feed": 30, "z": -30, "toX": 12, "peckDepth": 1e-9})",
                           R"({"type": "turn-part", "tool": 1, "feed": 30, "z": -30, "toX": 12, "peckDepth": 0.009})"})
        CHECK(refusal(groove_job(std::string(op).find("part") != std::string::npos ? part : tool, op))
                  .find("/operations/0/peckDepth: peckDepth must be at least 0.010 mm") != std::string::npos);
    CHECK(refusal(groove_job(part, R"({"type": "turn-part", "tool": 1, "feed": 30, "z": -30, "toX": 12, "peckDepth": 0.01})")).empty());
    const std::string big = R"({"clearance": 20, "stock": {"bar": {"diameter": 300, "length": 80, "faceZ": 0}},
      "tools": [{"number": 1, "type": "parting-tool", "width": 3, "rpm": 300, "fluteLength": 200}],
      "operations": [{"type": "turn-part", "tool": 1, "feed": 30, "z": -30, "peckDepth": 0.01}]})";
    CHECK(refusal(big).find("/operations/0/peckDepth: peckDepth 0.010 mm makes 15000 pecks of the 150.000 mm deep plunge, more "
                            "than 10000: use larger pecks") != std::string::npos);
    // On a mill: the machine kind's check names the operation.
    const Job job = read_job(R"({"clearance": 20, "tools": [{"number": 1, "type": "grooving-tool", "width": 3, "rpm": 800}],
      "operations": [{"type": "turn-groove", "tool": 1, "feed": 30, "z": -10, "width": 3, "depth": 2, "startX": 30}]})",
                             "g.json");
    try {
        check_machine_kind(job, MachineKind::mill, "wabeco");
        FAIL("a groove on a mill was let through");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("/operations/0/type") != std::string::npos);
        CHECK(std::string(e.what()).find("turn-groove") != std::string::npos);
    }
}

TEST_CASE("lathe design: the shaft's groove and parting are cuts of their blade; a groove 0.1 mm too deep is a gouge") {
    const std::string shaft = CAMGEN_SOURCE_DIR "/samples/shaft.json";
    const Job job = read_job(test::read_file(shaft), "shaft.json");
    const PartDesign design = part_design(job);
    CHECK(design.unchecked.empty());
    REQUIRE(design.lathe.profiles.size() == 6);
    // The groove: D30 (radius 15), walls Z-12 and Z-16, bottom D27, chamfers 0.5.
    const LatheTurnDesign& g = design.lathe.profiles[3];
    CHECK(g.path == "/operations/5");
    CHECK(g.nose == 0);
    CHECK(g.blade_hi - g.blade_lo == doctest::Approx(3));
    CHECK(g.radius_range(-14, -14)->first == doctest::Approx(13.5));
    CHECK(g.radius_range(-11.75, -11.75)->first == doctest::Approx(14.75));
    CHECK(g.radius_range(-16.25, -16.25)->first == doctest::Approx(14.75));
    // The blade clears the bottom, and nothing beyond its reach.
    CHECK(g.left_radius(-14) == doctest::Approx(13.5));
    // The parting: the slot Z-45..-42 through, the chamfer on the part's edge.
    const LatheTurnDesign& p = design.lathe.profiles[5];
    CHECK(p.path == "/operations/7");
    CHECK(p.radius_range(-43.5, -43.5)->first == doctest::Approx(0));
    CHECK(p.radius_range(-41.75, -41.75)->first == doctest::Approx(21.75));
    const fs::path dir = test::scratch("simulate-groove");
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        CAPTURE(machine);
        const std::string posted = (dir / (machine + ".nc")).string();
        REQUIRE(test::run({shaft, "--machine", machine, "-q", "-o", posted}).code == 0);
        const test::Run clean = test::run({"simulate", posted, "--machine", machine, "--job", shaft, "--bar", "44,70,1"});
        CHECK_MESSAGE(clean.code == 0, std::string(clean.out + clean.err));
        CHECK_MESSAGE(clean.out.find("  the part is as designed\n") != std::string::npos, clean.out);
        // The finishing pass along the groove's bottom (X27 to Z-15) run at X26.8: 0.1 mm deep.
        const std::vector<std::string> lines = test::lines_of(test::read_file(posted));
        std::string text;
        bool in_groove = false, edited = false;
        std::size_t line = 0;
        for (std::size_t i = 0; i < lines.size(); ++i) {
            std::string l = lines[i];
            if (l.find("groove 4 wide") != std::string::npos) in_groove = true;
            if (in_groove && !edited && std::regex_search(l, std::regex(R"(X27(\.0+)?($|\s))"))) {
                l = std::regex_replace(l, std::regex(R"(X27(\.0+)?)"), "X26.8");
                edited = true;
                line = i + 1;
            }
            text += l + "\n";
        }
        REQUIRE(edited);
        const std::string deep = (dir / (machine + "-deep.nc")).string();
        std::ofstream(deep) << text;
        const test::Run r = test::run({"simulate", deep, "--machine", machine, "--job", shaft, "--bar", "44,70,1"});
        CHECK(r.code == 1);
        CHECK_MESSAGE(r.out.find("error: gouge: /operations/5 (the part inside the profile): material removed 0.1 mm inside the "
                                 "designed radius 13.5 at Z-") != std::string::npos,
                      r.out);
        CHECK_MESSAGE(r.out.find(fmt::format("by line {} (cut at", line)) != std::string::npos, r.out);
    }
}

}  // namespace test_turn_groove

namespace test_turn_groove {

TEST_CASE("turn-part: nothing cuts after a part-off through the centre; a pip stops the program for the operator") {
    const std::string tools = R"({"number": 1, "type": "parting-tool", "width": 3, "rpm": 500},
      {"number": 2, "type": "grooving-tool", "width": 3, "rpm": 700})";
    const std::string part = R"({"type": "turn-part", "tool": 1, "feed": 30, "z": -42})";
    const std::string groove = R"({"type": "turn-groove", "tool": 2, "feed": 30, "z": -12, "width": 3, "depth": 1})";
    // Through the centre, then a groove on the part that has fallen off: refused at the groove.
    const std::string after = refusal(groove_job(tools, part + ", " + groove));
    CHECK(after.find("/operations/1: /operations/0 parts the part off through the centre before this operation") !=
          std::string::npos);
    // A stop after it (to take the part out) is no cut; nor is parting off last.
    CHECK(refusal(groove_job(tools, part + R"(, {"type": "stop", "message": "take the part"})")).empty());
    CHECK(refusal(groove_job(tools, groove + ", " + part)).empty());
    // On a pip: the program stops after the plunge (and its retract) for the part to be broken
    // off, before the next operation's tool moves; without a pip it does not stop.
    const std::string pip = R"({"type": "turn-part", "tool": 1, "feed": 30, "z": -42, "toX": 1})";
    for (const bool with_pip : {true, false}) {
        CAPTURE(with_pip);
        const Job job = read_job(groove_job(tools, (with_pip ? pip : part) + (with_pip ? ", " + groove : std::string())), "p.json");
        const std::vector<Event> events = expand_job(job);
        std::size_t stop = events.size(), last_part_move = 0, first_groove_move = events.size();
        int op = -1;
        for (std::size_t i = 0; i < events.size(); ++i) {
            if (std::holds_alternative<OperationStart>(events[i])) ++op;
            if (const auto* s = std::get_if<Stop>(&events[i])) {
                stop = i;
                CHECK(s->kind == StopKind::mandatory);
                CHECK(s->message.find("break off the parted part") != std::string::npos);
            }
            const bool move = std::holds_alternative<Rapid>(events[i]) || std::holds_alternative<Linear>(events[i]);
            if (move && op == 0) last_part_move = i;
            if (move && op == 1 && first_groove_move == events.size()) first_groove_move = i;
        }
        if (with_pip) {
            REQUIRE(stop < events.size());
            CHECK(stop > last_part_move);
            CHECK(stop < first_groove_move);
        } else {
            CHECK(stop == events.size());
        }
    }
}

}  // namespace test_turn_groove

namespace test_turn_groove {

TEST_CASE("turning operations come in beyond the bar's face: the stock's faceZ, or where an earlier turn-face left it") {
    const std::string tools = R"({"number": 1, "type": "turning-tool", "noseRadius": 0.4, "rpm": 800},
      {"number": 2, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 500})";
    const std::string face = R"({"type": "turn-face", "tool": 1, "z": 0, "stepdown": 1, "feed": 100})";
    const std::string rough = R"({"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": 2, "allowanceX": 0.2,
      "allowanceZ": 0.1, "start": [24, 0], "path": [{"line": [30, 0]}, {"line": [30, -20]}, {"line": [38, -20]}]})";
    const std::string profile = R"({"type": "turn-profile", "tool": 1, "feed": 100, "start": [24, 0], "retractX": 44,
      "path": [{"line": [30, 0]}, {"line": [30, -20]}, {"line": [40, -20]}]})";
    // (A thread of the bar's diameter: one smaller would be cut on the bar nothing turned.)
    const std::string thread = R"({"type": "turn-thread", "tool": 2, "majorDiameter": 40, "minorDiameter": 37.546, "pitch": 2,
      "startZ": 0, "endZ": -10, "firstDepth": 0.3})";
    const auto job = [&](double face_z, const std::string& ops) {
        return fmt::format(R"({{"clearance": 20, "stock": {{"bar": {{"diameter": 40, "length": 80, "faceZ": {}}}}},
  "tools": [{}], "operations": [{}]}})",
                           face_z, tools, ops);
    };
    // The bar's face at Z5, not faced: each of them would rapid in X into the stub.
    CHECK(refusal(job(5, rough)).find("/operations/0: its passes come in at Z 1.100 mm, inside the bar, whose face is at Z "
                                      "5.000 mm (the stock's faceZ): face the bar first") != std::string::npos);
    CHECK(refusal(job(5, profile)).find("/operations/0: it rapids along Z to its start at Z 1.000 mm, inside the bar") !=
          std::string::npos);
    // The thread's passes start approachDistance (3 leads, 6 mm) beyond startZ 0: in air beyond a face at Z5, inside one at Z8.
    CHECK(refusal(job(5, thread)).empty());
    CHECK(refusal(job(8, thread)).find("/operations/0: its passes come in at Z ") != std::string::npos);
    // Faced to Z0 first (or a bar whose face is at Z0): they come in beyond it.
    for (const std::string& op : {rough, profile, thread}) {
        CHECK(refusal(job(5, face + ", " + op)).empty());
        CHECK(refusal(job(0, op)).empty());
    }
    // Faced to Z3 only: still inside, for a roughing from the whole bar; one from what the face
    // left ("stock": "auto", turn_rough.cpp) comes in 1 mm beyond Z3 at each level.
    const std::string shallow = R"({"type": "turn-face", "tool": 1, "z": 3, "stepdown": 1, "feed": 100})";
    const std::string rough_bar = rough.substr(0, rough.size() - 1) + R"(, "stock": "bar"})";
    CHECK(refusal(job(5, shallow + ", " + rough_bar)).find("whose face is at Z 3.000 mm (as an earlier turn-face left it)") !=
          std::string::npos);
    CHECK(refusal(job(5, shallow + ", " + rough)).empty());
}

}  // namespace test_turn_groove
