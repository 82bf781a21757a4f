#!/usr/bin/env bash
# Builds the C++ API reference (Doxygen over the public headers) into build/docs/html.
#   scripts/docs.sh [OUTPUT_DIR]      default: build/docs
#   scripts/docs.sh --check [DIR]     also fails (exit 1) on any Doxygen warning, listing them
# Needs Debian's doxygen (scripts/setup-deps.sh installs it).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
out="$(realpath -m "${1:-$repo/build/docs}")"

if ! command -v doxygen >/dev/null; then
  echo "docs.sh: doxygen is not installed (scripts/setup-deps.sh installs it)" >&2
  exit 1
fi
version="$(sed -n 's/^project(ffdkit VERSION \([0-9.]*\).*/\1/p' "$repo/CMakeLists.txt")"
mkdir -p "$out"
warnings="$out/doxygen-warnings.txt"
sed -e "s#@SOURCE_DIR@#$repo#g" -e "s#@OUTPUT_DIR@#$out#g" -e "s#@FFDKIT_VERSION@#$version#g" \
    -e "s#@WARN_LOGFILE@#$warnings#g" -e "s#@WARN_AS_ERROR@#NO#g" \
    "$repo/docs/Doxyfile.in" >"$out/Doxyfile"
rm -f "$warnings"
doxygen "$out/Doxyfile"
count=0
if [ -s "$warnings" ]; then count="$(grep -c '' "$warnings")"; fi
echo "docs.sh: $out/html/index.html ($count warning lines in $warnings)"
if [ "$check" = 1 ] && [ "$count" != 0 ]; then
  cat "$warnings" >&2
  echo "docs.sh: the public headers' documentation has $count Doxygen warning lines (above)" >&2
  exit 1
fi
