#!/bin/sh
# Labels never cover the data, under Xvfb with Mesa through --state-json:
#  1. A1G's continued branches over the diagram, omega at 12.8 (its grazing 12.7993 and fold 12.8306 right
#     under the running omega's label): the legend is a row outside the diagram's data area, so it holds no
#     bifurcation point drawn and does not overlap the label, and the label covers no point (it moves to the
#     plot's foot); the same in a short tile (plane, basins), where the legend is the word "key". The info
#     line (model, levels, points) lies below the data area too.
#  2. The diagram stays drawn, 100 px high at least, with the plane and the basins open at 1280x800, and at
#     --ui-scale 2 (README's layouts), where its settings fold into one button.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_legends.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_legends
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json cont --model A1G --omega 12.8 --continuation --bifurcation cf-up --bif-steps 100 --frames 10 \
    --screenshot "$dir/cont.png"
gui_json tiles --model A1G --omega 12.8 --small-plane --basins --continuation --bifurcation cf-up --bif-steps 50 --frames 10 \
    --screenshot "$dir/tiles.png"
gui_json scale2 --model A1G --size 1280x800 --ui-scale 2 --bifurcation cf-up --bif-steps 50 --frames 10 \
    --screenshot "$dir/scale2.png"

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
fail = []
def load(n):
    return json.load(open(f"{d}/{n}.json"))
def overlap(a, b):
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
for n in ("cont", "tiles"):
    c = load(n)["diagram"]
    lg = c["legend_rect"]
    if lg is None:
        fail.append(f"{n}: no legend drawn")
        continue
    inside = [p for p in c["markers_px"] if lg[0] <= p[0] <= lg[2] and lg[1] <= p[1] <= lg[3]]
    if inside:
        fail.append(f"{n}: the legend {lg} covers bifurcation points {inside}")
    if overlap(lg, c["omega_label_rect"]):
        fail.append(f"{n}: the legend {lg} covers the omega label {c['omega_label_rect']}")
    ol = c["omega_label_rect"]
    under = [p for p in c["markers_px"] if ol[0] - 4 <= p[0] <= ol[2] + 4 and ol[1] - 4 <= p[1] <= ol[3] + 4]
    if under:
        fail.append(f"{n}: the omega label {ol} covers bifurcation points {under}")
    if overlap(lg, c["plot_rect"]):
        fail.append(f"{n}: the legend {lg} lies over the diagram's data area {c['plot_rect']}")
    # The info line (model, levels, points) sits below the data area, in the x label's row.
    ir = c["info_rect"]
    if ir is None:
        fail.append(f"{n}: the diagram's info line is not drawn")
    elif overlap(ir, c["plot_rect"]):
        fail.append(f"{n}: the info line {ir} lies over the diagram's data area {c['plot_rect']}")
    if len(c["markers_px"]) < 4:
        fail.append(f"{n}: {len(c['markers_px'])} bifurcation points drawn, the continuation's are missing")
    print(f"{n}: legend {lg}, omega label {c['omega_label_rect']}, {len(c['markers_px'])} points drawn")
for n in ("tiles", "scale2"):
    j = load(n)
    r = j["diagram"]["plot_rect"]
    h = r[3] - r[1]
    print(f"{n}: the diagram's data area {r} ({h:.0f} px high)")
    if h < 100:
        fail.append(f"{n}: the diagram's data area is {h:.0f} px high: {r}")
for f in fail:
    print("gui_legends: FAIL:", f)
if fail:
    sys.exit(1)
print("gui_legends: passed")
PY
