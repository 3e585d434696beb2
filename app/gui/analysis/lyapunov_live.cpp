#include "lyapunov_live.hpp"

#include <cstdio>

#include "impactlab/analysis.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::gui {

void LiveLyapunov::update(const Params& p, double omega, double x, double v, double now_s, double every_s) {
    const bool changed = p.name != model_ || omega != omega_;
    if (changed) {   // the old estimate belongs to another attractor
        model_ = p.name;
        omega_ = omega;
        value_ = NAN;
        error_.clear();
        job_.cancel();
        last_start_ = -1e300;   // start on the new attractor as soon as the old job has stopped
    }
    if (auto r = job_.take_result(); r && started_model_ == model_ && started_omega_ == omega_) value_ = *r;
    if (const std::string e = job_.take_error(); !e.empty()) error_ = e;
    if (job_.running() || (!changed && now_s - last_start_ < every_s) || !(omega > 0)) return;
    last_start_ = now_s;
    started_model_ = model_;
    started_omega_ = omega_;
    // The published state without its phase: the estimate starts at phi = 0 from (x, v) and lets the
    // transient bring it back onto the attractor.
    job_.start([p, omega, x, v](Progress& prog) {
        State s;
        s.x = x;
        s.v = v;
        return analysis::lyapunov(p, omega, s, kTransient, kPeriods, analysis::analysis_tolerances(), &prog).lambda_max;
    });
}

std::string LiveLyapunov::text() const {
    if (!error_.empty()) return "not computed: " + error_;
    if (!(omega_ > 0)) return "(omega = 0: no forcing period)";
    if (std::isnan(value_)) return "computing...";
    char buf[64];
    // Within +-0.02 1/s of zero the 60-period average cannot tell a slow approach from weak chaos.
    std::snprintf(buf, sizeof buf, "%+.3f 1/s (%s)", value_, value_ > 0.02 ? "chaos" : value_ < -0.02 ? "settles" : "marginal");
    return buf;
}

}  // namespace impactlab::gui
