// A different unbalance: m0e is (1 + s) times the model's, F = s m0e phi'^2 sin(phi), s [-].
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const double sn = std::sin(c.phi), cs = std::cos(c.phi), w = c.omega;
    return {p[0] * c.m0e * w * w * sn, 0.0, 0.0, p[0] * c.m0e * (2.0 * w * c.alpha * sn + w * w * w * cs)};
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    return "the unbalance m0e is " + pm(p[0], s[0], 100.0) + " % off the model's " + fmt("%.5g", c.model ? c.model->m0e : 0.0) +
           " kg m (a different mass or radius)";
}
}  // namespace

const EffectLaw& unbalance_scale_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"unbalance_scale", "the unbalance is (1 + s) m0e instead of m0e", {"s", nullptr}, {"-", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_phi"};
        l.fit.needs = FitNeeds::Phi;
        l.fit.absorbed_by = "m0e";
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
