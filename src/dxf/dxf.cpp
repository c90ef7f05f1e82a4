#include "camgen/dxf/dxf.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <deque>
#include <map>
#include <sstream>
#include <unordered_map>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "camgen/geometry/arc.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen::dxf {

// The text pieces name: interned names (layers, linetypes, block names), handles in chunks
// (never moved, so views stay valid), chains of block names.
struct DrawingText {
    std::deque<std::string> names;
    std::unordered_map<std::string_view, std::string_view> by_name;
    std::vector<std::unique_ptr<char[]>> chunks;
    std::size_t chunk_used = 0, chunk_size = 0;
    std::deque<std::vector<std::string_view>> chains;
    std::unordered_map<std::string, std::span<const std::string_view>> by_chain;
    std::string_view last_name;  // the name interned last (entities in a row share a layer)

    std::string_view intern(std::string_view s) {
        if (s == last_name) return last_name;
        const auto found = by_name.find(s);
        if (found != by_name.end()) return last_name = found->second;
        const std::string_view v = names.emplace_back(s);
        by_name.emplace(v, v);
        return last_name = v;
    }
    // A handle (any short text) kept in a chunk.
    std::string_view keep(std::string_view s) {
        if (s.empty()) return {};
        if (chunk_used + s.size() > chunk_size) {
            chunk_size = std::max<std::size_t>(s.size(), 64 * 1024);
            chunks.push_back(std::make_unique<char[]>(chunk_size));
            chunk_used = 0;
        }
        char* at = chunks.back().get() + chunk_used;
        std::memcpy(at, s.data(), s.size());
        chunk_used += s.size();
        return {at, s.size()};
    }
    std::span<const std::string_view> chain(const std::vector<std::string_view>& names_in) {
        std::string key;
        for (std::string_view n : names_in) (key += n) += '\n';
        const auto found = by_chain.find(key);
        if (found != by_chain.end()) return found->second;
        std::vector<std::string_view>& kept = chains.emplace_back();
        for (std::string_view n : names_in) kept.push_back(intern(n));
        const std::span<const std::string_view> s(kept);
        by_chain.emplace(std::move(key), s);
        return s;
    }
};

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

// The same name without case (ASCII, as CAD compares names).
bool dxf_same_name(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i]))) return false;
    return true;
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

// A file mapped for reading; the pages behind the reader are let go (`release`): a mapped
// file's page read again is read again from the page cache, so views into the text stay valid.
class DxfMappedFile {
public:
    explicit DxfMappedFile(const std::string& path) {
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0) throw Error(path + ": cannot open the drawing: " + std::strerror(errno));
        struct stat st {};
        if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
            ::close(fd_);
            throw Error(path + ": cannot read the drawing");
        }
        size_ = static_cast<std::size_t>(st.st_size);
        if (size_ > max_file_bytes) {
            ::close(fd_);
            throw Error(path + ": the drawing is larger than " + std::to_string(max_file_bytes >> 20) + " MiB");
        }
        if (size_ > 0) {
            void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd_, 0);
            if (p == MAP_FAILED) {
                ::close(fd_);
                throw Error(path + ": cannot read the drawing: " + std::strerror(errno));
            }
            data_ = static_cast<const char*>(p);
            ::madvise(p, size_, MADV_SEQUENTIAL);
        }
    }
    DxfMappedFile(const DxfMappedFile&) = delete;
    DxfMappedFile& operator=(const DxfMappedFile&) = delete;
    ~DxfMappedFile() {
        if (data_) ::munmap(const_cast<char*>(data_), size_);
        if (fd_ >= 0) ::close(fd_);
    }
    std::string_view text() const { return {data_ ? data_ : "", size_}; }
    // Lets the pages before `pos` go (whole pages only).
    void release(std::size_t pos) {
        const std::size_t page = 4096;
        const std::size_t end = pos / page * page;
        if (!data_ || end <= released_) return;
        ::madvise(const_cast<char*>(data_) + released_, end - released_, MADV_DONTNEED);
        released_ = end;
    }

private:
    int fd_ = -1;
    const char* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t released_ = 0;
};

constexpr const char* dxf_binary_words = "a binary file, not an ASCII DXF drawing";

// Reads the file's group pairs one at a time: a code line (an integer) and a value line.
class DxfPairs {
public:
    DxfPairs(std::string_view text, const std::string& name, DxfMappedFile* file)
        : text_(text), name_(name), file_(file) {}

    // The next pair; false at the end of the text (a code without a value is an error).
    bool next(DxfGroup& g) {
        if (pos_ >= text_.size()) return false;
        if (file_ && pos_ >= next_release_) {
            file_->release(pos_ - std::min<std::size_t>(pos_, release_step));
            next_release_ = pos_ + release_step;
        }
        const std::size_t code_line = line_ + 1;
        std::string_view code_text = take_line();
        // The common code: digits, right-aligned in three columns.
        std::size_t i = 0;
        while (i < code_text.size() && code_text[i] == ' ') ++i;
        int code = 0;
        std::size_t digits = 0;
        while (i < code_text.size() && digits < 9 && static_cast<unsigned>(code_text[i] - '0') < 10u) {
            code = code * 10 + (code_text[i] - '0');
            ++i;
            ++digits;
        }
        if (digits == 0 || i != code_text.size()) {
            const std::string_view trimmed = dxf_trim(code_text);
            if (pos_ >= text_.size() && trimmed.empty()) return false;
            const auto [p, ec] = std::from_chars(trimmed.data(), trimmed.data() + trimmed.size(), code);
            if (ec != std::errc{} || p != trimmed.data() + trimmed.size() || trimmed.empty())
                fail(code_line, "expected a group code (an integer), got \"" + std::string(trimmed.substr(0, 40)) +
                                    "\": the file is not an ASCII DXF, or it is damaged");
        }
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
    // The text not read yet.
    std::string_view rest() const { return text_.substr(pos_); }

private:
    static constexpr std::size_t release_step = std::size_t{4} << 20;

private:
    // The next line (lines are short: a byte loop beats memchr), a NUL byte refused.
    std::string_view take_line() {
        const char* begin = text_.data() + pos_;
        const char* end = text_.data() + text_.size();
        const char* p = begin;
        while (p != end && *p != '\n') {
            if (*p == '\0') throw Error(name_ + ": " + dxf_binary_words);
            ++p;
        }
        std::string_view l(begin, static_cast<std::size_t>(p - begin));
        pos_ = static_cast<std::size_t>(p - text_.data()) + (p != end ? 1 : 0);
        ++line_;
        return l;
    }
    std::string_view text_;
    const std::string& name_;
    DxfMappedFile* file_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
    std::size_t next_release_ = 0;
};

// ---- Entities as records of groups

// The groups an entity is read from, by code: the index of the first and of the last group of
// each code the reader asks for (-1: none).
enum DxfSlot { dxf_s5, dxf_s6, dxf_s8, dxf_s10, dxf_s20, dxf_s11, dxf_s21, dxf_s40, dxf_s41, dxf_s42, dxf_s50, dxf_s51,
               dxf_s62, dxf_s67, dxf_s70, dxf_s210, dxf_s220, dxf_s230, dxf_s2, dxf_s66, dxf_slots };

inline int dxf_slot_of(int code) {
    switch (code) {
        case 2: return dxf_s2;
        case 5: return dxf_s5;
        case 6: return dxf_s6;
        case 8: return dxf_s8;
        case 10: return dxf_s10;
        case 20: return dxf_s20;
        case 11: return dxf_s11;
        case 21: return dxf_s21;
        case 40: return dxf_s40;
        case 41: return dxf_s41;
        case 42: return dxf_s42;
        case 50: return dxf_s50;
        case 51: return dxf_s51;
        case 62: return dxf_s62;
        case 66: return dxf_s66;
        case 67: return dxf_s67;
        case 70: return dxf_s70;
        case 210: return dxf_s210;
        case 220: return dxf_s220;
        case 230: return dxf_s230;
        default: return -1;
    }
}

struct DxfRecord {
    std::string_view type;
    std::size_t line = 0;
    std::vector<DxfGroup> groups;  // after the "0" group, xdata and 102 groups left out
    int first[dxf_slots];
    int last[dxf_slots];
    void clear() {
        groups.clear();
        std::fill(std::begin(first), std::end(first), -1);
        std::fill(std::begin(last), std::end(last), -1);
    }
    void add(const DxfGroup& g) {
        const int s = dxf_slot_of(g.code);
        if (s >= 0) {
            if (first[s] < 0) first[s] = static_cast<int>(groups.size());
            last[s] = static_cast<int>(groups.size());
        }
        groups.push_back(g);
    }
    const DxfGroup* first_of(int slot) const { return first[slot] < 0 ? nullptr : &groups[static_cast<std::size_t>(first[slot])]; }
    const DxfGroup* last_of(int slot) const { return last[slot] < 0 ? nullptr : &groups[static_cast<std::size_t>(last[slot])]; }
};

// 2D affine placement: p' = m * p + t.
struct DxfAffine {
    double a = 1, b = 0, c = 0, d = 1;  // [a b; c d]
    Vec2 t;
    Vec2 operator()(Vec2 p) const { return {a * p.x + b * p.y + t.x, c * p.x + d * p.y + t.y}; }
    double det() const { return a * d - b * c; }
    bool identity() const { return a == 1 && b == 0 && c == 0 && d == 1 && t.x == 0 && t.y == 0; }
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

// The profile placed by `m`, in place.
void dxf_transform_in_place(Profile& p, const DxfAffine& m) {
    if (m.identity()) return;
    p.start = m(p.start);
    const bool flip = m.det() < 0;
    for (ProfileSegment& s : p.segments) {
        s.end = m(s.end);
        if (s.centre) {
            s.centre = m(*s.centre);
            if (flip) s.direction = s.direction == ArcDirection::ccw ? ArcDirection::cw : ArcDirection::ccw;
        }
    }
}

// A bulge segment from `from` to `to`: bulge = tan(sweep / 4), positive counter-clockwise.
ProfileSegment dxf_bulge_segment(Vec2 from, Vec2 to, double bulge) {
    if (bulge == 0 || from == to) return {to, std::nullopt, ArcDirection::ccw};
    const Vec2 chord = to - from;
    const double c = norm(chord);
    // The centre sits left of the chord for a positive bulge below 180 degrees.
    const double offset = c * (1.0 - bulge * bulge) / (4.0 * bulge);
    const Vec2 mid = (from + to) * 0.5;
    const Vec2 centre = mid + left_of(chord) * (offset / c);
    return {to, centre, bulge > 0 ? ArcDirection::ccw : ArcDirection::cw};
}

// A polyline's profile built vertex by vertex (no list of vertices kept): each vertex with the
// bulge of the segment after it; segments of no length (a repeated vertex) dropped and counted.
struct DxfPolylineBuilder {
    Profile path;
    Vec2 first, prev, at;
    double prev_bulge = 0;
    std::size_t count = 0, dropped = 0;
    bool closed = false;

    void add(Vec2 v, double bulge) {
        if (count == 0) {
            first = v;
            path.start = v;
            at = v;
        } else {
            segment(dxf_bulge_segment(prev, v, prev_bulge));
        }
        prev = v;
        prev_bulge = bulge;
        ++count;
    }
    void finish(bool closed_flag) {
        if (closed_flag && count > 1 && prev != first) segment(dxf_bulge_segment(prev, first, prev_bulge));
        closed = closed_flag || (count > 2 && prev == first);
    }

private:
    void segment(const ProfileSegment& s) {
        if (distance(at, s.end) < profile_same_point) {
            ++dropped;
            return;
        }
        path.segments.push_back(s);
        at = s.end;
    }
};

struct DxfBlock {
    std::string name;
    Vec2 base;
    std::vector<Piece> pieces;           // in block coordinates
    struct Insert {
        std::string_view block;
        DxfAffine place;                  // one per array copy
        Origin origin;
    };
    std::vector<Insert> inserts;
    std::size_t line = 0;
};

constexpr std::string_view dxf_type_names[] = {"LINE", "POINT", "CIRCLE", "ARC", "LWPOLYLINE", "POLYLINE", "ELLIPSE", "SPLINE", "INSERT"};

// The static name of an entity type the reader makes pieces of (else the record's own view).
std::string_view dxf_type_name(std::string_view t) {
    for (std::string_view n : dxf_type_names)
        if (n == t) return n;
    return t;
}

class DxfReader {
public:
    DxfReader(std::string_view text, const std::string& name, const ReadOptions& o, DxfMappedFile* file, const PieceSink* sink)
        : pairs_(text, name, file), opt_(o), sink_(sink), text_(std::make_shared<DrawingText>()) {
        drawing_.name = name;
    }

    Drawing read() {
        DxfGroup g;
        bool eof = false;
        {
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
        }
        if (!eof) cut_short(last_line_, "the drawing (no EOF)");
        if (std::memchr(pairs_.rest().data(), 0, pairs_.rest().size())) throw Error(pairs_.name() + ": " + dxf_binary_words);
        resolve_inserts();
        drawing_.text = text_;
        return std::move(drawing_);
    }

private:
    bool next(DxfGroup& g) {
        if (held_) {
            g = held_g_;
            held_ = false;
            return true;
        }
        if (!pairs_.next(g)) return false;
        last_line_ = g.line;
        return true;
    }
    void push_back(const DxfGroup& g) {
        held_g_ = g;
        held_ = true;
    }

    [[noreturn]] void cut_short(std::size_t line, const std::string& what) {
        pairs_.fail(line, "the file ends inside " + what + ": it is cut short (truncated)");
    }

    void skip_section(std::size_t line, const std::string& name) {
        DxfGroup g;
        while (next(g))
            if (g.code == 0 && g.value == "ENDSEC") return;
        cut_short(line, "section " + name);
    }

    static bool parse_number(const DxfGroup& g, double& x) {
        const std::string_view v = dxf_trim(g.value);
        const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
        return ec == std::errc{} && p == v.data() + v.size() && !v.empty() && std::isfinite(x) && std::abs(x) <= 1e12;
    }
    std::string number_message(const DxfGroup& g) const {
        return "group code " + std::to_string(g.code) + " needs a number, got \"" + std::string(dxf_trim(g.value).substr(0, 40)) + "\"";
    }
    double number(const DxfGroup& g, const DxfRecord* r = nullptr) {
        double x = 0;
        if (!parse_number(g, x)) fail(g.line, r, number_message(g));
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
        std::string_view handle, layer;
        for (const DxfGroup& g : r.groups) {
            if (g.code == 5) handle = g.value;
            if (g.code == 8) layer = g.value;
        }
        s += " (";
        if (!handle.empty()) (s += "handle ").append(handle) += ", ";
        s += "layer ";
        s.append(layer.empty() ? std::string_view("0") : layer) += ")";
        return s;
    }
    [[noreturn]] void fail(std::size_t line, const DxfRecord* r, const std::string& message) {
        pairs_.fail(line, r ? where(*r) + ": " + message : message);
    }

    // Reads one record after its "0" group: every group up to the next "0", which is held.
    // With `poly`, an LWPOLYLINE's vertices (10, 20, 42) go into it as they come instead of into
    // the record (the first fault in them kept in `fault` until the whole record is read, so
    // that the message names the handle and layer wherever they stand).
    struct PolyFault {
        std::size_t line = 0;
        std::string message;
    };
    void read_record(DxfRecord& r, const DxfGroup& head, DxfPolylineBuilder* poly = nullptr, PolyFault* fault = nullptr,
                     long* poly_flags = nullptr) {
        r.type = head.value;
        r.line = head.line;
        r.clear();
        DxfGroup g;
        bool in_102 = false;
        bool have_vertex = false;
        Vec2 vertex;
        double bulge = 0;
        while (true) {
            if (!next(g)) cut_short(head.line, std::string(head.value));
            if (g.code == 0) {
                push_back(g);
                break;
            }
            if (g.code == 102) {
                in_102 = !g.value.empty() && g.value.front() == '{';
                continue;
            }
            if (in_102 || g.code >= 1000 || g.code == 999) continue;
            if (poly && (g.code == 10 || g.code == 20 || g.code == 42 || g.code == 70)) {
                if (!fault->message.empty()) continue;
                double x = 0;
                if (g.code == 70) {
                    const std::string_view v = dxf_trim(g.value);
                    long f = 0;
                    const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), f);
                    if (ec != std::errc{} || p != v.data() + v.size() || v.empty())
                        *fault = {g.line, "group code 70 needs an integer, got \"" + std::string(v.substr(0, 40)) + "\""};
                    else *poly_flags = f;
                    continue;
                }
                if (!parse_number(g, x)) {
                    *fault = {g.line, number_message(g)};
                    continue;
                }
                if (g.code == 10) {
                    if (have_vertex) poly->add(vertex, bulge);
                    vertex = {x, 0};
                    bulge = 0;
                    have_vertex = true;
                } else if (g.code == 20) {
                    if (!have_vertex) *fault = {g.line, "a vertex's Y (20) before its X (10)"};
                    else vertex.y = x;
                } else {
                    if (!have_vertex) *fault = {g.line, "a bulge (42) before the first vertex"};
                    else bulge = x;
                }
                continue;
            }
            if (poly && g.code == 90) {
                // The count of vertices: room for the segments at once (no more than the text left could hold).
                const std::string_view v = dxf_trim(g.value);
                long n = 0;
                const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
                if (ec == std::errc{} && n > 0)
                    poly->path.segments.reserve(std::min(static_cast<std::size_t>(n) + 1, pairs_.rest().size() / 8 + 1));
            }
            r.add(g);
        }
        if (poly && have_vertex && fault->message.empty()) poly->add(vertex, bulge);
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
            if (g.value == "ENDSEC") {
                tables_read_ = true;
                return;
            }
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

    std::size_t add_layer(const Layer& l) {
        const std::string key = dxf_upper(l.name);
        const auto found = layer_index_.find(key);
        if (found != layer_index_.end()) return found->second;
        layer_index_[key] = drawing_.layers.size();
        drawing_.layers.push_back(l);
        layer_linetype_.push_back(text_->intern(l.linetype));
        return drawing_.layers.size() - 1;
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
        const std::size_t start = last_line_;
        while (next(g)) {
            if (g.code != 0) pairs_.fail(g.line, "expected \"0\" and an entity, got group code " + std::to_string(g.code));
            if (!block && g.value == "ENDSEC") return;
            if (block && g.value == "ENDBLK") {
                read_record(record_, g);
                return;
            }
            if (g.value == "LWPOLYLINE") {
                lwpolyline(g, into, block == nullptr);
                continue;
            }
            read_record(record_, g);
            entity(record_, into, block == nullptr);
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
        o.type = dxf_type_name(r.type);
        o.line = r.line;
        o.layer = "0";
        o.linetype = "BYLAYER";
        o.colour = 256;
        if (const DxfGroup* g = r.last_of(dxf_s5)) o.handle = text_->keep(g->value);
        if (const DxfGroup* g = r.last_of(dxf_s8)) o.layer = text_->intern(g->value);
        if (const DxfGroup* g = r.last_of(dxf_s6)) o.linetype = text_->intern(g->value);
        if (r.first[dxf_s62] >= 0)
            for (const DxfGroup& g : r.groups)
                if (g.code == 62) o.colour = static_cast<int>(integer(g, &r));
        return o;
    }

    static void add_line(Profile& p, Vec2 to) { p.segments.push_back({to, std::nullopt, ArcDirection::ccw}); }

    // Paper space (67 = 1) when it is left out, and the extrusion (210, 220, 230: the last of each).
    bool paper(const DxfRecord& r) {
        if (r.first[dxf_s67] < 0) return false;
        for (const DxfGroup& g : r.groups)
            if (g.code == 67 && integer(g, &r) == 1 && !opt_.paper_space) return true;
        return false;
    }
    Vec3 extrusion(const DxfRecord& r) {
        Vec3 n{0, 0, 1};
        if (r.first[dxf_s210] < 0 && r.first[dxf_s220] < 0 && r.first[dxf_s230] < 0) return n;
        for (const DxfGroup& g : r.groups) {
            if (g.code == 210) n.x = number(g, &r);
            else if (g.code == 220) n.y = number(g, &r);
            else if (g.code == 230) n.z = number(g, &r);
        }
        return n;
    }

    // An LWPOLYLINE, its vertices read as they come.
    void lwpolyline(const DxfGroup& head, DxfBlock& into, bool model) {
        DxfPolylineBuilder b;
        PolyFault fault;
        long flags = 0;
        read_record(record_, head, &b, &fault, &flags);
        const DxfRecord& r = record_;
        if (paper(r)) return;
        const Vec3 n = extrusion(r);
        Piece piece;
        piece.origin = origin_of(r);
        if (!fault.message.empty()) fail(fault.line, &r, fault.message);
        if (!polyline(piece, r, b, (flags & 1) != 0, ocs(r, n))) return;
        keep(std::move(piece), into, model);
    }

    void entity(DxfRecord& r, DxfBlock& into, bool model) {
        const std::string_view t = r.type;
        // Paper space: left out unless asked.
        if (paper(r)) {
            if (t == "POLYLINE" || t == "INSERT") skip_sequence(r);
            return;
        }
        const Vec3 n = extrusion(r);
        auto coord = [&](int slot, double fallback = 0.0) {
            const DxfGroup* g = r.first_of(slot);
            return g ? number(*g, &r) : fallback;
        };
        auto need = [&](std::initializer_list<std::pair<int, int>> codes) {
            for (const auto& [code, slot] : codes)
                if (r.first[slot] < 0) fail(r.line, &r, "group code " + std::to_string(code) + " is missing");
        };
        Piece piece;
        if (t == "CIRCLE") {
            need({{10, dxf_s10}, {20, dxf_s20}, {40, dxf_s40}});
            piece.origin = origin_of(r);
            piece.kind = Piece::Kind::circle;
            const DxfAffine m = ocs(r, n);
            piece.centre = m({coord(dxf_s10), coord(dxf_s20)});
            piece.radius = coord(dxf_s40);
            if (!(piece.radius > 0)) fail(r.line, &r, "its radius (group code 40) must be more than 0");
        } else if (t == "LINE") {
            need({{10, dxf_s10}, {20, dxf_s20}, {11, dxf_s11}, {21, dxf_s21}});
            piece.origin = origin_of(r);
            piece.path.start = {coord(dxf_s10), coord(dxf_s20)};
            add_line(piece.path, {coord(dxf_s11), coord(dxf_s21)});
        } else if (t == "POINT") {
            need({{10, dxf_s10}, {20, dxf_s20}});
            piece.origin = origin_of(r);
            piece.kind = Piece::Kind::point;
            piece.centre = {coord(dxf_s10), coord(dxf_s20)};
        } else if (t == "ARC") {
            need({{10, dxf_s10}, {20, dxf_s20}, {40, dxf_s40}, {50, dxf_s50}, {51, dxf_s51}});
            piece.origin = origin_of(r);
            const Vec2 c{coord(dxf_s10), coord(dxf_s20)};
            const double radius = coord(dxf_s40);
            if (!(radius > 0)) fail(r.line, &r, "its radius (group code 40) must be more than 0");
            double a0 = coord(dxf_s50), a1 = coord(dxf_s51);
            while (a1 <= a0) a1 += 360.0;
            piece.path.start = c + unit_at(a0 * rad_per_deg) * radius;
            const Vec2 end = c + unit_at(a1 * rad_per_deg) * radius;
            piece.path.segments.push_back({end, c, ArcDirection::ccw});
            dxf_transform_in_place(piece.path, ocs(r, n));
        } else if (t == "POLYLINE") {
            piece.origin = origin_of(r);
            long flags = 0;
            for (const DxfGroup& g : r.groups)
                if (g.code == 70) flags = integer(g, &r);
            if (flags & (8 | 16 | 64))
                fail(r.line, &r, "a 3D polyline, polygon mesh or polyface mesh: camgen takes 2D drawings in XY");
            DxfPolylineBuilder b;
            DxfGroup g;
            DxfRecord& vx = vertex_;
            const std::size_t head_line = r.line;
            const DxfRecord& head = r;  // record_: the vertices are read into vertex_
            while (true) {
                if (!next(g)) cut_short(head_line, "a POLYLINE (no SEQEND)");
                if (g.code != 0) pairs_.fail(g.line, "expected \"0\" and VERTEX or SEQEND, got group code " + std::to_string(g.code));
                read_record(vx, g);
                if (vx.type == "SEQEND") break;
                if (vx.type != "VERTEX") fail(vx.line, &head, "expected VERTEX or SEQEND after the POLYLINE, got " + std::string(vx.type));
                long vflags = 0;
                Vec2 p;
                double bulge = 0;
                bool hx = false, hy = false;
                for (const DxfGroup& x : vx.groups) {
                    if (x.code == 10) p.x = number(x, &vx), hx = true;
                    else if (x.code == 20) p.y = number(x, &vx), hy = true;
                    else if (x.code == 42) bulge = number(x, &vx);
                    else if (x.code == 70) vflags = integer(x, &vx);
                }
                if (!hx || !hy) fail(vx.line, &vx, "a VERTEX needs its X and Y (10, 20)");
                if (vflags & 16) continue;  // a spline frame's control point: the fitted vertices follow
                b.add(p, bulge);
            }
            if (!polyline(piece, head, b, (flags & 1) != 0, ocs(head, n))) return;
        } else if (t == "ELLIPSE") {
            need({{10, dxf_s10}, {20, dxf_s20}, {11, dxf_s11}, {21, dxf_s21}, {40, dxf_s40}});
            piece.origin = origin_of(r);
            ellipse(piece, r, {coord(dxf_s10), coord(dxf_s20)}, {coord(dxf_s11), coord(dxf_s21)}, coord(dxf_s40), coord(dxf_s41, 0.0),
                    coord(dxf_s42, two_pi), n.z < 0);
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
        keep(std::move(piece), into, model);
    }

    void skip_sequence(const DxfRecord& r) {
        bool follows = r.type == "POLYLINE";
        for (const DxfGroup& g : r.groups)
            if (g.code == 66 && integer(g) == 1) follows = true;
        if (!follows) return;
        DxfGroup g;
        const std::string type(r.type);
        const std::size_t line = r.line;
        DxfRecord& x = vertex_;
        while (next(g)) {
            read_record(x, g);
            if (x.type == "SEQEND") return;
        }
        cut_short(line, type);
    }

    // The polyline's profile into the piece, placed by `m`; false when nothing is left of it.
    bool polyline(Piece& piece, const DxfRecord& r, DxfPolylineBuilder& b, bool closed, const DxfAffine& m) {
        if (b.count == 0) fail(r.line, &r, "a polyline without vertices");
        b.finish(closed);
        piece.closed = b.closed;
        if (b.dropped)
            drawing_.notes.push_back(pairs_.name() + " line " + std::to_string(r.line) + ": " + where(r) + ": " + std::to_string(b.dropped) +
                                     " zero-length segment" + (b.dropped == 1 ? "" : "s") + " dropped");
        if (b.path.segments.empty()) {
            drawing_.notes.push_back(pairs_.name() + " line " + std::to_string(r.line) + ": " + where(r) + ": a polyline of no length dropped");
            return false;
        }
        piece.path = std::move(b.path);
        if (piece.path.segments.capacity() > piece.path.segments.size() + piece.path.segments.size() / 8) piece.path.segments.shrink_to_fit();
        dxf_transform_in_place(piece.path, m);
        return true;
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
        ins.block = text_->intern(ins.block);
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

    // A piece read: kept in its block, or (model space) handed on; held while the layer table
    // may still come.
    void keep(Piece&& p, DxfBlock& into, bool model) {
        if (!model) into.pieces.push_back(std::move(p));
        else if (tables_read_) deliver(std::move(p));
        else pending_.push_back(std::move(p));
    }

    // The piece's BYLAYER colour and linetype resolved (a layer only entities name is added),
    // then handed to the sink or kept in the drawing.
    void deliver(Piece&& p) {
        std::size_t index = 0;
        const auto cached = layer_of_.find(p.origin.layer.data());
        if (cached != layer_of_.end() && cached->second.first == p.origin.layer.size()) {
            index = cached->second.second;
        } else {
            index = add_layer(Layer{std::string(p.origin.layer), 7, "CONTINUOUS"});
            layer_of_[p.origin.layer.data()] = {p.origin.layer.size(), index};
        }
        const Layer& l = drawing_.layers[index];
        if (p.origin.colour == 256 || p.origin.colour == 0) p.origin.colour = l.colour;
        if (dxf_same_name(p.origin.linetype, "BYLAYER") || dxf_same_name(p.origin.linetype, "BYBLOCK")) p.origin.linetype = layer_linetype_[index];
        ++delivered_;
        if (sink_) (*sink_)(std::move(p));
        else drawing_.pieces.push_back(std::move(p));
    }

    // The pieces held, then the model space's inserts expanded, nested, with their transforms.
    void resolve_inserts() {
        for (Piece& p : pending_) deliver(std::move(p));
        pending_ = {};
        std::vector<std::string_view> chain;
        for (const DxfBlock::Insert& ins : model_.inserts) expand(ins, DxfAffine{}, nullptr, chain);
        for (const auto& [type, count] : skipped_)
            drawing_.notes.push_back(pairs_.name() + ": " + std::to_string(count) + " " + type + " entit" + (count == 1 ? "y" : "ies") +
                                     " left out (not geometry)");
    }

    void expand(const DxfBlock::Insert& ins, const DxfAffine& outer, const Origin* parent, std::vector<std::string_view>& chain) {
        const auto found = blocks_.find(dxf_upper(ins.block));
        auto insert_fail = [&](const std::string& message) {
            pairs_.fail(ins.origin.line, "INSERT (" + (ins.origin.handle.empty() ? "" : "handle " + std::string(ins.origin.handle) + ", ") +
                                             "layer " + std::string(ins.origin.layer) + "): " + message);
        };
        if (found == blocks_.end()) insert_fail("block " + std::string(ins.block) + " is not defined in the BLOCKS section");
        if (std::find(chain.begin(), chain.end(), std::string_view(found->second.name)) != chain.end())
            insert_fail("block " + std::string(ins.block) + " inserts itself");
        if (static_cast<int>(chain.size()) >= max_insert_depth)
            insert_fail("inserts nested deeper than " + std::to_string(max_insert_depth));
        const DxfBlock& b = found->second;
        DxfAffine base;
        base.t = b.base * -1.0;
        const DxfAffine m = base.then(ins.place).then(outer);
        // What the insert passes on: layer "0", BYBLOCK linetype and colour take its own.
        Origin mine = ins.origin;
        std::vector<std::string_view> names;
        if (parent) {
            if (mine.layer == "0") mine.layer = parent->layer;
            if (dxf_same_name(mine.linetype, "BYBLOCK")) mine.linetype = parent->linetype;
            if (mine.colour == 0) mine.colour = parent->colour;
            names.assign(parent->blocks.begin(), parent->blocks.end());
        }
        names.push_back(b.name);
        mine.blocks = text_->chain(names);
        chain.push_back(b.name);
        const std::optional<double> scale = m.uniform_scale();
        for (const Piece& p : b.pieces) {
            if (delivered_ >= max_pieces) insert_fail("the inserts make more than " + std::to_string(max_pieces) + " pieces");
            Piece q = p;
            if (q.origin.layer == "0") q.origin.layer = mine.layer;
            if (dxf_same_name(q.origin.linetype, "BYBLOCK")) q.origin.linetype = mine.linetype;
            if (q.origin.colour == 0) q.origin.colour = mine.colour;
            q.origin.blocks = mine.blocks;
            const bool curved = q.kind == Piece::Kind::circle ||
                                std::any_of(q.path.segments.begin(), q.path.segments.end(), [](const ProfileSegment& s) { return s.centre.has_value(); });
            if (curved && !scale)
                insert_fail("block " + b.name + " is inserted with unequal X and Y scales: its " + std::string(q.origin.type) + " (line " +
                            std::to_string(q.origin.line) + ") would be an ellipse; scale it evenly or explode it in the CAD program");
            if (q.kind == Piece::Kind::path) dxf_transform_in_place(q.path, m);
            else q.centre = m(q.centre);
            if (q.kind == Piece::Kind::circle) q.radius *= *scale;
            deliver(std::move(q));
        }
        for (const DxfBlock::Insert& inner : b.inserts) expand(inner, m, &mine, chain);
        chain.pop_back();
    }

    DxfPairs pairs_;
    const ReadOptions& opt_;
    const PieceSink* sink_;
    std::shared_ptr<DrawingText> text_;
    Drawing drawing_;
    DxfGroup held_g_;
    bool held_ = false;
    std::size_t last_line_ = 0;
    DxfRecord record_, vertex_;
    DxfBlock model_;
    bool tables_read_ = false;
    std::vector<Piece> pending_;
    std::size_t delivered_ = 0;
    std::unordered_map<std::string, DxfBlock> blocks_;
    std::unordered_map<std::string, std::size_t> layer_index_;
    std::vector<std::string_view> layer_linetype_;  // interned, by layer index
    std::unordered_map<const char*, std::pair<std::size_t, std::size_t>> layer_of_;  // a layer name's text -> (size, layer index)
    std::map<std::string, std::size_t> skipped_;
};

}  // namespace

namespace {

// Binary DXF and DWG refused by name (a NUL byte anywhere else is refused as the reader meets
// it, and any other fault of a file with a NUL byte is that).
void dxf_check_text(std::string_view text, const std::string& name) {
    static constexpr char binary_sentinel[] = "AutoCAD Binary DXF";
    if (text.substr(0, sizeof binary_sentinel - 1) == binary_sentinel)
        throw Error(name + ": a binary DXF: camgen reads ASCII DXF only; save the drawing as ASCII DXF from the CAD program");
    if (text.size() >= 6 && text.substr(0, 4) == "AC10" && std::isdigit(static_cast<unsigned char>(text[4])))
        throw Error(name + ": a DWG drawing (AutoCAD's own binary format), not DXF: save it as ASCII DXF from the CAD program");
}

Drawing dxf_read(std::string_view text, const std::string& name, const ReadOptions& options, DxfMappedFile* file, const PieceSink* each) {
    dxf_check_text(text, name);
    try {
        return DxfReader(text, name, options, file, each).read();
    } catch (const Error&) {
        if (std::memchr(text.data(), 0, text.size())) throw Error(name + ": " + dxf_binary_words);
        throw;
    }
}

}  // namespace

Drawing read_text(std::string_view text, const std::string& name, const ReadOptions& options) {
    return dxf_read(text, name, options, nullptr, nullptr);
}

Drawing read_text(std::string_view text, const std::string& name, const PieceSink& each, const ReadOptions& options) {
    return dxf_read(text, name, options, nullptr, &each);
}

Drawing read_file(const std::string& path, const ReadOptions& options) {
    DxfMappedFile file(path);
    return dxf_read(file.text(), path, options, &file, nullptr);
}

Drawing read_file(const std::string& path, const PieceSink& each, const ReadOptions& options) {
    DxfMappedFile file(path);
    return dxf_read(file.text(), path, options, &file, &each);
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
    std::string s(o.type);
    if (!o.handle.empty()) (s += " handle ").append(o.handle);
    (s += " (line " + std::to_string(o.line) + ", layer ").append(o.layer) += ")";
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
            linetypes.emplace_back(p.origin.linetype);
        for (std::string_view b : p.origin.blocks)
            if (std::none_of(blocks.begin(), blocks.end(), [&](const std::string& n) { return dxf_same_name(n, b); })) blocks.emplace_back(b);
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
                return std::any_of(p.origin.blocks.begin(), p.origin.blocks.end(), [&](std::string_view b) { return dxf_same_name(b, n); });
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

namespace {

// chain() and chain_taking(): with `take`, the pieces' paths are moved into the chains.
ChainResult dxf_chain(const std::vector<const Piece*>& pieces, double gap, const std::string& file, bool take) {
    ChainResult result;
    struct Open {
        Profile path;
        const Piece* piece;
    };
    std::vector<Open> open;
    // For duplicates, by first point bucket: the pieces' own paths (circles' made once), not copies.
    std::vector<std::pair<const Profile*, const Piece*>> seen;
    std::deque<Profile> circle_paths;
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
                        if (dxf_same_path(*seen[i].first, p)) return seen[i].second;
                }
        }
        return static_cast<const Piece*>(nullptr);
    };
    // First the pieces left out (no length, drawn twice), each compared in place.
    for (const Piece* piece : pieces) {
        if (piece->kind == Piece::Kind::point) continue;
        const Profile* own = &piece->path;
        if (piece->kind == Piece::Kind::circle) own = &circle_paths.emplace_back(dxf_circle_profile(piece->centre, piece->radius));
        if (profile_length(*own) < profile_same_point) {
            result.notes.push_back(file + ": " + describe(piece->origin) + " has no length: left out");
            if (piece->kind == Piece::Kind::circle) circle_paths.pop_back();
            continue;
        }
        if (const Piece* first = duplicate(*own)) {
            result.notes.push_back(file + ": " + describe(piece->origin) + " is drawn twice (also " + describe(first->origin) + "): left out");
            if (piece->kind == Piece::Kind::circle) circle_paths.pop_back();
            continue;
        }
        seen.push_back({own, piece});
        by_start[bucket(own->start)].push_back(seen.size() - 1);
    }
    // Then each piece kept: a closed chain of its own, or open, to be chained.
    std::size_t circle = 0;
    for (const auto& [own, piece] : seen) {
        Profile path;
        if (piece->kind == Piece::Kind::circle) path = std::move(circle_paths[circle++]);
        else if (take) path = std::move(const_cast<Piece*>(piece)->path);
        else path = piece->path;
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
        c.profile = std::move(open[i].path);  // used: no longer looked at
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

}  // namespace

ChainResult chain(const std::vector<const Piece*>& pieces, double gap, const std::string& file) {
    return dxf_chain(pieces, gap, file, false);
}

ChainResult chain_taking(const std::vector<Piece*>& pieces, double gap, const std::string& file) {
    return dxf_chain(std::vector<const Piece*>(pieces.begin(), pieces.end()), gap, file, true);
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
