#pragma once
// Helpers for the tests of the lathe's material checks (check_blade_material: the blades' rapids
// and the threads' diameters against what earlier operations keep and the bar's solid they
// left): a job's refusal, a lathe tool table and job around operations, a turned profile with
// its kept radius worked out here, and the post-and-simulate check of an accepted job on the
// three lathes.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

namespace camgen::test {

// The refusal's text, or "" where the job is read.
inline std::string job_refusal(const std::string& text) {
    try {
        (void)read_job(text, "blade.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// T3 a turning tool (R0.4, orientation 2), T5 a 3 mm grooving tool, T6 a 3 mm parting tool, T8
// an internal grooving tool, T9 a face grooving tool, T2 a 16 mm drill, T7 an external and T10
// an internal threading tool.
constexpr const char* blade_tools = R"([{"number": 3, "type": "turning-tool", "noseRadius": 0.4, "orientation": 2, "rpm": 1200},
  {"number": 5, "type": "grooving-tool", "width": 3, "fluteLength": 10, "rpm": 700},
  {"number": 6, "type": "parting-tool", "width": 3, "fluteLength": 25, "rpm": 500},
  {"number": 8, "type": "grooving-tool", "width": 2.5, "fluteLength": 4, "orientation": 3, "rpm": 700},
  {"number": 9, "type": "grooving-tool", "width": 3, "fluteLength": 6, "orientation": 7, "rpm": 700},
  {"number": 2, "type": "drill", "diameter": 16, "tipAngle": 118, "rpm": 600},
  {"number": 7, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "rpm": 400},
  {"number": 10, "type": "threading-tool", "noseRadius": 0.1, "profileAngle": 60, "orientation": 3, "rpm": 400}])";

// A job of those tools, clearance Z20, `stock` (", \"stock\": ..." or "") and the operations.
inline std::string blade_job(const std::string& stock, const std::string& operations) {
    return fmt::format(R"({{"name": "t", "units": "mm", "clearance": 20{}, "tools": {}, "operations": [{}]}})", stock, blade_tools,
                       operations);
}

// A turned profile's points (Z, radius), a polyline from the axis at its start, and its
// operation's JSON.
struct TurnedProfile {
    std::vector<std::pair<double, double>> points;  // (Z, radius), Z falling
    std::string json;
};

// The radius the profile keeps at Z (0 outside its stretch of Z).
inline double kept_at(const TurnedProfile& p, double z) {
    double top = 0.0;
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
        const auto [z0, r0] = p.points[i];
        const auto [z1, r1] = p.points[i + 1];
        if (z > z0 || z < z1) continue;
        top = std::max(top, z0 == z1 ? std::max(r0, r1) : r0 + (r1 - r0) * (z - z0) / (z1 - z0));
    }
    return top;
}

// Whether a line at `radius` along Z from lo to hi runs under the radius `material(z)` for more
// than a few µm (sampled every 0.5 µm).
template <class Material>
bool runs_through(const Material& material, double radius, double lo, double hi) {
    int inside = 0;
    for (double z = lo; z <= hi; z += 0.0005) {
        inside = material(z) > radius + 1e-5 ? inside + 1 : 0;
        if (inside * 0.0005 > 0.004) return true;
    }
    return false;
}
inline bool crosses(const TurnedProfile& p, double radius, double lo, double hi) {
    return runs_through([&](double z) { return kept_at(p, z); }, radius, lo, hi);
}

// A profile D(a) from the face to Z s, then D(b) to Z-40 (with a 1 mm chamfer at the face): a
// shoulder up at s, or (b < a) a taper down from s over a - b along Z (an orientation-2 tool
// turns no face towards the chuck).
inline TurnedProfile shoulder(double a, double b, double s) {
    TurnedProfile p;
    const double t = b < a ? s - (a - b) : s;
    p.points = {{0, 0}, {0, a / 2 - 1}, {-1, a / 2}, {s, a / 2}, {t, b / 2}, {-40, b / 2}};
    p.json = fmt::format(R"({{"type": "turn-profile", "tool": 3, "feed": 0.1, "feedMode": "per-revolution", "start": [0, 0],
  "retractX": 44, "path": [{{"line": [{}, 0]}}, {{"line": [{}, -1]}}, {{"line": [{}, {}]}}, {{"line": [{}, {}]}},
  {{"line": [{}, -40]}}]}})",
                         a - 2, a, a, s, b, t, b);
    return p;
}

// Posts the job on the three lathes and simulates each against it: no crash (a thread pass that
// overloads its insert is one too).
inline void simulates_without_crash(const std::string& text, const std::filesystem::path& dir, int k) {
    const std::string path = (dir / fmt::format("j{}.json", k)).string();
    std::ofstream(path) << text;
    for (const std::string machine : {"linuxcnc-lathe", "fanuc-lathe", "sinumerik-lathe"}) {
        const std::string nc = (dir / fmt::format("j{}-{}.nc", k, machine)).string();
        const Run posted = run({path, "--machine", machine, "-q", "-o", nc});
        REQUIRE_MESSAGE(posted.code == 0, posted.err);
        const Run r = run({"simulate", nc, "--machine", machine, "--job", path});
        INFO(machine);
        CHECK_MESSAGE(r.out.find("crash") == std::string::npos, r.out);
        CHECK_MESSAGE(r.err.find("crash") == std::string::npos, r.err);
    }
}

}  // namespace camgen::test
