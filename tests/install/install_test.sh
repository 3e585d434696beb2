#!/bin/sh
# The desktop install: cmake --install into a temporary prefix, then both programs run from an unrelated
# directory and find their font and icon under PREFIX/share/impactlab. Checks the .desktop entry and the
# AppStream metainfo with their validators where installed. The GUI part is skipped without xvfb-run.
# usage: install_test.sh BUILD_DIR PNG_CHECK OUT_DIR
build="$1"; check="$2"; dir="$3"
here=$(cd "$(dirname "$0")" && pwd)
set -u
rm -rf "$dir"
mkdir -p "$dir/elsewhere"
prefix="$dir/prefix"
fail() { echo "install_test: $*"; exit 1; }
cmake --install "$build" --prefix "$prefix" >"$dir/install.log" 2>&1 || { cat "$dir/install.log"; fail "cmake --install failed"; }
for f in bin/impactlab bin/impactlab-gui share/impactlab/fonts/DejaVuSans.ttf share/impactlab/fonts/DejaVu-LICENSE.txt \
         share/impactlab/icons/impactlab-64.png share/impactlab/shaders/rig_shapes.vert share/impactlab/shaders/rig_shapes.frag \
         share/applications/io.github.impactlab.impactlab.desktop share/icons/hicolor/64x64/apps/impactlab.png \
         share/metainfo/io.github.impactlab.impactlab.metainfo.xml; do
    [ -f "$prefix/$f" ] || fail "not installed: $f"
done
if command -v desktop-file-validate >/dev/null 2>&1; then
    desktop-file-validate "$prefix/share/applications/io.github.impactlab.impactlab.desktop" || fail "the .desktop entry does not validate"
fi
if command -v appstreamcli >/dev/null 2>&1; then
    appstreamcli validate --no-net --pedantic "$prefix/share/metainfo/io.github.impactlab.impactlab.metainfo.xml" >"$dir/appstream.log" 2>&1 ||
        { cat "$dir/appstream.log"; fail "the metainfo file does not validate"; }
fi

cd "$dir/elsewhere" || fail "no directory $dir/elsewhere"
# The command-line program: a short CF sweep and its plot (the plot's text needs the font).
"$prefix/bin/impactlab" bifurcation --model A1H --sweep up --steps 12 --out diag.csv --png diag.png >cli.log 2>&1 ||
    { cat cli.log; fail "impactlab bifurcation failed from $dir/elsewhere"; }
[ -s diag.csv ] && [ -s diag.png ] || fail "impactlab wrote no diagram"
"$check" diag.png || fail "the installed impactlab's plot is not a real picture"

# The Python module, where the build has it: installed under the prefix's dist-packages and imported from here.
python=$(sed -n 's/^IMPACTLAB_PYTHON_EXECUTABLE:INTERNAL=//p' "$build/CMakeCache.txt")
if [ -n "$python" ] && [ -d "$build/python/impactlab" ]; then
    pkg="$prefix/lib/python3/dist-packages"
    for f in __init__.py __init__.pyi _result.py py.typed; do [ -f "$pkg/impactlab/$f" ] || fail "not installed: $pkg/impactlab/$f"; done
    ls "$pkg"/impactlab/_impactlab*.so >/dev/null 2>&1 || fail "not installed: the extension under $pkg/impactlab"
    PYTHONPATH="$pkg" "$python" -c "import impactlab; assert impactlab.__file__.startswith('$pkg'); \
print(impactlab.simulate(impactlab.Model.from_name('A1H'), omega=18, duration=5)['x'][:3])" >py.log 2>&1 ||
        { cat py.log; fail "the installed Python module does not run from $dir/elsewhere"; }
fi

if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "install_test: xvfb-run is not installed: the installed impactlab-gui was not run"
    exit 0
fi
# The program's own exit status, not xvfb-run's (whose clean-up can race a quick exit): gui_lib's xvfb_rc.
TEST=install_test
. "$here/../app/gui_lib.sh"
xvfb_rc "$PWD/gui.rc" "$prefix/bin/impactlab-gui" --frames 30 --screenshot gui.png --model A1H --preset 1 >gui.log 2>&1
[ "$rc" -eq 0 ] || { cat gui.log; fail "the installed impactlab-gui failed (exit $rc)"; }
if grep -q "not found" gui.log; then cat gui.log; fail "the installed impactlab-gui did not find its font"; fi
"$check" gui.png 1280 800 || fail "the installed impactlab-gui's screenshot is not a real picture"
echo "install_test: installed into $prefix; impactlab and impactlab-gui ran from $dir/elsewhere"
