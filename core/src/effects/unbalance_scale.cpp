// A different unbalance: m0e is (1 + s) times the model's, F = s m0e phi'^2 sin(phi), s [-].
#include <cmath>

#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce unbalance_scale(const double* p, const ForceContext& c) {
    const double sn = std::sin(c.phi), cs = std::cos(c.phi), w = c.omega;
    return {p[0] * c.m0e * w * w * sn, 0.0, 0.0, p[0] * c.m0e * (2.0 * w * c.alpha * sn + w * w * w * cs)};
}
}  // namespace impactlab::effects
