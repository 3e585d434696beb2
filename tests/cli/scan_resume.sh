#!/usr/bin/env bash
# scan --resume trusts nothing in its tile log: a log left by a scan stopped with SIGTERM is refused when the
# model's parameters (a file that kept the name "A1H") or the tolerance differ, or when a row was tampered
# with, and the untouched log is resumed.
#   scan_resume.sh IMPACTLAB
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_scan_resume.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 2
fail() { echo "FAIL: $*"; cat out.log 2>/dev/null; exit 1; }
args=(scan --x omega:9:13.5:12 --y xI:-0.003:0.003:40 --measure period --transient 20 --record 40 --threads 1 --out p.csv)

"$exe" "${args[@]}" --model A1H 2>/dev/null &
pid=$!
for _ in $(seq 600); do
  [[ -f p.csv.tiles ]] && (($(grep -c '^row .* end$' p.csv.tiles || true) >= 2)) && break
  sleep 0.05
done
kill -TERM "$pid"
wait "$pid"
rows=$(grep -c '^row .* end$' p.csv.tiles || true)
((rows >= 2 && rows < 40)) || fail "the scan was stopped at $rows of 40 rows"
cp p.csv.tiles log.orig

# The same name, other parameters: refused, and the log is left for the right scan.
printf '{"base": "A1H", "name": "A1H", "k": 1672.8}\n' >stiff.json
"$exe" "${args[@]}" --model stiff.json --resume >out.log 2>&1
[[ $? == 2 ]] && grep -q "belongs to another scan" out.log || fail "a log of other parameters was resumed"
cmp -s p.csv.tiles log.orig || fail "a refused resume changed the log"
# Another tolerance.
"$exe" "${args[@]}" --model A1H --rtol 1e-9 --resume >out.log 2>&1
[[ $? == 2 ]] && grep -q "belongs to another scan" out.log || fail "a log of another --rtol was resumed"
# A token the log never writes, in a row that is not the last.
sed '2s/ 0x[^ ]* / abc /' log.orig >p.csv.tiles
"$exe" "${args[@]}" --model A1H --resume >out.log 2>&1
[[ $? == 2 ]] && grep -q "line 2: 'abc' is not a number" out.log || fail "a tampered row was read"
[[ ! -e p.csv ]] || fail "a refused resume wrote p.csv"
# The log as the scan left it: resumed.
cp log.orig p.csv.tiles
"$exe" "${args[@]}" --model A1H --resume >out.log 2>&1 || fail "the untouched log was refused"
grep -q "resumed $rows of 40 rows" out.log || fail "expected 'resumed $rows of 40 rows'"
[[ $(wc -l <p.csv) == 481 ]] || fail "p.csv has $(wc -l <p.csv) lines, expected 481"
echo "scan_resume: $rows rows resumed; other parameters, another rtol and a tampered row refused"
