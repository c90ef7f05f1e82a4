// Thread milling (issue 29, item 2): the thread tables, the thread-mill tool, the operation's
// helix (exactly the pitch per turn, a partial last turn), its radii against the tables, its
// leads (on the thread's helix, never off it), its direction and order, the machines that
// write the helix as lines, and bad input; and the path helix that keeps an exact pitch.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/vocabulary/threads.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_thread_mill {

using namespace camgen;

namespace {

constexpr double two_pi = 2 * std::numbers::pi;

// A job with one thread mill (tool 3, `tool` keys) and one thread-mill operation (`keys`),
// the stock top at Z0.
std::string thread_job(const std::string& keys, const std::string& tool = R"("diameter": 6, "minPitch": 0.5, "maxPitch": 2.5)",
                       const std::string& spindle = "cw") {
    return fmt::format(R"({{"name": "t", "units": "mm", "clearance": 15,
  "tools": [{{"number": 3, "type": "thread-mill", {}, "rpm": 6000, "direction": "{}"}},
            {{"number": 4, "type": "end-mill", "diameter": 6, "rpm": 6000}}],
  "operations": [{{"type": "thread-mill", "tool": 3, "retractPlane": 5, "safeDistance": 1, "feed": 300, {}}}]}})",
                       tool, spindle, keys);
}

struct Recorder : EventSink {
    std::vector<Event> events;
    void emit(const Event& e) override { events.push_back(e); }
};

// The events of a job's operations (without the tool change and spindle around them).
std::vector<Event> events_of(const std::string& job_text) {
    Recorder r;
    expand_job(read_job(job_text, "t.json"), r);
    return r.events;
}

// One feed move of the job: where it starts and its event.
struct Move {
    Vec3 from;
    Event event;
};

std::vector<Move> moves_of(const std::vector<Event>& events) {
    std::vector<Move> out;
    Vec3 at{};
    for (const Event& e : events) {
        if (const auto* r = std::get_if<Rapid>(&e)) at = r->to;
        if (const auto* l = std::get_if<Linear>(&e)) {
            out.push_back({at, e});
            at = l->to;
        }
        if (const auto* a = std::get_if<Arc>(&e)) {
            out.push_back({at, e});
            at = a->to;
        }
    }
    return out;
}

// The arcs of a given movement kind, with their starts.
std::vector<std::pair<Vec3, Arc>> arcs_of(const std::vector<Event>& events, Movement m) {
    std::vector<std::pair<Vec3, Arc>> out;
    for (const Move& mv : moves_of(events))
        if (const auto* a = std::get_if<Arc>(&mv.event); a && a->movement == m) out.push_back({mv.from, *a});
    return out;
}

// The signed angle (radians, counter-clockwise > 0) an arc turns about its centre.
double signed_sweep(const Vec3& from, const Arc& a) {
    const ArcGeometry g = resolve_arc(from, a);
    return a.direction == ArcDirection::ccw ? g.sweep : -g.sweep;
}

// Reads a job expecting an error at `path` whose message holds `text`.
void check_refused(const std::string& job_text, const std::string& path, const std::string& text) {
    try {
        read_job(job_text, "t.json");
        FAIL("no error for " << path);
    } catch (const InputError& e) {
        const std::string what = e.what();
        CHECK_MESSAGE(what.find(path + ":") != std::string::npos, what);
        CHECK_MESSAGE(what.find(text) != std::string::npos, what);
    }
}

}  // namespace

TEST_CASE("thread tables: ISO 261 and ASME B1.1 designations, the basic profile's diameters") {
    std::string why;
    const auto m10 = find_thread("M10", why);
    REQUIRE(m10);
    CHECK(m10->name == "M10x1.5");
    CHECK(m10->series == ThreadSeries::metric_coarse);
    CHECK(m10->major == 10);
    CHECK(m10->pitch == 1.5);
    // D1 = D - 1.082532 P, d3 = d - 1.226869 P (ISO 68-1, ISO 965-1).
    CHECK(internal_minor_diameter(10, 1.5) == doctest::Approx(10 - 1.082532 * 1.5).epsilon(1e-7));
    CHECK(external_minor_diameter(16, 2) == doctest::Approx(16 - 1.226869 * 2).epsilon(1e-7));
    CHECK(thread_triangle_height(1) == doctest::Approx(0.866025).epsilon(1e-6));
    const auto fine = find_thread("M10x1.25", why);
    REQUIRE(fine);
    CHECK(fine->series == ThreadSeries::metric_fine);
    CHECK(fine->pitch == 1.25);
    CHECK(find_thread("m12 x 1.5", why)->pitch == 1.5);
    CHECK_FALSE(find_thread("M10x2", why));
    CHECK(why == "M10 has no pitch 2 in ISO 261: its pitches are 1.5 (coarse), 1.25, 1, 0.75 (or give majorDiameter, "
                 "minorDiameter and pitch)");
    CHECK_FALSE(find_thread("M11", why));
    CHECK(why.find("M11 is not an ISO 261 size") == 0);
    // The coarse pitches REFERENCE.md section 10 names.
    for (auto [name, pitch] : {std::pair{"M3", 0.5}, {"M4", 0.7}, {"M5", 0.8}, {"M6", 1.0}, {"M8", 1.25}, {"M12", 1.75},
                               {"M14", 2.0}, {"M16", 2.0}, {"M20", 2.5}, {"M24", 3.0}})
        CHECK(find_thread(name, why)->pitch == pitch);

    const auto unc = find_thread("1/4-20 UNC", why);
    REQUIRE(unc);
    CHECK(unc->name == "1/4-20 UNC");
    CHECK(unc->major == doctest::Approx(6.35));
    CHECK(unc->pitch == doctest::Approx(1.27));
    const auto unf = find_thread("#10-32", why);
    REQUIRE(unf);
    CHECK(unf->name == "#10-32 UNF");
    CHECK(unf->major == doctest::Approx(4.826));
    CHECK_FALSE(find_thread("1/4-24 UNC", why));
    CHECK(why == "\"1/4-24 UNC\" is not in ASME B1.1's UNC and UNF series: 1/4 has 1/4-20 UNC and 1/4-28 UNF");
    CHECK_FALSE(find_thread("1/4-28 UNC", why));
    CHECK_FALSE(find_thread("bolt", why));
    // Every row is sane: fine pitches finer than the coarse one, sizes in order.
    double last = 0;
    for (const MetricThreadSize& m : metric_thread_sizes()) {
        CHECK(m.major > last);
        last = m.major;
        for (double p : m.fine) CHECK(p < m.coarse);
    }
}

TEST_CASE("thread-mill tools: pitch or minPitch and maxPitch, refused on other types and by other operations") {
    const Job job = read_job(thread_job(R"("thread": "M10", "endDepth": 6, "holes": [[0, 0]])",
                                        R"("diameter": 6, "pitch": 1.5, "flutes": 4)"),
                             "t.json");
    const Tool& t = job.tools.at(3);
    CHECK(t.type == ToolType::thread_mill);
    CHECK(t.min_pitch == 1.5);
    CHECK(t.max_pitch == 1.5);
    CHECK(t.flutes == 4);
    CHECK_FALSE(t.centre_cutting);
    check_refused(thread_job(R"("thread": "M10", "endDepth": 6, "holes": [[0, 0]])", R"("diameter": 6)"), "/tools/0",
                  "a thread-mill needs pitch");
    check_refused(thread_job(R"("thread": "M10", "endDepth": 6, "holes": [[0, 0]])", R"("diameter": 6, "minPitch": 1)"),
                  "/tools/0/maxPitch", "a thread-mill needs pitch");
    check_refused(thread_job(R"("thread": "M10", "endDepth": 6, "holes": [[0, 0]])",
                             R"("diameter": 6, "minPitch": 2, "maxPitch": 1)"),
                  "/tools/0/maxPitch", "maxPitch (1.000 mm) is less than minPitch (2.000 mm)");
    check_refused(R"({"clearance": 10, "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 1, "pitch": 1}],
                     "operations": []})",
                  "/tools/0/pitch", "pitch is for a thread-mill, not an end-mill");
    check_refused(R"({"clearance": 10, "tools": [{"number": 1, "diameter": 6, "rpm": 1, "flutes": 0}], "operations": []})",
                  "/tools/0/flutes", "flutes must be between 1 and 1000");

    // The thread mill in operations that cannot use it, and the thread-mill with another tool.
    const std::string tools = R"("tools": [{"number": 3, "type": "thread-mill", "diameter": 6, "pitch": 1, "rpm": 1000},
                                          {"number": 4, "type": "end-mill", "diameter": 6, "rpm": 1000}])";
    auto job_with = [&](const std::string& op) { return R"({"clearance": 10, )" + tools + R"(, "operations": [)" + op + "]}"; };
    check_refused(job_with(R"({"type": "contour", "tool": 3, "endDepth": 2, "feed": 100, "side": "outside",
                               "profile": {"circle": {"centre": [0, 0], "diameter": 20}}})"),
                  "/operations/0/tool", "tool 3 (/tools/0) is a thread mill: a contour cuts with an end mill");
    check_refused(job_with(R"({"type": "pocket", "tool": 3, "endDepth": 2, "feed": 100,
                               "profile": {"circle": {"centre": [0, 0], "diameter": 20}}})"),
                  "/operations/0/tool", "is a thread mill: a pocket");
    check_refused(job_with(R"({"type": "drill", "tool": 3, "endDepth": 2, "plungingFeedrate": 100, "holes": [[0, 0]]})"),
                  "/operations/0/tool", "tool 3 (/tools/0) is a thread mill: a drill operation goes down");
    check_refused(job_with(R"({"type": "bore-mill", "tool": 3, "diameter": 20, "pitch": 1, "endDepth": 2, "feed": 100,
                               "holes": [[0, 0]]})"),
                  "/operations/0/tool", "is a thread mill: a bore-mill goes down");
    check_refused(job_with(R"({"type": "thread-mill", "tool": 4, "thread": "M10", "endDepth": 2, "feed": 100,
                               "holes": [[0, 0]]})"),
                  "/operations/0/tool", "tool 4 (/tools/1) is a end-mill: a thread-mill operation needs a tool of type");
}

TEST_CASE("thread-mill: the helix advances exactly the pitch per turn, a partial last turn, the table's diameters") {
    // M10x1.5, 12.5 deep: 8 whole turns and a third, bottom-up (right-hand, climb, M3: G3).
    const std::vector<Event> ev = events_of(thread_job(R"("thread": "M10", "endDepth": 12.5, "holes": [[20, 10]])"));
    const auto cuts = arcs_of(ev, Movement::cutting);
    REQUIRE(cuts.size() == 2);
    const auto& [whole_from, whole] = cuts[0];
    const auto& [part_from, part] = cuts[1];
    CHECK(whole.direction == ArcDirection::ccw);
    CHECK(whole.turns == 7);  // a full circle and 7 more
    CHECK(whole_from.z == -12.5);
    CHECK(whole.to.z == -12.5 + 8 * 1.5);
    CHECK(whole.to.x == whole_from.x);
    CHECK(whole.to.y == whole_from.y);
    // The final radius: tool centre + tool radius = D / 2.
    const double r = std::hypot(whole_from.x - 20, whole_from.y - 10);
    CHECK(r + 3 == doctest::Approx(5).epsilon(1e-12));
    // The partial turn: a third of a turn for half a pitch, ending at the stock top.
    const double sweep = signed_sweep(part_from, part);
    CHECK(sweep == doctest::Approx(two_pi / 3).epsilon(1e-12));
    CHECK(part.to.z == 0);
    CHECK((part.to.z - part_from.z) / (sweep / two_pi) == doctest::Approx(1.5).epsilon(1e-12));
    CHECK(std::hypot(part.to.x - 20, part.to.y - 10) == doctest::Approx(r).epsilon(1e-12));

    // A whole number of pitches: one arc, no partial.
    const auto whole_only = arcs_of(events_of(thread_job(R"("thread": "M10", "endDepth": 12, "holes": [[0, 0]])")),
                                    Movement::cutting);
    REQUIRE(whole_only.size() == 1);
    CHECK(whole_only[0].second.turns == 7);
    CHECK(whole_only[0].second.to.z == 0);

    // External M16: the last pass's tool centre at d3 / 2 + tool radius; passes in equal steps
    // from the major diameter in; a spring pass repeats the last.
    const std::vector<Event> ext = events_of(thread_job(
        R"("thread": "M16", "side": "external", "endDepth": 10, "passes": 3, "springPass": true, "holes": [[0, 0]])"));
    const auto ext_cuts = arcs_of(ext, Movement::cutting);
    const auto ext_spring = arcs_of(ext, Movement::finishing);
    REQUIRE(ext_cuts.size() == 3);
    REQUIRE(ext_spring.size() == 1);
    const double d3 = 16 - 1.226869 * 2;
    std::vector<double> radii;
    for (const auto& [from, a] : ext_cuts) radii.push_back(std::hypot(from.x, from.y));
    CHECK(radii[2] - 3 == doctest::Approx(d3 / 2).epsilon(1e-6));
    CHECK(radii[0] - radii[1] == doctest::Approx(radii[1] - radii[2]).epsilon(1e-9));
    CHECK(radii[0] - 3 == doctest::Approx(8 - (8 - d3 / 2) / 3).epsilon(1e-6));
    CHECK(std::hypot(ext_spring[0].first.x, ext_spring[0].first.y) == doctest::Approx(radii[2]).epsilon(1e-12));
    // Round a boss, climb with M3 is clockwise; right-hand clockwise goes down: top-down.
    CHECK(ext_cuts[0].second.direction == ArcDirection::cw);
    CHECK(ext_cuts[0].first.z == 0);
    CHECK(ext_cuts[0].second.to.z == -10);
}

TEST_CASE("thread-mill: the internal lead arcs stay on the thread's helix, start and end at the axis") {
    const std::vector<Event> ev = events_of(thread_job(R"("thread": "M10", "endDepth": 12.5, "holes": [[20, 10]])"));
    const auto cuts = arcs_of(ev, Movement::cutting);
    const double r = std::hypot(cuts[0].first.x - 20, cuts[0].first.y - 10);
    // Z of the helix (extended past its ends) at the angle `a` about the axis, continuous from
    // the helix start at angle 0, Z-12.5, ccw rising 1.5 a turn.
    auto helix_z = [&](double unwrapped) { return -12.5 + 1.5 * unwrapped / two_pi; };
    for (Movement m : {Movement::lead_in, Movement::lead_out}) {
        const auto leads = arcs_of(ev, m);
        REQUIRE(leads.size() == 1);
        const auto& [from, a] = leads[0];
        const ArcGeometry g = resolve_arc(from, a);
        CHECK(a.direction == ArcDirection::ccw);
        CHECK(g.sweep == doctest::Approx(std::numbers::pi));
        CHECK(g.radius == doctest::Approx(r / 2));
        // The lead-in starts at the axis, the lead-out ends there.
        const Vec3 axis_end = m == Movement::lead_in ? from : a.to;
        CHECK(std::hypot(axis_end.x - 20, axis_end.y - 10) < 1e-12);
        // The angle about the axis at the lead's far end from it, unwrapped from the helix.
        const double base = m == Movement::lead_in ? 0.0 : 8 * two_pi + two_pi / 3;
        for (int i = 1; i < 64; ++i) {
            const Vec3 p = point_on_arc(g, i / 64.0);
            double angle = std::atan2(p.y - 10, p.x - 20) - std::fmod(base, two_pi);
            while (angle > std::numbers::pi) angle -= two_pi;
            while (angle <= -std::numbers::pi) angle += two_pi;
            INFO(i << ": " << p.x << " " << p.y << " " << p.z);
            CHECK(p.z == doctest::Approx(helix_z(base + angle)).epsilon(1e-12));
            CHECK(std::hypot(p.x - 20, p.y - 10) < r);
        }
    }
}

TEST_CASE("thread-mill: hand, direction and order; a counter-clockwise spindle; both given must agree") {
    auto first_cut = [](const std::string& keys, const std::string& spindle = "cw") {
        return arcs_of(events_of(thread_job(keys + R"(, "thread": "M10", "endDepth": 9, "holes": [[0, 0]])",
                                            R"("diameter": 6, "minPitch": 0.5, "maxPitch": 2.5)", spindle)),
                       Movement::cutting)
            .at(0);
    };
    // Right-hand internal: climb with M3 is G3 rising; conventional is G2 falling.
    auto [f1, a1] = first_cut(R"("hand": "right")");
    CHECK((a1.direction == ArcDirection::ccw && f1.z == -9 && a1.to.z == 0));
    auto [f2, a2] = first_cut(R"("direction": "conventional")");
    CHECK((a2.direction == ArcDirection::cw && f2.z == 0 && a2.to.z == -9));
    // Left-hand: climb (G3) falls.
    auto [f3, a3] = first_cut(R"("hand": "left")");
    CHECK((a3.direction == ArcDirection::ccw && f3.z == 0 && a3.to.z == -9));
    // Sequence given: the direction follows.
    auto [f4, a4] = first_cut(R"("sequence": "top-down")");
    CHECK((a4.direction == ArcDirection::cw && f4.z == 0));
    // M4 swaps climb's turning sense.
    auto [f5, a5] = first_cut(R"("hand": "right")", "ccw");
    CHECK((a5.direction == ArcDirection::cw && f5.z == 0));
    check_refused(thread_job(R"("direction": "climb", "sequence": "top-down", "thread": "M10", "endDepth": 9, "holes": [[0, 0]])"),
                  "/operations/0/sequence",
                  "a right-hand internal thread milled climb with the spindle clockwise (M3) is milled bottom-up");
}

TEST_CASE("thread-mill: refusals name the JSON path: fit, pitch, depth, flutes, designation") {
    const std::string hole = R"("endDepth": 10, "holes": [[0, 0]])";
    // An M6 (D1 4.917) with a 6 mm tool.
    check_refused(thread_job(R"("thread": "M6", )" + hole), "/operations/0/tool",
                  "tool 3 (/tools/0, diameter 6.000 mm) does not fit M6x1");
    check_refused(thread_job(R"("thread": "M10", )" + hole, R"("diameter": 6, "pitch": 1.25)"), "/operations/0/thread",
                  "M10x1.5 has pitch 1.500 mm, but tool 3 (/tools/0) is a multi-form thread mill of pitch 1.250 mm");
    check_refused(thread_job(R"("thread": "M20x2", )" + hole, R"("diameter": 6, "minPitch": 0.5, "maxPitch": 1.5)"),
                  "/operations/0/thread", "cuts pitches from 0.500 mm to 1.500 mm");
    check_refused(thread_job(R"("thread": "M10", )" + hole, R"("diameter": 6, "pitch": 1.5, "fluteLength": 10.2)"),
                  "/operations/0/endDepth", "the thread is milled 10.375 mm deep below the reference plane");
    check_refused(thread_job(R"("thread": "M10x3", )" + hole), "/operations/0/thread", "M10 has no pitch 3 in ISO 261");
    check_refused(thread_job(R"("thread": "M10", "pitch": 1, )" + hole), "/operations/0/pitch",
                  "give the thread by its designation or by majorDiameter");
    check_refused(thread_job(R"("majorDiameter": 10, "minorDiameter": 8, )" + hole), "/operations/0/pitch",
                  "a thread-mill needs thread");
    check_refused(thread_job(R"("majorDiameter": 10, "minorDiameter": 7, "pitch": 1.5, )" + hole),
                  "/operations/0/minorDiameter", "deeper than a 60-degree thread of pitch 1.500 mm can be");
    // External: the lead-in's start too close to the major diameter with a tiny tool.
    check_refused(thread_job(R"("thread": "M16", "side": "external", )" + hole,
                             R"("diameter": 0.5, "minPitch": 0.5, "maxPitch": 2.5)"),
                  "/operations/0/tool", "is too small for the lead-in of M16x2");
    // By diameters.
    const auto cuts = arcs_of(
        events_of(thread_job(R"("majorDiameter": 12, "minorDiameter": 10.5, "pitch": 1, "endDepth": 3, "holes": [[0, 0]])")),
        Movement::cutting);
    REQUIRE(cuts.size() == 1);
    CHECK(std::hypot(cuts[0].first.x, cuts[0].first.y) == doctest::Approx(3));
    CHECK(cuts[0].second.turns == 2);
}

TEST_CASE("thread-mill: machines without helices get lines within tolerance; every machine reads back as the job") {
    const std::string job_text =
        thread_job(R"("thread": "M10", "endDepth": 12.5, "passes": 2, "springPass": true, "holes": [[20, 10], [40, 10]])");
    const Job job = read_job(job_text, "t.json");
    for (const char* name : {"wabeco", "kosy", "heidenhain", "linuxcnc", "fanuc", "grbl", "sinumerik"}) {
        INFO(name);
        const Machine machine = load_machine(name);
        const std::string program = test::post_program(job, machine);
        const Trace read = trace_program(read_program(program, machine, "t.nc"), machine);
        const auto mismatch = compare_traces(trace_expected(expand_job(job), machine), read, compare_tolerance(machine, 0.0));
        CHECK_MESSAGE(!mismatch, (mismatch ? mismatch->message : ""));
        if (std::string(name) == "wabeco" || std::string(name) == "kosy" || std::string(name) == "heidenhain") {
            // Lines: every point of the final passes' helix within the chord tolerance plus the
            // output's rounding of the radius D / 2 - tool radius = 2, Z on the helix.
            int on_helix = 0;
            for (const camgen::Step& s : read.steps) {
                if (s.arc || s.from.z == s.to.z) continue;
                for (const Vec3& p : {s.from, s.to}) {
                    for (Vec2 c : {Vec2{20, 10}, Vec2{40, 10}}) {
                        const double rr = std::hypot(p.x - c.x, p.y - c.y);
                        if (std::abs(rr - 2) > 0.01 || p.z < -12.5 - 1e-9 || p.z > 1e-9) continue;
                        double a = std::atan2(p.y - c.y, p.x - c.x);
                        if (a < 0) a += two_pi;
                        // Z on the helix at this angle, modulo a pitch.
                        double dz = std::fmod(p.z + 12.5 - 1.5 * a / two_pi, 1.5);
                        if (dz < 0) dz += 1.5;
                        CHECK(std::min(dz, 1.5 - dz) < 0.001);
                        CHECK(std::abs(rr - 2) <= 0.005 + 0.001);
                        ++on_helix;
                    }
                }
            }
            CHECK(on_helix > 100);
        }
    }
}

TEST_CASE("path helix: an exact pitch keeps a partial last turn unless wholeTurns") {
    auto path_job = [](const std::string& helix) {
        return std::string(R"({"clearance": 10, "tools": [{"number": 1, "type": "end-mill", "diameter": 3, "rpm": 1000}],
          "operations": [{"type": "path", "tool": 1, "z": -1, "feed": 100, "start": [5, 0], "path": [{"helix": )") +
               helix + R"(}, {"line": [0, 0]}]}]})";
    };
    // From Z-1 to Z-9.5 at pitch 2: 4 turns and a quarter, ending a quarter turn on (ccw: +Y).
    const Job exact = read_job(path_job(R"({"centre": [0, 0], "direction": "ccw", "z": -9.5, "pitch": 2})"), "t.json");
    const auto& op = std::get<PathOp>(exact.operations[0]);
    const auto& h = std::get<PathHelix>(op.elements[0]);
    CHECK(h.turns == 4);
    CHECK(h.partial == doctest::Approx(std::numbers::pi / 2));
    CHECK(h.end.x == doctest::Approx(0).epsilon(1e-12));
    CHECK(h.end.y == doctest::Approx(5));
    // The line after it starts there, at the helix's Z.
    CHECK(std::get<PathLine>(op.elements[1]).end == Vec3{0, 0, -9.5});
    const auto arcs = arcs_of(events_of(path_job(R"({"centre": [0, 0], "direction": "ccw", "z": -9.5, "pitch": 2})")),
                              Movement::cutting);
    REQUIRE(arcs.size() == 1);
    const double sweep = signed_sweep(arcs[0].first, arcs[0].second);
    CHECK(sweep == doctest::Approx(4.25 * two_pi));
    CHECK(-(arcs[0].second.to.z - arcs[0].first.z) / (sweep / two_pi) == doctest::Approx(2).epsilon(1e-12));

    // wholeTurns: 5 turns of 1.7, back over the start.
    const Job whole = read_job(path_job(R"({"centre": [0, 0], "direction": "ccw", "z": -9.5, "pitch": 2, "wholeTurns": true})"),
                               "t.json");
    const auto& hw = std::get<PathHelix>(std::get<PathOp>(whole.operations[0]).elements[0]);
    CHECK(hw.turns == 5);
    CHECK(hw.partial == 0);
    CHECK(hw.end == Vec2{5, 0});
    check_refused(path_job(R"({"centre": [0, 0], "direction": "ccw", "turns": 2, "pitch": 2, "wholeTurns": true})"),
                  "/operations/0/path/0/helix/wholeTurns", "wholeTurns is for a helix given by z and pitch");
    // A remainder under 0.002 mm along the circle rounds to whole turns.
    const Job tiny = read_job(path_job(R"({"centre": [0, 0], "direction": "cw", "z": -9.0001, "pitch": 2})"), "t.json");
    const auto& ht = std::get<PathHelix>(std::get<PathOp>(tiny.operations[0]).elements[0]);
    CHECK(ht.turns == 4);
    CHECK(ht.partial == 0);
}

}  // namespace test_thread_mill
