// A generic force for a spring rate that cycles in time, which no named effect explains:
//   unexplained_x_cycle  F = -(a sin(2 pi (t - t0) / P) + b cos(2 pi (t - t0) / P)) x
// a, b [N/m], P [s], t0 [s] (the record's start). A temperature cycle or a mount that loosens and settles
// changes the stiffness in time; a drift takes a trend, this a cycle. Offered only where the residual shows
// one (identify/features.cpp), its period started there and refined by the fit.
#include <cmath>

#include "effects/effects.hpp"
#include "effects/law_helpers.hpp"

namespace impactlab::effects {
namespace {

EffectForce force(const double* p, const ForceContext& c) {
    const double P = p[2];
    if (!(P > 0)) return {};
    const double w = 2.0 * kPi / P, ph = w * (c.t - p[3]);
    const double sn = std::sin(ph), cs = std::cos(ph);
    const double S = p[0] * sn + p[1] * cs, dS = w * (p[0] * cs - p[1] * sn);
    return {-S * c.x, -S, 0.0, -dS * c.x};
}

std::string describe(const double* p, const double* s, const EffectReportContext& c) {
    const double A = std::hypot(p[0], p[1]);
    std::string share;
    if (c.rig && c.model && c.model->k != 0.0) share = " (" + fmt("%.2g", 100.0 * A / std::abs(c.model->k)) + " % of k)";
    return "no library effect explains this part of the residual; a spring rate that cycles in time does: it swings by +/- " +
           fmt("%.3g", A) + (c.rig ? " N/m" : "") + share + " with a period of " + pm(p[2], s[2]) +
           " s: the missing physics changes the stiffness periodically over the record (a temperature cycle, a loosening mount)";
}

void start(double* p, const EffectStartContext& c) {
    p[0] = 0.0;
    p[1] = 0.0;
    p[2] = c.cycle_period > 0 ? c.cycle_period : 1.0;
}

}  // namespace

const EffectLaw& unexplained_x_cycle_law() {
    static const EffectLaw law = [] {
        EffectLaw l{"unexplained_x_cycle", "a spring rate that cycles in time (a force -S(t) x, S periodic) no named effect explains",
                    {"a", "b", "P", "t0", nullptr}, {"N/m", "N/m", "s", "s", nullptr}, {0.0, 0.0, 1.0, 0.0}, force};
        l.fit = hint({0, 1, 2}, {1, 1, 1e-3}, 2);
        l.fit.lo[2] = 1e-3;
        l.fit.generic = true;
        l.fit.needs = FitNeeds::Cycle;
        l.describe = describe;
        l.start = start;
        return l;
    }();
    return law;
}

}  // namespace impactlab::effects
