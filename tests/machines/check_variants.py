#!/usr/bin/env python3
"""A machine file cannot break motion (issue 24). For every built-in machine (machines/*.json),
variants that change one setting ({"extends": "<name>", ...}): formats' decimals, scale, width,
zeropad, forceDecimal, forceSign; the decimal mark and other globals (xDiameterProg,
iDiameterProg, separators, block numbers, tolerance); arc settings (form, planes, helices,
sweep); start-block words (each one taken out, a mode word added). For each variant either

  * camgen refuses the machine file: exit code 1, a message "FILE:LINE: /json/path: ..." naming
    the variant's file and a line in it, or
  * every sample the machine posts (those with a golden program in tests/golden/<machine>/)
    that the variant posts reads back: `camgen verify PROG --machine FILE --job SAMPLE` says it
    matches, and for the ISO machines whose own programs rs274 runs (LinuxCNC's interpreter, the
    independent reader) `rs274 -g` runs it to PROGRAM_END with exit 0. A sample the variant
    cannot post (a job refused on it, exit 1, naming the sample, nothing written) is counted,
    not failed.

Variants and variant x sample pairs are sampled: --variants of each machine's ~250 (default 50, or CAMGEN_VARIANTS,
0: all) are read, and each accepted one posts --samples of its machine's samples (default 1),
drawn with the seed. KNOWN_GAPS lists the variants left out, and why. The seed is printed;
--seed (or CAMGEN_VARIANT_SEED) repeats a run, --samples 0 posts every sample of every variant.

Usage: check_variants.py CAMGEN SOURCE_DIR [--seed N] [--variants N] [--samples N] [--jobs N]
                         [--machine NAME]... [--keep DIR]"""
import argparse
import concurrent.futures
import itertools
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

FORMAT_KEYS = ["xyz", "ijk", "x", "z", "i", "feed", "rpm", "dwell", "feedPerRev", "angle", "code"]
FORMAT_SETTINGS = {
    "decimals": [0, 1, 2, 3, 4, 6],
    "scale": [0.5, 2, 10],
    "width": [1, 3, 8],
    "zeropad": [True, False],
    "forceDecimal": [True, False],
    "forceSign": [True, False],
}
GLOBALS = {
    "decimalMark": [".", ","],
    "xDiameterProg": [True, False],
    "iDiameterProg": [True, False],
    "variableDelimeter": ["", "  "],
    "showSequenceNumbers": [True, False],
    "sequenceNumberIncrement": [1, 100],
    "tolerance": [0.0005, 0.02],
    "linebreak": ["\r\n"],
    "cutterCompensation": [False],
}
PLANE_SETS = [[], ["xy"], ["xz"], ["yz"], ["xy", "xz"], ["xz", "yz"], ["xy", "xz", "yz"]]
ARCS = {
    "format": ["ijk-relative", "ijk-absolute", "radius", "nccad-angle"],
    "planes": PLANE_SETS,
    "helical": [True, False],
    "maxSweep": [90, 180, 359],
    "forceXY": [True, False],
    "minSegments": [3],
    "maxRadius": [4],
    "chordTolerance": [0.05],
}
START_WORDS = ["G7", "G8", "G17", "G18", "G19", "DIAMON", "DIAMOF", "G40", "G80", "G90", "G94", "G21"]
TOP = {"modalMotion": [False], "comments": ["semicolon", "parentheses"], "commentMaxLength": [12]}
ISO_DIALECTS = {"iso", "iso-lathe"}
# Variants camgen cannot refuse yet, each with why. A LinuxCNC lathe without G7 programs X as a
# radius, but the file is then one camgen cannot tell from a Fanuc T lathe (system B/C, feed
# modes G94/G95) whose diameter mode is a parameter: rs274 reads its X as radii.
KNOWN_GAPS = {("linuxcnc-lathe", "startBlock-G7")}


def variants_of(name, base):
    """Every one-setting change of machine `base` (its JSON), as (label, patch)."""
    out = []
    for key, (setting, values) in itertools.product(FORMAT_KEYS, FORMAT_SETTINGS.items()):
        for v in values:
            out.append((f"formats.{key}.{setting}={json.dumps(v)}", {"formats": {key: {setting: v}}}))
    for setting, values in GLOBALS.items():
        for v in values:
            out.append((f"globals.{setting}={json.dumps(v)}", {"globals": {setting: v}}))
    for setting, values in ARCS.items():
        for v in values:
            out.append((f"arcs.{setting}={json.dumps(v)}", {"arcs": {setting: v}}))
    start = base.get("frame", {}).get("startBlock", [])
    for i, word in enumerate(start):
        rest = start[:i] + start[i + 1:]
        out.append((f"startBlock-{word}", {"frame": {"startBlock": rest}}))
    for word in START_WORDS:
        if word not in start:
            out.append((f"startBlock+{word}", {"frame": {"startBlock": start + [word]}}))
    for setting, values in TOP.items():
        for v in values:
            out.append((f"{setting}={json.dumps(v)}", {setting: v}))
    # The lathe settings only mean something on lathes; a mill refuses them already.
    return [(label, {"extends": name, **patch}) for label, patch in out if (name, label) not in KNOWN_GAPS]


def run(args, env=None, timeout=60):
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, timeout=timeout)
    return p.returncode, p.stdout.decode(errors="replace"), p.stderr.decode(errors="replace")


class Checker:
    def __init__(self, camgen, source, work, rs274):
        self.camgen, self.source, self.work, self.rs274 = camgen, source, work, rs274
        self.tools = os.path.join(work, "tool.tbl")
        with open(self.tools, "w") as f:
            # rs274's table is in inches; tools 1 to 99, and the turret calls T0101 .. T0909.
            for i in range(1, 100):
                f.write(f"T{i} P{i} Z0 D0.1 ;tool {i}\n")
            for i in range(1, 10):
                f.write(f"T{i * 101} P{100 + i} Z0 D0.1 ;turret tool {i}\n")

    def rs274_runs(self, program):
        """None when rs274 runs the program to PROGRAM_END with exit 0, else why not."""
        # rs274 keeps its tool table in $HOME/.tool.mmap: one HOME per thread.
        home = os.path.join(self.work, f"home-{threading.get_ident()}")
        os.makedirs(home, exist_ok=True)
        code, out, err = run([self.rs274, "-t", self.tools, "-g", program], env={**os.environ, "HOME": home})
        if code == 0 and "PROGRAM_END" in out:
            return None
        return f"rs274 exit {code}: {err.strip()[-300:]}"

    def post(self, machine_file, sample, out, use_rs274):
        """(outcome, detail): outcome 'ok', 'job-refused' or 'FAIL'."""
        code, _, err = run([self.camgen, sample, "--machine", machine_file, "-o", out, "--quiet"])
        if code != 0:
            if os.path.exists(out):
                return "FAIL", f"exit {code} but {out} was written"
            if code == 1 and err.startswith(f"camgen: {machine_file}:"):
                # Refused by the dialect when it starts to post (its settings): the file is named.
                return "refused-late", err.strip()
            if code == 1 and sample in err:
                return "job-refused", err.strip()
            return "FAIL", f"post exit {code}: {err.strip()}"
        code, vout, verr = run([self.camgen, "verify", out, "--machine", machine_file, "--job", sample])
        if code != 0:
            return "FAIL", f"verify exit {code}: {(vout + verr).strip()[-600:]}"
        if use_rs274:
            why = self.rs274_runs(out)
            if why:
                return "FAIL", why
        return "ok", ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("camgen")
    ap.add_argument("source")
    ap.add_argument("--seed", type=int, default=int(os.environ.get("CAMGEN_VARIANT_SEED", "24")))
    ap.add_argument("--variants", type=int, default=int(os.environ.get("CAMGEN_VARIANTS", "50")),
                    help="variants per machine, drawn with the seed from the ~250 of each (0: all; 50 keeps ctest "
                         "near a minute on 2 cores)")
    ap.add_argument("--samples", type=int, default=1, help="samples posted per accepted variant (0: all)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--machine", action="append", default=[])
    ap.add_argument("--keep", help="a folder to keep the variants and programs in")
    a = ap.parse_args()
    camgen = os.path.abspath(a.camgen)
    rs274 = shutil.which("rs274")
    rng = random.Random(a.seed)
    print(f"seed {a.seed} (--seed N or CAMGEN_VARIANT_SEED to repeat or change); left out: "
          f"{', '.join(f'{m} {v}' for m, v in sorted(KNOWN_GAPS))}")
    started = time.monotonic()
    work = a.keep or tempfile.mkdtemp(prefix="camgen-variants-")
    os.makedirs(work, exist_ok=True)
    checker = Checker(camgen, a.source, work, rs274)
    machines_dir = os.path.join(a.source, "machines")
    names = sorted(f[:-5] for f in os.listdir(machines_dir) if f.endswith(".json"))
    if a.machine:
        names = [n for n in names if n in a.machine]
    failures, counts = [], {}

    tasks = []  # (machine, label, file, samples, use_rs274)
    for name in names:
        base = json.load(open(os.path.join(machines_dir, name + ".json")))
        golden = os.path.join(a.source, "tests", "golden", name)
        samples = sorted(os.path.join(a.source, "samples", f.rsplit(".", 1)[0] + ".json")
                         for f in os.listdir(golden) if not f.endswith(".err"))
        # rs274 judges the ISO machines whose own programs it runs (Fanuc T's G50 S and T0101
        # are no words of LinuxCNC's).
        use_rs274 = False
        if rs274 and base.get("dialect") in ISO_DIALECTS:
            use_rs274 = all(checker.rs274_runs(os.path.join(golden, f)) is None
                            for f in os.listdir(golden) if not f.endswith(".err"))
        variants = variants_of(name, base)
        if a.variants and a.variants < len(variants):
            variants = rng.sample(variants, a.variants)
        counts[name] = {"variants": len(variants), "refused": 0, "accepted": 0, "posted": 0, "job-refused": 0,
                        "refused-late": 0, "rs274": use_rs274}
        for k, (label, doc) in enumerate(variants):
            path = os.path.join(work, f"{name}-{k:03d}.json")
            with open(path, "w") as f:
                f.write("{\n")
                items = list(doc.items())
                for j, (key, value) in enumerate(items):
                    f.write(f"  {json.dumps(key)}: {json.dumps(value)}{',' if j + 1 < len(items) else ''}\n")
                f.write("}\n")
            chosen = samples if a.samples == 0 else rng.sample(samples, min(a.samples, len(samples)))
            tasks.append((name, label, path, chosen, use_rs274))

    def check(task):
        name, label, path, chosen, use_rs274 = task
        code, _, err = run([camgen, "--describe-machine", path])
        if code != 0:
            where = err.split(path + ":", 1)
            if code == 1 and len(where) == 2 and re.match(r"\d+: /", where[1]) and int(where[1].split(":")[0]) > 0:
                return name, label, "refused", [], err.strip()
            return name, label, "FAIL", [f"{label}: refused without naming {path} and a line (exit {code}): {err.strip()}"], ""
        results = []
        for sample in chosen:
            out = path[:-5] + "-" + os.path.basename(sample)[:-5] + ".nc"
            outcome, detail = checker.post(path, sample, out, use_rs274)
            results.append((sample, outcome, detail))
        fails = [f"{label} ({path}) with {os.path.basename(s)}: {d}" for s, o, d in results if o == "FAIL"]
        return name, label, "accepted", fails, results

    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for name, label, status, fails, results in pool.map(check, tasks):
            c = counts[name]
            if status == "refused":
                c["refused"] += 1
            elif status == "accepted":
                c["accepted"] += 1
                for _, outcome, _ in results:
                    key = {"ok": "posted"}.get(outcome, outcome)
                    if key in c:
                        c[key] += 1
            failures.extend(fails)

    for name, c in counts.items():
        print(f"{name:16} variants {c['variants']:4}  refused {c['refused']:4}  accepted {c['accepted']:4}  "
              f"posted and read back {c['posted']:4}{' (and rs274)' if c['rs274'] else ''}  "
              f"job refused {c['job-refused']:3}  refused when posting {c['refused-late']:3}")
    total = {k: sum(c[k] for c in counts.values()) for k in ("variants", "refused", "accepted", "posted")}
    print(f"total: {total['variants']} variants, {total['refused']} refused, {total['accepted']} accepted, "
          f"{total['posted']} programs posted and read back; {time.monotonic() - started:.1f} s")
    if not a.keep:
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print(f"{len(failures)} FAILURES (seed {a.seed}):")
        for f in failures:
            print("  " + f)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
