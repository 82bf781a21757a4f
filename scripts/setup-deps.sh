#!/usr/bin/env bash
# Installs every Debian 12 package that ffdkit's build, tests and app need.
# Idempotent: installs only what is missing, and runs `apt-get update` once, only then.
#   scripts/setup-deps.sh           the build, tests and app
#   scripts/setup-deps.sh --fuzz    also clang and libFuzzer (scripts/fuzz.sh)
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config git
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
)
if [ "${1:-}" = "--fuzz" ]; then
  packages+=(clang libfuzzer-14-dev libclang-rt-14-dev)
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
