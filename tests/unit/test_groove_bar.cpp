// External grooves, part-offs and threads against the bar nothing has turned yet
// (check_blade_material with a stock bar): the tester's jobs (a groove with startX 32 in a D40
// bar that no operation turned where it is; an M24 thread on a D30 bar) are refused at startX
// and at the thread's key, naming the bar's solid, and post nothing; after a turn-rough or a
// turn-profile that turns the bar down there they post and simulate without a crash. `camgen
// simulate` reports a thread pass into a diameter larger than the thread as an overload. And
// generated jobs (bars of several diameters, faced or not, turned down by a turn-rough, a
// turn-profile or both over part of their length or not at all, grooves and threads on either
// side of the turned zone's end): each refusal is a job whose blade rapids or thread, worked out
// here from its keys, would meet the material; each accepted one posts and simulates without a
// crash on the three lathes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "blade_support.hpp"

namespace test_groove_bar {

using namespace camgen;

namespace {

std::string bar(double diameter, double face_z = 0.0) {
    return fmt::format(R"(, "stock": {{"bar": {{"diameter": {}, "length": 70, "faceZ": {}}}}})", diameter, face_z);
}

// A turn-rough (no allowances) and a turn-profile of the same shape: D a from the face (a 1 mm
// chamfer) down to Z s, its end at the shoulder; the profile faces the end from the axis first
// (its nose, run along the chamfer's start, would reach into it from a start there).
std::string turned_path(double a, double s, bool from_axis = false) {
    return fmt::format(R"("start": [{}, 0], "path": [{}{{"line": [{}, -1]}}, {{"line": [{}, {}]}}])", from_axis ? 0 : a - 2,
                       from_axis ? fmt::format(R"({{"line": [{}, 0]}}, )", a - 2) : std::string(), a, a, s);
}
std::string rough(double a, double s) {
    return fmt::format(R"({{"type": "turn-rough", "tool": 3, "feed": 0.2, "feedMode": "per-revolution", "depthOfCut": 2, {}}})",
                       turned_path(a, s));
}
std::string profile(double a, double s, double retract) {
    return fmt::format(R"({{"type": "turn-profile", "tool": 3, "feed": 0.1, "feedMode": "per-revolution", "retractX": {}, {}}})",
                       retract, turned_path(a, s, true));
}
std::string groove(double start_x, double z, double width, double approach, double chamfer) {
    return fmt::format(R"({{"type": "turn-groove", "tool": 5, "feed": 0.05, "feedMode": "per-revolution", "startX": {}, "z": {},
      "width": {}, "bottomX": {}, "approachDistance": {}, "chamfer": {}}})",
                       start_x, z, width, start_x - 4, approach, chamfer);
}
std::string thread(const std::string& designation, double end_z) {
    return fmt::format(R"({{"type": "turn-thread", "tool": 7, "thread": "{}", "startZ": 0, "endZ": {}, "firstDepth": 0.3,
      "springPasses": 1}})",
                       designation, end_z);
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Posting the job from a file: its exit code and whether it wrote the output.
struct Posted {
    int code;
    bool written;
    std::string err;
};
Posted post_file(const std::string& text, const std::string& name, const std::string& machine) {
    const std::filesystem::path dir = test::scratch("groove-bar");
    const std::string path = (dir / (name + ".json")).string(), nc = (dir / (name + ".nc")).string();
    std::filesystem::remove(nc);
    std::ofstream(path) << text;
    const test::Run r = test::run({path, "--machine", machine, "-q", "-o", nc});
    return {r.code, std::filesystem::exists(nc), r.err};
}

// Simulates the program in a D24 bar: "" where it exits 0 without an overload, else what it said.
std::string fits_text(const std::filesystem::path&, const std::string& nc, const std::string& machine, const std::string& job) {
    const test::Run fits = test::run({"simulate", nc, "--machine", machine, "--job", job, "--bar", "24,70,0"});
    const std::string said = fits.out + fits.err;
    return fits.code == 0 && !has(said, "overloaded") ? std::string() : said;
}

}  // namespace

TEST_CASE("groove bar: the tester's groove into the D40 bar nothing turned is refused at startX and posts nothing") {
    const std::string d40 = bar(40);
    const std::string g = test::blade_job(d40, groove(32, -20, 4, 1, 0));
    const std::string e = test::job_refusal(g);
    CHECK_MESSAGE(has(e, "/operations/0/startX: the blade's rapid along X from X 42.000 mm to X 34.000 mm at Z -23.000 mm runs "
                         "through the bar's solid between Z -23.000 mm and Z -20.000 mm: the operations before it left the bar "
                         "(X 40.000 mm) up to X 40.000 mm there, none (a turn-face, turn-rough, turn-profile, groove or "
                         "part-off) turned it down to X 34.000 mm"),
                  e);
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        const Posted p = post_file(g, "tester-groove-" + machine, machine);
        INFO(machine);
        CHECK(p.code != 0);
        CHECK_FALSE(p.written);
        CHECK_MESSAGE(has(p.err, "/operations/0/startX"), p.err);
    }
    // A turn-face alone turns nothing down there.
    CHECK(has(test::job_refusal(test::blade_job(bar(40, 1), R"({"type": "turn-face", "tool": 3, "z": 0, "feed": 0.1,
      "feedMode": "per-revolution"}, )" + groove(32, -20, 4, 1, 0))),
              "/operations/1/startX: the blade's rapid along X"));
    // Turned down to D32 over it first (a turn-rough, a turn-profile, both): read.
    for (const std::string& before : {rough(32, -30), profile(32, -30, 42), rough(32, -30) + ", " + profile(32, -30, 42)})
        CHECK_MESSAGE(test::job_refusal(test::blade_job(d40, before + ", " + groove(32, -20, 4, 1, 0))) == "", before);
    // The groove beyond the turned zone's end (Z-30) is in the bar again.
    const std::string beyond = test::job_refusal(test::blade_job(d40, rough(32, -30) + ", " + groove(32, -33, 4, 1, 0)));
    CHECK_MESSAGE(has(beyond, "/operations/1/startX: the blade's rapid along X from X 42.000 mm to X 34.000 mm at Z -36.000 mm "
                              "runs through the bar's solid between Z -36.000 mm and Z -33.000 mm"),
                  beyond);
    // Its chamfer's move along Z at the approach level runs into the shoulder at Z-30.
    const std::string chamfer = test::job_refusal(test::blade_job(d40, rough(32, -30) + ", " + groove(32, -26, 4, 1, 1)));
    CHECK_MESSAGE((has(chamfer, "/operations/1/startX: the blade's rapid along Z at X 34.000 mm") &&
                   has(chamfer, "runs through the bar's solid between Z -32.000 mm and Z -30.000 mm")),
                  chamfer);
    // startX the bar's: read anywhere.
    CHECK(test::job_refusal(test::blade_job(d40, groove(40, -20, 4, 1, 0))) == "");
    // An earlier groove opened the way: a second, deeper one in its slot with startX its bottom.
    CHECK(test::job_refusal(test::blade_job(d40, groove(40, -20, 6, 1, 0) + ", " + groove(36, -20, 6, 1, 0))) == "");
    CHECK(has(test::job_refusal(test::blade_job(d40, groove(40, -20, 6, 1, 0) + ", " + groove(36, -19, 6, 1, 0))),
              "/operations/1/startX: the blade's rapid"));
}

TEST_CASE("groove bar: a part-off and a face groove into the bar nothing turned are refused") {
    const std::string part = test::job_refusal(test::blade_job(bar(40), R"({"type": "turn-part", "tool": 6, "feed": 0.05,
      "feedMode": "per-revolution", "startX": 30, "z": -35})"));
    CHECK_MESSAGE(has(part, "/operations/0/startX: the blade's rapid along X from X 42.000 mm to X 32.000 mm at Z -38.000 mm "
                            "runs through the bar's solid between Z -38.000 mm and Z -35.000 mm"),
                  part);
    CHECK(test::job_refusal(test::blade_job(bar(40), rough(30, -40) + R"(, {"type": "turn-part", "tool": 6, "feed": 0.05,
      "feedMode": "per-revolution", "startX": 30, "z": -35})")) == "");
    // A face groove below the bar's face: its blade comes down through the bar.
    const std::string face = test::job_refusal(test::blade_job(bar(40), R"({"type": "turn-groove", "tool": 9, "side": "face",
      "feed": 0.04, "feedMode": "per-revolution", "z": -5, "innerX": 20, "outerX": 28, "depth": 2})"));
    CHECK_MESSAGE(has(face, "/operations/0/z: the blade's rapid from X 22.000 mm Z 20.000 mm to X 22.000 mm Z -4.000 mm (its "
                            "body above it, up to the clearance) runs through the bar's solid between Z -4.000 mm and Z 0.000 mm"),
                  face);
}

TEST_CASE("groove bar: a thread larger than the diameter it is cut on is refused at its key") {
    // The tester's M24 on a D30 bar.
    const std::string m24 = test::blade_job(bar(30), thread("M24", -20));
    const std::string e = test::job_refusal(m24);
    CHECK_MESSAGE(has(e, "/operations/0/thread: the thread M24x3 (major diameter 24.000 mm) is cut on the bar's solid between "
                         "Z -20.000 mm and Z 0.000 mm: the operations before it left the bar (diameter 30.000 mm) up to "
                         "diameter 30.000 mm there, none (a turn-face, turn-rough, turn-profile, groove or part-off) turned "
                         "it down to the major"),
                  e);
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        const Posted p = post_file(m24, "tester-thread-" + machine, machine);
        INFO(machine);
        CHECK(p.code != 0);
        CHECK_FALSE(p.written);
    }
    // By its diameters: at majorDiameter.
    CHECK(has(test::job_refusal(test::blade_job(bar(30), R"({"type": "turn-thread", "tool": 7, "majorDiameter": 24,
      "minorDiameter": 20.32, "pitch": 3, "startZ": 0, "endZ": -20, "firstDepth": 0.3})")),
              "/operations/0/majorDiameter: the thread (major diameter 24.000 mm) is cut on the bar's solid"));
    // Turned to the major first: read. Within the tolerance (0.05 radial) too; beyond it not.
    CHECK(test::job_refusal(test::blade_job(bar(30), rough(24, -25) + ", " + thread("M24", -20))) == "");
    CHECK(test::job_refusal(test::blade_job(bar(30), rough(24.08, -25) + ", " + thread("M24", -20))) == "");
    const std::string over = test::job_refusal(test::blade_job(bar(30), rough(24.12, -25) + ", " + thread("M24", -20)));
    CHECK_MESSAGE(has(over, "/operations/1/thread: the thread M24x3 (major diameter 24.000 mm) is cut on the bar's solid between "
                            "Z -20.000 mm and Z -0.990 mm: the operations before it left the bar (diameter 30.000 mm) up to "
                            "diameter 24.120 mm there"),
                  over);
    // The turned zone ends before the thread does.
    CHECK(has(test::job_refusal(test::blade_job(bar(30), rough(24, -15) + ", " + thread("M24", -20))),
              "/operations/1/thread: the thread M24x3 (major diameter 24.000 mm) is cut on the bar's solid between Z -20.000 mm "
              "and Z -15.000 mm"));
    // Without a bar: what an earlier turn-profile keeps.
    const std::string kept = test::job_refusal(test::blade_job("", profile(30, -30, 34) + ", " + thread("M24", -20)));
    CHECK_MESSAGE(has(kept, "/operations/1/thread: the thread M24x3 (major diameter 24.000 mm) is cut on the material that the "
                            "profile of /operations/0 keeps: diameter up to 30.000 mm between Z -20.000 mm and Z 0.000 mm"),
                  kept);
    CHECK(test::job_refusal(test::blade_job("", profile(24, -30, 34) + ", " + thread("M24", -20))) == "");
    // Nothing known of the material: read.
    CHECK(test::job_refusal(test::blade_job("", thread("M24", -20))) == "");
    // Inside: the bore must be the minor (M24: D1 20.752).
    const std::string inside = R"({"type": "turn-thread", "tool": 10, "side": "internal", "thread": "M24", "startZ": 0,
      "endZ": -15, "firstDepth": 0.2})";
    CHECK(has(test::job_refusal(test::blade_job(bar(50), inside)),
              "/operations/0/thread: the thread M24x3 (minor diameter 20.752 mm) is cut into the bar's solid between Z -15.000 mm "
              "and Z 0.000 mm: nothing before it (the bar's bore, a turn-drill"));
    CHECK(has(test::job_refusal(test::blade_job(bar(50), R"({"type": "turn-drill", "tool": 2, "startDepth": 0, "endDepth": -30,
      "safeDistance": 2, "plungingFeedrate": 0.1, "feedMode": "per-revolution"}, )" + inside)),
              "/operations/1/thread: the thread M24x3 (minor diameter 20.752 mm) is cut into the bar's solid"));
    CHECK(test::job_refusal(test::blade_job(R"(, "stock": {"bar": {"diameter": 50, "length": 70, "faceZ": 0, "boreDiameter": 20.8}})",
                                            inside)) == "");
    CHECK(has(test::job_refusal(test::blade_job(
                  R"(, "stock": {"bar": {"diameter": 50, "length": 70, "faceZ": 0, "boreDiameter": 20.5}})", inside)),
              "/operations/0/thread: the thread M24x3 (minor diameter 20.752 mm)"));
}

TEST_CASE("groove bar: simulate reports a thread pass into a diameter larger than the thread as an overload") {
    // The job without a stock posts (nothing known of the material); simulated in a D30 bar its
    // first pass cuts 3 mm more than the thread's.
    const std::filesystem::path dir = test::scratch("groove-bar-sim");
    const std::string path = (dir / "m24.json").string();
    std::ofstream(path) << test::blade_job("", thread("M24", -20));
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        INFO(machine);
        const std::string nc = (dir / ("m24-" + machine + ".nc")).string();
        REQUIRE(test::run({path, "--machine", machine, "-q", "-o", nc}).code == 0);
        const test::Run over = test::run({"simulate", nc, "--machine", machine, "--job", path, "--bar", "30,70,0"});
        CHECK(over.code != 0);
        const std::string said = over.out + over.err, fitted = fits_text(dir, nc, machine, path);
        CHECK_MESSAGE(has(said, "a thread pass cuts 3.3 mm deep (radial) in one pass, more than a thread of "
                                               "lead 3 mm is deep (2.598 mm, a sharp 60-degree V): the threading insert is "
                                               "overloaded (a crash)"),
                      said);
        // On a D24 bar, the thread's own passes: no error.
        CHECK_MESSAGE(fitted.empty(), fitted);
    }
}

TEST_CASE("groove bar: generated grooves and threads refused only where they meet the bar's material; the rest simulate without a crash") {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto half = [&](double lo, double hi) { return std::round((lo + (hi - lo) * u(rng)) * 2) / 2; };
    const std::filesystem::path dir = test::scratch("groove-bar-generated");
    const double bars[] = {36, 40, 44, 50};
    struct Metric {
        const char* name;
        double major;
    };
    const Metric threads[] = {{"M16", 16}, {"M20", 20}, {"M24", 24}, {"M30", 30}, {"M36", 36}};
    int refused = 0, read = 0, k = 0, refused_threads = 0, read_threads = 0;
    for (int n = 0; n < 44; ++n) {
        const double d = bars[n % 4];
        const int zone = (n / 4) % 4;  // 0 none, 1 turn-rough, 2 turn-profile, 3 both
        const double a = 2 * std::round(half(d - 14, d - 4) / 2), s = half(-32, -12);
        const bool faced = n % 3 == 0;
        std::string ops = faced ? R"({"type": "turn-face", "tool": 3, "z": 0, "feed": 0.1, "feedMode": "per-revolution"}, )" : "";
        if (zone == 1 || zone == 3) ops += rough(a, s) + ", ";
        if (zone >= 2) ops += profile(a, s, d + 2) + ", ";
        // The material's radius at Z as this job leaves it: the bar, turned to D a (its 1 mm
        // chamfer at the face) down to Z s; nothing beyond the face.
        auto material = [&](double z) {
            if (z > 0) return 0.0;
            if (zone > 0 && z >= s) return z > -1 ? a / 2 - 1 - z : a / 2;
            return d / 2;
        };
        const bool is_thread = n % 5 == 4;
        bool meets = false;
        if (is_thread) {
            const Metric t = threads[static_cast<std::size_t>(u(rng) * 5) % 5];
            if (t.major > d) continue;
            const double end = half(-25, -8);
            ops += thread(t.name, end);
            meets = test::runs_through(material, t.major / 2 + 0.05, end, 0.0);
        } else {
            const double start = u(rng) < 0.5 || zone == 0 ? a : d;
            const double z = half(-40, -4), width = half(3, 6), approach = u(rng) < 0.5 ? 1.0 : half(0.5, 2);
            const double chamfer = u(rng) < 0.4 ? 0.5 : 0.0;
            ops += groove(start, z, width, approach, chamfer);
            const double air = start / 2 + approach, reach = chamfer > 0 ? chamfer + approach : 0.0;
            meets = test::runs_through(material, air, z - width - reach, z + reach);
        }
        const std::string text = test::blade_job(bar(d, faced ? 1 : 0), ops);
        const std::string e = test::job_refusal(text);
        INFO(text);
        if (!e.empty()) {
            ++refused;
            refused_threads += is_thread;
            CHECK_MESSAGE(meets, e);
            CHECK_MESSAGE((has(e, "/startX: the blade's rapid") || has(e, "/thread: the thread")), e);
            continue;
        }
        ++read;
        read_threads += is_thread;
        CHECK_MESSAGE(!meets, "read, though the blade's rapids or the thread meet the material");
        test::simulates_without_crash(text, dir, k++);
    }
    // Every kind was made.
    CHECK(refused >= 8);
    CHECK(read >= 8);
    CHECK(refused_threads >= 1);
    CHECK(read_threads >= 1);
}

}  // namespace test_groove_bar
