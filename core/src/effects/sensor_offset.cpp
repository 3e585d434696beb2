// A zero offset of the position sensor: it reads x + o, o [m]. It changes what is measured, not the motion:
// the force is zero; impactlab fit and synth apply it to the measured x (x_measured = g x + o).
#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce sensor_offset(const double*, const ForceContext&) { return {}; }
}  // namespace impactlab::effects
