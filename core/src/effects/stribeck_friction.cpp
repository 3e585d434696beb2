// Stribeck friction: extra resistance at low speed that fades above a speed vs,
//   F = -Fs exp(-(v/vs)^2) v / sqrt(v^2 + eps^2),  Fs [N], vs [m/s], eps = 1e-6 m/s (the model's smoothing).
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    constexpr double eps = 1e-6;
    const double vs = std::max(std::abs(p[1]), 1e-9);
    const double s2 = c.v * c.v + eps * eps, inv = 1.0 / std::sqrt(s2);
    const double sgn = c.v * inv, dsgn = eps * eps * inv / s2;
    const double q = c.v / vs, g = std::exp(-q * q), dg = -2.0 * q / vs * g;
    return {-p[0] * g * sgn, 0.0, -p[0] * (dg * sgn + g * dsgn), 0.0};
}

// Fs from zero, the speed scale vs from the trial value.
void start(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    p[1] = c.start;
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    return "extra friction of " + pm(p[0], s[0]) + unit(c, "N", "model force units") + " at low speed that fades above about " + pm(std::abs(p[1]), s[1]) +
           unit(c, "m/s", "data units / s") + " (a Stribeck effect: stiction in the bearings)";
}
}  // namespace

const EffectLaw& stribeck_friction_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"stribeck_friction", "extra friction at low speed fading above vs, -Fs exp(-(v/vs)^2) sign(v)",
                    {"Fs", "vs", nullptr}, {"N", "m/s", nullptr}, {0.0, 0.01}, force};
        // Extra friction (Fs > 0) below a speed the data can resolve: a reversal's timing is known to a fraction
        // of a millisecond, so speeds below a few mm/s are out of reach (a "negative Stribeck" there only
        // smooths the friction step and is not physics).
        l.fit = hint({0, 1}, {1.0, 1e-4}, 1);
        l.fit.rivals = {"unexplained_v"};
        l.fit.starts = {0.005, 0.0075, 0.01, 0.015, 0.02, 0.03, 0.05, 0.075, 0.1};
        l.fit.n_starts = 9;
        l.fit.positive = true;
        l.fit.lo[0] = 0.0;
        l.fit.lo[1] = 0.005;
        l.fit.test_first_only = true;   // the speed scale has no null value
        l.start = start;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
