#!/usr/bin/env bash
# Every command that writes, on a disk that fills up midway (fail_writes.so, LD_PRELOAD): it exits 1 with the
# system's reason, the outputs it would have replaced are byte for byte as before (a CSV and its PNG, a fit
# report, continue's folder: all or none), and no partial file and no new output is left.
#
#   disk_full.sh EXE FAIL_WRITES_SO
# Each command runs once to count the bytes it writes, then with budgets of 0 bytes (the first write fails),
# half of that, and all but its last 64 bytes (every file but the end of the last is written).
set -u
EXE=$1
LIB=$2
[[ $EXE == /* ]] || EXE="$(cd "$(dirname "$EXE")" && pwd)/$(basename "$EXE")"
[[ $LIB == /* ]] || LIB="$(cd "$(dirname "$LIB")" && pwd)/$(basename "$LIB")"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_disk_full.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
status=0
# (Under AddressSanitizer the preloaded library comes first; that is fine for a test.)
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"

# A record for fit, written once without any budget.
"$EXE" synth --model A1H --duration 4 --rate 200 --seed 3 --out "$WORK/rec.csv" >/dev/null 2>&1 ||
  { echo "FAIL: synth could not write the record fit reads"; exit 1; }

# check NAME OUTPUTS -- ARGS...: OUTPUTS (space-separated; a name ending in / is a folder holding files) exist
# with old contents before each failing run and must be unchanged after it.
check() {
  local name=$1 outputs=$2
  shift 3
  local total
  rm -rf "$WORK/run" && mkdir "$WORK/run" && cd "$WORK/run" || exit 2
  cp "$WORK/rec.csv" .
  LD_PRELOAD=$LIB IMPACTLAB_TEST_WRITE_COUNT=$WORK/count "$EXE" "$@" >"$WORK/out" 2>&1 ||
    { echo "FAIL: $name: the run without a budget failed:"; cat "$WORK/out"; status=1; return; }
  total=$(cat "$WORK/count")
  for budget in 0 $((total / 2)) $((total > 64 ? total - 64 : 0)); do
    rm -rf "$WORK/run" && mkdir "$WORK/run" && cd "$WORK/run" || exit 2
    cp "$WORK/rec.csv" .
    local o
    for o in $outputs; do
      if [[ $o == */ ]]; then mkdir -p "$o"; for f in branches.csv points.csv report.md report.json model_after.json; do echo "old $f" >"$o$f"; done
      else echo "old $o" >"$o"; fi
    done
    find . -type f | sort | xargs md5sum >"$WORK/before"
    LD_PRELOAD=$LIB IMPACTLAB_TEST_WRITE_BUDGET=$budget "$EXE" "$@" >"$WORK/out" 2>&1
    local rc=$?
    [[ $rc == 1 ]] || { echo "FAIL: $name (budget $budget of $total bytes): exit status $rc, expected 1"; cat "$WORK/out"; status=1; }
    grep -q "No space left on device" "$WORK/out" ||
      { echo "FAIL: $name (budget $budget of $total bytes): the message does not say the disk is full:"; cat "$WORK/out"; status=1; }
    # The tile log of a scan that stopped is what --resume reads: the only new file allowed.
    find . -type f ! -name '*.tiles' | sort | xargs md5sum >"$WORK/after"
    diff "$WORK/before" "$WORK/after" >/dev/null ||
      { echo "FAIL: $name (budget $budget of $total bytes): files changed:"; diff "$WORK/before" "$WORK/after"; status=1; }
    local left
    left=$(find . -name '*.partial-*')
    [[ -z $left ]] || { echo "FAIL: $name (budget $budget of $total bytes): left behind: $left"; status=1; }
  done
  cd "$WORK" || exit 2
}

check simulate "s.csv" -- simulate --omega 10 --duration 1 --dt 0.01 --out s.csv
check poincare "p.csv" -- poincare --omega 18 --periods 40 --out p.csv
check bifurcation "d.csv d.png" -- bifurcation --steps 6 --transient 2 --record 4 --out d.csv --png d.png
check figure3 "f.png" -- figure3 --steps 2 --out f.png
check synth "y.csv" -- synth --model A1H --duration 1 --rate 100 --out y.csv
check synth_gz "y.csv.gz" -- synth --model A1H --duration 1 --rate 100 --out y.csv.gz
check fit "r/" -- fit rec.csv --model A1H --report r
check scan "s.csv s.png" -- scan --x omega:10:12:3 --y xI:-0.01:0:3 --transient 1 --record 2 --threads 1 --out s.csv --png s.png
check orbit "o.csv o.png" -- orbit --model A1H --omega 10 --out o.csv --png o.png
check continue "c/ c.png" -- continue --model A1H --omega-min 9 --omega-max 10 --out c --png c.png
check lyapunov "l.csv l.png" -- lyapunov --sweep up --steps 3 --omega-min 10 --omega-max 12 --record 4 --out l.csv --png l.png
check basins "b.csv b.png" -- basins --omega 13 --grid 6 --out b.csv --png b.png
check recovery "t.md" -- recovery --null --seeds 2 --versions A1H --duration 10 --out t.md
[[ $status == 0 ]] && echo "disk_full: every command kept its old outputs"
exit $status
