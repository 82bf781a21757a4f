#!/usr/bin/env bash
# The committed sample scenes are exactly what make_examples.cpp writes.
#   check_examples.sh MAKER SOURCE_EXAMPLES_DIR
set -euo pipefail
maker="$1"
committed="$2"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$maker" "$out" >/dev/null
status=0
for scene in "$out"/*/scene.json; do
  name="$(basename "$(dirname "$scene")")"
  if ! cmp -s "$scene" "$committed/$name/scene.json"; then
    echo "scenes/examples/$name/scene.json differs from what make_examples.cpp writes (run scripts/update-examples.sh):"
    diff -u "$committed/$name/scene.json" "$scene" | head -20 || true
    status=1
  fi
done
echo "checked $(ls "$out" | wc -l) sample scenes"
exit $status
