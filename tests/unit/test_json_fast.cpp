// The fast JSON reader against nlohmann's: the same document wherever the fast one reads the
// text, and nlohmann's (with its error) wherever it does not.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_json_fast {

namespace cj = camgen::json;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Checks the two readers on `text`; returns whether the fast one read it.
bool same_reading(const std::string& text, int max_nesting = 64) {
    const auto fast = cj::parse_document_fast(text, max_nesting);
    std::optional<cj::Document> slow;
    std::string error;
    try {
        slow = cj::parse_document_with_nlohmann(text, "in.json", max_nesting);
    } catch (const camgen::InputError& e) {
        error = e.what();
    }
    if (fast) {
        INFO("text: " << text);
        REQUIRE_MESSAGE(slow.has_value(), "the fast reader took what nlohmann refuses: " << error);
        CHECK(cj::fingerprint(*fast) == cj::fingerprint(*slow));
    }
    // Whoever reads it, parse_document gives nlohmann's document or error.
    try {
        const cj::Document doc = cj::parse_document(text, "in.json", max_nesting);
        CHECK(slow.has_value());
        if (slow) CHECK(cj::fingerprint(doc) == cj::fingerprint(*slow));
    } catch (const camgen::InputError& e) {
        CHECK(std::string(e.what()) == error);
    }
    return fast.has_value();
}

// Random JSON text in the shapes of a job (objects with "holes", "path" and "line" keys,
// points of two or three numbers) and besides, with every spelling of numbers, strings with
// escapes and UTF-8, and whitespace of every kind.
class RandomJson {
public:
    explicit RandomJson(unsigned seed) : rng_(seed) {}

    std::string document() {
        std::string out;
        value(out, 0);
        return out;
    }

private:
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

    void ws(std::string& out) {
        static const char* const spaces[] = {"", "", "", " ", "\n", "\r\n", "\t", "  "};
        out += spaces[pick(8)];
    }

    void number(std::string& out) {
        static const char* const fixed[] = {
            "0", "-0", "0.0", "-0.0", "1", "-1", "12", "1e9", "-1e9", "1000000001", "1.5e-3", "2E+2", "3e0",
            "18446744073709551615", "18446744073709551616", "-9223372036854775808", "-9223372036854775809",
            "9223372036854775807", "123456789012345678901234567890", "0.1", "0.30000000000000004",
            "4.9406564584124654e-324", "2.2250738585072014e-308", "1.7976931348623157e308", "1e-400", "1e400",
            "-12.000", "7.25", "99999999999999999999.5"};
        if (pick(3) == 0) {
            out += fixed[pick(static_cast<int>(std::size(fixed)))];
            return;
        }
        if (pick(2)) out += '-';
        const int digits = 1 + pick(6);
        out += static_cast<char>('1' + pick(9));
        for (int i = 1; i < digits; ++i) out += static_cast<char>('0' + pick(10));
        if (pick(2)) {
            out += '.';
            for (int i = 0, n = 1 + pick(5); i < n; ++i) out += static_cast<char>('0' + pick(10));
        }
        if (pick(5) == 0) out += std::string(pick(2) ? "e" : "E") + (pick(2) ? "-" : "") + std::to_string(pick(20));
    }

    void string(std::string& out) {
        static const char* const pieces[] = {"a", "holes", "path", "line", "x", " ", "\\\"", "\\\\", "\\/", "\\n",
                                             "\\t", "\\u00e9", "\\ud83d\\ude00", "\xc3\xa9", "\xe2\x82\xac",
                                             "\xf0\x9f\x98\x80", "~", "/"};
        out += '"';
        for (int i = 0, n = pick(4); i < n; ++i) out += pieces[pick(static_cast<int>(std::size(pieces)))];
        out += '"';
    }

    void point(std::string& out) {
        out += '[';
        const int n = pick(6) == 0 ? 1 + pick(4) : 2 + pick(2);
        for (int i = 0; i < n; ++i) {
            if (i) out += ',';
            ws(out);
            number(out);
        }
        out += ']';
    }

    void value(std::string& out, int depth) {
        const int kind = depth > 5 ? pick(4) : pick(9);
        switch (kind) {
            case 0: number(out); break;
            case 1: string(out); break;
            case 2: out += pick(2) ? "true" : (pick(2) ? "false" : "null"); break;
            case 3: point(out); break;
            case 4:
            case 5: {  // an object, often with the keys that pack
                static const char* const keys[] = {"\"holes\"", "\"path\"", "\"line\"", "\"a\"", "\"b\"", "\"x\""};
                out += '{';
                ws(out);
                for (int i = 0, n = pick(4); i < n; ++i) {
                    if (i) out += ',';
                    ws(out);
                    const int key = pick(static_cast<int>(std::size(keys)));
                    out += keys[key];
                    ws(out);
                    out += ':';
                    ws(out);
                    if (key == 0) list(out, depth, [&] { point(out); });
                    else if (key == 1) list(out, depth, [&] { line(out, depth); });
                    else if (key == 2) point(out);
                    else value(out, depth + 1);
                    ws(out);
                }
                out += '}';
                break;
            }
            default: list(out, depth, [&] { value(out, depth + 1); });
        }
    }

    void line(std::string& out, int depth) {
        if (pick(8) == 0) {
            value(out, depth + 1);
            return;
        }
        out += "{\"line\":";
        ws(out);
        point(out);
        if (pick(10) == 0) out += ", \"arc\": 1";
        out += '}';
    }

    template <class Element>
    void list(std::string& out, int, Element&& element) {
        out += '[';
        for (int i = 0, n = pick(5); i < n; ++i) {
            if (i) out += ',';
            ws(out);
            element();
            ws(out);
        }
        out += ']';
    }

    std::mt19937 rng_;
};

// `text` with one byte changed, removed or added: the kind of damage that makes errors.
std::string damaged(std::string text, std::mt19937& rng) {
    static const char bytes[] = {'{', '}', '[', ']', ',', ':', '"', '\\', '-', '.', 'e', '0', '1', ' ', '\n',
                                 't',  'n', 'N', '\x01', '\xff', '\xc3', '\xed', '\xef'};
    if (text.empty()) return text;
    const auto at = std::uniform_int_distribution<std::size_t>(0, text.size() - 1)(rng);
    const char byte = bytes[std::uniform_int_distribution<std::size_t>(0, sizeof bytes - 1)(rng)];
    switch (rng() % 3) {
        case 0: text[at] = byte; break;
        case 1: text.erase(at, 1); break;
        default: text.insert(text.begin() + static_cast<std::ptrdiff_t>(at), byte);
    }
    return text;
}

}  // namespace

TEST_CASE("the fast JSON reader reads every sample, machine file, error job and fuzz seed as nlohmann does") {
    int files = 0;
    for (const char* dir : {"/samples", "/machines", "/tests/errors", "/tests/fuzz/corpus/mutated", "/docs"}) {
        const fs::path root = fs::path(CAMGEN_SOURCE_DIR) / fs::path(dir).relative_path();
        if (!fs::exists(root)) continue;
        for (const auto& entry : fs::directory_iterator(root)) {
            if (entry.path().extension() != ".json") continue;
            const std::string text = slurp(entry.path());
            INFO(entry.path().string());
            // Every one of them is well-formed, without \u escapes: the fast reader's to read.
            CHECK(same_reading(text));
            ++files;
        }
    }
    CHECK(files > 20);
}

TEST_CASE("the fast JSON reader gives the same documents as nlohmann on random and damaged JSON") {
    RandomJson random(20261130);
    std::mt19937 rng(7);
    int fast = 0, slow = 0;
    for (int i = 0; i < 4000; ++i) {
        const std::string text = random.document();
        (same_reading(text) ? fast : slow)++;
        for (int k = 0; k < 3; ++k) (same_reading(damaged(text, rng)) ? fast : slow)++;
    }
    // Both readers get their share: the test compares documents, and lets nlohmann judge the rest.
    CHECK(fast > 4000);
    CHECK(slow > 2000);
}

TEST_CASE("the fast JSON reader leaves \\u escapes, byte-order marks, duplicate keys, deep nesting and "
          "unreadable numbers to nlohmann") {
    CHECK(same_reading(R"({"name": "Platte \u00d8 50"})") == false);
    CHECK(same_reading("\xef\xbb\xbf{\"a\": 1}") == false);
    CHECK(same_reading(R"({"a": 1, "a": 2})") == false);
    CHECK(same_reading(R"({"path": [{"line": [1, 2], "line": [3, 4]}]})") == false);
    CHECK(same_reading(R"({"a": 1e400})") == false);
    CHECK(same_reading(R"({"a": 1e-400})") == false);  // nlohmann reads 0, from_chars refuses
    CHECK(same_reading(std::string(64, '[') + std::string(64, ']')) == true);
    CHECK(same_reading(std::string(65, '[') + std::string(65, ']')) == false);
    CHECK(same_reading(std::string(3, '[') + std::string(3, ']'), 2) == false);
    CHECK(same_reading(std::string(300, '[') + std::string(300, ']'), 1000) == false);  // bounded recursion
    // What it does read: UTF-8 names, the other escapes, integers beyond 64 bits, -0.
    CHECK(same_reading("{\"name\": \"Platte \xc3\x98 50 \\\"A\\\"\\n\", \"n\": -0, \"big\": 18446744073709551616}"));
    CHECK(same_reading(R"({"holes": [[1, 2], [3.5, -4e2]], "path": [{"line": [1, 2, 3]}]})"));
    // Invalid UTF-8 and control bytes are nlohmann's to refuse.
    CHECK(same_reading("{\"a\": \"\xc0\xaf\"}") == false);
    CHECK(same_reading("{\"a\": \"\xed\xa0\x80\"}") == false);
    CHECK(same_reading("{\"a\": \"\x01\"}") == false);
}

}  // namespace test_json_fast
