// Generalised Hunt-Crossley contact (versions C, C1): F_I = kI (h^n1 + b h^n2 |h'|^n3 sign h'), F_I >= 0.
#pragma once
#include "impactlab/params.hpp"

namespace impactlab::hunt_crossley {
// Parameter order: kI [N/m^n1], b [(s/m)^n3], n1, n2, n3.
ContactForce contact(const double* p, double h, double hdot);
// |h'| below this enters the Newton matrix as this value: d|h'|^n3/dh' is infinite at 0 (MODEL.md).
inline constexpr double kSlopeFloorVelocity = 1e-3;   // [m/s]
}  // namespace impactlab::hunt_crossley
