// The JSON Schemas: `camgen schema job|machine` equals the committed schema/*.schema.json, the
// schemas carry every key the readers know, and a job may name its schema in "$schema".
// (tests/schema/validate.py checks the samples and machine files with an independent validator.)
#include <string>

#include <doctest/doctest.h>

#include "camgen/common/error.hpp"
#include "camgen/schema/schema.hpp"
#include "camgen/operations/registry.hpp"
#include "support.hpp"

// Unity builds compile several test files as one: each keeps its names in its own namespace.
namespace test_schema {

using namespace camgen;
using test::Run;
using test::run;

namespace {

const std::string regenerate =
    "the key tables changed: regenerate the committed schemas with scripts/update-golden (or "
    "build/camgen schema job > schema/job.schema.json and build/camgen schema machine > "
    "schema/machine.schema.json), review the diff and commit it";

const std::string minimal_job = R"({
  "$schema": "./schema/job.schema.json",
  "clearance": 10,
  "tools": [{"number": 1, "diameter": 6, "rpm": 1000}],
  "operations": [{"type": "drill", "tool": 1, "endDepth": 5, "plungingFeedrate": 100, "holes": [[0, 0]]}]
})";

}  // namespace

TEST_CASE("camgen schema job, machine and tools equal the committed schema files byte for byte") {
    for (const std::string name : {"job", "machine", "tools"}) {
        CAPTURE(name);
        Run r = run({"schema", name});
        CHECK(r.code == 0);
        CHECK(r.err.empty());
        const std::string committed = test::read_file(std::string(CAMGEN_SOURCE_DIR "/schema/") + name + ".schema.json");
        INFO(regenerate);
        CHECK(r.out == committed);
        CHECK(r.out.ends_with("}\n"));
    }
}

TEST_CASE("camgen schema with an unknown or missing word is a usage error") {
    Run r = run({"schema", "machines"});
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err == "camgen: unknown schema \"machines\" (did you mean \"machine\"?); camgen schema takes job, machine, tools\n");
    Run none = run({"schema"});
    CHECK(none.code == 2);
    Run help = run({"--help"});
    CHECK(help.out.find("schema") != std::string::npos);
}

TEST_CASE("the schemas are draft 2020-12 and carry every key of the readers' tables") {
    const nlohmann::ordered_json job = job_schema();
    CHECK(job["$schema"] == "https://json-schema.org/draft/2020-12/schema");
    CHECK(job["additionalProperties"] == false);
    CHECK(job["properties"].contains("$schema"));
    const auto& defs = job["$defs"];
    // Every operation type has its object, dispatched on "type".
    for (const auto& type : operation_type_names()) {
        CAPTURE(type);
        REQUIRE(defs.contains(type));
        CHECK(defs[type]["properties"]["type"]["const"] == type);
        CHECK(defs[type]["additionalProperties"] == false);
    }
    // The drilling fields come from the vocabulary's table, with its bounds.
    for (const auto& d : drill_fields) {
        CAPTURE(d.key);
        REQUIRE(defs["drill"]["properties"].contains(d.key));
        if (d.min) CHECK(defs["drill"]["properties"][d.key].contains(d.min->inclusive ? "minimum" : "exclusiveMinimum"));
    }
    CHECK(defs["drill"]["properties"]["cycle"]["enum"] == names_of(cycle_kinds));
    CHECK(defs["tool"]["properties"]["diameter"]["exclusiveMinimum"] == 0);
    CHECK(defs["pathArc"]["properties"]["plane"]["default"] == "xy");
    CHECK(defs["contour"]["properties"]["side"]["enum"] == names_of(contour_sides));
    const std::string feed = defs["contour"]["properties"]["feed"]["description"];
    CHECK(feed.find("mm/min") != std::string::npos);

    const nlohmann::ordered_json machine = machine_schema();
    // description, dialect and extension are required unless the file extends another.
    CHECK_FALSE(machine.contains("required"));
    CHECK(machine["properties"].contains("extends"));
    for (const char* key : {"description", "dialect", "extension"}) {
        const nlohmann::ordered_json either = {{"anyOf", {{{"required", {"extends"}}}, {{"required", {key}}}}}};
        bool found = false;
        for (const auto& rule : machine["allOf"]) found = found || rule["anyOf"] == either["anyOf"];
        CHECK_MESSAGE(found, key);
    }
    // MillDrillingFields names, then the TurnDrillingFields names a mill has no field of.
    std::vector<std::string> cycle_fields = drill_field_keys();
    for (const std::string& t : turn_drill_field_keys())
        if (!drill_field_named(t)) cycle_fields.push_back(t);
    CHECK(machine["$defs"]["drillingCycle"]["properties"]["fields"]["items"]["enum"] == cycle_fields);
}

TEST_CASE("a job may name its schema in \"$schema\"; camgen ignores it") {
    Job job = read_job(minimal_job, "test.json");
    CHECK(job.operations.size() == 1);
    std::string bad = minimal_job;
    bad.replace(bad.find("\"./schema/job.schema.json\""), 26, "42");
    CHECK_THROWS_WITH_AS(read_job(bad, "test.json"), "test.json:2: /$schema: expected a string, got a number (42)",
                         InputError);
}

}  // namespace test_schema
