# Shared by the GUI tests (gui_*.sh), sourced after they set TEST (their name in messages), gui (the
# impactlab-gui binary) and dir (their output folder). POSIX sh.

# gui_need TOOL...: skip the test (exit 77, CTest's skip code) when a tool is missing.
gui_need() {
    for tool; do
        if ! command -v "$tool" >/dev/null 2>&1; then
            echo "$TEST: $tool is not installed: skipped"
            exit 77
        fi
    done
}

# gui_exec NAME ARGS...: the GUI headless under Xvfb with Mesa's software OpenGL on a GUI_SCREEN
# (default 1280x800) screen; its output in $dir/NAME.log, its exit status in $rc.
gui_exec() {
    name="$1"; shift
    xvfb_rc "$dir/$name.rc" "$gui" "$@" >"$dir/$name.log" 2>&1
}

# xvfb_rc RCFILE PROGRAM ARGS...: PROGRAM under Xvfb; its own exit status in $rc. xvfb-run's clean-up of its
# temporary folder can fail after the program has ended (exit 5, "problem while cleaning up temporary
# directory", a race seen when the program exits within a few frames): the program's status is what counts.
xvfb_rc() {
    xvfb_rcfile="$1"; shift
    rm -f "$xvfb_rcfile"
    LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 ${GUI_SCREEN:-1280x800}x24" \
        sh -c 'f="$1"; shift; "$@"; echo $? >"$f"' sh "$xvfb_rcfile" "$@"
    rc=$?
    if [ -s "$xvfb_rcfile" ]; then rc=$(cat "$xvfb_rcfile"); fi
}

# gui_refuses FLAG ARGS...: the GUI given ARGS must exit 2 (a usage error, before any window) naming FLAG.
gui_refuses() {
    flag="$1"; shift
    "$gui" "$@" >"$dir/refused.log" 2>&1
    refused_rc=$?
    if [ $refused_rc -ne 2 ] || ! grep -q -- "$flag" "$dir/refused.log"; then
        cat "$dir/refused.log"; echo "$TEST: '$*' should exit 2 naming $flag, got $refused_rc"; exit 1
    fi
}

# gui_json NAME ARGS...: as gui_exec, with --state-json $dir/NAME.json; fails the test on a non-zero exit.
gui_json() {
    json_name="$1"; shift
    rm -f "$dir/$json_name.json"
    gui_exec "$json_name" "$@" --state-json "$dir/$json_name.json"
    if [ $rc -ne 0 ]; then cat "$dir/$json_name.log"; echo "$TEST: $json_name: impactlab-gui exited with $rc"; exit 1; fi
}
