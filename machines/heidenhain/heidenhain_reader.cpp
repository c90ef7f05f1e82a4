// Reading the Heidenhain TNC conversational dialect: numbered blocks
// from "0 BEGIN PGM name MM" to "END PGM name MM", "; comments", TOOL CALL n Z S.. (and
// TOOL CALL Z S.. for a new speed), M3/M4/M5, L X.. Y.. Z.. R0 FMAX (rapid) and L .. F..
// (feed; F is modal, FMAX holds for its block only), R0/RL/RR, arcs CC X Y + C X Y DR+/DR-,
// dwell cycle 9 (CYCL DEF 9.0 / 9.1), STOP, M0 and M1 (optional) with the message as the
// block's comment, and the drilling cycles 200, 203 and 207 with their Q
// parameters (continuation lines ending in "~"), each hole called by L X Y R0 FMAX M99. A
// cycle call is read back into the DrillCycle whose longhand moves camgen means by it: the
// inverse of heidenhain_cycle (README "Drilling: canned or longhand").
#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/post/longhand.hpp"
#include "machines/heidenhain/heidenhain_reader.hpp"
#include "machines/heidenhain/heidenhain_words.hpp"
#include "src/reader/nc_reader.hpp"

namespace camgen::reader {

namespace {

using heidenhain::Q;

std::vector<std::string_view> tokens_of(std::string_view s) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && is_blank(s[i])) ++i;
        size_t start = i;
        while (i < s.size() && !is_blank(s[i])) ++i;
        if (i > start) out.push_back(s.substr(start, i - start));
    }
    return out;
}

// A drilling cycle definition: its number and Q parameters, as written.
struct CycleDef {
    int number = 0;  // 200, 203, 207
    std::map<int, double> q;
    std::map<int, std::string> text;
    int line = 0;
};

// The cycle form of a cycle number, or nullptr.
const heidenhain::CycleForm* cycle_form(int number) {
    for (const heidenhain::CycleForm* f : heidenhain::cycle_forms)
        if (f->number == number) return f;
    return nullptr;
}

class HeidenhainReader : public NcReader {
public:
    using NcReader::NcReader;

protected:
    bool frame_line(std::string_view) override { return false; }
    void line(std::string_view text) override;
    void block(const Block&) override {}  // every line is read by line()
    void finish() override;
    std::vector<std::pair<std::string, std::string>> modal_state() const override;

private:
    // A word such as X+10.5 or F300, read as the machine's formats write it.
    Word word(std::string_view token) const;
    void content(std::string_view text);
    void begin_pgm(const std::vector<std::string_view>& t);
    void end_pgm(const std::vector<std::string_view>& t);
    void tool_call(const std::vector<std::string_view>& t);
    void m_block(const std::vector<std::string_view>& t);
    void cycle_def(const std::vector<std::string_view>& t, bool continued);
    void parameter_line(std::string_view text);
    void cycle_defined();
    void move(const std::vector<std::string_view>& t, bool circle);
    void circle_centre(const std::vector<std::string_view>& t);
    // The DrillCycle a call (M99) of the defined cycle means with the spindle in this state.
    DrillCycle cycle_with(SpindleState spindle, double rpm) const;

    std::string comment_;          // the comment of the block being read
    int next_block_ = 0;
    std::string program_;          // the name after BEGIN PGM
    bool begun_ = false, stopped_ = false, ended_ = false;
    std::optional<CycleDef> defining_;  // a cycle definition whose Q lines are being read
    std::optional<CycleDef> cycle_;     // the defined cycle M99 calls
    int dwell_def_line_ = 0;       // the line of CYCL DEF 9.0, until its 9.1
    std::optional<Vec2> centre_;   // CC
    CompensationSide comp_ = CompensationSide::off;
};

Word HeidenhainReader::word(std::string_view token) const {
    Word w;
    w.letter = token[0];
    w.text = std::string(token);
    std::string_view number = token.substr(1);
    auto v = parse_number(number);
    if (number.empty() || !v || !is_digit(number.back()))
        fail(fmt::format("{}: expected a letter and a number", token));
    w.value = *v == 0.0 ? 0.0 : *v;
    w.has_point = number.find(machine_.decimal_mark) != std::string_view::npos;
    return w;
}

void HeidenhainReader::line(std::string_view raw) {
    std::string_view text = trim(raw);
    if (defining_) {
        parameter_line(text);
        return;
    }
    // Every line but a cycle's parameter lines is a numbered block.
    size_t digits = 0;
    while (digits < text.size() && is_digit(text[digits])) ++digits;
    if (digits == 0 || (digits < text.size() && !is_blank(text[digits])))
        fail(fmt::format("a block without its number: \"{}\"", text));
    Word n;
    n.letter = 'N';
    n.text = std::string(text.substr(0, digits));
    n.value = std::stod(n.text);
    int number = integer_of(n);
    if (number != next_block_) fail(fmt::format("block number {} where {} comes next", number, next_block_));
    ++next_block_;
    content(trim(text.substr(digits)));
}

std::vector<std::pair<std::string, std::string>> HeidenhainReader::modal_state() const {
    std::vector<std::pair<std::string, std::string>> s = NcReader::modal_state();
    s.emplace_back("cycle definition", defining_ ? fmt::format("CYCL DEF {} (not finished)", defining_->number)
                                       : dwell_def_line_ ? std::string("CYCL DEF 9.0 (without its 9.1)")
                                       : cycle_ ? fmt::format("CYCL DEF {}", cycle_->number)
                                                : std::string("none"));
    s.emplace_back("radius compensation", comp_ == CompensationSide::off ? "R0" : comp_ == CompensationSide::left ? "RL" : "RR");
    s.emplace_back("program end", ended_ ? "END PGM read" : stopped_ ? "M30 read" : "not read");
    return s;
}

void HeidenhainReader::content(std::string_view text) {
    if (text.empty()) fail("an empty block");
    std::string_view comment;
    if (size_t semi = text.find(';'); semi != std::string_view::npos) {
        comment = trim(text.substr(semi + 1));
        text = trim(text.substr(0, semi));
        Block b;
        b.comments.emplace_back(comment);
        emit_comments(b);
    }
    if (ended_) fail("a block after END PGM");
    std::vector<std::string_view> t = tokens_of(text);
    if (t.empty()) return;  // a comment block
    comment_ = std::string(comment);
    if (!begun_ && !(t.size() >= 2 && t[0] == "BEGIN" && t[1] == "PGM")) fail("the program must begin with BEGIN PGM");
    if (stopped_ && !(t.size() >= 2 && t[0] == "END" && t[1] == "PGM")) fail("a block after the end of the program (M30)");
    if (dwell_def_line_ && !(t.size() >= 3 && t[0] == "CYCL" && t[1] == "DEF" && t[2] == "9.1"))
        fail(fmt::format("CYCL DEF 9.0 on line {} without its CYCL DEF 9.1 DWELL", dwell_def_line_));
    bool calls = std::find(t.begin(), t.end(), "M99") != t.end();
    if (!calls) drill_end();
    if (t[0] == "BEGIN") begin_pgm(t);
    else if (t[0] == "END") end_pgm(t);
    else if (t[0] == "TOOL") tool_call(t);
    else if (t[0] == "CYCL") cycle_def(t, !text.empty() && text.back() == '~');
    else if (t[0] == "L") move(t, false);
    else if (t[0] == "CC") circle_centre(t);
    else if (t[0] == "C") move(t, true);
    else if (t[0] == "STOP") {
        if (t.size() != 1) fail("STOP: camgen writes it alone, its message as the block's comment");
        stop(StopKind::mandatory, comment_);
    }
    else if (t[0][0] == 'M') m_block(t);
    else fail(fmt::format("unknown block \"{}\"", text));
}

void HeidenhainReader::finish() {
    if (defining_) fail(fmt::format("the cycle definition of line {} is not finished", defining_->line));
    if (dwell_def_line_) fail(fmt::format("CYCL DEF 9.0 on line {} without its CYCL DEF 9.1 DWELL", dwell_def_line_));
    if (!ended_) fail("the program does not end with END PGM");
    NcReader::finish();
}

void HeidenhainReader::begin_pgm(const std::vector<std::string_view>& t) {
    if (begun_) fail("a second BEGIN PGM");
    if (t.size() != 4 || t[1] != "PGM" || (t[3] != "MM" && t[3] != "INCH"))
        fail("expected BEGIN PGM <name> MM (or INCH)");
    begun_ = true;
    program_ = std::string(t[2]);
    set_units(t[3] == "INCH" ? Units::inch : Units::mm);
}

void HeidenhainReader::end_pgm(const std::vector<std::string_view>& t) {
    if (t.size() != 4 || t[1] != "PGM") fail("expected END PGM <name> MM (or INCH)");
    if (t[2] != program_) fail(fmt::format("END PGM {} ends a program named {}", t[2], program_));
    if (t[3] != (machine_.units == Units::inch ? "INCH" : "MM")) fail(fmt::format("END PGM in {}, BEGIN PGM in the other unit", t[3]));
    ended_ = true;
}

void HeidenhainReader::tool_call(const std::vector<std::string_view>& t) {
    // TOOL CALL [n] Z [S<rpm>]: with a number a tool change, without one a new speed.
    if (t.size() < 3 || t[1] != "CALL") fail("expected TOOL CALL [n] Z [S..]");
    size_t i = 2;
    std::optional<int> tool;
    if (is_digit(t[i][0])) {
        Word n;
        n.letter = 'T';
        n.text = std::string(t[i]);
        auto v = parse_number(t[i]);
        if (!v) fail(fmt::format("TOOL CALL {}: not a tool number", t[i]));
        n.value = *v;
        tool = integer_of(n);
        ++i;
    }
    if (i >= t.size() || t[i] != "Z") fail("TOOL CALL without the tool axis Z");
    ++i;
    std::optional<double> speed;
    if (i < t.size() && t[i][0] == 'S') speed = rpm(word(t[i++]));
    if (i < t.size()) fail(fmt::format("{} has no meaning in TOOL CALL", t[i]));
    if (!tool && !speed) fail("TOOL CALL Z without a tool number or a speed S");
    if (tool) {
        // The tool changes with the spindle stopped.
        if (spindle_ != SpindleState::off) emit(Spindle{SpindleState::off, 0.0});
        spindle_ = SpindleState::off;
        change_tool(*tool, commented_description(*tool));
        // The call applies the called tool's own length from the tool table (no register of its
        // own, as G43 H has; TOOL CALL's DL is not read): the offset is the tool's, compared with it.
        select_length_offset(fmt::format("TOOL CALL {}", *tool));
    }
    if (speed) spindle_speed(*speed, nullptr);
}

void HeidenhainReader::m_block(const std::vector<std::string_view>& t) {
    if (t.size() != 1) fail(fmt::format("{}: camgen writes M functions in blocks of their own (M99 after L)", t[0]));
    Word m = word(t[0]);
    switch (code_of(m)) {
        case code(3):
        case code(4):
        case code(5): switch_spindle(m, "(TOOL CALL .. S)"); break;
        case code(2):
        case code(30): stopped_ = true; break;
        case code(0): stop(StopKind::mandatory, comment_); break;
        case code(1): stop(StopKind::optional, comment_); break;
        default:
            if (const auto mode = coolant_of(m)) {
                emit(Coolant{*mode, ""});
                break;
            }
            fail(fmt::format("unknown code {}", m.text));
    }
}

void HeidenhainReader::cycle_def(const std::vector<std::string_view>& t, bool continued) {
    if (t.size() < 3 || t[1] != "DEF") fail("expected CYCL DEF <number> ...");
    if (t[2] == "9.0") {
        if (t.size() != 5 || t[3] != "DWELL" || t[4] != "TIME") fail("expected CYCL DEF 9.0 DWELL TIME");
        dwell_def_line_ = line_;
        return;
    }
    if (t[2] == "9.1") {
        if (!dwell_def_line_) fail("CYCL DEF 9.1 without CYCL DEF 9.0 before it");
        if (t.size() != 5 || t[3] != "DWELL") fail("expected CYCL DEF 9.1 DWELL <seconds>");
        Word s = word(std::string("P") + std::string(t[4]));
        s.text = std::string(t[4]);
        // Cycle 9 acts where it is defined.
        emit(Dwell{seconds(s)});
        dwell_def_line_ = 0;
        return;
    }
    const heidenhain::CycleForm* form = nullptr;
    for (const heidenhain::CycleForm* f : heidenhain::cycle_forms)
        if (t[2] == std::to_string(f->number)) form = f;
    if (!form) fail(fmt::format("camgen cannot read cycle {}", t[2]));
    std::string title;
    for (size_t i = 3; i < t.size() && t[i] != "~"; ++i) {
        if (!title.empty()) title += ' ';
        title.append(t[i]);
    }
    if (title != form->title) fail(fmt::format("CYCL DEF {} is {}, not \"{}\"", form->number, form->title, title));
    if (!continued) fail(fmt::format("CYCL DEF {} without its Q parameters (the line ends in ~ before them)", form->number));
    std::string name = fmt::format("CYCL DEF {}", form->number);
    bool known = false;
    for (const DrillingCycleSpec& s : machine_.drilling) known = known || (s.canned && s.name == name);
    if (!known) fail(fmt::format("{} is not a canned cycle of machine {}", name, machine_.name));
    defining_ = CycleDef{form->number, {}, {}, line_};
}

void HeidenhainReader::parameter_line(std::string_view text) {
    // "Q200=+2 ;SET-UP CLEARANCE ~": a value, its comment, and "~" unless it is the last one.
    bool more = !text.empty() && text.back() == '~';
    if (more) text = trim(text.substr(0, text.size() - 1));
    if (size_t semi = text.find(';'); semi != std::string_view::npos) text = trim(text.substr(0, semi));
    size_t eq = text.find('=');
    if (text.empty() || text[0] != 'Q' || eq == std::string_view::npos)
        fail(fmt::format("\"{}\": the cycle of line {} expects its Q parameters, Q<n>=<value>", text, defining_->line));
    auto n = parse_number(text.substr(1, eq - 1));
    auto v = parse_number(text.substr(eq + 1));
    if (!n || *n != std::floor(*n) || !(*n >= 0 && *n < 10000) || !v) fail(fmt::format("\"{}\" is not Q<n>=<value>", text));
    int q = static_cast<int>(*n);
    const heidenhain::CycleForm& form = *cycle_form(defining_->number);
    auto q_at = [&](size_t k) { return heidenhain::number(form.parameters[k].q); };
    size_t k = defining_->q.size();
    if (k >= form.parameters.size() || q_at(k) != q)
        fail(fmt::format("Q{} where cycle {} has {}", q, form.number,
                         k < form.parameters.size() ? fmt::format("Q{} next", q_at(k)) : std::string("no more parameters")));
    defining_->q[q] = *v == 0.0 ? 0.0 : *v;
    defining_->text[q] = std::string(text);
    if (!more) {
        if (defining_->q.size() != form.parameters.size())
            fail(fmt::format("cycle {} ends after Q{}: Q{} is missing", form.number, q, q_at(defining_->q.size())));
        cycle_defined();
    }
}

void HeidenhainReader::cycle_defined() {
    cycle_ = std::move(defining_);
    defining_.reset();
    // Every parameter is checked where it is written (the spindle matters only when called).
    (void)cycle_with(SpindleState::cw, 1.0);
}

DrillCycle HeidenhainReader::cycle_with(SpindleState spindle, double rpm) const {
    const CycleDef& d = *cycle_;
    auto q = [&](Q n) { return d.q.at(heidenhain::number(n)); };  // as written
    // In internal units through the machine's formats (an INCH program writes inches).
    auto len = [&](Q n) { return length_value(q(n)); };
    auto sec = [&](Q n) { return seconds_value(q(n)); };
    auto bad = [&](Q n, const std::string& why) -> void {
        fail(fmt::format("cycle {}: {}: {}", d.number, d.text.at(heidenhain::number(n)), why));
    };
    const double unit = resolution().position;
    // Q200, Q201 and Q204 count from the surface Q203 (camgen writes the feed-start plane as
    // the surface when it lies below the reference plane).
    DrillCycle c;
    c.reference_z = len(Q::surface);
    if (q(Q::setup_clearance) < 0) bad(Q::setup_clearance, "the set-up clearance must not be negative");
    if (!(q(Q::depth) < 0)) bad(Q::depth, "the depth must be negative (below the surface)");
    if (q(Q::second_setup_clearance) < q(Q::setup_clearance))
        bad(Q::second_setup_clearance, "the 2nd set-up clearance is below the set-up clearance");
    c.safe_z = len(Q::surface) + len(Q::setup_clearance);
    c.bottom_z = len(Q::surface) + len(Q::depth);
    c.retract_z = len(Q::surface) + len(Q::second_setup_clearance);
    c.spindle_rpm = rpm;
    c.spindle_direction = spindle == SpindleState::ccw ? SpindleDirection::ccw : SpindleDirection::cw;
    c.output = CycleOutput::canned;
    DrillValues& p = c.values;
    auto dwell = [&](Q n) -> std::optional<double> {
        if (q(n) < 0) bad(n, "a dwell must not be negative");
        return q(n) > 0 ? std::optional<double>(sec(n)) : std::nullopt;
    };

    if (d.number == heidenhain::rigid_tapping.number) {
        // Rigid tapping: the pitch's sign gives the hand; feed = pitch x the spindle speed.
        if (q(Q::pitch) == 0) bad(Q::pitch, "the pitch must not be 0");
        c.kind = q(Q::pitch) < 0 ? CycleKind::tap_left : CycleKind::tap;
        p.set(DrillField::pitch, std::abs(len(Q::pitch)));
        if (spindle == SpindleState::off || !(rpm > 0)) fail("cycle 207 called with the spindle off");
        c.feed = *p.get(DrillField::pitch) * rpm;
    } else {
        if (!(q(Q::plunge_feed) > 0)) bad(Q::plunge_feed, "the plunging feed must be > 0");
        c.feed = feed_value(q(Q::plunge_feed));
        p.set(DrillField::plunging_feedrate, c.feed);
        if (!(q(Q::plunging_depth) > 0)) bad(Q::plunging_depth, "the plunging depth must be > 0");
        p.set(DrillField::bottom_dwell, dwell(Q::bottom_dwell));
        if (q(Q::top_dwell) < 0) bad(Q::top_dwell, "a dwell must not be negative");
        if (d.number == heidenhain::drilling.number) {
            // One plunge: camgen writes the whole depth. The TNC dwells at the top (Q210) only
            // between plunges, so one plunge has no such dwell.
            if (len(Q::plunging_depth) < -len(Q::depth) - unit)
                bad(Q::plunging_depth, "a plunging depth less than the depth pecks: camgen writes pecking as cycle 203");
            c.kind = p.get(DrillField::bottom_dwell) ? CycleKind::dwell : CycleKind::drill;
        } else {
            // Cycle 203. Q213 = 0: full retracts (camgen's "deep"); Q213 > 0: chip breaking
            // (camgen writes 99 and never more breaks). The pecks are read as camgen means them,
            // measured from the set-up clearance, re-approaching the machine's peckClearance
            // above the last peck after a full retract, the top dwell before every peck that
            // starts from the set-up clearance, and the retraction feed Q208 on the way out of
            // the finished hole only. A real TNC measures plunges from the surface and picks
            // its own advance stop distance (README "Drilling: canned or longhand").
            const double breaks = q(Q::breaks);
            if (breaks < 0 || breaks > heidenhain::max_breaks || breaks != std::floor(breaks))
                bad(Q::breaks, fmt::format("the number of chip breaks is a whole number 0..{}", heidenhain::max_breaks));
            c.kind = breaks == 0 ? CycleKind::deep : CycleKind::chip_break;
            p.set(DrillField::first_depth, len(Q::plunging_depth));
            if (q(Q::decrement) < 0) bad(Q::decrement, "the decrement must not be negative");
            if (q(Q::decrement) > 0) {
                p.set_degression_type(DegressionType::value);
                p.set(DrillField::degression, len(Q::decrement));
            }
            if (q(Q::min_plunging_depth) < 0)
                bad(Q::min_plunging_depth, "the minimum plunging depth must not be negative");
            if (q(Q::min_plunging_depth) > 0) p.set(DrillField::minimum_depth, len(Q::min_plunging_depth));
            // Q210 acts after full retracts only: with chip breaking camgen makes none.
            if (c.kind == CycleKind::deep) p.set(DrillField::top_dwell, dwell(Q::top_dwell));
            if (!(q(Q::retraction_feed) > 0)) bad(Q::retraction_feed, "the retraction feed must be > 0");
            // 99999 as written (whatever the units) is FMAX.
            if (q(Q::retraction_feed) != heidenhain::fmax_feed)
                p.set(DrillField::retract_feedrate, feed_value(q(Q::retraction_feed)));
            // Q256 is the back-off of a chip break; full retracts do not use it.
            if (c.kind == CycleKind::chip_break) {
                if (!(q(Q::chip_break_distance) > 0))
                    bad(Q::chip_break_distance, "the chip-breaking distance must be > 0");
                p.set(DrillField::pecking_retract, len(Q::chip_break_distance));
            }
            if (c.kind == CycleKind::chip_break) {
                size_t pecks = 0;
                try {
                    pecks = peck_depths(c).size();
                } catch (const InputError& e) {
                    fail(fmt::format("cycle 203: pecks that cannot reach the bottom of the hole: {}", e.detail()));
                }
                if (pecks > breaks + 1)
                    bad(Q::breaks, fmt::format("{} pecks make more chip breaks than that: the TNC would retract fully "
                                         "after {}", pecks, breaks));
            }
        }
    }
    std::string name = fmt::format("CYCL DEF {}", d.number);
    bool offered = false;
    for (const DrillingCycleSpec& s : machine_.drilling) offered = offered || (s.canned && s.name == name && s.kind == c.kind);
    if (!offered)
        fail(fmt::format("{} as a {} cycle is not a canned cycle of machine {}", name, name_of(cycle_kinds, c.kind), machine_.name));
    return c;
}

void HeidenhainReader::circle_centre(const std::vector<std::string_view>& t) {
    std::optional<double> x, y;
    for (size_t i = 1; i < t.size(); ++i) {
        Word w = word(t[i]);
        std::optional<double>& slot = w.letter == 'X' ? x : w.letter == 'Y' ? y : x;
        if (w.letter != 'X' && w.letter != 'Y') fail(fmt::format("{} has no meaning in CC", w.text));
        if (slot) fail(fmt::format("two {} words in one block", w.letter));
        slot = length(w);
    }
    if (!x || !y) fail("CC needs both X and Y (the circle centre)");
    centre_ = Vec2{*x, *y};
}

void HeidenhainReader::move(const std::vector<std::string_view>& t, bool circle) {
    std::optional<double> x, y, z, f;
    std::optional<CompensationSide> comp;
    std::optional<ArcDirection> dir;
    bool fmax = false, call = false;
    for (size_t i = 1; i < t.size(); ++i) {
        std::string_view k = t[i];
        if (k == "FMAX") {
            if (fmax || f) fail("two feeds in one block");
            fmax = true;
        } else if (k == "R0" || k == "RL" || k == "RR") {
            if (comp) fail("two radius compensations in one block");
            if (circle) fail(fmt::format("{} on C: camgen compensates on L blocks", k));
            comp = k == "R0" ? CompensationSide::off : k == "RL" ? CompensationSide::left : CompensationSide::right;
        } else if (k == "DR+" || k == "DR-") {
            if (!circle) fail(fmt::format("{} on an L block", k));
            if (dir) fail("two directions in one block");
            dir = k == "DR+" ? ArcDirection::ccw : ArcDirection::cw;
        } else if (k == "M99") {
            if (circle) fail("M99 on C: camgen calls cycles from L blocks");
            call = true;
        } else {
            Word w = word(k);
            std::optional<double>* slot = w.letter == 'X' ? &x : w.letter == 'Y' ? &y : w.letter == 'Z' ? &z : w.letter == 'F' ? &f : nullptr;
            if (!slot) fail(fmt::format("unknown word {}", w.text));
            if (*slot || (w.letter == 'F' && fmax)) fail(fmt::format("two {} words in one block", w.letter));
            *slot = w.letter == 'F' ? feed(w) : length(w);
        }
    }
    if (comp && *comp != comp_) {
        comp_ = *comp;
        emit(Compensation{comp_});
    }
    if (f) feed_ = *f;
    if (circle) {
        if (!dir) fail("C without its direction DR+ or DR-");
        if (fmax) fail("C with FMAX: an arc is a feed move");
        if (!centre_) fail("C without a circle centre CC before it");
        if (!x && !y && !z) fail("C without its end point");
        ArcWords a;
        a.direction = *dir;
        a.plane = Plane::xy;
        a.x = x, a.y = y, a.z = z;
        a.i = centre_->x, a.j = centre_->y;
        a.absolute_centre = true;
        arc(a);
        return;
    }
    if (call) {
        // The cycle defined last drills at the end of this positioning block.
        if (!cycle_) fail("M99 without a drilling cycle defined (CYCL DEF 200, 203 or 207)");
        if (!fmax) fail("M99 on a feed move: camgen positions holes with R0 FMAX");
        if (z) fail("Z on a cycle call: camgen positions the hole in X and Y at the retract plane");
        if (!position_known()) fail("a cycle call from an unknown position");
        rapid_to(x, y, std::nullopt);
        DrillCycle c = cycle_with(spindle_, rpm_);
        if (!current_cycle() || !(*current_cycle() == c)) drill_cycle(c);
        Vec3 here = position();
        drill_point({here.x, here.y});
        return;
    }
    if (!x && !y && !z) fail("L without a coordinate");
    if (fmax) rapid_to(x, y, z);
    else linear_to(x, y, z);
}

}  // namespace

std::unique_ptr<NcReader> make_heidenhain_reader(const Machine& machine, std::string source) {
    return std::make_unique<HeidenhainReader>(machine, std::move(source));
}

}  // namespace camgen::reader
