#!/bin/sh
# The continued branches over the diagram are the CLI's: impactlab-gui --continuation (the diagram's range,
# 0.5..25 rad/s) reports the overlay's special points through --state-json, and `impactlab continue` over
# the same range must give the same points (kind, period, omega to 1e-9). Among them, for A1G: the first
# doubling 10.8613, the period-2 fold 12.8306 and grazing 12.7993, and no doubling between 12 and 13.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_continuation.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_continuation
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json overlay --model A1G --omega 12 --continuation --frames 5
"$cli" continue --model A1G --omega-min 0.5 --omega-max 25 --out "$dir/cli" >"$dir/cli.log" 2>&1 ||
    { cat "$dir/cli.log"; echo "$TEST: impactlab continue failed"; exit 1; }

python3 - "$dir" <<'PY'
import csv, json, sys
d = sys.argv[1]
with open(f"{d}/overlay.json") as f:
    ov = json.load(f)["continuation"]
fail = []
if ov is None or ov["cancelled"] or ov["model"] != "A1G":
    fail.append(f"no finished A1G overlay: {ov}")
    gui = []
else:
    gui = [(p["kind"], p["period"], p["omega"]) for p in ov["points"]]
with open(f"{d}/cli/points.csv") as f:
    cli = [(r["kind"], int(r["period"]), float(r["omega"])) for r in csv.DictReader(f)]
if len(gui) != len(cli):
    fail.append(f"the overlay has {len(gui)} points, the CLI {len(cli)}")
for (gk, gp, gw), (ck, cp, cw) in zip(sorted(gui), sorted(cli)):
    if gk != ck or gp != cp or abs(gw - cw) > 1e-6 * max(1.0, abs(cw)):
        fail.append(f"overlay {gk} period {gp} at {gw} vs CLI {ck} period {cp} at {cw}")
def has(kind, period, w, tol):
    return any(k == kind and p == period and abs(x - w) < tol for k, p, x in gui)
for kind, period, w in (("period_doubling", 1, 10.8613), ("fold", 2, 12.8306), ("grazing", 2, 12.7993)):
    if not has(kind, period, w, 1e-4):
        fail.append(f"no {kind} of period {period} at {w} in the overlay: {gui}")
if any(k == "period_doubling" and 12.0 < x < 13.0 for k, p, x in gui):
    fail.append(f"a period doubling between 12 and 13 in the overlay: {gui}")
for f in fail:
    print("gui_continuation: FAIL:", f)
if fail:
    sys.exit(1)
print(f"gui_continuation: passed ({len(gui)} special points, the same as the CLI's)")
PY
