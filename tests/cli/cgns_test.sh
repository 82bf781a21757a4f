#!/bin/bash
# CGNS through ffdkit-cli with CGNS's own tools as the judges (docs/volume-meshes.md): a TetGen
# mesh of the unit cube (2 x 2 x 2 cubes of 6 tetrahedra, its 48 boundary triangles) is converted
# by tetgen_to_cgns (Debian's cgns-convert); ffdkit-cli deform writes it with tests/data/openfoam/
# bulge.json; cgnscheck reports for the written file what it reports for the input (no error),
# cgnsdiff finds the same tree, and with the data compared only the three coordinate arrays
# differ. A folding tool is refused with the CGNS element numbers of the bad cells and nothing
# written; --allow-inverted writes it. Needs cgns-convert (scripts/setup-deps.sh): fails without it.
# usage: cgns_test.sh FFDKIT_CLI SOURCE_DIR
set -u
cli=$1
data=$2/tests/data/openfoam
work=$(mktemp -d "${TMPDIR:-/tmp}/ffdkit-cgns-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
for tool in tetgen_to_cgns cgnscheck cgnsdiff; do
  command -v $tool > /dev/null || { echo "FAIL: $tool is not installed (apt-get install cgns-convert; scripts/setup-deps.sh does)"; exit 1; }
done

cd "$work"
python3 - <<'PY'
from collections import Counter
n = 2
pts = [(i / n, j / n, k / n) for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
def idx(i, j, k): return 1 + i + (n + 1) * (j + (n + 1) * k)
tets = []
for k in range(n):
    for j in range(n):
        for i in range(n):
            c = [idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
                 idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)]
            for t in [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]:
                tets.append([c[x] for x in t])
faces, orient = Counter(), {}
for t in tets:
    for f in [(t[0], t[2], t[1]), (t[0], t[1], t[3]), (t[1], t[2], t[3]), (t[0], t[3], t[2])]:
        faces[tuple(sorted(f))] += 1
        orient[tuple(sorted(f))] = f
boundary = [orient[k] for k, c in faces.items() if c == 1]
with open('cube.node', 'w') as f:
    f.write('%d 3 0 0\n' % len(pts) + ''.join('%d %r %r %r\n' % (i + 1, *p) for i, p in enumerate(pts)))
with open('cube.ele', 'w') as f:
    f.write('%d 4 0\n' % len(tets) + ''.join('%d %d %d %d %d\n' % (i + 1, *t) for i, t in enumerate(tets)))
with open('cube.face', 'w') as f:
    f.write('%d 1\n' % len(boundary) + ''.join('%d %d %d %d 1\n' % (i + 1, *t) for i, t in enumerate(boundary)))
PY
tetgen_to_cgns cube cube.cgns > convert.log 2>&1 || { cat convert.log; echo "FAIL: tetgen_to_cgns"; exit 1; }

"$cli" deform -q -w "$data/bulge.json" cube.cgns -o out.cgns || fail "deform with bulge.json failed"
cgnscheck cube.cgns > check.in 2>&1
cgnscheck out.cgns > check.out 2>&1 || fail "cgnscheck failed on the written file"
grep -q "^checking complete" check.out || { fail "cgnscheck did not complete"; cat check.out; }
grep -qi "error" check.out && { fail "cgnscheck reports an error"; cat check.out; }
[ "$(tail -1 check.in)" = "$(tail -1 check.out)" ] || fail "cgnscheck: '$(tail -1 check.out)' for the output, '$(tail -1 check.in)' for the input"
structure=$(cgnsdiff cube.cgns out.cgns)
[ -z "$structure" ] || fail "cgnsdiff finds another tree: $structure"
cgnsdiff -d cube.cgns out.cgns > data.diff
[ "$(wc -l < data.diff)" -eq 3 ] && [ "$(grep -c '^/Base/Zone/GridCoordinates/Coordinate[XYZ] <> .*data values differ' data.diff)" -eq 3 ] ||
  { fail "cgnsdiff -d: not exactly the three coordinate arrays"; cat data.diff; }
"$cli" info --quality out.cgns | grep -q "^quality: cells 48," || fail "info --quality of the written file"

if "$cli" deform -q -w "$data/fold.json" cube.cgns -o fold.cgns 2> refusal; then fail "a folding tool was not refused"; fi
grep -q "cells inverted or of zero volume (first: " refusal || { fail "the refusal does not name the cells"; cat refusal; }
[ ! -e fold.cgns ] || fail "fold.cgns written although refused"
[ -z "$(ls -A | grep '^\.')" ] || fail "a temporary was left: $(ls -A | grep '^\.')"
"$cli" deform -q -w "$data/fold.json" cube.cgns -o fold.cgns --allow-inverted 2> /dev/null || fail "--allow-inverted did not write"
cgnscheck fold.cgns > check.fold 2>&1 || fail "cgnscheck failed on the folded file"

if [ $failures -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all CGNS checks passed"
