#!/bin/bash
# A decomposed OpenFOAM case deformed by an mpirun batch (docs/volume-meshes.md) against OpenFOAM's
# own tools: blockMesh makes the cube of tests/data/openfoam/cube, decomposePar splits it into 3
# processor folders, `mpirun -n N ffdkit-cli deform` (N = 2, and 5: more ranks than meshes)
# deforms it, and the result is what deforming the reconstructed case in one process gives:
#   - the case's own constant/polyMesh/points is that run's file byte for byte;
#   - every processor point equals, value for value, the serial run's point that decomposePar's
#     pointProcAddressing maps it to;
#   - reconstructParMesh, run on the processor folders alone, rebuilds the serial run's points;
#   - every file but the points is the input's, byte for byte.
# A folding tool (its inverted cells all in one processor folder) fails the whole batch: nothing
# is written, no temporary is left. With --allow-inverted the batch counts the serial run's bad
# cells. Needs Debian's openfoam and Open MPI (scripts/setup-deps.sh): fails without them.
# usage: openfoam_mpi_test.sh FFDKIT_CLI MPIEXEC SOURCE_DIR
set -u
data=$3/tests/data/openfoam
source "$(dirname "${BASH_SOURCE[0]}")/mpi_test_setup.sh" "$1" "$2" "$data/bulge.json"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

source "$(dirname "${BASH_SOURCE[0]}")/openfoam_test_setup.sh" "$data"

# The case: blockMesh's cube, points written with 17 digits so that reconstructParMesh's output
# carries the values exactly, decomposed in x into 3 processor folders.
case=$work/case
cube_write_precision=17 decomposed_cube "$case" "$work"
[ -f "$case/processor2/constant/polyMesh/pointProcAddressing" ] || { echo "FAIL: decomposePar wrote no processor2"; exit 1; }

# The serial reference: the reconstructed case alone (no processor folders), one process.
mkdir "$work/whole"
cp -r "$case/system" "$case/constant" "$work/whole/"
"$cli" deform -q -w "$tool" "$work/whole" -o "$work/serial" || { echo "FAIL: serial deform"; exit 1; }
cmp -s "$work/whole/constant/polyMesh/points" "$work/serial/constant/polyMesh/points" &&
  fail "the tool did not move the points (the comparison would prove nothing)"

# Every processor point is the serial run's point at its pointProcAddressing index, exactly.
compare_processors() {  # output
  python3 - "$1" "$work/serial/constant/polyMesh/points" <<'PY'
import re, sys, glob, os
def foam_list(path, item):
    text = open(path).read()
    body = text[text.index('\n(', text.index('}')) + 2:text.rindex(')')]
    return re.findall(item, body)
number = r'[-+0-9.eE]+'
serial = [tuple(float(v) for v in p.split()) for p in foam_list(sys.argv[2], r'\(([^()]*)\)')]
bad = 0
procs = sorted(glob.glob(os.path.join(sys.argv[1], 'processor*')))
assert len(procs) == 3, procs
for proc in procs:
    mesh = os.path.join(proc, 'constant', 'polyMesh')
    local = [tuple(float(v) for v in p.split()) for p in foam_list(os.path.join(mesh, 'points'), r'\(([^()]*)\)')]
    address = [int(a) for a in foam_list(os.path.join(mesh, 'pointProcAddressing'), number)]
    assert len(local) == len(address) > 0, (proc, len(local), len(address))
    for i, g in enumerate(address):
        if local[i] != serial[g]:
            bad += 1
            if bad < 5: print('%s point %d: %r, serial point %d: %r' % (proc, i, local[i], g, serial[g]))
print('%d processor points differ from the serial run' % bad)
sys.exit(1 if bad else 0)
PY
}

# Every file of $1 but the points is byte for byte in $2.
same_but_points() {
  (cd "$1" && find . -type f ! -name 'points' | sort) > "$work/files.a"
  (cd "$2" && find . -type f ! -name 'points' | sort) > "$work/files.b"
  cmp -s "$work/files.a" "$work/files.b" || fail "$2: not the same files as $1"
  while read -r f; do cmp -s "$1/$f" "$2/$f" || fail "$2/$f differs from $1/$f"; done < "$work/files.a"
}

for ranks in 2 5; do
  out=$work/batch$ranks
  "$mpiexec" -n $ranks "$cli" deform -q -w "$tool" "$case" -o "$out" || { fail "mpirun -n $ranks deform failed"; continue; }
  cmp -s "$work/serial/constant/polyMesh/points" "$out/constant/polyMesh/points" ||
    fail "-n $ranks: the case's constant/polyMesh/points differs from the serial run's"
  compare_processors "$out" || fail "-n $ranks: processor points differ from the serial run's"
  same_but_points "$case" "$out"
done

# reconstructParMesh rebuilds the mesh from the processor folders alone: the serial run's points.
rm -rf "$work/batch2/constant/polyMesh"
(cd "$work/batch2" && foam reconstructParMesh -constant -mergeTol 1e-10 > log.reconstruct 2>&1) ||
  { fail "reconstructParMesh failed"; cat "$work/batch2/log.reconstruct"; }
python3 - "$work/batch2/constant/polyMesh/points" "$work/serial/constant/polyMesh/points" <<'PY' || fail "reconstructParMesh's points differ from the serial run's"
import re, sys
def points(path):
    text = open(path).read()
    body = text[text.index('\n(', text.index('}')) + 2:text.rindex(')')]
    return [tuple(float(v) for v in p.split()) for p in re.findall(r'\(([^()]*)\)', body)]
rebuilt, serial = points(sys.argv[1]), points(sys.argv[2])
same_order = rebuilt == serial
same_set = sorted(rebuilt) == sorted(serial)
print('reconstructParMesh: %d points, serial %d; same order: %s, same values: %s' % (len(rebuilt), len(serial), same_order, same_set))
sys.exit(0 if same_set and len(rebuilt) == len(serial) else 1)
PY

# A folding tool: the batch fails on every rank, nothing is written, no temporary is left.
if "$mpiexec" -n 2 "$cli" deform -q -w "$data/fold.json" "$case" -o "$work/folded" 2> "$work/refusal"; then
  fail "a folding tool was not refused"
fi
grep -q "inverted or of zero volume" "$work/refusal" || { fail "the refusal does not name the cells"; cat "$work/refusal"; }
grep -q "processor[0-9]: " "$work/refusal" || { fail "the refusal does not name the processor folder"; cat "$work/refusal"; }
[ ! -e "$work/folded" ] || fail "$work/folded written although refused"
[ -z "$(ls -A "$work" | grep '^\.')" ] || fail "a temporary was left in $work: $(ls -A "$work" | grep '^\.')"

# --allow-inverted: written, and the batch counts the cells one process counts.
"$cli" deform -w "$data/fold.json" "$work/whole" -o "$work/serial-folded" --allow-inverted > /dev/null 2> "$work/serial.warning" ||
  fail "--allow-inverted: the serial run did not write"
serial_bad=$(sed -n 's/.*mesh with \([0-9]*\) of .*/\1/p' "$work/serial.warning")
"$mpiexec" -n 2 "$cli" deform -w "$data/fold.json" "$case" -o "$work/folded" --allow-inverted > /dev/null 2> "$work/batch.warning" ||
  fail "--allow-inverted: the batch did not write"
batch_bad=$(sed -n 's/.*in which \([0-9]*\) of the case.*/\1/p' "$work/batch.warning")
grep -q "processor2: 6 of 72 cells inverted" "$work/batch.warning" || fail "the batch's warning does not name processor2's cells"
echo "fold: serial $serial_bad bad cells, batch $batch_bad"
[ -n "$serial_bad" ] && [ "$serial_bad" -gt 0 ] && [ "$serial_bad" = "$batch_bad" ] ||
  { fail "bad cells: serial '$serial_bad', batch '$batch_bad'"; cat "$work/serial.warning" "$work/batch.warning"; }
compare_processors "$work/folded" > /dev/null 2>&1 && fail "the folded processors equal the bulged serial run"
[ -d "$work/folded/processor2" ] || fail "--allow-inverted: processor2 not written"

if [ $failures -gt 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all decomposed-case checks passed"
