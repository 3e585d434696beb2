#include "options.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <optional>
#include <string_view>
#include <tuple>
#include <utility>

#include "analysis/bifurcation_job.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"
#include "window/layout.hpp"
#include "sim/param_edit.hpp"
#include "analysis/plane_curves.hpp"
#include "sim/presets.hpp"
#include "files/model_file.hpp"
#include "files/session.hpp"
#include "views/strip_keys.hpp"

namespace impactlab::gui {

const char* usage_text() {
    return "usage: impactlab-gui [options]\n"
           "\n"
           "Interactive visualiser of the forced impact oscillator: the rig animated, phase portrait,\n"
           "Poincare map, potential well, x(t) and bifurcation diagrams, all live.\n"
           "\n"
           "  --model NAME       model version: A1C, A1C1, A1G, A1H, A3C, A3C1, A3G, A3H (default A1H), or a\n"
           "                     parameter file FILE.json as the CLI reads it (its version, the Parameters\n"
           "                     panel's values and x_I; anything else it holds is refused, naming the key)\n"
           "  --omega W          forcing frequency [rad/s], 0..30 (default 9)\n"
           "  --xI X             bumper position [m], -0.02..0.02 (default 0)\n"
           "  --x0 X, --v0 V     initial state [m], [m/s] (default -0.011, 0: the left well)\n"
           "  --speed S          simulated seconds per real second, 0.01..100 (default 1)\n"
           "  --paused           start paused\n"
           "  --warmup S         first run S simulated seconds at 100x (the Poincare map fills), then --speed\n"
           "  --theme dark|light colour theme (default dark)\n"
           "  --scale S, --ui-scale S  UI scale, 0.5..3 (default: the monitor's content scale)\n"
           "  --presentation [P] presentation mode (key P): the rig and plot P large under a slim bar;\n"
           "                     P one of phase (default), poincare, potential, strip, bifurcation\n"
           "  --hide PANEL       hide a panel (repeatable, or comma-separated): controls, rig, bifurcation,\n"
           "                     phase, poincare, potential, strip (View > Panels shows it again)\n"
           "  --maximise PANEL   start with PANEL filling the plot area (key Z over a panel, Esc restores)\n"
           "  --magnify G        the rig's displacement magnification, 1..10 (default 1; 3 in presentation)\n"
           "  --size WxH         window size in pixels (default 1280x800)\n"
           "  --preset N         start on preset N of the model (1-4, as keys 1-4: period 1, period 2, chaos,\n"
           "                     a periodic window); sets omega, x0 and xI = 0 (over --omega, --x0, --xI)\n"
           "  --show-help        open the keyboard shortcuts window at start\n"
           "  --param KEY=VALUE  set a parameter of the model at start, as the Parameters panel (F4) does\n"
           "                     (repeatable; m, c, k, T, m0e, eps or the impact law's: kI, kappa0, ...)\n"
           "  --show-params      open the Parameters panel at start\n"
           "  --guide            open \"What to try\" (it opens by itself when no flag scripts the run)\n"
           "  --demo N           run its demonstration N at start: 1 period doubling, 2 the road to chaos,\n"
           "                     3 switching the impact model, 4 the energy budget, 5 basins of attraction\n"
           "  --details          the status bar's technical fields (epoch, samples, dropped)\n"
           "  --clicker          the Poincare clicker on: each click on the map starts an orbit in its own colour\n"
           "  --orbit X,V        (repeatable) such a click at x = X m, v = V m/s, spread over --frames\n"
           "  --phi0 RAD         the Poincare section's phase: points at phi = RAD + 2 pi k, 0..2 pi (default 0)\n"
           "  --strip Q[,Q2]     the time strip's trace and a second one below it: x, v, E (energy),\n"
           "                     F (bumper force), drive (m0e ω² cos φ); default x (right-click the strip)\n"
           "  --bifurcation P    compute a bifurcation diagram at start: cf-up, cf-down or ef\n"
           "  --bif-steps N      omega steps of a CF sweep, 10..2000 (default 300)\n"
           "  --bif-zoom W0:W1   show the diagram zoomed to omega in [W0, W1] (wheel, drag and double-click\n"
           "                     zoom, pan and reset every plot)\n"
           "  --ramp W1:RATE     ramp omega live from --omega to W1 rad/s at RATE rad/s per s (1e-3 .. 2), drawing\n"
           "                     the section points over the bifurcation diagram as it goes\n"
           "  --bif-range W0:W1  compute the diagram over omega in [W0, W1], 0 <= W0 < W1 <= 30 (default 0:25;\n"
           "                     EF: the ramp ends at W1)\n"
           "  --bif-box W0:W1    once the first diagram is done, compute [W0, W1] as a box dragged on it with\n"
           "                     the right mouse button does (the same steps over the narrower range)\n"
           "  --bif-y x|v        the diagram's quantity at the sections: x (default) or v\n"
           "  --bif-over P       the diagram's swept parameter: omega (default), xI or m0e, the latter two moved\n"
           "                     at the fixed --omega (CF only); --bif-range, --bif-box and --bif-zoom are then\n"
           "                     in its SI units: xI in [-0.1, 0.1] m, m0e in (0, 10] kg m\n"
           "  --bif-lyapunov     the lambda_max(omega) strip under the diagram, computed with it (slow)\n"
           "  --lyap-steps N     omegas of that strip, 5..300 (default 60)\n"
           "  --bif-settle N     CF: a level whose section points do not yet recur (period <= 32) runs up to N\n"
           "                     more records, as impactlab bifurcation --settle; still unsettled, it is drawn\n"
           "                     grey, 'not settled' (default 10; 0: no verdicts, every level drawn alike)\n"
           "  --bif-nowait       with --frames: count the frames while the diagram computes (a screenshot\n"
           "                     of it half-filled)\n"
           "  --data FILE        load a measured run (CSV, plain or gzip) into the Measured data window\n"
           "                     and fit the model to it (with --frames: counted once the fit is done,\n"
           "                     and no model switch unless --switch-model is given)\n"
           "  --plane FILE       show a parameter plane (impactlab scan --out FILE) in the Parameter plane\n"
           "                     tile; a bad file is reported there naming its line (exit 1 with --frames)\n"
           "  --continuation     continue the period-1 branch over the diagram's omega range at start (key O)\n"
           "  --continue-here    continue the running orbit over the diagram's range once the Poincare map has\n"
           "                     settled on it (Shift+O); a chaotic map is an error (exit 1 with --frames)\n"
           "  --small-plane      compute a 60 x 30 (omega, xI) plane at start (the Parameter plane tile, F2)\n"
           "  --plane-doubling   continue the first period-1 doubling over the plane (--plane or --small-plane)\n"
           "  --plane-grazing auto|W,X,V[,K]  continue a grazing over the plane (dashed): the first period-1\n"
           "                     one over its omega range, or the period-K orbit's at omega W through (X, V) [m,\n"
           "                     m/s], as impactlab continue prints it (impactlab scan --grazing-from)\n"
           "  --plane-fold auto|W,X,V[,K]  the same for a fold (dotted; impactlab scan --fold-from)\n"
           "  --basins           compute the basins of attraction at --omega at start (the Basins tile, F3)\n"
           "  --basins-box X0:X1:V0:V1  the basins over that box of (x0 [m], v0 [m/s]) (a right-drag on them)\n"
           "  --browse DIR       open File > Load session on DIR: its folders and .json files, listed\n"
           "  --session FILE     load a session (File > Load session, Ctrl+O) at start; a bad file is refused\n"
           "                     naming the file, the key (or line) and the problem (exit 2)\n"
           "  --twin             a second cart 1 um to the right of the first, same model (sensitivity)\n"
           "  --ghost M          a second cart from the same state under the impact law of version M (A1G)\n"
           "  --set-state X,V    at the first frame set x [m], v [m/s] as a click in the phase portrait does\n"
           "\n"
           "Headless checks and benchmarks:\n"
           "  --frames N         render N frames, switch the model once half-way, save --screenshot, print\n"
           "                     the simulated time reached and exit (with --bifurcation or --warmup:\n"
           "                     counted once the diagram is done and the warm-up is over)\n"
           "  --screenshot FILE  PNG written after --frames\n"
           "  --press [ctrl+]K   press key K (a-z), with Ctrl if asked, at frame 3 (tests of the shortcuts)\n"
           "  --tap K            press and release key K (a-z) within one frame's events at frame 3, as a tap\n"
           "                     shorter than a frame does (xdotool key K)\n"
           "  --double-click ROW (repeatable) a double-click on the session browser's row ROW (\"sub/\" for a\n"
           "                     folder), the mouse held still where that row was at the first click; the k-th\n"
           "                     from frame 10 + 8 k (tests of the browser)\n"
           "  --state-json FILE  JSON written after --frames: model, omega, xI, sim_time, fps, and the Poincare\n"
           "                     map as shown: poincare_period (k, 0 for chaos, null while settling) and\n"
           "                     poincare_points [[x, v], ...] [m, m/s]. With --preset, --state-json or --data\n"
           "                     no model switch happens unless --switch-model is given\n"
           "  --switch-model M   the version switched to half-way (default: H <-> G, same stiffness)\n"
           "  --save-session F   with --frames: save the session (as Ctrl+S does) at the end\n"
           "  --clip-out DIR     with --frames: at the end, export the last --clip-seconds as a clip into a new\n"
           "                     folder in DIR: PNG frames at 30 fps, and clip.mp4 where ffmpeg is on PATH\n"
           "  --clip-seconds S   [s] of simulated time for --clip-out, 0.1..60 (default 2)\n"
           "  --replay-back S    with --frames: end in replay S seconds before the newest sample (Shift+R)\n"
           "  --replay-continue  with --replay-back: continue the run from there (Enter), 60 frames more\n"
           "  --then-preset N    apply preset N half-way instead (as pressing key N)\n"
           "  --then-xI X        move the bumper to X [m] half-way instead (as the x_I slider)\n"
           "  --then-omega W     set omega to W [rad/s] half-way instead (as the arrow keys: live, no reset)\n"
           "  --then-phi0 RAD    set the section phase to RAD half-way instead (as its slider: the map restarts)\n"
           "  --bench-plot       frames per second with --points points on every plot (needs a display)\n"
           "  --points N         points per plot for --bench-plot (default 100000)\n"
           "  --plot-backend B   how dense curves are drawn: raster (CPU, default), gpu (instanced\n"
           "                     shaders), imgui (ImDrawList polylines)\n"
           "  --bench-ring       samples per second through the SPSC ring buffer (two threads)\n"
           "  --bench-sim        the simulation's real-time factor, A1H and A1C at omega = 18\n"
           "  --soak S           run S wall seconds at 100x, switching the model every 3 s through all\n"
           "                     versions; print RSS and dropped samples every 10 s; exit 1 if the\n"
           "                     memory grows by more than 16 MB after the first quarter\n"
           "  --help             this text\n"
           "\n"
           "Keys: space pause, N step one period, R reset, left/right omega, up/down xI, [ ] speed,\n"
           "      M impact model, K stiffness, B bifurcation, C clear Poincare map, O continued branches,\n"
           "      P presentation mode, V its plot, Z maximise the panel under the mouse, Esc restore,\n"
           "      Shift+R replay, Ctrl+S / Ctrl+O save / load a session,\n"
           "      F2 parameter plane, F3 basins, F1 help (all in the app).\n";
}

namespace {

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

double number(const std::string& flag, const std::string& text, double lo, double hi) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    // An underflow (1e-320) is a number; an overflow (1e309) is not.
    if (text.empty() || end != text.c_str() + text.size() || (errno == ERANGE && std::fabs(v) > 1.0) || !std::isfinite(v))
        throw OptionsError(flag + ": '" + text + "' is not a number");
    if (v < lo || v > hi)
        throw OptionsError(flag + ": " + text + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
    return v;
}

// "A:B" with A in [lo_a, hi_a] and B in [lo_b, hi_b] (--bif-zoom, --bif-range, --bif-box, --ramp); `form` names
// the two parts in the message ("W0:W1").
std::pair<double, double> number_pair(const std::string& flag, const std::string& text, const char* form, double lo_a,
                                      double hi_a, double lo_b, double hi_b) {
    const auto c = text.find(':');
    if (c == std::string::npos) throw OptionsError(flag + ": '" + text + "' is not " + form);
    return {number(flag, text.substr(0, c), lo_a, hi_a), number(flag, text.substr(c + 1), lo_b, hi_b)};
}

// An omega range W0:W1 within [0, 30] rad/s, at least min_width wide.
std::pair<double, double> omega_range(const std::string& flag, const std::string& text, double min_width) {
    const auto r = number_pair(flag, text, "W0:W1", 0.0, 30.0, 0.0, 30.0);
    if (!(r.second - r.first >= min_width)) {
        std::string what = flag;   // (appended: GCC 12's -Wrestrict false positive on a + chain)
        what.append(": ").append(text).append(min_width > 0 ? " is too narrow (W0 < W1 by at least " : " is empty (W0 < W1 wanted");
        if (min_width > 0) what.append(std::to_string(min_width).substr(0, 4)).append(" rad/s wanted");
        throw OptionsError(what.append(")"));
    }
    return r;
}

// --bif-range, --bif-box (at least a box's smallest span wide) or --bif-zoom over the swept parameter `over`:
// omega as omega_range; xI or m0e within sweep_limits [m, kg m], A < B.
std::pair<double, double> bif_range(const std::string& over, const std::string& flag, const std::string& text) {
    const SweepParam s = *parse_sweep_param(over);
    const double min_width = flag == "--bif-box" ? sweep_limits(s).min_box : 0.0;
    if (s == SweepParam::Omega) return omega_range(flag, text, min_width);
    const SweepLimits lim = sweep_limits(s);
    const auto r = number_pair(flag, text, "A:B", lim.lo, lim.hi, lim.lo, lim.hi);
    if (!(r.second - r.first > 0 && r.second - r.first >= min_width))
        throw OptionsError(flag + ": " + text + " is empty or too narrow (A < B wanted, in " + over + "'s " +
                           sweep_param_unit(s) + ")");
    return r;
}

int integer(const std::string& flag, const std::string& text, int lo, int hi) {
    errno = 0;
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
        throw OptionsError(flag + ": '" + text + "' is not an integer");
    if (v < lo || v > hi)
        throw OptionsError(flag + ": " + text + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v);
}

std::string version(const std::string& flag, const std::string& name) {
    try {
        return make_version(name).name;
    } catch (const ParamError&) {
        std::string all;
        for (const auto& n : version_names()) all += (all.empty() ? "" : ", ") + n;
        throw OptionsError(flag + ": unknown model version '" + name + "' (one of " + all + ")");
    }
}

// The flags as they are read: the one at i, and the argument after it as its value.
struct FlagReader {
    const std::vector<std::string>& args;
    std::size_t i = 0;
    const std::string& value() {
        if (i + 1 >= args.size()) throw OptionsError(args[i] + ": missing value");
        return args[++i];
    }
    // The next argument unless it is a flag (an optional value), else null.
    const std::string* optional_value() {
        if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) return &args[++i];
        return nullptr;
    }
};

// What is settled only once every flag is read: --model's file, whether --xI was given, and the ranges that
// are in --bif-over's units.
struct Pending {
    std::optional<GuiModel> model_file;   // --model FILE.json
    bool xI_given = false;
    std::map<std::string, std::string> bif_ranges;   // --bif-range, --bif-box, --bif-zoom
};

// "A,B,C": each part checked by `check`, which throws naming it.
template <class Check> std::vector<std::string> comma_list(const std::string& list, Check check) {
    std::vector<std::string> out;
    for (std::size_t from = 0;;) {
        const std::size_t c = list.find(',', from);
        std::string p = list.substr(from, c == std::string::npos ? std::string::npos : c - from);
        check(p);
        out.push_back(std::move(p));
        if (c == std::string::npos) return out;
        from = c + 1;
    }
}

// Each family of flags below takes flag a (and its value from r) and says whether it did.

// The model and the cart's start.
bool start_flag(const std::string& a, FlagReader& r, Options& o, Pending& pend) {
    if (a == "--model") {
        const std::string& v = r.value();
        if (v.size() > 5 && v.substr(v.size() - 5) == ".json") {   // as every CLI --model: a parameter file
            try {
                pend.model_file = gui_model_from_file(v);
            } catch (const ModelFileError& e) {
                throw OptionsError(std::string("--model: ") + e.what());
            }
            o.model = pend.model_file->version;
            o.model_file = v;
        } else {
            o.model = version(a, v);
            pend.model_file.reset();
            o.model_file.clear();
        }
    } else if (a == "--omega") o.omega = number(a, r.value(), 0.0, 30.0);
    else if (a == "--xI" || a == "--xi") {
        o.xI = number(a, r.value(), -0.02, 0.02);
        pend.xI_given = true;
    } else if (a == "--x0") o.x0 = number(a, r.value(), -0.05, 0.05);
    else if (a == "--v0") o.v0 = number(a, r.value(), -2.0, 2.0);
    else if (a == "--speed") o.speed = number(a, r.value(), 0.01, 100.0);
    else if (a == "--paused") o.paused = true;
    else if (a == "--show-help") o.show_help = true;
    else if (a == "--data") o.data = r.value();
    else if (a == "--warmup") o.warmup = number(a, r.value(), 0.0, 1e5);
    else return false;
    return true;
}

// The window: theme, scale, presentation, panels, size.
bool layout_flag(const std::string& a, FlagReader& r, Options& o) {
    if (a == "--theme") {
        const std::string& t = r.value();
        if (t != "dark" && t != "light") throw OptionsError("--theme: '" + t + "' is neither dark nor light");
        o.light = t == "light";
    } else if (a == "--scale" || a == "--ui-scale") o.ui_scale = number(a, r.value(), 0.5, 3.0);
    else if (a == "--presentation") {
        o.presentation = true;
        if (const std::string* p = r.optional_value()) {   // an optional plot name
            const auto id = panel_from_key(*p);
            if (!id || view_info(*id).presentation_order == 0)
                throw OptionsError("--presentation: '" + *p + "' is not one of " + panel_keys(true));
            o.presentation_plot = *p;
        }
    } else if (a == "--hide") {
        const std::vector<std::string> keys = comma_list(r.value(), [](const std::string& p) {
            if (p != "controls" && !panel_from_key(p)) throw OptionsError("--hide: '" + p + "' is not a panel (controls, " + panel_keys() + ")");
        });
        o.hide.insert(o.hide.end(), keys.begin(), keys.end());
    } else if (a == "--maximise" || a == "--maximize") {
        const std::string& p = r.value();
        if (!panel_from_key(p)) throw OptionsError(a + ": '" + p + "' is not a panel (" + panel_keys() + ")");
        o.maximise = p;
    } else if (a == "--magnify") o.magnify = number(a, r.value(), 1.0, 10.0);
    else if (a == "--size") {
        const std::string& s = r.value();
        const auto x = s.find('x');
        if (x == std::string::npos) throw OptionsError("--size: '" + s + "' is not WIDTHxHEIGHT");
        o.width = integer(a, s.substr(0, x), 320, 8192);
        o.height = integer(a, s.substr(x + 1), 240, 8192);
    } else return false;
    return true;
}

// A scripted run: frames, its files, what changes half-way, the keys and clicks it makes.
bool script_flag(const std::string& a, FlagReader& r, Options& o) {
    if (a == "--frames") o.frames = integer(a, r.value(), 1, 10000000);
    else if (a == "--screenshot") o.screenshot = r.value();
    else if (a == "--state-json") o.state_json = r.value();
    else if (a == "--preset") o.preset = integer(a, r.value(), 1, 100);
    else if (a == "--then-preset") o.then_preset = integer(a, r.value(), 1, 100);
    else if (a == "--then-xI" || a == "--then-xi") {
        o.then_xI = number(a, r.value(), -0.02, 0.02);
        o.then_xi = true;
    } else if (a == "--then-omega") {
        o.then_omega = number(a, r.value(), 0.0, 30.0);
        o.then_w = true;
    } else if (a == "--then-phi0") {
        o.then_phi0 = number(a, r.value(), 0.0, 2.0 * std::numbers::pi);
        o.then_phase = true;
    } else if (a == "--switch-model") o.switch_model = version(a, r.value());
    else if (a == "--set-state") {
        const std::string& sv = r.value();
        const auto c = sv.find(',');
        if (c == std::string::npos) throw OptionsError("--set-state: '" + sv + "' is not X,V (metres, m/s)");
        o.set_x = number(a, sv.substr(0, c), -0.05, 0.05);
        o.set_v = number(a, sv.substr(c + 1), -2.0, 2.0);
        o.set_state = true;
    } else if (a == "--orbit") {
        const std::string& sv = r.value();
        const auto c = sv.find(',');
        if (c == std::string::npos) throw OptionsError("--orbit: '" + sv + "' is not X,V (metres, m/s)");
        o.orbits.emplace_back(number(a, sv.substr(0, c), -0.05, 0.05), number(a, sv.substr(c + 1), -2.0, 2.0));
    } else if (a == "--press") {
        o.press = r.value();
        const std::string key = o.press.rfind("ctrl+", 0) == 0 ? o.press.substr(5) : o.press;
        if (key.size() != 1 || key[0] < 'a' || key[0] > 'z')
            throw OptionsError("--press: '" + o.press + "' is not a letter a-z, with or without ctrl+");
    } else if (a == "--tap") {
        const std::string key = r.value();
        if (key.size() != 1 || key[0] < 'a' || key[0] > 'z') throw OptionsError("--tap: '" + key + "' is not a letter a-z");
        o.tap = key[0];
    } else return false;
    return true;
}

// The bifurcation diagram begun at launch, its ranges and its Lyapunov strip.
bool diagram_flag(const std::string& a, FlagReader& r, Options& o, Pending& pend) {
    if (a == "--bifurcation") {
        const std::string& p = r.value();
        if (p != "cf-up" && p != "cf-down" && p != "ef") throw OptionsError("--bifurcation: '" + p + "' is not one of cf-up, cf-down, ef");
        o.bifurcation = p;
    } else if (a == "--bif-steps") o.bif_steps = integer(a, r.value(), 10, 2000);
    else if (a == "--bif-zoom" || a == "--bif-range" || a == "--bif-box") pend.bif_ranges[a] = r.value();   // once --bif-over is known
    else if (a == "--bif-over") {
        o.bif_over = r.value();
        if (!parse_sweep_param(o.bif_over)) throw OptionsError("--bif-over: '" + o.bif_over + "' is not one of omega, xI, m0e");
    } else if (a == "--ramp")
        std::tie(o.ramp_to, o.ramp_rate) = number_pair(a, r.value(), "W1:RATE (target rad/s : rad/s per s)", 0.0, 30.0, 1e-3, 2.0);
    else if (a == "--bif-y") {
        o.bif_y = r.value();
        if (o.bif_y != "x" && o.bif_y != "v") throw OptionsError("--bif-y: '" + o.bif_y + "' is not x or v");
    } else if (a == "--bif-lyapunov") o.bif_lyapunov = true;
    else if (a == "--lyap-steps") o.lyap_steps = integer(a, r.value(), 5, 300);
    else if (a == "--bif-settle") o.bif_settle = integer(a, r.value(), 0, 100);
    else if (a == "--bif-nowait") o.bif_nowait = true;
    else return false;
    return true;
}

// The analysis jobs begun at launch: planes and their curves, continuation, basins.
bool analysis_flag(const std::string& a, FlagReader& r, Options& o) {
    if (a == "--plane") o.plane = r.value();
    else if (a == "--continuation") o.continuation = true;
    else if (a == "--small-plane") o.small_plane = true;
    else if (a == "--plane-doubling") o.plane_doubling = true;
    else if (a == "--plane-grazing" || a == "--plane-fold") {
        const std::string& v = r.value();
        if (!parse_curve_start(v))
            throw OptionsError(a + ": '" + v + "' is neither auto nor OMEGA,X,V[,K] (a point as impactlab continue prints it, "
                               "omega in [0.05, 1000] rad/s, X in [-0.1, 0.1] m, V in [-10, 10] m/s, K in 1..64)");
        (a == "--plane-fold" ? o.plane_fold : o.plane_grazing) = v;
    } else if (a == "--continue-here") o.continue_here = true;
    else if (a == "--basins") o.basins = true;
    else if (a == "--basins-box") {
        // x0 on the rail, v0 within 2 m/s (the session files' limits), each range not empty.
        const std::string& t = r.value();
        const auto c = t.find(':', t.find(':') + 1);
        if (c == std::string::npos) throw OptionsError("--basins-box: '" + t + "' is not X0:X1:V0:V1 (m, m/s)");
        const auto [x0, x1] = number_pair(a, t.substr(0, c), "X0:X1:V0:V1 (m, m/s)", -0.05, 0.05, -0.05, 0.05);
        const auto [v0, v1] = number_pair(a, t.substr(c + 1), "X0:X1:V0:V1 (m, m/s)", -2.0, 2.0, -2.0, 2.0);
        if (!(x0 < x1) || !(v0 < v1)) throw OptionsError("--basins-box: " + t + " is empty (X0 < X1 and V0 < V1 wanted)");
        o.basins_box = {x0, x1, v0, v1};
        o.basins = true;
    } else return false;
    return true;
}

// Sessions, clips and replay.
bool session_flag(const std::string& a, FlagReader& r, Options& o) {
    if (a == "--session") o.session = r.value();
    else if (a == "--browse") o.browse = r.value();
    else if (a == "--double-click") o.double_clicks.push_back(r.value());
    else if (a == "--save-session") o.save_session = r.value();
    else if (a == "--clip-out") o.clip_out = r.value();
    else if (a == "--clip-seconds") o.clip_seconds = number(a, r.value(), 0.1, 60.0);
    else if (a == "--replay-back") o.replay_back = number(a, r.value(), 0.001, 3600.0);
    else if (a == "--replay-continue") o.replay_continue = true;
    else return false;
    return true;
}

// The panels' own state: the companion cart, the parameters, the guide, the clicker, the time strip.
bool panel_flag(const std::string& a, FlagReader& r, Options& o) {
    if (a == "--twin") o.twin = true;
    else if (a == "--ghost") o.ghost = version(a, r.value());
    else if (a == "--param") {
        const std::string& kv = r.value();
        const auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0) throw OptionsError("--param: '" + kv + "' is not KEY=VALUE (e.g. k=1200)");
        o.params.emplace_back(kv.substr(0, eq), number("--param " + kv.substr(0, eq), kv.substr(eq + 1), -1e300, 1e300));
    } else if (a == "--show-params") o.show_params = true;
    else if (a == "--guide") o.guide = true;
    else if (a == "--demo") o.demo = static_cast<int>(number(a, r.value(), 1, 5));
    else if (a == "--details") o.details = true;
    else if (a == "--clicker") o.clicker = true;
    else if (a == "--phi0") o.phi0 = number(a, r.value(), 0.0, 2.0 * std::numbers::pi);
    else if (a == "--strip") {
        const std::string& list = r.value();
        o.strip = comma_list(list, [](const std::string& q) {
            if (std::find(std::begin(kStripKeys), std::end(kStripKeys), std::string_view(q)) == std::end(kStripKeys))
                throw OptionsError("--strip: '" + q + "' is not one of x, v, E, F, drive");
        });
        if (o.strip.size() > 2) throw OptionsError("--strip: at most two traces ('" + list + "')");
    } else return false;
    return true;
}

// The soak and the benchmarks, and the plot backend they compare.
bool bench_flag(const std::string& a, FlagReader& r, Options& o) {
    if (a == "--soak") o.soak = number(a, r.value(), 1.0, 86400.0);
    else if (a == "--bench-plot") o.bench_plot = true;
    else if (a == "--bench-ring") o.bench_ring = true;
    else if (a == "--bench-sim") o.bench_sim = true;
    else if (a == "--points") o.bench_points = integer(a, r.value(), 1, 10000000);
    else if (a == "--plot-backend") {
        const std::string& b = r.value();
        if (b != "raster" && b != "gpu" && b != "imgui") throw OptionsError("--plot-backend: '" + b + "' is not one of raster, gpu, imgui");
        o.plot_backend = b;
    } else return false;
    return true;
}

// What needs every flag read: the ranges in --bif-over's units, the presets and --param on the model given
// (--model may come after them), the model file's values, and the flags that need another.
void settle(Options& o, const Pending& pend) {
    for (const auto& [flag, text] : pend.bif_ranges) {
        const auto r = bif_range(o.bif_over, flag, text);
        if (flag == "--bif-zoom") std::tie(o.bif_zoom_lo, o.bif_zoom_hi) = r;
        else if (flag == "--bif-range") std::tie(o.bif_range_lo, o.bif_range_hi) = r;
        else std::tie(o.bif_box_lo, o.bif_box_hi) = r;
    }
    if (o.bif_over != "omega" && o.bifurcation == "ef")
        throw OptionsError("--bifurcation ef: the EF ramp is a ramp of omega, not of " + o.bif_over + " (--bif-over): use cf-up or cf-down");
    if (!o.screenshot.empty() && o.frames == 0 && !o.bench_plot) throw OptionsError("--screenshot needs --frames N or --bench-plot");
    if (!o.state_json.empty() && o.frames == 0) throw OptionsError("--state-json needs --frames N");
    for (const auto& [flag, n] : {std::pair{"--preset", o.preset}, std::pair{"--then-preset", o.then_preset}}) {
        const std::size_t count = presets_for(o.model).size();
        if (static_cast<std::size_t>(n) > count)
            throw OptionsError(std::string(flag) + ": " + std::to_string(n) + " is out of range [1, " +
                               std::to_string(count) + "] for " + o.model);
    }
    if (pend.model_file) {   // the file's parameters first (a --param after them wins), its x_I unless --xI is given
        o.params.insert(o.params.begin(), pend.model_file->params.begin(), pend.model_file->params.end());
        if (!pend.xI_given) o.xI = pend.model_file->xI;
    }
    {   // --param: each value as the panel would take it
        Params p = make_version(o.model);
        for (const auto& [key, value] : o.params)
            if (std::string err; !set_param(p, key, value, err)) throw OptionsError("--param " + key + ": " + err);
    }
    if (!o.orbits.empty() && o.frames == 0) throw OptionsError("--orbit needs --frames N");
    if (o.then_preset > 0 && o.frames == 0) throw OptionsError("--then-preset needs --frames N");
    if (o.then_xi && o.frames == 0) throw OptionsError("--then-xI needs --frames N");
    if (o.then_w && o.frames == 0) throw OptionsError("--then-omega needs --frames N");
    if (o.then_phase && o.frames == 0) throw OptionsError("--then-phi0 needs --frames N");
    for (const std::string& h : o.hide)
        if (h == o.maximise) throw OptionsError("--maximise " + h + ": that panel is hidden by --hide");
    if (!o.save_session.empty() && o.frames == 0) throw OptionsError("--save-session needs --frames N");
    if (!o.clip_out.empty() && o.frames == 0) throw OptionsError("--clip-out needs --frames N");
    if (o.replay_back > 0 && o.frames == 0) throw OptionsError("--replay-back needs --frames N");
    if (o.replay_continue && o.replay_back <= 0) throw OptionsError("--replay-continue needs --replay-back S");
    if (o.twin && !o.ghost.empty()) throw OptionsError("--twin and --ghost: one companion cart at a time");
    if (o.then_preset > 0 && !o.switch_model.empty())
        throw OptionsError("--then-preset: half-way there is either a preset or a --switch-model, not both");
}

}  // namespace

Options parse_options(const std::vector<std::string>& args) {
    Options o;
    Pending pend;
    for (FlagReader r{args}; r.i < args.size(); ++r.i) {
        const std::string& a = args[r.i];
        // A file flag given twice would silently drop one of the files.
        static const char* const once[] = {"--session", "--save-session", "--data", "--plane", "--screenshot", "--state-json", "--clip-out"};
        const auto here = args.begin() + static_cast<std::ptrdiff_t>(r.i);
        for (const char* f : once)
            if (a == f && std::find(args.begin(), here, a) != here) throw OptionsError(a + ": given twice");
        if (a == "--help" || a == "-h") o.help = true;
        else if (!start_flag(a, r, o, pend) && !layout_flag(a, r, o) && !script_flag(a, r, o) && !diagram_flag(a, r, o, pend) &&
                 !analysis_flag(a, r, o) && !session_flag(a, r, o) && !panel_flag(a, r, o) && !bench_flag(a, r, o))
            throw OptionsError("unknown option '" + a + "' (see impactlab-gui --help)");
    }
    settle(o, pend);
    return o;
}

namespace {
void check_writable(const std::string& flag, const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw OptionsError(flag + ": '" + path + "' is a directory");
    // A probe beside the file: the output is written whole later (temporary + rename) into that folder.
    const std::string probe = path + ".probe";
    {
        std::ofstream f(probe);
        if (!f) throw OptionsError(flag + ": cannot write '" + path + "'");
    }
    fs::remove(probe, ec);
}
}  // namespace

void check_files(const Options& o) {
    // Started by hand (from an icon, say), a bad --data or --session is shown in the window, which opens
    // anyway; a headless run (--frames, --soak) still stops here with exit code 2.
    const bool interactive = o.frames == 0 && o.soak <= 0 && !o.bench_plot;
    if (!o.data.empty() && !interactive) {
        try {
            check_input_file(o.data);
        } catch (const InputFileError& e) {
            throw OptionsError("--data: cannot read '" + o.data + "': " + e.reason);
        }
    }
    if (!o.screenshot.empty()) check_writable("--screenshot", o.screenshot);
    if (!o.state_json.empty()) check_writable("--state-json", o.state_json);
    if (!o.save_session.empty()) check_writable("--save-session", o.save_session);
    if (!o.session.empty() && !interactive) {
        try {
            load_session(o.session, Session{});
        } catch (const SessionError& e) {
            throw OptionsError(std::string("--session: ") + e.what());
        }
    }
    if (!o.clip_out.empty()) {
        std::error_code ec;
        if (!std::filesystem::is_directory(o.clip_out, ec))
            throw OptionsError("--clip-out: '" + o.clip_out + "' is not a folder");
        const std::string probe = (std::filesystem::path(o.clip_out) / ".impactlab-clip.probe").string();
        if (!std::ofstream(probe)) throw OptionsError("--clip-out: cannot write in '" + o.clip_out + "'");
        std::filesystem::remove(probe, ec);
    }
}

}  // namespace impactlab::gui
