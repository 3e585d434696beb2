// The measured-data panel's GL-free half: the mapping of the panel's fields onto identify's load options,
// the mapping of an effect subset onto a model, and a worker that runs the core's load_measured / run_fit /
// evaluate_model off the UI thread and hands each result over whole, once. A fit reports its stage and
// progress through the core's FitProgress and stops soon after a cancel; a cancelled load or evaluation
// runs to its end and its result is discarded.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "impactlab/identify.hpp"
#include "impactlab/identify_data.hpp"

namespace impactlab::gui {

// What the panel's column-mapping fields hold. Empty strings: the MODEL.md names (t, x, phi or u).
struct DataColumns {
    std::string t, x;
    std::string forcing;          // the phi (or u) column: a header name or a 1-based number
    bool forcing_is_u = false;    // the forcing column is a measured input u, not the angle phi
    double rate = 0.0;            // [Hz] for a file without a time column; 0: the file has one
    double x_scale = 1.0;         // multiplies x (1e-3 for a file in mm)
    bool free_run = false;        // nothing drove the record (a decay): u = 0, other columns ignored
};
identify::LoadOptions load_options_from(const DataColumns& c);

// The core's messages name the CLI's flags ("--x-scale 1e-3"); the panel has fields for some of them. This
// names the panel's field instead, and marks the rest as the command line's ("--rows" is not in the panel).
std::string panel_wording(const std::string& core_message);

// Effects are toggled by bit k of `mask` for report.effects_found[k] (at most 32 are toggleable).
constexpr std::size_t kMaxToggleEffects = 32;
std::uint32_t all_effects_mask(const identify::FitReport& report);
// The report's baseline model with the chosen found effects applied (apply_effect, with their fitted
// parameters). mask 0 is report.before; all_effects_mask is the model the fit ended with. Throws ParamError.
identify::Model model_for_subset(const identify::FitReport& report, std::uint32_t mask);

// The model a fit starts from: the version (or parameter file) `name`, forced the way the data are.
identify::Model model_for_data(const std::string& name, const identify::MeasuredData& data);

// A display extent of a few series together that ignores outliers: the quantiles q and 1 - q of all their
// finite values, widened by `pad` of the span either side. {0, 0} when there is no finite value.
std::pair<double, double> robust_extent(const std::vector<const std::vector<double>*>& series, double q, double pad);

struct DataJobResult {
    enum class Kind { Load, Fit, Evaluate } kind = Kind::Load;
    std::uint64_t id = 0;
    std::string error;                                  // non-empty: the job threw (message)
    std::shared_ptr<const identify::MeasuredData> data; // Load
    std::shared_ptr<const identify::FitReport> report;  // Fit
    std::uint32_t mask = 0;                             // Evaluate: the subset evaluated
    identify::ErrorSummary errors;                      // Evaluate
};

class DataJob {
public:
    DataJob() = default;
    ~DataJob();   // discards and joins
    DataJob(const DataJob&) = delete;
    DataJob& operator=(const DataJob&) = delete;

    // UI thread. Each one discards any job in progress and starts a new one; returns its id.
    std::uint64_t start_load(const std::string& path, const identify::LoadOptions& options);
    std::uint64_t start_fit(std::shared_ptr<const identify::MeasuredData> data, const identify::Model& model,
                            const identify::FitOptions& options);
    std::uint64_t start_evaluate(std::shared_ptr<const identify::MeasuredData> data, const identify::Model& model,
                                 const identify::FitOptions& options, std::uint32_t mask);
    // UI thread. The running job's result will be discarded; a fit is also asked to stop.
    void cancel();
    // Any thread: the running fit's stage (FitStage, -1 before it starts) and fraction done, 0..1.
    int fit_stage() const { return fit_progress_ ? fit_progress_->stage.load(std::memory_order_relaxed) : -1; }
    double fit_fraction() const { return fit_progress_ ? fit_progress_->fraction.load(std::memory_order_relaxed) : 0.0; }
    // Any thread: a job whose result is still wanted is running.
    bool running() const { return busy_.load(std::memory_order_acquire); }
    DataJobResult::Kind running_kind() const { return kind_; }
    double running_for_s() const;
    // UI thread. The finished job's result, once.
    std::optional<DataJobResult> take_result();
    // Blocks until the wanted job is done or `timeout_s` passes (headless --frames runs). True if done.
    bool wait(double timeout_s);

private:
    std::uint64_t launch(DataJobResult::Kind kind, std::function<void(DataJobResult&)> work);
    void reap(bool all);
    struct Worker {
        std::thread thread;
        std::shared_ptr<std::atomic<bool>> done;
    };
    std::vector<Worker> workers_;      // the wanted one and any discarded ones still running
    std::uint64_t next_id_ = 0;
    std::atomic<std::uint64_t> wanted_{0};
    std::atomic<bool> busy_{false};
    DataJobResult::Kind kind_ = DataJobResult::Kind::Load;
    double started_s_ = 0;
    std::mutex mutex_;                 // guards result_
    std::optional<DataJobResult> result_;
    // The current fit's progress (shared with its worker, which may outlive a cancel). Set on the UI thread.
    std::shared_ptr<identify::FitProgress> fit_progress_;
};

}  // namespace impactlab::gui
