// Command-line options of impactlab-gui. GL-free. Bad flags: OptionsError (main prints it and exits 2).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace impactlab::gui {

struct OptionsError : std::runtime_error { using std::runtime_error::runtime_error; };

struct Options {
    std::string model = "A1H";
    std::string browse;          // --browse DIR: the Load session window open on DIR's session files
    std::vector<std::string> double_clicks;   // --double-click ROW: the mouse held still on the session browser's row, clicked twice
    std::string model_file;      // --model FILE.json: the file (model is its version, params its values)
    double omega = 9.0;          // [rad/s]
    double xI = 0.0;             // [m]
    double x0 = -0.011, v0 = 0;  // [m], [m/s]: the left well
    double speed = 1.0;
    bool paused = false;
    double warmup = 0;           // [s] of simulated time run at 100x first (a populated Poincare map at once)
    bool light = false;          // theme
    double ui_scale = 0;         // 0: from the monitor's content scale
    // The layout: presentation mode and its plot, panels hidden or maximised, the rig's
    // displacement magnification (0: the mode's default, x1 normal, x3 presenting).
    bool presentation = false;
    std::string presentation_plot = "phase";
    std::vector<std::string> hide;   // panel keys (layout.hpp) and "controls"
    std::string maximise;            // a panel key
    double magnify = 0;
    int width = 1280, height = 800;

    int frames = 0;              // > 0: render this many frames, save the screenshot, print the sim time, exit
    std::string screenshot;      // with --frames: the PNG to write
    std::string state_json;      // with --frames: what the panels show, as JSON (model, omega, Poincare map, ...)
    int preset = 0;              // > 0: start on preset N (1-based, as keys 1-4) of the model
    int then_preset = 0;         // with --frames: apply preset N half-way (as key N), instead of the model switch
    bool then_xi = false;        // with --frames: move the bumper to then_xI half-way (as the slider), no model switch
    double then_xI = 0;          // [m]
    bool then_w = false;         // with --frames: set omega to then_omega half-way (as the arrow keys)
    double then_omega = 0;       // [rad/s]
    std::string switch_model;    // with --frames: the version switched to half-way ("" = swap G and H)
    std::string bifurcation;     // "", "cf-up", "cf-down", "ef": start computing at launch
    int bif_steps = 300;
    double bif_zoom_lo = 0, bif_zoom_hi = 0;   // --bif-zoom W0:W1: the diagram's view starts zoomed to it
    double ramp_to = -1, ramp_rate = 0;         // --ramp W1:RATE: a live omega ramp at start (-1: none)
    double bif_range_lo = 0, bif_range_hi = 0; // --bif-range W0:W1 [rad/s]: the range computed (0, 0: the default)
    double bif_box_lo = 0, bif_box_hi = 0;     // --bif-box W0:W1: a right-drag over it once the first diagram is done
    std::string bif_y = "x";     // --bif-y x|v: the diagram's quantity at the sections
    std::string bif_over = "omega";   // --bif-over omega|xI|m0e: the diagram's swept parameter (the ranges above
                                      // are then in its SI units: m, kg m)
    bool bif_lyapunov = false;   // --bif-lyapunov: the lambda_max strip under the diagram
    int lyap_steps = 0;          // --lyap-steps N: its omegas (0: the panel's default)
    int bif_settle = 10;         // --bif-settle N: more records a CF level may run to settle (0: not judged)
    bool bif_nowait = false;     // --bif-nowait: --frames does not wait for the diagram

    double soak = 0;             // > 0: run this many wall seconds at 100x, switching the model every 3 s; RSS report
    bool bench_plot = false, bench_ring = false, bench_sim = false;
    int bench_points = 100000;
    std::string plot_backend = "raster";   // raster, gpu, imgui
    bool help = false;
    bool show_help = false;      // open the shortcuts window at start
    std::string data;            // a measured run to load into the "Measured data" window at start (and fit)
    // Analysis: a scan CSV for the plane window; jobs begun at start (--frames waits for them).
    std::string plane;           // --plane FILE
    bool continuation = false;   // --continuation: the continued branches over the diagram
    bool small_plane = false;    // --small-plane: a 60 x 30 (omega, xI) plane on a worker
    bool continue_here = false;  // --continue-here: continue the running periodic orbit once the map settles
    bool plane_doubling = false; // --plane-doubling: the continued doubling over the plane, once it is there
    std::string plane_grazing;   // --plane-grazing auto|W,X,V[,K]: the continued grazing over the plane
    std::string plane_fold;      // --plane-fold auto|W,X,V[,K]: the continued fold over it
    bool basins = false;         // --basins: the basins at --omega
    std::vector<double> basins_box;   // --basins-box X0:X1:V0:V1 [m, m/s]: the basins over that box (implies --basins)
    // Sessions and clips.
    std::string session;         // --session FILE: load at start (validated before the window opens)
    std::string save_session;    // --save-session FILE: with --frames, written at the end
    std::string clip_out;        // --clip-out DIR: with --frames, export the last --clip-seconds as a clip
    double clip_seconds = 2.0;   // [s] of simulated time
    double replay_back = 0;      // [s] with --frames: end in replay this far before the newest sample
    bool replay_continue = false;   // with --replay-back: continue from there (Enter), 60 more frames
    // The companion cart and the mouse's state, as scripts set them.
    bool twin = false;           // --twin: a second cart 1 um to the right, the same model
    std::string ghost;           // --ghost M: a second cart from the same state under M's impact law
    std::string press;           // --press [ctrl+]KEY: that key pressed at frame 3 (headless tests of the keys)
    char tap = 0;                // --tap KEY: pressed and released within one frame's events at frame 3
    bool set_state = false;      // --set-state X,V: at the first frame, as a click in the phase portrait
    double set_x = 0, set_v = 0; // [m], [m/s]
    // The parameters panel (views/params_panel.hpp).
    std::vector<std::pair<std::string, double>> params;   // --param KEY=VALUE: at the first frame, as typed there
    bool show_params = false;    // --show-params: the panel open at start
    std::vector<std::string> strip;   // --strip Q[,Q2]: the time strip's traces (x, v, E, F, drive)
    // The first screen (views/guide_panel.hpp).
    bool guide = false;          // --guide: "What to try" open (it opens by itself on an unscripted start)
    int demo = 0;                // --demo N: run demonstration N (1-5) at the first frame
    bool details = false;        // --details: the status bar's technical fields (epoch, samples, dropped)
    // The Poincare clicker (views/poincare_panel.hpp).
    bool clicker = false;        // --clicker: on at start
    double phi0 = 0;             // --phi0: the section phase [rad], 0 .. 2 pi (sections at phi0 + 2 pi k)
    bool then_phase = false;     // with --frames: set the section phase to then_phi0 half-way (as the slider)
    double then_phi0 = 0;        // [rad]
    std::vector<std::pair<double, double>> orbits;   // --orbit X,V (repeatable): clicks spread over --frames
};

// argv without the program name. Throws OptionsError naming the flag and the problem.
Options parse_options(const std::vector<std::string>& args);
// The files the options name, checked before any window opens: --data must be readable, --screenshot and
// --state-json writable (a probe file beside each, removed again). Throws OptionsError naming the flag.
void check_files(const Options& o);
const char* usage_text();

}  // namespace impactlab::gui
