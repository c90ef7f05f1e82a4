#pragma once
// Helpers shared by the unit tests: run the pipeline in-process, split NC text into words.
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "camgen/cli/cli.hpp"
#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"

namespace camgen::test {

// The camgen command the tests run: CAMGEN_BINARY from the environment (the sanitized twin's
// ctest entries point it at build/sanitized/camgen, CMakeLists.txt), else the one built beside
// the tests. The test objects are shared by both test programs, so this is read at run time.
#ifdef CAMGEN_BINARY
inline const char* camgen_binary() {
    const char* env = std::getenv("CAMGEN_BINARY");
    return env && *env ? env : CAMGEN_BINARY;
}
#endif

// Whether the sanitizers' runtime is linked in (the twin test programs): their allocator and
// shadow memory raise a process's peak memory. The test objects are compiled without the
// instrumentation, so this is asked of the linked program, not of the compiler.
extern "C" void __asan_init() __attribute__((weak));
inline bool sanitizer_runtime() { return &__asan_init != nullptr; }

struct Posted {
    std::string text;
    std::string warnings;
    std::string notes;  // (post_noted's)
};

// Posts a job given as JSON text for a machine given by name.
// Posts a job for a machine as the command line does (its work offset and program number);
// warnings go to `warnings` when given.
inline std::string post_program(const Job& job, const Machine& machine, bool snippet = false,
                                std::ostream* warnings = nullptr) {
    std::ostringstream out;
    PostOptions o;
    o.snippet = snippet;
    o.program_name = job.name;
    o.warnings = warnings;
    o.work_offset = job.work_offset;
    o.program_number = job.program_number;
    check_machine_kind(job, machine.kind, machine.name);
    auto post = make_post(machine, out, o);
    post->open();
    expand_job(job, *post);
    post->close();
    return out.str();
}

// The diameter of each tool of a job, mm, by number (for an interpreter's tool table).
inline std::map<int, double> tool_diameters(const Job& job) {
    std::map<int, double> out;
    for (const auto& [number, tool] : job.tools) out[number] = tool.diameter;
    return out;
}

// Posts a job for a machine keeping camgen's notes (a cycle written longhand and why, ...):
// the program in `text`, the notes in `notes`.
inline Posted post_noted(const Job& job, const Machine& machine) {
    std::ostringstream out, notes;
    PostOptions o;
    o.notes = &notes;
    auto post = make_post(machine, out, o);
    post->open();
    expand_job(job, *post);
    post->close();
    return {out.str(), {}, notes.str()};
}
inline Posted post_noted(const std::string& job_json, const Machine& machine, const std::string& source = "test.json") {
    return post_noted(read_job(job_json, source), machine);
}

inline Posted post_job(const std::string& job_json, const std::string& machine_name, bool snippet = false) {
    std::ostringstream warn;
    std::string text = post_program(read_job(job_json, "test.json"), load_machine(machine_name), snippet, &warn);
    return {std::move(text), warn.str()};
}

// The lines of a text.
inline std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// The words of one block: letter -> value text ("G02 D90 I0 J10" -> {G:02, D:90, I:0, J:10}).
inline std::map<char, std::string> words_of(const std::string& line) {
    std::map<char, std::string> w;
    std::istringstream in(line);
    for (std::string word; in >> word;)
        if (!word.empty()) w[word[0]] = word.substr(1);
    return w;
}

// The result of running the command line in-process.
struct Run {
    int code;
    std::string out;
    std::string err;
};

// Runs camgen with these arguments (after "camgen"), standard input given as text.
inline Run run(std::vector<std::string> args, const std::string& stdin_text = "") {
    std::vector<const char*> argv{"camgen"};
    for (const auto& a : args) argv.push_back(a.c_str());
    std::istringstream in(stdin_text);
    std::ostringstream out, err;
    int code = run_cli(static_cast<int>(argv.size()), argv.data(), in, out, err);
    return {code, out.str(), err.str()};
}

// An empty scratch folder for one test, under the system's temporary folder.
// The process id is in its name: two test runs at once (a build tree and a fresh clone) must not
// share, and clear, each other's folders.
inline std::filesystem::path scratch(const std::string& name) {
    std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("camgen-test-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A job with one drilling operation at (10, 10) and (30, 10) given by its JSON keys (tool 1:
// a 5 mm drill at 1000 rpm with `tool_extra` keys, tool 2: an 8 mm tap at 300 rpm).
inline std::string drill_job(const std::string& op, const std::string& tool_extra = "") {
    return R"({"name": "t", "units": "mm", "clearance": 20, "tools": [
  {"number": 1, "type": "drill", "diameter": 5, "rpm": 1000)" + tool_extra + R"(},
  {"number": 2, "type": "tap", "diameter": 8, "rpm": 300}],
"operations": [{"type": "drill", )" + op + R"(, "holes": [[10, 10], [30, 10]]}]})";
}

// Writes `text` to <scratch folder "job-NAME">/NAME.json and returns its path.
inline std::string file_with(const std::string& name, const std::string& text) {
    std::filesystem::path p = scratch("job-" + name) / (name + ".json");
    std::ofstream(p) << text;
    return p.string();
}

inline std::string read_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// ---- a small NC interpreter for arc tests ----
// It reads what the iso and nccad posts write (G0/G1/G2/G3, G17/G18/G19, X Y Z, I J K, R, D)
// and works the arcs out on its own, from the words alone: the plane's normal is +Z, +Y, +X for
// G17, G18, G19, and G3 turns positively about it (right-hand rule), as LinuxCNC and Fanuc
// define it. It does not use camgen's arc code, so it can check it.

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, double k) { return {a.x * k, a.y * k, a.z * k}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normal_of(Plane p) { return p == Plane::xy ? Vec3{0, 0, 1} : p == Plane::xz ? Vec3{0, 1, 0} : Vec3{1, 0, 0}; }
// `v` without its part along the unit vector `n`.
inline Vec3 flatten(Vec3 v, Vec3 n) { return v - n * dot(v, n); }
// `v` turned by `angle` radians about the unit vector `n` (Rodrigues).
inline Vec3 turn(Vec3 v, Vec3 n, double angle) {
    return v * std::cos(angle) + cross(n, v) * std::sin(angle) + n * (dot(n, v) * (1 - std::cos(angle)));
}

// One move as the control runs it.
struct NcMove {
    std::string line;
    int g = 0;                 // 0, 1, 2, 3
    Plane plane = Plane::xy;
    Vec3 from, to;
    Vec3 centre;               // arcs: in the start's plane
    double radius_start = 0, radius_end = 0;
    double sweep = 0;          // arcs: radians, > 0
    // The point at fraction t of the move (an arc with unequal radii is a spiral).
    Vec3 at(double t) const {
        if (g < 2) return from + (to - from) * t;
        Vec3 n = normal_of(plane);
        Vec3 a = flatten(from - centre, n);
        double r = radius_start + (radius_end - radius_start) * t;
        Vec3 p = centre + turn(a, n, (g == 3 ? 1 : -1) * sweep * t) * (r / length(a));
        return p + n * (dot(to - from, n) * t);
    }
};

// Interprets NC text; `form` says how arc words are read. Lines that are not motion (program
// frame, comments, tool and spindle words, messages) are skipped.
inline std::vector<NcMove> interpret(const std::string& text, ArcFormat form, Vec3 start = {}) {
    std::vector<NcMove> moves;
    Vec3 pos = start;
    int motion = 0;
    Plane plane = Plane::xy;
    for (const std::string& raw : lines_of(text)) {
        if (raw.empty() || raw[0] == '(' || raw[0] == ';' || raw[0] == '%' || raw[0] == '_' || raw[0] == 'O') continue;
        std::istringstream in(raw);
        std::map<char, double> w;
        bool skip = false;
        for (std::string word; in >> word;) {
            char letter = word[0];
            if (letter == 'M') {  // spindle, messages: no motion
                skip = true;
                break;
            }
            if (letter == 'N') continue;
            double value = std::stod(word.substr(1));
            if (letter == 'G') {
                int g = static_cast<int>(value);
                if (g <= 3) motion = g;
                else if (g == 17) plane = Plane::xy;
                else if (g == 18) plane = Plane::xz;
                else if (g == 19) plane = Plane::yz;
                else if (g >= 73 && g <= 89) skip = true;  // drilling cycles: not followed here
                continue;
            }
            w[letter] = value;
        }
        if (skip) continue;
        bool axis = w.count('X') || w.count('Y') || w.count('Z') || w.count('D');
        if (!axis) continue;
        NcMove m;
        m.line = raw;
        m.g = motion;
        m.plane = plane;
        m.from = pos;
        m.to = {w.count('X') ? w['X'] : pos.x, w.count('Y') ? w['Y'] : pos.y, w.count('Z') ? w['Z'] : pos.z};
        if (motion >= 2) {
            const Vec3 n = normal_of(plane);
            const double sign = motion == 3 ? 1.0 : -1.0;
            // The in-plane words of the centre: I J (G17), I K (G18), J K (G19).
            Vec3 ijk{w.count('I') ? w['I'] : 0.0, w.count('J') ? w['J'] : 0.0, w.count('K') ? w['K'] : 0.0};
            if (form == ArcFormat::nccad_angle) {
                m.centre = pos + Vec3{ijk.x, ijk.y, 0};
                m.sweep = w['D'] * std::numbers::pi / 180.0;
                m.to = m.centre + turn(pos - m.centre, n, sign * m.sweep);
            } else if (form == ArcFormat::radius) {
                Vec3 chord = flatten(m.to - pos, n);
                double h = length(chord) / 2, r = w['R'];
                double d = std::sqrt(std::max(r * r - h * h, 0.0));
                Vec3 left = cross(n, chord) * (1.0 / length(chord));
                // R > 0: the short way round, the centre on the side the arc turns to.
                double side = (sign > 0) == (r > 0) ? 1.0 : -1.0;
                m.centre = pos + chord * 0.5 + left * (side * d);
            } else {
                Vec3 in_plane = flatten(ijk, n);
                m.centre = form == ArcFormat::ijk_relative ? pos + in_plane : in_plane;
            }
            m.centre = flatten(m.centre, n) + n * dot(pos, n);
            Vec3 a = flatten(pos - m.centre, n), b = flatten(m.to - m.centre, n);
            m.radius_start = length(a);
            m.radius_end = length(b);
            if (form != ArcFormat::nccad_angle) {
                double angle = std::atan2(dot(n, cross(a, b)), dot(a, b)) * sign;
                while (angle <= 1e-12) angle += 2 * std::numbers::pi;
                // End equal to the start (as written): a full circle.
                if (length(flatten(m.to - pos, n)) == 0.0) angle = 2 * std::numbers::pi;
                m.sweep = angle;
            }
        }
        moves.push_back(m);
        pos = m.to;
    }
    return moves;
}

// Posts events (as a snippet) for a machine.
inline std::string post_events(const Machine& machine, const std::vector<Event>& events) {
    std::ostringstream out;
    PostOptions o;
    o.snippet = true;
    auto post = make_post(machine, out, o);
    post->open();
    for (const Event& e : events) post->emit(e);
    post->close();
    return out.str();
}

// The first number in NC text that has an exponent or is minus zero, or NaN / inf; "" if none.
// A number here is what follows a word letter or '=': sign, digits, decimal mark, digits.
inline std::string bad_number(const std::string& text) {
    for (size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (c == 'n' && text.compare(i, 3, "nan") == 0) return "nan";
        if (c == 'i' && text.compare(i, 3, "inf") == 0 && text.compare(i, 4, "info") != 0) return "inf";
        if (!(std::isupper(static_cast<unsigned char>(c)) || c == '=')) continue;
        size_t j = i + 1;
        bool minus = j < text.size() && text[j] == '-';
        if (j < text.size() && (text[j] == '-' || text[j] == '+')) ++j;
        size_t digits_start = j;
        bool nonzero = false;
        while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '.' || text[j] == ',')) {
            if (std::isdigit(static_cast<unsigned char>(text[j])) && text[j] != '0') nonzero = true;
            ++j;
        }
        if (j == digits_start || !std::isdigit(static_cast<unsigned char>(text[digits_start]))) continue;
        if (j < text.size() && (text[j] == 'e' || text[j] == 'E') && j + 1 < text.size() &&
            (std::isdigit(static_cast<unsigned char>(text[j + 1])) || text[j + 1] == '-' || text[j + 1] == '+'))
            return text.substr(i, j + 2 - i);
        if (minus && !nonzero) return text.substr(i, j - i);
    }
    return {};
}

}  // namespace camgen::test
