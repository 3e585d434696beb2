// impactlab.html's main: the visualiser in a browser tab. The page's URL parameters are the desktop flags
// (?model=A1H&preset=2&frames=900 is --model A1H --preset 2 --frames 900; a parameter without a value,
// ?presentation, is a flag alone). The browser owns the frame loop: App::loop_once() runs once per
// animation frame, and the simulation's slice runs inside it (SimThread::pump: no threads in a file://
// page). With frames=N, after N frames the page writes what --state-json writes into <pre id="state-json">
// and stops. Such a scripted run steps on timers, so that a browser under virtual time runs it too.
// Files: what the program writes into its working folder (/home/web_user: a saved session, a screenshot, a
// CSV export) is handed to the browser as a download; a file picked with the page's "Open a file" or dropped
// on the canvas is written into the page's memory and opened (a session, or a measured record).
#include <emscripten.h>
#include <emscripten/html5.h>
#include <GLFW/glfw3.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "window/app.hpp"
#include "window/bench.hpp"
#include "window/options.hpp"

// clang-format off
// The query string as flags, one per line ("--model\nA1H\n--presentation\n...").
EM_JS(char*, web_query_flags, (), {
    const q = new URLSearchParams(window.location.search);
    let out = "";
    for (const e of q.entries()) {   // no destructuring: emscripten 3.1.6's JS optimiser drops it
        if (e[0] === "gl-cache") continue;   // the page's own (shell.html), not the program's
        out += "--" + e[0] + "\n";
        if (e[1] !== "") out += e[1] + "\n";
    }
    return stringToNewUTF8(out);
});
EM_JS(void, web_set_text, (const char* id, const char* text), {
    const el = document.getElementById(UTF8ToString(id));
    if (el) el.textContent = UTF8ToString(text);
});
EM_JS(void, web_mark_done, (int code), { document.body.setAttribute("data-exit", String(code)); });
// The file at `path` (in the page's memory) as a download named `name`.
EM_JS(void, web_download, (const char* path, const char* name), {
    const data = FS.readFile(UTF8ToString(path));
    const url = URL.createObjectURL(new Blob([data], { type: "application/octet-stream" }));
    const a = document.createElement("a");
    a.href = url;
    a.download = UTF8ToString(name);
    document.body.appendChild(a);
    a.click();
    setTimeout(function () { URL.revokeObjectURL(url); a.remove(); }, 5000);
});
// The page's "Open a file" input: each file picked is copied into /home/web_user/opened/ and handed to the
// program (web_open_file). Drops on the canvas reach GLFW's drop callback instead.
EM_JS(void, web_install_picker, (), {
    const input = document.getElementById("open-file");
    if (!input) return;
    input.addEventListener("change", function () {
        for (let i = 0; i < input.files.length; ++i) {
            const file = input.files[i];
            const reader = new FileReader();
            reader.onload = function () {
                const dir = "/home/web_user/opened";
                try { FS.mkdir(dir); } catch (e) { }
                const path = dir + "/" + file.name.split("/").join("_");
                FS.writeFile(path, new Uint8Array(reader.result));
                _web_open_file(stringToNewUTF8(path));
            };
            reader.onerror = function () { console.warn("impactlab: cannot read " + file.name + ": " + reader.error); };
            reader.readAsArrayBuffer(file);
        }
        input.value = "";
    });
});
EM_JS(int, web_view_width, (), { return window.innerWidth; });
EM_JS(int, web_view_height, (), { return window.innerHeight; });
// clang-format on

namespace {

using impactlab::gui::App;
std::unique_ptr<App> g_app;
bool g_fixed_size = false;   // ?size=WxH: the canvas keeps it; otherwise it follows the browser window
int g_w = 0, g_h = 0;
constexpr const char* kStateFile = "/state.json";

void fail(const std::string& what) {
    std::fprintf(stderr, "impactlab: error: %s\n", what.c_str());
    web_set_text("status", ("error: " + what).c_str());
    web_mark_done(1);
}

// The frame rate as frames over wall time from the first frame to the last (the App's own fps is a
// smoothed 1/frame time, which reads high when long and short frames alternate).
long g_frames = 0;
double g_first_ms = 0, g_tick_ms = 0;   // g_tick_ms: time spent in tick() (building and submitting frames)

// Downloads: the regular files directly in the working folder (a dot file is a write in progress), each
// offered again when its size or time changes. Subfolders (a clip's frames, opened files) stay in the page.
constexpr const char* kHome = "/home/web_user";
std::map<std::string, std::pair<std::uintmax_t, std::filesystem::file_time_type>> g_offered;

void offer_downloads() {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (fs::directory_iterator it(kHome, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.' || !it->is_regular_file(ec)) continue;
        const auto stamp = std::make_pair(it->file_size(ec), it->last_write_time(ec));
        if (ec) continue;
        auto [slot, fresh] = g_offered.try_emplace(name, stamp);
        if (!fresh && slot->second == stamp) continue;
        slot->second = stamp;
        web_download(it->path().c_str(), name.c_str());
        std::printf("web: download %s (%ju bytes)\n", name.c_str(), stamp.first);
    }
}

void finish() {
    const double s = (emscripten_get_now() - g_first_ms) / 1000.0;
    if (g_frames > 1 && s > 0)
        std::printf("web: %ld frames in %.1f s: %.1f frames per second, %.1f ms a frame in the page's code\n", g_frames - 1,
                    s, static_cast<double>(g_frames - 1) / s, g_tick_ms / static_cast<double>(g_frames));
    const int code = g_app->finish();
    offer_downloads();   // --save-session, --screenshot and the like write at the end
    std::ifstream in(kStateFile);
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    web_set_text("state-json", json.c_str());
    web_mark_done(code);
}

void tick() {
    const double t0 = emscripten_get_now();
    if (g_frames++ == 0) g_first_ms = t0;
    struct Clock {
        double t0;
        ~Clock() { g_tick_ms += emscripten_get_now() - t0; }
    } clock{t0};
    try {
        if (!g_fixed_size) {   // follow the browser window
            const int w = web_view_width(), h = web_view_height();
            if (w != g_w || h != g_h) {
                g_w = w;
                g_h = h;
                if (GLFWwindow* win = glfwGetCurrentContext()) glfwSetWindowSize(win, w, h);
            }
        }
        if (g_frames % 15 == 0) offer_downloads();
        if (!g_app->loop_once()) {
            emscripten_cancel_main_loop();
            finish();
        }
    } catch (const std::exception& e) {
        emscripten_cancel_main_loop();
        fail(e.what());
    }
}

}  // namespace

// A file the page's picker copied into memory (web_install_picker); takes `path` (malloc'd) over.
extern "C" EMSCRIPTEN_KEEPALIVE void web_open_file(char* path) {
    if (g_app) g_app->open_user_file(path);
    std::free(path);
}

int main() {
    using namespace impactlab::gui;
    // Relative names (a session's, a screenshot's, a CSV export's) land where offer_downloads looks.
    std::error_code ec;
    std::filesystem::create_directories(kHome, ec);
    std::filesystem::current_path(kHome, ec);
    std::vector<std::string> args;
    {
        char* flags = web_query_flags();
        std::istringstream lines(flags);
        std::free(flags);
        for (std::string line; std::getline(lines, line);) args.push_back(line);
    }
    Options opt;
    try {
        opt = parse_options(args);
    } catch (const OptionsError& e) {
        fail(std::string("URL parameters: ") + e.what());
        return 0;
    }
    if (opt.bench_sim) {   // ?bench-sim: the simulation's rate in this browser, printed into #log
        web_set_text("status", "");
        // Three passes: the browser compiles the WebAssembly with its fast baseline compiler first and
        // optimises the hot functions while they run, so the first pass is slower; the best one counts.
        for (int pass = 1; pass <= 3; ++pass) {
            std::printf("bench-sim: pass %d of 3\n", pass);
            bench_sim();
        }
        web_mark_done(0);
        return 0;
    }
    for (const std::string& a : args) g_fixed_size = g_fixed_size || a == "--size";
    if (!g_fixed_size) {
        g_w = opt.width = web_view_width();
        g_h = opt.height = web_view_height();
    }
    if (opt.frames > 0) opt.state_json = kStateFile;   // read back into the page when the frames are done
    try {
        g_app = std::make_unique<App>(opt);
        if (std::string error; !g_app->open(error)) {
            fail(error);
            return 0;
        }
    } catch (const std::exception& e) {
        fail(e.what());
        return 0;
    }
    web_set_text("status", "");
    web_install_picker();
    // 0 frames per second: the browser's animation frames; no simulated infinite loop (main returns and
    // the runtime stays alive with the App in g_app). An open page, and ?bench-plot, run on them.
    // A scripted run (?frames=N) steps on 16 ms timers from its first frame on: under virtual time (headless
    // Chromium's --virtual-time-budget) a wait for anything but a timer can spend the whole budget at once.
    if (opt.frames > 0) {
        emscripten_set_main_loop(tick, 60, 0);   // frames per second > 0: the first frame on a timer too
        emscripten_set_main_loop_timing(EM_TIMING_SETTIMEOUT, 16);
    } else {
        emscripten_set_main_loop(tick, 0, 0);
    }
    return 0;
}
