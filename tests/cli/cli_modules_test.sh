#!/bin/bash
# ffdkit-cli loads VTK and OpenCASCADE only with the module of a command that needs them
# (docs/cli.md): what the dynamic loader reports (LD_DEBUG=libs) is checked, and a missing or
# broken module is a clear error naming its file and the command, exit 1, nothing written.
# usage: cli_modules_test.sh FFDKIT_CLI SOURCE_DIR CASE [WITH_CAD]
#   CASE start    info and deform (an .obj to .ply) load neither VTK nor OpenCASCADE; a .vtp
#                 output loads the VTK module, a STEP input the OpenCASCADE module
#   CASE render   render loads the VTK module (and, for a scene naming a STEP part, the
#                 OpenCASCADE module too) and writes the PNG; needs a display (xvfb-run)
#   CASE missing  a copy of ffdkit-cli without its modules, or with a broken one
set -u
cli=$1
source_dir=$2
case_name=$3
with_cad=${4:-OFF}
tool=$source_dir/tests/data/openfoam/bulge.json
mesh=$source_dir/tests/data/y_up_column.obj
step=$source_dir/tests/fuzz/corpus/fuzz_cad_step/box.step
work=$(mktemp -d "${TMPDIR:-/tmp}/ffdkit-cli-modules-XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# loaded NAME ARGS...: runs ffdkit-cli with LD_DEBUG=libs; the loader's log goes to $work/NAME.libs,
# the program's own output to $work/NAME.out; returns the exit status.
loaded() {
  local name=$1
  shift
  LD_DEBUG=libs LD_DEBUG_OUTPUT="$work/$name.libs" "$cli" "$@" > "$work/$name.out" 2>&1
  local status=$?
  cat "$work/$name.libs".* > "$work/$name.libs" 2>/dev/null
  return $status
}
# The libraries a run initialised ("calling init: PATH" lines of LD_DEBUG=libs).
initialised() { grep -o 'calling init: .*' "$work/$1.libs" | sed 's/calling init: //'; }
expect_none() {  # NAME PATTERN WHAT
  local found
  found=$(initialised "$1" | grep -E "$2")
  [ -z "$found" ] || fail "$1 loaded $3:"$'\n'"$found"
}
expect_some() {  # NAME PATTERN WHAT
  initialised "$1" | grep -qE "$2" || { fail "$1 did not load $3"; initialised "$1"; }
}

case "$case_name" in
start)
  loaded info info "$tool" || { fail "info failed"; cat "$work/info.out"; }
  grep -q "lattice lattice: 3x3x3 control points" "$work/info.out" || { fail "info printed no lattice"; cat "$work/info.out"; }
  loaded deform deform -w "$tool" "$mesh" -o "$work/column.ply" || { fail "deform failed"; cat "$work/deform.out"; }
  [ -s "$work/column.ply" ] || fail "deform wrote no column.ply"
  for run in info deform; do
    [ "$(initialised "$run" | wc -l)" -gt 5 ] || fail "$run: no 'calling init' lines in the loader's log"
    expect_none "$run" '/libvtk[^/]*$|ffdkit-cli-vtk\.so$' "VTK"
    expect_none "$run" '/libTK[^/]*$|ffdkit-cli-cad\.so$' "OpenCASCADE"
  done
  loaded vtp deform -w "$tool" "$mesh" -o "$work/column.vtp" || { fail "deform to .vtp failed"; cat "$work/vtp.out"; }
  grep -q '<VTKFile type="PolyData"' "$work/column.vtp" || fail "column.vtp is not VTK XML poly data"
  expect_some vtp '/ffdkit-cli-vtk\.so$' "the VTK module"
  expect_some vtp '/libvtkIOXML[^/]*$' "VTK's XML writer"
  expect_none vtp '/libTK[^/]*$|ffdkit-cli-cad\.so$' "OpenCASCADE"
  if [ "$with_cad" = ON ]; then
    loaded step deform -w "$tool" "$step" -o "$work/box.step" || { fail "deform of a STEP input failed"; cat "$work/step.out"; }
    grep -q "^ISO-10303-21;" "$work/box.step" || fail "box.step is not a STEP file"
    expect_some step '/ffdkit-cli-cad\.so$' "the OpenCASCADE module"
    expect_some step '/libTKSTEP[^/]*$' "OpenCASCADE's STEP reader"
    expect_none step '/libvtk[^/]*$|ffdkit-cli-vtk\.so$' "VTK"
  fi
  ;;
render)
  scene=$source_dir/scenes/examples/press
  loaded render render "$scene" "$work/press.png" --size 64x48 || { fail "render failed"; cat "$work/render.out"; }
  [ "$(head -c 8 "$work/press.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "press.png is not a PNG"
  expect_some render '/ffdkit-cli-vtk\.so$' "the VTK module"
  expect_some render '/libvtkRenderingOpenGL2[^/]*$' "VTK's OpenGL renderer"
  expect_none render '/libTK[^/]*$|ffdkit-cli-cad\.so$' "OpenCASCADE (the scene has no STEP part)"
  if [ "$with_cad" = ON ]; then
    cp "$step" "$work/box.step"
    echo '{"format": "ffdkit-scene", "version": 2, "objects": [{"name": "part", "mesh": {"path": "box.step"}}]}' \
      > "$work/scene.json"
    loaded cad_render render "$work/scene.json" "$work/part.png" --size 64x48 ||
      { fail "render of a scene with a STEP part failed"; cat "$work/cad_render.out"; }
    [ -s "$work/part.png" ] || fail "no part.png"
    expect_some cad_render '/ffdkit-cli-vtk\.so$' "the VTK module"
    expect_some cad_render '/ffdkit-cli-cad\.so$' "the OpenCASCADE module (the scene's part)"
  fi
  ;;
missing)
  # A copy of the program alone: no module next to it, none in ../lib/ffdkit.
  mkdir -p "$work/alone/bin"
  cp "$cli" "$work/alone/bin/ffdkit-cli"
  alone=$work/alone/bin/ffdkit-cli
  expect_error() {  # NAME STATUS PATTERN ARGS...
    local name=$1 status=$2 pattern=$3
    shift 3
    "$alone" "$@" > "$work/$name.out" 2>&1
    local got=$?
    [ "$got" -eq "$status" ] || fail "$name: exit $got, expected $status"
    grep -qE "$pattern" "$work/$name.out" || { fail "$name: no message matching: $pattern"; cat "$work/$name.out"; }
    if grep -qiE "segmentation|abort|core dumped|terminate called" "$work/$name.out"; then fail "$name crashed"; fi
  }
  "$alone" info "$tool" > "$work/info.out" 2>&1 || { fail "info without modules failed"; cat "$work/info.out"; }
  "$alone" deform -w "$tool" "$mesh" -o "$work/column.ply" > "$work/ply.out" 2>&1 ||
    { fail "deform to .ply without modules failed"; cat "$work/ply.out"; }
  here=$work/alone/bin/ffdkit-cli-vtk.so
  expect_error render 1 "^ffdkit-cli render: error: cannot load ffdkit-cli's VTK module ffdkit-cli-vtk.so, which render needs: no such file \(looked for $here and $work/alone/lib/ffdkit/ffdkit-cli-vtk.so\)" \
    render "$source_dir/scenes/examples/press" "$work/press.png"
  [ ! -e "$work/press.png" ] || fail "render without its module wrote press.png"
  expect_error plot 1 "^ffdkit-cli plot: error: cannot load ffdkit-cli's VTK module .*which plot needs" \
    plot --generator g3-clothoid "$work/none.json" -o "$work/plot.png"
  expect_error vtp 1 "^ffdkit-cli deform: error: .*column.vtp: cannot load ffdkit-cli's VTK module ffdkit-cli-vtk.so, which writing a .vtp file needs" \
    deform -w "$tool" "$mesh" -o "$work/column.vtp"
  [ -z "$(ls "$work" | grep column.vtp)" ] || fail "deform without the VTK module left $(ls "$work" | grep column.vtp)"
  if [ "$with_cad" = ON ]; then
    expect_error step 1 "^ffdkit-cli deform: error: cannot load ffdkit-cli's OpenCASCADE module ffdkit-cli-cad.so, which deform with a STEP or IGES input needs" \
      deform -w "$tool" "$step" -o "$work/box.step"
    [ ! -e "$work/box.step" ] || fail "deform without the OpenCASCADE module wrote box.step"
  fi
  # In the install tree's place (../lib/ffdkit), a file that is no shared object: dlopen's reason.
  mkdir -p "$work/alone/lib/ffdkit"
  echo "not a shared object" > "$work/alone/lib/ffdkit/ffdkit-cli-vtk.so"
  expect_error broken 1 "^ffdkit-cli render: error: cannot load ffdkit-cli's VTK module $work/alone/lib/ffdkit/ffdkit-cli-vtk.so, which render needs: .*(invalid ELF header|file too short)" \
    render "$source_dir/scenes/examples/press" "$work/press.png"
  # A shared object without the module's entry point (here: the program's C library).
  libc=$(ldd "$cli" | awk '/libc\.so/ {print $3}')
  cp "$libc" "$work/alone/bin/ffdkit-cli-vtk.so"
  expect_error no_entry 1 "^ffdkit-cli render: error: cannot load ffdkit-cli's VTK module $here, which render needs: it has no entry point ffdkit_cli_vtk_module" \
    render "$source_dir/scenes/examples/press" "$work/press.png"
  ;;
*)
  echo "unknown case '$case_name'"
  exit 2
  ;;
esac
if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "ok: $case_name"
