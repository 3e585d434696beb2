// A misaligned magnet pair: the fixed magnet sits d to the side of x = 0, so the magnetic part of F_SA acts
// at x - d. Parameters: d [m], then the magnetic law it shifts (a1 [N/m], a3 [N/m^3], b2 [1/m^2],
// b4 [1/m^4]; identification copies them from the base model). The extra force is
//   F = -(F_mag(x - d) - F_mag(x)),  F_mag(x) = (a1 x + a3 x^3) / (1 + b2 x^2 + b4 x^4).
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const MagnetForce shifted = magnet_law(p, c.x - p[0]), nominal = magnet_law(p, c.x);
    return {-(shifted.F - nominal.F), -(shifted.dF - nominal.dF), 0.0, 0.0};
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
        EffectLaw l = magnet_effect_law("magnet_offset", "the fixed magnet sits d off x = 0 (misaligned magnets): F_mag acts at x - d",
                                        "d", "m", force, describe);
        l.fit.rivals = {"unexplained_x"};
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
