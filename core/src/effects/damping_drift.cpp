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

void adapt(double* p, const Params& m) { p[1] = m.c; }
void start(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    adapt(p, *c.model);
}
std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return "the viscous damping c drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record (" +
           fmt("%+.2g", 100.0 * p[0] * 60.0) + " % a minute; a bearing's oil warming, or wear)";
}
}  // namespace

const EffectLaw& damping_drift_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"damping_drift",
                    "the viscous damping drifts over the record: c scales by 1 + r (t - t0)",
                    {"r", "c", "t0", nullptr},
                    {"1/s", "N s/m", "s", nullptr},
                    {0.0, 12.373, 0.0},
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
