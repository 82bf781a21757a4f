#!/bin/bash
# A scene naming an OpenFOAM case folder and a CGNS file as objects (docs/volume-meshes.md):
#   - deform --scene writes each byte for byte as deform -w of the same mesh with the scene's tool
#     (bulge.json): OUT/cube the case, OUT/tets.cgns the CGNS file;
#   - checkMesh says "Mesh OK" on the case written;
#   - the two are written all or nothing: with the OpenFOAM case folded (fold.json), nothing is
#     written, the valid CGNS file neither.
# Needs Debian's openfoam and CGNS (scripts/setup-deps.sh): fails without them.
# usage: volume_scene_cases_test.sh FFDKIT_CLI SOURCE_DIR
set -u
cli=$1
data=$2/tests/data/openfoam
cgns=$2/tests/fuzz/corpus/fuzz_cgns/tets-hdf5.cgns  # two tetrahedra in the unit cube, written by libcgns
work=$(mktemp -d "${TMPDIR:-/tmp}/ffdkit-volume-scene-cases-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
source "$(dirname "${BASH_SOURCE[0]}")/openfoam_test_setup.sh" "$data"

scene=$work/scene
mkdir -p "$scene/cube"
cp -r "$data/cube/system" "$scene/cube/"
(cd "$scene/cube" && foam blockMesh > "$work/log.blockMesh" 2>&1) || { cat "$work/log.blockMesh"; echo "FAIL: blockMesh"; exit 1; }
cp "$cgns" "$scene/tets.cgns"
# The scene: both objects attached to the tool's lattice.
make_scene() {
  python3 - "$1" "$2" <<'PY'
import json, sys
tool = json.load(open(sys.argv[1]))
scene = {"format": "ffdkit-scene", "version": 2,
         "objects": [{"name": "cube", "mesh": {"path": "cube"}}, {"name": "tets", "mesh": {"path": "tets.cgns"}}],
         "widgets": tool, "attachments": [{"lattice": tool["lattices"][0]["name"], "objects": ["cube", "tets"]}]}
json.dump(scene, open(sys.argv[2], "w"), indent=1)
PY
}
make_scene "$data/bulge.json" "$scene/scene.json"
"$cli" deform -q --scene "$scene/scene.json" -o "$work/out" || fail "deform --scene"
"$cli" deform -q -w "$data/bulge.json" "$scene/cube" -o "$work/cube-w" || fail "deform -w of the case"
"$cli" deform -q -w "$data/bulge.json" "$scene/tets.cgns" -o "$work/tets-w.cgns" || fail "deform -w of the CGNS file"
diff -r "$work/out/cube" "$work/cube-w" > /dev/null || fail "the case written from the scene differs from deform -w's"
cmp -s "$work/out/tets.cgns" "$work/tets-w.cgns" || fail "the CGNS file written from the scene differs from deform -w's"
cmp -s "$work/out/cube/constant/polyMesh/points" "$scene/cube/constant/polyMesh/points" &&
  fail "the bulge moved no point of the case (the comparison would prove nothing)"
cmp -s "$work/out/tets.cgns" "$scene/tets.cgns" && fail "the bulge moved no point of the CGNS file"
(cd "$work/out/cube" && foam checkMesh > "$work/log.checkMesh" 2>&1)
grep -q "^Mesh OK" "$work/log.checkMesh" || { fail "checkMesh does not say Mesh OK"; cat "$work/log.checkMesh"; }

# The case folded: nothing written, the CGNS file neither.
make_scene "$data/fold.json" "$scene/folded.json"
if "$cli" deform -q --scene "$scene/folded.json" -o "$work/folded" 2> "$work/refusal"; then
  fail "a folded case was not refused"
fi
grep -q "inverted or of zero volume" "$work/refusal" || { fail "the refusal does not name the cells"; cat "$work/refusal"; }
[ -e "$work/folded/tets.cgns" ] && fail "the CGNS file was written beside a refused case"
[ -e "$work/folded/cube" ] && fail "a refused case was written"
[ -z "$(ls -A "$work/folded" 2> /dev/null)" ] || { fail "the refused batch left files"; ls -A "$work/folded"; }

if [ "$failures" -gt 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "deform --scene wrote the OpenFOAM case and the CGNS file as deform -w does; checkMesh: Mesh OK; a fold wrote nothing"
