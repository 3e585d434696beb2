// The parameter plane's view (a tile, F2): a scan CSV loaded or a small (omega, xI) plane computed on a
// worker, drawn as period classes (or impacts, lambda, x range) with a legend; the white line is where the
// bifurcation diagram cuts the plane, the dot the running (omega, xI), and a click sets omega and xI live.
// Over it, the core's continued period doubling, grazing and fold (plane_curves.hpp, on workers): solid,
// dashed and dotted as impactlab scan's PNG, from the first one over the plane's omega range or from a cell
// picked with a right-click. UI thread only.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analysis_jobs.hpp"
#include "window/options.hpp"
#include "analysis/plane_curves.hpp"
#include "analysis/plane_data.hpp"
#include "views/analysis_view.hpp"

namespace impactlab::gui {

class Plot;

class PlanePanel {
public:
    PlanePanel() = default;
    PlanePanel(const PlanePanel&) = delete;
    PlanePanel& operator=(const PlanePanel&) = delete;

    // --plane FILE (loaded now: its error is returned), --small-plane, --plane-doubling, --plane-grazing and
    // --plane-fold (begun at the first frames: the curves once a plane is there).
    std::string configure(const Options& opt);
    // Loads a scan CSV; an error is shown in the view (and returned), the old plane kept.
    std::string load(const std::string& path);
    void start(const AnalysisContext& c);
    // A curve over the plane shown ("" when started, else why not: no plane, axes not omega and xI or m0e).
    std::string start_curve(const AnalysisContext& c, analysis::BifKind kind, const CurveStart& from);
    bool busy() const;
    // Every frame, drawn or not: starts what the command line asked for and takes the workers' results.
    AnalysisAction poll(const AnalysisContext& c, std::string& startup_error);
    // Inside its tile.
    AnalysisAction draw(const AnalysisContext& c);
    void release_gl();
    nlohmann::json state() const;   // for --state-json

private:
    // The one row above the plot: the plane's and the curves' menus, the measure, a running job's progress.
    AnalysisAction draw_controls(const AnalysisContext& c);
    // The curves over the plot, and their names (beside it in the legend, else over it).
    void draw_curves(Plot& plot, bool legend);
    void draw_legend(const std::vector<double>& vals, bool classes, double vmin, double vmax);

    Job<PlaneData> job_;
    PlaneCurves curves_;
    std::optional<PlaneData> plane_;
    bool want_plane_ = false;
    std::array<std::optional<CurveStart>, kPlaneCurves> want_curve_;   // asked on the command line
    std::optional<PlaneCell> picked_;   // the cell a right-click picked (the context menu's start)
    char path_[512] = {};
    std::string error_;
    int measure_ = 0;
    PlaneRequest req_;
    unsigned tex_ = 0;
    bool dirty_ = true;
};

}  // namespace impactlab::gui
