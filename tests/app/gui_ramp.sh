#!/bin/sh
# GUI test of the live omega ramp and the energy bar through --state-json, under Xvfb with Mesa:
#  1. --ramp 11:0.1 from omega = 9 at 20x: the ramp ends at 11 rad/s (the slider follows it), it collected
#     section points for the diagram, and the energy balance went on through it (t0 = 0) and closes.
#  2. --ramp 30:1e-3 runs on (active, omega between 9 and 30); Reset is not needed: a bad --ramp exits 2.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_ramp.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_ramp
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

run() {   # run NAME ARGS...: writes $dir/NAME.json
    run_name="$1"; shift
    gui_json "$run_name" --model A1H --omega 9 "$@"
}

run done --ramp 11:0.1 --speed 20 --frames 200
run going --ramp 30:0.001 --speed 1 --frames 30

"$gui" --ramp 11 --frames 2 >"$dir/bad.log" 2>&1
rc=$?
if [ $rc -ne 2 ] || ! grep -q -- "--ramp" "$dir/bad.log"; then
    cat "$dir/bad.log"; echo "gui_ramp: --ramp 11 (no rate) should exit 2 naming the flag, got $rc"; exit 1
fi

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)
fail = []
a = load("done")
r, e = a["ramp"], a["energy_balance"]
if r["active"]: fail.append(f"done: the ramp is still active at sim time {a['sim_time']}")
if abs(a["omega"] - 11.0) > 1e-6: fail.append(f"done: omega {a['omega']} after a ramp to 11")
if r["points"] < 10: fail.append(f"done: only {r['points']} section points on the ramp")
if e["t0"] != 0.0: fail.append(f"done: the energy balance restarted during the ramp (t0 = {e['t0']})")
flow = abs(e["E0"]) + abs(e["E"]) + e["work_unbalance"] + e["dissipated_resistance"] + e["dissipated_bumper"]
if not abs(e["residual"]) < 1e-5 * flow: fail.append(f"done: the energy balance is off by {e['residual']} J of {flow} J")
b = load("going")
if not b["ramp"]["active"]: fail.append("going: a ramp at 1e-3 rad/s per s ended within 30 frames")
if not 9.0 <= b["omega"] < 9.1: fail.append(f"going: omega {b['omega']} after 30 frames at 1e-3 rad/s per s")
for f in fail: print("gui_ramp:", f)
if fail: sys.exit(1)
print(f"gui_ramp: ok: ramp 9 -> 11 with {r['points']} section points; energy balance closes to {e['residual']:.2e} J of {flow:.3f} J")
PY
