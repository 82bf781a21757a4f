#!/usr/bin/env bash
# Regenerates docs/images/fold-tint.png (docs/app.md, "Fold-over tint"): builds the GUI test
# tests/app/edit_guards_gui_test.cpp and runs its fold-tint case under Xvfb, which pushes a
# lattice point through its neighbour with real mouse and key events and saves the window.
#   scripts/fold-tint-screenshot.sh [FOLDER]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FFDKIT_BUILD_DIR:-$root/build}"
out="$(realpath -m "${1:-$root/docs/images}")"
"$root/scripts/build.sh" --target edit_guards_gui_test
mkdir -p "$out"
export QT_QPA_PLATFORM=xcb OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
FFDKIT_SCREENSHOT_DIR="$out" xvfb-run -a -s "-screen 0 1280x1024x24" \
  "$build/tests/app/edit_guards_gui_test" pushingAPointThroughItsNeighbourTintsTheCellRed
echo "fold-tint-screenshot: $out/fold-tint.png"
