// The force laws of Eq. (1)-(3), each a small inline function: they sit in the integrator's inner loop.
#pragma once

#include <cmath>

#include "impactlab/params.hpp"

namespace impactlab {

struct ForceAndSlope { double F, dF; };

// Bearing resistance F_R(v) = c v + T v / sqrt(v^2 + eps^2) [N] and dF_R/dv.
inline ForceAndSlope resistance(const Params& p, double v) {
    const double s2 = v * v + p.eps * p.eps;
    const double inv = 1.0 / std::sqrt(s2);
    return {p.c * v + p.T * v * inv, p.c + p.T * p.eps * p.eps * inv / s2};
}

// Springs plus magnets, Eq. (3): F_SA(x) [N] and dF_SA/dx.
inline ForceAndSlope spring_magnet(const Params& p, double x) {
    const double x2 = x * x;
    const double num = x * (p.a[0] + x2 * (p.a[1] + x2 * (p.a[2] + x2 * p.a[3])));
    const double dnum = p.a[0] + x2 * (3 * p.a[1] + x2 * (5 * p.a[2] + x2 * 7 * p.a[3]));
    const double den = 1.0 + x2 * (p.b[0] + x2 * (p.b[1] + x2 * (p.b[2] + x2 * p.b[3])));
    const double dden = x * (2 * p.b[0] + x2 * (4 * p.b[1] + x2 * (6 * p.b[2] + x2 * 8 * p.b[3])));
    return {p.k * x + num / den, p.k + (dnum * den - num * dden) / (den * den)};
}

// Potential energy of F_SA, V(x) = int_0^x F_SA, by 16-point Gauss-Legendre (exact enough for plots and
// energy balances: the integrand is smooth and |x| < a few cm).
double spring_magnet_potential(const Params& p, double x);

// Inertial forcing of the unbalance, m0e * phi'^2 * sin(phi) [N] (the paper's term; the tangential term is
// the effect "tangential_unbalance").
inline double unbalance_force(const Params& p, double phi, double omega) {
    return p.m0e * omega * omega * std::sin(phi);
}
// Its time derivative, with alpha = omega' [N/s].
inline double unbalance_force_rate(const Params& p, double phi, double omega, double alpha) {
    return p.m0e * (2.0 * omega * alpha * std::sin(phi) + omega * omega * omega * std::cos(phi));
}

}  // namespace impactlab
