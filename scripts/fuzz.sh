#!/usr/bin/env bash
# Builds the fuzz targets of tests/fuzz with clang + libFuzzer (ASan + UBSan) into build-fuzz/
# and runs each for SECONDS (default 60), starting from its seed corpus. New inputs go to
# out/fuzz/<target>/corpus, crashes to out/fuzz/<target>/ (copy each into
# tests/fuzz/regressions/<target>/ once fixed: the corpus tests then run it on every CI run).
#   scripts/fuzz.sh [SECONDS] [TARGET...]      e.g. scripts/fuzz.sh 1800 fuzz_mesh_ply
# FFDKIT_FUZZ_RUNS=N also stops a target after N executions (whichever comes first), e.g.
# FFDKIT_FUZZ_RUNS=10000000 FFDKIT_JOBS=1 scripts/fuzz.sh 3600 fuzz_scene_file.
# FFDKIT_FUZZ_SKIP_BUILD=1 runs the targets as built (while build-fuzz/ builds other targets).
# Prints executions, wall and CPU seconds per target; exits 1 if any target found a crash.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
build="${FFDKIT_FUZZ_BUILD_DIR:-$root/build-fuzz}"
jobs="${FFDKIT_JOBS:-$(nproc)}"
"$root/scripts/setup-deps.sh" --fuzz

all=(fuzz_mesh_ply fuzz_mesh_obj fuzz_mesh_stl fuzz_mesh_xyz fuzz_mesh_npy fuzz_mesh_gltf fuzz_mesh_glb fuzz_mesh_roundtrip
     fuzz_mesh_vtp fuzz_mesh_vtk fuzz_openfoam fuzz_gmsh fuzz_su2 fuzz_unv fuzz_elmer fuzz_lsdyna fuzz_kratos fuzz_cgns
     fuzz_widget_file fuzz_scene_file fuzz_generator)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=("${all[@]}"); fi

if [ -z "${FFDKIT_FUZZ_SKIP_BUILD:-}" ]; then
  if [ ! -f "$build/CMakeCache.txt" ]; then
    generator=()
    if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
    CC=clang CXX=clang++ cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DFFDKIT_FUZZ=ON -DFFDKIT_BUILD_APP=OFF -DFFDKIT_BUILD_BENCH=OFF
  fi
  build_args=()
  for t in "${targets[@]}"; do build_args+=(--target "$t"); done
  cmake --build "$build" --parallel "$jobs" "${build_args[@]}"
fi

# allocator_may_return_null: an absurd allocation inside VTK's XML reader (the size a binary
# block's header announces) fails as in a release build (bad_alloc, reported as an error);
# the VTK objects that exception strands are not reported as leaks (detect_leaks=0).
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=0:allocator_may_return_null=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
runs_limit=()
if [ -n "${FFDKIT_FUZZ_RUNS:-}" ]; then runs_limit=(-runs="$FFDKIT_FUZZ_RUNS"); fi
found=0
printf '%-20s %12s %8s %8s %8s %s\n' target executions seconds cpu-s exec/s result
for t in "${targets[@]}"; do
  out="$root/out/fuzz/$t"
  mkdir -p "$out/corpus"
  log="$out/fuzz.log"
  status=0
  # -rss_limit_mb / -malloc_limit_mb: allocating what a file merely announces is a finding (every
  # reader checks a count against the bytes there, and charges its read budget, first).
  malloc_limit=1024
  # Inputs up to 64 KiB; the scene target's up to 16 KiB (every sample scene fits): parsing 64 KiB
  # of JSON under ASan and coverage costs more than reading and animating a small scene. Its
  # mutator makes inputs of at most 4 KiB (JSON_MAX_SIZE in tests/fuzz/CMakeLists.txt) and cuts
  # longer ones to fit, so a corpus of longer inputs still loads whole (-max_len would truncate
  # them to JSON that no longer parses).
  max_len=65536
  extra=()
  target_asan="$ASAN_OPTIONS"
  if [ "$t" = fuzz_scene_file ]; then
    max_len=16384
    # Its coverage features made libFuzzer's entropic scheduling a quarter of the time and ASan's
    # allocation stacks another tenth (perf), so both are off for it. With third-party headers
    # out of coverage too (tests/fuzz/coverage_ignorelist.txt, every target), replaying its corpus
    # of 8,306 inputs runs over 1,000 inputs per CPU second (docs/robustness.md measures it and
    # says where the rest goes). A crash it finds is replayed with the full options.
    extra=(-entropic=0)
    target_asan="$ASAN_OPTIONS:malloc_context_size=0"
  fi
  # -timeout: a unit running 60 s (wall) is a hang. ASan + coverage run a QI fit ~100x slower
  # than a release build (30 ms -> 3 s of CPU), so a shorter limit flags fits that are not hangs.
  # The CPU seconds are printed too: when other work shares the cores, the wall time overstates
  # the work done.
  TIMEFORMAT='%R %U %S'
  { time env ASAN_OPTIONS="$target_asan" "$build/tests/fuzz/$t" "$out/corpus" "$root/tests/fuzz/corpus/$t" -max_total_time="$seconds" "${runs_limit[@]}" "${extra[@]}" \
    -rss_limit_mb=2048 -malloc_limit_mb=$malloc_limit -timeout=60 -max_len=$max_len -print_final_stats=1 \
    -artifact_prefix="$out/" >"$log" 2>&1 || status=$?; } 2>"$out/cpu-time"
  time=$(awk '{printf "%.0f", $1}' "$out/cpu-time")
  cpu=$(awk '{printf "%.0f", $2 + $3}' "$out/cpu-time")
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  rate=$(awk -v r="$runs" -v t="$time" 'BEGIN { if (r ~ /^[0-9]+$/ && t > 0) printf "%.0f", r / t; else print "?" }')
  result=ok
  if [ "$status" -ne 0 ]; then result="CRASH (see $log)"; found=1; fi
  printf '%-20s %12s %8s %8s %8s %s\n' "$t" "$runs" "$time" "$cpu" "$rate" "$result"
done
exit $found
