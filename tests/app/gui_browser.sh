#!/bin/sh
# The file browser of the session window: --browse DIR opens File > Load session on DIR, which lists its
# folders first (with ../), then its .json files in any case, sorted, hidden ones left out (--state-json's
# session_browser); a folder that does not exist is said there instead of a list. A session saved into the
# folder shows up in it. Then the gestures that once lost a file (--double-click, the mouse held still):
#  - Save (Ctrl+S), double-click on "sub/": the first click opens it, the second lands on the row where
#    sub/live.json now lies, which must not be picked, opened or saved over; the field now names a file in
#    sub/ (saving into a folder means that folder).
#  - Save, double-click on an existing file: nothing is written, the window asks "Overwrite?".
#  - Load, double-click on "sub/": the same, nothing loaded.
# A folder of 3,000 sessions is listed whole, but only the rows in view are built each frame.
# Exit 77 (CTest's skip code) without xvfb-run or python3.
# usage: gui_browser.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_browser
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
rm -rf "$dir/files"
mkdir -p "$dir/files/sub" "$dir/files/.git"
for f in b.json A.JSON c.csv .hidden.json; do echo '{}' >"$dir/files/$f"; done
echo '{"keep": "this file"}' >"$dir/files/sub/live.json"

gui_json saved --model A1G --frames 5 --save-session "$dir/files/s1.json"
gui_json listed --browse "$dir/files" --frames 5 --screenshot "$dir/browser.png"
gui_json missing --browse "$dir/files/none" --frames 5
gui_json into_sub --browse "$dir/files" --press ctrl+s --double-click sub/ --frames 30 --screenshot "$dir/into_sub.png"
gui_json over_file --browse "$dir/files/sub" --press ctrl+s --double-click live.json --frames 30 --screenshot "$dir/over_file.png"
gui_json load_sub --browse "$dir/files" --double-click sub/ --frames 30
rm -rf "$dir/many"
python3 -c "import os, sys; os.makedirs(sys.argv[1]); [open(os.path.join(sys.argv[1], 's%05d.json' % i), 'w').close() for i in range(3000)]" "$dir/many"
gui_json many --browse "$dir/many" --frames 5

python3 - "$dir" <<'PY'
import json, os, sys
d = sys.argv[1]
l, m = (json.load(open(f"{d}/{n}.json")) for n in ("listed", "missing"))
fail = []
b = l["session_browser"]
if l["session_window"] != "load" or os.path.realpath(b["dir"]) != os.path.realpath(f"{d}/files"):
    fail.append(f"listed: window {l['session_window']}, folder {b and b['dir']}")
if b["entries"] != ["../", "sub/", "A.JSON", "b.json", "s1.json"]:
    fail.append(f"listed: {b['entries']}")
mb = m["session_browser"]
if "cannot list" not in mb["error"] or mb["entries"]:
    fail.append(f"missing: {mb}")
live = open(f"{d}/files/sub/live.json").read()
if live != '{"keep": "this file"}\n':
    fail.append(f"sub/live.json was written over: {live[:80]!r}")
sub = os.path.realpath(f"{d}/files/sub")
i, o, ls = (json.load(open(f"{d}/{n}.json")) for n in ("into_sub", "over_file", "load_sub"))
if i["session_window"] != "save" or os.path.realpath(i["session_browser"]["dir"]) != sub:
    fail.append(f"into_sub: window {i['session_window']}, folder {i['session_browser']['dir']}")
if os.path.realpath(os.path.dirname(i["session_path"])) != sub or i["session_path"].endswith("live.json"):
    fail.append(f"into_sub: the field says {i['session_path']}, not a new file in sub/")
if i["session_overwrite_asked"] is not None:
    fail.append(f"into_sub: asked to overwrite {i['session_overwrite_asked']}")
if o["session_window"] != "save" or os.path.realpath(o["session_overwrite_asked"] or "") != os.path.join(sub, "live.json"):
    fail.append(f"over_file: window {o['session_window']}, asked {o['session_overwrite_asked']}")
if ls["session_window"] != "load" or os.path.realpath(ls["session_browser"]["dir"]) != sub:
    fail.append(f"load_sub: window {ls['session_window']}, folder {ls['session_browser']['dir']}")
mb = json.load(open(f"{d}/many.json"))["session_browser"]
if len(mb["entries"]) != 3001 or not 1 <= mb["rows_drawn"] <= 40:
    fail.append(f"many: {len(mb['entries'])} entries listed (3001 asked), {mb['rows_drawn']} rows built in a frame (the view's, at most 40)")
for f in fail:
    print("gui_browser:", f)
if fail:
    sys.exit(1)
print("gui_browser: passed")
PY
