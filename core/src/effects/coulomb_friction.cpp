// A change of the dry rolling resistance, F = -dT v / sqrt(v^2 + eps^2), dT [N], with the model's
// smoothing eps = 1e-6 m/s: more (dT > 0) or less dry friction than T.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    constexpr double eps = 1e-6;
    const double s2 = c.v * c.v + eps * eps, inv = 1.0 / std::sqrt(s2);
    return {-p[0] * c.v * inv, 0.0, -p[0] * eps * eps * inv / s2, 0.0};
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const double T = c.model ? c.model->T : 0.0;
    return "the dry rolling resistance is " + pm(p[0], s[0]) + unit(c, "N", "model force units") + " more than the model's T = " + fmt("%.5g", T) + unit(c, "N", "") + " (" +
           (T != 0 ? fmt("%+.2g", 100 * p[0] / T) + " %" : std::string("new")) + "; negative: less)";
}
}  // namespace

const EffectLaw& coulomb_friction_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"coulomb_friction", "a change of the dry rolling resistance, -dT sign(v)", {"dT", nullptr}, {"N", nullptr},
                    {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_v"};
        l.fit.needs = FitNeeds::DryFriction;
        l.fit.absorbed_by = "T";
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
