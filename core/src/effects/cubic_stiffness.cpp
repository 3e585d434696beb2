// A cubic stiffness term F = -k3 x^3, k3 [N/m^3]: springs or magnets that harden (k3 > 0) or soften (k3 < 0)
// with the stroke, symmetric about x = 0. Real rigs' springs are seldom linear over their whole travel.
#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) { return {-p[0] * c.x * c.x * c.x, -3.0 * p[0] * c.x * c.x, 0.0, 0.0}; }

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const char* kind = p[0] >= 0 ? "hardening" : "softening";
    if (!c.rig)
        return std::string("a cubic restoring term -k3 y^3 with k3 = ") + pm(p[0], s[0]) + ": a symmetric " + kind +
               " nonlinearity (the frequency " + (p[0] >= 0 ? "rises" : "falls") + " with the amplitude)";
    return std::string("a cubic stiffness term -k3 x^3 with k3 = ") + pm(p[0], s[0]) + " N/m^3: at |x| = " + fmt("%.3g", c.x_typ * 1e3) +
           " mm it adds " + fmt("%.2g", -p[0] * c.x_typ * c.x_typ * c.x_typ) + " N, odd in x (a " + kind +
           " spring, the same on both sides)";
}
}  // namespace

const EffectLaw& cubic_stiffness_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"cubic_stiffness", "a cubic stiffness term -k3 x^3 (hardening or softening springs)", {"k3", nullptr},
                    {"N/m^3", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_x"};
        l.fit.power = 3;
        l.fit.absorbed_by = "a3";
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
