// A misaligned magnet pair: the fixed magnet sits d to the side of x = 0, so the magnetic part of F_SA acts
// at x - d. Parameters: d [m], then the magnetic law it shifts (a1 [N/m], a3 [N/m^3], b2 [1/m^2],
// b4 [1/m^4]; identification copies them from the base model). The extra force is
//   F = -(F_mag(x - d) - F_mag(x)),  F_mag(x) = (a1 x + a3 x^3) / (1 + b2 x^2 + b4 x^4).
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
struct Mag { double F, dF; };
Mag magnet(const double* p, double x) {
    const double x2 = x * x;
    const double num = x * (p[1] + p[2] * x2), dnum = p[1] + 3.0 * p[2] * x2;
    const double den = 1.0 + x2 * (p[3] + p[4] * x2), dden = x * (2.0 * p[3] + 4.0 * p[4] * x2);
    return {num / den, (dnum * den - num * dden) / (den * den)};
}

EffectForce force(const double* p, const ForceContext& c) {
    const Mag shifted = magnet(p, c.x - p[0]), nominal = magnet(p, c.x);
    return {-(shifted.F - nominal.F), -(shifted.dF - nominal.dF), 0.0, 0.0};
}

// The magnetic law it shifts is the model's own.
void adapt(double* p, const Params& m) {
    p[1] = m.a[0];
    p[2] = m.a[1];
    p[3] = m.b[0];
    p[4] = m.b[1];
}
void start(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    adapt(p, *c.model);
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    if (!c.rig)
        return "the nonlinear restoring term acts about y = " + pm(p[0], s[0]) + " instead of 0 (in the data's units): an asymmetric "
               "nonlinearity";
    return "the fixed magnet sits " + pm(std::abs(p[0]), s[0], 1e3) + " mm " + (p[0] > 0 ? "towards +x" : "towards -x") +
           " of x = 0 (misaligned magnets): the two wells are no longer mirror images";
}
}  // namespace

const EffectLaw& magnet_offset_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"magnet_offset", "the fixed magnet sits d off x = 0 (misaligned magnets): F_mag acts at x - d",
                    {"d", "a1", "a3", "b2", "b4", nullptr}, {"m", "N/m", "N/m^3", "1/m^2", "1/m^4", nullptr},
                    {0.0, -1763.5, 0.0, 4907.6, 0.0}, force};
        l.fit = hint({0}, {1e-5});
        l.fit.needs = FitNeeds::Magnets;
        l.start = start;
        l.adapt = adapt;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
