#!/bin/bash
# ffdkit-cli info and validate on a decomposed OpenFOAM case (docs/volume-meshes.md), judged by
# OpenFOAM's own tools: blockMesh makes the cube of tests/data/openfoam/cube, decomposePar splits
# it into 3 processor folders, and
#   - info lists each processor mesh with the cell count decomposePar reports for it, and the
#     total is blockMesh's cell count;
#   - validate says ok;
#   - once a folding tool has deformed the case (deform --allow-inverted, one process), info
#     --quality counts as many bad cells over the processors as it counts on the folded
#     reconstructed mesh alone, and validate fails naming the processor folder that holds them.
# Needs Debian's openfoam (scripts/setup-deps.sh): fails without it.
# usage: openfoam_decomposed_info_test.sh FFDKIT_CLI SOURCE_DIR
set -u
cli=$1
data=$2/tests/data/openfoam
work=$(mktemp -d "${TMPDIR:-/tmp}/ffdkit-decomposed-info-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

source "$(dirname "${BASH_SOURCE[0]}")/openfoam_test_setup.sh" "$data"
case=$work/case
decomposed_cube "$case" "$work"

# decomposePar's cell count per processor ("Processor 0 / Number of cells = 9"), in order.
expected=$(awk '/^Processor [0-9]+/ { p = $2 } /Number of cells =/ && p != "" { print "processor" p, $NF; p = "" }' "$work/log.decomposePar")
total=$(awk '/^ *nCells:/ { print $2; exit }' "$work/log.blockMesh")
[ -n "$expected" ] && [ -n "$total" ] || { fail "could not read decomposePar's or blockMesh's cell counts"; cat "$work/log.decomposePar"; }

"$cli" info "$case" > "$work/info" 2>&1 || { fail "info exited $?"; cat "$work/info"; }
listed=$(sed -n 's/^\(processor[0-9]*\): .* \([0-9]*\) cells, .*/\1 \2/p' "$work/info")
[ "$listed" = "$expected" ] || { fail "info's processor cell counts differ from decomposePar's"; echo "info:"; echo "$listed"; echo "decomposePar:"; echo "$expected"; }
grep -q "^3 processors, and the reconstructed mesh" "$work/info" || { fail "info does not say 3 processors and the reconstructed mesh"; cat "$work/info"; }
grep -q "^total over the processors: $total cells" "$work/info" || { fail "the total is not blockMesh's $total cells"; cat "$work/info"; }

"$cli" validate "$case" > "$work/validate" 2>&1 || { fail "validate of the decomposed case failed"; cat "$work/validate"; }
grep -q "ok (decomposed OpenFOAM case, 3 processors, $total cells" "$work/validate" || { fail "validate's summary"; cat "$work/validate"; }

# Folded by a tool: the processor meshes and the reconstructed mesh hold the same bad cells.
"$cli" deform -q --allow-inverted -w "$data/fold.json" "$case" -o "$work/folded" 2> "$work/deform.log" ||
  { fail "deform --allow-inverted"; cat "$work/deform.log"; }
mkdir "$work/whole"
cp -r "$work/folded/system" "$work/folded/constant" "$work/whole/"
serial_bad=$("$cli" info --quality "$work/whole" | sed -n 's/^bad cells: \([0-9]*\) of .*/\1/p')
[ -n "$serial_bad" ] && [ "$serial_bad" -gt 0 ] || fail "the folding tool made no bad cell in the reconstructed mesh ($serial_bad)"
"$cli" info --quality "$work/folded" > "$work/info-folded" 2>&1 || { fail "info --quality of the folded case"; cat "$work/info-folded"; }
grep -q "^total quality: .*, $serial_bad cells inverted or of zero volume" "$work/info-folded" ||
  { fail "info counts other bad cells over the processors than on the reconstructed mesh ($serial_bad)"; cat "$work/info-folded"; }
if "$cli" validate "$work/folded" > "$work/validate-folded" 2>&1; then
  fail "validate passed a folded case"
fi
grep -q "processor[0-9]: .*inverted or of zero volume" "$work/validate-folded" ||
  { fail "validate does not name the processor with bad cells"; cat "$work/validate-folded"; }

if [ "$failures" -gt 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "info and validate agree with decomposePar and blockMesh; $serial_bad folded cells counted alike"
