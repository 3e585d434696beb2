// Generalised Hunt-Crossley contact (versions C, C1): F_I = kI (h^n1 + b h^n2 |h'|^n3 sign h'), F_I >= 0.
#pragma once
#include "impactlab/params.hpp"

namespace impactlab::hunt_crossley {
// Parameter order: kI [N/m^n1], b [(s/m)^n3], n1, n2, n3.
ContactForce contact(const double* p, double h, double hdot);
// Below this contact speed |h'|^n3 continues linearly (|h'| / v_l) v_l^n3: the power law's infinite slope at
// h' = 0 made a cart resting on the bumper chatter across h' = 0 at ~2e6 steps/s. An impact
// spends ~1e-11 s below 0.1 um/s, so impacts are unchanged; only the creep of a resting contact is smoothed.
inline constexpr double kLinearVelocity = 1e-7;   // [m/s]
}  // namespace impactlab::hunt_crossley
