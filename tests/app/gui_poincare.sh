#!/bin/sh
# GUI test of the Poincare map through --state-json, under Xvfb with Mesa's software OpenGL:
#  1. A1H from the default omega (period 1), then preset 2 half-way (as pressing key 2): the map must say
#     period 2, and every point on it must lie within 20 um / 0.2 mm/s of one of two distinct centres, so
#     nothing of the period-1 orbit or of the transient survived the change.
#  2. Preset 2 three frames after start at 1x: no section has recurred yet, so the map says "settling"
#     (poincare_period null) and shows no point.
#  3. Preset 3 (chaos) at 100x: poincare_period 0 and a map of many points; the potential plot's y range
#     holds the trail's largest energy.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_poincare.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_poincare
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

run() {   # run NAME ARGS...: writes $dir/NAME.json
    run_name="$1"; shift
    gui_json "$run_name" --model A1H "$@"
}

run change --speed 20 --frames 300 --then-preset 2
run settling --preset 2 --speed 1 --frames 3
run chaos --preset 3 --speed 100 --frames 150

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)
fail = []

j = load("change")
pts = j["poincare_points"]
if j["model"] != "A1H" or abs(j["omega"] - 12.0) > 1e-9:
    fail.append(f"change: model {j['model']} omega {j['omega']}, expected A1H at 12 rad/s (preset 2)")
if j["poincare_period"] != 2:
    fail.append(f"change: the label says period {j['poincare_period']}, expected 2")
centres = []
for x, v in pts:
    if not any(abs(x - cx) < 20e-6 and abs(v - cv) < 2e-4 for cx, cv in centres):
        centres.append((x, v))
if len(centres) != 2:
    fail.append(f"change: the {len(pts)} points on the map form {len(centres)} clusters, expected 2 "
                f"(a transient or period-1 point survived): {centres[:6]}")
elif abs(centres[0][0] - centres[1][0]) < 1e-3:
    fail.append(f"change: the two clusters are not distinct: {centres}")
if j["poincare_seen"] < len(pts) or j["sim_time"] <= 0 or not j["fps"] > 0:
    fail.append(f"change: inconsistent counts: seen {j['poincare_seen']}, points {len(pts)}, "
                f"sim_time {j['sim_time']}, fps {j['fps']}")

j = load("settling")
if j["poincare_period"] is not None or j["poincare_status"] != "settling" or j["poincare_points"]:
    fail.append(f"settling: period {j['poincare_period']} ({j['poincare_status']}) with "
                f"{len(j['poincare_points'])} points, expected null and none")

j = load("chaos")
if j["poincare_period"] != 0 or len(j["poincare_points"]) < 100:
    fail.append(f"chaos: period {j['poincare_period']} with {len(j['poincare_points'])} points, expected 0 and > 100")
# The potential plot's y range holds the largest energy of the trail (the old fixed
# limit, 2.3 times the wells' depth, was about 35 mJ; this orbit reaches past it).
lo, hi = j["potential_view"]
if not (lo < j["energy"] < hi and j["energy_max_trail"] < hi):
    fail.append(f"chaos: the potential plot shows {lo * 1e3:.1f}..{hi * 1e3:.1f} mJ, the energy is "
                f"{j['energy'] * 1e3:.1f} mJ now and up to {j['energy_max_trail'] * 1e3:.1f} mJ on the trail")

for f in fail:
    print("gui_poincare: FAIL:", f)
if fail:
    sys.exit(1)
print("gui_poincare: passed (period 2 after the change in 2 clusters, settling shows nothing, chaos is 0)")
PY
