#!/usr/bin/env bash
# Builds and runs the libFuzzer harnesses of tests/fuzz for CTest (label fuzz).
#   run_fuzzers.sh build SOURCE_DIR FUZZ_BUILD_DIR
#       configures and builds FUZZ_BUILD_DIR with clang++-14 and -DROCKDD_FUZZ=ON
#   run_fuzzers.sh run SOURCE_DIR FUZZ_BUILD_DIR HARNESS SECONDS
#       runs HARNESS (scene_reader, overrides, msh, geo) for SECONDS on a fresh corpus seeded
#       from data/, tests/scenes/ and tests/meshes/; a finding fails with its input saved
#       in FUZZ_BUILD_DIR/findings/HARNESS/.
# Exits 77 (CTest's SKIP_RETURN_CODE) when clang or libFuzzer's runtime is missing: the GCC
# build and its tests do not need them. tools/setup installs both.
set -euo pipefail
skip=77
mode=$1 source_dir=$2 build_dir=$3

clang=${ROCKDD_FUZZ_CLANG:-clang-14}
clangxx=${ROCKDD_FUZZ_CLANGXX:-clang++-14}

need_toolchain() {
  if ! command -v "$clangxx" >/dev/null; then
    echo "fuzz: skipped, $clangxx not found (Debian package clang-14; tools/setup installs it)"
    exit $skip
  fi
  local runtime
  runtime=$("$clangxx" -print-file-name=libclang_rt.fuzzer-x86_64.a 2>/dev/null || true)
  if [ ! -f "$runtime" ]; then
    runtime=$(find "$("$clangxx" -print-resource-dir)" -name 'libclang_rt.fuzzer-x86_64.a' \
      2>/dev/null | head -n1)
  fi
  if [ -z "$runtime" ] || [ ! -f "$runtime" ]; then
    echo "fuzz: skipped, libFuzzer's runtime libclang_rt.fuzzer-x86_64.a not found" \
      "(Debian package libclang-rt-14-dev; tools/setup installs it)"
    exit $skip
  fi
}

# The seeds of one harness, copied into a fresh corpus folder (libFuzzer adds to it).
seed_corpus() {
  local harness=$1 corpus=$2
  rm -rf "$corpus"
  mkdir -p "$corpus"
  case $harness in
    scene_reader)
      cp "$source_dir"/data/*.toml "$source_dir"/tests/scenes/good/*.toml \
        "$source_dir"/tests/scenes/bad/*.toml "$corpus"/
      ;;
    overrides) cp "$source_dir"/tests/fuzz/seeds/overrides/* "$corpus"/ ;;
    msh) cp "$source_dir"/tests/meshes/*.msh "$corpus"/ ;;
    geo)
      # Not size_field_inside.geo: its every mutant runs to the meshing time limit (3 s), and
      # the limits are tested in tests/test_mesh.cpp.
      cp "$source_dir"/data/*.geo "$source_dir"/data/verification/*.geo "$corpus"/
      find "$source_dir"/tests/meshes -name '*.geo' ! -name size_field_inside.geo \
        -exec cp {} "$corpus"/ \;
      ;;
    *)
      echo "fuzz: unknown harness $harness" >&2
      exit 2
      ;;
  esac
}

case $mode in
  build)
    need_toolchain
    jobs=$(nproc 2>/dev/null || echo 2)
    mkdir -p "$build_dir"
    # A unity build parses the heavy headers once per batch of sources: 89 s of CPU against
    # 130 s on 2 cores (70 s against 76 s of wall time alone, more beside other tests).
    CC=$clang CXX=$clangxx cmake -S "$source_dir" -B "$build_dir" -DROCKDD_FUZZ=ON \
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_UNITY_BUILD=ON >"$build_dir/configure.log" 2>&1 ||
      {
        cat "$build_dir/configure.log"
        exit 1
      }
    cmake --build "$build_dir" -j"$jobs"
    ;;
  run)
    harness=$4 seconds=$5
    need_toolchain
    program=$build_dir/bin/fuzz_$harness
    if [ ! -x "$program" ]; then
      echo "fuzz: $program was not built (the Fuzz.Build test makes it)" >&2
      exit 1
    fi
    work=$build_dir/runs/$harness
    findings=$build_dir/findings/$harness
    mkdir -p "$work" "$findings"
    seed_corpus "$harness" "$work/corpus"
    # CTest's runs are reproducible: a fixed seed and a fixed number of inputs, with the time
    # as a cap only, so CI fails on an engine change, not on the luck of a random seed (a
    # random 20 s once found a Gmsh crash that later runs did not). ROCKDD_FUZZ_SEED=0 asks
    # libFuzzer for a random seed and ROCKDD_FUZZ_RUNS=-1 for no limit: exploring, by hand.
    options=(-seed="${ROCKDD_FUZZ_SEED:-1}" -runs="${ROCKDD_FUZZ_RUNS:-3000}"
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=16384
      -artifact_prefix="$findings/" -print_final_stats=1)
    if [ "$harness" = msh ]; then
      # Gmsh leaks on nearly every malformed file (lsan.supp), so libFuzzer would stop the
      # world for a leak scan after each input: 18 inputs/s instead of about 1,000. The
      # engine's mesh code holds memory only in containers.
      options+=(-detect_leaks=0)
    elif [ "$harness" = geo ]; then
      # Gmsh runs in a meshing process per input, and its limits (3 s, 1 GB: fuzz_geo.cpp)
      # are what is fuzzed; -timeout stays above them. Leaks: as for msh.
      options+=(-detect_leaks=0 -dict="$source_dir/tests/fuzz/geo.dict")
    else
      options+=(-dict="$source_dir/tests/fuzz/scene.dict")
    fi
    export LSAN_OPTIONS="suppressions=$source_dir/tests/fuzz/lsan.supp:print_suppressions=0"
    cd "$work"
    if ! "$program" "${options[@]}" corpus; then
      echo "fuzz: $harness found an input the engine does not refuse cleanly; it is in" \
        "$findings/. Reproduce with: $program <file>. Fix the engine, then add the input as a" \
        "named regression case (docs/stability.md, Fuzzing)." >&2
      exit 1
    fi
    ;;
  *)
    echo "usage: $0 build|run SOURCE_DIR FUZZ_BUILD_DIR [HARNESS SECONDS]" >&2
    exit 2
    ;;
esac
