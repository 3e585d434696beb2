#!/bin/sh
# The file browser of the session window: --browse DIR opens File > Load session on DIR, which lists its
# folders first (with ../), then its .json files in any case, sorted, hidden ones left out (--state-json's
# session_browser); a folder that does not exist is said there instead of a list. A session saved into the
# folder shows up in it. Exit 77 (CTest's skip code) without xvfb-run or python3.
# usage: gui_browser.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_browser
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
rm -rf "$dir/files"
mkdir -p "$dir/files/sub" "$dir/files/.git"
for f in b.json A.JSON c.csv .hidden.json; do echo '{}' >"$dir/files/$f"; done

gui_json saved --model A1G --frames 5 --save-session "$dir/files/s1.json"
gui_json listed --browse "$dir/files" --frames 5 --screenshot "$dir/browser.png"
gui_json missing --browse "$dir/files/none" --frames 5

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
for f in fail:
    print("gui_browser:", f)
if fail:
    sys.exit(1)
print("gui_browser: passed")
PY
