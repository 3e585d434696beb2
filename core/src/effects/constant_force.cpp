// A constant force along the rail, F0 [N]: a tilted rail (F0 = m g sin(theta)) or a cable's pull.
#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce constant_force(const double* p, const ForceContext&) { return {p[0], 0.0, 0.0, 0.0}; }
}  // namespace impactlab::effects
