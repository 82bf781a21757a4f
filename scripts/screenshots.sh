#!/usr/bin/env bash
# Renders every sample scene with the ffdkit application (its --screenshot option: the window's
# 3D view, glyphs and lattices included) into docs/images/<scene>.png, as shown in the README,
# and the whole window on the hierarchy scene, its child lattice selected (transformer and
# properties shown), into docs/images/app-window.png, and the transformers of the default
# scene's widget and lattice into docs/images/transformer-*.png (docs/app.md).
# Runs under Xvfb when there is no display. Builds the application first unless
# FFDKIT_NO_BUILD=1.
#   scripts/screenshots.sh [scene-name ...]     (default: every folder of scenes/examples)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FFDKIT_BUILD_DIR:-$root/build}"
if [ "${FFDKIT_NO_BUILD:-0}" != 1 ]; then
  "$root/scripts/setup-deps.sh"
  "$root/scripts/build.sh" --target ffdkit
fi
app="$build/app/gui/ffdkit"
[ -x "$app" ] || { echo "screenshots.sh: no application at $app (set FFDKIT_BUILD_DIR)" >&2; exit 1; }

if [ "$#" -gt 0 ]; then
  scenes=("$@")
else
  scenes=()
  for dir in "$root"/scenes/examples/*/; do
    [ -f "$dir/scene.json" ] && scenes+=("$(basename "$dir")")
  done
fi

export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
# A fresh settings and data folder: the pictures do not depend on the user's saved window
# layout, and the runs add nothing to the user's recent files.
user_folders="$(mktemp -d)"
trap 'rm -rf "$user_folders"' EXIT
export XDG_CONFIG_HOME="$user_folders/config" XDG_DATA_HOME="$user_folders/data"
run=()
if [ -z "${DISPLAY:-}" ]; then
  export QT_QPA_PLATFORM=xcb
  run=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset")
fi

mkdir -p "$root/docs/images"
for name in "${scenes[@]}"; do
  "${run[@]}" "$app" "$root/scenes/examples/$name" --screenshot "$root/docs/images/$name.png"
done
if [ "$#" -eq 0 ]; then
  "${run[@]}" "$app" "$root/scenes/examples/hierarchy" --select child --window-screenshot "$root/docs/images/app-window.png"
  # The transformer manipulator of an affine widget and of a lattice (docs/app.md).
  "${run[@]}" "$app" "$root/scenes/examples/default" --select pull --screenshot "$root/docs/images/transformer-widget.png"
  "${run[@]}" "$app" "$root/scenes/examples/default" --select lattice --screenshot "$root/docs/images/transformer-lattice.png"
fi
