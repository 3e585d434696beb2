#!/bin/sh
# The grazing and fold curves over the parameter plane, under Xvfb with Mesa, against the CLI's:
#  1. A1G at xI = -4 mm on a small (omega, xI from -7 to -3.5 mm) plane: --plane-grazing from the grazing
#     `continue` prints (9.6005 rad/s) and --plane-fold auto give the same points, bit for bit, as
#     `scan --grazing-from ... --fold-from auto --curves-out` (the same core functions), and the same start.
#  2. The fold curve's point nearest xI = -3.5 mm is where `continue` at that xI finds its fold (1e-5 rad/s).
#  3. A malformed start exits 2 naming the flag; --plane-fold without a plane exits 1 naming it.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_plane_curves.sh IMPACTLAB_GUI IMPACTLAB_CLI OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_plane_curves
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

graze=9.60049626,-0.0156163,-0.00744857
"$cli" scan --model A1G --xI -0.004 --x omega:8.5:10.5:5 --y xI:-0.007:-0.0035:8 --transient 2 --record 4 --threads 2 \
    --out "$dir/plane.csv" --png "$dir/plane.png" --grazing-from $graze --fold-from auto --curves-out "$dir/curves.csv" \
    2>"$dir/cli.log" || { cat "$dir/cli.log"; echo "$TEST: the scan failed"; exit 1; }
gui_json at4 --model A1G --xI -0.004 --plane "$dir/plane.csv" --plane-grazing $graze --plane-fold auto --frames 20 \
    --screenshot "$dir/curves.png"
# The fold curve's point nearest xI = -3.5 mm, for `continue` there.
near=$(python3 -c 'import json, sys
pts = json.load(open(sys.argv[1]))["plane"]["fold"]["points"]
print("%.17g %.17g" % tuple(min(pts, key=lambda p: abs(p[1] + 0.0035))))' "$dir/at4.json") || { echo "$TEST: no fold curve"; exit 1; }
set -- $near
"$cli" continue --model A1G --xI "$2" --omega-min 8.5 --omega-max 10.5 --max-period 1 --out "$dir/cont.csv" \
    >"$dir/cont.log" 2>&1 || { cat "$dir/cont.log"; echo "$TEST: continue failed"; exit 1; }

gui_exec bad --model A1G --plane "$dir/plane.csv" --plane-grazing 9.6,abc --frames 5
if [ $rc -ne 2 ] || ! grep -q -- "--plane-grazing: '9.6,abc'" "$dir/bad.log"; then
    cat "$dir/bad.log"; echo "$TEST: a malformed --plane-grazing should exit 2 naming the flag, got $rc"; exit 1
fi
gui_exec noplane --model A1G --plane-fold auto --frames 5
if [ $rc -ne 1 ] || ! grep -q -- "--plane-fold: no plane" "$dir/noplane.log"; then
    cat "$dir/noplane.log"; echo "$TEST: --plane-fold without a plane should exit 1 naming the flag, got $rc"; exit 1
fi

python3 - "$dir" <<'PY'
import csv, json, re, sys
d = sys.argv[1]
fail = []
cli = {}
with open(f"{d}/curves.csv") as f:
    for r in csv.DictReader(f):
        cli.setdefault(r["curve"], []).append([float(r["omega"]), float(r["xI"])])
log = open(f"{d}/cli.log").read()
with open(f"{d}/at4.json") as f:
    p = json.load(f)["plane"]
for kind, start in (("grazing", "9.60049626,-0.0156163,-0.00744857,1"), ("fold", "auto")):
    g = p[kind]
    if not g:
        fail.append(f"{kind}: no curve in the state")
        continue
    if g["start"] != start or g["model"] != "A1G" or g["second"] != "xI" or g["cancelled"]:
        fail.append(f"{kind}: {g['start']} {g['model']} {g['second']} cancelled={g['cancelled']}")
    if len(cli.get(kind, [])) < 5:
        fail.append(f"{kind}: the CLI wrote {len(cli.get(kind, []))} points")
    elif g["points"] != cli[kind]:
        fail.append(f"{kind}: the GUI's points {g['points']} are not the CLI's {cli[kind]}")
m = re.search(r"period-1 fold at omega = ([0-9.]+)", log)
if not m or abs(p["fold"]["omega0"] - float(m.group(1))) > 1e-7:
    fail.append(f"fold: the GUI starts at {p['fold']['omega0']}, the CLI at {m and m.group(1)}")
if p["doubling"] is not None:
    fail.append("doubling: drawn though not asked for")
m = re.search(r"^fold +omega = ([0-9.]+)", open(f"{d}/cont.log").read(), re.M)
w, q = min(p["fold"]["points"], key=lambda p: abs(p[1] + 0.0035))
if abs(q + 0.0035) > 1e-4:
    fail.append(f"fold: its point nearest xI = -3.5 mm is at {q}")
if not m or abs(w - float(m.group(1))) > 1e-5:
    fail.append(f"fold at xI = {q}: the GUI's {w}, continue's {m and m.group(1)}")
for f in fail:
    print("gui_plane_curves:", f)
if fail:
    sys.exit(1)
print("gui_plane_curves: passed")
PY
