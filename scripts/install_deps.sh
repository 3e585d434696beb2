#!/usr/bin/env bash
# Installs the Debian packages impactlab needs (only those missing). Safe to run again.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev nlohmann-json3-dev libstb-dev doctest-dev fonts-dejavu-core zlib1g-dev libceres-dev
  libsundials-dev libboost-dev
  libimgui-dev libglfw3-dev libgl-dev libgl1-mesa-dri xvfb xauth
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
