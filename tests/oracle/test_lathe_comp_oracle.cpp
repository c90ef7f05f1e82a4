// LinuxCNC oracle for nose-radius compensation by the control (camgen issue 30, item 3): rs274
// with a lathe tool table (D the nose diameter, Q the orientation, in inches) runs linuxcnc-lathe
// programs with G41/G42 in G18 over random profiles (tapers, arcs, chamfers, shoulders; outside
// with G42, inside with G41; orientations 1 to 8), and
// - camgen's read-back of each program (reader + trace with the tool's radius and orientation)
//   moves the tip as rs274 does, within 0.001 mm, or both refuse it;
// - the nose circle about the centre (rs274's tip less the orientation's offset) touches the
//   designed profile and never crosses it, within 0.002 mm (distances computed here, from the
//   profile's lines and arcs, independently of camgen's geometry);
// - a turn-profile job with "compensation": "control" posted for linuxcnc-lathe runs in rs274 as
//   camgen's own trace of the job (what verify and the simulation see) and as its read-back.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen_motion.hpp"
#include "rs274.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_lathe_comp_oracle {

using namespace camgen;

namespace {

constexpr double pi_ = std::numbers::pi;

std::string rs274() {
    auto p = oracle::find_rs274();
    if (!p) FAIL("rs274 (LinuxCNC's standalone interpreter) was not found: install linuxcnc-uspace");
    return *p;
}

// A point in the lathe's plane: z along the spindle, x a radius.
struct P {
    double z = 0, x = 0;
};
P operator+(P a, P b) { return {a.z + b.z, a.x + b.x}; }
P operator-(P a, P b) { return {a.z - b.z, a.x - b.x}; }
P operator*(P a, double k) { return {a.z * k, a.x * k}; }
double len(P a) { return std::hypot(a.z, a.x); }
double crossp(P a, P b) { return a.z * b.x - a.x * b.z; }
double dotp(P a, P b) { return a.z * b.z + a.x * b.x; }

// A move of the tip (or of the centre): a line, or an arc turning ccw (> 0) or cw (< 0) in
// (z, x) about `centre`.
struct Seg {
    P from, to;
    bool arc = false;
    P centre;
    int rotation = 0;
};

// The signed sweep of an arc from `from` to `to`, ccw positive (a full turn when they meet).
double sweep_of(const Seg& s) {
    double a = std::atan2(s.from.x - s.centre.x, s.from.z - s.centre.z);
    double b = std::atan2(s.to.x - s.centre.x, s.to.z - s.centre.z);
    double d = b - a;
    if (s.rotation > 0) {
        while (d <= 1e-12) d += 2 * pi_;
    } else {
        while (d >= -1e-12) d -= 2 * pi_;
    }
    return d;
}

P point_at(const Seg& s, double t) {
    if (!s.arc) return s.from + (s.to - s.from) * t;
    const double r = len(s.from - s.centre);
    const double a = std::atan2(s.from.x - s.centre.x, s.from.z - s.centre.z) + sweep_of(s) * t;
    return s.centre + P{std::cos(a), std::sin(a)} * r;
}

double seg_length(const Seg& s) { return s.arc ? len(s.from - s.centre) * std::abs(sweep_of(s)) : len(s.to - s.from); }

// The distance from q to a segment, exactly (a line's nearest point; an arc's, where the ray
// from its centre through q crosses it, else its nearer end).
double distance_to(P q, const Seg& s) {
    if (!s.arc) {
        const P d = s.to - s.from;
        const double l2 = dotp(d, d);
        const double t = l2 > 0 ? std::clamp(dotp(q - s.from, d) / l2, 0.0, 1.0) : 0.0;
        return len(q - (s.from + d * t));
    }
    const double r = len(s.from - s.centre);
    const double sweep = sweep_of(s);
    const double a0 = std::atan2(s.from.x - s.centre.x, s.from.z - s.centre.z);
    double a = std::atan2(q.x - s.centre.x, q.z - s.centre.z) - a0;
    if (sweep > 0) {
        while (a < 0) a += 2 * pi_;
        while (a >= 2 * pi_) a -= 2 * pi_;
        if (a <= sweep) return std::abs(len(q - s.centre) - r);
    } else {
        while (a > 0) a -= 2 * pi_;
        while (a <= -2 * pi_) a += 2 * pi_;
        if (a >= sweep) return std::abs(len(q - s.centre) - r);
    }
    return std::min(len(q - s.from), len(q - s.to));
}

double distance_to(P q, const std::vector<Seg>& path) {
    double d = 1e18;
    for (const Seg& s : path) d = std::min(d, distance_to(q, s));
    return d;
}

// The unit tangent of a segment at its start (t = 0) or end (t = 1).
P tangent(const Seg& s, bool at_end) {
    if (!s.arc) return (s.to - s.from) * (1.0 / len(s.to - s.from));
    const P p = at_end ? s.to : s.from;
    const P rr = (p - s.centre) * (1.0 / len(p - s.centre));
    return s.rotation > 0 ? P{-rr.x, rr.z} : P{rr.x, -rr.z};
}

// LinuxCNC's tip from the nose centre (interp_queue.cc latheorigin_x/z), written here again.
P tip_from_centre(int q, double r) {
    P d;
    if (q == 1 || q == 2 || q == 6) d.x = -r;
    if (q == 3 || q == 4 || q == 8) d.x = r;
    if (q == 2 || q == 3 || q == 7) d.z = -r;
    if (q == 1 || q == 4 || q == 5) d.z = r;
    return d;
}

// A random profile travelled towards -Z from Z0: Z never grows, the radius stays within
// [lo, hi]; lines along Z, tapers, 45 degree chamfers, shoulders up and down, arcs of at most
// 90 degrees of a radius at least `min_arc`; every element at least `min_len` long.
std::vector<Seg> random_profile(std::mt19937& rng, double lo, double hi, double min_len, double min_arc) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Seg> out;
    P at{0.0, lo + (hi - lo) * u(rng)};
    const int n = 3 + static_cast<int>(u(rng) * 5);
    int last_kind = -1;
    for (int k = 0; k < n; ++k) {
        int kind = static_cast<int>(u(rng) * 6);
        // No shoulder after a shoulder (up then down would run back over itself).
        if ((kind == 3 || kind == 4) && (last_kind == 3 || last_kind == 4)) kind = 0;
        last_kind = kind;
        Seg s;
        s.from = at;
        switch (kind) {
            case 0: s.to = at + P{-(min_len + 5 * u(rng)), 0.0}; break;  // along Z
            case 1: {  // taper
                const double dz = min_len + 4 * u(rng);
                double dx = (u(rng) - 0.5) * dz;
                dx = std::clamp(at.x + dx, lo, hi) - at.x;
                s.to = at + P{-dz, dx};
                break;
            }
            case 2: {  // chamfer up or down, 45 degrees
                const double c = min_len + u(rng);
                const double dx = (at.x + c <= hi) ? c : -c;
                s.to = at + P{-c, dx};
                break;
            }
            case 3:  // shoulder up
            case 4: {  // shoulder down
                double dx = (min_len + 3 * u(rng)) * (kind == 3 ? 1 : -1);
                if (at.x + dx > hi || at.x + dx < lo) dx = -dx;
                if (at.x + dx > hi || at.x + dx < lo) dx = 0;
                s.to = at + P{dx == 0 ? -min_len : 0.0, dx};
                break;
            }
            default: {  // an arc of up to 90 degrees, bulging either way
                const double r = min_arc + 4 * u(rng);
                const double sweep = (0.3 + 0.7 * u(rng)) * pi_ / 2;
                // Chord direction towards -Z, tilted by at most what keeps Z falling along the arc.
                const double tilt = (u(rng) - 0.5) * (pi_ / 2 - sweep);
                const double chord = 2 * r * std::sin(sweep / 2);
                const P dir{-std::cos(tilt), std::sin(tilt)};
                P end = at + dir * chord;
                if (end.x > hi || end.x < lo) {
                    end = at + P{dir.z, -dir.x} * chord;
                    if (end.x > hi || end.x < lo) end = at + P{-chord, 0.0};
                }
                const P d = end - at;
                const P mid = at + d * 0.5;
                const double h = std::sqrt(std::max(0.0, r * r - dotp(d, d) / 4));
                const P nrm = P{-d.x, d.z} * (1.0 / len(d));  // left of the chord
                const bool left = u(rng) < 0.5;
                s.to = end;
                s.arc = true;
                s.centre = mid + nrm * (left ? h : -h);
                // The short way round: ccw when the centre lies left of the chord.
                s.rotation = left ? 1 : -1;
                break;
            }
        }
        at = s.to;
        out.push_back(s);
    }
    return out;
}

std::string num(double v) {
    std::string s = fmt::format("{:.6f}", v);
    if (s == "-0.000000") s = "0.000000";
    return s;
}

// The program: G7 (X a diameter), the tool from the clearance to 3 mm before the start, G41/G42
// on the feed to the start, the profile, G40 on a feed out by `lift` along +X, rapid away.
std::string program_of(const std::vector<Seg>& profile, bool left, double lift) {
    std::ostringstream o;
    const P start = profile.front().from;
    o << "G18 G7 G40 G80 G90 G94 G21\n";
    o << "T1 M6\n";
    o << "G0 G43 Z20 H1\n";
    o << "G0 X" << num(2 * (start.x + (left ? -lift : lift))) << "\n";
    o << "G0 Z3\n";
    o << "G0 X" << num(2 * start.x) << "\n";
    o << (left ? "G41" : "G42") << " G1 Z" << num(start.z) << " F100\n";
    for (const Seg& s : profile) {
        if (!s.arc) {
            o << "G1 X" << num(2 * s.to.x) << " Z" << num(s.to.z) << "\n";
        } else {
            o << (s.rotation > 0 ? "G3" : "G2") << " X" << num(2 * s.to.x) << " Z" << num(s.to.z) << " I"
              << num(s.centre.x - s.from.x) << " K" << num(s.centre.z - s.from.z) << "\n";
        }
    }
    const P end = profile.back().to;
    o << "G40 G1 X" << num(2 * (end.x + (left ? -lift : lift))) << "\n";
    o << "G0 Z20\n";
    o << "M2\n";
    return o.str();
}

// rs274's moves in XZ after its tool change, and which of them it made under compensation.
struct Run {
    std::vector<Seg> moves;
    std::vector<bool> compensated;
};

std::vector<double> args_of(const std::string& line) {
    std::vector<double> v;
    const auto open = line.find('('), close = line.rfind(')');
    std::istringstream in(line.substr(open + 1, close - open - 1));
    for (std::string part; std::getline(in, part, ',');) {
        char* end = nullptr;
        const double d = std::strtod(part.c_str(), &end);
        if (end != part.c_str()) v.push_back(d);
    }
    return v;
}

Run parse_xz(const std::string& canon) {
    Run run;
    P at{0, 0};
    bool on = false, started = false, first = false;
    std::istringstream in(canon);
    for (std::string line; std::getline(in, line);) {
        if (line.find("CHANGE_TOOL(") != std::string::npos) started = first = true;
        if (line.find("cutter radius compensation on") != std::string::npos) on = true;
        if (line.find("cutter radius compensation off") != std::string::npos) on = false;
        Seg s;
        if (line.find("STRAIGHT_FEED(") != std::string::npos || line.find("STRAIGHT_TRAVERSE(") != std::string::npos) {
            const auto a = args_of(line);
            s.to = {a.at(2), a.at(0)};
        } else if (line.find("ARC_FEED(") != std::string::npos) {
            // G18: first axis Z, second X.
            const auto a = args_of(line);
            s.to = {a.at(0), a.at(1)};
            s.centre = {a.at(2), a.at(3)};
            s.rotation = static_cast<int>(a.at(4));
            s.arc = true;
        } else {
            continue;
        }
        s.from = at;
        at = s.to;
        if (!started || (!s.arc && len(s.to - s.from) < 1e-9)) continue;
        // The first move after the tool change: camgen's read-back knows not where it starts.
        if (first) {
            first = false;
            continue;
        }
        run.moves.push_back(s);
        run.compensated.push_back(on);
    }
    return run;
}

// camgen's read-back of the program: the trace's moves after the tool change, in (z, x).
std::vector<Seg> camgen_moves(const Trace& t) {
    std::vector<Seg> out;
    bool started = false;
    for (const Step& s : t.steps) {
        if (s.kind == StepKind::tool_change) started = true;
        if (!started || (s.kind != StepKind::rapid && s.kind != StepKind::feed) || !s.from_known) continue;
        Seg g;
        g.from = {s.from.z, s.from.x};
        g.to = {s.to.z, s.to.x};
        if (s.arc) {
            g.arc = true;
            g.centre = {s.arc->centre.z, s.arc->centre.x};
            g.rotation = s.arc->direction == ArcDirection::ccw ? 1 : -1;
        } else if (len(g.to - g.from) < 1e-9) {
            continue;
        }
        out.push_back(g);
    }
    return out;
}

std::string describe(const Seg& s) {
    if (!s.arc) return fmt::format("line to Z{:.4f} r{:.4f}", s.to.z, s.to.x);
    return fmt::format("arc {} to Z{:.4f} r{:.4f} about Z{:.4f} r{:.4f}", s.rotation > 0 ? "ccw" : "cw", s.to.z, s.to.x,
                       s.centre.z, s.centre.x);
}

// Both lists move alike: the same kinds, ends (and centres) within `tol` mm.
bool same_moves(std::vector<Seg> a, const std::vector<Seg>& b, double tol, std::string& why) {
    // rs274 knows where it starts (its origin), camgen only once X and Z have both been given:
    // the rapids before that (G43 Z20, then X) are rs274's alone.
    for (int k = 0; k < 2 && a.size() > b.size() && !a.front().arc; ++k) a.erase(a.begin());
    if (a.size() != b.size()) {
        why = fmt::format("{} moves in rs274, {} in camgen\nrs274:", a.size(), b.size());
        for (const Seg& s : a) why += "\n  " + describe(s);
        why += "\ncamgen:";
        for (const Seg& s : b) why += "\n  " + describe(s);
        return false;
    }
    for (std::size_t i = 0; i < a.size(); ++i) {
        const bool ok = a[i].arc == b[i].arc && len(a[i].to - b[i].to) <= tol &&
                        (!a[i].arc || (len(a[i].centre - b[i].centre) <= tol && a[i].rotation == b[i].rotation));
        if (!ok) {
            why = fmt::format("move {}: rs274 {}, camgen {}", i, describe(a[i]), describe(b[i]));
            return false;
        }
    }
    return true;
}

struct Envelope {
    double worst_gouge = 0;  // how far the nose crosses the profile (> 0: into it), mm
    double worst_gap = 0;    // how far the nose stays off a point it must touch, mm
};

// The nose of radius r whose centre runs `centre` against the designed `profile` (the tool on
// the left of travel for G41): every profile point at least r from the centre path, and within
// r of it except near a sharp concave corner (where the nose cannot reach), the entry's corner
// with the first element counted as one.
Envelope envelope(const std::vector<Seg>& profile, const std::vector<Seg>& centre, double r, bool left) {
    Envelope e;
    // The concave corners and how far along each side the nose leaves the profile.
    std::vector<std::pair<P, double>> corners;
    P before{-1, 0};  // the entry runs along -Z
    for (std::size_t k = 0; k < profile.size(); ++k) {
        const P din = k == 0 ? before : tangent(profile[k - 1], true), dout = tangent(profile[k], false);
        const double c = crossp(din, dout);
        const bool concave = left ? c > 1e-9 : c < -1e-9;
        if (concave) {
            const double turn = std::acos(std::clamp(dotp(din, dout), -1.0, 1.0));
            // Beside an arc the nose leaves the profile a little further than beside a line.
            const bool arc = profile[k].arc || (k > 0 && profile[k - 1].arc);
            corners.push_back({profile[k].from, r * std::tan(turn / 2) + (arc ? 0.5 * r : 0.02)});
        }
    }
    for (const Seg& s : profile) {
        const double l = seg_length(s);
        const int n = std::max(2, static_cast<int>(l / 0.01));
        for (int i = 0; i <= n; ++i) {
            const P q = point_at(s, double(i) / n);
            const double d = distance_to(q, centre);
            e.worst_gouge = std::max(e.worst_gouge, r - d);
            bool near_corner = false;
            for (const auto& [p, reach] : corners) near_corner = near_corner || len(q - p) < reach;
            if (!near_corner) e.worst_gap = std::max(e.worst_gap, d - r);
        }
    }
    // And the other way: every centre point at least r from the profile.
    for (const Seg& s : centre) {
        const int n = std::max(2, static_cast<int>(seg_length(s) / 0.01));
        for (int i = 0; i <= n; ++i) e.worst_gouge = std::max(e.worst_gouge, r - distance_to(point_at(s, double(i) / n), profile));
    }
    return e;
}

Machine lathe_machine() { return load_machine("linuxcnc-lathe"); }

}  // namespace

TEST_CASE("control nose compensation: camgen reads G41/G42 in G18 as rs274 runs them, and the nose envelopes the profile") {
    const std::string interp = rs274();
    const Machine machine = lathe_machine();
    std::mt19937 rng(20261203);
    const double radii[] = {0.4, 0.8, 1.2};
    const int outside_q[] = {2, 3, 1, 6, 8};
    const int inside_q[] = {3, 2, 4, 8, 7};
    int accepted = 0, refused_both = 0, cases = 0;
    std::set<int> orientations_seen_out, orientations_seen_in;
    for (int c = 0; c < 120; ++c) {
        const bool left = c % 2 == 1;  // G41: inside (a bore), G42: outside
        const double r = radii[c % 3];
        const int q = left ? inside_q[(c / 2) % 5] : outside_q[(c / 2) % 5];
        const std::vector<Seg> profile = random_profile(rng, left ? 8.0 : 5.0, left ? 16.0 : 15.0, 2.5 * r + 0.5, 3 * r + 1);
        const std::string program = program_of(profile, left, 2.0);
        CAPTURE(program);
        CAPTURE(q);
        CAPTURE(r);
        ++cases;
        std::string canon;
        bool rs_refused = false;
        try {
            canon = oracle::run_rs274_canon(interp, program, {{1, 2 * r}}, {{1, q}});
        } catch (const std::runtime_error&) {
            rs_refused = true;
        }
        std::optional<Trace> ours;
        try {
            TraceOptions o;
            o.compensation_radii = {{1, r}};
            o.compensation_orientations = {{1, q}};
            ours = trace_program(read_program(program, machine, "comp.ngc"), machine, o);
        } catch (const ControlRefusal&) {
        }
        REQUIRE_MESSAGE(rs_refused == !ours.has_value(), (rs_refused ? "rs274 refuses, camgen does not" : "camgen refuses, rs274 does not"));
        if (rs_refused) {
            ++refused_both;
            continue;
        }
        ++accepted;
        (left ? orientations_seen_in : orientations_seen_out).insert(q);
        const Run run = parse_xz(canon);
        std::string why;
        CHECK_MESSAGE(same_moves(run.moves, camgen_moves(*ours), 0.001, why), why);
        // The nose centre's path under compensation (the entry left out: it comes from the air).
        std::vector<Seg> centre;
        bool entry = true;
        const P off = tip_from_centre(q, r);
        for (std::size_t i = 0; i < run.moves.size(); ++i) {
            if (!run.compensated[i]) continue;
            if (entry) {
                entry = false;
                continue;
            }
            Seg s = run.moves[i];
            s.from = s.from - off;
            s.to = s.to - off;
            s.centre = s.centre - off;
            centre.push_back(s);
        }
        REQUIRE(!centre.empty());
        const Envelope e = envelope(profile, centre, r, left);
        CHECK(e.worst_gouge <= 0.002);
        CHECK(e.worst_gap <= 0.002);
    }
    MESSAGE(fmt::format("{} cases: {} run, {} refused by both", cases, accepted, refused_both));
    CHECK(accepted >= cases * 3 / 4);
    CHECK(orientations_seen_out.count(2));
    CHECK(orientations_seen_out.count(3));
    CHECK(orientations_seen_in.count(2));
    CHECK(orientations_seen_in.count(3));
}

TEST_CASE("control nose compensation: a turn-profile job posted for linuxcnc-lathe runs in rs274 as camgen traces it") {
    const std::string interp = rs274();
    const Machine machine = lathe_machine();
    const std::string paths[] = {
        R"([{"line": [28, 0]}, {"line": [30, -1]}, {"line": [30, -20]}, {"arc": {"end": [40, -25], "centre": [40, -20], "direction": "cw"}}, {"line": [40, -40]}])",
        R"([{"line": [20, -5]}, {"line": [26, -15]}, {"line": [26, -22]}, {"line": [34, -22]}, {"line": [36, -23]}, {"line": [36, -35]}])",
        R"([{"arc": {"end": [30, -4], "centre": [22, -4], "direction": "ccw"}}, {"line": [30, -12]}, {"arc": {"end": [30, -20], "centre": [18, -16], "direction": "ccw"}}, {"line": [30, -30]}])",
    };
    const std::string starts[] = {"[24, 0]", "[20, 0]", "[22, 0]"};
    for (int orientation : {2, 3}) {
        for (int k = 0; k < 3; ++k) {
            for (double nose : {0.4, 0.8}) {
                const std::string text = fmt::format(
                    R"({{"name": "comp", "units": "mm", "clearance": 20, "tools": [{{"number": 1, "type": "turning-tool",
  "noseRadius": {}, "orientation": {}, "rpm": 1000}}], "operations": [{{"type": "turn-profile", "tool": 1, "xValues": "diameter",
  "feed": 100, "start": {}, "retractX": 50, "compensation": "control", "path": {}}}]}})",
                    nose, orientation, starts[k], paths[k]);
                CAPTURE(text);
                Job job;
                try {
                    job = read_job(text, "comp.json");
                } catch (const InputError& e) {
                    // An orientation 3 tool cannot reach some outside surfaces: camgen refuses
                    // the job, as it does under computer compensation.
                    CHECK(orientation != 2);
                    MESSAGE(std::string(e.what()));
                    continue;
                }
                const std::string program = oracle::posted_program(job, machine);
                CAPTURE(program);
                CHECK(program.find("G42 G1") != std::string::npos);
                CHECK(program.find("G40 X") != std::string::npos);
                CHECK(program.find(fmt::format("Q{}", orientation)) != std::string::npos);
                const Run run = parse_xz(oracle::run_rs274_canon(interp, program, {{1, 2 * nose}}, {{1, orientation}}));
                TraceOptions o;
                o.compensation_radii = {{1, nose}};
                o.compensation_orientations = {{1, orientation}};
                const Trace read = trace_program(read_program(program, machine, "comp.ngc"), machine, o);
                std::vector<Event> events;
                struct Collect : EventSink {
                    std::vector<Event>& out;
                    explicit Collect(std::vector<Event>& o) : out(o) {}
                    void emit(const Event& e) override { out.push_back(e); }
                } collect(events);
                expand_job(job, collect);
                const Trace expected = trace_events(events, machine);
                std::string why;
                CHECK_MESSAGE(same_moves(run.moves, camgen_moves(read), 0.001, why), why);
                CHECK_MESSAGE(same_moves(run.moves, camgen_moves(expected), 0.001, why), why);
            }
        }
    }
}

}  // namespace test_lathe_comp_oracle
