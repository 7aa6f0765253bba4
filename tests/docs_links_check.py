#!/usr/bin/python3
"""The repository's pages link only inside it, and every link resolves.

    docs_links_check.py SOURCE

For every Markdown file of the repository (git ls-files, else every *.md outside build
folders): each link and image `[text](target)` that is not a URL must name a file or folder
inside SOURCE that exists, and an anchor (`page.md#anchor`, `#anchor`) must be a heading of
that page (GitHub's rule: lower case, punctuation dropped, spaces to hyphens). No tracked text
file may name `../shared`, a folder beside the clone that a user of the repository does not
have. README.md must link docs/scene.md. Exit 0 when all hold, 1 otherwise (each finding on
stderr).
"""

import os
import re
import subprocess
import sys

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")


def tracked(source, pattern=None):
    try:
        out = subprocess.run(["git", "-C", source, "ls-files", "-z"], check=True,
                             capture_output=True).stdout.decode()
        files = [f for f in out.split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for root, dirs, names in os.walk(source):
            dirs[:] = [d for d in dirs if not d.startswith((".", "build"))
                       and not os.path.exists(os.path.join(root, d, "CMakeCache.txt"))]
            files += [os.path.relpath(os.path.join(root, n), source) for n in names]
    return [f for f in files if pattern is None or f.endswith(pattern)]


def slug(heading):
    text = re.sub(r"[`*_]|<[^>]+>", "", heading)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading: its text
    text = re.sub(r"[^\w\- ]", "", text.strip().lower())
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        found, seen, fenced = set(), {}, False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if FENCE.match(line):
                    fenced = not fenced
                    continue
                m = None if fenced else HEADING.match(line)
                if m:
                    base = slug(m.group(1))
                    n = seen.get(base, 0)
                    seen[base] = n + 1
                    found.add(base if n == 0 else f"{base}-{n}")
        cache[path] = found
    return cache[path]


def main():
    source = os.path.realpath(sys.argv[1])
    problems, links = [], 0
    for page in tracked(source, ".md"):
        path = os.path.join(source, page)
        fenced = False
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                if FENCE.match(line):
                    fenced = not fenced
                if fenced:
                    continue
                for target in LINK.findall(re.sub(r"`[^`]*`", "", line)):
                    if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto:, ...
                        continue
                    links += 1
                    where = f"{page}:{number}: ({target})"
                    file_part, _, anchor = target.partition("#")
                    resolved = os.path.realpath(os.path.join(os.path.dirname(path), file_part))
                    if os.path.commonpath([resolved, source]) != source:
                        problems.append(f"{where} leads outside the repository")
                        continue
                    if not os.path.exists(resolved):
                        problems.append(f"{where}: no such file")
                        continue
                    if anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
                        problems.append(f"{where}: no heading '#{anchor}' in "
                                        f"{os.path.relpath(resolved, source)}")
    for name in tracked(source):
        path = os.path.join(source, name)
        if name.startswith("tests/docs_links_check") or not os.path.isfile(path):
            continue
        try:
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    if "../shared" in line:
                        problems.append(f"{name}:{number}: names ../shared, outside the "
                                        "repository")
        except UnicodeDecodeError:
            continue  # binary
    with open(os.path.join(source, "README.md"), encoding="utf-8") as f:
        if "(docs/scene.md)" not in f.read():
            problems.append("README.md does not link docs/scene.md")
    for problem in problems:
        print(problem, file=sys.stderr)
    print(f"{links} links checked, {len(problems)} problems")
    return 1 if problems or links == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
