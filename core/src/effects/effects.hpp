// Force laws of the extra physical effects; each is defined in its own file in this folder and listed once
// in registry.cpp. Sign convention: the returned force acts on the cart, positive towards +x, so it is
// exactly what the residual r = m x'' + F_R + F_SA + F_I - forcing measures.
#pragma once
#include "impactlab/params.hpp"

namespace impactlab::effects {
EffectForce constant_force(const double* p, const ForceContext& c);
EffectForce quadratic_damping(const double* p, const ForceContext& c);
EffectForce tangential_unbalance(const double* p, const ForceContext& c);
EffectForce magnet_offset(const double* p, const ForceContext& c);
EffectForce even_stiffness(const double* p, const ForceContext& c);
EffectForce linear_stiffness(const double* p, const ForceContext& c);
EffectForce viscous_damping(const double* p, const ForceContext& c);
EffectForce coulomb_friction(const double* p, const ForceContext& c);
EffectForce stribeck_friction(const double* p, const ForceContext& c);
EffectForce phase_offset(const double* p, const ForceContext& c);
EffectForce unbalance_scale(const double* p, const ForceContext& c);
EffectForce sensor_offset(const double* p, const ForceContext& c);
EffectForce sensor_gain(const double* p, const ForceContext& c);
EffectForce unexplained_x(const double* p, const ForceContext& c);
EffectForce unexplained_v(const double* p, const ForceContext& c);
EffectForce unexplained_x_signv(const double* p, const ForceContext& c);
EffectForce unexplained_phi(const double* p, const ForceContext& c);
}  // namespace impactlab::effects
