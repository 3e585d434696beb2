#!/bin/sh
# GUI test of "What to try" through --guide, --demo and --state-json, under Xvfb with Mesa: each of the five
# demonstrations sets up what its sentence speaks of (the model, omega, the ramp, the ghost cart, the
# diagram, the basins); the guide opens with --guide and stays shut in a scripted run; the status bar's
# technical fields only with --details; --demo 6 exits 2.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_guide.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_guide
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json scripted --frames 5
gui_json d1 --guide --demo 1 --frames 30 --screenshot "$dir/guide.png"
gui_json d2 --demo 2 --frames 10
gui_json d3 --demo 3 --frames 10
gui_json d4 --demo 4 --details --frames 10
gui_json d5 --demo 5 --frames 10

"$gui" --demo 6 --frames 2 >"$dir/bad.log" 2>&1
rc=$?
if [ $rc -ne 2 ] || ! grep -q -- "--demo" "$dir/bad.log"; then
    cat "$dir/bad.log"; echo "gui_guide: --demo 6 should exit 2 naming the flag, got $rc"; exit 1
fi

python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
def load(name):
    with open(f"{d}/{name}.json") as f:
        return json.load(f)
fail = []
def need(name, ok, what):
    if not ok: fail.append(f"{name}: {what}")
s = load("scripted")
need("scripted", not s["guide"]["open"] and s["guide"]["demo"] == 0 and not s["guide"]["details"], f"guide {s['guide']}")
a = load("d1")
need("d1", a["guide"]["open"] and a["guide"]["demo"] == 1, f"guide {a['guide']}")
# The ramp lasts 55 s of simulated time (2.75 s at 20x): on a slow machine 30 frames may outlast it.
r = a["ramp"]
need("d1", a["model"] == "A1H" and r["omega_from"] == 10.3 and r["omega_to"] == 11.4 and r["points"] > 0 and
     (r["active"] or abs(a["omega"] - 11.4) < 1e-9), f"model {a['model']}, omega {a['omega']}, ramp {r}")
b = load("d2")
need("d2", b["model"] == "A1H" and b["ramp"]["omega_to"] == 16 and b["diagram"]["model"] == "A1H",
     f"model {b['model']}, ramp {b['ramp']}, diagram {b['diagram'].get('model')}")
c = load("d3")
need("d3", c["model"] == "A1C" and c["companion"]["mode"] == "ghost" and c["companion"]["model"] == "A1G",
     f"model {c['model']}, companion {c['companion']}")
e = load("d4")
need("d4", e["model"] == "A1H" and e["omega"] == 18 and not e["ramp"]["active"] and e["guide"]["details"],
     f"model {e['model']}, omega {e['omega']}, details {e['guide']['details']}")
f = load("d5")
need("d5", f["model"] == "A1G" and f["omega"] == 13 and f["guide"]["basins_open"], f"model {f['model']}, omega {f['omega']}, {f['guide']}")
for x in fail:
    print("gui_guide:", x)
if fail:
    sys.exit(1)
print("gui_guide: passed")
PY
