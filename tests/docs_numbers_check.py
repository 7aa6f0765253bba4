#!/usr/bin/python3
"""The numbers README.md and docs/library.md quote are what their commands print today.

    docs_numbers_check.py --rockdd BUILD/bin/rockdd --tip BUILD/bin/tip_in_tree
                          --source SOURCE --work DIR [--python PYTHON]

- README.md's ensemble: the ```sh block that runs `rockdd mc` and `tools/plot ensemble` is run
  as written (its paths mapped to this build and source tree, its output folder to DIR), and
  the line `tools/plot ensemble` prints about the peaks must be in README.md verbatim, its mean
  and spread in docs/status.md, and seed 1's peak stress in both. Six realizations of the
  paper's compression specimen: about 2 minutes on 2 cores.
- README.md's Python snippet runs without an error (with --python, the build's module on
  PYTHONPATH).
- docs/library.md: the tip displacement the installed examples print (tip_in_tree, the same
  program built in the tree) is quoted wherever the page quotes one, and with --python every
  line tests/consumer/example.py prints is in the page's transcript of it.

Exit 0 when every check holds, 1 otherwise.
"""

import argparse
import csv
import os
import re
import shlex
import shutil
import subprocess
import sys
import tomllib

FAILURES = []


def expect(condition, message):
    if not condition:
        FAILURES.append(message)
        print(f"FAIL: {message}", file=sys.stderr)


def blocks(text, language):
    return re.findall(r"^```" + language + r"\n(.*?)^```", text, flags=re.S | re.M)


def readme_ensemble(args, readme):
    found = [b for b in blocks(readme, "sh") if "rockdd mc " in b and "tools/plot ensemble" in b]
    expect(len(found) == 1, f"README.md has {len(found)} sh blocks with rockdd mc and "
                            "tools/plot ensemble, not 1")
    if len(found) != 1:
        return
    work = os.path.join(args.work, "readme_ensemble")
    shutil.rmtree(work, ignore_errors=True)  # an earlier run's ensemble would be resumed
    os.makedirs(work)
    printed = ""
    for line in found[0].splitlines():
        words = shlex.split(line, comments=True)
        if not words:
            continue
        if words[0].endswith("bin/rockdd"):
            words[0] = args.rockdd
        elif words[0] == "tools/plot":
            words[0] = os.path.join(args.source, "tools", "plot")
        words = [os.path.join(args.source, w) if w.startswith("data/") else w for w in words]
        run = subprocess.run(words, cwd=work, capture_output=True, text=True)
        expect(run.returncode == 0, f"{line}: exit {run.returncode}\n{run.stderr}")
        printed += run.stdout
    quoted = [line for line in printed.splitlines() if line.startswith("peaks.")]
    expect(bool(quoted), "tools/plot ensemble printed no peaks line")
    for line in quoted:
        print(line)
        expect(line in readme, f"README.md does not quote what tools/plot ensemble prints:\n"
                               f"  {line}")
    # docs/status.md quotes the mean and spread, and both pages seed 1's peak stress (its force
    # over the specimen's width and thickness, as tools/plot ensemble takes it).
    with open(os.path.join(args.source, "docs", "status.md"), encoding="utf-8") as f:
        status = f.read()
    spread = re.search(r"peak stress (\S+ ± \S+ MPa)", quoted[0] if quoted else "")
    expect(spread and f"the peak is {spread.group(1)}" in status,
           f"docs/status.md does not quote the ensemble's {spread and spread.group(1)}")
    with open(os.path.join(args.source, "data", "uniaxial_compression.toml"), "rb") as f:
        scene = tomllib.load(f)
    area = scene["mesh"]["size"][0] * scene["scene"].get("thickness", 1.0)
    with open(os.path.join(work, "mc", "uniaxial-compression", "mc.csv"), newline="") as f:
        seed_1 = [r for r in csv.DictReader(f) if r["seed"] == "1"]
    expect(len(seed_1) == 1, "no row of seed 1 in the README's ensemble")
    if seed_1:
        peak = f"{float(seed_1[0]['peaks.top.fy']) / area / 1e6:.3g} MPa"
        print(f"seed 1: peak stress {peak}")
        expect(f"seed 1 peaks at {peak}" in readme, f"README.md does not quote seed 1's {peak}")
        expect(f"peaks at\n  {peak}" in status or f"peaks at {peak}" in status,
               f"docs/status.md does not quote seed 1's {peak}")


def readme_python(args, readme):
    snippets = blocks(readme, "python")
    expect(len(snippets) >= 1, "README.md has no Python snippet")
    for snippet in snippets:
        run = subprocess.run([args.python, "-c", snippet], cwd=args.source, capture_output=True,
                             text=True, env=dict(os.environ, PYTHONPATH=args.pythonpath))
        expect(run.returncode == 0, f"README.md's Python snippet failed:\n{run.stderr}")


def library(args):
    with open(os.path.join(args.source, "docs", "library.md"), encoding="utf-8") as f:
        page = f.read()
    scene = os.path.join(args.source, "data", "cantilever_model_1.toml")
    tip = subprocess.run([args.tip, scene], capture_output=True, text=True, check=True)
    line = tip.stdout.strip()
    quoted = re.findall(r"tip uy = -?[0-9][0-9.eE+-]*", page)
    expect(len(quoted) >= 2, f"docs/library.md quotes {len(quoted)} tip displacements")
    for q in quoted:
        expect(q == line, f"docs/library.md quotes '{q}', the examples print '{line}'")
    if not args.python:
        return
    example = subprocess.run(
        [args.python, os.path.join(args.source, "tests", "consumer", "example.py"), scene],
        capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=args.pythonpath))
    expect(example.returncode == 0, f"example.py failed:\n{example.stderr}")
    transcript = [b for b in blocks(page, "sh") if "$ python3 example.py" in b]
    expect(len(transcript) == 1, "docs/library.md has no transcript of example.py")
    if transcript:
        for out in (example.stdout + example.stderr).splitlines():
            expect(out in transcript[0].splitlines(),
                   f"docs/library.md's transcript of example.py lacks '{out}'")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--rockdd", required=True)
    p.add_argument("--tip", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--python", help="the Python the build's module is for (default: none)")
    p.add_argument("--pythonpath", default="", help="where the build's module is")
    args = p.parse_args()
    args.rockdd, args.work = os.path.abspath(args.rockdd), os.path.abspath(args.work)
    with open(os.path.join(args.source, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    library(args)
    if args.python:
        readme_python(args, readme)
    readme_ensemble(args, readme)
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", file=sys.stderr)
        return 1
    print("ok: README.md and docs/library.md quote what their commands print")
    return 0


if __name__ == "__main__":
    sys.exit(main())
