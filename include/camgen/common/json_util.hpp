#pragma once
// Reading JSON input (job and machine files) with errors that name the JSON path and line.
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "camgen/common/key_spec.hpp"
#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen::json {

// Maps JSON pointers ("/operations/2/holes/5") of a text to 1-based line numbers.
class LineMap {
public:
    LineMap() = default;
    // Keeps a copy of `text`, which must already be valid JSON. It is scanned on the first
    // lookup: only error messages need lines, and a map of every value of a large job costs
    // more than reading it.
    explicit LineMap(std::string_view text)
        : copy_(std::make_shared<const std::string>(text)), text_(*copy_) {}
    // The same without a copy, for a text that outlives the map and its copies (a job's text,
    // which may be large).
    static LineMap borrowing(std::string_view text) {
        LineMap map;
        map.text_ = text;
        return map;
    }
    // Line where the value at `pointer` starts (for an object member: its key); 0 if unknown.
    int line_of(std::string_view pointer) const;
    // The same, scanning the text only up to that value and keeping no map (a value near the
    // start of a large job, such as its stock, is found without mapping the rest); 0 if unknown.
    int line_of_early(std::string_view pointer) const;

private:
    std::shared_ptr<const std::string> copy_;  // shared: copies of a map share the text
    std::string_view text_;
    mutable bool scanned_ = false;
    mutable std::vector<std::pair<std::string, int>> entries_;  // in document order
    // After a few lookups (a job with many errors), entries_'s indices sorted by pointer, so
    // that each further lookup is a binary search.
    mutable std::size_t lookups_ = 0;
    mutable std::vector<std::size_t> by_pointer_;
};

// Where an input came from: its name for messages and its line map.
struct Source {
    std::string name;   // file name, or "<stdin>"
    LineMap lines;
};

// Parses JSON text; a syntax error (NaN, Infinity, trailing commas, ...) or arrays and objects
// nested deeper than `max_nesting` become an InputError naming the line and column. The
// nesting is checked on the text before anything is built.
nlohmann::json parse(std::string_view text, const std::string& source_name, int max_nesting = 64);

// A large array of a job read straight into numbers by parse_document: the holes
// [[x, y], ...] of a "holes" key, or the lines [{"line": [x, y]}, {"line": [x, y, z]}, ...] of
// a "path" key, when every element has that form and every number is at most 1e9 in size.
// Anything else stays in the document, so that it gets the messages it always got.
struct PackedArray {
    enum class Form { points, lines };
    Form form = Form::points;
    // `stride` numbers per element: 2 while no element has a z, else 3 (z NaN where an element
    // has two numbers), so that a million 2D points take 16 MB, not 24.
    std::size_t stride = 2;
    std::vector<double> xyz;
    // One per element: how each of its numbers was written (float, integer, unsigned), two bits
    // each, x in the lowest.
    std::vector<std::uint8_t> kinds;

    std::size_t size() const { return kinds.size(); }
    double x(std::size_t i) const { return xyz[stride * i]; }
    double y(std::size_t i) const { return xyz[stride * i + 1]; }
    double z(std::size_t i) const { return stride == 3 ? xyz[3 * i + 2] : std::numeric_limits<double>::quiet_NaN(); }
    bool has_z(std::size_t i) const { return z(i) == z(i); }
    // How number k (0: x, 1: y, 2: z) of element i was written.
    std::uint8_t kind(std::size_t i, int k) const { return (kinds[i] >> (2 * k)) & 3; }
    // Appends an element of two or three numbers and how each was written.
    void add(const double* numbers, const std::uint8_t* number_kinds, int count);
    // The array as the document would have held it.
    nlohmann::json to_json() const;
};

// A parsed job: the document, in which each packed array is a placeholder, and the packed arrays.
struct Document {
    nlohmann::json root;
    std::vector<PackedArray> packed;
    // The packed array `value` stands for, or nullptr when it is an ordinary value.
    const PackedArray* packed_at(const nlohmann::json& value) const;
};

// parse, with the arrays PackedArray describes packed.
//
// Both read well-formed text with a fast reader of camgen's own, and any other text (or text
// with a \u escape, a byte-order mark, a duplicate key, ...) again with nlohmann's parser,
// which names the error: the messages are nlohmann's whichever reader was fast enough.
Document parse_document(std::string_view text, const std::string& source_name, int max_nesting = 64);
// The two readers apart, for tests that hold them to the same documents: the fast one gives
// nothing where it leaves the text to nlohmann's.
std::optional<Document> parse_document_fast(std::string_view text, int max_nesting = 64);
Document parse_document_with_nlohmann(std::string_view text, const std::string& source_name, int max_nesting = 64);
// A document as text that tells apart everything the job reader could see: number kinds (1,
// 1.0 and -1 differ), strings byte for byte, the packed arrays with their forms, strides and
// every number's bits and kind. For holding the two readers to the same documents.
std::string fingerprint(const Document& doc);

// Escapes a key for use in a JSON pointer ("~" -> "~0", "/" -> "~1").
std::string pointer_escape(std::string_view key);

// Throws InputError at `path`, with the line looked up in `source`.
[[noreturn]] void fail(const Source& source, const std::string& path, const std::string& detail);

// The closest of `candidates` to `word` by edit distance, if close enough to be a likely typo.
std::optional<std::string> did_you_mean(std::string_view word,
                                        const std::vector<std::string>& candidates);

// Checked access to the members of one JSON object. Every key that is read is remembered;
// finish() reports any other key as unknown, with a "did you mean" hint.
class Fields {
public:
    // Throws if `value` is not an object.
    Fields(const nlohmann::json& value, std::string path, const Source& source);

    const std::string& path() const { return path_; }
    // "/path/key"
    std::string path_of(std::string_view key) const;
    bool has(std::string_view key) const;

    // Numbers must be finite. `required` variants throw when the key is missing.
    double number(std::string_view key);
    std::optional<double> optional_number(std::string_view key);
    int integer(std::string_view key);
    std::optional<int> optional_integer(std::string_view key);
    std::string string(std::string_view key);
    std::optional<std::string> optional_string(std::string_view key);
    bool boolean(std::string_view key, bool fallback);
    // A member of any type (marked as read); nullptr if absent.
    const nlohmann::json* member(std::string_view key);
    // A required member of any type.
    const nlohmann::json& required(std::string_view key);

    // One of a fixed set of strings, mapped to a value; the error lists the choices.
    template <class E>
    E choice(std::string_view key, std::initializer_list<std::pair<std::string_view, E>> options,
             std::optional<E> fallback = std::nullopt) {
        auto text = fallback ? optional_string(key) : std::optional<std::string>(string(key));
        if (!text) return *fallback;
        std::vector<std::string> names;
        for (const auto& [name, value] : options) {
            if (name == *text) return value;
            names.emplace_back(name);
        }
        fail_choice(key, *text, names);
    }

    // One of the names of a vocabulary table; the error lists the names.
    template <class E, std::size_t N>
    E choice(std::string_view key, const Named<E> (&table)[N],
             std::type_identity_t<std::optional<E>> fallback = std::nullopt) {
        auto text = fallback ? optional_string(key) : std::optional<std::string>(string(key));
        if (!text) return *fallback;
        if (auto v = value_named(table, *text)) return *v;
        fail_choice(key, *text, names_of(table));
    }

    // Throws InputError at /path/key (or at /path when key is empty).
    [[noreturn]] void fail(std::string_view key, const std::string& detail) const;
    // Reports keys that were never read. Call after reading every known key.
    void finish() const;
    // Marks the keys of `table` as known, then reports any other key (finish()).
    void finish(std::span<const KeySpec> table) const;

    // The error for a string that is none of `names`, with a "did you mean" hint.
    [[noreturn]] void fail_choice(std::string_view key, const std::string& got,
                                  const std::vector<std::string>& names) const;

private:
    const nlohmann::json& value_;
    std::string path_;
    const Source& source_;
    mutable std::set<std::string, std::less<>> read_;
};

// Checked number at an arbitrary path (array elements): finite, else InputError.
double number_at(const nlohmann::json& value, const std::string& path, const Source& source);

}  // namespace camgen::json
