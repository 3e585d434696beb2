#!/usr/bin/env bash
# File names that are not UTF-8 (a Latin-1 name) are carried as bytes: fit reads such a record and writes its
# report, the name shown as \xNN in report.json (valid JSON) and report.md; outputs with such names are
# written; nothing throws nlohmann's type_error.
#
#   names_as_bytes.sh EXE
set -u
EXE=$1
[[ $EXE == /* ]] || EXE="$(cd "$(dirname "$EXE")" && pwd)/$(basename "$EXE")"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_names.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 2
status=0
name=$'r\xe9sum\xe9.csv'   # "résumé.csv" in Latin-1

"$EXE" synth --model A1H --duration 4 --rate 200 --seed 3 --out "$name" >out.txt 2>&1 ||
  { echo "FAIL: synth could not write '$name':"; cat out.txt; status=1; }
[[ -s $name ]] || { echo "FAIL: synth wrote no file of that name"; status=1; }
grep -q $'\xe9' out.txt && { echo "FAIL: synth printed the name's raw bytes:"; cat -v out.txt; status=1; }
"$EXE" fit "$name" --model A1H --no-plots --report rep >out.txt 2>&1
rc=$?
[[ $rc == 0 ]] || { echo "FAIL: fit on '$name': exit status $rc"; cat out.txt; status=1; }
grep -q "type_error" out.txt && { echo "FAIL: fit: nlohmann's type_error"; cat out.txt; status=1; }
grep -q $'\xe9' out.txt && { echo "FAIL: fit printed the name's raw bytes:"; cat -v out.txt; status=1; }
grep -q 'r\\\\xe9sum\\\\xe9\.csv' rep/report.json || { echo "FAIL: report.json does not name r\\xe9sum\\xe9.csv escaped"; status=1; }
grep -q 'r\\xe9sum\\xe9\.csv' rep/report.md || { echo "FAIL: report.md does not name r\\xe9sum\\xe9.csv escaped"; status=1; }
# The whole report is UTF-8 (iconv refuses anything else), so any JSON reader takes it.
for f in rep/report.json rep/report.md rep/model_after.json; do
  iconv -f UTF-8 -t UTF-8 "$f" >/dev/null 2>&1 || { echo "FAIL: $f is not UTF-8"; status=1; }
done
# A message quoting such a name shows it escaped, never the raw byte.
"$EXE" fit "$name" $'--x-col=\xff' --report rep2 >out.txt 2>&1
grep -q $'\xff' out.txt && { echo "FAIL: a message printed a raw non-UTF-8 byte:"; cat -v out.txt; status=1; }
[[ $status == 0 ]] && echo "names_as_bytes: names carried as bytes"
exit $status
