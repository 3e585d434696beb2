// A misaligned magnet pair: the fixed magnet sits d to the side of x = 0, so the magnetic part of F_SA acts
// at x - d. Parameters: d [m], then the magnetic law it shifts (a1 [N/m], a3 [N/m^3], b2 [1/m^2],
// b4 [1/m^4]; identification copies them from the base model). The extra force is
//   F = -(F_mag(x - d) - F_mag(x)),  F_mag(x) = (a1 x + a3 x^3) / (1 + b2 x^2 + b4 x^4).
#include "effects/effects.hpp"

namespace impactlab::effects {
namespace {
struct Mag { double F, dF; };
Mag magnet(const double* p, double x) {
    const double x2 = x * x;
    const double num = x * (p[1] + p[2] * x2), dnum = p[1] + 3.0 * p[2] * x2;
    const double den = 1.0 + x2 * (p[3] + p[4] * x2), dden = x * (2.0 * p[3] + 4.0 * p[4] * x2);
    return {num / den, (dnum * den - num * dden) / (den * den)};
}
}  // namespace

EffectForce magnet_offset(const double* p, const ForceContext& c) {
    const Mag shifted = magnet(p, c.x - p[0]), nominal = magnet(p, c.x);
    return {-(shifted.F - nominal.F), -(shifted.dF - nominal.dF), 0.0, 0.0};
}
}  // namespace impactlab::effects
