#!/bin/sh
# GUI test of session files and clip export, under Xvfb with Mesa's software OpenGL:
#  1. A1G at omega 12.5, xI 2 mm, light theme, scale 1.25 saved with --save-session; loaded with --session:
#     the state JSON shows that model, omega and xI, the run goes on from the saved time, and saving again
#     gives the same model, forcing, view and companion cart (the twin).
#  2. Bad session files are refused before a window opens (exit 2), naming the file, the key or line, and
#     the problem: omega out of range, not JSON, a missing file, an unknown model, an unknown key.
#  3. --clip-out: the last second as 31 PNG frames (30 fps) in a new folder, a real picture that changes
#     from the first frame to the last, no staging folder left, and the toast's summary (ffmpeg or not);
#     a --clip-out that is not a folder is refused naming the flag.
#  4. Replay continued from 3 s back (see below).
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_session.sh IMPACTLAB_GUI PNG_CHECK OUT_DIR
gui="$1"; check="$2"; dir="$3"
TEST=gui_session
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
rm -rf "$dir"
mkdir -p "$dir"
fail() { echo "gui_session: FAIL: $*"; exit 1; }

gui_run() { gui_exec "$@"; }   # gui_run NAME ARGS...: output in $dir/NAME.log, exit status in $rc

# 1. Round trip.
gui_run save --model A1G --omega 12.5 --xI 0.002 --theme light --scale 1.25 --speed 4 --twin --frames 60 \
    --presentation potential --hide strip --magnify 4 --save-session "$dir/s1.json" --state-json "$dir/a.json"
[ $rc -eq 0 ] || { cat "$dir/save.log"; fail "saving exited with $rc"; }
gui_run load --session "$dir/s1.json" --frames 20 --state-json "$dir/b.json" --save-session "$dir/s2.json"
[ $rc -eq 0 ] || { cat "$dir/load.log"; fail "loading exited with $rc"; }
python3 - "$dir" <<'PY' || exit 1
import json, sys
d = sys.argv[1]
s1, s2, b = (json.load(open(f"{d}/{n}.json")) for n in ("s1", "s2", "b"))
fail = []
if s1["model"] != "A1G" or abs(s1["omega"] - 12.5) > 1e-12 or abs(s1["xI"] - 0.002) > 1e-12:
    fail.append(f"saved {s1['model']} omega {s1['omega']} xI {s1['xI']}, expected A1G, 12.5, 0.002")
if b["model"] != s1["model"] or abs(b["omega"] - s1["omega"]) > 1e-12 or abs(b["xI"] - s1["xI"]) > 1e-12:
    fail.append(f"loaded: the panels show {b['model']} omega {b['omega']} xI {b['xI']}, the file says "
                f"{s1['model']} {s1['omega']} {s1['xI']}")
if not (s1["state"]["t"] > 0 and b["sim_time"] >= s1["state"]["t"]):
    fail.append(f"the run did not go on from the saved t = {s1['state']['t']}: sim_time {b['sim_time']}")
for k in ("model", "omega", "xI", "speed", "view", "windows", "bifurcation", "data", "companion", "layout"):
    if s1[k] != s2[k]:
        fail.append(f"saved again, '{k}' differs: {s1[k]} then {s2[k]}")
if s1["view"]["theme"] != "light" or s1["view"]["ui_scale"] != 1.25 or s1["companion"]["mode"] != "twin":
    fail.append(f"the view or the companion was not saved: {s1['view']} {s1['companion']}")
want = {"mode": "presentation", "hidden": ["strip"], "maximised": None, "presentation_plot": "potential", "magnify": [1.0, 4.0]}
if s1["layout"] != want:
    fail.append(f"the layout saved is {s1['layout']}, expected {want}")
lb = b["layout"]
if lb["mode"] != "presentation" or lb["presentation_plot"] != "potential" or "strip" not in lb["hidden_panels"] \
        or abs(lb["magnification"] - 4.0) > 1e-12:
    fail.append(f"loaded: the layout shown is {lb}")
for f in fail:
    print("gui_session: FAIL:", f)
sys.exit(1 if fail else 0)
PY

# 2. Bad files: exit 2 before any window, the message names file, key (or line) and problem.
bad() {   # bad NAME CONTENT EXPECTED-MESSAGE-PART
    printf '%s' "$2" >"$dir/$1.json"
    "$gui" --session "$dir/$1.json" --frames 5 >"$dir/$1.log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "$1: exit $rc, expected 2"
    grep -qF -- "$3" "$dir/$1.log" || { cat "$dir/$1.log"; fail "$1: the message does not say '$3'"; }
}
bad omega '{"format": "impactlab-gui session", "omega": 45}' "--session: $dir/omega.json: key 'omega': 45 is out of range [0, 30]"
bad notjson '{"format": "impactlab-gui session",
  "omega": 9,,}' "$dir/notjson.json: line 2, column 14: not valid JSON"
bad model '{"format": "impactlab-gui session", "model": "A7Q"}' "key 'model': unknown model version 'A7Q'"
bad key '{"format": "impactlab-gui session", "view": {"zoomm": {}}}' "key 'view.zoomm': unknown key"
"$gui" --session "$dir/none.json" --frames 5 >"$dir/none.log" 2>&1
[ $? -eq 2 ] && grep -qF "$dir/none.json: cannot read it" "$dir/none.log" || fail "a missing session file: $(cat "$dir/none.log")"

# 3. A clip of the last second.
mkdir -p "$dir/clips"
gui_run clip --model A1H --preset 3 --speed 5 --frames 90 --clip-out "$dir/clips" --clip-seconds 1
[ $rc -eq 0 ] || { cat "$dir/clip.log"; fail "the clip run exited with $rc"; }
clip=$(ls -d "$dir"/clips/impactlab-clip-A1H-* 2>/dev/null | head -n 1)
[ -n "$clip" ] || fail "no clip folder in $dir/clips: $(ls -a "$dir/clips")"
frames=$(ls "$clip"/frame-*.png | wc -l)
[ "$frames" -eq 31 ] || fail "$frames frames, expected 31 (1 s at 30 fps)"
[ "$(ls -A "$dir/clips" | grep -c '^\.')" -eq 0 ] || fail "a staging folder was left: $(ls -A "$dir/clips")"
"$check" "$clip/frame-00016.png" 1280 800 || fail "frame 16 is not a real picture"
cmp -s "$clip/frame-00001.png" "$clip/frame-00031.png" && fail "the first and last frames are the same picture"
if command -v ffmpeg >/dev/null 2>&1; then
    [ -s "$clip/clip.mp4" ] || fail "ffmpeg is installed but there is no clip.mp4"
else
    grep -qF "ffmpeg not found: wrote 31 PNG frames to $clip" "$dir/clip.log" || fail "no 'ffmpeg not found' summary: $(cat "$dir/clip.log")"
fi
"$gui" --frames 5 --clip-out "$dir/s1.json" >"$dir/notdir.log" 2>&1
[ $? -eq 2 ] && grep -qF -- "--clip-out: '$dir/s1.json' is not a folder" "$dir/notdir.log" || fail "--clip-out to a file: $(cat "$dir/notdir.log")"
# 4. Replay: 3 s back, continue from there (Enter): the history keeps the past up to that instant and
#    drops the old future (one sample per ms from the first to the last, none twice), and the run goes on.
gui_run cont --model A1H --preset 1 --speed 5 --frames 120 --replay-back 3 --replay-continue --state-json "$dir/cont.json"
[ $rc -eq 0 ] || { cat "$dir/cont.log"; fail "the replay run exited with $rc"; }
tc=$(sed -n 's/.*continuing from t = \([0-9.]*\) s.*/\1/p' "$dir/cont.log")
[ -n "$tc" ] || fail "no 'continuing from t = ...' in the log: $(cat "$dir/cont.log")"
python3 - "$dir/cont.json" "$tc" <<'PY' || exit 1
import json, sys
j = json.load(open(sys.argv[1]))
h, tc = j["history"], float(sys.argv[2])
expected = round((h["t_last"] - h["t_first"]) / 1e-3) + 1   # 1 ms samples at 5x
if abs(h["samples"] - expected) > 2:
    print(f"gui_session: FAIL: continued at t = {tc}: {h['samples']} samples over "
          f"{h['t_first']}..{h['t_last']} s, expected {expected} (the old future kept?)")
    sys.exit(1)
if not (h["t_last"] > tc + 0.5 and j["sim_time"] > tc + 0.5 and h["replay_t"] is None):
    print(f"gui_session: FAIL: the run did not go on from t = {tc}: {h}, sim_time {j['sim_time']}")
    sys.exit(1)
PY
# 5. The Poincare map while replaying is the map of the replayed instant: the section points it has seen
#    are those up to the cursor (one a forcing period from t = 0), not the live ones 15 s later.
gui_run pmap --model A1H --preset 3 --speed 10 --frames 400 --replay-back 15 --state-json "$dir/pmap.json"
[ $rc -eq 0 ] || { cat "$dir/pmap.log"; fail "the replay run of the map exited with $rc"; }
python3 - "$dir/pmap.json" <<'PY' || exit 1
import json, math, sys
j = json.load(open(sys.argv[1]))
h = j["history"]
period = 2 * math.pi / j["omega"]
if h["replay_t"] is None or h["replay_t"] < 3 or h["t_last"] - h["replay_t"] < 12:
    print(f"gui_session: FAIL: not replaying 15 s back at t >= 3 s: {h}")
    sys.exit(1)
seen, expected = j["poincare_seen"], h["replay_t"] / period
if abs(seen - expected) > 2:
    print(f"gui_session: FAIL: replaying at t = {h['replay_t']:.2f} s the map has seen {seen} sections, "
          f"expected {expected:.1f} (the live map's {h['t_last'] / period:.1f}?)")
    sys.exit(1)
PY
echo "gui_session: passed (round trip A1G 12.5 rad/s 2 mm, five bad files refused, a 31-frame clip, replay continued, the map replayed)"
