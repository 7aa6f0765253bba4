#!/usr/bin/env bash
# rockdd under AddressSanitizer and UndefinedBehaviorSanitizer, for CTest (label sanitize;
# issue 28): every input a user can hand the command line, run by a build whose every object
# is instrumented, so that a memory error or undefined behaviour on any of them fails CI.
#   run_sanitized.sh build SOURCE_DIR BUILD_DIR
#       configures BUILD_DIR (RelWithDebInfo, -DROCKDD_SANITIZE=ON: the engine, the Gmsh
#       module and rockdd only, MPI on when found) and builds rockdd
#   run_sanitized.sh scenes SOURCE_DIR BUILD_DIR
#       `rockdd check` and a two-step `rockdd run` of every scene of data/ and data/verification/,
#       and a two-realization `rockdd mc`: each must exit 0
#   run_sanitized.sh bad-input SOURCE_DIR BUILD_DIR
#       `rockdd check` of every scene of tests/scenes/bad/ (exit 2), of a scene on every mesh of
#       tests/meshes/ (exit 0 or 2) and `rockdd mc` on a mesh Gmsh's reader crashed on (exit 2)
# Any sanitizer report, or another exit status, fails the test with the command and its output.
set -euo pipefail
mode=$1 source_dir=$2 build_dir=$3
rockdd=$build_dir/bin/rockdd

# The meshing limits kept near what these inputs need (the largest mesh of data/ has 18,534
# triangles): the defaults allow the largest mesh the memory available allows a run, which
# tests/meshes/size_field_inside.geo would take many minutes to reach.
export ROCKDD_MESHING_SECONDS=30 ROCKDD_MESHING_BYTES=1e9
# A finding ends the process with status 86, which no rockdd exit means; leaks are reported.
export ASAN_OPTIONS=exitcode=86:detect_leaks=1:abort_on_error=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:exitcode=86

failures=0
# expect "STATUSES" COMMAND...: runs COMMAND; a status outside STATUSES (space-separated) or a
# sanitizer report in its output is a failure.
expect() {
  local statuses=$1 output status
  shift
  set +e
  output=$("$@" 2>&1)
  status=$?
  set -e
  if [[ " $statuses " != *" $status "* ]] ||
    grep -qE 'ERROR: (Address|Leak)Sanitizer|runtime error:' <<<"$output"; then
    echo "sanitize: FAILED (exit $status, expected $statuses): $*"
    echo "$output" | tail -n 60
    failures=$((failures + 1))
  fi
}

# --set options that end SCENE after two steps: time.steps, or time.end at twice time.dt.
two_steps() {
  python3 - "$1" <<'EOF'
import sys, tomllib
with open(sys.argv[1], "rb") as f:
    time = tomllib.load(f).get("time", {})
if "steps" in time:
    print("--set time.steps=2")
elif "end" in time:
    print(f"--set time.end={2 * time['dt']!r}")
EOF
}

case $mode in
  build)
    jobs=$(nproc 2>/dev/null || echo 2)
    mkdir -p "$build_dir"
    # RelWithDebInfo at -O1 -g1 (line tables: reports still name file and line): half the
    # compile time of its -O2 -g (engine/simulation.cpp: 21 s against 43 s). A unity build
    # parses the heavy headers (Eigen, oneTBB, toml++) once per batch of sources instead of
    # once per source: 188 s against 269 s on 2 cores (291 against 477 s of CPU), with every
    # scene as clean under it.
    cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROCKDD_SANITIZE=ON \
      -DCMAKE_UNITY_BUILD=ON \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
      >"$build_dir/configure.log" 2>&1 || {
      cat "$build_dir/configure.log"
      exit 1
    }
    cmake --build "$build_dir" -j"$jobs" --target rockdd
    ;;
  scenes | bad-input)
    if [ ! -x "$rockdd" ]; then
      echo "sanitize: $rockdd was not built (the Sanitize.Build test makes it)" >&2
      exit 1
    fi
    work=$build_dir/runs/$mode
    rm -rf "$work"
    mkdir -p "$work"
    cd "$work"
    # A cache of its own: the check meshes and stores, the run reads it back (both paths).
    export ROCKDD_MESH_CACHE=$work/mesh-cache
    ;;&
  scenes)
    for scene in "$source_dir"/data/*.toml "$source_dir"/data/verification/*.toml; do
      expect 0 "$rockdd" check "$scene"
      # shellcheck disable=SC2046 # two_steps prints words to split
      # Exit 1 is a run that failed numerically (brazilian_disk_failure at its full load).
      expect "0 1" "$rockdd" run "$scene" --out out --quiet $(two_steps "$scene")
    done
    expect 0 "$rockdd" mc "$source_dir/data/uniaxial_compression.toml" --realizations 2 \
      --out mc --quiet --set 'mesh.divisions=[15, 30]' --set time.end=0.0125
    ;;
  bad-input)
    for scene in "$source_dir"/tests/scenes/bad/*.toml; do
      expect 2 "$rockdd" check "$scene"
    done
    for mesh in "$source_dir"/tests/meshes/*.msh "$source_dir"/tests/meshes/*.geo; do
      kind=${mesh##*.}
      name=$(basename "$mesh")
      printf '[scene]\nname = "mesh"\n[mesh]\n%s = "%s"\n[[material]]\ndensity = 2000.0\n%s\n' \
        "$kind" "$mesh" 'young = 1e9
poisson = 0.2
[[boundary]]
on = "*"
fix = ["x", "y"]' >"$name.toml"
      expect "0 2" "$rockdd" check "$name.toml"
    done
    printf '[scene]\nname = "mc-bad-mesh"\n[mesh]\nmsh = "%s"\n%s\n' \
      "$source_dir/tests/meshes/msh4_node_count_short.msh" '[[material]]
density = 2000.0
young = 1e9
poisson = 0.2
tensile_strength = 1e6
homogeneity = 1.5
heterogeneous = ["young"]
seed = 1' >mc_bad_mesh.toml
    expect 2 "$rockdd" mc mc_bad_mesh.toml --realizations 2 --out mc
    ;;
  *)
    echo "usage: $0 build|scenes|bad-input SOURCE_DIR BUILD_DIR" >&2
    exit 2
    ;;
esac
if [ "$mode" != build ]; then
  if ((failures > 0)); then
    echo "sanitize: $failures command(s) failed under ASan/UBSan (above)" >&2
    exit 1
  fi
  echo "sanitize: $mode clean under ASan and UBSan"
fi
