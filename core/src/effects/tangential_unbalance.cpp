// The unbalance's tangential force -s m0e phi'' cos(phi): the paper drops it; it matters when the motor's
// speed ripples or ramps. s [-] scales it (1 = the full physical term).
#include <cmath>

#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce tangential_unbalance(const double* p, const ForceContext& c) {
    const double F = -p[0] * c.m0e * c.alpha * std::cos(c.phi);
    return {F, 0.0, 0.0, p[0] * c.m0e * c.alpha * c.omega * std::sin(c.phi)};
}
}  // namespace impactlab::effects
