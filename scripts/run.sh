#!/usr/bin/env bash
# The main job: installs what is missing, builds (Release) and opens the default scene in the
# ffdkit application. With no display it runs the same under Xvfb and saves a screenshot.
#   scripts/run.sh [scene-file-or-folder]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup-deps.sh"
"$root/scripts/build.sh" --target ffdkit
build="${FFDKIT_BUILD_DIR:-$root/build}"
scene="${1:-$root/scenes/examples/default}"

if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec "$build/app/gui/ffdkit" "$scene"
fi

mkdir -p "$root/out"
shot="$root/out/default-scene.png"
echo "run.sh: no display; running under Xvfb and saving a screenshot"
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" "$build/app/gui/ffdkit" "$scene" --screenshot "$shot"
echo "run.sh: screenshot of $scene saved to $shot"
