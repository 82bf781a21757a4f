#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (unit, render and GUI tests) through
# CTest under Xvfb. Prints CTest's summary; exits non-zero on any failure.
#   scripts/test.sh [extra ctest arguments, e.g. -L core]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup-deps.sh"
"$root/scripts/build.sh"
build="${FFDKIT_BUILD_DIR:-$root/build}"
jobs="${FFDKIT_JOBS:-$(nproc)}"

# GUI and render tests need a display: run the whole suite inside one Xvfb server (Mesa's
# software GL). XDG_RUNTIME_DIR keeps Qt from warning on every start.
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
export QT_QPA_PLATFORM=xcb
# OpenMP threads that spin while idle would starve the other tests running beside them.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
xvfb-run -a -s "-screen 0 1280x1024x24" \
  ctest --test-dir "$build" --output-on-failure --parallel "$jobs" --timeout 600 "$@"
