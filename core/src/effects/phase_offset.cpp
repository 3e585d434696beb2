// A phase offset of the unbalance: the mass leads the measured angle by delta [rad] (an encoder or
// optocoupler set off its mark), F = m0e phi'^2 (sin(phi + delta) - sin(phi)).
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const double ds = std::sin(c.phi + p[0]) - std::sin(c.phi), dc = std::cos(c.phi + p[0]) - std::cos(c.phi);
    const double w2 = c.omega * c.omega;
    return {c.m0e * w2 * ds, 0.0, 0.0, c.m0e * (2.0 * c.omega * c.alpha * ds + w2 * c.omega * dc)};
}

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return "the unbalance leads the measured angle by " + pm(p[0], s[0]) + " rad (" + fmt("%.2g", p[0] * 180 / kPi) +
           " degrees): the encoder or optocoupler mark is off, or the angle lags";
}
}  // namespace

const EffectLaw& phase_offset_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"phase_offset", "the unbalance leads the measured angle by delta (encoder mark off)", {"delta", nullptr},
                    {"rad", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1e-4});
        l.fit.rivals = {"unexplained_phi"};
        l.fit.needs = FitNeeds::Phi;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
