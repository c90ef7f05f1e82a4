#!/usr/bin/env python3
"""Every relative link of the user documentation resolves inside the repository.

    check_links.py SOURCE_DIR

Reads README.md and docs/*.md; for each Markdown link `[text](target)` that is not a URL
(http:, https:, mailto:), the file must exist inside SOURCE_DIR (a link that leaves the
repository is a failure) and a `#anchor` must be a heading of the target file, made into an
anchor the way GitHub does (lower case, punctuation other than `-` and `_` dropped, spaces to
`-`). Exits 0 when all resolve, 1 naming each that does not.
"""
import os
import re
import sys

LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def anchors_of(path):
    found = set()
    in_fence = False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                in_fence = not in_fence
            if in_fence or not line.startswith("#"):
                continue
            title = line.lstrip("#").strip()
            slug = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
            found.add(slug)
    return found


def main():
    root = os.path.realpath(sys.argv[1])
    pages = [os.path.join(root, "README.md")] + sorted(
        os.path.join(root, "docs", p) for p in os.listdir(os.path.join(root, "docs")) if p.endswith(".md"))
    bad = 0
    links = 0
    for page in pages:
        with open(page, encoding="utf-8") as f:
            text = f.read()
        # Links inside code blocks are examples, not links.
        text = re.sub(r"```.*?```", "", text, flags=re.S)
        for number, line in enumerate(text.split("\n"), 1):
            for target in LINK.findall(line):
                if re.match(r"^(https?|mailto):", target):
                    continue
                links += 1
                file_part, _, anchor = target.partition("#")
                resolved = os.path.realpath(os.path.join(os.path.dirname(page), file_part)) if file_part else page
                where = os.path.relpath(page, root)
                if not (resolved == root or resolved.startswith(root + os.sep)):
                    print(f"{where}: {target}: leaves the repository")
                    bad += 1
                elif not os.path.exists(resolved):
                    print(f"{where}: {target}: no such file")
                    bad += 1
                elif anchor and resolved.endswith(".md") and anchor not in anchors_of(resolved):
                    print(f"{where}: {target}: no heading #{anchor} in {os.path.relpath(resolved, root)}")
                    bad += 1
    print(f"{links} links, {bad} broken")
    return 1 if bad or links == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
