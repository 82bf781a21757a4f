# Sourced by the OpenFOAM shell tests (openfoam_test.sh, openfoam_decomposed_info_test.sh,
# openfoam_mpi_test.sh): fails the test unless OpenFOAM's tools are installed (Debian's openfoam,
# scripts/setup-deps.sh), and defines
#   foam TOOL ARGS...            runs an OpenFOAM tool in OpenFOAM's environment;
#   decomposed_cube CASE LOGS    makes the blockMesh cube of tests/data/openfoam/cube in the new
#                                folder CASE and splits it in x into 3 processor folders
#                                (decomposePar), the tools' output in LOGS/log.TOOL; exits the
#                                test on a failure. Set cube_write_precision first to change the
#                                controlDict's writePrecision (17: points that read back exactly).
# usage: source openfoam_test_setup.sh DATA_DIR     (DATA_DIR: tests/data/openfoam)
openfoam_data=$1
bashrc=/usr/share/openfoam/etc/bashrc
if [ ! -f "$bashrc" ] || ! command -v checkMesh > /dev/null || ! command -v decomposePar > /dev/null; then
  echo "FAIL: OpenFOAM is not installed (apt-get install openfoam; scripts/setup-deps.sh does)"
  exit 1
fi
# OpenFOAM's tools need its environment; its bashrc complains about helper scripts Debian leaves out.
foam() { (set +u; . "$bashrc" > /dev/null 2>&1; "$@"); }

decomposed_cube() {
  local case=$1 logs=$2
  mkdir -p "$case"
  cp -r "$openfoam_data/cube/system" "$case/"
  if [ -n "${cube_write_precision:-}" ]; then
    sed -i "s/^writePrecision .*/writePrecision  $cube_write_precision;/" "$case/system/controlDict"
  fi
  cat > "$case/system/decomposeParDict" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }
numberOfSubdomains 3;
method simple;
simpleCoeffs { n (3 1 1); delta 0.001; }
DICT
  local tool
  for tool in blockMesh decomposePar; do
    (cd "$case" && foam "$tool" > "$logs/log.$tool" 2>&1) || { cat "$logs/log.$tool"; echo "FAIL: $tool"; exit 1; }
  done
}
