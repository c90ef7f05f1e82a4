// Reading the ISO (Fanuc-style) dialect: %, O-number, N sequence numbers, modal G groups
// (motion, plane, units, distance, feed mode, compensation, length offset, return level),
// tool changes as the machine's toolChange setting writes them (T.. M6, or GRBL's
// "(Insert tool n: ...)" comment and M0), stops M0/M1 with the message in the block's comment
// (or LinuxCNC's "(MSG, text)"), S.. M3/M4/M5, G4 P, arcs by the machine's arc format
// (helices as full-turn blocks or with P), the machine's canned cycles with sticky R/Z/Q/P and
// G98/G99 (G98: back to the Z before the first cycle block, G99: to R), LinuxCNC G33.1 rigid
// tapping, M2/M30. The lathe's codes, turret calls and Fanuc T's G74 are its lathe variant's
// (iso_lathe_reader.cpp), through the hooks of IsoReader (iso_reader.hpp).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "machines/iso/iso_reader.hpp"
#include "camgen/common/error.hpp"
#include "machines/iso/iso_words.hpp"

namespace camgen::reader {

namespace {

// The cycle kind of an ISO canned-cycle code (in tenths), if it is one.
std::optional<CycleKind> cycle_kind_of(int g) {
    for (const iso::CycleCode& c : iso::cycle_codes)
        if (code(c.code) == g) return c.kind;
    return std::nullopt;
}

bool has_field(const DrillingCycleSpec& spec, DrillField f) {
    return std::find(spec.fields.begin(), spec.fields.end(), f) != spec.fields.end();
}

}  // namespace

IsoReader::IsoReader(const Machine& machine, std::string source, const iso::Settings& settings)
    : NcReader(machine, std::move(source)), settings_(settings) {}

std::vector<std::pair<std::string, std::string>> IsoReader::modal_state() const {
    std::vector<std::pair<std::string, std::string>> s = NcReader::modal_state();
    s.emplace_back("plane", plane_ == Plane::xy ? "G17" : plane_ == Plane::xz ? "G18" : "G19");
    s.emplace_back("tool length offset", length_offset_);
    s.emplace_back("canned cycle return level", g98_ ? "G98" : "G99");
    s.emplace_back("program numbers", std::to_string(program_numbers_));
    s.emplace_back("tool change announced", pending_insert_ ? fmt::format("Insert tool {}", pending_insert_->number) : "none");
    s.emplace_back("program end", ended_ ? "read" : "not read");
    return s;
}

const DrillingCycleSpec* IsoReader::canned_spec(int g) const {
    for (const DrillingCycleSpec& spec : machine_.drilling) {
        if (!spec.canned || spec.name.size() < 2 || spec.name[0] != 'G') continue;
        if (auto v = parse_number(std::string_view(spec.name).substr(1)); v && code(*v) == g) return &spec;
    }
    return nullptr;
}

std::optional<IsoInsertTool> IsoReader::insert_tool(const std::string& comment) const {
    // The pause post's comment: "Insert tool <n>" or "Insert tool <n>: <description>".
    constexpr std::string_view prefix = "Insert tool ";
    if (comment.rfind(prefix, 0) != 0) return std::nullopt;
    std::string_view rest = std::string_view(comment).substr(prefix.size());
    size_t end = rest.find_first_not_of("0123456789");
    std::string_view number = rest.substr(0, end);
    if (number.empty() || number.size() > 9)
        fail(fmt::format("({}): no tool number after \"Insert tool\"", comment));
    IsoInsertTool t{std::stoi(std::string(number)), "", line_};
    if (end != std::string_view::npos) {
        if (rest.substr(end, 2) != ": " || rest.size() == end + 2)
            fail(fmt::format("({}): expected \"Insert tool {}: <description>\"", comment, t.number));
        t.description = std::string(rest.substr(end + 2));
    }
    return t;
}

void IsoReader::line(std::string_view text) {
    Block b = split_line(text);
    bool announced_before = pending_insert_.has_value();
    emit_comments(b);
    if (pauses_for_tools()) announce_tools(b);
    if (!b.words.empty()) block(b);
    if (announced_before && pending_insert_)
        fail(fmt::format("the tool change announced on line {} (Insert tool {}) is not made: machine {} pauses "
                         "for it with M0 on the next line",
                         pending_insert_->line, pending_insert_->number, machine_.name));
}

void IsoReader::announce_tools(const Block& b) {
    for (const std::string& c : b.comments) {
        auto t = insert_tool(c);
        if (!t) continue;
        if (pending_insert_)
            fail(fmt::format("a second tool change comment before the M0 that makes the one on line {}", pending_insert_->line));
        pending_insert_ = t;
    }
}

void IsoReader::refuse_tool_words(const Word* t, const BlockCodes& codes) const {
    if (t)
        fail(fmt::format("{}: machine {} has no tool changer; it announces a tool in a comment "
                         "(Insert tool <n>) and pauses with M0", t->text, machine_.name));
    if (codes.m.tool_change)
        fail(fmt::format("M6: machine {} has no tool changer; it announces a tool in a comment (Insert tool <n>) "
                         "and pauses with M0", machine_.name));
}

void IsoReader::finish() {
    if (pending_insert_)
        fail(fmt::format("the tool change announced on line {} (Insert tool {}) is not made: the program ends "
                         "without its M0",
                         pending_insert_->line, pending_insert_->number));
    if (!ended_) fail("the program does not end with M2 or M30: it may have been cut short");
    NcReader::finish();
}

IsoReader::BlockCodes IsoReader::block_codes(const Block& b, BlockWords& w) {
    BlockCodes k;
    for (const Word& x : b.words) {
        if (x.letter == 'G') {
            Code c{code_of(x), &x};
            // A lathe's feed mode codes (frame feedModes; Fanuc T's G98/G99 are these, not return levels).
            if (feed_mode_of(x)) {
                set_group(k.feed_mode, c);
                continue;
            }
            switch (c.value) {
                case code(0): case code(1): case code(2): case code(3): case code(80): set_group(k.motion, c); break;
                case code(iso::rigid_tap_code):
                    if (!canned_spec(c.value))
                        fail(fmt::format("{} (rigid tapping) is not a cycle of machine {}", x.text, machine_.name));
                    set_group(k.motion, c);
                    break;
                case code(17): case code(18): case code(19): set_group(k.plane, c); break;
                case code(7): case code(8): {
                    // LinuxCNC's diameter (G7) and radius (G8) modes, on a machine whose start block
                    // selects one: its xDiameterProg says which.
                    const auto& start = machine_.frame.start_block;
                    const bool has_modes = std::find(start.begin(), start.end(), "G7") != start.end() ||
                                           std::find(start.begin(), start.end(), "G8") != start.end();
                    if (!has_modes) fail(fmt::format("unknown code {}", x.text));
                    if ((c.value == code(7)) != machine_.x_diameter)
                        fail(fmt::format("{}: machine {} {}", x.text, machine_.name,
                                         machine_.x_diameter ? "programs X as a diameter (G7)" : "programs X as a radius (G8)"));
                    x_mode_selected_ = true;
                    break;
                }
                case code(20): case code(21): set_group(k.units, c); break;
                case code(90): break;
                case code(91): fail(fmt::format("{} (incremental positions): camgen posts never write it", x.text));
                case code(94): set_group(k.feed_mode, c); break;
                case code(93): case code(95):
                    fail(fmt::format("{}: only feed per minute (G94) is read", x.text));
                case code(40): case code(41): case code(42): set_group(k.comp, c); break;
                case code(43): case code(49): set_group(k.length_offset, c); break;
                case code(98): case code(99): set_group(k.return_level, c); break;
                case code(4): set_group(k.dwell, c); break;
                case code(53): set_group(k.machine_coords, c); break;
                default:
                    if (work_offset_code(c.value)) {
                        set_group(k.work_offset, c);
                        break;
                    }
                    if (cycle_kind_of(c.value)) {
                        // (a dialect's own cycle of that code, not a drilling cycle: Fanuc T's G74 face grooving)
                        if (!canned_spec(c.value) && variant_code(k, x, c)) break;
                        if (!canned_spec(c.value)) {
                            std::vector<std::string> names;
                            for (const auto& s : machine_.drilling)
                                if (s.canned) names.push_back(s.name);
                            fail(fmt::format("{} is not a canned cycle of machine {} (it has: {})", x.text, machine_.name,
                                             names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
                        }
                        set_group(k.motion, c);
                        break;
                    }
                    if (!variant_code(k, x, c)) fail(fmt::format("unknown code {}", x.text));
            }
        } else if (x.letter == 'M') {
            Code c{code_of(x), &x};
            if (shared_m_code(c, k.m, "modal group")) continue;
            if (coolant_of(x)) {
                set_group(k.coolant, c);
                continue;
            }
            fail(fmt::format("unknown code {}", x.text));
        } else {
            w.add(x);
        }
    }
    return k;
}

void IsoReader::block(const Block& b) {
    if (ended_) fail("a block after the end of the program");
    if (b.words.front().letter == 'O') {
        if (b.words.size() != 1) fail("the program number O.. must stand alone on its line");
        (void)integer_of(b.words.front());
        ++program_numbers_;
        return;
    }
    BlockWords w(*this, address_letters());
    const BlockCodes k = block_codes(b, w);

    // In the order of RS274/NGC: feed, speed, tool, tool change, spindle, dwell, modes, motion, stop.
    if (k.feed_mode && feed_mode_of(*k.feed_mode->word)) set_feed_mode(*feed_mode_of(*k.feed_mode->word));
    if (!f_is_lead(k.motion ? k.motion->value : motion_))
        if (const Word* f = w.take('F')) set_feed(*f);
    variant_words(k, w);
    if (const Word* s = w.take('S')) spindle_speed(rpm(*s), k.m.spindle ? k.m.spindle->word : nullptr);
    const Word* t = w.take('T');
    if (t && variant_tool_call(*t)) t = nullptr;
    if (pauses_for_tools()) refuse_tool_words(t, k);
    if (t) selected_tool_ = integer_of(*t);
    bool tool_pause = false;
    if (k.m.stop && k.m.stop->value == code(0) && pauses_for_tools() && pending_insert_) {
        // GRBL: the spindle is off; the operator changes the tool the comment names.
        change_tool(pending_insert_->number, pending_insert_->description);
        pending_insert_.reset();
        tool_pause = true;
    }
    if (k.m.tool_change) {
        if (!selected_tool_) fail("M6 without a tool number T");
        change_tool(*selected_tool_, commented_description(*selected_tool_));
    }
    if (k.m.spindle) switch_spindle(*k.m.spindle->word, "S");
    if (k.coolant) emit(Coolant{*coolant_of(*k.coolant->word), ""});
    if (k.work_offset) select_work_offset(k.work_offset->value, *k.work_offset->word, w);
    if (k.dwell) {
        const Word* p = w.take('P');
        if (!p) fail(fmt::format("{} without its time P", k.dwell->word->text));
        emit(Dwell{seconds(*p)});
    }
    if (k.plane) {
        const Plane p = k.plane->value == code(17) ? Plane::xy : k.plane->value == code(18) ? Plane::xz : Plane::yz;
        // rs274 changes the plane before it reads the block's G40: a change under G41/G42 is refused.
        if (comp_on_ && p != plane_)
            fail(fmt::format("{}: cannot change planes with cutter radius compensation on (G41/G42 in force)",
                             k.plane->word->text));
        plane_ = p;
    }
    if (k.units) set_units(k.units->value == code(20) ? Units::inch : Units::mm);
    if (k.comp) {
        comp_on_ = k.comp->value != code(40);
        if (k.comp->value == code(40)) {
            emit(Compensation{CompensationSide::off});
        } else {
            check_comp_plane(*k.comp->word);
            if (!machine_.cutter_compensation)
                fail(fmt::format("{}: machine {} has no cutter radius compensation (its cutterCompensation is false)",
                                 k.comp->word->text, machine_.name));
            const Word* d = w.take('D');
            const CompensationSide side = k.comp->value == code(41) ? CompensationSide::left : CompensationSide::right;
            // A lathe's G41/G42 (nose-radius compensation) take the tool's own table entry or
            // offset (LinuxCNC: the tool table's D and Q; Fanuc T: the offset of T0101 with its
            // R and T): no D word, register 0 = the tool's number.
            // LinuxCNC's mill G41/G42 without D takes the radius of the tool in the spindle
            // (compensationWithoutD; rs274 offsets by the loaded tool's table diameter).
            if (!d && (machine_.kind == MachineKind::lathe || settings_.compensation_without_d)) emit(Compensation{side, 0});
            else if (!d) fail(fmt::format("{} without its offset number D", k.comp->word->text));
            // The radius is the control's, in its offset register D (trace_program applies it).
            else emit(Compensation{side, integer_of(*d)});
        }
    }
    if (k.length_offset && k.length_offset->value == code(43)) {
        if (!settings_.length_offset_h)
            fail(fmt::format("{}: machine {} takes no tool length offset from a table (its lengthOffsetH is false)",
                             k.length_offset->word->text, machine_.name));
        const Word* h = w.take('H');
        if (!h) fail(fmt::format("{} without its offset number H", k.length_offset->word->text));
        length_offset_ = fmt::format("G43 H{}", integer_of(*h));
        select_length_offset(length_offset_);
    } else if (k.length_offset) {
        length_offset_ = "G49";
        select_length_offset("");
    }
    if (k.return_level && !settings_.return_levels)
        fail(fmt::format("{}: machine {} has no canned cycle return levels (its returnLevels is false)",
                         k.return_level->word->text, machine_.name));
    if (k.return_level) g98_ = k.return_level->value == code(98);
    if (k.motion) {
        if (k.motion->value == code(80)) {
            drill_end();
            cycle_r_.reset();
            cycle_z_.reset();
            cycle_q_.reset();
            cycle_p_.reset();
            initial_z_.reset();
        }
        motion_ = k.motion->value;
    }
    if (k.machine_coords) {
        // G53 G0 Z0: the machine's safe retract (frame safeRetract), the only G53 move camgen writes.
        if (machine_.frame.safe_retract.empty())
            fail(fmt::format("{}: machine {} has no safe retract in machine coordinates", k.machine_coords->word->text, machine_.name));
        const Word* z = w.take('Z');
        const bool rapid = (k.motion ? k.motion->value : motion_) == code(0);
        if (!z || z->value != 0.0 || w.has('X') || w.has('Y') || !rapid)
            fail(fmt::format("{}: camgen writes G53 only as G53 G0 Z0, the machine's safe retract", k.machine_coords->word->text));
        drill_end();
        initial_z_.reset();
        retract_to_top();
    }
    bool axes = w.has('X') || w.has('Y') || w.has('Z') || w.has('I') || w.has('J') || w.has('K') || w.has('R') ||
                w.has('Q') || w.unused('P');
    if (w.has('X') && !x_mode_selected_) {
        // LinuxCNC powers up in radius mode (G8) and keeps the mode of the program before: X
        // means what the start block's G7/G8 says only once it is read.
        const auto& start = machine_.frame.start_block;
        for (const char* mode : {"G7", "G8"})
            if (std::find(start.begin(), start.end(), mode) != start.end())
                fail(fmt::format("X before {}: machine {} programs X as a {} from its start block's {} (LinuxCNC powers "
                                 "up in radius mode, G8, and keeps the last program's)",
                                 mode, machine_.name, machine_.x_diameter ? "diameter" : "radius", mode));
        x_mode_selected_ = true;  // the machine selects no mode: X is as its xDiameterProg says
    }
    if (axes && !k.machine_coords) {
        if (motion_ < 0 || motion_ == code(80))
            fail(motion_ < 0 ? "coordinates before any motion code (G0, G1, ...)" : "coordinates after G80 without a motion code");
        motion_block(motion_, w);
    }
    w.require_all_used();
    if (k.m.stop && (k.m.stop->value == code(0) || k.m.stop->value == code(1)) && !tool_pause) {
        // A stop for the operator, its message the block's comment.
        if (k.m.stop->value == code(1) && !settings_.stop.optional_stop)
            fail(fmt::format("M1: machine {} ignores M1 (it has no optional stop switch), so the program would not stop "
                             "there; camgen writes M0",
                             machine_.name));
        std::string message;
        for (const std::string& c : b.comments) message += (message.empty() ? "" : " ") + c;
        if (message.rfind(iso::msg_prefix, 0) == 0) {
            message.erase(0, iso::msg_prefix.size());
            message.erase(0, message.find_first_not_of(' ') == std::string::npos ? message.size() : message.find_first_not_of(' '));
        }
        stop(k.m.stop->value == code(1) ? StopKind::optional : StopKind::mandatory, std::move(message));
    }
    if (k.m.stop && (k.m.stop->value == code(2) || k.m.stop->value == code(30))) {
        drill_end();
        ended_ = true;
    }
}

void IsoReader::motion_block(int mode, BlockWords& w) {
    if (cycle_kind_of(mode) && canned_spec(mode)) {
        cycle_block(mode, w);
        return;
    }
    if (mode == code(iso::rigid_tap_code)) {
        rigid_tap(w);
        return;
    }
    drill_end();
    if (variant_motion(mode, w)) return;
    initial_z_.reset();
    if (std::optional<ArcWords> a = move_or_arc(mode, plane_, w)) {
        a->r = w.length('R');
        if (const Word* pw = w.take('P')) {
            if (!settings_.arc_turns)
                fail(fmt::format("{} on an arc: machine {} takes no number of turns (its arcTurns is false)", pw->text,
                                 machine_.name));
            // P on an arc: the number of turns (LinuxCNC), 1 for a plain arc.
            int p = integer_of(*pw);
            if (p < 1) fail(fmt::format("{}: an arc makes at least one turn", pw->text));
            a->turns = p - 1;
        }
        arc(*a);
    }
}

void IsoReader::cycle_block(int g, BlockWords& w) {
    const DrillingCycleSpec& spec = *canned_spec(g);
    if (variant_cycle(spec, w)) return;
    if (spec.style == CannedStyle::fanuc_g74)
        fail(fmt::format("{}: Fanuc T's end-face peck drilling is read by the iso-lathe dialect only", spec.name));
    const std::string name = spec.name;
    if (w.has('I') || w.has('J') || w.has('K')) fail(fmt::format("I/J/K in a {} block", name));
    if (!position_known()) fail(fmt::format("{} from an unknown position", name));
    check_cycle_plane(name);
    Vec3 here = position();
    if (!initial_z_) initial_z_ = here.z;
    std::optional<double> x, y;
    if (const Word* v = w.take('X')) x = length(*v);
    if (const Word* v = w.take('Y')) y = length(*v);
    if (const Word* v = w.take('Z')) cycle_z_ = length(*v);
    if (const Word* v = w.take('R')) cycle_r_ = length(*v);
    bool pecks = spec.kind == CycleKind::deep || spec.kind == CycleKind::chip_break;
    if (const Word* v = w.take('Q')) {
        if (!pecks || !has_field(spec, DrillField::first_depth))
            fail(fmt::format("{}: {} on machine {} takes no peck depth Q", v->text, name, machine_.name));
        cycle_q_ = length(*v);
    }
    if (const Word* v = w.take('P')) {
        if (!has_field(spec, DrillField::bottom_dwell))
            fail(fmt::format("{}: {} on machine {} takes no dwell P", v->text, name, machine_.name));
        cycle_p_ = seconds(*v);
    }
    if (!cycle_z_) fail(fmt::format("{} without its depth Z", name));
    if (!cycle_r_) fail(fmt::format("{} without its R plane", name));
    if (!(*cycle_z_ < *cycle_r_)) fail(fmt::format("{}: the bottom Z is not below R", name));
    if (!feed_) fail(fmt::format("{} without a feed F", name));
    DrillCycle c;
    c.kind = spec.kind;
    c.safe_z = *cycle_r_;
    c.reference_z = *cycle_r_;
    // G98: back to the Z the tool had before the first cycle block (if above R); G99: to R.
    c.retract_z = g98_ ? std::max(*initial_z_, *cycle_r_) : *cycle_r_;
    c.bottom_z = *cycle_z_;
    c.feed = *feed_;
    c.spindle_rpm = rpm_;
    DrillValues& p = c.values;
    c.output = CycleOutput::canned;
    if (pecks) {
        if (!cycle_q_) fail(fmt::format("{} without its peck depth Q", name));
        if (!(*cycle_q_ > 0)) fail(fmt::format("{}: the peck depth Q must be > 0", name));
        p.set(DrillField::first_depth, *cycle_q_);
    }
    if (cycle_p_ && has_field(spec, DrillField::bottom_dwell) && *cycle_p_ > 0) p.set(DrillField::bottom_dwell, *cycle_p_);
    if (spec.kind == CycleKind::tap || spec.kind == CycleKind::tap_left) {
        // A tap's feed is pitch x spindle speed.
        if (!(rpm_ > 0)) fail(fmt::format("{} without a spindle speed S", name));
        // G84/G74 tap in with the spindle as it runs (rs274 refuses "Spindle turning clockwise in
        // G74", "... counterclockwise in G84", "Spindle not turning in G74"): the posts write M4
        // before G74.
        const bool left = spec.kind == CycleKind::tap_left;
        if (spindle_ == SpindleState::off)
            fail(fmt::format("{} with the spindle off: the cycle taps with the running spindle ({})", name,
                             left ? "M4 for a left-hand tap" : "M3"));
        // A tap against its thread is the control's to refuse (LinuxCNC does; Fanuc's answer is
        // unconfirmed): with --job it is the program's first difference (MISMATCH), not a read error.
        if ((spindle_ == SpindleState::cw) == left)
            throw ControlRefusal("", fmt::format("{} with the spindle turning {}: the cycle taps with the running spindle, so the tap would "
                             "go in turning the wrong way ({} needs {})",
                             name, left ? "clockwise (M3)" : "counterclockwise (M4)",
                             left ? "a left-hand tap" : "a right-hand tap", left ? "M4" : "M3"),
                                 line_, source_);
        c.spindle_direction = left ? SpindleDirection::ccw : SpindleDirection::cw;
        p.set(DrillField::pitch, *feed_ / rpm_);
    } else {
        p.set(DrillField::plunging_feedrate, *feed_);
    }
    if (!current_cycle() || !(*current_cycle() == c)) drill_cycle(c);
    drill_point({x.value_or(here.x), y.value_or(here.y)});
}

void IsoReader::rigid_tap(BlockWords& w) {
    // LinuxCNC G33.1 Z K: from where the tool stands, in to Z synchronised with the spindle
    // (feed = pitch K x speed), spindle reversed, out to the start Z, the spindle's direction
    // restored. Tapping left-hand under M4 is the same cycle the other way round. It is read
    // as the tap the posts would write longhand from that Z.
    for (char letter : {'X', 'Y', 'I', 'J', 'R', 'Q', 'P'})
        if (const Word* x = w.find(letter))
            fail(fmt::format("{} on G33.1: camgen positions the hole with G0 and taps along Z only", x->text));
    const Word* zw = w.take('Z');
    const Word* kw = w.take('K');
    if (!zw || !kw) fail("G33.1 needs the hole bottom Z and the pitch K");
    if (!position_known()) fail("G33.1 from an unknown position");
    const double bottom = length(*zw), pitch = length(*kw);
    const Vec3 here = position();
    if (!(pitch > 0)) fail(fmt::format("{}: the pitch must be > 0", kw->text));
    if (!(bottom < here.z)) fail(fmt::format("G33.1 {}: the bottom is not below the start Z", zw->text));
    if (spindle_ == SpindleState::off || !(rpm_ > 0)) fail("G33.1 with the spindle off: rigid tapping follows the spindle");
    DrillCycle c;
    c.kind = spindle_ == SpindleState::cw ? CycleKind::tap : CycleKind::tap_left;
    c.retract_z = c.reference_z = c.safe_z = here.z;
    c.bottom_z = bottom;
    c.feed = pitch * rpm_;
    c.spindle_rpm = rpm_;
    c.spindle_direction = spindle_ == SpindleState::cw ? SpindleDirection::cw : SpindleDirection::ccw;
    DrillValues& p = c.values;
    c.output = CycleOutput::canned;
    p.set(DrillField::pitch, pitch);
    drill_cycle(c);
    drill_point({here.x, here.y});
    drill_end();
}

bool IsoReader::variant_code(BlockCodes&, const Word&, Code) { return false; }

bool IsoReader::variant_motion(int, BlockWords&) { return false; }

bool IsoReader::f_is_lead(int) const { return false; }

void IsoReader::variant_words(const BlockCodes&, BlockWords&) {}

bool IsoReader::variant_tool_call(const Word&) { return false; }

bool IsoReader::variant_cycle(const DrillingCycleSpec&, BlockWords&) { return false; }

void IsoReader::check_comp_plane(const Word& g) const {
    // The control compensates in one plane: camgen's mill posts in XY (G17), its lathe posts in XZ
    // (G18). rs274 refuses a lathe tool's G41/G42 outside G18 and any outside XY and XZ, and offsets a
    // mill's in XZ under G18: camgen reads neither.
    const bool lathe = machine_.kind == MachineKind::lathe;
    if (lathe && plane_ != Plane::xz)
        fail(fmt::format("{} with lathe tool, but plane is not G18 (it is {})", g.text, plane_ == Plane::xy ? "G17" : "G19"));
    if (!lathe && plane_ != Plane::xy)
        fail(fmt::format("{} under {}: the control would offset the tool in the {} plane; camgen reads cutter radius "
                         "compensation in the XY plane (G17) only",
                         g.text, plane_ == Plane::xz ? "G18" : "G19", plane_ == Plane::xz ? "XZ" : "YZ"));
}

void IsoReader::check_cycle_plane(const std::string& name) const {
    // A canned cycle drills along the plane's normal (rs274: G18 G83 drills along Y, G19 G81 along
    // X): only G17 drills along Z, on a lathe (its axis) and on a mill (camgen's posts drill only
    // under G17).
    if (plane_ != Plane::xy)
        fail(fmt::format("{} under {}: it would drill along {} ({})", name, plane_ == Plane::xz ? "G18" : "G19",
                         plane_ == Plane::xz ? "Y" : "X",
                         machine_.kind == MachineKind::lathe ? "a lathe drills on its axis under G17"
                                                             : "camgen reads a drilling cycle along Z, under G17, only"));
}

std::unique_ptr<NcReader> make_iso_reader(const Machine& machine, std::string source) {
    return std::make_unique<IsoReader>(machine, std::move(source), settings_of<iso::Settings>(machine));
}

}  // namespace camgen::reader
