#!/bin/sh
# Defects a teacher meets, through --state-json and saved files, under Xvfb:
#  1. `--model A1G --omega 12.5 --frames 30 --save-session s.json` saves model A1G (the headless model switch
#     half-way is for runs that only look, not for one that saves).
#  2. A session file with 1e999 or a key given twice is refused with a message naming the file, not an abort.
#  3. Started by hand (no --frames) with a bad --session or --data, the window opens anyway (still running
#     when `timeout` stops it) and shows the session's error; headless (--frames) the run stops with exit 2.
#  4. Keys (--press): Ctrl+O opens Load session and starts no continuation; O alone starts one (so the
#     check can fail); M from H goes to C, past "none".
#  5. Every panel hidden: the layout reports the hint the window shows (View > Panels), not a blank window;
#     with one panel shown, no hint.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_teacher.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_teacher
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3 timeout
mkdir -p "$dir"

rm -f "$dir/s.json"
gui_exec save --model A1G --omega 12.5 --frames 30 --save-session "$dir/s.json"
[ $rc -eq 0 ] || { cat "$dir/save.log"; echo "$TEST: --save-session run exited with $rc"; exit 1; }
python3 -c "import json,sys; m=json.load(open(sys.argv[1]))['model']; sys.exit(0 if m == 'A1G' else print('$TEST: saved model', m) or 1)" "$dir/s.json" || exit 1

for bad in huge dup; do
    case $bad in
        huge) printf '{"format": "impactlab-gui session", "omega": 1e999}\n' >"$dir/$bad.json"; want="number is out of range" ;;
        dup) printf '{"format": "impactlab-gui session", "omega": 9, "omega": 12}\n' >"$dir/$bad.json"; want="key 'omega' appears twice" ;;
    esac
    gui_exec "$bad" --session "$dir/$bad.json" --frames 5
    if [ $rc -ne 2 ] || ! grep -q "$dir/$bad.json: .*$want" "$dir/$bad.log"; then
        cat "$dir/$bad.log"; echo "$TEST: --session $bad.json: exit $rc, expected 2 with \"$want\""; exit 1
    fi
done
by_hand() {   # by_hand NAME ARGS...: no --frames, stopped by timeout after 6 s; $rc 124 if it was still running
    name="$1"; shift
    xvfb_rc "$dir/$name.rc" timeout 6 "$gui" "$@" >"$dir/$name.log" 2>&1
    [ $rc -eq 124 ] || { cat "$dir/$name.log"; echo "$TEST: $name: exit $rc before the timeout, expected a window"; exit 1; }
}
by_hand by_hand_session --session "$dir/huge.json"
grep -q "session not loaded: .*number is out of range" "$dir/by_hand_session.log" ||
    { cat "$dir/by_hand_session.log"; echo "$TEST: by hand with a bad --session: the error is not shown"; exit 1; }
by_hand by_hand_data --data "$dir/nonexistent.csv"

gui_json press_ctrl_o --model A1G --press ctrl+o --frames 10
gui_json press_o --model A1G --press o --frames 10
gui_json press_m --model A1H --press m --frames 10
python3 - "$dir" <<'PY' || exit 1
import json, sys
d = sys.argv[1]
def load(n):
    return json.load(open(f"{d}/{n}.json"))
j = load("press_ctrl_o")
if j["session_window"] != "load" or j["continuation"] is not None:
    sys.exit(f"gui_teacher: Ctrl+O: session window {j['session_window']}, continuation {j['continuation'] is not None}")
j = load("press_o")
if j["session_window"] is not None or j["continuation"] is None or not j["continuation"]["points"]:
    sys.exit(f"gui_teacher: O: session window {j['session_window']}, no continuation computed")
if load("press_m")["model"] != "A1C":
    sys.exit(f"gui_teacher: M from A1H gave {load('press_m')['model']}, expected A1C (none is skipped)")
PY

gui_json hidden --hide controls,rig,phase,poincare,potential,strip,bifurcation --frames 5
gui_json one --hide controls,rig,phase,poincare,potential,strip --frames 5
python3 - "$dir" <<'PY' || exit 1
import json, sys
d = sys.argv[1]
hidden = json.load(open(f"{d}/hidden.json"))["layout"]
one = json.load(open(f"{d}/one.json"))["layout"]
if hidden["visible_panels"] or hidden["nothing_shown_hint"] is not True:
    sys.exit(f"gui_teacher: every panel hidden: visible {hidden['visible_panels']}, hint {hidden['nothing_shown_hint']}")
if one["visible_panels"] != ["bifurcation"] or one["nothing_shown_hint"] is not False:
    sys.exit(f"gui_teacher: one panel shown: visible {one['visible_panels']}, hint {one['nothing_shown_hint']}")
PY
echo "$TEST: passed"
