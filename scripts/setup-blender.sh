#!/usr/bin/env bash
# Installs Debian's blender, which only bench/compare/blender_lattice.sh needs (a large package:
# scripts/setup-deps.sh leaves it out). Idempotent.
set -euo pipefail
if dpkg-query -W -f='${Status}' blender 2>/dev/null | grep -q "install ok installed"; then
  echo "setup-blender: blender present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends blender
