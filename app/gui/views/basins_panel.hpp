// The basins' view (a tile, F3): the (x0, v0) grid at phi = 0 at the current omega, each cell coloured by
// the attractor it runs to (analysis::compute_basins on a worker), with the attractors' section points; a
// click restarts the simulation from that state. UI thread only.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>

#include "analysis_jobs.hpp"
#include "options.hpp"
#include "views/analysis_view.hpp"

namespace impactlab::gui {

class BasinsPanel {
public:
    BasinsPanel() = default;
    BasinsPanel(const BasinsPanel&) = delete;
    BasinsPanel& operator=(const BasinsPanel&) = delete;

    void configure(const Options& opt) { want_ = opt.basins; }   // --basins: begun at the first frame
    void start(const AnalysisContext& c);
    bool busy() const { return want_ || job_.running(); }
    // Every frame, drawn or not: starts what the command line asked for and takes the worker's result.
    AnalysisAction poll(const AnalysisContext& c, std::string& startup_error);
    // Inside its tile.
    AnalysisAction draw(const AnalysisContext& c);
    void release_gl();

private:
    Job<analysis::BasinResult> job_;
    std::optional<analysis::BasinResult> basins_;
    std::string model_;
    bool want_ = false;
    int grid_ = 80;
    unsigned tex_ = 0;
    bool dirty_ = true;
};

}  // namespace impactlab::gui
