#!/bin/sh
# The bifurcation panel through --state-json: a diagram over --bif-range fills while
# computing (a run that does not wait for it sees some but not all of its levels, whole levels only), and
# after it reports its omega range and every column; --bif-box recomputes a sub-range with the same steps and
# the view follows it; after a model switch the diagram says it is stale; the running attractor's points are
# counted in or off the diagram's view. A bad --bif-range is refused.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_diagram.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
command -v xvfb-run >/dev/null 2>&1 || { echo "gui_diagram: xvfb-run is not installed: skipped"; exit 77; }
command -v python3 >/dev/null 2>&1 || { echo "gui_diagram: python3 is not installed: skipped"; exit 77; }
mkdir -p "$dir"
TEST=gui_diagram
. "$(dirname "$0")/gui_lib.sh"
run() {   # run NAME ARGS...: the GUI headless at 1280x800, its state JSON in $dir/NAME.json
    name="$1"; shift
    rm -f "$dir/$name.json"
    xvfb_rc "$dir/$name.rc" "$gui" --size 1280x800 "$@" --state-json "$dir/$name.json" >"$dir/$name.log" 2>&1
    cat "$dir/$name.log"
    [ $rc -eq 0 ] || { echo "gui_diagram: $name: impactlab-gui exited with $rc"; exit 1; }
}
check() {   # check NAME PYTHON-EXPRESSION-OVER-d (the "diagram" object)
    python3 - "$dir/$1.json" "$2" <<'PY' || { echo "gui_diagram: $1: failed: $2"; exit 1; }
import json, sys
d = json.load(open(sys.argv[1]))["diagram"]
ok = eval(sys.argv[2], {"d": d})
print("gui_diagram:", sys.argv[2], "->", ok, "in", {k: d[k] for k in d if k != "lyapunov"})
sys.exit(0 if ok else 1)
PY
}

# 1. Done: A1H over 8-14 rad/s, 60 levels of 70 points.
run done --model A1H --omega 12 --bifurcation cf-up --bif-range 8:14 --bif-steps 60 --frames 10
check done 'd["model"] == "A1H" and d["omega_lo"] == 8 and d["omega_hi"] == 14 and d["steps"] == 60'
check done 'd["levels_done"] == 60 and d["points"] == 60 * 70 and not d["running"] and not d["stale"]'
check done 'd["view_omega"] == [8, 14]'

# 2. While computing (--bif-nowait): 1500 levels of A1C take longer than 5 frames; what is there is whole levels.
run partial --model A1C --bifurcation cf-up --bif-steps 1500 --bif-nowait --frames 5
check partial 'd["running"] and d["steps"] == 1500 and d["levels_done"] < 1500 and d["points"] == 70 * d["levels_done"]'
check partial 'd["omega_lo"] == 0 and d["omega_hi"] == 25 and d["view_omega"] == [0, 25]'

# 3. A box over 12-13 rad/s once the first diagram is done: the same 40 steps over it, and the view follows.
run box --model A1G --bifurcation cf-up --bif-steps 40 --bif-box 12:13 --frames 10
check box 'd["omega_lo"] == 12 and d["omega_hi"] == 13 and d["steps"] == 40 and d["levels_done"] == 40'
check box 'd["view_omega"] == [12, 13] and not d["running"]'

# 4. Stale: the A1H diagram stays after a switch to A1G, and says so.
run stale --model A1H --bifurcation cf-up --bif-range 8:10 --bif-steps 20 --switch-model A1G --frames 10
check stale 'd["model"] == "A1H" and d["stale"] and d["levels_done"] == 20'

# 5. The running attractor's section points on the diagram (the live points): at omega = 9 inside the
# 0-25 diagram they are in its view; at omega = 30, beyond its omega axis, every one is counted as off to
# the right (and said so on the plot), none drawn at the edge as if it were there.
run live_in --model A1H --omega 9 --warmup 60 --bifurcation cf-up --bif-steps 30 --frames 30
check live_in 'd["live_points"]["total"] > 0 and d["live_points"]["in_view"] == d["live_points"]["total"]'
run live_out --model A1H --omega 30 --warmup 60 --bifurcation cf-up --bif-steps 30 --frames 30 --screenshot "$dir/live_out.png"
check live_out 'd["view_omega"] == [0, 25] and d["live_points"]["total"] > 0'
check live_out 'd["live_points"]["beyond"] == d["live_points"]["total"] and d["live_points"]["in_view"] == 0'

# 6. A bad range is refused with the flag named (exit 2), before any window.
"$gui" --bif-range 5:3 --frames 2 >"$dir/bad.log" 2>&1
rc=$?
cat "$dir/bad.log"
[ $rc -eq 2 ] || { echo "gui_diagram: --bif-range 5:3 gave exit code $rc, not 2"; exit 1; }
grep -q -- "--bif-range: 5:3 is empty" "$dir/bad.log" || { echo "gui_diagram: the error does not name --bif-range"; exit 1; }
"$gui" --bif-range 0:40 --frames 2 >"$dir/bad.log" 2>&1
[ $? -eq 2 ] && grep -q -- "--bif-range: 40 is out of range" "$dir/bad.log" || { cat "$dir/bad.log"; echo "gui_diagram: --bif-range 0:40 not refused"; exit 1; }
echo "gui_diagram: passed"
exit 0
