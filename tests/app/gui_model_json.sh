#!/bin/sh
# --model FILE.json in the visualiser reads the parameter file with the core's parser, as the CLI does:
#  1. {"base": "A1G", "k": 1300, "m0e": 0.027, "xI": 0.001} runs A1G with k and m0e edited (the Parameters
#     panel's values, starred) and the bumper at 1 mm; --state-json names the file.
#  2. A file with a bad value is refused (exit 2) with the CLI's own words ("--model: FILE: key 'k': ...").
#  3. A file with a force effect, which the visualiser cannot run, is refused naming the key 'effects'.
# Exit 77 (CTest's skip code) without xvfb-run or python3.
# usage: gui_model_json.sh IMPACTLAB_GUI IMPACTLAB OUT_DIR
gui="$1"; cli="$2"; dir="$3"
TEST=gui_model_json
. "$(dirname "$0")/gui_lib.sh"
gui_need xvfb-run python3
mkdir -p "$dir"
cd "$dir" || exit 1
printf '{ "base": "A1G", "name": "A1G, stiffer", "k": 1300, "m0e": 0.027, "xI": 0.001 }\n' >model_good.json
printf '{ "base": "A1H", "k": "x" }\n' >model_bad.json
printf '{ "base": "A1H", "effects": [ { "id": "constant_force", "F0": -0.36 } ] }\n' >model_effect.json

gui_json state --model model_good.json --frames 5
"$gui" --model model_bad.json --frames 5 >gui_bad.log 2>&1; rc=$?
"$cli" orbit --model model_bad.json --omega 10 --out orbit.csv >cli_bad.log 2>&1
g=$(sed -n 's/^impactlab-gui: error: //p' gui_bad.log); c=$(sed -n 's/^impactlab: error: //p' cli_bad.log)
if [ $rc -ne 2 ] || [ -z "$g" ] || [ "$g" != "$c" ]; then
    cat gui_bad.log cli_bad.log; echo "$TEST: a bad file: exit $rc, the GUI says '$g', the CLI '$c'"; exit 1
fi
"$gui" --model model_effect.json --frames 5 >gui_effect.log 2>&1; rc=$?
if [ $rc -ne 2 ] || ! grep -q "model_effect.json: key 'effects'" gui_effect.log; then
    cat gui_effect.log; echo "$TEST: a file with an effect should exit 2 naming 'effects', got $rc"; exit 1
fi

python3 - <<'PY'
import json, sys
s = json.load(open("state.json"))
fail = []
if s["model"] != "A1G" or s["model_file"] != "model_good.json" or abs(s["xI"] - 0.001) > 1e-12:
    fail.append(f"model {s['model']}, file {s['model_file']}, xI {s['xI']}")
if s["params"]["k"] != 1300 or s["params"]["m0e"] != 0.027 or not s["params_edited"]:
    fail.append(f"params {s['params']} (edited {s['params_edited']})")
for f in fail:
    print("gui_model_json:", f)
if fail:
    sys.exit(1)
print("gui_model_json: passed")
PY
