// A second, stiff stop the base model lacks (an end of the rail, a loose bracket): past xS the cart meets
// a spring kS [N/m] with a dashpot cS [N s/m] that only pushes. Penetration d = side (x - xS) > 0 with
// side = -1 for a stop below the travel, +1 above it;
//   F = -side max(0, kS d + cS d'),  d' = side v.
// The restitution of such a contact is e = exp(-pi z / sqrt(1 - z^2)), z = cS / (2 sqrt(kS m)). It is a
// force of the state, so the integrator resolves each contact; the side is read from the data (the end of
// the travel away from the model's bumper), never fitted.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {
EffectForce force(const double* p, const ForceContext& c) {
    const double side = p[3] < 0 ? -1.0 : 1.0;
    const double d = side * (c.x - p[0]);
    if (d <= 0) return {};
    const double push = p[1] * d + p[2] * side * c.v;
    if (push <= 0) return {};   // the stop lets go rather than pull the cart back
    return {-side * push, -p[1], -p[2], 0.0};
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const double m = c.model ? c.model->m : 1.0;
    const double kS = std::max(p[1], 1e-12);
    const double z = std::max(p[2], 0.0) / (2.0 * std::sqrt(kS * m));
    const double e = z < 1.0 ? std::exp(-kPi * z / std::sqrt(1.0 - z * z)) : 0.0;
    const std::string where = p[3] < 0 ? "below" : "above";
    if (!c.rig)
        return "a stiff stop " + where + " the travel at x = " + pm(p[0], s[0]) + " (stiffness " + pm(p[1], s[1]) +
               ", restitution about " + fmt("%.2f", e) + ")";
    return "an end stop " + where + " the travel at x = " + pm(p[0], s[0], 1e3) + " mm, stiffness " + pm(p[1], s[1]) +
           " N/m, damping " + pm(p[2], s[2]) + " N s/m (restitution about " + fmt("%.2f", e) +
           "): the cart bounces off something the model has no stop for";
}
}  // namespace

const EffectLaw& end_stop_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"end_stop", "a stiff one-sided stop at xS: -side max(0, kS d + cS d'), d = side (x - xS)",
                    {"xS", "kS", "cS", "side", nullptr}, {"m", "N/m", "N s/m", "-", nullptr}, {-0.02, 1e7, 2000.0, -1.0}, force};
        // Never screened on the equation error: a contact of a sample or two is aliased there. fit proposes it
        // from the reversals themselves (identify/stops.cpp), with the reversals kept out of the residual.
        l.fit.from_reversals = true;
        l.describe = describe;
        return l;
    }();
    return law;
}
}  // namespace impactlab::effects
