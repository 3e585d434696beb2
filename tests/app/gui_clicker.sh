#!/bin/sh
# GUI test of the Poincare clicker through --orbit and --state-json, under Xvfb with Mesa: A1G at 13 rad/s,
# where an impacting period-1 orbit and a chaotic attractor coexist. Two clicks: from (-20 mm, -0.1 m/s) the
# kept orbit settles on the period-1 point (its last 20 section points within 1 um), from (-13 mm, 0) it
# stays chaotic (they spread over more than 1 mm); each orbit keeps its own points and its start.
# --orbit without --frames, or a bad pair, exits 2.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_clicker.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_clicker
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json two --model A1G --omega 13 --speed 100 --orbit -0.02,-0.1 --orbit -0.013,0 --frames 900 --screenshot "$dir/two.png"

for bad in "--orbit 1,2 --frames 2" "--orbit -0.01 --frames 2" "--orbit -0.01,0"; do
    # shellcheck disable=SC2086
    "$gui" $bad >"$dir/bad.log" 2>&1
    rc=$?
    if [ $rc -ne 2 ] || ! grep -q -- "--orbit" "$dir/bad.log"; then
        cat "$dir/bad.log"; echo "gui_clicker: '$bad' should exit 2 naming --orbit, got $rc"; exit 1
    fi
done

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
with open(f"{d}/two.json") as f:
    j = json.load(f)
fail = []
c = j["clicker"]
o = c["orbits"]
if not c["on"] or len(o) != 2:
    fail.append(f"clicker {c}")
else:
    if o[0]["start"] != [-0.02, -0.1] or o[1]["start"] != [-0.013, 0]: fail.append(f"starts {o[0]['start']}, {o[1]['start']}")
    if o[0]["points"] < 50 or o[1]["points"] < 50: fail.append(f"points {o[0]['points']}, {o[1]['points']}")
    if o[0]["spread"] is None or o[0]["spread"] > 1e-6: fail.append(f"orbit 1 did not settle on period 1: spread {o[0]['spread']}")
    if o[1]["spread"] is None or o[1]["spread"] < 1e-3: fail.append(f"orbit 2 is not chaotic: spread {o[1]['spread']}")
for x in fail:
    print("gui_clicker:", x)
if fail:
    sys.exit(1)
print("gui_clicker: passed")
PY
