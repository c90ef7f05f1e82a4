#include "camgen/common/json_util.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_set>

#include "camgen/common/error.hpp"
#include "camgen/common/large_buffer.hpp"
#include "src/common/fast_json_reader.hpp"

namespace camgen::json {

namespace {

// Appends the code point `cp` to `out` as UTF-8.
void append_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

// A single pass over valid JSON text that reports every value's pointer and line.
// Iterative (an explicit stack), so deeply nested input cannot overflow the call stack.
class Scanner {
public:
    explicit Scanner(std::string_view text) : text_(text) {}

    // Calls on_value(pointer, line) for every value in document order, and
    // on_duplicate(pointer, line) for an object key seen twice in the same object
    // (only when `check_duplicates`).
    template <class OnValue, class OnDuplicate>
    void run(OnValue&& on_value, OnDuplicate&& on_duplicate, bool check_duplicates) {
        struct Frame {
            bool object;
            std::size_t index;
            std::size_t prefix;  // length of the container's own pointer
            std::unordered_set<std::string> keys;
        };
        std::vector<Frame> stack;
        std::string pointer;
        skip_ws();
        int value_line = line_;
        enum class State { value, element, after };
        State state = State::value;
        while (pos_ < text_.size()) {
            if (state == State::value) {
                on_value(std::string_view(pointer), value_line);
                const char c = text_[pos_];
                if (c == '{' || c == '[') {
                    stack.push_back(Frame{c == '{', 0, pointer.size(), {}});
                    ++pos_;
                    skip_ws();
                    if (pos_ < text_.size() && (text_[pos_] == '}' || text_[pos_] == ']')) {
                        ++pos_;
                        stack.pop_back();
                        state = State::after;
                    } else {
                        state = State::element;
                    }
                } else {
                    skip_scalar();
                    state = State::after;
                }
            } else if (state == State::element) {
                Frame& frame = stack.back();
                pointer.resize(frame.prefix);
                pointer += '/';
                value_line = line_;
                if (frame.object) {
                    std::string key = read_string();
                    pointer += pointer_escape(key);
                    if (check_duplicates && !frame.keys.insert(std::move(key)).second)
                        on_duplicate(std::string_view(pointer), value_line);
                    skip_ws();
                    if (pos_ < text_.size() && text_[pos_] == ':') ++pos_;
                    skip_ws();
                } else {
                    pointer += std::to_string(frame.index);
                }
                ++frame.index;
                state = State::value;
            } else {
                if (stack.empty()) break;
                skip_ws();
                if (pos_ >= text_.size()) break;
                if (text_[pos_] == ',') {
                    ++pos_;
                    skip_ws();
                    state = State::element;
                } else {  // '}' or ']'
                    ++pos_;
                    pointer.resize(stack.back().prefix);
                    stack.pop_back();
                }
            }
        }
    }

private:
    void skip_ws() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_;
            } else if (c != ' ' && c != '\t' && c != '\r') {
                break;
            }
            ++pos_;
        }
    }

    // Skips a number, literal or string.
    void skip_scalar() {
        if (text_[pos_] == '"') {
            ++pos_;
            while (pos_ < text_.size() && text_[pos_] != '"') pos_ += text_[pos_] == '\\' ? 2 : 1;
            ++pos_;
            return;
        }
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == ',' || c == ']' || c == '}' || c == ' ' || c == '\t' || c == '\r' ||
                c == '\n')
                break;
            ++pos_;
        }
    }

    unsigned hex4() {
        unsigned value = 0;
        for (int i = 0; i < 4 && pos_ < text_.size(); ++i, ++pos_) {
            const char c = text_[pos_];
            value <<= 4;
            if (c >= '0' && c <= '9') value |= static_cast<unsigned>(c - '0');
            else if (c >= 'a' && c <= 'f') value |= static_cast<unsigned>(c - 'a' + 10);
            else if (c >= 'A' && c <= 'F') value |= static_cast<unsigned>(c - 'A' + 10);
        }
        return value;
    }

    // Reads a string token (pos_ at its opening quote) and returns it decoded.
    std::string read_string() {
        std::string out;
        ++pos_;
        while (pos_ < text_.size() && text_[pos_] != '"') {
            const char c = text_[pos_++];
            if (c != '\\') {
                out += c;
                continue;
            }
            if (pos_ >= text_.size()) break;
            const char e = text_[pos_++];
            switch (e) {
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': {
                    std::uint32_t cp = hex4();
                    if (cp >= 0xD800 && cp < 0xDC00 && pos_ + 1 < text_.size() &&
                        text_[pos_] == '\\' && text_[pos_ + 1] == 'u') {
                        pos_ += 2;
                        const std::uint32_t low = hex4();
                        cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
                    }
                    append_utf8(out, cp);
                    break;
                }
                default: out += e; break;  // '"', '\\', '/'
            }
        }
        ++pos_;
        return out;
    }

    std::string_view text_;
    std::size_t pos_ = 0;
    int line_ = 1;
};

// Line (1-based) and column (1-based, in bytes) of the byte at `index`.
std::pair<int, int> line_column(std::string_view text, std::size_t index) {
    index = std::min(index, text.size());
    const auto head = text.substr(0, index);
    const int line = 1 + static_cast<int>(std::count(head.begin(), head.end(), '\n'));
    const auto newline = head.rfind('\n');
    const auto column = newline == std::string_view::npos ? index + 1 : index - newline;
    return {line, static_cast<int>(column)};
}

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// If the token around `index` (where parsing stopped) spells NaN or Infinity, where it starts.
std::optional<std::size_t> nan_or_infinity_at(std::string_view text, std::size_t index) {
    if (index >= text.size()) return std::nullopt;
    std::size_t start = index;
    while (start > 0) {
        const unsigned char c = static_cast<unsigned char>(text[start - 1]);
        if (!std::isalpha(c) && c != '-' && c != '+') break;
        --start;
    }
    std::size_t end = index;
    while (end < text.size() && std::isalpha(static_cast<unsigned char>(text[end]))) ++end;
    std::string token = lower(text.substr(start, end - start));
    while (!token.empty() && (token[0] == '-' || token[0] == '+')) token.erase(0, 1);
    if (token.starts_with("nan") || token.starts_with("inf")) return start;
    return std::nullopt;
}

// "an object", "a string \"abc\"", "null", ...: the actual value, for type errors.
std::string describe(const nlohmann::json& value) {
    using T = nlohmann::json::value_t;
    switch (value.type()) {
        case T::null: return "null";
        case T::object: return "an object";
        case T::array: return "an array";
        case T::boolean: return value.get<bool>() ? "a boolean (true)" : "a boolean (false)";
        case T::string: {
            std::string text = value.dump();
            if (text.size() > 40) text = text.substr(0, 36) + "...\"";
            return "a string " + text;
        }
        case T::number_integer:
        case T::number_unsigned:
        case T::number_float: return "a number (" + value.dump() + ")";
        default: return value.type_name();
    }
}

[[noreturn]] void type_error(const Source& source, const std::string& path, const char* expected,
                             const nlohmann::json& got) {
    fail(source, path, std::string("expected ") + expected + ", got " + describe(got));
}

double checked_number(const nlohmann::json& value, const std::string& path, const Source& source) {
    if (!value.is_number()) type_error(source, path, "a number", value);
    const double d = value.get<double>();
    if (!std::isfinite(d)) fail(source, path, "expected a finite number, got " + value.dump());
    // No quantity camgen reads is this large; such a number is a typo, and would only make
    // the arithmetic downstream meaningless.
    if (std::abs(d) > 1e9) fail(source, path, "number " + value.dump() + " is out of range (at most 1e9 in size)");
    return d;
}

int checked_integer(const nlohmann::json& value, const std::string& path, const Source& source) {
    if (!value.is_number()) type_error(source, path, "an integer", value);
    constexpr auto lo = std::numeric_limits<int>::min();
    constexpr auto hi = std::numeric_limits<int>::max();
    if (value.is_number_unsigned()) {
        const auto u = value.get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(hi)) fail(source, path, "integer " + value.dump() + " is too large");
        return static_cast<int>(u);
    }
    if (value.is_number_integer()) {
        const auto i = value.get<std::int64_t>();
        if (i < lo || i > hi) fail(source, path, "integer " + value.dump() + " is out of range");
        return static_cast<int>(i);
    }
    const double d = value.get<double>();
    if (!std::isfinite(d) || d != std::floor(d))
        fail(source, path, "expected an integer, got " + value.dump());
    if (d < lo || d > hi) fail(source, path, "integer " + value.dump() + " is out of range");
    return static_cast<int>(d);
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

}  // namespace

int LineMap::line_of_early(std::string_view pointer) const {
    if (scanned_ || text_.empty()) return line_of(pointer);
    struct Found {
        int line;
    };
    try {
        Scanner(text_).run(
            [&](std::string_view p, int line) {
                if (p == pointer) throw Found{line};
            },
            [](std::string_view, int) {}, false);
    } catch (const Found& found) {
        return found.line;
    }
    return 0;
}

int LineMap::line_of(std::string_view pointer) const {
    // Kept in document order: building stays O(n); lookups (only made for error messages)
    // are a linear search, until a job with many errors has made enough of them to pay for
    // sorting an index (a thousand broken operations would otherwise take a thousand scans).
    if (!scanned_) {
        scanned_ = true;
        if (!text_.empty())
            Scanner(text_).run(
                [this](std::string_view p, int line) { entries_.emplace_back(p, line); },
                [](std::string_view, int) {}, false);
    }
    constexpr std::size_t linear_lookups = 16;
    if (++lookups_ <= linear_lookups || entries_.size() < 64) {
        for (const auto& [p, line] : entries_)
            if (p == pointer) return line;
        return 0;
    }
    if (by_pointer_.size() != entries_.size()) {
        by_pointer_.resize(entries_.size());
        for (std::size_t i = 0; i < by_pointer_.size(); ++i) by_pointer_[i] = i;
        // Stable: of equal pointers the first in the document is found, as by the linear search.
        std::stable_sort(by_pointer_.begin(), by_pointer_.end(),
                         [this](std::size_t a, std::size_t b) { return entries_[a].first < entries_[b].first; });
    }
    auto it = std::lower_bound(by_pointer_.begin(), by_pointer_.end(), pointer,
                               [this](std::size_t i, std::string_view p) { return entries_[i].first < p; });
    if (it == by_pointer_.end() || entries_[*it].first != pointer) return 0;
    return entries_[*it].second;
}

namespace {
// What a byte means to the nesting scan; most bytes of a job (digits, commas, spaces) nothing.
enum NestingByte : std::uint8_t { plain_byte, quote_byte, escape_byte, open_byte, close_byte };
constexpr std::array<std::uint8_t, 256> nesting_bytes = [] {
    std::array<std::uint8_t, 256> t{};
    t['"'] = quote_byte;
    t['\\'] = escape_byte;
    t['['] = t['{'] = open_byte;
    t[']'] = t['}'] = close_byte;
    return t;
}();

// Where the text first nests deeper than `max_nesting` (outside strings), if it does. One
// table look-up per byte: this runs over every byte of a job before it is parsed.
std::optional<std::size_t> too_deep_at(std::string_view text, int max_nesting) {
    int depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const std::uint8_t kind = nesting_bytes[static_cast<unsigned char>(text[i])];
        if (kind == plain_byte) continue;
        if (in_string) {
            if (kind == escape_byte) ++i;
            else if (kind == quote_byte) in_string = false;
            continue;
        }
        if (kind == quote_byte) in_string = true;
        else if (kind == open_byte) {
            if (++depth > max_nesting) return i;
        } else if (kind == close_byte) {
            --depth;
        }
    }
    return std::nullopt;
}
}  // namespace

namespace {

using Json = nlohmann::json;

// The `[` in `text`. Counted in blocks of 240 bytes into one byte, which cannot overflow: the
// compiler adds 16 bytes at a time in byte lanes (0.25 instructions a byte; counting into a
// size_t widens each lane, 2.4 a byte).
std::size_t opens_in(std::string_view text) {
    constexpr std::size_t block = 240;
    std::size_t n = 0;
    std::size_t i = 0;
    for (; i + block <= text.size(); i += block) {
        unsigned char in_block = 0;
        for (std::size_t j = i; j < i + block; ++j) in_block = static_cast<unsigned char>(in_block + (text[j] == '[' ? 1 : 0));
        n += in_block;
    }
    for (; i < text.size(); ++i) n += text[i] == '[' ? 1 : 0;
    return n;
}

// Placeholder of a packed array in the document: a binary value (which JSON text never
// makes) of this subtype, holding the array's index.
constexpr std::uint8_t packed_subtype = 0x63;

// How a number was written, kept for each packed number.
enum NumberKind : std::uint8_t { float_number, integer_number, unsigned_number };

// Builds the document from nlohmann's SAX events as its own DOM parser does, and besides
// - notes a key that an object already has (nlohmann would keep the last silently);
// - packs the arrays PackedArray describes as they are read, without a value per number: an
//   element that does not fit unpacks the array (its elements so far and the one begun) into
//   the document, which then reads on as usual.
// A packed array's numbers are reserved at once for as many elements as there are `[` left in
// the text (each element has one, and every `[` outside a string starts an array): exact for
// a job whose one large array is its last, and never short, so that a million holes are not
// copied from one doubled buffer into the next.
class DocumentBuilder {
public:
    DocumentBuilder(Document& doc, bool pack, std::string_view text) : doc_(doc), pack_(pack), opens_left_(opens_in(text)) {}
    bool duplicate() const { return duplicate_; }

    bool null() { return plain([&] { add(nullptr); }); }
    bool boolean(bool v) { return plain([&] { add(v); }); }
    bool number_integer(Json::number_integer_t v) {
        return number(static_cast<double>(v), integer_number) || plain([&] { add(v); });
    }
    bool number_unsigned(Json::number_unsigned_t v) {
        return number(static_cast<double>(v), unsigned_number) || plain([&] { add(v); });
    }
    bool number_float(Json::number_float_t v, const Json::string_t&) {
        return number(v, float_number) || plain([&] { add(v); });
    }
    bool string(Json::string_t& v) { return plain([&] { add(std::move(v)); }); }
    bool binary(Json::binary_t& v) { return plain([&] { add(std::move(v)); }); }

    bool start_object(std::size_t) {
        if (stage_ == Stage::element && packed_.form == PackedArray::Form::lines) {
            stage_ = Stage::object;
            return true;
        }
        return plain([&] { open(Json::value_t::object); });
    }
    bool key(Json::string_t& k) {
        if (stage_ == Stage::object && k == "line") {
            stage_ = Stage::line;
            return true;
        }
        unpack();
        auto& members = stack_.back()->get_ref<Json::object_t&>();
        auto [it, inserted] = members.emplace(k, nullptr);
        if (!inserted) {
            duplicate_ = true;
            it->second = nullptr;
        }
        member_ = &it->second;
        next_packs_ = !pack_ ? Next::none : k == "holes" ? Next::points : k == "path" ? Next::lines : Next::none;
        return true;
    }
    bool end_object() {
        if (stage_ == Stage::closing) {
            commit_element();
            stage_ = Stage::element;
            return true;
        }
        unpack();
        stack_.pop_back();
        return true;
    }
    bool start_array(std::size_t) {
        --opens_left_;  // every array starts at a `[` of the text, which counted them all
        if ((stage_ == Stage::element && packed_.form == PackedArray::Form::points) || stage_ == Stage::line) {
            stage_ = Stage::numbers;
            count_ = 0;
            return true;
        }
        unpack();
        const Next next = !stack_.empty() && stack_.back()->is_object() ? next_packs_ : Next::none;
        open(Json::value_t::array);
        if (next != Next::none) begin_packed(next);
        return true;
    }
    bool end_array() {
        if (stage_ == Stage::numbers && (count_ == 2 || (count_ == 3 && packed_.form == PackedArray::Form::lines))) {
            if (packed_.form == PackedArray::Form::lines) {
                stage_ = Stage::closing;  // the element is complete when its object closes
                return true;
            }
            commit_element();
            stage_ = Stage::element;
            return true;
        }
        if (stage_ == Stage::element) {
            stage_ = Stage::none;
            if (packed_.size() > 0) {
                // Held until the job is read: the room reserved for the arrays after this one
                // (the `[` left were theirs) goes, a copy of this one's numbers. The last large
                // array of a job keeps its buffer, which it fills.
                if (packed_.kinds.capacity() - packed_.size() > packed_.size() / 4) {
                    packed_.xyz.shrink_to_fit();
                    packed_.kinds.shrink_to_fit();
                }
                const auto index = static_cast<std::uint32_t>(doc_.packed.size());
                *stack_.back() = Json::binary({static_cast<std::uint8_t>(index), static_cast<std::uint8_t>(index >> 8),
                                               static_cast<std::uint8_t>(index >> 16), static_cast<std::uint8_t>(index >> 24)},
                                              packed_subtype);
                doc_.packed.push_back(std::move(packed_));
            }
            stack_.pop_back();
            return true;
        }
        unpack();
        stack_.pop_back();
        return true;
    }

    template <class Exception>
    bool parse_error(std::size_t, const std::string&, const Exception& ex) {
        throw ex;
    }

private:
    // Where a packed array is: none (not in one), between its elements, in a line element's
    // object before its key, after the "line" key, in an element's numbers, after a line
    // element's numbers (before the object closes).
    enum class Stage { none, element, object, line, numbers, closing };
    enum class Next { none, points, lines };

    // A packed array begins, with room for as many elements as `[` are left.
    void begin_packed(Next next) {
        stage_ = Stage::element;
        packed_ = PackedArray{};
        packed_.form = next == Next::points ? PackedArray::Form::points : PackedArray::Form::lines;
        reserve_large(packed_.xyz, 2 * opens_left_);
        reserve_large(packed_.kinds, opens_left_);
    }

    // An event that no packed array takes: unpack, then do it.
    template <class Do>
    bool plain(Do&& action) {
        unpack();
        action();
        return true;
    }

    // Adds the element read (numbers_) to the packed array.
    void commit_element() {
        std::uint8_t kinds[3];
        for (int i = 0; i < count_; ++i) kinds[i] = kinds_[i];
        packed_.add(numbers_, kinds, count_);
    }

    // A number for the element being packed; false when it does not fit (then unpacked).
    bool number(double v, NumberKind kind) {
        if (stage_ == Stage::numbers && count_ < 3 && std::abs(v) <= 1e9) {
            numbers_[count_] = v;
            kinds_[count_++] = kind;
            return true;
        }
        unpack();
        return false;
    }

    Json* add(Json value) {
        if (stack_.empty()) {
            doc_.root = std::move(value);
            return &doc_.root;
        }
        if (stack_.back()->is_array()) {
            auto& items = stack_.back()->get_ref<Json::array_t&>();
            items.push_back(std::move(value));
            return &items.back();
        }
        *member_ = std::move(value);
        return member_;
    }
    void open(Json::value_t type) { stack_.push_back(add(Json(type))); }

    // Puts the packed elements into the document array and replays the element begun.
    void unpack() {
        if (stage_ == Stage::none) return;
        const Stage stage = stage_;
        stage_ = Stage::none;
        *stack_.back() = packed_.to_json();
        const bool lines = packed_.form == PackedArray::Form::lines;
        if (stage == Stage::element) return;
        if (lines) {
            open(Json::value_t::object);
            if (stage == Stage::object) return;
            Json::string_t line = "line";
            key(line);
            if (stage == Stage::line) return;
        }
        open(Json::value_t::array);
        for (int i = 0; i < count_; ++i) {
            if (kinds_[i] == float_number) add(numbers_[i]);
            else if (kinds_[i] == integer_number) add(static_cast<Json::number_integer_t>(numbers_[i]));
            else add(static_cast<Json::number_unsigned_t>(numbers_[i]));
        }
        if (stage == Stage::closing) stack_.pop_back();
    }

    Document& doc_;
    bool pack_;
    std::vector<Json*> stack_;
    Json* member_ = nullptr;
    bool duplicate_ = false;
    Next next_packs_ = Next::none;
    Stage stage_ = Stage::none;
    std::size_t opens_left_;  // the `[` in the text after the last array begun
    PackedArray packed_;
    double numbers_[3] = {};
    NumberKind kinds_[3] = {};
    int count_ = 0;
};

// The fast reader's document, or nothing when it gave up or found a duplicate key (then
// nlohmann's reading decides, and names the error).
std::optional<Document> read_fast(std::string_view text, int max_nesting, bool pack) {
    Document doc;
    DocumentBuilder builder(doc, pack, text);
    if (!detail::FastJsonReader(text, builder, max_nesting).run() || builder.duplicate()) return std::nullopt;
    return doc;
}

// Reads `text` into `doc` with nlohmann's parser; see parse.
void parse_into(Document& doc, std::string_view text, const std::string& source_name, int max_nesting, bool pack) {
    if (const auto at = too_deep_at(text, max_nesting)) {
        const auto [line, column] = line_column(text, *at);
        throw InputError("", fmt::format("line {}, column {}: arrays and objects nested deeper than {} levels", line,
                                         column, max_nesting),
                         line, source_name);
    }
    DocumentBuilder builder(doc, pack, text);
    try {
        Json::sax_parse(text, &builder, Json::input_format_t::json, true, false);
    } catch (const nlohmann::json::parse_error& e) {
        std::size_t index = e.byte > 0 ? e.byte - 1 : 0;
        const auto nan_at = nan_or_infinity_at(text, index);
        if (nan_at) index = *nan_at;
        const auto [line, column] = line_column(text, index);
        std::string detail;
        if (nan_at) {
            detail = "NaN and Infinity are not valid JSON numbers";
        } else {
            detail = e.what();
            const auto at = detail.find(", column ");
            const auto colon = at == std::string::npos ? at : detail.find(": ", at);
            if (colon != std::string::npos) detail.erase(0, colon + 2);
        }
        throw InputError("", "line " + std::to_string(line) + ", column " + std::to_string(column) +
                                 ": " + detail,
                         line, source_name);
    } catch (const nlohmann::json::exception& e) {
        // Number overflow (1e999) is reported without a position: find the number in the text.
        std::string message = e.what();
        const auto open = message.find('\'');
        const auto close = open == std::string::npos ? open : message.find('\'', open + 1);
        if (close == std::string::npos) throw InputError("", message, 0, source_name);
        const std::string token = message.substr(open + 1, close - open - 1);
        const auto [line, column] = line_column(text, text.find(token));
        throw InputError("", "line " + std::to_string(line) + ", column " + std::to_string(column) +
                                 ": the number " + token +
                                 " is out of range (numbers must be finite)",
                         line, source_name);
    }
    // nlohmann keeps the last of two equal keys silently; a typo'd copy would go unnoticed.
    // The scan that finds the first one's pointer and line runs only when there is one.
    if (builder.duplicate())
        Scanner(text).run([](std::string_view, int) {},
                          [&](std::string_view pointer, int line) {
                              throw InputError(std::string(pointer), "duplicate key", line, source_name);
                          },
                          true);
}

}  // namespace

nlohmann::json parse(std::string_view text, const std::string& source_name, int max_nesting) {
    if (auto doc = read_fast(text, max_nesting, false)) return std::move(doc->root);
    Document doc;
    parse_into(doc, text, source_name, max_nesting, false);
    return std::move(doc.root);
}

Document parse_document(std::string_view text, const std::string& source_name, int max_nesting) {
    if (auto doc = read_fast(text, max_nesting, true)) return std::move(*doc);
    return parse_document_with_nlohmann(text, source_name, max_nesting);
}

std::optional<Document> parse_document_fast(std::string_view text, int max_nesting) {
    return read_fast(text, max_nesting, true);
}

Document parse_document_with_nlohmann(std::string_view text, const std::string& source_name, int max_nesting) {
    Document doc;
    parse_into(doc, text, source_name, max_nesting, true);
    return doc;
}

std::string fingerprint(const Document& doc) {
    std::string out = doc.root.dump();
    for (const auto& packed : doc.packed) {
        out += packed.form == PackedArray::Form::points ? "\npoints" : "\nlines";
        out += " stride ";
        out += std::to_string(packed.stride);
        for (const double v : packed.xyz) {
            std::uint64_t bits = 0;
            std::memcpy(&bits, &v, sizeof bits);
            out += ' ';
            out += std::to_string(bits);
        }
        for (const auto k : packed.kinds) {
            out += " k";
            out += std::to_string(k);
        }
    }
    return out;
}

void PackedArray::add(const double* numbers, const std::uint8_t* number_kinds, int count) {
    if (count == 3 && stride == 2) {
        // The first element with a z: every element gets a place for one.
        std::vector<double> wide;
        reserve_large(wide, xyz.capacity() / 2 * 3);
        for (std::size_t i = 0; i < size(); ++i)
            wide.insert(wide.end(), {xyz[2 * i], xyz[2 * i + 1], std::numeric_limits<double>::quiet_NaN()});
        xyz = std::move(wide);
        stride = 3;
    }
    xyz.push_back(numbers[0]);
    xyz.push_back(numbers[1]);
    if (stride == 3) xyz.push_back(count == 3 ? numbers[2] : std::numeric_limits<double>::quiet_NaN());
    std::uint8_t packed_kinds = 0;
    for (int k = 0; k < count; ++k) packed_kinds = static_cast<std::uint8_t>(packed_kinds | (number_kinds[k] << (2 * k)));
    kinds.push_back(packed_kinds);
}

nlohmann::json PackedArray::to_json() const {
    Json items = Json::array();
    auto& list = items.get_ref<Json::array_t&>();
    list.reserve(size());
    for (std::size_t i = 0; i < size(); ++i) {
        Json point = Json::array();
        for (std::size_t k = 0; k < (has_z(i) ? 3u : 2u); ++k) {
            const double v = xyz[stride * i + k];
            const std::uint8_t written = kind(i, static_cast<int>(k));
            if (written == float_number) point.push_back(v);
            else if (written == integer_number) point.push_back(static_cast<Json::number_integer_t>(v));
            else point.push_back(static_cast<Json::number_unsigned_t>(v));
        }
        if (form == Form::lines) list.push_back(Json{{"line", std::move(point)}});
        else list.push_back(std::move(point));
    }
    return items;
}

const PackedArray* Document::packed_at(const nlohmann::json& value) const {
    if (!value.is_binary()) return nullptr;
    const auto& bytes = value.get_binary();
    if (!bytes.has_subtype() || bytes.subtype() != packed_subtype || bytes.size() != 4) return nullptr;
    const std::uint32_t index = bytes[0] | (bytes[1] << 8) | (bytes[2] << 16) | (static_cast<std::uint32_t>(bytes[3]) << 24);
    return index < packed.size() ? &packed[index] : nullptr;
}

std::string pointer_escape(std::string_view key) {
    std::string out;
    out.reserve(key.size());
    for (const char c : key) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}

void fail(const Source& source, const std::string& path, const std::string& detail) {
    // The nearest pointer, from `path` up to the root, that has a line.
    int line = 0;
    std::string_view pointer = path;
    while (true) {
        line = source.lines.line_of(pointer);
        if (line > 0 || pointer.empty()) break;
        pointer = pointer.substr(0, pointer.rfind('/') == std::string_view::npos ? 0 : pointer.rfind('/'));
    }
    throw InputError(path, detail, line, source.name);
}

std::optional<std::string> did_you_mean(std::string_view word,
                                        const std::vector<std::string>& candidates) {
    const std::string w = lower(word);
    const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
    std::optional<std::string> best;
    std::size_t best_distance = limit + 1;
    for (const auto& candidate : candidates) {
        const std::size_t d = edit_distance(w, lower(candidate));
        if (d < best_distance) {
            best_distance = d;
            best = candidate;
        }
    }
    return best;
}

Fields::Fields(const nlohmann::json& value, std::string path, const Source& source)
    : value_(value), path_(std::move(path)), source_(source) {
    if (!value_.is_object()) type_error(source_, path_, "an object", value_);
}

std::string Fields::path_of(std::string_view key) const {
    return path_ + "/" + pointer_escape(key);
}

bool Fields::has(std::string_view key) const {
    read_.emplace(key);
    return value_.contains(key);
}

const nlohmann::json* Fields::member(std::string_view key) {
    read_.emplace(key);
    const auto it = value_.find(key);
    return it == value_.end() ? nullptr : &*it;
}

const nlohmann::json& Fields::required(std::string_view key) {
    const nlohmann::json* value = member(key);
    if (!value) fail(key, "required key \"" + std::string(key) + "\" is missing");
    return *value;
}

double Fields::number(std::string_view key) {
    return checked_number(required(key), path_of(key), source_);
}

std::optional<double> Fields::optional_number(std::string_view key) {
    const nlohmann::json* value = member(key);
    if (!value) return std::nullopt;
    return checked_number(*value, path_of(key), source_);
}

int Fields::integer(std::string_view key) {
    return checked_integer(required(key), path_of(key), source_);
}

std::optional<int> Fields::optional_integer(std::string_view key) {
    const nlohmann::json* value = member(key);
    if (!value) return std::nullopt;
    return checked_integer(*value, path_of(key), source_);
}

std::string Fields::string(std::string_view key) {
    const nlohmann::json& value = required(key);
    if (!value.is_string()) type_error(source_, path_of(key), "a string", value);
    return value.get<std::string>();
}

std::optional<std::string> Fields::optional_string(std::string_view key) {
    const nlohmann::json* value = member(key);
    if (!value) return std::nullopt;
    if (!value->is_string()) type_error(source_, path_of(key), "a string", *value);
    return value->get<std::string>();
}

bool Fields::boolean(std::string_view key, bool fallback) {
    const nlohmann::json* value = member(key);
    if (!value) return fallback;
    if (!value->is_boolean()) type_error(source_, path_of(key), "true or false", *value);
    return value->get<bool>();
}

void Fields::fail(std::string_view key, const std::string& detail) const {
    json::fail(source_, key.empty() ? path_ : path_of(key), detail);
}

void Fields::finish() const {
    // The object's members are sorted by key; report the unknown one that comes first in the file.
    std::optional<std::string> first;
    int first_line = std::numeric_limits<int>::max();
    for (auto it = value_.begin(); it != value_.end(); ++it) {
        if (read_.count(it.key())) continue;
        int line = source_.lines.line_of(path_of(it.key()));
        if (line == 0) line = std::numeric_limits<int>::max() - 1;
        if (line < first_line) {
            first_line = line;
            first = it.key();
        }
    }
    if (!first) return;
    std::string detail = "unknown key \"" + *first + "\"";
    const std::vector<std::string> known(read_.begin(), read_.end());
    if (auto hint = did_you_mean(*first, known)) detail += " (did you mean \"" + *hint + "\"?)";
    fail(*first, detail);
}

void Fields::finish(std::span<const KeySpec> table) const {
    for (const auto& k : table) has(k.key);
    finish();
}

void Fields::fail_choice(std::string_view key, const std::string& got,
                         const std::vector<std::string>& names) const {
    std::string detail = "\"" + got + "\" is not one of ";
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) detail += i + 1 == names.size() ? " or " : ", ";
        detail += "\"" + names[i] + "\"";
    }
    if (auto hint = did_you_mean(got, names)) detail += " (did you mean \"" + *hint + "\"?)";
    fail(key, detail);
}

double number_at(const nlohmann::json& value, const std::string& path, const Source& source) {
    return checked_number(value, path, source);
}

}  // namespace camgen::json
