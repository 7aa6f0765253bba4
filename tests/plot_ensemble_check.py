#!/usr/bin/python3
"""tools/plot ensemble on a 4-realization ensemble: its PNGs, and with --html a page whose
images all resolve.

    plot_ensemble_check.py --rockdd BUILD/bin/rockdd --source SOURCE --work DIR

Runs `rockdd mc` on data/uniaxial_compression.toml at 10 x 20 cells (seeds 1-4, about a
second), then `tools/plot ensemble MCDIR --html`. Checks: the three figures are PNG files;
report.html names at least six images (the three figures and the weakest, median and
strongest crack patterns) and every one is a PNG file beside it; the page quotes the command,
the commit, the overrides, mc.json's Weibull modulus and each seed of the three crack
patterns, which are the seeds with the lowest, median and highest peak in mc.csv. Then once
more with --no-last-frame: no crack pattern, and the page says why. Exit 0 when every check
holds, 1 otherwise.
"""

import argparse
import csv
import html.parser
import json
import os
import shutil
import subprocess
import sys

FAILURES = []


def expect(condition, message):
    if not condition:
        FAILURES.append(message)
        print(f"FAIL: {message}", file=sys.stderr)


class Images(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.sources = []

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.sources.append(dict(attrs).get("src"))


def is_png(path):
    try:
        with open(path, "rb") as f:
            return f.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 1000
    except OSError:
        return False


def ensemble(args, work, *extra):
    shutil.rmtree(work, ignore_errors=True)
    command = [args.rockdd, "mc", os.path.join(args.source, "data", "uniaxial_compression.toml"),
               "--realizations", "4", "--jobs", "2", "--threads", "2", "--quiet",
               "--set", "mesh.divisions=[10, 20]", "--out", work, *extra]
    subprocess.run(command, check=True)
    mcdir = os.path.join(work, "uniaxial-compression")
    plot = subprocess.run([os.path.join(args.source, "tools", "plot"), "ensemble", mcdir,
                           "--html"], capture_output=True, text=True)
    print(plot.stdout, end="")
    expect(plot.returncode == 0, f"tools/plot ensemble exited {plot.returncode}: {plot.stderr}")
    return mcdir


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--rockdd", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    args = p.parse_args()

    mcdir = ensemble(args, os.path.join(args.work, "kept"))
    for name in ("ensemble_peaks.png", "ensemble_weibull.png", "ensemble_curves.png"):
        expect(is_png(os.path.join(mcdir, "figures", name)), f"no figure {name}")
    page = os.path.join(mcdir, "report.html")
    expect(os.path.isfile(page), "no report.html")
    if not os.path.isfile(page):
        return 1
    with open(page, encoding="utf-8") as f:
        text = f.read()
    images = Images()
    images.feed(text)
    expect(len(images.sources) >= 6, f"the page names {len(images.sources)} images, not 6")
    for source in images.sources:
        expect(source and not source.startswith(("/", "http:", "https:", "file:")),
               f"image '{source}' is not relative to the page")
        expect(source and is_png(os.path.join(mcdir, source)), f"image '{source}' is missing")
    with open(os.path.join(mcdir, "mc.json")) as f:
        report = json.load(f)
    with open(os.path.join(mcdir, "mc.provenance.json")) as f:
        provenance = json.load(f)
    shape = report["statistics"]["peaks.top.fy"]["weibull"]["shape"]
    expect(f"{shape:.4g}" in text, f"the page does not quote the Weibull modulus {shape:.4g}")
    expect(provenance["runs"][-1]["commit"] in text, "the page does not name the commit")
    expect("mesh.divisions=[10, 20]" in text, "the page does not name the overrides")
    expect("--realizations 4" in text, "the page does not quote the command")
    with open(os.path.join(mcdir, "mc.csv"), newline="") as f:
        rows = sorted(csv.DictReader(f), key=lambda r: float(r["peaks.top.fy"]))
    for label, row in (("weakest", rows[0]), ("median", rows[1]), ("strongest", rows[-1])):
        png = f"figures/crack_{label}_seed_{row['seed']}.png"
        expect(png in images.sources, f"the {label} crack pattern is not {png}")

    bare = ensemble(args, os.path.join(args.work, "no_frames"), "--no-last-frame")
    with open(os.path.join(bare, "report.html"), encoding="utf-8") as f:
        text = f.read()
    images = Images()
    images.feed(text)
    expect(not any("crack_" in s for s in images.sources), "crack patterns without frames")
    expect("--no-last-frame" in text, "the page does not say why there is no crack pattern")
    expect(len(images.sources) == 3, f"{len(images.sources)} images without frames, not 3")
    for source in images.sources:
        expect(is_png(os.path.join(bare, source)), f"image '{source}' is missing")

    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", file=sys.stderr)
        return 1
    print("ok: the figures, and a page whose images all resolve")
    return 0


if __name__ == "__main__":
    sys.exit(main())
