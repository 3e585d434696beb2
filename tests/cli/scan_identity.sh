#!/usr/bin/env bash
# impactlab scan gives the same file bit for bit on 1 thread, 2 threads and `mpirun -np 3` (when Open MPI
# is installed; CI installs it), and a scan killed half-way and resumed gives the same file again.
#   scan_identity.sh IMPACTLAB
set -euo pipefail
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_scan_test.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"
args=(scan --model A1G --x omega:9:13.5:12 --y xI:-0.003:0.003:8 --measure period,impacts,xrange --transient 20 --record 40)

"$exe" "${args[@]}" --threads 1 --out one.csv 2>/dev/null
"$exe" "${args[@]}" --threads 2 --out two.csv 2>/dev/null
cmp one.csv two.csv || { echo "FAIL: 1 and 2 threads differ"; exit 1; }
[[ $(wc -l <one.csv) -eq 97 ]] || { echo "FAIL: one.csv has $(wc -l <one.csv) lines, expected 97"; exit 1; }
[[ ! -e one.csv.tiles ]] || { echo "FAIL: the tile log of a finished scan was left behind"; exit 1; }

if command -v mpirun >/dev/null; then
  mpirun --allow-run-as-root --oversubscribe --mca btl_vader_single_copy_mechanism none -np 3 \
    "$exe" "${args[@]}" --out mpi.csv 2>mpi.log || { echo "FAIL: mpirun"; cat mpi.log; exit 1; }
  cmp one.csv mpi.csv || { echo "FAIL: mpirun -np 3 differs from 1 thread"; exit 1; }
  grep -q "2 MPI workers" mpi.log || { echo "FAIL: the MPI run did not use its workers"; cat mpi.log; exit 1; }
  echo "mpirun -np 3: identical"
else
  echo "mpirun not installed: the MPI comparison is skipped (scripts/install_deps.sh installs openmpi-bin)"
fi

# Killed after some rows reached the log, then resumed: nothing lost, nothing computed twice.
"$exe" "${args[@]}" --threads 1 --out res.csv 2>/dev/null &
pid=$!
for _ in $(seq 1 600); do
  [[ -f res.csv.tiles ]] && (($(grep -c '^row .* end$' res.csv.tiles || true) >= 3)) && break
  sleep 0.02
done
kill -9 "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
done_rows=$(grep -c '^row .* end$' res.csv.tiles || true)
((done_rows >= 1 && done_rows < 8)) || { echo "FAIL: the kill came at $done_rows of 8 rows; nothing to resume"; exit 1; }
"$exe" "${args[@]}" --threads 1 --out res.csv --resume 2>resume.log
grep -q "resumed $done_rows of 8 rows" resume.log || { echo "FAIL: expected 'resumed $done_rows of 8 rows'"; cat resume.log; exit 1; }
grep -q "($((8 - done_rows)) rows computed" resume.log || { echo "FAIL: rows computed twice"; cat resume.log; exit 1; }
cmp one.csv res.csv || { echo "FAIL: the resumed scan differs"; exit 1; }
echo "killed after $done_rows of 8 rows, resumed: identical"
