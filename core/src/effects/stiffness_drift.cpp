// The linear spring rate drifts over the record: k scales by 1 + r (t - t0) (t0: the record's start), r [1/s]
// (springs warming or relaxing). Parameters: r, then the model's k it scales (copied). F = -r (t - t0) k x.
// A parameter that changes with time is no force of the state: only a trend over the whole record shows it.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    return {-p[0] * (c.t - p[2]) * p[1] * c.x, -p[0] * (c.t - p[2]) * p[1], 0.0, -p[0] * p[1] * c.x};
}

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return drift_sentence("the spring rate k", "springs warming or relaxing", p, s);
}
}  // namespace

const EffectLaw& stiffness_drift_law() {
    static const EffectLaw law =
        base_drift_law<&Params::k>("stiffness_drift",
                                   "the spring rate drifts over the record: k scales by 1 + r (t - t0)",
                                   "k", "N/m", 1115.2, force, describe);
    return law;
}
}  // namespace impactlab::effects
