// Fanuc T's G70 after G71 on fanuc-lathe (issue 30): a turn-profile right after a turn-rough of
// the same profile finishes the cycle's shape with G70 P Q, the G71 written with the finishing
// pass's tip path as its shape and the allowances as U/W, where camgen's model of both cycles
// (fanuc_g7x with an allowance, fanuc_g70; geometry/lathe_cycle.hpp) cuts camgen's passes; the
// fanuc-lathe reader expands both into the same moves. No Fanuc control was run: these tests hold
// the post, the link and the reader to the model, and the model to the profile and the bar.
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>

#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/geometry/compensation.hpp"
#include "camgen/operations/fanuc_finish.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/operations/turn_profile/turn_profile.hpp"
#include "camgen/operations/turn_rough/turn_rough.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/reader/reader.hpp"
#include "support.hpp"
#include "lathe_profiles.hpp"

namespace test_fanuc_g70 {

using namespace camgen;

namespace {

// A rough and a finishing pass of the same profile; `rough_extra`/`finish_extra` add keys.
std::string g70_job(const std::string& path, double start_x, double doc, double nose_rough, double nose_finish,
                    const std::string& rough_extra, const std::string& finish_extra, double allowance_z = 0.1) {
    return fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0.5}}}},
  "tools": [{{"number": 1, "type": "turning-tool", {}"orientation": 2, "rpm": 1000}},
            {{"number": 2, "type": "turning-tool", {}"orientation": 2, "rpm": 1500}}],
  "operations": [{{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.5}},
                 {{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": {}, "allowanceX": 0.4, "allowanceZ": {},
                   "start": [{}, 0], "path": {}{}}},
                 {{"type": "turn-profile", "tool": 2, "feed": 90, "start": [{}, 0], "path": {}, "retractX": 44{}}}]}})",
                       nose_rough > 0 ? fmt::format(R"("noseRadius": {}, )", nose_rough) : std::string(),
                       nose_finish > 0 ? fmt::format(R"("noseRadius": {}, )", nose_finish) : std::string(), doc, allowance_z, start_x, path, rough_extra, start_x, path, finish_extra);
}

bool g70_found_by_verify(const Job& j, const Machine& m, const std::string& text) {
    try {
        return compare_traces(trace_expected(expand_job(j), m), trace_program(read_program(text, m, "t.nc"), m),
                              compare_tolerance(m))
            .has_value();
    } catch (const InputError&) {
        return true;  // refused by the reader
    }
}

// `text` with the number after the first `word` (e.g. "U" after "G71 P") replaced by `value`.
std::string g70_replace_after(std::string text, const std::string& anchor, const std::string& word, const std::string& value) {
    const std::size_t at = text.find(anchor);
    REQUIRE(at != std::string::npos);
    const std::size_t w = text.find(" " + word, at);
    REQUIRE(w != std::string::npos);
    std::size_t end = w + 1 + word.size();
    while (end < text.size() && text[end] != ' ' && text[end] != '\n') ++end;
    text.replace(w + 1, end - (w + 1), word + value);
    return text;
}

}  // namespace

TEST_CASE("fanuc-g70: generated profiles roughed and finished: G70 where exact, read back as the job's moves") {
    const Machine fanuc = load_machine("fanuc-lathe");
    Machine plain = fanuc;  // without sequence numbers: the shape's blocks carry their own
    plain.block.sequence_numbers = false;
    std::mt19937 rng(70);
    int with_g70 = 0, noses = 0, refused_other = 0, unreachable = 0, checked = 0, nose_notes = 0;
    for (int n = 0; n < 45; ++n) {
        double d0 = 0;
        const std::string path = test::stepped_shaft_profile(rng, d0);
        const double doc = n % 3 == 0 ? 1.5 : (n % 3 == 1 ? 1.0 : 2.2);
        // Sharp tips (or compensation none on both): the shapes are one; noses of 0.4 on both
        // with computer compensation: they are not (the rough's runs round the end onto the face).
        // kind 0: noses of 0.4 on both, compensation none; 1: 0.8 roughing and 0.4 finishing,
        // none; 2: 0.4 on both, computer.
        const int kind = n % 3;
        const double nose = kind == 1 ? 0.8 : 0.4;
        const std::string comp = kind != 2 ? R"(, "compensation": "none")" : "";
        CAPTURE(path);
        CAPTURE(kind);
        std::optional<Job> read_in;
        try {
            read_in = read_job(g70_job(path, d0, doc, nose, 0.4, comp, comp, kind == 2 ? 0.5 : 0.1), "g70.json");
        } catch (const InputError&) {
            ++unreachable;
            continue;
        }
        const Job& j = *read_in;
        const auto& rough = std::get<TurnRoughOp>(j.operations.at(1));
        const auto& finish = std::get<TurnProfileOp>(j.operations.at(2));
        REQUIRE(finish.g70.has_value());  // linked: the same profile right after the rough
        const bool exact = !finish.g70->refusal;
        CHECK(exact == rough.finish.has_value());
        if (kind == 2) {
            // The noses' tip paths differ: never G70, and the note says why.
            CHECK_FALSE(exact);
            if (finish.g70->refusal && finish.g70->refusal->find("nose radius") != std::string::npos) ++nose_notes;

        }
        for (const Machine* m : {&fanuc, static_cast<const Machine*>(&plain)}) {
            const auto p = test::post_noted(j, *m);
            const bool g70 = p.text.find("G70 P") != std::string::npos;
            CHECK(g70 == exact);
            if (!exact) {
                // As before: U0 W0 (where the cycle is written) and the finishing longhand, with a note.
                CHECK(p.text.find("U0.400 W0.100") == std::string::npos);
                CHECK(p.notes.find("G70 cannot finish it") != std::string::npos);
            }
            if (m == &fanuc) {
                if (g70) ++with_g70;
                else if (kind == 2) ++noses;
                else ++refused_other;
                if (!g70 && kind != 2) MESSAGE(*finish.g70->refusal);
            }
            // verify --job: the program read back moves as the job's events traced for the machine.
            const Trace read = trace_program(read_program(p.text, *m, "t.nc"), *m);
            const auto miss = compare_traces(trace_expected(expand_job(j), *m), read, compare_tolerance(*m));
            CHECK_MESSAGE(!miss, (miss ? miss->message : "") << "\n" << p.text);
            if (!g70) continue;
            // U is the diameter's allowance (2 x 0.2 radial), W the face's; G70 names the cycle's shape.
            CHECK(p.text.find("U0.400 W0.100 F200") != std::string::npos);  // (kinds 0 and 1)
            const std::size_t at = p.text.find("G71 P");
            const long ns = std::stol(p.text.substr(at + 5));
            const long nf = std::stol(p.text.substr(p.text.find('Q', at) + 1));
            CHECK(p.text.find(fmt::format("G70 P{} Q{}", ns, nf)) != std::string::npos);
            // The finishing feed in the shape (G70's), the rough's on the cycle (G71's).
            const std::size_t shape_f = p.text.find(" F90", at);
            CHECK(shape_f != std::string::npos);
            CHECK(shape_f < p.text.find("G70"));
            // A wrong U, W or G70 P is found by verify.
            CHECK(g70_found_by_verify(j, *m, g70_replace_after(p.text, "G71 P", "U", "0.800")));
            CHECK(g70_found_by_verify(j, *m, g70_replace_after(p.text, "G71 P", "W", "0.300")));
            CHECK(g70_found_by_verify(j, *m, g70_replace_after(p.text, "G70", "P", std::to_string(ns + 1))));
        }
        if (!exact) continue;
        // The cycle's moves (the finishing shape moved by the allowances): no feed below the
        // rough's boundary, the last pass on it.
        TurnCycle c = turn_cycle(rough);
        c.finish = rough.finish;
        const std::vector<LatheCycleMove> moves = turn_cycle_path(c, RoughCyclePattern::fanuc_g71);
        Vec2 at{c.start.z, c.start.x};
        for (const LatheCycleMove& mv : moves) {
            if (mv.kind == LatheCycleMove::Kind::feed)
                for (int s = 0; s <= 20; ++s) {
                    const Vec2 q = at + (mv.end - at) * (s / 20.0);
                    const double below = test::stepped_profile_radius_at(rough.tip_boundary, q.x, false);
                    if (below >= 0)
                        CHECK_MESSAGE(q.y >= below - 1e-6, "a feed below the boundary at Z " << q.x << " radius " << q.y
                                                                                              << " (boundary " << below << ")");
                }
            at = mv.end;
            ++checked;
        }
        // G70's moves under Fanuc's pattern: the finishing pass is the turn-profile's own (the
        // same feeds along the same tip path), its rapids outside the finished profile and, in
        // Z, beyond the bar's face or outside the bar.
        EventRecorder events;
        expand(finish, Context{j, j.tools.at(2)}, events);
        const auto& fc = std::get<FinishCycle>(events.events.at(0));
        std::vector<Vec2> own, g70;
        auto zx = [](const Vec3& v) { return Vec2{v.z, v.x}; };
        for (const PlainMove& pm : fc.plain)
            if (const auto* l = std::get_if<Linear>(&pm); l && l->movement == Movement::finishing) own.push_back(zx(l->to));
            else if (const auto* a = std::get_if<Arc>(&pm); a && a->movement == Movement::finishing) own.push_back(zx(a->to));
        Vec2 from{};
        bool have_from = false;  // (the first rapid comes from the tool change: not a path)
        for (const Event& e : finish_cycle_moves(fc, RoughCyclePattern::fanuc_g71)) {
            if (const auto* l = std::get_if<Linear>(&e); l && l->movement == Movement::finishing) g70.push_back(zx(l->to));
            else if (const auto* a = std::get_if<Arc>(&e); a && a->movement == Movement::finishing) g70.push_back(zx(a->to));
            if (const auto* r = std::get_if<Rapid>(&e); r && have_from) {
                for (int s = 0; s <= 40; ++s) {
                    const Vec2 q = from + (zx(r->to) - from) * (s / 40.0);  // (Z, radius)
                    const double kept = test::stepped_profile_radius_at(finish.profile, q.x, true);
                    if (kept >= 0) CHECK_MESSAGE(q.y >= kept - 1e-6, "a rapid into the finished part at Z " << q.x);
                    // (the turn-face faced the bar to Z0)
                    CHECK_MESSAGE((q.x >= -1e-9 || q.y >= 20 - 1e-9 || kept >= 0), "a rapid into the bar at Z " << q.x);
                }
            }
            have_from = true;
            if (const auto* r = std::get_if<Rapid>(&e)) from = zx(r->to);
            else if (const auto* l = std::get_if<Linear>(&e)) from = zx(l->to);
            else if (const auto* a = std::get_if<Arc>(&e)) from = zx(a->to);
        }
        REQUIRE(own.size() == g70.size());
        for (std::size_t k = 0; k < own.size(); ++k) CHECK(distance(own[k], g70[k]) < 1e-9);
    }
    MESSAGE("fanuc-g70: " << with_g70 << " with G70, " << noses << " not (noses, " << nose_notes << " for the noses' paths), " << refused_other << " not (other), "
                          << unreachable << " unreachable, " << checked << " cycle moves checked");
    CHECK(with_g70 >= 15);
    CHECK(noses >= 10);
    CHECK(nose_notes >= 5);  // (the others: the rough's own cycle refused, a boundary inside the bar's face)
}

TEST_CASE("fanuc-g70: who asks for it: output, the operation before, the machine") {
    const Machine fanuc = load_machine("fanuc-lathe");
    const Machine linuxcnc = load_machine("linuxcnc-lathe");
    const std::string path = R"([{"line": [20, -10]}, {"line": [30, -10]}, {"line": [30, -20]}])";
    auto job = [&](const std::string& rough_extra, const std::string& finish_extra) {
        return read_job(g70_job(path, 16, 1.5, 0.4, 0.4, R"(, "compensation": "none")" + rough_extra,
                                R"(, "compensation": "none")" + finish_extra),
                        "g70.json");
    };
    // auto: G70 on fanuc-lathe, the turn-profile's own moves on linuxcnc-lathe (no note there).
    {
        const Job j = job("", "");
        CHECK(test::post_noted(j, fanuc).text.find("G70 P") != std::string::npos);
        const auto l = test::post_noted(j, linuxcnc);
        CHECK(l.text.find("G70") == std::string::npos);
        CHECK(l.notes.find("G70") == std::string::npos);
    }
    // longhand: no link, the turn-rough's cycle as before (U0 W0).
    {
        const Job j = job("", R"(, "output": "longhand")");
        const std::string t = test::post_noted(j, fanuc).text;
        CHECK(t.find("G70") == std::string::npos);
        CHECK(t.find("U0.000 W0.000") != std::string::npos);
    }
    // canned: G70 or an error at its output.
    {
        const Job j = job("", R"(, "output": "canned")");
        CHECK(test::post_noted(j, fanuc).text.find("G70 P") != std::string::npos);
        CHECK_THROWS_WITH_AS(test::post_noted(j, linuxcnc), doctest::Contains("/operations/2/output"), InputError);
    }
    {
        // The rough longhand: G70 has no shape to run.
        const Job j = job(R"(, "output": "longhand")", R"(, "output": "canned")");
        CHECK_THROWS_WITH_AS(test::post_noted(j, fanuc), doctest::Contains("written longhand"), InputError);
        const Job a = job(R"(, "output": "longhand")", "");
        const auto p = test::post_noted(a, fanuc);
        CHECK(p.text.find("G70") == std::string::npos);
        CHECK(p.notes.find("G70 cannot finish it: the turn-rough before it is written longhand") != std::string::npos);
    }
    // canned without a turn-rough of the same profile right before it: refused when read.
    CHECK_THROWS_WITH_AS(read_job(fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0}}}},
  "tools": [{{"number": 2, "type": "turning-tool", "noseRadius": 0.4, "orientation": 2, "rpm": 1500}}],
  "operations": [{{"type": "turn-profile", "tool": 2, "feed": 90, "start": [16, 0], "path": {}, "retractX": 44,
                   "output": "canned", "compensation": "none"}}]}})",
                                              path),
                             "g70.json"),
                         doctest::Contains("/operations/0/output"), InputError);
    // Control compensation: G42 is not G70's.
    {
        const Job j = read_job(fmt::format(R"({{"clearance": 10, "stock": {{"bar": {{"diameter": 40, "length": 60, "faceZ": 0.5}}}},
  "tools": [{{"number": 1, "type": "turning-tool", "noseRadius": 0.4, "orientation": 2, "rpm": 1000}},
            {{"number": 2, "type": "turning-tool", "noseRadius": 0.4, "orientation": 2, "rpm": 1500}}],
  "operations": [{{"type": "turn-face", "tool": 1, "feed": 150, "z": 0, "stepdown": 0.5}},
                 {{"type": "turn-rough", "tool": 1, "feed": 200, "depthOfCut": 1.5, "start": [16, 0], "path": {}, "compensation": "none"}},
                 {{"type": "turn-profile", "tool": 2, "feed": 90, "start": [16, 0], "path": {}, "retractX": 44,
                   "compensation": "control", "approachDistance": 2}}]}})",
                                         path, path),
                               "g70.json");
        const auto p = test::post_noted(j, fanuc);
        CHECK(p.text.find("G70") == std::string::npos);
        CHECK(p.notes.find("compensation is control") != std::string::npos);
        const Trace read = trace_program(read_program(p.text, fanuc, "t.nc"), fanuc);
        CHECK_FALSE(compare_traces(trace_expected(expand_job(j), fanuc), read, compare_tolerance(fanuc)));
    }
}

TEST_CASE("fanuc-g70: the reader reads G71 U W and G70 P Q, and refuses what the control would not run") {
    const Machine fanuc = load_machine("fanuc-lathe");
    auto read = [&](const std::string& body) { return read_program("%\nO1000\nG18 G40 G80 G98 G21\nT0101\nG97 S1000 M3\nG0 X44.000 Z2.000\n" + body + "M30\n%\n", fanuc, "t.nc"); };
    auto refusal = [&](const std::string& body) {
        try {
            (void)read(body);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string cycle = "G71 U1.400 R0.500\nG71 P100 Q102 U0.400 W0.100 F200\n";
    const std::string shape = "N100 G0 X20.000\nN101 G1 Z-10.000 F90\nN102 G1 X40.000 Z-12.000\n";
    CHECK(refusal(cycle + shape + "G70 P100 Q102\n") == "");
    CHECK(refusal(cycle + shape + "G70 P101 Q102\n").find("no G71 or G72 before it") != std::string::npos);
    CHECK(refusal(cycle + shape + "G70 P100 Q101\n").find("no G71 or G72 before it") != std::string::npos);
    CHECK(refusal("G70 P100 Q102\n").find("no G71 or G72 before it") != std::string::npos);
    CHECK(refusal(cycle + shape + "G70 P100\n").find("without P(ns) and Q(nf)") != std::string::npos);
    CHECK(refusal(cycle + shape + "G70 P100 Q102 U0.2\n").find("G70 P(ns) Q(nf) only") != std::string::npos);
    // A bare move after G70 (one-shot on the control) is refused as such, not as a word on G70.
    CHECK(refusal(cycle + shape + "G70 P100 Q102\nX50.\n").find("X50. without a motion code after G70") !=
          std::string::npos);
    CHECK(refusal(cycle + shape + "G70 P100 Q102\nG0 X50.\n") == "");
    CHECK(refusal("G71 U1.400 R0.500\nG71 P100 Q102 U-0.400 W0.000 F200\n" + shape).find("negative") != std::string::npos);
    // A second F in the shape (G70 would change feed within it), a G1 ns (the control would feed
    // each infeed), a second shape numbered as the first (which one G70 P finds is not known).
    CHECK(refusal(cycle + "N100 G0 X20.000\nN101 G1 Z-10.000 F90\nN102 G1 X40.000 Z-12.000 F10\n")
              .find("a second F in G71's finishing shape") != std::string::npos);
    CHECK(refusal(cycle + "N100 G1 X20.000\nN101 G1 Z-10.000 F90\nN102 G1 X40.000 Z-12.000\n").find("is not G0") !=
          std::string::npos);
    CHECK(refusal(cycle + shape + "G0 X44.000 Z2.000\n" + cycle + shape).find("a finishing shape N100 was read before") !=
          std::string::npos);
    // The moves: G71 roughs to the shape moved by (W, U/2); G70 runs the shape at its F from A and back.
    const Trace t = trace_program(read(cycle + shape + "G70 P100 Q102\n"), fanuc);
    double lowest_g71_feed = 1e9;
    bool g70_on_shape = false;
    bool after_g71 = false;
    for (const Step& s : t.steps) {
        if (s.kind != StepKind::feed) continue;
        if (!after_g71 && std::abs(s.to.z - (-10.0 + 0.1)) < 1e-9 && std::abs(s.to.x - 10.2) < 1e-9) after_g71 = true;
        if (after_g71 && std::abs(s.to.z + 10.0) < 1e-9 && std::abs(s.to.x - 10.0) < 1e-9) {
            g70_on_shape = true;
            CHECK(s.feed == doctest::Approx(90));
        }
        if (!g70_on_shape) {
            lowest_g71_feed = std::min(lowest_g71_feed, s.to.x);
            CHECK(s.feed == doctest::Approx(200));
        }
    }
    CHECK(after_g71);  // the last pass of G71 on the moved shape (radius 10 + 0.2, Z -10 + 0.1)
    CHECK(g70_on_shape);
    CHECK(lowest_g71_feed >= 10.2 - 1e-9);
    CHECK(t.steps.back().to.x == doctest::Approx(22.0));  // back at A
    CHECK(t.steps.back().to.z == doctest::Approx(2.0));
}

TEST_CASE("fanuc-g70: G70's rapids are checked against the finished part, nose and all") {
    // A profile (Z, radius) of D20 for 10 mm, a shoulder up to D30, D30 for 10 mm.
    Profile p;
    p.plane = ProfilePlane::xz;
    p.start = Vec2{0.0, 10.0};
    p.segments = {{Vec2{-10.0, 10.0}, std::nullopt, ArcDirection::ccw},
                  {Vec2{-10.0, 15.0}, std::nullopt, ArcDirection::ccw},
                  {Vec2{-20.0, 15.0}, std::nullopt, ArcDirection::ccw}};
    auto shape_from = [&](Vec2 a) { return fanuc_g7x_shape(LatheCycleAxis::z, a, p); };
    const Vec2 zero{0.0, 0.0};
    // From A beyond the bar: in air, with a sharp tip and with a nose of 0.8 (orientation 2).
    CHECK_FALSE(fanuc_g70_air(p, Vec2{1.0, 16.0}, shape_from(Vec2{1.0, 16.0}), 0.0, zero));
    CHECK_FALSE(fanuc_g70_air(p, Vec2{1.0, 16.0}, shape_from(Vec2{1.0, 16.0}), 0.8, lathe_tip_offset(2, 0.8)));
    // A below the shoulder: the rapid back from the end runs through it.
    const auto low = fanuc_g70_air(p, Vec2{1.0, 12.0}, shape_from(Vec2{1.0, 12.0}), 0.0, zero);
    REQUIRE(low);
    CHECK(low->find("from the shape's end back to the start point") != std::string::npos);
    // The nose counts, not only its tip: a tip path 0.5 above D30 is air for a sharp tip and for
    // orientation 2 (the nose above its tip), not for orientation 3 (the nose 0.8 below its tip).
    CHECK_FALSE(fanuc_g70_air(p, Vec2{1.0, 15.5}, shape_from(Vec2{1.0, 15.5}), 0.0, zero));
    CHECK_FALSE(fanuc_g70_air(p, Vec2{1.0, 15.5}, shape_from(Vec2{1.0, 15.5}), 0.4, lathe_tip_offset(2, 0.4)));
    CHECK(fanuc_g70_air(p, Vec2{1.0, 15.5}, shape_from(Vec2{1.0, 15.5}), 0.4, lathe_tip_offset(3, 0.4)));
}

}  // namespace test_fanuc_g70

namespace test_fanuc_g70 {

using namespace camgen;

TEST_CASE("fanuc-g70: after G70 the next feed is written again, per minute and per revolution") {
    // G70 leaves the shape's F in force; a rough after it at the first rough's feed must say its F
    // (a review found the per-revolution feed remembered across G70: the second G71 was written
    // without F and would have roughed at the finishing feed).
    const Machine fanuc = load_machine("fanuc-lathe");
    for (const std::string mode : {"per-revolution", "per-minute"}) {
        const bool rev = mode == "per-revolution";
        const std::string rough_feed = rev ? "0.25" : "250", finish_feed = rev ? "0.1" : "100";
        const std::string profile =
            R"("start": [24, 0], "path": [{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]}, {"line": [40, -20]}, {"line": [40, -40]}])";
        const std::string text = fmt::format(
            R"({{"name": "g70feed", "units": "mm", "clearance": 20,
 "stock": {{"bar": {{"diameter": 44, "length": 70, "faceZ": 0}}}},
 "tools": [{{"number": 3, "type": "turning-tool", "noseRadius": 0.4, "orientation": 2, "rpm": 1500}},
           {{"number": 4, "type": "turning-tool", "noseRadius": 0.8, "orientation": 2, "rpm": 1000}}],
 "operations": [
  {{"type": "turn-rough", "tool": 4, "feedMode": "{0}", "feed": {1}, "depthOfCut": 1.5, "allowanceX": 0.4, "allowanceZ": 0.1,
    "compensation": "none", {3}}},
  {{"type": "turn-profile", "tool": 3, "feedMode": "{0}", "feed": {2}, "compensation": "none", "retractX": 44, {3}}},
  {{"type": "turn-rough", "tool": 4, "feedMode": "{0}", "feed": {1}, "depthOfCut": 1.5, "allowanceX": 0.2, "allowanceZ": 0.05,
    "compensation": "none", "output": "canned", "start": [20, 0], "path": [{{"line": [24, -2]}}, {{"line": [24, -10]}}, {{"line": [28, -10]}}]}}]}})",
            mode, rough_feed, finish_feed, profile);
        CAPTURE(mode);
        const Job j = read_job(text, "g70feed.json");
        const std::string program = test::post_noted(j, fanuc).text;
        const std::size_t g70 = program.find("G70 P");
        REQUIRE(g70 != std::string::npos);
        // The second G71's second block carries its F again.
        const std::size_t second = program.find("G71 P", g70);
        REQUIRE(second != std::string::npos);
        const std::string block = program.substr(second, program.find('\n', second) - second);
        CHECK(block.find(rev ? "F0.2500" : "F250") != std::string::npos);
        CHECK_FALSE(g70_found_by_verify(j, fanuc, program));
    }
}

}  // namespace test_fanuc_g70
