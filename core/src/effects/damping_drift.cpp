// The viscous damping drifts over the record: c scales by 1 + r (t - t0) (t0: the record's start), r [1/s] (oil
// warming, a bearing wearing in). Parameters: r, then the model's c it scales (copied). F = -r (t - t0) c v.
// A parameter that changes with time is no force of the state: only a trend over the whole record shows it.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    return {-p[0] * (c.t - p[2]) * p[1] * c.v, 0.0, -p[0] * (c.t - p[2]) * p[1], -p[0] * p[1] * c.v};
}

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return drift_sentence("the viscous damping c", "a bearing's oil warming, or wear", p, s);
}
}  // namespace

const EffectLaw& damping_drift_law() {
    static const EffectLaw law =
        base_drift_law<&Params::c>("damping_drift",
                                   "the viscous damping drifts over the record: c scales by 1 + r (t - t0)",
                                   "c", "N s/m", 12.373, force, describe);
    return law;
}
}  // namespace impactlab::effects
