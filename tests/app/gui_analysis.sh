#!/bin/sh
# The analysis views under Xvfb: a plane CSV loaded with --plane, the continued branches
# (--continuation) and the basins (--basins) computed on their workers before the frames are counted; the
# screenshot must be a real picture and the log must report each result. A plane CSV with a bad line must
# make the run exit 1 naming the file and the line (the window shows the same message and keeps going).
# Exit 77 (CTest's skip code) when xvfb-run is not installed.
# usage: gui_analysis.sh IMPACTLAB_GUI PNG_CHECK OUT_DIR
gui="$1"; check="$2"; dir="$3"
if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "gui_analysis: xvfb-run is not installed (apt-get install xvfb xauth): skipped"
    exit 77
fi
mkdir -p "$dir"
TEST=gui_analysis
. "$(dirname "$0")/gui_lib.sh"
plane="$dir/plane.csv"; bad="$dir/bad_plane.csv"; png="$dir/gui_analysis.png"; log="$dir/gui_analysis.log"
rm -f "$png" "$log"
# A 4 x 3 (omega, xI) plane as impactlab scan writes it: x fastest.
{
    echo "omega,xI,period,impacts"
    for y in -0.005 0 0.005; do
        for w in 8 10 12 14; do
            p=1; [ "$w" = 12 ] && p=2; [ "$w" = 14 ] && p=0
            echo "$w,$y,$p,1"
        done
    done
} >"$plane"
xvfb_rc "$dir/run.rc" "$gui" --model A1G --omega 13 --plane "$plane" --continuation --basins --frames 20 --switch-model A1G \
    --screenshot "$png" >"$log" 2>&1
cat "$log"
[ $rc -eq 0 ] || { echo "gui_analysis: impactlab-gui exited with $rc"; exit 1; }
[ -f "$png" ] || { echo "gui_analysis: no screenshot written"; exit 1; }
"$check" "$png" 1280 800 || exit 1
grep -q "continuation A1G: [1-9][0-9]* curves, [1-9][0-9]* bifurcation points" "$log" ||
    { echo "gui_analysis: no continued branches reported"; exit 1; }
grep -q "basins at omega = 13.000: [1-9][0-9]* attractors" "$log" || { echo "gui_analysis: no basins reported"; exit 1; }

# Line 4 of this file is short of a field.
printf 'omega,xI,period\n8,0,1\n10,0,1\n12,0\n' >"$bad"
xvfb_rc "$dir/bad.rc" "$gui" --model A1G --plane "$bad" --frames 5 --switch-model A1G >"$log" 2>&1
cat "$log"
[ $rc -eq 1 ] || { echo "gui_analysis: a bad plane file gave exit code $rc, not 1"; exit 1; }
grep -q "$bad:4: expected 3 fields" "$log" || { echo "gui_analysis: the error does not name $bad:4"; exit 1; }
echo "gui_analysis: passed"
exit 0
