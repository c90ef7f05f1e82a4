#include "src/reader/nc_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "camgen/geometry/vec.hpp"
#include "camgen/common/error.hpp"
#include "camgen/common/number_text.hpp"
#include "camgen/post/longhand.hpp"

namespace camgen::reader {

namespace {

bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

const char* plane_name(Plane p) { return p == Plane::xy ? "XY" : p == Plane::xz ? "XZ" : "YZ"; }

// Half a unit of the last decimal a format writes, in the units the value had before scaling.
double half_unit(const nc::Format& f) { return 0.5 * std::pow(10.0, -f.spec().decimals) / f.spec().scale; }

}  // namespace

NcReader::NcReader(const Machine& machine, std::string source) : machine_(machine), source_(std::move(source)) {
    load_formats();
    forget_position();
}

void NcReader::load_formats() {
    xyz_ = machine_.format("xyz");
    ijk_ = machine_.format("ijk");
    feed_fmt_ = machine_.format("feed");
    rpm_fmt_ = machine_.format("rpm");
    dwell_fmt_ = machine_.format("dwell");
    angle_fmt_ = machine_.format("angle");
    x_ = machine_.format("x");
    z_ = machine_.format("z");
    i_ = machine_.format("i");
    feed_rev_fmt_ = machine_.format("feedPerRev");
}

const nc::Format& NcReader::length_format(char letter) const { return letter == 'X' ? x_ : letter == 'Z' ? z_ : xyz_; }

const nc::Format& NcReader::offset_format(char letter) const { return letter == 'I' ? i_ : ijk_; }

void NcReader::set_units(Units units) {
    if (machine_.units == units) return;
    if (!machine_.accepts(units))
        fail(fmt::format("a switch to {}: machine {} has no {} mode (its control accepts: {})", name_of(unit_names, units),
                         machine_.name, name_of(unit_names, units), machine_.accepted_unit_names()));
    machine_.units = units;
    load_formats();
    ReadResolution r = resolution();
    coarsest_ = {std::max(coarsest_.position, r.position), std::max(coarsest_.offset, r.offset),
                 std::max(coarsest_.angle, r.angle),       std::max(coarsest_.feed, r.feed),
                 std::max(coarsest_.rpm, r.rpm),           std::max(coarsest_.dwell, r.dwell)};
}

ReadResolution NcReader::resolution() const {
    ReadResolution r;
    r.position = half_unit(xyz_);
    r.offset = half_unit(ijk_);
    r.angle = half_unit(angle_fmt_);
    r.feed = half_unit(feed_fmt_);
    r.rpm = half_unit(rpm_fmt_);
    r.dwell = half_unit(dwell_fmt_);
    return r;
}

bool NcReader::message_code(const Word&) const { return false; }

bool NcReader::dotted_word(char) const { return false; }

bool NcReader::named_word(std::string_view) const { return false; }

void NcReader::finish() { drill_end(); }

void NcReader::fail(const std::string& detail) const { throw InputError("", detail, line_, source_); }

void NcReader::emit(Event event, bool from_unknown, double uncertainty, Approach approach) {
    const bool feed_move = std::holds_alternative<Linear>(event) || std::holds_alternative<Arc>(event) ||
                           std::holds_alternative<DrillPoint>(event);
    ReadEvent e{std::move(event), line_, from_unknown, uncertainty, approach};
    if (feed_move && feed_per_rev_) e.per_revolution = *feed_per_rev_;
    e.offsets = offsets_;
    sink_->read_event(e);
}

// ---- words ----

double NcReader::length(const Word& w) const {
    const nc::FormatSpec& s = length_format(w.letter).spec();
    if (s.force_decimal && s.decimals > 0 && !w.has_point)
        fail(fmt::format("{} has no decimal point: machine {} always writes one, and a Fanuc-style control "
                         "reads {} as {} {}", w.text, machine_.name, w.text,
                         number_text(w.value * std::pow(10.0, -s.decimals), std::max(s.decimals, 4)),
                         machine_.units == Units::inch ? "inch" : "mm"));
    return w.value / s.scale;
}

double NcReader::offset(const Word& w) const {
    const nc::FormatSpec& s = offset_format(w.letter).spec();
    if (s.force_decimal && s.decimals > 0 && !w.has_point)
        fail(fmt::format("{} has no decimal point: machine {} always writes one", w.text, machine_.name));
    return w.value / s.scale;
}

double NcReader::feed(const Word& w) const {
    if (!(w.value > 0)) fail(fmt::format("{}: a feed must be > 0", w.text));
    return w.value / feed_fmt_.spec().scale;
}

double NcReader::rpm(const Word& w) const {
    if (w.value < 0) fail(fmt::format("{}: a spindle speed must be >= 0", w.text));
    return w.value / rpm_fmt_.spec().scale;
}

double NcReader::seconds(const Word& w) const {
    if (w.value < 0) fail(fmt::format("{}: a dwell must be >= 0", w.text));
    return w.value / dwell_fmt_.spec().scale;
}

double NcReader::angle(const Word& w) const { return w.value / angle_fmt_.spec().scale; }

double NcReader::length_value(double written) const { return written / xyz_.spec().scale; }

double NcReader::feed_value(double written) const { return written / feed_fmt_.spec().scale; }

double NcReader::seconds_value(double written) const { return written / dwell_fmt_.spec().scale; }

double NcReader::rpm_value(double written) const { return written / rpm_fmt_.spec().scale; }

int NcReader::code_of(const Word& w) const {
    // No control has codes beyond G/M 9999; a larger number would not fit the tenths in an int.
    if (!(std::abs(w.value) < 10000.0)) fail(fmt::format("{} is not a code", w.text));
    int c = code(w.value);
    if (std::abs(w.value * 10.0 - c) > 1e-6) fail(fmt::format("{} is not a code", w.text));
    return c;
}

int NcReader::integer_of(const Word& w) const {
    if (w.value < 0 || w.value != std::floor(w.value) || w.value > 1e9)
        fail(fmt::format("{}: expected a whole number", w.text));
    return static_cast<int>(w.value);
}

std::optional<double> NcReader::parse_number(std::string_view text) const {
    std::string t(trim(text));
    if (t.empty()) return std::nullopt;
    for (char& c : t) {
        if (c == machine_.decimal_mark) c = '.';
        else if (c == '.' || c == ',') return std::nullopt;
    }
    double v = 0.0;
    const char* b = t.data();
    if (*b == '+') ++b;
    auto [p, ec] = std::from_chars(b, t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size()) return std::nullopt;
    return v;
}

namespace {
// A G code in tenths as the posts write it: "G54", "G59.1".
std::string g_word(int g) { return g % 10 ? fmt::format("G{}.{}", g / 10, g % 10) : fmt::format("G{}", g / 10); }
}  // namespace

bool NcReader::work_offset_code(int g) const {
    const std::string word = g_word(g);
    for (const std::string& o : machine_.frame.work_offsets)
        if (o == word || o.rfind(word + " P", 0) == 0) return true;
    return false;
}

void NcReader::select_work_offset(int g, const Word& text, BlockWords& w) {
    std::string word = g_word(g);
    if (!machine_.has_work_offset(word)) {
        const Word* p = w.take('P');
        if (!p) fail(fmt::format("{} without its offset number P", text.text));
        word += fmt::format(" P{}", integer_of(*p));
        if (!machine_.has_work_offset(word)) fail(fmt::format("{}: machine {} has no work offset {}", word, machine_.name, word));
    }
    work_offset_ = word;
    offsets_.work = OffsetWord(word);
    offsets_.work_line = line_;
}

void NcReader::select_length_offset(std::string_view description) {
    offsets_.length = OffsetWord(description);
    offsets_.length_line = line_;
}

std::optional<FeedMode> NcReader::feed_mode_of(const Word& g) const {
    for (const auto& [mode, c] : machine_.frame.feed_modes)
        if (c == g.text || (c.size() > 1 && c[0] == 'G' && parse_number(c.substr(1)) == g.value)) return mode;
    return std::nullopt;
}

void NcReader::set_feed_mode(FeedMode mode) {
    if (mode == feed_mode_) return;
    // RS274: a new feed mode needs a new F before the next feed move.
    feed_mode_ = mode;
    feed_.reset();
    feed_per_rev_.reset();
}

void NcReader::set_feed(const Word& f) {
    if (feed_mode_ == FeedMode::per_minute) {
        feed_ = feed(f);
        return;
    }
    if (!(f.value > 0)) fail(fmt::format("{}: a feed must be > 0", f.text));
    feed_per_rev_ = f.value / feed_rev_fmt_.spec().scale;
    feed_ = *feed_per_rev_ * rpm_;
}

std::optional<CoolantMode> NcReader::coolant_of(const Word& m) const {
    for (const auto& [mode, c] : machine_.frame.coolant)
        if (c == m.text || (c.size() > 1 && c[0] == 'M' && parse_number(c.substr(1)) == m.value)) return mode;
    return std::nullopt;
}

double NcReader::diameter_in(std::string_view description) {
    size_t mm = description.find(" mm ");
    if (mm == std::string_view::npos) mm = description.find(" mm");
    if (mm == std::string_view::npos || mm == 0) return 0.0;
    std::string_view number = description.substr(0, mm);
    double v = 0.0;
    auto [p, ec] = std::from_chars(number.data(), number.data() + number.size(), v);
    return ec == std::errc() && p == number.data() + number.size() && v > 0 ? v : 0.0;
}

void NcReader::set_group(std::optional<Code>& group, Code c, std::string_view group_name) const {
    if (group)
        fail(fmt::format("{} and {} in one block: they belong to the same {}", group->word->text, c.word->text, group_name));
    group = c;
}

bool NcReader::shared_m_code(Code c, MCodes& m, std::string_view group_name) const {
    switch (c.value) {
        case code(3): case code(4): case code(5): set_group(m.spindle, c, group_name); return true;
        case code(6): set_group(m.tool_change, c, group_name); return true;
        case code(0): case code(1): case code(2): case code(30): set_group(m.stop, c, group_name); return true;
        default: return false;
    }
}

std::string NcReader::commented_description(int tool) const {
    std::string prefix = fmt::format("T{} ", tool);
    return last_comment_.rfind(prefix, 0) == 0 ? last_comment_.substr(prefix.size()) : std::string();
}

void NcReader::stop(StopKind kind, std::string message) {
    drill_end();
    emit(Stop{kind, std::move(message)});
    forget_position();
}

std::vector<std::pair<std::string, std::string>> NcReader::modal_state() const {
    auto number = [](double v) { return fmt::format("{}", v); };
    const char* axes = "XYZ";
    std::string known;
    for (int i = 0; i < 3; ++i)
        if (known_[static_cast<std::size_t>(i)]) known += axes[i];
    std::vector<std::pair<std::string, std::string>> s{{"units", std::string(name_of(unit_names, machine_.units))},
            {"feed mode", std::string(name_of(feed_modes, feed_mode_))},
            {"work offset", work_offset_.empty() ? "none" : work_offset_},
            {"spindle speed", number(rpm_) + " rpm"},
            {"spindle", spindle_ == SpindleState::off ? "off" : spindle_ == SpindleState::cw ? "clockwise" : "counter-clockwise"},
            {"tool", std::to_string(tool_)},
            {"axes whose position is known", known.empty() ? "none" : known},
            {"safe height", at_top_ ? "at the machine's safe height" : "-"},
            {"drilling cycle", cycle_ ? std::string(name_of(cycle_kinds, cycle_->kind)) : "none"}};
    // Only under G96, so that the state of every other program reads as before.
    if (surface_mode_) s.emplace_back("surface speed", number(surface_speed_) + " m/min (G96)");
    return s;
}

void NcReader::change_tool(int tool, const std::string& description) {
    drill_end();
    tool_ = tool;
    emit(ToolChange{tool_, diameter_in(description), description});
    forget_position();
}

void NcReader::spindle_speed(double rpm, const Word* switch_code) {
    if (surface_mode_) {
        // Under G96 S is the surface speed: m/min, or ft/min in inch.
        surface_speed_ = machine_.units == Units::inch ? rpm * 0.3048 : rpm;
        if (!(surface_speed_ > 0)) fail("a surface speed S under G96 must be > 0");
    } else {
        rpm_ = rpm;
    }
    if (feed_per_rev_) feed_ = *feed_per_rev_ * rpm_;
    if (!switch_code && spindle_ != SpindleState::off) emit(Spindle{spindle_, rpm_, surface_mode_ ? surface_speed_ : 0.0});
}

void NcReader::constant_surface_speed(double limit) {
    if (!(limit > 0)) fail("a spindle limit under G96 must be > 0");
    surface_mode_ = true;
    rpm_ = limit;
    if (feed_per_rev_) feed_ = *feed_per_rev_ * rpm_;
}

void NcReader::constant_rpm() { surface_mode_ = false; }

void NcReader::spindle_limit(double limit) {
    if (!surface_mode_) return;
    rpm_ = limit;
    if (feed_per_rev_) feed_ = *feed_per_rev_ * rpm_;
    if (spindle_ != SpindleState::off) emit(Spindle{spindle_, rpm_, surface_speed_});
}

void NcReader::switch_spindle(const Word& m, std::string_view speed_word) {
    const int c = code_of(m);
    if (c == code(5)) {
        spindle_ = SpindleState::off;
        emit(Spindle{SpindleState::off, 0.0});
        return;
    }
    if (!(rpm_ > 0)) fail(fmt::format("{} without a spindle speed {}", m.text, speed_word));
    if (surface_mode_ && !(surface_speed_ > 0)) fail(fmt::format("{} under G96 without a surface speed {}", m.text, speed_word));
    spindle_ = c == code(3) ? SpindleState::cw : SpindleState::ccw;
    emit(Spindle{spindle_, rpm_, surface_mode_ ? surface_speed_ : 0.0});
}

// ---- block words ----

void NcReader::BlockWords::add(const Word& w) {
    if (w.letter == 0 || letters_.find(w.letter) == std::string_view::npos)
        reader_.fail(fmt::format("unknown word {}", w.text));
    if (words_.count(w.letter)) reader_.fail(fmt::format("two {} words in one block", w.letter));
    words_[w.letter] = Entry{&w, false};
}

const Word* NcReader::BlockWords::take(char letter) {
    auto it = words_.find(letter);
    if (it == words_.end()) return nullptr;
    it->second.used = true;
    return it->second.word;
}

std::optional<double> NcReader::BlockWords::length(char letter) {
    const Word* w = take(letter);
    return w ? std::optional<double>(reader_.length(*w)) : std::nullopt;
}

std::optional<double> NcReader::BlockWords::offset(char letter) {
    const Word* w = take(letter);
    return w ? std::optional<double>(reader_.offset(*w)) : std::nullopt;
}

const Word* NcReader::BlockWords::find(char letter) const {
    auto it = words_.find(letter);
    return it == words_.end() ? nullptr : it->second.word;
}

bool NcReader::BlockWords::unused(char letter) const {
    auto it = words_.find(letter);
    return it != words_.end() && !it->second.used;
}

void NcReader::BlockWords::require_all_used() const {
    for (const auto& [letter, entry] : words_)
        if (!entry.used) reader_.fail(fmt::format("{} has no meaning in this block", entry.word->text));
}

// ---- blocks ----

Block NcReader::split(std::string_view line) const {
    Block b;
    b.line = line_;
    const nc::BlockStyle& style = machine_.block;
    const std::string& sep = style.separator;
    bool sep_is_text = !sep.empty() && !is_blank(sep[0]);
    const char mark = machine_.decimal_mark;
    size_t i = 0, n = line.size();
    while (i < n) {
        char c = line[i];
        if (is_blank(c)) {
            ++i;
            continue;
        }
        if (sep_is_text && line.compare(i, sep.size(), sep) == 0) {
            i += sep.size();
            continue;
        }
        if (c == '(' && style.comment_style == nc::CommentStyle::parentheses) {
            size_t close = line.find(')', i + 1);
            if (close == std::string_view::npos) fail("a comment '(' without its ')'");
            std::string_view text = line.substr(i + 1, close - i - 1);
            if (text.find('(') != std::string_view::npos) fail("'(' inside a comment");
            b.comments.emplace_back(trim(text));
            i = close + 1;
            continue;
        }
        if (c == ';' && style.comment_style == nc::CommentStyle::semicolon) {
            b.comments.emplace_back(trim(line.substr(i + 1)));
            break;
        }
        if (!is_letter(c)) {
            const char* expect = style.comment_style == nc::CommentStyle::parentheses ? "comments are (...)" : "comments start with ';'";
            fail(fmt::format("unexpected character '{}' ({})", c, expect));
        }
        Word w;
        w.letter = static_cast<char>(c >= 'a' ? c - 'a' + 'A' : c);
        size_t start = i;
        if (size_t eq = line.find('=', i); eq != std::string_view::npos && eq > i + 1 &&
                                           std::all_of(line.begin() + i, line.begin() + eq, is_letter) &&
                                           named_word(line.substr(i, eq - i))) {
            w.name = std::string(line.substr(i, eq - i));
            w.letter = 0;
            i = eq;  // the '=' is skipped below like a letter
        }
        ++i;
        while (i < n && is_blank(line[i])) ++i;  // a format with a width pads with spaces
        std::string number;
        const char point_mark = dotted_word(w.letter) ? '.' : mark;
        if (i < n && (line[i] == '+' || line[i] == '-')) number += line[i++];
        int digits = 0;
        while (i < n) {
            if (is_digit(line[i])) {
                number += line[i];
                ++digits;
            } else if (line[i] == point_mark && !w.has_point) {
                number += '.';
                w.has_point = true;
            } else {
                break;
            }
            ++i;
        }
        w.text = std::string(line.substr(start, i - start));
        if (digits == 0) fail(fmt::format("word {} without a number", w.text));
        if (i < n && (line[i] == '.' || line[i] == ',') && line[i] != point_mark)
            fail(fmt::format("{}{}...: machine {} writes '{}' as its decimal mark", w.text, line[i], machine_.name, mark));
        const char* first = number.data() + (number[0] == '+' ? 1 : 0);
        auto [p, ec] = std::from_chars(first, number.data() + number.size(), w.value);
        if (ec != std::errc()) fail(fmt::format("{} is not a number that fits", w.text));
        if (w.value == 0.0) w.value = 0.0;  // no -0
        b.words.push_back(std::move(w));
        if (message_code(b.words.back())) {
            std::string_view rest = line.substr(i);
            if (style.comment_style == nc::CommentStyle::semicolon) {
                if (size_t semi = rest.find(';'); semi != std::string_view::npos) {
                    b.comments.emplace_back(trim(rest.substr(semi + 1)));
                    rest = rest.substr(0, semi);
                }
            }
            b.message = std::string(trim(rest));
            b.has_message = true;
            break;
        }
    }
    return b;
}

void NcReader::read(std::string_view text, ReadEventSink& sink) {
    start(sink);
    size_t pos = 0;
    while (pos < text.size()) {
        size_t nl = text.find('\n', pos);
        read_line(text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos));
        pos = nl == std::string_view::npos ? text.size() : nl + 1;
    }
    finish();
}

void NcReader::start(ReadEventSink& sink) {
    sink_ = &sink;
    coarsest_ = resolution();
    line_ = 0;
}

void NcReader::read_line(std::string_view line) {
    ++line_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    std::string_view t = trim(line);
    if (t.empty() || frame_line(t)) return;
    this->line(line);
}

Block NcReader::split_line(std::string_view text) {
    Block b = split(text);
    // A sequence number leads the block; it says nothing about motion.
    const std::string& seq = machine_.block.sequence_prefix;
    if (!b.words.empty() && seq.size() == 1 && b.words.front().letter == seq[0]) {
        (void)integer_of(b.words.front());
        b.words.erase(b.words.begin());
    }
    return b;
}

void NcReader::emit_comments(const Block& b) {
    for (const std::string& c : b.comments) {
        emit(Comment{c});
        last_comment_ = c;
    }
}

void NcReader::line(std::string_view text) {
    Block b = split_line(text);
    emit_comments(b);
    if (!b.words.empty() || b.has_message) block(b);
}

// ---- motion ----

void NcReader::forget_position() {
    // A lathe has no Y axis: its tool stays in the XZ plane (Y 0).
    const bool lathe = machine_.kind == MachineKind::lathe;
    known_ = {false, lathe, false};
    if (lathe) pos_[1] = 0.0;
    was_unknown_ = true;
    approach_ = Approach::z_first;
    at_top_ = false;
}

void NcReader::retract_to_top() {
    if (!was_unknown_) approach_ = Approach::z_first;  // a new stretch of unknown height begins
    known_[2] = false;
    was_unknown_ = true;
    at_top_ = true;
}

void NcReader::rapid_to(std::optional<double> x, std::optional<double> y, std::optional<double> z) {
    if (!x && !y && !z) return;
    bool was_known = position_known();
    Vec3 before = position();
    // X or Y moved while the height is unknown (before Z or in the same block as the first Z).
    if (was_unknown_ && (x || y) && !known_[2] && !at_top_) approach_ = Approach::xy_first;
    if (z) at_top_ = false;
    const std::optional<double>* axes[3] = {&x, &y, &z};
    for (int a = 0; a < 3; ++a)
        if (*axes[a]) {
            pos_[static_cast<size_t>(a)] = **axes[a];
            known_[static_cast<size_t>(a)] = true;
        }
    if (x && y) xy_uncertainty_ = 0.0;
    if (!position_known()) return;  // still partly unknown: the move cannot be traced yet
    if (was_known && before == position() && !was_unknown_) return;
    const bool from_unknown = was_unknown_ || !was_known;
    emit(Rapid{position()}, from_unknown, xy_uncertainty_, from_unknown ? approach_ : Approach::z_first);
    was_unknown_ = false;
}

void NcReader::linear_to(std::optional<double> x, std::optional<double> y, std::optional<double> z) {
    if (!x && !y && !z) return;
    if (!position_known())
        fail("a feed move from an unknown position (after a tool change or home run the first move must be a "
             "rapid that sets X, Y and Z)");
    if (!feed_) fail("a feed move without a feed (F)");
    Vec3 p = position();
    if (x) p.x = *x;
    if (y) p.y = *y;
    if (z) p.z = *z;
    pos_ = {p.x, p.y, p.z};
    if (x && y) xy_uncertainty_ = 0.0;
    emit(Linear{p, *feed_}, false, xy_uncertainty_);
}

void NcReader::thread_to(const std::string& name, std::optional<double> x, double z, const Word& lead, bool along_path) {
    if (!position_known()) fail(fmt::format("{} from an unknown position", name));
    if (spindle_ == SpindleState::off || !(rpm_ > 0))
        fail(fmt::format("{} with the spindle off: a thread-cutting move follows the spindle", name));
    double l = lead.value / feed_rev_fmt_.spec().scale;
    if (!(l > 0)) fail(fmt::format("{}: the lead must be > 0", lead.text));
    Vec3 p = position();
    if (x) {
        const double dx = std::abs(*x - p.x), dz = std::abs(z - p.z);
        if (dx > 1e-9 && !(dz > 0 && dx <= dz + 0.001))
            fail(fmt::format("{} steeper than 45 degrees from Z: camgen reads a taper's lead along Z only", name));
        if (along_path && dx > 1e-9) l *= dz / std::hypot(dx, dz);
        p.x = *x;
    }
    p.z = z;
    pos_ = {p.x, p.y, p.z};
    emit(ThreadFeed{p, l});
}

void NcReader::arc(const ArcWords& a) {
    const ArcSettings& s = machine_.arcs;
    if (std::find(s.planes.begin(), s.planes.end(), a.plane) == s.planes.end()) {
        std::vector<std::string> names;
        for (Plane p : s.planes) names.emplace_back(plane_name(p));
        fail(fmt::format("an arc in the {} plane: machine {} makes arcs only in {}", plane_name(a.plane), machine_.name,
                         names.empty() ? std::string("no plane") : fmt::format("{}", fmt::join(names, ", "))));
    }
    if (!position_known())
        fail("an arc from an unknown position (after a tool change or home run the first move must be a rapid)");
    if (!feed_) fail("an arc without a feed (F)");
    const ReadResolution res = resolution();
    Vec3 start = position(), end = start;
    if (a.x) end.x = *a.x;
    if (a.y) end.y = *a.y;
    if (a.z) end.z = *a.z;
    PlanePoint ps = to_plane(start, a.plane), pe = to_plane(end, a.plane);
    PlanePoint pc{0.0, 0.0, ps.w};
    bool ccw = a.direction == ArcDirection::ccw;
    // Which of I/J/K hold the plane's (u, v) centre coordinates (to_plane's axis order).
    const std::optional<double>* cu = a.plane == Plane::xy ? &a.i : a.plane == Plane::xz ? &a.k : &a.j;
    const std::optional<double>* cv = a.plane == Plane::xy ? &a.j : a.plane == Plane::xz ? &a.i : &a.k;
    const std::optional<double>* off_plane = a.plane == Plane::xy ? &a.k : a.plane == Plane::xz ? &a.j : &a.i;
    const char* cu_name = a.plane == Plane::xy ? "I" : a.plane == Plane::xz ? "K" : "J";
    const char* cv_name = a.plane == Plane::xy ? "J" : a.plane == Plane::xz ? "I" : "K";
    const char* off_name = a.plane == Plane::xy ? "K" : a.plane == Plane::xz ? "J" : "I";
    if (*off_plane) fail(fmt::format("{} on an arc in the {} plane", off_name, plane_name(a.plane)));

    if (a.d) {
        // nccad: G02 D<sweep> I J, the centre relative to the start; the control computes the end.
        if (a.plane != Plane::xy) fail("a D-form arc outside the XY plane");
        if (a.x || a.y) fail("a D-form arc with an end point: write either D or X and Y");
        if (a.z) fail("Z on a D-form arc: nccad cannot make a helix in this form");
        if (!a.i || !a.j) fail("a D-form arc needs both I and J");
        double d = *a.d;
        if (!(d > 0.0 && d <= 360.0)) fail(fmt::format("D{}: the sweep of an arc must be in (0, 360] degrees", d));
        pc = {ps.u + *a.i, ps.v + *a.j, ps.w};
        double r = std::hypot(ps.u - pc.u, ps.v - pc.v);
        if (r == 0.0) fail("a D-form arc of radius 0 (I0 J0)");
        double a0 = std::atan2(ps.v - pc.v, ps.u - pc.u);
        double a1 = a0 + (ccw ? 1.0 : -1.0) * d / deg_per_rad;
        pe = d >= 360.0 ? ps : PlanePoint{pc.u + r * std::cos(a1), pc.v + r * std::sin(a1), ps.w};
        // The control turns the rounded start about the rounded centre by the rounded angle:
        // the end may be off by twice the centre's rounding plus the angle's, beyond the start's.
        xy_uncertainty_ += 2.0 * std::numbers::sqrt2 * res.offset + r * res.angle / deg_per_rad;
    } else if (a.r) {
        if (*cu || *cv) fail("an arc with both R and a centre (I/J/K)");
        double du = pe.u - ps.u, dv = pe.v - ps.v, chord = std::hypot(du, dv);
        if (chord == 0.0) fail("an R arc whose end is its start: R cannot say a full circle");
        double r = std::abs(*a.r);
        double slack = machine_.tolerance + 2.0 * res.position;
        if (chord / 2.0 > r + slack)
            fail(fmt::format("R{}: the radius is smaller than half the distance to the end ({})", number_text(*a.r, 6),
                             number_text(chord / 2.0)));
        double h = std::sqrt(std::max(0.0, r * r - chord * chord / 4.0));
        // Sweeps up to 180 degrees (R > 0): counter-clockwise arcs have their centre on the
        // left of the chord, clockwise ones on the right; R < 0 means the other side.
        double side = (ccw ? 1.0 : -1.0) * (*a.r > 0 ? 1.0 : -1.0);
        pc = {(ps.u + pe.u) / 2.0 - side * h * dv / chord, (ps.v + pe.v) / 2.0 + side * h * du / chord, ps.w};
    } else {
        if (a.absolute_centre) {
            if (!*cu || !*cv)
                fail(fmt::format("an arc in the {} plane needs both {} and {} (absolute centre)", plane_name(a.plane),
                                 cu_name, cv_name));
            pc = {**cu, **cv, ps.w};
        } else {
            if (!*cu && !*cv)
                fail(fmt::format("an arc without its centre ({} and {}) or radius (R)", cu_name, cv_name));
            pc = {ps.u + cu->value_or(0.0), ps.v + cv->value_or(0.0), ps.w};
        }
        double rs = std::hypot(ps.u - pc.u, ps.v - pc.v), re = std::hypot(pe.u - pc.u, pe.v - pc.v);
        double slack = machine_.tolerance + 2.0 * (res.position + res.offset);
        if (std::abs(rs - re) > slack)
            fail(fmt::format("the arc's end is not on its circle: radius {:.4f} from the start, {:.4f} from the end "
                             "(more than the machine's tolerance {} apart)", rs, re, machine_.tolerance));
        if (rs == 0.0) fail("an arc of radius 0");
    }
    if (pe.w != ps.w || a.turns > 0) {
        if (!s.helical) fail(fmt::format("a helical arc: machine {} makes no helices", machine_.name));
    }
    end = from_plane(pe, a.plane);
    Arc ev{end, from_plane(pc, a.plane), a.direction, a.plane, *feed_, a.turns};
    ArcGeometry geo = resolve_arc(start, ev);
    double sweep = (geo.sweep - 2.0 * std::numbers::pi * a.turns) * deg_per_rad;
    // The words are rounded: a piece the post cut at exactly the limit may read up to about
    // two half-steps of the grid over the radius wider (a full circle in two halves of a
    // 10.5 mm radius read as 180.005 degrees on kosy: a fuzz finding).
    const double rounding = geo.radius > 0 ? 2 * resolution().position / geo.radius * deg_per_rad : 0.0;
    if (sweep > s.max_sweep + 1e-3 + rounding)
        fail(fmt::format("an arc of {:.3f} degrees in one block: machine {} takes at most {} degrees per block", sweep,
                         machine_.name, s.max_sweep));
    bool plane_written = a.plane == Plane::xy ? (a.x && a.y) : a.plane == Plane::xz ? (a.x && a.z) : false;
    if (plane_written) xy_uncertainty_ = 0.0;
    pos_ = {end.x, end.y, end.z};
    emit(ev, false, xy_uncertainty_);
}

std::optional<NcReader::ArcWords> NcReader::move_or_arc(int motion, Plane plane, BlockWords& w) {
    std::optional<double> x = w.length('X'), y = w.length('Y'), z = w.length('Z');
    if (y && machine_.kind == MachineKind::lathe)
        fail(fmt::format("a Y word: machine {} is a lathe, its tool moves in X and Z only", machine_.name));
    if (motion == code(0)) {
        rapid_to(x, y, z);
        return std::nullopt;
    }
    if (motion == code(1)) {
        linear_to(x, y, z);
        return std::nullopt;
    }
    ArcWords a;
    a.direction = motion == code(2) ? ArcDirection::cw : ArcDirection::ccw;
    a.plane = plane;
    a.x = x, a.y = y, a.z = z;
    a.i = w.offset('I'), a.j = w.offset('J'), a.k = w.offset('K');
    a.absolute_centre = machine_.arcs.format == ArcFormat::ijk_absolute;
    return a;
}

// ---- drilling ----

void NcReader::drill_cycle(const DrillCycle& cycle) {
    try {
        (void)peck_depths(cycle);
    } catch (const InputError& e) {
        fail(fmt::format("pecks that cannot reach the bottom of the hole: {}", e.detail()));
    }
    drill_end();
    cycle_ = cycle;
    emit(cycle);
}

void NcReader::drill_point(Vec2 at) {
    if (!cycle_) throw std::logic_error("drill point outside a cycle");
    if (!position_known()) fail("a drilling cycle from an unknown position");
    // The control computes the depths of a cycle from rounded parameters: the feed-start
    // plane may be a sum of two (Sinumerik RFP + SDIS, Heidenhain Q203 + Q200), each peck
    // adds the rounding of its depth, and a degression the rounding of its value once more
    // per peck.
    const double n = static_cast<double>(peck_depths(*cycle_).size());
    const bool degressive = cycle_->values.degression_type() != DegressionType::none;
    const double uncertainty = resolution().position * (1.0 + n + (degressive ? n * (n - 1.0) / 2.0 : 0.0));
    emit(DrillPoint{at}, false, uncertainty);
    // DrillCycle's contract: between holes the tool returns to the retract plane.
    pos_ = {at.x, at.y, cycle_->retract_z};
    xy_uncertainty_ = 0.0;
}

void NcReader::drill_end() {
    if (!cycle_) return;
    emit(DrillEnd{});
    cycle_.reset();
}

}  // namespace camgen::reader
