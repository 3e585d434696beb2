#!/bin/sh
# What the Poincare view tells a class is what the core finds, on both sides of every bifurcation the core's
# continuation reports for A1G, A1H and A3C (rigid, rigid with an impact duration, compliant) over 5..25
# rad/s (period doublings, folds, grazings), not only at the presets. At omega = omega* -/+ 0.05 rad/s the GUI runs from its default start with --warmup 300, and its
# label is checked against the core from the GUI's own last section point:
#  - period k: `impactlab orbit --period k` converges to a stable orbit within 2 tolerances of the GUI's
#    points; the points do not recur after any proper divisor of k (k is the least period); one cycle of
#    the map's impact counts sums to the orbit's impacts per period;
#  - chaos: `impactlab lyapunov` from that point gives lambda_max > 0;
#  - still settling after the warm-up fails: the label must have been decided.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_bifurcations.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_bifurcations
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
rm -rf "$dir"
mkdir -p "$dir/labels"

for m in A1G A1H A3C; do
    "$cli" continue --model "$m" --omega-min 5 --omega-max 25 --out "$dir/$m" >"$dir/$m.log" 2>&1 ||
        { cat "$dir/$m.log"; echo "$TEST: impactlab continue --model $m failed"; exit 1; }
    omegas=$(python3 - "$dir/$m/points.csv" <<'PY'
import csv, sys
ws = set()
for row in csv.DictReader(open(sys.argv[1])):
    for s in (-0.05, 0.05):
        w = round(float(row["omega"]) + s, 4)
        if 0.5 <= w <= 25: ws.add(w)
print(" ".join(str(w) for w in sorted(ws)))
PY
)
    [ -n "$omegas" ] || { echo "$TEST: $m: the continuation reported no special point"; exit 1; }
    for w in $omegas; do
        gui_json "labels/${m}_$w" --model "$m" --omega "$w" --warmup 300 --frames 30
    done
done

python3 - "$cli" "$dir" <<'PY'
import glob, json, os, re, subprocess, sys
cli, d = sys.argv[1], sys.argv[2]
fail, seen = [], 0
for path in sorted(glob.glob(f"{d}/labels/*.json")):
    name = os.path.basename(path)[:-5]
    model, w = name.split("_")
    j = json.load(open(path))
    k, pts, imp = j["poincare_period"], j["poincare_points"], j["poincare_impacts"]
    tx, tv = j["poincare_tol"]
    seen += 1
    if k is None or k < 0 or not pts:
        fail.append(f"{name}: still {j['poincare_status']} after the warm-up")
        continue
    x0, v0 = pts[-1]
    if k > 0:
        def gap(dd):   # the points' largest miss after dd periods, in tolerances
            return max(max(abs(pts[i][0] - pts[i - dd][0]) / tx, abs(pts[i][1] - pts[i - dd][1]) / tv)
                       for i in range(dd, len(pts)))
        least = len(pts) >= 2 * k and all(gap(dd) > 2 for dd in range(1, k) if k % dd == 0)
        r = subprocess.run([cli, "orbit", "--model", model, "--omega", w, "--period", str(k), "--from", f"{x0},{v0}",
                            "--out", f"{d}/labels/{name}_orbit.csv"], capture_output=True, text=True)
        m = re.search(r"section point: x = (\S+) m, v = (\S+) m/s", r.stdout)
        mi = re.search(r"impacts per period-\d+: (\d+)", r.stdout)
        near = m is not None and any(abs(float(m.group(1)) - x) <= 2 * tx and abs(float(m.group(2)) - v) <= 2 * tv
                                     for x, v in pts)
        stable = "stable: yes" in r.stdout
        impacts_ok = mi is not None and sum(imp[-k:]) == int(mi.group(1))
        ok = r.returncode == 0 and near and stable and least and impacts_ok
        print(f"{name}: period {k}, impacts {sum(imp[-k:])}; core: {'stable' if stable else 'NOT stable'} orbit "
              f"{'at' if near else 'NOT at'} the points, impacts {mi.group(1) if mi else '?'}, least period "
              f"{'yes' if least else 'no'}: {'ok' if ok else 'WRONG'}")
        if not ok:
            fail.append(f"{name}: the label says period {k}; the core says: {(r.stdout + r.stderr).strip()}")
    else:
        r = subprocess.run([cli, "lyapunov", "--model", model, "--omega", w, "--x0", repr(x0), "--v0", repr(v0)],
                           capture_output=True, text=True)
        m = re.search(r"lambda_max = (\S+)", r.stdout)
        lam = float(m.group(1)) if m else float("nan")
        print(f"{name}: chaos; core lambda_max = {lam} 1/s: {'ok' if lam > 0 else 'WRONG'}")
        if not lam > 0:
            fail.append(f"{name}: the label says chaos, the core's lambda_max = {lam} 1/s ({r.stderr.strip()})")
for f in fail:
    print("gui_bifurcations: FAIL:", f)
if fail or seen < 20:
    sys.exit(1)
print(f"gui_bifurcations: passed ({seen} labels beside the core's bifurcations agree with its orbits and exponents)")
PY
