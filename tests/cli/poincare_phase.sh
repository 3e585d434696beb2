#!/usr/bin/env bash
# impactlab poincare --phi0: --phi0 0 and 2 pi write the default file byte for byte; at phi0 = pi/2 the
# section points are the trajectory `impactlab simulate` samples at phi = pi/2 + 2 pi k (omega = 4 pi rad/s,
# so the instants 0.125 s + 0.5 s k lie on its 0.125 s grid), and differ from those at phi0 = 0.
#   poincare_phase.sh IMPACTLAB
set -euo pipefail
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d "${TMPDIR:-/tmp}/impactlab_phase_test.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"
w=12.566370614359172
common=(--model A1H --omega "$w" --periods 20 --x0 -0.011)

"$exe" poincare "${common[@]}" --out default.csv 2>/dev/null
"$exe" poincare "${common[@]}" --phi0 0 --out zero.csv 2>/dev/null
"$exe" poincare "${common[@]}" --phi0 6.283185307179586 --out twopi.csv 2>/dev/null
cmp default.csv zero.csv || { echo "FAIL: --phi0 0 differs from the default"; exit 1; }
cmp default.csv twopi.csv || { echo "FAIL: --phi0 2 pi differs from the default"; exit 1; }

"$exe" poincare "${common[@]}" --phi0 1.5707963267948966 --out quarter.csv 2>/dev/null
"$exe" simulate --model A1H --omega "$w" --duration 10 --dt 0.125 --x0 -0.011 --out traj.csv 2>/dev/null
[[ $(wc -l <quarter.csv) -eq 21 ]] || { echo "FAIL: quarter.csv has $(wc -l <quarter.csv) lines, expected 21"; exit 1; }
# Row n of the section against the sample at t = 0.125 + 0.5 (n - 1), which simulate interpolates.
awk -F, 'NR == FNR { if (FNR > 1) { x[$1] = $2; v[$1] = $3 } next }
         FNR > 1 && ($1 - 0.125) % 0.5 == 0 {
           n = ($1 - 0.125) / 0.5 + 1
           if (n in x) {
             dx = $2 - x[n]; dv = $3 - v[n]; if (dx < 0) dx = -dx; if (dv < 0) dv = -dv
             if (dx > mx) mx = dx; if (dv > mv) mv = dv; c++
             if ($4 - 1.5707963267948966 - 6.283185307179586 * (n - 1) > 1e-6) bad_phi++
           }
         }
         END {
           printf "%d sections vs simulate: |dx| <= %g m, |dv| <= %g m/s\n", c, mx, mv
           if (c != 20 || mx > 1e-6 || mv > 1e-5 || bad_phi) { print "FAIL: the sections at phi0 = pi/2 are not the trajectory there"; exit 1 }
         }' quarter.csv traj.csv
# The sections at pi/2 are other points than those at 0 (a rising cart there, at 0 a falling one).
if cmp -s <(tail -n 5 default.csv | cut -d, -f2) <(tail -n 5 quarter.csv | cut -d, -f2); then
  echo "FAIL: the sections at phi0 = pi/2 are those at 0"
  exit 1
fi
echo "poincare --phi0: ok"
