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

void adapt(double* p, const Params& m) { p[1] = m.k; }
void start(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    adapt(p, *c.model);
}
std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return "the spring rate k drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record (" + fmt("%+.2g", 100.0 * p[0] * 60.0) +
           " % a minute; springs warming or relaxing)";
}
}  // namespace

const EffectLaw& stiffness_drift_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"stiffness_drift",
                    "the spring rate drifts over the record: k scales by 1 + r (t - t0)",
                    {"r", "k", "t0", nullptr},
                    {"1/s", "N/m", "s", nullptr},
                    {0.0, 1115.2, 0.0},
                    force};
        l.fit = hint({0}, {1e-5});
        l.describe = describe;
        l.start = start;
        l.adapt = adapt;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
