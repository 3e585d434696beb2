// Stribeck friction: extra resistance at low speed that fades above a speed vs,
//   F = -Fs exp(-(v/vs)^2) v / sqrt(v^2 + eps^2),  Fs [N], vs [m/s], eps = 1e-6 m/s (the model's smoothing).
#include <cmath>

#include "effects/effects.hpp"

namespace impactlab::effects {
EffectForce stribeck_friction(const double* p, const ForceContext& c) {
    constexpr double eps = 1e-6;
    const double vs = std::max(std::abs(p[1]), 1e-9);
    const double s2 = c.v * c.v + eps * eps, inv = 1.0 / std::sqrt(s2);
    const double sgn = c.v * inv, dsgn = eps * eps * inv / s2;
    const double q = c.v / vs, g = std::exp(-q * q), dg = -2.0 * q / vs * g;
    return {-p[0] * g * sgn, 0.0, -p[0] * (dg * sgn + g * dsgn), 0.0};
}
}  // namespace impactlab::effects
