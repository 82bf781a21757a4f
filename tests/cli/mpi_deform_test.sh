#!/usr/bin/env bash
# `mpirun -n 2 ffdkit-cli deform` over five point-file pieces writes, bit for bit, the files one
# process writes for the same pieces (docs/scaling.md); a bad piece on one rank fails the whole
# batch with nothing written.
#   mpi_deform_test.sh FFDKIT_CLI MPIEXEC WIDGET_FILE
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/mpi_test_setup.sh" "$@"
mpirun=("$mpiexec" -n 2)

# Five pieces of different sizes and extents (uneven shares: rank 0 gets 2, rank 1 gets 3).
for piece in 0 1 2 3 4; do
  awk -v seed="$piece" -v n="$((1500 + 400 * piece))" 'BEGIN {
    srand(seed + 1)
    for (i = 0; i < n; ++i) printf "%.17g %.17g %.17g\n", rand() * (1 + seed), rand() * 2 - 1, rand() * 0.5 + seed * 0.1
  }' > "$work/piece$piece.xyz"
done
pieces=("$work"/piece0.xyz "$work"/piece1.xyz "$work"/piece2.xyz "$work"/piece3.xyz "$work"/piece4.xyz)
args=(deform -w "$tool" "${pieces[@]}" --fit --set push-front=0.15 --set push-back=-0.1 --quiet)

"$cli" "${args[@]}" -o "$work/single"
"${mpirun[@]}" "$cli" "${args[@]}" -o "$work/batch"

for piece in 0 1 2 3 4; do
  cmp "$work/single/piece$piece.xyz" "$work/batch/piece$piece.xyz"
done
# The tool did deform every piece (else the comparison would prove nothing).
for piece in 0 1 2 3 4; do
  if cmp -s "$work/single/piece$piece.xyz" "$work/piece$piece.xyz"; then
    echo "piece$piece.xyz came out unchanged" >&2
    exit 1
  fi
done

# A malformed piece in rank 1's share: the batch fails and neither rank writes anything.
echo "1 2 not-a-number" > "$work/piece4.xyz"
if "${mpirun[@]}" "$cli" "${args[@]}" -o "$work/failed" 2> "$work/failed.log"; then
  echo "the batch with a malformed piece succeeded" >&2
  exit 1
fi
grep -q "piece4.xyz:1: " "$work/failed.log" || { cat "$work/failed.log" >&2; exit 1; }
if [ -n "$(ls -A "$work/failed" 2>/dev/null)" ]; then
  echo "the failed batch left files: $(ls -A "$work/failed")" >&2
  exit 1
fi
echo "mpi_deform_test: 2 ranks match 1 process bit for bit on 5 pieces; a bad piece fails the batch cleanly"
