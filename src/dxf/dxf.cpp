#include "camgen/dxf/dxf.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen::dxf {

namespace {

// ---- Group pairs

struct DxfGroup {
    int code = 0;
    std::string_view value;
    std::size_t line = 0;  // of the code
};

std::string dxf_upper(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

std::string_view dxf_trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

std::string dxf_number_text(double v) {
    std::ostringstream o;
    o.precision(10);
    o << v;
    return o.str();
}

// Reads the file's group pairs one at a time: a code line (an integer) and a value line.
class DxfPairs {
public:
    DxfPairs(std::string_view text, const std::string& name) : text_(text), name_(name) {}

    // The next pair; false at the end of the text (a code without a value is an error).
    bool next(DxfGroup& g) {
        if (pos_ >= text_.size()) return false;
        const std::size_t code_line = line_ + 1;
        std::string_view code_text = dxf_trim(take_line());
        if (pos_ >= text_.size() && code_text.empty()) return false;
        int code = 0;
        const auto [p, ec] = std::from_chars(code_text.data(), code_text.data() + code_text.size(), code);
        if (ec != std::errc{} || p != code_text.data() + code_text.size() || code_text.empty())
            fail(code_line, "expected a group code (an integer), got \"" + std::string(code_text.substr(0, 40)) +
                                "\": the file is not an ASCII DXF, or it is damaged");
        if (pos_ >= text_.size())
            fail(code_line, "the file ends after group code " + std::to_string(code) + " without its value: it is cut short");
        g.code = code;
        g.value = take_line();
        if (!g.value.empty() && g.value.back() == '\r') g.value.remove_suffix(1);
        g.line = code_line;
        return true;
    }
    [[noreturn]] void fail(std::size_t line, const std::string& message) const {
        throw Error(name_ + " line " + std::to_string(line) + ": " + message);
    }
    const std::string& name() const { return name_; }

private:
    std::string_view take_line() {
        const std::size_t nl = text_.find('\n', pos_);
        const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
        std::string_view l = text_.substr(pos_, end - pos_);
        pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
        ++line_;
        return l;
    }
    std::string_view text_;
    const std::string& name_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
};

// ---- Entities as records of groups

struct DxfRecord {
    std::string_view type;
    std::size_t line = 0;
    std::vector<DxfGroup> groups;  // after the "0" group, xdata and 102 groups left out
};

// 2D affine placement: p' = m * p + t.
struct DxfAffine {
    double a = 1, b = 0, c = 0, d = 1;  // [a b; c d]
    Vec2 t;
    Vec2 operator()(Vec2 p) const { return {a * p.x + b * p.y + t.x, c * p.x + d * p.y + t.y}; }
    double det() const { return a * d - b * c; }
    DxfAffine then(const DxfAffine& outer) const {  // outer after this
        DxfAffine r;
        r.a = outer.a * a + outer.b * c;
        r.b = outer.a * b + outer.b * d;
        r.c = outer.c * a + outer.d * c;
        r.d = outer.c * b + outer.d * d;
        r.t = outer(t);
        return r;
    }
    // The scale of a similarity (a rotation, a mirror and a uniform scale), nullopt otherwise.
    std::optional<double> uniform_scale() const {
        const double sx = std::hypot(a, c), sy = std::hypot(b, d);
        if (std::abs(sx - sy) > 1e-9 * std::max(sx, sy) || std::abs(a * b + c * d) > 1e-9 * sx * sy) return std::nullopt;
        return sx;
    }
};

Profile dxf_transform(const Profile& p, const DxfAffine& m) {
    Profile out;
    out.plane = p.plane;
    out.start = m(p.start);
    out.segments.reserve(p.segments.size());
    const bool flip = m.det() < 0;
    for (const ProfileSegment& s : p.segments) {
        ProfileSegment r;
        r.end = m(s.end);
        if (s.centre) {
            r.centre = m(*s.centre);
            r.direction = flip ? (s.direction == ArcDirection::ccw ? ArcDirection::cw : ArcDirection::ccw) : s.direction;
        }
        out.segments.push_back(r);
    }
    return out;
}

struct DxfBlock {
    std::string name;
    Vec2 base;
    std::vector<Piece> pieces;           // in block coordinates
    struct Insert {
        std::string block;
        DxfAffine place;                  // one per array copy
        Origin origin;
    };
    std::vector<Insert> inserts;
    std::size_t line = 0;
};

class DxfReader {
public:
    DxfReader(std::string_view text, const std::string& name, const ReadOptions& o) : pairs_(text, name), opt_(o) {
        drawing_.name = name;
    }

    Drawing read() {
        DxfGroup g;
        bool eof = false;
        while (next(g)) {
            if (g.code == 999) continue;  // comment
            if (g.code != 0) pairs_.fail(g.line, "expected \"0\" and SECTION or EOF, got group code " + std::to_string(g.code));
            if (g.value == "EOF") {
                eof = true;
                break;
            }
            if (g.value != "SECTION") pairs_.fail(g.line, "expected SECTION or EOF, got \"" + std::string(g.value.substr(0, 40)) + "\"");
            DxfGroup n;
            if (!next(n)) cut_short(g.line, "SECTION");
            if (n.code != 2) pairs_.fail(n.line, "a SECTION needs its name (group code 2) first");
            const std::string section(n.value);
            if (section == "HEADER") read_header();
            else if (section == "TABLES") read_tables();
            else if (section == "BLOCKS") read_blocks();
            else if (section == "ENTITIES") read_entities(model_, nullptr, "ENTITIES");
            else skip_section(n.line, section);
        }
        if (!eof) cut_short(last_line_, "the drawing (no EOF)");
        resolve_inserts();
        finish_layers();
        return std::move(drawing_);
    }

private:
    bool next(DxfGroup& g) {
        if (held_) {
            g = *held_;
            held_.reset();
            return true;
        }
        if (!pairs_.next(g)) return false;
        last_line_ = g.line;
        return true;
    }
    void push_back(const DxfGroup& g) { held_ = g; }

    [[noreturn]] void cut_short(std::size_t line, const std::string& what) {
        pairs_.fail(line, "the file ends inside " + what + ": it is cut short (truncated)");
    }

    void skip_section(std::size_t line, const std::string& name) {
        DxfGroup g;
        while (next(g))
            if (g.code == 0 && g.value == "ENDSEC") return;
        cut_short(line, "section " + name);
    }

    double number(const DxfGroup& g, const DxfRecord* r = nullptr) {
        const std::string_view v = dxf_trim(g.value);
        double x = 0;
        const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
        if (ec != std::errc{} || p != v.data() + v.size() || v.empty() || !std::isfinite(x) || std::abs(x) > 1e12)
            fail(g.line, r, "group code " + std::to_string(g.code) + " needs a number, got \"" + std::string(v.substr(0, 40)) + "\"");
        return x;
    }
    long integer(const DxfGroup& g, const DxfRecord* r = nullptr) {
        const std::string_view v = dxf_trim(g.value);
        long x = 0;
        const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
        if (ec != std::errc{} || p != v.data() + v.size() || v.empty())
            fail(g.line, r, "group code " + std::to_string(g.code) + " needs an integer, got \"" + std::string(v.substr(0, 40)) + "\"");
        return x;
    }

    std::string where(const DxfRecord& r) const {
        std::string s(r.type);
        std::string handle, layer;
        for (const DxfGroup& g : r.groups) {
            if (g.code == 5) handle = g.value;
            if (g.code == 8) layer = g.value;
        }
        s += " (";
        if (!handle.empty()) s += "handle " + handle + ", ";
        s += "layer " + (layer.empty() ? std::string("0") : layer) + ")";
        return s;
    }
    [[noreturn]] void fail(std::size_t line, const DxfRecord* r, const std::string& message) {
        pairs_.fail(line, r ? where(*r) + ": " + message : message);
    }

    // Reads one record after its "0" group: every group up to the next "0", which is held.
    void read_record(DxfRecord& r, const DxfGroup& head) {
        r.type = head.value;
        r.line = head.line;
        r.groups.clear();
        DxfGroup g;
        bool in_102 = false;
        while (true) {
            if (!next(g)) cut_short(head.line, std::string(head.value));
            if (g.code == 0) {
                push_back(g);
                return;
            }
            if (g.code == 102) {
                in_102 = !g.value.empty() && g.value.front() == '{';
                continue;
            }
            if (in_102 || g.code >= 1000 || g.code == 999) continue;
            r.groups.push_back(g);
        }
    }

    void read_header() {
        DxfGroup g;
        std::string variable;
        while (next(g)) {
            if (g.code == 0) {
                if (g.value == "ENDSEC") return;
                pairs_.fail(g.line, "expected ENDSEC to close the HEADER, got \"" + std::string(g.value.substr(0, 40)) + "\"");
            }
            if (g.code == 9) variable = g.value;
            else if (variable == "$INSUNITS" && g.code == 70) drawing_.insunits = static_cast<int>(integer(g));
        }
        cut_short(last_line_, "the HEADER section");
    }

    void read_tables() {
        DxfGroup g;
        DxfRecord r;
        while (next(g)) {
            if (g.code != 0) continue;
            if (g.value == "ENDSEC") return;
            if (g.value == "LAYER") {
                read_record(r, g);
                Layer l;
                for (const DxfGroup& x : r.groups) {
                    if (x.code == 2) l.name = x.value;
                    else if (x.code == 62) l.colour = static_cast<int>(std::abs(integer(x, &r)));
                    else if (x.code == 6) l.linetype = x.value;
                }
                if (!l.name.empty()) add_layer(l);
            }
        }
        cut_short(last_line_, "the TABLES section");
    }

    void add_layer(const Layer& l) {
        const std::string key = dxf_upper(l.name);
        if (layer_index_.count(key)) return;
        layer_index_[key] = drawing_.layers.size();
        drawing_.layers.push_back(l);
    }

    void read_blocks() {
        DxfGroup g;
        DxfRecord r;
        while (next(g)) {
            if (g.code != 0) continue;
            if (g.value == "ENDSEC") return;
            if (g.value != "BLOCK") continue;
            read_record(r, g);
            DxfBlock b;
            b.line = r.line;
            for (const DxfGroup& x : r.groups) {
                if (x.code == 2) b.name = x.value;
                else if (x.code == 10) b.base.x = number(x, &r);
                else if (x.code == 20) b.base.y = number(x, &r);
            }
            if (b.name.empty()) fail(r.line, &r, "a BLOCK needs its name (group code 2)");
            read_entities(b, &b, "BLOCK " + b.name);
            blocks_[dxf_upper(b.name)] = std::move(b);
        }
        cut_short(last_line_, "the BLOCKS section");
    }

    // Entities up to ENDSEC (ENTITIES) or ENDBLK (a block), into `into`.
    void read_entities(DxfBlock& into, const DxfBlock* block, const std::string& what) {
        DxfGroup g;
        DxfRecord r;
        const std::size_t start = last_line_;
        while (next(g)) {
            if (g.code != 0) pairs_.fail(g.line, "expected \"0\" and an entity, got group code " + std::to_string(g.code));
            if (!block && g.value == "ENDSEC") return;
            if (block && g.value == "ENDBLK") {
                read_record(r, g);
                return;
            }
            read_record(r, g);
            entity(r, into);
        }
        cut_short(start, what);
    }

    // The OCS of an entity as a placement in the XY plane: +Z as it is, -Z mirrors X.
    DxfAffine ocs(const DxfRecord& r, Vec3 n) {
        const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
        if (len == 0) fail(r.line, &r, "its extrusion direction (210/220/230) is zero");
        if (std::hypot(n.x, n.y) > 1e-9 * len)
            fail(r.line, &r, "it is not in the XY plane (extrusion " + dxf_number_text(n.x / len) + ", " + dxf_number_text(n.y / len) + ", " +
                                  dxf_number_text(n.z / len) + "): camgen takes 2D drawings in XY");
        DxfAffine m;
        if (n.z < 0) m.a = -1;
        return m;
    }

    Origin origin_of(const DxfRecord& r) {
        Origin o;
        o.type = std::string(r.type);
        o.line = r.line;
        o.layer = "0";
        o.linetype = "BYLAYER";
        o.colour = 256;
        for (const DxfGroup& g : r.groups) {
            if (g.code == 5) o.handle = g.value;
            else if (g.code == 8) o.layer = g.value;
            else if (g.code == 6) o.linetype = g.value;
            else if (g.code == 62) o.colour = static_cast<int>(integer(g, &r));
        }
        return o;
    }

    static void add_line(Profile& p, Vec2 to) { p.segments.push_back({to, std::nullopt, ArcDirection::ccw}); }
    // A bulge segment from `from` to `to`: bulge = tan(sweep / 4), positive counter-clockwise.
    static void add_bulge(Profile& p, Vec2 from, Vec2 to, double bulge) {
        if (bulge == 0 || from == to) return add_line(p, to);
        const Vec2 chord = to - from;
        const double c = norm(chord);
        // The centre sits left of the chord for a positive bulge below 180 degrees.
        const double offset = c * (1.0 - bulge * bulge) / (4.0 * bulge);
        const Vec2 mid = (from + to) * 0.5;
        const Vec2 centre = mid + left_of(chord) * (offset / c);
        p.segments.push_back({to, centre, bulge > 0 ? ArcDirection::ccw : ArcDirection::cw});
    }

    void entity(DxfRecord& r, DxfBlock& into) {
        const std::string_view t = r.type;
        // Paper space: left out unless asked.
        for (const DxfGroup& g : r.groups)
            if (g.code == 67 && integer(g, &r) == 1 && !opt_.paper_space) {
                if (t == "POLYLINE" || t == "INSERT") skip_sequence(r);
                return;
            }
        Vec3 n{0, 0, 1};
        for (const DxfGroup& g : r.groups) {
            if (g.code == 210) n.x = number(g, &r);
            else if (g.code == 220) n.y = number(g, &r);
            else if (g.code == 230) n.z = number(g, &r);
        }
        auto coord = [&](int code, double fallback = 0.0) {
            for (const DxfGroup& g : r.groups)
                if (g.code == code) return number(g, &r);
            return fallback;
        };
        auto has = [&](int code) {
            return std::any_of(r.groups.begin(), r.groups.end(), [&](const DxfGroup& g) { return g.code == code; });
        };
        auto need = [&](std::initializer_list<int> codes) {
            for (int c : codes)
                if (!has(c)) fail(r.line, &r, "group code " + std::to_string(c) + " is missing");
        };
        Piece piece;
        if (t == "LINE") {
            need({10, 20, 11, 21});
            piece.origin = origin_of(r);
            piece.path.start = {coord(10), coord(20)};
            add_line(piece.path, {coord(11), coord(21)});
        } else if (t == "POINT") {
            need({10, 20});
            piece.origin = origin_of(r);
            piece.kind = Piece::Kind::point;
            piece.centre = {coord(10), coord(20)};
        } else if (t == "CIRCLE") {
            need({10, 20, 40});
            piece.origin = origin_of(r);
            piece.kind = Piece::Kind::circle;
            const DxfAffine m = ocs(r, n);
            piece.centre = m({coord(10), coord(20)});
            piece.radius = coord(40);
            if (!(piece.radius > 0)) fail(r.line, &r, "its radius (group code 40) must be more than 0");
        } else if (t == "ARC") {
            need({10, 20, 40, 50, 51});
            piece.origin = origin_of(r);
            const Vec2 c{coord(10), coord(20)};
            const double radius = coord(40);
            if (!(radius > 0)) fail(r.line, &r, "its radius (group code 40) must be more than 0");
            double a0 = coord(50), a1 = coord(51);
            while (a1 <= a0) a1 += 360.0;
            piece.path.start = c + unit_at(a0 * rad_per_deg) * radius;
            const Vec2 end = c + unit_at(a1 * rad_per_deg) * radius;
            piece.path.segments.push_back({end, c, ArcDirection::ccw});
            piece.path = dxf_transform(piece.path, ocs(r, n));
        } else if (t == "LWPOLYLINE") {
            piece.origin = origin_of(r);
            long flags = 0;
            std::vector<Vec2> v;
            std::vector<double> bulge;
            for (const DxfGroup& g : r.groups) {
                if (g.code == 70) flags = integer(g, &r);
                else if (g.code == 10) {
                    v.push_back({number(g, &r), 0});
                    bulge.push_back(0);
                } else if (g.code == 20) {
                    if (v.empty()) fail(g.line, &r, "a vertex's Y (20) before its X (10)");
                    v.back().y = number(g, &r);
                } else if (g.code == 42) {
                    if (v.empty()) fail(g.line, &r, "a bulge (42) before the first vertex");
                    bulge.back() = number(g, &r);
                }
            }
            polyline(piece, r, v, bulge, (flags & 1) != 0, ocs(r, n));
            if (piece.path.segments.empty()) return;
        } else if (t == "POLYLINE") {
            piece.origin = origin_of(r);
            long flags = 0;
            for (const DxfGroup& g : r.groups)
                if (g.code == 70) flags = integer(g, &r);
            if (flags & (8 | 16 | 64))
                fail(r.line, &r, "a 3D polyline, polygon mesh or polyface mesh: camgen takes 2D drawings in XY");
            std::vector<Vec2> v;
            std::vector<double> bulge;
            DxfGroup g;
            DxfRecord vx;
            while (true) {
                if (!next(g)) cut_short(r.line, "a POLYLINE (no SEQEND)");
                if (g.code != 0) pairs_.fail(g.line, "expected \"0\" and VERTEX or SEQEND, got group code " + std::to_string(g.code));
                read_record(vx, g);
                if (vx.type == "SEQEND") break;
                if (vx.type != "VERTEX") fail(vx.line, &r, "expected VERTEX or SEQEND after the POLYLINE, got " + std::string(vx.type));
                long vflags = 0;
                Vec2 p;
                double b = 0;
                bool hx = false, hy = false;
                for (const DxfGroup& x : vx.groups) {
                    if (x.code == 10) p.x = number(x, &vx), hx = true;
                    else if (x.code == 20) p.y = number(x, &vx), hy = true;
                    else if (x.code == 42) b = number(x, &vx);
                    else if (x.code == 70) vflags = integer(x, &vx);
                }
                if (!hx || !hy) fail(vx.line, &vx, "a VERTEX needs its X and Y (10, 20)");
                if (vflags & 16) continue;  // a spline frame's control point: the fitted vertices follow
                v.push_back(p);
                bulge.push_back(b);
            }
            polyline(piece, r, v, bulge, (flags & 1) != 0, ocs(r, n));
            if (piece.path.segments.empty()) return;
        } else if (t == "ELLIPSE") {
            need({10, 20, 11, 21, 40});
            piece.origin = origin_of(r);
            ellipse(piece, r, {coord(10), coord(20)}, {coord(11), coord(21)}, coord(40), coord(41, 0.0), coord(42, two_pi), n.z < 0);
        } else if (t == "SPLINE") {
            piece.origin = origin_of(r);
            spline(piece, r);
        } else if (t == "INSERT") {
            insert(r, into, n);
            return;
        } else if (t == "TEXT" || t == "MTEXT" || t == "DIMENSION" || t == "HATCH" || t == "LEADER" || t == "MLEADER" ||
                   t == "MULTILEADER" || t == "ATTDEF" || t == "ATTRIB" || t == "VIEWPORT" || t == "SOLID" || t == "TOLERANCE" ||
                   t == "IMAGE" || t == "WIPEOUT" || t == "XLINE" || t == "RAY" || t == "TRACE" || t == "OLE2FRAME") {
            ++skipped_[std::string(t)];  // annotation and construction: not geometry to cut
            return;
        } else {
            fail(r.line, &r, "camgen does not read " + std::string(t) +
                                 " entities (it reads LINE, ARC, CIRCLE, LWPOLYLINE, POLYLINE, POINT, ELLIPSE, SPLINE, INSERT; "
                                 "explode or convert it in the CAD program)");
        }
        into.pieces.push_back(std::move(piece));
    }

    void skip_sequence(const DxfRecord& r) {
        bool follows = r.type == "POLYLINE";
        for (const DxfGroup& g : r.groups)
            if (g.code == 66 && integer(g) == 1) follows = true;
        if (!follows) return;
        DxfGroup g;
        DxfRecord x;
        while (next(g)) {
            read_record(x, g);
            if (x.type == "SEQEND") return;
        }
        cut_short(r.line, std::string(r.type));
    }

    void polyline(Piece& piece, const DxfRecord& r, const std::vector<Vec2>& v, const std::vector<double>& bulge, bool closed,
                  const DxfAffine& m) {
        if (v.empty()) fail(r.line, &r, "a polyline without vertices");
        Profile p;
        p.start = v[0];
        for (std::size_t i = 1; i < v.size(); ++i) add_bulge(p, v[i - 1], v[i], bulge[i - 1]);
        if (closed && v.size() > 1 && v.back() != v.front()) add_bulge(p, v.back(), v.front(), bulge.back());
        piece.closed = closed || (v.size() > 2 && v.back() == v.front());
        // A segment of length zero (a repeated vertex) is dropped.
        Profile clean;
        clean.start = p.start;
        Vec2 at = p.start;
        std::size_t dropped = 0;
        for (const ProfileSegment& s : p.segments) {
            if (distance(at, s.end) < profile_same_point) {
                ++dropped;
                continue;
            }
            clean.segments.push_back(s);
            at = s.end;
        }
        if (dropped)
            drawing_.notes.push_back(pairs_.name() + " line " + std::to_string(r.line) + ": " + where(r) + ": " + std::to_string(dropped) +
                                     " zero-length segment" + (dropped == 1 ? "" : "s") + " dropped");
        if (clean.segments.empty()) {
            drawing_.notes.push_back(pairs_.name() + " line " + std::to_string(r.line) + ": " + where(r) + ": a polyline of no length dropped");
            return;
        }
        piece.path = dxf_transform(clean, m);
    }

    // Arcs and lines within the tolerance along a parametric curve; `at(t)`, t from t0 to t1.
    // From `spans` even pieces, each piece is halved until a line from its start to its end,
    // or else the arc through its start, middle and end (a quarter turn at most), lies within
    // the tolerance of the curve's points at fifteen even steps inside it (the exact distance
    // of each point from the line or the arc). tests/unit/test_dxf.cpp measures the largest
    // deviation of fits against the curves ezdxf writes, densely sampled, both ways.
    template <class At>
    void fit(Piece& piece, const DxfRecord& r, At&& at, double t0, double t1, std::size_t spans) {
        const double tol = opt_.curve_tolerance;
        Profile& p = piece.path;
        p.start = at(t0);
        std::size_t count = 0;
        struct Span {
            double a, b;
            int depth;
        };
        constexpr int samples = 16;
        std::vector<Span> stack;
        for (std::size_t i = spans; i-- > 0;)
            stack.push_back({t0 + (t1 - t0) * double(i) / double(spans), t0 + (t1 - t0) * double(i + 1) / double(spans), 0});
        Vec2 inner[samples - 1];
        while (!stack.empty()) {
            const Span s = stack.back();
            stack.pop_back();
            const Vec2 a = at(s.a), b = at(s.b);
            for (int k = 1; k < samples; ++k) inner[k - 1] = at(s.a + (s.b - s.a) * k / samples);
            // The line.
            const Vec2 ab = b - a;
            const double len2 = dot(ab, ab);
            double worst = 0;
            for (const Vec2& q : inner) {
                const double t = len2 < 1e-24 ? 0.0 : std::clamp(dot(q - a, ab) / len2, 0.0, 1.0);
                worst = std::max(worst, distance(q, a + ab * t));
            }
            std::optional<ProfileSegment> seg;
            if (worst <= tol) {
                seg = ProfileSegment{b, std::nullopt, ArcDirection::ccw};
            } else {
                // The arc through start, middle and end.
                const Vec2 m = inner[samples / 2 - 1];
                const double d = 2 * cross(m - a, b - a);
                if (std::abs(d) > 1e-18) {
                    const Vec2 am = m - a, abv = b - a;
                    const Vec2 c = a + Vec2{(abv.y * dot(am, am) - am.y * dot(abv, abv)) / d, (am.x * dot(abv, abv) - abv.x * dot(am, am)) / d};
                    const double radius = distance(c, a);
                    const bool ccw = cross(m - a, b - m) > 0;
                    const double sa = std::atan2(a.y - c.y, a.x - c.x);
                    double sweep = std::atan2(b.y - c.y, b.x - c.x) - sa;
                    if (ccw && sweep < 0) sweep += two_pi;
                    if (!ccw && sweep > 0) sweep -= two_pi;
                    if (std::abs(sweep) <= pi / 2 + 1e-12) {
                        worst = 0;
                        for (const Vec2& q : inner) {
                            double u = std::atan2(q.y - c.y, q.x - c.x) - sa;
                            if (ccw && u < 0) u += two_pi;
                            if (!ccw && u > 0) u -= two_pi;
                            const bool within = ccw ? u <= sweep : u >= sweep;
                            worst = std::max(worst, within ? std::abs(distance(q, c) - radius) : std::min(distance(q, a), distance(q, b)));
                        }
                        if (worst <= tol) seg = ProfileSegment{b, c, ccw ? ArcDirection::ccw : ArcDirection::cw};
                    }
                }
            }
            if (!seg && s.depth < 30) {
                const double mid = (s.a + s.b) * 0.5;
                stack.push_back({mid, s.b, s.depth + 1});
                stack.push_back({s.a, mid, s.depth + 1});
                continue;
            }
            if (!seg) seg = ProfileSegment{b, std::nullopt, ArcDirection::ccw};
            if (distance(b, p.segments.empty() ? p.start : p.segments.back().end) >= profile_same_point) p.segments.push_back(*seg);
            if (++count > 10'000'000) fail(r.line, &r, "it needs more than 10,000,000 lines and arcs within the tolerance");
        }
    }

    void ellipse(Piece& piece, const DxfRecord& r, Vec2 c, Vec2 major, double ratio, double t0, double t1, bool mirrored) {
        const double a = norm(major);
        if (!(a > 0) || !(ratio > 0) || ratio > 1.0 + 1e-9) fail(r.line, &r, "its axes (11/21, 40) do not make an ellipse");
        while (t1 <= t0) t1 += two_pi;
        const bool full = t1 - t0 >= two_pi - 1e-9;
        const Vec2 minor = (mirrored ? left_of(major) * -1.0 : left_of(major)) * ratio;
        auto at = [&](double t) { return c + major * std::cos(t) + minor * std::sin(t); };
        if (std::abs(ratio - 1.0) < 1e-9) {  // a circle: arcs as arcs
            const ArcDirection dir = mirrored ? ArcDirection::cw : ArcDirection::ccw;
            piece.path.start = at(t0);
            const int n = (t1 - t0) > pi ? 2 : 1;
            for (int i = 1; i <= n; ++i) piece.path.segments.push_back({at(t0 + (t1 - t0) * i / n), c, dir});
        } else {
            fit(piece, r, at, t0, t1, std::max<std::size_t>(8, static_cast<std::size_t>(std::ceil((t1 - t0) / (pi / 8)))));
        }
        if (full) {
            piece.closed = true;
            piece.path.segments.back().end = piece.path.start;
        }
    }

    void spline(Piece& piece, const DxfRecord& r) {
        long flags = 0, degree = 3;
        std::vector<double> knots, weights;
        std::vector<Vec2> control, fitpts;
        Vec3 n{0, 0, 1};
        for (const DxfGroup& g : r.groups) {
            switch (g.code) {
                case 70: flags = integer(g, &r); break;
                case 71: degree = integer(g, &r); break;
                case 40: knots.push_back(number(g, &r)); break;
                case 41: weights.push_back(number(g, &r)); break;
                case 10: control.push_back({number(g, &r), 0}); break;
                case 20:
                    if (control.empty()) fail(g.line, &r, "a control point's Y (20) before its X (10)");
                    control.back().y = number(g, &r);
                    break;
                case 11: fitpts.push_back({number(g, &r), 0}); break;
                case 21:
                    if (fitpts.empty()) fail(g.line, &r, "a fit point's Y (21) before its X (11)");
                    fitpts.back().y = number(g, &r);
                    break;
                case 210: n.x = number(g, &r); break;
                case 220: n.y = number(g, &r); break;
                case 230: n.z = number(g, &r); break;
                default: break;
            }
        }
        (void)n;  // a spline's points are in world coordinates
        if (control.empty())
            fail(r.line, &r, "a spline given by fit points only (" + std::to_string(fitpts.size()) +
                                 "): camgen needs its control points; save the drawing with control points (or as polylines)");
        const std::size_t nc = control.size();
        if (degree < 1 || degree > 11) fail(r.line, &r, "its degree (71) must be 1 to 11, got " + std::to_string(degree));
        const std::size_t p = static_cast<std::size_t>(degree);
        if (nc <= p) fail(r.line, &r, "it has " + std::to_string(nc) + " control points, too few for degree " + std::to_string(p));
        if (knots.size() != nc + p + 1)
            fail(r.line, &r, "it has " + std::to_string(knots.size()) + " knots (40), but " + std::to_string(nc) + " control points of degree " +
                                 std::to_string(p) + " need " + std::to_string(nc + p + 1));
        for (std::size_t i = 1; i < knots.size(); ++i)
            if (knots[i] < knots[i - 1]) fail(r.line, &r, "its knots (40) decrease");
        if (!weights.empty() && weights.size() != nc)
            fail(r.line, &r, "it has " + std::to_string(weights.size()) + " weights (41) for " + std::to_string(nc) + " control points");
        for (double w : weights)
            if (!(w > 0)) fail(r.line, &r, "its weights (41) must be more than 0");
        if (weights.empty()) weights.assign(nc, 1.0);
        const double t0 = knots[p], t1 = knots[nc];
        if (!(t1 > t0)) fail(r.line, &r, "its knots (40) span nothing");
        // de Boor on homogeneous points.
        std::vector<double> hx(p + 1), hy(p + 1), hw(p + 1);
        auto at = [&](double t) {
            std::size_t k = p;
            while (k + 1 < nc && knots[k + 1] <= t) ++k;
            for (std::size_t j = 0; j <= p; ++j) {
                const std::size_t i = k - p + j;
                hw[j] = weights[i];
                hx[j] = control[i].x * weights[i];
                hy[j] = control[i].y * weights[i];
            }
            for (std::size_t level = 1; level <= p; ++level)
                for (std::size_t j = p; j >= level; --j) {
                    const std::size_t i = k - p + j;
                    const double den = knots[i + p + 1 - level] - knots[i];
                    const double alpha = den == 0 ? 0 : (t - knots[i]) / den;
                    hx[j] = (1 - alpha) * hx[j - 1] + alpha * hx[j];
                    hy[j] = (1 - alpha) * hy[j - 1] + alpha * hy[j];
                    hw[j] = (1 - alpha) * hw[j - 1] + alpha * hw[j];
                }
            return Vec2{hx[p] / hw[p], hy[p] / hw[p]};
        };
        const std::size_t spans = std::max<std::size_t>(8, 4 * (nc - p));
        fit(piece, r, at, t0, t1, std::min<std::size_t>(spans, 1'000'000));
        if (piece.path.segments.empty()) fail(r.line, &r, "a spline of no length");
        if ((flags & 1) || distance(piece.path.start, piece.path.segments.back().end) < profile_same_point) {
            piece.closed = true;
            if (distance(piece.path.start, piece.path.segments.back().end) < 10 * opt_.curve_tolerance)
                piece.path.segments.back().end = piece.path.start;
            else
                add_line(piece.path, piece.path.start);
        }
    }

    void insert(DxfRecord& r, DxfBlock& into, Vec3 n) {
        DxfBlock::Insert ins;
        ins.origin = origin_of(r);
        Vec2 at;
        double sx = 1, sy = 1, rot = 0, dx = 0, dy = 0;
        long cols = 1, rows = 1;
        for (const DxfGroup& g : r.groups) {
            switch (g.code) {
                case 2: ins.block = g.value; break;
                case 10: at.x = number(g, &r); break;
                case 20: at.y = number(g, &r); break;
                case 41: sx = number(g, &r); break;
                case 42: sy = number(g, &r); break;
                case 50: rot = number(g, &r); break;
                case 70: cols = integer(g, &r); break;
                case 71: rows = integer(g, &r); break;
                case 44: dx = number(g, &r); break;
                case 45: dy = number(g, &r); break;
                default: break;
            }
        }
        if (ins.block.empty()) fail(r.line, &r, "an INSERT needs its block's name (group code 2)");
        if (sx == 0 || sy == 0) fail(r.line, &r, "an INSERT scaled by 0");
        if (cols < 1 || rows < 1 || double(cols) * double(rows) > double(max_pieces))
            fail(r.line, &r, "its array of " + std::to_string(cols) + " x " + std::to_string(rows) + " copies is out of range");
        skip_sequence(r);
        const DxfAffine o = ocs(r, n);
        const Vec2 u = unit_at(rot * rad_per_deg);
        for (long j = 0; j < rows; ++j)
            for (long i = 0; i < cols; ++i) {
                // block point q -> o(at + R(rot) * (S * (q - base) + (i dx, j dy)))
                const Vec2 shift = at + rotated({double(i) * dx, double(j) * dy}, rot * rad_per_deg);
                DxfAffine m;
                m.a = u.x * sx, m.b = -u.y * sy, m.c = u.y * sx, m.d = u.x * sy;
                m.t = shift;
                ins.place = m.then(o);
                into.inserts.push_back(ins);
            }
    }

    // The model space's inserts expanded, nested, with their transforms.
    void resolve_inserts() {
        drawing_.pieces = std::move(model_.pieces);
        std::vector<std::string> chain;
        for (const DxfBlock::Insert& ins : model_.inserts) expand(ins, DxfAffine{}, nullptr, chain);
        for (const auto& [type, count] : skipped_)
            drawing_.notes.push_back(pairs_.name() + ": " + std::to_string(count) + " " + type + " entit" + (count == 1 ? "y" : "ies") +
                                     " left out (not geometry)");
    }

    void expand(const DxfBlock::Insert& ins, const DxfAffine& outer, const Origin* parent, std::vector<std::string>& chain) {
        const auto found = blocks_.find(dxf_upper(ins.block));
        auto insert_fail = [&](const std::string& message) {
            pairs_.fail(ins.origin.line, "INSERT (" + (ins.origin.handle.empty() ? "" : "handle " + ins.origin.handle + ", ") + "layer " +
                                             ins.origin.layer + "): " + message);
        };
        if (found == blocks_.end()) insert_fail("block " + ins.block + " is not defined in the BLOCKS section");
        if (std::find(chain.begin(), chain.end(), found->second.name) != chain.end())
            insert_fail("block " + ins.block + " inserts itself");
        if (static_cast<int>(chain.size()) >= max_insert_depth)
            insert_fail("inserts nested deeper than " + std::to_string(max_insert_depth));
        const DxfBlock& b = found->second;
        DxfAffine base;
        base.t = b.base * -1.0;
        const DxfAffine m = base.then(ins.place).then(outer);
        // What the insert passes on: layer "0", BYBLOCK linetype and colour take its own.
        Origin mine = ins.origin;
        if (parent) {
            if (mine.layer == "0") mine.layer = parent->layer;
            if (dxf_upper(mine.linetype) == "BYBLOCK") mine.linetype = parent->linetype;
            if (mine.colour == 0) mine.colour = parent->colour;
            mine.blocks = parent->blocks;
        }
        mine.blocks.push_back(b.name);
        chain.push_back(b.name);
        const std::optional<double> scale = m.uniform_scale();
        for (const Piece& p : b.pieces) {
            if (drawing_.pieces.size() >= max_pieces) insert_fail("the inserts make more than " + std::to_string(max_pieces) + " pieces");
            Piece q = p;
            if (q.origin.layer == "0") q.origin.layer = mine.layer;
            if (dxf_upper(q.origin.linetype) == "BYBLOCK") q.origin.linetype = mine.linetype;
            if (q.origin.colour == 0) q.origin.colour = mine.colour;
            q.origin.blocks = mine.blocks;
            const bool curved = q.kind == Piece::Kind::circle ||
                                std::any_of(q.path.segments.begin(), q.path.segments.end(), [](const ProfileSegment& s) { return s.centre.has_value(); });
            if (curved && !scale)
                insert_fail("block " + b.name + " is inserted with unequal X and Y scales: its " + q.origin.type + " (line " +
                            std::to_string(q.origin.line) + ") would be an ellipse; scale it evenly or explode it in the CAD program");
            if (q.kind == Piece::Kind::path) q.path = dxf_transform(q.path, m);
            else q.centre = m(q.centre);
            if (q.kind == Piece::Kind::circle) q.radius *= *scale;
            drawing_.pieces.push_back(std::move(q));
        }
        for (const DxfBlock::Insert& inner : b.inserts) expand(inner, m, &mine, chain);
        chain.pop_back();
    }

    void finish_layers() {
        for (Piece& p : drawing_.pieces) {
            auto found = layer_index_.find(dxf_upper(p.origin.layer));
            if (found == layer_index_.end()) {
                add_layer(Layer{p.origin.layer, 7, "CONTINUOUS"});
                found = layer_index_.find(dxf_upper(p.origin.layer));
            }
            const Layer& l = drawing_.layers[found->second];
            if (p.origin.colour == 256 || p.origin.colour == 0) p.origin.colour = l.colour;
            const std::string lt = dxf_upper(p.origin.linetype);
            if (lt == "BYLAYER" || lt == "BYBLOCK") p.origin.linetype = l.linetype;
        }
    }

    DxfPairs pairs_;
    const ReadOptions& opt_;
    Drawing drawing_;
    std::optional<DxfGroup> held_;
    std::size_t last_line_ = 0;
    DxfBlock model_;
    std::unordered_map<std::string, DxfBlock> blocks_;
    std::unordered_map<std::string, std::size_t> layer_index_;
    std::map<std::string, std::size_t> skipped_;
};

bool dxf_same_name(std::string_view a, std::string_view b) { return dxf_upper(a) == dxf_upper(b); }

}  // namespace

Drawing read_text(std::string_view text, const std::string& name, const ReadOptions& options) {
    static constexpr char binary_sentinel[] = "AutoCAD Binary DXF";
    if (text.substr(0, sizeof binary_sentinel - 1) == binary_sentinel)
        throw Error(name + ": a binary DXF: camgen reads ASCII DXF only; save the drawing as ASCII DXF from the CAD program");
    if (text.size() >= 6 && text.substr(0, 4) == "AC10" && std::isdigit(static_cast<unsigned char>(text[4])))
        throw Error(name + ": a DWG drawing (AutoCAD's own binary format), not DXF: save it as ASCII DXF from the CAD program");
    if (text.find('\0') != std::string_view::npos)
        throw Error(name + ": a binary file, not an ASCII DXF drawing");
    DxfReader reader(text, name, options);
    return reader.read();
}

Drawing read_file(const std::string& path, const ReadOptions& options) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open the drawing: " + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) throw Error(path + ": cannot read the drawing");
    if (static_cast<std::size_t>(size) > max_file_bytes)
        throw Error(path + ": the drawing is larger than " + std::to_string(max_file_bytes >> 20) + " MiB");
    in.seekg(0);
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), size);
    if (!in) throw Error(path + ": cannot read the drawing");
    return read_text(text, path, options);
}

std::optional<double> mm_per_unit(int insunits, std::string* name) {
    struct Unit {
        int code;
        double mm;
        const char* name;
    };
    static constexpr Unit units[] = {{1, 25.4, "inches"},      {2, 304.8, "feet"},        {4, 1.0, "millimetres"},
                                     {5, 10.0, "centimetres"}, {6, 1000.0, "metres"},     {8, 25.4e-6, "microinches"},
                                     {9, 0.0254, "mils"},      {10, 914.4, "yards"},      {13, 0.001, "microns"},
                                     {14, 100.0, "decimetres"}};
    for (const Unit& u : units)
        if (u.code == insunits) {
            if (name) *name = u.name;
            return u.mm;
        }
    if (name) *name = insunits == 0 ? "unitless" : "unit code " + std::to_string(insunits);
    return std::nullopt;
}

std::string describe(const Origin& o) {
    std::string s = o.type;
    if (!o.handle.empty()) s += " handle " + o.handle;
    s += " (line " + std::to_string(o.line) + ", layer " + o.layer + ")";
    return s;
}

std::vector<const Piece*> select(const Drawing& d, const Selection& s, std::string_view what) {
    auto list = [](const std::vector<std::string>& names) {
        std::string out;
        for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
        return out.empty() ? std::string("(none)") : out;
    };
    auto check_names = [&](const std::vector<std::string>& wanted, const std::vector<std::string>& have, const char* kind) {
        for (const std::string& w : wanted)
            if (std::none_of(have.begin(), have.end(), [&](const std::string& h) { return dxf_same_name(h, w); }))
                throw Error(d.name + ": " + kind + " " + w + " not found; " + kind + "s are: " + list(have));
    };
    std::vector<std::string> layers, linetypes, blocks;
    for (const Layer& l : d.layers) layers.push_back(l.name);
    for (const Piece& p : d.pieces) {
        if (std::none_of(linetypes.begin(), linetypes.end(), [&](const std::string& n) { return dxf_same_name(n, p.origin.linetype); }))
            linetypes.push_back(p.origin.linetype);
        for (const std::string& b : p.origin.blocks)
            if (std::none_of(blocks.begin(), blocks.end(), [&](const std::string& n) { return dxf_same_name(n, b); })) blocks.push_back(b);
    }
    check_names(s.layers, layers, "layer");
    check_names(s.linetypes, linetypes, "linetype");
    check_names(s.blocks, blocks, "block");
    std::vector<const Piece*> out;
    for (const Piece& p : d.pieces) {
        if (!s.layers.empty() && std::none_of(s.layers.begin(), s.layers.end(), [&](const std::string& n) { return dxf_same_name(n, p.origin.layer); }))
            continue;
        if (!s.colours.empty() && std::find(s.colours.begin(), s.colours.end(), p.origin.colour) == s.colours.end()) continue;
        if (!s.linetypes.empty() &&
            std::none_of(s.linetypes.begin(), s.linetypes.end(), [&](const std::string& n) { return dxf_same_name(n, p.origin.linetype); }))
            continue;
        if (!s.blocks.empty() && std::none_of(s.blocks.begin(), s.blocks.end(), [&](const std::string& n) {
                return std::any_of(p.origin.blocks.begin(), p.origin.blocks.end(), [&](const std::string& b) { return dxf_same_name(b, n); });
            }))
            continue;
        if (s.min_diameter || s.max_diameter) {
            if (p.kind != Piece::Kind::circle) continue;
            const double dia = 2 * p.radius;
            if (s.min_diameter && dia < *s.min_diameter - 1e-9) continue;
            if (s.max_diameter && dia > *s.max_diameter + 1e-9) continue;
        }
        out.push_back(&p);
    }
    (void)what;
    return out;
}

Box extent(const Profile& p) {
    Box b{p.start, p.start};
    for (Vec2 q : sample_profile(p, 0.001)) {
        b.min = {std::min(b.min.x, q.x), std::min(b.min.y, q.y)};
        b.max = {std::max(b.max.x, q.x), std::max(b.max.y, q.y)};
    }
    return b;
}

namespace {

Profile dxf_circle_profile(Vec2 c, double r) {
    Profile p;
    p.start = c + Vec2{r, 0};
    p.segments.push_back({c - Vec2{r, 0}, c, ArcDirection::ccw});
    p.segments.push_back({p.start, c, ArcDirection::ccw});
    return p;
}

Vec2 dxf_end(const Profile& p) { return p.segments.empty() ? p.start : p.segments.back().end; }

// The same geometry: same start and segments, or the same walked the other way.
bool dxf_same_path(const Profile& a, const Profile& b) {
    auto close = [](Vec2 p, Vec2 q) { return distance(p, q) < profile_same_point; };
    auto equal = [&](const Profile& x, const Profile& y) {
        if (x.segments.size() != y.segments.size() || !close(x.start, y.start)) return false;
        for (std::size_t i = 0; i < x.segments.size(); ++i) {
            const ProfileSegment &s = x.segments[i], &t = y.segments[i];
            if (!close(s.end, t.end) || s.centre.has_value() != t.centre.has_value()) return false;
            if (s.centre && (!close(*s.centre, *t.centre) || s.direction != t.direction)) return false;
        }
        return true;
    };
    return equal(a, b) || equal(a, reversed(b));
}

}  // namespace

ChainResult chain(const std::vector<const Piece*>& pieces, double gap, const std::string& file) {
    ChainResult result;
    struct Open {
        Profile path;
        const Piece* piece;
    };
    std::vector<Open> open;
    std::vector<std::pair<Profile, const Piece*>> seen;  // for duplicates, by first point bucket
    std::map<std::pair<long long, long long>, std::vector<std::size_t>> by_start;
    auto bucket = [](Vec2 p) { return std::pair<long long, long long>{std::llround(p.x * 1e4), std::llround(p.y * 1e4)}; };
    auto duplicate = [&](const Profile& p) {
        for (Vec2 key : {p.start, dxf_end(p)}) {
            const auto b = bucket(key);
            for (long long dx = -1; dx <= 1; ++dx)
                for (long long dy = -1; dy <= 1; ++dy) {
                    auto found = by_start.find({b.first + dx, b.second + dy});
                    if (found == by_start.end()) continue;
                    for (std::size_t i : found->second)
                        if (dxf_same_path(seen[i].first, p)) return seen[i].second;
                }
        }
        return static_cast<const Piece*>(nullptr);
    };
    for (const Piece* piece : pieces) {
        if (piece->kind == Piece::Kind::point) continue;
        Profile path = piece->kind == Piece::Kind::circle ? dxf_circle_profile(piece->centre, piece->radius) : piece->path;
        if (profile_length(path) < profile_same_point) {
            result.notes.push_back(file + ": " + describe(piece->origin) + " has no length: left out");
            continue;
        }
        if (const Piece* first = duplicate(path)) {
            result.notes.push_back(file + ": " + describe(piece->origin) + " is drawn twice (also " + describe(first->origin) + "): left out");
            continue;
        }
        seen.push_back({path, piece});
        by_start[bucket(path.start)].push_back(seen.size() - 1);
        const bool closed = piece->kind == Piece::Kind::circle || piece->closed || is_closed(path);
        if (closed) {
            Chain c;
            c.closed = true;
            c.profile = std::move(path);
            c.profile.segments.back().end = c.profile.start;
            c.pieces.push_back(piece);
            result.chains.push_back(std::move(c));
        } else {
            open.push_back({std::move(path), piece});
        }
    }
    // Greedy chaining: grow each chain at its end, then at its start, by the nearest free end
    // within `gap`.
    std::vector<bool> used(open.size(), false);
    // Ends bucketed by a grid of the gap's size (at least 1e-6).
    const double cell = std::max(gap, 1e-6) * 2;
    std::unordered_map<long long, std::vector<std::size_t>> ends;  // key -> 2 * index + (0 start, 1 end)
    auto key_of = [&](Vec2 p, long long dx, long long dy) {
        const long long x = static_cast<long long>(std::floor(p.x / cell)) + dx, y = static_cast<long long>(std::floor(p.y / cell)) + dy;
        return x * 1'000'003LL + y;
    };
    for (std::size_t i = 0; i < open.size(); ++i) {
        ends[key_of(open[i].path.start, 0, 0)].push_back(2 * i);
        ends[key_of(dxf_end(open[i].path), 0, 0)].push_back(2 * i + 1);
    }
    auto nearest = [&](Vec2 p) {
        std::optional<std::size_t> best;
        double best_d = gap;
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy) {
                auto found = ends.find(key_of(p, dx, dy));
                if (found == ends.end()) continue;
                for (std::size_t e : found->second) {
                    if (used[e / 2]) continue;
                    const Profile& q = open[e / 2].path;
                    const double d = distance(p, e % 2 ? dxf_end(q) : q.start);
                    if (d <= best_d && (!best || d < best_d || e < *best)) best = e, best_d = d;
                }
            }
        return best;
    };
    auto join_note = [&](const Piece* a, const Piece* b, double d) {
        if (d > profile_same_point)
            result.notes.push_back(file + ": a gap of " + dxf_number_text(d) + " between " + describe(a->origin) + " and " + describe(b->origin) +
                                   " closed");
    };
    for (std::size_t i = 0; i < open.size(); ++i) {
        if (used[i]) continue;
        used[i] = true;
        Chain c;
        c.profile = open[i].path;
        c.pieces.push_back(open[i].piece);
        // Forwards from the end.
        while (true) {
            const Vec2 e = dxf_end(c.profile);
            const std::optional<std::size_t> n = nearest(e);
            if (!n) break;
            used[*n / 2] = true;
            Profile next = *n % 2 ? reversed(open[*n / 2].path) : open[*n / 2].path;
            join_note(c.pieces.back(), open[*n / 2].piece, distance(e, next.start));
            for (const ProfileSegment& s : next.segments) c.profile.segments.push_back(s);
            c.pieces.push_back(open[*n / 2].piece);
        }
        // Backwards from the start.
        while (true) {
            const Vec2 s0 = c.profile.start;
            const std::optional<std::size_t> n = nearest(s0);
            if (!n) break;
            used[*n / 2] = true;
            Profile before = *n % 2 ? open[*n / 2].path : reversed(open[*n / 2].path);
            join_note(open[*n / 2].piece, c.pieces.front(), distance(dxf_end(before), s0));
            before.segments.back().end = s0;
            for (const ProfileSegment& s : c.profile.segments) before.segments.push_back(s);
            c.profile = std::move(before);
            c.pieces.insert(c.pieces.begin(), open[*n / 2].piece);
        }
        const double ends_apart = distance(c.profile.start, dxf_end(c.profile));
        if (ends_apart <= gap && (c.pieces.size() > 1 || open[i].piece->closed)) {
            join_note(c.pieces.back(), c.pieces.front(), ends_apart);
            c.profile.segments.back().end = c.profile.start;
            c.closed = true;
        }
        result.chains.push_back(std::move(c));
    }
    // Joined ends move a segment's end by up to the gap: arcs keep their centre (the end stays
    // within the gap of the circle).
    return result;
}

std::vector<int> nesting(const std::vector<Chain>& chains) {
    std::vector<int> parent(chains.size(), -1);
    std::vector<double> area(chains.size(), 0.0);
    for (std::size_t i = 0; i < chains.size(); ++i)
        if (chains[i].closed) area[i] = enclosed_area(chains[i].profile);
    for (std::size_t i = 0; i < chains.size(); ++i) {
        if (!chains[i].closed) continue;
        const std::vector<Vec2> pts = sample_profile(chains[i].profile, 0.01);
        for (std::size_t j = 0; j < chains.size(); ++j) {
            if (j == i || !chains[j].closed || area[j] <= area[i]) continue;
            // Inside when a point of it (off the other's boundary) is inside.
            bool inside = false;
            for (Vec2 p : pts)
                if (contains(chains[j].profile, p)) {
                    inside = true;
                    break;
                }
            if (inside && (parent[i] < 0 || area[j] < area[static_cast<std::size_t>(parent[i])])) parent[i] = static_cast<int>(j);
        }
    }
    return parent;
}

}  // namespace camgen::dxf
