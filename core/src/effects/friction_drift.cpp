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

void adapt(double* p, const Params& m) { p[1] = m.T; }
void start(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    adapt(p, *c.model);
}
std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return "the dry rolling resistance T drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record (" +
           fmt("%+.2g", 100.0 * p[0] * 60.0) + " % a minute; the rail wearing in, dust, or warming)";
}
}  // namespace

const EffectLaw& friction_drift_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"friction_drift",
                    "the dry rolling resistance drifts over the record: T scales by 1 + r (t - t0)",
                    {"r", "T", "t0", nullptr},
                    {"1/s", "N", "s", nullptr},
                    {0.0, 1.2267, 0.0},
                    force};
        l.fit = hint({0}, {1e-5});
        l.fit.needs = FitNeeds::DryFriction;
        l.describe = describe;
        l.start = start;
        l.adapt = adapt;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
