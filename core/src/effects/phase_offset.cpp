// A phase offset of the unbalance: the mass leads the measured angle by delta [rad] (an encoder or
// optocoupler set off its mark), F = m0e phi'^2 (sin(phi + delta) - sin(phi)).
#include <cmath>

#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce phase_offset(const double* p, const ForceContext& c) {
    const double ds = std::sin(c.phi + p[0]) - std::sin(c.phi), dc = std::cos(c.phi + p[0]) - std::cos(c.phi);
    const double w2 = c.omega * c.omega;
    return {c.m0e * w2 * ds, 0.0, 0.0, c.m0e * (2.0 * c.omega * c.alpha * ds + w2 * c.omega * dc)};
}
}  // namespace impactlab::effects
