// Force laws of the extra physical effects; each is defined in its own file in this folder and listed once
// in registry.cpp. Sign convention: the returned force acts on the cart, positive towards +x, so it is
// exactly what the residual r = m x'' + F_R + F_SA + F_I - forcing measures.
#pragma once
#include "impactlab/params.hpp"

namespace impactlab::effects {
EffectForce constant_force(const double* p, const ForceContext& c);
EffectForce quadratic_damping(const double* p, const ForceContext& c);
EffectForce tangential_unbalance(const double* p, const ForceContext& c);
}  // namespace impactlab::effects
