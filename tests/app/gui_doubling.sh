#!/bin/sh
# GUI test of the Poincare map's period label across the first period doubling (10.8613 rad/s for A1H and
# A1G), through --state-json, under Xvfb with Mesa's software OpenGL. Below the doubling the period-1
# orbit's multiplier is negative (-0.55 at 10.3, -0.96 at 10.8) and the cart approaches it alternating:
# the map must say period 1, with every point in one cluster; above it period 2, in two clusters.
#  1. From rest after --warmup 300: A1H at 10.3, 10.8 (period 1), 11.2, 12.0 (period 2); A1G at 10.5, 10.7
#     (period 1), 11.2, 12.0 (period 2).
#  2. After a live omega change half-way (--then-omega, as the arrow keys: no reset), both ways across it.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_doubling.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_doubling
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

for case in A1H:10.3 A1H:10.8 A1H:11.2 A1H:12.0 A1G:10.5 A1G:10.7 A1G:11.2 A1G:12.0; do
    m=${case%:*}; w=${case#*:}
    gui_json "rest_${m}_$w" --model "$m" --omega "$w" --warmup 300 --frames 120
done
for case in A1H:11.6:10.8 A1H:10.3:12.0 A1G:11.6:10.5 A1G:10.3:11.2; do
    m=${case%%:*}; rest=${case#*:}; w0=${rest%:*}; w1=${rest#*:}
    gui_json "live_${m}_$w1" --model "$m" --omega "$w0" --warmup 100 --speed 100 --frames 600 --then-omega "$w1"
done

python3 - "$dir" <<'PY'
import glob, json, os, sys
d = sys.argv[1]
fail = []
for path in sorted(glob.glob(f"{d}/*.json")):
    name = os.path.basename(path)[:-5]
    with open(path) as f:
        j = json.load(f)
    _, model, w = name.split("_")
    want = 1 if float(w) < 10.8613 else 2
    if j["model"] != model or abs(j["omega"] - float(w)) > 1e-9:
        fail.append(f"{name}: model {j['model']} at {j['omega']}, expected {model} at {w}")
    if j["poincare_period"] != want:
        fail.append(f"{name}: the label says period {j['poincare_period']} ({j['poincare_status']}), expected {want}")
        continue
    tx, tv = j["poincare_tol"]
    centres = []
    for x, v in j["poincare_points"]:
        if not any(abs(x - cx) <= 2 * tx and abs(v - cv) <= 2 * tv for cx, cv in centres):
            centres.append((x, v))
    if len(centres) != want:
        fail.append(f"{name}: {len(j['poincare_points'])} points in {len(centres)} clusters, expected {want}: {centres[:4]}")
for f in fail:
    print("gui_doubling: FAIL:", f)
if fail:
    sys.exit(1)
print("gui_doubling: passed (period 1 below 10.8613, period 2 above, from rest and after a live change)")
PY
