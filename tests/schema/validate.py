#!/usr/bin/env python3
"""Independent check of camgen's JSON Schemas with python3-jsonschema (Debian bookworm: 4.10).

    validate.py SOURCE_DIR [CAMGEN]

1. schema/job.schema.json, schema/machine.schema.json and schema/tools.schema.json are valid
   draft 2020-12 schemas (Draft202012Validator.check_schema).
2. Every samples/*.json is valid against the job schema, every machines/*.json against the
   machine schema; samples/library/tools.json against the tools schema and the job beside it
   against the job schema; bad libraries are rejected.
3. The validator rejects bad jobs (an unknown key, a wrong type, values out of range, a key
   the cycle does not use, ...), each for the expected reason. A good job is accepted first,
   so that each rejection is the one change's doing.
4. With CAMGEN (the built binary), camgen agrees: it reads the good job and refuses each bad one.
   Only this cross-check runs camgen; the validation itself is jsonschema's alone.

Exits 0 when all hold, 1 otherwise (naming each failure).
"""
import copy
import glob
import json
import os
import subprocess
import sys
import tempfile

try:
    import jsonschema
    from jsonschema import Draft202012Validator
except ImportError:
    print("python3-jsonschema is missing: install it (scripts/install-deps --tests, or apt-get install python3-jsonschema)")
    sys.exit(1)

GOOD_JOB = {
    "$schema": "./schema/job.schema.json",
    "clearance": 10,
    "tools": [
        {"number": 1, "type": "drill", "diameter": 6, "tipAngle": 118, "rpm": 1200},
        {"number": 2, "type": "tap", "diameter": 8, "rpm": 300},
        {"number": 3, "type": "end-mill", "diameter": 4, "rpm": 4000},
    ],
    "operations": [
        {"type": "drill", "tool": 1, "cycle": "deep", "endDepth": 12, "firstDepth": 4,
         "degressionType": "value", "degression": 1, "minimumDepth": 2, "plungingFeedrate": 120,
         "holes": [[10, 10], {"x": 30, "y": 10}]},
        {"type": "drill", "tool": 2, "cycle": "tap", "endDepth": 10, "pitch": 1.25,
         "grid": {"origin": [0, 0], "countX": 2, "countY": 2, "spacingX": 10, "spacingY": 10}},
        {"type": "path", "tool": 3, "z": -1, "feed": 300, "start": [20, 0],
         "path": [{"line": [30, 0]},
                  {"arc": {"end": [40, 10], "centre": [30, 10], "direction": "ccw"}},
                  {"helix": {"centre": [40, 12], "direction": "cw", "turns": 2, "pitch": 1}}]},
    ],
}


def edited(path, value=None, delete=False):
    """GOOD_JOB with the value at `path` (a list of keys and indices) set, added or deleted."""
    job = copy.deepcopy(GOOD_JOB)
    target = job
    for step in path[:-1]:
        target = target[step]
    if delete:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return job


# (what, job, the validator keyword that must reject it, the JSON path it must point at)
BAD_JOBS = [
    ("an unknown key", edited(["operations", 0, "holez"], [[0, 0]]), "additionalProperties", ["operations", 0]),
    ("a wrong type", edited(["clearance"], "ten"), "type", ["clearance"]),
    ("a tool diameter of 0", edited(["tools", 0, "diameter"], 0), "exclusiveMinimum", ["tools", 0, "diameter"]),
    ("a negative plungingFeedrate", edited(["operations", 0, "plungingFeedrate"], -5), "exclusiveMinimum",
     ["operations", 0, "plungingFeedrate"]),
    ("an unknown cycle", edited(["operations", 0, "cycle"], "peck"), "enum", ["operations", 0, "cycle"]),
    ("a key the cycle does not use", edited(["operations", 1, "plungingFeedrate"], 100), "false schema",
     ["operations", 1, "plungingFeedrate"]),
    ("a cycle without its required field", edited(["operations", 1, "pitch"], delete=True), "required",
     ["operations", 1]),
    ("a drill operation without holes", edited(["operations", 0, "holes"], delete=True), "anyOf", ["operations", 0]),
    ("a point of three numbers where two are needed", edited(["operations", 2, "start"], [1, 2, 3]), "maxItems",
     ["operations", 2, "start"]),
    ("a helix with z, turns and pitch", edited(["operations", 2, "path", 2, "helix", "z"], -5), "oneOf",
     ["operations", 2, "path", 2, "helix"]),
    ("a tool number of 0", edited(["tools", 0, "number"], 0), "minimum", ["tools", 0, "number"]),
]

BAD_MACHINE_EDITS = [
    ("an unknown key", ["arcs", "maxSweeps"], 90, "additionalProperties"),
    ("a wrong type", ["modalMotion"], "no", "type"),
    ("decimals out of range", ["formats", "xyz", "decimals"], 13, "maximum"),
    ("an unknown drilling field", ["drilling", "cycles", 0, "fields", 0], "plungeFeed", "enum"),
]


def leaf_errors(error):
    """The errors at the bottom of `error`'s context (where anyOf/oneOf/if-then lead)."""
    if not error.context:
        yield error
        return
    for sub in error.context:
        yield from leaf_errors(sub)


def rejects_for(validator, instance, keyword, path):
    """True when validating `instance` fails with `keyword` at `path` (also inside combinators)."""
    for error in validator.iter_errors(instance):
        for e in [error, *leaf_errors(error)]:
            where = list(e.absolute_path)
            if keyword == "false schema":
                # Some jsonschema versions report a false subschema at the object, not its key.
                if e.schema is False and where in (path, path[:-1]):
                    return True
            elif e.validator == keyword and where == path:
                return True
    return False


def describe_errors(validator, instance):
    return "; ".join(f"/{'/'.join(map(str, e.absolute_path))}: {e.message}" for e in validator.iter_errors(instance))


def camgen_reads(camgen, job):
    """camgen's exit code and message for a job (cross-check only)."""
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(job, f)
        name = f.name
    try:
        r = subprocess.run([camgen, name, "--events"], capture_output=True, text=True)
        return r.returncode, r.stderr.strip()
    finally:
        os.unlink(name)


def main():
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        return 2
    root = sys.argv[1]
    camgen = sys.argv[2] if len(sys.argv) == 3 else None
    failures = []
    print(f"{sys.executable}: jsonschema from {os.path.dirname(jsonschema.__file__)}, Draft202012Validator")

    validators = {}
    for name in ("job", "machine", "tools"):
        path = os.path.join(root, "schema", f"{name}.schema.json")
        with open(path, encoding="utf-8") as f:
            schema = json.load(f)
        try:
            Draft202012Validator.check_schema(schema)
        except jsonschema.exceptions.SchemaError as e:
            failures.append(f"{path} is not a valid draft 2020-12 schema: {e.message}")
            continue
        if schema.get("$schema") != "https://json-schema.org/draft/2020-12/schema":
            failures.append(f"{path} does not declare draft 2020-12")
        validators[name] = Draft202012Validator(schema)
        print(f"ok   {path}: a valid draft 2020-12 schema")
    if len(validators) != 3:
        print("\n".join("FAIL " + f for f in failures))
        return 1

    for name, pattern in (("job", "samples/*.json"), ("machine", "machines/*.json"),
                          ("tools", "samples/library/tools.json"), ("job", "samples/library/plate-library.json")):
        files = sorted(glob.glob(os.path.join(root, pattern)))
        if not files:
            failures.append(f"no files match {pattern}")
        for path in files:
            with open(path, encoding="utf-8") as f:
                instance = json.load(f)
            errors = describe_errors(validators[name], instance)
            if errors:
                failures.append(f"{path} is not valid against the {name} schema: {errors}")
            else:
                print(f"ok   {os.path.relpath(path, root)} is a valid {name} file")

    job_validator = validators["job"]
    errors = describe_errors(job_validator, GOOD_JOB)
    if errors:
        failures.append(f"the good job is rejected: {errors}")
    else:
        print("ok   the good job is valid")
    if camgen:
        code, message = camgen_reads(camgen, GOOD_JOB)
        if code != 0:
            failures.append(f"camgen refuses the good job: {message}")

    for what, job, keyword, path in BAD_JOBS:
        where = "/" + "/".join(map(str, path))
        if job_validator.is_valid(job):
            failures.append(f"the validator accepts a job with {what}")
            continue
        if not rejects_for(job_validator, job, keyword, path):
            failures.append(f"a job with {what} is rejected, but not by {keyword} at {where}: "
                            f"{describe_errors(job_validator, job)}")
            continue
        print(f"ok   a job with {what} is rejected ({keyword} at {where})")
        if camgen:
            code, message = camgen_reads(camgen, job)
            if code != 1:
                failures.append(f"camgen accepts a job with {what} (exit {code})")
            else:
                print(f"       camgen agrees: {message}")

    with open(os.path.join(root, "machines", "fanuc.json"), encoding="utf-8") as f:
        good_machine = json.load(f)
    for what, path, value, keyword in BAD_MACHINE_EDITS:
        machine = copy.deepcopy(good_machine)
        target = machine
        for step in path[:-1]:
            target = target[step]
        target[path[-1]] = value
        if validators["machine"].is_valid(machine):
            failures.append(f"the validator accepts a machine file with {what}")
        elif not rejects_for(validators["machine"], machine, keyword,
                             path[:-1] if keyword == "additionalProperties" else path):
            failures.append(f"a machine file with {what} is rejected, but not by {keyword}: "
                            f"{describe_errors(validators['machine'], machine)}")
        else:
            print(f"ok   a machine file with {what} is rejected ({keyword})")

    # A file that extends another gives only what differs; without extends the three are needed.
    extension = {"extends": "fanuc", "globals": {"decimalMark": ",", "showSequenceNumbers": True}}
    if not validators["machine"].is_valid(extension):
        failures.append("a machine file that extends fanuc is rejected: "
                        f"{describe_errors(validators['machine'], extension)}")
    else:
        print("ok   a machine file that extends fanuc and gives two globals is valid")
    for key in ("description", "dialect", "extension"):
        machine = copy.deepcopy(good_machine)
        del machine[key]
        if validators["machine"].is_valid(machine):
            failures.append(f"the validator accepts a machine file without {key} that extends nothing")
        else:
            print(f"ok   a machine file without {key} that extends nothing is rejected")

    # Tool libraries: each bad one rejected for its reason.
    with open(os.path.join(root, "samples", "library", "tools.json"), encoding="utf-8") as f:
        good_library = json.load(f)
    bad_libraries = (
        ("a tool without a name", ["tools", 0, "name"], None, "required"),
        ("an unknown key", ["tools", 0, "bogus"], 1, "additionalProperties"),
        ("a diameter as a string", ["tools", 0, "diameter"], "6", "type"),
        ("a tool number of 0", ["tools", 0, "number"], 0, "minimum"),
        ("a job's libraryNumber", ["tools", 0, "libraryNumber"], 3, "additionalProperties"),
        ("a negative surface speed", ["tools", 0, "cuttingData", 0, "surfaceSpeed"], -5, "exclusiveMinimum"),
        ("cutting data without a material", ["tools", 0, "cuttingData", 0, "material"], None, "required"),
    )
    for what, path, value, keyword in bad_libraries:
        library = copy.deepcopy(good_library)
        target = library
        for step in path[:-1]:
            target = target[step]
        if value is None:
            del target[path[-1]]
        else:
            target[path[-1]] = value
        if validators["tools"].is_valid(library):
            failures.append(f"the validator accepts a tool library with {what}")
        elif not rejects_for(validators["tools"], library, keyword,
                             path[:-1] if keyword in ("required", "additionalProperties") else path):
            failures.append(f"a tool library with {what} is rejected, but not by {keyword}: "
                            f"{describe_errors(validators['tools'], library)}")
        else:
            print(f"ok   a tool library with {what} is rejected ({keyword})")

    for f in failures:
        print("FAIL " + f)
    print(f"{'FAILED' if failures else 'passed'}: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
