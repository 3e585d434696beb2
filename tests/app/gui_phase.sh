#!/bin/sh
# GUI test of the Poincare section's phase (--phi0, --then-phi0) through --state-json, under Xvfb with Mesa,
# against the CLI's section at the same phase. A1H at 9 rad/s from x0 = -11 mm settles on a period-1 orbit:
#  1. --phi0 pi/2 from the start: the state reports the phase, the newest section point lies at phi = pi/2
#     mod 2 pi, and every settled point on the map is `impactlab poincare --phi0 pi/2`'s fixed point (within
#     1 um, 1e-5 m/s), millimetres away from the one at phi0 = 0.
#  2. --then-phi0 3 half-way, live through the simulation thread: a new epoch, and the map holds only points
#     of the new section (each within 1 um of the CLI's at 3 rad), none of the old one.
#  3. A session saved with --phi0 1 restores it.
#  4. --phi0 outside [0, 2 pi], not a number, or --then-phi0 without --frames exit 2 naming the flag.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_phase.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_phase
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"
start="--model A1H --omega 9 --x0 -0.011"

for phi0 in 0 1.5707963267948966 3; do
    # shellcheck disable=SC2086
    "$cli" poincare $start --periods 3 --transient 400 --phi0 $phi0 --out "$dir/cli_$phi0.csv" 2>"$dir/cli.log" ||
        { cat "$dir/cli.log"; echo "$TEST: impactlab poincare --phi0 $phi0 failed"; exit 1; }
done
# shellcheck disable=SC2086
gui_json quarter $start --phi0 1.5707963267948966 --speed 100 --frames 300 --screenshot "$dir/quarter.png"
# shellcheck disable=SC2086
gui_json live $start --speed 100 --frames 600 --then-phi0 3
# shellcheck disable=SC2086
gui_json saved $start --phi0 1 --speed 20 --frames 20 --save-session "$dir/s.json"
gui_json restored --session "$dir/s.json" --frames 20

gui_refuses --phi0 --phi0 7
gui_refuses --phi0 --phi0 -0.1
gui_refuses --phi0 --phi0 90deg
gui_refuses --then-phi0 --then-phi0 1

python3 - "$dir" <<'PY'
import csv, json, math, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)
def cli(phi0):
    with open(f"{d}/cli_{phi0}.csv") as f:
        row = list(csv.DictReader(f))[-1]
    return float(row["x"]), float(row["v"])
fail = []

def on_section(name, j, phi0, ref):
    if j["poincare_phi0"] is None or abs(j["poincare_phi0"] - phi0) > 1e-12:
        fail.append(f"{name}: poincare_phi0 {j['poincare_phi0']}, expected {phi0}")
    last = j["poincare_last_section"]
    if last is None or abs(last["phi_mod"] - phi0) > 1e-6:
        fail.append(f"{name}: the newest section is at phi mod 2 pi = {last and last['phi_mod']}, expected {phi0}")
    pts = j["poincare_points"]
    if j["poincare_period"] != 1 or not pts:
        fail.append(f"{name}: period {j['poincare_period']} with {len(pts)} points, expected period 1")
    worst = max((max(abs(x - ref[0]) / 1e-6, abs(v - ref[1]) / 1e-5) for x, v in pts), default=math.inf)
    if worst > 1:
        fail.append(f"{name}: a map point is off the CLI's section at phi0 = {phi0} {ref} by {worst:.3g} tolerances: {pts[:3]}")
    print(f"{name}: {len(pts)} points at phi0 = {phi0}, within {worst:.2g} of the tolerances of the CLI's {ref}")

q = cli("1.5707963267948966")
z = cli("0")
on_section("quarter", load("quarter"), math.pi / 2, q)
if abs(q[0] - z[0]) < 1e-3:
    fail.append(f"the CLI's sections at pi/2 {q} and 0 {z} are not millimetres apart: the test would not see a mix")

live = load("live")
on_section("live", live, 3.0, cli("3"))
if live["epoch"] < 1:
    fail.append(f"live: epoch {live['epoch']}: the phase change did not start a new one")

for name in ("saved", "restored"):
    j = load(name)
    if abs(j["poincare_phi0"] - 1.0) > 1e-12:
        fail.append(f"{name}: poincare_phi0 {j['poincare_phi0']}, expected 1")
with open(f"{d}/s.json") as f:
    s = json.load(f)
if s["view"].get("poincare_phi0") != 1.0:
    fail.append(f"the session's view has poincare_phi0 {s['view'].get('poincare_phi0')}, expected 1")

for x in fail:
    print("gui_phase:", x)
if fail:
    sys.exit(1)
print("gui_phase: passed")
PY
