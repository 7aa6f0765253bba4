#!/bin/sh
# Checks `tools/plot fracture` and `tools/plot curve` on an existing run folder with frames.
#
#   tests/plot_fracture_check.sh RUNDIR COLUMN
#
# RUNDIR: a rockdd run folder with frames.pvd, frames/ and history.csv; COLUMN: a history.csv
# column to plot against time. Exits non-zero on the first failure.
set -u
if [ $# -ne 2 ]; then
  echo "usage: $0 RUNDIR COLUMN" >&2
  exit 64
fi
run=$1
col=$2
plot="$(dirname "$0")/../tools/plot"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# Each drawing must succeed and write a non-empty PNG.
draws() {
  png=$1
  shift
  "$plot" "$@" -o "$tmp/$png" >"$tmp/out" 2>&1 || { cat "$tmp/out" >&2; fail "plot $*"; }
  [ -s "$tmp/$png" ] || fail "plot $* wrote no $png"
}
draws last.png fracture "$run"
draws block.png fracture "$run" --color block --magnify 100
draws s1.png fracture "$run" --color s1
draws s3.png fracture "$run" --color s3 --step 0
draws stages.png fracture "$run" --color damage --time 0 1e9 --dpi 60
draws first.png fracture "$run" --step 0
draws time.png fracture "$run" --time 1e9
draws event.png fracture "$run" --event first_damage
draws curve.png curve "$run" --x time --y "$col" --y-scale -1e-3 --mark-peak
grep -q "^peak" "$tmp/out" || fail "curve --mark-peak printed no peak"

# Each input problem must be reported on stderr with exit status 2 and write nothing.
refused() {
  "$plot" "$@" -o "$tmp/bad.png" >/dev/null 2>"$tmp/err"
  rc=$?
  [ "$rc" -eq 2 ] || fail "plot $*: exit status $rc, expected 2"
  [ -s "$tmp/err" ] || fail "plot $*: nothing on stderr"
  [ ! -e "$tmp/bad.png" ] || fail "plot $*: wrote a PNG"
}
refused fracture "$tmp/no-such-run"
refused fracture "$run" --step 999999999
refused fracture "$run" --step 0 999999999
refused fracture "$run" --event no_such_event
refused curve "$run" --y no.such.column
refused curve "$tmp/no-such-run" --y "$col"
echo "plot fracture/curve: all checks passed"
