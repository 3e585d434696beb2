#!/usr/bin/env bash
# The test job (CI runs exactly this): install what is missing, then
#  1. build the headless core, CLI and tests with the GUI OFF (the core must not need GL) and run them (the
#     Python module's pytest suite against the CLI and the notebook examples/tour.ipynb among them);
#  2. build everything (GUI and benchmarks included) and run the GUI smoke test under Xvfb;
#  3. install into a temporary prefix and run both programs from elsewhere, and make the .deb (cpack);
#  4. build the browser page (scripts/web.sh, emscripten) and open it in headless Chromium;
#  5. fuzz the loaders and the simulator for 20 s each (clang, libFuzzer, ASan + UBSan).
# Release builds, -Wall -Wextra warnings as errors.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
jobs="$(nproc)"

cmake -S . -B build-ci-core -DCMAKE_BUILD_TYPE=Release -DIMPACTLAB_WERROR=ON \
      -DIMPACTLAB_BUILD_APP=OFF -DIMPACTLAB_BUILD_BENCH=OFF -DIMPACTLAB_BUILD_TESTS=ON
cmake --build build-ci-core -j"$jobs"
ctest --test-dir build-ci-core --output-on-failure

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DIMPACTLAB_WERROR=ON \
      -DIMPACTLAB_BUILD_APP=ON -DIMPACTLAB_BUILD_BENCH=ON -DIMPACTLAB_BUILD_TESTS=ON
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -L gui

# 3. the desktop install (a temporary prefix, both programs run from another directory) and the .deb.
ctest --test-dir build --output-on-failure -L install
(cd build && cpack -G DEB)

# 4. the browser page: one HTML file, opened from file:// in headless Chromium (SwiftShader's WebGL2).
bash scripts/web.sh
ctest --test-dir build --output-on-failure -L web

# 5. a short fuzz run of the loaders and the simulator (libFuzzer, ASan + UBSan; scripts/fuzz.sh 3600 for a long one).
bash scripts/fuzz.sh 20
