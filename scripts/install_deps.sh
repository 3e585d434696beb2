#!/usr/bin/env bash
# Installs the Debian packages impactlab needs (only those missing). Safe to run again.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev nlohmann-json3-dev libstb-dev doctest-dev fonts-dejavu-core zlib1g-dev libceres-dev
  libsundials-dev libboost-dev
  libimgui-dev libglfw3-dev libgl-dev libgl1-mesa-dri xvfb xauth
  libopenmpi-dev openmpi-bin
  clang clang-format
  emscripten chromium dpkg-dev python3 desktop-file-utils
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-pandas
  jupyter-notebook python3-nbconvert python3-ipykernel python3-matplotlib
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
else
  echo "install_deps: installing ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# libFuzzer's runtime (scripts/fuzz.sh) is packaged per clang version: libclang-rt-N-dev for Debian's clang N.
clang_major="$(clang --version | sed -n 's/.*clang version \([0-9]*\).*/\1/p' | head -n 1)"
rt="libclang-rt-${clang_major}-dev"
if ! dpkg-query -W -f='${Status}' "$rt" 2>/dev/null | grep -q "install ok installed"; then
  echo "install_deps: installing $rt"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "$rt"
fi
