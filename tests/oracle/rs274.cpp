#include "rs274.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

namespace camgen::oracle {

namespace {

std::vector<double> arguments(const std::string& inside) {
    std::vector<double> v;
    std::string part;
    std::istringstream in(inside);
    while (std::getline(in, part, ',')) {
        // "0.0000 0.0000 2.5400" (USE_TOOL_LENGTH_OFFSET) or a plane name: take what parses.
        char* end = nullptr;
        double d = std::strtod(part.c_str(), &end);
        if (end != part.c_str()) v.push_back(d);
    }
    return v;
}

bool same_point(const Vec3& a, const Vec3& b) {
    return std::abs(a.x - b.x) < 1e-9 && std::abs(a.y - b.y) < 1e-9 && std::abs(a.z - b.z) < 1e-9;
}

std::string read_all(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

}  // namespace

std::string describe(const Step& s) {
    switch (s.kind) {
        case Step::Kind::traverse: return fmt::format("traverse ({:.4f}, {:.4f}, {:.4f})", s.to.x, s.to.y, s.to.z);
        case Step::Kind::feed:
            return fmt::format("feed ({:.4f}, {:.4f}, {:.4f}) F{:.4f}", s.to.x, s.to.y, s.to.z, s.value);
        case Step::Kind::dwell: return fmt::format("dwell {:.4f} s", s.value);
        case Step::Kind::spindle: return fmt::format("spindle {} {:.0f} rpm", s.spindle, s.value);
        case Step::Kind::rigid_tap: return fmt::format("rigid tap to ({:.4f}, {:.4f}, {:.4f})", s.to.x, s.to.y, s.to.z);
        case Step::Kind::arc:
            return fmt::format("arc {} to ({:.4f}, {:.4f}, {:.4f}) about ({:.4f}, {:.4f}) F{:.4f}", s.rotation > 0 ? "ccw" : "cw", s.to.x,
                               s.to.y, s.to.z, s.centre.x, s.centre.y, s.value);
    }
    return "?";
}

int oracle_stride() {
    const char* env = std::getenv("CAMGEN_ORACLE_STRIDE");
    const int stride = env ? std::atoi(env) : 1;
    return stride > 0 ? stride : 1;
}

bool oracle_case(int k) {
    const int stride = oracle_stride();
    return (k + k / stride) % stride == 0;
}

std::optional<std::string> find_rs274() {
    if (const char* env = std::getenv("CAMGEN_RS274"); env && *env) {
        if (::access(env, X_OK) == 0) return std::string(env);
        return std::nullopt;
    }
    if (const char* path = std::getenv("PATH")) {
        std::istringstream in(path);
        for (std::string dir; std::getline(in, dir, ':');) {
            std::string candidate = (dir.empty() ? "." : dir) + "/rs274";
            if (::access(candidate.c_str(), X_OK) == 0) return candidate;
        }
    }
    if (::access("/usr/bin/rs274", X_OK) == 0) return std::string("/usr/bin/rs274");
    return std::nullopt;
}

std::vector<Step> parse_canon(const std::string& canon) {
    std::vector<Step> steps;
    Vec3 pos{0, 0, 0};
    double feed = 0.0, speed = 0.0;
    std::string spindle = "off";
    bool xy_plane = true;
    auto push_spindle = [&](const std::string& state) {
        spindle = state;
        Step s;
        s.kind = Step::Kind::spindle;
        s.spindle = state;
        s.value = state == "off" ? 0.0 : speed;
        steps.push_back(s);
    };
    auto spindle_step = [&](const std::string& state) {
        if (state != spindle) push_spindle(state);
    };
    std::istringstream in(canon);
    for (std::string line; std::getline(in, line);) {
        auto open = line.find('(');
        auto close = line.rfind(')');
        if (open == std::string::npos || close == std::string::npos || close < open) continue;
        auto name_start = line.rfind(' ', open);
        std::string name = line.substr(name_start == std::string::npos ? 0 : name_start + 1, open - name_start - 1);
        std::vector<double> a = arguments(line.substr(open + 1, close - open - 1));
        if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED" || name == "RIGID_TAP") {
            if (a.size() < 3) throw std::runtime_error("cannot read rs274 line: " + line);
            Vec3 to{a[0], a[1], a[2]};
            if (name != "RIGID_TAP" && same_point(to, pos)) continue;
            Step s;
            s.kind = name == "STRAIGHT_TRAVERSE" ? Step::Kind::traverse
                     : name == "STRAIGHT_FEED"   ? Step::Kind::feed
                                                 : Step::Kind::rigid_tap;
            s.to = to;
            if (s.kind == Step::Kind::feed) s.value = feed;
            steps.push_back(s);
            // A rigid tap returns to where it started.
            if (s.kind != Step::Kind::rigid_tap) pos = to;
        } else if (name == "SELECT_PLANE") {
            xy_plane = line.find("CANON_PLANE_XY") != std::string::npos;
        } else if (name == "ARC_FEED" && xy_plane) {
            // ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end_point, ...)
            if (a.size() < 6) throw std::runtime_error("cannot read rs274 line: " + line);
            Step s;
            s.kind = Step::Kind::arc;
            s.to = {a[0], a[1], a[5]};
            s.centre = {a[2], a[3]};
            s.rotation = static_cast<int>(a[4]);
            s.value = feed;
            steps.push_back(s);
            pos = s.to;
        } else if (name == "SET_FEED_RATE") {
            feed = a.at(0);
        } else if (name == "DWELL") {
            if (a.at(0) > 0.0) {
                Step s;
                s.kind = Step::Kind::dwell;
                s.value = a[0];
                steps.push_back(s);
            }
        } else if (name == "SET_SPINDLE_SPEED") {
            const double v = a.at(a.size() - 1);
            if (v != speed) {
                speed = v;
                if (spindle != "off") push_spindle(spindle);
            }
        } else if (name == "START_SPINDLE_CLOCKWISE") {
            spindle_step("cw");
        } else if (name == "START_SPINDLE_COUNTERCLOCKWISE") {
            spindle_step("ccw");
        } else if (name == "STOP_SPINDLE_TURNING") {
            spindle_step("off");
        }
    }
    return steps;
}

std::vector<Step> run_rs274(const std::string& rs274, const std::string& program, const std::map<int, double>& tool_diameters) {
    return parse_canon(run_rs274_canon(rs274, program, tool_diameters));
}

std::string run_rs274_canon(const std::string& rs274, const std::string& program,
                            const std::map<int, double>& tool_diameters) {
    return run_rs274_canon(rs274, program, tool_diameters, {});
}

std::string run_rs274_canon(const std::string& rs274, const std::string& program, const std::map<int, double>& tool_diameters,
                            const std::map<int, int>& orientations) {
    namespace fs = std::filesystem;
    fs::path dir = fs::temp_directory_path() / fmt::format("camgen-oracle-{}", ::getpid());
    fs::create_directories(dir);
    static int counter = 0;
    fs::path ngc = dir / fmt::format("p{}.ngc", counter++);
    fs::path err = ngc, tools = ngc;
    err.replace_extension(".err");
    tools.replace_extension(".tbl");
    {
        std::ofstream f(ngc);
        f << program;
        // Tools 1 to 99, zero length: rs274's built-in table lacks some numbers.
        std::ofstream t(tools);
        // Its table is in inches (the standalone interpreter's machine units).
        for (int i = 1; i < 100; ++i) {
            const auto d = tool_diameters.find(i);
            const auto q = orientations.find(i);
            if (q != orientations.end())
                t << fmt::format("T{} P{} X0 Z0 D{:.9f} Q{} ;tool {}\n", i, i,
                                 d == tool_diameters.end() ? 1.0 : d->second / 25.4, q->second, i);
            else
                t << fmt::format("T{} P{} Z0 D{:.9f} ;tool {}\n", i, i, d == tool_diameters.end() ? 1.0 : d->second / 25.4, i);
        }
    }
    // rs274 keeps its tool table in $HOME/.tool.mmap, truncated at every start: two rs274 at
    // once (parallel test runs) would share it. Each run gets its own HOME.
    std::string command = fmt::format("HOME='{}' '{}' -t '{}' -g '{}' </dev/null 2>'{}'", dir.string(), rs274,
                                      tools.string(), ngc.string(), err.string());
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + rs274);
    std::string canon;
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) canon.append(buffer, n);
    int status = ::pclose(pipe);
    std::string message = read_all(err);
    std::error_code ec;
    for (const fs::path& p : {ngc, err, tools, dir / fs::path(".tool.mmap")}) fs::remove(p, ec);
    fs::remove(dir, ec);  // only when empty: another run may still use it
    if (status != 0 || canon.find("PROGRAM_END()") == std::string::npos)
        throw std::runtime_error(fmt::format("rs274 rejected the program (status {}): {}\n--- program ---\n{}", status,
                                             message, program));
    return canon;
}

std::vector<XzMove> xz_moves(const std::string& canon, double unit, double min_step) {
    std::vector<XzMove> out;
    double x = 0, z = 0, sync = 0;
    std::istringstream lines(canon);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t open = line.find('('), close = line.rfind(')');
        if (open == std::string::npos || close == std::string::npos || close < open) continue;
        const std::vector<double> a = arguments(line.substr(open + 1, close - open - 1));
        auto called = [&](const char* name) { return line.find(name) != std::string::npos; };
        XzMove m;
        if (called("START_SPEED_FEED_SYNC")) {
            sync = a.at(0) * unit;
            continue;
        } else if (called("STOP_SPEED_FEED_SYNC")) {
            sync = 0;
            continue;
        } else if (called("STRAIGHT_TRAVERSE") || called("STRAIGHT_FEED")) {
            if (a.size() < 3) throw std::runtime_error("cannot read rs274 line: " + line);
            m.rapid = called("STRAIGHT_TRAVERSE");
            m.x = a[0] * unit, m.z = a[2] * unit;
            m.sync = m.rapid ? 0.0 : sync;
            if (std::abs(m.x - x) < min_step && std::abs(m.z - z) < min_step) continue;
        } else if (called("ARC_FEED")) {
            if (a.size() < 5) throw std::runtime_error("cannot read rs274 line: " + line);
            m.arc = true;
            m.z = a[0] * unit, m.x = a[1] * unit, m.cz = a[2] * unit, m.cx = a[3] * unit;
        } else {
            continue;
        }
        m.from_x = x, m.from_z = z;
        x = m.x, z = m.z;
        out.push_back(m);
    }
    return out;
}

}  // namespace camgen::oracle
