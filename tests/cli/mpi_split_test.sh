#!/usr/bin/env bash
# `mpirun -n 2 ffdkit-cli deform` of ONE .xyz, .npy or binary .ply file, each rank reading,
# deforming and writing its slice of the vertices, writes byte for byte the file one process
# writes (docs/scaling.md); a truncated or malformed file fails on every rank with the file's
# message, and nothing is written.
#   mpi_split_test.sh FFDKIT_CLI MPIEXEC WIDGET_FILE
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/mpi_test_setup.sh" "$@"
fail() { echo "mpi_split_test: $*" >&2; exit 1; }

# The same 5003 random points in the three formats: .xyz with comments and blank lines (so that
# line and point numbers differ), a big-endian float64 .npy, and a binary PLY whose vertex
# records mix types (x, a uchar, y, z) with triangles and quads (written back fan-triangulated).
python3 - "$work/in" <<'PY'
import random, struct, sys
random.seed(7)
out = sys.argv[1]
n = 5003
pts = [(random.uniform(0, 2), random.uniform(-1, 1), random.uniform(0, 0.5)) for _ in range(n)]
with open(out + '.xyz', 'w') as f:
    f.write('# a point cloud\n')
    for i, p in enumerate(pts):
        if i % 997 == 5:
            f.write('\n   # a comment\n')
        f.write('%.17g %.17g %.17g\n' % p)
with open(out + '.npy', 'wb') as f:
    d = "{'descr': '>f8', 'fortran_order': False, 'shape': (%d, 3), }" % n
    d += ' ' * ((64 - (10 + len(d) + 1) % 64) % 64) + '\n'
    f.write(b'\x93NUMPY\x01\x00' + struct.pack('<H', len(d)) + d.encode())
    for p in pts:
        f.write(struct.pack('>3d', *p))
faces = [(i, i + 1, i + 2) if i % 2 else (i, i + 1, i + 2, i + 3) for i in range(0, n - 4, 3)]
with open(out + '.ply', 'wb') as f:
    f.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty uchar red\n'
             'property float y\nproperty float z\nelement face %d\nproperty list uchar int vertex_indices\n'
             'end_header\n' % (n, len(faces))).encode())
    for p in pts:
        f.write(struct.pack('<fBff', p[0], 7, p[1], p[2]))
    for fc in faces:
        f.write(struct.pack('<B%di' % len(fc), len(fc), *fc))
PY

deform=(deform -w "$tool" --fit --set push-front=0.15 --set push-back=-0.1 --quiet)
for ext in xyz npy ply; do
  "$cli" "${deform[@]}" "$work/in.$ext" -o "$work/single.$ext"
  "$mpiexec" -n 2 "$cli" "${deform[@]}" "$work/in.$ext" -o "$work/batch.$ext"
  cmp "$work/single.$ext" "$work/batch.$ext" || fail "2 ranks wrote another $ext file than 1 process"
  # The settings did move points (else the comparison would prove little).
  "$cli" deform -w "$tool" --fit --quiet "$work/in.$ext" -o "$work/rest.$ext"
  if cmp -s "$work/single.$ext" "$work/rest.$ext"; then fail "the deformed $ext file equals the one at rest"; fi
done
# Another format out, three ranks (uneven slices).
"$cli" "${deform[@]}" "$work/in.xyz" -o "$work/single-xyz.ply"
"$mpiexec" -n 3 "$cli" "${deform[@]}" "$work/in.xyz" -o "$work/batch-xyz.ply"
cmp "$work/single-xyz.ply" "$work/batch-xyz.ply" || fail "3 ranks wrote another PLY from .xyz than 1 process"

# More ranks than lines: a rank with an empty slice writes nothing and the file is still whole.
printf '0.1 0.2 0.3\n1.5 -0.5 0.25\n' > "$work/two.xyz"
"$cli" "${deform[@]}" "$work/two.xyz" -o "$work/single-two.xyz"
"$mpiexec" -n 3 "$cli" "${deform[@]}" "$work/two.xyz" -o "$work/batch-two.xyz"
cmp "$work/single-two.xyz" "$work/batch-two.xyz" || fail "3 ranks on 2 lines wrote another file than 1 process"

# Failures: every rank exits non-zero, nothing (not even a temporary) is left in the folder.
mkdir "$work/failed"
expect_failure() {  # NAME MESSAGE-THAT-EVERY-RANK-PRINTS|"" MESSAGE-OF-SOME-RANK
  local log="$work/failed/../$1.log"
  if "$mpiexec" -n 2 "$cli" "${deform[@]}" "$work/$1" -o "$work/failed/out.${1##*.}" 2> "$log"; then
    fail "the batch on $1 succeeded"
  fi
  [ "$(grep -c "^ffdkit-cli deform: error: " "$log")" -eq 2 ] || { cat "$log" >&2; fail "$1: not every rank reported an error"; }
  if [ -n "$2" ]; then
    [ "$(grep -cF "$2" "$log")" -eq 2 ] || { cat "$log" >&2; fail "$1: not every rank gave the message '$2'"; }
  fi
  grep -qF "$3" "$log" || { cat "$log" >&2; fail "$1: no rank gave the message '$3'"; }
  [ -z "$(ls -A "$work/failed")" ] || fail "$1: the failed batch left $(ls -A "$work/failed")"
}
# A PLY cut inside its vertices: every rank's header check sees it.
head -c 40000 "$work/in.ply" > "$work/cut.ply"
expect_failure cut.ply "cut.ply:3: element 'vertex' announces 5003 items of at least 13 bytes, the file has" "cut.ply"
# A PLY cut inside its faces: rank 0 reads them, rank 1 learns that it failed.
head -c 85000 "$work/in.ply" > "$work/cut-faces.ply"
single_error="$("$cli" "${deform[@]}" "$work/cut-faces.ply" -o "$work/x.ply" 2>&1 || true)"
expect_failure cut-faces.ply "" "${single_error#ffdkit-cli deform: error: }"
# An .npy one byte short.
head -c $(( $(stat -c %s "$work/in.npy") - 1 )) "$work/in.npy" > "$work/short.npy"
expect_failure short.npy "short.npy: shape (5003, 3) needs 120072 bytes of data, the file has 120071" "short.npy"
# A bad number in rank 1's half of an .xyz: the same line and point number as one process gives.
awk 'NR == 4000 { print "1 2 oops"; next } { print }' "$work/in.xyz" > "$work/bad.xyz"
single_error="$("$cli" "${deform[@]}" "$work/bad.xyz" -o "$work/x.xyz" 2>&1 || true)"
[[ "$single_error" == *"bad.xyz:4000: point "*"expected a number, got 'oops'"* ]] || fail "one process said: $single_error"
expect_failure bad.xyz "" "${single_error#ffdkit-cli deform: error: }"
# Over --max-points: every rank refuses the whole file before it reads a slice, as one process
# refuses it, whatever the number of ranks.
cp "$work/in.npy" "$work/big.npy"
cp "$work/in.xyz" "$work/big.xyz"
"$cli" "${deform[@]}" --max-points 5000 "$work/big.npy" -o "$work/x.npy" 2> /dev/null && fail "one process read big.npy over --max-points"
deform+=(--max-points 5000)
expect_failure big.npy "big.npy: vertices: 5003 points over the read limit of 5000 points (--max-points)" "big.npy"
expect_failure big.xyz "big.xyz: vertices: 5003 points over the read limit of 5000 points (--max-points)" "big.xyz"
echo "mpi_split_test: 2 ranks write one .xyz, .npy and .ply file bit for bit as 1 process; bad files and files over --max-points fail on every rank"
