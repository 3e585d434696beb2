// A magnetic force that drifts over the record: F_mag scales by 1 + r (t - t0), r [1/s] (a magnet warming and
// weakening, or a gap creeping). Parameters: r, then the magnetic law it scales (a1 [N/m], a3 [N/m^3], b2
// [1/m^2], b4 [1/m^4]; copied from the base model), then t0 [s], the record's start. The extra force is
//   F = -r (t - t0) F_mag(x),  F_mag(x) = (a1 x + a3 x^3) / (1 + b2 x^2 + b4 x^4).
// A parameter that changes with time is no force of the state: only a trend over the whole record shows it.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const MagnetForce m = magnet_law(p, c.x);
    const double tau = c.t - p[5];
    return {-p[0] * tau * m.F, -p[0] * tau * m.dF, 0.0, -p[0] * m.F};
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    if (!c.rig) return "the nonlinear restoring term drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record";
    return "the magnets' force drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record (" +
           fmt("%+.2g", 100.0 * p[0] * 60.0) + " % a minute; a magnet warming, or its gap creeping)";
}
}  // namespace

const EffectLaw& magnet_drift_law() {
    static const EffectLaw law = [] {
        EffectLaw l = magnet_effect_law("magnet_drift", "the magnets' force drifts over the record: F_mag scales by 1 + r (t - t0)", "r",
                                        "1/s", force, describe);
        l.names[5] = "t0";
        l.units[5] = "s";
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
