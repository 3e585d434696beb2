#!/bin/sh
# Session files keep the desk: the parameters edited, the time strip's traces and the Poincare clicker's
# orbits. A run with --param m0e=0.027, --strip v,E and two --orbit clicks saves a session; a run that loads it
# must report the same parameters (edited), traces, clicker and orbits (their starts, as many points, the same
# last point) through --state-json. A session whose params.m is -1 is refused with the core's words, naming
# the key; one whose strip names no quantity likewise. Exit 77 (CTest's skip code) without xvfb-run or python3.
# usage: gui_session_desk.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_session_desk
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"
s="$dir/desk.json"
rm -f "$s"

gui_json saved --model A1G --omega 13 --param m0e=0.027 --strip v,E --orbit -0.02,-0.1 --orbit -0.013,0 --speed 20 --frames 300 \
    --save-session "$s"
gui_json loaded --session "$s" --frames 5 --screenshot "$dir/loaded.png"

python3 - "$s" "$dir" <<'PY'
import json, sys
s, d = sys.argv[1], sys.argv[2]
j = json.load(open(s))
j["params"] = {"m": -1}
json.dump(j, open(f"{d}/bad_params.json", "w"))
j = json.load(open(s))
j["strip"] = ["q"]
json.dump(j, open(f"{d}/bad_strip.json", "w"))
PY
for bad in bad_params bad_strip; do
    gui_exec "$bad" --session "$dir/$bad.json" --frames 5
    key=params.m; [ "$bad" = bad_strip ] && key=strip
    if [ $rc -eq 0 ] || ! grep -q "key '$key'" "$dir/$bad.log"; then
        cat "$dir/$bad.log"; echo "$TEST: $bad should be refused naming '$key', got $rc"; exit 1
    fi
done
grep -q "must lie in" "$dir/bad_params.log" || { cat "$dir/bad_params.log"; echo "$TEST: not the core's words"; exit 1; }

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
a, b = (json.load(open(f"{d}/{n}.json")) for n in ("saved", "loaded"))
fail = []
if b["params"].get("m0e") != 0.027 or not b["params_edited"] or b["params"] != a["params"]:
    fail.append(f"params: saved {a['params']}, loaded {b['params']} (edited {b['params_edited']})")
if b["strip"]["traces"] != ["v", "E"]:
    fail.append(f"strip: {b['strip']['traces']}")
ca, cb = a["clicker"], b["clicker"]
if not cb["on"] or len(cb["orbits"]) != 2 or len(ca["orbits"]) != 2:
    fail.append(f"clicker: saved {ca}, loaded {cb}")
else:
    for oa, ob in zip(ca["orbits"], cb["orbits"]):
        if oa["start"] != ob["start"] or oa["points"] != ob["points"] or oa["last"] != ob["last"] or ob["points"] < 5:
            fail.append(f"orbit: saved {oa}, loaded {ob}")
for f in fail:
    print("gui_session_desk:", f)
if fail:
    sys.exit(1)
print("gui_session_desk: passed")
PY
