#!/bin/sh
# The bifurcation diagram over xI (--bif-over xI, the view's "over" combo): A1H at omega = 18 rad/s, the bumper
# moved from -5 to +5 mm in 8 levels. --state-json's `diagram` must say over = "xI" at omega 18 with the range
# asked for, and each level's xI and least and greatest x must be those of `impactlab bifurcation --over xI`
# for the same sweep (the same core function: equal to the CSV's 10 digits), and each level's verdict the
# CLI's period column: both judge a level with up to 10 more records (--bif-settle, --settle), and this sweep
# has levels that do not settle (drawn grey, counted in `not_settled`). The y range also holds a continued
# branch drawn outside the points' fit (A1G over 1-3 rad/s: the cart stays at the hilltop, the branch from
# the left well lies 1.5 cm below). Bad --bif-over or --bif-range values exit 2 naming the flag.
# Exit 77 (CTest's skip code) without xvfb-run or python3.
# usage: gui_diagram_over.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_diagram_over
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json xi --model A1H --omega 18 --bifurcation cf-up --bif-over xI --bif-range -0.005:0.005 --bif-steps 10 --frames 10 \
    --screenshot "$dir/xi.png"
"$cli" bifurcation --model A1H --sweep up --over xI --range -0.005:0.005 --omega 18 --steps 10 --out "$dir/cli.csv" \
    >"$dir/cli.log" 2>&1 || { cat "$dir/cli.log"; echo "$TEST: impactlab bifurcation --over xI failed"; exit 1; }
gui_json branch --model A1G --omega 2 --bifurcation cf-up --bif-range 1:3 --bif-steps 10 --continuation --frames 10
for bad in "--bif-over xi" "--bif-over xI --bif-range -0.2:0.01" "--bif-over m0e --bif-range 0:0.03" \
           "--bif-over xI --bifurcation ef"; do
    # shellcheck disable=SC2086
    "$gui" $bad --frames 2 >"$dir/bad.log" 2>&1
    rc=$?
    flag=${bad%% *}
    case "$bad" in *--bif-range*) flag=--bif-range ;; *ef) flag=--bifurcation ;; esac
    if [ $rc -ne 2 ] || ! grep -q -- "$flag" "$dir/bad.log"; then
        cat "$dir/bad.log"; echo "$TEST: '$bad' should exit 2 naming $flag, got $rc"; exit 1
    fi
done

python3 - "$dir" <<'PY'
import csv, json, sys
d = sys.argv[1]
g = json.load(open(f"{d}/xi.json"))["diagram"]
rows = list(csv.DictReader(open(f"{d}/cli.csv")))
fail = []
if g["over"] != "xI" or g["omega"] != 18 or g["lo"] != -0.005 or g["hi"] != 0.005 or g["running"]:
    fail.append(f"over {g['over']}, omega {g['omega']}, range {g['lo']}..{g['hi']}, running {g['running']}")
if g["levels_done"] != 10 or g["points"] != len(rows) or g["view_omega"] != [-0.005, 0.005]:
    fail.append(f"{g['levels_done']} levels, {g['points']} points (the CLI's {len(rows)}), view {g['view_omega']}")
levels = []
for r in rows:
    at, x = float(r["xI"]), float(r["x"])
    if not levels or levels[-1][0] != at:
        levels.append([at, x, x, int(r["period"])])
    levels[-1][1] = min(levels[-1][1], x)
    levels[-1][2] = max(levels[-1][2], x)
# The CSV holds 10 significant digits: equal to them.
close = lambda a, b: abs(a - b) <= 1e-9 * max(abs(a), abs(b)) + 1e-15
if len(g["level_x"]) != len(levels) or not all(close(a, b) for gl, cl in zip(g["level_x"], levels) for a, b in zip(gl[:3], cl[:3])):
    fail.append(f"levels: the GUI's {g['level_x']} are not the CLI's {levels}")
if [gl[3] for gl in g["level_x"]] != [cl[3] for cl in levels]:
    fail.append(f"verdicts: the GUI's {[gl[3] for gl in g['level_x']]}, the CLI's {[cl[3] for cl in levels]}")
unsettled = sum(cl[3] == -1 for cl in levels)
if g["settle"] != 10 or g["not_settled"] != unsettled or unsettled == 0:
    fail.append(f"settle {g['settle']}, {g['not_settled']} levels not settled (the CLI's {unsettled}; none: no test)")
b = json.load(open(f"{d}/branch.json"))
bd, cont = b["diagram"], b["continuation"]
if not cont or cont["curves"] < 1 or cont["x_range"] is None:
    fail.append(f"no continued branch: {cont}")
else:
    lo, hi = cont["x_range"]
    pts = [v for l in bd["level_x"] for v in l[1:3]]
    vy = bd["view_y"]
    # The branch lies outside the points' own fit (else this would test nothing), and the view holds both.
    if min(pts) <= lo and max(pts) >= hi:
        fail.append(f"the branch {cont['x_range']} lies within the points' x {min(pts)}..{max(pts)}: no test")
    if not (vy[0] <= min(lo, min(pts)) and vy[1] >= max(hi, max(pts))):
        fail.append(f"the view's y {vy} does not hold the branch {cont['x_range']} and the points {min(pts)}..{max(pts)}")
for f in fail:
    print(f"gui_diagram_over: {f}")
if fail:
    sys.exit(1)
print("gui_diagram_over: passed")
PY
