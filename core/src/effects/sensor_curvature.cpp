// A curved scale of the position sensor: it reads x + s x^2, s [1/m] (a magnetostrictive or LVDT sensor's
// non-linearity, a laser triangulation's angle). Like sensor_gain it changes what is measured, not the
// motion: the force is zero; fit and synth read the true position through the curve before the gain and
// offset. Over a record in one well a gain and an offset imitate it; over both ends of the travel they
// cannot, and held-out data tell.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double*, const ForceContext&) { return {}; }
double measure(const double* p, double x) { return x + p[0] * x * x; }

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const std::string at = c.x_typ > 0 ? " (" + fmt("%.2g", p[0] * c.x_typ * c.x_typ * (c.rig ? 1e6 : 1.0)) +
                                             (c.rig ? " um" : " data units") + " at |x| = " +
                                             fmt("%.3g", c.x_typ * (c.rig ? 1e3 : 1.0)) + (c.rig ? " mm)" : ")")
                                       : std::string();
    return "the position sensor's scale is curved: it reads x + s x^2 with s = " + pm(p[0], s[0]) + (c.rig ? " 1/m" : "") + at +
           ": a non-linear sensor, not a force";
}
}  // namespace

const EffectLaw& sensor_curvature_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"sensor_curvature", "the position sensor reads x + s x^2 (no force; applied to the measurement)",
                    {"s", nullptr}, {"1/m", nullptr}, {0.0}, force};
        l.kind = EffectKind::Sensor;
        l.curved = true;
        // As for a gain error: with fitted base parameters the curve and the springs trade against each other.
        l.fit = hint({0}, {1e-3});
        l.fit.rivals = {"unexplained_x", "unexplained_v"};
        l.fit.needs = FitNeeds::FixedBaseline;
        l.fit.lo[0] = -50.0;   // 1/m: 5 mm off at 10 mm, far beyond any usable sensor
        l.fit.hi[0] = 50.0;
        l.measure = measure;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
