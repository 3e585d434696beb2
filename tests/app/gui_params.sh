#!/bin/sh
# GUI test of the Parameters panel through --param and --state-json, under Xvfb with Mesa:
#  1. A1H at omega = 9 without the unbalance (--param m0e=0): the panel's values say so (edited), and the
#     simulation took it: the cart comes to rest in its well (|v| < 1e-3 m/s now and at the last section),
#     where the same run with the paper's values keeps its period-1 orbit (|v| at the section > 5e-3 m/s).
#  2. An edited k and the compliant law's kI are reported back; the panel opens with --show-params.
#  3. A value validate() refuses, or a key the law does not have, exits 2 naming --param and the key.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_params.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_params
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json still --model A1H --omega 9 --param m0e=0 --warmup 40 --speed 20 --frames 30
gui_json paper --model A1H --omega 9 --warmup 40 --speed 20 --frames 30
gui_json edited --model A1C --omega 12 --param k=1300 --param kI=2e6 --show-params --frames 10 --screenshot "$dir/panel.png"

for bad in "m=-1" "kappa0=0.5" "k" "no_such=1"; do
    "$gui" --model A1C --param "$bad" --frames 2 >"$dir/bad.log" 2>&1
    rc=$?
    if [ $rc -ne 2 ] || ! grep -q -- "--param" "$dir/bad.log"; then
        cat "$dir/bad.log"; echo "gui_params: --param $bad should exit 2 naming the flag, got $rc"; exit 1
    fi
done

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)
fail = []
s, p, e = load("still"), load("paper"), load("edited")
if s["params"]["m0e"] != 0 or not s["params_edited"]: fail.append(f"still: params {s['params']}, edited {s['params_edited']}")
if abs(s["v"]) >= 1e-3: fail.append(f"still: v = {s['v']} m/s: the cart is not at rest without the unbalance")
pts = s["poincare_points"]
if not pts or abs(pts[-1][1]) >= 1e-3: fail.append(f"still: the last section point {pts[-1:]} is not at rest")
if p["params_edited"] or p["params"]["m0e"] <= 0: fail.append(f"paper: params {p['params']}, edited {p['params_edited']}")
pp = p["poincare_points"]
if not pp or abs(pp[-1][1]) <= 5e-3: fail.append(f"paper: the last section point {pp[-1:]} is at rest: the control run proves nothing")
if e["params"]["k"] != 1300 or e["params"]["kI"] != 2e6 or not e["params_edited"]: fail.append(f"edited: {e['params']}")
for f in fail:
    print("gui_params:", f)
if fail:
    sys.exit(1)
print("gui_params: passed")
PY
