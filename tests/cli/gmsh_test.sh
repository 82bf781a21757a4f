#!/bin/bash
# Gmsh as the client of ffdkit-cli deform (docs/volume-meshes.md): gmsh -3 meshes a unit cube
# (tetrahedra, hexahedra, prisms; first and second order; MSH 4.1 ASCII and binary, and SU2);
# ffdkit deforms it with tests/data/openfoam/bulge.json; gmsh reads the result back without an
# error, and gmsh's own re-save of input and output have the same $Elements and $PhysicalNames
# (tags intact); every byte but the coordinates is the input's (volume_mesh_compare.py). A
# folding tool (fold.json) is refused with nothing written; --allow-inverted writes anyway.
# Needs Debian's gmsh (scripts/setup-deps.sh): fails without it.
# usage: gmsh_test.sh FFDKIT_CLI SOURCE_DIR
set -u
cli=$1
src=$2
tools=$src/tests/data/openfoam
compare=$src/tests/cli/volume_mesh_compare.py
work=$(mktemp -d "${TMPDIR:-/tmp}/ffdkit-gmsh-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
if ! command -v gmsh > /dev/null; then
  echo "FAIL: gmsh is not installed (apt-get install gmsh; scripts/setup-deps.sh does)"
  exit 1
fi

# The unit cube three ways.
cat > "$work/tets.geo" <<'GEO'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Volume("fluid") = {1};
Physical Surface("walls") = {1, 2, 3, 4, 5, 6};
Mesh.MeshSizeMax = 0.4;
GEO
cat > "$work/hexes.geo" <<'GEO'
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 5; Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{4}; Recombine; };
Physical Volume("block") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
GEO
cat > "$work/prisms.geo" <<'GEO'
Point(1) = {0, 0, 0, 0.3}; Point(2) = {1, 0, 0, 0.3}; Point(3) = {1, 1, 0, 0.3}; Point(4) = {0, 1, 0, 0.3};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{3}; Recombine; };
Physical Volume("layers") = {out[1]};
Physical Surface("bottom") = {1};
GEO

# $1's gmsh re-save: its $PhysicalNames and $Elements sections.
tags_of() {
  gmsh "$1" -0 -format msh41 -o "$1.resaved.msh" > "$1.gmsh.log" 2>&1 || return 1
  ! grep -q "^Error" "$1.gmsh.log" || return 1
  sed -n '/^\$PhysicalNames/,/^\$EndPhysicalNames/p; /^\$Elements/,/^\$EndElements/p' "$1.resaved.msh"
}

for geo in tets hexes prisms; do
  for order in 1 2; do
    for kind in ascii binary su2; do
      name=$geo-o$order-$kind
      case $kind in
        ascii) args=(-format msh41); ext=msh ;;
        binary) args=(-format msh41 -bin); ext=msh ;;
        su2) args=(-format su2); ext=su2 ;;
      esac
      # SU2 holds first-order cells only.
      if [ $kind = su2 ] && [ $order = 2 ]; then continue; fi
      in="$work/$name.$ext"
      gmsh -3 -order $order "${args[@]}" "$work/$geo.geo" -o "$in" > "$work/$name.mesh.log" 2>&1 \
        || { fail "$name: gmsh could not mesh"; cat "$work/$name.mesh.log"; continue; }
      out="$work/$name-bulge.$ext"
      "$cli" deform -q -w "$tools/bulge.json" "$in" -o "$out" || { fail "$name: deform failed"; continue; }
      python3 "$compare" "$ext" "$in" "$out" > "$work/compare.log" || { fail "$name: $(cat "$work/compare.log")"; }
      if [ $ext = msh ]; then
        tags_of "$in" > "$work/tags.in" || { fail "$name: gmsh cannot read the input"; continue; }
        tags_of "$out" > "$work/tags.out" || { fail "$name: gmsh cannot read ffdkit's output"; cat "$out.gmsh.log"; continue; }
        [ -s "$work/tags.in" ] || fail "$name: no elements in gmsh's re-save"
        cmp -s "$work/tags.in" "$work/tags.out" || fail "$name: gmsh reads other elements or physical groups after the deformation"
      fi
      # A folding tool: refused, nothing written; --allow-inverted writes and says so.
      folded="$work/$name-fold.$ext"
      if "$cli" deform -q -w "$tools/fold.json" "$in" -o "$folded" 2> "$work/refusal"; then
        fail "$name: a folding tool was not refused"
      fi
      grep -q "inverted or of zero volume" "$work/refusal" || { fail "$name: the refusal does not name the cells"; cat "$work/refusal"; }
      [ ! -e "$folded" ] || fail "$name: $folded written although refused"
      "$cli" deform -q --allow-inverted -w "$tools/fold.json" "$in" -o "$folded" 2> "$work/warning" \
        || fail "$name: --allow-inverted did not write"
      grep -q "allow-inverted" "$work/warning" || fail "$name: --allow-inverted wrote without saying so"
      if [ $ext = msh ]; then
        tags_of "$folded" > /dev/null || fail "$name: gmsh cannot read the folded output"
      fi
      [ -z "$(ls -A "$work" | grep '^\.')" ] || fail "$name: a temporary was left in $work"
    done
  done
done

if [ $failures -gt 0 ]; then echo "$failures Gmsh/SU2 check(s) failed"; exit 1; fi
echo "all Gmsh and SU2 checks passed"
