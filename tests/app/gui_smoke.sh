#!/bin/sh
# GUI smoke test: run the visualiser under Xvfb with Mesa's software OpenGL for 120 frames (it switches the
# impact model once half-way, H -> G), save a screenshot, then check the PNG is a real picture and that the
# simulation advanced. Exit 77 (CTest's skip code) when xvfb-run is not installed.
# usage: gui_smoke.sh IMPACTLAB_GUI PNG_CHECK OUT_DIR
gui="$1"; check="$2"; dir="$3"
if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "gui_smoke: xvfb-run is not installed (apt-get install xvfb xauth): skipped"
    exit 77
fi
mkdir -p "$dir"
png="$dir/gui_smoke.png"; log="$dir/gui_smoke.log"
rm -f "$png" "$log"
TEST=gui_smoke
. "$(dirname "$0")/gui_lib.sh"
xvfb_rc "$dir/gui_smoke.rc" "$gui" --frames 120 --screenshot "$png" --state-json "$dir/gui_smoke.json" --switch-model A1G --model A1H \
    --omega 18 --speed 4 >"$log" 2>&1
cat "$log"
if [ $rc -ne 0 ]; then echo "gui_smoke: impactlab-gui exited with $rc"; exit 1; fi
[ -f "$png" ] || { echo "gui_smoke: no screenshot written"; exit 1; }
"$check" "$png" 1280 800 || exit 1
# Every tile must be a real picture of its own (the rig is drawn in the window's pass from a callback, the
# plots as opaque images: a tile whose drawing went missing would be flat), the rig's a full one. The tiles'
# rectangles come from --state-json.
if command -v python3 >/dev/null 2>&1; then
    regions=$(python3 -c '
import json, sys
j = json.load(open(sys.argv[1]))
for t in j["layout"]["tiles"]:
    x, y, w, h = (int(round(v)) for v in t["rect"])
    kind = "--busy" if "rig" in t["panels"] else "--region"   # the rig fills its tile
    print("%s %d %d %d %d" % (kind, x + 4, y + 24, w - 8, h - 28))
' "$dir/gui_smoke.json") || { echo "gui_smoke: no tiles in the state JSON"; exit 1; }
    [ -n "$regions" ] || { echo "gui_smoke: no tiles in the state JSON"; exit 1; }
    # shellcheck disable=SC2086
    "$check" "$png" 1280 800 $regions || { echo "gui_smoke: a tile looks blank"; exit 1; }
fi
# The simulation must have advanced, and the model switch must have happened.
t=$(sed -n 's/.*sim_time=\([0-9.]*\).*/\1/p' "$log" | tail -n 1)
[ -n "$t" ] || { echo "gui_smoke: no sim_time in the output"; exit 1; }
awk -v t="$t" 'BEGIN { exit !(t > 0.1) }' || { echo "gui_smoke: the simulation did not advance (sim_time=$t)"; exit 1; }
grep -q "model=A1G" "$log" || { echo "gui_smoke: the model was not switched to A1G"; exit 1; }
grep -q "epoch=0" "$log" && { echo "gui_smoke: the model switch did not reach the simulation (epoch 0)"; exit 1; }
echo "gui_smoke: passed (sim_time=$t s)"
exit 0
