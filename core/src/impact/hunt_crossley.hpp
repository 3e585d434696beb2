// Generalised Hunt-Crossley contact (versions C, C1): F_I = kI (h^n1 + b h^n2 |h'|^n3 sign h'), F_I >= 0.
#pragma once
#include "impactlab/params.hpp"

namespace impactlab::hunt_crossley {
// Parameter order: kI [N/m^n1], b [(s/m)^n3], n1, n2, n3.
ContactForce contact(const double* p, double h, double hdot);
// |h'| below this enters the secant slope as this value (the slope grows without bound as h' -> 0).
inline constexpr double kSlopeFloorVelocity = 1e-12;   // [m/s]
}  // namespace impactlab::hunt_crossley
