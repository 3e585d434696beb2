// A zero offset of the position sensor: it reads x + o, o [m]. It changes what is measured, not the motion:
// the force is zero; impactlab fit and synth apply it to the measured x (x_measured = g x + o).
#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double*, const ForceContext&) { return {}; }
double measure(const double* p, double x) { return x + p[0]; }

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    return "the position sensor reads " + (c.rig ? pm(p[0], s[0], 1e3) + " mm" : pm(p[0], s[0]) + " (data units)") + " more than the true position (a zero offset of the Hall sensor or its tape)";
}
}  // namespace

const EffectLaw& sensor_offset_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"sensor_offset", "the position sensor reads x + o (no force; applied to the measurement)", {"o", nullptr},
                    {"m", nullptr}, {0.0}, force};
        l.kind = EffectKind::Sensor;
        l.fit = hint({0}, {1e-5});
        l.fit.rivals = {"unexplained_x"};
        l.fit.absorbed_by = "gain";
        l.measure = measure;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
