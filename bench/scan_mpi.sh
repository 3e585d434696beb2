#!/usr/bin/env bash
# impactlab scan across local MPI ranks (Open MPI): the plane of `bench --scan` with 1, 2 and 4 worker ranks
# (mpirun -np 2, 3, 5: rank 0 hands out rows and writes), against the thread pool; every file identical.
#   bench/scan_mpi.sh [build/bin/impactlab]
set -euo pipefail
exe=$(realpath "${1:-build/bin/impactlab}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
args=(scan --model A1C --x omega:8:14:12 --y xI:-0.004:0.004:64 --measure period,impacts,xrange)
points=$((12 * 64))
run() {   # label, then the command; prints wall seconds and points per second
  local label=$1; shift
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  t1=$(date +%s.%N)
  awk -v l="$label" -v a="$t0" -v b="$t1" -v n="$points" 'BEGIN { printf "%-28s %8.2f s %10.1f points/s\n", l, b - a, n / (b - a) }'
}
run "threads: 1" "$exe" "${args[@]}" --threads 1 --out t1.csv
run "threads: $(nproc)" "$exe" "${args[@]}" --threads "$(nproc)" --out tn.csv
for workers in 1 2 4; do
  run "mpirun -np $((workers + 1)) ($workers workers)" mpirun --allow-run-as-root --oversubscribe \
    --mca btl_vader_single_copy_mechanism none -np $((workers + 1)) "$exe" "${args[@]}" --out mpi$workers.csv
done
for f in tn.csv mpi1.csv mpi2.csv mpi4.csv; do cmp t1.csv "$f"; done
echo "all files identical to the 1-thread run"
