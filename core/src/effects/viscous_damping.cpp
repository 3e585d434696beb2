// A change of the viscous bearing resistance, F = -dc v, dc [N s/m].
#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) { return {-p[0] * c.v, 0.0, -p[0], 0.0}; }

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const double cv = c.model ? c.model->c : 0.0;
    return "the viscous damping is " + pm(p[0], s[0]) + unit(c, "N s/m", "force units per data unit / s") + " more than the model's c = " + fmt("%.5g", cv) + unit(c, "N s/m", "") + " (" +
           (cv != 0 ? fmt("%+.2g", 100 * p[0] / cv) + " %" : std::string("new")) + "; negative: less)";
}
}  // namespace

const EffectLaw& viscous_damping_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"viscous_damping", "a change of the viscous bearing resistance, -dc v", {"dc", nullptr}, {"N s/m", nullptr},
                    {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_v", "unexplained_x_v"};
        l.fit.absorbed_by = "c";
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
