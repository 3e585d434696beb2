// The dry rolling resistance drifts over the record: T scales by 1 + r (t - t0) (t0: the record's start), r
// [1/s] (a rail wearing in, dust, warming). Parameters: r, then the model's T it scales (copied). F = -r (t -
// t0) T v / sqrt(v^2 + eps^2).
// A parameter that changes with time is no force of the state: only a trend over the whole record shows it.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    constexpr double eps = 1e-6;  // the model's smoothing [m/s]
    const double s2 = c.v * c.v + eps * eps, inv = 1.0 / std::sqrt(s2), sg = c.v * inv;
    return {-p[0] * (c.t - p[2]) * p[1] * sg, 0.0, -p[0] * (c.t - p[2]) * p[1] * eps * eps * inv / s2, -p[0] * p[1] * sg};
}

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return drift_sentence("the dry rolling resistance T", "the rail wearing in, dust, or warming", p, s);
}
}  // namespace

const EffectLaw& friction_drift_law() {
    static const EffectLaw law =
        base_drift_law<&Params::T>("friction_drift",
                                   "the dry rolling resistance drifts over the record: T scales by 1 + r (t - t0)",
                                   "T", "N", 1.2267, force, describe, FitNeeds::DryFriction);
    return law;
}
}  // namespace impactlab::effects
