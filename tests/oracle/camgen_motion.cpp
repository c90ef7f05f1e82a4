#include "camgen_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <doctest/doctest.h>

#include "camgen/analysis/trace.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"

namespace camgen::oracle {

std::string posted_program(const Job& job, const Machine& machine) {
    std::ostringstream out;
    PostOptions o;
    o.program_name = job.name;
    auto post = make_post(machine, out, o);
    post->open();
    expand_job(job, *post);
    post->close();
    return out.str();
}

namespace {

std::vector<Step> normalised(const Trace& trace);

}  // namespace

std::vector<Step> read_with_camgen(const std::string& program, const Machine& machine) {
    return normalised(trace_program(read_program(program, machine, "oracle.ngc"), machine));
}

CompensatedRead read_with_camgen(const std::string& program, const Machine& machine, const std::map<int, double>& radii) {
    CompensatedRead out;
    try {
        TraceCollector collect;
        TraceBuilder trace(machine, collect, TraceOptions{radii});
        read_program(program, machine, "oracle.ngc", trace);
        out.steps = normalised(collect.take());
    } catch (const ControlRefusal& e) {
        out.refused_line = e.line();
        const std::string prefix = "the control refuses this: ";
        out.refusal = e.detail().rfind(prefix, 0) == 0 ? e.detail().substr(prefix.size()) : e.detail();
    }
    return out;
}

namespace {

std::vector<Step> normalised(const Trace& trace) {
    std::vector<Step> steps;
    Vec3 at{0, 0, 0};  // rs274 starts at the origin
    std::string spindle = "off";
    for (const camgen::Step& s : trace.steps) {
        switch (s.kind) {
            case StepKind::rapid:
            case StepKind::feed: {
                if (s.to == at && !s.arc) break;  // a full circle ends where it starts
                Step o;
                o.kind = s.kind == StepKind::rapid ? Step::Kind::traverse
                         : s.arc                  ? Step::Kind::arc
                                                  : Step::Kind::feed;
                o.to = s.to;
                if (s.kind == StepKind::feed) o.value = s.feed;
                if (s.arc) {
                    // rs274's rotation: the turns begun, negative clockwise.
                    o.centre = {s.arc->centre.x, s.arc->centre.y};
                    const int turns = std::max(1, static_cast<int>(std::ceil(s.arc->sweep / (2 * std::numbers::pi) - 1e-9)));
                    o.rotation = s.arc->direction == ArcDirection::ccw ? turns : -turns;
                }
                steps.push_back(o);
                at = s.to;
                break;
            }
            case StepKind::dwell:
                if (s.seconds > 0) {
                    Step o;
                    o.kind = Step::Kind::dwell;
                    o.value = s.seconds;
                    steps.push_back(o);
                }
                break;
            case StepKind::spindle: {
                std::string state = s.spindle == SpindleState::cw ? "cw" : s.spindle == SpindleState::ccw ? "ccw" : "off";
                if (state == spindle) break;
                spindle = state;
                Step o;
                o.kind = Step::Kind::spindle;
                o.spindle = state;
                o.value = s.spindle == SpindleState::off ? 0.0 : s.rpm;
                steps.push_back(o);
                break;
            }
            case StepKind::tool_change: break;
            case StepKind::stop: break;  // no motion (tests/oracle/test_stop_oracle.cpp compares the stops)
        }
    }
    return steps;
}

}  // namespace

void check_read_as_run(const std::vector<Step>& theirs, const std::string& program, const Machine& machine, double tolerance) {
    auto from_first_feed = [](const std::vector<Step>& steps) {
        auto it = std::find_if(steps.begin(), steps.end(),
                               [](const Step& s) { return s.kind == Step::Kind::feed || s.kind == Step::Kind::arc; });
        return std::vector<Step>(it, steps.end());
    };
    const std::vector<Step> ours = from_first_feed(read_with_camgen(program, machine));
    const std::vector<Step> theirs_fed = from_first_feed(theirs);
    REQUIRE(theirs_fed.size() == ours.size());
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const Step& a = theirs_fed[i];
        INFO("step " << i << ": rs274 " << describe(a) << ", camgen " << describe(ours[i]));
        CHECK(a.kind == ours[i].kind);
        CHECK(std::abs(a.to.x - ours[i].to.x) <= tolerance);
        CHECK(std::abs(a.to.y - ours[i].to.y) <= tolerance);
        CHECK(std::abs(a.to.z - ours[i].to.z) <= tolerance);
        CHECK(a.rotation == ours[i].rotation);
    }
}

std::vector<XzMove> camgen_xz_moves(const std::string& program, const Machine& machine) {
    std::vector<XzMove> out;
    for (const Step& s : read_with_camgen(program, machine)) {
        if (s.kind != Step::Kind::traverse && s.kind != Step::Kind::feed && s.kind != Step::Kind::arc) continue;
        out.push_back({.rapid = s.kind == Step::Kind::traverse, .arc = s.kind == Step::Kind::arc, .x = s.to.x, .z = s.to.z});
    }
    return out;
}

}  // namespace camgen::oracle
