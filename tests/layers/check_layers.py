#!/usr/bin/env python3
"""The include rule of docs/design.md, checked on every source and header of camgen.

Each file belongs to a layer by its path; each `#include "..."` of a camgen header names the
layer of the header. A layer may include only the layers listed for it below. Prints every
violation with file and line and exits 1 when there is one; prints a summary otherwise.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()

# Path prefixes (of a file, or of an include as written) -> layer. First match wins.
LAYERS = [
    ("include/camgen/geometry/", "geometry"), ("src/geometry/", "geometry"), ("camgen/geometry/", "geometry"),
    ("include/camgen/vocabulary/", "vocabulary"), ("src/vocabulary/", "vocabulary"), ("camgen/vocabulary/", "vocabulary"),
    ("include/camgen/dxf/", "dxf"), ("src/dxf/", "dxf"), ("camgen/dxf/", "dxf"),
    ("include/camgen/common/", "common"), ("src/common/", "common"), ("camgen/common/", "common"),
    ("include/camgen/events/", "events"), ("src/events/", "events"), ("camgen/events/", "events"),
    ("include/camgen/job/", "job"), ("src/job/", "job"), ("camgen/job/", "job"),
    ("include/camgen/operations/", "operations"), ("operations/", "operations"), ("camgen/operations/", "operations"),
    ("include/camgen/nc/", "nc"), ("src/nc/", "nc"), ("camgen/nc/", "nc"),
    ("include/camgen/post/", "post"), ("src/post/", "post"), ("camgen/post/", "post"),
    ("include/camgen/reader/", "reader"), ("src/reader/", "reader"), ("camgen/reader/", "reader"),
    ("machines/", "dialect"),
    ("include/camgen/analysis/", "analysis"), ("src/analysis/", "analysis"), ("camgen/analysis/", "analysis"),
    ("include/camgen/simulation/", "simulation"), ("src/simulation/", "simulation"), ("camgen/simulation/", "simulation"),
    ("include/camgen/schema/", "schema"), ("src/schema/", "schema"), ("camgen/schema/", "schema"),
    ("include/camgen/cli/", "cli"), ("src/cli/", "cli"), ("camgen/cli/", "cli"),
]

BASE = {"geometry", "vocabulary", "common"}
ALLOWED = {
    "geometry": {"geometry"},
    "vocabulary": {"vocabulary", "geometry"},
    "common": {"common", "vocabulary", "geometry"},
    "events": {"events", "vocabulary", "geometry"},
    "job": {"job"} | BASE,
    "dxf": {"dxf", "geometry"},
    "operations": {"operations", "job", "events", "dxf"} | BASE,
    "nc": {"nc", "common"},
    "post": {"post", "nc", "events"} | BASE,
    "reader": {"reader", "post", "nc", "events"} | BASE,
    "dialect": {"dialect", "post", "reader", "nc", "events"} | BASE,
    "analysis": {"analysis", "reader", "post", "nc", "events"} | BASE,
    "simulation": {"simulation", "analysis", "reader", "post", "nc", "operations", "job", "events"} | BASE,
    "schema": {"schema", "operations", "job", "post", "nc", "events"} | BASE,
    "cli": {"cli", "dxf", "schema", "simulation", "analysis", "reader", "dialect", "post", "nc", "operations", "job", "events"} | BASE,
}
# A dialect folder includes its own files and the shared registry header only, never another
# dialect's folder.
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def layer_of(path):
    for prefix, layer in LAYERS:
        if path.startswith(prefix):
            return layer
    return None


def main():
    files = sorted(p for d in ("include", "src", "operations", "machines")
                   for p in (ROOT / d).rglob("*") if p.suffix in (".cpp", ".hpp"))
    problems, checked, edges = [], 0, 0
    for f in files:
        rel = f.relative_to(ROOT).as_posix()
        layer = layer_of(rel)
        if layer is None:
            problems.append(f"{rel}: is in no layer of docs/design.md")
            continue
        checked += 1
        for n, line in enumerate(f.read_text().splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            target = m.group(1)
            to = layer_of(target)
            if to is None:
                problems.append(f"{rel}:{n}: includes \"{target}\", which is in no layer")
                continue
            edges += 1
            if to not in ALLOWED[layer]:
                problems.append(f"{rel}:{n}: {layer} may not include {to} (\"{target}\")")
            if layer == "dialect" and to == "dialect":
                own = rel.split("/")[1] if rel.count("/") >= 2 else None
                other = target.split("/")[1] if target.count("/") >= 2 else None
                if own and other and own != other:
                    problems.append(f"{rel}:{n}: dialect {own} includes dialect {other} (\"{target}\")")
    for p in problems:
        print(p)
    print(f"{checked} files, {edges} camgen includes checked: {len(problems)} violation(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
