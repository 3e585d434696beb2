#!/bin/sh
# GUI test of the layout through --state-json, under Xvfb with Mesa:
#  1. 1280x800 at --ui-scale 2: the tiles, the controls and the viewport as drawn: every tile inside the
#     window and clear of the others, every panel shown once (the extra ones as tabs), the controls tabbed
#     rather than scrolling, the magnification x1.
#  2. 1024x768 at scale 1 with --hide bifurcation,strip --maximise poincare: one tile, the Poincare map,
#     filling the plot area beside the controls; the hidden panels reported hidden.
#  3. --presentation poincare at --ui-scale 2: mode presentation, no controls, a bar, the rig and the map
#     only, a magnification above 1 by default (x3), and --magnify 5 sets it.
#  4. Bad layout flags: a clear message naming the flag, exit 2.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_layout.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_layout
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

GUI_SCREEN=1400x900
run() {   # run NAME ARGS...: writes $dir/NAME.json
    run_name="$1"; shift
    gui_json "$run_name" --model A1H --preset 2 --speed 20 --frames 12 "$@"
}

run scale2 --size 1280x800 --ui-scale 2
run hidden --size 1024x768 --ui-scale 1 --hide bifurcation,strip --maximise poincare
run present --size 1280x800 --ui-scale 2 --presentation poincare
run present5 --size 1280x800 --presentation --magnify 5

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)["layout"]
fail = []
def check(cond, what):
    if not cond:
        fail.append(what)

def inside(r, v):
    return r[0] >= v[0] - 0.5 and r[1] >= v[1] - 0.5 and r[0] + r[2] <= v[0] + v[2] + 0.5 and r[1] + r[3] <= v[1] + v[3] + 0.5
def overlap(a, b):
    return a[0] < b[0] + b[2] - 0.5 and b[0] < a[0] + a[2] - 0.5 and a[1] < b[1] + b[3] - 0.5 and b[1] < a[1] + a[3] - 0.5
def sound(name, l):
    rects = [t["rect"] for t in l["tiles"]] + [r for r in (l["controls"], l["bar"]) if r]
    for i, r in enumerate(rects):
        check(inside(r, l["viewport"]), f"{name}: {r} outside the window {l['viewport']}")
        for s in rects[i + 1:]:
            check(not overlap(r, s), f"{name}: {r} overlaps {s}")

# 1. scale 2 at 1280x800
l = load("scale2")
sound("scale2", l)
check(l["mode"] == "normal" and l["ui_scale"] == 2, f"scale2: mode/scale {l['mode']} {l['ui_scale']}")
panels = [p for t in l["tiles"] for p in t["panels"]]
check(sorted(panels) == sorted(["rig", "bifurcation", "phase", "poincare", "potential", "strip"]),
      f"scale2: panels {panels}")
check(any(len(t["panels"]) > 1 for t in l["tiles"]), "scale2: no tabs at scale 2 on 1280x800")
check(l["controls_tabbed"], "scale2: the controls scroll instead of being tabbed")
check(l["magnification"] == 1, f"scale2: magnification {l['magnification']} (x1 expected in normal mode)")
for t in l["tiles"]:
    check(t["rect"][2] >= 380 - 1 and t["rect"][3] >= 210 - 1, f"scale2: tile {t} under its minimum at scale 2")

# 2. hidden and maximised at 1024x768
l = load("hidden")
sound("hidden", l)
check(len(l["tiles"]) == 1 and l["tiles"][0]["panels"] == ["poincare"], f"hidden: tiles {l['tiles']}")
check(l["maximised"] == "poincare", f"hidden: maximised {l['maximised']}")
check(sorted(l["hidden_panels"]) == ["bifurcation", "strip"], f"hidden: hidden {l['hidden_panels']}")
c, r, v = l["controls"], l["tiles"][0]["rect"], l["viewport"]
check(abs(r[0] - (c[0] + c[2])) < 0.5 and abs(r[0] + r[2] - (v[0] + v[2])) < 0.5, f"hidden: {r} does not fill beside {c}")

# 3. presentation at scale 2
l = load("present")
sound("present", l)
check(l["mode"] == "presentation", f"present: mode {l['mode']}")
check(l["controls"] is None and l["bar"] is not None, "present: controls shown or no bar")
check([t["panels"] for t in l["tiles"]] == [["rig"], ["poincare"]], f"present: tiles {l['tiles']}")
check(l["magnification"] > 1, f"present: magnification {l['magnification']} (a larger default expected)")
check(l["bar"][3] < 0.2 * l["viewport"][3], f"present: the bar {l['bar']} is not slim")
l = load("present5")
check(l["magnification"] == 5, f"present5: --magnify 5 gave {l['magnification']}")
check(l["ui_scale"] >= 1.5 and l["ui_scale_normal"] < 1.5, f"present5: scale {l['ui_scale']} / {l['ui_scale_normal']}")
check(l["presentation_plot"] == "phase", f"present5: default plot {l['presentation_plot']}")

if fail:
    print("gui_layout: FAIL\n  " + "\n  ".join(fail))
    sys.exit(1)
print("gui_layout: ok")
PY
[ $? -eq 0 ] || exit 1

# 4. Bad flags name themselves and exit 2 before any window opens.
for bad in "--hide nothing" "--maximise controls" "--presentation clock" "--magnify 20" "--hide rig --maximise rig"; do
    # shellcheck disable=SC2086
    out=$("$gui" $bad 2>&1); rc=$?
    flag=$(echo "$bad" | awk '{print ($NF == "rig" ? "--maximise" : $1)}')
    if [ $rc -ne 2 ] || ! echo "$out" | grep -q -- "$flag"; then
        echo "gui_layout: '$bad' gave exit $rc and: $out"; exit 1
    fi
done
echo "gui_layout: bad flags ok"
