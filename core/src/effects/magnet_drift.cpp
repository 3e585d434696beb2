// A magnetic force that drifts over the record: F_mag scales by 1 + r t (t from the record's start), r [1/s]
// (a magnet warming and weakening, or a gap creeping). Parameters: r, then the magnetic law it scales (a1
// [N/m], a3 [N/m^3], b2 [1/m^2], b4 [1/m^4]; copied from the base model). The extra force is
//   F = -r t F_mag(x),  F_mag(x) = (a1 x + a3 x^3) / (1 + b2 x^2 + b4 x^4).
// A parameter that changes with time is no force of the state: only a trend over the whole record shows it.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
struct Mag { double F, dF; };
Mag magnet(const double* p, double x) {
    const double x2 = x * x;
    const double num = x * (p[1] + p[2] * x2), dnum = p[1] + 3.0 * p[2] * x2;
    const double den = 1.0 + x2 * (p[3] + p[4] * x2), dden = x * (2.0 * p[3] + 4.0 * p[4] * x2);
    return {num / den, (dnum * den - num * dden) / (den * den)};
}

EffectForce force(const double* p, const ForceContext& c) {
    const Mag m = magnet(p, c.x);
    return {-p[0] * c.t * m.F, -p[0] * c.t * m.dF, 0.0, -p[0] * m.F};
}

void adapt(double* p, const Params& m) {
    p[1] = m.a[0];
    p[2] = m.a[1];
    p[3] = m.b[0];
    p[4] = m.b[1];
}
void start(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    adapt(p, *c.model);
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    if (!c.rig) return "the nonlinear restoring term drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record";
    return "the magnets' force drifts by " + pm(p[0], s[0], 100.0) + " % per second over the record (" +
           fmt("%+.2g", 100.0 * p[0] * 60.0) + " % a minute; a magnet warming, or its gap creeping)";
}
}  // namespace

const EffectLaw& magnet_drift_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"magnet_drift", "the magnets' force drifts over the record: F_mag scales by 1 + r t",
                    {"r", "a1", "a3", "b2", "b4", nullptr}, {"1/s", "N/m", "N/m^3", "1/m^2", "1/m^4", nullptr},
                    {0.0, -1763.5, 0.0, 4907.6, 0.0}, force};
        l.fit = hint({0}, {1e-5});
        l.fit.needs = FitNeeds::Magnets;
        l.start = start;
        l.adapt = adapt;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
