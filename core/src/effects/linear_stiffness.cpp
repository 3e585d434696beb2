// A change of the linear spring rate, F = -dk x, dk [N/m]: springs stiffer (dk > 0) or softer than the model.
#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) { return {-p[0] * c.x, -p[0], 0.0, 0.0}; }

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const double k = c.model ? c.model->k : 0.0;
    return "the springs are " + pm(p[0], s[0]) + unit(c, "N/m", "force units per data unit") + " stiffer than the model's k = " + fmt("%.5g", k) + unit(c, "N/m", "") + " (" +
           fmt("%+.2g", 100 * p[0] / (k != 0 ? k : 1)) + " %; negative: softer)";
}
}  // namespace

const EffectLaw& linear_stiffness_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"linear_stiffness", "a change of the spring rate, -dk x", {"dk", nullptr}, {"N/m", nullptr}, {0.0}, force};
        l.fit = hint({0}, {1.0});
        l.fit.rivals = {"unexplained_x"};
        l.fit.absorbed_by = "k";
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
