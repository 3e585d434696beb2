// Quadratic (aerodynamic or turbulent-oil) damping: F = -cq v |v|, cq [N s^2/m^2].
#include <cmath>

#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce quadratic_damping(const double* p, const ForceContext& c) {
    return {-p[0] * c.v * std::abs(c.v), 0.0, -2.0 * p[0] * std::abs(c.v), 0.0};
}
}  // namespace impactlab::effects
