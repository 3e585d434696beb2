// Discontinuous impact with finite duration (versions G, H), Eqs. (9)-(12):
//   kappa(v-) = (kappa0 - kappa1) exp(-a_kappa |v-|) + kappa1,  T_imp(v-) = (Ti0 - Ti1) exp(-a_T |v-|) + Ti1.
#pragma once
#include "impactlab/params.hpp"

namespace impactlab::discontinuous {
// Parameter order: kappa0, kappa1, a_kappa [s/m], Ti0 [s], Ti1 [s], a_T [s/m].
double restitution(const double* p, double v_minus);
double duration(const double* p, double v_minus);
}  // namespace impactlab::discontinuous
