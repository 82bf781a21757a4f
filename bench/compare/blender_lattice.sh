#!/usr/bin/env bash
# Times Blender's lattice modifier and ffdkit's Deformer on the same job (1,000,000 uniform
# random points in the unit box, a 4x4x4 cubic B-spline lattice with every point moved) and
# prints the ratio ffdkit / Blender, wall and CPU time (medians), for ffdkit in double precision
# (its default) and in single precision (Precision::Single, float32 displacements, the precision
# Blender computes in). ROUNDS rounds alternate Blender and ffdkit (each the median of
# REPETITIONS), so that a changing load on a shared machine hits both alike; the ratio is that of
# the medians over the rounds, printed with the load average.
#   bench/compare/blender_lattice.sh [BUILD_DIR] [REPETITIONS] [ROUNDS]
# Installs Debian's blender first when it is missing (scripts/setup-blender.sh): the default
# scripts/setup-deps.sh never does. Needs bench_ffd built (scripts/build.sh --target bench_ffd).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build}"
reps="${2:-5}"
rounds="${3:-1}"
bench="$build/bench/ffd/bench_ffd"
if [ ! -x "$bench" ]; then
  echo "blender_lattice.sh: $bench not found; build it with scripts/build.sh --target bench_ffd" >&2
  exit 1
fi
command -v blender >/dev/null 2>&1 || "$root/scripts/setup-blender.sh"

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
bw=() bc=() fw=() fc=() sw=() sc=() loads=()
# The median line of one BM_Deform benchmark: csv name,iterations,real_time,cpu_time,time_unit,...
ffdkit_median() {
  OMP_WAIT_POLICY=passive "$bench" --benchmark_filter="^BM_Deform/points:1000000/lattice:4x4x4/basis:bspline3/$1" \
    --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true --benchmark_format=csv 2>/dev/null |
    grep '_median"' | head -1
}
for round in $(seq 1 "$rounds"); do
  loads+=("$(cut -d' ' -f1 /proc/loadavg)")
  blender_line="$(blender -b --factory-startup --python "$root/bench/compare/blender_lattice.py" -- 1000000 "$reps" 2>&1 |
    grep '^blender_lattice_ms' || true)"
  if [ -z "$blender_line" ]; then
    echo "blender_lattice.sh: Blender did not report a time; run bench/compare/blender_lattice.py by hand to see why" >&2
    exit 1
  fi
  read -r _ blender_wall blender_cpu <<<"$blender_line"
  ffdkit_line="$(ffdkit_median 'process_time')"
  single_line="$(ffdkit_median 'precision:single/')"
  bw+=("$blender_wall") bc+=("$blender_cpu")
  fw+=("$(echo "$ffdkit_line" | cut -d, -f3)") fc+=("$(echo "$ffdkit_line" | cut -d, -f4)")
  sw+=("$(echo "$single_line" | cut -d, -f3)") sc+=("$(echo "$single_line" | cut -d, -f4)")
  [ "$rounds" -gt 1 ] && echo "round $round (load ${loads[-1]}): Blender ${bw[-1]} / ${bc[-1]} ms," \
    "ffdkit ${fw[-1]} / ${fc[-1]} ms, single ${sw[-1]} / ${sc[-1]} ms (wall / CPU)"
done
blender_wall="$(printf '%s\n' "${bw[@]}" | median)" blender_cpu="$(printf '%s\n' "${bc[@]}" | median)"
ffdkit_wall="$(printf '%s\n' "${fw[@]}" | median)" ffdkit_cpu="$(printf '%s\n' "${fc[@]}" | median)"
single_wall="$(printf '%s\n' "${sw[@]}" | median)" single_cpu="$(printf '%s\n' "${sc[@]}" | median)"

echo "1,000,000 points, 4x4x4 cubic B-spline lattice (medians of $reps, then over $rounds round(s); load average ${loads[*]})"
printf '%-28s %10s %10s\n' "" "wall ms" "CPU ms"
printf '%-28s %10.2f %10.2f\n' "Blender lattice modifier" "$blender_wall" "$blender_cpu"
printf '%-28s %10.2f %10.2f\n' "ffdkit Deformer::deform" "$ffdkit_wall" "$ffdkit_cpu"
printf '%-28s %10.2f %10.2f\n' "  the same, single precision" "$single_wall" "$single_cpu"
awk -v fw="$ffdkit_wall" -v bw="$blender_wall" -v fc="$ffdkit_cpu" -v bc="$blender_cpu" \
  'BEGIN { printf "ratio ffdkit / Blender: %.3f (wall), %.3f (CPU)\n", fw / bw, fc / bc }'
awk -v fw="$single_wall" -v bw="$blender_wall" -v fc="$single_cpu" -v bc="$blender_cpu" \
  'BEGIN { printf "ratio ffdkit single / Blender: %.3f (wall), %.3f (CPU)\n", fw / bw, fc / bc }'
