#!/usr/bin/env bash
# Runs the impactlab CLI once in a fresh scratch directory and checks what it did.
#
#   run_cli_test.sh EXE [checks...] -- ARGS...
#
# checks:
#   --rc N | --rc nonzero       expected exit status (required)
#   --match REGEX               stdout+stderr must match this extended regex (repeatable)
#   --no-match REGEX            ... must not match it (repeatable)
#   --count REGEX N             exactly N lines of stdout+stderr match it (repeatable)
#   --mkdir DIR                 create the directory DIR in the scratch directory first (repeatable)
#   --fifo FILE                 create a named pipe FILE first (repeatable; nothing ever writes to it)
#   --sparse FILE SIZE          create FILE of SIZE (truncate's syntax: 2G) holding no data blocks
#   --write FILE TEXT           create FILE in the scratch directory before the run (repeatable)
#   --csv FILE HEADER MIN MAX   FILE must exist, start with the line HEADER and have MIN..MAX data rows
#                               of comma-separated finite numbers with as many fields as HEADER
#   --absent FILE               FILE must not exist after the run (no half-written output)
#   --unchanged FILE            FILE (from --write) must be byte for byte as written; no *.partial* file left
# ARGS are passed to EXE as they are, run inside the scratch directory (relative paths land there).
set -u

fail() {
  echo "FAIL: $*" >&2
  echo "---- command: $EXE ${ARGS[*]}" >&2
  echo "---- exit status: $RC" >&2
  echo "---- output:" >&2
  cat "$WORK/.out" >&2
  exit 1
}

EXE=$1
shift
# Absolute, since the run happens in the scratch directory.
[[ $EXE == */* && $EXE != /* ]] && EXE="$(cd "$(dirname "$EXE")" && pwd)/$(basename "$EXE")"
EXPECT_RC=""
MATCH=()
NOMATCH=()
COUNTS=()
WRITES=()
MKDIRS=()
FIFOS=()
SPARSE=()
CSVS=()
ABSENT=()
UNCHANGED=()
while [[ $# -gt 0 && $1 != "--" ]]; do
  case $1 in
    --rc) EXPECT_RC=$2; shift 2 ;;
    --match) MATCH+=("$2"); shift 2 ;;
    --no-match) NOMATCH+=("$2"); shift 2 ;;
    --count) COUNTS+=("$2" "$3"); shift 3 ;;
    --write) WRITES+=("$2" "$3"); shift 3 ;;
    --mkdir) MKDIRS+=("$2"); shift 2 ;;
    --fifo) FIFOS+=("$2"); shift 2 ;;
    --sparse) SPARSE+=("$2" "$3"); shift 3 ;;
    --csv) CSVS+=("$2" "$3" "$4" "$5"); shift 5 ;;
    --absent) ABSENT+=("$2"); shift 2 ;;
    --unchanged) UNCHANGED+=("$2"); shift 2 ;;
    *) echo "run_cli_test.sh: unknown check '$1'" >&2; exit 2 ;;
  esac
done
[[ $# -gt 0 && $1 == "--" ]] || { echo "run_cli_test.sh: missing '--' before the arguments" >&2; exit 2; }
shift
ARGS=("$@")
[[ -n $EXPECT_RC ]] || { echo "run_cli_test.sh: --rc is required" >&2; exit 2; }
[[ -x $EXE ]] || { echo "run_cli_test.sh: '$EXE' is not an executable" >&2; exit 2; }

WORK=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_cli_test.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
for d in "${MKDIRS[@]+"${MKDIRS[@]}"}"; do mkdir -p "$WORK/$d"; done
for f in "${FIFOS[@]+"${FIFOS[@]}"}"; do mkfifo "$WORK/$f"; done
for ((i = 0; i < ${#SPARSE[@]}; i += 2)); do truncate -s "${SPARSE[i + 1]}" "$WORK/${SPARSE[i]}"; done
for ((i = 0; i < ${#WRITES[@]}; i += 2)); do
  printf '%s\n' "${WRITES[i + 1]}" >"$WORK/${WRITES[i]}"
done
for f in "${UNCHANGED[@]+"${UNCHANGED[@]}"}"; do
  cp "$WORK/$f" "$WORK/.orig_${f//\//_}"
done

cd "$WORK" || exit 2
"$EXE" "${ARGS[@]}" </dev/null >"$WORK/.out" 2>&1
RC=$?

if [[ $EXPECT_RC == nonzero ]]; then
  [[ $RC -ne 0 ]] || fail "expected a non-zero exit status"
else
  [[ $RC -eq $EXPECT_RC ]] || fail "expected exit status $EXPECT_RC"
fi
# A crash is never an acceptable way to fail.
[[ $RC -lt 128 ]] || fail "killed by a signal"

for re in "${MATCH[@]+"${MATCH[@]}"}"; do
  grep -Eq -- "$re" "$WORK/.out" || fail "output does not match /$re/"
done
for re in "${NOMATCH[@]+"${NOMATCH[@]}"}"; do
  if grep -Eq -- "$re" "$WORK/.out"; then fail "output matches /$re/"; fi
done
for ((i = 0; i < ${#COUNTS[@]}; i += 2)); do
  n=$(grep -Ec -- "${COUNTS[i]}" "$WORK/.out")
  [[ $n -eq ${COUNTS[i + 1]} ]] || fail "$n lines match /${COUNTS[i]}/, expected ${COUNTS[i + 1]}"
done
for f in "${ABSENT[@]+"${ABSENT[@]}"}"; do
  [[ ! -e $WORK/$f ]] || fail "$f exists"
done
for f in "${UNCHANGED[@]+"${UNCHANGED[@]}"}"; do
  cmp -s "$WORK/$f" "$WORK/.orig_${f//\//_}" || fail "$f was changed"
done
if [[ ${#UNCHANGED[@]} -gt 0 ]] && find "$WORK" -name '*.partial*' | grep -q .; then fail "a partial file was left behind"; fi

for ((i = 0; i < ${#CSVS[@]}; i += 4)); do
  file=${CSVS[i]} header=${CSVS[i + 1]} min=${CSVS[i + 2]} max=${CSVS[i + 3]}
  [[ -f $WORK/$file ]] || fail "$file was not written"
  first=$(head -n 1 "$WORK/$file")
  [[ $first == "$header" ]] || fail "$file: header is '$first', expected '$header'"
  rows=$(($(wc -l <"$WORK/$file") - 1))
  ((rows >= min && rows <= max)) || fail "$file: $rows data rows, expected $min..$max"
  fields=$(awk -F, '{print NF; exit}' <<<"$header")
  bad=$(awk -F, -v n="$fields" 'NR > 1 {
          if (NF != n) { print NR ": " NF " fields"; exit }
          for (i = 1; i <= NF; ++i)
            if ($i !~ /^-?[0-9]+(\.[0-9]*)?([eE][-+]?[0-9]+)?$/) { print NR ": not a number: " $i; exit }
        }' "$WORK/$file")
  [[ -z $bad ]] || fail "$file: line $bad"
done
exit 0
