// The unbalance drifts over the record: m0e scales by 1 + r (t - t0) (t0: the record's start), r [1/s] (a mass
// shifting or loosening on its arm). F = r (t - t0) m0e phi'^2 sin(phi), with the model's m0e (carried by the
// force context).
// A parameter that changes with time is no force of the state: only a trend over the whole record shows it.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const double sn = std::sin(c.phi), cs = std::cos(c.phi), w = c.omega, F1 = c.m0e * w * w * sn;
    return {p[0] * (c.t - p[1]) * F1, 0.0, 0.0, p[0] * (F1 + (c.t - p[1]) * c.m0e * (2.0 * w * c.alpha * sn + w * w * w * cs))};
}

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return drift_sentence("the unbalance m0e", "a mass shifting or loosening on its arm", p, s);
}
}  // namespace

const EffectLaw& unbalance_drift_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"unbalance_drift",
                    "the unbalance drifts over the record: m0e scales by 1 + r (t - t0)",
                    {"r", "t0", nullptr},
                    {"1/s", "s", nullptr},
                    {0.0, 0.0},
                    force};
        l.fit = hint({0}, {1e-5});
        l.fit.needs = FitNeeds::Phi;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
