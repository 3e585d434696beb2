#!/usr/bin/env bash
# One fit of a record of ../shared/data through the CLI: it must end (ctest's TIMEOUT bounds it), exit 0 and
# write its report, whatever the record holds. A crash (a signal), a hang or an error exit fails the test.
#   shared_fit.sh IMPACTLAB SHARED_DIR -- FIT_ARGS... (each @SHARED@ replaced by SHARED_DIR)
# Exit 77 (skipped) when a data file the arguments name is missing (a clone without ../shared).
set -u
bin="$1"
shared="$2"
shift 3
args=()
for a in "$@"; do
  a="${a//@SHARED@/$shared}"
  if [[ "$a" == "$shared"/* && ! -e "$a" ]]; then
    echo "SKIPPED: shared data $a is missing" >&2
    exit 77
  fi
  args+=("$a")
done
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
start=$(date +%s)
"$bin" fit "${args[@]}" --report "$dir/rep" --no-plots > "$dir/out.txt" 2>&1
rc=$?
end=$(date +%s)
tail -n 25 "$dir/out.txt"
echo "exit $rc after $((end - start)) s"
if [ $rc -ge 128 ]; then
  echo "FAIL: the fit died of signal $((rc - 128))" >&2
  exit 1
fi
if [ $rc -ne 0 ]; then
  echo "FAIL: the fit exited $rc" >&2
  exit 1
fi
for f in report.json report.md model_after.json; do
  [ -s "$dir/rep/$f" ] || { echo "FAIL: no $f written" >&2; exit 1; }
done
grep -q '"verdict"' "$dir/rep/report.json" || { echo "FAIL: report.json has no verdict" >&2; exit 1; }
exit 0
