// The nccad dialect (MAX computer nccad: Wabeco, KOSY). REFERENCE.md §5.
#include "machines/nccad/nccad_post.hpp"

#include <cmath>

#include <fmt/format.h>

#include "camgen/common/json_util.hpp"

namespace camgen {

NccadPost::NccadPost(const Machine& machine, std::ostream& out, PostOptions options)
    : Post(machine, out, std::move(options)) {
    json::Source source{machine.source, json::LineMap{}};
    json::Fields f(machine.dialect_settings, "/settings", source);
    underscore_lines_ = f.optional_integer("underscoreLines").value_or(2);
    reference_run_ = f.boolean("referenceRun", false);
    home_at_end_ = f.boolean("homeAtEnd", true);
    end_of_program_ = f.boolean("endOfProgram", true);
    f.finish();
}

void NccadPost::on_open() {
    for (int i = 0; i < underscore_lines_; ++i) out_.raw("_");
    if (!options_.program_name.empty()) out_.comment(options_.program_name);
    out_.add(g(90)).end();
    if (reference_run_) out_.add(g(76)).end();
}

void NccadPost::on_close() {
    if (spindle_on_) out_.add(m(10)).add("O6.0").end();
    if (home_at_end_) out_.add(g(77)).end();
    if (end_of_program_) out_.add(g(99)).end();
}

void NccadPost::on_tool_change(const ToolChange& tool) {
    // nccad cannot change tools or set a speed: stop and show the operator what to do.
    pending_tool_ = tool;
}

void NccadPost::on_spindle(const Spindle& s) {
    if (s.state == SpindleState::ccw)
        fail("", fmt::format("machine {} cannot run the spindle counter-clockwise (tool {})", machine_.name, tool_));
    if (s.state == SpindleState::off) {
        if (pending_tool_) flush_tool_message(std::nullopt);
        out_.add(m(10)).add("O6.0").end();
        spindle_on_ = false;
        return;
    }
    if (pending_tool_) {
        flush_tool_message(s.rpm);
    } else if (s.rpm != speed_) {
        out_.add(m(1)).add(out_.clean_comment(fmt::format("Set spindle speed to {} rpm", rpm_fmt_.format(s.rpm)))).end();
    }
    speed_ = s.rpm;
    out_.add(m(10)).add("O6.1").end();
    spindle_on_ = true;
}

void NccadPost::flush_tool_message(std::optional<double> rpm) {
    const ToolChange& t = *pending_tool_;
    std::string msg = fmt::format("Insert tool {}", t.number);
    if (!t.description.empty()) msg += " " + t.description;
    if (rpm) msg += fmt::format(", spindle {} rpm", rpm_fmt_.format(*rpm));
    // ';' starts a comment in nccad: it must not appear in the message.
    for (char& c : msg)
        if (c == ';') c = ',';
    out_.add(m(1)).add(out_.clean_comment(msg)).end();
    pending_tool_.reset();
}

void NccadPost::on_dwell(double seconds) {
    // M30 P<n>: n in 1/18 s, rounded up so the dwell is never shorter than asked.
    long n = static_cast<long>(std::ceil(seconds * 18.0 - 1e-9));
    if (n < 1) n = 1;
    out_.add(m(30)).add(fmt::format("P{}", n)).end();
}

void NccadPost::on_compensation(const Compensation& compensation) {
    if (compensation.side != CompensationSide::off)
        fail("/compensation", fmt::format("machine {} has no cutter radius compensation", machine_.name));
}

void NccadPost::on_drilling_header(const DrillCycle&, const DrillingCycleSpec&) {}

void NccadPost::on_drilling_point(const DrillCycle& c, const DrillingCycleSpec&, Vec2 at, bool first) {
    std::string xs = x_.force(at.x), ys = y_.force(at.y);
    if (first) {
        // G81 X Y Z<bottom> B<retract plane> F: the feed runs from B to Z, then back to B.
        out_.add(g(81)).add(xs).add(ys).add(z_.force(c.bottom_z)).add(xyz_fmt_.word("B", c.retract_z))
            .add((feed_.reset(), feed_word(c.feed))).end();
    } else {
        out_.add(g(79)).add(xs).add(ys).end();
    }
}

void NccadPost::on_drilling_footer(const DrillCycle&, const DrillingCycleSpec&) {}

}  // namespace camgen
