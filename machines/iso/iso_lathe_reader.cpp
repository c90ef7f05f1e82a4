// Reading the ISO lathe dialect (iso-lathe: linuxcnc-lathe, fanuc-lathe): the ISO reader with
// what lathes write differently, by its hooks: Fanuc T's spindle limit G50 S and constant speed G97,
// turret calls T0101 (setting toolCall "turret"), canned cycles in any plane where the post
// writes no plane word for them (setting drillingPlane false, Fanuc T), and Fanuc T's two-block
// end-face peck drilling G74 R(e) / G74 Z Q F; Fanuc T's grooving cycles G75 R(e) / G75 X Z P Q F
// and (face grooving) G74 R(e) / G74 X Z P Q F, expanded into the moves of fanuc_g75.hpp's model;
// threading cycles: LinuxCNC's G76 P Z I J K R Q H
// and Fanuc T's two-block G76 P(m r a) Q R / G76 X Z P Q F, expanded into the passes of camgen's
// models of them (linuxcnc_g76.hpp, fanuc_g76.hpp); LinuxCNC's G71 and G72 roughing from a
// profile subroutine (o<n> sub ... o<n> endsub, then G71/G72 Q<n> D0 I R F), expanded into the
// moves the control makes (geometry/lathe_cycle.hpp); and Fanuc T's type I G71 U(depth)
// R(retract) / G71 P Q U0 W0 F with its finishing shape in the blocks ns..nf right after it,
// and its G72 W(depth) R(retract) / G72 P Q U0 W0 F alike, expanded into the moves of camgen's
// model of them (fanuc_g7x).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "camgen/geometry/lathe_cycle.hpp"
#include "camgen/geometry/profile.hpp"
#include "camgen/geometry/vec.hpp"
#include "machines/iso/iso_reader.hpp"
#include "machines/iso/iso_words.hpp"
#include "machines/iso/fanuc_g75.hpp"
#include "machines/iso/fanuc_g76.hpp"
#include "machines/iso/linuxcnc_g76.hpp"

namespace camgen::reader {

namespace {

class IsoLatheReader : public IsoReader {
public:
    IsoLatheReader(const Machine& machine, std::string source, const iso::LatheSettings& settings)
        : IsoReader(machine, std::move(source), settings), lathe_(settings) {}

protected:
    bool variant_code(BlockCodes& codes, const Word& x, Code c) override;
    void variant_words(const BlockCodes& codes, BlockWords& w) override;
    bool variant_tool_call(const Word& t) override;
    bool variant_cycle(const DrillingCycleSpec& spec, BlockWords& w) override;
    void check_cycle_plane(const std::string& name) const override;
    bool variant_motion(int mode, BlockWords& w) override;
    bool f_is_lead(int mode) const override;

    void line(std::string_view text) override;
    void finish() override;
    std::string_view address_letters() const override {
        // Fanuc T G71's U and W; LinuxCNC G76's E (the exit taper's length) and L (which end tapers).
        const bool uw = fanuc_rough_spec(RoughingCycleKind::rough_z) || fanuc_rough_spec(RoughingCycleKind::rough_x), el = g76_spec() && !fanuc_g76_style();
        if (uw && el) return "XYZIJKRQPFSTHDUWEL";
        if (uw) return "XYZIJKRQPFSTHDUW";
        if (el) return "XYZIJKRQPFSTHDEL";
        return IsoReader::address_letters();
    }

public:
    // The base's, and the profile subroutines read (a custom block may not define one).
    std::vector<std::pair<std::string, std::string>> modal_state() const override {
        auto s = IsoReader::modal_state();
        if (linuxcnc_g71_spec()) {
            s.emplace_back("profile subroutines", std::to_string(subs_.size()));
            s.emplace_back("subroutine being read", reading_sub_ ? std::to_string(*reading_sub_) : std::string("none"));
        }
        return s;
    }

protected:

private:
    void face_peck(const DrillingCycleSpec& spec, BlockWords& w);
    // The machine's LinuxCNC-style G71 (rough_z) or G72 (rough_x), if it has one (roughingCycles).
    const RoughingCycleSpec* linuxcnc_rough_spec(RoughingCycleKind kind) const {
        for (const RoughingCycleSpec& c : machine_.roughing_cycles)
            if (c.style == RoughingCycleStyle::linuxcnc && c.kind == kind) return &c;
        return nullptr;
    }
    // Whether it reads profile subroutines: it has a LinuxCNC-style roughing cycle.
    bool linuxcnc_g71_spec() const {
        return linuxcnc_rough_spec(RoughingCycleKind::rough_z) || linuxcnc_rough_spec(RoughingCycleKind::rough_x);
    }
    // The G code of the LinuxCNC-style roughing cycle `mode` is, if it is one the machine has.
    std::optional<LatheCycleAxis> rough_axis(int mode) const {
        if (mode == code(71) && linuxcnc_rough_spec(RoughingCycleKind::rough_z)) return LatheCycleAxis::z;
        if (mode == code(72) && linuxcnc_rough_spec(RoughingCycleKind::rough_x)) return LatheCycleAxis::x;
        return std::nullopt;
    }
    // "o<n> sub" / "o<n> endsub": n, or nullopt when the line is not that.
    static std::optional<int> sub_line(std::string_view text, std::string_view keyword);
    void sub_body_line(std::string_view text);
    void roughing_cycle(BlockWords& w, LatheCycleAxis axis);
    // A block of a G71 profile (G0/G1/G2/G3 X Z I K) onto `profile` (its start set by the
    // first block, `started`), `motion` the modal motion code in it; `where` names it in messages.
    void profile_block(const Block& b, Profile& profile, bool& started, int& motion, const std::string& where,
                       char first_only);
    // The moves of a roughing cycle from where the tool stands.
    void cycle_moves(const std::vector<LatheCycleMove>& moves);
    // The machine's Fanuc T G71 (roughingCycles of style fanuc-g71, rough_z) or G72 (style
    // fanuc-g72, rough_x), if it has one.
    const RoughingCycleSpec* fanuc_rough_spec(RoughingCycleKind kind) const {
        for (const RoughingCycleSpec& c : machine_.roughing_cycles)
            if (c.kind == kind && (c.style == RoughingCycleStyle::fanuc_g71 || c.style == RoughingCycleStyle::fanuc_g72)) return &c;
        return nullptr;
    }
    // The Fanuc roughing cycle `mode` is, if it is one the machine has.
    std::optional<LatheCycleAxis> fanuc_rough_axis(int mode) const {
        if (mode == code(71) && fanuc_rough_spec(RoughingCycleKind::rough_z)) return LatheCycleAxis::z;
        if (mode == code(72) && fanuc_rough_spec(RoughingCycleKind::rough_x)) return LatheCycleAxis::x;
        return std::nullopt;
    }
    void fanuc_g71(BlockWords& w, LatheCycleAxis axis);
    void fanuc_shape_line(std::string_view text);
    // Fanuc G71's first block: U(depth) R(retract), radial mm; G72's: W(depth) R(retract), mm
    // along Z (by axis: z, x).
    std::optional<std::pair<double, double>> fanuc_g71_first_[2];
    // A Fanuc G71 (G72) whose finishing shape ns..nf is being read.
    struct FanucG71Shape {
        LatheCycleAxis axis = LatheCycleAxis::z;
        std::string name;  // "G71", "G72"
        long ns = 0, nf = 0;
        Vec2 start;  // A, (Z, radius)
        double depth = 0.0, retract = 0.0;
        Vec2 allowance;  // (W, U/2)
        Profile shape;
        bool started = false;
        int motion = -1;
        std::optional<Word> feed;  // the first F in ns..nf, for G70
    };
    std::optional<FanucG71Shape> fanuc_shape_;
    // The finishing shapes read, by ns: what G70 P(ns) Q(nf) runs.
    std::map<long, FanucG71Shape> fanuc_shapes_;
    void fanuc_g70(BlockWords& w);
    // G70 on a machine with a Fanuc roughing cycle (whose shapes it finishes).
    bool fanuc_g70_code(int mode) const {
        return mode == code(70) && (fanuc_rough_spec(RoughingCycleKind::rough_z) || fanuc_rough_spec(RoughingCycleKind::rough_x));
    }

    // A profile subroutine being read (its number) and those read, by number: (Z, radius).
    std::optional<int> reading_sub_;
    Profile sub_profile_;
    bool sub_started_ = false;  // its first point is set
    int sub_motion_ = -1;       // the modal motion code inside it (tenths)
    std::map<int, Profile> subs_;
    void g76(BlockWords& w);
    // Fanuc T's G75 (along_z false) or G74 face grooving (along_z true), either block.
    void fanuc_groove(BlockWords& w, bool along_z);
    // The machine's G75 (groovingCycles of style fanuc-g75), if it has one.
    const GroovingCycleSpec* g75_spec() const {
        for (const GroovingCycleSpec& s : machine_.grooving)
            if (s.style == GrooveCycleStyle::fanuc_g75) return &s;
        return nullptr;
    }
    // The machine's G74 face grooving (groovingCycles of style fanuc-g74), if it has one.
    const GroovingCycleSpec* g74_spec() const {
        for (const GroovingCycleSpec& s : machine_.grooving)
            if (s.style == GrooveCycleStyle::fanuc_g74) return &s;
        return nullptr;
    }
    void fanuc_g76(BlockWords& w);
    // The machine's G76 (threadingCycles of style linuxcnc-g76 or fanuc-g76), if it has one.
    const ThreadingCycleSpec* g76_spec() const {
        for (const ThreadingCycleSpec& s : machine_.threading)
            if (s.style == ThreadCycleStyle::linuxcnc_g76 || s.style == ThreadCycleStyle::fanuc_g76) return &s;
        return nullptr;
    }
    bool fanuc_g76_style() const { return g76_spec() && g76_spec()->style == ThreadCycleStyle::fanuc_g76; }
    // The code of the thread-cutting move this machine writes (threadMove): 33 or 32.
    double thread_code() const {
        return lathe_.thread_move == iso::LatheThreadMove::g32_f ? iso::thread_g32_code : iso::thread_g33_code;
    }

    const iso::LatheSettings& lathe_;
    std::optional<double> face_back_off_;  // Fanuc T G74's first block R(e), mm (drilling and face grooving)
    std::optional<double> groove_back_off_;  // Fanuc T G75's first block R(e), mm
    std::optional<double> g50_limit_;      // Fanuc T's G50 S, rpm: the limit of a G96
    // Fanuc T G76's first block: m, r, a of P, the least depth Q and the finishing allowance R.
    struct FanucG76First {
        int m = 1, r = 0, a = 0;
        double least = 0.0, finish = 0.0;
    };
    std::optional<FanucG76First> fanuc_g76_first_;
};

std::optional<int> IsoLatheReader::sub_line(std::string_view text, std::string_view keyword) {
    std::size_t i = 0;
    if (text.empty() || (text[0] != 'o' && text[0] != 'O')) return std::nullopt;
    ++i;
    const std::size_t digits = i;
    while (i < text.size() && is_digit(text[i])) ++i;
    if (i == digits || i - digits > 5) return std::nullopt;
    const int n = std::stoi(std::string(text.substr(digits, i - digits)));
    if (i == text.size() || !is_blank(text[i])) return std::nullopt;
    while (i < text.size() && is_blank(text[i])) ++i;
    std::string rest(text.substr(i));
    while (!rest.empty() && is_blank(rest.back())) rest.pop_back();
    for (char& c : rest) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (rest != keyword) return std::nullopt;
    return n;
}

void IsoLatheReader::line(std::string_view text) {
    if (fanuc_shape_) {
        fanuc_shape_line(text);
        return;
    }
    if (!linuxcnc_g71_spec()) {
        IsoReader::line(text);
        return;
    }
    if (auto n = sub_line(text, "sub")) {
        if (reading_sub_) fail(fmt::format("o{} sub inside o{} sub: a subroutine ends (endsub) before the next", *n, *reading_sub_));
        if (subs_.count(*n)) fail(fmt::format("o{} sub: subroutine {} is defined already", *n, *n));
        reading_sub_ = *n;
        sub_profile_ = Profile{ProfilePlane::xz, {}, {}};
        sub_started_ = false;
        sub_motion_ = -1;
        return;
    }
    if (auto n = sub_line(text, "endsub")) {
        if (!reading_sub_ || *reading_sub_ != *n) fail(fmt::format("o{} endsub without o{} sub", *n, *n));
        if (sub_profile_.segments.empty())
            fail(fmt::format("o{} endsub: camgen reads a subroutine as a G71 profile, and this one has no element", *n));
        subs_[*n] = std::move(sub_profile_);
        reading_sub_.reset();
        return;
    }
    if (reading_sub_) {
        sub_body_line(text);
        return;
    }
    IsoReader::line(text);
}

void IsoLatheReader::sub_body_line(std::string_view text) {
    // A profile for G71: G0/G1/G2/G3 X Z (I K for arcs, I a radius, from the arc's start), the
    // first block to the profile's start with both X and Z.
    const Block b = split_line(text);
    if (b.words.empty()) return;  // a comment
    profile_block(b, sub_profile_, sub_started_, sub_motion_, fmt::format("subroutine o{}", *reading_sub_), 0);
}

void IsoLatheReader::profile_block(const Block& b, Profile& profile, bool& started, int& motion_code, const std::string& where,
                                   char first_only) {
    std::optional<int> motion;
    std::optional<double> x, z, i, k;
    for (const Word& w : b.words) {
        if (w.letter == 'G') {
            const int g = code_of(w);
            if (g != code(0) && g != code(1) && g != code(2) && g != code(3))
                fail(fmt::format("{} in {}: camgen reads a G71 profile of G0, G1, G2 and G3 only", w.text, where));
            if (motion) fail(fmt::format("{}: two motion codes in one block", w.text));
            motion = g;
        } else if (w.letter == 'X' && !x) {
            x = length(w);
        } else if (w.letter == 'Z' && !z) {
            z = length(w);
        } else if (w.letter == 'I' && !i) {
            i = offset(w);
        } else if (w.letter == 'K' && !k) {
            k = offset(w);
        } else {
            fail(fmt::format("{} in {}: camgen reads a G71 profile of G0/G1/G2/G3 X Z I K only", w.text, where));
        }
    }
    if (motion) motion_code = *motion;
    if (motion_code < 0) fail(fmt::format("{}: its first block has no motion code", where));
    const bool arc = motion_code == code(2) || motion_code == code(3);
    if (!arc && (i || k)) fail(fmt::format("I/K on a straight move in {}", where));
    if (!started) {
        // Fanuc's type I infeeds in the mode of block ns, G0 or G1; camgen's model rapids them.
        if (first_only && motion_code != code(0))
            fail(fmt::format("{}: its first block (ns) is not G0 (camgen models G71 and G72 with rapid infeeds; a G1 ns "
                             "makes the control feed each one)",
                             where));
        if (first_only == 'X') {
            // Type I: block ns moves along X only, from the start point.
            if (!x || z || arc) fail(fmt::format("{}: its first block (ns) moves along X only (G0 or G1 X, type I)", where));
            profile.start = Vec2{profile.start.x, *x};
        } else if (first_only == 'Z') {
            // G72 type I: block ns moves along Z only, from the start point.
            if (!z || x || arc) fail(fmt::format("{}: its first block (ns) moves along Z only (G0 or G1 Z, type I)", where));
            profile.start = Vec2{*z, profile.start.y};
        } else {
            if (!x || !z || arc) fail(fmt::format("{}: its first block is a straight move to the profile's start with X and Z", where));
            profile.start = Vec2{*z, *x};
        }
        started = true;
        return;
    }
    if (profile.segments.size() >= 100000) fail(fmt::format("{}: more than 100000 elements", where));
    const Vec2 from = profile.segments.empty() ? profile.start : profile.segments.back().end;
    const Vec2 to{z.value_or(from.x), x.value_or(from.y)};
    if (to == from) return;  // the control skips it
    if (!arc) {
        profile.segments.push_back({to, std::nullopt, ArcDirection::ccw});
        return;
    }
    if (!i && !k) fail(fmt::format("an arc without its centre I/K in {}", where));
    const Vec2 centre{from.x + k.value_or(0.0), from.y + i.value_or(0.0)};
    if (std::abs(distance(from, centre) - distance(to, centre)) > machine_.tolerance)
        fail(fmt::format("an arc in {} whose start and end are not equally far from its centre", where));
    profile.segments.push_back({to, centre, motion_code == code(3) ? ArcDirection::ccw : ArcDirection::cw});
}

void IsoLatheReader::cycle_moves(const std::vector<LatheCycleMove>& moves) {
    for (const LatheCycleMove& m : moves) {
        const Vec3 at = position();
        if (std::abs(at.x - m.end.y) < 1e-12 && std::abs(at.z - m.end.x) < 1e-12) continue;
        switch (m.kind) {
            case LatheCycleMove::Kind::rapid: rapid_to(m.end.y, std::nullopt, m.end.x); break;
            case LatheCycleMove::Kind::feed: linear_to(m.end.y, std::nullopt, m.end.x); break;
            case LatheCycleMove::Kind::arc: {
                ArcWords a;
                a.direction = m.direction;
                a.plane = Plane::xz;
                a.x = m.end.y;
                a.z = m.end.x;
                a.i = m.centre.y - at.x;
                a.k = m.centre.x - at.z;
                arc(a);
            } break;
        }
    }
}

void IsoLatheReader::fanuc_g71(BlockWords& w, LatheCycleAxis axis) {
    // Fanuc T's type I G71 in two blocks: the first, U(depth of cut, radial) R(retract), sets the
    // cycle's values; the second, P(ns) Q(nf) U(0) W(0) F, roughs from where the tool stands (A)
    // to the finishing shape in the blocks N<ns>..N<nf> that follow it (read there, see
    // fanuc_shape_line), and returns to A. G72 alike, its first block W(depth of cut, along Z) R.
    const bool g72 = axis == LatheCycleAxis::x;
    const std::string name = g72 ? "G72" : "G71";
    const char depth_letter = g72 ? 'W' : 'U', other_letter = g72 ? 'U' : 'W';
    std::optional<std::pair<double, double>>& first = fanuc_g71_first_[g72 ? 1 : 0];
    for (char letter : {'X', 'Y', 'Z', 'I', 'J', 'K', 'D', 'H'})
        if (const Word* x = w.find(letter))
            fail(fmt::format("{} on {}: camgen reads Fanuc's {} {} R / {} P Q U W F from the start point only", x->text, name,
                             name, depth_letter, name));
    auto radial = [&](const Word& word) {
        Word z = word;
        z.letter = 'Z';
        return length(z);
    };
    if (!w.has('P')) {
        const Word* u = w.take(depth_letter);
        const Word* r = w.take('R');
        if (!u || !r || w.has('Q') || w.has(other_letter))
            fail(fmt::format("the first {} block is {} {}(depth of cut) R(retract) (camgen reads both, not the control's "
                             "parameters)",
                             name, name, depth_letter));
        first = std::make_pair(radial(*u), radial(*r));
        if (!(first->first > 0) || !(first->second > 0))
            fail(fmt::format("{} {}: the depth of cut and the retract must be above 0", u->text, r->text));
        return;
    }
    const Word* p = w.take('P');
    const Word* q = w.take('Q');
    if (!q) fail(fmt::format("{} P without Q(nf), the finishing shape's last block", name));
    if (w.has('R')) fail(fmt::format("R on the second {} block: the retract is the first block's", name));
    // The finishing allowance: U on the diameter (as X), W along Z; the shape moved by them.
    Vec2 allowance{0.0, 0.0};
    if (const Word* a = w.take('U')) {
        Word x = *a;
        x.letter = 'X';
        allowance.y = length(x);
    }
    if (const Word* a = w.take('W')) {
        Word z = *a;
        z.letter = 'Z';
        allowance.x = length(z);
    }
    if (allowance.x < 0 || allowance.y < 0)
        fail(fmt::format("{} with a negative finishing allowance: camgen models the allowance towards +X and +Z only", name));
    if (!first) fail(fmt::format("{} P Q without its first block {} {} R", name, name, depth_letter));
    if (!position_known()) fail(fmt::format("{} from an unknown position", name));
    if (!feed_) fail(fmt::format("{} without a feed (F)", name));
    FanucG71Shape s;
    s.axis = axis;
    s.name = name;
    s.ns = integer_of(*p);
    s.nf = integer_of(*q);
    if (s.nf < s.ns) fail(fmt::format("{} {} {}: the last block comes before the first", name, p->text, q->text));
    const Vec3 here = position();
    s.start = Vec2{here.z, here.x};
    s.shape.plane = ProfilePlane::xz;
    s.shape.start = Vec2{here.z, here.x};
    s.depth = first->first;
    s.retract = first->second;
    s.allowance = allowance;
    fanuc_shape_ = std::move(s);
}

void IsoLatheReader::fanuc_shape_line(std::string_view text) {
    // A block of the finishing shape after G71 P Q: its sequence number, then the profile's words.
    FanucG71Shape& s = *fanuc_shape_;
    std::size_t at = 0;
    while (at < text.size() && is_blank(text[at])) ++at;
    std::optional<long> n;
    if (at < text.size() && (text[at] == 'N' || text[at] == 'n')) {
        std::size_t e = at + 1;
        while (e < text.size() && is_digit(text[e])) ++e;
        if (e > at + 1 && e - at <= 9) n = std::stol(std::string(text.substr(at + 1, e - at - 1)));
    }
    const Block b = split_line(text);
    if (!s.started && (!n || *n != s.ns))
        fail(fmt::format("{} P{}: the block after it is not N{} (camgen reads the finishing shape right after the cycle)",
                         s.name, s.ns, s.ns));
    if (n && (*n < s.ns || *n > s.nf)) fail(fmt::format("N{} within {}'s finishing shape N{}..N{}", *n, s.name, s.ns, s.nf));
    Block shape_block = b;
    // An F in ns..nf is G70's feed (G71 and G72 rough at their own block's F).
    for (auto it = shape_block.words.begin(); it != shape_block.words.end();) {
        if (it->letter != 'F') {
            ++it;
            continue;
        }
        // G70 feeds each block at the F in force there; camgen models the shape at one feed.
        if (s.feed) fail(fmt::format("{}: a second F in {}'s finishing shape N{}..N{} (camgen reads one feed for G70's pass)",
                                     it->text, s.name, s.ns, s.nf));
        s.feed = *it;
        it = shape_block.words.erase(it);
    }
    if (!shape_block.words.empty())
        profile_block(shape_block, s.shape, s.started, s.motion, fmt::format("{}'s finishing shape (N{})", s.name, s.ns),
                      s.axis == LatheCycleAxis::x ? 'Z' : 'X');
    if (!n || *n != s.nf) return;
    const FanucG71Shape done = std::move(s);
    fanuc_shape_.reset();
    if (done.shape.segments.empty())
        fail(fmt::format("{}'s finishing shape N{}..N{} has no element", done.name, done.ns, done.nf));
    const LatheCycleModel model = camgen::fanuc_g7x(done.axis, done.start, done.shape, done.depth, done.retract, done.allowance);
    if (model.refusal) fail(done.name + ": " + *model.refusal);
    cycle_moves(model.moves);
    // Which of two shapes numbered alike a G70 P would find is not in the sources: refused.
    if (fanuc_shapes_.count(done.ns))
        fail(fmt::format("{} P{}: a finishing shape N{} was read before (G70 P{} would not name one shape)", done.name, done.ns,
                         done.ns, done.ns));
    fanuc_shapes_[done.ns] = done;
}

void IsoLatheReader::fanuc_g70(BlockWords& w) {
    // G70 P(ns) Q(nf): from where the tool stands (A), the finishing shape read after a G71/G72
    // before it (block ns along X, for G72 along Z, from A) at the F of its blocks, back to A.
    // (A block of coordinates without a motion code after it comes here too: camgen reads the
    // cycles as modal motion, where Fanuc's G70 is one-shot, back to the motion mode before it.)
    if (!w.has('P') && !w.has('Q'))
        for (char letter : {'X', 'Y', 'Z', 'U', 'W'})
            if (const Word* x = w.find(letter))
                fail(fmt::format("{} without a motion code after G70: G70 is one-shot; camgen reads a block after it only "
                                 "with G0 or G1 written",
                                 x->text));
    for (char letter : {'X', 'Y', 'Z', 'I', 'J', 'K', 'D', 'H', 'U', 'W', 'R', 'F'})
        if (const Word* x = w.find(letter)) fail(fmt::format("{} on G70: camgen reads G70 P(ns) Q(nf) only", x->text));
    const Word* p = w.take('P');
    const Word* q = w.take('Q');
    if (!p || !q) fail("G70 without P(ns) and Q(nf), the finishing shape's first and last block");
    const long ns = integer_of(*p), nf = integer_of(*q);
    const auto found = fanuc_shapes_.find(ns);
    if (found == fanuc_shapes_.end() || found->second.nf != nf)
        fail(fmt::format("G70 P{} Q{}: no G71 or G72 before it with the finishing shape N{}..N{}", ns, nf, ns, nf));
    if (!position_known()) fail("G70 from an unknown position");
    const FanucG71Shape& s = found->second;
    const Vec3 here = position();
    const Vec2 a{here.z, here.x};
    // Block ns moves along one axis from where G70 starts: A' lies on A's line.
    Profile shape = s.shape;
    if (s.axis == LatheCycleAxis::z) shape.start.x = a.x;
    else shape.start.y = a.y;
    const LatheCycleModel model = camgen::fanuc_g70(s.axis, a, shape);
    if (model.refusal) fail("G70: " + *model.refusal);
    // The shape's F (else the F in force), which stays in force after it (camgen's reading; its
    // posts write F again before the next feed).
    if (s.feed) set_feed(*s.feed);
    if (!feed_) fail(fmt::format("G70 P{} Q{}: no feed in its blocks nor before it", ns, nf));
    cycle_moves(model.moves);
}

void IsoLatheReader::finish() {
    if (fanuc_shape_)
        fail(fmt::format("{} P{} Q{}: the program ends before N{}", fanuc_shape_->name, fanuc_shape_->ns, fanuc_shape_->nf,
                         fanuc_shape_->nf));
    if (reading_sub_) fail(fmt::format("subroutine o{} has no o{} endsub", *reading_sub_, *reading_sub_));
    IsoReader::finish();
}

void IsoLatheReader::roughing_cycle(BlockWords& w, LatheCycleAxis axis) {
    // G71 (G72) Q<n> D0 I<depth> R<retract> (F) from where the tool stands: the moves the control
    // makes.
    const char* name = axis == LatheCycleAxis::x ? "G72" : "G71";
    for (char letter : {'X', 'Y', 'Z', 'J', 'K', 'P'})
        if (const Word* x = w.find(letter))
            fail(fmt::format("{} on {}: camgen reads it as {} Q D I R F from where the tool stands", x->text, name, name));
    const Word* q = w.take('Q');
    if (!q) fail(fmt::format("{} without the profile's subroutine Q", name));
    const int n = integer_of(*q);
    const auto sub = subs_.find(n);
    if (sub == subs_.end()) fail(fmt::format("{} {}: no subroutine o{} sub before it", name, q->text, n));
    if (const Word* d = w.take('D'))
        if (offset(*d) != 0.0)
            fail(fmt::format("{} on {}: camgen reads {} with D0 only (the control's finishing offset of the profile is not "
                             "modelled)",
                             d->text, name, name));
    const Word* iw = w.take('I');
    const Word* rw = w.take('R');
    const double depth = iw ? offset(*iw) : 1.0, retract = rw ? length(*rw) : 0.5;  // LinuxCNC's defaults
    if (!position_known()) fail(fmt::format("{} from an unknown position", name));
    if (!feed_) fail(fmt::format("{} without a feed (F)", name));
    const Vec3 here = position();
    const LatheCycleModel model = linuxcnc_g7x(axis, Vec2{here.z, here.x}, sub->second, depth, retract);
    if (model.refusal) fail(std::string(name) + ": " + *model.refusal);
    cycle_moves(model.moves);
}

bool IsoLatheReader::variant_code(BlockCodes& codes, const Word&, Code c) {
    if (rough_axis(c.value) || fanuc_rough_axis(c.value) || fanuc_g70_code(c.value)) {
        set_group(codes.motion, c);
        return true;
    }
    if (c.value == code(iso::spindle_limit_code) || c.value == code(iso::constant_rpm_code) ||
        c.value == code(iso::surface_speed_code)) {
        // A lathe's spindle: G50 S<max rpm> (Fanuc T), G97 S<rpm> constant speed, G96 [D<max rpm>]
        // S<m/min> constant surface speed.
        set_group(codes.spindle_mode, c);
        return true;
    }
    if (c.value == code(thread_code()) || (c.value == code(76) && g76_spec()) || (c.value == code(75) && g75_spec()) ||
        (c.value == code(74) && g74_spec())) {
        set_group(codes.motion, c);
        return true;
    }
    return false;
}

bool IsoLatheReader::f_is_lead(int mode) const {
    // (G32 F and Fanuc T G76's F: the lead)
    if (mode == code(76) && fanuc_g76_style()) return true;
    return mode == code(thread_code()) && lathe_.thread_move == iso::LatheThreadMove::g32_f;
}

bool IsoLatheReader::variant_motion(int mode, BlockWords& w) {
    if (const auto axis = rough_axis(mode)) {
        roughing_cycle(w, *axis);
        return true;
    }
    if (const auto axis = fanuc_rough_axis(mode)) {
        fanuc_g71(w, *axis);
        return true;
    }
    if (fanuc_g70_code(mode)) {
        fanuc_g70(w);
        return true;
    }
    if (mode == code(76) && g76_spec()) {
        if (fanuc_g76_style())
            fanuc_g76(w);
        else
            g76(w);
        return true;
    }
    if (mode == code(75) && g75_spec()) {
        fanuc_groove(w, false);
        return true;
    }
    if (mode == code(74) && g74_spec()) {  // (a machine whose G74 is not a drilling cycle too)
        fanuc_groove(w, true);
        return true;
    }
    if (mode != code(thread_code())) return false;
    // The thread-cutting move: G33 [X] Z K (LinuxCNC) or G32 [X] Z F (Fanuc T) from where the
    // tool stands, the lead K or F mm per revolution; with X a taper of at most 45 degrees (a
    // chamfered runout), whose K LinuxCNC measures along the path, Fanuc's F along Z.
    const bool g32 = lathe_.thread_move == iso::LatheThreadMove::g32_f;
    const std::string name = g32 ? "G32" : "G33";
    for (char letter : {'Y', 'I', 'J', 'R', 'Q', 'P'})
        if (const Word* x = w.find(letter))
            fail(fmt::format("{} on {}: camgen cuts threads in X and Z only, each pass positioned with G0", x->text, name));
    const Word* xw = w.take('X');
    const Word* zw = w.take('Z');
    const Word* lw = w.take(g32 ? 'F' : 'K');
    if (!zw || !lw) fail(fmt::format("{} needs the end Z and the lead {}", name, g32 ? 'F' : 'K'));
    thread_to(name, xw ? std::optional<double>(length(*xw)) : std::nullopt, length(*zw), *lw, !g32);
    return true;
}

void IsoLatheReader::g76(BlockWords& w) {
    // LinuxCNC's G76 P Z I J K [R Q H]: from where the tool stands (the drive point) the passes
    // the control makes (linuxcnc_g76.hpp); I, J and K are read as X is (diameters under G7).
    for (char letter : {'X', 'Y', 'F'})
        if (const Word* x = w.find(letter))
            fail(fmt::format("{} on G76: camgen reads straight threads along Z from the drive point only", x->text));
    const Word* pw = w.take('P');
    const Word* zw = w.take('Z');
    const Word* iw = w.take('I');
    const Word* jw = w.take('J');
    const Word* kw = w.take('K');
    if (!pw || !zw || !iw || !jw || !kw) fail("G76 needs P, Z, I, J and K");
    if (!position_known()) fail("G76 from an unknown position");
    auto as_x = [&](const Word* word) {
        Word x = *word;
        x.letter = 'X';
        return length(x);
    };
    iso::LinuxcncG76 g;
    const Vec3 here = position();
    g.drive_x = here.x, g.drive_y = here.y, g.drive_z = here.z;
    g.z = length(*zw);
    g.i = as_x(iw);
    g.j = as_x(jw);
    g.k = as_x(kw);
    g.p = pw->value;  // the lead is read by thread_to, through the feed-per-revolution format
    if (const Word* r = w.take('R')) g.r = r->value;
    if (const Word* q = w.take('Q')) g.q = q->value;
    if (const Word* h = w.take('H')) {
        if (h->value != std::floor(h->value)) fail(fmt::format("{} on G76: the spring passes are a whole number", h->text));
        g.h = static_cast<int>(std::clamp(h->value, -1.0, 101.0));
    }
    if (!(g.z < g.drive_z)) fail(fmt::format("G76 {}: camgen cuts threads towards the chuck, below the drive point", zw->text));
    if (g.i == 0) fail(fmt::format("G76 {}: the thread's crest must lie off the drive line", iw->text));
    if (!(g.j > 0) || !(g.k > 0)) fail("G76: J and K must be > 0");
    if (!(g.r >= 1.0)) fail("G76: R must be 1 or more");
    if (!(g.q >= 0 && g.q < 90)) fail("G76: Q must be from 0 to below 90 degrees");
    if (g.h < 0 || g.h > 100) fail("G76: H must be from 0 to 100");
    if (g.j * std::pow(10000.0, 1.0 / g.r) < g.k) fail("G76: J is too small for K: more than 10000 passes");
    // The tapers: E along the drive line, L which ends (camgen reads the exit taper, L2).
    const Word* ew = w.take('E');
    const Word* lw = w.take('L');
    if (lw) {
        if (lw->value != 0 && lw->value != 2)
            fail(fmt::format("{} on G76: camgen reads an exit taper (L2) or none (L0), not an entry taper", lw->text));
        g.l = static_cast<int>(lw->value);
    }
    if (ew) {
        Word along = *ew;  // a length along the drive line, written as Z is
        along.letter = 'Z';
        g.e = length(along);
        if (!(g.e >= 0)) fail(fmt::format("{} on G76: the taper's length must be 0 or more", ew->text));
    }
    if (g.l == 2 && g.e > 0) {
        if (g.e < g.k - 0.001)
            fail(fmt::format("{} on G76: an exit taper steeper than 45 degrees (E below K); camgen reads 45 degrees or "
                             "flatter",
                             ew->text));
        // A pass of depth d runs from drive_z - d tan q to z + (k - d) tan q + E before its taper:
        // the deepest (d = k) runs towards -Z only where E < drive_z - z - k tan q.
        const double shift = g.k * std::tan(g.q * 3.14159265358979323846 / 180.0);
        if (g.e >= g.drive_z - g.z - shift)
            fail(fmt::format("{} on G76: the exit taper is not shorter than the thread (less the last pass's shift along "
                             "Z by the infeed angle)",
                             ew->text));
    }
    for (const Event& e : iso::linuxcnc_g76_moves(g)) {
        if (const auto* r = std::get_if<Rapid>(&e))
            rapid_to(r->to.x, std::nullopt, r->to.z);
        else
            thread_to("G76", std::get<ThreadFeed>(e).to.x, std::get<ThreadFeed>(e).to.z, *pw);
    }
}

void IsoLatheReader::fanuc_g76(BlockWords& w) {
    // Fanuc T's G76 in two blocks (fanuc_g76.hpp): the first, P(m r a) Q(least depth) R(finishing
    // allowance), sets the cycle's values; the second, X Z [R(taper)] P(height) Q(first depth) F(lead),
    // cuts the passes from where the tool stands (the start point) and returns there. P and Q are
    // radial, in least input increments without a decimal point.
    for (char letter : {'Y', 'I', 'J', 'K', 'H', 'D'})
        if (const Word* x = w.find(letter))
            fail(fmt::format("{} on G76: camgen reads Fanuc's two-block G76 from the start point only", x->text));
    const double increments = std::pow(10.0, length_format('Z').spec().decimals);
    auto increment_word = [&](const Word& q, double least) {
        if (q.has_point) fail(fmt::format("{} on G76: in least input increments, without a decimal point", q.text));
        const double v = length_value(q.value / increments);
        if (v < least) fail(fmt::format("{} on G76: below {}", q.text, least == 0 ? "0" : "one increment"));
        return v;
    };
    if (!w.has('X') && !w.has('Z')) {
        // The first block.
        if (w.has('F')) fail("F on the first G76 block (P Q R): the lead is the second block's");
        FanucG76First first;
        if (const Word* p = w.take('P')) {
            if (p->has_point || p->value < 0 || p->value != std::floor(p->value) || p->value > 999999)
                fail(fmt::format("{} on G76: P is six digits, m r a (finishing passes, chamfer, tool angle)", p->text));
            const int v = static_cast<int>(p->value);
            first.m = v / 10000, first.r = v / 100 % 100, first.a = v % 100;
        } else {
            fail("the first G76 block needs P(m r a)");
        }
        if (first.m < 1) fail("G76 P: m, the finishing passes, must be from 1 to 99");
        if (first.r != 0)
            fail(fmt::format("G76 P: a chamfer r of {} (0.1 leads): camgen reads threads with a straight runout only (r 00)",
                             first.r));
        if (std::find(std::begin(iso::fanuc_g76_tool_angles), std::end(iso::fanuc_g76_tool_angles), first.a) ==
            std::end(iso::fanuc_g76_tool_angles))
            fail(fmt::format("G76 P: the tool angle a {} is not one of 80, 60, 55, 30, 29, 0", first.a));
        if (const Word* q = w.take('Q')) first.least = increment_word(*q, 0.0);
        if (const Word* r = w.take('R')) {
            first.finish = length(*r);
            if (first.finish < 0) fail(fmt::format("{} on G76: the finishing allowance must be 0 or more", r->text));
        }
        fanuc_g76_first_ = first;
        return;
    }
    const Word* xw = w.take('X');
    const Word* zw = w.take('Z');
    const Word* pw = w.take('P');
    const Word* qw = w.take('Q');
    const Word* fw = w.take('F');
    if (!xw || !zw || !pw || !qw || !fw) fail("the second G76 block needs X, Z, P(height), Q(first depth) and F(lead)");
    if (const Word* r = w.take('R'); r && r->value != 0)
        fail(fmt::format("{} on G76: camgen reads straight threads only (no taper)", r->text));
    if (!fanuc_g76_first_) fail("G76 X Z P Q F without its first block G76 P Q R");
    if (!position_known()) fail("G76 from an unknown position");
    iso::FanucG76 g;
    const Vec3 here = position();
    g.start_x = here.x, g.start_y = here.y, g.start_z = here.z;
    g.x = length(*xw);
    g.z = length(*zw);
    g.k = increment_word(*pw, 1e-12);
    g.first = increment_word(*qw, 1e-12);
    g.least = fanuc_g76_first_->least;
    g.finish = fanuc_g76_first_->finish;
    g.m = fanuc_g76_first_->m;
    g.angle = fanuc_g76_first_->a;
    if (!(g.z < g.start_z)) fail(fmt::format("G76 {}: camgen cuts threads towards the chuck, below the start point", zw->text));
    if (g.x == g.start_x) fail(fmt::format("G76 {}: the thread's last pass must lie off the start point's X", xw->text));
    if (g.x < g.start_x ? g.x + g.k > g.start_x : g.x - g.k < g.start_x)
        fail(fmt::format("G76 {} {}: the thread's crest lies beyond the start point", xw->text, pw->text));
    if (!(g.finish < g.k)) fail("G76: the finishing allowance R must be below the height P");
    if (g.first * std::sqrt(10000.0) < g.k - g.finish && g.least * 10000 < g.k - g.finish)
        fail("G76: Q is too small for P: more than 10000 passes");
    for (const Event& e : iso::fanuc_g76_moves(g)) {
        if (const auto* r = std::get_if<Rapid>(&e))
            rapid_to(r->to.x, std::nullopt, r->to.z);
        else
            thread_to("G76", std::get<ThreadFeed>(e).to.x, std::get<ThreadFeed>(e).to.z, *fw);
    }
}

void IsoLatheReader::fanuc_groove(BlockWords& w, bool along_z) {
    // Fanuc T's G75 / G74 in two blocks: R(e) sets the back-off; X Z P Q F plunges from where the
    // tool stands (the start point) as fanuc_g75.hpp models it: G75 along X (P the peck, Q the
    // step along Z), G74 along Z (Q the peck, P the step along X). P and Q are in least input
    // increments without a decimal point; X is read as X (a diameter on a diameter machine).
    const std::string name = along_z ? g74_spec()->name : g75_spec()->name;
    std::optional<double>& back_off = along_z ? face_back_off_ : groove_back_off_;
    for (char letter : {'Y', 'I', 'J', 'K'})
        if (const Word* x = w.find(letter)) fail(fmt::format("{} in a {} block: camgen grooves in X and Z only", x->text, name));
    if (w.has('R') && !w.has('X') && !w.has('Z') && !w.has('P') && !w.has('Q')) {
        const Word* r = w.take('R');
        back_off = length(*r);
        if (!(*back_off > 0)) fail(fmt::format("{}: the back-off must be > 0", r->text));
        return;
    }
    if (const Word* r = w.find('R'))
        fail(fmt::format("{} in the second {} block: camgen reads no relief at the bottom (R(e) stands in the first block "
                         "alone)",
                         r->text, name));
    const Word* xw = w.take('X');
    const Word* zw = w.take('Z');
    const Word* pw = w.take('P');
    const Word* qw = w.take('Q');
    const Word* peck_w = along_z ? qw : pw;
    const Word* step_w = along_z ? pw : qw;
    if (!xw || !zw || !peck_w)
        fail(fmt::format("the second {} block needs X, Z and the peck {}", name, along_z ? 'Q' : 'P'));
    if (!back_off) fail(fmt::format("{} X Z {} without the first block {} R(e)", name, along_z ? 'Q' : 'P', name));
    for (const Word* iw : {pw, qw})
        if (iw && iw->has_point) fail(fmt::format("{}: P and Q are in least input increments, without a decimal point", iw->text));
    if (!position_known()) fail(fmt::format("{} from an unknown position", name));
    if (!feed_) fail(fmt::format("{} without a feed F", name));
    const Vec3 here = position();
    const double increments = std::pow(10.0, length_format('Z').spec().decimals);
    iso::FanucGroove g;
    g.along_z = along_z;
    g.start_x = here.x, g.start_y = here.y, g.start_z = here.z;
    g.x = length(*xw);
    g.z = length(*zw);
    g.peck = length_value(peck_w->value / increments);
    g.step = step_w ? length_value(step_w->value / increments) : 0.0;
    g.e = *back_off;
    g.feed = *feed_;
    const double d0 = along_z ? g.start_z : g.start_x, d_end = along_z ? g.z : g.x;
    const double s0 = along_z ? g.start_x : g.start_z, s_end = along_z ? g.x : g.z;
    const Word* bottom_w = along_z ? zw : xw;
    const Word* end_w = along_z ? xw : zw;
    // G75: X below the start point, an external groove; beyond it, an internal one (the pecks
    // mirrored). G74: the bottom towards the chuck, below the start point.
    if (d_end == d0)
        fail(fmt::format("{} {}: the groove's bottom must lie off the start point's {}", name, bottom_w->text, along_z ? 'Z' : 'X'));
    if (along_z && d_end > d0)
        fail(fmt::format("{} {}: camgen cuts face grooves towards the chuck, below the start point", name, bottom_w->text));
    if (!(g.peck > 0)) fail(fmt::format("{}: the peck {} must be > 0", peck_w->text, along_z ? 'Q' : 'P'));
    if (std::abs(s_end - s0) > 1e-9 && !(g.step > 0))
        fail(fmt::format("{} {}: a groove along {} needs its step {} > 0", name, end_w->text, along_z ? 'X' : 'Z', along_z ? 'P' : 'Q'));
    // The control's alarms (docs/reference.md): a peck longer than the plunge, a step longer than
    // the travel, a back-off longer than the peck (one least increment of slack for a diameter's
    // half).
    const double slack = 1.0 / increments + 1e-9;
    if (g.peck > std::abs(d0 - d_end) + slack)
        fail(fmt::format("{}: the peck is longer than the plunge from the start point to {}", peck_w->text, bottom_w->text));
    if (step_w && g.step > std::abs(s_end - s0) + slack)
        fail(fmt::format("{}: the step is longer than the travel from the start point to {}", step_w->text, end_w->text));
    if (g.e > g.peck + 1e-9) fail(fmt::format("{}: the back-off R(e) is longer than the peck", peck_w->text));
    if (std::abs(d0 - d_end) / g.peck > 10000) fail(fmt::format("{}: more than 10000 pecks", peck_w->text));
    if (g.step > 0 && std::abs(s_end - s0) / g.step > 10000) fail(fmt::format("{}: more than 10000 plunges", step_w->text));
    // Both bounds at once would still be 10^8 pecks from one block: the cycle's pecks are bounded too.
    const double plunges = g.step > 0 ? std::ceil(std::abs(s_end - s0) / g.step) + 1 : 1;
    if (std::ceil(std::abs(d0 - d_end) / g.peck) * plunges > 100000)
        fail(fmt::format("{} {}: more than 100000 pecks in one cycle", name, peck_w->text));
    for (const Event& e : iso::fanuc_groove_moves(g)) {
        if (const auto* r = std::get_if<Rapid>(&e)) rapid_to(r->to.x, std::nullopt, r->to.z);
        else linear_to(std::get<Linear>(e).to.x, std::nullopt, std::get<Linear>(e).to.z);
    }
}

void IsoLatheReader::variant_words(const BlockCodes& codes, BlockWords& w) {
    if (!codes.spindle_mode) return;
    const std::string& name = codes.spindle_mode->word->text;
    auto within_machine = [&](const Word& s) {
        if (machine_.limits.max_rpm > 0 && rpm(s) > machine_.limits.max_rpm)
            fail(fmt::format("{}: above the limit of machine {} ({} rpm)", s.text, machine_.name, machine_.limits.max_rpm));
        return rpm(s);
    };
    if (codes.spindle_mode->value == code(iso::constant_rpm_code)) {
        // G97 S: the S that follows is rpm (without it the control would turn at the number
        // the surface speed was).
        if (!w.has('S')) fail(fmt::format("{} without S: camgen writes {} S<rpm>", name, name));
        constant_rpm();
        return;
    }
    if (codes.spindle_mode->value == code(iso::surface_speed_code)) {
        // G96 S<m/min>, held to LinuxCNC's D or Fanuc T's G50 S (else the machine's limit).
        if (!w.has('S')) fail(fmt::format("{} without S, the surface speed", name));
        double limit = 0.0;
        if (const Word* d = w.take('D')) {
            if (lathe_.spindle_limit)
                fail(fmt::format("{} on {}: machine {} limits the spindle with G50 S", d->text, name, machine_.name));
            limit = within_machine(*d);
        } else if (g50_limit_) {
            limit = *g50_limit_;
        } else if (machine_.limits.max_rpm > 0) {
            limit = machine_.limits.max_rpm;
        } else {
            fail(fmt::format("{} without a spindle limit (D, or G50 S before it), and machine {} has no maxRpm", name,
                             machine_.name));
        }
        constant_surface_speed(limit);
        return;
    }
    // G50 S: the highest speed the spindle may turn, not a speed.
    const Word* s = w.take('S');
    if (!s || w.has('X') || w.has('Z')) fail(fmt::format("{}: camgen writes it only as the speed limit {} S", name, name));
    g50_limit_ = within_machine(*s);
    if (!(*g50_limit_ > 0)) fail(fmt::format("{}: a speed limit must be > 0", s->text));
    spindle_limit(*g50_limit_);
}

bool IsoLatheReader::variant_tool_call(const Word& t) {
    if (lathe_.tool_call != iso::LatheToolCall::turret) return false;
    // A turret call T<tool><offset>: the tool and the offset (its length and nose) the control
    // applies from here. camgen's post calls each tool with its own offset (T0101); another
    // offset (T0102, a second set for the same tool) is read, and verify --job finds it differs.
    const int call = integer_of(t);
    if (call < 100 || call > 9999)
        fail(fmt::format("{}: machine {} calls tool n with offset m as T<nn><mm>, T0101 to T9999", t.text, machine_.name));
    change_tool(call / 100, commented_description(call / 100));
    select_length_offset(fmt::format("T{:02}{:02}", call / 100, call % 100));
    return true;
}

bool IsoLatheReader::variant_cycle(const DrillingCycleSpec& spec, BlockWords& w) {
    if (spec.style != CannedStyle::fanuc_g74) return false;
    // G74 with X or P is face grooving (camgen's drilling G74 has neither); its first block R(e)
    // is the same for both.
    if (g74_spec() && (w.has('X') || w.has('P'))) {
        drill_end();
        fanuc_groove(w, true);
        return true;
    }
    face_peck(spec, w);
    return true;
}

void IsoLatheReader::check_cycle_plane(const std::string& name) const {
    // Fanuc T's face drilling cycles take no plane (drillingPlane false).
    if (lathe_.drilling_plane) IsoReader::check_cycle_plane(name);
}

void IsoLatheReader::face_peck(const DrillingCycleSpec& spec, BlockWords& w) {
    // Fanuc T G74 in two blocks: G74 R(e) sets the back-off; G74 Z Q F pecks from where the tool
    // stands (the start point, X0 on a centre hole) by Q, backs off e, ... to Z, and returns to
    // the start point. Q is in least input increments without a decimal point.
    const std::string& name = spec.name;
    for (char letter : {'Y', 'I', 'J', 'K', 'P'})
        if (const Word* x = w.find(letter)) fail(fmt::format("{} in a {} block: camgen drills with it on the axis only", x->text, name));
    if (const Word* r = w.take('R')) {
        if (w.has('Z') || w.has('Q') || w.has('X')) fail(fmt::format("{}: R(e) stands in the first {} block alone", r->text, name));
        face_back_off_ = length(*r);
        if (!(*face_back_off_ > 0)) fail(fmt::format("{}: the back-off must be > 0", r->text));
        return;
    }
    const Word* zw = w.take('Z');
    const Word* qw = w.take('Q');
    if (w.has('X')) fail(fmt::format("X in the second {} block: camgen drills at the start point's X", name));
    if (!zw || !qw) fail(fmt::format("the second {} block needs the bottom Z and the peck Q", name));
    if (!face_back_off_) fail(fmt::format("{} Z Q without the first block {} R(e)", name, name));
    if (qw->has_point) fail(fmt::format("{}: Q is in least input increments, without a decimal point", qw->text));
    if (!position_known()) fail(fmt::format("{} from an unknown position", name));
    if (!feed_) fail(fmt::format("{} without a feed F", name));
    const Vec3 here = position();
    const double bottom = length(*zw);
    const double increments = std::pow(10.0, length_format('Z').spec().decimals);
    const double peck = length_value(qw->value / increments);
    if (!(peck > 0)) fail(fmt::format("{}: the peck Q must be > 0", qw->text));
    if (!(bottom < here.z)) fail(fmt::format("{} {}: the bottom is not below the start point", name, zw->text));
    DrillCycle c;
    c.kind = CycleKind::chip_break;
    c.output = CycleOutput::canned;
    c.retract_z = c.reference_z = c.safe_z = here.z;
    c.bottom_z = bottom;
    c.feed = *feed_;
    c.spindle_rpm = rpm_;
    c.values.set(DrillField::first_depth, peck);
    c.values.set(DrillField::pecking_retract, *face_back_off_);
    c.values.set(DrillField::plunging_feedrate, *feed_);
    drill_cycle(c);
    drill_point({here.x, here.y});
    drill_end();
}

}  // namespace

std::unique_ptr<NcReader> make_iso_lathe_reader(const Machine& machine, std::string source) {
    return std::make_unique<IsoLatheReader>(machine, std::move(source), settings_of<iso::LatheSettings>(machine));
}

}  // namespace camgen::reader
