#!/usr/bin/env bash
# A command stopped by SIGINT or SIGTERM leaves no hidden partial file (.NAME.partial-PID), an old output of
# the same name as it was, and dies of that signal; a scan keeps its tile log (what --resume reads). Each run
# must be one the program accepts (under the row cap): the signal meets it computing, not refused.
#
#   signal_cleanup.sh EXE
# Each run is started with job control on (a background job of a script would otherwise ignore SIGINT), the
# signal sent once its partial file exists, whatever the machine's speed.
set -u
set -m
EXE=$1
[[ $EXE == /* ]] || EXE="$(cd "$(dirname "$EXE")" && pwd)/$(basename "$EXE")"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_signal_test.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 2
status=0

# run NAME SIGNAL OUTPUT WAIT ARGS...: OUTPUT (old) must be unchanged afterwards; the signal is sent once a file
# matching WAIT (a name pattern; "+" in front: and holding data) exists.
run() {
  local name=$1 sig=$2 out=$3 wait=$4
  shift 4
  rm -rf "$WORK/run" && mkdir "$WORK/run" && cd "$WORK/run" || exit 2
  # An old output of that name: the interrupted run must leave it as it was.
  mkdir -p "$(dirname "$out")" && echo "precious $out" >"$out"
  "$EXE" "$@" >/dev/null 2>&1 &
  local pid=$! found=0
  local size=()
  [[ $wait == +* ]] && { wait=${wait#+}; size=(-size +0); }
  for _ in $(seq 600); do   # up to a minute for the file to appear
    if find . -name "$wait" "${size[@]+"${size[@]}"}" | grep -q .; then found=1; break; fi
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if [[ $found == 0 ]]; then
    echo "FAIL: $name: no file $wait appeared (the run ended or is too fast to be interrupted)"
    kill -KILL "$pid" 2>/dev/null
    status=1
    return
  fi
  kill "-$sig" "$pid"
  wait "$pid"
  local rc=$? want=$((128 + $(kill -l "$sig")))
  [[ $rc == "$want" ]] || { echo "FAIL: $name: exit status $rc after SIG$sig, expected $want"; status=1; }
  local left
  left=$(find . -name '*.partial-*')
  [[ -z $left ]] || { echo "FAIL: $name: left behind: $left"; status=1; }
  [[ $(cat "$out") == "precious $out" ]] || { echo "FAIL: $name: the old $out was replaced"; status=1; }
  cd "$WORK" || exit 2
}

# simulate streams its rows: stopped once some are in the partial file.
run simulate TERM big.csv '+.big.csv.partial-*' simulate --omega 18 --duration 4e4 --dt 1e-3 --out big.csv
run simulate_int INT big.csv '+.big.csv.partial-*' simulate --omega 18 --duration 4e4 --dt 1e-3 --out big.csv
run poincare TERM p.csv '.p.csv.partial-*' poincare --omega 18 --periods 10000000 --out p.csv
run bifurcation INT d.csv '.d.csv.partial-*' bifurcation --steps 100000 --record 400 --out d.csv
run continue TERM c/branches.csv '.points.csv.partial-*' continue --model A1C --omega-min 5 --omega-max 25 --max-period 64 --out c
run basins TERM b.csv '.b.csv.partial-*' basins --omega 13 --grid 4000 --threads 1 --out b.csv
run lyapunov_sweep TERM l.csv '.l.csv.partial-*' lyapunov --sweep up --steps 100000 --out l.csv
run orbit INT o.csv '.o.csv.partial-*' orbit --model A1C --omega 0.05 --period 64 --out o.csv
run synth TERM y.csv '.y.csv.partial-*' synth --duration 1e5 --rate 100 --out y.csv
# scan writes its rows as they finish: stopped once the first is in the partial CSV.
run scan_streams TERM s.csv '+.s.csv.partial-*' scan --x omega:5:20:400 --y xI:-0.01:0.01:400 --threads 1 --out s.csv
run scan TERM s.csv '+s.csv.tiles' scan --x omega:5:20:400 --y xI:-0.01:0.01:400 --threads 1 --out s.csv
# The scan's tile log stays for --resume.
[[ -s $WORK/run/s.csv.tiles ]] || { echo "FAIL: scan: the tile log s.csv.tiles is gone"; status=1; }

# A closed pipe (`... 2>&1 | head -c 10`) ends a run like SIGINT: status 141, nothing left behind. The progress
# lines on stderr (one per 10 % into a pipe) are what meets the closed pipe.
rm -rf "$WORK/run" && mkdir "$WORK/run" && cd "$WORK/run" || exit 2
"$EXE" scan --x omega:5:20:160 --y xI:-0.01:0.01:40 --threads 1 --out s.csv 2>&1 | head -c 10 >/dev/null
rc=${PIPESTATUS[0]}
[[ $rc == 141 ]] || { echo "FAIL: sigpipe: exit status $rc after the pipe closed, expected 141 (SIGPIPE)"; status=1; }
left=$(find . -name '*.partial-*')
[[ -z $left ]] || { echo "FAIL: sigpipe: left behind: $left"; status=1; }
[[ ! -e s.csv ]] || { echo "FAIL: sigpipe: s.csv was written"; status=1; }

# SIGKILL leaves the partial file; the next run in that folder removes it (its PID is gone) and any other dead
# process's partial files there, but not those of a process still running.
rm -rf "$WORK/run" && mkdir "$WORK/run" && cd "$WORK/run" || exit 2
"$EXE" simulate --omega 18 --duration 4e4 --dt 1e-3 --out big.csv >/dev/null 2>&1 &
pid=$!
for _ in $(seq 600); do find . -name '.big.csv.partial-*' -size +0 | grep -q . && break; sleep 0.1; done
kill -KILL "$pid"
wait "$pid" 2>/dev/null
[[ -n $(find . -name ".big.csv.partial-$pid") ]] || { echo "FAIL: sigkill: no partial file to clean up (the test is void)"; status=1; }
sleep 0.1 &
dead=$!
wait "$dead"
echo x >".other.csv.partial-$dead"
echo x >".other.csv.partial-$dead-old"
mkdir ".clip.partial-$dead"
echo x >".clip.partial-$dead/frame.png"
sleep 60 &
alive=$!
echo x >".live.csv.partial-$alive"
echo x >"keep.partial-$dead"   # not a hidden partial name: never touched
"$EXE" simulate --omega 10 --duration 0.1 --dt 0.01 --out small.csv >/dev/null 2>&1 || { echo "FAIL: sigkill: the next run failed"; status=1; }
kill "$alive" 2>/dev/null
left=$(find . -name '.*.partial-*' ! -name ".live.csv.partial-$alive" | sort)
[[ -z $left ]] || { echo "FAIL: sigkill: the next run left the dead runs' partial files: $left"; status=1; }
[[ -e .live.csv.partial-$alive && -e keep.partial-$dead ]] || { echo "FAIL: sigkill: a live run's partial file or another file was removed"; status=1; }
cd "$WORK" || exit 2

[[ $status == 0 ]] && echo "signal_cleanup: all runs stopped cleanly"
exit $status
