// The parameter plane's view (a tile, F2): a scan CSV loaded or a small (omega, xI) plane computed on a
// worker, drawn as period classes (or impacts, lambda, x range) with a legend; the white line is where the
// bifurcation diagram cuts the plane, the dot the running (omega, xI), and a click sets omega and xI live.
// Over it, the core's continued period doubling (analysis::curve_over_plane, on a worker): the first
// period-1 doubling over the plane's omega range, followed along its second axis. UI thread only.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>

#include "analysis_jobs.hpp"
#include "impactlab/plane_doubling.hpp"
#include "options.hpp"
#include "plane_data.hpp"
#include "views/analysis_view.hpp"

namespace impactlab::gui {

// The doubling curve as the view shows it: which plane and model it was computed for.
struct PlaneDoublingShown {
    analysis::PlaneCurve result;
    std::string model, second;   // "A1C", "xI" or "m0e"
};

class PlanePanel {
public:
    PlanePanel() = default;
    PlanePanel(const PlanePanel&) = delete;
    PlanePanel& operator=(const PlanePanel&) = delete;

    // --plane FILE (loaded now: its error is returned), --small-plane and --plane-doubling (begun at the first
    // frames: the curve once a plane is there).
    std::string configure(const Options& opt);
    // Loads a scan CSV; an error is shown in the view (and returned), the old plane kept.
    std::string load(const std::string& path);
    void start(const AnalysisContext& c);
    // The doubling curve over the plane shown ("" when started, else why not: no plane, axes not omega and
    // xI or m0e).
    std::string start_doubling(const AnalysisContext& c);
    bool busy() const;
    // Every frame, drawn or not: starts what the command line asked for and takes the workers' results.
    AnalysisAction poll(const AnalysisContext& c, std::string& startup_error);
    // Inside its tile.
    AnalysisAction draw(const AnalysisContext& c);
    void release_gl();
    nlohmann::json state() const;   // for --state-json

private:
    Job<PlaneData> job_;
    Job<analysis::PlaneCurve> doubling_job_;
    std::optional<PlaneData> plane_;
    std::optional<PlaneDoublingShown> doubling_;
    std::string doubling_model_, doubling_second_;   // of the job running
    bool want_plane_ = false, want_doubling_ = false;
    char path_[512] = {};
    std::string error_;
    int measure_ = 0;
    PlaneRequest req_;
    unsigned tex_ = 0;
    bool dirty_ = true;
};

}  // namespace impactlab::gui
