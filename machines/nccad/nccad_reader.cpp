// Reading the nccad dialect (MAX computer nccad: Wabeco, KOSY): "_" lines,
// G90, "; comments", G00/G01, arcs as G02/G03 D<sweep> I J (the control computes the end) or
// in the classic form G02 X Y I J (both X and Y required), G81 X Y Z B F + G79 X Y drilling,
// M10 O6.1 / O6.0 spindle, M01 <message> (tool changes, spindle speeds and stops for the
// operator), M30 P<n> dwell in
// 1/18 s, G76 reference run, G77 home, G99 end of program.
#include <cmath>

#include <fmt/format.h>

#include "machines/nccad/nccad_reader.hpp"
#include "src/reader/nc_reader.hpp"

namespace camgen::reader {

namespace {

constexpr double dwell_tick = 1.0 / 18.0;  // s, the unit of M30 P

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }
bool ends_with(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

class NccadReader : public NcReader {
public:
    using NcReader::NcReader;
    ReadResolution resolution() const override {
        ReadResolution r = NcReader::resolution();
        r.dwell = dwell_tick;  // the post rounds dwells up to whole ticks
        return r;
    }

protected:
    bool frame_line(std::string_view line) override { return line == "_"; }
    bool message_code(const Word& w) const override { return w.letter == 'M' && code(w.value) == code(1); }
    bool dotted_word(char letter) const override { return letter == 'O'; }
    void block(const Block& b) override;
    std::vector<std::pair<std::string, std::string>> modal_state() const override {
        std::vector<std::pair<std::string, std::string>> s = NcReader::modal_state();
        s.emplace_back("program end", ended_ ? "read" : "not read");
        return s;
    }
    void finish() override {
        if (!ended_) fail("the program does not end with G99: it may have been cut short");
        NcReader::finish();
    }

private:
    void message(const std::string& text);
    void spindle_output(const Word& o);

    int motion_ = -1;  // modal G00..G03 (tenths); -1: none (also after a drilling block)
    bool ended_ = false;
};

void NccadReader::message(const std::string& text) {
    // camgen's wabeco post: "Insert tool <n>[ <description>][, spindle <rpm> rpm]" and
    // "Set spindle speed to <rpm> rpm". Any other message is a stop for the operator.
    auto speed = [&](std::string_view s) {
        auto v = parse_number(s);
        if (!v || *v < 0) fail(fmt::format("M01 {}: \"{}\" is not a spindle speed", text, s));
        rpm_ = *v;
    };
    std::string_view m = text;
    if (starts_with(m, "Insert tool ")) {
        m.remove_prefix(12);
        size_t end = m.find_first_not_of("0123456789");
        std::string_view number = m.substr(0, end);
        if (number.empty() || number.size() > 9) fail(fmt::format("M01 {}: no tool number after \"Insert tool\"", text));
        int tool = std::stoi(std::string(number));
        std::string_view rest = end == std::string_view::npos ? std::string_view() : m.substr(end);
        if (size_t s = rest.rfind(", spindle "); s != std::string_view::npos && ends_with(rest, " rpm")) {
            speed(rest.substr(s + 10, rest.size() - s - 10 - 4));
            rest = rest.substr(0, s);
        }
        while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
        // The post treats the position as unknown after a tool change, as the operator may jog.
        change_tool(tool, std::string(rest));
        motion_ = -1;
        return;
    }
    if (starts_with(m, "Set spindle speed to ") && ends_with(m, " rpm")) {
        speed(m.substr(21, m.size() - 21 - 4));
        return;
    }
    stop(StopKind::mandatory, text);
    motion_ = -1;
}

void NccadReader::spindle_output(const Word& o) {
    // M10 O<output>.<state>: output 6 is the spindle relay.
    if (o.text == "O6.1" || (o.has_point && std::abs(o.value - 6.1) < 1e-9)) {
        if (!(rpm_ > 0)) fail("M10 O6.1 (spindle on) before any spindle speed was given (M01 message)");
        emit(Spindle{SpindleState::cw, rpm_});
    } else if (o.text == "O6.0" || (o.has_point && o.value == 6.0)) {
        emit(Spindle{SpindleState::off, 0.0});
    } else {
        fail(fmt::format("M10 {}: only output 6 (the spindle, O6.1 on, O6.0 off) is known", o.text));
    }
}

void NccadReader::block(const Block& b) {
    if (ended_) fail("a block after the end of the program (G99)");
    const Word* g = nullptr;
    const Word* mw = nullptr;
    BlockWords w(*this, "XYZIJDFBOP");
    for (const Word& x : b.words) {
        if (x.letter == 'G' || x.letter == 'M') {
            const Word*& slot = x.letter == 'G' ? g : mw;
            if (slot) fail(fmt::format("{} and {} in one block", slot->text, x.text));
            slot = &x;
        } else {
            w.add(x);
        }
    }
    if (g && mw) fail(fmt::format("{} and {} in one block", g->text, mw->text));
    if (const Word* f = w.take('F')) feed_ = feed(*f);

    if (mw) {
        switch (code_of(*mw)) {
            case code(1): message(b.message); break;
            case code(10): {
                const Word* o = w.take('O');
                if (!o) fail("M10 without its output O");
                spindle_output(*o);
                break;
            }
            case code(30): {
                const Word* p = w.take('P');
                if (!p) fail("M30 (dwell) without its time P");
                emit(Dwell{integer_of(*p) * dwell_tick});
                break;
            }
            default: fail(fmt::format("unknown code {}", mw->text));
        }
    }

    // The motion of the block's axis words: the modal G00..G03, unless a code of the block's
    // own (G81, G79, G90, ...) has dealt with them.
    int motion = motion_;
    bool handled = false;
    if (g) {
        switch (int c = code_of(*g)) {
            case code(0): case code(1): case code(2): case code(3): motion = c; break;
            case code(90): handled = true; break;
            case code(76): case code(77):  // reference run, home: the position is the machine's
                drill_end();
                forget_position();
                motion_ = -1;
                handled = true;
                break;
            case code(99):
                drill_end();
                ended_ = true;
                handled = true;
                break;
            case code(81): {
                // G81 X Y Z<bottom> B<retract plane> F: rapid to B above the hole, feed to Z,
                // rapid back to B; further holes are G79 X Y.
                std::optional<double> x = w.length('X'), y = w.length('Y'), z = w.length('Z'), bz = w.length('B');
                if (!z || !bz) fail("G81 needs the bottom Z and the retract plane B");
                if (!(*z < *bz)) fail("G81: the bottom Z is not below the retract plane B");
                if (!feed_) fail("G81 without a feed F");
                if (!position_known()) fail("G81 from an unknown position");
                DrillCycle cycle;
                cycle.kind = CycleKind::drill;
                cycle.retract_z = cycle.reference_z = cycle.safe_z = *bz;
                cycle.bottom_z = *z;
                cycle.feed = *feed_;
                cycle.spindle_rpm = rpm_;
                cycle.output = CycleOutput::canned;
                cycle.values.set(DrillField::plunging_feedrate, *feed_);
                Vec3 here = position();
                drill_cycle(cycle);
                drill_point({x.value_or(here.x), y.value_or(here.y)});
                motion_ = -1;
                handled = true;
                break;
            }
            case code(79): {
                if (!current_cycle()) fail("G79 without a G81 before it");
                Vec3 here = position();
                std::optional<double> x = w.length('X'), y = w.length('Y');
                drill_point({x.value_or(here.x), y.value_or(here.y)});
                handled = true;
                break;
            }
            default: fail(fmt::format("unknown code {}", g->text));
        }
    }
    if (!handled && motion >= 0) {
        motion_ = motion;
        bool any = w.has('X') || w.has('Y') || w.has('Z') || w.has('I') || w.has('J') || w.has('D');
        if (any || g) drill_end();
        if (motion == code(0)) {
            rapid_to(w.length('X'), w.length('Y'), w.length('Z'));
        } else if (motion == code(1)) {
            linear_to(w.length('X'), w.length('Y'), w.length('Z'));
        } else if (any) {
            ArcWords a;
            a.direction = motion == code(2) ? ArcDirection::cw : ArcDirection::ccw;
            a.x = w.length('X'), a.y = w.length('Y'), a.z = w.length('Z');
            a.i = w.offset('I'), a.j = w.offset('J');
            if (const Word* d = w.take('D')) a.d = angle(*d);
            // The classic form needs both end coordinates: nccad fails when one was dropped.
            if (!a.d && (!a.x || !a.y))
                fail(fmt::format("G0{} without both X and Y: nccad needs the whole end point on an arc block",
                                 motion == code(2) ? 2 : 3));
            if (!a.d && (!a.i || !a.j)) fail("an nccad arc needs both I and J");
            arc(a);
        }
    } else if (!handled && (w.has('X') || w.has('Y') || w.has('Z'))) {
        fail("coordinates without a motion code (G00, G01, G79, ...)");
    }
    w.require_all_used();
}

}  // namespace

std::unique_ptr<NcReader> make_nccad_reader(const Machine& machine, std::string source) {
    return std::make_unique<NccadReader>(machine, std::move(source));
}

}  // namespace camgen::reader
