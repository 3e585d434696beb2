#!/usr/bin/env bash
# The sanitizer presets, one after the other: AddressSanitizer with LeakSanitizer (Open MPI's own
# allocations suppressed by tests/lsan.supp), UndefinedBehaviorSanitizer, ThreadSanitizer. Each builds the
# headless core, CLI and tests in build/<preset> and runs ctest there. Not part of .ci/run (too long for it
# on 2 cores); run by hand before a release:  bash scripts/sanitize.sh [asan|ubsan|tsan|asan-ubsan ...]
# asan-ubsan builds only the CLI with both sanitizers and fits every record of ../shared/data with it (the
# tests labelled shared-fit), stopping at the first report.
set -euo pipefail
cd "$(dirname "$0")/.."
presets=("$@")
[[ ${#presets[@]} -gt 0 ]] || presets=(asan ubsan tsan asan-ubsan)
for p in "${presets[@]}"; do
  cmake --preset "$p"
  cmake --build --preset "$p" -j"$(nproc)"
  ctest --preset "$p"
done
