#!/bin/sh
# GUI test of "What to try" through --guide, --demo and --state-json, under Xvfb with Mesa: each of the five
# demonstrations sets up what its sentence speaks of (the model, omega, the ramp, the ghost cart, the
# diagram, the basins); the guide opens with --guide and stays shut in a scripted run; the status bar's
# technical fields only with --details; --demo 6 exits 2. A demo run from the guide folds it away into
# the bottom-left corner (off the plots). Demo 1 at its promised moments (--warmup runs it at 100x first):
# before the doubling (omega near 10.8) the map holds one point and says omega moves; once the ramp has
# crossed it and ended at 11.2, the label says period 2 with two clusters. Demo 4 shows the State group.
# Exit 77 (CTest's skip code) when xvfb-run or python3 is missing.
# usage: gui_guide.sh IMPACTLAB_GUI OUT_DIR
gui="$1"; dir="$2"
TEST=gui_guide
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"

gui_json scripted --frames 5
gui_json d1 --guide --demo 1 --frames 30 --screenshot "$dir/guide.png"
gui_json d1_before --demo 1 --warmup 200 --frames 10 --screenshot "$dir/d1_before.png"
gui_json d1_after --demo 1 --warmup 800 --frames 30 --screenshot "$dir/d1_after.png"
gui_json d2 --demo 2 --frames 10
gui_json tap --model A1H --tap m --frames 10
gui_json d3 --demo 3 --frames 10
gui_json d4 --demo 4 --details --frames 10 --size 1280x720
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
need("d1", a["guide"]["open"] and a["guide"]["demo"] == 1 and a["guide"]["collapsed"], f"guide {a['guide']}")
gx0, gy0, gx1, gy1 = a["guide"]["rect"]
for t in a["layout"]["tiles"]:
    if "controls" in t["panels"]:
        continue
    x, y, w, h = t["rect"]
    if gx0 < x + w and x < gx1 and gy0 < y + h and y < gy1:
        fail.append(f"d1: the folded guide {a['guide']['rect']} covers the tile of {t['panels']} {t['rect']}")
# The ramp: 10.6 -> 11.2 at 1e-3 rad/s per s, 600 s of simulation, 30 s of wall time at 20x.
r = a["ramp"]
need("d1", a["model"] == "A1H" and r["omega_from"] == 10.6 and r["omega_to"] == 11.2 and r["rate"] == 0.001 and
     r["active"] and a["speed"] == 20, f"model {a['model']}, omega {a['omega']}, speed {a.get('speed')}, ramp {r}")
def clusters(j):
    tx, tv = j["poincare_tol"]
    centres = []
    for x, v in j["poincare_points"]:
        if not any(abs(x - cx) <= 3 * tx and abs(v - cv) <= 3 * tv for cx, cv in centres):
            centres.append((x, v))
    return len(centres)
bf = load("d1_before")
need("d1_before", bf["ramp"]["active"] and bf["poincare_omega_moving"] and 10.75 < bf["omega"] < 10.85 and
     bf["poincare_period"] == 1 and clusters(bf) == 1,
     f"omega {bf['omega']}, moving {bf['poincare_omega_moving']}, period {bf['poincare_period']} "
     f"({bf['poincare_status']}), {clusters(bf)} clusters")
af = load("d1_after")
need("d1_after", not af["ramp"]["active"] and abs(af["omega"] - 11.2) < 1e-9 and af["poincare_period"] == 2 and
     clusters(af) == 2 and af["speed"] == 20,
     f"omega {af['omega']}, ramp {af['ramp']}, period {af['poincare_period']} ({af['poincare_status']}), "
     f"{clusters(af)} clusters, speed {af.get('speed')}")
t = load("tap")   # a key tap shorter than a frame (pressed and released in one poll) is not lost
need("tap", t["model"] != "A1H" and t["model"].startswith("A1"), f"M tapped: model {t['model']}, expected the next law")
b = load("d2")
need("d2", b["model"] == "A1H" and b["ramp"]["omega_to"] == 16 and b["diagram"]["model"] == "A1H",
     f"model {b['model']}, ramp {b['ramp']}, diagram {b['diagram'].get('model')}")
c = load("d3")
need("d3", c["model"] == "A1C" and c["companion"]["mode"] == "ghost" and c["companion"]["model"] == "A1G",
     f"model {c['model']}, companion {c['companion']}")
e = load("d4")
need("d4", e["model"] == "A1H" and e["omega"] == 18 and not e["ramp"]["active"] and e["guide"]["details"] and
     e["guide"]["controls_tab"] in (None, "State"),
     f"model {e['model']}, omega {e['omega']}, details {e['guide']['details']}, tab {e['guide']['controls_tab']}")
f = load("d5")
need("d5", f["model"] == "A1G" and f["omega"] == 13 and f["guide"]["basins_open"], f"model {f['model']}, omega {f['omega']}, {f['guide']}")
for x in fail:
    print("gui_guide:", x)
if fail:
    sys.exit(1)
print("gui_guide: passed")
PY
