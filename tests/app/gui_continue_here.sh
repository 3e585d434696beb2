#!/bin/sh
# Continuation from the running orbit: A1G's preset 4 runs its wide period-1 window at 14.5 rad/s (the cart
# far in the left well, amid the chaos; the branch from the left well's bottom never reaches it).
# --continue-here waits for the Poincare map to settle, then continues the orbit through its newest section
# point over the diagram's range; --state-json's `continuation` must name that start (period 1 at
# omega = 14.5) and list the same special points (kind, period, omega to 1e-6) as `impactlab continue
# --omega-start 14.5 --from X,V --period 1` from the same point, with a period-1 fold on each side of 14.5
# rad/s (the window's two ends, 11.96 and 18.32). In chaos (A1G at 18 rad/s from rest, a map that has said
# chaos for 60 s of simulated time) it exits 1 naming the flag. Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_continue_here.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_continue_here
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json here --model A1G --preset 4 --warmup 100 --continue-here --frames 5 --screenshot "$dir/here.png"
from=$(python3 -c "import json,sys; o=json.load(open(sys.argv[1]))['continuation']['from_orbit']; print(f\"{o['x']!r},{o['v']!r}\")" \
       "$dir/here.json") || { echo "$TEST: no from_orbit in the state"; exit 1; }
"$cli" continue --model A1G --omega-min 0.5 --omega-max 25 --omega-start 14.5 --from "$from" --period 1 --out "$dir/cli" \
    >"$dir/cli.log" 2>&1 || { cat "$dir/cli.log"; echo "$TEST: impactlab continue failed"; exit 1; }

gui_exec chaos --model A1G --omega 18 --warmup 200 --speed 100 --continue-here --frames 5
if [ $rc -ne 1 ] || ! grep -q -- "--continue-here" "$dir/chaos.log"; then
    cat "$dir/chaos.log"; echo "$TEST: in chaos --continue-here should exit 1 naming the flag, got $rc"; exit 1
fi

python3 - "$dir" <<'PY'
import csv, json, sys
d = sys.argv[1]
with open(f"{d}/here.json") as f:
    ov = json.load(f)["continuation"]
fail = []
o = ov["from_orbit"]
if ov["cancelled"] or ov["model"] != "A1G" or o["period"] != 1 or abs(o["omega"] - 14.5) > 1e-9:
    fail.append(f"the start: {o}, model {ov['model']}, cancelled {ov['cancelled']}")
gui = [(p["kind"], p["period"], p["omega"]) for p in ov["points"]]
with open(f"{d}/cli/points.csv") as f:
    cli = [(r["kind"], int(r["period"]), float(r["omega"])) for r in csv.DictReader(f)]
if len(gui) != len(cli):
    fail.append(f"the overlay has {len(gui)} points, the CLI {len(cli)}: {gui} / {cli}")
for (gk, gp, gw), (ck, cp, cw) in zip(sorted(gui), sorted(cli)):
    if gk != ck or gp != cp or abs(gw - cw) > 1e-6 * max(1.0, abs(cw)):
        fail.append(f"overlay {gk} period {gp} at {gw} vs CLI {ck} period {cp} at {cw}")
for w0 in (11.9604, 18.3212):
    if not any(k == "fold" and p == 1 and abs(w - w0) < 1e-3 for k, p, w in gui):
        fail.append(f"no period-1 fold at {w0} rad/s: {gui}")
for f in fail:
    print("gui_continue_here: FAIL:", f)
if fail:
    sys.exit(1)
print(f"gui_continue_here: passed ({len(gui)} special points, the same as the CLI's; ends: {ov['end']})")
PY
