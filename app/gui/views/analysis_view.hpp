// What the analysis views (the continued branches, the parameter plane, the basins) read each frame and
// what they ask for. The App fills an AnalysisContext and routes an AnalysisAction to the simulation thread
// and to the layout (a view asks for its tile to open; F2, F3 and the Analysis menu toggle them).
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "impactlab/params.hpp"
#include "render/plot2d.hpp"

namespace impactlab::gui {

struct AnalysisContext {
    const Params* params = nullptr;   // the UI's copy of the model (with the current xI)
    std::string model;
    double omega = 0, xI = 0;         // what the simulation runs at [rad/s], [m]
    Range diagram_omega{0, 25};       // the bifurcation diagram's omega axis [rad/s]
    float ui_scale = 1;
    bool plane_open = false, basins_open = false;   // their tiles are in the layout
    // The running attractor as the Poincare map has settled it: a period-k orbit's newest section point
    // (continuation starts there), or chaos.
    struct Orbit {
        double x = 0, v = 0;   // [m, m/s] at phi = 2 pi n
        int period = 1;
    };
    std::optional<Orbit> orbit;
    bool chaotic = false;
    double sim_time = 0;   // [s] the newest sample's
};

// What a click asked for: the app sends it to the simulation thread, or opens and closes the tiles.
struct AnalysisAction {
    std::optional<double> omega, xI;
    std::optional<std::pair<double, double>> reset;   // restart at t = 0, phi = 0 from (x0 [m], v0 [m/s])
    std::string toast;
    bool toggle_plane = false, toggle_basins = false; // F2, F3, the Analysis menu
    bool open_plane = false, open_basins = false;     // a job was started: its tile shows it
    // Merges another view's action into this one (the later toast wins).
    void merge(const AnalysisAction& o) {
        if (o.omega) omega = o.omega;
        if (o.xI) xI = o.xI;
        if (o.reset) reset = o.reset;
        if (!o.toast.empty()) toast = o.toast;
        toggle_plane = toggle_plane || o.toggle_plane;
        toggle_basins = toggle_basins || o.toggle_basins;
        open_plane = open_plane || o.open_plane;
        open_basins = open_basins || o.open_basins;
    }
};

}  // namespace impactlab::gui
