// A change of the dry rolling resistance, F = -dT v / sqrt(v^2 + eps^2), dT [N], with the model's
// smoothing eps = 1e-6 m/s: more (dT > 0) or less dry friction than T.
#include <cmath>

#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce coulomb_friction(const double* p, const ForceContext& c) {
    constexpr double eps = 1e-6;
    const double s2 = c.v * c.v + eps * eps, inv = 1.0 / std::sqrt(s2);
    return {-p[0] * c.v * inv, 0.0, -p[0] * eps * eps * inv / s2, 0.0};
}
}  // namespace impactlab::effects
