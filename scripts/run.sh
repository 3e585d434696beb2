#!/usr/bin/env bash
# The main job: install what is missing, build (Release, programs in build/bin/), compute the paper's
# Fig. 3 into out/fig3.png, and open the visualiser when there is a display.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DIMPACTLAB_BUILD_APP=ON
cmake --build build -j"$(nproc)" --target impactlab impactlab-gui
mkdir -p out
build/bin/impactlab figure3 --out out/fig3.png
echo "Fig. 3 written to out/fig3.png"
if [ -n "${DISPLAY:-}" ] && [ -x build/bin/impactlab-gui ]; then
  exec build/bin/impactlab-gui
else
  echo "No display: start the visualiser later with build/bin/impactlab-gui"
fi
