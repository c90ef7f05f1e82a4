// JSON helpers: line map, parse errors, checked field access, did-you-mean, InputError text.
#include <doctest/doctest.h>

#include <string>

#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_json_util {

using camgen::InputError;
namespace cj = camgen::json;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// The InputError that parse() throws for `text` (fails the test if it does not throw).
InputError parse_error(const std::string& text) {
    try {
        cj::parse(text, "in.json");
    } catch (const InputError& e) {
        return e;
    }
    FAIL("parse() accepted: " << text);
    return InputError("", "");
}

struct Doc {
    std::string text;  // the line map reads it when an error needs a line
    nlohmann::json value;
    cj::Source source;
    explicit Doc(std::string json)
        : text(std::move(json)), value(cj::parse(text, "doc.json")), source{"doc.json", cj::LineMap(text)} {}
};

template <class F>
InputError error_of(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e;
    }
    FAIL("no InputError thrown");
    return InputError("", "");
}

}  // namespace

TEST_CASE("InputError composes SOURCE:LINE: PATH: DETAIL, leaving out empty parts") {
    CHECK(std::string(InputError("/operations/2/holes/5", "expected a number, got \"abc\"", 12,
                                 "job.json")
                          .what()) ==
          "job.json:12: /operations/2/holes/5: expected a number, got \"abc\"");
    CHECK(std::string(InputError("/a", "bad", 0, "job.json").what()) == "job.json: /a: bad");
    CHECK(std::string(InputError("", "bad", 3, "job.json").what()) == "job.json:3: bad");
    CHECK(std::string(InputError("/a", "bad").what()) == "/a: bad");
    CHECK(std::string(InputError("", "bad", 4).what()) == "line 4: bad");

    const InputError e("/tools/0", "oops");
    const InputError located = e.located("m.json", 9);
    CHECK(std::string(located.what()) == "m.json:9: /tools/0: oops");
    CHECK(located.path() == "/tools/0");
    CHECK(located.detail() == "oops");
    CHECK(located.line() == 9);
    CHECK(located.source() == "m.json");
}

TEST_CASE("pointer_escape escapes ~ and / (RFC 6901)") {
    CHECK(cj::pointer_escape("plain") == "plain");
    CHECK(cj::pointer_escape("a/b~c") == "a~1b~0c");
    CHECK(cj::pointer_escape("~1") == "~01");
}

TEST_CASE("LineMap finds the line of every value in nested arrays and objects") {
    const std::string text = R"({
  "a": [1,
    [2, 3],
    {"b": 4}
  ],
  "c/d": {"e~f": true},
  "g\"h": null,
  "i\/j": "x\ny",
  "k":

     7,
  "empty": [], "none": {},
  "last": [[],
   [[
     9]]]
})";
    const cj::LineMap map(text);
    CHECK(map.line_of("") == 1);
    CHECK(map.line_of("/a") == 2);
    CHECK(map.line_of("/a/0") == 2);
    CHECK(map.line_of("/a/1") == 3);
    CHECK(map.line_of("/a/1/0") == 3);
    CHECK(map.line_of("/a/1/1") == 3);
    CHECK(map.line_of("/a/2") == 4);
    CHECK(map.line_of("/a/2/b") == 4);
    CHECK(map.line_of("/c~1d") == 6);
    CHECK(map.line_of("/c~1d/e~0f") == 6);
    CHECK(map.line_of("/g\"h") == 7);
    CHECK(map.line_of("/i~1j") == 8);  // "\/" in a key is a "/" and is escaped as ~1
    CHECK(map.line_of("/k") == 9);     // an object member: the line of its key
    CHECK(map.line_of("/empty") == 12);
    CHECK(map.line_of("/none") == 12);
    CHECK(map.line_of("/last") == 13);
    CHECK(map.line_of("/last/0") == 13);
    CHECK(map.line_of("/last/1") == 14);
    CHECK(map.line_of("/last/1/0") == 14);
    CHECK(map.line_of("/last/1/0/0") == 15);
    CHECK(map.line_of("/a/3") == 0);
    CHECK(map.line_of("/nope") == 0);
    CHECK(map.line_of("/c/d") == 0);  // unescaped: a different pointer
}

TEST_CASE("LineMap decodes \\u escapes in keys") {
    const cj::LineMap map("{\n\"\\u00e9t\\u00E9\": 1,\n \"\\ud83d\\ude00\": 2}");
    CHECK(map.line_of("/\xc3\xa9t\xc3\xa9") == 2);
    CHECK(map.line_of("/\xf0\x9f\x98\x80") == 3);
}

TEST_CASE("LineMap of a scalar document and of deep nesting") {
    CHECK(cj::LineMap("\n\n 42").line_of("") == 3);
    std::string deep(20000, '[');
    deep += std::string(20000, ']');
    const cj::LineMap map(deep);  // iterative: no stack overflow
    CHECK(map.line_of("/0/0/0") == 1);
}

TEST_CASE("parse reports syntax errors with line and column") {
    const auto e = parse_error("{\n  \"a\": [1, 2,],\n  \"b\": 1\n}");
    CHECK(e.line() == 2);
    CHECK(e.path() == "");
    CHECK(e.source() == "in.json");
    CHECK(contains(e.what(), "in.json:2: line 2, column 14: syntax error"));

    const auto comment = parse_error("{\n// no comments\n\"a\": 1}");
    CHECK(comment.line() == 2);

    const auto truncated = parse_error("{\"a\": 1");
    CHECK(contains(truncated.what(), "line 1, column 8"));
    CHECK(contains(truncated.what(), "unexpected end of input"));
}

TEST_CASE("parse names NaN and Infinity") {
    for (const char* literal : {"NaN", "Infinity", "-Infinity", "nan", "-inf"}) {
        CAPTURE(literal);
        const auto e = parse_error(std::string("{\n\"a\": 1,\n\"b\": ") + literal + "\n}");
        CHECK(e.line() == 3);
        CHECK(contains(e.what(), "NaN and Infinity are not valid JSON numbers"));
    }
    const auto e = parse_error("[1,\n  NaN]");
    CHECK(contains(e.what(), "line 2, column 3: NaN and Infinity"));
}

TEST_CASE("parse rejects numbers that overflow to infinity") {
    const auto e = parse_error("{\n \"x\": 1,\n \"y\": -1e999\n}");
    CHECK(e.line() == 3);
    CHECK(contains(e.what(), "in.json:3: line 3, column 7"));
    CHECK(contains(e.what(), "-1e999"));
    CHECK(contains(e.what(), "finite"));
    // Underflow is harmless: it is zero.
    CHECK(cj::parse("[1e-999]", "x")[0].get<double>() == 0.0);
}

TEST_CASE("parse rejects duplicate keys, naming the second") {
    const auto e = parse_error("{\n \"a\": {\"b\": 1,\n  \"b\": 2}\n}");
    CHECK(e.path() == "/a/b");
    CHECK(e.line() == 3);
    CHECK(contains(e.what(), "duplicate key"));
    // Equal keys in different objects are fine.
    CHECK_NOTHROW(cj::parse(R"([{"a": 1}, {"a": 2}, {"x": {"a": 3}, "a": 4}])", "x"));
}

TEST_CASE("did_you_mean: case-insensitive Levenshtein within max(2, len/3)") {
    const std::vector<std::string> keys = {"holes", "grid", "boltCircle", "line", "endDepth"};
    CHECK(cj::did_you_mean("holez", keys) == std::optional<std::string>("holes"));
    CHECK(cj::did_you_mean("HOLES", keys) == std::optional<std::string>("holes"));
    CHECK(cj::did_you_mean("boltcirle", keys) == std::optional<std::string>("boltCircle"));
    CHECK(cj::did_you_mean("enddepht", keys) == std::optional<std::string>("endDepth"));
    CHECK(cj::did_you_mean("lin", keys) == std::optional<std::string>("line"));
    CHECK_FALSE(cj::did_you_mean("spindle", keys).has_value());
    CHECK_FALSE(cj::did_you_mean("xyz", {}).has_value());
    // A long word allows len/3 edits: 12 letters -> 4.
    CHECK(cj::did_you_mean("abcdefghijkl", {"abcdefghWXYZ"}) == std::optional<std::string>("abcdefghWXYZ"));
    CHECK_FALSE(cj::did_you_mean("abcdefghijkl", {"abcdefgVWXYZ"}).has_value());
}

TEST_CASE("Fields: typed access with path and line in every error") {
    const Doc doc(R"({
  "n": 2.5,
  "i": 3,
  "s": "abc",
  "b": true,
  "big": 1e300,
  "huge": 99999999999,
  "arr": [1, "x"],
  "obj": {"deep": {"v": "7"}}
})");
    cj::Fields f(doc.value, "", doc.source);
    CHECK(f.number("n") == 2.5);
    CHECK(f.number("i") == 3.0);
    CHECK(f.integer("i") == 3);
    CHECK(f.string("s") == "abc");
    CHECK(f.boolean("b", false) == true);
    CHECK(f.boolean("absent", true) == true);
    CHECK(f.optional_number("absent") == std::nullopt);
    CHECK(f.optional_integer("absent") == std::nullopt);
    CHECK(f.optional_string("absent") == std::nullopt);
    CHECK(f.member("absent") == nullptr);
    CHECK(f.has("s"));
    CHECK_FALSE(f.has("absent"));
    CHECK(f.path_of("a/b") == "/a~1b");

    auto e = error_of([&] { f.number("s"); });
    CHECK(e.path() == "/s");
    CHECK(e.line() == 4);
    CHECK(contains(e.what(), "doc.json:4: /s: expected a number, got a string \"abc\""));

    e = error_of([&] { f.integer("n"); });
    CHECK(e.line() == 2);
    CHECK(contains(e.what(), "expected an integer, got 2.5"));

    e = error_of([&] { f.integer("huge"); });
    CHECK(e.path() == "/huge");
    CHECK(contains(e.what(), "99999999999"));

    e = error_of([&] { f.string("i"); });
    CHECK(contains(e.what(), "expected a string, got a number (3)"));

    e = error_of([&] { f.boolean("s", false); });
    CHECK(contains(e.what(), "/s: expected true or false, got a string"));

    e = error_of([&] { f.number("b"); });
    CHECK(contains(e.what(), "got a boolean (true)"));

    e = error_of([&] { f.number("missing"); });
    CHECK(e.path() == "/missing");
    CHECK(e.line() == 1);  // falls back to the object's line
    CHECK(contains(e.what(), "required key \"missing\" is missing"));

    // Finite but absurd: no quantity camgen reads is above 1e9 in size.
    e = error_of([&] { f.number("big"); });
    CHECK(e.path() == "/big");
    CHECK(e.line() == 6);
    CHECK(contains(e.what(), "is out of range (at most 1e9 in size)"));

    // Array elements: number_at.
    const auto& arr = f.required("arr");
    CHECK(cj::number_at(arr[0], "/arr/0", doc.source) == 1.0);
    e = error_of([&] { cj::number_at(arr[1], "/arr/1", doc.source); });
    CHECK(e.path() == "/arr/1");
    CHECK(e.line() == 8);
    CHECK(contains(e.what(), "expected a number, got a string \"x\""));

    // Nested objects.
    cj::Fields obj(f.required("obj"), f.path_of("obj"), doc.source);
    cj::Fields deep(obj.required("deep"), obj.path_of("deep"), doc.source);
    e = error_of([&] { deep.number("v"); });
    CHECK(e.path() == "/obj/deep/v");
    CHECK(e.line() == 9);

    // Not an object.
    e = error_of([&] { cj::Fields(arr, "/arr", doc.source); });
    CHECK(e.path() == "/arr");
    CHECK(contains(e.what(), "expected an object, got an array"));
}

TEST_CASE("Fields::finish reports the first unknown key in the file, with a hint") {
    const Doc doc(R"({
  "holes": [],
  "zzz": 1,
  "endDeph": 2,
  "aaa": 3
})");
    cj::Fields f(doc.value, "", doc.source);
    f.member("holes");
    f.optional_number("endDepth");
    auto e = error_of([&] { f.finish(); });
    // "zzz" comes first in the file, though "aaa" sorts first.
    CHECK(e.path() == "/zzz");
    CHECK(e.line() == 3);
    CHECK(contains(e.what(), "unknown key \"zzz\""));
    CHECK_FALSE(contains(e.what(), "did you mean"));

    f.has("zzz");
    e = error_of([&] { f.finish(); });
    CHECK(e.path() == "/endDeph");
    CHECK(e.line() == 4);
    CHECK(contains(e.what(), "doc.json:4: /endDeph: unknown key \"endDeph\" (did you mean \"endDepth\"?)"));

    f.has("endDeph");
    f.has("aaa");
    CHECK_NOTHROW(f.finish());
}

TEST_CASE("Fields::choice maps strings and lists the choices") {
    const Doc doc("{\n\"dir\": \"ccw\",\n\"bad\": \"ccww\",\n\"num\": 1}");
    cj::Fields f(doc.value, "", doc.source);
    CHECK(f.choice<int>("dir", {{"cw", 1}, {"ccw", 2}}) == 2);
    CHECK(f.choice<int>("absent", {{"cw", 1}, {"ccw", 2}}, 1) == 1);
    auto e = error_of([&] { f.choice<int>("bad", {{"cw", 1}, {"ccw", 2}}); });
    CHECK(e.path() == "/bad");
    CHECK(e.line() == 3);
    CHECK(contains(e.what(), "\"ccww\" is not one of \"cw\" or \"ccw\""));
    CHECK(contains(e.what(), "did you mean \"ccw\"?"));
    e = error_of([&] { f.choice<int>("num", {{"cw", 1}, {"ccw", 2}}, 1); });
    CHECK(contains(e.what(), "expected a string"));
    e = error_of([&] { f.choice<int>("absent", {{"cw", 1}}); });
    CHECK(e.path() == "/absent");
}

TEST_CASE("fail falls back to the nearest parent with a line") {
    const Doc doc("{\n \"a\": {\n  \"b\": [\n   1]}}");
    auto e = error_of([&] { cj::fail(doc.source, "/a/b/5/x", "no"); });
    CHECK(e.line() == 3);
    CHECK(std::string(e.what()) == "doc.json:3: /a/b/5/x: no");
    e = error_of([&] { cj::fail(doc.source, "/a/b/0", "no"); });
    CHECK(e.line() == 4);
    e = error_of([&] { cj::fail(doc.source, "/zz", "no"); });
    CHECK(e.line() == 1);
}

TEST_CASE("parse_document packs holes and path lines, and leaves everything else as parse does") {
    const std::string text = R"({"holes": [[1, -2], [3.5, 4e2], [18446744073709551615, 0]], "a": {"holes": [[1, 2], [3, 4]],
        "path": [{"line": [1, 2]}, {"line": [3, 4, -5.25]}]}, "b": {"path": [{"line": [1, 2]}, {"arc": 1}]},
        "c": {"holes": [[1, 2], [3]]}, "d": {"path": [{"line": [1, 2], "x": 1}]}, "e": {"holes": []}, "f": [[1, 2]]})";
    const cj::Document doc = cj::parse_document(text, "doc.json");
    const nlohmann::json plain = cj::parse(text, "doc.json");
    // A number above 1e9 keeps the first holes unpacked; those of "a" are packed, and its lines.
    CHECK(doc.packed_at(doc.root["holes"]) == nullptr);
    const cj::PackedArray* holes = doc.packed_at(doc.root["a"]["holes"]);
    REQUIRE(holes != nullptr);
    CHECK(holes->form == cj::PackedArray::Form::points);
    CHECK(holes->size() == 2);
    CHECK(holes->x(1) == 3);
    CHECK(holes->y(1) == 4);
    CHECK_FALSE(holes->has_z(0));
    const cj::PackedArray* lines = doc.packed_at(doc.root["a"]["path"]);
    REQUIRE(lines != nullptr);
    CHECK(lines->form == cj::PackedArray::Form::lines);
    CHECK(lines->has_z(1));
    CHECK(lines->z(1) == -5.25);
    // Unpacked, each is the JSON parse reads, number kinds included.
    CHECK(holes->to_json().dump() == plain["a"]["holes"].dump());
    CHECK(lines->to_json().dump() == plain["a"]["path"].dump());
    // Lines with and without z in any order: each keeps its own (the first z widens the array).
    const std::string mixed = R"({"path": [{"line": [1, 2.5]}, {"line": [3, 4]}, {"line": [5, 6, 7.5]}, {"line": [8, 9]}]})";
    const cj::Document mixed_doc = cj::parse_document(mixed, "mixed.json");
    const cj::PackedArray* path = mixed_doc.packed_at(mixed_doc.root["path"]);
    REQUIRE(path != nullptr);
    CHECK(path->size() == 4);
    CHECK((path->x(1) == 3 && path->y(1) == 4 && !path->has_z(1)));
    CHECK((path->x(2) == 5 && path->y(2) == 6 && path->z(2) == 7.5));
    CHECK((path->x(3) == 8 && !path->has_z(3)));
    CHECK(path->to_json().dump() == cj::parse(mixed, "mixed.json")["path"].dump());
    // An element of another form, anywhere, leaves the whole array as parse reads it.
    for (const char* key : {"holes", "b", "c", "d", "e", "f"}) {
        const nlohmann::json& value = std::string(key) == "holes" ? doc.root["holes"] : doc.root[key];
        CHECK(value.dump() == (std::string(key) == "holes" ? plain["holes"] : plain[key]).dump());
    }
}

TEST_CASE("parse_document finds a duplicate key inside a packed element, with its line") {
    const InputError e = error_of(
        [] { cj::parse_document("{\"path\": [{\"line\": [1, 2]},\n {\"line\": [1, 2], \"line\": [3, 4]}]}", "in.json"); });
    CHECK(e.path() == "/path/1/line");
    CHECK(e.line() == 2);
    CHECK(std::string(e.what()) == "in.json:2: /path/1/line: duplicate key");
}

}  // namespace test_json_util
