#!/usr/bin/env bash
# Regenerates docs/images/lod-drag-{1,2,3,released}.png (docs/app.md, "Large meshes"): a widget
# dragged on a 1M-vertex sphere in the application window under Xvfb (real mouse events,
# tests/app/playback_timing), the view saved three times during the drag (the level-of-detail
# proxy) and after the release (the full mesh, exact).
#   scripts/lod-drag-frames.sh [FOLDER]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FFDKIT_BUILD_DIR:-$root/build}"
out="$(realpath -m "${1:-$root/docs/images}")"
"$root/scripts/build.sh" --target playback_timing
mkdir -p "$out"
export QT_QPA_PLATFORM=xcb OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
xvfb-run -a -s "-screen 0 1280x1024x24" "$build/tests/app/playback_timing" drag 1414 4 --frames "$out" 2>&1 |
  grep -v XDG_RUNTIME_DIR
echo "lod-drag-frames: $out/lod-drag-{1,2,3,released}.png"
