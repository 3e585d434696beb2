#!/usr/bin/env bash
# The C++ lines the last commit changed, checked against .clang-format: prints what clang-format would change
# on those lines and exits 1 if anything, 0 if nothing. Only the changed lines: the code written before
# .clang-format is left as it is. Usage: bash scripts/format_check.sh [BASE] (BASE: HEAD~1, the last commit).
# Like `git clang-format --diff BASE HEAD`, but a moved file counts only its changed lines (git clang-format
# diffs without rename detection, so it would check a moved file whole).
set -euo pipefail
cd "$(dirname "$0")/.."
base=${1:-HEAD~1}
if ! command -v clang-format >/dev/null; then
  echo "format_check: clang-format is missing (Debian: apt-get install clang-format)" >&2
  exit 2
fi
# "FILE FIRST:LAST" for each run of lines HEAD added or changed since BASE (renames followed).
ranges=$(git diff -M -U0 --no-color --no-ext-diff --diff-filter=AMR "$base" HEAD -- '*.cpp' '*.hpp' '*.h' '*.cc' |
  awk '/^\+\+\+ b\// { file = substr($2, 3); next }
       /^@@ / { split($3, r, ","); first = substr(r[1], 2); n = (2 in r) ? r[2] : 1
                if (n > 0) print file, first ":" first + n - 1 }')
status=0
for file in $(printf '%s\n' "$ranges" | awk 'NF { print $1 }' | sort -u); do
  lines=$(printf '%s\n' "$ranges" | awk -v f="$file" '$1 == f { printf " --lines=%s", $2 }')
  # shellcheck disable=SC2086 # one --lines=A:B per run
  if ! diff -u --label "a/$file" --label "b/$file" <(git show "HEAD:$file") \
       <(git show "HEAD:$file" | clang-format --assume-filename="$file" $lines); then
    status=1
  fi
done
if [ "$status" = 0 ]; then
  echo "format_check: the C++ lines changed since $base follow .clang-format"
else
  echo "format_check: clang-format would change the lines above (git clang-format $base applies it to the working tree)" >&2
fi
exit "$status"
