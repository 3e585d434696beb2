#!/bin/sh
# GUI test of the companion cart, the grazing monitor and the mouse's state through
# --state-json, under Xvfb with Mesa's software OpenGL:
#  1. --twin on A1H's chaos preset: the twin starts 1 um from the cart and the two part by orders of
#     magnitude (the separation grows past 1 mm);
#  2. --twin on the period-1 preset: the separation never grows (both settle on the same orbit);
#  3. --ghost A1G on A1C's chaos: the ghost runs A1G from the cart's state and the two part;
#  4. the grazing monitor on the period-1 orbit: clear of the bumper, xI - max x > 1 mm, no impact; in
#     A1G's chaos: impacts with v- > 0 and max x = xI;
#  5. --set-state beyond the rigid bumper is put on it (x = xI) with a message saying so;
#  6. the bumper moved 18 mm into the cart at once (--then-xI, as the slider) pushes
#     it continuously (no jump of x between two samples over 0.3 mm; before: the whole way in one), and the
#     cart pressed onto the compliant bumper reads "on the compliant bumper" (the rig's badge and the
#     status bar share that label);
#  7. bad --ghost and --set-state values exit 2 naming the flag.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_companion.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_companion
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

run() { gui_json "$@"; }   # run NAME ARGS...: writes $dir/NAME.json

run twin_chaos --model A1H --preset 3 --twin --speed 100 --frames 40
run twin_calm --model A1H --preset 1 --twin --speed 100 --frames 40
run ghost --model A1C --preset 3 --ghost A1G --speed 100 --frames 40
run graze_rigid --model A1G --preset 3 --speed 100 --frames 40
run beyond --model A1H --preset 1 --set-state 0.005,0 --paused --frames 10
run pressed --model A1C --preset 1 --then-xI -0.018 --speed 2 --frames 90

fail=0
for flag in "--ghost Z9" "--set-state 0.01" "--set-state 0.01,fast" "--twin --ghost A1G"; do
    # shellcheck disable=SC2086
    out=$("$gui" $flag 2>&1); rc=$?
    first=${flag%% *}
    if [ $rc -ne 2 ] || ! printf '%s' "$out" | grep -q -- "$first"; then
        echo "gui_companion: '$flag' gave exit $rc and '$out', expected 2 and a message naming $first"
        fail=1
    fi
done
grep -q "beyond the bumper" "$dir/beyond.log" || { echo "gui_companion: beyond: no message about the bumper"; fail=1; }

python3 - "$dir" <<'PY' || fail=1
import json, math, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)
fail = []

j = load("twin_chaos")
c = j["companion"]
if c["mode"] != "twin":
    fail.append(f"twin_chaos: companion mode {c['mode']}")
elif not (0.5e-6 < c["separation_start"] < 2e-6 and c["separation_max"] > 1e-3):
    fail.append(f"twin_chaos: the twin should start 1 um away and part past 1 mm: start {c['separation_start']}, "
                f"max {c['separation_max']}")
else:
    print(f"twin_chaos: |dx| from {c['separation_start']:.2e} m to {c['separation_max']:.2e} m "
          f"({math.log10(c['separation_max'] / c['separation_start']):.1f} decades) in {j['sim_time']:.0f} s")

j = load("twin_calm")
c = j["companion"]
if not (c["mode"] == "twin" and 0 < c["separation_start"] < 2e-6 and c["separation_max"] < 1e-5
        and c["separation"] <= c["separation_start"]):
    fail.append(f"twin_calm: on period 1 the twin should not part: {c}")
else:
    print(f"twin_calm: |dx| from {c['separation_start']:.2e} m to {c['separation']:.2e} m (max {c['separation_max']:.2e})")

j = load("ghost")
c = j["companion"]
if not (c["mode"] == "ghost" and c["model"] == "A1G" and c["separation_start"] < 1e-9 and c["separation_max"] > 1e-4):
    fail.append(f"ghost: A1G from the cart's state should part from A1C: {c}")

g = load("twin_calm")["grazing"]
if g is None or not (g["distance"] > 1e-3 and g["impacts"] == 0 and g["impact_velocity"] is None):
    fail.append(f"graze (period 1): expected clear of the bumper by > 1 mm, no impact: {g}")
j = load("graze_rigid")
g = j["grazing"]
if g is None:
    fail.append("graze_rigid: no grazing monitor values")
elif g["impacts"] > 0 and not (g["impact_velocity"] > 0 and abs(g["x_max"] - j["xI"]) < 1e-9 and abs(g["distance"]) < 1e-9):
    fail.append(f"graze_rigid: an impacting period should touch x_I with v- > 0: {g}")
elif g["impacts"] == 0 and not g["distance"] >= -1e-12:
    fail.append(f"graze_rigid: a period without impact should stay clear: {g}")

j = load("beyond")
if not (abs(j["x"] - j["xI"]) < 1e-12 and j["v"] == 0):
    fail.append(f"beyond: --set-state 0.005,0 past x_I = {j['xI']} should put the cart on the bumper: x {j['x']}, v {j['v']}")

j = load("pressed")
if j["regime_label"] != "I  on the compliant bumper":
    fail.append(f"pressed: the label says '{j['regime_label']}' for a cart pressed onto the compliant bumper")
if not (abs(j["xI"] + 0.018) < 1e-12 and abs(j["x"] + 0.018) < 1e-4 and j["x_max_step"] < 3e-4):
    fail.append(f"pressed: the bumper at x_I = {j['xI']} should have pushed the cart to it without a jump: "
                f"x {j['x']}, largest step of x(t) {j['x_max_step']} m")
else:
    print(f"pressed: the bumper pushed the cart 18 mm, largest step of x(t) {j['x_max_step'] * 1e3:.2f} mm")

for f in fail:
    print("gui_companion:", f)
sys.exit(1 if fail else 0)
PY
[ $fail -eq 0 ] && echo "gui_companion: ok"
exit $fail
