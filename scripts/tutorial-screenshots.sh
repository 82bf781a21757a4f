#!/usr/bin/env bash
# Regenerates the pictures of docs/tutorials/fig6-2-in-the-app.md: builds the screenshot
# program (tests/app/tutorial_screenshots.cpp) and runs it under Xvfb, which drives the real
# window with real mouse and key events and writes one PNG per step into
# docs/tutorials/images/ (or the folder given).
#   scripts/tutorial-screenshots.sh [FOLDER]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FFDKIT_BUILD_DIR:-$root/build}"
out="$(realpath -m "${1:-$root/docs/tutorials/images}")"
"$root/scripts/build.sh" --target tutorial_screenshots
mkdir -p "$out"
export QT_QPA_PLATFORM=xcb OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
FFDKIT_TUTORIAL_IMAGES="$out" xvfb-run -a -s "-screen 0 1280x1024x24" "$build/tests/app/tutorial_screenshots"
echo "tutorial-screenshots: $(ls "$out"/*.png | wc -l) pictures in $out"
