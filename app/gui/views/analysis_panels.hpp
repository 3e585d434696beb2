// The visualiser's analysis views: the continued branches over the bifurcation diagram,
// the parameter-plane window and the basins window, with their workers (analysis_jobs). The app hands
// them what it shows (AnalysisContext) and applies what a click asks for (AnalysisAction) through its own
// commands to the simulation thread; nothing here talks to that thread. UI thread only.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "analysis_jobs.hpp"
#include "impactlab/params.hpp"
#include "options.hpp"
#include "plane_data.hpp"
#include "plot2d.hpp"

namespace impactlab::gui {

struct AnalysisContext {
    const Params* params = nullptr;   // the UI's copy of the model (with the current xI)
    std::string model;
    double omega = 0, xI = 0;         // what the simulation runs at [rad/s], [m]
    Range diagram_omega{0, 25};       // the bifurcation diagram's omega axis [rad/s]
    float ui_scale = 1;
};

// What a click asked for: the app sends it to the simulation thread.
struct AnalysisAction {
    std::optional<double> omega, xI;
    std::optional<std::pair<double, double>> reset;   // restart at t = 0, phi = 0 from (x0 [m], v0 [m/s])
    std::string toast;
};

class AnalysisPanels {
public:
    AnalysisPanels() = default;
    AnalysisPanels(const AnalysisPanels&) = delete;
    AnalysisPanels& operator=(const AnalysisPanels&) = delete;

    // --plane FILE, --continuation, --basins, --small-plane: loaded now, computed at the first frame.
    void configure(const Options& opt);
    // Loads a scan CSV into the plane window; an error is shown there (and returned), the old plane kept.
    std::string load_plane(const std::string& path);
    void start_continuation(const AnalysisContext& c);
    void start_plane(const AnalysisContext& c);
    void start_basins(const AnalysisContext& c);
    // Any job still running, or one asked for at start and not begun yet (headless runs wait for them).
    bool busy() const;
    bool basins_shown() const { return show_basins_; }
    // The first error of a run asked for on the command line ("" when none): headless runs exit 1 with it.
    const std::string& startup_error() const { return startup_error_; }

    // Inside the main menu bar: the "Analysis" menu.
    void menu(const AnalysisContext& c);
    // Each frame, after the tiles: polls the workers, handles the keys (O, F2, F3), draws the windows.
    AnalysisAction draw(const AnalysisContext& c);
    // Inside the bifurcation diagram's plot, last: branches (stable solid, unstable dashed) and the
    // bifurcation points (a symbol per kind, named on hover).
    void overlay_diagram(Plot& plot) const;
    // Before the GL context goes.
    void release_gl();
    // The continued branches shown over the diagram (--state-json reports their special points).
    const std::optional<ContinuationOverlay>& overlay() const { return overlay_; }

private:
    void poll(AnalysisAction& act);
    void draw_plane_window(const AnalysisContext& c, AnalysisAction& act);
    void draw_basins_window(const AnalysisContext& c, AnalysisAction& act);

    Job<ContinuationOverlay> cont_job_;
    Job<PlaneData> plane_job_;
    Job<analysis::BasinResult> basin_job_;
    std::optional<ContinuationOverlay> overlay_;
    std::optional<PlaneData> plane_;
    std::optional<analysis::BasinResult> basins_;
    std::string basins_model_;
    std::string live_model_;   // the model and xI at the last draw(): the overlay says when it is stale
    double live_xI_ = 0;
    bool show_plane_ = false, show_basins_ = false;
    bool want_cont_ = false, want_plane_ = false, want_basins_ = false;   // asked for at start
    std::string startup_error_;
    char plane_path_[512] = {};
    std::string plane_error_;
    int plane_measure_ = 0;
    PlaneRequest plane_req_;
    int basin_grid_ = 80;
    unsigned plane_tex_ = 0, basin_tex_ = 0;
    bool plane_dirty_ = true, basin_dirty_ = true;
};

}  // namespace impactlab::gui
