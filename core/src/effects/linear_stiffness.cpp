// A change of the linear spring rate, F = -dk x, dk [N/m]: springs stiffer (dk > 0) or softer than the model.
#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce linear_stiffness(const double* p, const ForceContext& c) { return {-p[0] * c.x, -p[0], 0.0, 0.0}; }
}  // namespace impactlab::effects
