// Command-line options of impactlab-gui. GL-free. Bad flags: OptionsError (main prints it and exits 2).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace impactlab::gui {

struct OptionsError : std::runtime_error { using std::runtime_error::runtime_error; };

struct Options {
    std::string model = "A1H";
    double omega = 9.0;          // [rad/s]
    double xI = 0.0;             // [m]
    double x0 = -0.011, v0 = 0;  // [m], [m/s]: the left well
    double speed = 1.0;
    bool paused = false;
    double warmup = 0;           // [s] of simulated time run at 100x first (a populated Poincare map at once)
    bool light = false;          // theme
    double ui_scale = 0;         // 0: from the monitor's content scale
    int width = 1280, height = 800;

    int frames = 0;              // > 0: render this many frames, save the screenshot, print the sim time, exit
    std::string screenshot;      // with --frames: the PNG to write
    std::string state_json;      // with --frames: what the panels show, as JSON (model, omega, Poincare map, ...)
    int preset = 0;              // > 0: start on preset N (1-based, as keys 1-4) of the model
    int then_preset = 0;         // with --frames: apply preset N half-way (as key N), instead of the model switch
    std::string switch_model;    // with --frames: the version switched to half-way ("" = swap G and H)
    std::string bifurcation;     // "", "cf-up", "cf-down", "ef": start computing at launch
    int bif_steps = 300;
    double bif_zoom_lo = 0, bif_zoom_hi = 0;   // --bif-zoom W0:W1: the diagram's view starts zoomed to it

    double soak = 0;             // > 0: run this many wall seconds at 100x, switching the model every 3 s; RSS report
    bool bench_plot = false, bench_ring = false, bench_sim = false;
    int bench_points = 100000;
    std::string plot_backend = "raster";   // raster, gpu, imgui
    bool help = false;
    bool show_help = false;      // open the shortcuts window at start
    std::string data;            // a measured run to load into the "Measured data" window at start (and fit)
    // Analysis (issues 9, 10): a scan CSV for the plane window; jobs begun at start (--frames waits for them).
    std::string plane;           // --plane FILE
    bool continuation = false;   // --continuation: the continued branches over the diagram
    bool small_plane = false;    // --small-plane: a 60 x 30 (omega, xI) plane on a worker
    bool basins = false;         // --basins: the basins at --omega
};

// argv without the program name. Throws OptionsError naming the flag and the problem.
Options parse_options(const std::vector<std::string>& args);
// The files the options name, checked before any window opens: --data must be readable, --screenshot and
// --state-json writable (a probe file beside each, removed again). Throws OptionsError naming the flag.
void check_files(const Options& o);
const char* usage_text();

}  // namespace impactlab::gui
