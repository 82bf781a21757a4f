#!/usr/bin/env bash
# Rewrites the sample scenes in scenes/examples/ from scenes/examples/make_examples.cpp.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh" --target ffdkit-make-examples >/dev/null
"${FFDKIT_BUILD_DIR:-$root/build}/scenes/ffdkit-make-examples" "$root/scenes/examples"
