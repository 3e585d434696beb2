// An even (asymmetric) stiffness term F = -k2 x^2, k2 [N/m^2]: magnets or springs that pull harder on
// one side, so the two wells differ in depth.
#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) { return {-p[0] * c.x * c.x, -2.0 * p[0] * c.x, 0.0, 0.0}; }

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    if (!c.rig)
        return "an even (quadratic) restoring term -k2 y^2 with k2 = " + pm(p[0], s[0]) +
               ": an asymmetric nonlinearity, the even-order distortion";
    return "an even stiffness term -k2 x^2 with k2 = " + pm(p[0], s[0]) + " N/m^2: at |x| = " + fmt("%.3g", c.x_typ * 1e3) +
           " mm it adds " + fmt("%.2g", -p[0] * c.x_typ * c.x_typ) + " N on both sides, so the wells differ (asymmetric magnets or springs)";
}
}  // namespace

const EffectLaw& even_stiffness_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"even_stiffness", "an even stiffness term -k2 x^2 (asymmetric magnets or springs)", {"k2", nullptr},
                    {"N/m^2", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_x"};
        l.fit.power = 2;
        l.fit.power_odd = false;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
