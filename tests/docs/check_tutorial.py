#!/usr/bin/env python3
"""Runs every command of a Markdown walkthrough (docs/tutorial.md) and compares what it prints
with what the page shows.

    check_tutorial.py CAMGEN PAGE [--update]

The page is read top to bottom, in one scratch folder:
- a fenced block whose opening line is preceded by `<!-- file: NAME -->` is written to NAME
  (the reader types it in; later commands use it);
- a fenced `console` block holds commands and their output: a line `$ COMMAND` is run with
  bash in the scratch folder (standard error into standard output, `camgen` being CAMGEN); the
  lines after it, up to the next `$ ` line or the end of the block, are what it must print,
  byte for byte (trailing spaces aside). A command that fails shows `[exit N]` as its last
  line; a command without it must exit 0.

With --update the page's console blocks are rewritten with what the commands print now
(review the diff like a golden file). Exits 0 when every command printed what the page shows,
1 otherwise, naming the command and showing both.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

FENCE = re.compile(r"^(```+)(\S*)\s*$")
FILE_MARK = re.compile(r"^<!--\s*file:\s*(\S+)\s*-->\s*$")


def run(command, folder, camgen):
    bindir = os.path.join(folder, ".bin")
    env = dict(os.environ)
    env["PATH"] = bindir + os.pathsep + env.get("PATH", "")
    env["LC_ALL"] = "C"
    # The user's own machines and configuration stay out of the walkthrough.
    env["XDG_CONFIG_HOME"] = os.path.join(folder, ".config")
    env.pop("CAMGEN_MACHINES", None)
    done = subprocess.run(["bash", "-c", command], cwd=folder, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, timeout=120)
    lines = done.stdout.decode("utf-8", "replace").splitlines()
    if done.returncode != 0:
        lines.append(f"[exit {done.returncode}]")
    return [line.rstrip() for line in lines]


def main():
    args = [a for a in sys.argv[1:] if a != "--update"]
    update = "--update" in sys.argv[1:]
    if len(args) != 2:
        print(__doc__)
        return 2
    camgen, page = os.path.abspath(args[0]), args[1]
    with open(page, encoding="utf-8") as f:
        text = f.read().split("\n")

    folder = tempfile.mkdtemp(prefix="camgen-tutorial-")
    os.makedirs(os.path.join(folder, ".bin"))
    os.symlink(camgen, os.path.join(folder, ".bin", "camgen"))
    failures = 0
    commands = 0
    out = []
    i = 0
    pending_file = None
    try:
        while i < len(text):
            line = text[i]
            mark = FILE_MARK.match(line)
            if mark:
                pending_file = mark.group(1)
                out.append(line)
                i += 1
                continue
            fence = FENCE.match(line)
            if not fence:
                if line.strip():
                    pending_file = None
                out.append(line)
                i += 1
                continue
            ticks, lang = fence.group(1), fence.group(2)
            end = i + 1
            while end < len(text) and text[end].rstrip() != ticks:
                end += 1
            if end == len(text):
                print(f"{page}:{i + 1}: a fenced block that never ends")
                return 1
            body = text[i + 1:end]
            if pending_file:
                with open(os.path.join(folder, pending_file), "w", encoding="utf-8") as f:
                    f.write("\n".join(body) + "\n")
                pending_file = None
                out.extend(text[i:end + 1])
            elif lang == "console":
                out.append(line)
                j = 0
                while j < len(body):
                    if not body[j].startswith("$ "):
                        print(f"{page}:{i + 2 + j}: console block line before any command: {body[j]!r}")
                        return 1
                    command = body[j][2:]
                    k = j + 1
                    while k < len(body) and not body[k].startswith("$ "):
                        k += 1
                    expected = [l.rstrip() for l in body[j + 1:k]]
                    got = run(command, folder, camgen)
                    commands += 1
                    if got != expected and not update:
                        failures += 1
                        print(f"{page}:{i + 2 + j}: `{command}` printed:")
                        print("\n".join("    " + l for l in got))
                        print("  the page shows:")
                        print("\n".join("    " + l for l in expected))
                    out.append(body[j])
                    out.extend(got)
                    j = k
                out.append(text[end])
            else:
                out.extend(text[i:end + 1])
            i = end + 1
    finally:
        shutil.rmtree(folder, ignore_errors=True)

    if update:
        with open(page, "w", encoding="utf-8") as f:
            f.write("\n".join(out))
        print(f"{page}: {commands} commands run, page rewritten")
        return 0
    if commands == 0:
        print(f"{page}: no command found")
        return 1
    if failures:
        print(f"{page}: {failures} of {commands} commands printed something else")
        return 1
    print(f"{page}: {commands} commands printed what the page shows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
