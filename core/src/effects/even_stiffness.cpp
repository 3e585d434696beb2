// An even (asymmetric) stiffness term F = -k2 x^2, k2 [N/m^2]: magnets or springs that pull harder on
// one side, so the two wells differ in depth.
#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce even_stiffness(const double* p, const ForceContext& c) {
    return {-p[0] * c.x * c.x, -2.0 * p[0] * c.x, 0.0, 0.0};
}
}  // namespace impactlab::effects
