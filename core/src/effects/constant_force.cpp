// A constant force along the rail, F0 [N]: a tilted rail (F0 = m g sin(theta)) or a cable's pull.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext&) { return {p[0], 0.0, 0.0, 0.0}; }

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    if (!c.rig) return "a constant force of " + pm(p[0], s[0]) + " (in the model's force units): an offset of the input or of the system's equilibrium";
    const double m = c.model ? c.model->m : 1.0, tilt = std::asin(std::min(1.0, std::abs(p[0]) / (m * 9.81))) * 180.0 / kPi;
    return "a constant force of " + pm(p[0], s[0]) + " N along the rail (" + (p[0] > 0 ? "towards +x" : "towards -x") +
           "): a tilt of about " + fmt("%.2g", tilt) + " degrees, or a pull on the cart";
}
}  // namespace

const EffectLaw& constant_force_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"constant_force", "a constant force along the rail (a tilted rail)", {"F0", nullptr}, {"N", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_x"};
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
