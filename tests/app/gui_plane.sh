#!/bin/sh
# The parameter plane's tile and the continued doubling over it, under Xvfb with Mesa:
#  1. A plain run has no analysis tile, and none is counted as hidden.
#  2. --plane FILE --plane-doubling: the plane is a tile of the layout (inside the window, beside no
#     overlap), and the doubling found over its omega range is the CLI's (`scan --doubling-from auto`, the
#     same core function): the same omega to 1e-7, and the curve A1C's vertical line at 10.86134 rad/s from
#     the grazing near xI = -3.3 mm up to the plane's top.
#  3. --plane-doubling without a plane exits 1 naming the flag.
#  4. A1C at omega 10.9-11.1, |xI| <= 1 mm, as the CLI scans it: every cell settled to period 2 (20
#     transient periods once left 5 and 10 there), and so the GUI's plane shows it.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_plane.sh IMPACTLAB_GUI IMPACTLAB_CLI OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_plane
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

"$cli" scan --model A1C --x omega:9.5:12.5:13 --y xI:-0.006:0.002:9 --out "$dir/plane.csv" --png "$dir/plane.png" \
    --doubling-from auto --threads 2 2>"$dir/cli.log" || { cat "$dir/cli.log"; echo "gui_plane: the scan failed"; exit 1; }
"$cli" scan --model A1C --x omega:10.9:11.1:3 --y xI:-0.001:0.001:3 --out "$dir/settled.csv" 2>"$dir/cli2.log" ||
    { cat "$dir/cli2.log"; echo "gui_plane: the 3 x 3 scan failed"; exit 1; }
gui_json settled --model A1C --plane "$dir/settled.csv" --frames 5
gui_json plain --model A1C --frames 5
gui_json plane --model A1C --plane "$dir/plane.csv" --plane-doubling --frames 20 --screenshot "$dir/plane_tile.png"

gui_exec noplane --model A1C --plane-doubling --frames 5
if [ $rc -ne 1 ] || ! grep -q -- "--plane-doubling" "$dir/noplane.log"; then
    cat "$dir/noplane.log"; echo "gui_plane: --plane-doubling without a plane should exit 1 naming the flag, got $rc"; exit 1
fi

python3 - "$dir" <<'PY'
import json, re, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)
fail = []
plain, j = load("plain"), load("plane")
lp = plain["layout"]
if "plane" in lp["visible_panels"] or "plane" in lp["hidden_panels"] or "basins" in lp["hidden_panels"]:
    fail.append(f"plain: the analysis tiles show or count as hidden: {lp['visible_panels']} / {lp['hidden_panels']}")
l = j["layout"]
tiles = [t for t in l["tiles"] if "plane" in t["panels"]]
vx, vy, vw, vh = l["viewport"]
if len(tiles) != 1:
    fail.append(f"plane: {len(tiles)} tiles hold the plane")
else:
    x, y, w, h = tiles[0]["rect"]
    if not (x >= vx and y >= vy and x + w <= vx + vw + 0.5 and y + h <= vy + vh + 0.5 and w > 200 and h > 140):
        fail.append(f"plane: its tile {tiles[0]['rect']} is not inside the viewport at a usable size")
    for t in l["tiles"]:
        if t is tiles[0]:
            continue
        a, b, c, e = t["rect"]
        if a < x + w and x < a + c and b < y + h and y < b + e:
            fail.append(f"plane: its tile overlaps {t['panels']}")
p = j["plane"]
if not p["loaded"] or p["x"] != "omega" or p["y"] != "xI" or (p["nx"], p["ny"]) != (13, 9):
    fail.append(f"plane: {p}")
db = p["doubling"]
cli = open(f"{d}/cli.log").read()
m = re.search(r"period-1 doubling at omega = ([0-9.]+)", cli)
if not db or not db["found"]:
    fail.append(f"doubling: not found: {db}")
elif not m:
    fail.append("the CLI did not report its doubling: " + cli)
else:
    if abs(db["omega0"] - float(m.group(1))) > 1e-7:
        fail.append(f"doubling: the GUI's {db['omega0']} is not the CLI's {m.group(1)}")
    pts = db["points"]
    qs = [q for _, q in pts]
    if len(pts) < 8 or any(abs(w - 10.86134) > 1e-5 for w, _ in pts):
        fail.append(f"doubling: not the vertical line at 10.86134: {pts}")
    if not (-0.0034 < min(qs) < -0.0032) or abs(max(qs) - 0.002) > 1e-9:
        fail.append(f"doubling: spans xI {min(qs)} .. {max(qs)}, not -3.3 mm .. 2 mm")
    if "doubling lost" not in db["end"]:
        fail.append(f"doubling: its lower end is not the grazing: {db['end']}")
st = load("settled")["plane"]
if st.get("periods") != [2] * 9:
    fail.append(f"settled: the cells at 10.9-11.1 rad/s read {st.get('periods')}, not period 2 everywhere")
for f in fail:
    print("gui_plane:", f)
if fail:
    sys.exit(1)
print("gui_plane: passed")
PY
