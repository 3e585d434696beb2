// The basins' view (a tile, F3): the (x0, v0) grid at phi = 0 at the current omega, each cell coloured by
// the attractor it runs to (analysis::compute_basins on a worker), with the attractors' section points; a
// click restarts the simulation from that state. UI thread only.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>

#include "analysis/analysis_jobs.hpp"
#include "window/options.hpp"
#include "views/analysis_view.hpp"

namespace impactlab::gui {

class BasinsPanel {
public:
    BasinsPanel() = default;
    BasinsPanel(const BasinsPanel&) = delete;
    BasinsPanel& operator=(const BasinsPanel&) = delete;

    // --basins, --basins-box: begun at the first frame.
    void configure(const Options& opt);
    // At the running omega, over the box dragged (or given), else over the default window (the rail left of
    // the bumper, |v0| <= 0.3 m/s).
    void start(const AnalysisContext& c);
    nlohmann::json state() const;   // for --state-json
    bool busy() const { return want_ || job_.running(); }
    // Every frame, drawn or not: starts what the command line asked for and takes the worker's result.
    AnalysisAction poll(const AnalysisContext& c, std::string& startup_error);
    // Inside its tile.
    AnalysisAction draw(const AnalysisContext& c);
    void release_gl();

private:
    void draw_controls(const AnalysisContext& c);   // draw()'s row above the map
    Job<analysis::BasinResult> job_;
    std::optional<analysis::BasinResult> basins_;
    std::string model_;
    bool want_ = false;
    int grid_ = 80;
    struct Box {
        double x0, x1, v0, v1;   // [m], [m/s]
    };
    std::optional<Box> box_;     // the user's box (a right-drag, --basins-box)
    bool dragging_ = false;
    double drag_x_ = 0, drag_v_ = 0;   // where the drag began
    unsigned tex_ = 0;
    bool dirty_ = true;
};

}  // namespace impactlab::gui
