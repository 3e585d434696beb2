// A change of the viscous bearing resistance, F = -dc v, dc [N s/m]: more (dc > 0) or less damping than c.
#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce viscous_damping(const double* p, const ForceContext& c) { return {-p[0] * c.v, 0.0, -p[0], 0.0}; }
}  // namespace impactlab::effects
