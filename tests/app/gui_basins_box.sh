#!/bin/sh
# Basins over a box of the user's (a right-drag on the basins, or --basins-box): A1G at 13 rad/s over
# x0 in [-22, -10] mm, v0 in [-0.15, 0.05] m/s, the tile's 80 x 80 grid. --state-json's `basins` must hold
# that box and grid, and the same attractors with the same cells as `impactlab basins --grid 80 --x-range
# -0.022:-0.01 --v-range -0.15:0.05` (the core's compute_basins both): the impacting period-1 orbit and the
# chaos, about half each. An empty box exits 2 naming the flag. Exit 77 (CTest's skip code) without xvfb-run
# or python3.
# usage: gui_basins_box.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_basins_box
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json box --model A1G --omega 13 --basins-box -0.022:-0.01:-0.15:0.05 --frames 5 --screenshot "$dir/box.png"
"$cli" basins --model A1G --omega 13 --grid 80 --x-range -0.022:-0.01 --v-range -0.15:0.05 --threads 2 \
    --out "$dir/cli.csv" >"$dir/cli.txt" 2>"$dir/cli.log" || { cat "$dir/cli.log"; echo "$TEST: impactlab basins failed"; exit 1; }
"$gui" --basins-box -0.01:-0.02:0:1 --frames 2 >"$dir/bad.log" 2>&1
rc=$?
if [ $rc -ne 2 ] || ! grep -q -- "--basins-box" "$dir/bad.log"; then
    cat "$dir/bad.log"; echo "$TEST: an empty box should exit 2 naming the flag, got $rc"; exit 1
fi

python3 - "$dir" <<'PY'
import csv, json, sys
d = sys.argv[1]
b = json.load(open(f"{d}/box.json"))["basins"]
fail = []
if not b["computed"] or b["cancelled"] or b["x_range"] != [-0.022, -0.01] or b["v_range"] != [-0.15, 0.05] \
        or (b["nx"], b["nv"]) != (80, 80) or b["omega"] != 13:
    fail.append(f"the box: {b}")
gui = sorted((a["kind"], a["period"], a["cells"]) for a in b.get("attractors", []))
with open(f"{d}/cli.txt") as f:
    cli = sorted((r["kind"], int(r["period"]), int(r["cells"])) for r in csv.DictReader(f))
if gui != cli:
    fail.append(f"the GUI's attractors {gui} are not the CLI's {cli}")
if [k for k, _, _ in gui] != ["chaos", "period"] or min(c for _, _, c in gui) < 0.3 * 6400:
    fail.append(f"not the period-1 orbit and the chaos, about half each: {gui}")
for f in fail:
    print("gui_basins_box:", f)
if fail:
    sys.exit(1)
print(f"gui_basins_box: passed ({gui})")
PY
