#!/bin/sh
# The bifurcation diagram over v as well as x (--bif-y v, the diagram's x | v combo): A1H's CF sweep over
# 8 - 12 rad/s, 40 levels. --state-json's `diagram` must say y = "v" with its view fitted to the section
# points' v as `impactlab bifurcation` writes them for the same sweep (the CSV's v column; the view pads the
# points' span by 6 % each side), and a diagram of x must fit x's instead. --bif-y q exits 2 naming the flag.
# Exit 77 (CTest's skip code) without xvfb-run or python3.
# usage: gui_diagram_v.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_diagram_v
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json v --model A1H --bifurcation cf-up --bif-range 8:12 --bif-steps 40 --bif-y v --frames 10 --screenshot "$dir/v.png"
gui_json x --model A1H --bifurcation cf-up --bif-range 8:12 --bif-steps 40 --frames 10
"$cli" bifurcation --model A1H --sweep up --omega-min 8 --omega-max 12 --steps 40 --out "$dir/cli.csv" >"$dir/cli.log" 2>&1 ||
    { cat "$dir/cli.log"; echo "$TEST: impactlab bifurcation failed"; exit 1; }
"$gui" --bif-y q --frames 2 >"$dir/bad.log" 2>&1
rc=$?
if [ $rc -ne 2 ] || ! grep -q -- "--bif-y" "$dir/bad.log"; then
    cat "$dir/bad.log"; echo "$TEST: --bif-y q should exit 2 naming the flag, got $rc"; exit 1
fi

python3 - "$dir" <<'PY'
import csv, json, sys
d = sys.argv[1]
dv, dx = (json.load(open(f"{d}/{n}.json"))["diagram"] for n in ("v", "x"))
rows = list(csv.DictReader(open(f"{d}/cli.csv")))
fail = []
def fitted(view, values, what):
    lo, hi = min(values), max(values)
    pad = 0.06 * max(hi - lo, 1e-3)
    if abs(view[0] - (lo - pad)) > 0.02 * (hi - lo) + 1e-9 or abs(view[1] - (hi + pad)) > 0.02 * (hi - lo) + 1e-9:
        fail.append(f"{what}: the view {view} is not the CLI's {what} [{lo}, {hi}] padded by {pad}")
for dd, q in ((dv, "v"), (dx, "x")):
    if dd["y"] != q or dd["running"] or dd["levels_done"] != 40 or dd["points"] != len(rows):
        fail.append(f"{q}: {dd['y']}, running {dd['running']}, {dd['levels_done']} levels, {dd['points']} points "
                    f"(the CLI's {len(rows)})")
    fitted(dd["view_y"], [float(r[q]) for r in rows], q)
for f in fail:
    print("gui_diagram_v:", f)
if fail:
    sys.exit(1)
print("gui_diagram_v: passed")
PY
