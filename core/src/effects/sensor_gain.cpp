// A gain error of the position sensor: it reads g x, g [-] (1 = calibrated). Like sensor_offset it changes
// what is measured, not the motion: the force is zero; fit and synth apply x_measured = g x + o.
#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double*, const ForceContext&) { return {}; }
double measure(const double* p, double x) { return p[0] * x; }
void start(double* p, const EffectStartContext&) { p[0] = 1.0; }   // calibrated is the null

std::string describe(const double* p, const double* s, const EffectReportContext&) {
    return "the position sensor's gain is " + pm(p[0], s[0]) + " (it reads " + fmt("%+.2g", 100 * (p[0] - 1)) +
           " % of the travel too much): a calibration error";
}
}  // namespace

const EffectLaw& sensor_gain_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"sensor_gain", "the position sensor reads g x (no force; applied to the measurement)", {"g", nullptr},
                    {"-", nullptr}, {1.0}, force};
        l.kind = EffectKind::Sensor;
        // A gain error rescales every term of the equation: with fitted base parameters it is not identifiable.
        l.fit = hint({0}, {1e-3});
        l.fit.rivals = {"unexplained_x"};
        l.fit.needs = FitNeeds::FixedBaseline;
        l.fit.lo[0] = 0.5;
        l.fit.hi[0] = 2.0;
        l.measure = measure;
        l.start = start;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
