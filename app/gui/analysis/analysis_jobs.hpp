// The visualiser's analysis jobs on worker threads, each handing its finished result to
// the UI whole, as BifurcationJob does: the continued branches for the bifurcation diagram, a small
// parameter plane, the basins of attraction at one omega. The computations are the core's
// (continue_orbits, scan_rows, compute_basins); this file only says what is asked and reshapes the answer
// for drawing. GL-free.
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "impactlab/analysis.hpp"
#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"
#include "analysis/plane_data.hpp"

namespace impactlab::gui {

// The threads a job's computation may use: as asked, or 1 in a browser page (no threads there).
inline int worker_threads(int asked) {
#ifdef __EMSCRIPTEN__
    (void)asked;
    return 1;
#else
    return asked;
#endif
}

// One computation at a time on its own thread, with progress and cancel through a Progress the work
// receives; the result (or the exception's message) is handed over once.
template <class R>
class Job {
public:
    using Work = std::function<R(Progress&)>;
    Job() = default;
    ~Job() {   // cancels and joins
        cancel();
        join();
    }
    Job(const Job&) = delete;
    Job& operator=(const Job&) = delete;

    // UI thread. Cancels and joins any job in progress (its result is dropped), then starts `work`.
    void start(Work work) {
        cancel();
        join();
        {
            std::lock_guard<std::mutex> lock(mutex_);
            result_.reset();
            error_.clear();
        }
        progress_ = std::make_unique<Progress>();
        running_.store(true, std::memory_order_release);
        auto body = [this, w = std::move(work), prog = progress_.get()] {
            std::optional<R> r;
            std::string error;
            try {
                r.emplace(w(*prog));
            } catch (const std::exception& e) {   // a stalled run, a bad spec: reported, never fatal
                error = e.what();
            }
            {
                std::lock_guard<std::mutex> lock(mutex_);
                result_ = std::move(r);
                error_ = std::move(error);
            }
            running_.store(false, std::memory_order_release);
        };
#ifdef __EMSCRIPTEN__
        body();   // a browser page has no threads: the job runs here, whole
#else
        thread_ = std::thread(std::move(body));
#endif
    }
    // UI thread. Asks the work to stop; what it returns when cancelled is still handed over.
    void cancel() {
        if (progress_) progress_->cancel.store(true, std::memory_order_relaxed);
    }
    // Any thread.
    bool running() const { return running_.load(std::memory_order_acquire); }
    // UI thread (progress_ is replaced only by start, on the UI thread).
    double progress() const { return progress_ ? progress_->fraction.load(std::memory_order_relaxed) : 0.0; }
    // UI thread. The finished result, once.
    std::optional<R> take_result() {
        std::lock_guard<std::mutex> lock(mutex_);
        return std::exchange(result_, std::nullopt);
    }
    // UI thread. Why the last job failed, once ("" if it did not).
    std::string take_error() {
        std::lock_guard<std::mutex> lock(mutex_);
        return std::exchange(error_, std::string());
    }
    // UI thread. Waits for the job to end (tests; headless runs).
    void wait() { join(); }

private:
    void join() {
        if (thread_.joinable()) thread_.join();
    }
    std::unique_ptr<Progress> progress_;
    std::thread thread_;
    std::atomic<bool> running_{false};
    std::mutex mutex_;   // guards result_ and error_
    std::optional<R> result_;
    std::string error_;
};

// ---- Continued branches, as curves over the bifurcation diagram -----------------------------------------

// Continued along omega: a curve's param is omega [rad/s].
using BranchCurve = analysis::BranchCurve;
struct ContinuationOverlay {
    std::string model;
    double xI = 0;                        // [m] the bumper they were computed at
    double omega_lo = 0, omega_hi = 0;
    std::vector<BranchCurve> curves;
    std::vector<analysis::BifPoint> points;
    bool cancelled = false;
    double seconds = 0;
    // Started from the running orbit (else from the left well at omega_lo): its omega, section point, period.
    bool from_orbit = false;
    double start_omega = 0, start_x = 0, start_v = 0;
    int start_period = 1;
    std::string end;   // why the first branch ended, each way ("" when it did not start)
};
// The period-1 branch from the left well over [omega_lo, omega_hi] with its period doublings (up to period
// 8), as curves; any thread (the job's worker).
ContinuationOverlay compute_continuation(const Params& p, double omega_lo, double omega_hi, Progress& progress);
// The same from a running orbit: the period-k orbit through the section point (x, v) at omega, continued
// both ways over [omega_lo, omega_hi] with its doublings, as `impactlab continue --omega-start W --from X,V
// --period K` does. Any thread.
ContinuationOverlay compute_continuation_from(const Params& p, double omega_lo, double omega_hi, double omega, double x,
                                              double v, int period, Progress& progress);

// ---- A small parameter plane --------------------------------------------------------------------------------

struct PlaneRequest {
    double omega_lo = 0.5, omega_hi = 25;   // [rad/s]
    double xI_lo = -0.01, xI_hi = 0.01;     // [m]
    int nx = 60, ny = 30;
    int threads = 2;
};
// (omega, xI) with period and impacts per point, rows continued along omega as `impactlab scan` does; a
// cancelled plane keeps the rows it finished. Any thread.
PlaneData compute_plane(const Params& p, const std::string& model, const PlaneRequest& req, Progress& progress);

// ---- Basins -----------------------------------------------------------------------------------------------

// The basin grid the panel asks for at omega (x0 from 3 cm left of the bumper to it, or -3..3 cm without
// one, as `impactlab basins`; v0 in +-0.3 m/s). Any thread.
analysis::BasinSpec basin_request(const Params& p, double omega, int grid, int threads);

}  // namespace impactlab::gui
