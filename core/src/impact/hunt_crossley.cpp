#include "impact/hunt_crossley.hpp"

#include <algorithm>
#include <cmath>

namespace impactlab::hunt_crossley {

namespace {
// h^n with the common n = 1.5 done by a square root (pow is the cost of a contact step).
inline double power(double h, double n) { return n == 1.5 ? h * std::sqrt(h) : std::pow(h, n); }
}  // namespace

ContactForce contact(const double* p, double h, double hdot) {
    const double kI = p[0], b = p[1], n1 = p[2], n2 = p[3], n3 = p[4];
    if (h <= 0.0) return {0.0, 0.0, 0.0, 0.0};
    const double hn1 = power(h, n1), hn2 = power(h, n2);
    const double av = std::abs(hdot);
    // Below kLinearVelocity the factor |h'|^n3 continues linearly (slope finite at h' = 0). One pow a call:
    // |h'|^(n3-1), the secant slope's factor below, is |h'|^n3 / |h'| (pow was a fifth of a contact step).
    double avn3, avn3_1;
    if (av >= kLinearVelocity) {
        avn3 = std::pow(av, n3);
        avn3_1 = avn3 / av;
    } else {
        avn3_1 = std::pow(kLinearVelocity, n3 - 1.0);
        avn3 = av * avn3_1;
    }
    const double sgn = hdot > 0.0 ? 1.0 : (hdot < 0.0 ? -1.0 : 0.0);
    const double F = kI * (hn1 + b * hn2 * avn3 * sgn);
    if (F <= 0.0) return {0.0, 0.0, 0.0, 0.0};   // the bumper never pulls
    const double dF_dh = kI * (n1 * hn1 / h + b * n2 * hn2 / h * avn3 * sgn);
    // Secant slope F_damping / h' in the Newton matrix (MODEL.md): the exact n3 |h'|^(n3-1) underestimates
    // the damping at creep speeds and stalls the implicit method; below v_l the secant is the exact slope.
    const double dF_dhdot = kI * b * hn2 * avn3_1;
    // The true slope: n3 |h'|^(n3-1) on the power law, the secant itself on the linear part below v_l.
    const double dF_dhdot_true = av >= kLinearVelocity ? n3 * dF_dhdot : dF_dhdot;
    return {F, dF_dh, dF_dhdot, dF_dhdot_true};
}

}  // namespace impactlab::hunt_crossley
