#!/usr/bin/env bash
# What a user sees of a large mesh in the application window under Mesa's software GL (Xvfb):
# drags of a widget on a 1M- and a 10M-vertex sphere and playback of a keyed 1M-vertex sphere, with
# the level of detail off (every frame the full mesh) and on (View > Simplify While Moving, the
# default). Each run prints its frames per second, the median and worst frame time, each frame's
# stages (wall-clock and CPU ms) and the time from the release to the displayed exact mesh, and
# writes its per-frame trace (when each frame was displayed, its frame time, its stages and its CPU
# time, in ms: bench/app/window-timing/README.md) to $FFDKIT_TIMING_DIR (default build/window-timing/).
#   scripts/window-timing.sh [drag-seconds] [runs]     needs build/tests/app/playback_timing
# With runs > 1 each measurement is made that many times (traces NAME-RUN.txt), one round of all of
# them after the other, for medians.
# Timings on a shared machine are noisy: compare runs made one after the other.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FFDKIT_BUILD_DIR:-$root/build}"
out="${FFDKIT_TIMING_DIR:-$build/window-timing}"
seconds="${1:-5}"
runs="${2:-1}"
mkdir -p "$out"
export OMP_WAIT_POLICY=passive QT_QPA_PLATFORM=xcb
run() {  # name, then playback_timing's arguments
  local name="$1"
  shift
  echo "== $name: playback_timing $*"
  xvfb-run -a -s "-screen 0 1280x1024x24" "$build/tests/app/playback_timing" "$@" --trace "$out/$name.txt" 2>&1 |
    grep -v "XDG_RUNTIME_DIR"
}
for ((r = 1; r <= runs; ++r)); do
  suffix=""
  [ "$runs" -gt 1 ] && suffix="-$r"
  for lod in off on; do
    run "drag-1M-lod-$lod$suffix" drag 1414 "$seconds" --lod "$lod"
    run "play-1M-lod-$lod$suffix" play 1414 "$seconds" --lod "$lod"
    run "drag-10M-lod-$lod$suffix" drag 4472 "$seconds" --lod "$lod"
  done
done
echo "traces in $out"
