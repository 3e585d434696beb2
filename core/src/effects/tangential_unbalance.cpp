// The unbalance's tangential force -s m0e phi'' cos(phi): the paper drops it; it matters when the motor's
// speed ripples or ramps. s [-] scales it (1 = the full physical term).
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const double F = -p[0] * c.m0e * c.alpha * std::cos(c.phi);
    return {F, 0.0, 0.0, p[0] * c.m0e * c.alpha * c.omega * std::sin(c.phi)};
}

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return "the unbalance's tangential force -m0e phi'' cos(phi) at " + pm(p[0], s[0]) +
           " times its full size: the motor's speed changes push the cart";
}
}  // namespace

const EffectLaw& tangential_unbalance_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"tangential_unbalance", "the unbalance's tangential force -m0e phi'' cos(phi) (motor speed changes)",
                    {"scale", nullptr}, {"-", nullptr}, {1.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_phi"};
        l.fit.needs = FitNeeds::Phi | FitNeeds::SpeedChanges;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
