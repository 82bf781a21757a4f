#!/usr/bin/env bash
# Installs every Debian 12 package that ffdkit's build, tests and app need.
# Idempotent: installs only what is missing, and runs `apt-get update` once, only then.
#   scripts/setup-deps.sh           the build, tests and app
#   scripts/setup-deps.sh --fuzz    also libFuzzer (scripts/fuzz.sh)
#   scripts/setup-deps.sh --cost    print what the install costs (packages and disk, with their
#                                   dependencies, beyond Debian's required and important ones)
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config git
  lld  # the linker (cmake/FfdkitOptions.cmake): links the test programs about ten times quicker than ld.bfd
  clang libomp-14-dev libclang-rt-14-dev  # scripts/test.sh's sanitizer stages: clang compiles ASan + UBSan builds about three times quicker than GCC; its OpenMP and sanitizer runtimes
  libeigen3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libopenmpi-dev openmpi-bin
  nlohmann-json3-dev
  libfast-float-dev libtinygltf-dev
  zlib1g-dev liblz4-dev liblzma-dev
  libvtk9-dev
  qt6-base-dev libqt6opengl6-dev libqt6svg6
  libgl1-mesa-dev libgl1-mesa-dri libglx-mesa0 libegl-mesa0 mesa-utils
  xvfb xauth libxcb1-dev
  python3 doxygen
  pybind11-dev python3-dev python3-numpy python3-pytest
  openfoam  # tests/cli/openfoam_test.sh: blockMesh, foamFormatConvert and checkMesh judge what ffdkit writes
  gmsh  # volume-mesh tests: gmsh -3 makes the meshes and reads back what ffdkit writes
  libcgns-dev cgns-convert  # the CGNS reader/writer and cgnscheck, which judges what it writes
  blender  # the Blender add-on's tests and the side-by-side timing against Blender's lattice modifier
  libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev  # cad/: STEP and IGES
)
fuzz=0
cost=0
for arg in "$@"; do
  case "$arg" in
    --fuzz) fuzz=1 ;;
    --cost) cost=1 ;;
    *) echo "setup-deps: unknown option $arg (--fuzz, --cost)" >&2; exit 2 ;;
  esac
done
if [ "$fuzz" = 1 ]; then
  packages+=(libfuzzer-14-dev)
fi

if [ "$cost" = 1 ]; then
  # What the list stands for beyond what every Debian system has (priority required/important):
  # its installed packages with their dependencies (dpkg's records), plus what apt would install
  # for any still missing (a simulated install, no Recommends, as below). Sizes in installed KiB.
  deps=$(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts --no-breaks --no-replaces \
           --no-enhances "${packages[@]}" | grep -v '^ ' | grep -v '<' | sort -u)
  installed=$({ dpkg-query -W -f='${Package} ${Installed-Size} ${Priority} ${db:Status-Abbrev}\n' $deps 2>/dev/null || true; } |
                awk '$4 == "ii" && $3 != "required" && $3 != "important" {n++; kib += $2} END {print n + 0, kib + 0}')
  toInstall=$({ apt-get install -s -qq --no-install-recommends "${packages[@]}" 2>/dev/null || true; } | awk '/^Inst /{print $2}')
  simulated="0 0"
  if [ -n "$toInstall" ]; then
    simulated=$(apt-cache show --no-all-versions $toInstall | awk '/^Installed-Size:/ {n++; kib += $2} END {print n + 0, kib + 0}')
  fi
  read -r n1 k1 <<<"$installed"
  read -r n2 k2 <<<"$simulated"
  awk -v n=$((n1 + n2)) -v kib=$((k1 + k2)) 'BEGIN {printf "setup-deps: %d packages, %.1f GB installed\n", n, kib / 1024 / 1024}'
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
