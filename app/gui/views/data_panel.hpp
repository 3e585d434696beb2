// The "Measured data" window: load a data file (with a column mapping for other layouts), run the core's
// fit loop (identify::run_fit) on a worker for the app's current model, and show what it found: measured and
// simulated x(t), the residual against x, v and phi before and after, the effects found with a toggle each,
// and the errors of the chosen subset (identify::evaluate_model, on the worker). UI thread only; every
// number comes from the core.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "data/data_job.hpp"
#include "render/plot2d.hpp"
#include "views/file_browser.hpp"

namespace impactlab::gui {

// What the panel needs from the app each frame.
struct DataPanelContext {
    std::string model;   // the current version ("A1H")
    double xI = 0.0;     // the app's bumper position [m]
    float ui_scale = 1.0f;
};

class DataPanel {
public:
    DataPanel();
    // Starts loading `path`; with `then_fit`, the fit runs as soon as it is loaded.
    void load(const std::string& path, bool then_fit);
    // Call once a frame (also while the window is closed): takes finished jobs over, starts evaluations.
    void poll(const DataPanelContext& ctx);
    // The window; `open` is its close box.
    void draw(bool* open, const DataPanelContext& ctx);
    // Headless runs: blocks until the load / fit / evaluations in hand are done (or `timeout_s`).
    void settle(const DataPanelContext& ctx, double timeout_s);

    bool busy() const { return job_.running() || pending_fit_; }
    bool has_data() const { return static_cast<bool>(data_); }
    bool has_report() const { return static_cast<bool>(report_); }
    const std::string& error() const { return error_; }   // the last failure of a load or fit ("" if none)
    std::string loaded_path() const { return data_ ? data_->source : std::string(); }   // "" when none (sessions)
    // --state-json: the record loaded (its file, samples and span), whether it is being loaded or fitted, the
    // last error and whether a fit report is shown.
    nlohmann::json state() const;

private:
    void start_fit(const DataPanelContext& ctx);
    void take(DataJobResult r, const DataPanelContext& ctx);
    void draw_file_row();
    void draw_fit_row(const DataPanelContext& ctx);
    void draw_effects();
    void draw_errors();
    void draw_record(ImVec2 size);   // the record loaded, before a fit
    void draw_trace(ImVec2 size);
    void draw_sections(ImVec2 size);
    void draw_residual(const char* id, const char* xlabel, const std::vector<double>& var, double scale, Range xr,
                       ImVec2 size);

    DataJob job_;
    identify::FitOptions fit_options_;

    // Fields.
    char path_[512] = {};
    FileBrowser browser_{{".csv", ".gz"}, ""};   // the data files beside the path (Browse)
    bool browsing_ = false;
    char t_col_[64] = {}, x_col_[64] = {}, f_col_[64] = {};
    bool f_is_u_ = false;
    float rate_ = 0.0f, x_scale_ = 1.0f;
    bool free_run_ = false;

    // State.
    std::string error_;                                 // the last failure (shown in red)
    std::shared_ptr<const identify::MeasuredData> data_;
    std::shared_ptr<const identify::FitReport> report_;
    bool pending_fit_ = false;                          // fit once the load finishes
    std::uint32_t mask_ = 0, all_ = 0;                  // effects switched on; all found
    std::map<std::uint32_t, identify::ErrorSummary> evals_;
    std::map<std::uint32_t, std::string> eval_errors_;
    identify::Model base_model_;                        // the model the last fit started from
    std::string fit_model_name_;

    // Display ranges of the report's plots (robust: the 0.5 % .. 99.5 % quantiles).
    Range record_t_, record_x_, trace_t_, trace_x_, res_y_, res_x_, res_v_, sec_w_, sec_x_;
};

}  // namespace impactlab::gui
