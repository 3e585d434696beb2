// The visualiser's analysis views: the continued branches over the bifurcation diagram (this class, with
// its worker), the parameter plane (views/plane_panel) and the basins (views/basins_panel), each a tile of the
// layout; the Analysis menu and the keys O, F2 and F3. The app hands them what it shows (AnalysisContext)
// and applies what a click asks for (AnalysisAction) through its own commands to the simulation thread;
// nothing here talks to that thread. UI thread only.
#pragma once

#include <array>
#include <vector>

#include <optional>
#include <string>

#include "analysis/analysis_jobs.hpp"
#include "window/options.hpp"
#include "render/plot2d.hpp"
#include "views/analysis_view.hpp"
#include "views/basins_panel.hpp"
#include "views/plane_panel.hpp"

namespace impactlab::gui {

class AnalysisPanels {
public:
    AnalysisPanels() = default;
    AnalysisPanels(const AnalysisPanels&) = delete;
    AnalysisPanels& operator=(const AnalysisPanels&) = delete;

    // --plane FILE, --continuation, --continue-here, --basins, --small-plane, --plane-doubling: loaded now,
    // computed at the first frame (--continue-here: once the Poincare map has settled).
    void configure(const Options& opt);
    void start_continuation(const AnalysisContext& c);
    // The branch through the running orbit (Shift+O, --continue-here): "" when started, else why not (the
    // map has not settled on a periodic orbit).
    std::string start_continuation_here(const AnalysisContext& c);
    // Any job still running, or one asked for at start and not begun yet (headless runs wait for them).
    bool busy() const;
    // The first error of a run asked for on the command line ("" when none): headless runs exit 1 with it.
    const std::string& startup_error() const { return startup_error_; }

    // Inside the main menu bar: the "Analysis" menu.
    AnalysisAction menu(const AnalysisContext& c);
    // Each frame, whether the tiles are drawn or not: polls the workers, handles the keys (O, F2, F3).
    AnalysisAction poll(const AnalysisContext& c);
    // Inside the bifurcation diagram's plot, last: branches (stable solid, unstable dashed) and the
    // bifurcation points (a symbol per kind, named on hover).
    void overlay_diagram(Plot& plot) const;
    // Its legend, as a row of items where the caller is (above the diagram, outside the plot); compact: the
    // word "key", the row shown while it is hovered.
    void overlay_legend(bool compact) const;
    // Before the GL context goes.
    void release_gl();
    // The continued branches shown over the diagram (--state-json reports their special points).
    const std::optional<ContinuationOverlay>& overlay() const { return overlay_; }
    // As last drawn (screen pixels): the legend row's rectangle (x0, y0, x1, y1; zeros: none drawn) and the
    // bifurcation markers inside the plot.
    const std::array<float, 4>& legend_rect() const { return legend_; }
    const std::vector<std::array<float, 2>>& markers() const { return markers_; }

    PlanePanel plane;     // the parameter plane's tile
    BasinsPanel basins;   // the basins' tile

private:
    Job<ContinuationOverlay> cont_job_;
    std::optional<ContinuationOverlay> overlay_;
    std::string live_model_;   // the model and xI at the last poll(): the overlay says when it is stale
    double live_xI_ = 0;
    bool want_cont_ = false;   // asked for at start
    bool want_here_ = false;   // --continue-here: once the map has settled
    long here_wait_ = 0;       // frames waited for it
    double here_chaos_since_ = -1;   // [s] simulated time since when the map has said chaos (-1: it has not)
    std::string startup_error_;
    mutable std::array<float, 4> legend_{};              // drawn by the const overlay_legend
    mutable std::vector<std::array<float, 2>> markers_;
};

}  // namespace impactlab::gui
