#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, ASan + UBSan) and fuzzes each for SECONDS (default 20) from the
# checked-in corpus (tests/fuzz/corpus: the issue's inputs among them). A crash, leak, sanitizer report, hang
# (-timeout) or a run past 512 MB (-rss_limit_mb) fails the script and leaves the input in build-fuzz/crashes.
#   scripts/fuzz.sh            # CI: 20 s each
#   scripts/fuzz.sh 3600       # the long run documented in the README
#   scripts/fuzz.sh 60 session # only the harnesses named (csv json gzip sim session)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
harnesses=("${@:2}")
[[ ${#harnesses[@]} -gt 0 ]] || harnesses=(csv json gzip sim session)
mkdir -p build-fuzz
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DIMPACTLAB_FUZZ=ON \
      -DIMPACTLAB_BUILD_APP=OFF -DIMPACTLAB_BUILD_TESTS=OFF -DIMPACTLAB_BUILD_BENCH=OFF > build-fuzz/build.log
cmake --build build-fuzz -j"$(nproc)" --target fuzz_csv fuzz_json fuzz_gzip fuzz_sim fuzz_session >> build-fuzz/build.log
mkdir -p build-fuzz/crashes
for t in "${harnesses[@]}"; do
  work="build-fuzz/corpus-$t"   # the checked-in corpus stays as it is; new inputs land here
  mkdir -p "$work"
  echo "fuzz_$t: ${seconds} s"
  [[ -x build-fuzz/bin/fuzz_$t ]] || { echo "fuzz: build-fuzz/bin/fuzz_$t was not built (see build-fuzz/build.log)" >&2; exit 1; }
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    build-fuzz/bin/fuzz_$t "$work" "tests/fuzz/corpus/$t" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=512 -max_len=65536 -artifact_prefix=build-fuzz/crashes/$t- -print_final_stats=1 2>&1 |
    grep -E "^(#[0-9]+ *DONE|stat::number_of_executed_units|stat::peak_rss_mb|==[0-9]+==ERROR|SUMMARY|.*Test unit written)" || true
  if ls build-fuzz/crashes/$t-* >/dev/null 2>&1; then
    echo "fuzz_$t: FAILED, inputs in build-fuzz/crashes/" >&2
    exit 1
  fi
done
echo "fuzz: no crash, leak, hang or sanitizer report"
