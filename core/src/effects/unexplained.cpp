// Generic smooth forces for a residual that no named effect explains (impactlab fit's last resort).
// Each names the variable the missing force depends on:
//   unexplained_x        F = S(x)                    S a cubic B-spline on [lo, hi], 6 coefficients [N]
//   unexplained_v        F = S(v)                    (held constant outside [lo, hi])
//   unexplained_x_signv  F = S(x) v/sqrt(v^2+eps^2)  (a position-dependent dry friction or hysteresis)
//   unexplained_phi      F = sum_k a_k cos(k phi) + b_k sin(k phi), k = 1..3 [N]
// Parameters of the spline laws: lo, hi (the range, in the variable's unit), c1..c6 [N].
#include <algorithm>
#include <cmath>

#include "effects/effects.hpp"

namespace impactlab::effects {
namespace {

constexpr double kEps = 1e-6;   // [m/s], the model's friction smoothing

// Cubic B-spline kernel and its derivative at u (support |u| < 2).
inline void bspline(double u, double& b, double& db) {
    const double a = std::abs(u);
    if (a >= 2.0) {
        b = db = 0.0;
    } else if (a <= 1.0) {
        b = 2.0 / 3.0 - u * u + 0.5 * a * a * a;
        db = -2.0 * u + 1.5 * u * a;
    } else {
        const double r = 2.0 - a;
        b = r * r * r / 6.0;
        db = -(u > 0 ? 1.0 : -1.0) * 0.5 * r * r;
    }
}

// S(s) and dS/ds: 6 uniform B-splines centred at lo - h, lo, ..., hi + h with h = (hi - lo) / 3.
struct Value { double S, dS; };
Value spline(const double* p, double s) {
    const double lo = p[0], hi = p[1];
    if (!(hi > lo)) return {0.0, 0.0};
    const double h = (hi - lo) / 3.0;
    const bool inside = s > lo && s < hi;
    const double sc = std::clamp(s, lo, hi);
    double S = 0.0, dS = 0.0;
    for (int j = 0; j < 6; ++j) {
        double b, db;
        bspline((sc - (lo + (j - 1) * h)) / h, b, db);
        S += p[2 + j] * b;
        dS += p[2 + j] * db / h;
    }
    return {S, inside ? dS : 0.0};
}

}  // namespace

EffectForce unexplained_x(const double* p, const ForceContext& c) {
    const Value s = spline(p, c.x);
    return {s.S, s.dS, 0.0, 0.0};
}

EffectForce unexplained_v(const double* p, const ForceContext& c) {
    const Value s = spline(p, c.v);
    return {s.S, 0.0, s.dS, 0.0};
}

EffectForce unexplained_x_signv(const double* p, const ForceContext& c) {
    const Value s = spline(p, c.x);
    const double s2 = c.v * c.v + kEps * kEps, inv = 1.0 / std::sqrt(s2);
    const double sg = c.v * inv, dsg = kEps * kEps * inv / s2;
    return {s.S * sg, s.dS * sg, s.S * dsg, 0.0};
}

EffectForce unexplained_phi(const double* p, const ForceContext& c) {
    double F = 0.0, dF = 0.0;
    for (int k = 1; k <= 3; ++k) {
        const double a = p[2 * (k - 1)], b = p[2 * (k - 1) + 1];
        const double cs = std::cos(k * c.phi), sn = std::sin(k * c.phi);
        F += a * cs + b * sn;
        dF += k * (-a * sn + b * cs);
    }
    return {F, 0.0, 0.0, dF * c.omega};
}

}  // namespace impactlab::effects
