// Reading the Sinumerik 840D dialect: N sequence numbers, "; comments",
// G17/G18/G19, G70/G71, G90, G94, G0-G3 with I/J/K (relative to the start) or CR=, G4 F<s> dwell,
// G40/G41/G42, T.. D1 and M6, S.. M3/M4/M5, M30/M2, stops M0/M1 with the message MSG("...")
// shows (MSG() clears it), and the drilling cycles as the post writes
// them: MCALL CYCLE81..CYCLE89(...), then one G0 X Y block per hole (each calls the cycle at
// its position, from the Z the tool stands at), then MCALL alone. Each cycle call is read back
// into the DrillCycle whose longhand moves camgen means by it: the inverse of
// sinumerik_cycle_call (README "Drilling: canned or longhand").
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "machines/sinumerik/sinumerik_reader.hpp"
#include "machines/sinumerik/sinumerik_words.hpp"
#include "src/reader/nc_reader.hpp"

namespace camgen::reader {

namespace {

// The parameters of a standard cycle call, by position (nullopt: left empty, the default).
struct CycleCall {
    std::string name;  // "CYCLE83"
    std::vector<std::optional<double>> values;
    std::vector<std::string> texts;  // as written, for messages
    int line = 0;
};

class SinumerikReader : public NcReader {
public:
    using NcReader::NcReader;

protected:
    bool frame_line(std::string_view) override { return false; }
    bool named_word(std::string_view name) const override { return name == "CR" || name == "LIMS"; }
    void line(std::string_view text) override;
    void block(const Block& b) override;
    void finish() override;
    std::vector<std::pair<std::string, std::string>> modal_state() const override;

private:
    // MSG("text") shows a message, MSG() clears it (`call`: from "MSG").
    void message(std::string_view call);
    std::string message_;  // the message shown
    void modal_call(std::string_view call);
    // The DrillCycle a call of the active modal cycle means, with the feed and spindle now in
    // effect (CYCLE81/82/83/86/89 drill at the active F).
    DrillCycle cycle_now() const;

    std::optional<CycleCall> mcall_;
    int motion_ = -1;
    Plane plane_ = Plane::xy;
    std::optional<int> selected_tool_;
    std::string selected_edge_;  // SelectedOffsets::length of the tool selected ("D1"; "": D0)
    bool active_tool_ = false;   // a tool change (M6) was read
    std::string active_edge_;    // the edge in force since then ("D1"; "": D0)
    bool comp_on_ = false;       // G41/G42 in force
    Units base_units_ = machine_.units;  // the control's base system: F's unit under G70/G71
    bool diamon_ = false;        // DIAMON read (a lathe's X as a diameter), or none to read
    std::optional<double> lims_;  // LIMS=, rpm: the limit of a G96
    bool ended_ = false;
};

std::vector<std::pair<std::string, std::string>> SinumerikReader::modal_state() const {
    std::vector<std::pair<std::string, std::string>> s = NcReader::modal_state();
    s.emplace_back("plane", plane_ == Plane::xy ? "G17" : plane_ == Plane::xz ? "G18" : "G19");
    s.emplace_back("modal cycle call", mcall_ ? mcall_->name : "none");
    s.emplace_back("program end", ended_ ? "read" : "not read");
    return s;
}

void SinumerikReader::message(std::string_view call) {
    if (ended_) fail("a block after the end of the program");
    // MSG ( [ "text" ] ) [; comment]: the string first, since it may hold ';'.
    std::string_view rest = trim(call.substr(3));
    if (rest.empty() || rest.front() != '(') fail(fmt::format("{}: expected MSG(\"text\") or MSG()", call));
    rest = trim(rest.substr(1));
    std::optional<std::string> text;
    if (!rest.empty() && rest.front() == '"') {
        const size_t close = rest.find('"', 1);
        if (close == std::string_view::npos) fail(fmt::format("{}: the message's string does not end", call));
        text = std::string(rest.substr(1, close - 1));
        rest = trim(rest.substr(close + 1));
    }
    if (rest.empty() || rest.front() != ')') fail(fmt::format("{}: the message is one string in double quotes", call));
    rest = trim(rest.substr(1));
    if (!rest.empty() && rest.front() != ';') fail(fmt::format("{}: nothing may follow MSG(...) but a comment", call));
    message_ = text.value_or("");
}

void SinumerikReader::line(std::string_view text) {
    // "N80 MCALL CYCLE81(...)" is no block of address words: read it here.
    std::string_view rest = trim(text);
    if (!rest.empty() && rest.front() == 'N') {
        size_t digits = rest.find_first_not_of("0123456789", 1);
        if (digits != 1 && digits != std::string_view::npos && is_blank(rest[digits])) rest = trim(rest.substr(digits));
    }
    if (rest.rfind("MSG", 0) == 0 && rest.size() > 3 && (rest[3] == '(' || is_blank(rest[3]))) {
        (void)split_line(text.substr(0, text.find("MSG")));  // checks the sequence number
        message(rest);
        return;
    }
    if (rest.rfind("MCALL", 0) == 0 && (rest.size() == 5 || is_blank(rest[5]) || rest[5] == ';')) {
        (void)split_line(text.substr(0, text.find("MCALL")));  // checks the sequence number
        std::string_view call = rest.substr(5);
        if (size_t semi = call.find(';'); semi != std::string_view::npos) {
            Block comment;
            comment.comments.emplace_back(trim(call.substr(semi + 1)));
            emit_comments(comment);
            call = call.substr(0, semi);
        }
        if (ended_) fail("a block after the end of the program");
        modal_call(trim(call));
        return;
    }
    // DIAMON (a lathe's X as a diameter) is a word of its own, not an address: where the
    // machine's start block selects it (and its xDiameterProg says so), it is read here.
    if (const size_t at = text.find("DIAMON"); at != std::string_view::npos) {
        const auto& start = machine_.frame.start_block;
        if (std::find(start.begin(), start.end(), "DIAMON") == start.end() || !machine_.x_diameter)
            fail(fmt::format("DIAMON: machine {} does not program X as a diameter", machine_.name));
        diamon_ = true;
        std::string rest(text);
        rest.erase(at, 6);
        NcReader::line(rest);
        return;
    }
    if (text.find("DIAMOF") != std::string_view::npos)
        fail(fmt::format("DIAMOF (X as a radius): camgen reads X {} on machine {}",
                         machine_.x_diameter ? "as a diameter, under DIAMON," : "as the machine's xDiameterProg says",
                         machine_.name));
    NcReader::line(text);
}

void SinumerikReader::finish() {
    if (mcall_) fail(fmt::format("the program ends with the modal call {} of line {} still active (MCALL ends it)",
                                 mcall_->name, mcall_->line));
    if (!ended_) fail("the program does not end with M30 or M2: it may have been cut short");
    NcReader::finish();
}

void SinumerikReader::modal_call(std::string_view call) {
    if (call.empty()) {
        if (!mcall_) fail("MCALL without a modal cycle call to end");
        mcall_.reset();
        drill_end();
        return;
    }
    size_t open = call.find('(');
    if (open == std::string_view::npos || call.back() != ')')
        fail(fmt::format("MCALL {}: expected a cycle call NAME(parameters)", call));
    CycleCall c;
    c.name = std::string(trim(call.substr(0, open)));
    c.line = line_;
    bool known = false;
    for (const DrillingCycleSpec& s : machine_.drilling) known = known || (s.canned && s.name == c.name);
    if (!known) {
        std::vector<std::string> names;
        for (const DrillingCycleSpec& s : machine_.drilling)
            if (s.canned && std::find(names.begin(), names.end(), s.name) == names.end()) names.push_back(s.name);
        fail(fmt::format("{} is not a cycle of machine {} (it has: {})", c.name, machine_.name,
                         names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
    }
    std::string_view list = call.substr(open + 1, call.size() - open - 2);
    for (size_t pos = 0;;) {
        size_t comma = list.find(',', pos);
        std::string_view item = trim(list.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos));
        c.texts.emplace_back(item);
        if (item.empty()) {
            c.values.emplace_back();
        } else {
            auto v = parse_number(item);
            if (!v) fail(fmt::format("{}: parameter {} \"{}\" is not a number", c.name, c.values.size() + 1, item));
            c.values.push_back(v);
        }
        if (comma == std::string_view::npos) break;
        pos = comma + 1;
    }
    const sinumerik::CycleForm* form = nullptr;
    for (const sinumerik::CycleForm& f : sinumerik::cycle_forms)
        if (f.name == c.name) form = &f;
    if (!form) fail(fmt::format("camgen cannot read {} calls", c.name));
    if (c.values.size() > form->count)
        fail(fmt::format("{} takes at most {} parameters, not {}", c.name, form->count, c.values.size()));
    c.values.resize(form->count);
    c.texts.resize(form->count);
    drill_end();
    mcall_ = c;
    (void)cycle_now();  // every parameter is checked where it is written
}

DrillCycle SinumerikReader::cycle_now() const {
    const CycleCall& call = *mcall_;
    const std::string& name = call.name;
    auto has = [&](size_t i) { return call.values[i].has_value(); };
    auto need = [&](size_t i, const char* what) {
        if (!has(i)) fail(fmt::format("{} without {} (parameter {})", name, what, i + 1));
        return *call.values[i];
    };
    auto empty = [&](size_t i, const char* what, const char* why) {
        if (has(i)) fail(fmt::format("{}: {} = {}: {}", name, what, call.texts[i], why));
    };
    auto zero_or_empty = [&](size_t i, const char* what) {
        if (has(i) && *call.values[i] != 0.0)
            fail(fmt::format("{}: {} = {}: camgen writes it 0 and reads no other value", name, what, call.texts[i]));
    };
    auto positive = [&](size_t i) -> std::optional<double> {
        if (!has(i)) return std::nullopt;
        if (*call.values[i] < 0) fail(fmt::format("{}: parameter {} = {} must not be negative", name, i + 1, call.texts[i]));
        return *call.values[i] > 0 ? call.values[i] : std::nullopt;
    };
    // Parameters in internal units through the machine's formats (inch programs write inches).
    auto dwell_at = [&](size_t i) -> std::optional<double> {
        auto v = positive(i);
        return v ? std::optional<double>(seconds_value(*v)) : std::nullopt;
    };
    auto length_at = [&](size_t i) -> std::optional<double> {
        auto v = positive(i);
        return v ? std::optional<double>(length_value(*v)) : std::nullopt;
    };
    auto direction = [&](size_t i, const char* what) {
        double v = need(i, what);
        if (v != 3.0 && v != 4.0) fail(fmt::format("{}: {} = {}: 3 (M3) or 4 (M4)", name, what, call.texts[i]));
        return v == 3.0 ? SpindleDirection::cw : SpindleDirection::ccw;
    };

    // RTP, RFP, SDIS, DP, DPR: SDIS is measured from RFP, DP is absolute.
    namespace common = sinumerik::common;
    DrillCycle c;
    c.retract_z = length_value(need(common::rtp, "the retract plane RTP"));
    c.reference_z = length_value(need(common::rfp, "the reference plane RFP"));
    const double sdis = length_value(need(common::sdis, "the safety distance SDIS"));
    if (sdis < 0)
        fail(fmt::format("{}: the safety distance SDIS = {} must not be negative", name, call.texts[common::sdis]));
    c.safe_z = c.reference_z + sdis;
    c.bottom_z = length_value(need(common::dp, "the final drilling depth DP"));
    empty(common::dpr, "DPR", "camgen writes the depth absolute (DP) and reads no relative depth");
    if (!(c.bottom_z < c.safe_z)) fail(fmt::format("{}: the depth DP is not below RFP + SDIS", name));
    if (c.retract_z < c.safe_z) fail(fmt::format("{}: the retract plane RTP is below RFP + SDIS", name));
    c.spindle_rpm = rpm_;
    c.spindle_direction = spindle_ == SpindleState::ccw ? SpindleDirection::ccw : SpindleDirection::cw;
    c.output = CycleOutput::canned;
    DrillValues& p = c.values;
    auto active_feed = [&] {
        // The cycle drills at the feed in effect where it is called.
        if (!feed_) fail(fmt::format("{} without a feed F before it", name));
        c.feed = *feed_;
        p.set(DrillField::plunging_feedrate, c.feed);
    };

    if (name == sinumerik::cycle81::form.name) {
        c.kind = CycleKind::drill;
        active_feed();
    } else if (name == sinumerik::cycle82::form.name) {
        c.kind = CycleKind::dwell;
        p.set(DrillField::bottom_dwell, dwell_at(sinumerik::cycle82::dtb));
        active_feed();
    } else if (name == sinumerik::cycle83::form.name) {
        namespace q = sinumerik::cycle83;
        const double vari = need(q::vari, "VARI");
        if (vari != 0.0 && vari != 1.0)
            fail(fmt::format("{}: VARI = {}: 0 (chip breaking) or 1 (full retract)", name, call.texts[q::vari]));
        const bool full = vari == 1.0;
        c.kind = full ? CycleKind::deep : CycleKind::chip_break;
        const double fdep = length_value(need(q::fdep, "the first drilling depth FDEP"));
        empty(q::fdpr, "FDPR", "camgen writes the first depth absolute (FDEP)");
        if (!(fdep < c.safe_z))
            fail(fmt::format("{}: the first depth FDEP = {} is not below RFP + SDIS", name, call.texts[q::fdep]));
        p.set(DrillField::first_depth, c.safe_z - fdep);
        if (has(q::dam) && *call.values[q::dam] != 0.0) {
            if (*call.values[q::dam] < 0)
                fail(fmt::format("{}: DAM = {}: camgen reads only a degression value", name, call.texts[q::dam]));
            p.set_degression_type(DegressionType::value);
            p.set(DrillField::degression, length_value(*call.values[q::dam]));
        }
        empty(q::dtb, "DTB", "a dwell at every peck depth is no camgen cycle (camgen dwells at the bottom with _DTD)");
        // DTS acts only between full retracts (VARI=1), as the control runs it.
        if (full) p.set(DrillField::top_dwell, dwell_at(q::dts));
        if (has(q::frf)) {
            if (!(*call.values[q::frf] > 0 && *call.values[q::frf] <= 1))
                fail(fmt::format("{}: FRF = {} is not in (0, 1]", name, call.texts[q::frf]));
            p.set(DrillField::first_feedrate_factor, call.values[q::frf]);
        }
        empty(q::axn, "_AXN", "camgen drills along Z only");
        if (has(q::mdep)) p.set(DrillField::minimum_depth, length_at(q::mdep));
        if (!full && has(q::vrt)) {
            if (!(*call.values[q::vrt] > 0)) fail(fmt::format("{}: _VRT = {} must be > 0", name, call.texts[q::vrt]));
            p.set(DrillField::pecking_retract, length_value(*call.values[q::vrt]));
        }
        p.set(DrillField::bottom_dwell, dwell_at(q::dtd));
        if (full) {
            // The re-approach distance of full-retract pecks: camgen's longhand stops the
            // machine's peckClearance above the last peck, and so must the program.
            double dis1 = length_value(need(q::dis1, "the advance distance _DIS1 (without it the control picks its own)"));
            if (std::abs(dis1 - machine_.peck_clearance) > resolution().position)
                fail(fmt::format("{}: _DIS1 = {}: machine {} re-approaches {} mm above the last peck", name,
                                 call.texts[q::dis1], machine_.name, machine_.peck_clearance));
        }
        active_feed();
    } else if (name == sinumerik::cycle84::form.name) {
        namespace q = sinumerik::cycle84;
        p.set(DrillField::bottom_dwell, dwell_at(q::dtb));
        c.spindle_direction = direction(q::sdac, "SDAC (the spindle direction after the cycle)");
        empty(q::mpit, "MPIT", "camgen writes the pitch as PIT");
        const double pit = length_value(need(q::pit, "the pitch PIT"));
        if (pit == 0.0) fail(fmt::format("{}: the pitch PIT must not be 0", name));
        zero_or_empty(q::poss, "POSS");
        c.kind = pit < 0 ? CycleKind::tap_left : CycleKind::tap;
        p.set(DrillField::pitch, std::abs(pit));
        const double sst = rpm_value(need(q::sst, "the tapping speed SST"));
        if (!(sst > 0)) fail(fmt::format("{}: the tapping speed SST must be > 0", name));
        p.set(DrillField::tapping_speed, sst);
        if (has(q::sst1)) {
            if (!(*call.values[q::sst1] > 0)) fail(fmt::format("{}: the retract speed SST1 must be > 0", name));
            p.set(DrillField::retract_speed, rpm_value(*call.values[q::sst1]));
        }
        c.feed = *p.get(DrillField::pitch) * sst;
        if (!(rpm_ > 0)) fail(fmt::format("{} without a spindle speed S before it", name));
    } else if (name == sinumerik::cycle85::form.name) {
        namespace q = sinumerik::cycle85;
        c.kind = CycleKind::ream;
        p.set(DrillField::bottom_dwell, dwell_at(q::dtb));
        c.feed = feed_value(need(q::ffr, "the feed FFR"));
        if (!(c.feed > 0)) fail(fmt::format("{}: the feed FFR must be > 0", name));
        p.set(DrillField::plunging_feedrate, c.feed);
        if (has(q::rff)) {
            if (!(*call.values[q::rff] > 0)) fail(fmt::format("{}: the retract feed RFF must be > 0", name));
            p.set(DrillField::retract_feedrate, feed_value(*call.values[q::rff]));
        }
    } else if (name == sinumerik::cycle86::form.name) {
        // Out along the hole axis, no lift-off.
        namespace q = sinumerik::cycle86;
        c.kind = CycleKind::bore_stop;
        p.set(DrillField::bottom_dwell, dwell_at(q::dtb));
        c.spindle_direction = direction(q::sdir, "SDIR (the spindle direction)");
        zero_or_empty(q::rpa, "RPA");
        zero_or_empty(q::rpo, "RPO");
        zero_or_empty(q::rpap, "RPAP");
        zero_or_empty(q::poss, "POSS");
        active_feed();
    } else {  // CYCLE89
        c.kind = CycleKind::bore_dwell;
        p.set(DrillField::bottom_dwell, dwell_at(sinumerik::cycle89::dtb));
        active_feed();
    }
    bool offered = false;
    for (const DrillingCycleSpec& s : machine_.drilling) offered = offered || (s.canned && s.name == name && s.kind == c.kind);
    if (!offered)
        fail(fmt::format("{} as a {} cycle is not a canned cycle of machine {}", name, name_of(cycle_kinds, c.kind), machine_.name));
    return c;
}

void SinumerikReader::block(const Block& b) {
    if (ended_) fail("a block after the end of the program");
    std::optional<Code> motion, plane, units, comp, dwell, work_offset, coolant, speed_mode;
    MCodes m;
    BlockWords w(*this, "XYZIJKFSTD");
    const Word* cr = nullptr;
    const Word* lims = nullptr;
    auto set_group = [&](std::optional<Code>& group, Code c) { NcReader::set_group(group, c, "group"); };
    for (const Word& x : b.words) {
        if (x.name == "CR") {
            if (cr) fail("two CR= words in one block");
            cr = &x;
        } else if (x.name == "LIMS") {
            // A lathe's spindle limit under constant surface speed (G96).
            if (machine_.kind != MachineKind::lathe) fail(fmt::format("{}: a lathe's spindle limit", x.text));
            if (lims) fail("two LIMS= words in one block");
            lims = &x;
        } else if (x.letter == 'G') {
            Code c{code_of(x), &x};
            // A lathe's feed modes (frame feedModes: G94, G95 per revolution).
            if (auto mode = feed_mode_of(x)) {
                set_feed_mode(*mode);
                continue;
            }
            switch (c.value) {
                case code(0): case code(1): case code(2): case code(3): set_group(motion, c); break;
                case code(33):
                    // Thread cutting with constant lead, G33 Z K: on a lathe only.
                    if (machine_.kind != MachineKind::lathe) fail(fmt::format("unknown code {}", x.text));
                    set_group(motion, c);
                    break;
                case code(96): case code(97):
                    // Constant surface speed (G96 S in m/min, within LIMS=) or constant rpm (G97 S).
                    if (machine_.kind != MachineKind::lathe) fail(fmt::format("unknown code {}", x.text));
                    set_group(speed_mode, c);
                    break;
                case code(17): case code(18): case code(19): set_group(plane, c); break;
                case code(70): case code(71): case code(700): case code(710): set_group(units, c); break;
                case code(90): break;
                case code(91): fail(fmt::format("{} (incremental positions): camgen posts never write it", x.text));
                case code(94): break;
                case code(93): case code(95): fail(fmt::format("{}: only feed per minute (G94) is read", x.text));
                case code(40): case code(41): case code(42): set_group(comp, c); break;
                case code(4): set_group(dwell, c); break;
                default:
                    if (work_offset_code(c.value)) {
                        set_group(work_offset, c);
                        break;
                    }
                    fail(fmt::format("unknown code {}", x.text));
            }
        } else if (x.letter == 'M') {
            if (shared_m_code(Code{code_of(x), &x}, m, "group")) continue;
            if (!coolant_of(x)) fail(fmt::format("unknown code {}", x.text));
            set_group(coolant, Code{code_of(x), &x});
        } else {
            w.add(x);
        }
    }

    // In a G4 block F is the dwell in seconds, not a feed.
    if (dwell) {
        const Word* f = w.take('F');
        if (!f) fail(fmt::format("{} without its time F (seconds)", dwell->word->text));
        if (b.words.size() != 2) fail(fmt::format("{} must stand in a block of its own with its F", dwell->word->text));
        emit(Dwell{seconds(*f)});
    }
    if (const Word* f = dwell ? nullptr : w.take('F')) set_feed(*f);
    if (lims) {
        const double limit = rpm(*lims);
        if (!(limit > 0)) fail(fmt::format("{}: a speed limit must be > 0", lims->text));
        if (machine_.limits.max_rpm > 0 && limit > machine_.limits.max_rpm)
            fail(fmt::format("{}: above the limit of machine {} ({} rpm)", lims->text, machine_.name, machine_.limits.max_rpm));
        lims_ = limit;
        spindle_limit(limit);
    }
    if (speed_mode) {
        const std::string& name = speed_mode->word->text;
        if (!w.has('S')) fail(fmt::format("{} without S: camgen writes {} S", name, name));
        if (speed_mode->value == code(97)) {
            // G97 also switches feed per revolution on, as G95 ("G97: revolutional feedrate and
            // constant spindle speed", SINUMERIK ONE programming manual; the 840D manual of 2004:
            // "the same effect as G95"): camgen's post writes G94 after it for feed per minute.
            constant_rpm();
            set_feed_mode(FeedMode::per_revolution);
        } else {
            if (!lims_ && !(machine_.limits.max_rpm > 0))
                fail(fmt::format("{} without a spindle limit LIMS= before it, and machine {} has no maxRpm", name, machine_.name));
            constant_surface_speed(lims_.value_or(machine_.limits.max_rpm));
            // G96 switches feed per revolution (G95) on.
            set_feed_mode(FeedMode::per_revolution);
        }
    }
    if (const Word* s = w.take('S')) spindle_speed(rpm(*s), m.spindle ? m.spindle->word : nullptr);
    if (const Word* t = w.take('T')) {
        selected_tool_ = integer_of(*t);
        // D: the tool's cutting edge, selected with it: its length and radius apply from the tool
        // change (M6). camgen's post writes D1; a T without D leaves the edge to the control's
        // machine data (Siemens' default: D1, unconfirmed for a given control), which verify --job
        // does not assume.
        // D0 selects no edge: no length and no radius (SelectedOffsets::length "").
        const Word* d = w.take('D');
        selected_edge_ = !d                     ? fmt::format("T{} without D: the control's default edge", *selected_tool_)
                         : integer_of(*d) == 0 ? std::string()
                                               : fmt::format("D{}", integer_of(*d));
    } else if (const Word* d = w.take('D')) {
        // D without T selects another edge of the tool in the spindle (D0: none), in force from
        // this block on: its length applies with the next move along Z.
        if (!active_tool_) fail(fmt::format("{} without a tool in the spindle (T.. M6 before it)", d->text));
        if (comp_on_) fail(fmt::format("{} under G41/G42: camgen reads a change of edge only with G40 in force", d->text));
        active_edge_ = integer_of(*d) == 0 ? std::string() : fmt::format("D{}", integer_of(*d));
        select_length_offset(active_edge_);
    }
    if (m.tool_change) {
        if (!selected_tool_) fail("M6 without a tool selected by T");
        if (mcall_) fail(fmt::format("a tool change while the modal call {} of line {} is active", mcall_->name, mcall_->line));
        change_tool(*selected_tool_, commented_description(*selected_tool_));
        active_tool_ = true;
        active_edge_ = selected_edge_;
        select_length_offset(selected_edge_);
    }
    if (m.spindle) switch_spindle(*m.spindle->word, "S");
    if (coolant) emit(Coolant{*coolant_of(*coolant->word), ""});
    if (work_offset) select_work_offset(work_offset->value, *work_offset->word, w);
    if (plane) {
        const Plane p = plane->value == code(17) ? Plane::xy : plane->value == code(18) ? Plane::xz : Plane::yz;
        if (comp_on_ && p != plane_)
            fail(fmt::format("{} under G41/G42: camgen reads a change of plane only with G40 in force", plane->word->text));
        plane_ = p;
    }
    if (units) {
        // G700/G710: positions and feeds in inch or mm. G70/G71 change the positions only, the F
        // stays in the control's base system (802D sl, 840D manuals: "feedrates ... are not
        // influenced by G70/G71"), which camgen takes as the machine's units: G71 on a metric
        // machine is G710, but a G70 there would leave F in mm/min under inch positions.
        const bool inch = units->value == code(70) || units->value == code(700);
        const bool positions_only = units->value == code(70) || units->value == code(71);
        if (positions_only && (inch ? Units::inch : Units::mm) != base_units_)
            fail(fmt::format("{} sets {} positions but leaves F in the control's base system ({}, machine {}): camgen "
                             "reads {} (positions and feeds) instead",
                             units->word->text, inch ? "inch" : "mm", name_of(unit_names, base_units_), machine_.name,
                             inch ? "G700" : "G710"));
        set_units(inch ? Units::inch : Units::mm);
    }
    if (comp) {
        // G41/G42 take the radius of the cutting edge selected with the tool (D1); under D0 there
        // is none, and the control would cut on the programmed path.
        if (comp->value != code(40) && active_tool_ && active_edge_.empty())
            fail(fmt::format("{} under D0: no cutting edge selected, no radius to offset by", comp->word->text));
        // The control offsets in the active plane; camgen reads a mill's compensation in XY (G17)
        // and a lathe's in XZ (G18) only.
        const Plane comp_plane = machine_.kind == MachineKind::lathe ? Plane::xz : Plane::xy;
        if (comp->value != code(40) && plane_ != comp_plane)
            fail(fmt::format("{} under {}: the control would offset the tool in the {} plane; camgen reads {} "
                             "compensation in the {} plane ({}) only",
                             comp->word->text, plane_ == Plane::xy ? "G17" : plane_ == Plane::xz ? "G18" : "G19",
                             plane_ == Plane::xy ? "XY" : plane_ == Plane::xz ? "XZ" : "YZ",
                             machine_.kind == MachineKind::lathe ? "nose radius" : "cutter radius",
                             machine_.kind == MachineKind::lathe ? "XZ" : "XY",
                             machine_.kind == MachineKind::lathe ? "G18" : "G17"));
        comp_on_ = comp->value != code(40);
        emit(Compensation{comp->value == code(40)  ? CompensationSide::off
                          : comp->value == code(41) ? CompensationSide::left
                                                    : CompensationSide::right});
    }
    if (motion) motion_ = motion->value;
    if (w.has('X') && !diamon_ && machine_.x_diameter) {
        // X is a diameter only under DIAMON; the control's power-up mode is its machine data's
        // (and the last program's DIAMON/DIAMOF stays in force).
        const auto& start = machine_.frame.start_block;
        if (std::find(start.begin(), start.end(), "DIAMON") != start.end())
            fail(fmt::format("X before DIAMON: machine {} programs X as a diameter from its start block's DIAMON",
                             machine_.name));
        diamon_ = true;  // no DIAMON to read: X is as the machine's xDiameterProg says
    }
    bool axes = w.has('X') || w.has('Y') || w.has('Z') || w.has('I') || w.has('J') || w.has('K') || cr;
    if (axes) {
        if (motion_ < 0) fail("coordinates before any motion code (G0, G1, ...)");
        if (mcall_) {
            // Under a modal call every positioning block drills a hole where it ends.
            if (motion_ != code(0) || w.has('Z') || w.has('I') || w.has('J') || w.has('K') || cr)
                fail(fmt::format("under the modal call {} of line {} camgen writes only G0 X Y hole positions",
                                 mcall_->name, mcall_->line));
            if (!position_known()) fail(fmt::format("{} from an unknown position", mcall_->name));
            // The cycle drills along the plane's normal: only G17 drills along Z (a lathe's axis;
            // camgen's mill posts drill only under G17).
            if (plane_ != Plane::xy)
                fail(fmt::format("{} under {}: it would drill along {} ({})", mcall_->name,
                                 plane_ == Plane::xz ? "G18" : "G19", plane_ == Plane::xz ? "Y" : "X",
                                 machine_.kind == MachineKind::lathe ? "a lathe drills on its axis under G17"
                                                                     : "camgen reads a drilling cycle along Z, under G17, only"));
            std::optional<double> x = w.length('X'), y = w.length('Y');
            rapid_to(x, y, std::nullopt);
            DrillCycle c = cycle_now();
            if (!current_cycle() || !(*current_cycle() == c)) drill_cycle(c);
            Vec3 here = position();
            drill_point({here.x, here.y});
        } else if (motion_ == code(33)) {
            // G33 [X] Z K from where the tool stands, K mm per revolution along Z; with X a taper
            // of at most 45 degrees (a chamfered runout), whose lead is the longer axis's, Z's.
            for (char letter : {'Y', 'I', 'J'})
                if (const Word* x = w.find(letter))
                    fail(fmt::format("{} on G33: camgen cuts threads in X and Z only, each pass positioned with G0", x->text));
            if (cr) fail("CR= on G33");
            const Word* xw = w.take('X');
            const Word* zw = w.take('Z');
            const Word* kw = w.take('K');
            if (!zw || !kw) fail("G33 needs the end Z and the lead K");
            thread_to("G33", xw ? std::optional<double>(length(*xw)) : std::nullopt, length(*zw), *kw);
        } else if (std::optional<ArcWords> a = move_or_arc(motion_, plane_, w)) {
            if (cr) a->r = length(*cr);
            arc(*a);
        }
    }
    w.require_all_used();
    if (m.stop && (m.stop->value == code(0) || m.stop->value == code(1))) {
        if (mcall_) fail(fmt::format("a stop while the modal call {} of line {} is active", mcall_->name, mcall_->line));
        stop(m.stop->value == code(1) ? StopKind::optional : StopKind::mandatory, message_);
    }
    if (m.stop && (m.stop->value == code(2) || m.stop->value == code(30))) {
        if (mcall_) fail(fmt::format("the program ends with the modal call {} of line {} still active (MCALL ends it)",
                                     mcall_->name, mcall_->line));
        drill_end();
        ended_ = true;
    }
}

}  // namespace

std::unique_ptr<NcReader> make_sinumerik_reader(const Machine& machine, std::string source) {
    return std::make_unique<SinumerikReader>(machine, std::move(source));
}

}  // namespace camgen::reader
