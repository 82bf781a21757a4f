#!/bin/bash
# A scene whose object is a volume mesh (scenes/examples/volume-duct, a Gmsh mesh of tetrahedra):
# ffdkit-cli deform --scene writes the whole mesh in its own format, byte for byte what deforming
# the .msh file with the scene's widgets as a tool gives; Gmsh reads it back without an error. A
# pinch that pushes the top through the bottom is refused (nothing written); --allow-inverted
# writes it and says how many cells are bad. Needs Debian's gmsh (scripts/setup-deps.sh).
# usage: volume_scene_test.sh FFDKIT_CLI SOURCE_DIR
set -u
cli=$1
sample=$2/scenes/examples/volume-duct
work=$(mktemp -d "${TMPDIR:-/tmp}/ffdkit-volume-scene-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
command -v gmsh > /dev/null || { echo "FAIL: gmsh is not installed (apt-get install gmsh; scripts/setup-deps.sh does)"; exit 1; }

# The scene's widget model is a widget file of its own: the same tool, given with -w.
python3 - "$sample/scene.json" "$work/tool.json" <<'PY'
import json, sys
json.dump(json.load(open(sys.argv[1]))["widgets"], open(sys.argv[2], "w"), indent=2)
PY

"$cli" deform -q --scene "$sample" --set pinch=0.15 -o "$work/scene.msh" || fail "deform --scene"
"$cli" deform -q -w "$work/tool.json" --set pinch=0.15 "$sample/duct.msh" -o "$work/file.msh" || fail "deform -w of the file"
cmp -s "$work/scene.msh" "$work/file.msh" || fail "deform --scene and deform of the file with the same tool differ"
cmp -s "$work/scene.msh" "$sample/duct.msh" && fail "the pinch moved no point (the comparison would prove nothing)"
# Only the coordinates changed: the elements and physical groups are the input's, line for line.
sed -n '/^\$Elements/,/^\$EndElements/p; /^\$PhysicalNames/,/^\$EndPhysicalNames/p' "$sample/duct.msh" > "$work/in.tags"
sed -n '/^\$Elements/,/^\$EndElements/p; /^\$PhysicalNames/,/^\$EndPhysicalNames/p' "$work/scene.msh" > "$work/out.tags"
cmp -s "$work/in.tags" "$work/out.tags" || fail "the elements or physical groups changed"
gmsh "$work/scene.msh" -0 -o "$work/resaved.msh" > "$work/gmsh.log" 2>&1 || fail "gmsh could not read the deformed mesh"
grep -q "^Error" "$work/gmsh.log" && { fail "gmsh reported an error"; cat "$work/gmsh.log"; }

# A folding pinch: refused with the count, nothing written; --allow-inverted writes it.
if "$cli" deform -q --scene "$sample" --set pinch=1.5 -o "$work/folded.msh" 2> "$work/refusal"; then
  fail "a folding pinch was not refused"
fi
grep -q "inverted or of zero volume (first: " "$work/refusal" || { fail "the refusal does not name the cells"; cat "$work/refusal"; }
[ -e "$work/folded.msh" ] && fail "a refused mesh was written"
"$cli" deform --scene "$sample" --set pinch=1.5 --allow-inverted -o "$work/folded.msh" > "$work/allowed" 2>&1 ||
  { fail "--allow-inverted"; cat "$work/allowed"; }
grep -q "wrote a mesh with .* inverted or of zero volume .*(--allow-inverted)" "$work/allowed" ||
  { fail "--allow-inverted does not say how many cells are bad"; cat "$work/allowed"; }

if [ "$failures" -gt 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "deform --scene wrote the volume mesh as deforming the file does; gmsh reads it; a fold is refused"
