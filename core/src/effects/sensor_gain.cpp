// A gain error of the position sensor: it reads g x, g [-] (1 = calibrated). Like sensor_offset it changes
// what is measured, not the motion: the force is zero; fit and synth apply x_measured = g x + o.
#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce sensor_gain(const double*, const ForceContext&) { return {}; }
}  // namespace impactlab::effects
