// Quadratic (aerodynamic or turbulent-oil) damping: F = -cq v |v|, cq [N s^2/m^2]; a resistance, so cq >= 0.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    return {-p[0] * c.v * std::abs(c.v), 0.0, -2.0 * p[0] * std::abs(c.v), 0.0};
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const double cvis = c.model ? c.model->c : 0.0;
    return "a resistance growing with the square of the speed, cq = " + pm(p[0], s[0]) + unit(c, "N s^2/m^2", "force units per (data unit / s)^2") + ": at the typical speed of " +
           fmt("%.2g", c.v_typ) + unit(c, "m/s", "data units / s") + " it adds " + fmt("%.2g", p[0] * c.v_typ * c.v_typ) +
           unit(c, "N", "force units") + " to the viscous " + fmt("%.2g", cvis * c.v_typ) + unit(c, "N", "") + " (air or oil drag)";
}
}  // namespace

const EffectLaw& quadratic_damping_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"quadratic_damping", "a resistance growing with the square of speed, -cq v|v|", {"cq", nullptr},
                    {"N s^2/m^2", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_v"};
        l.fit.power = 2;
        l.fit.power_of_v = true;
        l.fit.lo[0] = 0.0;   // a resistance never pushes
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
