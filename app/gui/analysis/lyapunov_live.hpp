// The largest Lyapunov exponent at the running omega, live: recomputed on a worker from the latest
// published state every few seconds, so the state panel says whether what the class watches is chaotic
// (lambda > 0) or settles (lambda < 0). The computation is the core's analysis::lyapunov. GL-free.
#pragma once

#include <cmath>
#include <string>

#include "analysis/analysis_jobs.hpp"
#include "impactlab/params.hpp"

namespace impactlab::gui {

class LiveLyapunov {
public:
    // Periods the estimate waits (transient) and averages over; a change of model or omega restarts it.
    static constexpr int kTransient = 20, kPeriods = 60;
    // UI thread, every frame. Takes a finished estimate, and starts the next one from (x, v) when none runs
    // and the last started `every_s` ago, or at once after a change of model or omega.
    void update(const Params& p, double omega, double x, double v, double now_s, double every_s = 3.0);
    // UI thread. "+0.123 1/s (chaos)", "-1.20 1/s (settles)", or what it is doing.
    std::string text() const;
    // UI thread. The last estimate [1/s] for this model and omega (NaN before the first).
    double value() const { return value_; }
    // UI thread (tests). Waits for the computation in flight.
    void wait() { job_.wait(); }

private:
    Job<double> job_;
    double value_ = NAN;
    double last_start_ = -1e300;
    double omega_ = NAN, started_omega_ = NAN;
    std::string model_, started_model_;
    std::string error_;
};

}  // namespace impactlab::gui
