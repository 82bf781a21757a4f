#!/bin/bash
# One bad OpenFOAM case given to ffdkit-cli deform (docs/volume-meshes.md): a copy of the committed
# cube (tests/data/openfoam/cube) spoilt one way. Each must fail with exit 1 and a message naming
# the file (and the line or the item), and write nothing: no output folder, no hidden temporary.
# usage: openfoam_bad_input_test.sh FFDKIT_CLI SOURCE_DIR KIND
#   KIND: lying-header | truncated-points | face-out-of-range | missing-owner | gzip-bomb | symlink-outside
set -u
cli=$1
data=$2/tests/data/openfoam
kind=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/ffdkit-openfoam-bad-XXXXXX")
trap 'rm -rf "$work"' EXIT
case=$work/case
cp -r "$data/cube" "$case"
mesh=$case/constant/polyMesh
extra=()

case $kind in
  lying-header)  # the header says binary; the list is ASCII text
    sed -i 's/format      ascii;/format      binary;/' "$mesh/points"
    grep -q "format      binary;" "$mesh/points" || { echo "FAIL: the test could not spoil the header"; exit 1; }
    expected="$mesh/points:20: point: expected ')' right after the 343 binary items, got '33' (the list size is wrong, or the list is not binary as the header's 'format binary' says)"
    ;;
  truncated-points)  # cut in the middle of point 200
    head -n 220 "$mesh/points" > "$work/p" && printf '(0.5 0.' >> "$work/p" && mv "$work/p" "$mesh/points"
    expected="$mesh/points:221: point 200: "
    ;;
  face-out-of-range)  # face 0 names point 343 of 343
    sed -i 's/^4(1 8 57 50)$/4(1 8 343 50)/' "$mesh/faces"
    expected="$mesh/faces:21: face 0: 343 is outside 0..342"
    ;;
  missing-owner)
    rm "$mesh/owner"
    expected="$mesh: no 'owner' file (nor owner.gz)"
    ;;
  gzip-bomb)  # 256 MiB of zeros in 256 KiB; --max-memory 64M refuses them while inflating
    head -c 268435456 /dev/zero | gzip -1 > "$mesh/points.gz"
    rm "$mesh/points"
    extra=(--max-memory 64M)
    expected="$mesh/points.gz: the compressed file expands past"
    ;;
  symlink-outside)  # a file of the case is a link to a file outside it
    echo "secret" > "$work/secret"
    rm "$case/system/fvSchemes"
    ln -s "$work/secret" "$case/system/fvSchemes"
    expected="$case/system/fvSchemes: a symbolic link that leads outside the folder $case"
    ;;
  *) echo "unknown KIND '$kind'"; exit 2 ;;
esac

"$cli" deform -q -w "$data/bulge.json" "$case" -o "$work/out" "${extra[@]}" 2> "$work/err"
status=$?
failures=0
[ $status -eq 1 ] || { echo "FAIL: $kind: exit status $status, expected 1"; failures=1; }
grep -qF -- "$expected" "$work/err" || { echo "FAIL: $kind: the message does not say '$expected'"; failures=1; }
[ ! -e "$work/out" ] || { echo "FAIL: $kind: the output was written"; failures=1; }
leftovers=$(ls -A "$work" | grep '^\.')
[ -z "$leftovers" ] || { echo "FAIL: $kind: temporaries left: $leftovers"; failures=1; }
echo "$kind: $(cat "$work/err")"
exit $failures
