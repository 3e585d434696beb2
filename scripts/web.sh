#!/usr/bin/env bash
# Builds build-web/impactlab.html: the visualiser as one self-contained page (WebAssembly and font inside)
# that opens from disk in any browser with WebGL2. Debian's packages only: emscripten, and Dear ImGui's
# own sources from Debian's imgui source package, fetched with apt-get source through a private sources
# list and cache under build-web/apt (the system's apt setup is left as it is).
#   bash scripts/web.sh            # installs emscripten if missing (apt-get), then builds
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out=$root/build-web
mkdir -p "$out"

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
need=()
for p in emscripten dpkg-dev python3 cmake libeigen3-dev nlohmann-json3-dev libstb-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "web: installing ${need[*]}"
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}"
fi

# Dear ImGui 1.86, the version libimgui-dev has, from Debian's source package (a private apt state).
imgui_version=$(dpkg-query -W -f='${source:Version}' libimgui-dev 2>/dev/null || true)
imgui_version=${imgui_version:-1.86+ds-1}
apt_dir=$out/apt
imgui_src=$(ls -d "$apt_dir"/src/imgui-*/ 2>/dev/null | head -n 1 || true)
if [ -z "$imgui_src" ] || [ ! -f "$imgui_src/imgui.cpp" ]; then
  mkdir -p "$apt_dir"/{lists/partial,cache/archives/partial,etc/sources.list.d,src}
  codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-bookworm}")
  echo "deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian $codename main" \
    > "$apt_dir/etc/sources.list"
  : > "$apt_dir/status"
  apt_opts=(-o "Dir::Etc::SourceList=$apt_dir/etc/sources.list" -o "Dir::Etc::SourceParts=$apt_dir/etc/sources.list.d"
            -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache" -o "Dir::State::status=$apt_dir/status"
            -o "APT::Sandbox::User=$(id -un)" -o "Debug::NoLocking=1")
  echo "web: apt-get source imgui=$imgui_version (private sources list in $apt_dir)"
  apt-get "${apt_opts[@]}" update -qq
  (cd "$apt_dir/src" && apt-get "${apt_opts[@]}" source -qq "imgui=$imgui_version")
  imgui_src=$(ls -d "$apt_dir"/src/imgui-*/ | head -n 1)
fi
imgui_src=${imgui_src%/}

# Emscripten finds acorn and its other node modules in Debian's folder even under another node.
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}
jobs=${IMPACTLAB_WEB_JOBS:-2}
emcmake cmake -S app/web -B "$out/cmake" -DIMPACTLAB_IMGUI_SRC="$imgui_src" -DCMAKE_BUILD_TYPE=Release > "$out/configure.log" \
  || { cat "$out/configure.log"; exit 1; }
cmake --build "$out/cmake" -j "$jobs"

# The page: app/web/shell.html with the JavaScript (WebAssembly inside) in place of {{IMPACTLAB_JS}}.
python3 - "$root/app/web/shell.html" "$out/cmake/impactlab.js" "$out/impactlab.html" <<'PY'
import sys
shell, js, out = sys.argv[1:]
page = open(shell, encoding="utf-8").read()
code = open(js, encoding="utf-8").read().replace("</script", "<\\/script")
open(out, "w", encoding="utf-8").write(page.replace("{{IMPACTLAB_JS}}", code, 1))
PY
size=$(stat -c %s "$out/impactlab.html")
echo "web: wrote $out/impactlab.html ($((size / 1024)) KiB); open it in a browser (file://$out/impactlab.html)"
