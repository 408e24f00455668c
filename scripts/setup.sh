#!/usr/bin/env bash
# Installs, with apt, the Debian packages stiffsoft needs that are not installed yet.
# Idempotent: a machine that has them all runs no apt command at all. Extra package names given as
# arguments are installed too (scripts/fuzz.sh adds clang's). Xvfb and Mesa's software OpenGL are
# for `stiffsoft render` on a machine without a display (Debian's VTK renders through X11).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libsuitesparse-dev petsc-dev libgmsh-dev libcgal-dev libvtk9-dev
  libtbb-dev zlib1g-dev nlohmann-json3-dev libcli11-dev libspdlog-dev googletest libgtest-dev
  python3-matplotlib python3-numpy python3-dev python3-pytest pybind11-dev mypy
  xvfb xauth libgl1-mesa-dri
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
