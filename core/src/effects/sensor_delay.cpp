// A late position sensor: it reads x(t - tau), tau [s] (a slow Hall sensor, a filter or a buffer). No map of
// x alone can say that, but in the measured time frame it is exact as a force: the rig is time-invariant
// but for its drive, so x measured tau late is the rig driven tau late,
//     F = m0e (phi'(t - tau)^2 sin(phi(t - tau)) - phi'^2 sin(phi)),
// with phi(t - tau) = phi - omega tau + alpha tau^2 / 2 and phi'(t - tau) = omega - alpha tau (exact for a
// piecewise-linear omega away from its knots). At constant omega it is a phase offset -omega tau (the two
// cannot be told apart); a record whose omega changes tells them apart: the lag grows with omega.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const double tau = p[0], w = c.omega, a = c.alpha;
    const double wd = w - a * tau, pd = c.phi - w * tau + 0.5 * a * tau * tau;
    const double F = c.m0e * (wd * wd * std::sin(pd) - w * w * std::sin(c.phi));
    // d/dt with alpha constant: d(phi_d)/dt = omega_d, d(omega_d)/dt = alpha.
    const double dF = c.m0e * (2.0 * wd * a * std::sin(pd) + wd * wd * wd * std::cos(pd) - 2.0 * w * a * std::sin(c.phi) -
                               w * w * w * std::cos(c.phi));
    return {F, 0.0, 0.0, dF};
}

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return "the position sensor reads " + pm(p[0], s[0], 1e3) + " ms late (x measured is x(t - tau)): a sensor's or its filter's lag";
}
}  // namespace

const EffectLaw& sensor_delay_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"sensor_delay", "the position sensor reads x(t - tau) (a lag; acts as the drive tau late)", {"tau", nullptr},
                    {"s", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1e-5});
        // A delay shows only against the unbalance's angle, and is told from a phase offset only where omega
        // changes; a sensor can only be late.
        l.fit.needs = FitNeeds::Phi | FitNeeds::SpeedChanges;
        l.fit.lo[0] = 0.0;
        l.fit.hi[0] = 0.02;
        l.fit.positive = true;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
